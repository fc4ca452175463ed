# Sourced by the benchmarks that run one case with two libraries at once
# (bedAtRestBenchmark.sh, spheresInCornersBenchmark.sh); they set
# project, libA, libB and work first.

# The options -libA DIR -libB DIR [-work DIR] of "$@" into libA, libB and
# work (work keeps its default when not given); any other is an error
twoLibrariesOptions()
{
    while [ $# -gt 0 ]
    do
        case "$1" in
            -libA|-libB|-work)
                [ $# -ge 2 ] || { echo "$1 needs a value" 1>&2; exit 1; }
                case "$1" in
                    -libA) libA="$2" ;; -libB) libB="$2" ;; -work) work="$2" ;;
                esac
                shift 2 ;;
            *) echo "Unknown option $1 (see the header of $0)" 1>&2; exit 1 ;;
        esac
    done
}

# The ratios B/A of the two runs' summaries (contact geometry, the plugin,
# wall s per simulated s) and their octree queries
twoLibrariesRatios()
{
    /usr/bin/python3 - "$work" <<'PY'
import re, sys
work = sys.argv[1]
def figures(v):
    log = open("%s/%s/log.pimpleFoam" % (work, v)).read()
    s = log[log.rindex("Summary (wall-clock seconds"):]
    def part(name):
        return float(re.search(r"^\s+%s\s+([0-9.]+)" % re.escape(name), s, re.M).group(1))
    per = float(re.search(r"([0-9.e+]+) wall s per simulated s", s).group(1))
    q = int(re.findall(r"queries (\d+) over", log)[-1])
    return part("contact geometry and laws"), part("immersedDEM (all of the above)"), per, q
A, B = figures("A"), figures("B")
print("\nB/A:")
for k, name in enumerate(["contact geometry and laws [s]", "the plugin [s]", "wall s per simulated s"]):
    print("  %-32s %8.3f -> %8.3f  %.3f" % (name, A[k], B[k], B[k]/A[k]))
print("  %-32s %8d -> %8d" % ("octree queries", A[3], B[3]))
PY
}

# Checks that -libA and -libB hold libimmersedDEM.so, sources the
# project's bashrc, makes libA and libB absolute, and empties $work (only
# if absent or this benchmark's own: it holds A/log.pimpleFoam)
twoLibrariesPrepare()
{
    local l
    for l in "$libA" "$libB"
    do
        [ -f "$l/libimmersedDEM.so" ] \
            || { echo "No libimmersedDEM.so in '$l' (-libA and -libB are required)" 1>&2; exit 1; }
    done
    . "$project/src/etc/bashrc"
    libA="$(cd "$libA" && pwd -P)"; libB="$(cd "$libB" && pwd -P)"
    if [ -e "$work" ] && ! [ -f "$work/A/log.pimpleFoam" ]
    then
        echo "$work exists and is not this benchmark's: give another -work" 1>&2; exit 1
    fi
    rm -rf "$work"; mkdir -p "$work"
}

# pimpleFoam in $work/A with libA and in $work/B with libB, both at once
# (so they share the machine alike), each to its log.pimpleFoam
twoLibrariesRun()
{
    local lib=("$libA" "$libB") i=0 v
    for v in A B
    do
        (cd "$work/$v" && LD_LIBRARY_PATH="${lib[$i]}:$LD_LIBRARY_PATH" pimpleFoam > log.pimpleFoam 2>&1) &
        i=$((i + 1))
    done
    wait
}

# The case $1 copied to $work/A and $work/B and run with each library at
# once; exits 1 unless both runs ended
twoLibrariesRunCase()
{
    cp -r "$1" "$work/A"
    cp -r "$1" "$work/B"
    twoLibrariesRun
    local v failed=0
    for v in A B
    do
        grep -q "^End" "$work/$v/log.pimpleFoam" \
            || { echo "run $v did not end: $work/$v/log.pimpleFoam"; failed=1; }
    done
    [ $failed -eq 0 ] || exit 1
}

# In the case $1: endTime $2 and writeInterval $3 (adjustable run time),
# then blockMesh; exits 1 if either fails
twoLibrariesMesh()
{
    (
        cd "$1" \
     && foamDictionary -entry endTime -set "$2" system/controlDict > /dev/null \
     && foamDictionary -entry writeControl -set adjustableRunTime system/controlDict > /dev/null \
     && foamDictionary -entry writeInterval -set "$3" system/controlDict > /dev/null \
     && blockMesh > log.blockMesh 2>&1
    ) || { echo "Could not make the case in $1 (see $1/log.blockMesh)" 1>&2; exit 1; }
}
