#!/usr/bin/env python3
"""A sphere bouncing on a wall in a liquid (issue 15, item 3): the
effective restitution e = U_out/U_in against the Stokes number
St = rho_p d U_in/(9 mu), from the runs of Allrun (or the case test).

  wetBouncing.py --startVelocity NU      the start speed for viscosity NU
  wetBouncing.py [--plot FILE] [--results FILE] [--check] CASE...

U_in is the largest approach speed within half a diameter of the wall
before the impact; U_out the largest mean rising speed from the lowest
point of the bounce (the secant of the trajectory, as the experiments
measure it from the sphere's positions; the velocity of single CFD steps
alternates a little after the impact). e_dry is the material's (1 by
default). Reference: the fit e/e_dry = exp(-35/St) of Legendre, Daniel and
Guiraud (Phys. Fluids 17, 097105, 2005) to the measurements of Gondret,
Lance and Petit (Phys. Fluids 14, 643, 2002) and Joseph, Zenit, Hunt and
Rosenwinkel (J. Fluid Mech. 433, 329, 2001), who found no rebound below
St of about 10.

--check exits 1 unless, as issue 15 asks: no rebound (e/e_dry < 0.1)
below St 11; e/e_dry between 0.7 and 1 from St 300 to 1500; e/e_dry
growing with St up to 300 (by at most 0.05 less from one St to the
next). The deviation from the fit at every St is in the table.
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMData import readTable  # noqa: E402
from immersedDEMCase import caseConstants, number  # noqa: E402

# The case Allrun makes (touchingBodies/makeCase.py: a glass sphere in
# water), for --startVelocity only, before the case exists; a run's
# figures take every constant from its case
RHO_P, RHO_F, D, G = 2500.0, 1000.0, 0.01, 9.81


def terminalVelocity(nu, g=G, rhoP=RHO_P, rhoF=RHO_F, D=D):
    """Settling speed of the sphere from the standard drag curve
    (Schiller-Naumann with the Newton-regime term), by bisection."""
    lo, hi = 1e-6, 10.0
    for _ in range(200):
        U = 0.5*(lo + hi)
        Re = U*D/nu
        Cd = 24/Re*(1 + 0.15*Re**0.687) + 0.42/(1 + 42500/Re**1.16)
        drag = 0.5*rhoF*U*U*Cd*math.pi*D*D/4
        weight = (rhoP - rhoF)*g*math.pi*D**3/6
        lo, hi = (U, hi) if drag < weight else (lo, U)
    return U


def viscosity(case):
    return caseConstants(case).nu


def bounce(case, body="ball"):
    """(St, U_in, U_out) of the first impact of the case's sphere; its
    radius and density, the fluid's density and viscosity from the case"""
    c = caseConstants(case)
    R = number(c.bodyEntry(body)["radius"])
    D = 2*R
    rhoP, rhoF, nu = c.density(body), c.rhoFluid, c.nu
    b = readTable(os.path.join(case, "postProcessing/bodies/0/bodies.dat")).where(body=body)
    t, z, vz = b["time"], b["z"], b["vz"]
    # the impact: the first row (after the start) no longer moving down
    k = next((i for i in range(2, len(z)) if vz[i] >= 0), None)
    near = [-vz[i] for i in range(k if k else len(z)) if z[i] - R < 0.5*D]
    if not near:
        raise SystemExit("%s: the sphere never came within d/2 of the wall" % case)
    Uin = max(near)
    St = rhoP*D*Uin/(9*rhoF*nu)
    if k is None:
        return St, Uin, 0.0
    i0 = min(range(k - 1, min(k + 3, len(z))), key=lambda i: z[i])
    Uout = 0.0
    for i in range(i0 + 1, len(z)):
        if z[i] < z[i - 1]:
            break
        Uout = max(Uout, (z[i] - z[i0])/(t[i] - t[i0]))
    return St, Uin, Uout


def legendre(St):
    return math.exp(-35/St)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("cases", nargs="*")
    p.add_argument("--startVelocity", type=float)
    p.add_argument("--plot")
    p.add_argument("--results")
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    if a.startVelocity:
        print(-0.6*terminalVelocity(a.startVelocity))
        return 0
    data = sorted((bounce(c) + (viscosity(c), c) for c in a.cases))
    lines = ["# St U_in[m/s] U_out[m/s] e/e_dry Legendre_fit nu[m2/s] case"]
    for St, Uin, Uout, nu, c in data:
        lines.append("%8.2f %8.4f %8.4f %7.3f %7.3f %9.3g %s"
                     % (St, Uin, Uout, Uout/Uin, legendre(St), nu, os.path.basename(c)))
    print("\n".join(lines))
    if a.results:
        with open(a.results, "w") as f:
            f.write("\n".join(lines) + "\n")
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        St = [d[0] for d in data]
        e = [d[2]/d[1] for d in data]
        fit = [10**(0.5 + 3.2*i/200) for i in range(201)]
        plt.figure(figsize=(6, 4))
        plt.semilogx(fit, [legendre(s) for s in fit], "k-",
                     label="exp(-35/St): Legendre et al. 2005, fit to\nGondret et al. 2002, Joseph et al. 2001")
        plt.axvline(10, color="0.6", ls=":", label="St_c about 10 (Gondret et al.)")
        plt.semilogx(St, e, "ro", label="immersedDEM")
        plt.xlabel("St = rho_p d U_in / (9 mu)")
        plt.ylabel("e / e_dry")
        plt.ylim(-0.05, 1.05)
        plt.legend(fontsize=8, loc="upper left")
        plt.tight_layout()
        plt.savefig(a.plot, dpi=120)
    if a.check:
        bad = []
        es = []
        # The bands are issue 15's acceptance (issue 48 asks for the
        # measured points instead): 0.1, no rebound to be seen below the
        # measured critical St of about 10; 0.7-1, where the fit is
        # 0.89-0.98 and the measurements scatter below it; 0.05, the dip
        # allowed between neighbouring St, which has no measured figure
        # behind it yet
        for St, Uin, Uout, nu, c in data:
            e = Uout/Uin
            if St < 11 and e >= 0.1:
                bad.append("St %.1f: rebound %.3f (none below St 11)" % (St, e))
            if 300 <= St <= 1500 and not 0.7 <= e <= 1:
                bad.append("St %.1f: %.3f (0.7-1 from St 300 to 1500)" % (St, e))
            if St <= 300:
                es.append(e)
        if any(b < a_ - 0.05 for a_, b in zip(es, es[1:])):
            bad.append("e does not grow with St up to 300: %s" % " ".join("%.3f" % x for x in es))
        if not data:
            bad.append("no runs")
        for b in bad:
            print("FAILED: " + b)
        return 1 if bad else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
