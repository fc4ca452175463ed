#!/usr/bin/python3
"""Plot energyBoxBenchmark's energyBox_<law>.dat files (E/E0 - 1 at
contact-free sub-steps) into energyBox.png. Usage: plotEnergyBox.py [dir]"""
import glob, os, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

d = sys.argv[1] if len(sys.argv) > 1 else "."
fig, ax = plt.subplots(figsize=(7, 4))
for f in sorted(glob.glob(os.path.join(d, "energyBox_*.dat"))):
    law = os.path.basename(f)[len("energyBox_"):-4]
    steps, drift = [], []
    for line in open(f):
        if line.startswith("#"):
            continue
        n, t, e = line.split()
        steps.append(int(n)); drift.append(100*float(e))
    ax.plot(steps, drift, ".-" if law == "volume" else "-", label=law + (" (kinetic, contact-free steps)" if law == "volume" else " (kinetic + stored w(V))"), lw=1, ms=3)
ax.axhline(0.1, color="k", ls=":", lw=0.8)
ax.axhline(-0.1, color="k", ls=":", lw=0.8, label="+-0.1%")
ax.set_xlabel("DEM step")
ax.set_ylabel("energy / start - 1 [%]")
ax.set_title("10 lumpy stars + 10 cubes, closed box, e = 1, mu = 0")
ax.legend()
fig.tight_layout()
fig.savefig(os.path.join(d, "energyBox.png"), dpi=120)
print("wrote", os.path.join(d, "energyBox.png"))
