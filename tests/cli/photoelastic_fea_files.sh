#!/usr/bin/env bash
# biref photoelastic --fea: finite-element results read with their elements. The plate with a hole
# as CalculiX .frd and as .vtu (and as ASCII, appended-raw and legacy VTK) gives the same
# fringe-order map; the map agrees with an independent evaluation of the elements' shape functions
# (numpy + meshio); the hole has no material without a boundary file; --window-mm is honoured;
# 3-D cells, unknown arrays and cell data are refused with one line. Uses /usr/bin/python3 (Debian's
# numpy and meshio).
set -u
. "$(dirname "$0")/lib.sh"
ex=examples/photoelastic/fea
PY=/usr/bin/python3
map=(--thickness-mm 3 --light mono --lambda-nm 589 --size 120 --margin-pct 0 --map fringe-order)

expect_ok "frd" photoelastic --fea "$ex/plate_hole.frd" "${map[@]}" -o "$tmpdir/frd.csv"
expect_grep "frd holes" "120 x 120 px, range .*, [0-9]+ pixels without material"
expect_ok "vtu" photoelastic --fea "$ex/plate_hole.vtu" "${map[@]}" -o "$tmpdir/vtu.csv"
same() { # same A B LIMIT: the maps agree to LIMIT, NaN at the same pixels
  paste -d, "$1" "$2" | awk -F, -v lim="$3" -v what="$1 vs $2" 'NR > 1 {
      if (($3 == "nan") != ($6 == "nan")) bad++; else if ($3 != "nan") { d = $3 - $6; if (d < 0) d = -d; if (d > m) m = d; n++ } }
    END { if (bad || n < 5000 || m > lim) { printf "FAIL (%s: %d pixels, max |dN| %g, %d NaN mismatches)\n", what, n, m, bad; exit 1 } }'
}
same "$tmpdir/frd.csv" "$tmpdir/vtu.csv" 1e-4 || fails=$((fails + 1))

# NaN exactly inside the hole (r < 5 mm) and nowhere else on the plate, with no boundary file.
awk -F, 'NR > 1 { r = sqrt($1 * $1 + $2 * $2); if (r < 4.9 && $3 != "nan") bad++; if (r > 5.1 && $3 == "nan") bad++; if (r < 4.9) h++ }
  END { if (bad || h < 200) { print "FAIL (hole: " bad + 0 " pixels wrong of " h + 0 " in the hole)"; exit 1 } }' "$tmpdir/frd.csv" ||
  fails=$((fails + 1))

# The same data in other VTK encodings: ASCII XML, appended raw XML, legacy binary and ASCII.
$PY - "$ex/plate_hole.vtu" "$tmpdir" <<'PY' || fails=$((fails + 1))
import struct, sys
import meshio, numpy as np
m = meshio.read(sys.argv[1]); d = sys.argv[2]
meshio.write(d + "/ascii.vtu", m, binary=False)
meshio.write(d + "/legacy.vtk", m, binary=True)
meshio.write(d + "/legacy_ascii.vtk", m, binary=False)
# Appended raw data, written by hand: each block a UInt32 byte count, then the values.
blocks, arrays = [], []
def add(name, a, vtype, nc):
    off = sum(len(b) for b in blocks)
    raw = np.ascontiguousarray(a).tobytes()
    blocks.append(struct.pack("<I", len(raw)) + raw)
    return '<DataArray type="%s" Name="%s" NumberOfComponents="%d" format="appended" offset="%d"/>' % (vtype, name, nc, off)
conn = np.concatenate([c.data.ravel() for c in m.cells]).astype("<i8")
offs = np.cumsum([c.data.shape[1] for c in m.cells for _ in range(len(c.data))]).astype("<i8")
vt = {"triangle": 5, "triangle6": 22, "quad": 9, "quad8": 23}
types = np.concatenate([np.full(len(c.data), vt[c.type], "u1") for c in m.cells])
pts = add("Points", m.points.astype("<f8"), "Float64", 3)
S = add("S", m.point_data["S"].astype("<f8"), "Float64", 6)
c1, c2, c3 = add("connectivity", conn, "Int64", 1), add("offsets", offs, "Int64", 1), add("types", types, "UInt8", 1)
head = ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt32">\n'
        '<UnstructuredGrid><Piece NumberOfPoints="%d" NumberOfCells="%d">\n<Points>%s</Points>\n<Cells>%s%s%s</Cells>\n'
        '<PointData>%s</PointData>\n</Piece></UnstructuredGrid>\n<AppendedData encoding="raw">\n_'
        % (len(m.points), len(types), pts, c1, c2, c3, S))
open(d + "/appended.vtu", "wb").write(head.encode() + b"".join(blocks) + b"\n</AppendedData>\n</VTKFile>\n")
PY
for v in ascii.vtu appended.vtu legacy.vtk legacy_ascii.vtk; do
  expect_ok "$v" photoelastic --fea "$tmpdir/$v" "${map[@]}" -o "$tmpdir/$v.csv"
  same "$tmpdir/vtu.csv" "$tmpdir/$v.csv" 1e-6 || fails=$((fails + 1))
done

# An independent evaluation: each pixel centre located by brute force in the elements of the .vtu
# (Newton on the isoparametric map, shape functions written out again here), the stresses
# interpolated, N = h C (s1 - s2) / lambda.
$PY - "$ex/plate_hole.vtu" "$tmpdir/vtu.csv" <<'PY' || fails=$((fails + 1))
import sys
import meshio, numpy as np
m = meshio.read(sys.argv[1])
P = m.points[:, :2]; S = m.point_data["S"]
rows = np.genfromtxt(sys.argv[2], delimiter=",", skip_header=1)
xy, N = rows[:, :2], rows[:, 2]
def shapes(kind, r, s):
    if kind == "quad8":
        c = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
        Nc = [(1 + a * r) * (1 + b * s) * (a * r + b * s - 1) / 4 for a, b in c]
        Nm = [(1 - r * r) * (1 - s) / 2, (1 + r) * (1 - s * s) / 2, (1 - r * r) * (1 + s) / 2, (1 - r) * (1 - s * s) / 2]
        return np.array(Nc + Nm)
    t = 1 - r - s
    return np.array([t * (2 * t - 1), r * (2 * r - 1), s * (2 * s - 1), 4 * t * r, 4 * r * s, 4 * s * t])
def jac(kind, X, r, s, h=1e-7):
    f = lambda a, b: shapes(kind, a, b).T @ X
    return f(r, s), (f(r + h, s) - f(r - h, s)) / (2 * h), (f(r, s + h) - f(r, s - h)) / (2 * h)
val = np.full((len(xy), 3), np.nan)
for cb in m.cells:
    for e in cb.data:
        X = P[e]
        lo, hi = X.min(0) - 0.2 * np.ptp(X, 0), X.max(0) + 0.2 * np.ptp(X, 0)
        k = np.where((xy >= lo).all(1) & (xy <= hi).all(1) & np.isnan(val[:, 0]))[0]
        if not len(k): continue
        r = np.zeros(len(k)) + (0 if cb.type == "quad8" else 1 / 3); s = r.copy()
        for _ in range(30):
            x, xr, xs = jac(cb.type, X, r, s)
            fx, fy = x[:, 0] - xy[k, 0], x[:, 1] - xy[k, 1]
            det = xr[:, 0] * xs[:, 1] - xs[:, 0] * xr[:, 1]
            dr = (xs[:, 1] * fx - xs[:, 0] * fy) / det; ds = (-xr[:, 1] * fx + xr[:, 0] * fy) / det
            r, s = np.clip(r - dr, -5, 5), np.clip(s - ds, -5, 5)
        t = 1e-9
        x, _, _ = jac(cb.type, X, r, s)
        conv = np.hypot(x[:, 0] - xy[k, 0], x[:, 1] - xy[k, 1]) < 1e-9 * np.ptp(X)
        ins = conv & ((np.abs(r) <= 1 + t) & (np.abs(s) <= 1 + t) if cb.type == "quad8" else (r >= -t) & (s >= -t) & (r + s <= 1 + t))
        Ns = shapes(cb.type, r[ins], s[ins])
        val[k[ins]] = Ns.T @ S[e][:, [0, 1, 3]]
d = np.sqrt((val[:, 0] - val[:, 1]) ** 2 + 4 * val[:, 2] ** 2)
Nref = 3e-3 * 78e-12 * d * 1e6 / 589e-9
both = ~np.isnan(N) & ~np.isnan(Nref)
err = np.abs(N[both] - Nref[both]).max()
mism = int((np.isnan(N) != np.isnan(Nref)).sum())
print("independent interpolation: %d pixels, max |dN| %.2e, %d NaN mismatches" % (both.sum(), err, mism))
if err > 1e-4 or mism or both.sum() < 5000: print("FAIL (independent interpolation)"); sys.exit(1)
PY

# The window with --fea: a zoom on the hole's edge.
expect_ok "window" photoelastic --fea "$ex/plate_hole.vtu" --thickness-mm 3 --window-mm 3,-2,7,2 --size 40 \
  --map fringe-order -o "$tmpdir/w.csv"
awk -F, 'NR > 1 { n++; if ($1 < 3 || $1 > 7 || $2 < -2 || $2 > 2) bad++ } END { if (n != 1600 || bad) { print "FAIL (window)"; exit 1 } }' \
  "$tmpdir/w.csv" || fails=$((fails + 1))
expect_ok "disk picture" photoelastic --fea "$ex/disk.vtu" --size 64 -o "$tmpdir/disk.png" --json
grep -q '"triangle6"\|"tri6"' "$tmpdir/out" || { echo "FAIL (disk element types in JSON)"; fails=$((fails + 1)); }

# Refusals, one line each.
printf '# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nPOINT_DATA 4\nTENSORS stress double\n1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 1\n' > "$tmpdir/tet.vtk"
expect_error "3-D cells" photoelastic --fea "$tmpdir/tet.vtk" -o "$tmpdir/x.png"
grep -q "3-D cell.*plane-stress model, or a section" "$tmpdir/err" || { echo "FAIL (3-D message)"; cat "$tmpdir/err"; fails=$((fails + 1)); }
printf '# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 3 double\n0 0 0\n1 0 0\n0 1 1\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\nPOINT_DATA 3\nTENSORS stress double\n1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 1\n' > "$tmpdir/shell.vtk"
expect_error "shell out of plane" photoelastic --fea "$tmpdir/shell.vtk" -o "$tmpdir/x.png"
grep -q "not in one plane" "$tmpdir/err" || { echo "FAIL (shell message)"; fails=$((fails + 1)); }
expect_error "unknown array" photoelastic --fea "$ex/plate_hole.vtu" --fea-stress sigma_vm -o "$tmpdir/x.png"
grep -q "no point-data array 'sigma_vm' (point data: S (6))" "$tmpdir/err" || { echo "FAIL (array message)"; cat "$tmpdir/err"; fails=$((fails + 1)); }
expect_error "unknown frd component" photoelastic --fea "$ex/plate_hole.frd" --columns sxx=S11,syy=S22,txy=S12 -o "$tmpdir/x.png"
cp "$ex/plate_hole.vtu" "$tmpdir/plate.dat"
expect_error "no extension" photoelastic --fea "$tmpdir/plate.dat" -o "$tmpdir/x.png"
grep -q "fea-format" "$tmpdir/err" || { echo "FAIL (format message)"; fails=$((fails + 1)); }
expect_ok "format given" photoelastic --fea "$tmpdir/plate.dat" --fea-format vtu --size 16 -o "$tmpdir/x.png"
expect_error "fea and nodes" photoelastic --fea "$ex/plate_hole.vtu" --stress-nodes examples/photoelastic/disk_nodes.csv -o "$tmpdir/x.png"
expect_error "damaged vtu" photoelastic --fea "$tmpdir/x.png" --fea-format vtu -o "$tmpdir/y.png"
finish
