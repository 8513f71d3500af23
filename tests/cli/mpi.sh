#!/usr/bin/env bash
# Several processes (mpirun -n 3, docs/CLUSTER.md): the frame and the accuracy study equal the single
# process's (the PFM and the PNG byte for byte, the JSON value for value, timings aside); a bad input
# on some ranks only gives one error line and the same non-zero exit everywhere; commands that do
# not share their work refuse. Skipped (77) when the build has no MPI or mpirun is missing.
set -u
. "$(dirname "$0")/lib.sh"
if ! command -v mpirun >/dev/null 2>&1 || ! ldd "$BIREF" 2>/dev/null | grep -q 'libmpi'; then
  echo "skipped: $BIREF is built without MPI, or mpirun is missing"
  exit 77
fi
# 3 processes on whatever cores there are; Open MPI refuses root unless told.
mpi=(mpirun --oversubscribe --bind-to none -n 3)
[ "$(id -u)" -ne 0 ] || mpi+=(--allow-run-as-root)
# The sanitizer build: LeakSanitizer also ignores Open MPI's own allocations (.ci/lsan_openmpi.supp,
# which says why the stacks must be unwound in full), next to the project's usual list.
if [ -n "${LSAN_OPTIONS:-}" ]; then
  supp_dir=$(cd "$(dirname "$0")/../../.ci" && pwd)
  cat "$supp_dir/lsan.supp" "$supp_dir/lsan_openmpi.supp" >"$tmpdir/lsan.supp"
  export LSAN_OPTIONS="suppressions=$tmpdir/lsan.supp:print_suppressions=0:fast_unwind_on_malloc=0"
fi
size=(--width 96 --height 54)
[ -z "${BIREF_TEST_QUICK:-}" ] || size=(--width 64 --height 36)

# expect_same_render DESCRIPTION ARGS...: one process and three give the same files.
expect_same_render() {
  local what=$1; shift
  if ! "$BIREF" render "$@" -o "$tmpdir/one.png" --pfm "$tmpdir/one.pfm" --threads 1 "${size[@]}" -q >/dev/null \
       2>"$tmpdir/err"; then
    echo "FAIL ($what): one process"; sed 's/^/  stderr: /' "$tmpdir/err" | head -5; fails=$((fails + 1)); return
  fi
  if ! "${mpi[@]}" "$BIREF" render "$@" -o "$tmpdir/three.png" --pfm "$tmpdir/three.pfm" --threads 1 "${size[@]}" \
       -q >"$tmpdir/out" 2>"$tmpdir/err"; then
    echo "FAIL ($what): mpirun -n 3"; sed 's/^/  stderr: /' "$tmpdir/err" | head -8; fails=$((fails + 1)); return
  fi
  if ! cmp -s "$tmpdir/one.pfm" "$tmpdir/three.pfm" || ! cmp -s "$tmpdir/one.png" "$tmpdir/three.png"; then
    echo "FAIL ($what): the images of 1 and 3 processes differ"; fails=$((fails + 1))
  fi
  # Rank 0 alone reports.
  if [ "$(grep -c '^wrote ' "$tmpdir/out")" -ne 1 ]; then
    echo "FAIL ($what): expected one report line from rank 0"; sed 's/^/  stdout: /' "$tmpdir/out"; fails=$((fails + 1))
  fi
}
expect_same_render "fig9a, prefilter" examples/fig9a.json
# (The sanitizer build, some 30x slower, checks the one frame above.)
[ -n "${BIREF_TEST_QUICK:-}" ] ||
  expect_same_render "fig9c between world-fixed polarizers, supersampled" examples/fig9c_analyzer45.json \
    --supersample 2 --antialias none

# A bad scene on ranks 1 and 2 only: rank 0 says their line, once; every rank exits 2, nothing written.
rc=0
echo '{"camera": ' >"$tmpdir/bad.json"
mpirun_base=(mpirun --oversubscribe --bind-to none)
[ "$(id -u)" -ne 0 ] || mpirun_base+=(--allow-run-as-root)
"${mpirun_base[@]}" -n 1 "$BIREF" render examples/fig9a.json -o "$tmpdir/bad.png" "${size[@]}" : \
  -n 2 "$BIREF" render "$tmpdir/bad.json" -o "$tmpdir/bad.png" "${size[@]}" >"$tmpdir/out" 2>"$tmpdir/err" || rc=$?
if [ "$rc" -ne 2 ] || [ "$(grep -c '^biref render: error: ' "$tmpdir/err")" -ne 1 ] ||
   ! grep -q "bad.json" "$tmpdir/err" || [ -e "$tmpdir/bad.png" ]; then
  echo "FAIL (bad scene on ranks 1-2): rc=$rc"; sed 's/^/  stderr: /' "$tmpdir/err" | head -5; fails=$((fails + 1))
fi

# A command that does not share its work refuses, once. (Not in the sanitizer build: mpirun takes
# seconds to end a job whose processes failed.)
rc=0
[ -n "${BIREF_TEST_QUICK:-}" ] ||
  "${mpi[@]}" "$BIREF" slab --eta-o 1.5 --eta-e 1.6 --axis 0,1,0 --thickness-um 10 >"$tmpdir/out" 2>"$tmpdir/err" || rc=$?
if [ -z "${BIREF_TEST_QUICK:-}" ] &&
   { [ "$rc" -ne 2 ] || [ "$(grep -c '^biref slab: error: ' "$tmpdir/err")" -ne 1 ] || [ -s "$tmpdir/out" ]; }; then
  echo "FAIL (slab under mpirun): rc=$rc"; sed 's/^/  stderr: /' "$tmpdir/err" | head -5; fails=$((fails + 1))
fi

# The accuracy study: the same JSON from one process and from three.
grid=(--theta-max-deg 80 --azimuths 2)
[ -z "${BIREF_TEST_QUICK:-}" ] || grid=(--theta-max-deg 40 --azimuths 1)
small=(accuracy "${grid[@]}" --theta-step-deg 40 --reference-samples 256 --check-samples 512 --threads 1 --json -q)
"$BIREF" "${small[@]}" >"$tmpdir/a1.json" 2>"$tmpdir/err" || { echo "FAIL (accuracy, one process)"; fails=$((fails + 1)); }
"${mpi[@]}" "$BIREF" "${small[@]}" >"$tmpdir/a3.json" 2>"$tmpdir/err" ||
  { echo "FAIL (accuracy, mpirun -n 3)"; sed 's/^/  stderr: /' "$tmpdir/err" | head -5; fails=$((fails + 1)); }
if ! /usr/bin/python3 "$(dirname "$0")/accuracy_reports_equal.py" "$tmpdir/a1.json" "$tmpdir/a3.json"; then
  echo "FAIL (accuracy: 1 vs 3 processes)"
  fails=$((fails + 1))
fi
finish
