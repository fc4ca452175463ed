# Helpers for the case tests (sourced). Each test gets its own work folder
# (argument 1), copies a case template there and checks what the run wrote.
set -u
projectDir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd -P)"
. "$projectDir/src/etc/bashrc"

nFailed=0
nPassed=0

pass() { nPassed=$((nPassed + 1)); echo "PASS: $*"; }
failed() { nFailed=$((nFailed + 1)); echo "FAIL: $*"; }

# expect <description> <command...>: the command must succeed
expect()
{
    local what="$1"; shift
    if "$@"; then pass "$what"; else failed "$what"; fi
}

# logHas <file> <fixed string>
logHas() { grep -qF -- "$2" "$1"; }

# copyCase <template name> <destination>
copyCase()
{
    rm -rf "$2"
    mkdir -p "$(dirname "$2")"
    cp -r "$projectDir/caseTemplates/$1" "$2"
    (cd "$2" && ./Allclean >/dev/null 2>&1)
}

finish()
{
    echo "$nPassed passed, $nFailed failed"
    [ "$nFailed" -eq 0 ]
}
