#!/usr/bin/env bash
# biref photoelastic calibrate / demodulate --tfp: the round trip of one white-light colour
# picture. The disk (200 px, one sample at each pixel centre) with camera noise sigma = 2/255
# demodulates, from a seed near the rim, to the --map fringe-order within 0.05 for N <= 3
# wherever r <= 0.9 R and at least 0.3 R from the load points; the measured error by order is
# printed. Plus the table's form and one-line refusals. Uses /usr/bin/python3 (numpy).
set -u
. "$(dirname "$0")/lib.sh"
PY=/usr/bin/python3
expect_ok "calibrate help" photoelastic calibrate --help
expect_ok "calibrate" photoelastic calibrate -o "$tmpdir/table.csv"
expect_grep "calibrate report" "601 rows, N 0..6 at 550 nm, camera srgb"
grep -q '^fringe_order,r,g,b$' "$tmpdir/table.csv" && grep -q '^0.0000,0.000000,0.000000,0.000000$' "$tmpdir/table.csv" ||
  { echo "FAIL (table form: header, black at N = 0 in the dark field)"; fails=$((fails + 1)); }

expect_ok "picture" photoelastic --preset disk --size 200 --supersample 1 --antialias none -o "$tmpdir/disk.png"
expect_ok "truth" photoelastic --preset disk --size 200 --map fringe-order -o "$tmpdir/truth.csv"
$PY "$(dirname "$0")/camera_noise.py" "$tmpdir/disk.png" "$tmpdir/photo.png" 2.0 1 || fails=$((fails + 1))
expect_ok "demodulate" photoelastic demodulate --tfp "$tmpdir/photo.png" --calibration "$tmpdir/table.csv" --seed 185,100 \
  -o "$tmpdir/N.csv"
paste -d, "$tmpdir/N.csv" "$tmpdir/truth.csv" | awk -F, '
  NR > 1 && $6 != "nan" { x = $4; y = $5; r = sqrt(x * x + y * y); d1 = sqrt(x * x + (y - 25) ^ 2); d2 = sqrt(x * x + (y + 25) ^ 2)
    if (r > 22.5 || d1 < 7.5 || d2 < 7.5) next
    b = int($6); if (b > 6) b = 6; c[b]++
    d = ($3 == "nan") ? 99 : $3 - $6; if (d < 0) d = -d; if (d > m[b]) m[b] = d; s[b] += d }
  END { for (b = 0; b <= 6; b++) if (c[b]) printf "  N %d-%d: %5d px, mean |dN| %.4f, max %.4f\n", b, b + 1, c[b], s[b] / c[b], m[b]
        if (c[0] < 3000 || c[2] < 3000 || m[0] > 0.05 || m[1] > 0.05 || m[2] > 0.05) { print "FAIL (round trip N <= 3)"; exit 1 } }' ||
  fails=$((fails + 1))

# Refusals.
expect_error "seed off its order" photoelastic demodulate --tfp "$tmpdir/photo.png" --calibration "$tmpdir/table.csv" \
  --seed 185,100,1 -o "$tmpdir/x.csv"
expect_error "seed outside" photoelastic demodulate --tfp "$tmpdir/photo.png" --calibration "$tmpdir/table.csv" \
  --seed 500,1 -o "$tmpdir/x.csv"
expect_error "no seed" photoelastic demodulate --tfp "$tmpdir/photo.png" --calibration "$tmpdir/table.csv" -o "$tmpdir/x.csv"
expect_error "table is not a table" photoelastic demodulate --tfp "$tmpdir/photo.png" --calibration "$tmpdir/photo.png" \
  --seed 1,1 -o "$tmpdir/x.csv"
expect_error "output over input" photoelastic demodulate --tfp "$tmpdir/photo.png" --calibration "$tmpdir/table.csv" \
  --seed 1,1 -o "$tmpdir/table.csv"
printf 'lambda_nm,r,g,b\n400,1,0,0\n500,0,1,0\n' > "$tmpdir/cam.csv"
expect_error "short camera" photoelastic calibrate --camera "$tmpdir/cam.csv" -o "$tmpdir/t2.csv"
printf 'lambda_nm,r,g,b\n400,0,0,1\n500,0,1,0\n600,1,0,0\n700,0.5,0,0\n' > "$tmpdir/cam.csv"
expect_ok "camera" photoelastic calibrate --camera "$tmpdir/cam.csv" --max-order 2 -o "$tmpdir/t2.csv" --json
grep -q '"encoding":[[:space:]]*"linear"' "$tmpdir/out" || { echo "FAIL (camera table encoding)"; fails=$((fails + 1)); }
finish
