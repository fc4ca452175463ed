#!/usr/bin/env python3
"""Table and plot of the unsteadyCylinder study (see Allrun).

    plotUnsteadyCylinder.py <work> [-cycles N] [-o DIR]
    plotUnsteadyCylinder.py -settled <immersed run> <body-fitted run> [-cycles N] [-o DIR]

For every run folder <work>/<series>/<scheme>_<dt>: the figures of the last
N lift cycles (forceFigures.py), the change when the step is halved, and
the difference to the body-fitted run with the same scheme and the finer
step. Plots the lift and drag histories over the last cycles of the runs with
backward and 2 outer correctors and of the coarser step with 1 (time shifted so that the last upward lift crossing is at 0).
"""
import glob, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from forceFigures import history, figures, scales

a = sys.argv[1:]
cycles = int(a[a.index("-cycles") + 1]) if "-cycles" in a else 4
out = a[a.index("-o") + 1] if "-o" in a else "."


def settled(immersed, bodyFitted):
    """The two settled runs of the README (to t = 120 s): their figures
    over the last cycles, the difference, and unsteadyCylinderSettled.png"""
    got = {}
    for name, d in (("immersed", immersed), ("body-fitted", bodyFitted)):
        t, Cd, Cl = history(d)
        u, dd = scales(d)
        got[name] = (figures(t, Cd, Cl, None, cycles, U=u, D=dd), (t, Cd, Cl))
    keys = ("CdMean", "CdAmp", "ClAmp", "St")
    for name, (f, _) in got.items():
        print("%-12s " % name + " ".join("%s %.5g" % (k, f[k]) for k in keys))
    fi, fb = got["immersed"][0], got["body-fitted"][0]
    print("immersed/body-fitted - 1: " + " ".join("%s %+.2f%%" % (k, 100*(fi[k]/fb[k] - 1)) for k in keys))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for name, (f, (t, Cd, Cl)) in got.items():
        sel = [i for i in range(len(t)) if f["from"] <= t[i] <= f["to"]]
        tt = [t[i] - f["to"] for i in sel]
        style = "-" if name == "body-fitted" else "--"
        ax[0].plot(tt, [Cl[i] for i in sel], style, label=name, lw=1)
        ax[1].plot(tt, [Cd[i] for i in sel], style, label=name, lw=1)
    ax[0].set_ylabel("lift coefficient")
    ax[1].set_ylabel("drag coefficient")
    ax[1].set_xlabel("t - t(last upward lift crossing) [D/U]")
    ax[0].legend(fontsize=8)
    fig.suptitle("fixed 2D cylinder, Re 100, settled (t = 120 D/U): immersed 20 cells/D, body-fitted fine O-grid")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "unsteadyCylinderSettled.png"), dpi=110)


if a[0] == "-settled":
    settled(a[1], a[2])
    sys.exit(0)
work = a[0]

runs = {}
for d in sorted(glob.glob(os.path.join(work, "*", "*_*"))):
    if not os.path.isfile(os.path.join(d, "log.pimpleFoam")):
        continue
    series = os.path.basename(os.path.dirname(d))
    scheme, dt = os.path.basename(d).rsplit("_", 1)
    t, Cd, Cl = history(d)
    u, dd = scales(d)
    try:
        f = figures(t, Cd, Cl, None, cycles, U=u, D=dd)
    except SystemExit as e:
        print("%s: %s" % (d, e))
        continue
    runs[(series, scheme, float(dt))] = (f, (t, Cd, Cl))

keys = ("CdMean", "CdAmp", "ClAmp", "St")
print("%-12s %-9s %8s %8s %8s %8s %8s %7s" % ("series", "scheme", "deltaT", "CdMean", "CdAmp", "ClAmp", "St", "cycles"))
for (s, sc, dt), (f, _) in sorted(runs.items()):
    print("%-12s %-9s %8.4g %8.4f %8.5f %8.4f %8.4f %7d" % (s, sc, dt, f["CdMean"], f["CdAmp"], f["ClAmp"], f["St"], f["cycles"]))

print("\nchange when deltaT is halved (fine/coarse - 1):")
for (s, sc, dt), (f, _) in sorted(runs.items()):
    c = runs.get((s, sc, 2*dt))
    if c:
        print("%-12s %-9s %6.4g->%-6.4g " % (s, sc, 2*dt, dt)
              + " ".join("%s %+.2f%%" % (k, 100*(f[k]/c[0][k] - 1)) for k in keys))

print("\nagainst the body-fitted run with the same scheme and deltaT (immersed/bodyFitted - 1):")
for (s, sc, dt), (f, _) in sorted(runs.items()):
    if s.startswith("bodyFitted"):
        continue
    r = runs.get(("bodyFitted", sc, dt))
    if r:
        print("%-12s %-9s %8.4g " % (s, sc, dt)
              + " ".join("%s %+.2f%%" % (k, 100*(f[k]/r[0][k] - 1)) for k in keys))

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("(no matplotlib: no plot)")
    sys.exit(0)
fig, ax = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
for (s, sc, dt), (f, (t, Cd, Cl)) in sorted(runs.items()):
    # the recommended settings, and one outer corrector at the coarser step
    if not (sc.endswith("-o2") or (sc == "backward-o1" and dt == max(k[2] for k in runs if k[0] == s))):
        continue
    t0 = f["to"]
    sel = [i for i in range(len(t)) if t[i] >= f["from"]]
    tt = [t[i] - t0 for i in sel]
    style = "-" if s.startswith("bodyFitted") else "--"
    lab = "%s %s dt %g" % (s, sc, dt)
    ax[0].plot(tt, [Cl[i] for i in sel], style, label=lab, lw=1)
    ax[1].plot(tt, [Cd[i] for i in sel], style, label=lab, lw=1)
ax[0].set_ylabel("lift coefficient")
ax[1].set_ylabel("drag coefficient")
ax[1].set_xlabel("t - t(last upward lift crossing) [D/U]")
ax[0].legend(fontsize=6, ncol=2)
fig.suptitle("fixed 2D cylinder, Re 100: immersed sharp surface and body-fitted O-grid")
fig.tight_layout()
fig.savefig(os.path.join(out, "unsteadyCylinder.png"), dpi=110)
