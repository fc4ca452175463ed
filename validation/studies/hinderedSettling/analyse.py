#!/usr/bin/env python3
"""Hindered settling against Richardson & Zaki (issue 45, item 3).

    analyse.py <work> [-plot FILE.png] [-tolerance 0.05]

<work> holds the runs of Allrun: phi<f> (spheres at volume fraction f in a
periodic box of 5 D), single<L> (one sphere in a box of L diameters),
and, if run, cubePhi<f> and cubeSingle5 (cubes of the sphere's volume),
box<L>-phi<f>[-s<S>] (spheres at fraction f in a box of L diameters,
from insertion seed S, default 1),
phi<f>-s<S> (the 5 D suspension from another random start: its U is
averaged with phi<f>'s in the main table), phi<f>-n<N> and single5-n<N>
(at N cells per diameter: the resolution table).
For each run the settling velocity U is the mean of -vz over the bodies
and over the second half of the run, in the frame of zero mean
volumetric flux that the fvOption's drive holds. Fluid and body
constants (nu, rhoInf, g, the density, the radius) are read from the
case of the smallest single-sphere box (every run is made alike by
makeCase.sh).

The isolated sphere's terminal velocity U_t, two ways:
- the standard drag curve (Schiller & Naumann 1933:
  C_D = 24/Re (1 + 0.15 Re^0.687); at Re 5 Clift, Grace & Weber's
  recommended curve is 1% above it): an unbounded fluid;
- the code's own: the single-sphere boxes extrapolated in D/L with the
  periodic array's leading form U(L) = U_t (1 - k D/L) (Hasimoto 1959:
  k = 1.42 in Stokes flow; fitted from the two largest boxes).
The check uses the first: the two boxes are not in the range where the
linear form holds (README.md).

References for U/U_t:
- Richardson & Zaki (1954) with Garside & Al-Dibouni's (1977) exponent:
  (1 - phi)^n, (5.1 - n)/(n - 2.7) = 0.1 Re_t^0.9. Judged: within the
  tolerance (issue 45's 5%).
- Yin & Koch (2007), Phys. Fluids 19, 093302: lattice-Boltzmann
  simulations of unbounded (periodic) suspensions, U/U_t = k (1 - phi)^n
  with k 0.86 +- 0.06, n 4.0 +- 0.3 at Re_t 5.00 (values as transcribed
  in dwille/bbtools, c-tools/phase-averages/flow/plt/rz-relations.py,
  "Yin and Koch, 2007, data"; not checked against the paper). Printed.

Cubes (printed, not judged: the correlation is written for spheres):
U over the spheres' U at the same fraction, and over the single cube's
velocity in the 5 D box against Haider & Levenspiel's drag for the
cube's sphericity (0.806).
"""
import argparse, glob, math, os, re, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "src", "python"))
from immersedDEMData import readTable  # noqa: E402
from immersedDEMCase import caseConstants, number  # noqa: E402
from immersedDEMBeds import garsideAlDibouni, schillerNaumannTerminalVelocity, terminalVelocity  # noqa: E402

YIN_KOCH_RE5 = (0.86, 0.06, 4.0, 0.3)   # k, its error, n, its error at Re_t 5.00


_tables = {}


def bodies(run):
    """The run's bodies.dat, read once."""
    if run not in _tables:
        _tables[run] = readTable(os.path.join(run, "postProcessing/sphere/0/bodies.dat"))
    return _tables[run]


def settling(run):
    """U, its change between the halves of the window, bodies, end time."""
    t = bodies(run)
    times, vz = t["time"], t["vz"]
    tEnd = max(times)
    per = {}
    for time, v in zip(times, vz):
        if time >= 0.5*tEnd:
            per.setdefault(time, []).append(-v)
    window = sorted(per)
    means = [sum(per[x])/len(per[x]) for x in window]
    half = len(means)//2
    u = sum(means)/len(means)
    change = (sum(means[half:])/(len(means) - half) - sum(means[:half])/half)/u
    return u, change, len(per[window[0]]), tEnd


def blockMeans(run, width=5.0):
    """The mean of -vz over the bodies in blocks of width seconds."""
    t = bodies(run)
    blocks = {}
    for time, v in zip(t["time"], t["vz"]):
        blocks.setdefault(int(time//width), []).append(-v)
    return [(width*b, sum(v)/len(v)) for b, v in sorted(blocks.items())]


NUMBER = r"[0-9]+(?:\.[0-9]+)?"
RUN_NAME = re.compile(r"^(?:(?P<single>single)(?P<L>{0})(?:-n(?P<sn>[0-9]+))?"
                      r"|phi(?P<phi>{0})(?:-s(?P<seed>[0-9]+)|-n(?P<n>[0-9]+))?"
                      r"|box(?P<box>{0})-phi(?P<bphi>{0})(?:-s(?P<bseed>[0-9]+))?"
                      r"|(?P<csingle>cubeSingle)(?P<cL>{0})|cubePhi(?P<cphi>{0}))$".format(NUMBER))


def runs(work):
    """The runs in work by kind: (kind, phi, box [D], cells per D named or
    None, path, seed); kind single, spheres, box or cube (phi 0: one
    cube); seed 1 unless the name ends -s<seed>. Folders of other names
    are not runs of this study."""
    found = []
    for path in sorted(glob.glob(os.path.join(work, "*"))):
        m = RUN_NAME.match(os.path.basename(path))
        if not m or not os.path.isdir(path):
            continue
        n = m.group("n") or m.group("sn")
        n = int(n) if n else None
        named = m.group("seed") or m.group("bseed")
        seed = int(named) if named else 1
        if named and seed == 1:
            # seed 1 is the plain name's start: not a second sample
            print("(%s skipped: seed 1 is the run %s)" % (os.path.basename(path), os.path.basename(path)[:-3]))
            continue
        if not os.path.exists(os.path.join(path, "postProcessing/sphere/0/bodies.dat")):
            print("(%s skipped: no bodies.dat)" % os.path.basename(path))
            continue
        if not finished(path):
            print("(%s has not reached its end time: analysed to where it is)" % os.path.basename(path))
        if m.group("single"):
            found.append(("single", 0.0, float(m.group("L")), n, path, seed))
        elif m.group("phi"):
            found.append(("spheres", float(m.group("phi")), 5.0, n, path, seed))
        elif m.group("box"):
            found.append(("box", float(m.group("bphi")), float(m.group("box")), n, path, seed))
        elif m.group("csingle"):
            found.append(("cube", 0.0, float(m.group("cL")), n, path, seed))
        else:
            found.append(("cube", float(m.group("cphi")), 5.0, n, path, seed))
    return found


def finished(run):
    """Whether the run's log ends with End (OpenFOAM's last line)."""
    log = os.path.join(run, "log.pimpleFoam")
    if not os.path.exists(log):
        return False
    with open(log) as f:
        return any(line.strip() == "End" for line in f)


def cellsPerDiameter(run, D):
    """Cells per diameter of a run: blockMeshDict's N over the box's side."""
    case = caseConstants(run)
    lo, hi = case.meshBounds()
    return int(round(number(case.dictionary("system", "blockMeshDict")["N"])*D/(hi[0] - lo[0])))


def linearInInverseBox(sizes):
    """Least-squares U = U_inf - c D/L through {L: U}: U_inf, c, and the
    largest residual over U (0 for two boxes)."""
    xs = [1.0/L for L in sizes]
    ys = [sizes[L] for L in sizes]
    mx, my = sum(xs)/len(xs), sum(ys)/len(ys)
    slope = sum((x - mx)*(y - my) for x, y in zip(xs, ys))/sum((x - mx)**2 for x in xs)
    uInf = my - slope*mx
    worst = max(abs(uInf + slope*x - y)/y for x, y in zip(xs, ys))
    return uInf, -slope, worst


def boxSizes(boxes, spheres, ut, n, kYK, nYK):
    """The suspensions in boxes of several sizes, extrapolated to an
    unbounded one as U = U_inf - c D/L (the leading finite-size term of a
    periodic suspension, as Hasimoto's for one sphere; with three boxes
    or more the residual says whether the points lie on it). Returns
    {phi: (U_inf/U_t, the number of boxes)}. Printed, not judged."""
    limits = {}
    for phi in sorted(boxes):
        sizes = dict(boxes[phi])
        if phi in spheres:
            sizes[5.0] = spheres[phi]
        if len(sizes) < 2:
            continue
        uInf, c, worst = linearInInverseBox(sizes)
        r = uInf/ut
        limits[phi] = (r, len(sizes))
        print("box-size limit, phi %g, boxes %s D: U_inf %.5f m/s, U_inf/U_t %.4f (Richardson & Zaki %+.1f%%, Yin & Koch %+.1f%%);"
              " c %.3f m/s, largest residual %.2f%%%s"
              % (phi, " ".join("%g" % L for L in sorted(sizes)), uInf, r, 100*(r/(1 - phi)**n - 1),
                 100*(r/(kYK*(1 - phi)**nYK) - 1), c, 100*worst, "" if len(sizes) > 2 else " (two boxes: no check of the form)"))
        print("  (printed, not judged: %s Richardson & Zaki's 5%% band)" % ("within" if abs(r/(1 - phi)**n - 1) <= 0.05 else "outside"))
    return limits


def observedOrder(hs, us):
    """Order p and limit of three values us at spacings hs (any ratios),
    as u = u0 + a h^p; a string saying why when there is none."""
    d1, d2 = us[1] - us[0], us[2] - us[1]
    if d1 == 0 or d2 == 0 or (d1 > 0) != (d2 > 0):
        return "differences of opposite sign: not converging monotonically"
    def f(p):
        return (hs[0]**p - hs[1]**p)/(hs[1]**p - hs[2]**p) - d1/d2
    lo, hi = 0.05, 8.0
    if f(lo)*f(hi) > 0:
        return "order outside [%g, %g]" % (lo, hi)
    for _ in range(200):
        mid = 0.5*(lo + hi)
        if f(lo)*f(mid) <= 0:
            hi = mid
        else:
            lo = mid
    p = 0.5*(lo + hi)
    return p, us[2] + d2*hs[2]**p/(hs[1]**p - hs[2]**p)


def resolution(found, firstStart, singles, ut, n, kYK, nYK, D, nBase):
    """The runs repeated at other resolutions (names ending -n<N>) beside
    the base ones (firstStart: the spheres' U of the seed-1 runs, the same
    start as the finer ones). Printed, not judged."""
    finer = [r for r in found if r[3] is not None and r[0] in ("single", "spheres") and r[2] == 5.0]
    if not finer:
        return
    print()
    print("| run (box 5 D) | cells per D | U [m/s] | U/U_t | over the %d-cell run | Richardson-Zaki | change over the window |" % nBase)
    print("|---|---|---|---|---|---|---|")
    for kind, phi in sorted({(r[0], r[1]) for r in finer}, key=lambda k: k[1]):
        baseU = singles.get(5.0) if kind == "single" else firstStart.get(phi)
        series = [(nBase, baseU, None)] if baseU is not None else []
        for _, _, _, _, run, _ in (r for r in finer if (r[0], r[1]) == (kind, phi)):
            u, change, nb, tEnd = settling(run)
            series.append((cellsPerDiameter(run, D), u, change))
        series.sort(key=lambda x: x[0])
        name = "one sphere" if kind == "single" else "phi %g" % phi
        for cells, u, change in series:
            print("| %s | %d | %.5f | %.4f | %s | %s | %s |"
                  % (name, cells, u, u/ut, "%.4f" % (u/baseU) if baseU else "",
                     "%.4f" % ((1 - phi)**n) if phi > 0 else "", "%+.1f%%" % (100*change) if change is not None else "(above)"))
        if len({c for c, _, _ in series}) < len(series):
            print("  %s: two runs at the same cells per diameter: no extrapolation" % name)
        elif len(series) >= 3:
            fit = observedOrder([1.0/c for c, _, _ in series[-3:]], [u for _, u, _ in series[-3:]])
            if not isinstance(fit, str):
                p, uLim = fit
                print("  %s: observed order %.2f from %s cells; extrapolated U/U_t %.4f%s"
                      % (name, p, ", ".join("%d" % c for c, _, _ in series[-3:]), uLim/ut,
                         " (Richardson & Zaki %+.1f%%, Yin & Koch %+.1f%%)" % (100*((uLim/ut)/(1 - phi)**n - 1),
                                                                               100*((uLim/ut)/(kYK*(1 - phi)**nYK) - 1)) if phi > 0 else ""))
            else:
                print("  %s: %s; no extrapolation" % (name, fit))


def constants(run):
    """nu, the density ratio, |g| and the sphere's diameter of a run."""
    case = caseConstants(run)
    body = bodies(run)["body"][0]
    entry = case.bodyEntry(body)
    d = 2*number(entry["radius"]) if "radius" in entry else None
    return case.nu, case.density(body)/case.rhoFluid, case.gravity, d


def main():
    p = argparse.ArgumentParser()
    p.add_argument("work")
    p.add_argument("-plot")
    p.add_argument("-tolerance", type=float, default=0.05)
    a = p.parse_args()
    found = runs(a.work)
    base = [r for r in found if r[3] is None and r[5] == 1]
    seeded = [r for r in found if r[3] is None and r[0] == "spheres"]
    singles = {}
    for _, _, L, _, run, _ in sorted((r for r in base if r[0] == "single"), key=lambda r: r[2]):
        u, change, n, tEnd = settling(run)
        singles[L] = u
        print("one sphere, box %g D: U %.5f m/s (change over the window %+.2f%%, %g s)" % (L, u, 100*change, tEnd))
    if not singles:
        sys.exit("analyse.py: no single-sphere run in %s" % a.work)
    smallest = [r[4] for r in base if r[0] == "single" and r[2] == min(singles)][0]
    nu, ratio, g, D = constants(smallest)
    nBase = cellsPerDiameter(smallest, D)
    ut = schillerNaumannTerminalVelocity(nu, ratio, g, D)
    re = ut*D/nu
    n = garsideAlDibouni(re)
    print("isolated sphere, standard drag (Schiller & Naumann): U_t %.5f m/s, Re_t %.2f, Garside & Al-Dibouni n %.3f"
          % (ut, re, n))
    for L in sorted(singles):
        print("  box %g D: U/U_t %.4f (Hasimoto's Stokes correction 1 - 1.42 D/L would give %.4f)"
              % (L, singles[L]/ut, 1 - 1.42*D/L))
    utCode = None
    if len(singles) >= 2:
        (L1, u1), (L2, u2) = sorted(singles.items())[-2:]
        x1, x2 = D/L1, D/L2
        utCode = (u1*x2 - u2*x1)/(x2 - x1)
        print("the code's boxes extrapolated linearly in D/L from %g and %g D: U_t %.5f m/s (k %.3f), %.3f of the standard drag's"
              % (L1, L2, utCode, (1 - u2/utCode)/x2, utCode/ut))
    kYK, kErr, nYK, nErr = YIN_KOCH_RE5
    print()
    print("Spheres in boxes of 5 D, %d cells per diameter:" % nBase)
    print()
    print("| phi | spheres | U [m/s] | U/U_t | Richardson-Zaki (1-phi)^n | deviation | Yin & Koch k(1-phi)^n | deviation | U/U_t with the code's U_t | change over the window |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    ok = True
    rows = []
    spheres = {}
    seedLines = []
    firstStart = {}
    for phi in sorted({r[1] for r in seeded}):
        # every random start of this fraction: U their mean (independent
        # samples of the same suspension)
        samples = [(r[5],) + settling(r[4]) for r in sorted((r for r in seeded if r[1] == phi), key=lambda r: r[5])]
        u = sum(x[1] for x in samples)/len(samples)
        firstStart.update({phi: x[1] for x in samples if x[0] == 1})
        # the largest change of a start (a mean could cancel them)
        change = max((x[2] for x in samples), key=abs)
        nb = samples[0][3]
        if len(samples) > 1:
            seedLines.append("phi %g, U/U_t of each start (seed: value): %s; mean %.4f, the starts within %.1f%% of it"
                             % (phi, ", ".join("%d: %.4f" % (x[0], x[1]/ut) for x in samples), u/ut,
                                100*max(abs(x[1]/u - 1) for x in samples)))
        spheres[phi] = u
        rz = (1 - phi)**n
        yk = kYK*(1 - phi)**nYK
        dev = (u/ut)/rz - 1
        good = abs(dev) <= a.tolerance
        ok = ok and good
        rows.append((phi, u/ut))
        print("| %g | %s | %.5f | %.4f | %.4f | %+.1f%% | %.4f | %+.1f%% | %s | %+.1f%% |%s"
              % (phi, "%d" % nb if len(samples) == 1 else "%d, %d starts" % (nb, len(samples)), u, u/ut, rz, 100*dev, yk, 100*((u/ut)/yk - 1),
                 "%.4f" % (u/utCode) if utCode else "", 100*change,
                 "" if good else " outside %g%%" % (100*a.tolerance)))
    for line in seedLines:
        print(line)
    if len(rows) >= 2:
        xs = [math.log(1 - r[0]) for r in rows]
        ys = [math.log(r[1]) for r in rows]
        mx, my = sum(xs)/len(xs), sum(ys)/len(ys)
        nFit = sum((x - mx)*(y - my) for x, y in zip(xs, ys))/sum((x - mx)**2 for x in xs)
        print("fit of U/U_t = k (1 - phi)^n to the 5 D box's fractions: k %.3f, n %.2f (Yin & Koch %.2f +- %.2f, %.1f +- %.1f)"
              % (math.exp(my - nFit*mx), nFit, kYK, kErr, nYK, nErr))
    for phi, _ in rows:
        v = kYK*(1 - phi)**nYK
        print("Yin & Koch's k and n at their quoted limits, phi %g: %+.1f%% to %+.1f%% of their fit"
              % (phi, 100*((kYK - kErr)*(1 - phi)**(nYK + nErr)/v - 1), 100*((kYK + kErr)*(1 - phi)**(nYK - nErr)/v - 1)))
    for run in [r[4] for r in found if r[0] in ("spheres", "cube") and r[1] > 0]:
        print("5 s means of -vz [m/s], %s: %s" % (os.path.basename(run),
              " ".join("%g:%.3f" % m for m in blockMeans(run))))
    largeRows = []
    boxes = {}
    boxRuns = {}
    for _, phi, L, _, run, seed in (r for r in found if r[0] == "box" and r[3] is None):
        boxRuns.setdefault((phi, L), []).append((seed, run))
    for phi, L in sorted(boxRuns):
        # a suspension in a larger box (the box size's effect; not judged);
        # several starts averaged, as in the 5 D box
        samples = [(seed,) + settling(run) for seed, run in sorted(boxRuns[(phi, L)])]
        u = sum(x[1] for x in samples)/len(samples)
        change = sum(x[2] for x in samples)/len(samples)
        nb, tEnd = samples[0][3], min(x[4] for x in samples)
        boxes.setdefault(phi, {})[L] = u
        largeRows.append((phi, u/ut, L))
        starts = "" if len(samples) == 1 else (
            "; %d starts (seed: U/U_t %s), within %.1f%% of their mean"
            % (len(samples), ", ".join("%d: %.4f" % (x[0], x[1]/ut) for x in samples),
               100*max(abs(x[1]/u - 1) for x in samples)))
        print("box %g D, phi %g (%d spheres, to %g s): U %.5f m/s, U/U_t %.4f (Richardson & Zaki %+.1f%%, Yin & Koch %+.1f%%),"
              " %s the 5 D box's; change over the window %+.1f%%%s"
              % (L, phi, nb, tEnd, u, u/ut, 100*((u/ut)/(1 - phi)**n - 1), 100*((u/ut)/(kYK*(1 - phi)**nYK) - 1),
                 "%.4f of" % (u/spheres[phi]) if phi in spheres else "no run in", 100*change, starts))
    boxLimit = boxSizes(boxes, spheres, ut, n, kYK, nYK)
    resolution(found, firstStart, singles, ut, n, kYK, nYK, D, nBase)
    cubeRows = []
    cubeSingle = os.path.join(a.work, "cubeSingle5")
    cubeRuns = [r[4] for r in sorted((r for r in base if r[0] == "cube" and r[1] > 0), key=lambda r: r[1])]
    if cubeRuns or os.path.isdir(cubeSingle):
        print()
        side = (math.pi/6)**(1.0/3)*D
        uhl, dv, psi = terminalVelocity(side**3, 6*side**2, ratio, 1.0, nu, g)
        uhls, _, _ = terminalVelocity(math.pi/6*D**3, math.pi*D**2, ratio, 1.0, nu, g)
        print("Haider & Levenspiel: the cube (sphericity %.3f) U_t %.5f m/s, the sphere %.5f: cube/sphere %.4f"
              % (psi, uhl, uhls, uhl/uhls))
        if os.path.isdir(cubeSingle):
            uc5, change, nb, tEnd = settling(cubeSingle)
            print("one cube (side %.4f m, the sphere's volume), box 5 D: U %.5f m/s (change over the window %+.2f%%, %g s);"
                  " over the sphere's in the same box %s (Haider & Levenspiel's ratio %.4f)"
                  % (side, uc5, 100*change, tEnd, "%.4f" % (uc5/singles[5.0]) if 5.0 in singles else "(no sphere run)",
                     uhl/uhls))
        print()
        print("| phi | cubes | U [m/s] | over the spheres' U at this phi | U over Haider & Levenspiel's U_t | Richardson-Zaki at the cube's Re_t | change over the window |")
        print("|---|---|---|---|---|---|---|")
        nc = garsideAlDibouni(uhl*D/nu)
        for run in cubeRuns:
            phi = [r[1] for r in found if r[4] == run][0]
            u, change, nb, tEnd = settling(run)
            cubeRows.append((phi, u/uhl))
            # ("<phi> (cubes)": Allvalidate's summary reads the rows that
            # start with a bare number, the spheres' judged ones)
            print("| %g (cubes) | %d | %.5f | %s | %.4f | %.4f | %+.1f%% |"
                  % (phi, nb, u, "%.4f" % (u/spheres[phi]) if phi in spheres else "not run",
                     u/uhl, (1 - phi)**nc, 100*change))
    print()
    print("PASS" if ok else "FAIL: a fraction misses Richardson & Zaki by more than %g%%" % (100*a.tolerance))
    if a.plot and rows:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        f = [i/200 for i in range(0, 61)]
        ax.plot(f, [(1 - x)**n for x in f], "k-", label="Richardson & Zaki, n = %.2f (Garside & Al-Dibouni)" % n)
        ax.fill_between(f, [(1 - a.tolerance)*(1 - x)**n for x in f], [(1 + a.tolerance)*(1 - x)**n for x in f],
                        color="0.9", label="+-%g%%" % (100*a.tolerance))
        ax.plot(f, [kYK*(1 - x)**nYK for x in f], "k--",
                label="Yin & Koch (2007) simulations: %.2f (1 - phi)^%.1f" % (kYK, nYK))
        ax.plot([r[0] for r in rows], [r[1] for r in rows], "o", label="immersedDEM, spheres (U_t standard drag)")
        sizes = sorted({L for _, _, L in largeRows})
        for i, L in enumerate(sizes):
            pts = [(phi, r) for phi, r, LL in largeRows if LL == L]
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "^v<>"[i % 4], color="C%d" % (i + 1),
                    label="immersedDEM, spheres, box of %g D" % L)
        if boxLimit:
            ax.plot(sorted(boxLimit), [boxLimit[phi][0] for phi in sorted(boxLimit)], "D", color="C5",
                    label="immersedDEM, spheres, U_inf - c D/L through %s boxes" % "/".join(sorted({"%d" % boxLimit[phi][1] for phi in boxLimit})))
        if cubeRows:
            ax.plot([r[0] for r in cubeRows], [r[1] for r in cubeRows], "s", color="C7",
                    label="immersedDEM, cubes (U_t Haider & Levenspiel)")
        ax.set_xlabel("volume fraction phi")
        ax.set_ylabel("U / U_t")
        ax.set_ylim(0, 1.05)
        ax.set_title("Hindered settling, Re_t = %.1f, triply periodic boxes of 5 D (and as marked), %d cells per D" % (re, nBase), fontsize=9)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
