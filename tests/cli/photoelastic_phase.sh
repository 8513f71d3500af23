#!/usr/bin/env bash
# biref photoelastic --phase-steps and demodulate: the six-step set of the disk as 16-bit PNGs and
# as PFMs, demodulated from the empty field (order 0) back to the fringe order of --map within
# 0.02 away from the load points; the four-step set; --format pfm pictures; one-line errors.
set -u
. "$(dirname "$0")/lib.sh"
common=(--preset disk --light mono --lambda-nm 589 --size 120)

expect_ok "demodulate help" photoelastic demodulate --help
expect_grep "help" "--zero-order"
expect_ok "six PNG steps" photoelastic "${common[@]}" --phase-steps 6 -o "$tmpdir/s.png"
expect_grep "step 6" "s-6.png: quarter-wave plate 135 deg, analyzer 135 deg"
expect_ok "fringe-order map of the closed form" photoelastic "${common[@]}" --map fringe-order -o "$tmpdir/truth.csv"
check_round_trip() { # DIR: fringe-order.csv against the truth map
  paste -d, "$tmpdir/truth.csv" "$1/fringe-order.csv" | awk -F, '
    NR == 1 { next }
    { x = $1; y = $2; r = sqrt(x * x + y * y); d1 = sqrt(x * x + (y - 25) ^ 2); d2 = sqrt(x * x + (y + 25) ^ 2)
      if ($3 == "nan" || r > 22.5 || d1 < 7.5 || d2 < 7.5) next
      n++; d = $3 - $6; if ($6 == "nan") d = 99; if (d < 0) d = -d; if (d > m) m = d }
    END { printf "%d pixels, max |dN| %.4f\n", n, m; if (n < 5000 || m > 0.02) { print "FAIL (round trip)"; exit 1 } }'
}
expect_ok "demodulate PNG" photoelastic demodulate "$tmpdir"/s-{1,2,3,4,5,6}.png --zero-order 1,1 --format csv \
  -o "$tmpdir/m6"
check_round_trip "$tmpdir/m6" || fails=$((fails + 1))
expect_ok "four PFM steps" photoelastic "${common[@]}" --phase-steps 4 -o "$tmpdir/f.pfm" --json
expect_grep "json steps" '"analyzer_deg":[[:space:]]*45'
expect_ok "demodulate PFM" photoelastic demodulate "$tmpdir"/f-{1,2,3,4}.pfm --order-at 1,1,0 --format csv -o "$tmpdir/m4" --json
expect_grep "json maps" '"unwrapped_pixels"'
check_round_trip "$tmpdir/m4" || fails=$((fails + 1))
expect_ok "PFM maps" photoelastic demodulate "$tmpdir"/f-{1,2,3,4}.pfm --zero-order 1,1 -o "$tmpdir/m4p"
for m in isoclinic phase-wrapped fringe-order modulation background; do
  [ "$(head -c 2 "$tmpdir/m4p/$m.pfm")" = "Pf" ] || { echo "FAIL ($m.pfm)"; fails=$((fails + 1)); }
done

# Float pictures.
expect_ok "pfm grey" photoelastic "${common[@]}" --format pfm -o "$tmpdir/g.pfm"
[ "$(head -c 2 "$tmpdir/g.pfm")" = "Pf" ] || { echo "FAIL (grey PFM)"; fails=$((fails + 1)); }
expect_ok "pfm colour" photoelastic --preset hole --size 40 --format pfm -o "$tmpdir/c.pfm"
[ "$(head -c 2 "$tmpdir/c.pfm")" = "PF" ] || { echo "FAIL (colour PFM)"; fails=$((fails + 1)); }

# Errors.
expect_error "white steps" photoelastic --preset disk --phase-steps 6 -o "$tmpdir/w.pfm"
expect_error "steps 5" photoelastic "${common[@]}" --phase-steps 5 -o "$tmpdir/w.pfm"
expect_error "steps ext" photoelastic "${common[@]}" --phase-steps 4 -o "$tmpdir/w.tif"
expect_error "map and pfm" photoelastic "${common[@]}" --format pfm --map isoclinic -o "$tmpdir/w.pfm"
expect_error "five images" photoelastic demodulate "$tmpdir"/s-{1,2,3,4,5}.png --zero-order 1,1 -o "$tmpdir/x"
expect_error "no reference" photoelastic demodulate "$tmpdir"/s-{1,2,3,4,5,6}.png -o "$tmpdir/x"
expect_error "reference outside" photoelastic demodulate "$tmpdir"/s-{1,2,3,4,5,6}.png --zero-order 500,1 -o "$tmpdir/x"
expect_ok "small steps" photoelastic --preset disk --light mono --size 60 --phase-steps 4 -o "$tmpdir/z.png"
expect_error "size mismatch" photoelastic demodulate "$tmpdir"/s-{1,2,3}.png "$tmpdir/z-4.png" --zero-order 1,1 -o "$tmpdir/x"
expect_error "not an image" photoelastic demodulate "$tmpdir"/truth.csv "$tmpdir"/s-{2,3,4}.png --zero-order 1,1 -o "$tmpdir/x"
finish
