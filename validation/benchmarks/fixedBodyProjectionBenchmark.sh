#!/bin/bash
# Fixed bodies are projected once (issue 18, item 3): the wall time of a 2D
# fixed cylinder at Re 100 with 40 cells per diameter (80 000 cells, the
# sharp surface), run twice side by side: projecting every body every step
# (the debug switch immersedBoundaryProjection 1, the former behaviour) and
# projecting only bodies that moved (the default: the cylinder once).
# Prints the solver's wall time, the projection's seconds (from the function
# object's log lines) and the time saved.
#
#   validation/benchmarks/fixedBodyProjectionBenchmark.sh [-steps N] [-work DIR]
set -u
here="$(cd "$(dirname "$0")" && pwd -P)"
project="$(cd "$here/../.." && pwd -P)"
steps=20; work=/tmp/immersedDEM-benchmark-fixedBodyProjection
while [ $# -gt 0 ]
do
    case "$1" in
        -steps) steps="$2"; shift 2 ;;
        -work)  work="$2"; shift 2 ;;
        *) echo "Unknown option $1" 1>&2; exit 1 ;;
    esac
done
. "$project/src/etc/bashrc"
rm -rf "$work"; mkdir -p "$work"
for v in everyStep once
do
    cp -r "$here/fixedCylinder" "$work/$v"
    mkdir -p "$work/$v/constant/triSurface"
    python3 "$project/validation/cases/settling2D/cylinderSTL.py" \
        "$work/$v/constant/triSurface/cylinder.stl" -0.0015 0.0015
    sed -i "s/^endTime .*/endTime         $(python3 -c "print($steps*0.0125)");/" "$work/$v/system/controlDict"
    if [ $v = everyStep ]
    then
        printf '\nDebugSwitches\n{\n    immersedBoundaryProjection 1;\n}\n' >> "$work/$v/system/controlDict"
    fi
    (cd "$work/$v" && blockMesh > log.blockMesh 2>&1 && pimpleFoam > log.pimpleFoam 2>&1) \
        || { echo "$v run failed: see $work/$v"; exit 1; }
done
/usr/bin/python3 - "$work" <<'PY'
import re, sys, os
work = sys.argv[1]
res = {}
print("%-10s %7s %10s %15s %16s %18s" % ("run", "steps", "wall [s]", "projection [s]", "projection share", "bodies projected"))
for v in ("everyStep", "once"):
    p = total = 0.0; steps = 0; projected = 0
    for line in open(os.path.join(work, v, "log.pimpleFoam")):
        m = re.search(r"seconds: projection (\S+) DEM (\S+) forcing (\S+) \(projected bodies (\d+)\)", line)
        if m:
            steps += 1; p += float(m.group(1)); projected += int(m.group(4))
        m = re.match(r"ExecutionTime = \S+ s\s+ClockTime = (\S+) s", line)
        if m:
            total = float(m.group(1))
    res[v] = (total, p)
    print("%-10s %7d %10.2f %15.3f %15.1f%% %18d" % (v, steps, total, p, 100 * p / total, projected))
(t0, p0), (t1, p1) = res["everyStep"], res["once"]
print("projection seconds saved %.3f (%.1f%% of the every-step run's wall time); wall time ratio once/everyStep %.3f"
      % (p0 - p1, 100 * (p0 - p1) / t0, t1 / t0))
PY
