#!/usr/bin/env bash
# Instructions per shading sample of every method timed by `biref accuracy --cost`, counted by
# callgrind: unlike wall-clock times they do not depend on the load of a shared machine.
#
# usage: scripts/accuracy_callgrind.sh [BIREF [ITERATIONS [extra biref accuracy options...]]]
#   BIREF       the CLI (default build/biref)
#   ITERATIONS  samples per method (default 1032: a quarter of the default grid's 4128 states, in
#               their golden-ratio order, so every angle range is represented; the ground truth
#               then runs for a few minutes under callgrind)
#
# Each timed loop of `--cost-iterations` is one call of acc_cost_loop; callgrind collects only
# inside it (--toggle-collect) and writes one dump per call (--dump-after). The JSON's cost.order
# names the loops in call order. Prints a markdown table on stdout.
set -euo pipefail
BIREF=${1:-build/biref}
ITERS=${2:-1032}
shift $(($# > 2 ? 2 : $#))
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" --toggle-collect=acc_cost_loop \
  --dump-after=acc_cost_loop "$BIREF" accuracy --cost-only --cost-iterations "$ITERS" --threads 1 --json "$@" \
  >"$out/cost.json" 2>"$out/valgrind.log"

mapfile -t order < <(jq -r '.cost.order[]' "$out/cost.json")
printf '| loop | instructions per sample |\n|---|---|\n'
for i in "${!order[@]}"; do
  dump="$out/cg.out.$((i + 1))"
  if [ ! -f "$dump" ]; then
    echo "missing callgrind dump $dump (did acc_cost_loop get inlined?)" >&2
    exit 1
  fi
  ir=$(awk '/^summary:/ {print $2}' "$dump")
  awk -v ir="$ir" -v n="$ITERS" -v name="${order[$i]}" 'BEGIN { printf "| %s | %.0f |\n", name, ir / n }'
done
