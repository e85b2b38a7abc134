//! Algebraic transformations: the straight-line map C → P, eqs. [5, 6] and [39, 40], and the
//! Lagrange transfinite start grid C → D.

use crate::grid::arclength::EdgeFunctions;
use crate::grid::boundary::Boundary2;
use crate::grid::Grid2;

/// Parameter-space grid (s_ij, t_ij) ∈ P = [0, 1]² at the nodes of C; i fastest.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamGrid {
    ni: usize,
    nj: usize,
    /// s at each node.
    pub s: Vec<f64>,
    /// t at each node.
    pub t: Vec<f64>,
}

impl ParamGrid {
    /// A parameter grid from its arrays (i fastest), e.g. the Hermite blend [47]–[49].
    ///
    /// # Panics
    /// If `s` or `t` does not hold `ni * nj` values.
    pub fn from_parts(ni: usize, nj: usize, s: Vec<f64>, t: Vec<f64>) -> Self {
        assert!(
            s.len() == ni * nj && t.len() == ni * nj,
            "s, t need ni*nj values"
        );
        ParamGrid { ni, nj, s, t }
    }

    /// Nodes along i.
    pub fn ni(&self) -> usize {
        self.ni
    }

    /// Nodes along j.
    pub fn nj(&self) -> usize {
        self.nj
    }

    /// (s, t) at node (i, j).
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> (f64, f64) {
        let p = i + self.ni * j;
        (self.s[p], self.t[p])
    }
}

/// The straight-line algebraic transformation, eqs. [39, 40] in closed form (METHOD.md §1):
/// with a = s_E3, b = s_E4 − s_E3, c = t_E1, d = t_E2 − t_E1,
/// s = (a + b c) / (1 − b d), t = c + d s.
///
/// Every ξ = const line is a straight segment in P, and so is every η = const line.
pub fn straight_line(ef: &EdgeFunctions) -> ParamGrid {
    let (ni, nj) = (ef.ni(), ef.nj());
    let mut s = vec![0.0; ni * nj];
    let mut t = vec![0.0; ni * nj];
    for j in 0..nj {
        let c = ef.t_e1[j];
        let d = ef.t_e2[j] - c;
        for i in 0..ni {
            let a = ef.s_e3[i];
            let b = ef.s_e4[i] - a;
            let sv = (a + b * c) / (1.0 - b * d);
            s[i + ni * j] = sv;
            t[i + ni * j] = c + d * sv;
        }
    }
    set_edge_values(ef, &mut s, &mut t);
    ParamGrid { ni, nj, s, t }
}

/// Writes the boundary values of an algebraic map exactly as the edge functions give them
/// (s = 0 on E1, 1 on E2, s_E3, s_E4 along E3, E4; t likewise), so the edges carry no
/// round-off of the interior formula.
pub(crate) fn set_edge_values(ef: &EdgeFunctions, s: &mut [f64], t: &mut [f64]) {
    let (ni, nj) = (ef.ni(), ef.nj());
    for j in 0..nj {
        s[ni * j] = 0.0;
        s[ni - 1 + ni * j] = 1.0;
        t[ni * j] = ef.t_e1[j];
        t[ni - 1 + ni * j] = ef.t_e2[j];
    }
    for i in 0..ni {
        t[i] = 0.0;
        t[i + ni * (nj - 1)] = 1.0;
        s[i] = ef.s_e3[i];
        s[i + ni * (nj - 1)] = ef.s_e4[i];
    }
}

/// Lagrange transfinite interpolation of the boundary, uniform in (ξ, η): the start grid of
/// the Picard iteration. It may fold; the final grid does not depend on it.
pub fn transfinite<const D: usize>(b: &Boundary2<D>) -> Grid2<D> {
    use crate::grid::Edge::*;
    let (ni, nj) = (b.ni(), b.nj());
    let (e1, e2, e3, e4) = (b.edge(E1), b.edge(E2), b.edge(E3), b.edge(E4));
    let (c00, c10, c01, c11) = (e3[0], e3[ni - 1], e4[0], e4[ni - 1]);
    let mut g = Grid2::<D>::from_fn(ni, nj, |i, j| {
        let u = i as f64 / (ni - 1) as f64;
        let v = j as f64 / (nj - 1) as f64;
        std::array::from_fn(|c| {
            (1.0 - u) * e1[j][c] + u * e2[j][c] + (1.0 - v) * e3[i][c] + v * e4[i][c]
                - ((1.0 - u) * (1.0 - v) * c00[c]
                    + u * (1.0 - v) * c10[c]
                    + (1.0 - u) * v * c01[c]
                    + u * v * c11[c])
        })
    });
    b.apply_to(&mut g);
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_line_lines_are_straight_in_p() {
        let ef = EdgeFunctions {
            s_e3: vec![0.0, 0.1, 0.5, 1.0],
            s_e4: vec![0.0, 0.4, 0.6, 1.0],
            t_e1: vec![0.0, 0.3, 1.0],
            t_e2: vec![0.0, 0.7, 1.0],
        };
        let pg = straight_line(&ef);
        for j in 0..3 {
            for i in 0..4 {
                let (s, t) = pg.at(i, j);
                let s_line = ef.s_e3[i] * (1.0 - t) + ef.s_e4[i] * t;
                let t_line = ef.t_e1[j] * (1.0 - s) + ef.t_e2[j] * s;
                assert!((s - s_line).abs() < 1e-15 && (t - t_line).abs() < 1e-15);
            }
        }
    }
}
