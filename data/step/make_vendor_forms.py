#!/usr/bin/env python3
"""Writes test files derived from others of this folder.

cone_patch_vendor_forms.step: the face of cone_patch.step with the entity forms
that CAD systems write and truck-stepio 0.3 alone loses, so that the same face must come out:
- plane angles in degrees (a CONVERSION_BASED_UNIT 'DEGREE' in the unit context, as Creo,
  Inventor, Pro/E and UG write): the cone's semi-angle atan(1/2) written as 26.565051177078;
- the edge along the circle of radius 2 (z = 0) on a TRIMMED_CURVE($, circle, (point),
  (point), .T., .CARTESIAN.) whose circle's AXIS2_PLACEMENT_3D is named `$` (Rhino 8);
- the edge along the circle of radius 1 (z = 2) on a TRIMMED_CURVE that runs against its
  circle (sense .F., trims by point), the edge's same_sense .F. accordingly;
- an AXIS2_PLACEMENT_3D along the x axis without a reference direction (CATIA), for a
  placement the face does not use;
- a PRODUCT whose frame_of_reference is the empty list `()` (zoo.dev), at which the
  tokenizer of truck-stepio 0.3 refused the whole file.

plane_notch_tolerant.step: plane_notch.step with its vertex (4, 3, 0) moved to (4, 3, 0.01),
so that its two edges there leave the plane z = 0 by up to 1e-2 (2e-3 of the loop's size 5,
above the relative tolerance 1e-3), and the file's distance uncertainty 5e-3 instead of 1e-7
(the gap is then within 3 uncertainties, as CATIA's ventilator has them).

plane_notch_sloppy.step: plane_notch.step with its edge from (4, 0) to (4, 3) on a straight
B-spline through x = 4.01: that edge's ends miss its vertices, and the ends of the edges before and
after it, by 1e-2 (2e-3 of the loop's size 5, a hundred thousand times the file's uncertainty
1e-7), as TraceParts writes a circle of radius 1.49 between vertices at radius 1.50.

cylinder_patch_nurbs_vendor_order.step: cylinder_patch_nurbs.step with the partial entities
of its complex instances in the order Spatial's writer (TraceParts) uses, `_` before letters
(`B_SPLINE_SURFACE(…) B_SPLINE_SURFACE_WITH_KNOTS(…) BOUNDED_SURFACE() …`), at which the reader
lost every rational surface and its face; and a second face on a RECTANGULAR_TRIMMED_SURFACE of
the same NURBS surface over its whole parameter range (the same shape; truck-stepio 0.3 reads
no trimmed surface, so that face is left out and must be named).

    python3 make_vendor_forms.py data/step
"""
import math
import pathlib
import sys


def main():
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    here = pathlib.Path(__file__).parent
    text = (here / "cone_patch.step").read_text()
    deg = math.degrees(math.atan(0.5))

    def sub(old, new):
        nonlocal text
        assert text.count(old) == 1, old
        text = text.replace(old, new)

    sub("CONICAL_SURFACE('',#34,2.,0.463647609001)", f"CONICAL_SURFACE('',#34,2.,{deg:.12f})")
    sub("#93 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );",
        "#93 = ( CONVERSION_BASED_UNIT('DEGREE',#97) NAMED_UNIT(*) PLANE_ANGLE_UNIT() );")
    sub("#61 = EDGE_CURVE('',#46,#62,#64,.T.);", "#61 = EDGE_CURVE('',#46,#62,#99,.T.);")
    sub("#66 = AXIS2_PLACEMENT_3D('',#67,#68,#69);", "#66 = AXIS2_PLACEMENT_3D($,#67,#68,#69);")
    sub("#21 = EDGE_CURVE('',#22,#24,#26,.T.);", "#21 = EDGE_CURVE('',#22,#24,#100,.F.);")
    extra = [
        "#97 = PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(1.745329251994E-02),#98);",
        "#98 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );",
        "#99 = TRIMMED_CURVE($,#65,(#47),(#63),.T.,.CARTESIAN.);",
        "#100 = TRIMMED_CURVE($,#27,(#25),(#23),.F.,.CARTESIAN.);",
        "#101 = AXIS2_PLACEMENT_3D('',#29,#102,$);",
        "#102 = DIRECTION('',(1.,0.,0.));",
        "#103 = CIRCLE('',#101,1.);",
        "#104 = PRODUCT('p', 'NONE', $, ());",
    ]
    sub("ENDSEC;\nEND-ISO-10303-21;", "\n".join(extra) + "\nENDSEC;\nEND-ISO-10303-21;")
    (out / "cone_patch_vendor_forms.step").write_text(text)

    text = (here / "plane_notch.step").read_text()
    sub("#20 = CARTESIAN_POINT('',(4.00,3.00,0.));", "#20 = CARTESIAN_POINT('',(4.00,3.00,0.01));")
    sub("LENGTH_MEASURE(1.E-07)", "LENGTH_MEASURE(5.E-03)")
    (out / "plane_notch_tolerant.step").write_text(text)

    text = (here / "plane_notch.step").read_text()
    sub("#36 = EDGE_CURVE('',#19,#21,#35,.T.);", "#36 = EDGE_CURVE('',#19,#21,#66,.T.);")
    extra = [
        "#66 = B_SPLINE_CURVE_WITH_KNOTS('',1,(#67,#68),.POLYLINE_FORM.,.F.,.F.,(2,2),(0.,3.),"
        ".UNSPECIFIED.);",
        "#67 = CARTESIAN_POINT('',(4.01,0.00,0.));",
        "#68 = CARTESIAN_POINT('',(4.01,3.00,0.));",
    ]
    sub("ENDSEC;\nEND-ISO-10303-21;", "\n".join(extra) + "\nENDSEC;\nEND-ISO-10303-21;")
    (out / "plane_notch_sloppy.step").write_text(text)

    text = (here / "cylinder_patch_nurbs.step").read_text()
    for old, new in [
        ("#31 = ( BOUNDED_SURFACE() B_SPLINE_SURFACE(", "#31 = ( B_SPLINE_SURFACE("),
        (".PIECEWISE_BEZIER_KNOTS.) \nGEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE((",
         ".PIECEWISE_BEZIER_KNOTS.) \nRATIONAL_B_SPLINE_SURFACE(("),
        (",(1.,1.))) REPRESENTATION_ITEM('') SURFACE() );",
         ",(1.,1.))) BOUNDED_SURFACE() GEOMETRIC_REPRESENTATION_ITEM() REPRESENTATION_ITEM('')\n"
         "SURFACE() );"),
        ("#16 = OPEN_SHELL('',(#17));", "#16 = OPEN_SHELL('',(#17,#200));"),
    ]:
        sub(old, new)
    extra = [
        "#200 = ADVANCED_FACE('',(#18),#201,.T.);",
        "#201 = RECTANGULAR_TRIMMED_SURFACE('',#31,0.,1.570796326795,0.,3.,.T.,.T.);",
    ]
    sub("ENDSEC;\nEND-ISO-10303-21;", "\n".join(extra) + "\nENDSEC;\nEND-ISO-10303-21;")
    (out / "cylinder_patch_nurbs_vendor_order.step").write_text(text)


if __name__ == "__main__":
    main()
