//! The algebraic stage: edge functions → parameter grids and control functions.
//!
//! | what | equations | module |
//! |---|---|---|
//! | straight-line transformation (2D), Lagrange transfinite start | [5, 6] [39, 40] | [`transform`] |
//! | bilinear transformation (3D) | [70–72] [90–92] | [`bilinear3d`] |
//! | transfinite start of a volume block | — | [`transfinite3d`] |
//! | Hermite-blended transformation (orthogonality) | [47–49] | [`blend`] |
//! | control functions P11, P12, P22 | [19, 20] | [`control2d`] |
//! | the 18 control functions of a volume | [83, 84] | [`control3d`] |
//! | 180° block edges: edge functions warped like √ of the distance | — | [`flat_edge`] |
//! | Coons patches of volume faces from their edges | — | [`coons`] |
//! | periodic (s, t), start grid and control functions of an O-grid with a floating cut | [5, 6] [19, 20] | [`periodic`] |
pub mod bilinear3d;
pub mod blend;
pub mod control2d;
pub mod control3d;
pub mod coons;
pub mod flat_edge;
pub mod periodic;
pub mod scramble;
pub mod transfinite3d;
pub mod transform;

/// Which control functions drive the grid system.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ControlKind {
    /// From the straight-line algebraic transformation [19]: the paper's method (default).
    #[default]
    Algebraic,
    /// All zero: a Laplace (Winslow) grid, which loses boundary clustering. For comparison.
    Laplace,
}

/// Control functions per node, fixed during the whole elliptic solve: `K` values at each node
/// of a grid of `dims` nodes (i fastest), zero on the boundary. Its two uses are
/// [`control2d::Control2`] (K = 6, eqs. [19, 20]) and [`control3d::Control3`] (K = 18, eqs.
/// [83, 84]).
#[derive(Clone, Debug, PartialEq)]
pub struct Controls<const K: usize, const DIM: usize> {
    dims: [usize; DIM],
    p: Vec<[f64; K]>,
}

impl<const K: usize, const DIM: usize> Controls<K, DIM> {
    /// All control functions zero: the grid system reduces to a Laplace (Winslow) grid.
    pub fn zeros(dims: [usize; DIM]) -> Self {
        Controls {
            dims,
            p: vec![[0.0; K]; dims.iter().product()],
        }
    }

    /// Node counts (ni, nj[, nk]).
    pub fn dims(&self) -> [usize; DIM] {
        self.dims
    }

    /// The control functions at node index n.
    #[inline]
    pub fn at(&self, n: usize) -> &[f64; K] {
        &self.p[n]
    }

    /// True if every value is finite (a degenerate algebraic map gives infinities).
    pub fn all_finite(&self) -> bool {
        self.p.iter().all(|q| q.iter().all(|v| v.is_finite()))
    }
}
