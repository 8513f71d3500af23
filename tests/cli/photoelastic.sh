#!/usr/bin/env bash
# biref photoelastic: pictures, profiles against the closed form, JSON keys, determinism across
# threads, the card example, and one-line errors for bad options and malformed stress grids.
set -u
. "$(dirname "$0")/lib.sh"
small=(--size 48)

expect_ok "help" photoelastic --help
expect_grep "help lists --stress-grid" "--stress-grid"
expect_grep "help lists --profile" "--profile"

# Pictures of every preset, both polariscopes, both lights.
for preset in disk hole beam; do
  expect_ok "$preset white circular" photoelastic --preset "$preset" "${small[@]}" -o "$tmpdir/$preset.png"
  expect_ok "$preset mono plane" photoelastic --preset "$preset" --polariscope plane --polarizer linear:30 \
    --light mono --lambda-nm 546 --tint "${small[@]}" -o "$tmpdir/$preset-mono.png"
done
for f in disk hole beam disk-mono; do
  if [ "$(head -c 4 "$tmpdir/$f.png" | od -An -c | tr -d ' ')" != "211PNG" ]; then
    echo "FAIL ($f.png is not a PNG)"; fails=$((fails + 1))
  fi
done

# Determinism: the picture does not depend on the thread count.
expect_ok "threads 1" photoelastic --preset hole --tension-deg 30 --size 40 --threads 1 -o "$tmpdir/t1.png"
expect_ok "threads 2" photoelastic --preset hole --tension-deg 30 --size 40 --threads 2 -o "$tmpdir/t2.png"
cmp -s "$tmpdir/t1.png" "$tmpdir/t2.png" || { echo "FAIL (threads change the picture)"; fails=$((fails + 1)); }

# Oblique view: the picture is foreshortened (square pixels), and the JSON records the tilt.
expect_ok "tilted disk" photoelastic --preset disk --tilt-deg 60 --size 40 -o "$tmpdir/tilt.png" --json
expect_grep "tilted height" '"height":[[:space:]]*20,'
expect_grep "tilt in json" '"tilt_deg":[[:space:]]*60'
expect_ok "tilted mono profile" photoelastic --preset hole --tilt-deg 30 --light mono --profile -20,10,20,10 --profile-points 5

# Profile along the disk's vertical diameter, monochromatic, index-matched surround (no
# reflections): N = 4 C P R / (pi lambda (R^2 - y^2)) and dark circular intensity sin^2(pi N).
expect_ok "disk profile" photoelastic --preset disk --radius-mm 20 --load-N 400 --material epoxy --eta-i 1.57 \
  --light mono --lambda-nm 589 --profile 0,-18,0,18 --profile-points 37
awk -v C=50e-12 -v P=400 -v R=0.02 -v lam=589e-9 '
  /^#/ { next }
  { y = $2 * 1e-3; N = 4 * C * P * R / (3.141592653589793 * lam * (R * R - y * y));
    s = sin(3.141592653589793 * N); n++;
    if (($8 - N) ^ 2 > (1e-6 * N) ^ 2) { print "FAIL (fringe order at y = " $2 ": " $8 " vs " N ")"; bad++ }
    if (($9 - s * s) ^ 2 > 1e-12) { print "FAIL (intensity at y = " $2 ": " $9 " vs " s * s ")"; bad++ } }
  END { if (n != 37) { print "FAIL (profile has " n " rows)"; bad++ } exit bad > 0 }' "$tmpdir/out" ||
  fails=$((fails + 1))

# JSON: white-light fringe orders are quoted at 550 nm; outside points have nulls.
expect_ok "json profile" photoelastic --preset hole --profile -30,0,30,0 --profile-points 7 --json
expect_grep "json fringe lambda" '"fringe_order_lambda_nm":[[:space:]]*550'
expect_grep "json note" 'fringe_order_note'
expect_grep "json retardation" '"retardation_nm":'
expect_grep "json outside" '"retardation_nm":[[:space:]]*null'
expect_ok "json picture" photoelastic --preset beam "${small[@]}" -o "$tmpdir/b.png" --json
expect_grep "json picture keys" '"ms":'

# A stress grid: the card example (Flamant load on the edge), and a disk sampled on a grid
# renders like the closed form.
bash "$(dirname "$0")/../../examples/photoelastic/card_stress.sh" "$tmpdir/card.csv" 300 0.76 2.0 ||
  { echo "FAIL (card_stress.sh)"; fails=$((fails + 1)); }
expect_ok "card picture" photoelastic --stress-grid "$tmpdir/card.csv" --thickness-mm 0.76 \
  --polariscope plane --polarizer linear:0 "${small[@]}" -o "$tmpdir/card.png"
expect_ok "example csv" photoelastic --stress-grid "$(dirname "$0")/../../examples/photoelastic/gradient.csv" \
  "${small[@]}" -o "$tmpdir/g.png"

# Malformed stress grids: exit 2 and one line that names the line of the file.
H='x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa'
csv_error() { # NAME EXPECTED-MESSAGE CONTENT
  printf '%b' "$3" >"$tmpdir/$1.csv"
  expect_error "csv $1" photoelastic --stress-grid "$tmpdir/$1.csv" -o "$tmpdir/$1.png" "${small[@]}"
  if ! grep -q -- "$2" "$tmpdir/err"; then
    echo "FAIL (csv $1): message lacks '$2':"; sed 's/^/  stderr: /' "$tmpdir/err"; fails=$((fails + 1))
  fi
  if [ -e "$tmpdir/$1.png" ]; then echo "FAIL (csv $1): picture written"; fails=$((fails + 1)); fi
}
csv_error missing-column "line 1: the header lacks column txy_MPa" 'x_mm,y_mm,sxx_MPa,syy_MPa\n0,0,1,2\n'
csv_error non-numeric "line 3, column syy_MPa: not a number: 'x'" "$H\n0,0,1,2,3\n1,0,1,x,3\n0,1,1,2,3\n1,1,1,2,3\n"
csv_error nan "line 4, column sxx_MPa: not a finite number: 'nan'" "$H\n0,0,1,2,3\n1,0,1,2,3\n0,1,nan,2,3\n1,1,1,2,3\n"
csv_error irregular "line 3: x_mm = 1 follows 0 with a gap of 1, but other values are 0.5 apart" \
  "$H\n0,0,1,2,3\n1,0,1,2,3\n1.5,0,1,2,3\n0,1,1,2,3\n1,1,1,2,3\n1.5,1,1,2,3\n"
csv_error too-few "line 4: the file ends after 3 data rows" "$H\n0,0,1,2,3\n1,0,1,2,3\n0,1,1,2,3\n"
csv_error truncated "line 5: truncated row (2 of 5 fields" "$H\n0,0,1,2,3\n1,0,1,2,3\n0,1,1,2,3\n1,1"
csv_error no-header "line 1: expected the header" "0,0,1,2,3\n"
csv_error empty "empty file" ""
expect_error "missing csv" photoelastic --stress-grid "$tmpdir/none.csv" -o "$tmpdir/none.png"
grep -q "cannot read" "$tmpdir/err" || { echo "FAIL (missing csv message)"; fails=$((fails + 1)); }

# Bad usage.
expect_error "no specimen" photoelastic -o "$tmpdir/x.png"
expect_error "two specimens" photoelastic --preset disk --preset hole -o "$tmpdir/x.png"
expect_error "unknown preset" photoelastic --preset cube -o "$tmpdir/x.png"
expect_error "option of another preset" photoelastic --preset hole --load-N 5 -o "$tmpdir/x.png"
grep -q -- "--load-N does not apply to hole" "$tmpdir/err" || { echo "FAIL (foreign option message)"; fails=$((fails + 1)); }
expect_error "grid with preset options" photoelastic --stress-grid "$tmpdir/card.csv" --radius-mm 3 -o "$tmpdir/x.png"
expect_error "unknown material" photoelastic --preset disk --material steel -o "$tmpdir/x.png"
expect_error "negative C" photoelastic --preset disk --C-brewster -3 -o "$tmpdir/x.png"
expect_error "n0 below 1" photoelastic --preset disk --n0 0.5 -o "$tmpdir/x.png"
expect_error "zero thickness" photoelastic --preset disk --thickness-mm 0 -o "$tmpdir/x.png"
expect_error "hole larger than plate" photoelastic --preset hole --radius-mm 40 -o "$tmpdir/x.png"
expect_error "negative load" photoelastic --preset disk --load-N -5 -o "$tmpdir/x.png"
expect_error "lambda with white" photoelastic --preset disk --lambda-nm 589 -o "$tmpdir/x.png"
expect_error "tint with white" photoelastic --preset disk --tint -o "$tmpdir/x.png"
expect_error "tint in the infrared" photoelastic --preset disk --light mono --lambda-nm 900 --tint -o "$tmpdir/x.png"
# Anti-aliasing: pictures are prefiltered by default (a normal view), --antialias none samples the
# fringes at points and gives a different picture; the option is refused where it does not apply.
expect_ok "prefiltered by default" photoelastic --preset disk --size 64 -o "$tmpdir/aa_default.png" --json
expect_grep "default reported" '"antialias":[[:space:]]*"prefilter"'
expect_ok "explicit prefilter" photoelastic --preset disk --size 64 --antialias prefilter -o "$tmpdir/aa_pre.png"
expect_ok "point sampling" photoelastic --preset disk --size 64 --antialias none -o "$tmpdir/aa_none.png" --json
expect_grep "none reported" '"antialias":[[:space:]]*"none"'
cmp -s "$tmpdir/aa_default.png" "$tmpdir/aa_pre.png" || { echo "FAIL (default is not the prefilter)"; fails=$((fails + 1)); }
cmp -s "$tmpdir/aa_pre.png" "$tmpdir/aa_none.png" && { echo "FAIL (--antialias none changes nothing)"; fails=$((fails + 1)); }
expect_error "bad antialias" photoelastic --preset disk --antialias box -o "$tmpdir/x.png"
expect_error "antialias with a map" photoelastic --preset disk --antialias none --map fringe-order -o "$tmpdir/x.pfm"
expect_error "antialias with a tilt" photoelastic --preset disk --antialias prefilter --tilt-deg 20 -o "$tmpdir/x.png"

expect_error "bad polariscope" photoelastic --preset disk --polariscope elliptic -o "$tmpdir/x.png"
expect_error "bad field" photoelastic --preset disk --field grey -o "$tmpdir/x.png"
expect_error "bad light" photoelastic --preset disk --light laser -o "$tmpdir/x.png"
expect_error "nothing to do" photoelastic --preset disk
expect_error "bad profile" photoelastic --preset disk --profile 1,2,3
expect_error "samples without profile" photoelastic --preset disk --profile-points 5 -o "$tmpdir/x.png"
expect_error "size zero" photoelastic --preset disk --size 0 -o "$tmpdir/x.png"
expect_error "tilt too large" photoelastic --preset disk --tilt-deg 85 -o "$tmpdir/x.png"
expect_error "bad view" photoelastic --preset disk --window-mm 1,0,1,1 -o "$tmpdir/x.png"
expect_error "unknown option" photoelastic --preset disk --frobnicate -o "$tmpdir/x.png"
# Dispersion of birefringence: alpha 0 is the default picture exactly; another alpha changes the
# colours and is reported; out-of-range values and tilted white views with alpha are refused.
expect_ok "alpha default" photoelastic --preset beam --size 48 -o "$tmpdir/alpha_default.png"
expect_ok "alpha 0" photoelastic --preset beam --size 48 --dispersion-alpha 0 -o "$tmpdir/alpha0.png"
expect_ok "alpha 0.4" photoelastic --preset beam --size 48 --dispersion-alpha 0.4 -o "$tmpdir/alpha04.png" --json
expect_grep "alpha reported" '"dispersion_alpha":[[:space:]]*0.4'
"$BIREF" diff "$tmpdir/alpha_default.png" "$tmpdir/alpha0.png" --json | grep -Eq '"max":[[:space:]]*0[,}]' ||
  { echo "FAIL (--dispersion-alpha 0 is not the default picture)"; fails=$((fails + 1)); }
"$BIREF" diff "$tmpdir/alpha0.png" "$tmpdir/alpha04.png" --json | grep -Eq '"max":[[:space:]]*0[,}]' &&
  { echo "FAIL (--dispersion-alpha 0.4 changes nothing)"; fails=$((fails + 1)); }
expect_ok "alpha mono tilted" photoelastic --preset disk --size 24 --light mono --tilt-deg 20 --dispersion-alpha 0.3 \
  -o "$tmpdir/alpha_tilt.png"
expect_error "alpha tilted white" photoelastic --preset disk --size 24 --tilt-deg 20 --dispersion-alpha 0.3 -o "$tmpdir/x.png"
expect_error "alpha out of range" photoelastic --preset disk --dispersion-alpha 5 -o "$tmpdir/x.png"
expect_error "alpha nan" photoelastic --preset disk --dispersion-alpha nan -o "$tmpdir/x.png"
expect_error "stray argument" photoelastic --preset disk extra -o "$tmpdir/x.png"
expect_error "unwritable output" photoelastic --preset disk -o "$tmpdir/no/such/dir/x.png"
[ -e "$tmpdir/x.png" ] && { echo "FAIL (a picture was written by a failing call)"; fails=$((fails + 1)); }

finish
