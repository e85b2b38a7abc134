//! Geometric kernels shared by planar and surface grids: node access in R³, cell normals,
//! corner Jacobians and angles, the neighbour-flip test, NaN-propagating min/max.

use crate::grid::boundary::collapsed_edges;
use crate::{Edge, Grid2};

/// A point or vector in R³ (planar grids use z = 0).
pub(crate) type V3 = [f64; 3];

#[inline]
pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
pub(crate) fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// Minimum that returns NaN if either argument is NaN (`f64::min` would hide it).
#[inline]
pub(super) fn nmin(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.min(b)
    }
}

/// Maximum that returns NaN if either argument is NaN.
#[inline]
pub(super) fn nmax(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// Ratio of two spacings inverted to be ≥ 1: 1 if both are zero, ∞ if only one is.
#[inline]
pub(super) fn growth_ratio(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        return f64::NAN;
    }
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    if hi == 0.0 {
        1.0
    } else {
        hi / lo // lo = 0 gives ∞
    }
}

/// Angle in degrees in [0°, 180°] between two vectors (0° if either has zero length).
#[inline]
pub(super) fn angle_deg(a: V3, b: V3) -> f64 {
    norm(cross(a, b)).atan2(dot(a, b)).to_degrees()
}

/// Read-only view of a grid's nodes as points of R³; the one place where planar and surface
/// grids differ is [`Nodes::normal`].
pub(super) struct Nodes<'a> {
    x: &'a [f64],
    y: &'a [f64],
    z: Option<&'a [f64]>,
    pub ni: usize,
    pub nj: usize,
    /// True for a surface grid (D = 3): cell normals from the diagonals, neighbour-flip test.
    pub surface: bool,
    /// Block sides E1..E4 collapsed to a point (poles, [`collapsed_edges`]).
    pub poles: [bool; 4],
}

impl<'a> Nodes<'a> {
    /// View of a planar (D = 2) or surface (D = 3) grid.
    pub fn new<const D: usize>(g: &'a Grid2<D>) -> Self {
        debug_assert!(D == 2 || D == 3);
        let poles = if g.ni() >= 2 && g.nj() >= 2 {
            let edges = Edge::ALL.map(|e| g.edge(e));
            collapsed_edges(edges.each_ref().map(|e| &e[..]))
        } else {
            [false; 4]
        };
        Nodes {
            x: g.coord(0),
            y: g.coord(1),
            z: (D >= 3).then(|| g.coord(2)),
            ni: g.ni(),
            nj: g.nj(),
            surface: D >= 3,
            poles,
        }
    }

    /// The edge of cell (i, j) on a pole side ([`eval_cell`]'s `pole`), if any.
    #[inline]
    pub fn pole_edge(&self, i: usize, j: usize) -> Option<usize> {
        // Cell edges: 0 bottom (E3 side), 1 right (E2), 2 top (E4), 3 left (E1).
        let [e1, e2, e3, e4] = self.poles;
        if e3 && j == 0 {
            Some(0)
        } else if e4 && j + 2 == self.nj {
            Some(2)
        } else if e1 && i == 0 {
            Some(3)
        } else if e2 && i + 2 == self.ni {
            Some(1)
        } else {
            None
        }
    }

    /// Number of cells, 0 for grids smaller than 2 × 2.
    pub fn cells(&self) -> usize {
        if self.ni < 2 || self.nj < 2 {
            0
        } else {
            (self.ni - 1) * (self.nj - 1)
        }
    }

    /// Node (i, j).
    #[inline]
    pub fn p(&self, i: usize, j: usize) -> V3 {
        let k = i + self.ni * j;
        [self.x[k], self.y[k], self.z.map_or(0.0, |z| z[k])]
    }

    /// Nodes of cell (i, j) counter-clockwise in (ξ, η): (i,j), (i+1,j), (i+1,j+1), (i,j+1).
    #[inline]
    pub fn cell(&self, i: usize, j: usize) -> [V3; 4] {
        [
            self.p(i, j),
            self.p(i + 1, j),
            self.p(i + 1, j + 1),
            self.p(i, j + 1),
        ]
    }

    /// Reference normal of a cell: +z for planar grids; for surfaces the normalised cross
    /// product of the diagonals (x₂ − x₀) × (x₃ − x₁), the zero vector if that vanishes.
    #[inline]
    pub fn normal(&self, c: &[V3; 4]) -> V3 {
        if !self.surface {
            return [0.0, 0.0, 1.0];
        }
        let m = cross(sub(c[2], c[0]), sub(c[3], c[1]));
        let l = norm(m);
        if l > 0.0 && l.is_finite() {
            [m[0] / l, m[1] / l, m[2] / l]
        } else if l.is_nan() {
            [f64::NAN; 3]
        } else {
            [0.0; 3]
        }
    }

    /// Surface fold by normal flip: more than half of the edge neighbours of cell (i, j) with a
    /// non-degenerate normal point against its normal `n`. Catches a cell turned over as a whole,
    /// whose corners are all positive relative to its own (also turned) normal.
    pub fn flipped(&self, i: usize, j: usize, n: V3) -> bool {
        let (mut counted, mut against) = (0usize, 0usize);
        let mut look = |ii: usize, jj: usize| {
            let m = self.normal(&self.cell(ii, jj));
            if m != [0.0; 3] {
                counted += 1;
                if dot(n, m) < 0.0 {
                    against += 1;
                }
            }
        };
        if i > 0 {
            look(i - 1, j);
        }
        if i + 2 < self.ni {
            look(i + 1, j);
        }
        if j > 0 {
            look(i, j - 1);
        }
        if j + 2 < self.nj {
            look(i, j + 1);
        }
        2 * against > counted
    }
}

/// The angle θ in [0°, 360°) of the direction (x, y) = (`cos_part`, `sin_part`) (0° for the
/// zero vector): a corner's angle from its in-plane cosine part and its Jacobian.
#[inline]
pub(super) fn corner_angle(sin_part: f64, cos_part: f64) -> f64 {
    let theta = sin_part.atan2(cos_part).to_degrees();
    if theta < 0.0 {
        theta + 360.0
    } else {
        theta
    }
}

/// A value in [0, 4) that increases with [`corner_angle`] (the "diamond angle", one division
/// instead of an arctangent): 1 − x/(|x| + |y|) for y ≥ 0, 3 + x/(|x| + |y|) below; 0 for the
/// zero vector; NaN for a NaN component.
#[inline]
pub(super) fn pseudo_angle(sin_part: f64, cos_part: f64) -> f64 {
    let r = cos_part.abs() + sin_part.abs();
    if r == 0.0 {
        return 0.0;
    }
    let t = cos_part / r;
    // −0.0 counts as y ≥ 0, as atan2(−0.0, x) gives −0° or −180°, i.e. 0° or 180° here
    if sin_part >= 0.0 {
        1.0 - t
    } else if sin_part < 0.0 {
        3.0 + t
    } else {
        f64::NAN
    }
}

/// Raw corner Jacobians ((x_{k+1} − x_k) × (x_{k−1} − x_k)) · n of a cell, k = 0..3.
#[inline]
pub(super) fn corner_jacobians(c: &[V3; 4], n: V3) -> [f64; 4] {
    std::array::from_fn(|k| {
        let a = sub(c[(k + 1) % 4], c[k]);
        let b = sub(c[(k + 3) % 4], c[k]);
        dot(cross(a, b), n)
    })
}

/// Metrics of one cell, Jacobians relative to the orientation sign `s` (±1).
#[derive(Clone, Copy, Debug)]
pub(super) struct CellEval {
    /// Smallest corner Jacobian.
    pub jmin: f64,
    /// Largest corner Jacobian.
    pub jmax: f64,
    /// Smallest scaled corner Jacobian J / (|a| |b|), 0 at a corner with a zero-length edge.
    pub smin: f64,
    /// Equiangular skewness max[(θmax − 90°)/90°, (90° − θmin)/90°].
    pub skew: f64,
    /// Longest / shortest edge (∞ with a zero-length edge).
    pub aspect: f64,
    /// A corner Jacobian ≤ 0 or NaN, other than at a flat corner ([`FLAT`]).
    pub folded: bool,
}

/// A corner whose Jacobian is within this of 0 relative to |a| |b|, with both edges of
/// nonzero length and pointing apart (angle 180° to rounding), is *flat*, not folded: the
/// degenerate but valid quad at a block corner placed inside a straight edge (a three-sided
/// CAD face gridded as one block).
pub(super) const FLAT: f64 = 1e-10;

/// Evaluates a cell with reference normal `n` and orientation sign `s`; `pole` is the cell
/// edge (k: from c[k] to c[k+1]) that lies on a block side collapsed to a point, if any: if
/// it has zero length the cell is evaluated as the triangle it is (three corners, three sides).
///
/// The corner angle is measured in the plane normal to `n`, signed by the corner Jacobian and
/// taken in [0°, 360°): a reflex (non-convex or folded) corner has θ > 180°, so the skewness of
/// such a cell exceeds 1. A zero-length edge gives θ = 0° (skewness 1).
#[inline]
pub(super) fn eval_cell(c: &[V3; 4], n: V3, s: f64, pole: Option<usize>) -> CellEval {
    let e: [V3; 4] = std::array::from_fn(|k| sub(c[(k + 1) % 4], c[k]));
    let l: [f64; 4] = std::array::from_fn(|k| norm(e[k]));
    let (mut jmin, mut jmax, mut smin) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
    // the corners of smallest and largest angle, found by a pseudo-angle (one division)
    // instead of an arctangent per corner: (pseudo-angle, sine part, cosine part)
    let (mut lo, mut hi) = ((f64::INFINITY, 0.0, 0.0), (f64::NEG_INFINITY, 0.0, 0.0));
    let mut nan_angle = false;
    let mut folded = false;
    // A cell edge of zero length on a block side collapsed to a pole: the cell is a
    // triangle; its two corners at the pole are one corner, between the edges to c[q+2]
    // and c[q+3].
    let pole = pole.filter(|&q| l[q] == 0.0);
    for k in 0..4 {
        // the corner's two edges (indices into e and l)
        let (ia, ip) = match pole {
            Some(q) if k == (q + 1) % 4 => continue,
            Some(q) if k == q => ((q + 1) % 4, (q + 3) % 4),
            _ => (k, (k + 3) % 4),
        };
        let (a, p) = (e[ia], e[ip]);
        let b = [-p[0], -p[1], -p[2]];
        let jac = s * dot(cross(a, b), n);
        let ll = l[ia] * l[ip];
        let scaled = if ll == 0.0 {
            0.0
        } else {
            (jac / ll).clamp(-1.0, 1.0)
        };
        // In-plane cosine part: a·b minus the components along n.
        let c_ab = dot(a, b) - dot(a, n) * dot(b, n);
        let flat = ll > 0.0 && jac.abs() <= FLAT * ll && dot(a, b) < 0.0;
        // Written so that a NaN Jacobian counts as folded.
        folded |= jac.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) && !flat;
        let p = pseudo_angle(jac, c_ab);
        nan_angle |= p.is_nan();
        if p < lo.0 {
            lo = (p, jac, c_ab);
        }
        if p > hi.0 {
            hi = (p, jac, c_ab);
        }
        jmin = nmin(jmin, jac);
        jmax = nmax(jmax, jac);
        smin = nmin(smin, scaled);
    }
    let skew = if nan_angle {
        f64::NAN
    } else {
        let (tmin, tmax) = (corner_angle(lo.1, lo.2), corner_angle(hi.1, hi.2));
        nmax((tmax - 90.0) / 90.0, (90.0 - tmin) / 90.0)
    };
    let sides = l.iter().enumerate().filter(|&(k, _)| Some(k) != pole);
    let lmax = sides.clone().fold(0.0, |m: f64, (_, &v)| nmax(m, v));
    let lmin = sides.fold(f64::INFINITY, |m: f64, (_, &v)| nmin(m, v));
    let aspect = if lmin > 0.0 {
        lmax / lmin
    } else if lmin == 0.0 {
        f64::INFINITY
    } else {
        f64::NAN
    };
    CellEval {
        jmin,
        jmax,
        smin,
        skew,
        aspect,
        folded,
    }
}
