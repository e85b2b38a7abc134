//! Normalized arclength edge functions s_E3, s_E4, t_E1, t_E2, eqs. [30]–[38].

use crate::grid::boundary::{collapsed_edges, Boundary2};
use crate::grid::Edge;

/// Edge functions of the algebraic transformation: monotone maps from the computational
/// coordinate of an edge's nodes to [0, 1] (METHOD.md §1). `s_e3[i]`, `s_e4[i]` for i = 0..=N;
/// `t_e1[j]`, `t_e2[j]` for j = 0..=M.
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeFunctions {
    pub s_e3: Vec<f64>,
    pub s_e4: Vec<f64>,
    pub t_e1: Vec<f64>,
    pub t_e2: Vec<f64>,
}

/// Cumulative chord length of a point list: 0 at the first point.
pub fn chord_length<const D: usize>(pts: &[[f64; D]]) -> Vec<f64> {
    let mut s = Vec::with_capacity(pts.len());
    let mut acc = 0.0;
    s.push(0.0);
    for w in pts.windows(2) {
        acc += w[0]
            .iter()
            .zip(&w[1])
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            .sqrt();
        s.push(acc);
    }
    s
}

/// Normalized cumulative chord length of a point list, eqs. [30]–[38]: 0 at the first point,
/// exactly 1 at the last.
pub fn normalized_arclength<const D: usize>(pts: &[[f64; D]]) -> Vec<f64> {
    let mut s = chord_length(pts);
    let acc = s.last().copied().unwrap_or(0.0);
    for v in s.iter_mut() {
        *v /= acc;
    }
    *s.last_mut().unwrap() = 1.0;
    s
}

/// The normalized arclength of each edge E1..E4, eqs. [30]–[38]; an edge collapsed to a point
/// (a pole) takes that of the opposite edge, or the uniform distribution if both are poles:
/// the grid lines then fan into the pole as they leave the opposite edge.
pub fn edge_arclengths<const D: usize>(edges: [&[[f64; D]]; 4]) -> [Vec<f64>; 4] {
    let poles = collapsed_edges(edges);
    std::array::from_fn(|k| {
        let opposite = k ^ 1; // E1 ↔ E2, E3 ↔ E4
        if !poles[k] {
            normalized_arclength(edges[k])
        } else if !poles[opposite] {
            normalized_arclength(edges[opposite])
        } else {
            let n = edges[k].len();
            (0..n).map(|i| i as f64 / (n - 1) as f64).collect()
        }
    })
}

impl EdgeFunctions {
    /// The arclength edge functions of a boundary, eqs. [30]–[38] (a pole takes the opposite
    /// edge's, [`edge_arclengths`]).
    pub fn arclength<const D: usize>(b: &Boundary2<D>) -> Self {
        let [t_e1, t_e2, s_e3, s_e4] = edge_arclengths(Edge::ALL.map(|e| b.edge(e)));
        EdgeFunctions {
            s_e3,
            s_e4,
            t_e1,
            t_e2,
        }
    }

    /// Uniform edge functions (the identity map; gives zero control functions).
    pub fn uniform(ni: usize, nj: usize) -> Self {
        let u = |n: usize| {
            (0..n)
                .map(|k| k as f64 / (n - 1) as f64)
                .collect::<Vec<_>>()
        };
        EdgeFunctions {
            s_e3: u(ni),
            s_e4: u(ni),
            t_e1: u(nj),
            t_e2: u(nj),
        }
    }

    /// Nodes along i.
    pub fn ni(&self) -> usize {
        self.s_e3.len()
    }

    /// Nodes along j.
    pub fn nj(&self) -> usize {
        self.t_e1.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arclength_of_unequal_spacing() {
        let s = normalized_arclength(&[[0.0, 0.0], [1.0, 0.0], [1.0, 3.0]]);
        assert_eq!(s, vec![0.0, 0.25, 1.0]);
    }
}
