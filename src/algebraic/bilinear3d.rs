//! The twelve edge functions and the algebraic bilinear transformation C → P of a volume
//! block, eqs. [70]–[72] and [90]–[92] (METHOD.md §6).

use crate::grid::arclength::normalized_arclength;
use crate::grid::faces::Faces;
use crate::{Error, Result};
use rayon::prelude::*;

/// Edge functions from the edges' normalized arclength: `s[e]` on the ξ-edges E1–E4 (i =
/// 0..=N), `t[e]` on the η-edges E5–E8 (j), `u[e]` on the ζ-edges E9–E12 (k).
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeFunctions3 {
    pub s: [Vec<f64>; 4],
    pub t: [Vec<f64>; 4],
    pub u: [Vec<f64>; 4],
}

impl EdgeFunctions3 {
    /// Normalized arclength of the twelve edges of the faces ([30]–[38] in 3D).
    pub fn arclength(f: &Faces) -> Self {
        EdgeFunctions3 {
            s: std::array::from_fn(|e| normalized_arclength(&f.edge(e))),
            t: std::array::from_fn(|e| normalized_arclength(&f.edge(4 + e))),
            u: std::array::from_fn(|e| normalized_arclength(&f.edge(8 + e))),
        }
    }

    /// Node counts (ni, nj, nk).
    pub fn dims(&self) -> [usize; 3] {
        [self.s[0].len(), self.t[0].len(), self.u[0].len()]
    }
}

/// Parameter-space grid (s, t, u) ∈ [0, 1]³ at the nodes of C, i fastest.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamGrid3 {
    dims: [usize; 3],
    pub s: Vec<f64>,
    pub t: Vec<f64>,
    pub u: Vec<f64>,
}

impl ParamGrid3 {
    /// The (s, t, u) grid of `dims` nodes with the given values (i fastest).
    pub fn from_values(dims: [usize; 3], s: Vec<f64>, t: Vec<f64>, u: Vec<f64>) -> Self {
        let n: usize = dims.iter().product();
        assert!(s.len() == n && t.len() == n && u.len() == n);
        ParamGrid3 { dims, s, t, u }
    }

    /// Node counts (ni, nj, nk).
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The parameters (s, t, u) of a grid of `dims` nodes (i fastest).
    pub(crate) fn from_parts(dims: [usize; 3], s: Vec<f64>, t: Vec<f64>, u: Vec<f64>) -> Self {
        let n: usize = dims.iter().product();
        assert!(s.len() == n && t.len() == n && u.len() == n);
        ParamGrid3 { dims, s, t, u }
    }

    /// (s, t, u) at node index p.
    #[inline]
    pub fn at(&self, p: usize) -> [f64; 3] {
        [self.s[p], self.t[p], self.u[p]]
    }
}

/// Solves the three coupled bilinear equations [70]–[72] at one node, given the edge values
/// a = (s_E1..s_E4)(ξ_i), b = (t_E5..t_E8)(η_j), c = (u_E9..u_E12)(ζ_k), by Newton's method
/// from the tensor-product guess. Returns None if Newton does not converge to 1e-15.
pub fn solve_node(a: [f64; 4], b: [f64; 4], c: [f64; 4]) -> Option<[f64; 3]> {
    // f(p, q) = v0 (1−p)(1−q) + v1 p (1−q) + v2 (1−p) q + v3 p q and its partials.
    let bl = |v: [f64; 4], p: f64, q: f64| {
        (
            v[0] * (1.0 - p) * (1.0 - q)
                + v[1] * p * (1.0 - q)
                + v[2] * (1.0 - p) * q
                + v[3] * p * q,
            (v[1] - v[0]) * (1.0 - q) + (v[3] - v[2]) * q,
            (v[2] - v[0]) * (1.0 - p) + (v[3] - v[1]) * p,
        )
    };
    let mean = |v: [f64; 4]| 0.25 * (v[0] + v[1] + v[2] + v[3]);
    let (mut s, mut t, mut u) = (mean(a), mean(b), mean(c));
    for _ in 0..60 {
        // s = A(t, u), t = B(s, u), u = C(s, t)
        let (fa, a_t, a_u) = bl(a, t, u);
        let (fb, b_s, b_u) = bl(b, s, u);
        let (fc, c_s, c_t) = bl(c, s, t);
        let r = [s - fa, t - fb, u - fc];
        if r.iter().all(|v| v.abs() < 1e-15) {
            return Some([s, t, u]);
        }
        // Jacobian [[1, −a_t, −a_u], [−b_s, 1, −b_u], [−c_s, −c_t, 1]] solved by Cramer.
        let m = [[1.0, -a_t, -a_u], [-b_s, 1.0, -b_u], [-c_s, -c_t, 1.0]];
        let d = det3(m);
        if d.abs() <= 1e-300 || d.is_nan() {
            return None;
        }
        let mut dx = [0.0; 3];
        for (col, dv) in dx.iter_mut().enumerate() {
            let mut mc = m;
            for row in 0..3 {
                mc[row][col] = r[row];
            }
            *dv = det3(mc) / d;
        }
        s -= dx[0];
        t -= dx[1];
        u -= dx[2];
        if !(s.is_finite() && t.is_finite() && u.is_finite()) {
            return None;
        }
    }
    let (fa, _, _) = bl(a, t, u);
    let (fb, _, _) = bl(b, s, u);
    let (fc, _, _) = bl(c, s, t);
    ((s - fa).abs() < 1e-13 && (t - fb).abs() < 1e-13 && (u - fc).abs() < 1e-13)
        .then_some([s, t, u])
}

/// Determinant of a 3 × 3 matrix.
#[inline]
pub fn det3(m: [[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// The algebraic bilinear transformation [70]–[72] at every node (rayon over k-planes).
///
/// Every node lies on three bilinear surfaces in P, one per family (ξ = ξ_i: s a bilinear
/// function of (t, u), and so on); (s, t, u) is their intersection. On the faces it reduces to
/// the 2D straight-line transformation of that face's four edges, and on the edges to the edge
/// functions (both exactly: the boundary values are set, not solved).
///
/// # Errors
/// A node where Newton's method fails or leaves [0, 1]³ (edge functions that are not
/// monotone), naming `place` and the node.
pub fn bilinear(ef: &EdgeFunctions3, place: &str) -> Result<ParamGrid3> {
    let dims = ef.dims();
    let [ni, nj, nk] = dims;
    let plane = ni * nj;
    let mut out = vec![[0.0; 3]; plane * nk];
    out.par_chunks_mut(plane)
        .enumerate()
        .try_for_each(|(k, row)| -> Result<()> {
            let c: [f64; 4] = std::array::from_fn(|e| ef.u[e][k]);
            for j in 0..nj {
                let b: [f64; 4] = std::array::from_fn(|e| ef.t[e][j]);
                for i in 0..ni {
                    let a: [f64; 4] = std::array::from_fn(|e| ef.s[e][i]);
                    let eps = 1e-12;
                    let v = solve_node(a, b, c)
                        .filter(|v| v.iter().all(|x| (-eps..=1.0 + eps).contains(x)))
                        .ok_or_else(|| {
                            Error::input(
                                place,
                                format!(
                                    "the bilinear transformation [70–72] has no solution in \
                                     the unit cube at node ({i}, {j}, {k}) (edge \
                                     distributions not monotone?)"
                                ),
                            )
                        })?;
                    row[i + ni * j] = v;
                }
            }
            Ok(())
        })?;
    let mut pg = ParamGrid3 {
        dims,
        s: out.iter().map(|v| v[0]).collect(),
        t: out.iter().map(|v| v[1]).collect(),
        u: out.iter().map(|v| v[2]).collect(),
    };
    // Exact values on the faces: s = 0 on F1, 1 on F2; t on F3/F4; u on F5/F6.
    for p in 0..plane * nk {
        let (i, j, k) = (p % ni, (p / ni) % nj, p / plane);
        if i == 0 || i == ni - 1 {
            pg.s[p] = (i > 0) as u8 as f64;
        }
        if j == 0 || j == nj - 1 {
            pg.t[p] = (j > 0) as u8 as f64;
        }
        if k == 0 || k == nk - 1 {
            pg.u[p] = (k > 0) as u8 as f64;
        }
    }
    Ok(pg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_solution_satisfies_the_three_bilinear_equations() {
        let a = [0.3, 0.45, 0.2, 0.6];
        let b = [0.1, 0.5, 0.35, 0.05];
        let c = [0.7, 0.55, 0.9, 0.8];
        let [s, t, u] = solve_node(a, b, c).unwrap();
        let bl = |v: [f64; 4], p: f64, q: f64| {
            v[0] * (1.0 - p) * (1.0 - q)
                + v[1] * p * (1.0 - q)
                + v[2] * (1.0 - p) * q
                + v[3] * p * q
        };
        assert!((s - bl(a, t, u)).abs() < 1e-15);
        assert!((t - bl(b, s, u)).abs() < 1e-15);
        assert!((u - bl(c, s, t)).abs() < 1e-15);
    }

    #[test]
    fn equal_edge_functions_give_the_tensor_product() {
        let s: Vec<f64> = (0..5).map(|i| (i as f64 / 4.0).powi(2)).collect();
        let t: Vec<f64> = (0..4).map(|j| (j as f64 / 3.0).sqrt()).collect();
        let u: Vec<f64> = (0..6).map(|k| k as f64 / 5.0).collect();
        let ef = EdgeFunctions3 {
            s: std::array::from_fn(|_| s.clone()),
            t: std::array::from_fn(|_| t.clone()),
            u: std::array::from_fn(|_| u.clone()),
        };
        let pg = bilinear(&ef, "b").unwrap();
        let p = 2 + 5 * (1 + 4 * 3);
        let v = pg.at(p);
        assert!((v[0] - s[2]).abs() < 1e-15 && (v[1] - t[1]).abs() < 1e-15);
        assert!((v[2] - u[3]).abs() < 1e-15);
    }
}
