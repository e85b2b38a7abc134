//! Inversion of a quadrilateral mesh, Section 4.2 step 5 (METHOD.md §5): for a target point
//! (s, t), find the quad (p, q) of the mesh (s^I, t^I) that contains it, solve the bilinear
//! equations for (α, β) ∈ [0, 1]², and interpolate any nodal field (here u, v) there.
//!
//! Targets come as a structured sweep, so a walk from the previous target's quad is the fast
//! path; a BVH over the quads' boxes ([`ellipgrid_geometry::bvh::BoxTree`]) is the fallback
//! when the walk fails. Points on edges and corners (where round-off may put them a hair
//! outside every quad) are accepted within a tolerance and clamped, never dropped.

use crate::{Error, Result};
use ellipgrid_geometry::bvh::BoxTree;

/// Points with α or β this far outside [0, 1] still count as inside (then clamped).
pub const INSIDE_TOL: f64 = 1e-10;

/// A structured quad mesh in the plane: node (i, j) at `i + ni j`, cells (p, q) for
/// p < ni − 1, q < nj − 1.
pub struct QuadMesh<'a> {
    ni: usize,
    nj: usize,
    s: &'a [f64],
    t: &'a [f64],
    tree: BoxTree,
}

/// Where a point was found: cell (p, q) and bilinear coordinates (α, β) ∈ [0, 1]².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellHit {
    pub p: usize,
    pub q: usize,
    pub alpha: f64,
    pub beta: f64,
}

impl<'a> QuadMesh<'a> {
    /// A mesh over nodal coordinates `s`, `t` (i fastest), with its BVH. Fails on
    /// non-finite coordinates (`place` names the block).
    pub fn new(ni: usize, nj: usize, s: &'a [f64], t: &'a [f64], place: &str) -> Result<Self> {
        assert!(ni >= 2 && nj >= 2 && s.len() == ni * nj && t.len() == ni * nj);
        let mut boxes = Vec::with_capacity((ni - 1) * (nj - 1));
        for q in 0..nj - 1 {
            for p in 0..ni - 1 {
                let c = corners(ni, s, t, p, q);
                let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
                for v in c {
                    for k in 0..2 {
                        lo[k] = lo[k].min(v[k]);
                        hi[k] = hi[k].max(v[k]);
                    }
                }
                boxes.push([lo[0], lo[1], 0.0, hi[0], hi[1], 0.0]);
            }
        }
        let tree = BoxTree::new(&boxes).map_err(|source| Error::Geometry {
            place: place.to_string(),
            source,
        })?;
        Ok(QuadMesh { ni, nj, s, t, tree })
    }

    /// Locates `x` by walking from cell `start` (the previous target's cell).
    pub fn walk(&self, x: [f64; 2], start: (usize, usize)) -> Option<CellHit> {
        let (mut p, mut q) = start;
        let max_steps = 4 + 2 * (self.ni + self.nj);
        for _ in 0..max_steps {
            let (a, b) = bilinear_inverse(&corners(self.ni, self.s, self.t, p, q), x)?;
            let inside_a = (-INSIDE_TOL..=1.0 + INSIDE_TOL).contains(&a);
            let inside_b = (-INSIDE_TOL..=1.0 + INSIDE_TOL).contains(&b);
            if inside_a && inside_b {
                return Some(self.hit(p, q, a, b));
            }
            let (p0, q0) = (p, q);
            if !inside_a {
                if a < 0.0 && p > 0 {
                    p -= 1;
                } else if a > 1.0 && p + 2 < self.ni {
                    p += 1;
                }
            }
            if !inside_b {
                if b < 0.0 && q > 0 {
                    q -= 1;
                } else if b > 1.0 && q + 2 < self.nj {
                    q += 1;
                }
            }
            if (p, q) == (p0, q0) {
                return None; // outside the mesh, or the walk is stuck at its boundary
            }
        }
        None
    }

    /// Locates `x` through the BVH: the candidate quads whose boxes hold it, decided exactly.
    pub fn search(&self, x: [f64; 2], scratch: &mut Vec<usize>) -> Option<CellHit> {
        scratch.clear();
        self.tree.candidates([x[0], x[1], 0.0], scratch);
        let mut best: Option<(f64, CellHit)> = None;
        for &c in scratch.iter() {
            let (p, q) = (c % (self.ni - 1), c / (self.ni - 1));
            if let Some((a, b)) = bilinear_inverse(&corners(self.ni, self.s, self.t, p, q), x) {
                // distance outside [0,1]² in (α, β): 0 inside
                let out = (-a).max(a - 1.0).max(-b).max(b - 1.0).max(0.0);
                if out <= INSIDE_TOL && best.is_none_or(|(o, _)| out < o) {
                    best = Some((out, self.hit(p, q, a, b)));
                }
            }
        }
        best.map(|(_, h)| h)
    }

    /// Locates `x`: walk from `start`, then the BVH.
    pub fn locate(
        &self,
        x: [f64; 2],
        start: (usize, usize),
        scratch: &mut Vec<usize>,
    ) -> Option<CellHit> {
        self.walk(x, start).or_else(|| self.search(x, scratch))
    }

    /// Bilinear interpolation of a nodal field at a hit.
    pub fn interpolate(&self, f: &[f64], h: &CellHit) -> f64 {
        let n = h.p + self.ni * h.q;
        let (a, b) = (h.alpha, h.beta);
        f[n] * (1.0 - a) * (1.0 - b)
            + f[n + 1] * a * (1.0 - b)
            + f[n + self.ni] * (1.0 - a) * b
            + f[n + self.ni + 1] * a * b
    }

    fn hit(&self, p: usize, q: usize, a: f64, b: f64) -> CellHit {
        CellHit {
            p,
            q,
            alpha: a.clamp(0.0, 1.0),
            beta: b.clamp(0.0, 1.0),
        }
    }
}

fn corners(ni: usize, s: &[f64], t: &[f64], p: usize, q: usize) -> [[f64; 2]; 4] {
    let n = p + ni * q;
    [
        [s[n], t[n]],
        [s[n + 1], t[n + 1]],
        [s[n + ni], t[n + ni]],
        [s[n + ni + 1], t[n + ni + 1]],
    ]
}

/// Solves x = c00 (1−α)(1−β) + c10 α(1−β) + c01 (1−α)β + c11 αβ for (α, β) by Newton from the
/// quad's centre (METHOD.md §5 step 5). Returns the converged (α, β), possibly outside
/// [0, 1]² (the caller decides), or `None` if Newton fails (degenerate quad).
pub fn bilinear_inverse(c: &[[f64; 2]; 4], x: [f64; 2]) -> Option<(f64, f64)> {
    let [c00, c10, c01, c11] = *c;
    let e = [c10[0] - c00[0], c10[1] - c00[1]];
    let f = [c01[0] - c00[0], c01[1] - c00[1]];
    let g = [
        c11[0] - c10[0] - c01[0] + c00[0],
        c11[1] - c10[1] - c01[1] + c00[1],
    ];
    let scale = e[0].abs() + e[1].abs() + f[0].abs() + f[1].abs();
    let (mut a, mut b) = (0.5, 0.5);
    for _ in 0..30 {
        let r = [
            c00[0] + e[0] * a + f[0] * b + g[0] * a * b - x[0],
            c00[1] + e[1] * a + f[1] * b + g[1] * a * b - x[1],
        ];
        let ja = [e[0] + g[0] * b, e[1] + g[1] * b];
        let jb = [f[0] + g[0] * a, f[1] + g[1] * a];
        let det = ja[0] * jb[1] - ja[1] * jb[0];
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let da = (r[0] * jb[1] - r[1] * jb[0]) / det;
        let db = (ja[0] * r[1] - ja[1] * r[0]) / det;
        a -= da;
        b -= db;
        if da.abs() + db.abs() < 1e-15 * (1.0 + a.abs() + b.abs())
            || r[0].abs() + r[1].abs() <= 1e-16 * scale
        {
            return Some((a, b));
        }
        if !(a.is_finite() && b.is_finite()) || a.abs() > 1e6 || b.abs() > 1e6 {
            return None;
        }
    }
    Some((a, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rng(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A distorted, fold-free mesh of the unit square.
    fn mesh(n: usize) -> (Vec<f64>, Vec<f64>) {
        let mut s = vec![0.0; n * n];
        let mut t = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                let (u, v) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
                let w = 0.08 * (std::f64::consts::PI * u).sin() * (std::f64::consts::PI * v).sin();
                s[i + n * j] = u + w * (3.0 * v).cos();
                t[i + n * j] = v + w * (2.0 * u).sin();
            }
        }
        (s, t)
    }

    #[test]
    fn bilinear_inverse_recovers_alpha_beta() {
        let c = [[0.0, 0.0], [2.0, 0.1], [0.3, 1.0], [1.9, 1.4]];
        let (a, b) = (0.3, 0.8);
        let x = [
            c[0][0] * (1.0 - a) * (1.0 - b)
                + c[1][0] * a * (1.0 - b)
                + c[2][0] * (1.0 - a) * b
                + c[3][0] * a * b,
            c[0][1] * (1.0 - a) * (1.0 - b)
                + c[1][1] * a * (1.0 - b)
                + c[2][1] * (1.0 - a) * b
                + c[3][1] * a * b,
        ];
        let (ra, rb) = bilinear_inverse(&c, x).unwrap();
        assert!((ra - a).abs() < 1e-14 && (rb - b).abs() < 1e-14);
    }

    #[test]
    fn walk_bvh_and_brute_force_agree_including_edges_and_corners() {
        let n = 21;
        let (s, t) = mesh(n);
        let m = QuadMesh::new(n, n, &s, &t, "test").unwrap();
        let mut r = rng(3);
        let mut pts: Vec<[f64; 2]> = (0..2000).map(|_| [r(), r()]).collect();
        // nodes (corners and edges of quads) and points on mesh edges
        for k in (0..n * n).step_by(7) {
            pts.push([s[k], t[k]]);
        }
        pts.push([0.0, 0.0]);
        pts.push([1.0, 1.0]);
        pts.push([0.5 * (s[3] + s[4]), 0.5 * (t[3] + t[4])]);
        let mut scratch = Vec::new();
        let mut prev = (0, 0);
        for x in pts {
            let brute = (0..(n - 1) * (n - 1)).find_map(|c| {
                let (p, q) = (c % (n - 1), c / (n - 1));
                let (a, b) = bilinear_inverse(&corners(n, &s, &t, p, q), x)?;
                let ok = |v: f64| (-INSIDE_TOL..=1.0 + INSIDE_TOL).contains(&v);
                (ok(a) && ok(b)).then_some((p, q))
            });
            let w = m.walk(x, prev);
            let b = m.search(x, &mut scratch);
            let l = m
                .locate(x, prev, &mut scratch)
                .expect("every point of the square is found");
            assert!(brute.is_some(), "{x:?}");
            for h in [w, b].into_iter().flatten() {
                // a point on a shared edge may belong to either quad: check it interpolates back
                let xs = m.interpolate(&s, &h);
                let xt = m.interpolate(&t, &h);
                assert!(
                    (xs - x[0]).abs() < 1e-12 && (xt - x[1]).abs() < 1e-12,
                    "{x:?} {h:?}"
                );
            }
            assert!(b.is_some(), "BVH missed {x:?}");
            prev = (l.p, l.q);
        }
    }
}
