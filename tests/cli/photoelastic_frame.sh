#!/usr/bin/env bash
# biref photoelastic: the frame and the material as an engineer gives them. --window-mm for every
# field source (nodes included), a window off the part refused; a boundary that encloses no node
# refused; --fringe-value F@L as the alternative to --C-brewster, the material used printed and in
# the JSON; the margin around finite-element parts.
set -u
. "$(dirname "$0")/lib.sh"
ex=examples/photoelastic
nodes=(--stress-nodes "$ex/disk_nodes.csv" --columns sxx=S11,syy=S22,txy=S12)

# The window with nodes: every pixel of the map lies in it.
expect_ok "nodes window" photoelastic "${nodes[@]}" --window-mm 0,0,10,10 --size 20 --map fringe-order -o "$tmpdir/w.csv"
awk -F, 'NR > 1 { n++; if ($1 < 0 || $1 > 10 || $2 < 0 || $2 > 10) bad++ }
  END { if (n != 400 || bad) { print "FAIL (window ignored: " n + 0 " pixels, " bad + 0 " outside)"; exit 1 } }' \
  "$tmpdir/w.csv" || fails=$((fails + 1))
for src in "--preset disk" "--preset hole" "--preset beam"; do
  # shellcheck disable=SC2086
  expect_ok "window $src" photoelastic $src --window-mm 1,1,3,2 --size 20 --map sigma1 -o "$tmpdir/p.csv"
  awk -F, 'NR > 1 && ($1 < 1 || $1 > 3 || $2 < 1 || $2 > 2) { bad++ } END { exit bad > 0 }' "$tmpdir/p.csv" ||
    { echo "FAIL (window $src)"; fails=$((fails + 1)); }
done
expect_error "window off the part" photoelastic "${nodes[@]}" --window-mm 100,100,110,110 -o "$tmpdir/x.png"
grep -q "does not overlap the part" "$tmpdir/err" || { echo "FAIL (window message)"; fails=$((fails + 1)); }

# A boundary around no node (another part, or the wrong length unit) is refused.
printf 'x,y\n100,100\n110,100\n110,110\n' > "$tmpdir/far.csv"
expect_error "boundary off the nodes" photoelastic "${nodes[@]}" --boundary "$tmpdir/far.csv" -o "$tmpdir/x.png"
grep -q "encloses none of the 785 nodes" "$tmpdir/err" || { echo "FAIL (boundary message)"; cat "$tmpdir/err"; fails=$((fails + 1)); }
awk -F, '/^[-0-9]/ { printf "%.9g,%.9g\n", $1 / 1000 + 30, $2 / 1000 + 30; next } { print }' "$ex/disk_boundary.csv" > "$tmpdir/m.csv"
expect_error "boundary in metres" photoelastic "${nodes[@]}" --boundary "$tmpdir/m.csv" -o "$tmpdir/x.png"

# --fringe-value 7.0@546.1 is polycarbonate's C = 78 Br: the same retardation map.
expect_ok "preset material" photoelastic --preset disk --size 30 --map retardation -o "$tmpdir/c.csv"
expect_grep "default material printed" "material: polycarbonate \(the default"
expect_ok "fringe value" photoelastic --preset disk --size 30 --fringe-value 7.0@546.1 --map retardation -o "$tmpdir/f.csv"
expect_grep "fringe value printed" "fringe value 7 N/mm at 546.1 nm"
paste -d, "$tmpdir/c.csv" "$tmpdir/f.csv" | awk -F, 'NR > 1 && $3 != "nan" { n++; d = ($3 - $6) / ($3 > 1 ? $3 : 1); if (d < 0) d = -d; if (d > 2e-4) bad++ }
  END { if (bad || n < 400) { print "FAIL (fringe value map)"; exit 1 } }' || fails=$((fails + 1))
expect_ok "fringe value json" photoelastic --preset disk --size 8 --fringe-value 11@589.3 -o "$tmpdir/j.png" --json
/usr/bin/python3 - "$tmpdir/out" <<'PY' || fails=$((fails + 1))
import json, sys
m = json.load(open(sys.argv[1]))["material"]
C = 589.3e-9 / 11e3 / 1e-12
ok = m["default"] is False and m["fringe_value_N_per_mm"] == 11 and m["fringe_value_lambda_nm"] == 589.3 \
     and abs(m["C_brewster"] - C) < 1e-9 * C
if not ok: print("FAIL (fringe value in JSON)", m); sys.exit(1)
PY
expect_ok "default json" photoelastic --preset disk --size 8 -o "$tmpdir/j.png" --json
grep -q '"default":[[:space:]]*true' "$tmpdir/out" || { echo "FAIL (default material flagged in JSON)"; fails=$((fails + 1)); }
expect_error "fringe value without wavelength" photoelastic --preset disk --fringe-value 7 -o "$tmpdir/x.png"
grep -q "F@LAMBDA_NM" "$tmpdir/err" || { echo "FAIL (fringe value message)"; fails=$((fails + 1)); }
expect_error "fringe value and C" photoelastic --preset disk --fringe-value 7@546.1 --C-brewster 70 -o "$tmpdir/x.png"

# The margin: 5 % of the larger side around finite-element parts by default, as asked otherwise.
frame() { /usr/bin/python3 -c 'import json,sys; print(" ".join("%.4f" % v for v in json.load(open(sys.argv[1]))["frame_mm"]))' "$tmpdir/out"; }
expect_ok "margin 0" photoelastic "${nodes[@]}" --margin-pct 0 --size 8 -o "$tmpdir/j.png" --json
read -r x0 x1 y0 y1 <<<"$(frame)"
expect_ok "margin default" photoelastic "${nodes[@]}" --size 8 -o "$tmpdir/j.png" --json
read -r a0 a1 b0 b1 <<<"$(frame)"
awk -v x0="$x0" -v x1="$x1" -v a0="$a0" -v a1="$a1" -v y0="$y0" -v b0="$b0" 'BEGIN {
  d = 0.05 * (x1 - x0); e = x0 - a0; f = a1 - x1; g = y0 - b0
  if (d < 2 || (e - d) ^ 2 > 1e-6 || (f - d) ^ 2 > 1e-6 || (g - d) ^ 2 > 1e-6) { print "FAIL (default margin)", d, e, f, g; exit 1 } }' ||
  fails=$((fails + 1))
expect_error "margin and window" photoelastic "${nodes[@]}" --margin-pct 3 --window-mm 0,0,1,1 -o "$tmpdir/x.png"
finish
