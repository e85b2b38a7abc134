#!/usr/bin/env python3
"""Writes plane_cusp.step: one planar face bounded by a loop of three edges in the plane z = 0
(millimetres), counterclockwise about +z: a sliver with a cusp, as the CATIA ventilator's
three-edge faces (two long edges meeting at a few degrees, a short third edge).

    A = (0, 0)     the cusp: the loop turns there by 176° (interior angle 4°)
    B = (10, 0)    turning 96°
    C = (10, 2)    turning 109°

Every edge is a circular arc bulging into the face (a concave side): A → B of radius 100,
B → C of radius 20, C → A of radius 60.

Four corners on three concave edges put one corner inside a concave edge (its cell's angle
above 180°) or leave the cusp a corner of 4°: every corner set by turning angle folds the
face's (u, v) grid, and no balanced set exists (no point inside an edge that does not bend
outwards). Gridded with the cusp as a collapsed side (E1 one point in (u, v) and in 3D,
`src/cad/trim/cusp.rs`) the face is fold-free, its cells at the cusp triangles.

Plain Python, no CAD kernel: written by make_notch.py's writer, with CIRCLE edge curves.

    python3 make_cusp.py data/step
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_notch import write_polygon_face  # noqa: E402

A = (0.0, 0.0)
B = (10.0, 0.0)
C = (10.0, 2.0)
# per edge A → B, B → C, C → A: None (a line) or (radius, side) of an arc (arc_centre)
EDGES = [(100.0, 1), (20.0, 1), (60.0, 1)]


def arc_centre(p, q, r, side):
    """Centre of the circle of radius r through p and q, on the right of p → q if side > 0
    (the arc from p to q then bulges to the left of the chord), else on the left."""
    mx, my = 0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])
    dx, dy = q[0] - p[0], q[1] - p[1]
    d = math.hypot(dx, dy)
    h = side * math.sqrt(r * r - 0.25 * d * d)
    return (mx + h * dy / d, my - h * dx / d)


def write(name, out, script, pts=None, edges=None):
    pts = pts or [A, B, C]
    edges = edges or EDGES

    def curve(add, k, a, b):
        if edges[k] is None:
            length = math.hypot(b[0] - a[0], b[1] - a[1])
            p = add(f"CARTESIAN_POINT('',({a[0]!r},{a[1]!r},0.))")
            d = add(f"DIRECTION('',({(b[0] - a[0]) / length!r},{(b[1] - a[1]) / length!r},0.))")
            v = add(f"VECTOR('',#{d},1.)")
            return add(f"LINE('',#{p},#{v})")
        # EDGES[k] = (radius, side): side > 0 bulges to the left of a → b (into the face of a
        # counterclockwise loop: clockwise about +z), side < 0 to the right (outwards)
        r, side = edges[k]
        c = arc_centre(a, b, r, side)
        pc = add(f"CARTESIAN_POINT('',({c[0]!r},{c[1]!r},0.))")
        nz = add(f"DIRECTION('',(0.,0.,{-1.0 if side > 0 else 1.0!r}))")
        rx = add("DIRECTION('',(1.,0.,0.))")
        ax = add(f"AXIS2_PLACEMENT_3D('',#{pc},#{nz},#{rx})")
        return add(f"CIRCLE('',#{ax},{r!r})")

    write_polygon_face(name, pts, out, script, curve=curve, coord="{!r}",
                       stamp="2026-11-27T15:00:00")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write("plane_cusp", out, "make_cusp.py")


if __name__ == "__main__":
    main()
