//! Boundary input of a 2D block: the four edge point lists E1..E4 (METHOD.md, notation).
//!
//! A [`Boundary2`] is validated on construction — opposite edges with equal point counts,
//! corners that meet, finite coordinates, no repeated points, no self-intersection — so every
//! later stage may rely on it. It is not a grid: only its boundary nodes are known.

use crate::grid::{Edge, Grid2};
use crate::{Error, Result};

/// Relative tolerance (of the boundary's diameter) within which edge end points must meet.
pub const CORNER_TOLERANCE: f64 = 1e-6;

/// Four edges of a block in R^D. E1 (i = 0) and E2 (i = N) run along j; E3 (j = 0) and
/// E4 (j = M) run along i. Corners are shared: `E1[0] = E3[0]`, `E2[0] = E3[N]`,
/// `E1[M] = E4[0]`, `E2[M] = E4[N]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Boundary2<const D: usize> {
    edges: [Vec<[f64; D]>; 4],
}

/// Relative length (of the boundary's diameter) at or below which a block side counts as
/// collapsed to a point: a pole ([`Boundary2::with_poles`]).
pub const POLE_TOLERANCE: f64 = 1e-12;

/// Which of the edges E1..E4 are collapsed to a point (length ≤ [`POLE_TOLERANCE`] of the
/// diameter of all four).
pub fn collapsed_edges<const D: usize>(edges: [&[[f64; D]]; 4]) -> [bool; 4] {
    let (mut lo, mut hi) = ([f64::INFINITY; D], [f64::NEG_INFINITY; D]);
    for p in edges.iter().flat_map(|e| e.iter()) {
        for c in 0..D {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let diam = (0..D).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
    edges.map(|pts| {
        let len: f64 = pts
            .windows(2)
            .map(|w| {
                (0..D)
                    .map(|c| (w[1][c] - w[0][c]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .sum();
        diam > 0.0 && len <= POLE_TOLERANCE * diam
    })
}

/// Euclidean distance of two points.
pub(crate) fn dist<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(u, v)| (u - v) * (u - v))
        .sum::<f64>()
        .sqrt()
}

impl<const D: usize> Boundary2<D> {
    /// Validates four edges (E1, E2, E3, E4) and joins their corners exactly (the corner
    /// values of E3 and E4 are kept). `place` names the block in error messages.
    pub fn new(edges: [Vec<[f64; D]>; 4], place: &str) -> Result<Self> {
        Self::build(edges, place, false)
    }

    /// As [`Boundary2::new`], but a side may be collapsed to a point, a *pole* (the nose of a
    /// fuselage, the three-sided B-spline patches CAD systems write): its length at most
    /// [`POLE_TOLERANCE`] of the diameter; all its points are then made that point exactly.
    /// Two adjacent sides may not both be poles (the block would have only two sides).
    pub fn with_poles(edges: [Vec<[f64; D]>; 4], place: &str) -> Result<Self> {
        Self::build(edges, place, true)
    }

    fn build(mut edges: [Vec<[f64; D]>; 4], place: &str, poles: bool) -> Result<Self> {
        for e in Edge::ALL {
            let pts = &edges[e.index()];
            let at = |m: String| Error::input(format!("{place}, edge {e}"), m);
            if pts.len() < 3 {
                return Err(at(format!(
                    "{} point(s); an edge needs at least 3",
                    pts.len()
                )));
            }
            if let Some(k) = pts.iter().position(|p| p.iter().any(|v| !v.is_finite())) {
                return Err(at(format!("point {k} is not finite: {:?}", pts[k])));
            }
        }
        let [e1, e2, e3, e4] = &edges;
        if e1.len() != e2.len() {
            return Err(Error::input(
                place,
                format!(
                    "opposite edges E1 and E2 have {} and {} points; they must be equal",
                    e1.len(),
                    e2.len()
                ),
            ));
        }
        if e3.len() != e4.len() {
            return Err(Error::input(
                place,
                format!(
                    "opposite edges E3 and E4 have {} and {} points; they must be equal",
                    e3.len(),
                    e4.len()
                ),
            ));
        }
        let diam = bbox_diameter(edges.iter().flatten());
        if diam <= 0.0 {
            return Err(Error::input(place, "all boundary points coincide"));
        }
        let tol = CORNER_TOLERANCE * diam;
        let (m, n) = (e1.len() - 1, e3.len() - 1);
        let corners = [
            ("E1 start", e1[0], "E3 start", e3[0]),
            ("E2 start", e2[0], "E3 end", e3[n]),
            ("E1 end", e1[m], "E4 start", e4[0]),
            ("E2 end", e2[m], "E4 end", e4[n]),
        ];
        for (na, a, nb, b) in corners {
            let d = dist(&a, &b);
            if d > tol {
                return Err(Error::input(
                    place,
                    format!(
                        "edges do not meet: {na} {a:?} and {nb} {b:?} are {d:.3e} apart \
                         (tolerance {tol:.1e}); check the edge directions (E1, E2 run from \
                         E3 to E4; E3, E4 run from E1 to E2)"
                    ),
                ));
            }
        }
        edges[0][0] = edges[2][0];
        edges[1][0] = edges[2][n];
        edges[0][m] = edges[3][0];
        edges[1][m] = edges[3][n];
        let collapsed = if poles {
            collapsed_edges([&edges[0][..], &edges[1], &edges[2], &edges[3]])
        } else {
            [false; 4]
        };
        if (collapsed[0] || collapsed[1]) && (collapsed[2] || collapsed[3]) {
            return Err(Error::input(
                place,
                "two adjacent edges are collapsed to points: the block has only two sides",
            ));
        }
        for e in Edge::ALL {
            if !collapsed[e.index()] {
                continue;
            }
            // The pole: the corner value of the adjacent E3/E4 (or E1/E2) edges, exactly.
            let p = edges[e.index()][0];
            edges[e.index()].iter_mut().for_each(|q| *q = p);
            match e {
                Edge::E1 => (edges[2][0], edges[3][0]) = (p, p),
                Edge::E2 => (edges[2][n], edges[3][n]) = (p, p),
                Edge::E3 => (edges[0][0], edges[1][0]) = (p, p),
                Edge::E4 => (edges[0][m], edges[1][m]) = (p, p),
            }
        }
        for e in Edge::ALL {
            if collapsed[e.index()] {
                continue;
            }
            let pts = &edges[e.index()];
            let len: f64 = pts.windows(2).map(|w| dist(&w[0], &w[1])).sum();
            if len <= 1e-12 * diam {
                return Err(Error::input(
                    format!("{place}, edge {e}"),
                    "the edge has zero length",
                ));
            }
            if let Some(k) = pts
                .windows(2)
                .position(|w| dist(&w[0], &w[1]) <= 1e-14 * diam)
            {
                return Err(Error::input(
                    format!("{place}, edge {e}"),
                    format!("points {k} and {} coincide", k + 1),
                ));
            }
        }
        let b = Boundary2 { edges };
        if D == 2 {
            b.check_simple(place)?;
        }
        Ok(b)
    }

    /// The boundary nodes of an existing grid.
    pub fn from_grid(g: &Grid2<D>, place: &str) -> Result<Self> {
        Self::new(Edge::ALL.map(|e| g.edge(e)), place)
    }

    /// Nodes along i (N + 1).
    pub fn ni(&self) -> usize {
        self.edges[2].len()
    }

    /// Nodes along j (M + 1).
    pub fn nj(&self) -> usize {
        self.edges[0].len()
    }

    /// The points of edge `e` in increasing index order.
    pub fn edge(&self, e: Edge) -> &[[f64; D]] {
        &self.edges[e.index()]
    }

    /// Diagonal of the bounding box of all boundary points.
    pub fn diameter(&self) -> f64 {
        bbox_diameter(self.edges.iter().flatten())
    }

    /// Writes the boundary nodes into `g` (which must be `ni × nj`).
    pub fn apply_to(&self, g: &mut Grid2<D>) {
        let (ni, nj) = (self.ni(), self.nj());
        assert_eq!((g.ni(), g.nj()), (ni, nj));
        for j in 0..nj {
            g.set(0, j, self.edges[0][j]);
            g.set(ni - 1, j, self.edges[1][j]);
        }
        for i in 0..ni {
            g.set(i, 0, self.edges[2][i]);
            g.set(i, nj - 1, self.edges[3][i]);
        }
    }

    /// The closed boundary polygon E3, E2, E4 reversed, E1 reversed (counter-clockwise for a
    /// right-handed block), without repeating the corners.
    pub fn polygon(&self) -> Vec<[f64; D]> {
        let [e1, e2, e3, e4] = &self.edges;
        let mut p: Vec<[f64; D]> = e3.clone();
        p.extend_from_slice(&e2[1..]);
        p.extend(e4.iter().rev().skip(1));
        p.extend(e1.iter().rev().skip(1).take(e1.len() - 2));
        p
    }

    /// Rejects a planar boundary polygon that crosses itself (names the two edges).
    fn check_simple(&self, place: &str) -> Result<()> {
        // Segment k of the polygon, with the edge it belongs to.
        let mut segs: Vec<([f64; 2], [f64; 2], Edge, usize)> = Vec::new();
        for e in Edge::ALL {
            for (k, w) in self.edges[e.index()].windows(2).enumerate() {
                segs.push(([w[0][0], w[0][1]], [w[1][0], w[1][1]], e, k));
            }
        }
        let bb: Vec<[f64; 4]> = segs
            .iter()
            .map(|(a, b, _, _)| {
                [
                    a[0].min(b[0]),
                    a[0].max(b[0]),
                    a[1].min(b[1]),
                    a[1].max(b[1]),
                ]
            })
            .collect();
        let mut order: Vec<usize> = (0..segs.len()).collect();
        order.sort_by(|&a, &b| bb[a][0].total_cmp(&bb[b][0]));
        for (oi, &a) in order.iter().enumerate() {
            for &b in &order[oi + 1..] {
                if bb[b][0] > bb[a][1] {
                    break;
                }
                if bb[a][2] > bb[b][3] || bb[b][2] > bb[a][3] {
                    continue;
                }
                let (p1, p2, ea, ka) = segs[a];
                let (q1, q2, eb, kb) = segs[b];
                if shares_endpoint(&p1, &p2, &q1, &q2) {
                    continue;
                }
                if segments_cross(p1, p2, q1, q2) {
                    return Err(Error::input(
                        place,
                        format!(
                            "the boundary intersects itself: segment {ka} of edge {ea} crosses \
                             segment {kb} of edge {eb}"
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

fn shares_endpoint(p1: &[f64; 2], p2: &[f64; 2], q1: &[f64; 2], q2: &[f64; 2]) -> bool {
    p1 == q1 || p1 == q2 || p2 == q1 || p2 == q2
}

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// True if the closed segments p1p2 and q1q2 intersect (touching counts).
pub(crate) fn segments_cross(p1: [f64; 2], p2: [f64; 2], q1: [f64; 2], q2: [f64; 2]) -> bool {
    let d1 = orient(q1, q2, p1);
    let d2 = orient(q1, q2, p2);
    let d3 = orient(p1, p2, q1);
    let d4 = orient(p1, p2, q2);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |a: [f64; 2], b: [f64; 2], c: [f64; 2], d: f64| {
        d == 0.0
            && c[0] >= a[0].min(b[0])
            && c[0] <= a[0].max(b[0])
            && c[1] >= a[1].min(b[1])
            && c[1] <= a[1].max(b[1])
    };
    on(q1, q2, p1, d1) || on(q1, q2, p2, d2) || on(p1, p2, q1, d3) || on(p1, p2, q2, d4)
}

fn bbox_diameter<'a, const D: usize>(pts: impl Iterator<Item = &'a [f64; D]>) -> f64 {
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for p in pts {
        for c in 0..D {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    (0..D).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_square(n: usize) -> [Vec<[f64; 2]>; 4] {
        let u: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
        [
            u.iter().map(|&v| [0.0, v]).collect(),
            u.iter().map(|&v| [1.0, v]).collect(),
            u.iter().map(|&v| [v, 0.0]).collect(),
            u.iter().map(|&v| [v, 1.0]).collect(),
        ]
    }

    #[test]
    fn accepts_a_square_and_rejects_bad_edges() {
        assert!(Boundary2::new(unit_square(5), "b").is_ok());
        let mut e = unit_square(5);
        e[1].pop();
        let m = Boundary2::new(e, "blk").unwrap_err().to_string();
        assert!(m.contains("E1 and E2"), "{m}");
        let mut e = unit_square(5);
        e[3].reverse();
        let m = Boundary2::new(e, "blk").unwrap_err().to_string();
        assert!(m.contains("do not meet"), "{m}");
        let mut e = unit_square(5);
        e[2][2][1] = f64::NAN;
        let m = Boundary2::new(e, "blk").unwrap_err().to_string();
        assert!(m.contains("edge E3") && m.contains("not finite"), "{m}");
        let mut e = unit_square(5);
        e[2][2] = [0.5, 1.5]; // E3 pokes through E4
        let m = Boundary2::new(e, "blk").unwrap_err().to_string();
        assert!(m.contains("intersects itself"), "{m}");
        let mut e = unit_square(5);
        e[2][2] = e[2][1];
        let m = Boundary2::new(e, "blk").unwrap_err().to_string();
        assert!(m.contains("coincide"), "{m}");
        let e = unit_square(2);
        assert!(Boundary2::new(e, "blk")
            .unwrap_err()
            .to_string()
            .contains("at least 3"));
    }
}
