#!/usr/bin/env bash
# biref photoelastic --key and --scale-bar: the key strip below the picture, the scale bar on it
# (a few percent of the pixels, nothing else changed), JSON fields, and misuse refused.
set -u
. "$(dirname "$0")/lib.sh"
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{ printf "%d %d\n", $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8 }'; }

expect_ok "picture without key or scale bar" photoelastic --preset disk --size 200 -o "$tmpdir/a.png"
expect_ok "scale bar" photoelastic --preset disk --size 200 --scale-bar -o "$tmpdir/b.png" --json
expect_grep "bar length" '"scale_bar_mm":[[:space:]]*10'
[ "$(png_size "$tmpdir/b.png")" = "200 200" ] || { echo "FAIL (scale bar changes the size)"; fails=$((fails + 1)); }
expect_ok "diff" diff "$tmpdir/a.png" "$tmpdir/b.png" --json
frac=$(sed -n 's/.*"over_1":[[:space:]]*\([0-9.e+-]*\).*/\1/p' "$tmpdir/out")
awk -v f="$frac" 'BEGIN { if (!(f > 0.005 && f < 0.05)) { print "FAIL (scale bar covers " f " of the picture)"; exit 1 } }' \
  || fails=$((fails + 1))

expect_ok "key white" photoelastic --preset disk --size 200 --key -o "$tmpdir/k.png" --json
expect_grep "key orders" '"key_fringe_orders":[[:space:]]*6'
expect_grep "png height" '"png_height":[[:space:]]*264'
[ "$(png_size "$tmpdir/k.png")" = "200 264" ] || { echo "FAIL (key strip size)"; fails=$((fails + 1)); }
expect_ok "key mono" photoelastic --preset beam --light mono --tint --size 150 --key --scale-bar -o "$tmpdir/m.png" --json
expect_grep "mono key" '"key_fringe_orders":[[:space:]]*[1-9]'

expect_error "key on a map" photoelastic --preset disk --map isoclinic --key -o "$tmpdir/x.pfm"
expect_error "key without picture" photoelastic --preset disk --profile 0,0,0,1 --scale-bar
finish
