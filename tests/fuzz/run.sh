#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and runs each for SECONDS (default 20)
# from its seed corpus in tests/fuzz/corpus/TARGET. Inputs that find new coverage go to a
# scratch directory, crashes to build-fuzz/artifacts/. Exit status non-zero on any crash.
# Long runs: see tests/fuzz/README.md.
set -euo pipefail
cd "$(dirname "$0")/../.."
secs=${1:-20}
build=${BIREF_FUZZ_BUILD:-build-fuzz}
jobs=$(nproc 2>/dev/null || echo 2)
[ "$jobs" -le 2 ] || jobs=2
targets=(fuzz_scene fuzz_stress_grid fuzz_png fuzz_stack fuzz_nodes fuzz_options)
# The command line is built too: fuzz_options parses with its option tables.
cmake -S . -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBIREF_FUZZ=ON \
  -DBIREF_BUILD_CLI=ON -DBIREF_BUILD_TESTS=OFF -DBIREF_BUILD_SHARED=OFF -DBIREF_INSTALL=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target "${targets[@]}"
mkdir -p "$build/artifacts"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# One target per core at once (libFuzzer is single-threaded): each still gets SECONDS of a core,
# in half the wall time on two cores.
fuzz_one() {
  local t=$1 dict=() rc=0
  mkdir -p "$scratch/$t"
  [ -f "tests/fuzz/$t.dict" ] && dict=(-dict="tests/fuzz/$t.dict")
  # -rss_limit_mb: the PNG reader may legitimately allocate a 64-megapixel image.
  "$build/$t" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2560 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$t-" "${dict[@]}" "$scratch/$t" "tests/fuzz/corpus/$t" 2>"$scratch/$t.log" || rc=$?
  echo "$rc" >"$scratch/$t.rc"
}
running=0
for t in "${targets[@]}"; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  echo "fuzz: $t for ${secs} s" >&2
  fuzz_one "$t" &
  running=$((running + 1))
done
wait
failed=0
for t in "${targets[@]}"; do
  if [ "$(cat "$scratch/$t.rc" 2>/dev/null)" != 0 ]; then
    tail -60 "$scratch/$t.log" >&2
    echo "fuzz: $t FAILED (reproducer in $build/artifacts/)" >&2
    failed=1
    continue
  fi
  # Coverage reached (cov: edges, ft: features) and inputs run, for comparing run lengths.
  grep -E '^#[0-9]+[[:space:]]+DONE' "$scratch/$t.log" | tail -1 | sed "s/^/fuzz: $t: /" >&2 || true
  grep -E '^stat::number_of_executed_units|^stat::new_units_added' "$scratch/$t.log" | sed "s/^/fuzz: $t: /" >&2 || true
done
[ "$failed" = 0 ] || exit 1
echo "fuzz: all targets ran ${secs} s without a failure" >&2
