#!/usr/bin/env bash
# Installs what is missing, builds biref and runs the main job: renders the default scenes into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
"./scripts/install-deps.sh"
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build >/dev/null
cmake --build build -j "$jobs"
mkdir -p out
if [ -f examples/default.json ]; then
  for scene in examples/default.json examples/fig9a.json examples/fig9b.json examples/fig9c.json; do
    [ -f "$scene" ] || continue
    name=$(basename "$scene" .json)
    ./build/biref render "$scene" -o "out/$name.png"
    echo "wrote out/$name.png"
  done
else
  ./build/biref slab --eta-o 1.775 --eta-e 1.231 --axis 0.084,0.979,-0.187 --thickness-mm 1.15 \
    --theta-deg 30 --lambda-nm 550
fi
