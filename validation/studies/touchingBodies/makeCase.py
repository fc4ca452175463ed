#!/usr/bin/env python3
"""Writes a small immersedDEM case for the dense-suspension case tests: a
tank of wall patches (noSlip) filled with water (nu 1e-6, rho 1000), cubic
cells, default coupling settings (surface sharp, penalty 1000,
addedMassCoefficient 1), maxCo-controlled step, bodies of glass density
(2500) given as name:shape:x:y:z[:vx:vy:vz[:motion]] [m, m/s] with shape
'cube' (10 mm edge, STL) or 'sphereR' (radius R [m]), an optional initial
velocity and motion (free, fixed, prescribed). --sealedWalls switches
sealedWalls on in the fvOption; --nu sets the fluid's viscosity,
--lubrication the entries of the lubrication dictionary, --deltaT a fixed
CFD step (no maxCo control).

  makeCase.py <case> --body a:cube:-0.005:0:0.1 [--body ...] [--wallPatch]
              [--lo "x y z"] [--hi "x y z"] [--h 3.125] [--endTime 0.2]
              [--youngsModulus 6.3e10] [--contact "level 2;"] [--sealedWalls]
"""
import argparse, os
p = argparse.ArgumentParser()
p.add_argument("case")
p.add_argument("--body", action="append", default=[])
p.add_argument("--wallPatch", action="store_true", help="the tank's patches are DEM walls")
p.add_argument("--lo", default="-25 -25 0", help="tank corner [mm]")
p.add_argument("--hi", default="25 25 150", help="tank corner [mm]")
p.add_argument("--h", type=float, default=3.125, help="cell size [mm]")
p.add_argument("--endTime", default="0.2")
p.add_argument("--writeInterval", default="0.1")
p.add_argument("--youngsModulus", default="6.3e10")
p.add_argument("--restitution", default="", help="the glass's restitution (default: the material default)")
p.add_argument("--sealedWalls", action="store_true", help="sealedWalls yes in the fvOption")
p.add_argument("--contact", default="", help="entries of the contact dictionary")
p.add_argument("--lubrication", default="", help="entries of the lubrication dictionary")
p.add_argument("--nu", default="1e-06", help="kinematic viscosity [m2/s]")
p.add_argument("--deltaT", default="", help="fixed CFD step [s]")
a = p.parse_args()
lo = [float(x) for x in a.lo.split()]
hi = [float(x) for x in a.hi.split()]
n = [round((h - l)/a.h) for l, h in zip(lo, hi)]
for s in ("0", "constant/triSurface", "system"):
    os.makedirs(os.path.join(a.case, s), exist_ok=True)

def write(path, cls, obj, body):
    with open(os.path.join(a.case, path), "w") as f:
        f.write("FoamFile { version 2.0; format ascii; class %s; object %s; }\n\n%s"
                % (cls, obj, body))

write("0/U", "volVectorField", "U", "dimensions [0 1 -1 0 0 0 0];\n"
      "internalField uniform (0 0 0);\nboundaryField { walls { type noSlip; } }\n")
write("0/p", "volScalarField", "p", "dimensions [0 2 -2 0 0 0 0];\n"
      "internalField uniform 0;\nboundaryField { walls { type zeroGradient; } }\n")
write("constant/g", "uniformDimensionedVectorField", "g",
      "dimensions [0 1 -2 0 0 0 0];\nvalue (0 0 -9.81);\n")
write("constant/transportProperties", "dictionary", "transportProperties",
      "transportModel Newtonian;\nnu %s;\n" % a.nu)
write("constant/turbulenceProperties", "dictionary", "turbulenceProperties",
      "simulationType laminar;\n")
write("constant/fvOptions", "dictionary", "fvOptions",
      "bodies { type immersedBoundaryForce; fields (U);%s }\n"
      % (" sealedWalls yes;" if a.sealedWalls else ""))
corners = [(lo[0], lo[1], lo[2]), (hi[0], lo[1], lo[2]), (hi[0], hi[1], lo[2]), (lo[0], hi[1], lo[2]),
           (lo[0], lo[1], hi[2]), (hi[0], lo[1], hi[2]), (hi[0], hi[1], hi[2]), (lo[0], hi[1], hi[2])]
write("system/blockMeshDict", "dictionary", "blockMeshDict",
      "scale 0.001;\nvertices (" + " ".join("(%g %g %g)" % c for c in corners) + ");\n"
      "blocks ( hex (0 1 2 3 4 5 6 7) (%d %d %d) simpleGrading (1 1 1) );\n" % tuple(n) +
      "boundary ( walls { type wall; faces ( (0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2)"
      " (0 3 2 1) (4 5 6 7) ); } );\n")
write("system/controlDict", "dictionary", "controlDict", """application pimpleFoam;
libs ("libimmersedDEM.so");
startFrom latestTime; startTime 0; stopAt endTime; endTime %s;
%s
writeControl adjustableRunTime; writeInterval %s; purgeWrite 0;
writeFormat binary; writePrecision 10; writeCompression off;
timeFormat general; timePrecision 8; runTimeModifiable false;
functions { bodies { type immersedDEM; rhoInf 1000; } }
""" % (a.endTime,
       "deltaT %s; adjustTimeStep no;" % a.deltaT if a.deltaT
       else "deltaT 0.0005; adjustTimeStep yes; maxCo 0.5; maxDeltaT 0.005;",
       a.writeInterval))
write("system/fvSchemes", "dictionary", "fvSchemes", """ddtSchemes { default backward; }
gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linear; div((nuEff*dev2(T(grad(U))))) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
""")
write("system/fvSolution", "dictionary", "fvSolution", """solvers
{
    p { solver GAMG; smoother GaussSeidel; tolerance 1e-7; relTol 0.01; }
    pFinal { $p; relTol 0; }
    "(U|UFinal)" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-8; relTol 0; }
}
PIMPLE { momentumPredictor yes; nOuterCorrectors 1; nCorrectors 2; nNonOrthogonalCorrectors 0; pRefCell 0; pRefValue 0; }
""")
# A 10 mm cube centred on the origin, outward normals [m]
e = 0.005
vtx = [(x, y, z) for x in (-e, e) for y in (-e, e) for z in (-e, e)]
quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
with open(os.path.join(a.case, "constant/triSurface/cube.stl"), "w") as f:
    f.write("solid cube\n")
    for q in quads:
        for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for i in t:
                f.write("   vertex %g %g %g\n" % vtx[i])
            f.write("  endloop\n endfacet\n")
    f.write("endsolid cube\n")
bodies = ""
for spec in a.body:
    name, shape, x, y, z, *vel = spec.split(":")
    motion = " motion %s;" % vel.pop() if len(vel) == 4 else ""
    if shape == "cube":
        geo = 'shape triangleMesh; file "cube.stl"; scale 1;'
    elif shape.startswith("sphere"):
        geo = "shape sphere; radius %s;" % shape[len("sphere"):]
    else:
        raise SystemExit("unknown shape " + shape)
    velocity = " velocity (%s %s %s);" % tuple(vel) if vel else ""
    bodies += "    %s { %s material glass; density 2500; position (%s %s %s);%s%s }\n" % (
        name, geo, x, y, z, velocity, motion)
walls = "walls { tank { type patch; patches (walls); material glass; } }\n" if a.wallPatch else ""
contact = "contact { %s }\n" % a.contact if a.contact else ""
contact += "lubrication { %s }\n" % a.lubrication if a.lubrication else ""
write("constant/immersedDEMProperties", "dictionary", "immersedDEMProperties",
      "materials { glass { youngsModulus %s; poissonsRatio 0.24;%s } }\n%sbodies\n{\n%s}\n%s"
      % (a.youngsModulus, " restitution %s;" % a.restitution if a.restitution else "", contact, bodies, walls))
