#!/usr/bin/python3
"""fixedBed.py: the settled bead bed of a packedBed run, frozen, as a case
for the flow alone at another resolution.

Usage: fixedBed.py POUR CASE CELLS [-tEnd T] [-above MM]

POUR   a finished run of caseTemplates/packedBed with -spheres (its
       bodies.dat and VTK)
CASE   the case to write (emptied first)
CELLS  cells per bead diameter (3, 6, 12: cells of 1, 0.5, 0.25 mm for
       the 3 mm beads)

The beads take their positions at the last time of the pour's table and
their radii from its last VTK (the largest distance of a bead's vertices
from its centre: the tessellation's corners lie on the sphere), each a
body with `motion fixed`. The tube is the pour's (square, same side),
cut -above MM above the highest bead (default 9 mm, three diameters: a tap
above the bed and an outlet the bed's wakes do not reach). The inflow
ramps from 0 to the pour's Uin in 0.02 s and holds to -tEnd (default 0.5
s). Every other setting is the template's.
"""
import math
import os
import re
import shutil
import sys

for _d in (os.path.join(os.environ.get("IMMERSEDDEM_DIR", ""), "src", "python"),
           os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python")):
    if os.path.isfile(os.path.join(_d, "immersedDEMData.py")) and _d not in sys.path:
        sys.path.append(_d)
from immersedDEMData import readRuns  # noqa: E402


def fail(msg):
    sys.stderr.write("fixedBed.py: %s\n" % msg)
    sys.exit(1)


def setEntry(path, name, value):
    t = open(path).read()
    t2, n = re.subn(r"(?m)^(%s\s+)[^;]*;" % re.escape(name), r"\g<1>%s;" % value, t)
    if n != 1:
        fail("no single '%s' entry in %s" % (name, path))
    open(path, "w").write(t2)


def lastVTK(pour):
    best = None
    for root, _, files in os.walk(os.path.join(pour, "postProcessing", "bed")):
        for f in files:
            m = re.match(r"bodies_([0-9.eE+-]+)\.vtk$", f)
            if m and (best is None or float(m.group(1)) > best[0]):
                best = (float(m.group(1)), os.path.join(root, f))
    if best is None:
        fail("no VTK/bodies_<time>.vtk under %s/postProcessing/bed" % pour)
    return best


def vtkPoints(path):
    """{body index: [points]} of a VTK written by immersedDEM."""
    w = open(path).read().split()
    i = w.index("POINTS")
    n = int(w[i + 1])
    xs = [float(v) for v in w[i + 3:i + 3 + 3*n]]
    pts = [tuple(xs[3*k:3*k + 3]) for k in range(n)]
    i = w.index("POLYGONS")
    m = int(w[i + 1])
    faces = []
    j = i + 3
    for _ in range(m):
        faces.append([int(v) for v in w[j + 1:j + 4]])
        j += 4
    i = w.index("LOOKUP_TABLE", j)
    ids = [int(v) for v in w[i + 2:i + 2 + m]]
    out = {}
    for b, f in zip(ids, faces):
        out.setdefault(b, set()).update(f)
    return {b: [pts[k] for k in s] for b, s in out.items()}


def readBeads(pour):
    table = readRuns(os.path.join(pour, "postProcessing", "bed"))
    tLast = max(table["time"])
    rows = [r for r in table.rows if abs(r[table.index("time")] - tLast) < 1e-12]
    names = [r[table.index("body")] for r in rows]
    centres = [tuple(r[table.index(k)] for k in ("x", "y", "z")) for r in rows]
    speed = max(math.sqrt(sum(r[table.index(k)]**2 for k in ("vx", "vy", "vz"))) for r in rows)
    tVtk, vtk = lastVTK(pour)
    pts = vtkPoints(vtk)
    if len(pts) != len(rows):
        fail("%s has %d bodies, the table at t %g has %d" % (vtk, len(pts), tLast, len(rows)))
    beads = []
    for (b, p), name, c in zip(sorted(pts.items()), names, centres):
        d = [math.dist(q, c) for q in p]
        r = max(d)
        # A sphere: every vertex at the same distance (the VTK at the table's
        # last time: else the bead moved between them)
        if min(d) < (1 - 1e-6)*r:
            fail("body %s of %s is not a sphere about its table centre (vertex distances %.6g-%.6g m): "
                 "the VTK at t %g and the table at t %g disagree, or the pour was not of beads "
                 "(Allrun -spheres)" % (name, vtk, min(d), r, tVtk, tLast))
        beads.append((name, c, r))
    return beads, tLast, tVtk, speed


def main():
    args = sys.argv[1:]
    tEnd, above = 0.5, 9.0
    pos = []
    while args:
        a = args.pop(0)
        if a == "-tEnd" and args:
            tEnd = float(args.pop(0))
        elif a == "-above" and args:
            above = float(args.pop(0))
        else:
            pos.append(a)
    if len(pos) != 3:
        fail("usage: fixedBed.py POUR CASE CELLS [-tEnd T] [-above MM]")
    pour, case, cells = pos[0], pos[1], int(pos[2])
    if cells % 3:
        fail("CELLS must be a multiple of 3 (cells of 3/CELLS mm on a 20 mm tube)")
    beads, tLast, tVtk, speed = readBeads(pour)
    if abs(tLast - tVtk) > 1e-9:
        fail("the pour's table ends at t %g, its last VTK is at t %g: run the pour to a write time" % (tLast, tVtk))
    zTop = max(c[2] + r for _, c, r in beads)
    H = math.ceil(zTop*1e3 + above)
    if os.path.exists(case):
        shutil.rmtree(case)
    os.makedirs(case)
    for d in ("0", "system", "constant"):
        shutil.copytree(os.path.join(pour, d), os.path.join(case, d))
    shutil.rmtree(os.path.join(case, "constant", "polyMesh"), ignore_errors=True)
    shutil.copytree(os.path.join(pour, "constant", "triSurface"), os.path.join(case, "constant", "triSurface"),
                    dirs_exist_ok=True)
    bp = os.path.join(case, "system", "bedParameters")
    for k, v in (("H", H), ("nXY", 20*cells//3), ("nZ", H*cells//3), ("tFlow", 0.001), ("tRamp", 0.02),
                 ("tEnd", tEnd)):
        setEntry(bp, k, v)
    p = os.path.join(case, "constant", "immersedDEMProperties")
    t = open(p).read()
    m = re.search(r"(?ms)^insertion\s*\{.*?^\}\s*$", t)
    if not m:
        fail("no insertion dictionary in %s" % p)
    mat = re.search(r"material\s+(\w+);", t).group(1)
    rho = re.search(r"density\s+([^;]+);", t).group(1)
    lines = ["// The pour's beads at t %g s (%s), frozen: issue 48, packed-bed resolution study" % (tLast, pour),
             "bodies", "{"]
    for name, c, r in beads:
        lines.append("    %s { shape sphere; radius %.9g; material %s; density %s; position (%.9g %.9g %.9g); "
                     "motion fixed; }" % (name, r, mat, rho, c[0], c[1], c[2]))
    lines.append("}")
    t = t[:m.start()] + "\n".join(lines) + "\n" + t[m.end():]
    open(p, "w").write(t)
    # Pressure taps every millimetre, an eighth of a millimetre above it (off
    # the faces of 1, 0.5 and 0.25 mm cells), and the inlet: the template's
    # taps (a quarter above) sit on the faces of 0.25 mm cells
    common = ('type surfaceFieldValue; libs ("libfieldFunctionObjects.so"); timeStart $tFlow; '
              'writeControl timeStep; writeInterval 1; log false; writeFields false; '
              'operation areaAverage; fields (p);')
    with open(os.path.join(case, "system", "pressureTaps"), "w") as f:
        f.write("// Written by fixedBed.py: the mean p over the inlet and over planes at z + 0.125 mm\n")
        f.write("pInlet { %s regionType patch; name inlet; }\n" % common)
        for z in range(1, H):
            f.write("p_z%03d { %s regionType sampledSurface; name p_z%03d; sampledSurfaceDict { type "
                    "cuttingPlane; planeType pointAndNormal; pointAndNormalDict { point (0 0 %d.125e-3); "
                    "normal (0 0 1); } interpolate false; } }\n" % (z, common, z, z))
    with open(os.path.join(case, "beads.txt"), "w") as f:
        f.write("# the frozen beads: name x y z radius [m]; pour %s at t %g s (largest speed there %.3g m/s)\n"
                % (os.path.abspath(pour), tLast, speed))
        for name, c, r in beads:
            f.write("%s %.9g %.9g %.9g %.9g\n" % (name, c[0], c[1], c[2], r))
    print("fixedBed.py: %d beads (t %g s, largest speed %.3g m/s), tube %d mm high, %d cells per bead "
          "diameter, to t %g s: %s" % (len(beads), tLast, speed, H, cells, tEnd, case))


if __name__ == "__main__":
    main()
