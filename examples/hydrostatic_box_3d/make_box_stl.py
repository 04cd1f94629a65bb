#!/usr/bin/python3
"""Writes the closed surface of the axis-aligned box [0, a] x [0, b] x [0, c] in metres, shifted
by (x, y, z), as ASCII STL: 12 triangles, outward normals (counter-clockwise seen from outside).
fix fsi/sph treats both sides of a triangle alike, so the fluid inside sees the inner faces.

  python3 make_box_stl.py > box.stl                     (the container: 0.012 0.012 0.02)
  python3 make_box_stl.py 0.0096 0.0096 0.008 0.0012 0.0012 0.0008 > fluid.stl   (the fluid block)
"""
import sys


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
    values = [float(v) for v in sys.argv[1:]]
    if len(values) not in (0, 3, 6):
        sys.exit("usage: make_box_stl.py [a b c [x y z]]")
    a, b, c = values[0:3] if values else (0.012, 0.012, 0.02)
    offset = values[3:6] if len(values) == 6 else (0.0, 0.0, 0.0)
    out = ["solid box"]
    for normal, triangle in box_triangles(a, b, c, offset):
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
