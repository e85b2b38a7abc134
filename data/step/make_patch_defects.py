"""Writes patch_defects.step: two bare B-spline surfaces (in a GEOMETRIC_SET, as OpenVSP
writes its components) with the boundary defects of OpenVSP's supersonic model that fold a
one-block grid (issue #14), for tests/step_patch_defects.rs.

Face 1, a fold-back: a planar quarter ring in the plane x = 0, degrees 4 (u, radial) x 3 (v,
round the quarter), one Bezier patch. Row k of the control net is the cubic quarter-circle
polygon of radius R[k] about (y, z) = (0, 0), with the arc factor KAPPA[k]:
(R, 0), (R, kR), (kR, R), (0, R). The radii run 3.6, 3.5125, 3.425, 3.1625, 3.25: the
quartic r(u) falls below its end value 3.25 (to 3.2338 at u = 0.903) and comes back, so the
patch covers the strip of radii 3.2338 to 3.25 twice, once each way, and its radial sides
overshoot their end corners, as OpenVSP's end caps do. Row 3's arc factor differs from the
others' (0.5538 against 0.5523), as in the model: the iso-line u = 2^(-1/3) = 0.7937 at which
the sides come back to their end corners lies within 4e-4 of the diameter of the side u = 1,
not on it.

Face 2, kinks: a flat (almost) bilinear wing planform, degrees 1 x 1, u across the chord (2
rows), v along the span with simple knots 0, 1, 2, 3 (C0 at each), the leading edge cranked
twice (the supersonic model's wing, face 33, scaled by 1/100 about its root leading edge):
at v = 2 (normalized 2/3) the leading edge turns by 25 degrees, at v = 1 by 4.

No CAD kernel: the text is written here. Usage: python3 make_patch_defects.py data/step
"""

import os
import sys

R = [3.6, 3.5125, 3.425, 3.1625, 3.25]
KAPPA = [0.55246, 0.55246, 0.55246, 0.55374, 0.55246]

WING = [
    [
        (50.0, 0.0, 2.2),
        (100.331961732356, 5.0, 0.925963245057104),
        (157.024817180472, 15.0, -0.0612828312105451),
        (210.649036861027, 52.002684, -1.86645738736529),
    ],
    [
        (209.94876603757, 0.0, -1.84873351292967),
        (211.280190295346, 5.0, -2.46381237207514),
        (213.97687980257, 15.0, -2.39849550630725),
        (223.930965395189, 52.002684, -2.87678728566898),
    ],
]


def fmt(x):
    s = repr(round(float(x), 12))
    return s[:-1] if s.endswith(".0") else s


class Writer:
    def __init__(self):
        self.lines = []
        self.n = 1

    def add(self, text):
        self.lines.append(f"#{self.n}={text};")
        self.n += 1
        return self.n - 1

    def surface(self, rows, du, dv, u, v):
        """rows[i][j]: control point i along u, j along v; u and v (multiplicities, knots)."""
        ids = []
        for row in rows:
            r = []
            for p in row:
                coords = ",".join(fmt(c) for c in p)
                k = self.add("CARTESIAN_POINT(''," + f"({coords}))")
                r.append(f"#{k}")
            ids.append("(" + ",".join(r) + ")")
        mult = lambda k: ",".join(str(m) for m in k[0])
        knots = lambda k: ",".join(fmt(t) for t in k[1])
        return self.add(
            f"B_SPLINE_SURFACE_WITH_KNOTS('',{du},{dv},({','.join(ids)}),.UNSPECIFIED.,.F.,.F.,"
            f".F.,({mult(u)}),({mult(v)}),({knots(u)}),({knots(v)}),.UNSPECIFIED.)"
        )


def main(out):
    w = Writer()
    ring = [[(0.0, r, 0.0), (0.0, r, k * r), (0.0, k * r, r), (0.0, 0.0, r)] for r, k in zip(R, KAPPA)]
    s1 = w.surface(ring, 4, 3, ([5, 5], [0, 1]), ([4, 4], [0, 1]))
    s = 0.01
    x0 = WING[0][0]
    wing = [[tuple(s * (p[c] - x0[c]) for c in range(3)) for p in row] for row in WING]
    s2 = w.surface(wing, 1, 1, ([2, 2], [0, 1]), ([2, 1, 1, 2], [0, 1, 2, 3]))
    w.add(f"GEOMETRIC_SET('',(#{s1},#{s2}))")
    text = "\n".join(
        [
            "ISO-10303-21;",
            "HEADER;",
            "FILE_DESCRIPTION(('a quarter ring folding back over itself and a cranked wing "
            "planform, as OPENVSP writes them; written by data/step/make_patch_defects.py for "
            "ellipgrid tests'),'2;1');",
            "FILE_NAME('patch_defects.step','2026-11-27T21:30:00',(''),(''),'','','');",
            "FILE_SCHEMA(('CONFIG_CONTROL_DESIGN'));",
            "ENDSEC;",
            "DATA;",
            *w.lines,
            "ENDSEC;",
            "END-ISO-10303-21;",
            "",
        ]
    )
    path = os.path.join(out, "patch_defects.step")
    with open(path, "w") as f:
        f.write(text)
    print(f"{path}: a folded-back quarter ring (4 x 3) and a cranked wing (1 x 1)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
