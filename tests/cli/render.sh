#!/usr/bin/env bash
# biref render / diff / bench: bad scenes and paths give one error line; render + diff round trip;
# bench --json keys. Images are tiny to keep this fast.
set -u
. "$(dirname "$0")/lib.sh"
small=(--width 24 --height 14 --quiet)

expect_ok "render help" render --help
expect_grep "render help lists --method" "--method"
expect_ok "diff help" diff --help
expect_grep "diff help documents the scale" "white"
expect_ok "bench help" bench --help
expect_grep "bench help lists --max-seconds" "--max-seconds"

# A valid scene, then broken copies of it.
good=$tmpdir/good.json
cat >"$good" <<'JSON'
{"camera": {"position": [1.5, 1.2, 2.5], "look_at": [0, 0, 0], "fov_deg": 45, "width": 32, "height": 18},
 "slabs": [{"center": [0, 0, 0], "size": [2, 2], "thickness_um": 40, "normal": [0, 0, 1],
            "tangent": [1, 0, 0], "axis": [0.3, 0.6, 0.5], "eta_o": 1.54, "eta_e": 1.55}],
 "light": {"panel": {"center": [0, 0, -2], "size": [3, 3], "normal": [0, 0, 1], "radiance": 1},
           "polarization": {"type": "sp", "s": 0.1, "p": 0.9}},
 "filter": {"type": "s"}}
JSON
bad() { # bad NAME SED-EXPRESSION EXPECTED-FIELD
  sed -e "$2" "$good" >"$tmpdir/$1.json"
  expect_error "$1" render "$tmpdir/$1.json" -o "$tmpdir/$1.png" "${small[@]}"
  if ! grep -q "^biref render: error: $tmpdir/$1.json: $3" "$tmpdir/err"; then
    echo "FAIL ($1): error does not name $3:"; sed 's/^/  stderr: /' "$tmpdir/err"; fails=$((fails + 1))
  fi
  if [ -e "$tmpdir/$1.png" ]; then echo "FAIL ($1): output written"; fails=$((fails + 1)); fi
}
bad zero-thickness 's/"thickness_um": 40/"thickness_um": 0/' 'slabs\[0\].thickness_um: must be positive'
bad neg-eta 's/"eta_e": 1.55/"eta_e": -1.55/' 'slabs\[0\].eta_e'
bad zero-axis 's/"axis": \[0.3, 0.6, 0.5\]/"axis": [0, 0, 0]/' 'slabs\[0\].axis'
bad missing-normal 's/"normal": \[0, 0, 1\],//' 'slabs\[0\].normal: missing'
bad wrong-type 's/"fov_deg": 45/"fov_deg": "wide"/' 'camera.fov_deg'
bad zero-fov 's/"fov_deg": 45/"fov_deg": 0/' 'camera.fov_deg'
bad huge-width 's/"width": 32/"width": 1000000/' 'camera.width'
bad inf 's/"fov_deg": 45/"fov_deg": 1e999/' 'camera.fov_deg'
bad nan 's/"fov_deg": 45/"fov_deg": NaN/' 'scene: malformed JSON'
bad up-parallel 's/"fov_deg": 45/"up": [1.5, 1.2, 2.5], "fov_deg": 45/' 'camera.up'
bad inside-slab 's/"position": \[1.5, 1.2, 2.5\]/"position": [0.2, 0.1, 0]/' 'camera.position'
bad polarization 's/"type": "sp", "s": 0.1, "p": 0.9/"type": "circular"/' 'light.polarization.type'
bad filter 's/"type": "s"}}/"type": "q"}}/' 'filter.type'
bad unknown-field 's/"eta_o"/"eta_x": 1, "eta_o"/' 'slabs\[0\].eta_x: unknown field'
head -c 200 "$good" >"$tmpdir/trunc.json"
expect_error "truncated scene" render "$tmpdir/trunc.json" -o "$tmpdir/t.png" "${small[@]}"
expect_error "missing scene file" render "$tmpdir/nope.json" -o "$tmpdir/t.png"
expect_error "missing -o" render "$good"
expect_error "missing scene argument" render -o "$tmpdir/t.png"
expect_error "bad method" render "$good" -o "$tmpdir/t.png" --method magic
expect_error "samples without numeric" render "$good" -o "$tmpdir/t.png" --spectral-samples 8
expect_error "zero width" render "$good" -o "$tmpdir/t.png" --width 0
expect_error "bad threads" render "$good" -o "$tmpdir/t.png" --threads x
expect_error "unknown option" render "$good" -o "$tmpdir/t.png" --frobnicate
sed -e 's/"type": "sp", "s": 0.1, "p": 0.9/"type": "linear", "direction": [0, 1, 0]/' "$good" >"$tmpdir/wf.json"
expect_ok "world-fixed polarizer with analytic" render "$tmpdir/wf.json" -o "$tmpdir/wf.png" "${small[@]}"
expect_ok "world-fixed polarizer with numeric" render "$tmpdir/wf.json" -o "$tmpdir/wf.png" "${small[@]}" \
  --method numeric --spectral-samples 8
expect_ok "world-fixed polarizer with expansion" render "$tmpdir/wf.json" -o "$tmpdir/wf.png" "${small[@]}" \
  --method expansion
expect_ok "fig. 9c with a world-fixed analyzer at 45 degrees" render examples/fig9c_analyzer45.json \
  -o "$tmpdir/f45.png" "${small[@]}" --method expansion --order 2
expect_error "order without expansion" render "$good" -o "$tmpdir/t.png" "${small[@]}" --order 2
expect_error "order out of range" render "$good" -o "$tmpdir/t.png" "${small[@]}" --method expansion --order 9
expect_error "tolerance out of range" render "$good" -o "$tmpdir/t.png" "${small[@]}" --method expansion --tolerance 2

# Unwritable outputs: exit 1, one line, and nothing left behind.
rc=0; "$BIREF" render "$good" -o "$tmpdir/no/such/dir/x.png" "${small[@]}" >"$tmpdir/out" 2>"$tmpdir/err" || rc=$?
if [ "$rc" -ne 1 ] || [ "$(wc -l <"$tmpdir/err")" -ne 1 ]; then
  echo "FAIL (unwritable -o): rc=$rc"; sed 's/^/  stderr: /' "$tmpdir/err"; fails=$((fails + 1))
fi
mkdir "$tmpdir/adir"
rc=0; "$BIREF" render "$good" -o "$tmpdir/adir" "${small[@]}" >"$tmpdir/out" 2>"$tmpdir/err" || rc=$?
[ "$rc" -eq 1 ] || { echo "FAIL (-o is a directory): rc=$rc"; fails=$((fails + 1)); }
if ls "$tmpdir" | grep -q '\.tmp'; then echo "FAIL (temporary file left behind)"; fails=$((fails + 1)); fi

# Render, re-render with another thread count, diff: identical. A different method differs a little.
expect_ok "render writing PNG, PFM and JSON" render "$good" -o "$tmpdir/a.png" --threads 1 --quiet --json --pfm "$tmpdir/a.pfm"
expect_grep "render json mean_srgb" '"mean_srgb":'
expect_grep "render json ms" '"ms":'
[ -s "$tmpdir/a.pfm" ] || { echo "FAIL (no PFM)"; fails=$((fails + 1)); }
expect_ok "render 2 threads" render "$good" -o "$tmpdir/b.png" --threads 2 --quiet
expect_ok "diff identical" diff "$tmpdir/a.png" "$tmpdir/b.png" -o "$tmpdir/d.png" --json
expect_grep "identical: max 0" '"max":[[:space:]]*0[,}]?$'
[ -s "$tmpdir/d.png" ] || { echo "FAIL (no diff map)"; fails=$((fails + 1)); }
expect_ok "render numeric" render "$good" -o "$tmpdir/n.png" --method numeric --spectral-samples 16 --quiet
expect_ok "diff analytic vs numeric" diff "$tmpdir/a.png" "$tmpdir/n.png"
expect_grep "diff plain output" "95th percentile"
expect_ok "render smaller" render "$good" -o "$tmpdir/s.png" "${small[@]}"
expect_error "diff size mismatch" diff "$tmpdir/a.png" "$tmpdir/s.png"
expect_error "diff not a png" diff "$tmpdir/a.png" "$good"
expect_error "diff missing file" diff "$tmpdir/a.png" "$tmpdir/none.png"
expect_error "diff one argument" diff "$tmpdir/a.png"

# Anti-aliasing: prefilter is the default of the analytic method (json says so); none and
# --supersample work; the numeric methods refuse the prefilter; bad values are usage errors.
expect_ok "render default antialias" render "$good" -o "$tmpdir/p.png" "${small[@]}" --json
expect_grep "default is prefilter" '"antialias":[[:space:]]*"prefilter"'
expect_ok "render antialias none" render "$good" -o "$tmpdir/p.png" "${small[@]}" --antialias none --json
expect_grep "none in json" '"antialias":[[:space:]]*"none"'
expect_ok "render supersample" render "$good" -o "$tmpdir/p.png" "${small[@]}" --supersample 2 --json
expect_grep "supersample in json" '"supersample":[[:space:]]*2'
expect_ok "numeric defaults to none" render "$good" -o "$tmpdir/p.png" "${small[@]}" --method numeric --spectral-samples 8
expect_error "prefilter with numeric" render "$good" -o "$tmpdir/p.png" "${small[@]}" --method numeric --antialias prefilter
expect_error "bad antialias" render "$good" -o "$tmpdir/p.png" "${small[@]}" --antialias box
expect_error "supersample 0" render "$good" -o "$tmpdir/p.png" "${small[@]}" --supersample 0
expect_error "supersample too large" render "$good" -o "$tmpdir/p.png" "${small[@]}" --supersample 65
expect_ok "diff map without legend" diff "$tmpdir/a.png" "$tmpdir/b.png" -o "$tmpdir/d2.png" --no-legend

# --chroma-map: written with its statistics; a grey-lit slab without polarizers is nearly grey,
# the crossed polarizers of the fig. 9c scene are far from it; a bad path is one error line.
src=$(dirname "$0")/../..
expect_ok "chroma map" render "$src/examples/fig9b.json" -o "$tmpdir/c.png" --width 32 --height 18 --quiet \
  --chroma-map "$tmpdir/cm.png" --json
expect_grep "chroma map in json" '"chroma_map":'
expect_grep "fig9b nearly grey" '"p99":[[:space:]]*0\.'
[ -s "$tmpdir/cm.png" ] || { echo "FAIL (chroma map file)"; fails=$((fails + 1)); }
expect_ok "chroma map coloured" render "$src/examples/fig9c.json" -o "$tmpdir/c.png" --width 32 --height 18 --quiet \
  --chroma-map "$tmpdir/cm.png" --json
expect_grep "fig9c coloured" '"max":[[:space:]]*([1-9][0-9]|[4-9])'
expect_error "chroma map unwritable" render "$good" -o "$tmpdir/c.png" "${small[@]}" --chroma-map /nonexistent/cm.png

# bench: JSON keys, extrapolation under a tiny budget.
expect_ok "bench json" bench --scene "$good" --width 32 --height 18 --methods analytic,numeric-8 --max-seconds 2 --json
for key in width height threads methods method ms_per_frame ns_per_pixel extrapolated frames_timed first_frame_ms \
  first_frame_cpu_ms; do
  expect_grep "bench key $key" "\"$key\":"
done
expect_grep "bench antialias none by default" '"antialias":[[:space:]]*"none"'
# Whole frames after the first are timed (the budget allows them at this size); --frames 0 times
# the first alone; the gl backend needs a frame to time.
expect_ok "bench json again" bench --scene "$good" --width 32 --height 18 --methods analytic --json
expect_grep "bench times frames after the first" '"frames_timed":[[:space:]]*[1-9]'
expect_ok "bench first frame alone" bench --scene "$good" --width 32 --height 18 --methods analytic --frames 0 --json
expect_grep "bench frames 0" '"frames_timed":[[:space:]]*0,'
# A budget spent by the first frame (here the probe row is the whole frame) times no more frames.
expect_ok "bench budget spent" bench --scene "$good" --width 8 --height 1 --methods analytic --max-seconds 1e-9 --json
expect_grep "bench budget spent: no more frames" '"frames_timed":[[:space:]]*0,'
expect_error "bench gl without frames" bench --scene "$good" --width 32 --height 18 --methods analytic --backend gl \
  --frames 0
expect_ok "bench extrapolates" bench --scene "$good" --width 32 --height 18 --methods ground-truth \
  --max-seconds 0.001 --json
expect_grep "bench extrapolated true" '"extrapolated":[[:space:]]*true'
expect_ok "bench table" bench --scene "$good" --width 16 --height 8 --methods analytic,numeric-8
expect_grep "bench table title" "Spectral integration method"
expect_error "bench bad method" bench --scene "$good" --methods analytic,numeric-0
expect_error "bench unknown method" bench --scene "$good" --methods fast
expect_error "bench empty method" bench --scene "$good" --methods analytic,,numeric-8
expect_error "bench bad budget" bench --scene "$good" --max-seconds 0
# --antialias: the prefiltered analytic method times (numeric methods keep point look-ups).
expect_ok "bench prefilter" bench --scene "$good" --width 32 --height 18 --methods analytic,numeric-8 \
  --antialias prefilter --json
expect_grep "bench antialias prefilter" '"antialias":[[:space:]]*"prefilter"'
expect_error "bench bad antialias" bench --scene "$good" --antialias box
finish
