#!/usr/bin/env python3
"""Writes plane_bolt_circle.step, plane_flange.step and plane_holes_2x2.step for
tests/step_holes.rs.

plane_bolt_circle.step: one planar face in z = 0 (millimetres), the rectangle
[0, 10] x [0, 8] (four LINE edges, counterclockwise about +z) with four circular holes of
radius 0.5 on a bolt circle of radius 2.6 about (5, 4), at 45, 135, 225 and 315 degrees (each
hole one closed CIRCLE edge, run clockwise), as the corpus's flanges and plates with bolt
patterns (#14). The holes' x ranges overlap in pairs and so do their y ranges: no straight
u = const or v = const line separates them, but parallel lines at about 22.5 degrees do
(the holes' extents along that normal are 1.41, 1.99, 1.41 apart).
Area 80 - 4 * pi * 0.25 = 80 - pi.

plane_flange.step: the disc of radius 5 about (5, 5) (one CIRCLE edge) with a bore of radius 2 about (5, 5) and six
holes of radius 0.5 on a circle of radius 3.2 about it, at 0, 60, ..., 300 degrees: no set of
parallel lines separates the seven holes, a fan of six cuts from the bore to the outer loop
(at 30, 90, ..., 330 degrees) does. Area 25 pi - 4 pi - 6 * pi * 0.25 = 19.5 pi.

plane_holes_2x2.step: the square [0, 6] x [0, 6] with four holes of radius 1.15 at (1.75,
1.75), (4.25, 1.75), (1.75, 4.25), (4.25, 4.25), 0.2 apart: no parallel lines separate them
and, seen from any one of them, two others overlap: refused with the reason.

Plain Python, no CAD kernel: make_notch.py's entities, the holes as OpenCascade writes a
drilled plate's (one vertex and one CIRCLE edge per hole, ORIENTED_EDGE .F. in a FACE_BOUND).

    python3 make_bolt_circle.py data/step
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_notch import write_face_file  # noqa: E402


def bolts(centre, radius, r, angles):
    """Holes of radius r on the circle of radius RADIUS about CENTRE at ANGLES (degrees)."""
    return [(centre[0] + radius * math.cos(math.radians(a)),
             centre[1] + radius * math.sin(math.radians(a)), r) for a in angles]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    write(out, "plane_bolt_circle", 10.0, 8.0, bolts((5.0, 4.0), 2.6, 0.5, [45, 135, 225, 315]))
    write(out, "plane_flange", None, 5.0,
          [(5.0, 5.0, 2.0)] + bolts((5.0, 5.0), 3.2, 0.5, range(0, 360, 60)))
    write(out, "plane_holes_2x2", 6.0, 6.0,
          [(x, y, 1.15) for y in (1.75, 4.25) for x in (1.75, 4.25)])


def write(out, name, W, H, holes):
    """Writes OUT/NAME.step: the rectangle [0, W] x [0, H] in z = 0 (if W is None the disc
    of radius H about (H, H)) with circular HOLES (centre x, centre y, radius)."""

    def bounds(add, placement):
        _, z, x, axis = placement
        plane = add(f"PLANE('',#{axis})")

        def point(px, py):
            return add(f"CARTESIAN_POINT('',({px!r},{py!r},0.))")

        if W is None:
            # A disc of radius H about (H, H): one closed CIRCLE edge, counterclockwise.
            v = add(f"VERTEX_POINT('',#{point(2 * H, H)})")
            place = add(f"AXIS2_PLACEMENT_3D('',#{point(H, H)},#{z},#{x})")
            circle = add(f"CIRCLE('',#{place},{H!r})")
            edge = add(f"EDGE_CURVE('',#{v},#{v},#{circle},.T.)")
            oriented = [add(f"ORIENTED_EDGE('',*,*,#{edge},.T.)")]
        else:
            pts = [(0.0, 0.0), (W, 0.0), (W, H), (0.0, H)]
            verts = [add(f"VERTEX_POINT('',#{point(*p)})") for p in pts]
            oriented = []
            for k in range(4):
                (ax, ay), (bx, by) = pts[k], pts[(k + 1) % 4]
                length = math.hypot(bx - ax, by - ay)
                d = add(f"DIRECTION('',({(bx - ax) / length!r},{(by - ay) / length!r},0.))")
                v = add(f"VECTOR('',#{d},1.)")
                c = add(f"LINE('',#{point(ax, ay)},#{v})")
                edge = add(f"EDGE_CURVE('',#{verts[k]},#{verts[(k + 1) % 4]},#{c},.T.)")
                oriented.append(add(f"ORIENTED_EDGE('',*,*,#{edge},.T.)"))
        loop = add("EDGE_LOOP('',(" + ",".join(f"#{o}" for o in oriented) + "))")
        ids = [add(f"FACE_OUTER_BOUND('',#{loop},.T.)")]
        for (cx, cy, RH) in holes:
            v = add(f"VERTEX_POINT('',#{point(cx + RH, cy)})")
            place = add(f"AXIS2_PLACEMENT_3D('',#{point(cx, cy)},#{z},#{x})")
            circle = add(f"CIRCLE('',#{place},{RH!r})")
            edge = add(f"EDGE_CURVE('',#{v},#{v},#{circle},.T.)")
            o = add(f"ORIENTED_EDGE('',*,*,#{edge},.F.)")
            hole = add(f"EDGE_LOOP('',(#{o}))")
            ids.append(add(f"FACE_BOUND('',#{hole},.T.)"))
        return ids, plane

    write_face_file(name, out, "make_bolt_circle.py", "2026-11-27T23:40:00", bounds)


if __name__ == "__main__":
    main()
