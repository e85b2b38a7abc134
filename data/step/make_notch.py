#!/usr/bin/env python3
"""Writes plane_notch.step: one planar face bounded by a loop of five straight edges,
(0,0) (4,0) (4,3) (2,0.5) (0,3) in the plane z = 0 (millimetres), counterclockwise about +z:
a rectangle with a V notch in its top side. The loop turns 141.3° at (4,3) and (0,3), 90° at
(0,0) and (4,0), and 102.7° outwards at (2,0.5), the reentrant vertex: by the size of their
turns alone it would be a corner. Area 7.

Plain Python, no CAD kernel: the entities are the ones OpenCascade writes for the other test
faces (see README.md), with LINE edge curves and no pcurves.

    python3 make_notch.py data/step
"""
import sys

PTS = [(0, 0), (4, 0), (4, 3), (2, 0.5), (0, 3)]


def write_polygon_face(name, pts, out, script, curve=None, coord="{:.2f}",
                       stamp="2026-11-25T23:00:00", surface=None, lift=None):
    """Writes OUT/NAME.step: one planar face bounded by the edges of the loop PTS
    (counterclockwise about +z in the plane z = 0, millimetres); SCRIPT goes in FILE_NAME with
    the time STAMP. Edge k runs from PTS[k] to the next point along CURVE(add, k, a, b), which
    adds the entities of its curve through add(text) -> entity number and returns the
    curve's number (default: a LINE); COORD formats the points' coordinates. SURFACE(add,
    axis) adds the face's surface (default: the PLANE z = 0 of the placement `axis`) and
    LIFT(px, py) places a loop point in 3D (default: (px, py, 0))."""

    def line(add, k, a, b):
        return line_edge(add, a, b, coord)

    def bounds(add, placement):
        axis = placement[3]
        plane = surface(add, axis) if surface else add(f"PLANE('',#{axis})")
        loop = polygon_loop(add, pts, coord, curve or line, lift)
        return [add(f"FACE_OUTER_BOUND('',#{loop},.T.)")], plane

    write_face_file(name, out, script, stamp, bounds)


def polygon_loop(add, pts, coord, curve, lift=None):
    """Adds the EDGE_LOOP through the points PTS (closed, in order) and returns its number:
    a VERTEX_POINT per point (placed in 3D by LIFT(px, py), default (px, py, 0) with COORD
    formatting), edge k from PTS[k] to the next along CURVE(add, k, a, b)."""
    verts = []
    for (px, py) in pts:
        if lift:
            q = ",".join(repr(c) for c in lift(px, py))
            p = add(f"CARTESIAN_POINT('',({q}))")
        else:
            p = add(f"CARTESIAN_POINT('',({coord.format(px)},{coord.format(py)},0.))")
        verts.append(add(f"VERTEX_POINT('',#{p})"))
    oriented = []
    n = len(pts)
    for k in range(n):
        c = curve(add, k, pts[k], pts[(k + 1) % n])
        edge = add(f"EDGE_CURVE('',#{verts[k]},#{verts[(k + 1) % n]},#{c},.T.)")
        oriented.append(add(f"ORIENTED_EDGE('',*,*,#{edge},.T.)"))
    return add("EDGE_LOOP('',(" + ",".join(f"#{o}" for o in oriented) + "))")


def line_edge(add, a, b, coord="{:.2f}"):
    """Adds a LINE from A to B in the plane z = 0 and returns its number."""
    (ax, ay), (bx, by) = a, b
    length = ((bx - ax) ** 2 + (by - ay) ** 2) ** 0.5
    p = add(f"CARTESIAN_POINT('',({coord.format(ax)},{coord.format(ay)},0.))")
    d = add(f"DIRECTION('',({(bx - ax) / length!r},{(by - ay) / length!r},0.))")
    v = add(f"VECTOR('',#{d},1.)")
    return add(f"LINE('',#{p},#{v})")


def write_face_file(name, out, script, stamp, bounds):
    """Writes OUT/NAME.step: one face in a shell-based surface model of an AP214 product
    (millimetres), SCRIPT and STAMP in FILE_NAME. BOUNDS(add, placement) adds the face's
    surface and bounds through add(text) -> entity number (placement: the ids of the origin,
    z and x directions and the origin's AXIS2_PLACEMENT_3D) and returns (bound ids, surface
    id)."""
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
    bound_ids, surface = bounds(add, (origin, z, x, axis))
    face = add("ADVANCED_FACE('',(" + ",".join(f"#{b}" for b in bound_ids)
               + f"),#{surface},.T.)")
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
                f"FILE_NAME('{name}','{stamp}',('ellipgrid'),(''),"
                f"'{script}','','');\n"
                "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\n"
                "DATA;\n")
        for k, t in enumerate(e, 1):
            f.write(f"#{k} = {t};\n")
        f.write("ENDSEC;\nEND-ISO-10303-21;\n")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write_polygon_face("plane_notch", PTS, out, "make_notch.py")


if __name__ == "__main__":
    main()
