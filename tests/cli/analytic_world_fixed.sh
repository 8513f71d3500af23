#!/usr/bin/env bash
# World-fixed polarizers with the analytic method (its general coherency/analyzer terms, the GPU
# shader's formulas) against the exact path-group expansion on fig. 9c with a 45-degree analyzer,
# 320x180, by statistics: mean dE00 <= 0.1, 99th percentile <= 1.5 (measured: 0.034, 0.83), with
# and without the prefilter.
set -u
. "$(dirname "$0")/lib.sh"


scene=examples/fig9c_analyzer45.json
size=(--width 320 --height 180 --quiet)
for aa in prefilter none; do
  expect_ok "analytic, $aa" render "$scene" -o "$tmpdir/analytic-$aa.png" "${size[@]}" --antialias "$aa"
  expect_ok "expansion, $aa" render "$scene" -o "$tmpdir/expansion-$aa.png" "${size[@]}" --antialias "$aa" \
    --method expansion
  expect_ok "diff, $aa" diff "$tmpdir/analytic-$aa.png" "$tmpdir/expansion-$aa.png" --json
  mean=$(json_num mean "$tmpdir/out")
  p99=$(json_num p99 "$tmpdir/out")
  echo "fig9c_analyzer45 ($aa): analytic vs expansion dE00 mean $mean, p99 $p99"
  awk -v m="$mean" -v p="$p99" 'BEGIN { exit !(m != "" && p != "" && m <= 0.1 && p <= 1.5) }' ||
    { echo "FAIL ($aa): mean $mean > 0.1 or p99 $p99 > 1.5"; fails=$((fails + 1)); }
done
finish
