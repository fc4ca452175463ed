"""Checks of the bouncingBodies results; exit 1 on any failure.

    check.py <output folder> [<case>]

The case (default: three folders above the output folder) gives gravity,
the bodies' sizes, densities, start and restitution (constant/g,
constant/immersedDEMProperties)."""
import json
import math
import os
import sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMData import readTable
from immersedDEMCase import caseConstants, number, vector

out = sys.argv[1]
case = sys.argv[2] if len(sys.argv) > 2 else os.path.join(out, "..", "..", "..")
fails = []


def check(what, ok, detail=""):
    print(("PASS: " if ok else "FAIL: ") + what + (" (" + detail + ")" if detail else ""))
    if not ok:
        fails.append(what)


# bodies.dat: header and rows
table = readTable(os.path.join(out, "bodies.dat"))
header = table.columns
need = "time body x y z vx vy vz wx wy wz Fx Fy Fz Fcx Fcy Fcz Ffx Ffy Ffz".split()
check("bodies.dat has the documented columns", all(c in header for c in need))
col = {c: i for i, c in enumerate(header)}
rows = table.rows
num = lambda r, c: r[col[c]]
finite = all(math.isfinite(x) for r in rows for x in r if x not in ("ball", "block"))
check("no NaN or inf in bodies.dat", finite)

ball = [r for r in rows if r[col["body"]] == "ball"]
block = [r for r in rows if r[col["body"]] == "block"]

# The case: the ball falls from its start onto the floor; the block's
# weight and thickness from its surface
c = caseConstants(case)
props = c.dictionary("constant", "immersedDEMProperties")
g = c.gravity
ballEntry = props["bodies"]["ball"]
R = number(ballEntry["radius"])
drop = vector(ballEntry["position"])[2] - R
vImpact = math.sqrt(2 * g * drop)
materials = props["materials"]
floorMaterial = props["walls"]["floor"]["material"]
# pair restitution: the smaller of the ball's and the floor's
e = min(number(materials[ballEntry["material"]]["restitution"]),
        number(materials[floorMaterial]["restitution"]))
blockEntry = props["bodies"]["block"]
scale = number(blockEntry.get("scale", "1"))
stl = [tuple(float(x)*scale for x in l.split()[1:4])
       for l in open(os.path.join(case, "constant", "triSurface", blockEntry["file"].strip('"')))
       if l.strip().startswith("vertex")]
volume = abs(sum(a[0]*(b[1]*d[2] - b[2]*d[1]) - a[1]*(b[0]*d[2] - b[2]*d[0]) + a[2]*(b[0]*d[1] - b[1]*d[0])
                 for a, b, d in zip(stl[0::3], stl[1::3], stl[2::3]))/6)
blockMass = number(blockEntry["density"])*volume
# lying flat on its largest face: the centroid half its smallest extent up
blockHalf = min(max(p[k] for p in stl) - min(p[k] for p in stl) for k in range(3))/2
first = next(i for i, r in enumerate(ball) if num(r, "vz") > 0)
vUp = max(num(r, "vz") for r in ball[first:first + 50])
# 5%: the case's virtual mesh is coarse (h = 2 mm = d/5, 2 levels, for
# speed), its volume law's error at that size; the 2% acceptance of the
# restitution is the unit test demRestitution (analytic geometry)
check("ball rebounds with e = %.2f within 5%%" % e, abs(vUp / (e * vImpact) - 1) < 0.05,
      "rebound %.4f m/s, impact %.4f m/s, ratio %.4f" % (vUp, vImpact, vUp / vImpact))
# 10% of R: the soft rubber's deepest overlap at this impact is just
# below it (Hertz's (15 m v^2/(16 E* sqrt(R)))^(2/5) is 9.5% of R); a
# contact missed lets the ball through by R or more
check("ball never passes through the floor (overlap < 10% of R)",
      min(num(r, "z") for r in ball) > R * 0.9, "min z %.6f" % min(num(r, "z") for r in ball))

last = ball[-1]
# at rest: within 1% of R of touching (pressed in by its own weight, a
# fraction of a percent for this soft rubber) and 1e-3 m/s (against an
# impact of 0.94 m/s: a bounce still going would be far above it)
check("ball at rest on the floor", abs(num(last, "z") - R) < 0.01 * R
      and abs(num(last, "vz")) < 1e-3, "z %.6f vz %.2e" % (num(last, "z"), num(last, "vz")))
lb = block[-1]
speed = math.sqrt(sum(num(lb, c) ** 2 for c in ("vx", "vy", "vz")))
# 2% of its half thickness: flat, not on an edge (which would be 30% up)
check("block at rest flat on the floor (centroid %g mm up)" % (1e3*blockHalf),
      abs(num(lb, "z") - blockHalf) < 0.02 * blockHalf and speed < 1e-3,
      "z %.6f speed %.2e" % (num(lb, "z"), speed))
# At rest the contact carries the weight on average (momentum balance);
# 2%: the contact's oscillation about rest sampled at the written times
tail = [num(r, "Fcz") for r in block if num(r, "time") > 0.3]
mean = sum(tail) / len(tail)
check("mean contact force on the resting block balances its weight within 2%",
      abs(mean / (blockMass * g) - 1) < 0.02, "mean Fcz %.6f N, weight %.6f N" % (mean, blockMass * g))

# contacts.dat
contacts = readTable(os.path.join(out, "contacts.dat"))
check("contacts.dat header and rows", contacts.columns[:5] == "time bodyA bodyB volume Fn".split()
      and len(contacts) > 0 and all(a == "floor" for a in contacts["bodyA"]))

# VTK series: every write time, each file complete
vtk = os.path.join(out, "VTK")
series = json.load(open(os.path.join(vtk, "bodies.vtk.series")))
times = [f["time"] for f in series["files"]]
check("VTK series lists the 9 write times", len(times) == 9 and abs(times[-1] - 0.4) < 1e-9,
      str(times[:3]) + "...")
ok = True
for f in series["files"]:
    text = open(os.path.join(vtk, f["name"])).read().split("\n")
    npts = int(next(l for l in text if l.startswith("POINTS")).split()[1])
    npoly = int(next(l for l in text if l.startswith("POLYGONS")).split()[1])
    ok = ok and npts > 0 and npoly > 0 and text[-2].strip() != ""
check("every VTK file is complete", ok)

print("%d checks failed" % len(fails))
sys.exit(1 if fails else 0)
