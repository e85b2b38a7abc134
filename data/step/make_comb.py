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

Plain Python, no CAD kernel: written by make_notch.py's writer (LINE edge curves, no
pcurves).

    python3 make_comb.py data/step
"""
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


if __name__ == "__main__":
    main()
