#!/usr/bin/env python3
"""Writes cylinder_band_seamless.step from cylinder_band.step: the same lateral face of a
cylinder r = 1, 0 <= z <= 2 (area 4 pi), bounded by its two circles as two loops and without
the seam edge, the way several CAD systems (Inventor, for one) write a full cylinder band.

Plain text edit, no CAD kernel: the face's one EDGE_LOOP (circle, seam, circle, seam
reversed) becomes two EDGE_LOOPs, one circle each, under two FACE_BOUNDs; the seam's
entities stay in the file unused.

nurbs_band_seamless.step: the same band on the same cylinder written as a rational B-spline
surface closed on itself around the axis, as Zoo's exhaust manifold and ball bearing write
their pipes and rings: u around the circle (degree 2, the nine-point rational circle from
(1, 0), knots 0, 1/4, 1/2, 3/4, 1 of multiplicities 3, 2, 2, 2, 3; its first and last rows
of control points equal), v along z from 0 to 2 (degree 1); no seam edge, and the edges'
circles without pcurves (those were the cylinder's).

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
    nurbs(out, text.replace("cylinder_band_seamless.step", "nurbs_band_seamless.step"))


def nurbs(out, text):
    """The seamless band with its cylinder #31 replaced by the closed rational B-spline."""
    h = 0.5 ** 0.5
    circle = [(1, 0, 1), (1, 1, h), (0, 1, 1), (-1, 1, h), (-1, 0, 1), (-1, -1, h), (0, -1, 1),
              (1, -1, h), (1, 0, 1)]
    pts, rows, weights = [], [], []
    for i, (x, y, w) in enumerate(circle):
        ids = []
        for z in (0, 2):
            ids.append(9100 + len(pts))
            pts.append(f"#{ids[-1]} = CARTESIAN_POINT('',({x:.1f},{y:.1f},{z:.1f}));\n")
        rows.append("(" + ",".join(f"#{k}" for k in ids) + ")")
        weights.append(f"({w!r},{w!r})")
    surface = ("#31 = ( BOUNDED_SURFACE() B_SPLINE_SURFACE(2,1,(" + ",".join(rows)
               + "),.UNSPECIFIED.,.F.,.F.,.F.) B_SPLINE_SURFACE_WITH_KNOTS((3,2,2,2,3),(2,2),"
               "(0.,0.25,0.5,0.75,1.),(0.,1.),.UNSPECIFIED.) GEOMETRIC_REPRESENTATION_ITEM() "
               "RATIONAL_B_SPLINE_SURFACE((" + ",".join(weights) + ")) REPRESENTATION_ITEM('') "
               "SURFACE() );\n")
    edits = [
        ("#31 = CYLINDRICAL_SURFACE('',#32,1.);\n", surface + "".join(pts)),
        ("#21 = EDGE_CURVE('',#22,#22,#24,.T.);", "#21 = EDGE_CURVE('',#22,#22,#25,.T.);"),
        ("#66 = EDGE_CURVE('',#44,#44,#67,.T.);", "#66 = EDGE_CURVE('',#44,#44,#68,.T.);"),
    ]
    for old, new in edits:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    with open(os.path.join(out, "nurbs_band_seamless.step"), "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
