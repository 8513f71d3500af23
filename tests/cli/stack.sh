#!/usr/bin/env bash
# biref stack: a one-layer stack file gives biref slab's numbers (1e-12); every bad input gives one
# error line and a non-zero exit.
set -u
. "$(dirname "$0")/lib.sh"
ex=$(dirname "$0")/../../examples/stacks

expect_ok "help" stack --help
expect_grep "help lists options" "--lambda-nm"
expect_ok "json" stack "$ex/solc_folded.json" --theta-deg 20 --lambda-nm 550 --json
expect_grep "T present" '"T":'
expect_grep "jones_R present" '"jones_R":'
expect_ok "tmm" stack "$ex/film_on_glass.json" --method tmm --json
expect_grep "tmm method" '"method":[[:space:]]*"tmm"'
expect_ok "table" stack "$ex/cellophane3.json" --theta-deg 40
expect_grep "table energy" "Energy check"

cat >"$tmpdir/one.json" <<'JSON'
{"eta_i": 1.2, "layers": [{"eta_o": 1.5, "eta_e": 1.6, "axis": [0.3, 0.5, 0.8], "thickness_um": 10}]}
JSON
"$BIREF" stack "$tmpdir/one.json" --theta-deg 30 --lambda-nm 550 --json >"$tmpdir/stack.json"
"$BIREF" slab --eta-o 1.5 --eta-e 1.6 --axis 0.3,0.5,0.8 --thickness-um 10 --eta-i 1.2 --theta-deg 30 \
  --lambda-nm 550 --json >"$tmpdir/slab.json"
python3 - "$tmpdir/stack.json" "$tmpdir/slab.json" <<'PY' || fails=$((fails + 1))
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
worst = 0.0
for key in ("T", "R", "jones_T", "jones_R"):
    for i in "sp":
        for o in "sp":
            x, y = a[key][i][o], b[key][i][o]
            x, y = (x if isinstance(x, list) else [x]), (y if isinstance(y, list) else [y])
            worst = max(worst, max(abs(u - v) for u, v in zip(x, y)))
if worst > 1e-12:
    print(f"FAIL (one-layer stack vs slab): worst difference {worst:.3g}")
    sys.exit(1)
PY

bad() { # bad DESCRIPTION JSON: a stack file that must be refused
  printf '%s\n' "$2" >"$tmpdir/bad.json"
  expect_error "$1" stack "$tmpdir/bad.json"
}
bad "not json" '{"layers": ['
bad "no layers" '{"eta_i": 1}'
bad "empty layers" '{"layers": []}'
bad "unknown key" '{"layers": [{"eta": 1.5, "thickness_um": 1}], "extra": 1}'
bad "repeated key" '{"layers": [{"eta": 1.5, "eta": 1.6, "thickness_um": 1}]}'
bad "no thickness" '{"layers": [{"eta": 1.5}]}'
bad "two thicknesses" '{"layers": [{"eta": 1.5, "thickness_um": 1, "thickness_nm": 5}]}'
bad "negative index" '{"layers": [{"eta_o": -1.5, "eta_e": 1.6, "axis": [0,0,1], "thickness_um": 1}]}'
bad "zero axis" '{"layers": [{"eta_o": 1.5, "eta_e": 1.6, "axis": [0,0,0], "thickness_um": 1}]}'
bad "axis and azimuth" '{"layers": [{"eta_o": 1.5, "eta_e": 1.6, "axis": [0,0,1], "azimuth_deg": 3, "thickness_um": 1}]}'
bad "isotropic with axis" '{"layers": [{"eta": 1.5, "axis": [0,0,1], "thickness_um": 1}]}'
bad "zero eta_i" '{"eta_i": 0, "layers": [{"eta": 1.5, "thickness_um": 1}]}'
python3 -c 'import json; print(json.dumps({"layers": [{"eta": 1.5, "thickness_um": 1}] * 65}))' >"$tmpdir/many.json"
expect_error "too many layers" stack "$tmpdir/many.json"
expect_error "missing file argument" stack
expect_error "unreadable file" stack "$tmpdir/none.json"
expect_error "two files" stack "$ex/cellophane3.json" "$ex/cellophane3.json"
expect_error "theta 90" stack "$ex/cellophane3.json" --theta-deg 90
expect_error "lambda zero" stack "$ex/cellophane3.json" --lambda-nm 0
expect_error "lambda nan" stack "$ex/cellophane3.json" --lambda-nm nan
expect_error "unknown method" stack "$ex/cellophane3.json" --method magic

# biref spectrum --stack: the expansion by default, numeric and ground truth on request; a one-layer
# stack's numeric colours are the slab's; conflicting options are refused.
expect_ok "spectrum --stack" spectrum --stack "$ex/cellophane3.json" --polarization s --analyzer p --json
expect_grep "stack spectrum method" '"method":[[:space:]]*"expansion"'
expect_grep "stack spectrum groups" '"groups":'
expect_ok "spectrum --stack fallback reported" spectrum --stack "$ex/cellophane3.json" --theta-deg 60 --json
expect_grep "fallback reason" '"reason":[[:space:]]*"too many path groups"'
expect_ok "spectrum --stack ground truth" spectrum --stack "$ex/lyot_stage1.json" --method ground-truth
expect_grep "ground truth samples" "16384 samples"
"$BIREF" spectrum --stack "$tmpdir/one.json" --theta-deg 30 --method numeric --spectral-samples 256 --json \
  >"$tmpdir/sstack.json"
"$BIREF" spectrum --eta-o 1.5 --eta-e 1.6 --axis 0.3,0.5,0.8 --thickness-um 10 --eta-i 1.2 --theta-deg 30 \
  --method numeric --spectral-samples 256 --json >"$tmpdir/sslab.json"
python3 - "$tmpdir/sstack.json" "$tmpdir/sslab.json" <<'PY' || fails=$((fails + 1))
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
worst = max(abs(u - v) for d in ("T", "R") for i in "sp" for o in "sp" for u, v in zip(a[d][i][o], b[d][i][o]))
worst = max(worst, max(abs(u - v) for u, v in zip(a["mixed"]["T_xyz"], b["mixed"]["T_xyz"])))
if worst > 1e-12:
    print(f"FAIL (one-layer stack spectrum vs slab): worst difference {worst:.3g}")
    sys.exit(1)
PY
# Layers of a dispersive material: a one-layer quartz stack is biref slab --material quartz at
# every wavelength (1e-12); its numeric colours are the slab's; the material's fallback is reported.
cat >"$tmpdir/quartz.json" <<'JSON'
{"eta_i": 1.2, "layers": [{"material": "quartz", "axis": [0.3, 0.5, 0.8], "thickness_um": 40}]}
JSON
for lam in 400 550 690; do
  "$BIREF" stack "$tmpdir/quartz.json" --theta-deg 30 --lambda-nm $lam --json >"$tmpdir/qstack.json"
  "$BIREF" slab --material quartz --axis 0.3,0.5,0.8 --thickness-um 40 --eta-i 1.2 --theta-deg 30 \
    --lambda-nm $lam --json >"$tmpdir/qslab.json"
  python3 - "$tmpdir/qstack.json" "$tmpdir/qslab.json" $lam <<'PY' || fails=$((fails + 1))
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
worst = 0.0
for key in ("T", "R", "jones_T", "jones_R"):
    for i in "sp":
        for o in "sp":
            x, y = a[key][i][o], b[key][i][o]
            x, y = (x if isinstance(x, list) else [x]), (y if isinstance(y, list) else [y])
            worst = max(worst, max(abs(u - v) for u, v in zip(x, y)))
if worst > 1e-12 or a["input"]["layers"][0]["material"] != "quartz":
    print(f"FAIL (one-layer quartz stack vs slab --material at {sys.argv[3]} nm): worst difference {worst:.3g}")
    sys.exit(1)
PY
done
"$BIREF" spectrum --stack "$tmpdir/quartz.json" --theta-deg 30 --method numeric --spectral-samples 256 --json \
  >"$tmpdir/qsstack.json"
"$BIREF" spectrum --material quartz --axis 0.3,0.5,0.8 --thickness-um 40 --eta-i 1.2 --theta-deg 30 \
  --method numeric --spectral-samples 256 --json >"$tmpdir/qsslab.json"
python3 - "$tmpdir/qsstack.json" "$tmpdir/qsslab.json" <<'PY' || fails=$((fails + 1))
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
worst = max(abs(u - v) for d in ("T", "R") for i in "sp" for o in "sp" for u, v in zip(a[d][i][o], b[d][i][o]))
if worst > 1e-12:
    print(f"FAIL (one-layer quartz stack spectrum vs slab --material): worst difference {worst:.3g}")
    sys.exit(1)
PY
expect_ok "dispersive stack expansion" spectrum --stack "$ex/quartz_zero_order_halfwave.json" --json
expect_grep "dispersive stack expanded" '"fallback":[[:space:]]*false'
printf '%s' '{"layers": [{"material": "rutile", "azimuth_deg": 45, "thickness_um": 300},
  {"material": "rutile", "azimuth_deg": 135, "thickness_um": 301}]}' >"$tmpdir/rutile0.json"
expect_ok "dispersive stack fallback" spectrum --stack "$tmpdir/rutile0.json" --theta-deg 28.6479 --json
expect_grep "dispersive fallback reported" '"fallback":[[:space:]]*true'
expect_grep "dispersive fallback says why" '"reason":[[:space:]]*"too many path groups'
expect_ok "dispersive stack tmm" stack "$ex/quartz_multi_order_halfwave.json" --method tmm --lambda-nm 450
bad "material with eta_o" '{"layers": [{"material": "quartz", "eta_o": 1.5, "axis": [0,0,1], "thickness_um": 1}]}'
bad "unknown material" '{"layers": [{"material": "unobtainium", "axis": [0,0,1], "thickness_um": 1}]}'
bad "material not a string" '{"layers": [{"material": 3, "axis": [0,0,1], "thickness_um": 1}]}'
bad "material without axis" '{"layers": [{"material": "quartz", "thickness_um": 1}]}'
bad "isotropic material with axis" '{"layers": [{"material": "pmma", "axis": [0,0,1], "thickness_um": 1}]}'
expect_error "material unphysical at lambda" stack "$tmpdir/quartz.json" --lambda-nm 100.2

expect_error "stack with slab options" spectrum --stack "$ex/cellophane3.json" --eta-o 1.5
expect_error "stack with eta-i" spectrum --stack "$ex/cellophane3.json" --eta-i 1.3
expect_error "stack with analytic" spectrum --stack "$ex/cellophane3.json" --method analytic
expect_error "stack with order" spectrum --stack "$ex/cellophane3.json" --order 2
expect_error "stack tolerance out of range" spectrum --stack "$ex/cellophane3.json" --tolerance 0.5
expect_error "stack samples without numeric" spectrum --stack "$ex/cellophane3.json" --spectral-samples 64
expect_error "stack file missing" spectrum --stack "$tmpdir/none.json"
finish
