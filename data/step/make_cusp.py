#!/usr/bin/env python3
"""Writes plane_cusp.step: one planar face bounded by a loop of three edges in the plane z = 0
(millimetres), counterclockwise about +z: a sliver with a cusp, as the CATIA ventilator's
three-edge faces (two long edges meeting at a few degrees, a short third edge).

    A = (0, 0)     the cusp: the loop turns there by 176° (interior angle 4°)
    B = (10, 0)    turning 96°
    C = (10, 2)    turning 109°

Every edge is a circular arc bulging into the face (a concave side): A → B of radius 100,
B → C of radius 20, C → A of radius 60.

Four corners on three concave edges put one corner inside a concave edge (its cell's angle
above 180°) or leave the cusp a corner of 4°: every corner set by turning angle folds the
face's (u, v) grid, and no balanced set exists (no point inside an edge that does not bend
outwards). Gridded with the cusp as a collapsed side (E1 one point in (u, v) and in 3D,
`src/cad/trim/cusp.rs`) the face is fold-free, its cells at the cusp triangles.

Plain Python, no CAD kernel: the entities are those of make_notch.py's writer, with CIRCLE
edge curves.

    python3 make_cusp.py data/step
"""
import math
import sys

A = (0.0, 0.0)
B = (10.0, 0.0)
C = (10.0, 2.0)
# per edge A → B, B → C, C → A: None (a line) or (radius, side) of an arc (arc_centre)
EDGES = [(100.0, 1), (20.0, 1), (60.0, 1)]


def arc_centre(p, q, r, side):
    """Centre of the circle of radius r through p and q, on the right of p → q if side > 0
    (the arc from p to q then bulges to the left of the chord), else on the left."""
    mx, my = 0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])
    dx, dy = q[0] - p[0], q[1] - p[1]
    d = math.hypot(dx, dy)
    h = side * math.sqrt(r * r - 0.25 * d * d)
    return (mx + h * dy / d, my - h * dx / d)


def write(name, out, script, pts=None, edges=None):
    pts = pts or [A, B, C]
    edges = edges or EDGES
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
    add(f"PRODUCT('{name}','{name}','',(#8))")
    add("PRODUCT_CONTEXT('',#2,'mechanical')")
    add("PRODUCT_DEFINITION_CONTEXT('part definition',#2,'design')")
    rep = add(None)  # #10, filled in below
    origin = add("CARTESIAN_POINT('',(0.,0.,0.))")
    z = add("DIRECTION('',(0.,0.,1.))")
    x = add("DIRECTION('',(1.,0.,0.))")
    axis = add(f"AXIS2_PLACEMENT_3D('',#{origin},#{z},#{x})")
    plane = add(f"PLANE('',#{axis})")
    verts = []
    for (px, py) in pts:
        p = add(f"CARTESIAN_POINT('',({px!r},{py!r},0.))")
        verts.append(add(f"VERTEX_POINT('',#{p})"))
    oriented = []

    def line(k, a, b):
        length = math.hypot(b[0] - a[0], b[1] - a[1])
        p = add(f"CARTESIAN_POINT('',({a[0]!r},{a[1]!r},0.))")
        d = add(f"DIRECTION('',({(b[0] - a[0]) / length!r},{(b[1] - a[1]) / length!r},0.))")
        v = add(f"VECTOR('',#{d},1.)")
        return add(f"LINE('',#{p},#{v})")

    def arc(k, a, b):
        # EDGES[k] = (radius, side): side > 0 bulges to the left of a → b (into the face of a
        # counterclockwise loop: clockwise about +z), side < 0 to the right (outwards)
        r, side = edges[k]
        c = arc_centre(a, b, r, side)
        pc = add(f"CARTESIAN_POINT('',({c[0]!r},{c[1]!r},0.))")
        nz = add(f"DIRECTION('',(0.,0.,{-1.0 if side > 0 else 1.0!r}))")
        rx = add("DIRECTION('',(1.,0.,0.))")
        ax = add(f"AXIS2_PLACEMENT_3D('',#{pc},#{nz},#{rx})")
        return add(f"CIRCLE('',#{ax},{r!r})")

    kinds = [line if e is None else arc for e in edges]
    n = len(pts)
    for k in range(n):
        a, b = pts[k], pts[(k + 1) % n]
        curve = kinds[k](k, a, b)
        edge = add(f"EDGE_CURVE('',#{verts[k]},#{verts[(k + 1) % n]},#{curve},.T.)")
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
    with open(f"{out}/{name}.step", "w") as f:
        f.write("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ellipgrid test face'),'2;1');\n"
                f"FILE_NAME('{name}','2026-11-27T15:00:00',('ellipgrid'),(''),"
                f"'{script}','','');\n"
                "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\n"
                "DATA;\n")
        for k, t in enumerate(e, 1):
            f.write(f"#{k} = {t};\n")
        f.write("ENDSEC;\nEND-ISO-10303-21;\n")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write("plane_cusp", out, "make_cusp.py")


if __name__ == "__main__":
    main()
