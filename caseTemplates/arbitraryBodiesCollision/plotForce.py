#!/usr/bin/python3
"""The normal contact force against time from
postProcessing/bodies/0/contacts.dat (summed over the contact regions at each
DEM sub-step), written to postProcessing/bodies/0/contactForce.png."""
import os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src", "python"))
from immersedDEMData import readTable
from immersedDEMFigure import pyplot

plt = pyplot("plotForce.py", checksFollow=False)
if plt is None:
    sys.exit(1)

here = os.path.dirname(os.path.abspath(__file__))
folder = os.path.join(here, "postProcessing", "bodies", "0")
contacts = readTable(os.path.join(folder, "contacts.dat"))
force = {}
for time, Fn in zip(contacts["time"], contacts["Fn"]):
    force[time] = force.get(time, 0.0) + Fn
if not force:
    sys.exit("no contact in " + os.path.join(folder, "contacts.dat"))
t = sorted(force)
params = dict(l.rstrip("\n").split(" ", 1) for l in open(os.path.join(here, "caseParameters")))
fig, ax = plt.subplots(figsize=(7, 4.2))
ax.plot([1e3 * x for x in t], [force[x] for x in t], ".-", ms=2)
ax.set_xlabel("t [ms]")
ax.set_ylabel("normal contact force [N]")
ax.set_title("Lumpy star on bent rod: %s, %s cells per diameter, level %s"
             % (params["model"], params["cellsPerDiameter"], params["level"]))
ax.grid(alpha=0.3)
fig.tight_layout()
out = os.path.join(folder, "contactForce.png")
fig.savefig(out, dpi=120)
print("peak normal force %.4g N at %.4g ms; plot %s" % (max(force.values()), 1e3 * max(force, key=force.get), out))
