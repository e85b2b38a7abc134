"""Writes data/step/tube_with_holes.step (a cylinder face with two holes) and
data/step/plane_holes_overlapping.step (a plane face whose two holes no straight u or v cut
separates) and data/step/washer.step (an annulus: two one-edge circles), for the tests of faces with holes (tests/step_holes.rs). OpenCascade through cadquery-ocp 8.0.1.1.0, the writer
settings of make_step_faces.py (AP214, millimetres, pcurves kept).

A solid cylinder r = 2 about z, 0 <= z <= 4, drilled through along y by a cylinder r = 0.5 at
z = 2: the lateral face keeps its seam (at theta = 0) and gets two holes, at theta = 90 and
270 degrees, bounded by the intersection curves (written as B-splines). Area of the lateral
face: 2 pi 2 4 - 2 A, with A = integral over |sin t| <= 1/4 of 2 R sqrt(r^2 - R^2 sin^2 t) dt
(R = 2, r = 0.5), printed with OCC's area of the face.

plane_holes_overlapping.step: the rectangle [0,4]x[0,3] in z = 0 with holes r = 0.8 at
(1.2, 1.1) and (2.6, 1.9): their x ranges [0.4, 2.0], [1.8, 3.4] and y ranges [0.3, 1.9],
[1.1, 2.7] overlap, so the face must be refused with the reason; area 12 - 1.28 pi.

washer.step: the top face (z = 1) of a cylinder r = 2, 0 <= z <= 1, bored through by a
cylinder r = 1 about the same axis: an annulus bounded by two circles of one edge each (the
rays from the hole's centre to the outer loop's corners meet the hole at its vertex); area
3 pi.

Usage: PYTHONPATH=<dir with OCP> python3 make_step_holes.py data/step
"""

import math
import os
import sys

from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
from OCP.GProp import GProp_GProps
from OCP.GeomAdaptor import GeomAdaptor_Surface
from OCP.BRep import BRep_Tool
from OCP.GeomAbs import GeomAbs_Cylinder, GeomAbs_Plane
from OCP.TopAbs import TopAbs_FACE, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_step_faces as m  # noqa: E402  (write_step, read_step)

R, H, r, z0 = 2.0, 4.0, 0.5, 2.0


def hole_area():
    # t = asin((r / R) sin p): A = int 2 R sqrt(r^2 - R^2 sin^2 t) dt over |sin t| <= r / R,
    # smooth in p; Gauss-Legendre on [-pi/2, pi/2] with many points.
    n = 400
    total = 0.0
    for k in range(n):
        # midpoint rule on a periodic-like smooth integrand (the integrand vanishes with all
        # odd derivatives at the ends after the substitution): spectrally accurate
        p = -math.pi / 2 + (k + 0.5) * math.pi / n
        s = (r / R) * math.sin(p)
        dt = (r / R) * math.cos(p) / math.sqrt(1 - s * s)
        total += 2 * R * math.sqrt(max(r * r - R * R * s * s, 0.0)) * dt * math.pi / n
    return total


def main(out):
    m.OUT = out
    body = BRepPrimAPI_MakeCylinder(R, H).Shape()
    drill = BRepPrimAPI_MakeCylinder(
        gp_Ax2(gp_Pnt(0, -3, z0), gp_Dir(0, 1, 0)), r, 6
    ).Shape()
    cut = BRepAlgoAPI_Cut(body, drill)
    shape = cut.Shape()
    assert BRepCheck_Analyzer(shape).IsValid()
    path = m.write_step(shape, "tube_with_holes.step")
    back = m.read_step(path)
    ex = TopExp_Explorer(back, TopAbs_FACE)
    found = 0
    while ex.More():
        f = TopoDS.Face(ex.Current())
        s = GeomAdaptor_Surface(BRep_Tool.Surface_s(f))
        wires = 0
        w = TopExp_Explorer(f, TopAbs_WIRE)
        while w.More():
            wires += 1
            w.Next()
        if s.GetType() == GeomAbs_Cylinder and abs(s.Cylinder().Radius() - R) < 1e-12:
            props = GProp_GProps()
            BRepGProp.SurfaceProperties_s(f, props, 1e-12)
            exact = 2 * math.pi * R * H - 2 * hole_area()
            print(f"lateral face: {wires} loops, area OCC {props.Mass():.10f}, exact {exact:.10f}")
            assert wires == 3 and abs(props.Mass() - exact) < 1e-6 * exact
            found += 1
        ex.Next()
    assert found == 1

    # The plate face with two holes that overlap in x and in y.
    plate = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, -1), 4, 3, 1).Shape()
    for cx, cy in [(1.2, 1.1), (2.6, 1.9)]:
        hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(cx, cy, -2), gp_Dir(0, 0, 1)), 0.8, 3)
        plate = BRepAlgoAPI_Cut(plate, hole.Shape()).Shape()
    ex = TopExp_Explorer(plate, TopAbs_FACE)
    top = None
    while ex.More():
        f = TopoDS.Face(ex.Current())
        s = GeomAdaptor_Surface(BRep_Tool.Surface_s(f))
        if s.GetType() == GeomAbs_Plane and abs(s.Plane().Location().Z()) < 1e-12:
            top = f
        ex.Next()
    assert top is not None and BRepCheck_Analyzer(top).IsValid()
    m.write_step(top, "plane_holes_overlapping.step")
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(top, props)
    print(f"overlapping holes: area OCC {props.Mass():.10f}, exact {12 - 1.28 * math.pi:.10f}")

    # The washer: an annulus between two one-edge circles.
    tube = BRepAlgoAPI_Cut(
        BRepPrimAPI_MakeCylinder(2.0, 1.0).Shape(),
        BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -1), gp_Dir(0, 0, 1)), 1.0, 3).Shape(),
    ).Shape()
    ex = TopExp_Explorer(tube, TopAbs_FACE)
    washer = None
    while ex.More():
        f = TopoDS.Face(ex.Current())
        s = GeomAdaptor_Surface(BRep_Tool.Surface_s(f))
        if s.GetType() == GeomAbs_Plane and abs(s.Plane().Location().Z() - 1.0) < 1e-12:
            washer = f
        ex.Next()
    assert washer is not None and BRepCheck_Analyzer(washer).IsValid()
    m.write_step(washer, "washer.step")
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(washer, props)
    print(f"washer: area OCC {props.Mass():.10f}, exact {3 * math.pi:.10f}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
