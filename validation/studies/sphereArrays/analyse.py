#!/usr/bin/env python3
"""Stokes drag in simple cubic sphere arrays against Zick & Homsy (1982).

    analyse.py <work> [-c "0.064 ..."] [-n "8 12 16"]

For each run <work>/c<c>-n<n> (makeCase.py): K = F/(6 pi mu a U), F the
mean fluid force along the flow on the eight spheres at the end, U the
box's mean velocity (meanVelocityForce's Ubar), mu and a read from the
case. Reference: Zick & Homsy, J. Fluid Mech. 115, 13 (1982), Table 2,
simple cubic arrays (their U the mean over the whole cell, the spheres
included, as here); at 0.027 it is Hasimoto's (1959) series to 4 digits.
Checks (exit 1 on a failure):
- steady: K changed by less than 0.1% over the last fifth of the run (a
  Stokes flow after 5 of its slowest viscous modes: what changes is the
  remaining e^-5 of the start);
- converging: at every fraction the error shrinks with each refinement;
- the finest run of every fraction within 5% of Zick & Homsy: the target
  of hindered settling (issue 45), whose velocity at Re << 1 carries the
  drag's error one to one.
"""
import argparse, math, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMData import readTable  # noqa: E402
from immersedDEMCase import caseConstants, number, vector  # noqa: E402

ZICK_HOMSY = {0.027: 2.008, 0.064: 2.810, 0.125: 4.292, 0.216: 7.442, 0.343: 15.4, 0.45: 28.1, 0.5236: 42.1}
BAND = 0.05


def dragCoefficient(run):
    case = caseConstants(run)
    mu = case.rhoFluid*case.nu
    t = readTable(os.path.join(run, "postProcessing/sphere/0/bodies.dat"))
    names = sorted(set(t["body"]))
    a = number(case.bodyEntry(names[0])["radius"])
    U = vector(case.dictionary("constant", "fvOptions")["drive"]["meanVelocityForceCoeffs"]["Ubar"])[0]
    times = sorted(set(t["time"]))
    def K(time):
        rows = t.where(time=time)
        return sum(rows["Ffx"])/len(rows)/(6*math.pi*mu*a*U)
    end = K(times[-1])
    earlier = K(min(times, key=lambda x: abs(x - 0.8*times[-1])))
    params = dict(l.split() for l in open(os.path.join(run, "caseParameters")) if l.strip())
    return end, end/earlier - 1, float(params["cellsPerDiameter"]), len(names)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("work")
    p.add_argument("-c", default="0.064 0.125 0.216 0.343")
    p.add_argument("-n", default="8 12 16")
    a = p.parse_args()
    fractions = [float(x) for x in a.c.split()]
    resolutions = [int(x) for x in a.n.split()]
    ok = True
    print("Stokes drag K = F/(6 pi mu a U) in simple cubic arrays against Zick & Homsy (1982), Table 2")
    print("%-6s %-8s %-10s %-10s %-8s %-9s %s" % ("c", "cells/D", "K", "Z&H", "error", "steady", "spheres"))
    for c in fractions:
        if c not in ZICK_HOMSY:
            sys.exit("analyse.py: %g is not one of Zick & Homsy's fractions %s" % (c, sorted(ZICK_HOMSY)))
        ref = ZICK_HOMSY[c]
        errors = []
        cells = []
        for n in resolutions:
            K, change, cpd, nb = dragCoefficient(os.path.join(a.work, "c%g-n%d" % (c, n)))
            err = K/ref - 1
            errors.append(err)
            cells.append(cpd)
            steady = abs(change) < 1e-3
            ok = ok and steady
            print("%-6g %-8.2f %-10.4f %-10.4g %+7.2f%% %+8.4f%% %d%s"
                  % (c, cpd, K, ref, 100*err, 100*change, nb, "" if steady else "  NOT STEADY"))
        converging = all(abs(errors[i + 1]) < abs(errors[i]) for i in range(len(errors) - 1))
        if len(errors) >= 2 and errors[-1] != 0 and errors[-2] != 0:
            # apparent order from the two finest runs (their actual cells per diameter)
            order = math.log(abs(errors[-2]/errors[-1]))/math.log(cells[-1]/cells[-2])
            print("c %g: apparent order of the error from the two finest runs %.2f" % (c, order))
        within = abs(errors[-1]) <= BAND
        ok = ok and converging and within
        print("c %g: %s, finest %+.2f%% %s" % (c, "converging" if converging else "NOT converging",
              100*errors[-1], "within %g%%" % (100*BAND) if within else "OUTSIDE %g%%" % (100*BAND)))
    print("PASS" if ok else "FAIL")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
