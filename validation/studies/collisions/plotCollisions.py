#!/usr/bin/python3
"""Plots, checks and timing table of the collision experiments.

    plotCollisions.py <work folder> [<output folder>]

Reads <work>/<case>/<model>/postProcessing/<name>/0/{contacts,bodies}.dat,
caseParameters and wallTime (seconds, the whole Allrun) for case in sphere,
arbitrary, steel. Writes into the output folder (default: next to this
script):
  sphereSphereForce.png      normal force against time, every model (Fig. 3)
  arbitraryBodiesForce.png   the same for the arbitrary bodies (Fig. 4a)
  arbitraryBodiesTrajectory.png  the moving body's centre (Fig. 4b) and the
                             relative difference virtualMesh - dynamic of
                             the normal force over the contact (Fig. 4c)
  results.txt                peaks, differences, wall times and ratios
Exits 1 when a check fails: virtualMesh peak within 2% of sphere and of
dynamic (sphere case); virtualMesh within 2% of dynamic over the contact
(arbitrary case, the largest difference of the force histories relative
to the peak)."""
import os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMData import readTable

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
work = sys.argv[1]
out = sys.argv[2] if len(sys.argv) > 2 else here
os.makedirs(out, exist_ok=True)


def folder(case, model):
    return os.path.join(work, case, model)


def available(case, model):
    return os.path.isfile(os.path.join(folder(case, model), "wallTime"))


def table(case, model, name):
    pp = os.path.join(folder(case, model), "postProcessing")
    sub = os.listdir(pp)[0]
    return readTable(os.path.join(pp, sub, "0", name))


def force(case, model):
    """Normal force summed over the contact regions at each DEM time"""
    f = {}
    c = table(case, model, "contacts.dat")
    for time, Fn in zip(c["time"], c["Fn"]):
        f[time] = f.get(time, 0.0) + Fn
    t = np.array(sorted(f))
    return t, np.array([f[x] for x in t])


def trajectory(case, model):
    top = table(case, model, "bodies.dat").where(body="top")
    return np.array(top["time"]), np.array([top["x"], top["y"], top["z"]]).T


def wall(case, model):
    return float(open(os.path.join(folder(case, model), "wallTime")).read())


def cpu(case, model):
    """pimpleFoam's CPU seconds (its last ExecutionTime): unlike the wall
    time, not stretched by other jobs sharing the cores"""
    t = 0.0
    for l in open(os.path.join(folder(case, model), "log.pimpleFoam")):
        if l.startswith("ExecutionTime = "):
            t = float(l.split()[2])
    return t


def plugin(case, model):
    """Seconds in projection, DEM and forcing, summed over the log lines"""
    tot = {"projection": 0.0, "DEM": 0.0, "forcing": 0.0}
    for l in open(os.path.join(folder(case, model), "log.pimpleFoam")):
        if l.startswith("immersedDEM ") and "seconds:" in l:
            w = l.split("seconds:")[1].split()
            for k, v in zip(w[0::2], w[1::2]):
                tot[k] += float(v)
    return tot


def reached(case, model):
    rows = table(case, model, "bodies.dat")
    return rows.last("time") if len(rows) else 0.0


def finished(case, model):
    """Whether pimpleFoam ran to its end and as far in time as the case's
    other models (a dynamic-refinement run may be stopped, or given an
    earlier end with Allrun -dynamicEndTime, after the contact: its wall
    time is then a lower bound)"""
    log = os.path.join(folder(case, model), "log.pimpleFoam")
    if not (os.path.isfile(log) and any(l.strip() == "End" for l in open(log))):
        return False
    others = [reached(case, m) for m in ("sphere", "cells", "virtualMesh", "dynamic")
              if m != model and available(case, m)]
    return not others or reached(case, model) >= max(others) - 1e-9


def steps(case, model):
    """CFD time steps pimpleFoam took (the models' trajectories after the
    contact differ, and with them the Courant-limited steps)"""
    log = os.path.join(folder(case, model), "log.pimpleFoam")
    return sum(1 for l in open(log) if l.startswith("Time = "))


def parameters(case, model):
    p = {}
    for l in open(os.path.join(folder(case, model), "caseParameters")):
        k, _, v = l.partition(" ")
        p[k] = v.strip()
    return p


lines, ok = [], True
for case in ("sphere", "arbitrary", "steel"):
    for m in ("sphere", "cells", "virtualMesh", "dynamic"):
        if available(case, m):
            p = parameters(case, m)
            lines.append("%s/%s: %s cells per diameter, L = %s, contact %s on cells of %s m"
                         % (case, m, p.get("cellsPerDiameter"), p.get("level"), p.get("contactMethod"), p.get("contactCellSize")))
lines.append("")
style = {"sphere": "k-", "cells": "C1-", "virtualMesh": "C0-", "dynamic": "C2--"}

for case, png, title in (("sphere", "sphereSphereForce.png", "Two rubber spheres, 1 m/s"),
                         ("arbitrary", "arbitraryBodiesForce.png", "Bent rod and lumpy star, 1 m/s")):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    peaks = {}
    for m in ("sphere", "cells", "virtualMesh", "dynamic"):
        if not available(case, m):
            continue
        t, f = force(case, m)
        if len(f) == 0:
            continue
        peaks[m] = f.max()
        ax.plot(1e3 * t, f, style[m], label="%s (peak %.3f N)" % (m, f.max()), drawstyle="steps-post" if m == "cells" else "default",
                lw=4 if m == "sphere" else 1.5, alpha=0.35 if m == "sphere" else 1.0)
    if not peaks:
        plt.close(fig)
        continue
    ax.set_xlabel("t [ms]"); ax.set_ylabel("normal contact force [N]"); ax.set_title(title)
    ax.grid(alpha=0.3); ax.legend()
    fig.tight_layout(); fig.savefig(os.path.join(out, png), dpi=120)
    lines.append("%s case: peaks %s" % (case, ", ".join("%s %.4f N" % kv for kv in peaks.items())))
    # The stair-step as a number: the largest departure of each force
    # history from the reference's over the reference's contact, relative
    # to the reference's peak (virtualMesh against dynamic in the arbitrary
    # case is the check below)
    ref = "sphere" if case == "sphere" else "dynamic"
    if available(case, ref):
        tr, fr = force(case, ref)
        if len(fr):
            for m in (("cells", "virtualMesh") if case == "sphere" else ("cells",)):
                if available(case, m):
                    tm, fm = force(case, m)
                    fi = np.interp(tr, tm, fm, left=0.0, right=0.0) if len(fm) else 0 * fr
                    lines.append("  %s force history against %s: largest difference %.1f%% of the peak"
                                 % (m, ref, 100 * np.abs(fi - fr).max() / fr.max()))
    for m in ("virtualMesh", "cells"):
        for r in (("sphere", "dynamic") if case == "sphere" else ("dynamic",)):
            if m in peaks and r in peaks:
                d = peaks[m] / peaks[r] - 1
                lines.append("  %s peak against %s: %+.2f%%%s" % (m, r, 100 * d, " (bound 2%)" if m == "virtualMesh" else " (the stair-step)"))
                if m == "virtualMesh":
                    # 2%: the study's bound for the virtual mesh against
                    # the exact or refined reference (README: the force
                    # history 1.87% with curved leaves, 2.58% with the
                    # flat planes it replaced)
                    ok &= abs(d) <= 0.02
            elif m == "virtualMesh":
                lines.append("  %s peak against %s: not checked (no %s run in %s)" % (m, r, r if r not in peaks else m, work))

if available("steel", "virtualMesh"):
    t, f = force("steel", "virtualMesh")
    lines.append("steel case: virtualMesh peak %.4f N, first to last touch %.3f ms" % (f.max(), 1e3 * (t[f > 0][-1] - t[f > 0][0]) if (f > 0).any() else 0))

# Arbitrary case: trajectory and the difference of the force histories
if not (available("arbitrary", "virtualMesh") and available("arbitrary", "dynamic")):
    lines.append("arbitrary case: virtualMesh against dynamic over the contact: not checked (needs both runs in %s)" % work)
else:
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for m in ("cells", "virtualMesh", "dynamic"):
        if available("arbitrary", m):
            t, x = trajectory("arbitrary", m)
            a1.plot(1e3 * x[:, 0], 1e3 * x[:, 2], style[m], label=m)
    a1.set_xlabel("x [mm]"); a1.set_ylabel("z [mm]"); a1.set_title("centre of the star"); a1.legend(); a1.grid(alpha=0.3)
    tv, fv = force("arbitrary", "virtualMesh"); td, fd = force("arbitrary", "dynamic")
    lo, hi = max(tv[0], td[0]), min(tv[-1], td[-1])
    grid = np.linspace(lo, hi, 400)
    gv, gd = np.interp(grid, tv, fv), np.interp(grid, td, fd)
    rel = (gv - gd) / max(gd.max(), 1e-30)
    a2.plot(1e3 * grid, 100 * rel, "C0-")
    a2.set_xlabel("t [ms]"); a2.set_ylabel("(F_virtualMesh - F_dynamic)/peak [%]"); a2.grid(alpha=0.3)
    a2.set_title("virtual mesh against dynamic refinement")
    fig.tight_layout(); fig.savefig(os.path.join(out, "arbitraryBodiesTrajectory.png"), dpi=120)
    worst = np.abs(rel).max()
    lines.append("arbitrary case: largest |F_virtualMesh - F_dynamic| over the contact: %.2f%% of the peak" % (100 * worst))
    ok &= worst <= 0.02     # as the peak's 2% (above)

lines.append("")
lines.append("wall times [s] (each model's whole Allrun, one after the other on this machine):")
for case in ("sphere", "arbitrary", "steel"):
    times = {m: wall(case, m) for m in ("sphere", "cells", "virtualMesh", "dynamic") if available(case, m)}
    n = {m: steps(case, m) for m in times}
    if times:
        lines.append("  %s: %s" % (case, ", ".join("%s %s%.1f (%d CFD steps%s)" % (
            m, "" if finished(case, m) else "> ", times[m], n[m],
            "" if finished(case, m) else ", stopped at t = %.3f ms" % (1e3 * reached(case, m))) for m in times)))
        for m in times:
            p = plugin(case, m)
            lines.append("    %s: pimpleFoam CPU %.1f s; projection %.1f s, DEM %.1f s, forcing %.1f s (wall)"
                         % (m, cpu(case, m), p["projection"], p["DEM"], p["forcing"]))
    for a, b, paper, target in (("virtualMesh", "cells", "1.3", "<= 1.10"), ("dynamic", "virtualMesh", "34 / >10", ">= 50 / >= 20"),
                                ("virtualMesh", "sphere", "1.4", "")):
        if a in times and b in times:
            if finished(case, a) and finished(case, b):
                lines.append("    %s / %s = %.2f, per CFD step %.2f; pimpleFoam CPU %.2f (paper %s; target %s)"
                             % (a, b, times[a] / times[b], times[a] / n[a] / (times[b] / n[b]),
                                cpu(case, a) / cpu(case, b), paper, target or "-"))
            elif finished(case, b):
                lines.append("    %s / %s > %.1f, pimpleFoam CPU > %.1f (%s stopped at t = %.3f ms of the %.3f ms %s ran; paper %s; target %s)"
                             % (a, b, times[a] / times[b], cpu(case, a) / cpu(case, b), a, 1e3 * reached(case, a),
                                1e3 * reached(case, b), b, paper, target or "-"))

text = "\n".join(lines) + "\n"
tmp = os.path.join(out, "results.txt.tmp")
open(tmp, "w").write(text)
os.replace(tmp, os.path.join(out, "results.txt"))
print(text)
print("checks passed" if ok else "FAILED: a check is outside its bound")
sys.exit(0 if ok else 1)
