#!/usr/bin/env python3
"""makeCase.py <dir> <c> <cellsPerDiameter>

A simple cubic array of spheres (d = 1 m) at volume fraction c, from
caseTemplates/periodicSphereArray: a periodic box of two lattice cells a
side holding 2 x 2 x 2 fixed spheres (the code asks a period of at least
twice a body's size), each a fraction of a cell off the mesh's symmetry,
the same way in every lattice cell, so the eight are one array. nu = 1,
the mean velocity over the box (the superficial velocity, Zick & Homsy's
U) held at 0.01 m/s by meanVelocityForce: Re = 0.01. The step keeps the
template's viscous Fourier number nu deltaT/h^2 = 1.28 (0.02 s at 8
cells per diameter); the run lasts 2 s, 5 times the slowest viscous mode
of the largest box here (0.064: (2 L)^2/(4 pi^2 nu) = 0.41 s).
"""
import math, os, re, shutil, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
template = os.path.join(here, "..", "..", "..", "caseTemplates", "periodicSphereArray")
d, c, n = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
L = (math.pi/6/c)**(1.0/3)        # the lattice cell [m]
N = int(round(2*L*n))             # cells along the box (two lattice cells)
h = 2*L/N
shutil.rmtree(d, ignore_errors=True)
shutil.copytree(template, d)
os.chdir(d)
subprocess.run(["./Allclean"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
s = open("system/blockMeshDict").read()
s = re.sub(r"(?m)^L .*$", "L       %.10g;" % (2*L), s)
s = re.sub(r"(?m)^N .*$", "N       %d;" % N, s)
open("system/blockMeshDict", "w").write(s)


def setEntry(entry, value, path):
    subprocess.run(["foamDictionary", "-entry", entry, "-set", value, path], check=True, stdout=subprocess.DEVNULL)


setEntry("deltaT", "%.6g" % (0.02*(h*8)**2), "system/controlDict")
setEntry("endTime", "2", "system/controlDict")
setEntry("writeInterval", "2", "system/controlDict")
bodies = ""
for i in range(2):
    for j in range(2):
        for k in range(2):
            p = (L/2 + i*L + 0.3*h, L/2 + j*L + 0.67*h, L/2 + k*L + 1.01*h)
            bodies += ("    s%d%d%d { shape sphere; radius 0.5; material steel; density 1000;"
                       " position (%.10g %.10g %.10g); motion fixed; }\n" % ((i, j, k) + p))
s = open("constant/immersedDEMProperties").read()
s = s[:s.index("\nbodies")] + "\nbodies\n{\n" + bodies + "}\n"
open("constant/immersedDEMProperties", "w").write(s)
open("caseParameters", "w").write("c %g\ncellsPerDiameter %g\nN %d\nlatticeCell %.10g\n" % (c, N/(2*L), N, L))
