#!/usr/bin/env bash
# Output files: atomic replace of regular files (mode kept, umask honoured), write-through for
# symlinks, FIFOs and "-", outputs that would overwrite an input refused, long names, no
# temporary files or empty outputs left behind by failures or interrupts.
set -u
. "$(dirname "$0")/lib.sh"
small=(--width 16 --height 10 --quiet)
scene=$tmpdir/s.json
cat >"$scene" <<'JSON'
{"camera": {"position": [1.5, 1.2, 2.5], "look_at": [0, 0, 0], "fov_deg": 45, "width": 16, "height": 10},
 "slabs": [{"center": [0, 0, 0], "size": [2, 2], "thickness_um": 40, "normal": [0, 0, 1],
            "tangent": [1, 0, 0], "axis": [0.3, 0.6, 0.5], "eta_o": 1.54, "eta_e": 1.55}],
 "light": {"panel": {"center": [0, 0, -2], "size": [3, 3], "normal": [0, 0, 1], "radiance": 1}}}
JSON
fail() { echo "FAIL ($1)"; fails=$((fails + 1)); }
is_png() { [ "$(head -c 4 "$1" | tail -c 3)" = "PNG" ]; }
mode() { stat -c %a "$1"; }

# A new file honours the umask; an existing file keeps its mode.
(umask 027 && "$BIREF" render "$scene" -o "$tmpdir/new.png" "${small[@]}" >/dev/null) || fail "render new"
[ "$(mode "$tmpdir/new.png")" = 640 ] || fail "umask 027 gives 640, got $(mode "$tmpdir/new.png")"
(umask 022 && "$BIREF" render "$scene" -o "$tmpdir/pub.png" "${small[@]}" >/dev/null) || fail "render pub"
[ "$(mode "$tmpdir/pub.png")" = 644 ] || fail "umask 022 gives 644, got $(mode "$tmpdir/pub.png")"
chmod 600 "$tmpdir/new.png"
expect_ok "replace existing" render "$scene" -o "$tmpdir/new.png" "${small[@]}"
[ "$(mode "$tmpdir/new.png")" = 600 ] || fail "existing mode 600 kept, got $(mode "$tmpdir/new.png")"
is_png "$tmpdir/new.png" || fail "replaced file is a PNG"

# A symlink is written through: the link stays, its target gets the image.
echo old >"$tmpdir/target.png"
ln -s target.png "$tmpdir/link.png"
expect_ok "through symlink" render "$scene" -o "$tmpdir/link.png" "${small[@]}"
[ -L "$tmpdir/link.png" ] || fail "symlink replaced by a file"
is_png "$tmpdir/target.png" || fail "symlink target written"

# A FIFO is written into, not replaced.
mkfifo "$tmpdir/pipe"
cat "$tmpdir/pipe" >"$tmpdir/from-pipe" &
reader=$!
expect_ok "into FIFO" render "$scene" -o "$tmpdir/pipe" "${small[@]}"
wait "$reader"
[ -p "$tmpdir/pipe" ] || fail "FIFO replaced by a file"
is_png "$tmpdir/from-pipe" || fail "FIFO reader got the PNG"

# "-" is standard output; the summary then goes to standard error.
"$BIREF" render "$scene" -o - "${small[@]}" >"$tmpdir/stdout.png" 2>/dev/null || fail "render -o -"
is_png "$tmpdir/stdout.png" || fail "-o - writes a PNG to standard output"
expect_error "json with -o -" render "$scene" -o - --json "${small[@]}"

# A 250-character file name works (the temporary name must not grow it past NAME_MAX).
long=$(printf 'x%.0s' $(seq 246)).png
expect_ok "250-character name" render "$scene" -o "$tmpdir/$long" "${small[@]}"
is_png "$tmpdir/$long" || fail "250-character name written"

# Outputs that are inputs are refused, and the input survives.
cp "$scene" "$tmpdir/keep.json"
expect_error "render onto its scene" render "$tmpdir/keep.json" -o "$tmpdir/keep.json" "${small[@]}"
cmp -s "$scene" "$tmpdir/keep.json" || fail "scene overwritten"
ln -s keep.json "$tmpdir/keep-link.png"
expect_error "render onto its scene through a link" render "$tmpdir/keep.json" -o "$tmpdir/keep-link.png" "${small[@]}"
cmp -s "$scene" "$tmpdir/keep.json" || fail "scene overwritten through a link"
expect_error "pfm onto the png" render "$scene" -o "$tmpdir/pub.png" --pfm "$tmpdir/pub.png" "${small[@]}"
cp "$tmpdir/pub.png" "$tmpdir/a.png"
cp "$tmpdir/a.png" "$tmpdir/a-copy.png"
expect_error "diff onto an input" diff "$tmpdir/a.png" "$tmpdir/pub.png" -o "$tmpdir/a.png"
cmp -s "$tmpdir/a.png" "$tmpdir/a-copy.png" || fail "diff input overwritten"
printf 'x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa\n0,0,1,0,0\n1,0,1,0,0\n0,1,1,0,0\n1,1,1,0,0\n' >"$tmpdir/g.csv"
cp "$tmpdir/g.csv" "$tmpdir/g-copy.csv"
expect_error "photoelastic onto its grid" photoelastic --stress-grid "$tmpdir/g.csv" -o "$tmpdir/g.csv" --size 20
cmp -s "$tmpdir/g.csv" "$tmpdir/g-copy.csv" || fail "stress grid overwritten"

# Unwritable places: one error line, nothing created.
expect_error "missing directory" render "$scene" -o "$tmpdir/no/such/dir.png" "${small[@]}"
expect_error "directory as output" render "$scene" -o "$tmpdir" "${small[@]}"

# An interrupted figure run leaves neither empty outputs nor temporary files.
mkdir "$tmpdir/fig"
"$BIREF" figure table1 --quick --scenes "$(dirname "$0")/../../examples" -o "$tmpdir/fig" >/dev/null 2>&1 &
pid=$!
sleep 1
kill -TERM "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
for f in "$tmpdir/fig"/* "$tmpdir/fig"/.[!.]*; do
  [ -e "$f" ] || continue
  [ -s "$f" ] || fail "interrupted figure left the empty file $(basename "$f")"
done

# No temporary files anywhere after all of the above.
litter=$(find "$tmpdir" -name '.biref-*' -o -name '*.tmp*')
[ -z "$litter" ] || fail "temporary files left: $litter"
finish
