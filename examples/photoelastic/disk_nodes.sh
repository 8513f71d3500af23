#!/usr/bin/env bash
# Writes an unstructured node table of a disk under diametral compression, as a finite-element
# program would export it (columns node,x,y,z,S11,S22,S12,Mises in mm and MPa), plus its circular
# boundary: the input of 'biref photoelastic --stress-nodes' (docs/PHOTOELASTICITY.md).
#
# The stresses are the closed form of the disk (Frocht; the same field as --preset disk), sampled
# at scattered nodes: a jittered triangular lattice of spacing SPACING_MM, finer on the rim, and
# rings around each load point that grade from 0.4 mm to 6 mm like a mesh refined at the contacts.
#
# usage: disk_nodes.sh NODES.csv BOUNDARY.csv [SPACING_MM (default 2.5)] [SEED (default 1)]
#        (radius 25 mm, thickness 6 mm, load 500 N: the defaults of --preset disk)
set -euo pipefail
nodes=${1:?usage: disk_nodes.sh NODES.csv BOUNDARY.csv [SPACING_MM] [SEED]}
boundary=${2:?usage: disk_nodes.sh NODES.csv BOUNDARY.csv [SPACING_MM] [SEED]}
step=${3:-2.5}
seed=${4:-1}
awk -v s0="$step" -v seed="$seed" -v bfile="$boundary" '
function emit(x, y,   r1, r2, a, b, sxx, syy, txy, k, vm) {
  r1 = x * x + (R - y) * (R - y); r2 = x * x + (R + y) * (R + y)
  r1 = r1 * r1; r2 = r2 * r2; k = 2 * P / (pi * h)
  sxx = -k * ((R - y) * x * x / r1 + (R + y) * x * x / r2 - 1 / (2 * R))
  syy = -k * ((R - y) ^ 3 / r1 + (R + y) ^ 3 / r2 - 1 / (2 * R))
  txy = k * ((R - y) ^ 2 * x / r1 - (R + y) ^ 2 * x / r2)
  vm = sqrt(sxx * sxx - sxx * syy + syy * syy + 3 * txy * txy)
  printf "%d,%.6f,%.6f,0,%.7g,%.7g,%.7g,%.7g\n", ++id, x, y, sxx, syy, txy, vm
}
function near_load(x, y, d) { return x * x + (y - R) ^ 2 < d * d || x * x + (y + R) ^ 2 < d * d }
BEGIN {
  srand(seed); pi = atan2(0, -1); R = 25; P = 500; h = 6; rmax = 6
  print "node,x,y,z,S11,S22,S12,Mises"
  # Jittered triangular lattice inside the disk, away from the rim and the refined zones.
  dy = s0 * sqrt(3) / 2
  for (j = -int(R / dy) - 1; j <= int(R / dy) + 1; j++)
    for (i = -int(R / s0) - 1; i <= int(R / s0) + 1; i++) {
      x = (i + (j % 2) * 0.5) * s0 + (rand() - 0.5) * 0.3 * s0; y = j * dy + (rand() - 0.5) * 0.3 * s0
      if (x * x + y * y < (R - 0.4 * s0) ^ 2 && !near_load(x, y, rmax)) emit(x, y)
    }
  # The rim, twice as fine, except at the (singular) load points.
  n = int(2 * pi * R / (0.5 * s0)); off = rand()
  for (i = 0; i < n; i++) {
    t = 2 * pi * (i + off) / n; x = R * cos(t); y = R * sin(t)
    if (!near_load(x, y, 0.3)) emit(x, y)
  }
  # Graded rings around both load points (inside the disk only).
  for (side = -1; side <= 1; side += 2)
    for (rho = 0.4; rho <= rmax * 1.2; rho *= 1 + 0.08 * s0) {
      m = int(pi / (0.12 * s0)) + 1; off = rand()
      for (i = 0; i < 2 * m; i++) {
        t = pi * (i + off) / m; x = rho * cos(t); y = side * R + rho * sin(t)
        if (x * x + y * y < R * R * (1 - 1e-9)) emit(x, y)
      }
    }
  # Boundary: the circle as a polygon of 720 vertices.
  print "x,y" > bfile
  for (i = 0; i < 720; i++) printf "%.6f,%.6f\n", R * cos(2 * pi * i / 720), R * sin(2 * pi * i / 720) > bfile
}' > "$nodes"
