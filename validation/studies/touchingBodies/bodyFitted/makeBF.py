#!/usr/bin/env python3
"""Body-fitted quarter-tank case of one cube of a face-to-face pair, in the
cubes' frame (the cube is at rest, the tank fluid moves up past it at W(t),
the IB pair's mean fall speed read from ib_history.csv).

Quarter domain x in [0,25] mm, y in [0,25] mm, z in [0,150] mm with symmetry
planes x = 0 (the gap's mid-plane) and y = 0; the cube occupies
x in [0.05,10.05], y in [0,5], z in [95,105] mm (removed: no block inside).

usage: makeBF.py [CASE] [--work DIR] [--ib CSV] [--gapCells 8] [--first 0.15]
       [--growth 1.15] [--halfGap 0.05] [--endTime 0.2] [--maxCo 0.9]
CASE defaults to DIR/bfcase, --ib to DIR/ib_history.csv.
The patch "cube" is split into cubeGap (x=0.05), cubeOuter (x=10.05),
cubeSide (y=5), cubeBottom (z=95), cubeTop (z=105), all in group "cube".
Forces on the patches are those on HALF a cube (y >= 0): multiply x and z
components by 2 for one whole cube. Prints the mesh summary.
"""
import argparse, csv, math, os, sys

ap = argparse.ArgumentParser(description="body-fitted quarter-tank case of two touching cubes")
ap.add_argument("case", nargs="?", help="case directory (default WORK/bfcase)")
ap.add_argument("--work", default="/tmp/immersedDEM-bodyFitted", help="work directory")
ap.add_argument("--ib", help="IB history from extractIB.py (default WORK/ib_history.csv)")
ap.add_argument("--gapCells", type=int, default=8)
ap.add_argument("--first", type=float, default=0.15, help="cell size at the cube faces, mm")
ap.add_argument("--growth", type=float, default=1.15, help="cell-to-cell growth away from the cube")
ap.add_argument("--halfGap", type=float, default=0.05, help="half gap, mm (sensitivity only)")
ap.add_argument("--endTime", type=float, default=0.2)
ap.add_argument("--maxCo", type=float, default=0.9)
args = ap.parse_args()
if args.case is None:
    args.case = os.path.join(args.work, "bfcase")
if args.ib is None:
    args.ib = os.path.join(args.work, "ib_history.csv")

A = args.first
G = args.growth


def solve_ratio(L, n, a):
    """cell-to-cell ratio r so that n cells starting at size a fill L"""
    if abs(n * a - L) < 1e-12:
        return 1.0
    lo, hi = (1.0 + 1e-12, 3.0) if n * a < L else (0.2, 1.0 - 1e-12)
    f = lambda r: a * (r ** n - 1) / (r - 1) - L
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if (f(mid) > 0) == (f(hi) > 0):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def one_sided(L, a, g, cap):
    """cells from size a (at the START of the segment) growing by g up to
    cap, then uniform. Returns (n, sections, sizes): sections as blockMesh
    multi-grading (lengthFrac cellFrac expansion) in the segment's direction."""
    ng = max(1, int(math.ceil(math.log(cap / a) / math.log(g))))
    Lg = a * (g ** ng - 1) / (g - 1)
    if L - Lg < cap:  # geometric alone: fewest cells with growth <= g
        ng = 1
        while a * (g ** ng - 1) / (g - 1) < L:
            ng += 1
        r = solve_ratio(L, ng, a)
        return ng, [(1.0, 1.0, r ** (ng - 1))], [a * r ** i for i in range(ng)]
    nu = max(1, int(round((L - Lg) / cap)))
    n = ng + nu
    sizes = [a * g ** i for i in range(ng)] + [(L - Lg) / nu] * nu
    return n, [(Lg / L, ng / n, g ** (ng - 1)), ((L - Lg) / L, nu / n, 1.0)], sizes


def reverse(sec, sizes):
    return [(l, c, 1.0 / e) for (l, c, e) in reversed(sec)], list(reversed(sizes))


def two_sided(L, a, g, cap):
    """fine at both ends (symmetric)"""
    n, sec, sizes = one_sided(L / 2, a, g, cap)
    half = [(l / 2, c / 2, e) for (l, c, e) in sec]
    rsec, rsizes = reverse(half, sizes)
    return 2 * n, half + rsec, sizes + rsizes


def sections(sizes):
    """exact blockMesh multi-grading for a list of cell sizes made of
    geometric runs: greedy maximal runs of constant cell-to-cell ratio"""
    L, n = sum(sizes), len(sizes)
    out, i0 = [], 0
    while i0 < n:
        i1 = i0 + 1
        if i1 < n:
            r = sizes[i1] / sizes[i0]
            while i1 + 1 < n and abs(sizes[i1 + 1] / sizes[i1] - r) < 1e-9 * r:
                i1 += 1
            i1 += 1
        run = sizes[i0:i1]
        out.append((sum(run) / L, len(run) / n, run[-1] / run[0]))
        i0 = i1
    return out


def seg(sizes):
    return (len(sizes), sections(sizes), sizes)


def split(sizes, x0, at):
    """split a size list starting at x0 at the node nearest to 'at'"""
    nodes = [x0]
    for s_ in sizes:
        nodes.append(nodes[-1] + s_)
    m = min(range(1, len(sizes)), key=lambda q: abs(nodes[q] - at))
    return nodes[m], sizes[:m], sizes[m:]


# Topology: lattice of x-lines (0, xg, 10.05, 25), y-lines (0, 5, y2, 25),
# z-lines (0, z1, 95, 105, z4, 150). The x-line xg is 0.05 on the cube's
# gap face (y <= 5, 95 <= z <= 105) and FAN mm elsewhere: the gap's 8-cell
# slab fans out to FAN beyond the cube so that its cells do not stay
# 6 um thin through the whole tank (aspect ratios of 600 stall the
# pressure solver).
FAN = args.gapCells * A          # slab cells of ~A away from the cube
DY = DZ = 5.0                    # fan length beyond the cube's edges
HG = args.halfGap
sx = [HG / args.gapCells] * args.gapCells
sx1 = two_sided(10.0, A, G, 1.0)[2]
sx2 = one_sided(25.0 - 10.0 - HG, A, G, 2.0)[2]
sy0 = list(reversed(one_sided(5.0, A, G, 1.0)[2]))
y2, sy1, sy2 = split(one_sided(20.0, A, G, 2.0)[2], 5.0, 5.0 + DY)
lo = list(reversed(one_sided(95.0, A, G, 4.0)[2]))
z1, sz0, sz1 = split(lo, 0.0, 95.0 - DZ)
sz2 = two_sided(10.0, A, G, 1.0)[2]
z4, sz3, sz4 = split(one_sided(45.0, A, G, 2.5)[2], 105.0, 105.0 + DZ)

X = [0.0, None, 10.0 + HG, 25.0]
Y = [0.0, 5.0, y2, 25.0]
Z = [0.0, z1, 95.0, 105.0, z4, 150.0]
NI, NJ, NK = len(X), len(Y), len(Z)
segX = [seg(sx), seg(sx1), seg(sx2)]
segY = [seg(sy0), seg(sy1), seg(sy2)]
segZ = [seg(sz0), seg(sz1), seg(sz2), seg(sz3), seg(sz4)]


def xcoord(i, j, k):
    if i != 1:
        return X[i]
    return HG if (j <= 1 and 2 <= k <= 3) else FAN


def vid(i, j, k):
    return i + NI * (j + NJ * k)


def gstr(sec):
    if len(sec) == 1:
        return "%.10g" % sec[0][2]
    return "(" + " ".join("(%.10g %.10g %.10g)" % s for s in sec) + ")"


CUBE = (1, 0, 2)
blocks = []
for k in range(NK - 1):
    for j in range(NJ - 1):
        for i in range(NI - 1):
            if (i, j, k) == CUBE:
                continue
            blocks.append((i, j, k))


def hexv(i, j, k):
    return [vid(i, j, k), vid(i + 1, j, k), vid(i + 1, j + 1, k), vid(i, j + 1, k),
            vid(i, j, k + 1), vid(i + 1, j, k + 1), vid(i + 1, j + 1, k + 1), vid(i, j + 1, k + 1)]


# outward faces of the hex model
FACES = {"x-": (0, 4, 7, 3), "x+": (1, 2, 6, 5), "y-": (0, 1, 5, 4),
         "y+": (3, 7, 6, 2), "z-": (0, 3, 2, 1), "z+": (4, 5, 6, 7)}
NB = {"x-": (-1, 0, 0), "x+": (1, 0, 0), "y-": (0, -1, 0), "y+": (0, 1, 0),
      "z-": (0, 0, -1), "z+": (0, 0, 1)}
CUBEPATCH = {"x+": "cubeGap", "x-": "cubeOuter", "y-": "cubeSide",
             "z+": "cubeBottom", "z-": "cubeTop"}  # seen from the neighbour
patches = {n: [] for n in ("cubeGap", "cubeOuter", "cubeSide", "cubeBottom", "cubeTop",
                           "symX", "symY", "sides", "bottom", "top")}
for (i, j, k) in blocks:
    hv = hexv(i, j, k)
    for fn, loc in FACES.items():
        di, dj, dk = NB[fn]
        ni, nj, nk = i + di, j + dj, k + dk
        f = [hv[m] for m in loc]
        if (ni, nj, nk) == CUBE:
            patches[CUBEPATCH[fn]].append(f)
        elif ni < 0:
            patches["symX"].append(f)
        elif nj < 0:
            patches["symY"].append(f)
        elif ni > NI - 2 or nj > NJ - 2:
            patches["sides"].append(f)
        elif nk < 0:
            patches["bottom"].append(f)
        elif nk > NK - 2:
            patches["top"].append(f)

ncells = 0
for (i, j, k) in blocks:
    ncells += segX[i][0] * segY[j][0] * segZ[k][0]

# The dictionary writer (and the case's folders) of the IB tank cases
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import tankCase
write = tankCase.writer(args.case)


# ---------------------------------------------------------------- blockMesh
b = ["convertToMeters 0.001;\n\nvertices\n("]
for k in range(NK):
    for j in range(NJ):
        for i in range(NI):
            b.append("    (%.10g %.10g %.10g) // %d" % (xcoord(i, j, k), Y[j], Z[k], vid(i, j, k)))
b.append(");\n\nblocks\n(")
for (i, j, k) in blocks:
    b.append("    hex (%s) (%d %d %d) simpleGrading (%s %s %s)" % (
        " ".join(map(str, hexv(i, j, k))), segX[i][0], segY[j][0], segZ[k][0],
        gstr(segX[i][1]), gstr(segY[j][1]), gstr(segZ[k][1])))
b.append(");\n\nedges ();\n\nboundary\n(")
ptype = {"symX": "symmetryPlane", "symY": "symmetryPlane", "sides": "wall",
         "bottom": "patch", "top": "patch"}
for n, fl in patches.items():
    t = ptype.get(n, "wall")
    grp = "\n        inGroups (cube);" if n.startswith("cube") else ""
    b.append("    %s\n    {\n        type %s;%s\n        faces\n        (" % (n, t, grp))
    for f in fl:
        b.append("            (%s)" % " ".join(map(str, f)))
    b.append("        );\n    }")
b.append(");\n\nmergePatchPairs ();\n")
write("system/blockMeshDict", "dictionary", "blockMeshDict", "\n".join(b))

# ---------------------------------------------------------------- W(t) table
rows = list(csv.DictReader(open(args.ib)))
table = [(float(r["t"]), -float(r["vz_mean"])) for r in rows]
tab = "\n".join("            (%.8g (0 0 %.8g))" % (t, w) for t, w in table)
with open(os.path.join(args.case, "W.csv"), "w") as f:
    f.write("t,W\n" + "".join("%.8g,%.8g\n" % tw for tw in table))

uni = """uniformFixedValue;
        uniformValue table
        (
%s
        );""" % tab

write("0/U", "volVectorField", "U", """
dimensions      [0 1 -1 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{
    cube        { type noSlip; }
    symX        { type symmetryPlane; }
    symY        { type symmetryPlane; }
    sides
    {
        type    %s
    }
    bottom
    {
        type    %s
    }
    top
    {
        type        inletOutlet;
        inletValue  uniform (0 0 0);
        value       uniform (0 0 0);
    }
}
""" % (uni, uni))

write("0/p", "volScalarField", "p", """
dimensions      [0 2 -2 0 0 0 0];
internalField   uniform 0;
boundaryField
{
    cube        { type zeroGradient; }
    symX        { type symmetryPlane; }
    symY        { type symmetryPlane; }
    sides       { type zeroGradient; }
    bottom      { type zeroGradient; }
    top         { type fixedValue; value uniform 0; }
}
""")

write("constant/transportProperties", "dictionary", "transportProperties", """
transportModel  Newtonian;
nu              1e-06;
""")
write("constant/turbulenceProperties", "dictionary", "turbulenceProperties", """
simulationType  laminar;
""")

# ---------------------------------------------------------------- system
fo_forces = ""
for name, pl in (("forces", "(cube)"), ("forcesGap", "(cubeGap)"),
                 ("forcesOuter", "(cubeOuter)")):
    fo_forces += """
    %s
    {
        type            forces;
        libs            ("libforces.so");
        writeControl    timeStep;
        writeInterval   1;
        log             false;
        patches         %s;
        rho             rhoInf;
        rhoInf          1000;
        CofR            (%g 0 0.1);
    }
""" % (name, pl, 1e-3 * (HG + 5.0))
fo_p = ""
for pn in ("cubeGap", "cubeOuter", "cubeBottom", "cubeTop", "cubeSide"):
    fo_p += """
    p_%s
    {
        type            surfaceFieldValue;
        libs            ("libfieldFunctionObjects.so");
        writeControl    timeStep;
        writeInterval   1;
        log             false;
        writeFields     false;
        regionType      patch;
        name            %s;
        operation       areaAverage;
        fields          (p);
    }
""" % (pn, pn)

write("system/controlDict", "dictionary", "controlDict", """
application     pimpleFoam;
startFrom       startTime;
startTime       0;
stopAt          endTime;
endTime         %g;
deltaT          1e-05;
writeControl    adjustableRunTime;
writeInterval   0.02;
purgeWrite      0;
writeFormat     binary;
writePrecision  8;
writeCompression off;
timeFormat      general;
timePrecision   8;
runTimeModifiable true;
adjustTimeStep  yes;
maxCo           %g;
maxDeltaT       5e-04;

functions
{
%s
%s
}
""" % (args.endTime, args.maxCo, fo_forces, fo_p))

write("system/fvSchemes", "dictionary", "fvSchemes", """
ddtSchemes      { default backward; }
gradSchemes     { default Gauss linear; grad(U) cellLimited Gauss linear 1; }
divSchemes
{
    default         none;
    div(phi,U)      Gauss linearUpwind grad(U);
    div((nuEff*dev2(T(grad(U))))) Gauss linear;
}
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes   { default corrected; }
""")

write("system/fvSolution", "dictionary", "fvSolution", """
solvers
{
    p
    {
        solver          GAMG;
        smoother        DICGaussSeidel;  // GaussSeidel stalls on the gap's thin cells
        nCellsInCoarsestLevel 50;
        tolerance       1e-07;
        relTol          0.01;
    }
    pFinal
    {
        $p;
        relTol          0;
    }
    "(U|UFinal)"
    {
        solver          smoothSolver;
        smoother        symGaussSeidel;
        tolerance       1e-08;
        relTol          0;
    }
}
PIMPLE
{
    momentumPredictor yes;
    consistent      yes;  // plain PISO oscillates (+-0.2 N) in the gap's thin cells
    nOuterCorrectors 1;
    nCorrectors     2;
    nNonOrthogonalCorrectors 0;
    pRefCell        0;
    pRefValue       0;
}
""")

# ---------------------------------------------------------------- summary
def desc(name, sg):
    n, sec, sizes = sg
    return "%-14s %3d cells, sizes %.4g .. %.4g mm (first %.4g, last %.4g), %d sections" % (
        name, n, min(sizes), max(sizes), sizes[0], sizes[-1], len(sec))
print("fan width %g mm, y2 %.4g, z1 %.4g, z4 %.4g" % (FAN, y2, z1, z4))
for nm, sg in zip(("x[0,xg]", "x[xg,10.05]", "x[10.05,25]"), segX):
    print(desc(nm, sg))
for nm, sg in zip(("y[0,5]", "y[5,y2]", "y[y2,25]"), segY):
    print(desc(nm, sg))
for nm, sg in zip(("z[0,z1]", "z[z1,95]", "z[95,105]", "z[105,z4]", "z[z4,150]"), segZ):
    print(desc(nm, sg))
print("blocks %d, cells %d" % (len(blocks), ncells))
