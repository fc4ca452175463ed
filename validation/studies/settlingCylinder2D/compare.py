#!/usr/bin/env python3
"""The free immersed cylinder's terminal velocity against the body-fitted one
(issue 18: within 3%).

    compare.py -reference U_T <immersed run> [<immersed run> ...] [-window 0.5]
               [-tolerance 0.03] [-drift 1e-3] [-plot FILE.png]

For each immersed run (makeCase.py immersed, run with pimpleFoam) the
terminal velocity is the mean speed |vy| (settling or rising) over the last -window
seconds of postProcessing/bodies/0/bodies.dat; the speed must have settled
there (its change over the window below 0.5% of it) and the body must have
stayed near the axis (|x| below -drift D, 1e-3 by default). Prints a table row per run and exits
1 if a run misses the reference by more than -tolerance or has not settled.
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMCase import caseConstants, number  # noqa: E402


def constants(run):
    """The cylinder's diameter (its surface's extent across), density
    ratio and the fluid's viscosity, from the run's case"""
    c = caseConstants(run)
    e = c.bodyEntry("cylinder")
    scale = number(e.get("scale", "1"))
    xs = [float(l.split()[1])*scale
          for l in open(os.path.join(run, "constant", "triSurface", e["file"].strip('"')))
          if l.strip().startswith("vertex")]
    return max(xs) - min(xs), c.density("cylinder")/c.rhoFluid, c.nu


def motion(run):
    path = os.path.join(run, "postProcessing/bodies/0/bodies.dat")
    lines = [l.split() for l in open(path) if l.strip()]
    head = lines[0][1:]
    rows = [dict(zip(head, l)) for l in lines[1:]]
    t = [float(r["time"]) for r in rows]
    v = [abs(float(r["vy"])) for r in rows]
    x = [float(r["x"]) for r in rows]
    y = [float(r["y"]) for r in rows]
    return t, v, x, y


def cellsPerD(run):
    for l in open(os.path.join(run, "system/blockMeshDict")):
        if l.strip().startswith("hex"):
            nx = int(l.split("(")[2].split()[0])
            return nx/8
    return float("nan")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("runs", nargs="+")
    p.add_argument("-reference", type=float, required=True, help="body-fitted terminal velocity [m/s]")
    p.add_argument("-window", type=float, default=0.5, help="averaging window at the end [s]")
    p.add_argument("-tolerance", type=float, default=0.03)
    p.add_argument("-drift", type=float, default=1e-3, help="largest lateral offset allowed [D]")
    p.add_argument("-plot")
    a = p.parse_args()
    ok = True
    print("| run | cells per D | terminal velocity [m/s] | against body-fitted | change over the window | largest abs(x)/D |")
    print("|---|---|---|---|---|---|")
    series = []
    for run in a.runs:
        D, ratio, nu = constants(run)
        t, v, x, y = motion(run)
        tEnd = t[-1]
        w = [i for i in range(len(t)) if t[i] >= tEnd - a.window]
        if t[w[0]] > tEnd - 0.9*a.window or len(w) < 10:
            sys.exit("compare.py: %s: the run is shorter than the window" % run)
        # time-weighted mean over the window
        ut = sum(0.5*(v[i] + v[i - 1])*(t[i] - t[i - 1]) for i in w[1:])/(t[w[-1]] - t[w[0]])
        half = len(w)//2
        m1 = sum(v[i] for i in w[:half])/half
        m2 = sum(v[i] for i in w[half:])/(len(w) - half)
        drift = (m2 - m1)/ut
        xmax = max(abs(xi) for xi in x)/D
        err = ut/a.reference - 1
        # 0.005: settled, the speed's change over the window a sixth of
        # the 3% target (the approach is exponential: at 0.5% it is still
        # visible in the mean). -drift (1e-3 D by default): the flow is
        # symmetric about the axis, so a drift is an asymmetry of the
        # discretisation; the settling case test's run drifts 6e-4 D
        # (README); an offset x changes the drag as (2x/W)^2, 6e-8 at
        # 1e-3 D, so the centred reference holds
        good = abs(err) <= a.tolerance and abs(drift) < 0.005 and xmax < a.drift
        ok = ok and good
        print("| %s | %g | %.5f | %+.2f%% | %+.2f%% | %.1e |%s"
              % (os.path.basename(os.path.normpath(run)), cellsPerD(run), ut, 100*err, 100*drift, xmax,
                 "" if good else " FAILED"))
        series.append((run, t, v))
    print("body-fitted reference: %.5f m/s (Re %.2f at nu %g, D %g m)" % (a.reference, a.reference*D/nu, nu, D))
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.2))
        for run, t, v in series:
            ax.plot(t, [vi/a.reference for vi in v], label="immersed, %g cells per D" % cellsPerD(run))
        ax.axhline(1.0, color="k", lw=1, ls="--", label="body-fitted (cylinder's frame, steady)")
        ax.axhspan(1 - a.tolerance, 1 + a.tolerance, color="0.9", zorder=0, label="+-%g%%" % (100*a.tolerance))
        ax.set_xlabel("t [s]")
        ax.set_ylabel("settling speed / body-fitted terminal velocity")
        ax.set_title("2D cylinder settling in a channel (W = 8 D, rho_s/rho_f = %g, Re about %.3g)"
                     % (ratio, a.reference*D/nu), fontsize=9)
        ax.set_ylim(0, 1.15)
        ax.legend(fontsize=8, loc="lower right")
        fig.tight_layout()
        fig.savefig(a.plot, dpi=110)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
