#!/usr/bin/env python3
"""Writes plane_slot.step: one planar face bounded by a loop of eight straight edges,
(0,0) (100,0) (100,60) (55,60) (55,10) (45,10) (45,60) (0,60) in the plane z = 0
(millimetres), counterclockwise about +z: a plate with a slot 10 wide and 50 deep cut from
its top side. The loop turns 90° outwards at (55,10) and (45,10), the reentrant vertices.
Area 100 × 60 − 10 × 50 = 5500.

As one block face the discrete Winslow grid of the face's (u, v) parametrization folds next
to the slot (8 and 30 cells at 17 and 33 nodes, not untangled); the face is cut at its two
reentrant vertices into three blocks (`src/cad/reentrant.rs`).

Plain Python, no CAD kernel: written by make_notch.py's writer (LINE edge curves, no
pcurves).

    python3 make_slot.py data/step
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_notch import write_polygon_face  # noqa: E402

PTS = [(0, 0), (100, 0), (100, 60), (55, 60), (55, 10), (45, 10), (45, 60), (0, 60)]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write_polygon_face("plane_slot", PTS, out, "make_slot.py")


if __name__ == "__main__":
    main()
