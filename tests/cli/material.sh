#!/usr/bin/env bash
# biref material and the dispersive-material options of slab and spectrum: exact JSON fields,
# extrapolation warned about, unphysical formulas and conflicting options refused with one line.
set -u
. "$(dirname "$0")/lib.sh"

expect_ok "help" material --help
expect_grep "help names the list" "material list"
expect_ok "list" material list
for m in calcite quartz sapphire rutile mgf2 yvo4 linbo3 bbo polycarbonate pmma; do
  expect_grep "list has $m" "^$m "
done
expect_ok "list json" material list --json
expect_grep "list json source" '"source":'
expect_ok "calcite json" material calcite --lambda-nm 589.3 --json
# Exactly the documented fields, in order.
keys=$(grep -oE '^[[:space:]]*"[a-z_]+":' "$tmpdir/out" | tr -d ' \t":' | tr '\n' ' ')
if [ "$keys" != "name lambda_nm n_o n_e n_o_group n_e_group source range_nm " ]; then
  echo "FAIL (material json fields): got '$keys'"
  fails=$((fails + 1))
fi
expect_grep "calcite n_o" '"n_o":[[:space:]]*1\.6583'
expect_grep "calcite n_e" '"n_e":[[:space:]]*1\.4861'
expect_ok "text" material rutile --lambda-nm 550
expect_grep "rutile group" "1\.49[0-9]+ x the phase birefringence"
# Outside the valid range: evaluated, one warning line.
"$BIREF" material rutile --lambda-nm 400 --json >"$tmpdir/out" 2>"$tmpdir/err" || { echo "FAIL (extrapolated: exit)"; fails=$((fails + 1)); }
grep -q "outside the valid range 430-1530 nm (extrapolated)" "$tmpdir/err" || { echo "FAIL (extrapolation warning)"; fails=$((fails + 1)); }
expect_error "unknown material" material unobtainium
expect_error "no argument" material
expect_error "two arguments" material calcite quartz
expect_error "list with lambda" material list --lambda-nm 500
expect_error "negative lambda" material calcite --lambda-nm -5
expect_error "repeated lambda" material calcite --lambda-nm 500 --lambda-nm 600
expect_error "pole at the wavelength" material rutile --lambda-nm 283.37

geo=(--axis 0.3,0.9,0.2 --thickness-um 50 --theta-deg 30)
expect_ok "slab with a material" slab --material calcite "${geo[@]}" --lambda-nm 450 --json
expect_grep "slab indices at 450 nm" '"eta_o":[[:space:]]*1\.6725'
expect_grep "slab names the material" '"name":[[:space:]]*"calcite"'
expect_ok "slab tmm with a material" slab --material quartz "${geo[@]}" --lambda-nm 450 --method tmm --json
expect_ok "slab with formulas" slab --sellmeier-o 1.0,0.01 --cauchy-e 1.5,0.004 "${geo[@]}" --json
expect_ok "slab with one formula and one constant" slab --eta-o 1.6 --cauchy-e 1.5,0.004 "${geo[@]}" --json
printf 'lambda_nm,n_o,n_e\n400,1.70,1.50\n700,1.66,1.48\n' >"$tmpdir/table.csv"
expect_ok "slab with a table" slab --dispersion-csv "$tmpdir/table.csv" "${geo[@]}" --json
expect_error "material and eta-o" slab --material calcite --eta-o 1.5 "${geo[@]}"
expect_error "two materials" slab --material calcite --material quartz "${geo[@]}"
expect_error "eta-o twice" slab --eta-o 1.5 --eta-o 1.6 --eta-e 1.5 "${geo[@]}"
expect_error "formula and eta for one index" slab --eta-o 1.5 --sellmeier-o 1,0.01 --eta-e 1.5 "${geo[@]}"
expect_error "unknown material" slab --material unobtainium "${geo[@]}"
expect_error "odd sellmeier" slab --sellmeier-o 1,0.01,2 --eta-e 1.5 "${geo[@]}"
expect_error "short cauchy" slab --cauchy-o 1.5 --eta-e 1.5 "${geo[@]}"
expect_error "missing n_e" slab --sellmeier-o 1,0.01 "${geo[@]}"
expect_error "pole at the wavelength" slab --sellmeier-o 1,0.25 --eta-e 1.5 "${geo[@]}" --lambda-nm 500
expect_error "n below 1" slab --cauchy-o 0.9,0.001 --eta-e 1.5 "${geo[@]}"
expect_error "missing table" slab --dispersion-csv "$tmpdir/none.csv" "${geo[@]}"
printf '400,1.70,1.50\n300,1.66,1.48\n' >"$tmpdir/bad.csv"
expect_error "decreasing table" slab --dispersion-csv "$tmpdir/bad.csv" "${geo[@]}"

expect_ok "spectrum numeric with a material" spectrum --material rutile --axis 0.3,0.9,0.2 --thickness-um 10 \
  --method numeric --spectral-samples 128 --json
expect_grep "spectrum names the material" '"name":[[:space:]]*"rutile"'
expect_grep "spectrum extrapolated part" '"extrapolated_nm":[[:space:]]*\[\[380, 430\]\]'
expect_ok "spectrum general light with a material" spectrum --material calcite "${geo[@]}" --method numeric \
  --polarizer linear:45 --analyzer linear:-45
expect_ok "spectrum analytic with a material" spectrum --material calcite "${geo[@]}" --json
expect_grep "analytic with a material" '"method":[[:space:]]*"analytic"'
expect_ok "spectrum expansion with a material" spectrum --material calcite "${geo[@]}" --method expansion
expect_error "spectrum pole in the band" spectrum --sellmeier-o 1,0.25 --eta-e 1.5 "${geo[@]}" --method numeric
# Scenes: "material" in place of eta_o/eta_e, refused where it cannot be honoured.
expect_ok "render a rutile plate" render examples/materials/rutile_plate.json -o "$tmpdir/rutile.png" \
  --width 32 --height 18 -q
[ -s "$tmpdir/rutile.png" ] || { echo "FAIL: rutile.png missing"; fails=$((fails + 1)); }
# The GL backend renders them (tests/cli/gl.sh); the browser viewer's data module does not take them.
expect_error "gl-data refuses a material" gl-data -o "$tmpdir/m.js" examples/materials/rutile_plate.json
[ ! -e "$tmpdir/m.js" ] || { echo "FAIL: gl-data wrote a module for a material scene"; fails=$((fails + 1)); }
sed 's/"material": "rutile"/"material": "rutile", "eta_o": 2.6/' examples/materials/rutile_plate.json >"$tmpdir/both.json"
expect_error "scene with material and eta_o" render "$tmpdir/both.json" -o "$tmpdir/both.png"
sed 's/"material": "rutile"/"material": "unobtainium"/' examples/materials/rutile_plate.json >"$tmpdir/unknown.json"
expect_error "scene with an unknown material" render "$tmpdir/unknown.json" -o "$tmpdir/unknown.png"
finish
