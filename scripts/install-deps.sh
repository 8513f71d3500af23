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
# Fuzzing the parsers (tests/fuzz): clang, its libFuzzer/sanitizer runtimes and OpenMP.
pkgs+=(clang libclang-rt-14-dev libomp-14-dev)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present" >&2
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
