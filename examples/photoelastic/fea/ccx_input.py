#!/usr/bin/python3
"""Turns a gmsh Abaqus-format mesh (.inp) of a plane part into a CalculiX plane-stress analysis.

    ccx_input.py plate MESH.inp OUT.inp   plate with a hole, 60 x 60 mm, 4 MPa tension along x
    ccx_input.py disk  MESH.inp OUT.inp   disk of radius 25 mm, 500 N diametral compression

Units mm, N, MPa; polycarbonate (E = 2400 MPa, nu = 0.37); thickness 3 mm (plate) or 6 mm (disk).
Only the plane elements (CPS*) are kept; gmsh's edge elements are dropped. Standard library only."""
import sys

kind, mesh, out = sys.argv[1:4]
nodes, elems, etype = {}, [], None
section = None
for line in open(mesh):
    s = line.strip()
    if not s or s.startswith("**"):
        continue
    if s.startswith("*"):
        key = s.upper()
        section = "node" if key.startswith("*NODE") else "elem" if key.startswith("*ELEMENT") else None
        if section == "elem":
            t = [p.split("=")[1].strip() for p in s.split(",") if p.strip().upper().startswith("TYPE")][0]
            section = "elem" if t.upper().startswith("CPS") else None
            if section:
                etype = t
        continue
    f = [v for v in s.split(",") if v.strip()]
    if section == "node":
        nodes[int(f[0])] = (float(f[1]), float(f[2]))
    elif section == "elem":
        elems.append([int(v) for v in f])


def near(x, y, tol=1e-6):
    return [i for i, (a, b) in nodes.items() if abs(a - x) < tol and abs(b - y) < tol]


o = open(out, "w")
o.write("*HEADING\n%s for biref photoelastic examples\n*NODE, NSET=NALL\n" % kind)
for i, (x, y) in sorted(nodes.items()):
    o.write("%d, %.12g, %.12g, 0\n" % (i, x, y))
o.write("*ELEMENT, TYPE=%s, ELSET=EALL\n" % etype)
for e in elems:
    o.write(", ".join(str(v) for v in e) + "\n")
thick = 3.0 if kind == "plate" else 6.0
o.write("*MATERIAL, NAME=PC\n*ELASTIC\n2400, 0.37\n*SOLID SECTION, ELSET=EALL, MATERIAL=PC\n%g\n" % thick)
o.write("*BOUNDARY\n")
if kind == "plate":
    # Symmetric restraint: x fixed on the vertical centre line's edge nodes, y on the horizontal's.
    for n in near(0, -30) + near(0, 30):
        o.write("%d, 1, 1\n" % n)
    for n in near(-30, 0) + near(30, 0):
        o.write("%d, 2, 2\n" % n)
else:
    top, bot = near(0, 25)[0], near(0, -25)[0]
    o.write("%d, 1, 1\n%d, 1, 2\n" % (top, bot))
o.write("*STEP\n*STATIC\n")
if kind == "plate":
    # Remote tension: -4 MPa "pressure" on the element faces lying on x = +-30 (face k joins
    # corners k and k+1 of the quad).
    o.write("*DLOAD\n")
    for e in elems:
        eid, conn = e[0], e[1:5]
        for k in range(4):
            a, b = nodes[conn[k]], nodes[conn[(k + 1) % 4]]
            if abs(abs(a[0]) - 30) < 1e-6 and abs(b[0] - a[0]) < 1e-9:
                o.write("%d, P%d, -4\n" % (eid, k + 1))
else:
    o.write("*CLOAD\n%d, 2, -500\n" % top)
o.write("*EL FILE\nS\n*END STEP\n")
