#!/usr/bin/env bash
# Writes the stress field of a credit-card-sized plate (85.6 x 54 mm) pressed on the middle of its
# top edge as a biref stress-grid CSV (header x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa).
#
# The field is Flamant's solution for a point force P on the edge of a half-plane,
# sigma_r = -2 P cos(theta) / (pi h r), purely radial about the load point (Timoshenko & Goodier,
# Theory of Elasticity, sec. 36), cut to the card. The load acts 1 mm above the edge, which
# stands in for a finger's contact patch and keeps the grid finite. Only near the load is this the
# card's true stress (the card's other edges are not traction-free in the half-plane solution):
# a picture generator, not an analysis.
#
# usage: card_stress.sh OUT.csv [LOAD_N (default 60)] [THICKNESS_MM (default 0.76)] [SPACING_MM (default 0.4)]
set -euo pipefail
out=${1:?usage: card_stress.sh OUT.csv [LOAD_N] [THICKNESS_MM] [SPACING_MM]}
load=${2:-60}
thick=${3:-0.76}
step=${4:-0.4}
awk -v P="$load" -v h="$thick" -v d="$step" 'BEGIN {
  pi = atan2(0, -1); W = 85.6; H = 54; ytop = H / 2 + 1.0
  nx = int(W / d + 0.5); ny = int(H / d + 0.5)
  print "x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa"
  for (j = 0; j <= ny; j++) for (i = 0; i <= nx; i++) {
    x = -W / 2 + i * W / nx; y = -H / 2 + j * H / ny
    dx = x; dy = y - ytop; r2 = dx * dx + dy * dy
    # N/mm^2 = MPa: sigma_r = -2 P cos(theta) / (pi h r), cos(theta) = -dy / r, n = (dx, dy) / r.
    s = -2 * P * (-dy) / (pi * h * r2 * r2)
    printf "%.6f,%.6f,%.6g,%.6g,%.6g\n", x, y, s * dx * dx, s * dy * dy, s * dx * dy
  }
}' > "$out"
