#!/usr/bin/env python3
"""Terminal velocity of the settling 2D cylinder, body-fitted (issue 18).

    terminal.py <work> [makeCase.py bodyFitted options, e.g. -nTheta 48 -nRadial 60]

In the cylinder's frame at terminal speed U the flow is steady: the walls and
the inflow move past the held cylinder at U. Each run (stock simpleFoam,
makeCase.py bodyFitted) gives the drag per slab depth F(U); a secant on
log F against log U finds the U at which F equals the buoyant weight per
depth, |rho_s - rho_f| g pi D^2/4, to 1e-5 (-density rho_s, default
1500). Runs go to <work>/U_<speed>.
Prints one line: U_t, Re and the number of cells.
"""
import math, os, re, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import makeCase  # noqa: E402


def drag(work, U, extra):
    d = os.path.join(work, "U_%.9g" % U)
    if not os.path.exists(os.path.join(d, "done")):
        subprocess.run(["rm", "-rf", d], check=True)
        out = subprocess.run([sys.executable, os.path.join(here, "makeCase.py"), d, "bodyFitted",
                              "-U", repr(U)] + extra, check=True, capture_output=True, text=True).stdout
        for app in ("blockMesh", "simpleFoam"):
            with open(os.path.join(d, "log." + app), "w") as log:
                if subprocess.run([app], cwd=d, stdout=log, stderr=subprocess.STDOUT).returncode:
                    sys.exit("terminal.py: %s failed in %s" % (app, d))
        log = open(os.path.join(d, "log.simpleFoam")).read()
        if "SIMPLE solution converged" not in log:
            sys.exit("terminal.py: simpleFoam did not converge in %s (raise -iterations)" % d)
        open(os.path.join(d, "done"), "w").write(out)
    cells = int(re.search(r"(\d+) cells", open(os.path.join(d, "done")).read()).group(1))
    last = [l for l in open(os.path.join(d, "postProcessing/forces/0/force.dat")) if not l.startswith("#")][-1]
    fx = float(last.split("(")[1].split()[0])
    slab = 0.001
    if "-slab" in extra:
        slab = float(extra[extra.index("-slab") + 1])
    return fx/slab, cells


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    work, extra = sys.argv[1], sys.argv[2:]
    nu = float(extra[extra.index("-nu") + 1]) if "-nu" in extra else 1e-4
    rhoS = float(extra[extra.index("-density") + 1]) if "-density" in extra else makeCase.RHO_S
    # (a light body rises: the flow is the mirror image of the settling
    # one of the same |rho_s - rho_f|)
    W = makeCase.buoyantWeightPerDepth(rhoS)
    U0 = 0.1
    F0, cells = drag(work, U0, extra)
    # a first guess from a drag growing like U^1.3 (Re about 10)
    U1 = U0*(W/F0)**(1/1.3)
    F1, cells = drag(work, U1, extra)
    for _ in range(20):
        if abs(F1/W - 1) < 1e-5:    # the secant's stop: far below the grids' 0.01-0.03% spread
            break
        n = math.log(F1/F0)/math.log(U1/U0)
        U0, F0 = U1, F1
        U1 = U1*(W/F1)**(1/n)
        F1, cells = drag(work, U1, extra)
    else:
        sys.exit("terminal.py: no convergence")
    print("body-fitted terminal velocity %.6f m/s, Re %.4f, drag/weight %.7f, %d cells"
          % (U1, U1*makeCase.D/nu, F1/W, cells))


if __name__ == "__main__":
    main()
