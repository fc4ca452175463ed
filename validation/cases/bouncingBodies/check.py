"""Checks of the bouncingBodies results; exit 1 on any failure."""
import json
import math
import os
import sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMData import readTable

out = sys.argv[1]
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

# The ball falls from z = 0.05 (bottom 45 mm above the floor) onto the floor
g, R, drop = 9.81, 0.005, 0.045
vImpact = math.sqrt(2 * g * drop)
e = min(0.5, 0.9)       # pair restitution: the smaller of rubber and steel
first = next(i for i, r in enumerate(ball) if num(r, "vz") > 0)
vUp = max(num(r, "vz") for r in ball[first:first + 50])
# The case's virtual mesh is coarse (h = 2 mm = d/5, 2 levels, for speed),
# so the rebound is within 5% here; the 2% acceptance of the restitution
# is the unit test demRestitution (analytic geometry)
check("ball rebounds with e = %.2f within 5%%" % e, abs(vUp / (e * vImpact) - 1) < 0.05,
      "rebound %.4f m/s, impact %.4f m/s, ratio %.4f" % (vUp, vImpact, vUp / vImpact))
check("ball never passes through the floor (overlap < 10% of R)",
      min(num(r, "z") for r in ball) > R * 0.9, "min z %.6f" % min(num(r, "z") for r in ball))

last = ball[-1]
check("ball at rest on the floor", abs(num(last, "z") - R) < 0.01 * R
      and abs(num(last, "vz")) < 1e-3, "z %.6f vz %.2e" % (num(last, "z"), num(last, "vz")))
lb = block[-1]
speed = math.sqrt(sum(num(lb, c) ** 2 for c in ("vx", "vy", "vz")))
check("block at rest flat on the floor (centroid 2 mm up)",
      abs(num(lb, "z") - 0.002) < 0.02 * 0.002 and speed < 1e-3,
      "z %.6f speed %.2e" % (num(lb, "z"), speed))
# At rest the contact carries the weight on average (momentum balance)
tail = [num(r, "Fcz") for r in block if num(r, "time") > 0.3]
mean = sum(tail) / len(tail)
check("mean contact force on the resting block balances its weight within 2%",
      abs(mean / (0.0006 * g) - 1) < 0.02, "mean Fcz %.6f N, weight %.6f N" % (mean, 0.0006 * g))

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
