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

Plain Python, no CAD kernel: the entities are those of make_notch.py (LINE edge curves, no
pcurves).

    python3 make_lshape.py data/step
"""
import sys

PTS = [(43, 0), (225, 0), (225, 105), (0, 105), (0, 80), (43, 80)]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    e = []

    def add(text):
        e.append(text)
        return len(e)

    add("APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#2)")
    add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')")
    add("SHAPE_DEFINITION_REPRESENTATION(#4,#10)")
    add("PRODUCT_DEFINITION_SHAPE('','',#5)")
    add("PRODUCT_DEFINITION('design','',#6,#9)")
    add("PRODUCT_DEFINITION_FORMATION('','',#7)")
    add("PRODUCT('plane_lshape','plane_lshape','',(#8))")
    add("PRODUCT_CONTEXT('',#2,'mechanical')")
    add("PRODUCT_DEFINITION_CONTEXT('part definition',#2,'design')")
    rep = add(None)  # #10, filled in below
    origin = add("CARTESIAN_POINT('',(0.,0.,0.))")
    z = add("DIRECTION('',(0.,0.,1.))")
    x = add("DIRECTION('',(1.,0.,0.))")
    axis = add(f"AXIS2_PLACEMENT_3D('',#{origin},#{z},#{x})")
    plane = add(f"PLANE('',#{axis})")
    verts = []
    for (px, py) in PTS:
        p = add(f"CARTESIAN_POINT('',({px:.2f},{py:.2f},0.))")
        verts.append(add(f"VERTEX_POINT('',#{p})"))
    oriented = []
    n = len(PTS)
    for k in range(n):
        (ax, ay), (bx, by) = PTS[k], PTS[(k + 1) % n]
        length = ((bx - ax) ** 2 + (by - ay) ** 2) ** 0.5
        p = add(f"CARTESIAN_POINT('',({ax:.2f},{ay:.2f},0.))")
        d = add(f"DIRECTION('',({(bx - ax) / length!r},{(by - ay) / length!r},0.))")
        v = add(f"VECTOR('',#{d},1.)")
        line = add(f"LINE('',#{p},#{v})")
        edge = add(f"EDGE_CURVE('',#{verts[k]},#{verts[(k + 1) % n]},#{line},.T.)")
        oriented.append(add(f"ORIENTED_EDGE('',*,*,#{edge},.T.)"))
    loop = add("EDGE_LOOP('',(" + ",".join(f"#{o}" for o in oriented) + "))")
    bound = add(f"FACE_OUTER_BOUND('',#{loop},.T.)")
    face = add(f"ADVANCED_FACE('',(#{bound}),#{plane},.T.)")
    shell = add(f"OPEN_SHELL('',(#{face}))")
    model = add(f"SHELL_BASED_SURFACE_MODEL('',(#{shell}))")
    unc = add("UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{},"
              "'distance_accuracy_value','confusion accuracy')".format(len(e) + 3))
    ctx = add("( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT("
              f"(#{unc})) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{len(e) + 2},#{len(e) + 3},"
              f"#{len(e) + 4})) REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT "
              "and UNCERTAINTY') )")
    add("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )")
    add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )")
    add("( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )")
    e[rep - 1] = f"MANIFOLD_SURFACE_SHAPE_REPRESENTATION('',(#{axis},#{model}),#{ctx})"
    with open(f"{out}/plane_lshape.step", "w") as f:
        f.write("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ellipgrid test face'),'2;1');\n"
                "FILE_NAME('plane_lshape','2026-11-25T23:00:00',('ellipgrid'),(''),"
                "'make_lshape.py','','');\n"
                "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\n"
                "DATA;\n")
        for k, t in enumerate(e, 1):
            f.write(f"#{k} = {t};\n")
        f.write("ENDSEC;\nEND-ISO-10303-21;\n")


if __name__ == "__main__":
    main()
