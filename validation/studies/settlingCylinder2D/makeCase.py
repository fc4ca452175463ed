#!/usr/bin/env python3
"""Write a case of a circular cylinder settling along the axis of a 2D
channel (issue 18: a free 2D body against a body-fitted reference).

    makeCase.py <dir> immersed   [-n 16] [options]
    makeCase.py <dir> bodyFitted -U <speed> [options]

The problem (SI units): cylinder diameter D = 10 mm, density (-density,
default 1500 kg/m3), in a liquid of 1000 kg/m3 and nu (default 1e-4 m2/s)
between two walls 8 D apart (blockage 1/8), gravity 9.81 m/s2 along the
channel. Settling on the axis it reaches a steady terminal velocity U_t at
Re = U_t D/nu of about 10 (at the default density). A body lighter than the
liquid rises instead; its terminal speed comes from the buoyant weight
|rho_s - rho_f| g pi D^2/4 per depth in the same way.

immersed: the lab frame. A closed channel of width 8 D and height -height D
    (-periodic: periodic along its length, a period of -height D),
    uniform cells D/n, one cell (1 mm) thick with empty front and back; the
    cylinder a free body (an STL prism longer than the slab) released at rest
    on the axis -start D below the top (or -startFromBottom D above the
    bottom, for a rising body); stock pimpleFoam, backward, two
    outer correctors, maxCo-controlled step; the motion in
    postProcessing/bodies/0/bodies.dat.
bodyFitted: the cylinder's frame at terminal speed, where the flow is
    steady: the cylinder held on the axis, the walls and the inflow moving
    past it at -U along the channel (here along +x, the cylinder's fall being
    -x); an O-grid of stock blockMesh (the one of the unsteady-cylinder
    study) with the channel walls as its sides; stock simpleFoam (SIMPLEC)
    to a converged steady state; the force on the cylinder from the stock
    forces function object. U_t is the U whose drag per slab depth equals the
    buoyant weight |rho_s - rho_f| g pi D^2/4 per depth,
    buoyantWeightPerDepth(rho_s) (terminal.py finds it). The flow around a
    rising body is the mirror image of that around a settling one, so the
    case itself does not depend on the density: -density only checks it
    (it must differ from the liquid's) and sets the weight.
"""
import argparse, importlib.util, math, os

here = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location(
    "unsteadyCylinderCase", os.path.join(here, "../unsteadyCylinder/makeCase.py"))
oGrid = importlib.util.module_from_spec(spec)
spec.loader.exec_module(oGrid)
write = oGrid.write

D = oGrid.D                       # 10 mm
RHO_F, RHO_S, G = 1000.0, 1500.0, 9.81
HALF_WIDTH = 4.0                  # channel half-width [D]


def buoyantWeightPerDepth(rhoS=RHO_S):
    """The body's weight less its buoyancy per slab depth [N/m], as a
    magnitude: a light body (rhoS < RHO_F) rises at the terminal speed of
    this drag"""
    return abs(rhoS - RHO_F)*G*math.pi*D*D/4


def transport(d, nu):
    write(os.path.join(d, "constant/transportProperties"), "dictionary",
          "transportProperties", "\ntransportModel  Newtonian;\nnu              %g;\n" % nu)
    write(os.path.join(d, "constant/turbulenceProperties"), "dictionary",
          "turbulenceProperties", "\nsimulationType  laminar;\n")


def bodyFitted(a):
    d = a.dir
    # the steady flow in the body's frame is the same (mirrored) for a
    # settling and a rising body: only the weight its drag must balance,
    # buoyantWeightPerDepth(a.density), depends on the density
    m = argparse.Namespace(nTheta=a.nTheta, nRadial=a.nRadial, radialGrading=a.radialGrading,
                           xUp=a.xUp, xDown=a.xDown, yHalf=HALF_WIDTH, hFar=a.hFar, slab=a.slab)
    mesh, nc = oGrid.bodyFittedMesh(m)
    # the O-grid's symmetry sides are the channel's walls here
    mesh = mesh.replace("sides { type symmetry;", "walls { type wall;")
    write(os.path.join(d, "system/blockMeshDict"), "dictionary", "blockMeshDict", mesh)
    u = "(%.12g 0 0)" % a.U
    write(os.path.join(d, "0/U"), "volVectorField", "U", """
dimensions      [0 1 -1 0 0 0 0];
internalField   uniform %s;
boundaryField
{
    inlet { type fixedValue; value uniform %s; }
    outlet { type inletOutlet; inletValue uniform (0 0 0); value uniform %s; }
    walls { type fixedValue; value uniform %s; }
    cylinder { type noSlip; }
    frontAndBack { type empty; }
}
""" % (u, u, u, u))
    write(os.path.join(d, "0/p"), "volScalarField", "p", """
dimensions      [0 2 -2 0 0 0 0];
internalField   uniform 0;
boundaryField
{
    inlet { type zeroGradient; }
    outlet { type fixedValue; value uniform 0; }
    walls { type zeroGradient; }
    cylinder { type zeroGradient; }
    frontAndBack { type empty; }
}
""")
    transport(d, a.nu)
    write(os.path.join(d, "system/controlDict"), "dictionary", "controlDict", """
application     simpleFoam;
startFrom       latestTime;
startTime       0;
stopAt          endTime;
endTime         %d;
deltaT          1;
writeControl    timeStep;
writeInterval   %d;
purgeWrite      1;
writeFormat     binary;
writePrecision  12;
writeCompression off;
timeFormat      general;
timePrecision   6;
runTimeModifiable false;

functions
{
    forces
    {
        type            forces;
        libs            ("libforces.so");
        writeControl    timeStep;
        writeInterval   1;
        patches         (cylinder);
        rho             rhoInf;
        rhoInf          %g;
        CofR            (0 0 0);
    }
}
""" % (a.iterations, a.iterations, RHO_F))
    write(os.path.join(d, "system/fvSchemes"), "dictionary", "fvSchemes",
          oGrid.fvSchemes(argparse.Namespace(ddt="steadyState"))
          .replace("div(phi,U)      Gauss linear", "div(phi,U)      bounded Gauss linear"))
    write(os.path.join(d, "system/fvSolution"), "dictionary", "fvSolution", """
solvers
{
    p
    {
        solver          GAMG;
        smoother        GaussSeidel;
        tolerance       1e-12;
        relTol          0.05;
    }
    U
    {
        solver          smoothSolver;
        smoother        symGaussSeidel;
        tolerance       1e-13;
        relTol          0.1;
    }
}
SIMPLE
{
    consistent      yes;
    nNonOrthogonalCorrectors 1;
    residualControl { p 1e-9; U 1e-10; }
}
relaxationFactors
{
    equations { U 0.9; }
}
""")
    return nc


def immersed(a):
    d = a.dir
    h = D/a.n
    nx = int(round(2*HALF_WIDTH*a.n))
    ny = int(round(a.height*a.n))
    # -periodic: bottom and top a cyclic pair (the channel periodic along
    # its length; the fvOption's balanceWeight holds the mean flux at zero)
    if a.periodic:
        boundaries = """    walls { type wall; faces ( (0 4 7 3) (1 2 6 5) ); }
    bottom { type cyclic; neighbourPatch top; faces ( (0 1 5 4) ); }
    top { type cyclic; neighbourPatch bottom; faces ( (3 7 6 2) ); }"""
    else:
        boundaries = "    walls { type wall; faces ( (0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2) ); }"
    write(os.path.join(d, "system/blockMeshDict"), "dictionary", "blockMeshDict", """
scale   %g;
vertices
(
    (%g 0 0) (%g 0 0) (%g %g 0) (%g %g 0)
    (%g 0 %g) (%g 0 %g) (%g %g %g) (%g %g %g)
);
blocks
(
    hex (0 1 2 3 4 5 6 7) (%d %d 1) simpleGrading (1 1 1)
);
boundary
(
%s
    frontAndBack { type empty; faces ( (0 3 2 1) (4 5 6 7) ); }
);
""" % (D, -HALF_WIDTH, HALF_WIDTH, HALF_WIDTH, a.height, -HALF_WIDTH, a.height,
       -HALF_WIDTH, a.slab/D, HALF_WIDTH, a.slab/D, HALF_WIDTH, a.height, a.slab/D,
       -HALF_WIDTH, a.height, a.slab/D, nx, ny, boundaries))
    cyclic = "    \"(bottom|top)\" { type cyclic; }\n" if a.periodic else ""
    write(os.path.join(d, "0/U"), "volVectorField", "U", """
dimensions      [0 1 -1 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{
    walls { type noSlip; }
%s    frontAndBack { type empty; }
}
""" % cyclic)
    write(os.path.join(d, "0/p"), "volScalarField", "p", """
dimensions      [0 2 -2 0 0 0 0];
internalField   uniform 0;
boundaryField
{
    walls { type zeroGradient; }
%s    frontAndBack { type empty; }
}
""" % cyclic)
    transport(d, a.nu)
    write(os.path.join(d, "constant/g"), "uniformDimensionedVectorField", "g", """
dimensions      [0 1 -2 0 0 0 0];
value           (0 %g 0);
""" % -G)
    # the unsteady-cylinder study's controlDict, its step set by maxCo
    run = argparse.Namespace(endTime=a.endTime, deltaT=0.05*h/0.1, writeInterval=a.endTime)
    fo = """    bodies
    {
        type        immersedDEM;
        rhoInf      %g;
    }""" % RHO_F
    write(os.path.join(d, "system/controlDict"), "dictionary", "controlDict",
          oGrid.controlDict(run, '"libimmersedDEM.so"', fo).replace(
              "adjustTimeStep  no;", "adjustTimeStep  yes;\nmaxCo           %g;\nmaxDeltaT       1;" % a.maxCo))
    # backward, two outer correctors: the unsteady-cylinder study's settings;
    # a reference pressure in the closed channel
    settings = argparse.Namespace(ddt="backward", nOuter=2, nCorrectors=2, nNonOrth=0)
    write(os.path.join(d, "system/fvSchemes"), "dictionary", "fvSchemes", oGrid.fvSchemes(settings))
    write(os.path.join(d, "system/fvSolution"), "dictionary", "fvSolution",
          oGrid.fvSolution(settings).replace(
              "    nNonOrthogonalCorrectors 0;\n",
              "    nNonOrthogonalCorrectors 0;\n    pRefCell            0;\n    pRefValue           0;\n"))
    y0 = (a.height - a.start)*D if a.startFromBottom is None else a.startFromBottom*D
    oGrid.immersedCylinder(d, a.slab, "(0 %g %g)" % (y0, a.slab/2),
                           density="        density     %g;\n" % a.density)
    return nx*ny


def main():
    p = argparse.ArgumentParser()
    p.add_argument("dir")
    p.add_argument("kind", choices=["bodyFitted", "immersed"])
    p.add_argument("-nu", type=float, default=1e-4, help="kinematic viscosity [m2/s]")
    p.add_argument("-slab", type=float, default=0.001)
    p.add_argument("-density", type=float, default=RHO_S,
                   help="cylinder density [kg/m3] (below %g: the body rises)" % RHO_F)
    # immersed
    p.add_argument("-n", type=int, default=16, help="immersed: cells per diameter")
    p.add_argument("-height", type=float, default=60, help="immersed: channel height [D]")
    p.add_argument("-start", type=float, default=6, help="immersed: start below the top [D]")
    p.add_argument("-startFromBottom", type=float, default=None,
                   help="immersed: start this far above the bottom [D] instead (for a rising body)")
    p.add_argument("-periodic", action="store_true",
                   help="immersed: the channel periodic along its length (bottom and top a cyclic pair)")
    p.add_argument("-endTime", type=float, default=3.0)
    p.add_argument("-maxCo", type=float, default=0.5)
    # bodyFitted
    p.add_argument("-U", type=float, default=0.1, help="bodyFitted: speed of the walls and inflow")
    p.add_argument("-nTheta", type=int, default=32, help="bodyFitted: cells per quarter circle")
    p.add_argument("-nRadial", type=int, default=40)
    p.add_argument("-radialGrading", type=float, default=15)
    p.add_argument("-xUp", type=float, default=12)
    p.add_argument("-xDown", type=float, default=24)
    p.add_argument("-hFar", type=float, default=0.25, help="largest cell far away [D]")
    p.add_argument("-iterations", type=int, default=4000)
    a = p.parse_args()
    if a.density <= 0 or a.density == RHO_F:
        p.error("-density must be positive and differ from the liquid's %g kg/m3" % RHO_F)
    if a.kind == "immersed":
        y0 = a.height - a.start if a.startFromBottom is None else a.startFromBottom
        if not 0.5 < y0 < a.height - 0.5:
            p.error("the cylinder (centre %g D above the bottom) is not inside the channel"
                    " of height %g D" % (y0, a.height))
    os.makedirs(a.dir, exist_ok=True)
    nc = bodyFitted(a) if a.kind == "bodyFitted" else immersed(a)
    print("%s: %s, %d cells" % (a.dir, a.kind, nc))


if __name__ == "__main__":
    main()
