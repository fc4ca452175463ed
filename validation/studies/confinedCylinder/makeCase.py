#!/usr/bin/env python3
"""Write the confined-cylinder benchmark 2D-2 of Schäfer & Turek (1996)
with the cylinder as an immersed fixed body (issue 48, item 1).

    makeCase.py <dir> [-n 10] [-endTime 10] [-maxCo 0.5] [-nOuter 2] [-ddt backward] [-shift 0]

The benchmark's own dimensions: a channel 2.2 m long and 0.41 m high
(x from 0 to 2.2, y from 0 to 0.41), a cylinder of D = 0.1 m centred at
(0.2, 0.2) (slightly below the mid-line, so the shedding starts by
itself), nu = 1e-3 m2/s, a parabolic inflow of mean U = 1 m/s (peak 1.5
m/s; Re = U D/nu = 100), no-slip walls at y = 0 and 0.41, p = 0 at the
outlet; the fluid starts at rest. A uniform Cartesian mesh of D/n cells,
one cell thick (z from 0 to D/n, front and back empty). The cylinder: a
fixed body, a 256-sided prism (constant/triSurface/cylinder.stl, three
slabs long), sharp surface, every setting at its default; stock
pimpleFoam, backward, two outer correctors (the documented settings for
unsteady forces, validation/studies/unsteadyCylinder), adjustable step at
maxCo. Forces: postProcessing/bodies/0/bodies.dat (Ffx, Ffy), with
rhoInf 1 (the benchmark's density).

-shift S moves the cylinder S cells downstream (x = 0.2 + S D/n): the
same flow, with the surface cutting the mesh elsewhere (the benchmark's
centre lies on a mesh vertex; S = 0.5 puts it on a face's centre). The
inflow is fully developed and the outlet 19 D away, so a shift of a
fraction of a cell changes the benchmark's answer by far less than the
bands; what it changes is the staircase of cells the body covers.
"""
import argparse
import importlib.util
import math
import os

D, H, LENGTH, XC, YC, NU, UMEAN = 0.1, 0.41, 2.2, 0.2, 0.2, 1e-3, 1.0

HEADER = """/*--------------------------------*- C++ -*----------------------------------*\\
  confinedCylinder (validation/studies/confinedCylinder/makeCase.py)
\\*---------------------------------------------------------------------------*/
FoamFile
{
    version     2.0;
    format      ascii;
    class       %s;
    object      %s;
}
"""


def unsteadyCylinder():
    """validation/studies/unsteadyCylinder/makeCase.py as a module"""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "unsteadyCylinder", "makeCase.py")
    spec = importlib.util.spec_from_file_location("unsteadyCylinderCase", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def write(d, rel, cls, body):
    path = os.path.join(d, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(HEADER % (cls, os.path.basename(rel)))
        f.write(body)


def cylinderSTL(path, z0, z1, xc=XC, sides=256):
    r = 0.5*D
    pts = [(xc + r*math.cos(2*math.pi*k/sides), YC + r*math.sin(2*math.pi*k/sides)) for k in range(sides)]
    with open(path, "w") as f:
        f.write("solid cylinder\n")

        def tri(a, b, c):
            f.write("facet normal 0 0 0\n outer loop\n")
            for p in (a, b, c):
                f.write("  vertex %.12e %.12e %.12e\n" % p)
            f.write(" endloop\nendfacet\n")
        for k in range(sides):
            (x0, y0), (x1, y1) = pts[k], pts[(k + 1) % sides]
            tri((x0, y0, z0), (x1, y1, z0), (x1, y1, z1))
            tri((x0, y0, z0), (x1, y1, z1), (x0, y0, z1))
            tri((xc, YC, z1), (x0, y0, z1), (x1, y1, z1))
            tri((xc, YC, z0), (x1, y1, z0), (x0, y0, z0))
        f.write("endsolid cylinder\n")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("dir")
    p.add_argument("-n", type=int, default=10, help="cells per diameter")
    p.add_argument("-endTime", type=float, default=10.0)
    p.add_argument("-maxCo", type=float, default=0.5)
    p.add_argument("-nOuter", type=int, default=2)
    p.add_argument("-ddt", default="backward")
    p.add_argument("-shift", type=float, default=0.0, help="cells the cylinder is moved downstream")
    a = p.parse_args()
    d = a.dir
    h = D/a.n
    xc = XC + a.shift*h
    nx, ny = int(round(LENGTH/h)), int(round(H/h))
    if abs(nx*h - LENGTH) > 1e-9 or abs(ny*h - H) > 1e-9:
        raise SystemExit("makeCase.py: -n %d does not divide the channel (2.2 x 0.41 m) into cells of D/n" % a.n)
    os.makedirs(d, exist_ok=True)
    write(d, "system/blockMeshDict", "dictionary", """
scale 1;
vertices
(
    (0 0 0) (%(L)g 0 0) (%(L)g %(H)g 0) (0 %(H)g 0)
    (0 0 %(h)g) (%(L)g 0 %(h)g) (%(L)g %(H)g %(h)g) (0 %(H)g %(h)g)
);
blocks ( hex (0 1 2 3 4 5 6 7) (%(nx)d %(ny)d 1) simpleGrading (1 1 1) );
boundary
(
    inlet  { type patch; faces ((0 4 7 3)); }
    outlet { type patch; faces ((1 2 6 5)); }
    walls  { type wall;  faces ((0 1 5 4) (3 7 6 2)); }
    frontAndBack { type empty; faces ((0 3 2 1) (4 5 6 7)); }
);
""" % {"L": LENGTH, "H": H, "h": h, "nx": nx, "ny": ny})
    umax = 1.5*UMEAN
    write(d, "0/U", "volVectorField", """
dimensions      [0 1 -1 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{
    // The benchmark's parabola u = 4 Umax y (H - y)/H^2, written about the
    // mid-line s = y - H/2: u = Umax - (4 Umax/H^2) s^2
    inlet
    {
        type        fixedProfile;
        profile     polynomial ( ((%.12g 0 0) (0 0 0)) ((%.12g 0 0) (2 0 0)) );
        direction   (0 1 0);
        origin      %.12g;
    }
    outlet { type inletOutlet; inletValue uniform (0 0 0); value uniform (0 0 0); }
    walls  { type noSlip; }
    frontAndBack { type empty; }
}
""" % (umax, -4*umax/H**2, 0.5*H))
    write(d, "0/p", "volScalarField", """
dimensions      [0 2 -2 0 0 0 0];
internalField   uniform 0;
boundaryField
{
    inlet  { type zeroGradient; }
    outlet { type fixedValue; value uniform 0; }
    walls  { type zeroGradient; }
    frontAndBack { type empty; }
}
""")
    write(d, "constant/transportProperties", "dictionary", "\ntransportModel  Newtonian;\nnu              %g;\n" % NU)
    write(d, "constant/turbulenceProperties", "dictionary", "\nsimulationType  laminar;\n")
    write(d, "constant/fvOptions", "dictionary", """
bodies
{
    type        immersedBoundaryForce;
    fields      (U);
}
""")
    write(d, "constant/immersedDEMProperties", "dictionary", """
materials
{
    steel   { youngsModulus 2e11; poissonsRatio 0.3; }
}
bodies
{
    cylinder
    {
        shape       triangleMesh;
        file        cylinder.stl;
        material    steel;
        density     7800;
        position    (%.12g %.12g %.12g);
        motion      fixed;
    }
}
""" % (xc, YC, 0.5*h))
    os.makedirs(os.path.join(d, "constant/triSurface"), exist_ok=True)
    cylinderSTL(os.path.join(d, "constant/triSurface/cylinder.stl"), -h, 2*h, xc)
    write(d, "system/controlDict", "dictionary", """
application     pimpleFoam;
libs            ("libimmersedDEM.so");
startFrom       latestTime;
startTime       0;
stopAt          endTime;
endTime         %g;
deltaT          %g;
adjustTimeStep  yes;
maxCo           %g;
writeControl    adjustableRunTime;
writeInterval   1;
purgeWrite      0;
writeFormat     binary;
writePrecision  10;
timeFormat      general;
timePrecision   8;
runTimeModifiable false;
functions
{
    bodies
    {
        type        immersedDEM;
        rhoInf      1;
    }
}
""" % (a.endTime, 0.1*h/umax, a.maxCo))
    # The schemes of the unbounded cylinder's study (the documented settings)
    write(d, "system/fvSchemes", "dictionary", unsteadyCylinder().fvSchemes(a))
    write(d, "system/fvSolution", "dictionary", """
solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-8; relTol 0.01; }
    pFinal { $p; relTol 0; }
    "(U|UFinal)" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-10; relTol 0; }
}
PIMPLE
{
    momentumPredictor   yes;
    nOuterCorrectors    %d;
    nCorrectors         2;
    nNonOrthogonalCorrectors 0;
}
""" % a.nOuter)
    print("%s: confined cylinder, %d cells per diameter, %d x %d cells, centre at x = %.6g m"
          % (d, a.n, nx, ny, xc))


if __name__ == "__main__":
    main()
