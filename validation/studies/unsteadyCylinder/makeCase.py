#!/usr/bin/env python3
"""Write a 2D cylinder-in-crossflow case at Re 100 (issue 18, item 1).

    makeCase.py <dir> bodyFitted|immersed [options]

D = 10 mm, U = 10 mm/s, nu = 1e-6 m2/s (Re 100; D/U = 1 s). Domain x from
-xUp to xDown, y from -yHalf to yHalf (in diameters), symmetry sides, one
cell thick (z from 0 to the slab thickness).

bodyFitted: an O-grid of stock blockMesh: four blocks from the cylinder to a
    square of half-width 2 D (nTheta cells per quarter, nRadial cells graded
    towards the wall), eight blocks outside it; the force from the stock
    forceCoeffs function object on patch cylinder.
immersed: a Cartesian mesh, uniform (D/n) in [-2 D, 8 D] x [-2 D, 2 D],
    graded outside it; the cylinder an STL prism (fixed body, sharp
    surface); the force from postProcessing/bodies/<t>/bodies.dat.

Both: the inlet velocity is tilted by 17 degrees for the first 5 s (to
start the shedding early), then along x.
"""
import argparse, math, os, subprocess, sys

D, U, NU = 0.01, 0.01, 1e-6

HEADER = """FoamFile
{
    version     2.0;
    format      ascii;
    class       %s;
    object      %s;
}
"""


def write(path, cls, obj, body):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(HEADER % (cls, obj))
        f.write(body)


def graded(length, h, hFar):
    """Cells and expansion (far over near) of a section of given length
    whose near cell is h and whose cells grow geometrically to about hFar"""
    best = None
    for n in range(2, 4000):
        # geometric growth with q^(n-1) = r; solve sum = length for r
        if n*h >= length:
            return n, 1.0
        lo, hi = 1.0, 1e4
        if True:
            for _ in range(200):
                r = math.sqrt(lo*hi)
                q = r**(1.0/(n - 1))
                tot = h*(q**n - 1)/(q - 1) if abs(q - 1) > 1e-12 else n*h
                if tot > length:
                    hi = r
                else:
                    lo = r
            r = math.sqrt(lo*hi)
        if r*h <= hFar:
            return n, r
    raise SystemExit("graded: no solution")


def controlDict(a, libs, functions):
    return """
application     pimpleFoam;
libs            (%s);
startFrom       latestTime;
startTime       0;
stopAt          endTime;
endTime         %g;
deltaT          %g;
writeControl    adjustableRunTime;
writeInterval   %g;
purgeWrite      0;
writeFormat     binary;
writePrecision  10;
writeCompression off;
timeFormat      general;
timePrecision   8;
runTimeModifiable false;
adjustTimeStep  no;

functions
{
%s
}
""" % (libs, a.endTime, a.deltaT, a.writeInterval, functions)


def fvSchemes(a):
    return """
ddtSchemes      { default %s; }
gradSchemes     { default Gauss linear; }
divSchemes
{
    default         none;
    div(phi,U)      Gauss linear;
    div((nuEff*dev2(T(grad(U))))) Gauss linear;
}
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes   { default corrected; }
""" % a.ddt


def fvSolution(a):
    return """
solvers
{
    p
    {
        solver          GAMG;
        smoother        GaussSeidel;
        tolerance       1e-9;
        relTol          0.01;
    }
    pFinal
    {
        $p;
        relTol          0;
    }
    "(U|UFinal)"
    {
        solver          smoothSolver;
        smoother        symGaussSeidel;
        tolerance       1e-10;
        relTol          0;
    }
}
PIMPLE
{
    momentumPredictor   yes;
    nOuterCorrectors    %d;
    nCorrectors         %d;
    nNonOrthogonalCorrectors %d;
}
""" % (a.nOuter, a.nCorrectors, a.nNonOrth)


def fields(d, wall):
    tilt = math.radians(17)
    ut = "(%g %g 0)" % (U*math.cos(tilt), U*math.sin(tilt))
    u0 = "(%g 0 0)" % U
    extraU = "    cylinder { type noSlip; }\n" if wall else ""
    extraP = "    cylinder { type zeroGradient; }\n" if wall else ""
    write(os.path.join(d, "0/U"), "volVectorField", "U", """
dimensions      [0 1 -1 0 0 0 0];
internalField   uniform %s;
boundaryField
{
    inlet
    {
        type            uniformFixedValue;
        uniformValue    table ((0 %s) (5 %s) (6 %s) (1e6 %s));
    }
    outlet { type inletOutlet; inletValue uniform (0 0 0); value uniform %s; }
    sides { type symmetry; }
    frontAndBack { type empty; }
%s}
""" % (u0, ut, ut, u0, u0, u0, extraU))
    write(os.path.join(d, "0/p"), "volScalarField", "p", """
dimensions      [0 2 -2 0 0 0 0];
internalField   uniform 0;
boundaryField
{
    inlet { type zeroGradient; }
    outlet { type fixedValue; value uniform 0; }
    sides { type symmetry; }
    frontAndBack { type empty; }
%s}
""" % extraP)
    write(os.path.join(d, "constant/transportProperties"), "dictionary",
          "transportProperties", "\ntransportModel  Newtonian;\nnu              %g;\n" % NU)
    write(os.path.join(d, "constant/turbulenceProperties"), "dictionary",
          "turbulenceProperties", "\nsimulationType  laminar;\n")


def immersedCylinder(d, slab, position, surface="", density="", motion=""):
    """The cylinder as an immersed glass body: constant/fvOptions,
    constant/immersedDEMProperties (extra lines for the fvOption and the
    body) and its STL prism, three slabs long, through the one-cell slab"""
    write(os.path.join(d, "constant/fvOptions"), "dictionary", "fvOptions", """
bodies
{
    type        immersedBoundaryForce;
    fields      (U);
%s}
""" % surface)
    write(os.path.join(d, "constant/immersedDEMProperties"), "dictionary",
          "immersedDEMProperties", """
materials
{
    glass   { youngsModulus 6.3e10; poissonsRatio 0.24; }
}
bodies
{
    cylinder
    {
        shape       triangleMesh;
        file        cylinder.stl;
        material    glass;
%s        position    %s;
%s    }
}
""" % (density, position, motion))
    here = os.path.dirname(os.path.abspath(__file__))
    stl = os.path.join(here, "../../cases/settling2D/cylinderSTL.py")
    os.makedirs(os.path.join(d, "constant/triSurface"), exist_ok=True)
    subprocess.check_call([sys.executable, stl, os.path.join(d, "constant/triSurface/cylinder.stl"),
                           str(-slab), str(2*slab)])


def immersedMesh(a):
    h = D/a.n
    hFar = a.hFar*D
    # sections: (length, cells, expansion)
    def sec(length, near):
        n, r = graded(length, h, hFar)
        return n, r
    xl, xr = a.xUp - 2, a.xDown - 8
    yo = a.yHalf - 2
    nxl, rxl = sec(xl*D, h)
    nxr, rxr = sec(xr*D, h)
    nyo, ryo = sec(yo*D, h)
    nxc, nyc = 10*a.n, 4*a.n
    nx, ny = nxl + nxc + nxr, 2*nyo + nyc
    dz = a.slab
    xg = "((%g %d %.9g) (%g %d 1) (%g %d %.9g))" % (xl, nxl, 1/rxl, 10, nxc, xr, nxr, rxr)
    yg = "((%g %d %.9g) (%g %d 1) (%g %d %.9g))" % (yo, nyo, 1/ryo, 4, nyc, yo, nyo, ryo)
    return """
scale   %g;
vertices
(
    (%g %g 0) (%g %g 0) (%g %g 0) (%g %g 0)
    (%g %g %g) (%g %g %g) (%g %g %g) (%g %g %g)
);
blocks
(
    hex (0 1 2 3 4 5 6 7) (%d %d 1) simpleGrading (%s %s 1)
);
boundary
(
    inlet { type patch; faces ( (0 4 7 3) ); }
    outlet { type patch; faces ( (1 2 6 5) ); }
    sides { type symmetry; faces ( (0 1 5 4) (3 7 6 2) ); }
    frontAndBack { type empty; faces ( (0 3 2 1) (4 5 6 7) ); }
);
""" % (D, -a.xUp, -a.yHalf, a.xDown, -a.yHalf, a.xDown, a.yHalf, -a.xUp, a.yHalf,
       -a.xUp, -a.yHalf, dz/D, a.xDown, -a.yHalf, dz/D, a.xDown, a.yHalf, dz/D,
       -a.xUp, a.yHalf, dz/D, nx, ny, xg, yg), nx*ny


def bodyFittedMesh(a):
    R, s = 0.5, 2.0          # in diameters
    nt, nr = a.nTheta, a.nRadial
    hs = 2*s/nt              # cell on the square's side [D]
    hFar = a.hFar
    nxl, rxl = graded((a.xUp - s), hs, hFar)
    nxr, rxr = graded((a.xDown - s), hs, hFar)
    nyo, ryo = graded((a.yHalf - s), hs, hFar)
    dz = a.slab/D
    xs = [-a.xUp, -s, s, a.xDown]
    ys = [-a.yHalf, -s, s, a.yHalf]
    verts, index = [], {}
    def vid(key, p):
        if key not in index:
            index[key] = len(verts)
            verts.append(p)
        return index[key]
    for z in (0, 1):
        for j in range(4):
            for i in range(4):
                vid(("g", i, j, z), (xs[i], ys[j], z*dz))
        for k in range(4):
            t = math.radians(45 + 90*k)
            vid(("c", k, z), (R*math.cos(t), R*math.sin(t), z*dz))
    # square corners at 45+90k degrees: k=0 (s,s)=g(2,2), 1 (-s,s)=g(1,2),
    # 2 (-s,-s)=g(1,1), 3 (s,-s)=g(2,1)
    corner = [(2, 2), (1, 2), (1, 1), (2, 1)]
    blocks, edges = [], []
    # radial grading: last (outer) cell over first
    for k in range(4):
        k1 = (k + 1) % 4
        c0, c1 = ("c", k, 0), ("c", k1, 0)
        s0, s1 = ("g",) + corner[k] + (0,), ("g",) + corner[k1] + (0,)
        lo = [index[c0], index[s0], index[s1], index[c1]]
        up = [index[c0[:2] + (1,)], index[s0[:3] + (1,)], index[s1[:3] + (1,)], index[c1[:2] + (1,)]]
        blocks.append("hex (%s) (%d %d 1) simpleGrading (%g 1 1)"
                      % (" ".join(map(str, lo + up)), nr, nt, a.radialGrading))
        tm = math.radians(90 + 90*k)
        for z in (0, 1):
            edges.append("arc %d %d (%.12g %.12g %g)" % (
                index[("c", k, z)], index[("c", k1, z)], R*math.cos(tm), R*math.sin(tm), z*dz))
    ncx = [nxl, nt, nxr]
    ncy = [nyo, nt, nyo]
    gx = [1/rxl, 1, rxr]
    gy = [1/ryo, 1, ryo]
    for j in range(3):
        for i in range(3):
            if i == 1 and j == 1:
                continue
            lo = [index[("g", i, j, 0)], index[("g", i + 1, j, 0)],
                  index[("g", i + 1, j + 1, 0)], index[("g", i, j + 1, 0)]]
            up = [index[("g", i, j, 1)], index[("g", i + 1, j, 1)],
                  index[("g", i + 1, j + 1, 1)], index[("g", i, j + 1, 1)]]
            blocks.append("hex (%s) (%d %d 1) simpleGrading (%.9g %.9g 1)"
                          % (" ".join(map(str, lo + up)), ncx[i], ncy[j], gx[i], gy[j]))
    def face(a_, b_, c_, d_):
        return "(%d %d %d %d)" % (index[a_], index[b_], index[c_], index[d_])
    inlet = [face(("g", 0, j, 0), ("g", 0, j, 1), ("g", 0, j + 1, 1), ("g", 0, j + 1, 0)) for j in range(3)]
    outlet = [face(("g", 3, j, 0), ("g", 3, j + 1, 0), ("g", 3, j + 1, 1), ("g", 3, j, 1)) for j in range(3)]
    sides = [face(("g", i, 0, 0), ("g", i + 1, 0, 0), ("g", i + 1, 0, 1), ("g", i, 0, 1)) for i in range(3)] + \
            [face(("g", i, 3, 0), ("g", i, 3, 1), ("g", i + 1, 3, 1), ("g", i + 1, 3, 0)) for i in range(3)]
    cyl = [face(("c", k, 0), ("c", k, 1), ("c", (k + 1) % 4, 1), ("c", (k + 1) % 4, 0)) for k in range(4)]
    ncells = 4*nr*nt + sum(ncx[i]*ncy[j] for i in range(3) for j in range(3) if (i, j) != (1, 1))
    return """
scale   %g;
vertices
(
%s
);
blocks
(
%s
);
edges
(
%s
);
boundary
(
    inlet { type patch; faces ( %s ); }
    outlet { type patch; faces ( %s ); }
    sides { type symmetry; faces ( %s ); }
    cylinder { type wall; faces ( %s ); }
);
defaultPatch { name frontAndBack; type empty; }
""" % (D, "\n".join("    (%.12g %.12g %.12g)" % p for p in verts),
       "\n".join("    " + b for b in blocks), "\n".join("    " + e for e in edges),
       " ".join(inlet), " ".join(outlet), " ".join(sides), " ".join(cyl)), ncells


def main():
    p = argparse.ArgumentParser()
    p.add_argument("dir")
    p.add_argument("kind", choices=["bodyFitted", "immersed"])
    p.add_argument("-n", type=int, default=10, help="immersed: cells per diameter")
    p.add_argument("-nTheta", type=int, default=32, help="bodyFitted: cells per quarter circle")
    p.add_argument("-nRadial", type=int, default=40)
    p.add_argument("-radialGrading", type=float, default=15)
    p.add_argument("-xUp", type=float, default=10)
    p.add_argument("-xDown", type=float, default=25)
    p.add_argument("-yHalf", type=float, default=10)
    p.add_argument("-hFar", type=float, default=1.0, help="largest cell far away [D]")
    p.add_argument("-slab", type=float, default=0.001)
    p.add_argument("-deltaT", type=float, default=0.02)
    p.add_argument("-endTime", type=float, default=100)
    p.add_argument("-writeInterval", type=float, default=10)
    p.add_argument("-ddt", default="backward")
    p.add_argument("-nOuter", type=int, default=1)
    p.add_argument("-nCorrectors", type=int, default=2)
    p.add_argument("-nNonOrth", type=int, default=0)
    p.add_argument("-surface", default="sharp")
    a = p.parse_args()
    d = a.dir
    os.makedirs(d, exist_ok=True)
    if a.kind == "bodyFitted":
        mesh, nc = bodyFittedMesh(a)
        fo = """    coeffs
    {
        type            forceCoeffs;
        libs            ("libforces.so");
        writeControl    timeStep;
        writeInterval   1;
        patches         (cylinder);
        rho             rhoInf;
        rhoInf          1000;
        CofR            (0 0 0);
        liftDir         (0 1 0);
        dragDir         (1 0 0);
        pitchAxis       (0 0 1);
        magUInf         %g;
        lRef            %g;
        Aref            %g;
    }""" % (U, D, D*a.slab)
        write(os.path.join(d, "system/controlDict"), "dictionary", "controlDict",
              controlDict(a, "", fo))
        fields(d, True)
    else:
        mesh, nc = immersedMesh(a)
        fo = """    bodies
    {
        type        immersedDEM;
        rhoInf      1000;
    }"""
        write(os.path.join(d, "system/controlDict"), "dictionary", "controlDict",
              controlDict(a, '"libimmersedDEM.so"', fo))
        fields(d, False)
        immersedCylinder(d, a.slab, "(0 0 %g)" % (a.slab/2), "    surface     %s;\n" % a.surface,
                         "        density     1500;\n", "        motion      fixed;\n")
    write(os.path.join(d, "system/blockMeshDict"), "dictionary", "blockMeshDict", mesh)
    write(os.path.join(d, "system/fvSchemes"), "dictionary", "fvSchemes", fvSchemes(a))
    write(os.path.join(d, "system/fvSolution"), "dictionary", "fvSolution", fvSolution(a))
    print("%s: %s, %d cells" % (d, a.kind, nc))


if __name__ == "__main__":
    main()
