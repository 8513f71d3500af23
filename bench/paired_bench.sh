#!/usr/bin/env bash
# Paired frame-time comparison of the analytic renderer: a given commit against the current tree.
#
# Both are built the same way (fresh Release build directories, default flags) and both render
# the SAME scene file (the current tree's, or --scene), alternating base/current in every round
# so that a change in the machine's load hits both alike. Reports per-round and median wall and
# CPU frame times and their ratios (base / current), with the load average before and after.
#
#   bench/paired_bench.sh                    # 13ce0eb vs the working tree, fig9a 1920x1080, 2 threads
#   bench/paired_bench.sh --base COMMIT --rounds 7 --scene examples/fig9b.json
#   bench/paired_bench.sh --keep DIR         # keep (and reuse) the builds in DIR
#
# Options: --base COMMIT (default 13ce0eb), --scene FILE (default examples/fig9a.json of the
# current tree), --width W --height H (1920 x 1080), --threads T (2), --rounds N (5),
# --methods LIST (analytic), --keep DIR, --json (one JSON object on stdout).
set -euo pipefail

base=13ce0eb scene="" width=1920 height=1080 threads=2 rounds=5 methods=analytic keep="" json=0
while [ $# -gt 0 ]; do
    case "$1" in
    --base) base=$2; shift 2 ;;
    --scene) scene=$2; shift 2 ;;
    --width) width=$2; shift 2 ;;
    --height) height=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --rounds) rounds=$2; shift 2 ;;
    --methods) methods=$2; shift 2 ;;
    --keep) keep=$2; shift 2 ;;
    --json) json=1; shift ;;
    -h | --help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "paired_bench: unknown option '$1' (see --help)" >&2; exit 2 ;;
    esac
done

src=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
base_sha=$(git -C "$src" rev-parse --verify "$base^{commit}") || { echo "paired_bench: unknown commit '$base'" >&2; exit 2; }
[ -n "$scene" ] || scene=$src/examples/fig9a.json
[ -f "$scene" ] || { echo "paired_bench: no scene file '$scene'" >&2; exit 2; }
scene=$(readlink -f "$scene")

if [ -n "$keep" ]; then
    work=$(mkdir -p "$keep" && readlink -f "$keep")
else
    work=$(mktemp -d "${TMPDIR:-/tmp}/biref-paired.XXXXXX")
fi
cleanup() {
    git -C "$src" worktree remove --force "$work/base-src" >/dev/null 2>&1 || true
    [ -n "$keep" ] || rm -rf "$work"
}
trap cleanup EXIT

log() { echo "paired_bench: $*" >&2; }

# The base commit in a temporary detached worktree; the current tree as it is on disk.
if [ ! -d "$work/base-src" ]; then
    git -C "$src" worktree add --detach "$work/base-src" "$base_sha" >/dev/null 2>&1
fi
build() { # source dir, build dir
    log "building $1"
    cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$2" -j2 --target biref_cli >/dev/null
}
build "$work/base-src" "$work/base-build"
build "$src" "$work/cur-build"
bin_base=$work/base-build/biref bin_cur=$work/cur-build/biref

run() { # binary -> "wall_ms cpu_ms"
    # The JSON goes to a file and is read after the benchmark has exited: a parser started in a
    # pipe alongside it spends its own start-up (~0.1 s of CPU) on one of the cores during the
    # timed frame, which cost a ~0.1 s frame 20-50 ms of wall time.
    "$1" bench --scene "$scene" --width "$width" --height "$height" --threads "$threads" --methods "$methods" \
        --max-seconds 1000 --json >"$work/run.json"
    python3 -c 'import json,sys; m=json.load(sys.stdin)["methods"][0]; print(m["ms_per_frame"], m["cpu_ms_per_frame"])' \
        <"$work/run.json"
}

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
cur_rev=$(git -C "$src" rev-parse --short HEAD)$([ -z "$(git -C "$src" status --porcelain --untracked-files=no)" ] || echo "+dirty")
log "base $(git -C "$src" rev-parse --short "$base_sha") vs current $cur_rev; scene $scene ${width}x${height}, $threads threads, $rounds rounds"
results=()
for ((i = 1; i <= rounds; i++)); do
    read -r bw bc < <(run "$bin_base")
    read -r cw cc < <(run "$bin_cur")
    results+=("$bw $bc $cw $cc")
    log "round $i: base $bw ms (cpu $bc)  current $cw ms (cpu $cc)"
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

printf '%s\n' "${results[@]}" | python3 -c '
import json, statistics, sys
rows = [list(map(float, l.split())) for l in sys.stdin if l.strip()]
med = lambda k: statistics.median(r[k] for r in rows)
out = {
    "base": sys.argv[1], "current": sys.argv[2], "scene": sys.argv[3],
    "width": int(sys.argv[4]), "height": int(sys.argv[5]), "threads": int(sys.argv[6]),
    "methods": sys.argv[7], "rounds": len(rows),
    "load_before": sys.argv[8], "load_after": sys.argv[9],
    "base_ms": med(0), "base_cpu_ms": med(1), "current_ms": med(2), "current_cpu_ms": med(3),
    "ratio_wall_median": statistics.median(r[0] / r[2] for r in rows),
    "ratio_cpu_median": statistics.median(r[1] / r[3] for r in rows),
    "per_round": [{"base_ms": r[0], "base_cpu_ms": r[1], "current_ms": r[2], "current_cpu_ms": r[3]} for r in rows],
}
if sys.argv[10] == "1":
    print(json.dumps(out, indent=2))
else:
    o = out
    print("base %s: %.1f ms/frame (cpu %.1f ms), median of %d rounds" % (o["base"], o["base_ms"], o["base_cpu_ms"], len(rows)))
    print("current %s: %.1f ms/frame (cpu %.1f ms)" % (o["current"], o["current_ms"], o["current_cpu_ms"]))
    print("speed-up (median of the paired ratios): wall %.2fx, cpu %.2fx" % (o["ratio_wall_median"], o["ratio_cpu_median"]))
    print("load average before %s, after %s" % (o["load_before"], o["load_after"]))
' "$(git -C "$src" rev-parse --short "$base_sha")" "$cur_rev" "$scene" "$width" "$height" "$threads" "$methods" \
    "$load_before" "$load_after" "$json"
