//! Control functions P11, P12, P22 of the Poisson system, eqs. [19, 20].

use crate::algebraic::transform::{straight_line, ParamGrid};
use crate::algebraic::{ControlKind, Controls, COMPUTED_FROM};
use crate::grid::arclength::EdgeFunctions;
use crate::grid::boundary::Boundary2;
use rayon::prelude::*;

/// The six control functions per node, fixed during the whole elliptic solve:
/// `p[n] = [P¹11, P²11, P¹12, P²12, P¹22, P²22]` at node n (i fastest); zero on the boundary.
pub type Control2 = Controls<6, 2>;

impl Control2 {
    /// Control functions at interior nodes, eqs. [19, 20]:
    /// P_ij = −T⁻¹ (s_{ξiξj}, t_{ξiξj})ᵀ with T = ∂(s, t)/∂(ξ, η).
    ///
    /// Central differences of the algebraic (s, t) grid in index space (unit spacing; the
    /// grid system is homogeneous in the spacing, so the factors 1/N, 1/M cancel). The mixed
    /// derivative uses the same 4-corner formula as the Picard operator, so straight-line
    /// grids are exact discrete solutions (METHOD.md §8).
    pub fn from_algebraic(pg: &ParamGrid) -> Self {
        let (ni, nj) = (pg.ni(), pg.nj());
        if ni * nj >= COMPUTED_FROM {
            return Controls::computed([ni, nj], [pg.s.clone(), pg.t.clone()], node);
        }
        let mut p = vec![[0.0; 6]; ni * nj];
        let (s, t) = (&pg.s, &pg.t);
        // rows in parallel (1M nodes: 45 → ~20 ms on 2 cores)
        p.par_chunks_mut(ni).enumerate().for_each(|(j, row)| {
            if j == 0 || j + 1 >= nj {
                return;
            }
            for (i, out) in row.iter_mut().enumerate().take(ni - 1).skip(1) {
                *out = interior(s, t, i + ni * j, ni);
            }
        });
        Controls::stored([ni, nj], p)
    }

    /// Nodes along i.
    pub fn ni(&self) -> usize {
        self.dims[0]
    }

    /// Nodes along j.
    pub fn nj(&self) -> usize {
        self.dims[1]
    }
}

/// The control functions at the interior node `n` of the (s, t) grid with `ni` nodes along
/// i (see [`Control2::from_algebraic`]).
#[inline]
fn interior(s: &[f64], t: &[f64], n: usize, ni: usize) -> [f64; 6] {
    let (e, w, nn, ss) = (n + 1, n - 1, n + ni, n - ni);
    let d = |f: &[f64]| {
        let fx = 0.5 * (f[e] - f[w]);
        let fy = 0.5 * (f[nn] - f[ss]);
        let fxx = f[e] - 2.0 * f[n] + f[w];
        let fyy = f[nn] - 2.0 * f[n] + f[ss];
        let fxy = 0.25 * (f[nn + 1] - f[nn - 1] - f[ss + 1] + f[ss - 1]);
        (fx, fy, fxx, fxy, fyy)
    };
    let (sx, sy, sxx, sxy, syy) = d(s);
    let (tx, ty, txx, txy, tyy) = d(t);
    let det = sx * ty - sy * tx;
    // T⁻¹ = (1/det) [ty −sy; −tx sx]
    let solve = |a: f64, b: f64| [-(ty * a - sy * b) / det, -(-tx * a + sx * b) / det];
    let p11 = solve(sxx, txx);
    let p12 = solve(sxy, txy);
    let p22 = solve(syy, tyy);
    [p11[0], p11[1], p12[0], p12[1], p22[0], p22[1]]
}

/// The control functions at node `n` of a grid of `dims` nodes from its (s, t) grid `st`:
/// [`interior`], zero on the boundary.
fn node(dims: &[usize; 2], st: &[Vec<f64>; 2], n: usize) -> [f64; 6] {
    let [ni, nj] = *dims;
    let (i, j) = (n % ni, n / ni);
    if i == 0 || j == 0 || i + 1 >= ni || j + 1 >= nj {
        return [0.0; 6];
    }
    interior(&st[0], &st[1], n, ni)
}

/// The control functions of a boundary for the chosen kind.
pub fn control_for<const D: usize>(b: &Boundary2<D>, kind: ControlKind) -> Control2 {
    match kind {
        ControlKind::Algebraic => {
            Control2::from_algebraic(&straight_line(&EdgeFunctions::arclength(b)))
        }
        ControlKind::Laplace => Control2::zeros([b.ni(), b.nj()]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebraic::transform::straight_line;
    use crate::grid::arclength::EdgeFunctions;

    /// The control functions computed at each use (large grids, #16) are those stored, bit
    /// for bit, zero on the boundary; grids from `COMPUTED_FROM` nodes on compute them.
    #[test]
    fn computed_controls_equal_stored_ones() {
        let dist = |n: usize, p: f64| -> Vec<f64> {
            (0..n)
                .map(|k| (k as f64 / (n - 1) as f64).powf(p))
                .collect()
        };
        let (ni, nj) = (11, 9);
        let ef = EdgeFunctions {
            s_e3: dist(ni, 1.7),
            s_e4: dist(ni, 0.8),
            t_e1: dist(nj, 1.3),
            t_e2: dist(nj, 2.1),
        };
        let pg = straight_line(&ef);
        let stored = Control2::from_algebraic(&pg);
        assert!(!stored.p.is_empty());
        let computed = Controls::computed([ni, nj], [pg.s.clone(), pg.t.clone()], node);
        assert!(computed.p.is_empty());
        assert_eq!(computed, stored);
        assert!(computed.is_computed() && !stored.is_computed());
        // stored once for Newton steps (poisson2d's linearize): the same values, bit for bit
        let copy = computed.stored_copy();
        assert!(!copy.is_computed());
        assert_eq!(copy, computed);
        assert!(computed.all_finite());
        assert!(stored.at(3 + ni * 4).iter().all(|v| *v != 0.0));
        assert_eq!(computed.at(ni * 4), [0.0; 6], "zero on the boundary");
        let big = EdgeFunctions {
            s_e3: dist(513, 1.7),
            s_e4: dist(513, 0.8),
            t_e1: dist(512, 1.3),
            t_e2: dist(512, 2.1),
        };
        const { assert!(513 * 512 >= COMPUTED_FROM) };
        assert!(Control2::from_algebraic(&straight_line(&big)).p.is_empty());
    }

    #[test]
    fn thomas_middlecoff_special_case() {
        // Equal opposite distributions, eqs. [25]–[28]: P¹11 = −s_ξξ/s_ξ, P²22 = −t_ηη/t_η,
        // all other control functions zero.
        let s: Vec<f64> = (0..6).map(|k| (k as f64 / 5.0).powi(2)).collect();
        let t: Vec<f64> = (0..5).map(|k| (k as f64 / 4.0).sqrt()).collect();
        let ef = EdgeFunctions {
            s_e3: s.clone(),
            s_e4: s.clone(),
            t_e1: t.clone(),
            t_e2: t.clone(),
        };
        let c = Control2::from_algebraic(&straight_line(&ef));
        let (i, j) = (2, 2);
        let q = c.at(i + 6 * j);
        let sxx = s[i + 1] - 2.0 * s[i] + s[i - 1];
        let sx = 0.5 * (s[i + 1] - s[i - 1]);
        let tyy = t[j + 1] - 2.0 * t[j] + t[j - 1];
        let ty = 0.5 * (t[j + 1] - t[j - 1]);
        assert!((q[0] + sxx / sx).abs() < 1e-14);
        assert!((q[5] + tyy / ty).abs() < 1e-14);
        for v in &q[1..5] {
            assert!(v.abs() < 1e-14);
        }
    }
}
