#!/usr/bin/env python3
"""Writes plane_lshape.step: one planar face bounded by a loop of six straight edges,
(43,0) (225,0) (225,105) (0,105) (0,80) (43,80) in the plane z = 0 (millimetres),
counterclockwise about +z: an L-shaped plate (a long rectangle with a short tab), the shape
of face 3 of the NX file of the corpus (bench/step_corpus.md). The loop turns 90° at five
vertices and 90° outwards at (43,80), the reentrant vertex, which lies inside a side of the
block face. Area 225 × 105 − 43 × 80 = 20185.

On a 33 × 33 grid the discrete Winslow grid of the face's (u, v) parametrization, and the
Section 4 grid on top of it, fold in the two cells next to the reentrant vertex (the
continuous maps are one-to-one); they are untangled (`src/surface/untangle.rs`).

Plain Python, no CAD kernel: written by make_notch.py's writer (LINE edge curves, no
pcurves).

    python3 make_lshape.py data/step
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_notch import write_polygon_face  # noqa: E402

PTS = [(43, 0), (225, 0), (225, 105), (0, 105), (0, 80), (43, 80)]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write_polygon_face("plane_lshape", PTS, out, "make_lshape.py")


if __name__ == "__main__":
    main()
