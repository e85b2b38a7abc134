#!/usr/bin/env python3
"""Writes plane_triangle_assembly.step: the part of plane_triangle.step (one planar triangle
face, (0,0), (3,0), (0,2) in z = 0, its shape representation #10 with the origin placement #11)
used twice in a sub-assembly `pair`, which is used once in the root assembly `frame`, in the
AP214 assembly structure CAD systems write (NEXT_ASSEMBLY_USAGE_OCCURRENCE, a
CONTEXT_DEPENDENT_SHAPE_REPRESENTATION of each usage, and a REPRESENTATION_RELATIONSHIP_WITH_
TRANSFORMATION whose ITEM_DEFINED_TRANSFORMATION maps a placement of the component onto one of
the parent):
- usage 1 of the triangle in `pair`: placement at (10, 0, 0), rotated 90° about z (x ↦ y);
- usage 2: placement at (0, 0, 5) with axis (1, 0, 0) and reference direction (0, 1, 0)
  (local x ↦ y, y ↦ z, z ↦ x), its transformation's two items written the other way round
  (the parent's placement first), as some writers do;
- `pair` in `frame`: placement at (0, 100, 0), unrotated.
So the file's two faces are the triangle moved by p ↦ (10, 100, 0) + (−p_y, p_x, p_z) and
p ↦ (0, 100, 5) + (p_z, p_x, p_y).

plane_triangle_mapped.step: the same two instances written as AP203's other assembly form,
mapped items: `pair`'s shape representation holds two MAPPED_ITEMs of the triangle's
representation (REPRESENTATION_MAP with the origin #11), the first targeted at an
AXIS2_PLACEMENT_3D, the second at a CARTESIAN_TRANSFORMATION_OPERATOR_3D (axis1 (0, 1, 0),
axis3 (1, 0, 0), origin (0, 0, 5)); `frame`'s holds one MAPPED_ITEM of `pair` at (0, 100, 0).
A DRAUGHTING_MODEL with an identity MAPPED_ITEM of the triangle (a presentation, as UG and
CADDS write) places nothing: the faces are the two above.

plane_triangle_assembly_inch.step: the same with both assemblies measured in inches (a
CONVERSION_BASED_UNIT 'INCH' of 25.4 mm), the part still in millimetres: the faces in inches,
p ↦ (10 − p_y/25.4, 100 + p_x/25.4, p_z/25.4) and (p_z/25.4, 100 + p_x/25.4, 5 + p_y/25.4).

    python3 make_assembly.py data/step
"""
import pathlib
import sys


def main():
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    here = pathlib.Path(__file__).parent
    base = (here / "plane_triangle.step").read_text()
    inch = """#400 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3)
GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#404)) GLOBAL_UNIT_ASSIGNED_CONTEXT((#401,#75,#76))
REPRESENTATION_CONTEXT('Context #2','3D Context in inches') );
#401 = ( CONVERSION_BASED_UNIT('INCH',#402) LENGTH_UNIT() NAMED_UNIT(#403) );
#402 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#74);
#403 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);
#404 = UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(4.E-09),#401,
  'distance_accuracy_value','confusion accuracy');
"""
    # the part's 3D context #73 is in millimetres
    for name, ctx, units in [("plane_triangle_assembly", "#73", ""),
                             ("plane_triangle_assembly_inch", "#400", inch)]:
        write(out / f"{name}.step", base, ctx, units)
    mapped(out / "plane_triangle_mapped.step", base)


def mapped(path, text):
    """The part of `text` placed twice in `pair` and `pair` once in `frame` by mapped items."""
    extra = """#500 = REPRESENTATION_MAP(#11,#10);
#501 = AXIS2_PLACEMENT_3D('',#502,#503,#504);
#502 = CARTESIAN_POINT('',(0.,0.,0.));
#503 = DIRECTION('',(0.,0.,1.));
#504 = DIRECTION('',(1.,0.,0.));
#510 = MAPPED_ITEM('triangle 1',#500,#511);
#511 = AXIS2_PLACEMENT_3D('',#512,#503,#513);
#512 = CARTESIAN_POINT('',(10.,0.,0.));
#513 = DIRECTION('',(0.,1.,0.));
#520 = MAPPED_ITEM('triangle 2',#500,#521);
#521 = CARTESIAN_TRANSFORMATION_OPERATOR_3D('','',#513,$,#522,$,#523);
#522 = CARTESIAN_POINT('',(0.,0.,5.));
#523 = DIRECTION('',(1.,0.,0.));
#530 = SHAPE_REPRESENTATION('pair',(#501,#510,#520),#73);
#531 = PRODUCT('pair','pair','',(#8));
#532 = PRODUCT_DEFINITION_FORMATION('','',#531);
#533 = PRODUCT_DEFINITION('design','',#532,#9);
#534 = PRODUCT_DEFINITION_SHAPE('','',#533);
#535 = SHAPE_DEFINITION_REPRESENTATION(#534,#530);
#540 = REPRESENTATION_MAP(#501,#530);
#541 = AXIS2_PLACEMENT_3D('',#542,#503,#504);
#542 = CARTESIAN_POINT('',(0.,100.,0.));
#543 = MAPPED_ITEM('pair',#540,#541);
#544 = AXIS2_PLACEMENT_3D('',#502,#503,#504);
#550 = SHAPE_REPRESENTATION('frame',(#544,#543),#73);
#551 = PRODUCT('frame','frame','',(#8));
#552 = PRODUCT_DEFINITION_FORMATION('','',#551);
#553 = PRODUCT_DEFINITION('design','',#552,#9);
#554 = PRODUCT_DEFINITION_SHAPE('','',#553);
#555 = SHAPE_DEFINITION_REPRESENTATION(#554,#550);
#560 = MAPPED_ITEM('',#500,#501);
#561 = DRAUGHTING_MODEL('',(#501,#560),#73);
ENDSEC;
END-ISO-10303-21;"""
    end = "ENDSEC;\nEND-ISO-10303-21;"
    assert text.count(end) == 1
    path.write_text(text.replace(end, extra) + "\n")


def write(path, text, ctx, units):
    """The part of `text` in the two assemblies, whose representations use context `ctx`
    (`units`: its entities, if new)."""
    extra = units + f"""#100 = PRODUCT('pair','pair','',(#8));
#101 = PRODUCT_DEFINITION_FORMATION('','',#100);
#102 = PRODUCT_DEFINITION('design','',#101,#9);
#103 = PRODUCT_DEFINITION_SHAPE('','',#102);
#104 = SHAPE_DEFINITION_REPRESENTATION(#103,#110);
#110 = SHAPE_REPRESENTATION('pair',(#111,#120,#130),{ctx});
#111 = AXIS2_PLACEMENT_3D('',#112,#113,#114);
#112 = CARTESIAN_POINT('',(0.,0.,0.));
#113 = DIRECTION('',(0.,0.,1.));
#114 = DIRECTION('',(1.,0.,0.));
#120 = AXIS2_PLACEMENT_3D('',#121,#122,#123);
#121 = CARTESIAN_POINT('',(10.,0.,0.));
#122 = DIRECTION('',(0.,0.,1.));
#123 = DIRECTION('',(0.,1.,0.));
#130 = AXIS2_PLACEMENT_3D('',#131,#132,#133);
#131 = CARTESIAN_POINT('',(0.,0.,5.));
#132 = DIRECTION('',(1.,0.,0.));
#133 = DIRECTION('',(0.,1.,0.));
#140 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('1','triangle 1','',#102,#5,$);
#141 = PRODUCT_DEFINITION_SHAPE('','',#140);
#142 = ITEM_DEFINED_TRANSFORMATION('','',#11,#120);
#143 = ( REPRESENTATION_RELATIONSHIP('','',#10,#110)
REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#142) SHAPE_REPRESENTATION_RELATIONSHIP() );
#144 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#143,#141);
#150 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('2','triangle 2','',#102,#5,$);
#151 = PRODUCT_DEFINITION_SHAPE('','',#150);
#152 = ITEM_DEFINED_TRANSFORMATION('','',#130,#11);
#153 = ( REPRESENTATION_RELATIONSHIP('','',#10,#110)
REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#152) SHAPE_REPRESENTATION_RELATIONSHIP() );
#154 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#153,#151);
#200 = PRODUCT('frame','frame','',(#8));
#201 = PRODUCT_DEFINITION_FORMATION('','',#200);
#202 = PRODUCT_DEFINITION('design','',#201,#9);
#203 = PRODUCT_DEFINITION_SHAPE('','',#202);
#204 = SHAPE_DEFINITION_REPRESENTATION(#203,#210);
#210 = SHAPE_REPRESENTATION('frame',(#211,#220),{ctx});
#211 = AXIS2_PLACEMENT_3D('',#112,#113,#114);
#220 = AXIS2_PLACEMENT_3D('',#221,#113,#114);
#221 = CARTESIAN_POINT('',(0.,100.,0.));
#240 = NEXT_ASSEMBLY_USAGE_OCCURRENCE('3','pair','',#202,#102,$);
#241 = PRODUCT_DEFINITION_SHAPE('','',#240);
#242 = ITEM_DEFINED_TRANSFORMATION('','',#111,#220);
#243 = ( REPRESENTATION_RELATIONSHIP('','',#110,#210)
REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#242) SHAPE_REPRESENTATION_RELATIONSHIP() );
#244 = CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#243,#241);
ENDSEC;
END-ISO-10303-21;"""
    end = "ENDSEC;\nEND-ISO-10303-21;"
    assert text.count(end) == 1
    text = text.replace(end, extra)
    path.write_text(text + "\n")


if __name__ == "__main__":
    main()
