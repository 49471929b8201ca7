#!/usr/bin/env python3
"""Writes the lecture's scenes (Lischinski, "Hierarchical Radiosity", sections 2-4) as OBJ + MTL.

Run from this folder: /usr/bin/python3 make_lecture_scenes.py
Every quad is written counter-clockwise seen from its front (right-hand rule).
"""


def quad(origin, u, v):
    """Corners origin, origin+u, origin+u+v, origin+v: front is u x v."""
    o = origin
    return [o, tuple(a + b for a, b in zip(o, u)), tuple(a + b + c for a, b, c in zip(o, u, v)),
            tuple(a + b for a, b in zip(o, v))]


def box_without_bottom(x0, z0, w, d, h):
    """Top and four sides of an axis-aligned box on the floor (y = 0), fronts facing out."""
    return [
        quad((x0, h, z0), (0, 0, d), (w, 0, 0)),        # top, +y
        quad((x0, 0, z0), (0, h, 0), (w, 0, 0)),        # front, -z
        quad((x0 + w, 0, z0 + d), (0, h, 0), (-w, 0, 0)),  # back, +z
        quad((x0, 0, z0 + d), (0, h, 0), (0, 0, -d)),   # left, -x
        quad((x0 + w, 0, z0), (0, h, 0), (0, 0, d)),    # right, +x
    ]


def write(name, comment, materials, groups):
    with open(name + ".mtl", "w") as f:
        f.write("# Materials of %s.obj (written by make_lecture_scenes.py)\n" % name)
        for m, (kd, ke) in materials.items():
            f.write("newmtl %s\nKd %g %g %g\n" % (m, *kd))
            if ke:
                f.write("Ke %g %g %g\n" % ke)
    with open(name + ".obj", "w") as f:
        f.write("# %s\n# Written by make_lecture_scenes.py in this folder.\nmtllib %s.mtl\n" % (comment, name))
        for group, material, polys in groups:
            f.write("\no %s\nusemtl %s\n" % (group, material))
            for p in polys:
                for x in p:
                    f.write("v %g %g %g\n" % x)
                f.write("f %s\n" % " ".join(str(-len(p) + i) for i in range(len(p))))


white = ((0.7, 0.7, 0.7), None)
light = ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))

# Section 2: two large surfaces far away from each other (4 x 4, 20 apart, facing each other).
write("two_far_surfaces",
      "Lecture section 2: two large surfaces far apart; the lower one emits, the upper one reflects",
      {"light": ((0.5, 0.5, 0.5), (1.0, 1.0, 1.0)), "white": white},
      [("emitter", "light", [quad((0, 0, 0), (0, 0, 4), (4, 0, 0))]),
       ("receiver", "white", [quad((0, 20, 0), (4, 0, 0), (0, 0, 4))])])

# Section 2: two large surfaces meeting along an edge (a wall that emits and a floor, 4 x 4 each).
write("two_surfaces_edge",
      "Lecture section 2: two large surfaces meeting along an edge (z = 0); the wall emits",
      {"light": ((0.5, 0.5, 0.5), (1.0, 1.0, 1.0)), "white": white},
      [("floor", "white", [quad((0, 0, 0), (0, 0, 4), (4, 0, 0))]),
       ("wall", "light", [quad((0, 0, 0), (4, 0, 0), (0, 4, 0))])])

# Section 4: a simple room (4 x 2.5 x 5 m) with a ceiling light just below the ceiling and a table.
W, H, D = 4.0, 2.5, 5.0
write("simple_room",
      "Lecture section 4: a simple room, 4 x 2.5 x 5 m, a 1 x 1 m ceiling light 1 cm below the ceiling, a table",
      {"white": white, "red": ((0.6, 0.1, 0.1), None), "blue": ((0.1, 0.15, 0.6), None),
       "light": ((0.0, 0.0, 0.0), (10.0, 10.0, 10.0)), "wood": ((0.5, 0.35, 0.2), None)},
      [("floor", "white", [quad((0, 0, 0), (0, 0, D), (W, 0, 0))]),
       ("ceiling", "white", [quad((0, H, 0), (W, 0, 0), (0, 0, D))]),
       ("wall_back", "white", [quad((0, 0, D), (0, H, 0), (W, 0, 0))]),
       ("wall_front", "white", [quad((W, 0, 0), (0, H, 0), (-W, 0, 0))]),
       ("wall_left", "red", [quad((0, 0, 0), (0, H, 0), (0, 0, D))]),
       ("wall_right", "blue", [quad((W, 0, D), (0, H, 0), (0, 0, -D))]),
       ("light", "light", [quad((1.5, H - 0.01, 2.0), (1, 0, 0), (0, 0, 1))]),
       ("table", "wood", box_without_bottom(1.4, 1.9, 1.2, 0.8, 0.75))])
