//! Tests of the STEP text rewrites.

use super::*;

#[test]
fn pcurve_masters_are_rewritten() {
    let t = "#47 = SURFACE_CURVE('',#48,(#52),.PCURVE_S1.);";
    assert_eq!(
        prefer_3d_curves(t),
        "#47 = SURFACE_CURVE('',#48,(#52),.CURVE_3D.);"
    );
    assert!(matches!(prefer_3d_curves("#1 = LINE();"), Cow::Borrowed(_)));
}

#[test]
fn unset_names_of_geometry_become_empty_and_other_unset_attributes_stay() {
    let t = "#1=AXIS2_PLACEMENT_3D($,#2,#3,$);\n#4=SI_UNIT($,.METRE.);\n\
        #5=( BOUNDED_CURVE() REPRESENTATION_ITEM($) );\n#6=CIRCLE('c',#1,1.);\n";
    let r = unnamed_labels(t);
    assert!(r.contains("#1=AXIS2_PLACEMENT_3D('',#2,#3,$);"), "{r}");
    assert!(r.contains("#4=SI_UNIT($,.METRE.);"), "{r}");
    assert!(r.contains("REPRESENTATION_ITEM('')"), "{r}");
    assert!(r.contains("#6=CIRCLE('c',#1,1.);"), "{r}");
}

#[test]
fn edges_and_swept_surfaces_on_trimmed_curves_refer_to_the_basis_with_the_sense_combined() {
    let t = "DATA;\n#1=TRIMMED_CURVE($,#2,(#9),(#10),.T.,.CARTESIAN.);\n\
        #3=TRIMMED_CURVE('',#1,(PARAMETER_VALUE(1.)),(PARAMETER_VALUE(0.)),\n.F.,.UNSPECIFIED.);\n\
        #4=EDGE_CURVE('',#5,#6,#1,.T.);\n#7 = EDGE_CURVE('a;b',#5,#6, #3 ,.T.);\n\
        #8=EDGE_CURVE('',#5,#6,#2,.F.);\n#11=SURFACE_OF_LINEAR_EXTRUSION('',#3,#12);\n\
        #13=ADVANCED_FACE('',(#14),#11,.T.);\n#15=SURFACE_OF_REVOLUTION('',#1,#16);\n\
        #17=ADVANCED_FACE('',(#14),#15,.F.);\nENDSEC;\n";
    let r = untrim_curves(t);
    assert!(r.contains("#4=EDGE_CURVE('',#5,#6,#2,.T.);"), "{r}");
    assert!(r.contains("#7 = EDGE_CURVE('a;b',#5,#6, #2 ,.F.);"), "{r}");
    assert!(r.contains("#8=EDGE_CURVE('',#5,#6,#2,.F.);"), "{r}");
    assert!(
        !r.contains("TRIMMED_CURVE"),
        "unreferenced trimmed curves stay: {r}"
    );
    assert!(
        r.contains("#11=SURFACE_OF_LINEAR_EXTRUSION('',#2,#12);"),
        "{r}"
    );
    assert!(r.contains("#13=ADVANCED_FACE('',(#14),#11,.F.);"), "{r}");
    assert!(r.contains("#15=SURFACE_OF_REVOLUTION('',#2,#16);"), "{r}");
    assert!(r.contains("#17=ADVANCED_FACE('',(#14),#15,.F.);"), "{r}");
    assert!(matches!(untrim_curves("#1=LINE();"), Cow::Borrowed(_)));
}

#[test]
fn placements_along_x_without_a_reference_direction_get_one() {
    let t = "DATA;\n#1=DIRECTION('',(-1.,0.,0.));\n#2=DIRECTION('',(0.,0.,1.E0));\n\
        #3=AXIS2_PLACEMENT_3D('c',#9,#1,$);\n#4=AXIS2_PLACEMENT_3D('d',#9,#2,$);\n\
        #5=AXIS2_PLACEMENT_3D('e',#9,#1,#2);\n#12=CIRCLE('',#3,1.);\nENDSEC;\n";
    let r = default_ref_directions(t);
    assert!(r.contains("#3=AXIS2_PLACEMENT_3D('c',#9,#1,#13);"), "{r}");
    assert!(r.contains("#4=AXIS2_PLACEMENT_3D('d',#9,#2,$);"), "{r}");
    assert!(r.contains("#5=AXIS2_PLACEMENT_3D('e',#9,#1,#2);"), "{r}");
    assert!(r.contains("#13=DIRECTION('',(0.,0.,1.));\nENDSEC;"), "{r}");
    assert!(matches!(
        default_ref_directions(&t.replace("(-1.,0.,0.)", "(0.,1.,0.)")),
        Cow::Borrowed(_)
    ));
}

#[test]
fn references_in_strings_are_not_counted() {
    let t = "#1=TRIMMED_CURVE('#1',#2,(#9),(#10),.T.,.CARTESIAN.);\n\
        #4=EDGE_CURVE('it''s #1',#5,#6,#1,.T.);\n#7=X(#1, '''#1''', #2 );\n#8=Y('#2');\n";
    let ids: HashMap<u64, ()> = [(1, ()), (2, ()), (3, ())].into_iter().collect();
    let n = reference_counts(t, &ids);
    assert_eq!((n[&1], n[&2], n[&3]), (2, 2, 0));
}

#[test]
fn empty_lists_become_unset_and_entities_without_attributes_stay() {
    let t = "#1 = (\n  LENGTH_UNIT()\n  NAMED_UNIT(*)\n  SI_UNIT($, .METRE.)\n);\n\
        #2 = PRODUCT('p', 'NONE', $, ());\n#3 = X(( ), 'a(),()', (#1, ()));\n";
    let r = empty_lists(t);
    assert!(r.contains("LENGTH_UNIT()"), "{r}");
    assert!(r.contains("#2 = PRODUCT('p', 'NONE', $, $);"), "{r}");
    assert!(r.contains("#3 = X($, 'a(),()', (#1, $));"), "{r}");
    assert!(matches!(empty_lists("#1 = A(1, (2));"), Cow::Borrowed(_)));
}

#[test]
fn empty_lists_in_and_after_strings_stay() {
    // `()` inside a string, after a string and after a doubled quote are no attributes
    let t = "#1 = A('(),()', 'it''s', ());\n#2 = B('x'(), (''), 'a''(', ());\n";
    let r = empty_lists(t);
    assert_eq!(
        r,
        "#1 = A('(),()', 'it''s', $);\n#2 = B('x'(), (''), 'a''(', $);\n"
    );
}
