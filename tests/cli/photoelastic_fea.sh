#!/usr/bin/env bash
# biref photoelastic --stress-nodes: an unstructured node export of the disk renders to the fringes
# of --preset disk; column mapping, units and the boundary; one-line errors naming row and column.
set -u
. "$(dirname "$0")/lib.sh"
ex=examples/photoelastic
cols=(--columns sxx=S11,syy=S22,txy=S12)

expect_ok "help lists --stress-nodes" photoelastic --help
expect_grep "help" "--stress-nodes"
expect_ok "example nodes" photoelastic --stress-nodes "$ex/disk_nodes.csv" "${cols[@]}" --boundary "$ex/disk_boundary.csv" \
  --size 48 -o "$tmpdir/ex.png"
expect_grep "wrote" "wrote .*ex.png: 48 x 48"

# The disk from scattered nodes (0.5 mm lattice, graded at the loads) against the closed form:
# fringe order within 0.01 in the interior (r <= 0.9 R, at least 0.4 R from the load points).
bash "$ex/disk_nodes.sh" "$tmpdir/n.csv" "$tmpdir/b.csv" 0.5
common=(--light mono --lambda-nm 589 --size 160 --window-mm -25,-25,25,25 --map fringe-order)
expect_ok "nodes map" photoelastic --stress-nodes "$tmpdir/n.csv" "${cols[@]}" --boundary "$tmpdir/b.csv" "${common[@]}" \
  -o "$tmpdir/n_map.csv"
expect_ok "preset map" photoelastic --preset disk "${common[@]}" -o "$tmpdir/p_map.csv"
paste -d, "$tmpdir/n_map.csv" "$tmpdir/p_map.csv" | awk -F, '
  NR == 1 { next }
  { x = $1; y = $2; r = sqrt(x * x + y * y); d1 = sqrt(x * x + (y - 25) ^ 2); d2 = sqrt(x * x + (y + 25) ^ 2)
    if (r > 22.5 || d1 < 10 || d2 < 10) next
    if ($3 == "nan" || $6 == "nan") { bad++; next }
    n++; d = $3 - $6; if (d < 0) d = -d; if (d > m) m = d }
  END { printf "interior pixels %d, max |dN| %.4f\n", n, m
        if (n < 10000 || m > 0.01 || bad) { print "FAIL (nodes vs closed form)"; exit 1 } }' || fails=$((fails + 1))

# The same nodes in metres and pascals give the same map.
awk -F, 'NR == 1 { print; next } { printf "%s,%.9g,%.9g,%s,%.9g,%.9g,%.9g,%s\n", $1, $2 / 1000, $3 / 1000, $4, $5 * 1e6, $6 * 1e6, $7 * 1e6, $8 }' \
  "$ex/disk_nodes.csv" > "$tmpdir/si.csv"
expect_ok "mm MPa" photoelastic --stress-nodes "$ex/disk_nodes.csv" "${cols[@]}" --size 40 --map retardation -o "$tmpdir/a.csv"
expect_ok "m Pa" photoelastic --stress-nodes "$tmpdir/si.csv" "${cols[@]}" --length-unit m --stress-unit Pa --size 40 \
  --map retardation -o "$tmpdir/b.csv"
paste -d, "$tmpdir/a.csv" "$tmpdir/b.csv" | awk -F, 'NR > 1 && $3 != "nan" { n++; d = $3 - $6; if (d < 0) d = -d; if (d > 1e-3 * ($3 > 1 ? $3 : 1)) bad++ }
  END { if (bad || n < 1000) { print "FAIL (units change the map, or " n + 0 " pixels with material)"; exit 1 } }' || fails=$((fails + 1))

# Outside the boundary: NaN in maps.
printf 'x,y\n-10,-10\n10,-10\n10,10\n-10,10\n' > "$tmpdir/sq.csv"
expect_ok "square boundary" photoelastic --stress-nodes "$ex/disk_nodes.csv" "${cols[@]}" --boundary "$tmpdir/sq.csv" \
  --size 50 --map sigma1 -o "$tmpdir/sq_map.csv"
awk -F, 'NR > 1 { ins = ($1 > -9.5 && $1 < 9.5 && $2 > -9.5 && $2 < 9.5); out = ($1 < -10.5 || $1 > 10.5 || $2 < -10.5 || $2 > 10.5)
  if (ins && $3 == "nan") bad++; if (out && $3 != "nan") bad++; n_in += ins; n_out += out }
  END { if (bad || n_in < 100 || n_out < 100) { print "FAIL (boundary mask)"; exit 1 } }' \
  "$tmpdir/sq_map.csv" || fails=$((fails + 1))

# Errors: one line, naming the row and column.
printf 'node,x,y,s11,s22,s12\n1,0,0,1,2,3\n2,1,0,1,2,3\n3,0,1,1,2,3\n' > "$tmpdir/fea.csv"
expect_error "unmapped columns" photoelastic --stress-nodes "$tmpdir/fea.csv" -o "$tmpdir/x.png"
grep -q "no column 'sxx' for sxx" "$tmpdir/err" || { echo "FAIL (unmapped message)"; fails=$((fails + 1)); }
expect_ok "mapped columns" photoelastic --stress-nodes "$tmpdir/fea.csv" --columns sxx=s11,syy=s22,txy=s12 --size 8 -o "$tmpdir/x.png"
printf 'node,x,y,s11,s22,s12\n1,0,0,1,2,3\n2,1,0,1,oops,3\n3,0,1,1,2,3\n' > "$tmpdir/bad.csv"
expect_error "bad value" photoelastic --stress-nodes "$tmpdir/bad.csv" --columns sxx=s11,syy=s22,txy=s12 -o "$tmpdir/x.png"
grep -q "line 3, column s22 (syy): not a number: 'oops'" "$tmpdir/err" || { echo "FAIL (row/column message)"; cat "$tmpdir/err"; fails=$((fails + 1)); }
expect_error "bad role" photoelastic --stress-nodes "$tmpdir/fea.csv" --columns sxy=s12 -o "$tmpdir/x.png"
expect_error "bad unit" photoelastic --stress-nodes "$tmpdir/fea.csv" --length-unit inch -o "$tmpdir/x.png"
expect_error "columns without nodes" photoelastic --preset disk --columns sxx=a -o "$tmpdir/x.png"
expect_error "two fields" photoelastic --preset disk --stress-nodes "$tmpdir/fea.csv" -o "$tmpdir/x.png"
expect_error "missing file" photoelastic --stress-nodes "$tmpdir/none.csv" -o "$tmpdir/x.png"
cp "$tmpdir/fea.csv" "$tmpdir/same.csv"
expect_error "output over the input" photoelastic --stress-nodes "$tmpdir/same.csv" --columns sxx=s11,syy=s22,txy=s12 \
  --map isoclinic -o "$tmpdir/same.csv"
expect_error "bad map" photoelastic --preset disk --map stress -o "$tmpdir/x.pfm"
expect_error "map extension" photoelastic --preset disk --map isoclinic -o "$tmpdir/x.png"
finish
