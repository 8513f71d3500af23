#!/usr/bin/env bash
# Regenerates the finite-element examples from their inputs: gmsh meshes the .geo files
# (quadratic elements), ccx_input.py writes the CalculiX analyses (plane stress, polycarbonate),
# CalculiX solves them, frd_to_vtu.py converts the results to .vtu with meshio.
#   plate_hole.frd, plate_hole.vtu   plate 60 x 60 x 3 mm, hole r = 5 mm, 4 MPa along x (CPS8)
#   disk.vtu                         disk r = 25 mm, h = 6 mm, 500 N diametral compression (CPS6)
# Needs Debian's gmsh, calculix-ccx and python3-meshio (scripts/install-deps.sh installs them).
# Usage: make.sh [OUTDIR]   (default: this directory)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
out=$(mkdir -p "${1:-$here}" && cd "${1:-$here}" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
for part in plate_hole disk; do
  gmsh -2 "$here/$part.geo" -format inp -o mesh.inp >gmsh.log 2>&1 || { cat gmsh.log; exit 1; }
  /usr/bin/python3 "$here/ccx_input.py" "$([ $part = disk ] && echo disk || echo plate)" mesh.inp "$part.inp"
  ccx -i "$part" >ccx.log 2>&1 || { tail -20 ccx.log; exit 1; }
  /usr/bin/python3 "$here/frd_to_vtu.py" "$part.frd" "$out/$part.vtu"
  echo "$part: $(grep -c '^ -1' "$part.frd") records, $(stat -c %s "$out/$part.vtu") bytes of .vtu"
done
cp plate_hole.frd "$out/plate_hole.frd"
