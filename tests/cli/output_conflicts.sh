#!/usr/bin/env bash
# Every command that writes files, with each output equal to each of its inputs and to each of its
# other outputs (literal, derived per step, per map, in an output directory; the same name, another
# spelling, a hard link or a symbolic link): refused with one line and status 2 before anything
# is written, every file left as it was.
set -u
. "$(dirname "$0")/lib.sh"
fail() { echo "FAIL ($1)"; fails=$((fails + 1)); }
d=$tmpdir
cat >"$d/s.json" <<'JSON'
{"camera": {"position": [1.5, 1.2, 2.5], "look_at": [0, 0, 0], "fov_deg": 45, "width": 8, "height": 6},
 "slabs": [{"center": [0, 0, 0], "size": [2, 2], "thickness_um": 40, "normal": [0, 0, 1],
            "tangent": [1, 0, 0], "axis": [0.3, 0.6, 0.5], "eta_o": 1.54, "eta_e": 1.55}],
 "light": {"panel": {"center": [0, 0, -2], "size": [3, 3], "normal": [0, 0, 1], "radiance": 1}}}
JSON
cp "$d/s.json" "$d/t.json"
"$BIREF" render "$d/s.json" -o "$d/a.png" --quiet >/dev/null || fail "setup a.png"
"$BIREF" render "$d/s.json" -o "$d/b.png" --quiet >/dev/null || fail "setup b.png"
cp examples/photoelastic/gradient.csv "$d/grid.csv"
cp examples/photoelastic/disk_nodes.csv "$d/nodes.csv"
cp examples/photoelastic/disk_boundary.csv "$d/boundary.csv"
cols=(--columns sxx=S11,syy=S22,txy=S12)

# refused DESCRIPTION PATTERN FILES... -- ARGS...: status 2, one line on stderr matching PATTERN,
# nothing on stdout, and every listed file byte for byte as before.
refused() {
  local what=$1 pattern=$2; shift 2
  local files=()
  while [ "$1" != "--" ]; do files+=("$1"); shift; done
  shift
  local i=0
  for f in "${files[@]}"; do cp -P "$f" "$d/before.$i" 2>/dev/null; i=$((i + 1)); done
  local rc=0
  "$BIREF" "$@" >"$d/out" 2>"$d/err" </dev/null || rc=$?
  if [ "$rc" -ne 2 ] || [ "$(wc -l <"$d/err")" -ne 1 ] || [ -s "$d/out" ]; then
    fail "$what: rc=$rc, stderr: $(head -3 "$d/err")"
  elif ! grep -Eq "$pattern" "$d/err"; then
    fail "$what: message does not match /$pattern/: $(cat "$d/err")"
  fi
  i=0
  for f in "${files[@]}"; do
    cmp -s "$f" "$d/before.$i" || fail "$what: $f changed"
    i=$((i + 1))
  done
}
over='would overwrite the input file'
same='are the same file'

# render: SCENE; -o, --pfm, --chroma-map.
r=(render "$d/s.json" --quiet)
refused "render -o SCENE" "$over" "$d/s.json" -- "${r[@]}" -o "$d/s.json"
refused "render --pfm SCENE" "$over" "$d/s.json" -- "${r[@]}" -o "$d/n.png" --pfm "$d/s.json"
refused "render --chroma-map SCENE" "$over" "$d/s.json" -- "${r[@]}" -o "$d/n.png" --chroma-map "$d/s.json"
refused "render -o = --pfm" "$same" "$d/a.png" -- "${r[@]}" -o "$d/a.png" --pfm "$d/a.png"
refused "render -o = --pfm, new file" "$same" -- "${r[@]}" -o "$d/new.png" --pfm "$d/new.png"
[ -e "$d/new.png" ] && fail "render -o = --pfm wrote the new file"
refused "render -o = --chroma-map" "$same" "$d/a.png" -- "${r[@]}" -o "$d/a.png" --chroma-map "$d/./a.png"
refused "render --pfm = --chroma-map" "$same" "$d/a.png" -- "${r[@]}" -o "$d/n.png" --pfm "$d/x.pfm" \
  --chroma-map "$d/sub/../x.pfm"
ln "$d/a.png" "$d/hard.png"
refused "render -o = --chroma-map, hard link" "$same" "$d/a.png" -- "${r[@]}" -o "$d/a.png" --chroma-map "$d/hard.png"
ln -s a.png "$d/soft.png"
refused "render -o = --chroma-map, symbolic link" "$same" "$d/a.png" -- "${r[@]}" -o "$d/soft.png" --chroma-map "$d/a.png"
ln -s s.json "$d/scene-link.png"
refused "render -o SCENE through a link" "$over" "$d/s.json" -- "${r[@]}" -o "$d/scene-link.png"
ln -s missing.png "$d/dangling.png"
refused "render -o = --chroma-map, dangling link" "$same" -- "${r[@]}" -o "$d/missing.png" --chroma-map "$d/dangling.png"
refused "render -o - and --pfm -" 'standard output' -- "${r[@]}" -o - --pfm -

# diff: A, B; -o.
refused "diff -o A" "$over" "$d/a.png" -- diff "$d/a.png" "$d/b.png" -o "$d/a.png"
refused "diff -o B" "$over" "$d/b.png" -- diff "$d/a.png" "$d/b.png" -o "$d/b.png"

# gl-data: SCENE...; -o.
refused "gl-data -o SCENE" "$over" "$d/s.json" -- gl-data -o "$d/s.json" "$d/s.json"
refused "gl-data -o second SCENE" "$over" "$d/t.json" -- gl-data -o "$d/t.json" "$d/s.json" "$d/t.json"

# photoelastic: --stress-grid, --stress-nodes, --boundary; -o (a picture, a map, a PFM, the images
# of a phase-stepped set).
refused "photoelastic -o --stress-grid" "$over" "$d/grid.csv" -- photoelastic --stress-grid "$d/grid.csv" \
  --map fringe-order -o "$d/grid.csv"
refused "photoelastic -o --stress-nodes" "$over" "$d/nodes.csv" -- photoelastic --stress-nodes "$d/nodes.csv" \
  "${cols[@]}" --map sigma1 -o "$d/nodes.csv"
refused "photoelastic -o --boundary" "$over" "$d/boundary.csv" -- photoelastic --stress-nodes "$d/nodes.csv" \
  "${cols[@]}" --boundary "$d/boundary.csv" --map sigma1 -o "$d/boundary.csv"
cp "$d/grid.csv" "$d/st-1.png"
refused "photoelastic --phase-steps image 1 = --stress-grid" "$over" "$d/st-1.png" -- photoelastic \
  --stress-grid "$d/st-1.png" --light mono --phase-steps 4 -o "$d/st.png"
cp "$d/grid.csv" "$d/st-3.pfm"
refused "photoelastic --phase-steps image 3 = --stress-grid" "$over" "$d/st-3.pfm" -- photoelastic \
  --stress-grid "$d/st-3.pfm" --light mono --phase-steps 6 -o "$d/st.pfm"
echo keep >"$d/ps-1.png"
ln -s ps-1.png "$d/ps-2.png"
refused "photoelastic --phase-steps image 2 = image 1" "$same" "$d/ps-1.png" -- photoelastic --preset disk \
  --light mono --phase-steps 4 -o "$d/ps.png"

# photoelastic demodulate: IMAGE...; five maps in -o DIR.
"$BIREF" photoelastic --preset disk --light mono --phase-steps 4 --size 16 -o "$d/steps/q.pfm" >/dev/null 2>&1 ||
  { mkdir -p "$d/steps" && "$BIREF" photoelastic --preset disk --light mono --phase-steps 4 --size 16 \
    -o "$d/steps/q.pfm" >/dev/null; } || fail "setup phase steps"
cp "$d/steps/q-1.pfm" "$d/steps/isoclinic.pfm"
imgs=("$d/steps/isoclinic.pfm" "$d/steps/q-2.pfm" "$d/steps/q-3.pfm" "$d/steps/q-4.pfm")
refused "demodulate map in -o DIR = IMAGE" "$over" "${imgs[@]}" -- photoelastic demodulate "${imgs[@]}" \
  --zero-order 1,1 -o "$d/steps"
mkdir "$d/maps"
echo keep >"$d/maps/modulation.csv"
ln -s modulation.csv "$d/maps/background.csv"
refused "demodulate map = another map" "$same" "$d/maps/modulation.csv" -- photoelastic demodulate \
  "$d/steps/q-"{1,2,3,4}.pfm --zero-order 1,1 --format csv -o "$d/maps"

# figure: the scenes of --scenes; the files in -o DIR.
mkdir -p "$d/fig" "$d/scenes"
cp "$d/s.json" "$d/fig/fig9_a.png"
ln -s ../fig/fig9_a.png "$d/scenes/fig9a.json"
if "$BIREF" figure --help >/dev/null 2>&1; then
  refused "figure -o DIR file = a scene" "$over" "$d/fig/fig9_a.png" -- figure fig9 --quick -o "$d/fig" \
    --scenes "$d/scenes"
fi

# accuracy: --materials; --csv, --markdown, --plot-dir's pictures.
cat >"$d/m.json" <<'JSON'
[{"name": "m", "eta_o": 1.54, "eta_e": 1.55, "axis": [0, 1, 0], "thickness_um": 40}]
JSON
acc=(accuracy --materials "$d/m.json" --theta-max-deg 1 --azimuths 1 --reference-samples 64 --check-samples 0)
refused "accuracy --csv --materials" "$over" "$d/m.json" -- "${acc[@]}" --csv "$d/m.json"
refused "accuracy --markdown --materials" "$over" "$d/m.json" -- "${acc[@]}" --markdown "$d/m.json"
echo keep >"$d/r.csv"
refused "accuracy --csv = --markdown" "$same" "$d/r.csv" -- "${acc[@]}" --csv "$d/r.csv" --markdown "$d/r.csv"
cp "$d/m.json" "$d/fig/accuracy_vs_theta.png"
refused "accuracy --plot-dir picture = --materials" "$over" "$d/fig/accuracy_vs_theta.png" -- accuracy \
  --materials "$d/fig/accuracy_vs_theta.png" --theta-max-deg 1 --azimuths 1 --plot-dir "$d/fig"
refused "accuracy --plot-dir picture = --csv" "$same" -- "${acc[@]}" --plot-dir "$d/fig" \
  --csv "$d/fig/accuracy_vs_theta.png"

# An output named with another format's extension is refused (render -o x.pfm wrote a PNG).
ext='writes .*, but the name ends in'
refused "render -o x.pfm" "$ext" -- "${r[@]}" -o "$d/x.pfm"
refused "render --pfm x.png" "$ext" -- "${r[@]}" -o "$d/n.png" --pfm "$d/y.png"
refused "render --chroma-map x.csv" "$ext" -- "${r[@]}" -o "$d/n.png" --chroma-map "$d/y.CSV"
refused "photoelastic -o x.pfm" "$ext" -- photoelastic --preset disk -o "$d/x.pfm"
refused "photoelastic --format pfm -o x.png" "$ext" -- photoelastic --preset disk --format pfm -o "$d/x.png"
refused "gl-data -o x.json" "$ext" -- gl-data -o "$d/x.json" "$d/s.json"
refused "diff -o x.pfm" "$ext" -- diff "$d/a.png" "$d/b.png" -o "$d/x.pfm"
refused "accuracy --csv x.md" "$ext" -- "${acc[@]}" --csv "$d/x.md"
for f in x.pfm y.png y.CSV x.json x.md; do [ -e "$d/$f" ] && fail "$f written"; done
expect_ok "render -o without an extension" render "$d/s.json" --quiet -o "$d/plain"

# A character device is not a file: several outputs may go to /dev/null.
expect_ok "render -o and --pfm to /dev/null" render "$d/s.json" --quiet -o /dev/null --pfm /dev/null

finish
