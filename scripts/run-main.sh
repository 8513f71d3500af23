#!/usr/bin/env bash
# Installs what is missing, builds biref and runs the main job: renders the default scenes into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
"./scripts/install-deps.sh"
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build >/dev/null
cmake --build build -j "$jobs"
mkdir -p out
# The paper's scenes with its method, and fig. 9c between world-fixed polarizers (the analytic
# method takes every light: the paper's s/p model and world-fixed polarizers alike).
for scene in default fig9a fig9c; do
  ./build/biref render "examples/$scene.json" -o "out/$scene.png"
done
# Fig. 9b's bands (unpolarized light, no analyzer) stay below the threshold of visibility
# (docs/REPRODUCTION.md): the chroma map beside it shows where they are.
./build/biref render examples/fig9b.json -o out/fig9b.png --chroma-map out/fig9b_chroma.png
./build/biref render examples/fig9c_analyzer45.json -o out/fig9c_analyzer45.png
# A scene of layer stacks (tape art between crossed polarizers): the numeric method with its 64
# samples of the stacks' exact Jones matrices takes about 2 s here; the stack expansion (what the
# analytic method renders stacks by) about 30 s at this size.
./build/biref render examples/stack_scenes/tape_art.json -o out/tape_art.png --method numeric
