#!/usr/bin/env python3
"""Force coefficients of the 2D cylinder cases of makeCase.py.

    forceFigures.py <case> [-from T] [-cycles N]

Reads the force history of a case (bodyFitted: postProcessing/coeffs/*/
coefficient.dat; immersed: postProcessing/bodies/*/bodies.dat, all start
times, later runs winning), and prints over the last N whole lift cycles
(or from time T): mean drag coefficient, drag amplitude (half of max - min
per lift cycle, averaged), lift amplitude (likewise) and Strouhal number
(from the upward zero crossings of the lift, linearly interpolated).
As a module: history(case) -> (t, Cd, Cl); figures(t, Cd, Cl, ...) -> dict;
scales(case) -> (U, D), the case's speed and diameter for the Strouhal
number (figures(..., U=, D=); the study's by default).
"""
import glob, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMCase import caseConstants, number, readDictionary, vector  # noqa: E402

# The study's diameter and speed (makeCase.py): the Strouhal number's
# default; scales(case) reads a run's own
D, U = 0.01, 0.01


def immersedConstants(case):
    """(rho, U, D) of an immersed run: rhoInf, the inflow's final speed
    (0/U's inlet) and the cylinder's diameter (its surface's extent)"""
    c = caseConstants(case)
    inlet = readDictionary(os.path.join(case, "0", "U"))["boundaryField"]["inlet"]
    if "uniformValue" in inlet:
        table = inlet["uniformValue"]          # table ((t (u v w)) ...)
        u = vector(table[-1][-1][-1])
    else:
        u = vector(inlet["value"][-1])         # uniform (u v w)
    e = c.bodyEntry("cylinder")
    scale = number(e.get("scale", "1"))
    xs = [float(l.split()[1])*scale
          for l in open(os.path.join(case, "constant", "triSurface", e["file"].strip('"')))
          if l.strip().startswith("vertex")]
    return c.rhoFluid, sum(x*x for x in u)**0.5, max(xs) - min(xs)


def _slab(case):
    # thickness of the one-cell slab from blockMeshDict's vertices
    txt = open(os.path.join(case, "system/blockMeshDict")).read()
    scale = float(txt.split("scale")[1].split(";")[0])
    zs = set()
    vs = txt.split("vertices")[1].split(");")[0]
    for tok in vs.replace("(", " ( ").replace(")", " ) ").split("(")[1:]:
        parts = tok.split(")")[0].split()
        if len(parts) == 3:
            zs.add(float(parts[2]))
    return (max(zs) - min(zs))*scale


def scales(case):
    """(U, D) of a run: a body-fitted one's forceCoeffs magUInf and lRef,
    an immersed one's inflow and cylinder (immersedConstants)"""
    cd = readDictionary(os.path.join(case, "system", "controlDict"))
    coeffs = cd.get("functions", {}).get("coeffs")
    if isinstance(coeffs, dict) and coeffs.get("type") == "forceCoeffs":
        return number(coeffs["magUInf"]), number(coeffs["lRef"])
    rho, u, d = immersedConstants(case)
    return u, d


def history(case):
    rows = {}
    files = glob.glob(os.path.join(case, "postProcessing/coeffs/*/coefficient*.dat"))
    if files:
        for f in sorted(files, key=lambda p: float(p.split("/")[-2])):
            head = None
            for line in open(f):
                if line.startswith("#"):
                    cols = line[1:].split()
                    if "Time" in cols:
                        head = cols
                    continue
                v = line.split()
                if not v or head is None:
                    continue
                r = dict(zip(head, v))
                rows[float(r["Time"])] = (float(r["Cd"]), float(r["Cl"]))
    else:
        files = glob.glob(os.path.join(case, "postProcessing/bodies/*/bodies*.dat"))
        if not files:
            raise SystemExit("forceFigures: no force history in %s" % case)
        rho, u, d = immersedConstants(case)
        q = 0.5*rho*u*u*d*_slab(case)
        for f in sorted(files, key=lambda p: (float(p.split("/")[-2]), os.path.getmtime(p))):
            head = None
            for line in open(f):
                if line.startswith("#"):
                    head = line[1:].split()
                    continue
                v = line.split()
                if not v or head is None:
                    continue
                r = dict(zip(head, v))
                rows[float(r["time"])] = (float(r["Ffx"])/q, float(r["Ffy"])/q)
    t = sorted(rows)
    return t, [rows[x][0] for x in t], [rows[x][1] for x in t]


def figures(t, Cd, Cl, tFrom=None, cycles=None, U=U, D=D):
    ups = []
    for i in range(1, len(t)):
        if Cl[i - 1] < 0 <= Cl[i]:
            f = -Cl[i - 1]/(Cl[i] - Cl[i - 1])
            ups.append(t[i - 1] + f*(t[i] - t[i - 1]))
    if tFrom is not None:
        ups = [u for u in ups if u >= tFrom]
    if cycles is not None:
        ups = ups[-(cycles + 1):]
    if len(ups) < 2:
        raise SystemExit("forceFigures: no whole lift cycle")
    clA, cdA, cdM = [], [], []
    for a, b in zip(ups[:-1], ups[1:]):
        idx = [i for i in range(len(t)) if a <= t[i] < b]
        cl = [Cl[i] for i in idx]
        cd = [Cd[i] for i in idx]
        clA.append((max(cl) - min(cl))/2)
        cdA.append((max(cd) - min(cd))/2)
        # time-weighted mean over the cycle
        s = 0.0
        for i, j in zip(idx[:-1], idx[1:]):
            s += 0.5*(Cd[i] + Cd[j])*(t[j] - t[i])
        cdM.append(s/(t[idx[-1]] - t[idx[0]]))
    n = len(clA)
    period = (ups[-1] - ups[0])/n
    return {
        "cycles": n, "from": ups[0], "to": ups[-1],
        "CdMean": sum(cdM)/n, "CdAmp": sum(cdA)/n, "ClAmp": sum(clA)/n,
        "St": D/(U*period),
        # spread of the lift amplitude over the cycles (saturation check)
        "ClAmpSpread": (max(clA) - min(clA))/(sum(clA)/n),
    }


def main():
    a = sys.argv[1:]
    if not a:
        raise SystemExit(__doc__)
    case, tFrom, cycles = a[0], None, 4
    if "-from" in a:
        tFrom = float(a[a.index("-from") + 1]); cycles = None
    if "-cycles" in a:
        cycles = int(a[a.index("-cycles") + 1])
    t, Cd, Cl = history(case)
    u, d = scales(case)
    f = figures(t, Cd, Cl, tFrom, cycles, U=u, D=d)
    print("%s: cycles %d (t %.3f to %.3f) CdMean %.4f CdAmp %.5f ClAmp %.4f St %.4f ClAmpSpread %.4f"
          % (case, f["cycles"], f["from"], f["to"], f["CdMean"], f["CdAmp"], f["ClAmp"], f["St"], f["ClAmpSpread"]))


if __name__ == "__main__":
    main()
