#!/usr/bin/env python3
"""Writes the coupled scale benchmark's case (issue 20): N lumpy stars
(caseTemplates/arbitraryBodiesCollision's lumpyStar.stl, 5,120 triangles,
volume-equivalent diameter d = 10 mm) at random orientations on a lattice
nx x ny x nz in a tank of water with wall patches (noSlip, DEM walls),
cubic cells of d/cellsPerBody, soft glass (Y 1e7, rho 2500), a fixed CFD
step of 1 ms, stock pimpleFoam, default coupling and contact settings.
The lattice spacing keeps every pair apart (no contact), as in the issue's
'settling lattice'; --spacing sets it in fluid cells instead (10: 1.25 d,
less than two of the star's largest radii: neighbours interlock, a packed
block where the DEM's contacts, films and separation proofs dominate).

  makeLattice.py <case> --lattice "4 4 8" [--cellsPerBody 8] [--steps 5]
                 [--seed 1] [--np 2] [--spacing CELLS]
"""
import argparse, math, os, random, shutil, struct, sys

here = os.path.dirname(os.path.abspath(__file__))
project = os.path.abspath(os.path.join(here, "..", "..", ".."))
sys.path.insert(0, os.path.join(project, "validation", "studies", "touchingBodies"))
import tankCase
star = os.path.join(project, "caseTemplates", "arbitraryBodiesCollision",
                    "constant", "triSurface", "lumpyStar.stl")

p = argparse.ArgumentParser()
p.add_argument("case")
p.add_argument("--lattice", default="4 4 8", help="bodies along x, y, z")
p.add_argument("--cellsPerBody", type=float, default=8, help="d/h")
p.add_argument("--steps", type=int, default=5, help="CFD steps of 1 ms")
p.add_argument("--seed", type=int, default=1)
p.add_argument("--np", type=int, default=2, help="subdomains of decomposeParDict")
p.add_argument("--spacing", type=int, default=0,
               help="lattice spacing in fluid cells (0: two radii and two cells apart)")
a = p.parse_args()
nx, ny, nz = (int(x) for x in a.lattice.split())

# The star's largest radius from its centroid (the STL is centred)
data = open(star, "rb").read()
nTri = struct.unpack("<I", data[80:84])[0]
rmax = 0.0
for i in range(nTri):
    v = struct.unpack("<12f", data[84 + 50*i:84 + 50*i + 48])
    for j in (3, 6, 9):
        rmax = max(rmax, math.sqrt(v[j]**2 + v[j + 1]**2 + v[j + 2]**2))
d = 0.01
h = d/a.cellsPerBody
# Spacing: two radii and two cells of fluid, in whole cells
spacing = h*(a.spacing if a.spacing > 0 else math.ceil((2*rmax + 2*h)/h))
n = [nx, ny, nz]
size = [k*spacing for k in n]
cells = [round(s/h) for s in size]

write = tankCase.writer(a.case)
shutil.copy(star, os.path.join(a.case, "constant", "triSurface", "lumpyStar.stl"))
tankCase.writeTank(write, [0.0, 0.0, 0.0], size, cells, 1, "1e-06")
write("system/controlDict", "dictionary", "controlDict", """application pimpleFoam;
libs ("libimmersedDEM.so");
startFrom startTime; startTime 0; stopAt endTime; endTime %g;
deltaT 0.001; adjustTimeStep no;
writeControl timeStep; writeInterval 100000; purgeWrite 0;
writeFormat binary; writePrecision 10; writeCompression off;
timeFormat general; timePrecision 8; runTimeModifiable false;
functions { bodies { type immersedDEM; rhoInf 1000; } }
""" % (a.steps*0.001))
tankCase.writeSolver(write)
write("system/decomposeParDict", "dictionary", "decomposeParDict",
      "numberOfSubdomains %d;\nmethod simple;\n"
      "simpleCoeffs { n (1 1 %d); delta 0.001; }\n" % (a.np, a.np))

rng = random.Random(a.seed)
bodies = ""
k = 0
for i in range(nx):
    for j in range(ny):
        for l in range(nz):
            x = [(i + 0.5)*spacing, (j + 0.5)*spacing, (l + 0.5)*spacing]
            # A random axis (uniform on the sphere) and angle
            z = rng.uniform(-1, 1); t = rng.uniform(0, 2*math.pi); s = math.sqrt(1 - z*z)
            ang = rng.uniform(0, 180)
            bodies += ("    star%d { shape triangleMesh; file \"lumpyStar.stl\"; material glass; "
                       "density 2500; position (%.9g %.9g %.9g); rotationAxis (%.6f %.6f %.6f); "
                       "rotationAngle %.4f; }\n" % (k, x[0], x[1], x[2], s*math.cos(t), s*math.sin(t), z, ang))
            k += 1
write("constant/immersedDEMProperties", "dictionary", "immersedDEMProperties",
      "materials { glass { youngsModulus 1e7; poissonsRatio 0.24; } }\n"
      "bodies\n{\n%s}\n"
      "walls { tank { type patch; patches (walls); material glass; } }\n" % bodies)
print("%d bodies, spacing %.4g m, %d x %d x %d = %d cells" % (k, spacing, cells[0], cells[1], cells[2],
      cells[0]*cells[1]*cells[2]))
