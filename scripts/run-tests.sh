#!/usr/bin/env bash
# Builds biref with -Werror and runs the whole test suite through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
"./scripts/install-deps.sh"
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DBIREF_WERROR=ON >/dev/null
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs"
