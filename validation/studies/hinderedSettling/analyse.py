#!/usr/bin/env python3
"""Hindered settling against Richardson & Zaki (issue 45, item 3).

    analyse.py <work> [-plot FILE.png] [-tolerance 0.05]

<work> holds the runs of Allrun: phi<f> (spheres at volume fraction f in a
periodic box) and single<L> (one sphere in a box of L diameters). For each
run the settling velocity is the mean of -vz over the bodies and over the
second half of the run, in the frame of zero mean volumetric flux that the
fvOption's drive holds. The isolated sphere's terminal velocity U_t is
extrapolated from the single-sphere boxes with the periodic array's
leading correction, U(L) = U_t (1 - k D/L) (Hasimoto 1959: in Stokes flow
k = 1.7601 (pi/6)^(1/3) = 1.42; fitted here from two boxes, as inertia at
Re 5 shortens the interaction).
Richardson & Zaki: U/U_t = (1 - phi)^n, n from Garside & Al-Dibouni
(1977): (5.1 - n)/(n - 2.7) = 0.1 Re_t^0.9, Re_t = U_t D/nu.
"""
import argparse, glob, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMData import readTable  # noqa: E402
from immersedDEMBeds import garsideAlDibouni  # noqa: E402

D, NU = 1.0, 0.0875


def settling(run):
    t = readTable(glob.glob(os.path.join(run, "postProcessing/sphere/0/bodies.dat"))[0])
    times = sorted(set(t["time"]))
    tEnd = times[-1]
    window = [x for x in times if x >= 0.5*tEnd]
    per = {}
    for k in range(len(t)):
        if t["time"][k] >= 0.5*tEnd:
            per.setdefault(t["time"][k], []).append(-t["vz"][k])
    means = [sum(per[x])/len(per[x]) for x in window]
    half = len(means)//2
    u = sum(means)/len(means)
    change = (sum(means[half:])/(len(means) - half) - sum(means[:half])/half)/u
    return u, change, len(per[window[0]]), tEnd


def main():
    p = argparse.ArgumentParser()
    p.add_argument("work")
    p.add_argument("-plot")
    p.add_argument("-tolerance", type=float, default=0.05)
    a = p.parse_args()
    singles = []
    for run in sorted(glob.glob(os.path.join(a.work, "single*"))):
        L = float(os.path.basename(run)[len("single"):])
        u, change, n, tEnd = settling(run)
        singles.append((L, u))
        print("one sphere, box %g D: U %.5f m/s (change over the window %+.2f%%, %g s)" % (L, u, 100*change, tEnd))
    singles.sort()
    if len(singles) >= 2:
        (L1, u1), (L2, u2) = singles[-2], singles[-1]
        x1, x2 = D/L1, D/L2
        ut = (u1*x2 - u2*x1)/(x2 - x1)
        k = (1 - u2/ut)/x2
        print("isolated sphere, extrapolated in D/L from %g and %g D: U_t %.5f m/s (k %.3f)" % (L1, L2, ut, k))
    else:
        sys.exit("analyse.py: two single-sphere boxes are needed for U_t")
    # Schiller-Naumann's standard drag, for comparison only
    us = 0.4
    for _ in range(100):
        re = us*D/NU
        us = (2 - 1)*1.0*D*D/(18*NU)/(1 + 0.15*re**0.687)
    print("for comparison, Schiller-Naumann's drag gives U_t %.5f m/s" % us)
    re = ut*D/NU
    n = garsideAlDibouni(re)
    print("Re_t %.2f, Garside & Al-Dibouni n %.3f" % (re, n))
    print()
    print("| phi | spheres | U [m/s] | U/U_t | Richardson-Zaki (1-phi)^n | deviation | change over the window |")
    print("|---|---|---|---|---|---|---|")
    ok = True
    rows = []
    for run in sorted(glob.glob(os.path.join(a.work, "phi*")), key=lambda r: float(os.path.basename(r)[3:])):
        phi = float(os.path.basename(run)[3:])
        u, change, nb, tEnd = settling(run)
        rz = (1 - phi)**n
        dev = (u/ut)/rz - 1
        good = abs(dev) <= a.tolerance
        ok = ok and good
        rows.append((phi, u/ut, rz))
        print("| %g | %d | %.5f | %.4f | %.4f | %+.1f%% | %+.1f%% |%s"
              % (phi, nb, u, u/ut, rz, 100*dev, 100*change, "" if good else " outside %g%%" % (100*a.tolerance)))
    if a.plot and rows:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        f = [i/100 for i in range(0, 31)]
        ax.plot(f, [(1 - x)**n for x in f], "k-", label="Richardson-Zaki, n = %.2f (Garside & Al-Dibouni)" % n)
        ax.fill_between(f, [(1 - a.tolerance)*(1 - x)**n for x in f], [(1 + a.tolerance)*(1 - x)**n for x in f],
                        color="0.9", label="+-%g%%" % (100*a.tolerance))
        ax.plot([r[0] for r in rows], [r[1] for r in rows], "o", label="immersedDEM, spheres")
        ax.set_xlabel("volume fraction phi")
        ax.set_ylabel("U / U_t")
        ax.set_title("Hindered settling, Re_t = %.1f, triply periodic box" % re, fontsize=9)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
