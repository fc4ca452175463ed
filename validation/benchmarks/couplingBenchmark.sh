#!/bin/bash
# Coupling benchmark: the plugin's share of the run time and the projection's
# independence of the mesh size, printed side by side from one run.
#
#   validation/benchmarks/couplingBenchmark.sh [-levels N] [-endTime T] [-work DIR]
#
# Runs the settlingSphere case (fluid E4, the issue's performance case) twice
# with the same resolution at the sphere (-levels, default 2: 16 cells per
# diameter): with the standard refined column, and with a column 2.5 times
# wider (2-4 times more cells). Prints, for each, the cells, the solver's
# wall time, the seconds spent in projection, DEM and forcing (from the
# function object's log lines) and their share of the run time, and the
# projection's time in the first step (it includes building OpenFOAM's cell
# tree of the whole mesh, once) and its median over the other steps: the
# same for both meshes when the projection visits only the cells near the
# body. Target: share <= 15%.
set -u
here="$(cd "$(dirname "$0")" && pwd -P)"
project="$(cd "$here/../.." && pwd -P)"
levels=2; endTime=0.3; work=/tmp/immersedDEM-benchmark-coupling
while [ $# -gt 0 ]
do
    case "$1" in
        -levels)  levels="$2"; shift 2 ;;
        -endTime) endTime="$2"; shift 2 ;;
        -work)    work="$2"; shift 2 ;;
        *) echo "Unknown option $1" 1>&2; exit 1 ;;
    esac
done
. "$project/src/etc/bashrc"
for v in standard wide
do
    rm -rf "$work/$v"; mkdir -p "$work"
    cp -r "$project/caseTemplates/settlingSphere" "$work/$v"
    if [ $v = wide ]
    then
        # Every refinement box 2.5 times as wide about the path
        sed -i -e 's/(0.028 0.028 -1) (0.072 0.072 1)/(0.005 0.005 -1) (0.095 0.095 1)/' \
               -e 's/(0.035 0.035 -1) (0.065 0.065 1)/(0.0125 0.0125 -1) (0.0875 0.0875 1)/' \
            "$work/$v/system/topoSetDict"
    fi
    (cd "$work/$v" && IMMERSEDDEM_DIR="$project" ./Allrun -fluid E4 -levels "$levels" -endTime "$endTime" > log.Allrun 2>&1) \
        || { echo "$v run failed: see $work/$v"; exit 1; }
done
/usr/bin/python3 - "$work" <<'PY'
import os, re, sys
work = sys.argv[1]
print("%-9s %9s %7s %9s %11s %7s %9s %7s %16s %16s" % ("mesh", "cells", "steps", "run [s]", "projection", "DEM", "forcing", "share",
      "1st step [ms]", "median step [ms]"))
shares = []
for v in ("standard", "wide"):
    d = os.path.join(work, v)
    cells = int(re.search(r"cells:\s+(\d+)", open(os.path.join(d, "log.checkMesh")).read()).group(1))
    p = dem = f = total = 0.0; steps = 0; perStep = []
    for line in open(os.path.join(d, "log.pimpleFoam")):
        m = re.search(r"seconds: projection (\S+) DEM (\S+) forcing (\S+)", line)
        if m:
            steps += 1
            perStep.append(float(m.group(1)))
            p += float(m.group(1)); dem += float(m.group(2)); f += float(m.group(3))
        # Wall-clock, like the plugin's timers
        m = re.match(r"ExecutionTime = \S+ s\s+ClockTime = (\S+) s", line)
        if m:
            total = float(m.group(1))
    share = (p + dem + f) / total
    shares.append(share)
    # The first step's projection includes building OpenFOAM's cell tree
    # once (the whole mesh); the others visit the cells near the body only
    print("%-9s %9d %7d %9.1f %11.2f %7.2f %9.2f %6.1f%% %16.1f %16.2f" % (v, cells, steps, total, p, dem, f, 100 * share,
          1e3 * perStep[0], 1e3 * sorted(perStep[1:])[len(perStep[1:]) // 2]))
print("plugin share of the run time (target <= 15%%): %.1f%% and %.1f%%" % tuple(100 * s for s in shares))
PY
