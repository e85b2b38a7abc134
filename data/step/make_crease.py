"""Writes wing_crease.step: one bare B-spline surface (in a GEOMETRIC_SET, as OpenVSP writes
its components) that is a whole swept wing wrapped round its airfoil with a flat tip cap as
its last spanwise knot span, as OpenVSP's wings are (issue #14), for tests/step_crease.rs.

The surface is degree 1 (u, spanwise) x 3 (v, round the airfoil); u knots 0, 1, 2, 3 (all
simple: a degree 1 direction is C0 at each of them), v two cubic Bezier segments (knots 0, 1,
2 of multiplicities 4, 3, 4: the lower and upper sides, meeting at the leading edge, the
control point (0, 0), as OpenVSP writes piecewise Bezier sections; the polygon's legs there
are vertical, so the section is smooth at the leading edge):
- row 0 (y = 0): the root airfoil, chord 1 from x = 0;
- row 1 (y = 2): the airfoil with chord 0.8 from x = 0.3 (sweep and taper: the skin kinks
  there by a few degrees, not a crease);
- row 2 (y = 3): the airfoil with chord 0.7 from x = 0.45, the last skin row;
- row 3 (y = 3): that airfoil's camber line, traversed from the trailing edge to the leading
  edge and back (the control points of the airfoil's lower and upper sides averaged in
  pairs: the row is symmetric, the curve doubles back on itself).
So the span u in [2, 3] is the flat tip cap in the plane y = 3 (a lens between the airfoil
and its camber line, both cusps at the trailing edge), meeting the skin at ~90 degrees along
the iso-line u = 2 (normalized 2/3): a crease. v = 0 and v = 1 are the same trailing-edge
line (the airfoil is closed there); on the cap both are the trailing-edge point.

The airfoil's control polygon (x along the chord, z up; trailing edge to trailing edge over
the lower side first) is a made-up thin section, 7 points, about 10 % thick. On the cap
the iso-line v = 1/2 is one point (the leading edge): the cap's two halves are lenses
between the lower (upper) side and the camber line with cusps at both ends.

No CAD kernel: the text is written here. Usage: python3 make_crease.py data/step
"""

import os
import sys

AIRFOIL = [
    (1.0, 0.0),
    (0.5, -0.06),
    (0.0, -0.05),
    (0.0, 0.0),
    (0.0, 0.07),
    (0.5, 0.09),
    (1.0, 0.0),
]

# (y, leading-edge x, chord) of the skin rows
SECTIONS = [(0.0, 0.0, 1.0), (2.0, 0.3, 0.8), (3.0, 0.45, 0.7)]


def camber(polygon):
    """The control points of the lower and upper sides averaged in pairs (j, n - 1 - j)."""
    n = len(polygon)
    return [
        tuple(0.5 * (a + b) for a, b in zip(polygon[j], polygon[n - 1 - j])) for j in range(n)
    ]


def fmt(x):
    s = repr(round(float(x), 12))
    return s[:-1] if s.endswith(".0") else s


def main(out):
    rows = []
    for y, x0, c in SECTIONS:
        rows.append([(x0 + c * x, y, c * z) for x, z in AIRFOIL])
    y, x0, c = SECTIONS[-1]
    rows.append([(x0 + c * x, y, c * z) for x, z in camber(AIRFOIL)])
    lines = []
    ids = []
    n = 1
    for row in rows:
        r = []
        for p in row:
            lines.append(f"#{n}=CARTESIAN_POINT('',({','.join(fmt(v) for v in p)}));")
            r.append(f"#{n}")
            n += 1
        ids.append("(" + ",".join(r) + ")")
    nv = len(AIRFOIL)
    v_mult = "4,3,4"
    v_knots = "0.,1.,2."
    nu = len(rows)
    u_mult = ",".join(["2"] + ["1"] * (nu - 2) + ["2"])
    u_knots = ",".join(fmt(k) for k in range(nu))
    surf = n
    lines.append(
        f"#{surf}=B_SPLINE_SURFACE_WITH_KNOTS('',1,3,({','.join(ids)}),.UNSPECIFIED.,.F.,.F.,"
        f".F.,({u_mult}),({v_mult}),({u_knots}),({v_knots}),.UNSPECIFIED.);"
    )
    lines.append(f"#{surf + 1}=GEOMETRIC_SET('',(#{surf}));")
    text = "\n".join(
        [
            "ISO-10303-21;",
            "HEADER;",
            "FILE_DESCRIPTION(('a wing wrapped round its airfoil with a flat tip cap as its "
            "last spanwise knot span (a crease), as OPENVSP writes wings; written by "
            "data/step/make_crease.py for ellipgrid tests'),'2;1');",
            "FILE_NAME('wing_crease.step','2026-11-27T17:30:00',(''),(''),'','','');",
            "FILE_SCHEMA(('CONFIG_CONTROL_DESIGN'));",
            "ENDSEC;",
            "DATA;",
            *lines,
            "ENDSEC;",
            "END-ISO-10303-21;",
            "",
        ]
    )
    path = os.path.join(out, "wing_crease.step")
    with open(path, "w") as f:
        f.write(text)
    print(f"{path}: degrees 1 x 3, {nu} x {nv} control points, tip cap u in [2, 3]")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
