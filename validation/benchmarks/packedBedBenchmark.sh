#!/bin/bash
# Packed-bed benchmark: what the showcase caseTemplates/packedBed costs.
#
#   validation/benchmarks/packedBedBenchmark.sh [-spheres] [-full] [-endTime T] [-work DIR]
#
# Runs the template (serial, its own settings; -spheres pours beads instead
# of the cylinder pellets, -full the full version) and prints, from the
# solver's log, per stage (stage 1: pour and settle, to tFlow; stage 2:
# water pumped through the bed) and for the whole run:
# - wall time per simulated second (pimpleFoam's ClockTime over the
#   simulated time);
# - the plugin's share of the wall time (projection + DEM + forcing, the
#   immersedDEM function object's timers, over the wall time);
# - seconds per part: projection, DEM (contacts and integration of all
#   sub-steps), forcing, and the rest (the fluid: pimpleFoam's own solve);
# - CFD steps, DEM sub-steps, the most contacts at once, and the DEM's
#   seconds per sub-step and per contact and sub-step.
# Then runs plotBed (the bed's figures and checks) if the run reached tFlow.
set -u
here="$(cd "$(dirname "$0")" && pwd -P)"
project="$(cd "$here/../.." && pwd -P)"
work=/tmp/immersedDEM-benchmark-packedBed; opts=()
while [ $# -gt 0 ]
do
    case "$1" in
        -spheres|-full) opts+=("$1"); shift ;;
        -endTime) [ $# -ge 2 ] || { echo "-endTime needs a value" 1>&2; exit 1; }
                  opts+=("$1" "$2"); shift 2 ;;
        -work)    [ $# -ge 2 ] || { echo "-work needs a value" 1>&2; exit 1; }
                  work="$2"; shift 2 ;;
        *) echo "Unknown option $1 (see the header of $0)" 1>&2; exit 1 ;;
    esac
done
. "$project/src/etc/bashrc"
rm -rf "$work"; mkdir -p "$(dirname "$work")"
cp -r "$project/caseTemplates/packedBed" "$work"
(cd "$work" && ./Allclean && IMMERSEDDEM_DIR="$project" ./Allrun "${opts[@]}" > log.Allrun 2>&1) \
    || { echo "packedBed run failed: see $work"; exit 1; }
/usr/bin/python3 - "$work" <<'PY'
import os, re, sys
work = sys.argv[1]
par = {}
for line in open(os.path.join(work, "system", "bedParameters")):
    m = re.match(r"(\w+)\s+([^;]+);", line)
    if m:
        par[m.group(1)] = m.group(2)
tFlow = float(par["tFlow"])
cells = int(re.search(r"cells:\s+(\d+)", open(os.path.join(work, "log.checkMesh")).read()).group(1))
log = open(os.path.join(work, "log.pimpleFoam")).read().split("\n")
bodies = 0
stages = {1: dict(p=0.0, dem=0.0, f=0.0, clock=0.0, steps=0, sub=0, cs=0, cmax=0, t0=0.0, t1=0.0),
          2: dict(p=0.0, dem=0.0, f=0.0, clock=0.0, steps=0, sub=0, cs=0, cmax=0, t0=tFlow, t1=tFlow)}
clock = 0.0
for line in log:
    m = re.match(r"immersedDEM \S+: t (\S+), bodies (\d+), contacts (\d+), DEM steps (\d+), "
                 r".*seconds: projection (\S+) DEM (\S+) forcing (\S+)", line)
    if m:
        t = float(m.group(1))
        s = stages[1 if t <= tFlow + 1e-12 else 2]
        bodies = int(m.group(2))
        c, n = int(m.group(3)), int(m.group(4))
        s["steps"] += 1; s["sub"] += n; s["cs"] += c*n; s["cmax"] = max(s["cmax"], c)
        s["p"] += float(m.group(5)); s["dem"] += float(m.group(6)); s["f"] += float(m.group(7))
        s["t1"] = t
        cur = s
        continue
    m = re.match(r"ExecutionTime = \S+ s\s+ClockTime = (\S+) s", line)
    if m and stages[1]["steps"]:
        new = float(m.group(1))
        cur["clock"] += new - clock
        clock = new
print("packedBed benchmark: %s, %d cells, %d bodies (%s)" % (work, cells, bodies,
      "serial, the template's settings"))
print("%-7s %9s %6s %8s %9s %10s %8s %8s %8s %8s %7s %8s %9s %12s" % (
      "stage", "simulated", "steps", "wall [s]", "wall/sim", "projection", "DEM", "forcing", "fluid",
      "share", "sub", "contacts", "DEM/sub", "DEM/c/sub"))
tot = dict(p=0.0, dem=0.0, f=0.0, clock=0.0, steps=0, sub=0, cs=0, cmax=0, t0=0.0, t1=0.0)
for k in (1, 2, "all"):
    s = stages[k] if k != "all" else tot
    if k != "all":
        for key in ("p", "dem", "f", "clock", "steps", "sub", "cs"):
            tot[key] += s[key]
        tot["cmax"] = max(tot["cmax"], s["cmax"]); tot["t1"] = max(tot["t1"], s["t1"])
    sim = s["t1"] - s["t0"]
    if s["steps"] == 0 or sim <= 0:
        print("%-7s not run" % k)
        continue
    plugin = s["p"] + s["dem"] + s["f"]
    print("%-7s %9.4g %6d %8.1f %9.4g %10.2f %8.2f %8.2f %8.2f %7.1f%% %8d %8d %9.3g %12.3g" % (
          k, sim, s["steps"], s["clock"], s["clock"]/sim, s["p"], s["dem"], s["f"],
          max(0.0, s["clock"] - plugin), 100*plugin/s["clock"] if s["clock"] > 0 else 0,
          s["sub"], s["cmax"], s["dem"]/max(1, s["sub"]), s["dem"]/s["cs"] if s["cs"] else float("nan")))
print("wall/sim: wall seconds per simulated second; share: the plugin's (projection + DEM + forcing) share of")
print("the wall time; fluid: the rest; sub: DEM sub-steps; contacts: the most at once; DEM/c/sub: DEM seconds")
print("per contact per sub-step (sum over steps of contacts x sub-steps at the step's end)")
PY
if grep -q "^End" "$work/log.pimpleFoam"
then
    echo
    (cd "$work" && /usr/bin/python3 ./plotBed -noplot)
fi
