#!/usr/bin/env bash
# biref accuracy runs its (angle, azimuth) states in parallel: a small study gives the same JSON on
# 1 and on 2 threads, the timings and the thread count aside.
set -u
. "$(dirname "$0")/lib.sh"
# The sanitizer build (BIREF_TEST_QUICK) is some 30x slower: fewer states, still several per thread.
grid=(--theta-max-deg 80 --azimuths 2)
[ -z "${BIREF_TEST_QUICK:-}" ] || grid=(--theta-max-deg 40 --azimuths 1)
small=(accuracy "${grid[@]}" --theta-step-deg 40 --reference-samples 256 --check-samples 512 --json)
expect_ok "1 thread" "${small[@]}" --threads 1
mv "$tmpdir/out" "$tmpdir/t1.json"
expect_ok "2 threads" "${small[@]}" --threads 2
mv "$tmpdir/out" "$tmpdir/t2.json"
if ! /usr/bin/python3 "$(dirname "$0")/accuracy_reports_equal.py" "$tmpdir/t1.json" "$tmpdir/t2.json"; then
  echo "FAIL (1 vs 2 threads)"
  fails=$((fails + 1))
fi
finish
