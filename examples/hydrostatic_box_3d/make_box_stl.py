#!/usr/bin/python3
"""Writes the closed surface of the axis-aligned box [0, a] x [0, b] x [0, c] in metres, shifted
by (x, y, z), as ASCII STL: 12 triangles, outward normals (counter-clockwise seen from outside).
fix fsi/sph treats both sides of a triangle alike, so the fluid inside sees the inner faces.

  python3 make_box_stl.py > box.stl                     (the container: 0.012 0.012 0.02)
  python3 make_box_stl.py 0.0096 0.0096 0.008 0.0012 0.0012 0.0008 > fluid.stl   (the fluid block)
  python3 make_box_stl.py --subdivide 16 > box_fine.stl (each face as 16 x 16 squares: 3 072
                                                          triangles; bench/boundary_elements.py)
"""
import sys


def subdivided(triangles, n):
    """Each face's two triangles (one square) as n x n squares of two triangles each."""
    triangles = list(triangles)
    for k in range(0, len(triangles), 2):
        normal, (p, q, r) = triangles[k]
        _, (_, _, s) = triangles[k + 1]

        def at(u, v):  # p + u (q - p) + v (s - p): the square's corner p, edges along q and s
            return tuple(p[i] + u * (q[i] - p[i]) + v * (s[i] - p[i]) for i in range(3))

        for i in range(n):
            for j in range(n):
                a, b = at(i / n, j / n), at((i + 1) / n, j / n)
                c, d = at((i + 1) / n, (j + 1) / n), at(i / n, (j + 1) / n)
                yield normal, (a, b, c)
                yield normal, (a, c, d)


def box_triangles(a, b, c, offset=(0.0, 0.0, 0.0)):
    ox, oy, oz = offset
    corner = [(ox + x, oy + y, oz + z) for z in (0.0, c) for y in (0.0, b)
              for x in (0.0, a)]  # index x + 2y + 4z
    # Each face as 4 corners counter-clockwise seen from outside, with its outward normal.
    faces = [((0, 2, 3, 1), (0, 0, -1)),  # bottom z = 0
             ((4, 5, 7, 6), (0, 0, 1)),   # top z = c
             ((0, 1, 5, 4), (0, -1, 0)),  # front y = 0
             ((2, 6, 7, 3), (0, 1, 0)),   # back y = b
             ((0, 4, 6, 2), (-1, 0, 0)),  # left x = 0
             ((1, 3, 7, 5), (1, 0, 0))]   # right x = a
    for (p, q, r, s), normal in faces:
        yield normal, (corner[p], corner[q], corner[r])
        yield normal, (corner[p], corner[r], corner[s])


def main():
    arguments = sys.argv[1:]
    parts = 1
    if arguments[:1] == ["--subdivide"]:
        if len(arguments) < 2 or not arguments[1].isdigit() or int(arguments[1]) < 1:
            sys.exit("make_box_stl.py: --subdivide needs a whole number >= 1 (squares per face edge)")
        parts = int(arguments[1])
        arguments = arguments[2:]
    values = [float(v) for v in arguments]
    if len(values) not in (0, 3, 6):
        sys.exit("usage: make_box_stl.py [--subdivide N] [a b c [x y z]]")
    a, b, c = values[0:3] if values else (0.012, 0.012, 0.02)
    offset = values[3:6] if len(values) == 6 else (0.0, 0.0, 0.0)
    out = ["solid box"]
    triangles = box_triangles(a, b, c, offset)
    for normal, triangle in (subdivided(triangles, parts) if parts > 1 else triangles):
        out.append("  facet normal %g %g %g" % normal)
        out.append("    outer loop")
        for vertex in triangle:
            out.append("      vertex %.9g %.9g %.9g" % vertex)
        out.append("    endloop")
        out.append("  endfacet")
    out.append("endsolid box")
    print("\n".join(out))


if __name__ == "__main__":
    main()
