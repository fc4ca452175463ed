#!/usr/bin/env python3
"""Post-process the body-fitted case: whole-cube forces, gap/outer pressure,
comparison with the IB run, squeeze-film parting estimate.

usage: post.py [CASE] [OUT_CSV] [--work DIR] [--ib CSV]
CASE defaults to DIR/bfcase, OUT_CSV to DIR/bf_force.csv, --ib to
DIR/ib_history.csv. Tables and estimates go to stdout.
The case is a quarter tank (symmetry planes x = 0 and y = 0): the patch
group 'cube' is HALF a cube (y >= 0); x and z components are doubled here
(y components are meaningless for the half body and are dropped).
"""
import argparse, bisect, csv, math, os, re, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "src", "python"))
from immersedDEMCase import number, readDictionary  # noqa: E402

ap = argparse.ArgumentParser(description="forces and parting estimates of the body-fitted case")
ap.add_argument("case", nargs="?", help="case directory (default WORK/bfcase)")
ap.add_argument("out", nargs="?", help="output CSV (default WORK/bf_force.csv)")
ap.add_argument("--work", default="/tmp/immersedDEM-bodyFitted", help="work directory")
ap.add_argument("--ib", help="IB history from extractIB.py (default WORK/ib_history.csv)")
args = ap.parse_args()
case = args.case or os.path.join(args.work, "bfcase")
out = args.out or os.path.join(args.work, "bf_force.csv")
ibcsv = args.ib or os.path.join(args.work, "ib_history.csv")
# The body-fitted case's viscosity; its density (pimpleFoam's kinematic
# pressure has none) and the cubes' are those of the immersed twin
# (makeCase.py: water, glass)
RHO = 1000.0
MU = RHO*number(readDictionary(os.path.join(case, "constant", "transportProperties"))["nu"])
RHO_CUBE = 2500.0
A = 0.010        # cube side (makeBF.py)
H0 = 1e-4        # initial gap (makeBF.py)


def read_forces(path):
    rows = []
    for l in open(path):
        if l.startswith("#") or not l.strip():
            continue
        v = [float(x) for x in re.sub(r"[()]", " ", l).split()]
        rows.append(v)   # t, tot xyz, p xyz, visc xyz
    return rows


def read_sfv(path):
    d = {}
    for l in open(path):
        if l.startswith("#") or not l.strip():
            continue
        t, v = l.split()[:2]
        d[float(t)] = float(v)
    return d


def interp(ts, vs, t):
    if t <= ts[0]:
        return vs[0]
    if t >= ts[-1]:
        return vs[-1]
    i = bisect.bisect_right(ts, t)
    f = (t - ts[i - 1]) / (ts[i] - ts[i - 1])
    return vs[i - 1] + f * (vs[i] - vs[i - 1])


pp = case + "/postProcessing/"
F = read_forces(pp + "forces/0/force.dat")
Fg = {r[0]: r for r in read_forces(pp + "forcesGap/0/force.dat")}
Fo = {r[0]: r for r in read_forces(pp + "forcesOuter/0/force.dat")}
pg = read_sfv(pp + "p_cubeGap/0/surfaceFieldValue.dat")
po = read_sfv(pp + "p_cubeOuter/0/surfaceFieldValue.dat")
Wt, Wv = zip(*[(float(r["t"]), float(r["W"])) for r in csv.DictReader(open(case + "/W.csv"))])

rows = []
for r in F:
    t = r[0]
    g, o = Fg.get(t), Fo.get(t)
    rows.append(dict(
        t=t, W=interp(Wt, Wv, t),
        Fx_pressure=2 * r[4], Fx_viscous=2 * r[7], Fx_total=2 * r[1], Fz_total=2 * r[3],
        Fx_gapFace=2 * g[1] if g else float("nan"),
        Fx_outerFace=2 * o[1] if o else float("nan"),
        pGap_Pa=RHO * pg.get(t, float("nan")), pOuter_Pa=RHO * po.get(t, float("nan"))))
for d in rows:
    d["dp_gap_outer_Pa"] = d["pGap_Pa"] - d["pOuter_Pa"]

keys = ["t", "W", "Fx_pressure", "Fx_viscous", "Fx_total", "Fz_total",
        "Fx_gapFace", "Fx_outerFace", "pGap_Pa", "pOuter_Pa", "dp_gap_outer_Pa"]
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(keys)
    for d in rows:
        w.writerow(["%.8g" % d[k] for k in keys])

# ---------------------------------------------------------------- IB history
ib = list(csv.DictReader(open(ibcsv)))
it = [float(r["t"]) for r in ib]
iF = [float(r["F_apart_mean"]) for r in ib]
iFa = [float(r["Ffx_a"]) for r in ib]
igap = [float(r["gap"]) for r in ib]

ts = [d["t"] for d in rows]


def bf_at(t, key, win=0.0):
    if win <= 0:
        return interp(ts, [d[key] for d in rows], t)
    sel = [d[key] for d in rows if abs(d["t"] - t) <= win / 2]
    return sum(sel) / len(sel) if sel else float("nan")


print("Whole cube, lateral force, positive = pushing the cubes apart (N); W upward speed of the far fluid in the cube frame")
print("%6s %7s | %10s %10s %10s %10s | %10s | %9s %9s | %10s %10s %8s" % (
    "t", "W", "Fx_p", "Fx_visc", "Fx_tot", "Fx_tot5ms", "Fz_tot", "p_gap-out", "dp/qW",
    "IB_F_apart", "IB_Ffx_a", "IB_gap"))
for t in (0.02, 0.04, 0.06, 0.08, 0.1, 0.12, 0.15, 0.2):
    if t > ts[-1] + 1e-9:
        continue
    Wv_ = bf_at(t, "W")
    dp = bf_at(t, "dp_gap_outer_Pa")
    print("%6.3f %7.4f | %10.3e %10.3e %10.3e %10.3e | %10.3e | %9.3f %9.3f | %10.3e %10.3e %8.2e" % (
        t, Wv_, bf_at(t, "Fx_pressure"), bf_at(t, "Fx_viscous"), bf_at(t, "Fx_total"),
        bf_at(t, "Fx_total", 0.005), bf_at(t, "Fz_total"), dp, dp / (0.5 * RHO * Wv_ ** 2) if Wv_ > 0 else float("nan"),
        interp(it, iF, t), interp(it, iFa, t), interp(it, igap, t)))


# ---------------------------------------------------------------- squeeze film
def parting(tt, FF, C, h0=H0, h1=1e-3):
    """quasi-static: F = C hdot / h^3 -> 1/h^2 = 1/h0^2 - (2/C) int F dt
    returns (t at h=h1 or None, t at divergence or None, h at the end, int F dt at the end)"""
    I = 0.0
    t1 = tinf = None
    for i in range(1, len(tt)):
        dI = 0.5 * (FF[i] + FF[i - 1]) * (tt[i] - tt[i - 1])
        Inew = I + dI
        for target, name in ((0.5 * C * (1 / h0 ** 2 - 1 / h1 ** 2), "t1"), (0.5 * C / h0 ** 2, "tinf")):
            if I < target <= Inew:
                tc = tt[i - 1] + (target - I) / dI * (tt[i] - tt[i - 1])
                if name == "t1" and t1 is None:
                    t1 = tc
                if name == "tinf" and tinf is None:
                    tinf = tc
        I = Inew
    inv = 1 / h0 ** 2 - 2 * I / C
    hend = 1 / math.sqrt(inv) if inv > 0 else float("inf")
    return t1, tinf, hend, I


def parting_inertia(tt, FF, C, m, h0=H0, h1=1e-3, dt=1e-6):
    """each cube: m dv/dt = F - C (2v)/h^3, dh/dt = 2 v (semi-implicit in the film term)"""
    h, v, t = h0, 0.0, tt[0]
    while t < tt[-1]:
        Fv = interp(tt, FF, t)
        k = 2 * C / h ** 3
        v = (v + dt * Fv / m) / (1 + dt * k / m)
        h += 2 * v * dt
        t += dt
        if h >= h1:
            return t, h
        if h <= 0:
            return None, 0.0
    return None, h


C_theory = 0.4217 * MU * A ** 4
m = RHO_CUBE * A ** 3
print("\nsqueeze film: C = 0.4217 mu a^4 = %.4g N s m (4.8e-12 also shown)" % C_theory)
print("target int F dt: h -> 1 mm at %.4g N s, h -> inf at %.4g N s (C theory)" % (
    0.5 * C_theory * (1 / H0 ** 2 - 1e6), 0.5 * C_theory / H0 ** 2))
bt = ts
bF = [d["Fx_total"] for d in rows]
for C in (C_theory, 4.8e-12):
    for name, (tt, FF) in (("body-fitted", (bt, bF)), ("IB", (it, iF))):
        t1, tinf, hend, I = parting(tt, FF, C)
        ti, hi = parting_inertia(tt, FF, C, m)
        print("C %.3g %-12s: int F dt to %.3f s = %.4g N s; h = 1 mm at %s, h -> inf at %s, h(end) = %s; "
              "with cube inertia: h = 1 mm at %s (h end %.3g m)" % (
                  C, name, tt[-1], I,
                  "%.4f s" % t1 if t1 else "never", "%.4f s" % tinf if tinf else "never",
                  "%.4g m" % hend, "%.4f s" % ti if ti else "never", hi))


def h_of_t(tt, FF, C, tq, h0=H0):
    I = 0.0
    for i in range(1, len(tt)):
        if tt[i] > tq:
            I += 0.5 * (FF[i - 1] + interp(tt, FF, tq)) * (tq - tt[i - 1])
            break
        I += 0.5 * (FF[i] + FF[i - 1]) * (tt[i] - tt[i - 1])
    inv = 1 / h0 ** 2 - 2 * I / C
    return 1 / math.sqrt(inv) if inv > 0 else float("inf")


print("\nquasi-static gap h(t) in mm, C = %.4g:" % C_theory)
tq = (0.04, 0.06, 0.08, 0.1, 0.11, 0.12, 0.13, 0.135, 0.14)
print("%-12s " % "t" + " ".join("%7.3f" % x for x in tq))
for name, (tt, FF) in (("body-fitted", (bt, bF)), ("IB", (it, iF))):
    print("%-12s " % name + " ".join("%7.3f" % (1e3 * h_of_t(tt, FF, C_theory, x)) for x in tq))
ma = m + RHO * A ** 3  # with an added mass of rho V (coefficient 1)
for name, (tt, FF) in (("body-fitted", (bt, bF)), ("IB", (it, iF))):
    ti, hi = parting_inertia(tt, FF, C_theory, ma)
    print("with mass + added mass rho V (%.4g kg), %s: h = 1 mm at %s" % (ma, name, "%.4f s" % ti if ti else "never (h end %.3g)" % hi))
