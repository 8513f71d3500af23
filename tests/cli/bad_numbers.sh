#!/usr/bin/env bash
# Numbers at the edge of double range: a result that would not be finite is refused with one
# error line naming the input, never printed or drawn; forged image sizes are refused up front.
set -u
. "$(dirname "$0")/lib.sh"
root=$(dirname "$0")/../..
slab=(--eta-o 1.5 --eta-e 1.6 --axis 0,1,0 --thickness-um 10)
named() { # named DESCRIPTION PATTERN: the last expect_error's message matches
  grep -Eq -e "$2" "$tmpdir/err" || { echo "FAIL ($1): message does not match /$2/"; sed 's/^/  stderr: /' "$tmpdir/err"; fails=$((fails + 1)); }
}

# Light: huge Stokes vectors overflow the coherency matrix; huge weights are only a ratio.
expect_error "stokes 1e308" spectrum "${slab[@]}" --method numeric --stokes 1e308,1e308,0,0
named "stokes names the option" '--stokes: too large'
expect_ok "polarization weights 1e308" spectrum "${slab[@]}" --polarization 1e308,1e308 --json
expect_grep "1e308,1e308 is unpolarized" '"s":[[:space:]]*0.5'
expect_ok "polarization weights 1e308,0" spectrum "${slab[@]}" --polarization 1e308,0 --json
expect_grep "1e308,0 is s" '"s":[[:space:]]*1[,}]'

# Scenes: exposure and radiance bounded so that no float pixel overflows.
cat >"$tmpdir/s.json" <<'JSON'
{"camera": {"position": [1.5, 1.2, 2.5], "look_at": [0, 0, 0], "fov_deg": 45, "width": 16, "height": 10,
            "exposure": 1},
 "slabs": [{"center": [0, 0, 0], "size": [2, 2], "thickness_um": 40, "normal": [0, 0, 1],
            "tangent": [1, 0, 0], "axis": [0.3, 0.6, 0.5], "eta_o": 1.54, "eta_e": 1.55}],
 "light": {"panel": {"center": [0, 0, -2], "size": [3, 3], "normal": [0, 0, 1], "radiance": 1}}}
JSON
sed 's/"exposure": 1/"exposure": 1e308/' "$tmpdir/s.json" >"$tmpdir/exp.json"
expect_error "exposure 1e308" render "$tmpdir/exp.json" -o "$tmpdir/exp.png" --pfm "$tmpdir/exp.pfm"
named "exposure named" 'camera.exposure'
sed 's/"radiance": 1/"radiance": 1e308/' "$tmpdir/s.json" >"$tmpdir/rad.json"
expect_error "radiance 1e308" render "$tmpdir/rad.json" -o "$tmpdir/rad.png"
named "radiance named" 'light.panels\[0\].radiance'
sed 's/"exposure": 1/"exposure": 1e20/; s/"radiance": 1/"radiance": 1e20/' "$tmpdir/s.json" >"$tmpdir/both.json"
expect_error "exposure x radiance 1e40" render "$tmpdir/both.json" -o "$tmpdir/both.png"
named "product named" 'camera.exposure'
[ ! -e "$tmpdir/exp.png" ] && [ ! -e "$tmpdir/exp.pfm" ] && [ ! -e "$tmpdir/rad.png" ] ||
  { echo "FAIL (images written for refused scenes)"; fails=$((fails + 1)); }

# Photoelastic loads: bounded by the nominal stress they give.
pe=(--profile 0,-5,0,5 --profile-points 3)
expect_error "load 1e300" photoelastic --preset disk --load-N 1e300 "${pe[@]}"
named "load named" 'load'
expect_error "thickness 1e-300" photoelastic --preset disk --thickness-mm 1e-300 "${pe[@]}"
named "thickness named" 'thickness'
expect_error "stress 1e300" photoelastic --preset hole --stress-MPa 1e300 "${pe[@]}"
named "stress named" 'remote stress'
expect_error "moment 1e300" photoelastic --preset beam --moment-Nmm 1e300 "${pe[@]}"
named "moment named" 'moment'
expect_error "exposure 1e308" photoelastic --preset disk --exposure 1e308 -o "$tmpdir/pe.png" --size 20
expect_ok "large but sane load" photoelastic --preset disk --load-N 5000 "${pe[@]}"
if grep -Eqi '(^|[^a-z])-?nan([^a-z]|$)' "$tmpdir/out"; then echo "FAIL (nan in a profile)"; fails=$((fails + 1)); fi

# Stress grids: values beyond a kilometre or a terapascal are refused with their line.
h='x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa'
printf '%s\n0,0,1e308,0,0\n1,0,1,0,0\n0,1,1,0,0\n1,1,1,0,0\n' "$h" >"$tmpdir/g1.csv"
expect_error "grid stress 1e308" photoelastic --stress-grid "$tmpdir/g1.csv" -o "$tmpdir/g1.png" --size 20
named "grid stress line" 'line 2, column sxx_MPa: 1e308 is out of range'
printf '%s\n-1e308,0,1,0,0\n1e308,0,1,0,0\n-1e308,1,1,0,0\n1e308,1,1,0,0\n' "$h" >"$tmpdir/g2.csv"
expect_error "grid x 1e308" photoelastic --stress-grid "$tmpdir/g2.csv" -o "$tmpdir/g2.png" --size 20
named "grid x line" 'line 2, column x_mm: -1e308 is out of range'

# Angles of 1e308 degrees are angles (modulo 360), for the analyzer as for the polarizer.
expect_ok "analyzer linear:1e308" spectrum "${slab[@]}" --method numeric --analyzer linear:1e308
expect_ok "polarizer linear:1e308" spectrum "${slab[@]}" --method numeric --polarizer linear:1e308
expect_ok "photoelastic polarizer linear:1e308" photoelastic --preset disk --polariscope plane --size 16 \
  --polarizer linear:1e308 -o "$tmpdir/pol.png"

# Coordinates of lines and windows: their lengths must stay finite (no -nan or -inf rows).
expect_error "profile 1e308" photoelastic --preset disk --profile 1e308,0,-1e308,0 --profile-points 2
named "profile bound" '--profile: coordinates are at most 1e\+06 mm'
expect_error "window 1e308" photoelastic --preset disk --window-mm -1e308,0,1e308,1 -o "$tmpdir/w.png"
named "window bound" '--window-mm: coordinates are at most'
expect_ok "profile at the bound" photoelastic --preset disk --profile 1e6,0,-1e6,0 --profile-points 2
if grep -Eqw -- '-?nan|-?inf' "$tmpdir/out"; then echo "FAIL (profile at the bound): non-finite output"; fails=$((fails + 1)); fi

# Demodulation: a reference fringe order beyond float maps is refused, not an all-inf map.
"$BIREF" photoelastic --preset disk --light mono --phase-steps 4 --size 24 -o "$tmpdir/st.pfm" >/dev/null
expect_error "order-at 1e308" photoelastic demodulate "$tmpdir"/st-{1,2,3,4}.pfm --order-at 12,12,1e308 -o "$tmpdir/maps"
named "order-at bound" 'reference fringe order 1e\+308 is out of range'
[ -e "$tmpdir/maps/fringe-order.pfm" ] && { echo "FAIL (order-at 1e308): a map was written"; fails=$((fails + 1)); }

# Refractive indices: at most 1000, so that a slab can always be evaluated (1e300 rendered a
# scene of failed evaluations with status 0).
expect_error "eta_o 1e300" spectrum --eta-o 1e300 --eta-e 1.5 --axis 0,1,0 --thickness-um 10
named "eta_o bound" 'eta_o must be at most 1000'
sed 's/"eta_o": 1.54/"eta_o": 1e300/' "$tmpdir/s.json" >"$tmpdir/eta.json"
expect_error "scene eta_o 1e300" render "$tmpdir/eta.json" -o "$tmpdir/eta.png"
named "scene eta_o bound" 'slabs\[0\]\.eta_o: must be at most 1000'
expect_ok "eta_o 1000" spectrum --eta-o 1000 --eta-e 1.5 --axis 0,1,0 --thickness-um 10

# Images: a 461-byte PNG declaring 16384 x 16384 pixels is refused before any decoding. The
# reader writes this message only from the header check that precedes every allocation, so the
# message itself shows where the refusal happened (no wall-clock test: timing is for benchmarks).
huge=$root/tests/fuzz/corpus/fuzz_png/huge_declared.png
expect_error "diff on a forged size" diff "$huge" "$huge"
named "forged size" 'too large \(16384x16384'
finish
