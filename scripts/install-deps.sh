#!/usr/bin/env bash
# Installs the Debian packages biref builds and tests with, only those that are missing.
set -euo pipefail
pkgs=(build-essential cmake pkg-config libpng-dev libcjson-dev liblapacke-dev liblapack-dev
      libblas-dev liblcms2-dev libcairo2-dev libplplot-dev
      plplot-driver-cairo libqhull-dev
      libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri)
# Finite-element results: VTK's readers for .vtu/.vtk (biref photoelastic --fea); gmsh and
# CalculiX regenerate the examples (examples/photoelastic/fea/make.sh); meshio for Python meshes.
pkgs+=(libvtk9-dev gmsh calculix-ccx python3-meshio)
# Python bindings and their tests, with Debian's own /usr/bin/python3.
pkgs+=(python3-numpy python3-cffi python3-pytest python3-pip python3-setuptools)
# The WebGL2 viewer's test: headless Chromium driven by /usr/bin/python3, the GLSL reference compiler.
pkgs+=(chromium glslang-tools python3)
# The three.js package (web/three) and its test: Node and npm; three itself comes from the npm
# registry at the version web/three/package-lock.json pins (npm ci, below).
pkgs+=(nodejs)
# Several processes (mpirun -n N biref render|accuracy|figure, docs/CLUSTER.md): Open MPI's headers,
# library and mpirun; CMake's BIREF_MPI=OFF builds without them.
pkgs+=(libopenmpi-dev openmpi-bin)
# Fuzzing the parsers (tests/fuzz): clang, its libFuzzer/sanitizer runtimes and OpenMP.
pkgs+=(clang libclang-rt-14-dev libomp-14-dev)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# Debian's npm is a package of its own; other nodejs builds carry npm.
command -v npm >/dev/null 2>&1 || missing+=(npm)
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present" >&2
else
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "install-deps: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# web/three's node_modules from its lock file, when missing or older than the lock file (the
# tests then need no network); npm ci also copies the library data into the package (prepare).
three_dir="$(dirname "$0")/../web/three"
if [ ! -f "$three_dir/node_modules/.package-lock.json" ] ||
   [ "$three_dir/package-lock.json" -nt "$three_dir/node_modules/.package-lock.json" ]; then
  echo "install-deps: npm ci in web/three" >&2
  (cd "$three_dir" && npm ci --no-audit --no-fund --loglevel=error)
fi
