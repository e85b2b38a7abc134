#!/usr/bin/env python3
"""Writes plane_lshape_hole.step: one planar face, the L-shaped plate (0,0) (10,0) (10,7)
(7,7) (7,10) (0,10) in the plane z = 0 (millimetres, counterclockwise about +z: a square with
a 3 × 3 notch) with a square hole of side 1 centred at (3,8.5) (a FACE_BOUND run clockwise).
The one-loop corners of the plate are its first four convex vertices in loop order (all turn
90°): (0,0), (10,0), (10,7), (7,10); the hole does not see (10,7) (the reentrant vertex (7,7)
stands between), so a straight cut from the hole to it crosses the plate's boundary. Area
10 × 10 − 3 × 3 − 1 = 90.

Plain Python, no CAD kernel: written by make_notch.py's file writer (LINE edge curves, no
pcurves).

    python3 make_lshape_hole.py data/step
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_notch import line_edge, polygon_loop, write_face_file  # noqa: E402

OUTER = [(0, 0), (10, 0), (10, 7), (7, 7), (7, 10), (0, 10)]
HOLE = [(2.5, 8), (2.5, 9), (3.5, 9), (3.5, 8)]  # clockwise


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."

    def bounds(add, placement):
        plane = add(f"PLANE('',#{placement[3]})")
        line = lambda add, k, a, b: line_edge(add, a, b)  # noqa: E731
        outer = polygon_loop(add, OUTER, "{:.2f}", line)
        hole = polygon_loop(add, HOLE, "{:.2f}", line)
        return [add(f"FACE_OUTER_BOUND('',#{outer},.T.)"),
                add(f"FACE_BOUND('',#{hole},.T.)")], plane

    write_face_file("plane_lshape_hole", out, "make_lshape_hole.py", "2026-11-28T11:00:00",
                    bounds)


if __name__ == "__main__":
    main()
