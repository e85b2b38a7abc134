//! Structured grids: node (i, j[, k]) ↔ (ξ_i, η_j[, ζ_k]) with ξ_i = i/N, η_j = j/M, ζ_k = k/L
//! (METHOD.md, notation). Coordinates are stored one array per component, i fastest, then j,
//! then k — the order of a Plot3D record, so a coordinate array is also the unknown vector of a
//! linear solve.

pub mod arclength;
pub mod boundary;
pub mod faces;
pub mod matching;
pub mod topology;

/// Block edges of a 2D block (METHOD.md): E1 = {ξ = 0}, E2 = {ξ = 1}, E3 = {η = 0}, E4 = {η = 1}.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Edge {
    E1,
    E2,
    E3,
    E4,
}

impl Edge {
    /// All four edges in order E1, E2, E3, E4.
    pub const ALL: [Edge; 4] = [Edge::E1, Edge::E2, Edge::E3, Edge::E4];

    /// 0-based position of the edge in [`Edge::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// True for E3 and E4, whose nodes run along i (ξ); false for E1 and E2 (along j).
    pub fn runs_along_i(self) -> bool {
        matches!(self, Edge::E3 | Edge::E4)
    }

    /// Parses "E1".."E4" (case-insensitive).
    pub fn parse(s: &str) -> Option<Edge> {
        match s.trim().to_ascii_uppercase().as_str() {
            "E1" => Some(Edge::E1),
            "E2" => Some(Edge::E2),
            "E3" => Some(Edge::E3),
            "E4" => Some(Edge::E4),
            _ => None,
        }
    }
}

impl std::fmt::Display for Edge {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "E{}", self.index() + 1)
    }
}

/// A structured grid of `ni × nj` nodes in R^D (D = 2: planar domain, D = 3: surface).
///
/// Node (i, j) is stored at `i + ni * j` in every coordinate array.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid2<const D: usize> {
    ni: usize,
    nj: usize,
    coords: [Vec<f64>; D],
}

impl<const D: usize> Grid2<D> {
    /// A grid of `ni × nj` nodes, all at the origin.
    pub fn zeros(ni: usize, nj: usize) -> Self {
        Grid2 {
            ni,
            nj,
            coords: std::array::from_fn(|_| vec![0.0; ni * nj]),
        }
    }

    /// A grid whose node (i, j) is `f(i, j)`.
    pub fn from_fn(ni: usize, nj: usize, mut f: impl FnMut(usize, usize) -> [f64; D]) -> Self {
        let mut g = Self::zeros(ni, nj);
        for j in 0..nj {
            for i in 0..ni {
                g.set(i, j, f(i, j));
            }
        }
        g
    }

    /// A grid from coordinate arrays (one per component, i fastest).
    ///
    /// # Panics
    /// If an array does not hold `ni * nj` values.
    pub fn from_coords(ni: usize, nj: usize, coords: [Vec<f64>; D]) -> Self {
        for c in &coords {
            assert_eq!(c.len(), ni * nj, "coordinate array length must be ni*nj");
        }
        Grid2 { ni, nj, coords }
    }

    /// Nodes along i (N + 1).
    pub fn ni(&self) -> usize {
        self.ni
    }

    /// Nodes along j (M + 1).
    pub fn nj(&self) -> usize {
        self.nj
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.ni * self.nj
    }

    /// True for a grid without nodes.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Linear index of node (i, j).
    #[inline]
    pub fn idx(&self, i: usize, j: usize) -> usize {
        i + self.ni * j
    }

    /// Node (i, j).
    #[inline]
    pub fn point(&self, i: usize, j: usize) -> [f64; D] {
        let p = self.idx(i, j);
        std::array::from_fn(|c| self.coords[c][p])
    }

    /// Sets node (i, j).
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, x: [f64; D]) {
        let p = self.idx(i, j);
        for (c, v) in x.into_iter().enumerate() {
            self.coords[c][p] = v;
        }
    }

    /// Coordinate array of component `c` (0 = x, 1 = y, 2 = z).
    pub fn coord(&self, c: usize) -> &[f64] {
        &self.coords[c]
    }

    /// Mutable coordinate array of component `c`.
    pub fn coord_mut(&mut self, c: usize) -> &mut [f64] {
        &mut self.coords[c]
    }

    /// All coordinate arrays.
    pub fn coords(&self) -> &[Vec<f64>; D] {
        &self.coords
    }

    /// All coordinate arrays, mutable.
    pub fn coords_mut(&mut self) -> &mut [Vec<f64>; D] {
        &mut self.coords
    }

    /// The nodes of an edge in increasing index order (j for E1/E2, i for E3/E4).
    pub fn edge(&self, e: Edge) -> Vec<[f64; D]> {
        match e {
            Edge::E1 => (0..self.nj).map(|j| self.point(0, j)).collect(),
            Edge::E2 => (0..self.nj).map(|j| self.point(self.ni - 1, j)).collect(),
            Edge::E3 => (0..self.ni).map(|i| self.point(i, 0)).collect(),
            Edge::E4 => (0..self.ni).map(|i| self.point(i, self.nj - 1)).collect(),
        }
    }

    /// True if (i, j) lies on the boundary.
    #[inline]
    pub fn is_boundary(&self, i: usize, j: usize) -> bool {
        i == 0 || j == 0 || i + 1 == self.ni || j + 1 == self.nj
    }

    /// Diagonal of the axis-aligned bounding box: the length scale of relative tolerances.
    pub fn diameter(&self) -> f64 {
        bbox_diameter(&self.coords)
    }

    /// True if every coordinate is finite.
    pub fn all_finite(&self) -> bool {
        use rayon::prelude::*;
        let finite = |ch: &[f64]| ch.iter().all(|v| v.is_finite());
        self.coords.iter().all(|c| {
            if crate::solve::multigrid::use_par(c.len()) {
                c.par_chunks(8192).all(finite)
            } else {
                finite(c)
            }
        })
    }
}

/// A structured volume grid of `ni × nj × nk` nodes in R³; node (i, j, k) at `i + ni (j + nj k)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid3 {
    ni: usize,
    nj: usize,
    nk: usize,
    coords: [Vec<f64>; 3],
}

impl Grid3 {
    /// A grid of `ni × nj × nk` nodes, all at the origin.
    pub fn zeros(ni: usize, nj: usize, nk: usize) -> Self {
        let n = ni * nj * nk;
        Grid3 {
            ni,
            nj,
            nk,
            coords: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
        }
    }

    /// A grid whose node (i, j, k) is `f(i, j, k)`.
    pub fn from_fn(
        ni: usize,
        nj: usize,
        nk: usize,
        mut f: impl FnMut(usize, usize, usize) -> [f64; 3],
    ) -> Self {
        let mut g = Self::zeros(ni, nj, nk);
        for k in 0..nk {
            for j in 0..nj {
                for i in 0..ni {
                    g.set(i, j, k, f(i, j, k));
                }
            }
        }
        g
    }

    /// The rectilinear (tensor-product) grid with node (i, j, k) at (xs[i], ys[j], zs[k]).
    pub fn rectilinear(xs: &[f64], ys: &[f64], zs: &[f64]) -> Self {
        Self::from_fn(xs.len(), ys.len(), zs.len(), |i, j, k| {
            [xs[i], ys[j], zs[k]]
        })
    }

    /// A grid from coordinate arrays (i fastest, then j, then k).
    ///
    /// # Panics
    /// If an array does not hold `ni * nj * nk` values.
    pub fn from_coords(ni: usize, nj: usize, nk: usize, coords: [Vec<f64>; 3]) -> Self {
        for c in &coords {
            assert_eq!(
                c.len(),
                ni * nj * nk,
                "coordinate array length must be ni*nj*nk"
            );
        }
        Grid3 { ni, nj, nk, coords }
    }

    /// Node counts (ni, nj, nk).
    pub fn dims(&self) -> [usize; 3] {
        [self.ni, self.nj, self.nk]
    }

    /// Linear index of node (i, j, k).
    #[inline]
    pub fn idx(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.ni * (j + self.nj * k)
    }

    /// Node (i, j, k).
    #[inline]
    pub fn point(&self, i: usize, j: usize, k: usize) -> [f64; 3] {
        let p = self.idx(i, j, k);
        [self.coords[0][p], self.coords[1][p], self.coords[2][p]]
    }

    /// Sets node (i, j, k).
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, k: usize, x: [f64; 3]) {
        let p = self.idx(i, j, k);
        for (c, v) in x.into_iter().enumerate() {
            self.coords[c][p] = v;
        }
    }

    /// Coordinate array of component `c`.
    pub fn coord(&self, c: usize) -> &[f64] {
        &self.coords[c]
    }

    /// All coordinate arrays.
    pub fn coords(&self) -> &[Vec<f64>; 3] {
        &self.coords
    }

    /// All coordinate arrays, mutable.
    pub fn coords_mut(&mut self) -> &mut [Vec<f64>; 3] {
        &mut self.coords
    }

    /// Diagonal of the axis-aligned bounding box: the length scale of relative tolerances.
    pub fn diameter(&self) -> f64 {
        bbox_diameter(&self.coords)
    }
}

/// The diagonal of the axis-aligned bounding box of nodes given by coordinate arrays (0 for
/// none).
pub fn bbox_diameter(coords: &[Vec<f64>]) -> f64 {
    coords
        .iter()
        .map(|c| {
            let (lo, hi) = c
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                    (lo.min(v), hi.max(v))
                });
            if hi >= lo {
                (hi - lo) * (hi - lo)
            } else {
                0.0
            }
        })
        .sum::<f64>()
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn index_order_is_i_fastest() {
        let g = Grid2::<2>::from_fn(3, 2, |i, j| [i as f64, j as f64]);
        assert_eq!(g.coord(0), &[0.0, 1.0, 2.0, 0.0, 1.0, 2.0]);
        assert_eq!(g.coord(1), &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
        assert_eq!(g.edge(Edge::E2), vec![[2.0, 0.0], [2.0, 1.0]]);
        assert_eq!(g.edge(Edge::E4)[1], [1.0, 1.0]);
        assert!((g.diameter() - 5f64.sqrt()).abs() < 1e-15);
    }
}
