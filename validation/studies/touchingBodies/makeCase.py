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
CFD step (no maxCo control); --periodic makes the box cyclic in all three
directions (--periodic xy: in x and y, walls at the bottom and top),
--gravity sets g.

  makeCase.py <case> --body a:cube:-0.005:0:0.1 [--body ...] [--wallPatch]
              [--lo "x y z"] [--hi "x y z"] [--h 3.125] [--endTime 0.2]
              [--youngsModulus 6.3e10] [--contact "level 2;"] [--sealedWalls]
              [--periodic [xy]] [--gravity "0 0 -9.81"]
"""
import argparse, os, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tankCase
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
p.add_argument("--periodic", nargs="?", const="xyz", default="",
               help="cyclic in these directions (xyz without a value) instead of walls")
p.add_argument("--gravity", default="0 0 -9.81", help="g [m/s2]")
a = p.parse_args()
lo = [float(x) for x in a.lo.split()]
hi = [float(x) for x in a.hi.split()]
n = [round((h - l)/a.h) for l, h in zip(lo, hi)]
write = tankCase.writer(a.case)
tankCase.writeTank(write, lo, hi, n, 0.001, a.nu, " sealedWalls yes;" if a.sealedWalls else "",
                   a.periodic, a.gravity)
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
tankCase.writeSolver(write)
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
