#!/usr/bin/env bash
# Scenes whose slabs are stacks ("layers"): a one-layer stack slab renders as the plain slab (dE00
# statistics; exact with the numeric method), the tape-art scene renders with no failed evaluation,
# every malformed stack slab is refused with one line naming its JSON path, and the GL back-end and
# gl-data refuse stacks.
set -u
. "$(dirname "$0")/lib.sh"

# plain.json: the scene at 96x54; one_layer.json: its slab written as a one-layer stack.
one_layer() { # one_layer SCENE PREFIX
  python3 - "$1" "$tmpdir/$2" <<'PY'
import json, sys
sc = json.load(open(sys.argv[1]))
sc["camera"]["width"], sc["camera"]["height"] = 96, 54
json.dump(sc, open(sys.argv[2] + "_plain.json", "w"))
sl = sc["slabs"][0]
sl["layers"] = [{k: sl.pop(k) for k in ("eta_o", "eta_e", "axis", "thickness_mm")}]
json.dump(sc, open(sys.argv[2] + "_stack.json", "w"))
PY
}

# same DESCRIPTION A.png B.png MEAN MAX: dE00 statistics of the two images within the bounds.
same() {
  "$BIREF" diff "$2" "$3" --json >"$tmpdir/diff.json" || { echo "FAIL ($1): diff failed"; fails=$((fails + 1)); return; }
  python3 - "$tmpdir/diff.json" "$4" "$5" "$1" <<'PY' || fails=$((fails + 1))
import json, sys
d = json.load(open(sys.argv[1]))
if not (d["mean"] <= float(sys.argv[2]) and d["max"] <= float(sys.argv[3])):
    print(f"FAIL ({sys.argv[4]}): dE00 mean {d['mean']:.4g} max {d['max']:.4g}")
    sys.exit(1)
PY
}

# s/p light through an s filter (fig. 9c) and world-fixed polarizers (analyzer at 45 deg).
for scene in fig9c fig9c_analyzer45; do
  one_layer "examples/$scene.json" "$scene"
  for m in numeric expansion; do
    for kind in plain stack; do
      expect_ok "$scene $kind $m" render "$tmpdir/${scene}_$kind.json" -o "$tmpdir/${scene}_${kind}_$m.png" \
        --method "$m" --antialias none --json
      expect_grep "$scene $kind $m: no failed evaluation" '"fallback_evaluations":[[:space:]]*0,'
    done
  done
  expect_grep "$scene stack slab counted" '"stack_slabs":[[:space:]]*1,'
  same "$scene one-layer stack = slab, numeric" "$tmpdir/${scene}_plain_numeric.png" "$tmpdir/${scene}_stack_numeric.png" 0 0
  same "$scene one-layer stack = slab, expansion" "$tmpdir/${scene}_plain_expansion.png" \
    "$tmpdir/${scene}_stack_expansion.png" 0.01 1.5
done

# A stack layer of a dispersive material: the quartz plate of examples/materials written as a
# one-layer stack renders as the plain material slab with the numeric method (n(λ) per sample in
# both), and as two halves; a material layer outside its band is refused with its path.
python3 - "$tmpdir" <<'PY'
import json, sys
sc = json.load(open("examples/materials/quartz_plate.json"))
sc["camera"]["width"], sc["camera"]["height"] = 48, 27
json.dump(sc, open(sys.argv[1] + "/quartz_plain.json", "w"))
sl = sc["slabs"][0]
layer = {k: sl.pop(k) for k in ("material", "axis", "thickness_um")}
sl["layers"] = [layer]
json.dump(sc, open(sys.argv[1] + "/quartz_stack.json", "w"))
sl["layers"] = [dict(layer, thickness_um=layer["thickness_um"] / 2)] * 2
json.dump(sc, open(sys.argv[1] + "/quartz_halves.json", "w"))
PY
for kind in plain stack halves; do
  expect_ok "quartz $kind numeric" render "$tmpdir/quartz_$kind.json" -o "$tmpdir/quartz_$kind.png" --method numeric \
    --antialias none --json
  expect_grep "quartz $kind: no failed evaluation" '"fallback_evaluations":[[:space:]]*0,'
done
same "quartz one-layer stack = material slab, numeric" "$tmpdir/quartz_plain.png" "$tmpdir/quartz_stack.png" 0 0
same "quartz halves = one layer, numeric" "$tmpdir/quartz_stack.png" "$tmpdir/quartz_halves.png" 0.001 0.01
cp "$tmpdir/quartz_stack.json" "$tmpdir/quartz_bad.json"
python3 - "$tmpdir/quartz_bad.json" <<'PY'
import json, sys
sc = json.load(open(sys.argv[1]))
sc["slabs"][0]["layers"][0]["material"] = "unobtainium"
json.dump(sc, open(sys.argv[1], "w"))
PY
expect_error "unknown layer material" render "$tmpdir/quartz_bad.json" -o "$tmpdir/bad.png"
grep -q "slabs\[0\]\.layers\[0\]\.material: unknown material" "$tmpdir/err" ||
  { echo "FAIL (unknown layer material: the message names its path)"; fails=$((fails + 1)); }

# Layer order: [A, B] seen from the +normal side is [B, A] seen with the normal flipped (local z
# flips with it: an axis (x, y, z) becomes (x, -y, -z)).
python3 - "$tmpdir" <<'PY'
import json, sys
sc = json.load(open("examples/fig9c.json"))
sc["camera"]["width"], sc["camera"]["height"] = 64, 36
A = {"eta_o": 1.55, "eta_e": 1.6, "axis": [0.3, 0.5, 0.8], "thickness_um": 20}
B = {"eta_o": 1.6, "eta_e": 1.5, "axis": [0.9, -0.1, 0.2], "thickness_um": 35}
flip = lambda l: dict(l, axis=[l["axis"][0], -l["axis"][1], -l["axis"][2]])
sl = sc["slabs"][0]
for k in ("eta_o", "eta_e", "axis", "thickness_mm"):
    sl.pop(k)
sl["layers"] = [A, B]
json.dump(sc, open(sys.argv[1] + "/ab.json", "w"))
sl["normal"] = [0, -1, 0]
sl["layers"] = [flip(B), flip(A)]
json.dump(sc, open(sys.argv[1] + "/ba.json", "w"))
PY
expect_ok "two layers" render "$tmpdir/ab.json" -o "$tmpdir/ab.png" --method numeric
expect_ok "two layers flipped" render "$tmpdir/ba.json" -o "$tmpdir/ba.png" --method numeric
same "layer order follows the normal" "$tmpdir/ab.png" "$tmpdir/ba.png" 1e-9 1e-9

# The tape-art scene: every pane a stack; the analytic method renders stacks by their expansion.
expect_ok "tape art numeric" render examples/stack_scenes/tape_art.json -o "$tmpdir/tape.png" --width 64 --height 48 \
  --method numeric --json
expect_grep "tape art: no failed evaluation" '"fallback_evaluations":[[:space:]]*0,'
expect_grep "tape art: 16 stack slabs" '"stack_slabs":[[:space:]]*16,'
expect_ok "tape art analytic" render examples/stack_scenes/tape_art.json -o "$tmpdir/tape_a.png" --width 24 --height 18 --json
expect_grep "analytic renders stacks by the expansion" '"stack_method":[[:space:]]*"expansion"'
expect_grep "tape art analytic: no failed evaluation" '"fallback_evaluations":[[:space:]]*0,'
expect_ok "plain scene" render "$tmpdir/fig9c_plain.json" -o "$tmpdir/p.png" --json
expect_grep "no stack method without stacks" '"stack_method":[[:space:]]*null'

# bad DESCRIPTION FIELD JSON-OF-SLAB-0: the scene with slab 0 replaced must be refused with one
# line naming FIELD.
bad() {
  python3 - "$tmpdir/bad.json" "$3" <<'PY'
import json, sys
sc = json.load(open("examples/stack_scenes/tape_art.json"))
sc["slabs"][0] = dict({"center": [0, 0, 0], "size": [1, 1], "normal": [0, 0, 1]}, **json.loads(sys.argv[2]))
json.dump(sc, open(sys.argv[1], "w"))
PY
  expect_error "$1" render "$tmpdir/bad.json" -o "$tmpdir/bad.png"
  grep -q "$2" "$tmpdir/err" || { echo "FAIL ($1): error does not name $2"; cat "$tmpdir/err"; fails=$((fails + 1)); }
}
L='{"eta_o": 1.5, "eta_e": 1.51, "azimuth_deg": 45, "thickness_um": 27}'
bad "layers with eta_o" 'slabs\[0\].eta_o' "{\"layers\": [$L], \"eta_o\": 1.5}"
bad "layers with a thickness" 'slabs\[0\].thickness_um' "{\"layers\": [$L], \"thickness_um\": 5}"
bad "layers with an axis" 'slabs\[0\].axis' "{\"layers\": [$L], \"axis\": [0, 1, 0]}"
bad "layers with a material" 'slabs\[0\].material' "{\"layers\": [$L], \"material\": \"quartz\"}"
bad "empty layers" 'slabs\[0\].layers' '{"layers": []}'
bad "layers not an array" 'slabs\[0\].layers' '{"layers": {"eta": 1.5}}'
bad "layer without thickness" 'slabs\[0\].layers\[1\].thickness_um' "{\"layers\": [$L, {\"eta\": 1.5}]}"
bad "layer with an unknown key" 'slabs\[0\].layers\[0\].colour' '{"layers": [{"eta": 1.5, "thickness_um": 1, "colour": 1}]}'
bad "isotropic layer with an axis" 'slabs\[0\].layers\[0\].axis' '{"layers": [{"eta": 1.5, "axis": [0,1,0], "thickness_um": 1}]}'
bad "negative layer index" 'slabs\[0\].layers\[0\].eta_e' '{"layers": [{"eta_o": 1.5, "eta_e": -1, "azimuth_deg": 0, "thickness_um": 1}]}'
bad "stack slab without normal" 'slabs\[0\].normal' "{\"layers\": [$L], \"normal\": null}"
python3 -c 'import json; L = {"eta": 1.5, "thickness_um": 1}; print(json.dumps([L] * 65))' >"$tmpdir/many"
bad "too many layers" 'slabs\[0\].layers' "{\"layers\": $(cat "$tmpdir/many")}"

expect_error "prefilter with stacks" render examples/stack_scenes/tape_art.json -o "$tmpdir/x.png" --antialias prefilter
grep -q "supersample" "$tmpdir/err" || { echo "FAIL (prefilter refusal names the remedy)"; fails=$((fails + 1)); }
expect_error "GL back-end refuses stacks" render examples/stack_scenes/tape_art.json -o "$tmpdir/x.png" --backend gl
grep -q "slabs\[0\] is a stack" "$tmpdir/err" || { echo "FAIL (GL refusal names the slab)"; fails=$((fails + 1)); }
expect_error "gl-data refuses stacks" gl-data examples/fig9c.json examples/stack_scenes/tape_art.json -o "$tmpdir/x.js"
grep -q "tape_art.json: slabs\[0\] is a stack" "$tmpdir/err" || { echo "FAIL (gl-data refusal)"; fails=$((fails + 1)); }
[ ! -e "$tmpdir/x.js" ] || { echo "FAIL (gl-data wrote a file)"; fails=$((fails + 1)); }
finish
