#!/usr/bin/env python3
"""Prints the Cornell box floor cut into 12 convex quads around the two blocks' footprints, as OBJ.

The published floor is one quad with the blocks standing on it (their side faces' bottom edges lie
inside it). The floor under a block is surface that nothing can see and that receives nothing, so its
radiosity drops to 0 across the footprint's edges: a discontinuity of the radiosity itself (Heckbert
1992, "Discontinuity meshing for radiosity": D0), which uniform and hierarchical meshes can only
approach by ever smaller elements across it. Cutting the floor along the footprints puts every D0
edge on a patch boundary and removes the unseen floor. Every vertex is either a published vertex
(the floor's corners, the blocks' bottom corners) or lies on a published floor edge (the front edge
z = 0, the green wall's foot x = 0, the back edge z = 559.2, the red wall's foot from (552.8, 0) to
(549.6, 559.2)) at the z or x of a footprint vertex, or on the line through two footprint vertices.

Usage: /usr/bin/python3 cut_cornell_floor.py   (its output is the floor of cornell_box.obj)
"""


def red_wall_x(z):
    """x of the published floor edge under the red wall, (552.8, 0) -> (549.6, 559.2), at depth z."""
    return 552.8 - 3.2 * z / 559.2


# Footprints in (x, z), y = 0: the published bottom corners of the short and the tall block.
A, B, C, D = (130, 65), (82, 225), (240, 272), (290, 114)
E, F, G, H = (423, 247), (265, 296), (314, 456), (472, 406)
A0 = (130 + 48 * 65 / 160, 0)  # the line B-A continued to the front edge z = 0

# Counter-clockwise in (x, z); reversed on output, which makes the normal +y (up). Every piece is a
# convex quad (the reader would fan-triangulate larger polygons into slivers, which the substructuring
# receivers resolve badly: 19% off on a 1412 mm^2 sliver). The three points on the green wall's foot
# x = 0 at z = 65 and 456 and on the back edge at x = 472 are the footprint vertices A, G and H
# carried straight to the floor's edge.
PIECES = [
    [(0, 0), A0, A, (0, 65)],
    [(0, 65), A, B, (0, 225)],
    [A0, (290, 0), D, A],
    [(290, 0), (552.8, 0), (red_wall_x(114), 114), D],
    [D, (red_wall_x(114), 114), (red_wall_x(247), 247), E],
    [D, E, F, C],
    [E, (red_wall_x(247), 247), (red_wall_x(406), 406), H],
    [H, (red_wall_x(406), 406), (549.6, 559.2), (472, 559.2)],
    [H, (472, 559.2), (314, 559.2), G],
    [(0, 225), B, C, (0, 456)],
    [C, F, G, (0, 456)],
    [(0, 456), G, (314, 559.2), (0, 559.2)],
]


def area(p):
    return 0.5 * sum(p[i][0] * p[(i + 1) % len(p)][1] - p[(i + 1) % len(p)][0] * p[i][1] for i in range(len(p)))


def check():
    for p in PIECES:  # convex quads: no right turn
        assert len(p) == 4, p
        for i in range(len(p)):
            a, b, c = p[i - 1], p[i], p[(i + 1) % len(p)]
            assert (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) >= -1e-9, p
    floor = area([(0, 0), (552.8, 0), (549.6, 559.2), (0, 559.2)])
    footprints = area([A, D, C, B]) + area([E, H, G, F])
    assert abs(sum(area(p) for p in PIECES) - (floor - footprints)) < 1e-6 * floor


if __name__ == "__main__":
    check()
    for p in PIECES:
        for x, z in reversed(p):
            print(f"v {float(x)!r} 0.0 {float(z)!r}")
        print("f " + " ".join(str(i - len(p)) for i in range(len(p))))
