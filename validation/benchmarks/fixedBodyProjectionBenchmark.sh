#!/bin/bash
# Fixed bodies are projected once (issue 18, item 3): the wall time of a 2D
# fixed cylinder at Re 100 with 40 cells per diameter (80 000 cells, the
# sharp surface), run twice side by side: projecting every body every step
# (the debug switch immersedBoundaryProjection 1, the former behaviour) and
# projecting only bodies that moved (the default: the cylinder once).
# Prints the wall and CPU seconds, the projection seconds (from the function
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
print("%-10s %6s %9s %9s %15s %17s %16s %9s" % ("run", "steps", "wall [s]", "CPU [s]", "projection [s]",
      "1st step proj [s]", "median step [ms]", "projected"))
for v in ("everyStep", "once"):
    per = []; projected = 0; wall = cpu = 0.0; cpus = []
    for line in open(os.path.join(work, v, "log.pimpleFoam")):
        m = re.search(r"seconds: projection (\S+) DEM (\S+) forcing (\S+) \(projected bodies (\d+)\)", line)
        if m:
            per.append(float(m.group(1))); projected += int(m.group(4))
        m = re.match(r"ExecutionTime = (\S+) s\s+ClockTime = (\S+) s", line)
        if m:
            cpu, wall = float(m.group(1)), float(m.group(2)); cpus.append(cpu)
    rest = sorted(per[1:])
    med = rest[len(rest) // 2]
    # CPU seconds per step after the first (the first builds the cell tree)
    stepCpu = (cpus[-1] - cpus[0]) / (len(cpus) - 1)
    res[v] = (med, stepCpu)
    print("%-10s %6d %9.1f %9.2f %15.3f %17.3f %16.3f %9d" % (v, len(per), wall, cpu, sum(per), per[0], 1e3 * med, projected))
(m0, c0), (m1, c1) = res["everyStep"], res["once"]
print("per step after the first: projection %.2f ms -> %.4f ms; CPU per step %.3f s -> %.3f s: the every-step"
      " projection was %.1f%% of a step's CPU time" % (1e3 * m0, 1e3 * m1, c0, c1, 100 * m0 / c0))
PY
