#!/usr/bin/env python3
"""Plot the body-fitted force history against the IB run: W(t), the lateral
force on one cube (body-fitted total and viscous part, IB, sensitivity runs
when their CSVs exist) and (p_gap - p_outer)/(rho W^2/2). Needs matplotlib.

usage: plot.py [--work DIR] [--bf CSV] [--ib CSV] [--sens CSV ...] [--out PNG]
Defaults: DIR/bf_force.csv, DIR/ib_history.csv,
DIR/sens_coarse_force.csv and DIR/sens_coarse_gap0.2_force.csv, DIR/bf_vs_ib.png.
"""
import argparse, csv, os
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

ap = argparse.ArgumentParser(description="body-fitted against IB plot")
ap.add_argument("--work", default="/tmp/immersedDEM-bodyFitted", help="work directory")
ap.add_argument("--bf", help="post.py's force CSV")
ap.add_argument("--ib", help="extractIB.py's CSV")
ap.add_argument("--sens", nargs="*", help="force CSVs of sensitivity runs (dashed, if present)")
ap.add_argument("--out", help="output PNG")
args = ap.parse_args()
W_ = args.work
bfcsv = args.bf or os.path.join(W_, "bf_force.csv")
ibcsv = args.ib or os.path.join(W_, "ib_history.csv")
sens = args.sens if args.sens is not None else [
    os.path.join(W_, "%s_force.csv" % e) for e in ("sens_coarse", "sens_coarse_gap0.2")]
out = args.out or os.path.join(W_, "bf_vs_ib.png")

bf = list(csv.DictReader(open(bfcsv)))
ib = list(csv.DictReader(open(ibcsv)))
t = [float(r["t"]) for r in bf]
fig, ax = plt.subplots(3, 1, figsize=(8, 10), sharex=True)
ax[0].plot(t, [float(r["W"]) for r in bf], label="W(t) = -vz_IB (pair's fall speed)")
ax[0].set_ylabel("m/s"); ax[0].legend()
ax[1].plot(t, [1e3 * float(r["Fx_total"]) for r in bf], label="body-fitted, gap 0.1 mm fixed: Fx total")
ax[1].plot(t, [1e3 * float(r["Fx_viscous"]) for r in bf], label="body-fitted: viscous part")
ax[1].plot([float(r["t"]) for r in ib], [1e3 * float(r["F_apart_mean"]) for r in ib], "o-", ms=3,
           label="IB (3.125 mm cells), fluid force apart (gap grows)")
for path in sens:
    try:
        e = list(csv.DictReader(open(path)))
    except OSError:
        continue
    name = os.path.basename(path)
    name = name[:-len("_force.csv")] if name.endswith("_force.csv") else name
    ax[1].plot([float(r["t"]) for r in e], [1e3 * float(r["Fx_total"]) for r in e], "--", lw=1, label=name)
ax[1].set_ylabel("lateral force on one cube, mN (+ = apart)"); ax[1].legend(fontsize=8); ax[1].grid(alpha=.3)
ax[2].plot(t, [float(r["dp_gap_outer_Pa"]) / (0.5 * 1000 * max(float(r["W"]), 1e-9) ** 2) for r in bf])
ax[2].set_ylim(0, 2); ax[2].set_ylabel("(p_gap - p_outer)/(rho W^2/2)"); ax[2].set_xlabel("t (s)"); ax[2].grid(alpha=.3)
plt.tight_layout(); plt.savefig(out, dpi=90)
print("wrote", out)
