#!/bin/bash
# Spheres thrown into the corners of a box tank whose walls are a mesh
# patch: what their contacts with the walls cost, two libraries side by
# side.
#
#   validation/benchmarks/spheresInCornersBenchmark.sh -libA DIR -libB DIR [-work DIR]
#
# Builds the case from caseTemplates/quickStart (its 40 x 40 x 80 mm tank
# of water, 4 mm cells, walls a `patch` wall): four glass spheres 10 mm
# across, each 0.1 mm from two side walls, thrown at 0.07 m/s into its
# corner, where they bounce off the floor and both sides for 0.25 s.
# Runs pimpleFoam twice at once, with libimmersedDEM.so from -libA and
# from -libB (folders holding the library; build the one to compare with
# from another commit and copy its .build/lib), so the two runs share the
# machine alike and their ratios hold. Prints each run's summary and
# work line (octree queries), and the ratios B/A. Exits 1 if a run fails.
# Where the two libraries' contact geometry differs (the octree's
# volume within 0.5% against the exact caps), the bounces differ too:
# the bodies' end positions are printed, not compared.
set -u
here="$(cd "$(dirname "$0")" && pwd -P)"
project="$(cd "$here/../.." && pwd -P)"
libA= libB= work=/tmp/immersedDEM-benchmark-spheresInCorners
. "$here/twoLibraries.sh"
twoLibrariesOptions "$@"
twoLibrariesPrepare
c="$work/case"
cp -r "$project/caseTemplates/quickStart" "$c"
rm -rf "$c/constant/triSurface"
cat > "$c/constant/immersedDEMProperties" <<'DICT'
FoamFile { version 2.0; format ascii; class dictionary; object immersedDEMProperties; }
materials
{
    glass { youngsModulus 1e7; poissonsRatio 0.24; restitution 0.9; friction 0.3; }
}
bodies
{
    b1 { shape sphere; radius 0.005; material glass; density 2500; position (-0.0149 -0.0149 0.012); velocity (-0.05 -0.05 0); }
    b2 { shape sphere; radius 0.005; material glass; density 2500; position (0.0149 -0.0149 0.012); velocity (0.05 -0.05 0); }
    b3 { shape sphere; radius 0.005; material glass; density 2500; position (-0.0149 0.0149 0.03); velocity (-0.05 0.05 0); }
    b4 { shape sphere; radius 0.005; material glass; density 2500; position (0.0149 0.0149 0.006); velocity (0.05 0.05 0); }
}
walls
{
    tank { type patch; patches (walls); material glass; }
}
DICT
twoLibrariesMesh "$c" 0.25 0.05
twoLibrariesRunCase "$c"
for v in A B
do
    log="$work/$v/log.pimpleFoam"
    echo "== $v"
    sed -n '/Summary (wall-clock seconds/,/largest overlap/p' "$log"
    grep "contacts evaluated" "$log" | tail -1
    echo "   bodies at the end (name, position):"
    tail -4 "$work/$v/postProcessing/bodies/0/bodies.dat" | awk '{print "     " $2, $3, $4, $5}'
done
twoLibrariesRatios
