#!/usr/bin/env python3
"""analyse.py: the confined-cylinder runs against Schäfer & Turek's (1996)
reference values for benchmark 2D-2.

    analyse.py WORK [-cycles 4] [-out FILE] [-noplot]

WORK holds n<CELLS>/ and n<CELLS>x<SHIFT>/ (makeCase.py cases, run; the
second with the cylinder moved SHIFT cells downstream). For each: the drag and lift
coefficients c = 2 F/(rho U^2 D dz) (F the fluid force on the body from
bodies.dat, Ffx and Ffy; rho 1, U = 1 m/s the mean inflow, D = 0.1 m, dz
the slab), over the last -cycles whole lift cycles (from upward zero
crossings): the largest drag and lift, the Strouhal number f D/U, and how
much the largest lift changed from cycle to cycle (settled?).

Reference (Schäfer, Turek et al. 1996, "Benchmark computations of laminar
flow around a cylinder", Notes Numer. Fluid Mech. 52, 547, benchmark 2D-2,
the bounds their contributors' best results fell in): c_D,max 3.22-3.24,
c_L,max 0.99-1.01, St 0.295-0.305 (README.md: where they were read). Deviations are from the middle of each
band. Prints, writes FILE, and plots confinedCylinder.png; reports, does not
judge (the study's README has the issue's targets).
"""
import glob
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMData import readRuns  # noqa: E402

D, U, RHO = 0.1, 1.0, 1.0
REFERENCE = {"CdMax": (3.22, 3.24), "ClMax": (0.99, 1.01), "St": (0.295, 0.305)}


def slab(case):
    txt = open(os.path.join(case, "system", "blockMeshDict")).read()
    verts = txt.split("vertices")[1].split(");")[0]
    zs = {float(t.split()[2]) for t in verts.replace(")", "(").split("(") if len(t.split()) == 3}
    return max(zs) - min(zs)


def history(case):
    table = readRuns(os.path.join(case, "postProcessing", "bodies"))
    q = 0.5*RHO*U*U*D*slab(case)
    t = table["time"]
    return t, [f/q for f in table["Ffx"]], [f/q for f in table["Ffy"]]


def figures(t, cd, cl, cycles):
    ups = [t[i - 1] + (t[i] - t[i - 1])*(-cl[i - 1])/(cl[i] - cl[i - 1])
           for i in range(1, len(t)) if cl[i - 1] < 0 <= cl[i]]
    ups = ups[-(cycles + 1):]
    if len(ups) < cycles + 1:
        return None
    per = []
    for a, b in zip(ups[:-1], ups[1:]):
        idx = [i for i in range(len(t)) if a <= t[i] < b]
        per.append((max(cd[i] for i in idx), max(cl[i] for i in idx), min(cl[i] for i in idx)))
    n = len(per)
    return {"CdMax": sum(p[0] for p in per)/n, "ClMax": sum(p[1] for p in per)/n,
            "ClMin": sum(p[2] for p in per)/n, "St": D/(U*(ups[-1] - ups[0])/n),
            "spread": (max(p[1] for p in per) - min(p[1] for p in per))/abs(sum(p[1] for p in per)/n),
            "from": ups[0], "to": ups[-1], "cycles": n}


def main():
    args = sys.argv[1:]
    cycles, out, plot = 4, None, True
    pos = []
    while args:
        a = args.pop(0)
        if a == "-cycles" and args:
            cycles = int(args.pop(0))
        elif a == "-out" and args:
            out = args.pop(0)
        elif a == "-noplot":
            plot = False
        else:
            pos.append(a)
    if len(pos) != 1:
        sys.exit("usage: analyse.py WORK [-cycles N] [-out FILE] [-noplot]")
    work = pos[0]
    runs = []
    for d in glob.glob(os.path.join(work, "n*")):
        m = re.fullmatch(r"n(\d+)(?:x([0-9.]+))?", os.path.basename(d))
        if m:
            runs.append((float(m.group(2) or 0), int(m.group(1)), d))
    runs.sort()
    lines = []

    def say(s=""):
        print(s)
        lines.append(s)
    mid = {k: 0.5*(a + b) for k, (a, b) in REFERENCE.items()}
    say("Confined cylinder, Schäfer & Turek 2D-2 (Re 100), immersed fixed body, sharp surface; last %d lift cycles"
        % cycles)
    say("reference bands: c_D,max %.2f-%.2f, c_L,max %.2f-%.2f, St %.3f-%.3f (deviations from their middles)"
        % (REFERENCE["CdMax"] + REFERENCE["ClMax"] + REFERENCE["St"]))
    say("%-6s %-6s %-14s %-9s %-8s %-9s %-8s %-8s %-8s %-9s" % ("cells", "shift", "cycles (s)", "c_D,max", "dev",
                                                                "c_L,max", "dev", "St", "dev", "lift spread"))
    rows = []
    for sh, n, case in runs:
        try:
            t, cd, cl = history(case)
        except (OSError, ValueError) as e:
            say("%-6d %-6g no force history (%s)" % (n, sh, e))
            continue
        f = figures(t, cd, cl, cycles)
        if f is None:
            say("%-6d %-6g fewer than %d whole lift cycles to t %.3g s" % (n, sh, cycles, t[-1] if t else 0))
            continue
        rows.append((n, sh, f, t, cd, cl))
        say("%-6d %-6g %-14s %-9.4f %-+8.1f %-9.4f %-+8.1f %-8.4f %-+8.1f %-9.2g"
            % (n, sh, "%.2f-%.2f" % (f["from"], f["to"]), f["CdMax"], 100*(f["CdMax"]/mid["CdMax"] - 1), f["ClMax"],
               100*(f["ClMax"]/mid["ClMax"] - 1), f["St"], 100*(f["St"]/mid["St"] - 1), f["spread"]))
    if out:
        with open(out, "w") as fh:
            fh.write("\n".join(lines) + "\n")
    if plot and rows:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
        for n, sh, f, t, cd, cl in rows:
            t0 = f["to"] - 2*(f["to"] - f["from"])/f["cycles"]
            sel = [i for i in range(len(t)) if t0 <= t[i] <= f["to"]]
            lab = "%d cells/D" % n + (", moved %g cell" % sh if sh else "")
            ax[0].plot([t[i] - f["to"] for i in sel], [cd[i] for i in sel], label=lab)
            ax[1].plot([t[i] - f["to"] for i in sel], [cl[i] for i in sel], label=lab)
        for a, k, lab in ((ax[0], "CdMax", "c_D"), (ax[1], "ClMax", "c_L")):
            a.axhspan(*REFERENCE[k], color="0.8", label="Schäfer & Turek max")
            a.set_ylabel(lab)
            a.legend(fontsize=8)
        ax[1].set_xlabel("t - end of the last cycle [s]")
        fig.tight_layout()
        fig.savefig(os.path.join(os.path.dirname(os.path.abspath(__file__)), "confinedCylinder.png"), dpi=110)


if __name__ == "__main__":
    main()
