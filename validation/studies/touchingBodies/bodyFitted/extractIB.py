#!/usr/bin/env python3
"""The IB run's fall speed and lateral fluid force history (touchingCubes'
bodies a at x < 0 and b at x > 0) from bodies.dat to a CSV:
t, vz_a, vz_b, vz_mean, Ffx_a, Ffx_b, F_apart_mean (= (-Ffx_a + Ffx_b)/2,
+ = apart), Flx_a, Fx_total_a, gap (= x_b - x_a - 10 mm).

usage: extractIB.py [--work DIR] [--bodies FILE] [--out CSV]
--bodies defaults to DIR/ib/case/postProcessing/bodies/0/bodies.dat,
--out to DIR/ib_history.csv.
"""
import argparse, csv, os

ap = argparse.ArgumentParser(description="IB history of the touching cubes from bodies.dat")
ap.add_argument("--work", default="/tmp/immersedDEM-bodyFitted", help="work directory")
ap.add_argument("--bodies", help="bodies.dat of the IB run")
ap.add_argument("--out", help="output CSV")
args = ap.parse_args()
f = args.bodies or os.path.join(args.work, "ib/case/postProcessing/bodies/0/bodies.dat")
out = args.out or os.path.join(args.work, "ib_history.csv")

lines = open(f).read().splitlines()
hdr = lines[0].lstrip("#").split()
col = {n: i for i, n in enumerate(hdr)}
by = {}
for l in lines[1:]:
    if l.startswith("#") or not l.strip(): continue
    r = l.split()
    by.setdefault(float(r[0]), {})[r[1]] = r
with open(out, "w", newline="") as o:
    w = csv.writer(o)
    w.writerow(["t", "vz_a", "vz_b", "vz_mean", "Ffx_a", "Ffx_b", "F_apart_mean",
                "Flx_a", "Fx_total_a", "gap"])
    for t in sorted(by):
        a, b = by[t]["a"], by[t]["b"]
        g = lambda r, n: float(r[col[n]])
        vza, vzb = g(a, "vz"), g(b, "vz")
        # a is at x<0: the force pushing it away from b is -Ffx_a
        fapart = 0.5 * (-g(a, "Ffx") + g(b, "Ffx"))
        gap = g(b, "x") - g(a, "x") - 0.010
        w.writerow(["%.6g" % t, "%.6g" % vza, "%.6g" % vzb, "%.6g" % (0.5*(vza+vzb)),
                    "%.6g" % g(a, "Ffx"), "%.6g" % g(b, "Ffx"), "%.6g" % fapart,
                    "%.6g" % g(a, "Flx"), "%.6g" % g(a, "Fx"), "%.6g" % gap])
print("columns used:", {n: col[n]+1 for n in ("vz", "Ffx", "Flx", "Fx", "x")})
print("wrote", out)
