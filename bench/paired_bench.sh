#!/usr/bin/env bash
# Paired benchmark: a base commit against the current working tree, row by row, side by side.
#
# Both are built the same way (fresh Release build directories, default flags plus --cmake-args)
# and run the SAME scene files (the current tree's), alternating base/current (and which goes
# first) in every round, so that a change in the machine's load hits both alike. Reports per row
# the median wall and CPU times of each side and the median of the paired ratios base/current
# (> 1: the current tree is faster), the load average before and after, and a few ratios within
# each side (prefilter/plain, analyzer/s-p, ...). A row whose feature a side lacks (an option,
# a method, a scene its parser refuses, MPI) is "n/a" for that side instead of failing.
#
#   bench/paired_bench.sh                        # every row, main vs the working tree (~15 min)
#   bench/paired_bench.sh --quick                # every row, smaller frames, 2 rounds (~5 min)
#   bench/paired_bench.sh --rows analytic,startup --base COMMIT --rounds 7
#   bench/paired_bench.sh --base 13ce0eb --rows analytic   # the original single measurement
#   bench/paired_bench.sh --dry-run              # the rows and their commands; builds nothing
#
# Rows (--rows LIST, comma-separated, or all):
#   analytic      fig9a 1920x1080, analytic, point look-ups (biref bench; --scene, --width,
#                 --height, --methods change this row)
#   prefilter     the same with --antialias prefilter (biref render's default)
#   fig9c         fig9c 1920x1080, analytic (the paper's s/p light)
#   analyzer45    fig9c_analyzer45 1920x1080, analytic (world-fixed polarizers)
#   expansion     fig9a 1920x1080, the path-group expansion
#   numeric-8     fig9a 1920x1080, numeric integration with 8 samples
#   numeric-32    the same with 32 samples
#   ground-truth  fig9a 1920x1080, 16384 samples: timed on evenly spaced rows for
#                 --gt-seconds and scaled to the frame (reported as extrapolated)
#   ss1, ss4      fig9a 960x540 with biref render --supersample 1 and 4 (the render's own
#                 frame time from its --json; no CPU time)
#   startup       biref render fig9a 640x360: the whole process, start to PNG written
#                 (median of --startup-runs runs per round)
#   render        biref render fig9a 1920x1080, the whole process
#   mpi           mpirun -n --mpi-ranks biref render fig9a 1920x1080, the whole process
#                 (n/a without mpirun or for a build without MPI)
#
# Options: --base COMMIT (default main), --rows LIST (all), --rounds N (5; --quick 2),
# --threads T (2; per MPI rank T / ranks), --quick (frames 960x540 and 480x270, ground truth
# 2 s), --gt-seconds S (8), --startup-runs N (5), --mpi-ranks N (2), --scene FILE,
# --width W, --height H, --methods LIST (the analytic row), --cmake-args "ARGS" (both builds),
# --keep DIR (keep and reuse the builds in DIR), --json (one JSON object on stdout),
# --dry-run, -h/--help. Times are printed as they come on stderr.
set -euo pipefail
{ # the whole script is read before it runs: editing it during a long run cannot change that run

all_rows="analytic prefilter fig9c analyzer45 expansion numeric-8 numeric-32 ground-truth ss1 ss4 startup render mpi"
base=main rows=all rounds="" threads=2 quick=0 gt_seconds="" startup_runs=5 mpi_ranks=2
scene="" width="" height="" methods=analytic cmake_args="" keep="" json=0 dry_run=0

die() { echo "paired_bench: $*" >&2; exit 2; }
seen=" "
once() { # an option given twice is an error, not a silent override
    case "$seen" in *" $1 "*) die "$1 given twice" ;; esac
    seen="$seen$1 "
}
value() { # option, argument count left, value
    [ "$2" -ge 2 ] || die "$1 needs a value"
    case "$3" in --*) die "$1 needs a value, not '$3'" ;; esac
}
count() { # option, value: a positive integer
    [[ "$2" =~ ^[1-9][0-9]{0,5}$ ]] || die "$1 expects a positive integer, not '$2'"
}
while [ $# -gt 0 ]; do
    opt=$1
    case "$opt" in
    --quick | --json | --dry-run) once "$opt"; shift ;;
    -h | --help) sed -n '2,44p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    --base | --rows | --rounds | --threads | --gt-seconds | --startup-runs | --mpi-ranks | --scene | --width | \
        --height | --methods | --cmake-args | --keep)
        once "$opt"; value "$opt" $# "${2-}"; shift ;;
    *) die "unknown option '$opt' (see --help)" ;;
    esac
    case "$opt" in
    --quick) quick=1 ;;
    --json) json=1 ;;
    --dry-run) dry_run=1 ;;
    --base) base=$1 ;;
    --rows) rows=$1 ;;
    --rounds) count "$opt" "$1"; rounds=$1 ;;
    --threads) count "$opt" "$1"; threads=$1 ;;
    --gt-seconds) count "$opt" "$1"; gt_seconds=$1 ;;
    --startup-runs) count "$opt" "$1"; startup_runs=$1 ;;
    --mpi-ranks) count "$opt" "$1"; mpi_ranks=$1 ;;
    --scene) scene=$1 ;;
    --width) count "$opt" "$1"; width=$1 ;;
    --height) count "$opt" "$1"; height=$1 ;;
    --methods) methods=$1 ;;
    --cmake-args) cmake_args=$1 ;;
    --keep) keep=$1 ;;
    esac
    case "$opt" in --quick | --json | --dry-run) ;; *) shift ;; esac
done

# The rows: known names, each once; "all" alone.
if [ "$rows" = all ]; then
    rows=${all_rows// /,}
fi
selected=" "
IFS=, read -r -a wanted <<<"$rows"
[ "${#wanted[@]}" -gt 0 ] || die "--rows is empty"
for r in "${wanted[@]}"; do
    case " $all_rows " in *" $r "*) ;; *) die "unknown row '$r' in --rows (rows: all ${all_rows// /, })" ;; esac
    case "$selected" in *" $r "*) die "row '$r' given twice in --rows" ;; esac
    selected="$selected$r "
done
[ -n "$rounds" ] || { [ "$quick" = 1 ] && rounds=2 || rounds=5; }
[ -n "$gt_seconds" ] || { [ "$quick" = 1 ] && gt_seconds=2 || gt_seconds=8; }
if [ -n "$scene" ]; then
    [ -f "$scene" ] || die "no scene file '$scene'"
    scene=$(readlink -f "$scene")
fi

src=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel 2>/dev/null) || die "not inside a git checkout"
base_sha=$(git -C "$src" rev-parse --verify --quiet "$base^{commit}") || die "unknown commit '$base'"
base_short=$(git -C "$src" rev-parse --short "$base_sha")
cur_rev=$(git -C "$src" rev-parse --short HEAD)$([ -z "$(git -C "$src" status --porcelain --untracked-files=no)" ] || echo "+dirty")

log() { echo "paired_bench: $*" >&2; }

if [ -n "$keep" ]; then
    work=$(mkdir -p "$keep" && readlink -f "$keep")
elif [ "$dry_run" = 1 ]; then
    work=${TMPDIR:-/tmp}/biref-paired.DRYRUN
else
    work=$(mktemp -d "${TMPDIR:-/tmp}/biref-paired.XXXXXX")
fi

if [ "$dry_run" = 0 ]; then
    # shellcheck disable=SC2317 # called by the trap
    cleanup() {
        git -C "$src" worktree remove --force "$work/base-src" >/dev/null 2>&1 || true
        [ -n "$keep" ] || rm -rf "$work"
    }
    trap cleanup EXIT
    # The base commit in a temporary detached worktree; the current tree as it is on disk.
    if [ ! -d "$work/base-src" ]; then
        git -C "$src" worktree add --detach "$work/base-src" "$base_sha" >/dev/null 2>&1
    elif [ "$(git -C "$work/base-src" rev-parse HEAD)" != "$base_sha" ]; then
        git -C "$work/base-src" checkout --detach --quiet "$base_sha"
    fi
    build() { # source dir, build dir
        log "building $1"
        # shellcheck disable=SC2086 # --cmake-args is a list of arguments
        if ! { cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release $cmake_args >"$2.log" 2>&1 &&
            nice cmake --build "$2" -j2 --target biref_cli >>"$2.log" 2>&1; }; then
            tail -20 "$2.log" >&2
            die "the build of $1 failed (log: $2.log)"
        fi
    }
    build "$work/base-src" "$work/base-build"
    build "$src" "$work/cur-build"
fi

# The rounds and the report: Python (standard library only, so any python3 will do).
export PB_SRC=$src PB_WORK=$work PB_BASE=$base_short PB_CURRENT=$cur_rev PB_ROWS=${selected# }
export PB_ROUNDS=$rounds PB_THREADS=$threads PB_QUICK=$quick PB_GT_SECONDS=$gt_seconds
export PB_STARTUP_RUNS=$startup_runs PB_MPI_RANKS=$mpi_ranks PB_SCENE=$scene PB_WIDTH=$width
export PB_HEIGHT=$height PB_METHODS=$methods PB_JSON=$json PB_DRY_RUN=$dry_run
python3 - <<'PYTHON'
import json, os, re, shutil, statistics, subprocess, sys, time

E = os.environ
src, work = E["PB_SRC"], E["PB_WORK"]
rounds, threads, quick = int(E["PB_ROUNDS"]), int(E["PB_THREADS"]), E["PB_QUICK"] == "1"
dry = E["PB_DRY_RUN"] == "1"
sides = {"base": (os.path.join(work, "base-build", "biref"), os.path.join(work, "base-src")),
         "current": (os.path.join(work, "cur-build", "biref"), src)}

def log(msg):
    print("paired_bench: " + msg, file=sys.stderr, flush=True)

def ex(name):
    return os.path.join(src, "examples", name)

# Frame sizes: the paper's 1920x1080 (quick: 960x540); supersampling at a quarter of that.
fw, fh = (960, 540) if quick else (1920, 1080)
sw, sh = fw // 2, fh // 2
a_scene = E["PB_SCENE"] or ex("fig9a.json")
a_w, a_h = int(E["PB_WIDTH"] or fw), int(E["PB_HEIGHT"] or fh)
mpi_threads = max(1, threads // int(E["PB_MPI_RANKS"]))

def bench(scene, w, h, method, antialias=None, max_seconds=1000):
    return {"kind": "bench", "scene": scene, "w": w, "h": h, "method": method, "antialias": antialias,
            "max_seconds": max_seconds}

ROWS = {
    "analytic": dict(bench(a_scene, a_w, a_h, E["PB_METHODS"]), what="%s %dx%d, %s" % (
        os.path.basename(a_scene)[:-5], a_w, a_h, E["PB_METHODS"])),
    "prefilter": dict(bench(ex("fig9a.json"), fw, fh, "analytic", "prefilter"),
                      what="fig9a %dx%d, analytic, prefilter" % (fw, fh)),
    "fig9c": dict(bench(ex("fig9c.json"), fw, fh, "analytic"), what="fig9c %dx%d, analytic, s/p" % (fw, fh)),
    "analyzer45": dict(bench(ex("fig9c_analyzer45.json"), fw, fh, "analytic"),
                       what="fig9c_analyzer45 %dx%d, analytic" % (fw, fh)),
    "expansion": dict(bench(ex("fig9a.json"), fw, fh, "expansion"), what="fig9a %dx%d, expansion" % (fw, fh)),
    "numeric-8": dict(bench(ex("fig9a.json"), fw, fh, "numeric-8"), what="fig9a %dx%d, numeric-8" % (fw, fh)),
    "numeric-32": dict(bench(ex("fig9a.json"), fw, fh, "numeric-32"), what="fig9a %dx%d, numeric-32" % (fw, fh)),
    "ground-truth": dict(bench(ex("fig9a.json"), fw, fh, "ground-truth", None, int(E["PB_GT_SECONDS"])),
                         what="fig9a %dx%d, ground truth (%s s of rows, scaled)" % (fw, fh, E["PB_GT_SECONDS"])),
    "ss1": {"kind": "render", "scene": ex("fig9a.json"), "w": sw, "h": sh, "args": ["--supersample", "1"],
            "what": "fig9a %dx%d render, 1 sample/pixel" % (sw, sh)},
    "ss4": {"kind": "render", "scene": ex("fig9a.json"), "w": sw, "h": sh, "args": ["--supersample", "4"],
            "what": "fig9a %dx%d render, 4x4 samples/pixel" % (sw, sh)},
    "startup": {"kind": "process", "scene": ex("fig9a.json"), "w": 640, "h": 360, "runs": int(E["PB_STARTUP_RUNS"]),
                "what": "biref render fig9a 640x360, whole process"},
    "render": {"kind": "process", "scene": ex("fig9a.json"), "w": fw, "h": fh, "runs": 1,
                     "what": "biref render fig9a %dx%d, whole process" % (fw, fh)},
    "mpi": {"kind": "mpi", "scene": ex("fig9a.json"), "w": fw, "h": fh, "runs": 1,
            "what": "mpirun -n %s biref render fig9a %dx%d, %d thread%s/rank" % (
                E["PB_MPI_RANKS"], fw, fh, mpi_threads, "" if mpi_threads == 1 else "s")},
}
# Ratios within each side: (name, numerator row, denominator row).
WITHIN = [("prefilter / point look-ups", "prefilter", "analytic"),
          ("world-fixed analyzer / s-p (fig9c)", "analyzer45", "fig9c"),
          ("expansion / analytic", "expansion", "analytic"),
          ("numeric-8 / analytic", "numeric-8", "analytic"),
          ("numeric-32 / analytic", "numeric-32", "analytic"),
          ("ground truth / analytic", "ground-truth", "analytic"),
          ("4x4 / 1 sample per pixel", "ss4", "ss1"),
          ("mpi / one process", "mpi", "render")]

def command(side, row, w=None, h=None, scene=None):
    """The argument list of one run of a row on one side."""
    binary = sides[side][0]
    w, h, scene = w or row["w"], h or row["h"], scene or row["scene"]
    out = os.path.join(work, "%s.out" % side)
    if row["kind"] == "bench":
        cmd = [binary, "bench", "--scene", scene, "--width", str(w), "--height", str(h), "--threads", str(threads),
               "--methods", row["method"], "--max-seconds", str(row["max_seconds"]), "--json"]
        if row["antialias"]:
            cmd += ["--antialias", row["antialias"]]
        return cmd
    render = [binary, "render", scene, "-o", out + ".png", "--width", str(w), "--height", str(h)]
    if row["kind"] == "render":
        return render + ["--threads", str(threads), "--json"] + row["args"]
    if row["kind"] == "process":
        return render + ["--threads", str(threads)]
    return ["mpirun", "-n", E["PB_MPI_RANKS"]] + render + ["--threads", str(mpi_threads)]

def run(cmd):
    """(exit status, wall ms, CPU ms of the process and its children, stdout, stderr). The output
    goes to files, read after the process has exited: a reader in a pipe would take one of the
    cores during the timed frame."""
    env = dict(os.environ)
    if os.geteuid() == 0 and cmd[0] == "mpirun":  # Open MPI refuses root without these
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    outp, errp = os.path.join(work, "run.stdout"), os.path.join(work, "run.stderr")
    with open(outp, "w") as o, open(errp, "w") as e:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=o, stderr=e, stdin=subprocess.DEVNULL, env=env)
        _, status, ru = os.wait4(p.pid, 0)
        wall = 1e3 * (time.perf_counter() - t0)
    p.returncode = os.waitstatus_to_exitcode(status)
    with open(outp) as o, open(errp) as e:
        return p.returncode, wall, 1e3 * (ru.ru_utime + ru.ru_stime), o.read(), e.read()

def measure(side, row, **size):
    """One measurement: {wall_ms, cpu_ms, ...} or a string saying why there is none."""
    rc, wall, cpu, out, err = run(command(side, row, **size))
    if rc != 0:
        lines = [l for l in err.splitlines() if l.strip()]
        return (lines[-1] if lines else "exit status %d" % rc)[:160]
    try:
        if row["kind"] == "bench":
            m = json.loads(out)["methods"][0]
            r = {"wall_ms": m["ms_per_frame"], "cpu_ms": m.get("cpu_ms_per_frame")}
            if m.get("extrapolated"):
                r["extrapolated_rows"] = m.get("rows_timed")
            return r
        if row["kind"] == "render":
            return {"wall_ms": json.loads(out)["ms"], "cpu_ms": None}
    except (ValueError, KeyError, IndexError, TypeError):
        return "unexpected output: " + out[:120].replace("\n", " ")
    return {"wall_ms": wall, "cpu_ms": cpu}

def lacks(side, row):
    """What this side lacks for the row before anything runs (MPI), or None."""
    if row["kind"] != "mpi":
        return None
    if not shutil.which("mpirun"):
        return "no mpirun on PATH"
    ldd = subprocess.run(["ldd", sides[side][0]], capture_output=True, text=True).stdout
    return None if "libmpi" in ldd else "built without MPI"

def probe(side, row, scene=None):
    """None if the row runs on this side (at a tiny size), else the reason."""
    r = measure(side, row, w=64, h=36, scene=scene)
    return r if isinstance(r, str) else None

names = E["PB_ROWS"].split()
if dry:
    print("base %s vs current %s (working tree %s); %d rounds, %d threads" % (E["PB_BASE"], E["PB_CURRENT"], src, rounds, threads))
    for n in names:
        print("%-13s %s\n              %s" % (n, ROWS[n]["what"], " ".join(command("current", ROWS[n]))))
    sys.exit(0)

load_before = open("/proc/loadavg").read().split()[:3]
log("base %s vs current %s; rows %s; %d rounds, %d threads" % (E["PB_BASE"], E["PB_CURRENT"], ", ".join(names), rounds, threads))
# Which side runs which row: a probe, and for the base the current scene file or else its own copy.
avail = {}
for n in names:
    row = ROWS[n]
    for side in sides:
        reason = lacks(side, row)
        if not reason:
            reason = probe(side, row)
            if reason and side == "base" and row["scene"].startswith(src + os.sep):
                own = os.path.join(sides["base"][1], os.path.relpath(row["scene"], src))
                if os.path.isfile(own) and probe(side, row, own) is None:
                    row["base_scene"] = own
                    reason = None
        avail[(n, side)] = reason
        if reason:
            log("%s: n/a on %s: %s" % (n, side, reason))

data = {(n, s): [] for n in names for s in sides}
for i in range(rounds):
    order = ["base", "current"] if i % 2 == 0 else ["current", "base"]
    for n in names:
        row, got = ROWS[n], {}
        for side in order:
            if avail[(n, side)]:
                continue
            scene = row.get("base_scene") if side == "base" else None
            runs = [measure(side, row, scene=scene) for _ in range(row.get("runs", 1))]
            bad = [r for r in runs if isinstance(r, str)]
            if bad:
                avail[(n, side)] = bad[0]
                log("%s: %s failed in round %d: %s" % (n, side, i + 1, bad[0]))
                continue
            best = sorted(runs, key=lambda r: r["wall_ms"])[len(runs) // 2]  # median run of the round
            data[(n, side)].append(best)
            got[side] = best
        if got:
            log("round %d %-13s " % (i + 1, n) + "  ".join(
                "%s %.1f ms%s" % (s, got[s]["wall_ms"], "" if got[s]["cpu_ms"] is None else " (cpu %.1f)" % got[s]["cpu_ms"])
                for s in ("base", "current") if s in got))
load_after = open("/proc/loadavg").read().split()[:3]

def median(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None

result_rows = []
for n in names:
    entry = {"row": n, "what": ROWS[n]["what"]}
    for side in sides:
        runs = data[(n, side)]
        if avail[(n, side)] or not runs:
            entry[side] = None
            entry[side + "_na"] = avail[(n, side)] or "no runs"
            continue
        entry[side] = {"wall_ms": median(r["wall_ms"] for r in runs), "cpu_ms": median(r["cpu_ms"] for r in runs),
                       "per_round": runs}
        ex_rows = [r.get("extrapolated_rows") for r in runs if "extrapolated_rows" in r]
        if ex_rows:
            entry[side]["extrapolated_from_rows"] = median(ex_rows)
        if side == "base" and "base_scene" in ROWS[n]:
            entry[side]["scene"] = ROWS[n]["base_scene"]
    b, c = entry["base"], entry["current"]
    pairs = list(zip(data[(n, "base")], data[(n, "current")])) if b and c else []
    entry["ratio_wall"] = median(x["wall_ms"] / y["wall_ms"] for x, y in pairs) if pairs else None
    entry["ratio_cpu"] = median(x["cpu_ms"] / y["cpu_ms"] for x, y in pairs
                                if x["cpu_ms"] and y["cpu_ms"]) if pairs else None
    result_rows.append(entry)

by = {e["row"]: e for e in result_rows}
within = []
for label, num, den in WITHIN:
    if num in by and den in by:
        w = {"ratio": label}
        for side in sides:
            a, d = by[num][side], by[den][side]
            w[side] = a["wall_ms"] / d["wall_ms"] if a and d else None
        within.append(w)

out = {"base": E["PB_BASE"], "current": E["PB_CURRENT"], "rounds": rounds, "threads": threads, "quick": quick,
       "load_before": " ".join(load_before), "load_after": " ".join(load_after), "rows": result_rows,
       "within_each_side": within}
if E["PB_JSON"] == "1":
    print(json.dumps(out, indent=2))
    sys.exit(0)

def ms(v):
    if v is None:
        return "-"
    if v >= 1e5:
        return "%.0f s" % (v / 1e3) if v < 6e5 else "%.1f min" % (v / 6e4)
    return "%.0f" % v if v >= 1000 else "%.1f" % v

def ratio(v):
    return "n/a" if v is None else "%.2fx" % v

print("base %s vs current %s, %d rounds (alternating), %d threads; medians in ms unless marked; speed-up = median of base/current"
      % (out["base"], out["current"], rounds, threads))
head = ("row", "measurement", "base", "current", "speed-up", "base cpu", "cur. cpu", "cpu speed-up")
fmt = "%-13s %-56s %9s %9s %9s %9s %9s %12s"
print(fmt % head)
notes = []
for e in result_rows:
    b, c = e["base"], e["current"]
    what = e["what"]
    ext = (c or b or {}).get("extrapolated_from_rows")
    if ext:
        what += " *"
    print(fmt % (e["row"], what[:56], ms(b and b["wall_ms"]) if b else "n/a", ms(c and c["wall_ms"]) if c else "n/a",
                 ratio(e["ratio_wall"]), ms(b and b["cpu_ms"]) if b else "n/a", ms(c and c["cpu_ms"]) if c else "n/a",
                 ratio(e["ratio_cpu"])))
    for side in sides:
        if e.get(side + "_na"):
            notes.append("%s on %s: n/a (%s)" % (e["row"], side, e[side + "_na"]))
        elif e[side] and e[side].get("scene"):
            notes.append("%s on base: its own copy of the scene (the current one is refused)" % e["row"])
    if ext:
        notes.append("* %s: extrapolated, timed on %g evenly spaced rows (current)" % (e["row"], ext))
for n in notes:
    print("  " + n)
if within:
    print("within each side (wall; first / second, > 1: the first costs more):")
    for w in within:
        print("  %-40s base %8s   current %8s" % (w["ratio"], ratio(w["base"]), ratio(w["current"])))
print("load average before %s, after %s" % (out["load_before"], out["load_after"]))
PYTHON
exit $?
}
