#!/usr/bin/env python3
"""Generate small STEP (AP214) test files for ellipgrid with OpenCascade.

Requires the OpenCascade Python bindings from PyPI:  pip install cadquery-ocp
Run:  python3 make_step_faces.py [OUTDIR]     (default: the current directory)

Writes one .step file per test case plus faces.json, which holds for each
file the analytic description of its faces (surface type, placement, radii,
parameter ranges) and the area OCC computes with BRepGProp.SurfaceProperties,
together with the closed-form area where one exists.  All lengths are in
millimetres (the writer's default; the files state SI_UNIT(.MILLI.,.METRE.)).
Angles in faces.json are in radians unless the key ends in _deg.
"""

import json
import math
import os
import sys

import OCP
from OCP.BRep import BRep_Tool
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeEdge,
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakePolygon,
    BRepBuilderAPI_MakeWire,
)
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepFilletAPI import BRepFilletAPI_MakeFillet
from OCP.BRepGProp import BRepGProp
from OCP.BRepLib import BRepLib
from OCP.BRepPrimAPI import (
    BRepPrimAPI_MakeBox,
    BRepPrimAPI_MakeCone,
    BRepPrimAPI_MakeCylinder,
)
from OCP.BRepTools import BRepTools
from OCP.GC import GC_MakeArcOfCircle
try:  # OCCT 8 merged GCE2d into GC
    from OCP.GC import GC_MakeSegment2d
except ImportError:  # OCCT 7.x
    from OCP.GCE2d import GCE2d_MakeSegment as GC_MakeSegment2d
from OCP.GeomAbs import GeomAbs_C2
from OCP.GeomAdaptor import GeomAdaptor_Surface
from OCP.GeomAPI import GeomAPI_PointsToBSplineSurface
from OCP.Geom import (
    Geom_CylindricalSurface,
    Geom_SphericalSurface,
    Geom_ToroidalSurface,
)
from OCP.GeomAbs import (
    GeomAbs_BSplineSurface,
    GeomAbs_Cone,
    GeomAbs_Cylinder,
    GeomAbs_Plane,
    GeomAbs_Sphere,
    GeomAbs_Torus,
)
from OCP.GProp import GProp_GProps
from OCP.IFSelect import IFSelect_RetDone
from OCP.Interface import Interface_Static
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader
try:  # OCCT 8: NCollection arrays live in OCP.collections
    from OCP.collections import Array2_double as TColStd_Array2OfReal
except ImportError:  # OCCT 7.x
    from OCP.TColStd import TColStd_Array2OfReal
try:
    from OCP.collections import Array2_gp_Pnt as TColgp_Array2OfPnt
except ImportError:  # OCCT 7.x
    from OCP.TColgp import TColgp_Array2OfPnt
from OCP.Approx import Approx_IsoParametric
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex, BRepBuilderAPI_NurbsConvert
from OCP.Geom2d import Geom2d_Line
from OCP.GeomAPI import GeomAPI_ProjectPointOnSurf
from OCP.TopLoc import TopLoc_Location
from OCP.gp import gp_Dir2d, gp_Vec
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_VERTEX, TopAbs_WIRE
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS
from OCP.gp import gp_Ax2, gp_Ax3, gp_Circ, gp_Dir, gp_Pnt, gp_Pnt2d

# OCCT 8 exposes TopoDS::Face etc. as plain functions, OCCT 7 as static *_s
_cast = lambda n: getattr(TopoDS, n + "_s", None) or getattr(TopoDS, n)
as_face, as_edge, as_vertex = _cast("Face"), _cast("Edge"), _cast("Vertex")

TOL = 1e-7
PI = math.pi
OUT = sys.argv[1] if len(sys.argv) > 1 else "."

# --------------------------------------------------------------------------
# helpers


def ax3_z():
    """Right-handed frame at the origin, main axis +z, x direction +x."""
    return gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0))


def explore(shape, kind):
    out = []
    exp = TopExp_Explorer(shape, kind)
    while exp.More():
        out.append(exp.Current())
        exp.Next()
    return out


def faces_of(shape):
    return [as_face(s) for s in explore(shape, TopAbs_FACE)]


def area(shape):
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, props)
    return props.Mass()


def volume(shape):
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return props.Mass()


SURF_NAMES = {
    GeomAbs_Plane: "plane",
    GeomAbs_Cylinder: "cylinder",
    GeomAbs_Cone: "cone",
    GeomAbs_Sphere: "sphere",
    GeomAbs_Torus: "torus",
    GeomAbs_BSplineSurface: "bspline",
}


def surf_type(face):
    ad = GeomAdaptor_Surface(BRep_Tool.Surface_s(face))
    return SURF_NAMES.get(ad.GetType(), str(ad.GetType()))


def _xyz(v):
    return [round(v.X(), 12) + 0.0, round(v.Y(), 12) + 0.0, round(v.Z(), 12) + 0.0]


def _ax3(a):
    return {"location": _xyz(a.Location()), "axis": _xyz(a.Direction()),
            "x_dir": _xyz(a.XDirection()), "y_dir": _xyz(a.YDirection()),
            "right_handed": bool(a.Direct())}


def surface_params(face):
    """The surface as stored in (and read back from) the STEP file."""
    ad = GeomAdaptor_Surface(BRep_Tool.Surface_s(face))
    t = ad.GetType()
    d = {"type": SURF_NAMES.get(t, str(t))}
    if t == GeomAbs_Plane:
        d.update(_ax3(ad.Plane().Position()))
    elif t == GeomAbs_Cylinder:
        c = ad.Cylinder()
        d.update(_ax3(c.Position()), radius=c.Radius())
    elif t == GeomAbs_Cone:
        c = ad.Cone()
        d.update(_ax3(c.Position()), ref_radius=c.RefRadius(), semi_angle=c.SemiAngle())
    elif t == GeomAbs_Sphere:
        c = ad.Sphere()
        d.update(_ax3(c.Position()), radius=c.Radius())
    elif t == GeomAbs_Torus:
        c = ad.Torus()
        d.update(_ax3(c.Position()), major_radius=c.MajorRadius(),
                 minor_radius=c.MinorRadius())
    elif t == GeomAbs_BSplineSurface:
        b = ad.BSpline()
        d.update(u_degree=b.UDegree(), v_degree=b.VDegree(),
                 poles=[b.NbUPoles(), b.NbVPoles()],
                 u_knots=[b.UKnot(i) for i in range(1, b.NbUKnots() + 1)],
                 v_knots=[b.VKnot(i) for i in range(1, b.NbVKnots() + 1)],
                 rational=bool(b.IsURational() or b.IsVRational()))
    return d


def bbox(shape):
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib
    b = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, b, False, False)
    lo, hi = b.CornerMin(), b.CornerMax()
    return [round(x, 9) + 0.0 for x in (lo.X(), lo.Y(), lo.Z(), hi.X(), hi.Y(), hi.Z())]


def loop_info(face):
    """[number of oriented edges per wire], number of distinct edges."""
    wires = explore(face, TopAbs_WIRE)
    per_wire = [len(explore(w, TopAbs_EDGE)) for w in wires]
    return per_wire, count_distinct(face, TopAbs_EDGE)


def count_distinct(shape, kind):
    """Number of distinct sub-shapes (a seam edge used twice counts once)."""
    seen = []
    for s in explore(shape, kind):
        if not any(s.IsSame(t) for t in seen):
            seen.append(s)
    return len(seen)


def uv_bounds(face):
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    return [u0, u1, v0, v1]


def check_valid(shape, name):
    if not BRepCheck_Analyzer(shape).IsValid():
        raise RuntimeError(f"{name}: shape is not valid (BRepCheck)")


def write_step(shape, name):
    """Write `shape` as AP214 through OCC's XDE STEP writer.

    STEPCAFControl_Writer drives the same STEPControl_Writer translator but
    takes the PRODUCT name from the document label, so the file's PRODUCT is
    named after the file (the plain writer appends a running counter to
    write.step.product.name).  No colours or layers are attached, so the data
    section is the same as the plain writer's.
    """
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    path = os.path.join(OUT, name)
    doc = TDocStd_Document(TCollection_ExtendedString("XmlOcaf"))
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    label = tool.AddShape(shape, False)
    TDataStd_Name.Set_s(label, TCollection_ExtendedString(name[:-5]))
    w = STEPCAFControl_Writer()
    # The writer must exist before these statics are registered.
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    Interface_Static.SetIVal_s("write.surfacecurve.mode", 1)  # keep pcurves
    if not w.Transfer(doc, STEPControl_AsIs):
        raise RuntimeError(f"{name}: STEP transfer failed")
    if w.Write(path) != IFSelect_RetDone:
        raise RuntimeError(f"{name}: STEP write failed")
    return path


def read_step(path):
    r = STEPControl_Reader()
    if r.ReadFile(path) != IFSelect_RetDone:
        raise RuntimeError(f"{path}: STEP read failed")
    r.TransferRoots()
    return r.OneShape()


def face_record(face):
    per_wire, distinct = loop_info(face)
    from OCP.TopAbs import TopAbs_REVERSED
    return {
        "surface": surf_type(face),
        "surface_occ": surface_params(face),
        "face_reversed": face.Orientation() == TopAbs_REVERSED,
        "bbox": bbox(face),
        "loops": len(per_wire),
        "oriented_edges_per_loop": per_wire,
        "distinct_edges": distinct,
        "uv_bounds_occ": uv_bounds(face),
        "area_occ": area(face),
    }


# --------------------------------------------------------------------------
# test cases; each returns (shape, description dict)


def cylinder_patch():
    r, h = 2.0, 3.0
    surf = Geom_CylindricalSurface(ax3_z(), r)
    face = BRepBuilderAPI_MakeFace(surf, 0.0, PI / 2, 0.0, h, TOL).Face()
    return face, {
        "what": "quarter cylinder, 2 lines + 2 circular arcs",
        "surface_def": {
            "type": "cylinder", "origin": [0, 0, 0], "axis": [0, 0, 1],
            "x_dir": [1, 0, 0], "radius": r,
            "param": "P(u,v) = (r cos u, r sin u, v)",
        },
        "u_range": [0.0, PI / 2], "v_range": [0.0, h],
        "area_exact": r * (PI / 2) * h, "area_formula": "r * pi/2 * h = 3 pi",
    }


def cylinder_band():
    r, h = 1.0, 2.0
    solid = BRepPrimAPI_MakeCylinder(r, h).Shape()
    lat = [f for f in faces_of(solid) if surf_type(f) == "cylinder"]
    assert len(lat) == 1
    return lat[0], {
        "what": "lateral face of BRepPrimAPI_MakeCylinder(1, 2), exported alone; "
                "loop = circle, seam, circle, seam reversed",
        "surface_def": {
            "type": "cylinder", "origin": [0, 0, 0], "axis": [0, 0, 1],
            "x_dir": [1, 0, 0], "radius": r,
            "param": "P(u,v) = (r cos u, r sin u, v)",
        },
        "u_range": [0.0, 2 * PI], "v_range": [0.0, h], "seam": "u = 0 (x = r, y = 0)",
        "area_exact": 2 * PI * r * h, "area_formula": "2 pi r h = 4 pi",
    }


def cone_patch():
    r1, r2, h = 2.0, 1.0, 2.0
    solid = BRepPrimAPI_MakeCone(r1, r2, h, PI).Shape()  # half frustum
    lat = [f for f in faces_of(solid) if surf_type(f) == "cone"]
    assert len(lat) == 1
    slant = math.hypot(r1 - r2, h)
    semi = math.atan2(r2 - r1, h)  # negative: radius shrinks with z
    return lat[0], {
        "what": "conical face of BRepPrimAPI_MakeCone(2, 1, 2, pi) (half frustum), "
                "2 lines + 2 half-circle arcs",
        "surface_def": {
            "type": "cone", "axis_line": "z axis",
            "radius_at_z": "r(z) = 2 - z/2 for 0 <= z <= 2",
            "half": "0 <= theta <= 180 deg, theta measured from +x toward +y (so y >= 0)",
            "as_written": "CONICAL_SURFACE placement origin (0,0,0), axis (0,0,-1), "
                          "ref_direction (1,0,0), radius 2, semi_angle atan(1/2) = "
                          f"{-semi:.12f}; OCC face uv: u in [pi, 2pi], v in [-sqrt 5, 0] "
                          "(v = slant distance along -axis)",
        },
        "theta_range": [0.0, PI], "z_range": [0.0, h], "slant_length": slant,
        "area_exact": 0.5 * PI * (r1 + r2) * slant,
        "area_formula": "pi (r1 + r2) s / 2, s = sqrt(5)  -> 1.5 pi sqrt(5)",
    }


def sphere_band():
    r = 1.5
    lat0, lat1 = -PI / 6, PI / 4
    surf = Geom_SphericalSurface(ax3_z(), r)
    face = BRepBuilderAPI_MakeFace(surf, 0.0, 2 * PI, lat0, lat1, TOL).Face()
    return face, {
        "what": "sphere band -30 deg <= latitude <= 45 deg all round; "
                "loop = circle, seam, circle, seam reversed",
        "surface_def": {
            "type": "sphere", "centre": [0, 0, 0], "axis": [0, 0, 1],
            "x_dir": [1, 0, 0], "radius": r,
            "param": "P(u,v) = r (cos v cos u, cos v sin u, sin v), v = latitude",
        },
        "u_range": [0.0, 2 * PI], "v_range": [lat0, lat1],
        "v_range_deg": [-30.0, 45.0], "seam": "u = 0",
        "area_exact": 2 * PI * r * r * (math.sin(lat1) - math.sin(lat0)),
        "area_formula": "2 pi r^2 (sin 45deg + sin 30deg)",
    }


def torus_patch():
    R, r = 3.0, 1.0
    surf = Geom_ToroidalSurface(ax3_z(), R, r)
    face = BRepBuilderAPI_MakeFace(surf, 0.0, PI / 2, 0.0, PI, TOL).Face()
    return face, {
        "what": "torus patch 0 <= u <= 90 deg, 0 <= v <= 180 deg (outer upper half of tube)",
        "surface_def": {
            "type": "torus", "centre": [0, 0, 0], "axis": [0, 0, 1],
            "x_dir": [1, 0, 0], "major_radius": R, "minor_radius": r,
            "param": "P(u,v) = ((R + r cos v) cos u, (R + r cos v) sin u, r sin v)",
        },
        "u_range": [0.0, PI / 2], "v_range": [0.0, PI],
        "area_exact": r * (PI / 2) * (R * PI + r * (math.sin(PI) - math.sin(0.0))),
        "area_formula": "r (pi/2) (R pi) = 1.5 pi^2",
    }


def nurbs_trimmed4():
    # z = 0.1 (x^2 - y^2) sampled on a 9 x 9 grid over [-2, 2]^2. The
    # Z-array form of GeomAPI_PointsToBSplineSurface gives a B-spline whose
    # parameters are exactly (u, v) = (x, y), so a straight segment in (u, v)
    # is the vertical projection of the x-y segment onto the surface.
    n = 9
    x0, dx = -2.0, 4.0 / (n - 1)
    zs = TColStd_Array2OfReal(1, n, 1, n)
    for i in range(1, n + 1):
        for j in range(1, n + 1):
            x = x0 + dx * (i - 1)
            y = x0 + dx * (j - 1)
            zs.SetValue(i, j, 0.1 * (x * x - y * y))
    api = GeomAPI_PointsToBSplineSurface()
    api.Init(zs, x0, dx, x0, dx, 3, 3, GeomAbs_C2, 1e-6)
    surf = api.Surface()
    quad = [(-1.5, -1.2), (1.4, -1.0), (1.2, 1.5), (-1.0, 1.1)]
    # check the (u, v) = (x, y) claim and the fit
    err = 0.0
    for (x, y) in quad + [(0.3, -0.7), (-1.9, 1.9)]:
        p = surf.Value(x, y)
        err = max(err, abs(p.X() - x), abs(p.Y() - y),
                  abs(p.Z() - 0.1 * (x * x - y * y)))
    assert err < 1e-6, err
    mw = BRepBuilderAPI_MakeWire()
    for k in range(4):
        a, b = quad[k], quad[(k + 1) % 4]
        seg = GC_MakeSegment2d(gp_Pnt2d(*a), gp_Pnt2d(*b)).Value()
        mw.Add(BRepBuilderAPI_MakeEdge(seg, surf).Edge())
    face = BRepBuilderAPI_MakeFace(surf, mw.Wire(), True).Face()
    BRepLib.BuildCurves3d_s(face, 1e-6)
    # reference area by Gauss quadrature on the x-y quadrilateral (bilinear map)
    ref = quad_area_on_graph(quad, lambda x, y: math.sqrt(1 + 0.04 * x * x + 0.04 * y * y))
    return face, {
        "what": "B-spline patch z = 0.1(x^2 - y^2) over [-2,2]^2 trimmed by one "
                "4-edge loop: the x-y quadrilateral projected vertically",
        "surface_def": {
            "type": "bspline", "graph": "z = 0.1 (x^2 - y^2)",
            "param": "P(u,v) = (u, v, 0.1(u^2 - v^2)) over u, v in [-2, 2] "
                     "(bicubic, fitted to a 9x9 grid; exact up to fit_max_error)",
            "u_degree": surf.UDegree(), "v_degree": surf.VDegree(),
            "poles": [surf.NbUPoles(), surf.NbVPoles()],
            "fit_max_error": err,
        },
        "trim_quad_xy": [list(q) for q in quad],
        "area_exact": ref,
        "area_formula": "integral over the x-y quad of sqrt(1 + 0.04 x^2 + 0.04 y^2) "
                        "(numerical, 40x40 Gauss-Legendre on the bilinear map)",
    }


def quad_area_on_graph(quad, g, n=40):
    """Integral of g(x, y) over a convex x-y quadrilateral (Gauss-Legendre)."""
    import numpy as np
    t, w = np.polynomial.legendre.leggauss(n)
    t = 0.5 * (t + 1.0)
    w = 0.5 * w
    (ax, ay), (bx, by), (cx, cy), (dx_, dy) = quad
    tot = 0.0
    for s, ws in zip(t, w):
        for r, wr in zip(t, w):
            x = (1 - s) * (1 - r) * ax + s * (1 - r) * bx + s * r * cx + (1 - s) * r * dx_
            y = (1 - s) * (1 - r) * ay + s * (1 - r) * by + s * r * cy + (1 - s) * r * dy
            xs = (1 - r) * (bx - ax) + r * (cx - dx_)
            ys = (1 - r) * (by - ay) + r * (cy - dy)
            xr = (1 - s) * (dx_ - ax) + s * (cx - bx)
            yr = (1 - s) * (dy - ay) + s * (cy - by)
            tot += ws * wr * abs(xs * yr - xr * ys) * g(x, y)
    return float(tot)


def polygon_face(pts):
    poly = BRepBuilderAPI_MakePolygon()
    for (x, y) in pts:
        poly.Add(gp_Pnt(x, y, 0.0))
    poly.Close()
    return BRepBuilderAPI_MakeFace(poly.Wire(), True).Face()


def shoelace(pts):
    s = 0.0
    for k in range(len(pts)):
        (x0, y0), (x1, y1) = pts[k], pts[(k + 1) % len(pts)]
        s += x0 * y1 - x1 * y0
    return 0.5 * s


def plane_pentagon():
    pts = [(0, 0), (4, 0), (4, 3), (2, 3.2), (0, 3)]
    return polygon_face(pts), {
        "what": "planar convex pentagon, corner (2,3.2) nearly flat (interior angle "
                f"{180 - 2 * math.degrees(math.atan2(0.2, 2)):.2f} deg) -> groups into 4 sides",
        "surface_def": {"type": "plane", "origin": [0, 0, 0], "normal": [0, 0, 1]},
        "corners_xy": [list(p) for p in pts],
        "area_exact": shoelace(pts), "area_formula": "12 + 0.4",
    }


def plane_triangle():
    pts = [(0, 0), (3, 0), (0, 2)]
    return polygon_face(pts), {
        "what": "planar triangle, three-sided face",
        "surface_def": {"type": "plane", "origin": [0, 0, 0], "normal": [0, 0, 1]},
        "corners_xy": [list(p) for p in pts],
        "area_exact": shoelace(pts), "area_formula": "3*2/2",
    }


def plane_nonconvex():
    # square [0,2]^2 whose top side is a circular arc (2,2) -> (1,1.3) -> (0,2)
    p = [gp_Pnt(0, 0, 0), gp_Pnt(2, 0, 0), gp_Pnt(2, 2, 0), gp_Pnt(1, 1.3, 0), gp_Pnt(0, 2, 0)]
    e1 = BRepBuilderAPI_MakeEdge(p[0], p[1]).Edge()
    e2 = BRepBuilderAPI_MakeEdge(p[1], p[2]).Edge()
    arc = GC_MakeArcOfCircle(p[2], p[3], p[4]).Value()
    e3 = BRepBuilderAPI_MakeEdge(arc).Edge()
    e4 = BRepBuilderAPI_MakeEdge(p[4], p[0]).Edge()
    w = BRepBuilderAPI_MakeWire(e1, e2, e3, e4).Wire()
    face = BRepBuilderAPI_MakeFace(w, True).Face()
    # circle through (0,2), (2,2), (1,1.3): centre (1, yc), radius R
    yc = (5 - 1.69) / 1.4
    R = yc - 1.3
    theta = 2 * math.asin(1.0 / R)
    seg = 0.5 * R * R * (theta - math.sin(theta))
    return face, {
        "what": "planar 4-edge face: square [0,2]^2 with the top side replaced by a "
                "concave circular arc through (2,2), (1,1.3), (0,2)",
        "surface_def": {"type": "plane", "origin": [0, 0, 0], "normal": [0, 0, 1]},
        "arc": {"centre": [1.0, yc, 0.0], "radius": R, "through": [[2, 2], [1, 1.3], [0, 2]]},
        "area_exact": 4.0 - seg,
        "area_formula": "4 - circular segment, R = 3.31/1.4 - 1.3, theta = 2 asin(1/R)",
    }


def box_with_hole_face():
    pts = [(0, 0), (4, 0), (4, 3), (0, 3)]
    poly = BRepBuilderAPI_MakePolygon()
    for (x, y) in pts:
        poly.Add(gp_Pnt(x, y, 0.0))
    poly.Close()
    mf = BRepBuilderAPI_MakeFace(poly.Wire(), True)
    rh = 0.75
    circ = gp_Circ(gp_Ax2(gp_Pnt(2, 1.5, 0), gp_Dir(0, 0, 1)), rh)
    hole = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circ).Edge()).Wire()
    hole.Reverse()  # inner loop runs clockwise
    mf.Add(hole)
    face = mf.Face()
    return face, {
        "what": "planar rectangle [0,4]x[0,3] with a circular hole centre (2,1.5) "
                "radius 0.75: two loops -> must be refused",
        "surface_def": {"type": "plane", "origin": [0, 0, 0], "normal": [0, 0, 1]},
        "hole": {"centre": [2, 1.5, 0], "radius": rh},
        "area_exact": 12.0 - PI * rh * rh, "area_formula": "12 - pi 0.75^2",
    }


def plate_with_holes():
    L, W, T = 40.0, 30.0, 5.0
    rh, rf = 3.0, 3.0
    box = BRepPrimAPI_MakeBox(L, W, T).Shape()
    # fillet the vertical edge at x = L, y = W
    mk = BRepFilletAPI_MakeFillet(box)
    target = None
    for e in explore(box, TopAbs_EDGE):
        e = as_edge(e)
        v = [BRep_Tool.Pnt_s(as_vertex(x)) for x in explore(e, TopAbs_VERTEX)]
        if all(abs(p.X() - L) < 1e-9 and abs(p.Y() - W) < 1e-9 for p in v):
            target = e
    assert target is not None
    mk.Add(rf, target)
    mk.Build()
    shape = mk.Shape()
    for (cx, cy) in [(10.0, 15.0), (25.0, 15.0)]:
        cyl = BRepPrimAPI_MakeCylinder(
            gp_Ax2(gp_Pnt(cx, cy, -1.0), gp_Dir(0, 0, 1)), rh, T + 2.0).Shape()
        shape = BRepAlgoAPI_Cut(shape, cyl).Shape()
    vol = L * W * T - 2 * PI * rh * rh * T - (1 - PI / 4) * rf * rf * T
    top = L * W - 2 * PI * rh * rh - (1 - PI / 4) * rf * rf
    side = (2 * (L + W) - 2 * rf + 0.5 * PI * rf) * T
    holes = 2 * 2 * PI * rh * T
    return shape, {
        "what": "plate 40x30x5 with two through holes (radius 3, centres (10,15), (25,15)) "
                "and the vertical edge at (40,30) filleted with radius 3",
        "holes": [{"centre": [10, 15], "radius": rh}, {"centre": [25, 15], "radius": rh}],
        "fillet": {"axis_point": [L - rf, W - rf, 0], "axis": [0, 0, 1], "radius": rf,
                   "z_range": [0, T]},
        "volume_exact": vol,
        "area_exact": 2 * top + side + holes,
        "area_formula": "2*(top) + outer sides + hole walls",
    }


# --------------------------------------------------------------------------
# reparametrized faces: the same shape with different (u, v) parametrizations


def dense(a, b, n, ends=()):
    """n equispaced values in [a, b] plus values crowding towards the ends
    listed in `ends` (where a sampled law is singular)."""
    vals = {a + (b - a) * k / (n - 1) for k in range(n)}
    for e in ends:
        for k in range(1, 9):
            for c in (1.0, 3.0):
                d = c * 10.0 ** -k * (b - a)
                vals.add(a + d if e == a else b - d)
    vals = sorted(vals)
    return [x for k, x in enumerate(vals) if k == 0 or x - vals[k - 1] > 1e-12]


def fit_points(law, n, m, deg_min=3, deg_max=5, tol3d=1e-9):
    """B-spline through the n x m points law(s, t), s = i/(n-1), t = j/(m-1).

    Approx_IsoParametric makes the spline parameter follow the sample index,
    so the surface parameters are (u, v) ~= (s, t) and the spline inherits
    the (non-linear) law as its parametrization."""
    pts = TColgp_Array2OfPnt(1, n, 1, m)
    for i in range(n):
        for j in range(m):
            pts.SetValue(i + 1, j + 1, gp_Pnt(*law(i / (n - 1), j / (m - 1))))
    api = GeomAPI_PointsToBSplineSurface()
    api.Init(pts, Approx_IsoParametric, deg_min, deg_max, GeomAbs_C2, tol3d)
    surf = api.Surface()
    assert tuple(surf.Bounds()) == (0.0, 1.0, 0.0, 1.0), surf.Bounds()
    assert not (surf.IsURational() or surf.IsVRational())
    err = max(surf.Value(i / (n - 1), j / (m - 1)).Distance(pts.Value(i + 1, j + 1))
              for i in range(n) for j in range(m))
    return surf, err


def bspline_info(surf):
    return {"u_degree": surf.UDegree(), "v_degree": surf.VDegree(),
            "poles": [surf.NbUPoles(), surf.NbVPoles()],
            "u_knots": [surf.UKnot(i) for i in range(1, surf.NbUKnots() + 1)],
            "v_knots": [surf.VKnot(i) for i in range(1, surf.NbVKnots() + 1)]}


def speed_range(surf, us, vs):
    """min and max of |dP/du| and |dP/dv| over the grid us x vs."""
    p, du, dv = gp_Pnt(), gp_Vec(), gp_Vec()
    su, sv = [], []
    for u in us:
        for v in vs:
            surf.D1(u, v, p, du, dv)
            su.append(du.Magnitude())
            sv.append(dv.Magnitude())
    return [min(su), max(su)], [min(sv), max(sv)]


def iso_rect_face(surf, u0, u1, v0, v1):
    """Face on `surf` bounded by the iso-curves u = u0, u1 and v = v0, v1.

    Each edge's 3D curve is the surface's own iso-curve (surf.UIso/VIso) and
    its pcurve the straight uv line with the same parameter, so the edges
    lie exactly on the surface."""
    vert = lambda u, v: BRepBuilderAPI_MakeVertex(surf.Value(u, v)).Vertex()
    c00, c10, c11, c01 = vert(u0, v0), vert(u1, v0), vert(u1, v1), vert(u0, v1)
    bld = BRep_Builder()

    def edge(curve, va, vb, a, b, line2d):
        e = BRepBuilderAPI_MakeEdge(curve, va, vb, a, b).Edge()
        bld.UpdateEdge(e, line2d, surf, TopLoc_Location(), TOL)
        return e

    bottom = edge(surf.VIso(v0), c00, c10, u0, u1, Geom2d_Line(gp_Pnt2d(0.0, v0), gp_Dir2d(1, 0)))
    right = edge(surf.UIso(u1), c10, c11, v0, v1, Geom2d_Line(gp_Pnt2d(u1, 0.0), gp_Dir2d(0, 1)))
    top = edge(surf.VIso(v1), c01, c11, u0, u1, Geom2d_Line(gp_Pnt2d(0.0, v1), gp_Dir2d(1, 0)))
    left = edge(surf.UIso(u0), c00, c01, v0, v1, Geom2d_Line(gp_Pnt2d(u0, 0.0), gp_Dir2d(0, 1)))
    wire = BRepBuilderAPI_MakeWire(bottom, right, as_edge(top.Reversed()),
                                   as_edge(left.Reversed())).Wire()
    return BRepBuilderAPI_MakeFace(surf, wire, True).Face()


def cylinder_patch_nurbs():
    r, h = 2.0, 3.0
    base, info = cylinder_patch()
    face = faces_of(BRepBuilderAPI_NurbsConvert(base, True).Shape())
    assert len(face) == 1
    face = face[0]
    assert surf_type(face) == "bspline"
    b = GeomAdaptor_Surface(BRep_Tool.Surface_s(face)).BSpline()
    assert b.IsURational() or b.IsVRational()
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    rerr = zerr = dev = 0.0
    for k in range(4001):
        u = u0 + (u1 - u0) * k / 4000
        for v in (v0, 0.5 * (v0 + v1), v1):
            p = b.Value(u, v)
            rerr = max(rerr, abs(math.hypot(p.X(), p.Y()) - r))
            zerr = max(zerr, abs(p.Z() - v))
        p = b.Value(u, v0)
        dev = max(dev, abs(math.atan2(p.Y(), p.X()) - (u - u0) / (u1 - u0) * PI / 2))
    su, sv = speed_range(b, [u0 + (u1 - u0) * k / 200 for k in range(201)], [v0, v1])
    return face, {
        "what": "cylinder_patch.step's quarter cylinder (r = 2, 0 <= theta <= 90 deg, "
                "0 <= z <= 3) after BRepBuilderAPI_NurbsConvert: same shape, rational "
                "B-spline surface, parameter not proportional to the angle",
        "surface_def": {
            "type": "bspline", "rational": True, "shape": "cylinder r = 2 about z",
            "origin": [0, 0, 0], "axis": [0, 0, 1], "x_dir": [1, 0, 0], "radius": r,
            "param": "u in [0, pi/2]: rational quadratic (one Bezier span, weights "
                     "1, sqrt(1/2), 1); v = z (linear). With w = u/(pi/2): "
                     "theta = atan2(w^2 + sqrt2 w(1-w), (1-w)^2 + sqrt2 w(1-w))",
            **bspline_info(b),
            "u_weights": [b.Weight(i, 1) for i in range(1, b.NbUPoles() + 1)],
            "max_abs_r_minus_2": rerr, "max_abs_z_minus_v": zerr,
            "max_abs_theta_minus_u_rad": dev,
            "max_abs_theta_minus_u_deg": math.degrees(dev),
            "dP_du_range": su, "dP_dv_range": sv,
        },
        "theta_range": [0.0, PI / 2], "z_range": [0.0, h],
        "u_range": list(b.Bounds()[:2]), "v_range": list(b.Bounds()[2:]),
        "area_exact": info["area_exact"], "area_formula": info["area_formula"],
    }


def cylinder_patch_skewed():
    r, h = 2.0, 3.0
    # The laws' singular points (s = 0, t = 0) lie outside the face; inside it
    # |dP/du| and |dP/dv| each vary by a factor of about 3.
    a0d, a1d, pa = -5.0, 120.0, 1.6
    z0, z1, pz = -0.3, 4.0, 0.7
    a0, a1 = math.radians(a0d), math.radians(a1d)
    n, m = 50, 30
    ang = lambda s: a0 + (a1 - a0) * s ** pa
    zed = lambda t: z0 + (z1 - z0) * t ** pz
    surf, perr = fit_points(lambda s, t: (r * math.cos(ang(s)), r * math.sin(ang(s)), zed(t)),
                            n, m)

    def proj(x, y, z):
        pr = GeomAPI_ProjectPointOnSurf(gp_Pnt(x, y, z), surf)
        assert pr.NbPoints() > 0 and pr.LowerDistance() < 1e-7
        return pr.LowerDistanceParameters()

    c = r * math.sqrt(0.5)
    ua, ub = proj(r, 0.0, 0.5 * h)[0], proj(0.0, r, 0.5 * h)[0]
    va, vb = proj(c, c, 0.0)[1], proj(c, c, h)[1]
    face = iso_rect_face(surf, ua, ub, va, vb)

    # shape error: distance from the cylinder (|r - 2|); the parametrization
    # is separable, x, y depend on u only and z on v only (up to ~1e-11)
    us_all, vs_all = dense(0.0, 1.0, 4001, ends=(0.0, 1.0)), dense(0.0, 1.0, 61, ends=(0.0,))
    us_face, vs_face = dense(ua, ub, 4001), dense(va, vb, 61)
    r_all = r_face = lawdev = 0.0
    for us, vs, face_part in ((us_all, vs_all, False), (us_face, vs_face, True)):
        for u in us:
            for v in vs:
                p = surf.Value(u, v)
                e = abs(math.hypot(p.X(), p.Y()) - r)
                if face_part:
                    r_face = max(r_face, e)
                    q = gp_Pnt(r * math.cos(ang(u)), r * math.sin(ang(u)), zed(v))
                    lawdev = max(lawdev, p.Distance(q))
                else:
                    r_all = max(r_all, e)
    # the boundary: theta = 0 / 90 deg on the u edges, z = 0 / 3 on the v edges
    bnd = 0.0
    for v in dense(va, vb, 301):
        for u, th in ((ua, 0.0), (ub, PI / 2)):
            p = surf.Value(u, v)
            bnd = max(bnd, r * abs(math.atan2(p.Y(), p.X()) - th))
    for u in dense(ua, ub, 301):
        for v, zz in ((va, 0.0), (vb, h)):
            bnd = max(bnd, abs(surf.Value(u, v).Z() - zz))
    assert r_all < 1e-7 and bnd < 1e-8, (r_all, bnd)
    # no folds: theta increases with u, z with v, over the whole surface
    th = [math.atan2(surf.Value(u, 0.5).Y(), surf.Value(u, 0.5).X()) for u in us_all]
    zz = [surf.Value(0.5, v).Z() for v in dense(0.0, 1.0, 4001, ends=(0.0,))]
    assert all(b > a for a, b in zip(th, th[1:])) and all(b > a for a, b in zip(zz, zz[1:]))
    su, sv = speed_range(surf, dense(ua, ub, 201), dense(va, vb, 31))
    return face, {
        "what": "cylinder_patch.step's quarter cylinder (r = 2, 0 <= theta <= 90 deg, "
                "0 <= z <= 3) on a non-rational B-spline with a strongly non-uniform "
                "parametrization whose parameter square is larger than the face "
                f"({a0d:g}..{a1d:g} deg, z {z0:g}..{z1:g}): trimmed on all four sides "
                "by iso-curves",
        "surface_def": {
            "type": "bspline", "rational": False, "shape": "cylinder r = 2 about z",
            "origin": [0, 0, 0], "axis": [0, 0, 1], "x_dir": [1, 0, 0], "radius": r,
            "param": "P(u,v) ~= (r cos a(u), r sin a(u), z(v)) over [0,1]^2, "
                     f"a(u) = {a0d:g} deg + {a1d - a0d:g} deg u^{pa:g}, "
                     f"z(v) = {z0:g} + {z1 - z0:g} v^{pz:g}",
            "fit": f"GeomAPI_PointsToBSplineSurface, {n} x {m} points at "
                   "(a(i/(n-1)), z(j/(m-1))), Approx_IsoParametric, degree 3..5, "
                   "C2, Tol3D 1e-9",
            **bspline_info(surf),
            "fit_error_at_points": perr,
            "max_abs_r_minus_2_whole_surface": r_all,
            "max_abs_r_minus_2_face": r_face,
            "max_boundary_error": bnd,
            "max_dist_from_law_point_in_face": lawdev,
            "dP_du_range_in_face": su, "dP_dv_range_in_face": sv,
        },
        "surface_theta_range_deg": [a0d, a1d], "surface_z_range": [z0, z1],
        "theta_range": [0.0, PI / 2], "z_range": [0.0, h],
        "u_range": [ua, ub], "v_range": [va, vb],
        "area_exact": r * (PI / 2) * h, "area_formula": "r * pi/2 * h = 3 pi",
    }


def wing_z(x, y):
    return 0.1 * math.sin(1.3 * x) * math.cos(0.9 * y) + 0.05 * x * y


def wing_area(n=64):
    """Area of the graph of wing_z over [0,2] x [0,1.5] (Gauss-Legendre)."""
    import numpy as np
    t, w = np.polynomial.legendre.leggauss(n)
    x, wx = 1.0 * (t + 1.0), 1.0 * w
    y, wy = 0.75 * (t + 1.0), 0.75 * w
    X, Y = np.meshgrid(x, y, indexing="ij")
    fx = 0.13 * np.cos(1.3 * X) * np.cos(0.9 * Y) + 0.05 * Y
    fy = -0.09 * np.sin(1.3 * X) * np.sin(0.9 * Y) + 0.05 * X
    return float(np.einsum("i,j,ij->", wx, wy, np.sqrt(1.0 + fx * fx + fy * fy)))


WING_NM = (61, 46)


def wing_patch(xlaw, ylaw, xlaw_s, ylaw_s, what, ends_u=(), ends_v=()):
    n, m = WING_NM
    surf, perr = fit_points(lambda s, t: (xlaw(s), ylaw(t), wing_z(xlaw(s), ylaw(t))), n, m)
    face = BRepBuilderAPI_MakeFace(surf, TOL).Face()
    ferr = lawdev = 0.0
    for u in dense(0.0, 1.0, 1201, ends_u):
        for v in dense(0.0, 1.0, 301, ends_v):
            p = surf.Value(u, v)
            ferr = max(ferr, abs(p.Z() - wing_z(p.X(), p.Y())))
            x, y = xlaw(u), ylaw(v)
            lawdev = max(lawdev, p.Distance(gp_Pnt(x, y, wing_z(x, y))))
    bnd = 0.0
    for w in dense(0.0, 1.0, 1001):
        bnd = max(bnd, abs(surf.Value(0.0, w).X()), abs(surf.Value(1.0, w).X() - 2.0),
                  abs(surf.Value(w, 0.0).Y()), abs(surf.Value(w, 1.0).Y() - 1.5))
    assert ferr < 1e-8 and bnd < 1e-8, (ferr, bnd)
    su, sv = speed_range(surf, dense(0.0, 1.0, 201), dense(0.0, 1.0, 151))
    return face, {
        "what": what,
        "surface_def": {
            "type": "bspline", "rational": False,
            "graph": "z = 0.1 sin(1.3 x) cos(0.9 y) + 0.05 x y over [0,2] x [0,1.5]",
            "param": f"P(u,v) ~= (X(u), Y(v), z(X, Y)) over [0,1]^2, X(u) = {xlaw_s}, "
                     f"Y(v) = {ylaw_s}",
            "fit": f"GeomAPI_PointsToBSplineSurface, {n} x {m} points at "
                   "(X(i/(n-1)), Y(j/(m-1))), Approx_IsoParametric, degree 3..5, "
                   "C2, Tol3D 1e-9",
            **bspline_info(surf),
            "fit_error_at_points": perr,
            "fit_max_error": ferr,
            "fit_max_error_def": "max |z - f(x, y)| over a dense (u, v) sample of the surface",
            "max_boundary_error": bnd,
            "max_dist_from_law_point": lawdev,
            "dP_du_range": su, "dP_dv_range": sv,
        },
        "x_range": [0.0, 2.0], "y_range": [0.0, 1.5],
        "u_range": [0.0, 1.0], "v_range": [0.0, 1.0],
        "area_exact": wing_area(),
        "area_formula": "integral over [0,2]x[0,1.5] of sqrt(1 + f_x^2 + f_y^2) "
                        "(numerical, 64x64 Gauss-Legendre)",
    }


def wing_patch_twisted():
    return wing_patch(lambda s: 2.0 * s, lambda t: 1.5 * t, "2 u", "1.5 v",
                      "doubly curved wing-like patch z = 0.1 sin(1.3x) cos(0.9y) + 0.05xy "
                      "over [0,2]x[0,1.5], B-spline fitted on a uniform (x, y) grid; "
                      "untrimmed 4-sided face")


def wing_patch_twisted_reparam():
    return wing_patch(lambda s: 2.0 * s ** 1.5, lambda t: 1.5 * (1.0 - (1.0 - t) ** 1.4),
                      "2 u^1.5", "1.5 (1 - (1 - v)^1.4)",
                      "same shape as wing_patch_twisted.step, B-spline fitted at the "
                      "non-uniform x = 2 s^1.5, y = 1.5(1 - (1-t)^1.4); untrimmed 4-sided "
                      "face; dP/du ~ 0 along x = 0 and dP/dv ~ 0 along y = 1.5",
                      ends_u=(0.0,), ends_v=(1.0,))


CASES = [
    ("cylinder_patch.step", cylinder_patch, ["CYLINDRICAL_SURFACE"]),
    ("cylinder_band.step", cylinder_band, ["CYLINDRICAL_SURFACE"]),
    ("cone_patch.step", cone_patch, ["CONICAL_SURFACE"]),
    ("sphere_band.step", sphere_band, ["SPHERICAL_SURFACE"]),
    ("torus_patch.step", torus_patch, ["TOROIDAL_SURFACE"]),
    ("nurbs_trimmed4.step", nurbs_trimmed4, ["B_SPLINE_SURFACE_WITH_KNOTS"]),
    ("plane_pentagon.step", plane_pentagon, ["PLANE"]),
    ("plane_triangle.step", plane_triangle, ["PLANE"]),
    ("plane_nonconvex.step", plane_nonconvex, ["PLANE", "CIRCLE"]),
    ("box_with_hole_face.step", box_with_hole_face, ["PLANE", "CIRCLE"]),
    ("plate_with_holes.step", plate_with_holes, ["PLANE", "CYLINDRICAL_SURFACE"]),
    ("cylinder_patch_nurbs.step", cylinder_patch_nurbs,
     ["B_SPLINE_SURFACE_WITH_KNOTS", "RATIONAL_B_SPLINE_SURFACE"]),
    ("cylinder_patch_skewed.step", cylinder_patch_skewed, ["B_SPLINE_SURFACE_WITH_KNOTS"]),
    ("wing_patch_twisted.step", wing_patch_twisted, ["B_SPLINE_SURFACE_WITH_KNOTS"]),
    ("wing_patch_twisted_reparam.step", wing_patch_twisted_reparam,
     ["B_SPLINE_SURFACE_WITH_KNOTS"]),
]

# Stricter checks for the reparametrized faces: one face, surface entities
# that must not appear, and the area tolerance.
STRICT = {
    "cylinder_patch_nurbs.step": ["CYLINDRICAL_SURFACE"],
    "cylinder_patch_skewed.step": ["CYLINDRICAL_SURFACE", "RATIONAL_B_SPLINE_SURFACE"],
    "wing_patch_twisted.step": ["PLANE", "RATIONAL_B_SPLINE_SURFACE"],
    "wing_patch_twisted_reparam.step": ["PLANE", "RATIONAL_B_SPLINE_SURFACE"],
}

ENTITIES = [
    "PLANE", "CYLINDRICAL_SURFACE", "CONICAL_SURFACE", "SPHERICAL_SURFACE",
    "TOROIDAL_SURFACE", "B_SPLINE_SURFACE_WITH_KNOTS", "RATIONAL_B_SPLINE_SURFACE",
    "ADVANCED_FACE",
    "EDGE_LOOP", "FACE_BOUND", "FACE_OUTER_BOUND", "ORIENTED_EDGE", "EDGE_CURVE",
    "SURFACE_CURVE", "SEAM_CURVE", "LINE", "CIRCLE", "B_SPLINE_CURVE_WITH_KNOTS",
    "PCURVE", "OPEN_SHELL", "CLOSED_SHELL", "MANIFOLD_SOLID_BREP",
    "SHELL_BASED_SURFACE_MODEL",
]


def count_entities(text):
    import re
    found = {}
    for name in ENTITIES:
        n = len(re.findall(r"[=(,\s]" + name + r"\s*\(", text))
        if n:
            found[name] = n
    return found


def quiet_occ():
    """Keep OCC's transfer statistics off stdout (warnings and failures stay)."""
    try:
        from OCP.Message import Message, Message_Gravity
        for p in Message.DefaultMessenger_s().Printers():
            p.SetTraceLevel(Message_Gravity.Message_Warning)
    except Exception:
        pass


def main():
    os.makedirs(OUT, exist_ok=True)
    quiet_occ()
    result = {
        "generator": {
            "package": "cadquery-ocp " + getattr(OCP, "__version__", "?"),
            "python": sys.version.split()[0],
            "units": "millimetre (SI_UNIT(.MILLI.,.METRE.))",
            "schema": "AP214 (AUTOMOTIVE_DESIGN)",
        },
        "files": {},
    }
    for name, fn, expect in CASES:
        shape, info = fn()
        check_valid(shape, name)
        path = write_step(shape, name)
        back = read_step(path)
        check_valid(back, name + " (read back)")
        text = open(path).read()
        ents = count_entities(text)
        for e in expect:
            assert e in ents, (name, e, ents)
        faces = faces_of(back)
        rec = dict(info)
        rec["face_count"] = len(faces)
        rec["edge_count_distinct"] = count_distinct(back, TopAbs_EDGE)
        rec["vertex_count_distinct"] = count_distinct(back, TopAbs_VERTEX)
        rec["faces"] = [face_record(f) for f in faces]
        rec["area_occ"] = area(back)
        if name in STRICT:
            # adaptive BRepGProp quadrature (Eps): good to ~1e-12 here
            props = GProp_GProps()
            est = BRepGProp.SurfaceProperties_s(back, props, 1e-12)
            rec["area_occ_adaptive"] = props.Mass()
            rec["area_occ_adaptive_eps"] = 1e-12
            rec["area_occ_adaptive_error_estimate"] = est
        if "volume_exact" in rec:
            rec["volume_occ"] = volume(back)
        rec["step_entities"] = ents
        rec["file_bytes"] = os.path.getsize(path)
        result["files"][name] = rec
        rel = abs(rec["area_occ"] - rec["area_exact"]) / rec["area_exact"]
        # the default (fixed-order) BRepGProp quadrature misses by up to ~2e-6
        # on the non-uniformly parametrized B-splines; they are checked to 1e-7
        # with the adaptive one below
        assert rel < (1e-5 if name in STRICT else 1e-6), (name, rec["area_occ"], rec["area_exact"])
        if name in STRICT:
            assert len(faces) == 1 and rec["faces"][0]["surface"] == "bspline", name
            for e in STRICT[name]:
                assert e not in ents, (name, e, ents)
            rel = abs(rec["area_occ_adaptive"] - rec["area_exact"]) / rec["area_exact"]
            assert rel < 1e-7, (name, rec["area_occ_adaptive"], rec["area_exact"])
        loops = [f["oriented_edges_per_loop"] for f in rec["faces"]]
        types = sorted({f["surface"] for f in rec["faces"]})
        print(f"{name:26s} faces={len(faces):2d} loops(edges)={loops if len(faces) == 1 else '...'} "
              f"types={types} area_occ={rec['area_occ']:.9g} area_exact={rec['area_exact']:.9g} "
              f"bytes={rec['file_bytes']}")
    with open(os.path.join(OUT, "faces.json"), "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
