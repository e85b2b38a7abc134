#!/usr/bin/env python3
"""Writes plane_strip_tab.step: one planar face bounded by a loop of eight straight edges,
(3.8,0.8) (3.8,1) (3,1) (3,0.8) (0,0.8) (0,0) (20,0) (20,0.8) in the plane z = 0
(millimetres), counterclockwise about +z: a thin strip 20 × 0.8 with a tab 0.8 wide and 0.2
high on its top side (as the thin bands of the corpus's CATIA engine block). The loop turns
by 90° at every vertex, outwards at (3.8,0.8) and (3,0.8), the tab's feet. Area 16.16.

Corners by turning angle (all equal, the first vertices in loop order; then the convex
ones) pair the tab's 0.2 and 0.8 long sides with the strip's 40 long rest, and the discrete
Winslow (u, v) grid folds; the cut at the tab's feet folds too. Corners chosen so that
opposite sides have balanced lengths are the strip's own four: one block, fold-free
(`src/cad/trim/balance.rs`).

Plain Python, no CAD kernel: written by make_notch.py's writer (LINE edge curves, no
pcurves).

    python3 make_strip_tab.py data/step
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_notch import write_polygon_face  # noqa: E402

PTS = [(3.8, 0.8), (3.8, 1.0), (3.0, 1.0), (3.0, 0.8), (0, 0.8), (0, 0), (20, 0), (20, 0.8)]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write_polygon_face("plane_strip_tab", PTS, out, "make_strip_tab.py")


if __name__ == "__main__":
    main()
