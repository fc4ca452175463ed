#!/usr/bin/python3
"""Terminal velocities of the settling-sphere runs against ten Cate et al.
(Phys. Fluids 14, 4012, 2002, Table 1), the plot of velocity against time,
and the plugin's share of the run time (from the immersedDEM log lines).

    plotSettlingSphere.py <work folder> E1 E2 ...

Also compares with the Navier-Stokes terminal velocity on a body-fitted
mesh (bodyFitted/results.txt, the finest level there) where it exists.

Writes settlingSphere.png and results.txt next to this script; exits 1 when a
terminal velocity is off the measured one by more than 3% or a sphere does
not come to rest on the bottom."""
import os, re, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMData import readTable
from immersedDEMCase import caseConstants, number

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

# ten Cate et al. (2002), Table 1: measured terminal velocity [m/s]
measured = {"E1": 0.038, "E2": 0.060, "E3": 0.091, "E4": 0.128}
# 3%: the study's target, about the measurement's own uncertainty (a 0.5%
# error in either stated density moves the terminal velocity by 2-3%:
# README)
tolerance = 0.03

here = os.path.dirname(os.path.abspath(__file__))
work, fluids = sys.argv[1], sys.argv[2:]


def trajectory(case):
    b = readTable(os.path.join(case, "postProcessing/sphere/0/bodies.dat"))
    return b["time"], b["z"], [-w for w in b["vz"]]



def bodyFitted():
    """Terminal velocity per fluid from bodyFitted/results.txt, finest level"""
    best = {}
    path = os.path.join(here, "bodyFitted", "results.txt")
    if not os.path.exists(path):
        return {}
    for line in open(path):
        m = re.match(r"(E\d) level (\d+) .*terminal velocity (\S+) m/s", line)
        if m and int(m.group(2)) >= best.get(m.group(1), (-1, 0))[0]:
            best[m.group(1)] = (int(m.group(2)), float(m.group(3)))
    return {f: u for f, (level, u) in best.items()}


def pluginShare(log):
    """Seconds in projection + DEM + forcing over the solver's wall time
    (both wall-clock: the plugin's timers are, and CPU time would overstate
    the share while other jobs share the cores)"""
    plugin, total = 0.0, 0.0
    for line in open(log):
        m = re.search(r"seconds: projection (\S+) DEM (\S+) forcing (\S+)", line)
        if m:
            plugin += sum(float(x) for x in m.groups())
        m = re.match(r"ExecutionTime = \S+ s\s+ClockTime = (\S+) s", line)
        if m:
            total = float(m.group(1))
    return plugin, total


rows, ok = [], True
reference = bodyFitted()
fig, ax = plt.subplots(figsize=(7, 4.5))
for f in fluids:
    case = os.path.join(work, f)
    t, z, w = trajectory(case)
    R = number(caseConstants(case).bodyEntry("sphere")["radius"])   # the case's
    d = 2*R
    # The terminal velocity: the largest settling velocity while the sphere
    # is more than a diameter above the bottom (the landing is not part of
    # it); whether it lands and rests: centre within 0.1 mm of R, at rest
    u = max(wi for zi, wi in zip(z, w) if zi > R + d)
    # at rest: 0.1 mm (the contact's overlap and the sealed wall cells are
    # far less) and 1 mm/s (against a terminal velocity of 38-128 mm/s)
    rests = abs(z[-1] - R) < 1e-4 and abs(w[-1]) < 1e-3
    ok &= rests
    err = u / measured[f] - 1
    plugin, total = pluginShare(os.path.join(case, "log.pimpleFoam"))
    ok &= abs(err) <= tolerance
    bf = ("%.4f  %+6.2f%%" % (reference[f], 100 * (u / reference[f] - 1))
          if f in reference else "-  -")
    rows.append("%s  %.4f  %.3f  %+6.2f%%  %s  %7.1f  %6.1f  %5.1f%%  %s"
                % (f, u, measured[f], 100 * err, bf, total, plugin,
                   100 * plugin / max(total, 1e-30), "yes" if rests else "NO"))
    line, = ax.plot(t, w, label="%s simulated" % f)
    ax.axhline(measured[f], color=line.get_color(), ls="--", lw=0.8)
    if f in reference:
        ax.axhline(reference[f], color=line.get_color(), ls=":", lw=0.8)
ax.set_xlabel("t [s]")
ax.set_ylabel("settling velocity [m/s]")
ax.set_title("Settling sphere (ten Cate et al. 2002)\ndashed: measured; dotted: body-fitted Navier-Stokes (duct)",
             fontsize=10)
ax.legend(loc="lower right")
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(os.path.join(here, "settlingSphere.png"), dpi=120)

header = ("fluid  u_sim [m/s]  u_measured  error  u_bodyFitted  error  run [s]  plugin [s]  share  rests on the bottom\n")
text = header + "\n".join(rows) + "\n"
tmp = os.path.join(here, "results.txt.tmp")
open(tmp, "w").write(text)
os.replace(tmp, os.path.join(here, "results.txt"))   # never half-written
print(text)
print("All within 3% and at rest on the bottom" if ok else "FAILED: a terminal velocity is off by more than 3%, or a sphere does not rest on the bottom")
sys.exit(0 if ok else 1)
