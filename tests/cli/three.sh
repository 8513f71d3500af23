#!/usr/bin/env bash
# The three.js package (web/three): its fig. 9c example page in headless Chromium (SwiftShader)
# against `biref render` of examples/fig9c.json at 320x180, mean dE00 <= 0.5 and 99th percentile
# <= 2, and a CPU render of a changed slab outside those bounds (the comparison can fail); the
# same page with method=analytic-pairs on a thin high-index plate against the CPU's analytic-pairs,
# and outside the bounds of its eq. 26; the
# mesh examples drawn without a WebGL error; `npm pack`'s tarball installed into an application
# outside the repository, imported by Node (properties, refused values, shader injection) and
# drawn by a page there (no page under BIREF_TEST_QUICK, the sanitizer run: they run no C code). Needs web/three/node_modules (scripts/install-deps.sh runs npm ci),
# Node, npm and Chromium; without them it fails.
set -u
. "$(dirname "$0")/lib.sh"
W=320 H=180
pkg=web/three

if [ ! -f $pkg/node_modules/three/build/three.module.js ]; then
  echo "FAIL: $pkg/node_modules/three is missing: run scripts/install-deps.sh (npm ci in $pkg)"
  exit 1
fi
# The package's copy of the library data (web/biref_data.js, checked by web.sh) is made fresh.
node $pkg/scripts/build-data.mjs || { echo "FAIL: build-data"; exit 1; }

# npm pack, then an application outside the repository with the tarball in its node_modules
# (extracted as npm would install it; three linked from the package's own install: no network).
app="$tmpdir/app"
mkdir -p "$app/node_modules"
tgz=$(cd $pkg && npm pack --offline --silent --pack-destination "$tmpdir" 2>"$tmpdir/pack.err" | tail -1)
if [ -z "$tgz" ] || [ ! -f "$tmpdir/$tgz" ]; then
  echo "FAIL: npm pack:"; sed 's/^/  /' "$tmpdir/pack.err" | head -5; fails=$((fails + 1))
else
  tar -xzf "$tmpdir/$tgz" -C "$tmpdir"
  for f in package.json src/index.js src/BirefringentMaterial.js src/biref_data.js; do
    [ -f "$tmpdir/package/$f" ] || { echo "FAIL: the packed package has no $f"; fails=$((fails + 1)); }
  done
  if tar -tzf "$tmpdir/$tgz" | grep -Eq 'node_modules|examples/'; then
    echo "FAIL: the packed package carries node_modules or the examples"; fails=$((fails + 1))
  fi
  mv "$tmpdir/package" "$app/node_modules/biref-three"
  ln -s "$PWD/$pkg/node_modules/three" "$app/node_modules/three"
  cp tests/web/three-app/index.html tests/web/three-app/app.js tests/web/three_package.mjs "$app/"
  (cd "$app" && node three_package.mjs) >"$tmpdir/node.out" 2>&1 ||
    { echo "FAIL: Node import of the packed package:"; sed 's/^/  /' "$tmpdir/node.out" | head -8; fails=$((fails + 1)); }
fi

expect_ok "fig9c cpu" render examples/fig9c.json -o "$tmpdir/fig9c-cpu.png" --width $W --height $H --quiet --antialias none
# The same slab 9 % thicker: the three.js picture of fig9c must be far from it.
sed -e 's/"thickness_mm": 1.15/"thickness_mm": 1.25/' examples/fig9c.json >"$tmpdir/changed.json"
expect_ok "changed cpu" render "$tmpdir/changed.json" -o "$tmpdir/changed-cpu.png" --width $W --height $H --quiet \
  --antialias none

# analytic-pairs (the material's method, the shader's u_pairs): the fig. 9c plate made 6 um thick with
# eta_o 2.2, where the pairs change the colour most (the CPU's analytic-pairs is mean dE00 1.26, p99
# 4.0 from its eq. 26). A uniform: the page reuses the program compiled for the first one.
sed -e 's/"thickness_mm": 1.15/"thickness_um": 6/' -e 's/"eta_o": 1.775/"eta_o": 2.2/' examples/fig9c.json >"$tmpdir/pairs.json"
for m in analytic analytic-pairs; do
  expect_ok "pairs scene cpu $m" render "$tmpdir/pairs.json" -o "$tmpdir/pairs-cpu-$m.png" --width $W --height $H \
    --quiet --antialias none --method $m
done

url="file://$PWD/$pkg/examples/index.html"
pages=("$url?example=fig9c&width=$W&height=$H&view=canvas" "$tmpdir/fig9c-three.png"
       "$url?example=fig9c&width=$W&height=$H&view=canvas&thickness_um=6&eta_o=2.2&method=analytic-pairs"
       "$tmpdir/pairs-three.png")
# Every mesh example (one page, one renderer: each program compiled once; small, as the
# compile dominates) and the application
# outside the repository, drawn without a WebGL error. They exercise no C code: the quick
# (sanitizer) run leaves them out.
if [ -z "${BIREF_TEST_QUICK:-}" ]; then
  pages+=("$url?example=all&width=80&height=45&view=canvas" "$tmpdir/meshes.png")
  [ -f "$app/index.html" ] && pages+=("file://$app/index.html" "$tmpdir/app.png")
fi
# The pages run no C code either: the sanitizer run stops after the CPU renders above; the -Werror
# run draws and checks every page.
if [ -n "${BIREF_TEST_QUICK:-}" ]; then
  finish
  exit
fi
# page_vs_cpu LABEL PAGE CPU near|far FAILURE: the dE00 of a page's screenshot against a CPU render;
# near: mean <= 0.5 and p99 <= 2 (the same picture), far: beyond either (a different one); FAILURE
# says what a failure means.
page_vs_cpu() {
  expect_ok "$1 diff" diff "$2" "$3" --json
  local mean p99
  mean=$(json_num mean "$tmpdir/out") p99=$(json_num p99 "$tmpdir/out")
  echo "$1: three.js vs cpu dE00 mean $mean, p99 $p99"
  if [ "$4" = near ]; then
    awk -v m="$mean" -v p="$p99" 'BEGIN { exit !(m != "" && p != "" && m <= 0.5 && p <= 2.0) }' ||
      { echo "FAIL ($1: $5): mean $mean > 0.5 or p99 $p99 > 2"; fails=$((fails + 1)); }
  else
    awk -v m="$mean" -v p="$p99" 'BEGIN { exit !(m > 0.5 || p > 2.0) }' ||
      { echo "FAIL ($1: $5): mean $mean, p99 $p99"; fails=$((fails + 1)); }
  fi
}
if ! /usr/bin/python3 tests/web/screenshot.py $W $H "${pages[@]}" 2>"$tmpdir/shot.err"; then
  echo "FAIL: pages:"; sed 's/^/  /' "$tmpdir/shot.err"; fails=$((fails + 1))
else
  page_vs_cpu fig9c "$tmpdir/fig9c-three.png" "$tmpdir/fig9c-cpu.png" near "the page differs from the cpu"
  page_vs_cpu changed "$tmpdir/fig9c-three.png" "$tmpdir/changed-cpu.png" far \
    "the comparison does not see a 9 % thicker slab"
  page_vs_cpu analytic-pairs "$tmpdir/pairs-three.png" "$tmpdir/pairs-cpu-analytic-pairs.png" near \
    "the page differs from the cpu"
  page_vs_cpu "pairs vs eq. 26" "$tmpdir/pairs-three.png" "$tmpdir/pairs-cpu-analytic.png" far \
    "the page's analytic-pairs is within the bounds of eq. 26: method ignored?"
fi
finish
