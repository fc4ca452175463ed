#!/bin/bash
# A settled bed's cost per CFD step, two libraries side by side.
#
#   validation/benchmarks/bedAtRestBenchmark.sh -case DIR -time T [-steps N] \
#       -libA DIR -libB DIR [-work DIR]
#
# Copies the time folder T of a finished case (DIR: a packedBed run, e.g.
# `./Allrun -full -fine` run to its end; T a written time with the bed at
# rest, e.g. its last; or any other case, such as a periodic suspension)
# twice, and runs pimpleFoam from T for about N CFD
# steps (default 25) in both copies at once: one with libimmersedDEM.so
# from -libA, one from -libB (each a folder holding the library; build the
# one to compare with from another commit and copy its .build/lib). The
# two runs share the machine alike (2 cores), so their ratios hold where
# their absolute times do not.
#
# Prints, per library, the function object's summary (wall-clock seconds
# per part) and work line (contacts evaluated and carried, films and
# films carried), then the ratios B/A of the plugin's seconds, of each of
# its parts, and of the wall time per simulated second. Exits 1 if either
# run fails, or if the two runs' bodies end further apart than 5% of the
# most a body moved in the window (or 3e-9 m, for a bed at rest): a check
# that B is the same physics, not a faster other one.
set -u
here="$(cd "$(dirname "$0")" && pwd -P)"
project="$(cd "$here/../.." && pwd -P)"
case_= time_= libA= libB= steps=25 work=/tmp/immersedDEM-benchmark-bedAtRest
while [ $# -gt 0 ]
do
    case "$1" in
        -case|-time|-steps|-libA|-libB|-work)
            [ $# -ge 2 ] || { echo "$1 needs a value" 1>&2; exit 1; }
            case "$1" in
                -case) case_="$2" ;; -time) time_="$2" ;; -steps) steps="$2" ;;
                -libA) libA="$2" ;; -libB) libB="$2" ;; -work) work="$2" ;;
            esac
            shift 2 ;;
        *) echo "Unknown option $1 (see the header of $0)" 1>&2; exit 1 ;;
    esac
done
for v in case_ time_ libA libB
do
    [ -n "${!v}" ] || { echo "-${v%_} is required (see the header of $0)" 1>&2; exit 1; }
done
[ -d "$case_/$time_" ] || { echo "No time folder $time_ in $case_" 1>&2; exit 1; }
. "$here/twoLibraries.sh"
twoLibrariesPrepare
# The CFD step at T, from the solver's last time folder's uniform/time
dt=$(sed -n 's/^deltaT[ \t]\+\([^;]*\);/\1/p' "$case_/$time_/uniform/time")
end=$(/usr/bin/python3 -c "print('%.6g' % ($time_ + ($steps + 0.5)*$dt))")
digits=$(/usr/bin/python3 -c "import re; print(max(6, len(re.sub(r'[^0-9]', '', '$time_').lstrip('0'))))")
for v in A B
do
    mkdir "$work/$v"
    cp -r "$case_/$time_" "$case_/constant" "$case_/system" "$work/$v/"
    # from T (a case started from 0 reads its startTime otherwise), with
    # enough digits in the time names to read T's folder (the solver may
    # have raised timePrecision during the run)
    (
        cd "$work/$v" \
     && foamDictionary -entry endTime -set "$end" system/controlDict > /dev/null \
     && foamDictionary -entry startFrom -set latestTime system/controlDict > /dev/null \
     && foamDictionary -entry timePrecision -set "$digits" system/controlDict > /dev/null
    )
done
echo "From t = $time_ to $end (deltaT $dt), A: $libA, B: $libB"
twoLibrariesRun
/usr/bin/python3 - "$work" <<'PY'
import glob, os, re, sys
work = sys.argv[1]
runs = {}
for v in "AB":
    log = open(os.path.join(work, v, "log.pimpleFoam")).read()
    if not re.search(r"^End\s*$", log, re.M):
        print("run %s did not end: %s" % (v, os.path.join(work, v, "log.pimpleFoam")))
        sys.exit(1)
    summary = log[log.rindex("Summary (wall-clock seconds"):]
    parts = {}
    for m in re.finditer(r"^\s{4}(\S.*?)\s{2,}([0-9.]+)\s+([0-9.]+)%$", summary, re.M):
        parts[m.group(1)] = float(m.group(2))
    per = float(re.search(r"([0-9.e+]+) wall s per simulated s", summary).group(1))
    work_line = re.findall(r"contacts evaluated .*", log)[-1]
    print("== %s" % v)
    print(summary[:summary.index("largest overlap")].rstrip())
    print("   " + work_line)
    runs[v] = (parts, per)
A, B = runs["A"], runs["B"]
print("\nB/A:")
for k in A[0]:
    if k in B[0] and A[0][k] > 0.05:
        print("  %-40s %7.3f s -> %7.3f s  %.3f" % (k, A[0][k], B[0][k], B[0][k]/A[0][k]))
print("  %-40s %7.1f -> %7.1f    %.3f" % ("wall s per simulated s", A[1], B[1], B[1]/A[1]))
# The same physics: the bodies' positions at the end, against how far
# they moved in the window. Round-off differences (an order of operations)
# grow where bodies move; a bed at rest keeps them near 1e-12 m
def positions(v):
    f = glob.glob(os.path.join(work, v, "postProcessing", "*", "*", "bodies.dat"))
    lines = open(f[0]).read().splitlines()
    head = lines[0].lstrip("#").split()
    rows = [l.split() for l in lines[1:] if l.strip() and not l.startswith("#")]
    first, last = rows[0][0], rows[-1][0]
    # (the unwrapped positions xu yu zu: a body crossing a periodic
    # boundary has not moved a period)
    cols = [head.index(c) for c in ("xu", "yu", "zu")]
    at = lambda t: {r[1]: tuple(float(r[c]) for c in cols) for r in rows if r[0] == t}
    return at(first), at(last)
(a0, a1), (b0, b1) = positions("A"), positions("B")
far = lambda p, q: max(max(abs(x - y) for x, y in zip(p[k], q[k])) for k in p)
if not (set(a0) == set(a1) == set(b0) == set(b1)):
    print("  bodies were inserted or removed in the window: no comparison of positions")
    sys.exit(1)
moved = far(a0, a1)
d = far(a1, b1)
print("  bodies' positions at the end differ by %.3g m; the most a body moved: %.3g m" % (d, moved))
# 5% of the window's largest motion, or 1e-6 of a 3 mm pellet for a bed at
# rest: above round-off's growth measured in these windows (0.4% in 0.2 s
# of a bed under flow, 1e-13 m in 0.03 s at rest), below a change of the
# physics (a body's motion off by a twentieth)
sys.exit(0 if d <= max(0.05*moved, 3e-9) else 1)
PY
