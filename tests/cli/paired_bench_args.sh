#!/usr/bin/env bash
# bench/paired_bench.sh's argument handling, without building or timing anything: --help lists
# every row, and a bad option, row list or number is one error line and exit status 2 before any
# build starts. (The biref argument of the other command-line tests is accepted and unused.)
set -u
root="$(cd "$(dirname "$0")/../.." && pwd)"
script=$root/bench/paired_bench.sh
fails=0
tmpdir=$(mktemp -d)
trap 'rm -rf "$tmpdir"' EXIT

if ! bash "$script" --help >"$tmpdir/help" 2>&1; then
    echo "FAIL (--help): non-zero exit"
    fails=$((fails + 1))
fi
for row in analytic prefilter fig9c analyzer45 expansion numeric-8 numeric-32 ground-truth ss1 ss4 startup render mpi; do
    if ! grep -Eq "^ +([a-z0-9-]+, )*$row( |,)" "$tmpdir/help"; then
        echo "FAIL (--help): row $row is not described"
        fails=$((fails + 1))
    fi
done

refuse() { # description, arguments...: exit status 2, exactly one line on stderr, nothing on stdout
    local what=$1 rc=0
    shift
    bash "$script" "$@" >"$tmpdir/out" 2>"$tmpdir/err" || rc=$?
    if [ "$rc" -ne 2 ] || [ "$(wc -l <"$tmpdir/err")" -ne 1 ] || [ -s "$tmpdir/out" ]; then
        echo "FAIL ($what): rc=$rc, stderr:"
        sed 's/^/  /' "$tmpdir/err" | head -5
        fails=$((fails + 1))
    fi
}
refuse "unknown row" --rows analytic,frame
refuse "row given twice" --rows startup,analytic,startup
refuse "empty row in the list" --rows analytic,,startup
refuse "empty row list" --rows ""
refuse "all with another row" --rows all,analytic
refuse "option given twice" --rounds 3 --rounds 4
refuse "flag given twice" --quick --quick
refuse "zero rounds" --rounds 0
refuse "not a number" --threads two
refuse "negative size" --width -5
refuse "missing value" --rows
refuse "an option as the value" --base --json
refuse "unknown option" --frobnicate
refuse "no such scene" --scene "$tmpdir/none.json"

# Inside a git checkout the plan is printed without building: every selected row, once.
if git -C "$root" rev-parse --git-dir >/dev/null 2>&1; then
    if ! bash "$script" --dry-run --quick --base HEAD --rows startup,analytic >"$tmpdir/plan" 2>"$tmpdir/err"; then
        echo "FAIL (--dry-run): non-zero exit"
        sed 's/^/  /' "$tmpdir/err" | head -5
        fails=$((fails + 1))
    elif [ "$(grep -cE '^(startup|analytic) ' "$tmpdir/plan")" -ne 2 ] || grep -q "^mpi " "$tmpdir/plan"; then
        echo "FAIL (--dry-run): the plan does not list exactly the selected rows"
        fails=$((fails + 1))
    fi
    refuse "unknown base commit" --dry-run --base no-such-commit-anywhere
fi

if [ "$fails" -ne 0 ]; then
    echo "$fails failure(s)"
    exit 1
fi
echo "all passed"
