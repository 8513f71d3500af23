#!/usr/bin/env bash
# The OpenGL back-end (EGL, headless; Mesa's llvmpipe where there is no GPU) against the CPU
# renderer on every example scene at 320x180: mean dE00 <= 0.3 and 99th percentile <= 1, on
# the dispersive plates (examples/materials) mean <= 0.05, p99 <= 1, and analytic-pairs (u_pairs)
# on thin high-index plates between crossed polarizers, mean <= 0.02, p99 <= 0.25. A
# machine without EGL / OpenGL 4.3 fails this test: the back-end is part of the product.
set -u
. "$(dirname "$0")/lib.sh"


expect_error "unknown backend" render examples/fig9a.json -o "$tmpdir/x.png" --backend vulkan
expect_error "gl with a numeric method" render examples/fig9a.json -o "$tmpdir/x.png" --backend gl --method numeric
expect_error "bench unknown backend" bench --backend vulkan
# No usable EGL vendor: one line, exit 1, no output file.
rc=0
__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json "$BIREF" render examples/fig9a.json -o "$tmpdir/none.png" \
  --backend gl --width 32 --height 18 >"$tmpdir/out" 2>"$tmpdir/err" || rc=$?
if [ "$rc" -ne 1 ] || [ "$(wc -l <"$tmpdir/err")" -ne 1 ] || [ -e "$tmpdir/none.png" ] ||
   ! grep -q "^biref render: error: --backend gl: " "$tmpdir/err"; then
  echo "FAIL (no EGL vendor): rc=$rc"; sed 's/^/  stderr: /' "$tmpdir/err"; fails=$((fails + 1))
fi

# NAME SCENE MEAN P99 [options]: SCENE rendered on the CPU with point look-ups (the shader has
# no prefilter) and on the GL back-end, as $tmpdir/NAME-{cpu,gl}.png; GL takes no fallback
# evaluation and the two agree to dE00 mean <= MEAN, 99th percentile <= P99.
gl_against_cpu() {
  local name=$1 scene=$2 bound=$3 bound99=$4 mean p99
  shift 4
  expect_ok "$name cpu" render "$scene" -o "$tmpdir/$name-cpu.png" "$@" --quiet --antialias none
  expect_ok "$name gl" render "$scene" -o "$tmpdir/$name-gl.png" "$@" --backend gl --json
  [ "$(json_num fallback_evaluations "$tmpdir/out")" = 0 ] ||
    { echo "FAIL ($name): GL fallback evaluations"; fails=$((fails + 1)); }
  expect_ok "$name diff" diff "$tmpdir/$name-gl.png" "$tmpdir/$name-cpu.png" --json
  mean=$(json_num mean "$tmpdir/out")
  p99=$(json_num p99 "$tmpdir/out")
  echo "$name: gl vs cpu dE00 mean $mean, p99 $p99"
  awk -v m="$mean" -v p="$p99" -v b="$bound" -v b99="$bound99" \
    'BEGIN { exit !(m != "" && p != "" && m <= b + 0 && p <= b99 + 0) }' ||
    { echo "FAIL ($name): mean $mean > $bound or p99 $p99 > $bound99"; fails=$((fails + 1)); }
}

# Beyond the examples: thin slabs (the coherent regime: the exact integral of the closed form)
# and a dense surround with total reflection inside the slabs (evanescent legs).
sed -e 's/"thickness_um": 45/"thickness_um": 4/' -e 's/"thickness_um": 70/"thickness_um": 7/' \
    -e 's/"thickness_um": 110/"thickness_um": 11/' examples/default.json >"$tmpdir/thin.json"
sed -e 's/"eta": 1.0/"eta": 1.7/' examples/default.json >"$tmpdir/dense_surround.json"
for scene in examples/*.json "$tmpdir/thin.json" "$tmpdir/dense_surround.json"; do
  name=$(basename "$scene" .json)
  gl_against_cpu "$name" "$scene" 0.3 1.0 --width 320 --height 180
done

# Dispersive materials (docs/GPU.md "Dispersive materials"): the example plates (the lags on
# sub-band tangents; the quartz one also between world-fixed polarizers), a 2 um calcite plate (the coherent regime with n(lambda)) and, not under
# BIREF_TEST_QUICK, a 4 mm one (tangents that break: the exact integral). The exact integrals
# interpolate the Fresnel coefficients between band states on the GPU: measured mean dE00 <= 0.011,
# p99 <= 0.55; the plates agree to mean <= 0.001, p99 0.
sed -e 's/"thickness_um": 40/"thickness_um": 2/' examples/materials/calcite_plate.json >"$tmpdir/calcite_thin.json"
sed -e 's/"thickness_um": 40/"thickness_um": 4000/' examples/materials/calcite_plate.json >"$tmpdir/calcite_thick.json"
# World-fixed polarizer and analyzer (the general light's terms per node run).
sed -e 's/"type": "sp",/"type": "linear",/' -e 's/"s": 0.1,/"direction": [1, 0, 0]/' -e '/"p": 0.9/d' \
    -e 's/"type": "s"/"type": "linear", "direction": [0, 0.6, 0.8]/' examples/materials/quartz_plate.json \
    >"$tmpdir/quartz_world_fixed.json"
material_scenes="examples/materials/*.json $tmpdir/quartz_world_fixed.json $tmpdir/calcite_thin.json"
plate_size=(--width 320 --height 180)
[ -n "${BIREF_TEST_QUICK:-}" ] && plate_size=(--width 160 --height 90) # the sanitizers' CPU renders
[ -n "${BIREF_TEST_QUICK:-}" ] || material_scenes="$material_scenes $tmpdir/calcite_thick.json"
for scene in $material_scenes; do
  name=$(basename "$scene" .json)
  size=("${plate_size[@]}")
  [ "$name" = calcite_thin ] && size=(--width 160 --height 90)
  [ "$name" = calcite_thick ] && size=(--width 40 --height 24)
  [ "$name" = calcite_thin ] && [ -n "${BIREF_TEST_QUICK:-}" ] && size=(--width 64 --height 36)
  gl_against_cpu "$name" "$scene" 0.05 1.0 "${size[@]}"
done
# The bound sees dispersion: the calcite plate with its constant indices at 589 nm exceeds it.
sed 's/"material": "calcite"/"eta_o": 1.6584, "eta_e": 1.4864/' examples/materials/calcite_plate.json >"$tmpdir/calcite_const.json"
expect_ok "calcite constant gl" render "$tmpdir/calcite_const.json" -o "$tmpdir/calcite_const-gl.png" \
  "${plate_size[@]}" --backend gl
expect_ok "calcite constant diff" diff "$tmpdir/calcite_const-gl.png" "$tmpdir/calcite_plate-cpu.png" --json
mean=$(json_num mean "$tmpdir/out")
awk -v m="$mean" 'BEGIN { exit !(m > 0.05) }' || { echo "FAIL (the comparison does not see calcite's dispersion: $mean)"; fails=$((fails + 1)); }

# analytic-pairs: the shader's sibling and entry pairs (u_pairs) against the CPU's, where they change
# the colour most: the example's plates at 4, 6 and 9 um with eta 2.2 / 2.1 (strong internal
# reflection, first-order colours) between crossed polarizers. There the CPU's analytic-pairs is
# mean dE00 0.24 (p99 1.7) from its eq. 26, and GL agrees with it to mean 0.0001, p99 0. Wrong lags
# in the shader fail the bounds: the entry pairs' dd + du and dd - du swapped give mean 0.062, p99
# 0.58; two of the siblings' lags swapped, mean 0.094, p99 0.78.
sed -e 's/"eta_o": 1.544/"eta_o": 2.2/' -e 's/"eta_e": 1.553/"eta_e": 2.1/' -e 's/"thickness_um": 45/"thickness_um": 4/' \
    -e 's/"thickness_um": 70/"thickness_um": 6/' -e 's/"thickness_um": 110/"thickness_um": 9/' examples/default.json \
    >"$tmpdir/thin_high_index.json"
gl_against_cpu pairs "$tmpdir/thin_high_index.json" 0.02 0.25 --width 320 --height 180 --method analytic-pairs
# ... and the pairs are seen: eq. 26 on the CPU is far from both (GL honours --method).
expect_ok "pairs: eq. 26 cpu" render "$tmpdir/thin_high_index.json" -o "$tmpdir/pairs-eq26.png" --width 320 --height 180 \
  --quiet --antialias none
for got in cpu gl; do
  expect_ok "pairs: $got vs eq. 26" diff "$tmpdir/pairs-$got.png" "$tmpdir/pairs-eq26.png" --json
  mean=$(json_num mean "$tmpdir/out")
  awk -v m="$mean" 'BEGIN { exit !(m > 0.2) }' ||
    { echo "FAIL (pairs: $got analytic-pairs only $mean from eq. 26)"; fails=$((fails + 1)); }
done

# A test that cannot fail is a defect: a wrong scene (another thickness) must exceed the bounds.
sed -e 's/"thickness_mm": 1.15/"thickness_mm": 1.25/' examples/fig9c.json >"$tmpdir/other.json"
expect_ok "other gl" render "$tmpdir/other.json" -o "$tmpdir/other-gl.png" --width 320 --height 180 --backend gl
expect_ok "other diff" diff "$tmpdir/other-gl.png" "$tmpdir/fig9c-cpu.png" --json
mean=$(json_num mean "$tmpdir/out")
awk -v m="$mean" 'BEGIN { exit !(m > 0.3) }' || { echo "FAIL (the comparison does not see a 9% thicker slab: $mean)"; fails=$((fails + 1)); }

expect_ok "bench gl" bench --scene examples/fig9c.json --width 64 --height 36 --methods analytic --backend gl --frames 2 --json
expect_grep "bench gl backend" '"backend":[[:space:]]*"gl"'
expect_grep "bench gl gpu time" '"gpu_ms_per_frame":'
finish
