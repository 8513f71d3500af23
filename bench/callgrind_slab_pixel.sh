#!/usr/bin/env bash
# Instructions per slab pixel of the CPU renderer (callgrind: independent of the machine's load).
#
#   bench/callgrind_slab_pixel.sh BIREF_BINARY [SCENE] [METHOD] [ANTIALIAS]
#
# Renders SCENE (default examples/fig9a.json) at 384 x 216 on one thread under callgrind with
# --antialias ANTIALIAS (default none, the point look-ups `biref bench` times; prefilter is the
# render command's default), counting only biref_render_image (the frame, without set-up and
# output; the toggle sits on the outer entry because the inner one is reached by a tail jump
# that callgrind does not see as a call), and divides by
# the number of slab pixels. Also prints the whole process's instructions (set-up, look-up
# table, sRGB encoding and PNG writing included) and the top functions of the frame.
set -euo pipefail
bin=$(readlink -f "$1")
scene=${2:-$(dirname "$0")/../examples/fig9a.json}
method=${3:-analytic}
aa=${4:-none}
W=384 H=216
tmp=$(mktemp -d "${TMPDIR:-/tmp}/biref-cg.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
frac=$("$bin" render "$scene" -o "$tmp/a.png" --width $W --height $H --threads 1 --method "$method" --antialias "$aa" --json -q |
    python3 -c 'import json,sys; print(json.load(sys.stdin)["slab_fraction"])')
valgrind --tool=callgrind --callgrind-out-file="$tmp/all.out" "$bin" render "$scene" -o "$tmp/b.png" \
    --width $W --height $H --threads 1 --method "$method" --antialias "$aa" -q >/dev/null 2>&1
valgrind --tool=callgrind --toggle-collect=biref_render_image --callgrind-out-file="$tmp/frame.out" \
    "$bin" render "$scene" -o "$tmp/c.png" --width $W --height $H --threads 1 --method "$method" --antialias "$aa" -q >/dev/null 2>&1
total=$(callgrind_annotate "$tmp/all.out" | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
frame=$(callgrind_annotate "$tmp/frame.out" | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
python3 -c "
import sys
W, H, frac, total, frame = $W, $H, $frac, $total, $frame
slab = round(frac * W * H)
print(f'slab pixels {slab} of {W*H}; frame {frame:,} instructions = {frame/slab:,.0f} per slab pixel')
print(f'whole process {total:,} instructions; outside the frame {total-frame:,}')
"
callgrind_annotate --inclusive=no "$tmp/frame.out" 2>/dev/null | sed -n '/^Ir/,$p' | head -25
