#!/usr/bin/env python3
"""Write a 2D plane-Couette case with a free body at the centre of the
periodic cell (a coupling-stability test: a neutrally placed body in a
linear shear flow should stay put, neither drift across the channel nor
pick up speed, and spin at half the fluid's vorticity).

    makeCouette.py <dir> [-shape circle|ellipse] [-n 10] [options]
    cd <dir> && blockMesh && pimpleFoam
    checkCouette.py <dir>

The problem (SI units): two walls H apart (default 20 mm) moving along x at
+Uw (the top one, y = +H/2) and -Uw (the bottom one, y = -H/2), default
Uw = 0.01 m/s; periodic (cyclic) along x with length Lx (default 20 mm);
one cell thick along z (a 1 mm slab, -slab) with empty front and back
(-shape sphere: 3D, periodic along z too, -Lz long, default -Lx);
uniform cells D/n; liquid of density 1000 kg/m3 and nu (default 1e-4 m2/s);
no gravity (constant/g zero). The initial velocity is the linear Couette
profile u = Uw 2y/H (y from the centre), the shear rate 2 Uw/H.

The body: a free cylinder of diameter D (default 2 mm; -shape ellipse: an
elliptic cylinder of semi-axes a = D/2 along x and b = D/4 along y), density
-density (default 2000 kg/m3), released at rest with its centroid at the
centre of the periodic cell (x = y = 0); an STL prism three slabs long
through the one-cell slab, as in validation/studies/settlingCylinder2D. In
the 2D mesh the plugin locks its translation along z and its rotation about
x and y itself. -shape sphere: a free sphere of diameter D at the centre of
the 3D cell, nothing locked.

Solver settings as settlingCylinder2D/makeCase.py immersed: stock
pimpleFoam, the unsteadyCylinder study's controlDict, fvSchemes and
fvSolution (backward, two outer correctors), adjustTimeStep with -maxCo and
-maxDeltaT, pRefCell 0 and pRefValue 0 in the closed periodic box; the
function object bodies { type immersedDEM; rhoInf 1000; } and the fvOption
of the unsteadyCylinder helper immersedCylinder, every plugin setting at
its default. The body's motion goes to postProcessing/bodies/0/bodies.dat;
the case's parameters to <dir>/couetteParameters (read by checkCouette.py).
"""
import argparse, importlib.util, math, os

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location(
    "unsteadyCylinderCase", os.path.join(here, "../unsteadyCylinder/makeCase.py"))
oGrid = importlib.util.module_from_spec(spec)
spec.loader.exec_module(oGrid)
write = oGrid.write

RHO_F = 1000.0


def prismSTL(path, a, b, z0, z1, N=128):
    """An elliptic (a = b: circular) cylinder along z from z0 to z1 [m],
    semi-axis a along x and b along y, centred on the z axis: an N-sided
    prism, triangles as in validation/cases/settling2D/cylinderSTL.py
    (outward normals)"""
    pts = [(a*math.cos(2*math.pi*k/N), b*math.sin(2*math.pi*k/N)) for k in range(N)]
    with open(path, "w") as out:
        out.write("solid cylinder\n")

        def tri(p, q, r):
            out.write("facet normal 0 0 0\n outer loop\n")
            for v in (p, q, r):
                out.write("  vertex %.9e %.9e %.9e\n" % v)
            out.write(" endloop\nendfacet\n")
        for k in range(N):
            (x0, y0), (x1, y1) = pts[k], pts[(k + 1) % N]
            tri((x0, y0, z0), (x1, y1, z0), (x1, y1, z1))
            tri((x0, y0, z0), (x1, y1, z1), (x0, y0, z1))
            tri((0, 0, z1), (x0, y0, z1), (x1, y1, z1))
            tri((0, 0, z0), (x1, y1, z0), (x0, y0, z0))
        out.write("endsolid cylinder\n")


def cells(length, h, what):
    n = int(round(length/h))
    if n < 1 or abs(n*h - length) > 1e-6*length:
        raise SystemExit("makeCouette.py: %s %g m is not a whole number of cells D/n = %g m"
                         % (what, length, h))
    return n


def couette(a):
    d = a.dir
    h = a.D/a.n
    nx = cells(a.Lx, h, "-Lx")
    ny = cells(a.H, h, "-H")
    x0, x1, y0, y1 = -a.Lx/2, a.Lx/2, -a.H/2, a.H/2
    sphere = a.shape == "sphere"
    # 3D (a sphere): periodic along z too, Lz long, the cell's centre at
    # z = 0; 2D: one cell from 0 to slab
    z0, z1 = (-a.Lz/2, a.Lz/2) if sphere else (0, a.slab)
    nz = cells(a.Lz, h, "-Lz") if sphere else 1
    frontAndBack = ("    front { type cyclic; neighbourPatch back; faces ( (0 3 2 1) ); }\n"
                    "    back { type cyclic; neighbourPatch front; faces ( (4 5 6 7) ); }"
                    if sphere else "    frontAndBack { type empty; faces ( (0 3 2 1) (4 5 6 7) ); }")
    sideBC = ("    front { type cyclic; }\n    back { type cyclic; }" if sphere
              else "    frontAndBack { type empty; }")
    write(os.path.join(d, "system/blockMeshDict"), "dictionary", "blockMeshDict", """
scale   1;
vertices
(
    (%.12g %.12g %.12g) (%.12g %.12g %.12g) (%.12g %.12g %.12g) (%.12g %.12g %.12g)
    (%.12g %.12g %.12g) (%.12g %.12g %.12g) (%.12g %.12g %.12g) (%.12g %.12g %.12g)
);
blocks
(
    hex (0 1 2 3 4 5 6 7) (%d %d %d) simpleGrading (1 1 1)
);
boundary
(
    bottom { type wall; faces ( (0 1 5 4) ); }
    top { type wall; faces ( (3 7 6 2) ); }
    left { type cyclic; neighbourPatch right; faces ( (0 4 7 3) ); }
    right { type cyclic; neighbourPatch left; faces ( (1 2 6 5) ); }
%s
);
""" % (x0, y0, z0, x1, y0, z0, x1, y1, z0, x0, y1, z0,
       x0, y0, z1, x1, y0, z1, x1, y1, z1, x0, y1, z1, nx, ny, nz, frontAndBack))

    # the linear Couette profile at the cell centres (blockMesh numbers the
    # cells of a block x fastest, then y, then z)
    profile = []
    for j in range(ny):
        u = "(%.12g 0 0)" % (a.Uw*2*(y0 + (j + 0.5)*h)/a.H)
        profile.extend([u]*nx)
    profile = profile*nz
    write(os.path.join(d, "0/U"), "volVectorField", "U", """
dimensions      [0 1 -1 0 0 0 0];
internalField   nonuniform List<vector>
%d
(
%s
)
;
boundaryField
{
    bottom { type fixedValue; value uniform (%.12g 0 0); }
    top { type fixedValue; value uniform (%.12g 0 0); }
    left { type cyclic; }
    right { type cyclic; }
%s
}
""" % (nx*ny*nz, "\n".join(profile), -a.Uw, a.Uw, sideBC))
    write(os.path.join(d, "0/p"), "volScalarField", "p", """
dimensions      [0 2 -2 0 0 0 0];
internalField   uniform 0;
boundaryField
{
    bottom { type zeroGradient; }
    top { type zeroGradient; }
    left { type cyclic; }
    right { type cyclic; }
%s
}
""" % sideBC)
    write(os.path.join(d, "constant/transportProperties"), "dictionary",
          "transportProperties", "\ntransportModel  Newtonian;\nnu              %g;\n" % a.nu)
    write(os.path.join(d, "constant/turbulenceProperties"), "dictionary",
          "turbulenceProperties", "\nsimulationType  laminar;\n")
    write(os.path.join(d, "constant/g"), "uniformDimensionedVectorField", "g", """
dimensions      [0 1 -2 0 0 0 0];
value           (0 0 0);
""")
    # the unsteady-cylinder study's controlDict, its step set by maxCo (the
    # first step at a Courant number of 0.05 at the wall speed)
    run = argparse.Namespace(endTime=a.endTime, deltaT=min(0.05*h/a.Uw, a.maxDeltaT),
                             writeInterval=a.writeInterval or a.endTime)
    fo = """    bodies
    {
        type        immersedDEM;
        rhoInf      %g;
    }""" % RHO_F
    write(os.path.join(d, "system/controlDict"), "dictionary", "controlDict",
          oGrid.controlDict(run, '"libimmersedDEM.so"', fo).replace(
              "adjustTimeStep  no;", "adjustTimeStep  yes;\nmaxCo           %g;\nmaxDeltaT       %g;"
              % (a.maxCo, a.maxDeltaT)))
    # backward, two outer correctors; a reference pressure in the closed
    # periodic box (as settlingCylinder2D/makeCase.py immersed)
    settings = argparse.Namespace(ddt="backward", nOuter=2, nCorrectors=2, nNonOrth=0)
    write(os.path.join(d, "system/fvSchemes"), "dictionary", "fvSchemes", oGrid.fvSchemes(settings))
    write(os.path.join(d, "system/fvSolution"), "dictionary", "fvSolution",
          oGrid.fvSolution(settings).replace(
              "    nNonOrthogonalCorrectors 0;\n",
              "    nNonOrthogonalCorrectors 0;\n    pRefCell            0;\n    pRefValue           0;\n"))
    # constant/fvOptions and constant/immersedDEMProperties as the helper
    # writes them (a free body named cylinder, file cylinder.stl), then the
    # STL replaced by this body's prism, three slabs long (-slab to 2 slab)
    # like the helper's
    oGrid.immersedCylinder(d, a.slab, "(0 0 %.12g)" % (a.slab/2),
                           density="        density     %g;\n" % a.density)
    semiB = a.D/4 if a.shape == "ellipse" else a.D/2
    if sphere:
        # the body a sphere at the centre of the cell
        props = os.path.join(d, "constant/immersedDEMProperties")
        text = open(props).read().replace(
            "        shape       triangleMesh;\n        file        cylinder.stl;\n",
            "        shape       sphere;\n        radius      %.12g;\n" % (a.D/2)).replace(
            "position    (0 0 %.12g);" % (a.slab/2), "position    (0 0 0);").replace(
            "    cylinder\n    {", "    sphere\n    {")
        if "shape       sphere;" not in text or "position    (0 0 0);" not in text:
            raise SystemExit("makeCouette.py: could not make the body a sphere in %s" % props)
        open(props, "w").write(text)
        os.remove(os.path.join(d, "constant/triSurface/cylinder.stl"))
    else:
        prismSTL(os.path.join(d, "constant/triSurface/cylinder.stl"), a.D/2, semiB,
                 -a.slab, 2*a.slab)
    with open(os.path.join(d, "couetteParameters"), "w") as f:
        f.write("# makeCouette.py: the case's parameters (SI), read by checkCouette.py\n")
        for k, v in (("shape", a.shape), ("D", a.D), ("a", a.D/2), ("b", semiB), ("H", a.H),
                     ("Lx", a.Lx), ("Uw", a.Uw), ("nu", a.nu), ("density", a.density),
                     ("n", a.n), ("x0", 0.0), ("y0", 0.0), ("z0", 0.0), ("slab", a.slab),
                     ("Lz", a.Lz if sphere else a.slab)):
            f.write("%s %s\n" % (k, v if isinstance(v, str) else "%.12g" % v))
    return nx*ny*nz


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("dir")
    p.add_argument("-shape", choices=["circle", "ellipse", "sphere"], default="circle",
                   help="circle: diameter D; ellipse: semi-axes D/2 along x, D/4 along y; "
                   "sphere: diameter D, in a 3D cell periodic along x and z")
    p.add_argument("-Lz", type=float, default=None,
                   help="sphere: periodic length along z [m] (default -Lx)")
    p.add_argument("-D", type=float, default=0.002, help="body diameter (ellipse: major axis) [m]")
    p.add_argument("-H", type=float, default=0.02, help="distance between the walls [m]")
    p.add_argument("-Lx", type=float, default=0.02, help="periodic length along x [m]")
    p.add_argument("-Uw", type=float, default=0.01, help="wall speed: top +Uw, bottom -Uw [m/s]")
    p.add_argument("-n", type=int, default=10, help="cells per diameter")
    p.add_argument("-nu", type=float, default=1e-4, help="kinematic viscosity [m2/s]")
    p.add_argument("-density", type=float, default=2000, help="body density [kg/m3]")
    p.add_argument("-slab", type=float, default=0.001, help="slab (one cell) thickness [m]")
    p.add_argument("-maxCo", type=float, default=0.5)
    p.add_argument("-maxDeltaT", type=float, default=1, help="cap on the time step [s]")
    p.add_argument("-endTime", type=float, default=2.0)
    p.add_argument("-writeInterval", type=float, default=None, help="field writes [s] (default endTime)")
    a = p.parse_args()
    if a.Lz is None:
        a.Lz = a.Lx
    if min(a.D, a.H, a.Lx, a.Uw, a.nu, a.density, a.slab, a.maxCo, a.maxDeltaT, a.endTime) <= 0 \
            or a.n < 1:
        p.error("every size, speed, density, step and time must be positive")
    if a.D >= a.H or a.D >= a.Lx or (a.shape == "sphere" and a.D >= a.Lz):
        p.error("the body (D %g m) must fit between the walls and in the periodic length" % a.D)
    os.makedirs(a.dir, exist_ok=True)
    nc = couette(a)
    print("%s: couette, %s, %d cells" % (a.dir, a.shape, nc))


if __name__ == "__main__":
    main()
