#!/usr/bin/env bash
# biref accuracy on a tiny configuration (θ = 0, 40, 80°, two azimuths, a 256-sample reference):
# the JSON, CSV and markdown outputs carry their documented parts; bad input fails cleanly.
set -u
. "$(dirname "$0")/lib.sh"
tiny=(--theta-max-deg 80 --theta-step-deg 40 --azimuths 2 --samples-ref 256 --samples-check 512 --threads 2)

expect_ok "help" accuracy --help
expect_grep "help lists options" "--samples-ref"

expect_ok "tiny json" accuracy "${tiny[@]}" --sweep-delta-eps 0.2 --json \
  --csv "$tmpdir/acc.csv" --markdown "$tmpdir/acc.md"
for key in config materials summary per_theta near_axis psi_max_deg acceptance criterion elapsed_s \
           theta_deg low high low_chromatic near_axis_chromatic near_axis_up reached_up frac_over_1 phi0; do
  expect_grep "key $key" "\"$key\":"
done
for method in analytic numeric-8 numeric-32 numeric-128 ref-vs-check analytic-vs-check; do
  expect_grep "method $method" "\"$method\":"
done
for name in '"a"' '"b"' '"c"' '"a:de\+0.2"' '"c:de\+0.2"'; do
  expect_grep "material $name" "\"name\":[[:space:]]*$name"
done
expect_grep "reference samples" '"samples_ref":[[:space:]]*256,'
expect_grep "sweep variant knows its base" '"base":[[:space:]]*"b"'

if ! head -1 "$tmpdir/acc.csv" | grep -q '^material,base,delta_eps,which,method,theta_deg,mean_de00,max_de00,phi0_de00,n_azimuths$'; then
  echo "FAIL (csv header)"
  fails=$((fails + 1))
fi
# 6 materials x 3 angles x 4 methods x (T, R), plus the 2 check comparisons x (T, R) of the 3 base
# materials at every angle (the check step rounds up to one angle step).
rows=$(($(wc -l <"$tmpdir/acc.csv") - 1))
if [ "$rows" -ne $((6 * 3 * 4 * 2 + 3 * 3 * 2 * 2)) ]; then
  echo "FAIL (csv rows): $rows"
  fails=$((fails + 1))
fi
for section in "Acceptance" "Near the optic axis" "| up |" "reference converged" "sweep" "Per angle"; do
  if ! grep -q "$section" "$tmpdir/acc.md"; then
    echo "FAIL (markdown section $section)"
    fails=$((fails + 1))
  fi
done

cat >"$tmpdir/mat.json" <<'JSON'
{"materials": [{"name": "quartz", "eta_o": 1.544, "eta_e": 1.553, "axis": [0, 1, 0.2],
                "thickness_um": 50, "polarization": "s", "analyzer": "p"}]}
JSON
expect_ok "materials file" accuracy "${tiny[@]}" --sweep-delta-eps none --materials "$tmpdir/mat.json"
expect_grep "markdown on stdout" "quartz"
expect_grep "file light" "100% s / 0% p, analyzer p"

expect_error "zero azimuths" accuracy "${tiny[@]}" --azimuths 0
expect_error "theta max 90" accuracy "${tiny[@]}" --theta-max-deg 90
expect_error "theta step 0" accuracy "${tiny[@]}" --theta-step-deg 0
expect_error "theta step nan" accuracy "${tiny[@]}" --theta-step-deg nan
expect_error "zero reference samples" accuracy "${tiny[@]}" --samples-ref 0
expect_error "negative check samples" accuracy "${tiny[@]}" --samples-check -1
expect_error "zero threads" accuracy "${tiny[@]}" --threads 0
expect_error "sweep gives eps_e <= 0" accuracy "${tiny[@]}" --sweep-delta-eps -5
expect_error "sweep garbage" accuracy "${tiny[@]}" --sweep-delta-eps 0.1,,0.2
expect_error "unknown cmf" accuracy "${tiny[@]}" --cmf nope
expect_error "inverted range" accuracy "${tiny[@]}" --range-nm 700,380
expect_error "missing materials file" accuracy "${tiny[@]}" --materials "$tmpdir/none.json"
echo '{"materials": [' >"$tmpdir/bad.json"
expect_error "materials file not JSON" accuracy "${tiny[@]}" --materials "$tmpdir/bad.json"
echo '[{"name": "x", "eta_e": 1.5, "axis": [0, 1, 0], "thickness_mm": 1}]' >"$tmpdir/bad.json"
expect_error "material without eta_o" accuracy "${tiny[@]}" --materials "$tmpdir/bad.json"
echo '[{"name": "x", "eta_o": 1.5, "eta_e": 1.5, "axis": [0, 0, 0], "thickness_mm": 1}]' >"$tmpdir/bad.json"
expect_error "material with zero axis" accuracy "${tiny[@]}" --materials "$tmpdir/bad.json"
echo '[{"name": "x", "eta_o": 1.5, "eta_e": 1.5, "axis": [0, 1, 0], "thickness_mm": 1, "thickness_um": 1}]' \
  >"$tmpdir/bad.json"
expect_error "material with two thicknesses" accuracy "${tiny[@]}" --materials "$tmpdir/bad.json"
echo '[{"name": "x", "eta_o": 1.5, "eta_e": 1.5, "axis": [0, 1, 0], "thickness_mm": 1, "analyzer": "q"}]' \
  >"$tmpdir/bad.json"
expect_error "material with bad analyzer" accuracy "${tiny[@]}" --materials "$tmpdir/bad.json"
expect_error "unwritable csv" accuracy "${tiny[@]}" --csv "$tmpdir/no/such/dir.csv"
expect_error "unknown option" accuracy "${tiny[@]}" --frobnicate
expect_error "stray argument" accuracy "${tiny[@]}" extra
finish
