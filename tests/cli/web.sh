#!/usr/bin/env bash
# The WebGL2 viewer (web/index.html) in headless Chromium (SwiftShader, no GPU needed): a
# screenshot of each example preset against the CPU renderer at 320x180, mean dE00 <= 0.3 and
# 99th percentile <= 1; a slab changed through the page's controls against the CPU render of the
# changed scene; method=analytic-pairs against the CPU's analytic-pairs where it differs from eq. 26.
# Also: web/biref_data.js is what `biref gl-data` makes now, and the shader
# compiles as GLSL ES 3.00 and as desktop GLSL 4.30 with the reference compiler. A machine
# without Chromium or glslangValidator fails this test.
# Under BIREF_TEST_QUICK (the sanitizer run) no page is drawn: the pages run no C code.
set -u
. "$(dirname "$0")/lib.sh"
W=320 H=180

# check_close NAME GOT.png REF.png: within the thresholds.
check_close() {
  expect_ok "$1 diff" diff "$2" "$3" --json
  local mean p99
  mean=$(json_num mean "$tmpdir/out") p99=$(json_num p99 "$tmpdir/out")
  echo "$1: browser vs cpu dE00 mean $mean, p99 $p99"
  awk -v m="$mean" -v p="$p99" 'BEGIN { exit !(m != "" && p != "" && m <= 0.3 && p <= 1.0) }' ||
    { echo "FAIL ($1): mean $mean > 0.3 or p99 $p99 > 1"; fails=$((fails + 1)); }
}

# The committed data module is the library's current output.
expect_ok "gl-data" gl-data -o "$tmpdir/biref_data.js" examples/*.json
cmp -s "$tmpdir/biref_data.js" web/biref_data.js ||
  { echo "FAIL: web/biref_data.js is stale: run  biref gl-data -o web/biref_data.js examples/*.json"; fails=$((fails + 1)); }
expect_error "gl-data without scenes" gl-data -o "$tmpdir/x.js"

# One source, two dialects.
for dialect in es desktop; do
  if [ $dialect = es ]; then
    prelude='#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\n'
  else
    prelude='#version 430 core\n'
  fi
  for stage in vert frag; do
    defs='#define BIREF_VERTEX\n'
    [ $stage = frag ] && defs='#define BIREF_FRAGMENT\n#define BIREF_SCENE\n#define BIREF_OUTPUT_SRGB\n#define BIREF_MAX_SLABS 8\n#define BIREF_MAX_PANELS 4\n'
    { printf "$prelude$defs"; cat shaders/biref_analytic.glsl; } >"$tmpdir/s.$stage"
    glslangValidator "$tmpdir/s.$stage" >"$tmpdir/glslang.log" 2>&1 ||
      { echo "FAIL: the shader does not compile as $dialect $stage:"; head -5 "$tmpdir/glslang.log"; fails=$((fails + 1)); }
  done
  # The per-hit part for another renderer, with dispersive materials (BIREF_MATERIALS).
  { printf "$prelude#define BIREF_MATERIALS\n"; cat shaders/biref_analytic.glsl
    printf 'out vec4 o;\nvoid main() { BirefLight L; L.pol_linear = 0.0; L.filter_linear = 0.0; L.pol_w = vec2(0.5);\n'
    printf '  L.mask = vec2(1.0); vec3 T, R; bool ok = biref_shade_material(vec3(0.0, -1.0, 0.0), vec3(0.0, 1.0, 0.0),\n'
    printf '  vec3(1.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0), 0, 40000.0, 1.0, L, T, R); o = vec4(T + R, ok ? 1.0 : 0.0); }\n'
  } >"$tmpdir/m.frag"
  glslangValidator "$tmpdir/m.frag" >"$tmpdir/glslang.log" 2>&1 ||
    { echo "FAIL: the shader with BIREF_MATERIALS does not compile as $dialect:"; head -5 "$tmpdir/glslang.log"; fails=$((fails + 1)); }
done

url="file://$PWD/web/index.html"
pages=()
for scene in examples/*.json; do
  name=$(basename "$scene" .json)
  method=()
  grep -q '"linear"' "$scene" && method=(--method expansion)
  # The shader has no prefilter: compare with the CPU's point look-ups.
  expect_ok "$name cpu" render "$scene" -o "$tmpdir/$name-cpu.png" --width $W --height $H --quiet "${method[@]}" \
    --antialias none
  pages+=("$url?scene=$name&width=$W&height=$H&view=canvas" "$tmpdir/$name-web.png")
done
# Controls: a thicker fig. 9c slab with another index, set through the page's sliders.
sed -e 's/"thickness_mm": 1.15/"thickness_mm": 1.25/' -e 's/"eta_o": 1.775/"eta_o": 1.7/' examples/fig9c.json >"$tmpdir/changed.json"
expect_ok "changed cpu" render "$tmpdir/changed.json" -o "$tmpdir/changed-cpu.png" --width $W --height $H --quiet \
  --antialias none
pages+=("$url?scene=fig9c&width=$W&height=$H&view=canvas&thickness_um=1250&eta_o=1.7" "$tmpdir/changed-web.png")

# A thin slab through the controls: the coherent regime (exact integral of the closed form).
sed -e 's/"thickness_um": 45/"thickness_um": 4/' examples/default.json >"$tmpdir/thin.json"
expect_ok "thin cpu" render "$tmpdir/thin.json" -o "$tmpdir/thin-cpu.png" --width $W --height $H --quiet
pages+=("$url?scene=default&width=$W&height=$H&view=canvas&thickness_um=4" "$tmpdir/thin-web.png")

# analytic-pairs (the shader's u_pairs) from the query: fig. 9c made a 6 um plate with eta_o 2.2,
# where the pairs change the colour most (the CPU's analytic-pairs is mean dE00 1.26, p99 4.0 from
# its eq. 26).
sed -e 's/"thickness_mm": 1.15/"thickness_um": 6/' -e 's/"eta_o": 1.775/"eta_o": 2.2/' examples/fig9c.json >"$tmpdir/pairs.json"
for m in analytic analytic-pairs; do
  expect_ok "pairs scene cpu $m" render "$tmpdir/pairs.json" -o "$tmpdir/pairs-cpu-$m.png" --width $W --height $H \
    --quiet --antialias none --method $m
done
pages+=("$url?scene=fig9c&width=$W&height=$H&view=canvas&thickness_um=6&eta_o=2.2&method=analytic-pairs" "$tmpdir/pairs-web.png")

# The pages run no C code: the sanitizer run (BIREF_TEST_QUICK) stops after the CPU renders above;
# the -Werror run draws and checks every page.
if [ -n "${BIREF_TEST_QUICK:-}" ]; then
  finish
  exit
fi
if ! /usr/bin/python3 tests/web/screenshot.py $W $H "${pages[@]}" 2>"$tmpdir/shot.err"; then
  echo "FAIL: screenshots:"; sed 's/^/  /' "$tmpdir/shot.err"; fails=$((fails + 1))
else
  for scene in examples/*.json; do
    name=$(basename "$scene" .json)
    check_close "$name" "$tmpdir/$name-web.png" "$tmpdir/$name-cpu.png"
  done
  check_close "changed through the controls" "$tmpdir/changed-web.png" "$tmpdir/changed-cpu.png"
  check_close "thin slab through the controls" "$tmpdir/thin-web.png" "$tmpdir/thin-cpu.png"
  check_close "analytic-pairs from the query" "$tmpdir/pairs-web.png" "$tmpdir/pairs-cpu-analytic-pairs.png"
  expect_ok "analytic-pairs vs eq. 26" diff "$tmpdir/pairs-web.png" "$tmpdir/pairs-cpu-analytic.png" --json
  mean=$(json_num mean "$tmpdir/out")
  awk -v m="$mean" 'BEGIN { exit !(m > 0.3) }' ||
    { echo "FAIL (the page's analytic-pairs is only $mean from eq. 26: method ignored?)"; fails=$((fails + 1)); }
  # ... and the comparison can fail: the changed page is far from the unchanged scene.
  expect_ok "changed vs unchanged" diff "$tmpdir/changed-web.png" "$tmpdir/fig9c-cpu.png" --json
  mean=$(json_num mean "$tmpdir/out")
  awk -v m="$mean" 'BEGIN { exit !(m > 0.3) }' || { echo "FAIL (the comparison does not see the change: $mean)"; fails=$((fails + 1)); }
fi
# Every query value is checked before anything is drawn: a bad one is an error shown in the page
# (and in the title), never "biref ready" on a blank, default or clamped canvas, nor an uncaught
# exception with nothing shown.
errs=(
  "$url?scene=__proto__" "unknown scene '__proto__'"
  "$url?scene=constructor&view=canvas" "unknown scene 'constructor'"
  "$url?scene=fig9c&width=0&height=10&view=canvas" "width: expected an integer from 1 to 4096, got '0'"
  "$url?scene=fig9c&width=-5" "width: expected an integer"
  "$url?scene=fig9c&width=abc" "width: expected an integer"
  "$url?scene=fig9c&width=1e9" "width: expected an integer"
  "$url?scene=fig9c&height=5000" "height: expected an integer from 1 to 4096"
  "$url?scene=fig9c&eta_o=9" "eta_o: expected a number from 1.2 to 2.5, got '9'"
  "$url?scene=fig9c&thickness_um=0x10" "thickness_um: expected a number"
  "$url?scene=fig9c&axis_tilt=%2010" "axis_tilt: expected a number"
  "$url?scene=fig9c&view=gallery" "view: expected canvas"
  "$url?scene=fig9c&widht=10" "unknown query key 'widht'"
  "$url?scene=fig9c&method=numeric" "method: expected analytic or analytic-pairs (the shader's methods), got 'numeric'"
  "$url?scene=fig9c&method=Analytic" "method: expected analytic or analytic-pairs"
  "$url?scene=fig9c&method=analytic&method=analytic-pairs" "query key 'method' given twice"
  "$url?scene=fig9c&width=10&width=20" "query key 'width' given twice"
)
if ! /usr/bin/python3 tests/web/screenshot.py $W $H --timeout 60 --errors "${errs[@]}" 2>"$tmpdir/errs.err"; then
  echo "FAIL: query errors:"; sed 's/^/  /' "$tmpdir/errs.err"; fails=$((fails + 1))
fi
finish
