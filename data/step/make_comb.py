#!/usr/bin/env python3
"""Writes plane_comb.step: one planar face bounded by a loop of 28 straight edges in the
plane z = 0 (millimetres), counterclockwise about +z, as the corpus's CATIA engine block
cylinder faces 364–371 (#14): a spine 15 wide and 68 tall, x in [30, 45], with three
fingers 12 wide on each side, x in [0, 30] on the left and [45, 95] on the right, at
y in [8, 20], [28, 40], [48, 60]. Every vertex turns by 90°; the 12 where a finger meets
the spine turn outwards (reentrant). Area 15 × 68 + 3 × 12 × (30 + 50) = 3900.

At 33 × 33 and 65 × 65 nodes every corner set of one block folds the discrete Winslow grid
of its (u, v) parametrization, and so does the cut at its reentrant vertices along their
bisectors (`src/cad/reentrant.rs`; at 17 × 17 one block is fold-free); each reentrant vertex sees another along
the continuations of both its edges, and the face cut by those 12 chords is 13 rectangles
(`src/cad/chords.rs`).

cylinder_comb.step: the same comb wrapped onto the cylinder x² + y² = 40² about z (a loop
point (p, q) at the angle p / 40 from +x and the height z = q; the edges along the axis LINEs,
the others CIRCLE arcs): its surface's scaled (u, v) plane is the plane comb's, so it is cut
the same way, and its area is 3900 too (the cylinder is developable), which the grids' flat
cells reach at second order.

Plain Python, no CAD kernel: written by make_notch.py's writer (LINE and CIRCLE edge curves,
no pcurves).

    python3 make_comb.py data/step
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_notch import write_polygon_face  # noqa: E402

X0, X1, X2, X3 = 0, 30, 45, 95   # left finger tips, spine, right finger tips
LEVELS = [(8, 20), (28, 40), (48, 60)]
TOP = 68


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    pts = [(X1, 0), (X2, 0)]
    for lo, hi in LEVELS:
        pts += [(X2, lo), (X3, lo), (X3, hi), (X2, hi)]
    pts += [(X2, TOP), (X1, TOP)]
    for lo, hi in reversed(LEVELS):
        pts += [(X1, hi), (X0, hi), (X0, lo), (X1, lo)]
    write_polygon_face("plane_comb", pts, out, "make_comb.py")
    write_polygon_face("cylinder_comb", pts, out, "make_comb.py", curve=arc,
                       surface=cylinder, lift=wrap)


R = 40.0


def wrap(p, q):
    """A loop point of the plane comb on the cylinder."""
    return (R * math.cos(p / R), R * math.sin(p / R), float(q))


def cylinder(add, axis):
    """The cylinder of radius R about z, placed at the writer's origin placement."""
    return add(f"CYLINDRICAL_SURFACE('',#{axis},{R!r})")


def arc(add, k, a, b):
    """Edge k from a to b: a LINE along the axis, else a CIRCLE arc at its height, its axis
    −z where the edge turns clockwise about z (so that the curve runs with the edge)."""
    (ax, ay), (bx, by) = a, b
    pa, pb = wrap(ax, ay), wrap(bx, by)
    if ax == bx:
        p = add("CARTESIAN_POINT('',({!r},{!r},{!r}))".format(*pa))
        d = add(f"DIRECTION('',(0.,0.,{1.0 if by > ay else -1.0}))")
        v = add(f"VECTOR('',#{d},1.)")
        return add(f"LINE('',#{p},#{v})")
    c = add(f"CARTESIAN_POINT('',(0.,0.,{float(ay)!r}))")
    z = add(f"DIRECTION('',(0.,0.,{1.0 if bx > ax else -1.0}))")
    x = add("DIRECTION('',(1.,0.,0.))")
    axis = add(f"AXIS2_PLACEMENT_3D('',#{c},#{z},#{x})")
    return add(f"CIRCLE('',#{axis},{R!r})")


if __name__ == "__main__":
    main()
