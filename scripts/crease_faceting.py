#!/usr/bin/python3
"""Dihedral angle at a faceted crease between a cylinder and a cone, by the shape of the
triangles on the crease: why netgen_hinge.stl's sharp-edge length depends on the faceting.

    /usr/bin/python3 scripts/crease_faceting.py [--radius R] [--angle DEG]

The hinge's countersunk holes: a vertical cylinder of radius 2.5 meets a cone along a circle,
where the surfaces' normals make 58.9 degrees, just under the 60-degree threshold of the
sharp-edge measure. A crease edge of length h joins two vertices of that circle; on each side a
triangle of height h sqrt(3)/2 stands on it, its apex on the surface at the azimuth of the edge's
midpoint shifted by `offset` edge lengths: 0 is the isosceles triangle a centroidal Voronoi
tessellation puts there, 0.5 the right triangle of a prism faceting (the input's). Prints the
dihedral angle (between the two triangles' normals) for a few edge lengths and offsets.
"""

import argparse
import math


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(a):
    n = math.sqrt(sum(x * x for x in a))
    return [x / n for x in a]


def normal(a, b, c):
    return unit(cross(sub(b, a), sub(c, a)))


def point(azimuth, radius, z):
    return [radius * math.cos(azimuth), radius * math.sin(azimuth), z]


def crease_dihedral(radius, crease_deg, h, offset):
    """Degrees between the normals of the cylinder's and the cone's triangle on one crease edge."""
    # The cone's generator, in (radial, z), is perpendicular to its normal, which makes
    # crease_deg with the cylinder's (radial) normal.
    rise = math.radians(crease_deg)
    g_radial, g_z = math.sin(rise), math.cos(rise)
    step = h / radius
    a, b = point(-step / 2, radius, 0.0), point(step / 2, radius, 0.0)
    height = h * math.sqrt(3.0) / 2.0
    below = point(offset * step, radius, -height)  # on the cylinder
    above = point(offset * step, radius + height * g_radial, height * g_z)  # on the cone
    n1, n2 = normal(a, b, below), normal(b, a, above)
    cosine = abs(sum(x * y for x, y in zip(n1, n2)))
    return math.degrees(math.acos(min(1.0, cosine)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--radius", type=float, default=2.5, help="cylinder radius (default: 2.5, the hinge's)")
    parser.add_argument("--angle", type=float, default=58.9,
                        help="angle between the surfaces' normals along the crease, degrees (default: 58.9)")
    args = parser.parse_args()
    offsets = (0.0, 0.25, 0.5)
    print("crease edge h | " + " | ".join("apex offset %.2f" % o for o in offsets))
    for h in (1.0, 0.7, 0.5, 0.35, 0.2):
        print("%12.2f  | " % h + " | ".join("%15.2f" % crease_dihedral(args.radius, args.angle, h, o) for o in offsets))


if __name__ == "__main__":
    main()
