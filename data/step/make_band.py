#!/usr/bin/env python3
"""Writes cylinder_band_seamless.step from cylinder_band.step: the same lateral face of a
cylinder r = 1, 0 <= z <= 2 (area 4 pi), bounded by its two circles as two loops and without
the seam edge, the way several CAD systems (Inventor, for one) write a full cylinder band.

Plain text edit, no CAD kernel: the face's one EDGE_LOOP (circle, seam, circle, seam
reversed) becomes two EDGE_LOOPs, one circle each, under two FACE_BOUNDs; the seam's
entities stay in the file unused.

    python3 make_band.py data/step
"""
import os
import sys


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    src = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cylinder_band.step")
    text = open(src).read()
    old = (
        "#17 = ADVANCED_FACE('',(#18),#31,.T.);\n"
        "#18 = FACE_BOUND('',#19,.T.);\n"
        "#19 = EDGE_LOOP('',(#20,#42,#65,#80));\n"
    )
    new = (
        "#17 = ADVANCED_FACE('',(#18,#9018),#31,.T.);\n"
        "#18 = FACE_BOUND('',#19,.T.);\n"
        "#19 = EDGE_LOOP('',(#20));\n"
        "#9018 = FACE_BOUND('',#9019,.T.);\n"
        "#9019 = EDGE_LOOP('',(#65));\n"
    )
    assert old in text, "cylinder_band.step is not the file this script edits"
    text = text.replace(old, new).replace("cylinder_band.step", "cylinder_band_seamless.step")
    with open(os.path.join(out, "cylinder_band_seamless.step"), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
