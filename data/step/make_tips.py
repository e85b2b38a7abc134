#!/usr/bin/env python3
"""Writes plane_tips.step: one planar face in the plane z = 0 (millimetres), a thin curved
band pointed at both ends, as the CATIA engine block's 17-edge bands (#14): 0.3 wide on a
radius of 14, bent through 120°, its rims meeting at two tips of 36° (above the 30° of a
cusp), a notch in the outer rim.

    A, B        the tips, on the inner rim at 150° and 30° about the centre O = (5, -14):
                the loop turns there by 144° (interior angle 36°)
    A → B       the inner rim, an arc of radius 14 about O (bulging into the face: concave)
    B → K1      an arc tangent to the outer rim at K1, leaving B at 18° to its chord
    K1 → N1     the outer rim, an arc of radius 14.3 about O
    N1 → N4     a notch 0.2 deep and 0.6 wide (straight sides, an arc of radius 14.1 at its
                bottom; convex at N1 and N4, reentrant at N2 and N3)
    N4 → K2     the outer rim
    K2 → A      as B → K1

Every corner set by turning angle and every balanced one folds the face's (u, v) grid, so
does the cut at the notch's reentrant vertices, and there is no cusp (no vertex turning by
more than 150°); with both tips collapsed (sides E1 and E2 one point each,
`src/cad/trim/cusp.rs`, the last try), E3 the inner rim and E4 the notched outer rim, it
is fold-free.

Plain Python, no CAD kernel: written by make_notch.py's writer (through make_cusp.py's
circle edges).

    python3 make_tips.py data/step
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_cusp import write  # noqa: E402

O = (5.0, -14.0)  # the rims' centre (off the origin: no coordinate ~1e-16 in the file)
R, W = 14.0, 0.3  # inner radius, width
THETA = 60.0      # the tips at 90° ± THETA about O
CHORD = 18.0      # the angle of the tip arcs' chords to the inner rim (degrees)
NW, ND = 0.3, 0.2  # the notch's half width and depth


def at(r, deg):
    t = math.radians(deg)
    return (O[0] + r * math.cos(t), O[1] + r * math.sin(t))


def tangent_radius(a, k):
    """Radius of the circle through a tangent to the outer rim at k (inside it)."""
    u = ((k[0] - O[0]) / (R + W), (k[1] - O[1]) / (R + W))
    d = (a[0] - k[0], a[1] - k[1])
    return -(d[0] ** 2 + d[1] ** 2) / (2 * (d[0] * u[0] + d[1] * u[1]))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    delta = math.degrees(W / math.tan(math.radians(CHORD)) / R)
    w = math.degrees(NW / (R + W))
    a, b = at(R, 90 + THETA), at(R, 90 - THETA)
    k1, k2 = at(R + W, 90 - THETA + delta), at(R + W, 90 + THETA - delta)
    n1, n2 = at(R + W, 90 - w), at(R + W - ND, 90 - w)
    n3, n4 = at(R + W - ND, 90 + w), at(R + W, 90 + w)
    # counterclockwise about +z; per edge (radius, side) of an arc (side > 0 bulges to the
    # left of a → b), None a line
    pts = [a, b, k1, n1, n2, n3, n4, k2]
    edges = [(R, 1), (tangent_radius(b, k1), -1), (R + W, -1), None, (R + W - ND, -1), None,
             (R + W, -1), (tangent_radius(a, k2), -1)]
    write("plane_tips", out, "make_tips.py", pts, edges)


if __name__ == "__main__":
    main()
