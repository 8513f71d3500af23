#!/usr/bin/env bash
# Input files that are not what they should be are refused with one line that says what is wrong,
# before the memory for them is taken: a device or a binary file (a NUL byte), a directory, a
# scene over its size limit, a stress grid whose rows cannot fill the lattice their coordinates
# span, numbers too long or too large for their column, nodes that cannot be triangulated.
set -u
. "$(dirname "$0")/lib.sh"
named() { # DESCRIPTION PATTERN: the last expect_error's message matches
  grep -Eq -e "$2" "$tmpdir/err" || { echo "FAIL ($1): message does not match /$2/"; sed 's/^/  stderr: /' "$tmpdir/err"; fails=$((fails + 1)); }
}
d=$tmpdir
nodes=(--columns sxx=S11,syy=S22,txy=S12)

# /dev/zero is refused at its first block, not read up to the size limit.
expect_error "scene /dev/zero" render /dev/zero -o "$d/z.png"
named "scene /dev/zero" "/dev/zero: cannot read: not a text file"
expect_error "grid /dev/zero" photoelastic --stress-grid /dev/zero -o "$d/z.png"
named "grid /dev/zero" "not a text file"
expect_error "nodes /dev/zero" photoelastic --stress-nodes /dev/zero -o "$d/z.png"
named "nodes /dev/zero" "not a text file"
expect_error "boundary /dev/zero" photoelastic --stress-nodes examples/photoelastic/disk_nodes.csv "${nodes[@]}" \
  --boundary /dev/zero -o "$d/z.png"
named "boundary /dev/zero" "not a text file"
expect_error "gl-data /dev/zero" gl-data -o "$d/z.js" /dev/zero

# A directory is not "an I/O error".
expect_error "scene is a directory" render "$d" -o "$d/z.png"
named "scene is a directory" "is a directory"
expect_error "grid is a directory" photoelastic --stress-grid "$d" -o "$d/z.png"
named "grid is a directory" "is a directory"

# Scenes: at most 1 MiB, refused by their size before they are read.
{ printf '{"camera": {"position": [1, 1, 1], "look_at": [0, 0, 0], "fov_deg": 45, "width": 8, "height": 8, '
  printf '"comment": "'; head -c 1100000 /dev/zero | tr '\0' a; printf '"}}'; } >"$d/big.json"
expect_error "scene over 1 MiB" render "$d/big.json" -o "$d/z.png"
named "scene over 1 MiB" "file too large \([0-9]+ bytes; the limit is 1 MiB\)"
head -c 1100000 "$d/big.json" | cat - | {
  "$BIREF" render /dev/stdin -o "$d/z.png" >/dev/null 2>"$d/err"
  [ $? -eq 2 ] && grep -q "file too large (over 1 MiB)" "$d/err" || { echo "FAIL (scene over 1 MiB from a pipe): $(cat "$d/err")"; exit 1; }
} || fails=$((fails + 1))

# A control character inside a scene's string (strict JSON).
printf '{"camera": {"position": [1, 1, 1], "look_at": [0, 0, 0], "fov_deg": 45, "width": 8, "height": 8, "comment": "a\tb"}}' \
  >"$d/tab.json"
expect_error "tab in a scene string" render "$d/tab.json" -o "$d/z.png"
named "tab in a scene string" "raw control character"

# A grid of a few rows whose coordinates span millions of nodes: irregular, said before the lattice
# is allocated (and said so, not "no row for the node ...").
{ echo x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa
  for x in $(seq 0 1999); do echo "$x,0,0,0,0"; done
  for y in $(seq 1 1999); do echo "0,$y,0,0,0"; done; } >"$d/sparse.csv"
expect_error "sparse grid" photoelastic --stress-grid "$d/sparse.csv" -o "$d/z.png"
named "sparse grid" "irregular grid: 3999 rows, but their x and y values span 2000 x 2000 nodes"

# Numbers too long, or too large for their column, say so.
long=$(head -c 200000 /dev/zero | tr '\0' 0)
{ echo x_mm,y_mm,sxx_MPa,syy_MPa,txy_MPa; echo "0,0,$long,0,0"; echo 1,0,0,0,0; echo 0,1,0,0,0; echo 1,1,0,0,0; } >"$d/long.csv"
expect_error "200000-digit zero in a grid" photoelastic --stress-grid "$d/long.csv" -o "$d/z.png"
named "200000-digit zero in a grid" "a field of 200000 characters is too long for a number"
{ echo x,y,sxx,syy,txy; echo "0,0,1e308,0,0"; echo 1,0,0,0,0; echo 0,1,0,0,0; } >"$d/huge_nodes.csv"
expect_error "1e308 MPa in nodes" photoelastic --stress-nodes "$d/huge_nodes.csv" -o "$d/z.png"
named "1e308 MPa in nodes" "line 2, column sxx: .*out of range"
{ echo x,y,sxx,syy,txy; echo "-1e308,0,0,0,0"; echo 1e308,0,0,0,0; echo 0,1e308,0,0,0; } >"$d/far_nodes.csv"
expect_error "nodes at 1e308 mm" photoelastic --stress-nodes "$d/far_nodes.csv" -o "$d/z.png"
named "nodes at 1e308 mm" "line 2, column x: .*out of range"
{ echo x,y,sxx,syy,txy; echo 0,0,0,0,0; echo 1,1,0,0,0; echo 2,2,0,0,0; echo 3,3,0,0,0; } >"$d/line_nodes.csv"
expect_error "nodes on a line" photoelastic --stress-nodes "$d/line_nodes.csv" -o "$d/z.png"
named "nodes on a line" "one line|do not span an area"
finish
