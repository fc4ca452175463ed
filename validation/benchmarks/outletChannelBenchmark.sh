#!/bin/bash
# Bodies carried out of a channel through its outlet: what their contacts
# with the walls cost near the outlet, and whether they keep their speed
# while they cross it; two libraries side by side.
#
#   validation/benchmarks/outletChannelBenchmark.sh -libA DIR -libB DIR [-work DIR]
#
# The case (a new user's, issue trial of 2026-12-07): a 60 x 20 x 20 mm
# channel of water, 1 mm cells, inlet 0.1 m/s (fixed velocity), outlet
# (zeroGradient, p 0) at x = 60 mm, no-slip walls, the walls a `patch`
# wall; six bodies (every default): neutrally buoyant and light spheres,
# a glass sphere and an STL cube on the floor, a neutrally buoyant STL
# cube, a light STL cylinder; 0.6 s. Four are carried out and removed.
# Runs pimpleFoam twice at once, with libimmersedDEM.so from -libA and
# from -libB (folders holding the library; build the one to compare with
# from another commit and copy its .build/lib). Prints each run's contact
# time, octree queries and removals, the ratios B/A, and for each body
# that left, its speed from when its front reaches the outlet (x = 56 mm,
# 4 mm before it) until its removal, as the lowest and highest over that
# speed. Exits 1 if a run fails.
set -u
here="$(cd "$(dirname "$0")" && pwd -P)"
project="$(cd "$here/../.." && pwd -P)"
libA= libB= work=/tmp/immersedDEM-benchmark-outletChannel
. "$here/twoLibraries.sh"
twoLibrariesOptions "$@"
twoLibrariesPrepare
c="$work/case"
cp -r "$project/caseTemplates/quickStart" "$c"
rm -rf "$c/constant/triSurface" "$c/0"
mkdir -p "$c/constant/triSurface" "$c/0"
header() { printf 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' "$1" "$2"; }
{ header dictionary blockMeshDict; cat <<'E'
scale 0.001;
vertices ((0 -10 0) (60 -10 0) (60 10 0) (0 10 0) (0 -10 20) (60 -10 20) (60 10 20) (0 10 20));
blocks (hex (0 1 2 3 4 5 6 7) (60 20 20) simpleGrading (1 1 1));
boundary
(
    inlet  { type patch; faces ((0 4 7 3)); }
    outlet { type patch; faces ((1 2 6 5)); }
    walls  { type wall;  faces ((0 1 5 4) (3 7 6 2) (0 3 2 1) (4 5 6 7)); }
);
E
} > "$c/system/blockMeshDict"
{ header volVectorField U; cat <<'E'
dimensions [0 1 -1 0 0 0 0];
internalField uniform (0.1 0 0);
boundaryField
{
    inlet  { type fixedValue; value uniform (0.1 0 0); }
    outlet { type zeroGradient; }
    walls  { type noSlip; }
}
E
} > "$c/0/U"
{ header volScalarField p; cat <<'E'
dimensions [0 2 -2 0 0 0 0];
internalField uniform 0;
boundaryField
{
    inlet  { type zeroGradient; }
    outlet { type fixedValue; value uniform 0; }
    walls  { type zeroGradient; }
}
E
} > "$c/0/p"
{ header dictionary immersedDEMProperties; cat <<'E'
materials
{
    plastic { youngsModulus 1e7; poissonsRatio 0.3; restitution 0.9; friction 0.3; }
    glass   { youngsModulus 1e7; poissonsRatio 0.24; restitution 0.9; friction 0.3; }
}
bodies
{
    ballN { shape sphere; radius 0.004; material plastic; density 1000; position (0.010 0 0.010); }
    ballH { shape sphere; radius 0.004; material glass; density 2500; position (0.014 0.005 0.004); }
    cubeN
    {
        shape triangleMesh; file "cube.stl"; scale 0.001; material plastic; density 1000;
        position (0.022 -0.004 0.012); rotationAxis (1 1 0); rotationAngle 30;
    }
    ballL { shape sphere; radius 0.004; material plastic; density 1050; position (0.026 0.005 0.010); }
    cubeH
    {
        shape triangleMesh; file "cube.stl"; scale 0.001; material glass; density 2500;
        position (0.032 -0.005 0.00325); rotationAxis (0 0 1); rotationAngle 45;
    }
    cylL
    {
        shape triangleMesh; file "cyl.stl"; scale 0.001; material plastic; density 1200;
        position (0.040 0.002 0.012); rotationAxis (1 0 0); rotationAngle 60;
    }
}
walls
{
    channel { type patch; patches (walls); material glass; }
}
E
} > "$c/constant/immersedDEMProperties"
(
    cd "$c" \
 && immersedDEMPrism constant/triSurface/cube.stl 9.192388155 6.5 4 > /dev/null \
 && immersedDEMPrism constant/triSurface/cyl.stl 8 5 24 > /dev/null \
 && foamDictionary -entry PIMPLE.pRefCell -remove system/fvSolution > /dev/null \
 && foamDictionary -entry PIMPLE.pRefValue -remove system/fvSolution > /dev/null \
 && foamDictionary -entry maxDeltaT -set 0.004 system/controlDict > /dev/null
) || { echo "Could not make the case in $c" 1>&2; exit 1; }
twoLibrariesMesh "$c" 0.6 0.1
twoLibrariesRunCase "$c"
for v in A B
do
    log="$work/$v/log.pimpleFoam"
    echo "== $v"
    grep "continued across" "$log"
    grep "immersedDEM: removed body" "$log" | sed 's/: its centre.*//'
    grep "contacts evaluated" "$log" | tail -1
done
twoLibrariesRatios
/usr/bin/python3 - "$work" "$project/src/python" <<'PY'
import sys
work = sys.argv[1]
sys.path.insert(0, sys.argv[2])
from immersedDEMData import readTable
print("\nSpeed crossing the outlet, over the speed when the front reaches it (lowest-highest):")
print("  %-6s %18s %18s" % ("body", "A", "B"))
tables = {v: readTable("%s/%s/postProcessing/bodies/0/bodies.dat" % (work, v)) for v in "AB"}
for b in ["ballN", "ballL", "cubeN", "cylL"]:
    row = []
    for v in "AB":
        t = tables[v].where(body=b)
        x, vx = list(t["x"]), list(t["vx"])
        if x[-1] < 0.059:
            row.append("not out"); continue
        i0 = next(k for k, xi in enumerate(x) if xi >= 0.056)
        row.append("%.3f-%.3f" % (min(vx[i0:])/vx[i0], max(vx[i0:])/vx[i0]))
    print("  %-6s %18s %18s" % (b, row[0], row[1]))
PY
