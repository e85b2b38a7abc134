"""Writes the faces whose boundary loop runs through a pole of their surface (the apex of a
cone, the pole of a sphere), for tests/step_poles.rs: OpenCascade through cadquery-ocp
8.0.1.1.0 with the writer settings of make_step_faces.py (AP214, millimetres, pcurves kept).

OCC keeps a degenerated edge at the pole in its own model but writes none: each loop below
has three edges and runs through the pole at a vertex, where the surface's (u, v) jumps along
the pole.

cone_apex.step: the conical face of BRepPrimAPI_MakeCone(1, 0, 2, pi/2), a quarter of the
full cone r(z) = 1 - z/2, 0 <= z <= 2, 0 <= theta <= 90 degrees (x, y >= 0): two generator
lines from the apex (0, 0, 2) and the quarter circle r = 1 at z = 0; area pi sqrt(5) / 4.

cone_apex_full.step: the conical face of BRepPrimAPI_MakeCone(1, 0, 2), a full turn: the
circle r = 1 at z = 0, the seam line to the apex and back; area pi sqrt(5).

sphere_octant.step: the spherical face of BRepPrimAPI_MakeSphere(1, 0, pi/2, pi/2), the
octant x, y, z >= 0 of the unit sphere: two meridians from the north pole (0, 0, 1) and the
quarter equator; area pi / 2.

sphere_lune.step: the spherical face of BRepPrimAPI_MakeSphere(1, -pi/2, pi/2, pi/2), the
lune 0 <= longitude <= 90 degrees of the unit sphere: two meridians from pole to pole, a loop
of two edges through both poles (refused: one pole per face only); area pi.

cone_apex_degenerate_edge.step: cone_apex.step with a degenerated edge at the apex written
into its loop, as some CAD systems write a pole: an EDGE_CURVE from the apex vertex to itself
on a LINE (zero length), fourth in the loop. Made from cone_apex.step's text (no CAD kernel).

Each face is written alone, read back, checked (one face, three oriented edges in one loop,
area from BRepGProp to 1e-9 of the closed form) and printed.

Usage: PYTHONPATH=<dir with OCP> python3 make_step_poles.py data/step
"""

import math
import os
import sys

from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCone, BRepPrimAPI_MakeSphere
from OCP.GProp import GProp_GProps
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopExp import TopExp_Explorer

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_step_faces as m  # noqa: E402


def face_of(shape, kind):
    faces = [f for f in m.faces_of(shape) if m.surf_type(f) == kind]
    assert len(faces) == 1, kind
    return faces[0]


def count(shape, kind):
    ex, n = TopExp_Explorer(shape, kind), 0
    while ex.More():
        n += 1
        ex.Next()
    return n


def main(out):
    m.OUT = out
    cases = [
        ("cone_apex.step", BRepPrimAPI_MakeCone(1.0, 0.0, 2.0, math.pi / 2).Shape(), "cone",
         math.pi * math.sqrt(5.0) / 4.0),
        ("cone_apex_full.step", BRepPrimAPI_MakeCone(1.0, 0.0, 2.0).Shape(), "cone",
         math.pi * math.sqrt(5.0)),
        ("sphere_octant.step",
         BRepPrimAPI_MakeSphere(1.0, 0.0, math.pi / 2, math.pi / 2).Shape(), "sphere",
         math.pi / 2.0),
        ("sphere_lune.step",
         BRepPrimAPI_MakeSphere(1.0, -math.pi / 2, math.pi / 2, math.pi / 2).Shape(), "sphere",
         math.pi),
    ]
    for name, solid, kind, exact in cases:
        face = face_of(solid, kind)
        assert BRepCheck_Analyzer(face).IsValid()
        path = m.write_step(face, name)
        back = m.read_step(path)
        assert count(back, TopAbs_FACE) == 1
        props = GProp_GProps()
        BRepGProp.SurfaceProperties_s(back, props, 1e-12)
        area = props.Mass()
        assert abs(area - exact) < 1e-9 * exact, (name, area, exact)
        text = open(path).read()
        loops = [l for l in text.splitlines() if "EDGE_LOOP" in l]
        edges = loops[0].count("#") - 1 if len(loops) == 1 else 0
        assert edges == (2 if name == "sphere_lune.step" else 3), loops
        print(f"{name}: {kind}, 1 loop of {edges} edges, area OCC {area:.12f}, exact {exact:.12f}")
    degenerate_edge(out)


def degenerate_edge(out):
    """cone_apex.step with an edge of zero length at the apex closing its loop."""
    text = open(os.path.join(out, "cone_apex.step")).read()
    loop = "#19 = EDGE_LOOP('',(#20,#43,#60));"
    apex = "#24 = VERTEX_POINT('',#25);"
    assert loop in text and apex in text, "cone_apex.step is not as written by OCC 8.0.1"
    edge = (
        "#19 = EDGE_LOOP('',(#20,#43,#60,#900));\n"
        "#900 = ORIENTED_EDGE('',*,*,#901,.T.);\n"
        "#901 = EDGE_CURVE('',#24,#24,#902,.T.);\n"
        "#902 = LINE('',#25,#903);\n"
        "#903 = VECTOR('',#904,1.);\n"
        "#904 = DIRECTION('',(1.,0.,0.));"
    )
    name = "cone_apex_degenerate_edge.step"
    with open(os.path.join(out, name), "w") as f:
        f.write(text.replace(loop, edge).replace("'cone_apex'", "'cone_apex_degenerate_edge'"))
    print(f"{name}: cone_apex.step with a zero-length edge at the apex")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
