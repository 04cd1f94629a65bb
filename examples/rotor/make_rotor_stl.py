#!/usr/bin/python3
"""Writes the rotor example's three surfaces as ASCII STL (metres).

  python3 make_rotor_stl.py rotor > rotor.stl   the five-blade axial rotor, in its body axes:
                                                the axis is x, the centre of mass the origin
  python3 make_rotor_stl.py duct > duct.stl     the duct: floor, side walls and lid of
                                                [0, L] x [0, W] x [0, H], open at x = 0 and L
                                                (the fluid is periodic along x)
  python3 make_rotor_stl.py fluid > fluid.stl   the water's initial region (FluidRegion stl):
                                                the duct up to the depth D, less the hub

Options (defaults in brackets; the scene's Geometry block must agree with them):
  rotor: --blades N [5] --tip-radius R [0.0095] --hub-radius r [0.003] --hub-length l [0.008]
         --chord c [0.007] --pitch DEG [40] --hub-sides N [10] --blade-pieces N [2]
  duct:  --length L [0.06] --width W [0.03] --height H [0.036] --pieces N [1]
  fluid: --length L --width W --depth D [0.027] --centre X Y Z [0.03 0.015 0.0135]
         --hub-radius --hub-length --hub-sides (as the rotor's) --margin m [0.001]

The rotor: a closed hub (a cylinder of `hub-sides` sides with conical end caps) and `blades` flat
blades, each a quad from the hub radius to the tip radius at equal angles around the axis, its
chord turned by `pitch` from the plane of rotation. Blade k lies along the radial direction
e_r = (0, cos t_k, sin t_k), t_k = 2 pi k / N, and the chord direction
cos(pitch) e_t - sin(pitch) e_x (e_t = e_x x e_r): turning about +x (right-handed) the blade
pushes the water towards +x. The blades have no thickness: fix fsi/sph acts on both sides of a
triangle alike. Each blade is cut into `blade-pieces` radial strips of two triangles.
"""
import argparse
import math
import sys


def facet(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = math.sqrt(sum(x * x for x in n))
    if length == 0.0:
        sys.exit(f"make_rotor_stl.py: a degenerate triangle {a} {b} {c}: check the options")
    return [x / length for x in n], (a, b, c)


def hub_triangles(radius, length, sides, centre=(0.0, 0.0, 0.0), inward=False):
    """The hub: a prism of `sides` sides around the x axis through `centre`, closed by cones to
    the axis one radius beyond each end; outward normals, or inward ones."""
    half = 0.5 * length
    cx, cy, cz = centre
    ring = [(cy + radius * math.cos(2 * math.pi * j / sides),
             cz + radius * math.sin(2 * math.pi * j / sides)) for j in range(sides)]
    tips = ((cx + half + radius, cy, cz), (cx - half - radius, cy, cz))
    corners = []
    for j in range(sides):
        p, q = ring[j], ring[(j + 1) % sides]
        a, b = (cx - half, p[0], p[1]), (cx - half, q[0], q[1])
        c, d = (cx + half, q[0], q[1]), (cx + half, p[0], p[1])
        corners += [(a, b, c), (a, c, d), (tips[0], d, c), (tips[1], b, a)]
    return [facet(a, c, b) if inward else facet(a, b, c) for a, b, c in corners]


def rotor_triangles(o):
    triangles = hub_triangles(o.hub_radius, o.hub_length, o.hub_sides)
    # The blades.
    beta = math.radians(o.pitch)
    for k in range(o.blades):
        t = 2 * math.pi * k / o.blades
        e_r = (0.0, math.cos(t), math.sin(t))
        e_t = (0.0, -math.sin(t), math.cos(t))
        chord = tuple(math.cos(beta) * e_t[i] - math.sin(beta) * (1.0 if i == 0 else 0.0)
                      for i in range(3))

        def at(r, s):
            return tuple(r * e_r[i] + s * chord[i] for i in range(3))

        # From just inside the hub (its flat sides lie within hub_radius) to the tip.
        inner = o.hub_radius * math.cos(math.pi / o.hub_sides)
        for j in range(o.blade_pieces):
            r0 = inner + (o.tip_radius - inner) * j / o.blade_pieces
            r1 = inner + (o.tip_radius - inner) * (j + 1) / o.blade_pieces
            a, b = at(r0, -0.5 * o.chord), at(r1, -0.5 * o.chord)
            c, d = at(r1, 0.5 * o.chord), at(r0, 0.5 * o.chord)
            triangles += [facet(a, b, c), facet(a, c, d)]
    return triangles


def duct_triangles(o):
    L, W, H, n = o.length, o.width, o.height, o.pieces
    triangles = []
    # Each wall as (corner, edge across the duct): floor z = 0, back y = W, lid z = H,
    # front y = 0; the other edge runs along x over the period.
    origins = [(0, 0, 0), (0, W, 0), (0, W, H), (0, 0, H)]
    acrosses = [(0, W, 0), (0, 0, H), (0, -W, 0), (0, 0, -H)]
    for origin, across in zip(origins, acrosses):
        for i in range(n):
            for j in range(n):
                def at(u, v):
                    return tuple(origin[k] + (L * u if k == 0 else 0.0) + across[k] * v
                                 for k in range(3))
                a, b = at(i / n, j / n), at((i + 1) / n, j / n)
                c, d = at((i + 1) / n, (j + 1) / n), at(i / n, (j + 1) / n)
                triangles += [facet(a, b, c), facet(a, c, d)]
    return triangles


def fluid_triangles(o):
    """The water: the box [0, L] x [0, W] x [0, depth] (outward normals) less the hub grown by
    `margin` (inward normals: the winding number is 0 inside it), so no particle starts in the
    hub or on its surface."""
    L, W, D = o.length, o.width, o.depth
    corner = [(x, y, z) for z in (0.0, D) for y in (0.0, W) for x in (0.0, L)]  # x + 2y + 4z
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    triangles = []
    for p, q, r, s in faces:  # counter-clockwise seen from outside
        triangles += [facet(corner[p], corner[q], corner[r]), facet(corner[p], corner[r], corner[s])]
    return triangles + hub_triangles(o.hub_radius + o.margin, o.hub_length + 2 * o.margin,
                                     o.hub_sides, tuple(o.centre), inward=True)


def positive(kind):
    def parse(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"'{text}' is not a {kind.__name__}")
        if value <= 0:
            raise argparse.ArgumentTypeError(f"{text} must be > 0")
        return value
    return parse


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="part", required=True)
    rotor = sub.add_parser("rotor")
    rotor.add_argument("--blades", type=positive(int), default=5)
    rotor.add_argument("--tip-radius", type=positive(float), default=0.0095)
    rotor.add_argument("--hub-radius", type=positive(float), default=0.003)
    rotor.add_argument("--hub-length", type=positive(float), default=0.008)
    rotor.add_argument("--chord", type=positive(float), default=0.007)
    rotor.add_argument("--pitch", type=positive(float), default=40.0)
    rotor.add_argument("--hub-sides", type=positive(int), default=10)
    rotor.add_argument("--blade-pieces", type=positive(int), default=2)
    duct = sub.add_parser("duct")
    duct.add_argument("--length", type=positive(float), default=0.06)
    duct.add_argument("--width", type=positive(float), default=0.03)
    duct.add_argument("--height", type=positive(float), default=0.036)
    duct.add_argument("--pieces", type=positive(int), default=1)
    fluid = sub.add_parser("fluid")
    fluid.add_argument("--length", type=positive(float), default=0.06)
    fluid.add_argument("--width", type=positive(float), default=0.03)
    fluid.add_argument("--depth", type=positive(float), default=0.027)
    fluid.add_argument("--centre", type=float, nargs=3, default=[0.03, 0.015, 0.0135])
    fluid.add_argument("--hub-radius", type=positive(float), default=0.003)
    fluid.add_argument("--hub-length", type=positive(float), default=0.008)
    fluid.add_argument("--hub-sides", type=positive(int), default=10)
    fluid.add_argument("--margin", type=positive(float), default=0.001)
    o = parser.parse_args()
    if o.part == "rotor":
        if o.tip_radius <= o.hub_radius:
            sys.exit(f"make_rotor_stl.py: --tip-radius {o.tip_radius} must exceed --hub-radius "
                     f"{o.hub_radius}")
        if o.hub_sides < 3 or o.pitch >= 90:
            sys.exit("make_rotor_stl.py: --hub-sides needs >= 3 and --pitch < 90 degrees")
        triangles = rotor_triangles(o)
    elif o.part == "duct":
        triangles = duct_triangles(o)
    else:
        triangles = fluid_triangles(o)
    out = [f"solid {o.part}"]
    for n, corners in triangles:
        out.append(f"  facet normal {n[0]:.9g} {n[1]:.9g} {n[2]:.9g}")
        out.append("    outer loop")
        out += [f"      vertex {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}" for p in corners]
        out.append("    endloop")
        out.append("  endfacet")
    out.append(f"endsolid {o.part}")
    print("\n".join(out))


if __name__ == "__main__":
    main()
