#!/usr/bin/env bash
# Regenerates the pictures of docs/PHOTOELASTICITY.md (docs/figures/photoelastic/).
# usage: examples/photoelastic/figures.sh [path/to/biref] [OUTDIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
biref=${1:-$here/../../build/biref}
out=${2:-$here/../../docs/figures/photoelastic}
mkdir -p "$out"
pe() { "$biref" photoelastic "$@"; }
S=(--size 320)

# Disk under diametral compression (R 25 mm, h 6 mm, P 500 N, polycarbonate).
pe --preset disk "${S[@]}" -o "$out/disk-circular-dark-white.png"
pe --preset disk "${S[@]}" --light mono --lambda-nm 589 -o "$out/disk-circular-dark-589.png"
pe --preset disk "${S[@]}" --field light --light mono --lambda-nm 589 -o "$out/disk-circular-light-589.png"
pe --preset disk "${S[@]}" --polariscope plane --polarizer linear:0 -o "$out/disk-plane-dark-white.png"
pe --preset disk "${S[@]}" --polariscope plane --polarizer linear:30 --light mono --lambda-nm 589 \
  -o "$out/disk-plane-dark-589-psi30.png"

# The same disk seen 40 degrees off its normal (general slab path; approximate, see the docs).
pe --preset disk "${S[@]}" --tilt-deg 40 -o "$out/disk-circular-dark-white-tilt40.png"

# Plate with a hole under tension (a 5 mm, 60 x 60 mm, h 3 mm, S 2.5 MPa).
pe --preset hole --stress-MPa 2.5 "${S[@]}" -o "$out/hole-circular-dark-white.png"
pe --preset hole --stress-MPa 2.5 "${S[@]}" --light mono --lambda-nm 546 --tint -o "$out/hole-circular-dark-546-tint.png"
pe --preset hole --stress-MPa 2.5 "${S[@]}" --polariscope plane --polarizer linear:0 \
  -o "$out/hole-plane-dark-white.png"

# Beam in pure bending (100 x 20 mm, h 6 mm, M 1500 N mm).
pe --preset beam --moment-Nmm 1500 --size 480 -o "$out/beam-circular-dark-white.png"
pe --preset beam --moment-Nmm 1500 --size 480 --field light --light mono --lambda-nm 589 \
  -o "$out/beam-circular-light-589.png"

# Stress from a finite-element node export: the example disk (scattered nodes, circular boundary),
# with the colour key and a scale bar; the preset disk in white light with its Michel-Levy key.
pe --stress-nodes "$here/disk_nodes.csv" --columns sxx=S11,syy=S22,txy=S12 --boundary "$here/disk_boundary.csv" \
  "${S[@]}" --light mono --lambda-nm 589 --key --scale-bar -o "$out/disk-nodes-589-key.png"
pe --preset disk "${S[@]}" --key --scale-bar -o "$out/disk-circular-dark-white-key.png"

# Phase stepping: the six images of the disk at 589 nm (16-bit linear grey PNG).
pe --preset disk --size 160 --light mono --lambda-nm 589 --phase-steps 6 -o "$out/disk-step.png"

# Fig. 2-like: a 0.76 mm polycarbonate card pressed on its top edge, between an s-polarised
# source (polarizer at 0 deg) and a crossed filter, white light.
csv=$(mktemp)
trap 'rm -f "$csv"' EXIT
"$here/card_stress.sh" "$csv" 300 0.76 0.4
pe --stress-grid "$csv" --thickness-mm 0.76 --polariscope plane --polarizer linear:0 --field dark --size 480 \
  -o "$out/card-plane-dark-white.png"
