#!/usr/bin/python3
"""Plots, checks and timing table of the collision experiments.

    plotCollisions.py <work folder>

Reads <work>/<case>/<model>/postProcessing/<name>/0/{contacts,bodies}.dat
and wallTime (seconds, the whole Allrun) for case in sphere, arbitrary,
steel. Writes next to this script:
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

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
work = sys.argv[1]


def folder(case, model):
    return os.path.join(work, case, model)


def available(case, model):
    return os.path.isfile(os.path.join(folder(case, model), "wallTime"))


def table(case, model, name):
    pp = os.path.join(folder(case, model), "postProcessing")
    sub = os.listdir(pp)[0]
    rows = [l.split() for l in open(os.path.join(pp, sub, "0", name)) if not l.startswith("#")]
    return rows


def force(case, model):
    """Normal force summed over the contact regions at each DEM time"""
    f = {}
    for r in table(case, model, "contacts.dat"):
        f[float(r[0])] = f.get(float(r[0]), 0.0) + float(r[4])
    t = np.array(sorted(f))
    return t, np.array([f[x] for x in t])


def trajectory(case, model):
    rows = [r for r in table(case, model, "bodies.dat") if r[1] == "top"]
    return np.array([float(r[0]) for r in rows]), np.array([[float(x) for x in r[2:5]] for r in rows])


def wall(case, model):
    return float(open(os.path.join(folder(case, model), "wallTime")).read())


lines, ok = [], True
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
        ax.plot(1e3 * t, f, style[m], label="%s (peak %.3f N)" % (m, f.max()), drawstyle="steps-post" if m == "cells" else "default")
    ax.set_xlabel("t [ms]"); ax.set_ylabel("normal contact force [N]"); ax.set_title(title)
    ax.grid(alpha=0.3); ax.legend()
    fig.tight_layout(); fig.savefig(os.path.join(here, png), dpi=120)
    lines.append("%s case: peaks %s" % (case, ", ".join("%s %.4f N" % kv for kv in peaks.items())))
    ref = "sphere" if case == "sphere" else "dynamic"
    for m in ("virtualMesh", "cells"):
        for r in (("sphere", "dynamic") if case == "sphere" else ("dynamic",)):
            if m in peaks and r in peaks:
                d = peaks[m] / peaks[r] - 1
                lines.append("  %s peak against %s: %+.2f%%" % (m, r, 100 * d))
                if m == "virtualMesh":
                    ok &= abs(d) <= 0.02

# Arbitrary case: trajectory and the difference of the force histories
if available("arbitrary", "virtualMesh") and available("arbitrary", "dynamic"):
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
    fig.tight_layout(); fig.savefig(os.path.join(here, "arbitraryBodiesTrajectory.png"), dpi=120)
    worst = np.abs(rel).max()
    lines.append("arbitrary case: largest |F_virtualMesh - F_dynamic| over the contact: %.2f%% of the peak" % (100 * worst))
    ok &= worst <= 0.02

lines.append("")
lines.append("wall times [s] (each model's whole Allrun, one after the other on this machine):")
for case in ("sphere", "arbitrary", "steel"):
    times = {m: wall(case, m) for m in ("sphere", "cells", "virtualMesh", "dynamic") if available(case, m)}
    if times:
        lines.append("  %s: %s" % (case, ", ".join("%s %.1f" % kv for kv in times.items())))
    for a, b, paper, target in (("virtualMesh", "cells", "1.3", "<= 1.10"), ("dynamic", "virtualMesh", "34 / >10", ">= 50 / >= 20"),
                                ("virtualMesh", "sphere", "1.4", "")):
        if a in times and b in times:
            lines.append("    %s / %s = %.2f (paper %s; target %s)" % (a, b, times[a] / times[b], paper, target or "-"))

text = "\n".join(lines) + "\n"
open(os.path.join(here, "results.txt"), "w").write(text)
print(text)
print("checks passed" if ok else "FAILED: a check is outside its bound")
sys.exit(0 if ok else 1)
