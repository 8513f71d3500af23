#!/usr/bin/env bash
# Progress on stderr when it is not a terminal (here a file): a job that runs for seconds prints
# plain progress lines and a final "done" line, without the terminal bar's carriage returns;
# --progress prints them from the start even for a short job; --quiet (or -q) prints none; the
# two exclude each other; every command accepts either.
set -u
. "$(dirname "$0")/lib.sh"
scene="$(dirname "$0")/../../examples/fig9a.json"
line_re='^biref render: +[0-9]+%  [0-9.]+ s'

# A render that runs at least 3 s: the image grows until it does, so that a fast machine cannot
# make the job too short to report (the first lines come after 2 s).
side=12
while :; do
  t0=$(date +%s%N)
  "$BIREF" render "$scene" -o "$tmpdir/long.png" --method ground-truth --width "$side" --height "$side" \
    --threads 1 >/dev/null 2>"$tmpdir/long.err"
  rc=$?
  ms=$((($(date +%s%N) - t0) / 1000000))
  if [ "$rc" -ne 0 ] || [ "$ms" -ge 3000 ] || [ "$side" -ge 400 ]; then break; fi
  side=$((side * 3 / 2))
done
if [ "$rc" -ne 0 ]; then
  echo "FAIL (long render): exit $rc"
  fails=$((fails + 1))
elif ! grep -Eq "$line_re" "$tmpdir/long.err" || ! grep -Eq '^biref render: done in [0-9.]+ s$' "$tmpdir/long.err"; then
  echo "FAIL (long render, ${ms} ms, ${side}x${side}): no progress lines on stderr"
  sed 's/^/  stderr: /' "$tmpdir/long.err" | head -5
  fails=$((fails + 1))
elif grep -q $'\r' "$tmpdir/long.err"; then
  echo "FAIL (long render): a terminal bar in a file"
  fails=$((fails + 1))
fi

# A short job: lines with --progress, none with --quiet/-q; both, or one twice, is an error. (That a short job prints
# nothing by default is not tested: a loaded machine can make any job last 2 s.)
short=(render "$scene" -o "$tmpdir/short.png" --width 24 --height 24 --threads 1)
check_stderr() { # DESCRIPTION EXPECT(lines|empty) ARGS...
  local what=$1 want=$2; shift 2
  if ! "$BIREF" "$@" >/dev/null 2>"$tmpdir/err"; then
    echo "FAIL ($what): non-zero exit"
    fails=$((fails + 1))
  elif [ "$want" = empty ] && [ -s "$tmpdir/err" ]; then
    echo "FAIL ($what): stderr not empty"
    sed 's/^/  stderr: /' "$tmpdir/err" | head -3
    fails=$((fails + 1))
  elif [ "$want" = lines ] && ! grep -Eq "^biref [a-z]+: +[0-9]+%" "$tmpdir/err"; then
    echo "FAIL ($what): no progress line"
    sed 's/^/  stderr: /' "$tmpdir/err" | head -3
    fails=$((fails + 1))
  fi
}
check_stderr "short render --progress" lines "${short[@]}" --progress
check_stderr "short render --quiet" empty "${short[@]}" --quiet
check_stderr "short render -q" empty "${short[@]}" -q
expect_error "--progress then --quiet" "${short[@]}" --progress --quiet
expect_error "-q then --progress" "${short[@]}" -q --progress
expect_error "--quiet twice" "${short[@]}" --quiet -q
expect_error "--progress twice" "${short[@]}" --progress --progress
acc=(accuracy --theta-max-deg 40 --theta-step-deg 20 --azimuths 2 --reference-samples 256 --json)
check_stderr "accuracy --progress" lines "${acc[@]}" --progress
check_stderr "accuracy --quiet" empty "${acc[@]}" --quiet
pe=(photoelastic --preset disk --size 32 -o "$tmpdir/pe.png")
check_stderr "photoelastic --progress" lines "${pe[@]}" --progress
check_stderr "photoelastic --quiet" empty "${pe[@]}" --quiet
bench=(bench --scene "$scene" --width 16 --height 16 --methods analytic,numeric-8 --max-seconds 0.05 --json)
check_stderr "bench --progress" lines "${bench[@]}" --progress

expect_ok "biref --help" --help
expect_grep "biref --help names --progress and --quiet" '--progress.*-q, --quiet'
for cmd in slab spectrum accuracy render diff bench figure gl-data photoelastic; do
  expect_ok "$cmd takes --quiet" "$cmd" --quiet --help
  expect_ok "$cmd takes --progress" "$cmd" --progress --help
done
finish
