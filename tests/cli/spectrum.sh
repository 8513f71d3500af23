#!/usr/bin/env bash
# biref spectrum: good runs give the documented JSON keys and a table; every bad input gives one
# error line, a non-zero exit and nothing on stdout.
set -u
. "$(dirname "$0")/lib.sh"
slab=(--eta-o 1.775 --eta-e 1.231 --axis 0.084,0.979,-0.187 --thickness-um 20 --theta-deg 30)

expect_ok "help" spectrum --help
expect_grep "help lists options" "--range-nm"

expect_ok "analytic json" spectrum "${slab[@]}" --json
for key in method samples cmf range_nm input T R mixed polarization analyzer T_xyz R_xyz T_srgb R_srgb; do
  expect_grep "key $key" "\"$key\":"
done
expect_grep "analytic is the default" '"method":[[:space:]]*"analytic"'
expect_grep "analytic has no samples" '"samples":[[:space:]]*null'
expect_grep "default cmf" '"cmf":[[:space:]]*"cie1931"'
expect_grep "default analyzer" '"analyzer":[[:space:]]*"none"'

expect_ok "numeric json" spectrum "${slab[@]}" --method numeric --spectral-samples 16 --json
expect_grep "numeric samples" '"samples":[[:space:]]*16,'
expect_ok "numeric default samples" spectrum "${slab[@]}" --method numeric --json
expect_grep "numeric default 64" '"samples":[[:space:]]*64,'
expect_ok "ground truth" spectrum "${slab[@]}" --method ground-truth --json
expect_grep "ground truth samples" '"samples":[[:space:]]*16384,'
expect_ok "wyman and range" spectrum "${slab[@]}" --cmf wyman2013 --range-nm 400,680 --json
expect_grep "wyman cmf" '"cmf":[[:space:]]*"wyman2013"'
expect_ok "fractions and analyzer" spectrum "${slab[@]}" --polarization 0.02,0.98 --analyzer s --json
expect_grep "fractions kept" '"p":[[:space:]]*0.98'
expect_grep "analyzer s" '"analyzer":[[:space:]]*"s"'
expect_ok "weights normalised" spectrum "${slab[@]}" --polarization 3,1 --json
expect_grep "3,1 is 75% s" '"s":[[:space:]]*0.75'

# Energy: unpolarised light, no analyzer, lossless slab: T + R = 1 in every band.
expect_ok "energy" spectrum "${slab[@]}" --method ground-truth --json
sums=$(tr -d ' \t\n' <"$tmpdir/out" | sed -E 's/.*"T_xyz":\[([^]]*)\],"R_xyz":\[([^]]*)\].*/\1,\2/')
if ! echo "$sums" | awk -F, '{ if (NF != 6) bad = 1; for (j = 1; j <= 3; j++) { d = $j + $(j + 3) - 1; if (d < -1e-6 || d > 1e-6) bad = 1 } }
                              END { exit bad }'; then
  echo "FAIL (energy): T + R != 1: $sums"
  fails=$((fails + 1))
fi

expect_ok "table" spectrum "${slab[@]}" --polarization p --analyzer s
expect_grep "table rows" "p -> s"
expect_grep "mixed line" "^Mixed: polarization p"
if grep -q $'\033' "$tmpdir/out"; then
  echo "FAIL (no swatch when stdout is not a terminal)"
  fails=$((fails + 1))
fi

expect_error "samples zero" spectrum "${slab[@]}" --method numeric --spectral-samples 0
expect_error "samples negative" spectrum "${slab[@]}" --method numeric --spectral-samples -4
expect_error "samples garbage" spectrum "${slab[@]}" --method numeric --spectral-samples 8x
expect_error "samples with analytic" spectrum "${slab[@]}" --spectral-samples 16
expect_error "samples with ground truth" spectrum "${slab[@]}" --method ground-truth --spectral-samples 16
expect_error "inverted range" spectrum "${slab[@]}" --range-nm 700,380
expect_error "empty range" spectrum "${slab[@]}" --range-nm 500,500
expect_error "zero range start" spectrum "${slab[@]}" --range-nm 0,700
expect_error "nan range" spectrum "${slab[@]}" --range-nm nan,700
expect_error "short range" spectrum "${slab[@]}" --range-nm 380
expect_error "range outside the cmf" spectrum "${slab[@]}" --range-nm 800,900
# Bands beyond the colour-matching data are refused, not integrated into nonsense.
expect_error "range to 1e9 nm" spectrum "${slab[@]}" --range-nm 380,1e9
expect_error "range 1-100000 nm" spectrum "${slab[@]}" --range-nm 1,100000
expect_error "range from 10 nm" spectrum "${slab[@]}" --range-nm 10,830
expect_error "range 1e-300-1e300, numeric" spectrum "${slab[@]}" --method numeric --range-nm 1e-300,1e300
expect_error "range beyond the wyman fit" spectrum "${slab[@]}" --cmf wyman2013 --range-nm 350,700
expect_ok "whole cie1931 table" spectrum "${slab[@]}" --range-nm 380,780
expect_ok "whole wyman range" spectrum "${slab[@]}" --cmf wyman2013 --range-nm 360,830
expect_error "unknown cmf" spectrum "${slab[@]}" --cmf cie1964
expect_error "unknown method" spectrum "${slab[@]}" --method magic
expect_error "unknown polarization" spectrum "${slab[@]}" --polarization circular
expect_error "negative fraction" spectrum "${slab[@]}" --polarization -1,2
expect_error "zero fractions" spectrum "${slab[@]}" --polarization 0,0
expect_error "unknown analyzer" spectrum "${slab[@]}" --analyzer x
expect_error "missing eta-o" spectrum --eta-e 1.2 --axis 0,1,0 --thickness-um 1
expect_error "zero thickness" spectrum --eta-o 1.5 --eta-e 1.6 --axis 0,1,0 --thickness-um 0
expect_error "zero axis" spectrum --eta-o 1.5 --eta-e 1.6 --axis 0,0,0 --thickness-um 1
expect_error "theta 90" spectrum "${slab[@]}" --theta-deg 90
expect_error "unknown option" spectrum "${slab[@]}" --frobnicate
expect_error "missing value" spectrum "${slab[@]}" --method
expect_error "stray argument" spectrum "${slab[@]}" extra

# Beyond the paper: the path-group expansion and general polarisers.
expect_ok "expansion" spectrum "${slab[@]}" --method expansion --json
expect_grep "expansion order reported" '"expansion_order"'
expect_ok "crossed linear polarisers" spectrum "${slab[@]}" --method expansion --polarizer linear:30 --analyzer linear:120
expect_ok "circular analyzer, numeric" spectrum "${slab[@]}" --method numeric --spectral-samples 256 --stokes 1,0.2,0.3,0.4 --analyzer circular:-1
expect_ok "fixed order" spectrum "${slab[@]}" --method expansion --order 3
expect_ok "general polariser with analytic" spectrum "${slab[@]}" --polarizer linear:10
expect_ok "circular analyzer with analytic" spectrum "${slab[@]}" --analyzer circular:+1 --stokes 1,0,0.6,0.8
expect_error "unphysical stokes" spectrum "${slab[@]}" --method expansion --stokes 1,1,1,0
expect_error "bad handedness" spectrum "${slab[@]}" --method expansion --polarizer circular:2
expect_error "bad linear angle" spectrum "${slab[@]}" --method expansion --analyzer linear:abc
expect_error "order without expansion" spectrum "${slab[@]}" --order 2
expect_error "order too high" spectrum "${slab[@]}" --method expansion --order 99
expect_error "tolerance zero" spectrum "${slab[@]}" --method expansion --tolerance 0
expect_error "order and tolerance" spectrum "${slab[@]}" --method expansion --order 2 --tolerance 1e-3
finish
