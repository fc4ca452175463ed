#!/bin/bash
# Issue 20's coupled scale benchmark: N lumpy stars (5,120 triangles, 8
# cells across) on a lattice in a tank of water, stock pimpleFoam, 1 ms
# CFD steps (settlingLattice/makeLattice.py writes the case). Prints, per
# CFD step (the median of the steps after the first, which builds the
# trees): projection, DEM and forcing seconds from the function object's
# log, the whole step's CPU and wall seconds, the plugin share, and the
# DEM's microseconds per body per sub-step; with -np 2 also the parallel
# run's wall seconds per step and the speedup; with -before LIBDIR the same
# case with another build's libimmersedDEM.so (a copy of .build/lib), run
# alternately with this one, and the ratios (with -np 2 both builds run in
# parallel too: the DEM's seconds and the speedups side by side);
# -spacing CELLS packs the lattice (makeLattice.py --spacing: 10 makes
# neighbours interlock, a block where the DEM dominates).
#
#   validation/benchmarks/settlingLatticeBenchmark.sh [-lattice "4 4 8"]
#       [-steps 8] [-np 2] [-before LIBDIR] [-repeat 1] [-spacing CELLS]
#       [-work DIR]
set -u
here="$(cd "$(dirname "$0")" && pwd -P)"
project="$(cd "$here/../.." && pwd -P)"
lattice="4 4 8"; steps=8; np=1; before=""; repeat=1; spacing=0
work=/tmp/immersedDEM-benchmark-settlingLattice
while [ $# -gt 0 ]
do
    case "$1" in
        -lattice) lattice="$2"; shift 2 ;;
        -steps)   steps="$2"; shift 2 ;;
        -np)      np="$2"; shift 2 ;;
        -before)  before="$(cd "$2" && pwd -P)"; shift 2 ;;
        -repeat)  repeat="$2"; shift 2 ;;
        -spacing) spacing="$2"; shift 2 ;;
        -work)    work="$2"; shift 2 ;;
        *) echo "Unknown option $1" 1>&2; exit 1 ;;
    esac
done
. "$project/src/etc/bashrc"
rm -rf "$work"; mkdir -p "$work"
python3 "$here/settlingLattice/makeLattice.py" "$work/case" --lattice "$lattice" \
    --steps "$steps" --np 2 --spacing "$spacing" > "$work/case.txt" || exit 1
cat "$work/case.txt"
(cd "$work/case" && blockMesh > log.blockMesh 2>&1) || { echo "blockMesh failed: see $work/case"; exit 1; }

# run NAME LIBDIR NP: a copy of the case, run with libimmersedDEM.so from
# LIBDIR (this build's when empty)
run()
{
    local name="$1" lib="$2" n="$3" dir="$work/$1"
    rm -rf "$dir"; cp -r "$work/case" "$dir"
    (
        cd "$dir" || exit 1
        [ -n "$lib" ] && export LD_LIBRARY_PATH="$lib:$LD_LIBRARY_PATH"
        if [ "$n" -gt 1 ]
        then
            decomposePar > log.decomposePar 2>&1 || exit 1
            mpirun -np "$n" pimpleFoam -parallel > log.pimpleFoam 2>&1
        else
            pimpleFoam > log.pimpleFoam 2>&1
        fi
    ) || { echo "$name failed: see $dir/log.pimpleFoam"; exit 1; }
    echo "ran $name"
}

runs=""
for k in $(seq 1 "$repeat")
do
    if [ -n "$before" ]
    then
        run "before$k" "$before" 1 || exit 1; runs="$runs before$k"
    fi
    run "serial$k" "" 1 || exit 1; runs="$runs serial$k"
    if [ "$np" -gt 1 ]
    then
        if [ -n "$before" ]
        then
            run "beforePar$k" "$before" "$np" || exit 1; runs="$runs beforePar$k"
        fi
        run "parallel$k" "" "$np" || exit 1; runs="$runs parallel$k"
    fi
done

/usr/bin/python3 - "$work" $runs <<'PY'
import os, re, statistics, sys
work, runs = sys.argv[1], sys.argv[2:]
def read(run):
    proj, dem, forcing, steps, cpu, wall = [], [], [], [], [], []
    bodies = 0
    for line in open(os.path.join(work, run, "log.pimpleFoam")):
        m = re.search(r"bodies (\d+), contacts \d+, DEM steps (\d+), .*seconds: projection (\S+) DEM (\S+) forcing (\S+)", line)
        if m:
            bodies = int(m.group(1)); steps.append(int(m.group(2)))
            proj.append(float(m.group(3))); dem.append(float(m.group(4))); forcing.append(float(m.group(5)))
        m = re.match(r"ExecutionTime = (\S+) s\s+ClockTime = (\S+) s", line)
        if m:
            cpu.append(float(m.group(1))); wall.append(float(m.group(2)))
    if len(cpu) < 3:
        raise SystemExit("%s: fewer than 3 steps in its log" % run)
    med = lambda v: statistics.median(v[1:])
    dcpu = [b - a for a, b in zip(cpu, cpu[1:])]
    dwall = [b - a for a, b in zip(wall, wall[1:])]
    r = dict(bodies=bodies, proj=med(proj), dem=med(dem), forcing=med(forcing), sub=med(steps),
             cpu=statistics.median(dcpu), wall=(wall[-1] - wall[0])/(len(wall) - 1))
    r["plugin"] = r["proj"] + r["dem"] + r["forcing"]
    r["share"] = r["plugin"]/r["cpu"]
    r["demBody"] = 1e6*r["dem"]/(r["bodies"]*r["sub"])
    r["projBody"] = 1e3*r["proj"]/r["bodies"]
    return r
res = {run: read(run) for run in runs}
print("\nper CFD step after the first (medians; CPU seconds of the master; wall from ClockTime):")
print("%-11s %6s %9s %12s %9s %9s %9s %9s %9s %8s %15s" % ("run", "bodies", "proj [s]", "proj/body[ms]",
      "DEM [s]", "forcing", "plugin", "CPU [s]", "wall [s]", "share", "DEM us/body/sub"))
for run in runs:
    r = res[run]
    print("%-11s %6d %9.3f %12.2f %9.3f %9.3f %9.3f %9.3f %9.2f %7.1f%% %15.2f" % (run, r["bodies"], r["proj"],
          r["projBody"], r["dem"], r["forcing"], r["plugin"], r["cpu"], r["wall"], 100*r["share"], r["demBody"]))
def mean(kind, key):
    v = [res[r][key] for r in runs if re.sub(r"\d+$", "", r) == kind]
    return sum(v)/len(v) if v else None
s = {k: mean("serial", k) for k in ("proj", "dem", "cpu", "wall", "share", "demBody")}
print("\nthis build: plugin share %.1f%% (target <= 30%%), DEM %.2f us per body per sub-step (target <= 10),"
      " %.2f s per CFD step on one core" % (100*s["share"], s["demBody"], s["cpu"]))
if any(r.startswith("before") for r in runs):
    b = {k: mean("before", k) for k in ("proj", "dem", "cpu", "wall", "share")}
    print("before/this build: projection %.2fx, DEM %.2fx, CPU per step %.2fx; plugin share %.1f%% -> %.1f%%"
          % (b["proj"]/s["proj"], b["dem"]/s["dem"], b["cpu"]/s["cpu"], 100*b["share"], 100*s["share"]))
if any(r.startswith("parallel") for r in runs):
    p = mean("parallel", "wall")
    print("mpirun -np 2: %.2f s wall per CFD step, serial %.2f s: speedup %.2f (target >= 1.7)" % (p, s["wall"], s["wall"]/p))
    print("mpirun -np 2: DEM %.3f s per CFD step on the master, serial %.3f s: DEM speedup %.2f"
          % (mean("parallel", "dem"), s["dem"], s["dem"]/mean("parallel", "dem")))
if any(r.startswith("beforePar") for r in runs):
    bp, bs = mean("beforePar", "wall"), b["wall"]
    print("before, mpirun -np 2: %.2f s wall per CFD step, serial %.2f s: speedup %.2f; DEM %.3f s, serial %.3f s:"
          " DEM speedup %.2f" % (bp, bs, bs/bp, mean("beforePar", "dem"), b["dem"], b["dem"]/mean("beforePar", "dem")))
PY
