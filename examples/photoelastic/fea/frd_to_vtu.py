#!/usr/bin/python3
"""Converts a CalculiX plane-stress result (.frd, ASCII) to a VTK unstructured grid with meshio:

    frd_to_vtu.py IN.frd OUT.vtu|OUT.vtk [ascii]

Points (x, y, 0) in the file's unit, the plane elements (tr3, tr6, qu4, qu8 -> VTK triangle,
quadratic triangle, quad, quadratic quad; CalculiX's node order is VTK's) and the last STRESS block
as the point-data tensor "S" (xx, yy, zz, xy, yz, xz, VTK's symmetric order). Written independently
of biref's C reader (src/photoelastic/frd.c), so that the two can check each other. Needs Debian's
python3-meshio: run with /usr/bin/python3."""
import sys

import meshio
import numpy as np

src, dst = sys.argv[1], sys.argv[2]
ascii_out = len(sys.argv) > 3 and sys.argv[3] == "ascii"
lines = open(src).read().split("\n")
ids, xyz, elems, stress = [], [], [], {}
TYPES = {7: ("triangle", 3), 8: ("triangle6", 6), 9: ("quad", 4), 10: ("quad8", 8)}
i = 0
while i < len(lines):
    ln = lines[i]
    if ln.startswith("    2C") or ln.startswith("    3C") or ln.startswith("  100C"):
        w = 10 if ln.rstrip().endswith("1") else 5
        key = ln[4:6]
        i += 1
        if key == "2C":
            while not lines[i].startswith(" -3"):
                r = lines[i]
                ids.append(int(r[3:3 + w]))
                xyz.append([float(r[3 + w + 12 * k:3 + w + 12 * (k + 1)]) for k in range(3)])
                i += 1
        elif key == "3C":
            while not lines[i].startswith(" -3"):
                t = int(lines[i][3 + w:8 + w])
                name, nn = TYPES[t]
                conn = []
                i += 1
                while len(conn) < nn:
                    r = lines[i][3:].rstrip()
                    conn += [int(r[k:k + w]) for k in range(0, len(r), w)]
                    i += 1
                elems.append((name, conn))
                continue
        else:
            comps, block = [], {}
            while not lines[i].startswith(" -3"):
                r = lines[i]
                if r.startswith(" -4"):
                    name = r[5:13].strip()
                elif r.startswith(" -5"):
                    comps.append(r[5:13].strip())
                elif r.startswith(" -1"):
                    block[int(r[3:3 + w])] = [float(r[3 + w + 12 * k:3 + w + 12 * (k + 1)]) for k in range(len(comps))]
                i += 1
            if name == "STRESS":
                stress = {n: dict(zip(comps, v)) for n, v in block.items()}
    i += 1
index = {n: k for k, n in enumerate(ids)}
cells = {}
for name, conn in elems:
    cells.setdefault(name, []).append([index[n] for n in conn])
order = ["SXX", "SYY", "SZZ", "SXY", "SYZ", "SZX"]
S = np.array([[stress[n][c] for c in order] for n in ids])
mesh = meshio.Mesh(np.array(xyz), [(k, np.array(v)) for k, v in cells.items()], point_data={"S": S})
if dst.endswith(".vtk"):
    meshio.write(dst, mesh, binary=not ascii_out)
else:
    meshio.write(dst, mesh, binary=not ascii_out, compression=None if ascii_out else "zlib")
