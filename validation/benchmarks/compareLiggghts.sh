#!/bin/bash
#------------------------------------------------------------------------------
# compareLiggghts.sh: the core's sphere DEM against LIGGGHTS on the same pour
# of 1000 spheres with a Hertz law (liggghts/pour1000.in beside this script,
# and its twin spherePourBenchmark.C), one code after the other on the same
# machine in the same run, timed with the same clock. Prints a table (steps,
# wall time, steps per second, final mean and maximum height of the centres,
# final kinetic energy) and the ratio of the wall times (ours / LIGGGHTS),
# and how closely the piles agree. Builds nothing.
#
# Both codes damp contacts in the same form, f_n = max(0, 4/3 E* sqrt(R*)
# delta^(3/2) + c sqrt(m* S_n) v_n) and c sqrt(m* S_t) tangentially, with
# the same c: ours c(0.5, 3/2) (a head-on rebound of exactly 0.5, printed
# by spherePourBenchmark), LIGGGHTS's hertz model with limitForce on given
# the coefficient of restitution e_L whose 2 sqrt(5/6) |beta(e_L)| is that
# c (passed as -var restitution).
# Asserted: the final mean height of the centres agrees within 2%, and
# every sphere stayed in the box in both codes (exit status 1 otherwise). 2%: the pile is chaotic (one pile's spread under
# round-off is about 0.2% in either code) and the codes differ by about
# 0.9% where they are not the same (tangential spring, integrator;
# README.md has the figures): 2% holds that and no more.
#
# Usage
#   compareLiggghts.sh [spherePourBenchmark] [--steps N] [--rounds R]
#                      [--cpu K] [--keep]
#
#   spherePourBenchmark  the benchmark binary (default: the one on PATH;
#                        src/etc/bashrc puts the project's bin dir there)
#   --steps N            steps in both codes (default 25000, 0.2 s)
#   --rounds R           run the two codes in turn R times (default 1) and
#                        print each round's ratio, their median and the
#                        ratio of the fastest runs: on a shared machine the
#                        same binary varies by up to 40% from run to run
#   --cpu K              pin both codes to core K (taskset): the cores of a
#                        shared machine need not be equally fast
#   --keep               keep the run directory (logs) and print its name
#
# Needs Debian's liggghts package (apt-get install liggghts); the environment
# variable LIGGGHTS may name another liggghts executable.
#------------------------------------------------------------------------------
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
input="$here/liggghts/pour1000.in"
bench=""
steps=25000
rounds=1
cpu=""
keep=0

while [ $# -gt 0 ]; do
    case "$1" in
        --steps) steps="${2:?--steps needs a number}"; shift 2 ;;
        --steps=*) steps="${1#--steps=}"; shift ;;
        --rounds) rounds="${2:?--rounds needs a number}"; shift 2 ;;
        --rounds=*) rounds="${1#--rounds=}"; shift ;;
        --cpu) cpu="${2:?--cpu needs a core number}"; shift 2 ;;
        --cpu=*) cpu="${1#--cpu=}"; shift ;;
        --keep) keep=1; shift ;;
        -h|--help) sed -n '2,38p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        -*) echo "compareLiggghts.sh: unknown option '$1'" >&2; exit 2 ;;
        *) bench="$1"; shift ;;
    esac
done

if ! [[ "$steps" =~ ^[0-9]+$ ]] || [ "$steps" -lt 1 ]; then
    echo "compareLiggghts.sh: --steps must be a positive integer, not '$steps'" >&2
    exit 2
fi
if ! [[ "$rounds" =~ ^[0-9]+$ ]] || [ "$rounds" -lt 1 ]; then
    echo "compareLiggghts.sh: --rounds must be a positive integer, not '$rounds'" >&2
    exit 2
fi
pin=()
if [ -n "$cpu" ]; then
    if ! [[ "$cpu" =~ ^[0-9]+$ ]] || [ "$cpu" -ge "$(nproc)" ]; then
        echo "compareLiggghts.sh: --cpu must be a core number below $(nproc), not '$cpu'" >&2
        exit 2
    fi
    if ! command -v taskset > /dev/null; then
        echo "compareLiggghts.sh: --cpu needs taskset (Debian's util-linux)" >&2
        exit 1
    fi
    pin=(taskset -c "$cpu")
fi

liggghts=${LIGGGHTS:-$(command -v liggghts || true)}
if [ -z "$liggghts" ] || [ ! -x "$liggghts" ]; then
    echo "compareLiggghts.sh: LIGGGHTS is not installed (no executable '${liggghts:-liggghts}' on PATH)." >&2
    echo "  Install Debian's package:  apt-get install -y liggghts" >&2
    exit 1
fi

if [ -z "$bench" ]; then
    bench=$(command -v spherePourBenchmark || true)
    if [ -z "$bench" ]; then
        echo "compareLiggghts.sh: spherePourBenchmark is not on PATH." >&2
        echo "  Build it (./Allwmake, or cmake --build <build> --target spherePourBenchmark)" >&2
        echo "  and source src/etc/bashrc, or give its path as the first argument." >&2
        exit 1
    fi
fi
if [ ! -x "$bench" ]; then
    echo "compareLiggghts.sh: '$bench' is not an executable" >&2
    exit 1
fi
# (the runs start in their own folders: a relative path is taken from here)
bench=$(cd "$(dirname "$bench")" && pwd)/$(basename "$bench")
if [ ! -f "$input" ]; then
    echo "compareLiggghts.sh: the LIGGGHTS input '$input' is missing" >&2
    exit 1
fi

run=$(mktemp -d "${TMPDIR:-/tmp}/compareLiggghts.XXXXXX")
if [ "$keep" = 0 ]; then
    trap 'rm -rf "$run"' EXIT
fi

now() { date +%s.%N; }

# The damping coefficient c of ours, and LIGGGHTS's restitution e_L with the
# same c: c = 2 sqrt(5/6) b, b = -ln e_L/sqrt(ln^2 e_L + pi^2), so
# ln e_L = -pi b/sqrt(1 - b^2)
damping=$("$bench" 0 --every=0 | sed -n 's/^RESULT .*damping=\([^ ]*\).*/\1/p')
if [ -z "$damping" ]; then
    echo "compareLiggghts.sh: spherePourBenchmark printed no damping (RESULT ... damping=c)" >&2
    exit 1
fi
restitutionL=$(awk -v c="$damping" 'BEGIN { pi = atan2(0, -1); b = c/(2*sqrt(5/6));
    printf "%.12g", exp(-pi*b/sqrt(1 - b*b)) }')

echo "compareLiggghts: $steps steps of the 1000-sphere pour"
echo "  damping:  c = $damping in both (LIGGGHTS: restitution $restitutionL, limitForce on)"
echo "  LIGGGHTS: $liggghts ($(dpkg-query -W -f='${Version}' liggghts 2>/dev/null || echo '?'))"
echo "  ours:     $bench"
echo "  machine:  $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo

# One round: each code once, in turn; its figures appended to rounds.txt
# (LIGGGHTS loop, ours loop, LIGGGHTS process, ours process)
oneRound() {
    local r=$1
    # LIGGGHTS first (serial, one process), in the run directory
    echo "Round $r of $rounds: running LIGGGHTS ..."
    t0=$(now)
    if ! (cd "$run" && "${pin[@]}" "$liggghts" -in "$input" -var nsteps "$steps" -var restitution "$restitutionL" -log "$run/log.liggghts" \
            > "$run/liggghts.out" 2>&1); then
        echo "compareLiggghts.sh: LIGGGHTS failed; its output:" >&2
        tail -20 "$run/liggghts.out" >&2
        exit 1
    fi
    t1=$(now)

    echo "Round $r of $rounds: running spherePourBenchmark ..."
    t2=$(now)
    if ! (cd "$run" && "${pin[@]}" "$bench" "$steps" > "$run/ours.out" 2>&1); then
        echo "compareLiggghts.sh: spherePourBenchmark failed; its output:" >&2
        tail -20 "$run/ours.out" >&2
        exit 1
    fi
    t3=$(now)

    # LIGGGHTS: the last thermo line (step atoms keTrans keRot zMean zMax) and
    # "Loop time of X on 1 procs for N steps"
    read -r lStep lAtoms lKet lKer lZmean lZmax < <(
        awk -v n="$steps" '$1 == n && NF == 6 { line = $0 } END { print line }' "$run/liggghts.out")
    lLoop=$(awk '/^Loop time of/ { t = $4 } END { print t }' "$run/liggghts.out")
    if [ -z "${lStep:-}" ] || [ -z "$lLoop" ]; then
        echo "compareLiggghts.sh: could not read LIGGGHTS's output ($run/liggghts.out)" >&2
        keep=1; trap - EXIT
        exit 1
    fi

    # Ours: the RESULT line
    result=$(grep '^RESULT ' "$run/ours.out" | tail -1)
    field() { echo "$result" | tr ' ' '\n' | awk -F= -v k="$1" '$1 == k { print $2 }'; }
    oSteps=$(field steps); oLoop=$(field wall); oKet=$(field keTrans); oKer=$(field keRot)
    oZmean=$(field meanHeight); oZmax=$(field maxHeight); oLost=$(field lost)
    if [ -z "$oSteps" ] || [ -z "$oLoop" ]; then
        echo "compareLiggghts.sh: could not read spherePourBenchmark's RESULT line ($run/ours.out)" >&2
        keep=1; trap - EXIT
        exit 1
    fi
    awk -v a="$lLoop" -v b="$oLoop" -v t0="$t0" -v t1="$t1" -v t2="$t2" -v t3="$t3" \
        'BEGIN { print a, b, t1 - t0, t3 - t2 }' >> "$run/rounds.txt"
}

for r in $(seq "$rounds"); do
    oneRound "$r"
done
echo

awk \
    -v lSteps="$lStep" -v lAtoms="$lAtoms" -v t0="$t0" -v t1="$t1" -v lLoop="$lLoop" \
    -v lKet="$lKet" -v lKer="$lKer" -v lZmean="$lZmean" -v lZmax="$lZmax" \
    -v oSteps="$oSteps" -v oLost="$oLost" -v t2="$t2" -v t3="$t3" -v oLoop="$oLoop" \
    -v oKet="$oKet" -v oKer="$oKer" -v oZmean="$oZmean" -v oZmax="$oZmax" \
'BEGIN {
    lProc = t1 - t0
    oProc = t3 - t2
    fmt = "%-12s %7s %9s %9s %10s %11s %10s %11s %11s\n"
    printf fmt, "code", "steps", "wall [s]", "loop [s]", "steps/s", "zMean [mm]", "zMax [mm]", "KEt [J]", "KEr [J]"
    row = "%-12s %7d %9.2f %9.2f %10.0f %11.4f %10.4f %11.3e %11.3e\n"
    printf row, "LIGGGHTS", lSteps, lProc, lLoop, lSteps/lLoop, 1e3*lZmean, 1e3*lZmax, lKet, lKer
    printf row, "immersedDEM", oSteps, oProc, oLoop, oSteps/oLoop, 1e3*oZmean, 1e3*oZmax, oKet, oKer
    printf "\n"
    printf "wall time ratio ours/LIGGGHTS: %.2f (whole process), %.2f (stepping loop)\n", oProc/lProc, oLoop/lLoop
    printf "  wall: the process as timed here (start-up and set-up included);\n"
    printf "  loop: each code'\''s own clock around its steps (LIGGGHTS'\''s \"Loop time\")\n"
    printf "\n"
    d = 100*(oZmean - lZmean)/lZmean
    dm = 100*(oZmax - lZmax)/lZmax
    tol = 2
    printf "physical result:\n"
    printf "  mean height of the centres: ours %.4f mm, LIGGGHTS %.4f mm, difference %+.2f %% (%s %g %%)\n", \
        1e3*oZmean, 1e3*lZmean, d, (d < tol && d > -tol) ? "within" : "NOT within", tol
    printf "  max height of the centres:  ours %.4f mm, LIGGGHTS %.4f mm, difference %+.2f %%\n", \
        1e3*oZmax, 1e3*lZmax, dm
    printf "  spheres: LIGGGHTS %d in the domain; ours %d outside the box\n", lAtoms, oLost
    printf "  final kinetic energy (residual of the settling pile; compare orders of magnitude):\n"
    printf "    ours %.3e J, LIGGGHTS %.3e J\n", oKet + oKer, lKet + lKer
}'


# More than one round: each round's ratio, their median, and the ratio of
# the fastest runs of each code
if [ "$rounds" -gt 1 ]; then
    echo
    awk '
    { l[NR] = $1; o[NR] = $2; q[NR] = $2/$1
      printf "round %d: stepping loop LIGGGHTS %.2f s, ours %.2f s, ratio %.2f\n", NR, $1, $2, q[NR] }
    END {
        n = NR
        for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (q[j] < q[i]) { t = q[i]; q[i] = q[j]; q[j] = t }
        med = n % 2 ? q[(n + 1)/2] : 0.5*(q[n/2] + q[n/2 + 1])
        lMin = l[1]; oMin = o[1]
        for (i = 2; i <= n; ++i) { if (l[i] < lMin) lMin = l[i]; if (o[i] < oMin) oMin = o[i] }
        printf "stepping loop ratio ours/LIGGGHTS over %d rounds: median %.2f, range %.2f-%.2f; fastest runs %.2f s / %.2f s = %.2f\n", n, med, q[1], q[n], oMin, lMin, oMin/lMin
    }' "$run/rounds.txt"
fi
if [ "$keep" = 1 ]; then
    echo
    echo "logs kept in $run (liggghts.out, log.liggghts, ours.out)"
fi

# The pile height (the last round's): within 2% (see the header); and every
# sphere kept in the box in both (ours: at every history line and the end;
# LIGGGHTS: none lost from its domain)
echo
status=0
if awk -v o="$oZmean" -v l="$lZmean" 'BEGIN { d = (o - l)/l; exit !(d < 0.02 && d > -0.02) }'; then
    echo "PASS: the mean height of the centres agrees with LIGGGHTS's within 2%"
else
    echo "FAILED: the mean height of the centres differs from LIGGGHTS's by 2% or more"
    status=1
fi
if [ "$oLost" = 0 ] && [ "$lAtoms" = 1000 ]; then
    echo "PASS: every sphere stayed in the box in both codes"
else
    echo "FAILED: spheres left the box (ours $oLost; LIGGGHTS keeps $lAtoms of 1000)"
    status=1
fi
exit $status
