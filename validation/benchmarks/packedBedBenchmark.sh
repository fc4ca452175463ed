#!/bin/bash
# Packed-bed benchmark: what the showcase caseTemplates/packedBed costs.
#
#   validation/benchmarks/packedBedBenchmark.sh [-spheres] [-full] [-fine] [-endTime T] [-work DIR]
#
# Runs the template (serial, its own settings; -spheres pours beads instead
# of the cylinder pellets, -full the full version, -fine halves the cells) and prints, from the
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
        -spheres|-full|-fine) opts+=("$1"); shift ;;
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
# The function object's line for step n follows pimpleFoam's ExecutionTime
# line of step n, whose ClockTime (whole seconds) does not yet hold the
# function object's work of step n: step n's wall time is taken as
# ClockTime(n+1) - ClockTime(n) (its plugin work and the next step's
# fluid), the first step's from the start, the last step's as the one
# before it
steps = []
clock = None
for line in log:
    m = re.match(r"ExecutionTime = \S+ s\s+ClockTime = (\S+) s", line)
    if m:
        clock = float(m.group(1))
        continue
    m = re.match(r"immersedDEM \S+: t (\S+), bodies (\d+), contacts (\d+), DEM steps (\d+), "
                 r".*seconds: projection (\S+) DEM (\S+) forcing (\S+)", line)
    if m and clock is not None:
        bodies = int(m.group(2))
        steps.append(dict(t=float(m.group(1)), c=int(m.group(3)), n=int(m.group(4)),
                          p=float(m.group(5)), dem=float(m.group(6)), f=float(m.group(7)), clock=clock))
if not steps:
    sys.exit("no step of the plugin in %s/log.pimpleFoam" % work)
for i, s in enumerate(steps):
    if len(steps) == 1:
        s["wall"] = s["clock"]
    elif i == 0:
        s["wall"] = steps[1]["clock"]
    elif i + 1 < len(steps):
        s["wall"] = steps[i + 1]["clock"] - s["clock"]
    else:
        s["wall"] = s["clock"] - steps[i - 1]["clock"]
stages = {}
prev = 0.0
for s in steps:
    k = 1 if s["t"] <= tFlow + 1e-12 else 2
    for key in (k, "all"):
        st = stages.setdefault(key, dict(p=0.0, dem=0.0, f=0.0, clock=0.0, steps=0, sub=0, cs=0, cmax=0,
                                         sim=0.0))
        st["steps"] += 1; st["sub"] += s["n"]; st["cs"] += s["c"]*s["n"]; st["cmax"] = max(st["cmax"], s["c"])
        st["p"] += s["p"]; st["dem"] += s["dem"]; st["f"] += s["f"]; st["clock"] += s["wall"]
        st["sim"] += s["t"] - prev
    prev = s["t"]
print("packedBed benchmark: %s, %d cells, %d bodies (%s)" % (work, cells, bodies,
      "serial, the template's settings"))
print("%-7s %9s %6s %8s %9s %10s %8s %8s %8s %8s %7s %8s %9s %12s" % (
      "stage", "simulated", "steps", "wall [s]", "wall/sim", "projection", "DEM", "forcing", "fluid",
      "share", "sub", "contacts", "DEM/sub", "DEM/c/sub"))
for k in (1, 2, "all"):
    s = stages.get(k)
    if not s or s["sim"] <= 0:
        print("%-7s not run" % k)
        continue
    sim = s["sim"]
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
