"""immersedDEMData and immersedDEMPlot run as a user would, on tables
written like the solver's (columns in a different order than usual, a
half-written last row): values by column name, errors that name the
column, plots written. Exit 1 on any failure."""
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
pyDir = os.path.join(here, "..", "..", "src", "python")
sys.path.insert(0, pyDir)
from immersedDEMData import readTable  # noqa: E402

fails = []


def check(what, ok, detail=""):
    print(("PASS: " if ok else "FAIL: ") + what + (" (" + detail + ")" if detail else ""))
    if not ok:
        fails.append(what)


work = tempfile.mkdtemp(prefix="immersedDEMPlot-")
out = os.path.join(work, "postProcessing", "bodies", "0")
os.makedirs(out)
with open(os.path.join(out, "bodies.dat"), "w") as f:
    f.write("# time body vz x y z vx vy\n")
    for i in range(5):
        t = 0.01 * i
        f.write("%g ball %g 0 0 %g 0.1 0\n" % (t, -0.1 * t, 0.05 - t))
        f.write("%g cube %g 1 0 0 0 0\n" % (t, 0.0))
    f.write("0.05 ball -0.0")          # being written: too short
with open(os.path.join(out, "contacts.dat"), "w") as f:
    f.write("# time bodyA bodyB volume Fn nx ny nz px py pz Ftx Fty Ftz\n")
    f.write("0.02 ball cube 1e-12 0.5 0 0 1 0 0 0 0 0 0\n")

t = readTable(os.path.join(out, "bodies.dat"))
check("rows of the wrong length are skipped", len(t) == 10, "%d rows" % len(t))
ball = t.where(body="ball")
check("values by column name, whatever the order",
      all(abs(z - (0.05 - 0.01 * i)) < 1e-12 for i, z in enumerate(ball["z"]))
      and abs(ball.last("vz") + 0.1 * 0.04) < 1e-12 and ball["x"] == [0.0] * 5)
check("body names stay text, in order of appearance", t.bodies() == ["ball", "cube"])
try:
    t["Fz"]
    check("an unknown column is an error naming it", False)
except KeyError as e:
    check("an unknown column is an error naming it", "Fz" in str(e) and "bodies.dat" in str(e))
c = readTable(os.path.join(out, "contacts.dat"))
check("contacts by name", c["Fn"] == [0.5] and c["bodyB"] == ["cube"])


def plot(*args):
    # As a user runs it: the script itself, with its own interpreter
    # (Debian's python3, which has matplotlib)
    return subprocess.run([os.path.join(pyDir, "immersedDEMPlot"), "-case", work] + list(args),
                          capture_output=True, text=True)


r = plot("z", "vz", "-bodies", "ball", "-o", os.path.join(work, "zv.png"))
check("plot of two columns for one body", r.returncode == 0 and os.path.getsize(os.path.join(work, "zv.png")) > 1000,
      r.stderr.strip())
r = plot("-contacts", "Fn")
check("plot of contacts.dat into the output folder", r.returncode == 0
      and os.path.exists(os.path.join(out, "Fn.png")), r.stderr.strip())
r = plot("-energy")
check("kinetic energy plot", r.returncode == 0 and os.path.exists(os.path.join(out, "kineticEnergy.png")),
      r.stderr.strip())
# A restart from 0.03 (its own folder, a column more: a newer version's
# table) replaces the first run's rows from 0.03 on; the default plot joins
# both runs, -time takes one
rs = os.path.join(work, "postProcessing", "bodies", "0.03")
os.makedirs(rs)
with open(os.path.join(rs, "bodies.dat"), "w") as f:
    f.write("# time body vz x y z vx vy m\n")
    for i in range(3, 8):
        t = 0.01 * i
        f.write("%g ball %g 0 0 %g 0.1 0 0.002\n" % (t, -0.1 * t, 0.05 - t))
from immersedDEMData import readRuns  # noqa: E402
j = readRuns(os.path.join(work, "postProcessing", "bodies"))
check("runs joined on their shared columns, the restart's rows from its start",
      j.columns == ["time", "body", "vz", "x", "y", "z", "vx", "vy"]
      and sorted(set(j["time"])) == [0.01 * i for i in range(8)]
      and len(j.where(body="cube")) == 3, "%s, %d rows" % (j.columns, len(j)))
r = plot("z")
check("by default every run of the case is plotted (t 0 to 0.07)",
      r.returncode == 0 and "t 0 to 0.07" in r.stdout, r.stdout.strip() + r.stderr.strip())
r = plot("z", "-time", "0.03")
check("-time: only that run", r.returncode == 0 and "t 0.03 to 0.07" in r.stdout and "5 rows" in r.stdout,
      r.stdout.strip() + r.stderr.strip())
r = plot("Fq")
check("an unknown column: exit 1 naming it", r.returncode == 1 and "'Fq'" in r.stderr, r.stderr.strip())
r = plot("z", "-name", "nothere")
check("a missing output folder: exit 1 naming it", r.returncode == 1 and "nothere" in r.stderr, r.stderr.strip())

# Without matplotlib: exit 1, naming what is missing and how to get it
fake = os.path.join(work, "nompl")
os.makedirs(fake)
with open(os.path.join(fake, "matplotlib.py"), "w") as f:
    f.write("raise ImportError('No module named matplotlib (test)')\n")
r = subprocess.run([os.path.join(pyDir, "immersedDEMPlot"), "-case", work, "z"], capture_output=True, text=True,
                   env=dict(os.environ, PYTHONPATH=fake))
check("without matplotlib: exit 1 naming it and the remedy", r.returncode == 1
      and "cannot import matplotlib" in r.stderr and "python3-matplotlib" in r.stderr, r.stderr.strip())

print("%d failed" % len(fails))
sys.exit(1 if fails else 0)
