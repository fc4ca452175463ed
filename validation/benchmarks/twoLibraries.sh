# Sourced by the benchmarks that run one case with two libraries at once
# (bedAtRestBenchmark.sh, spheresInCornersBenchmark.sh); they set
# project, libA, libB and work first.

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
