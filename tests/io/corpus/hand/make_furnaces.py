#!/usr/bin/env python3
"""Writes the hand-made corpus scenes: one closed unit cube (a furnace) per exporter habit.

Every cube has its faces' normals pointing inwards and two materials with the same E / (1 - rho) = 4
(walls: Kd 0.5, Ke 2; floor: Kd 0.75, Ke 1), so the exact answer is B = 4 on every face, whatever the
form factors, and the floor's material must stay apart from the walls' one. Usage: make_furnaces.py DIR
"""
import struct
import sys
from pathlib import Path

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
# The unit cube; each face counter-clockwise seen from inside; the floor (y = 0) first.
V = [(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1), (0, 1, 0), (1, 1, 0), (1, 1, 1), (0, 1, 1)]
F = [(1, 4, 3, 2), (5, 6, 7, 8), (1, 2, 6, 5), (4, 8, 7, 3), (1, 5, 8, 4), (2, 3, 7, 6)]
N = [(0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1), (1, 0, 0), (-1, 0, 0)]


def write_3dsmax():
    """3ds Max's gw::OBJ exporter: byte order mark, CRLF, 'mtllib ./NAME', two spaces after 'v', 4
    decimals, vt/vn indices, a smoothing group per face, a space at the end of face lines, '# N vertices'
    counts; the MTL's statements indented by a tab, default material names 'Material #25'."""
    walls, floor = "Material #25", "Material #26"
    obj = ["# 3ds Max Wavefront OBJ Exporter v0.97b - (c)2007 guruware", "# File Created: 02.12.2026 10:15:42", "",
           "mtllib ./furnace box.mtl", "", "#", "# object Box001", "#", ""]
    obj += ["v  %.4f %.4f %.4f" % v for v in V] + ["# 8 vertices", ""]
    obj += ["vn %.4f %.4f %.4f" % n for n in N] + ["# 6 vertex normals", ""]
    obj += ["vt %.4f %.4f %.4f" % t for t in [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]] + ["# 4 texture coords", ""]
    obj += ["g Box001"]
    for i, f in enumerate(F):
        obj += ["usemtl " + (floor if i == 0 else walls), "s %d" % (i + 2),
                "f " + " ".join("%d/%d/%d" % (v, k + 1, i + 1) for k, v in enumerate(f)) + " "]
    obj += ["# 6 polygons", ""]
    mtl = ["# 3ds Max Wavefront OBJ Exporter v0.97b - (c)2007 guruware", "# File Created: 02.12.2026 10:15:42", ""]
    for name, kd, ke in [(walls, 0.5, 2.0), (floor, 0.75, 1.0)]:
        mtl += ["newmtl " + name, "\tNs 10.0000", "\tNi 1.5000", "\td 1.0000", "\tTr 0.0000", "\tTf 1.0000 1.0000 1.0000",
                "\tillum 2", "\tKa %.4f %.4f %.4f" % (kd, kd, kd), "\tKd %.4f %.4f %.4f" % (kd, kd, kd),
                "\tKs 0.0000 0.0000 0.0000", "\tKe %.4f %.4f %.4f" % (ke, ke, ke), ""]
    d = out / "3dsmax"
    d.mkdir(parents=True, exist_ok=True)
    bom = b"\xef\xbb\xbf"
    (d / "furnace box.obj").write_bytes(bom + "\r\n".join(obj).encode() + b"\r\n")
    (d / "furnace box.mtl").write_bytes(bom + "\r\n".join(mtl).encode() + b"\r\n")


def write_sketchup():
    """SketchUp's OBJ export: inches (39.3701 per metre), every face as triangles with vt/vn, one 'g' per
    mesh, material names with spaces."""
    walls, floor = "Beige Wall", "Light Wood Floor"
    s = 39.3701
    obj = ["# Alias OBJ Model File", "# Exported from SketchUp, (c) 2000-2012 Trimble Navigation Limited",
           "# File units = inches", "", "mtllib furnace.mtl", "", "g Mesh1 Model", ""]
    obj += ["v %g %g %g" % (x * s, y * s, z * s) for x, y, z in V]
    obj += ["vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1"]
    obj += ["vn %g %g %g" % n for n in N]
    for i, f in enumerate(F):
        obj += ["usemtl " + (floor if i == 0 else walls)]
        for tri in [(0, 1, 2), (0, 2, 3)]:
            obj += ["f " + " ".join("%d/%d/%d" % (f[k], k + 1, i + 1) for k in tri)]
    obj += [""]
    mtl = []
    for name, kd, ke in [(walls, 0.5, 2.0), (floor, 0.75, 1.0)]:
        mtl += ["newmtl " + name, "Ka 0.000000 0.000000 0.000000", "Kd %.6f %.6f %.6f" % (kd, kd, kd),
                "Ks 0.330000 0.330000 0.330000", "Ke %.6f %.6f %.6f" % (ke, ke, ke), ""]
    d = out / "sketchup"
    d.mkdir(parents=True, exist_ok=True)
    (d / "furnace.obj").write_text("\n".join(obj))
    (d / "furnace.mtl").write_text("\n".join(mtl))


def write_meshlab():
    """MeshLab's PLY export (VCG library): binary little endian, 'comment VCGLIB generated', float
    positions, per-face colour as uchar red green blue alpha, and per-face custom attributes (MeshLab's
    "Define New Per Face Attribute" filter, exported with "Custom attributes" ticked) emission_r/g/b
    as float. Colours are bytes, so the reflectances are 128/255 (walls) and 191/255 (floor) and the
    emissions 4 (1 - rho) rounded to float: B = E / (1 - rho) is 4 to float precision on every face."""
    header = ["ply", "format binary_little_endian 1.0", "comment VCGLIB generated", "element vertex 8",
              "property float x", "property float y", "property float z", "element face 6",
              "property list uchar int vertex_indices", "property uchar red", "property uchar green",
              "property uchar blue", "property uchar alpha", "property float emission_r", "property float emission_g",
              "property float emission_b", "end_header"]
    body = b"".join(struct.pack("<3f", *v) for v in V)
    for i, f in enumerate(F):
        c = 191 if i == 0 else 128
        e = 4.0 * (1.0 - c / 255.0)
        body += struct.pack("<B4i", 4, *(v - 1 for v in f)) + struct.pack("<4B", c, c, c, 255)
        body += struct.pack("<3f", e, e, e)
    d = out / "meshlab"
    d.mkdir(parents=True, exist_ok=True)
    (d / "furnace.ply").write_bytes(("\n".join(header) + "\n").encode() + body)


write_3dsmax()
write_sketchup()
write_meshlab()
