#!/bin/bash
#------------------------------------------------------------------------------
# bitCompare.sh: does a change keep the results bit for bit? Builds a given
# revision in a git worktree, runs the same short cases with that build and
# with this tree's (built), and compares their bodies.dat and contacts.dat
# byte for byte (cmp). For refactorings that must not change a result.
#   validation/benchmarks/bitCompare.sh REV [WORKDIR]
# REV      the revision to compare with (e.g. main~2, a commit), or a tree
#          of it already built (a directory with .build/lib/libimmersedDEM.so,
#          such as a CI clone): used as it is
# WORKDIR  where the worktree and the runs go (default /tmp/bitCompare)
# Cases (about 25 minutes for both builds on 2 cores):
#   settlingPile to 0.03 s (coupled; films, mesh bodies, contacts),
#   arbitraryBodiesCollision to 0.004 s (coupled; non-convex, virtual mesh),
#   pelletPour to 0.08 s (dry; patch walls), bouncingBodies (dry; sphere and
#   mesh body on a floor) serial and -parallel.
# Exit status 1 when any file differs or a run failed.
#------------------------------------------------------------------------------
set -u
[ $# -ge 1 ] || { sed -n 2,16p "$0"; exit 1; }
rev="$1"
work="${2:-/tmp/bitCompare}"
here="$(cd "$(dirname "$0")/../.." && pwd -P)"
[ -f "$here/.build/lib/libimmersedDEM.so" ] || { echo "Build this tree first (./Allwmake)" 1>&2; exit 1; }
mkdir -p "$work"
if [ -f "$rev/.build/lib/libimmersedDEM.so" ]
then
    old="$(cd "$rev" && pwd -P)"
    prebuilt=1
    echo "Comparing with the tree built in $old ($(git -C "$old" rev-parse --short HEAD))"
else
    prebuilt=0
    old="$work/tree"
    if [ -d "$old" ]
    then
        git -C "$here" worktree remove --force "$old" 2>/dev/null || rm -rf "$old"
    fi
    git -C "$here" worktree prune
    git -C "$here" worktree add --detach "$old" "$rev" > /dev/null || exit 1
    echo "Building $rev in $old"
    (cd "$old" && ./Allwmake > "$work/log.Allwmake" 2>&1) || { echo "Build of $rev failed: see $work/log.Allwmake"; exit 1; }
fi

runCases()
{
    root="$1"; out="$2"
    rm -rf "$out"; mkdir -p "$out"
    (
        unset LD_LIBRARY_PATH
        export IMMERSEDDEM_DIR="$root"
        . "$root/src/etc/bashrc"
        t="$root/caseTemplates"
        cp -r "$t/settlingPile" "$out/pile" && (cd "$out/pile" && ./Allrun -endTime 0.03 > log.Allrun 2>&1)
        cp -r "$t/arbitraryBodiesCollision" "$out/bodies" && (cd "$out/bodies" && ./Allrun -endTime 0.004 > log.Allrun 2>&1)
        cp -r "$t/pelletPour" "$out/pour" && (cd "$out/pour" && foamDictionary -entry endTime -set 0.08 system/controlDict > /dev/null && ./Allrun > log.Allrun 2>&1)
        cp -r "$t/bouncingBodies" "$out/bounce" && (cd "$out/bounce" && ./Allrun > log.Allrun 2>&1)
        cp -r "$t/bouncingBodies" "$out/bounceParallel" && (cd "$out/bounceParallel" && ./Allrun -parallel > log.Allrun 2>&1)
    )
}

echo "Running the cases with $rev and with this tree (side by side)"
runCases "$old" "$work/old" &
runCases "$here" "$work/new" &
wait

status=0
for c in pile bodies pour bounce bounceParallel
do
    files=$(cd "$work/new/$c" 2>/dev/null && find postProcessing -name "bodies.dat" -o -name "contacts.dat" | sort)
    if [ -z "$files" ]
    then
        echo "$c: no output (see $work/new/$c/log.*)"; status=1; continue
    fi
    for f in $files
    do
        if cmp -s "$work/old/$c/$f" "$work/new/$c/$f"
        then
            echo "$c: identical $f ($(wc -l < "$work/new/$c/$f") lines)"
        else
            echo "$c: DIFFERS $f"; status=1
        fi
    done
done
[ $prebuilt = 1 ] || git -C "$here" worktree remove --force "$old" 2>/dev/null
exit $status
