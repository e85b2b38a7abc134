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
///
/// From [`COMPUTED_FROM`] nodes on, the algebraic control functions are not stored but
/// computed at each [`Controls::at`] from the (s, t[, u]) grid they come from (kept instead:
/// 16 instead of 48 bytes per node in 2D, 24 instead of 144 in 3D, #16), by the same
/// arithmetic as the stored ones (bit-identical).
#[derive(Clone, Debug)]
pub struct Controls<const K: usize, const DIM: usize> {
    dims: [usize; DIM],
    /// The stored values (empty when computed from `param`).
    p: Vec<[f64; K]>,
    /// The (s, t[, u]) grid the values are computed from (empty vectors when stored).
    param: [Vec<f64>; DIM],
    /// The values at node `n` from `dims` and `param` (zero on the boundary).
    node: NodeFn<K, DIM>,
}

/// The control functions at node `n` of a grid of `dims` nodes from its (s, t[, u]) grid.
type NodeFn<const K: usize, const DIM: usize> =
    fn(&[usize; DIM], &[Vec<f64>; DIM], usize) -> [f64; K];

/// Grids of at least this many nodes compute their algebraic control functions at each use
/// instead of storing them (see [`Controls`]): a few percent of an assembly's time, not
/// worth it where memory does not matter.
pub const COMPUTED_FROM: usize = 1 << 18;

impl<const K: usize, const DIM: usize> PartialEq for Controls<K, DIM> {
    /// Same size and the same values at every node, stored or computed.
    fn eq(&self, other: &Self) -> bool {
        self.dims == other.dims
            && (0..self.len()).all(|n| {
                let (a, b) = (self.at(n), other.at(n));
                a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits())
            })
    }
}

/// No control functions (the node function of stored values is never called).
fn zero_node<const K: usize, const DIM: usize>(
    _: &[usize; DIM],
    _: &[Vec<f64>; DIM],
    _: usize,
) -> [f64; K] {
    [0.0; K]
}

impl<const K: usize, const DIM: usize> Controls<K, DIM> {
    /// All control functions zero: the grid system reduces to a Laplace (Winslow) grid.
    pub fn zeros(dims: [usize; DIM]) -> Self {
        Self::stored(dims, vec![[0.0; K]; dims.iter().product()])
    }

    /// Stored values `p`, one per node.
    pub(crate) fn stored(dims: [usize; DIM], p: Vec<[f64; K]>) -> Self {
        Controls {
            dims,
            p,
            param: std::array::from_fn(|_| Vec::new()),
            node: zero_node::<K, DIM>,
        }
    }

    /// Values computed at each use by `node` from the (s, t[, u]) grid `param`.
    pub(crate) fn computed(
        dims: [usize; DIM],
        param: [Vec<f64>; DIM],
        node: NodeFn<K, DIM>,
    ) -> Self {
        Controls {
            dims,
            p: Vec::new(),
            param,
            node,
        }
    }

    /// Node counts (ni, nj[, nk]).
    pub fn dims(&self) -> [usize; DIM] {
        self.dims
    }

    /// Number of nodes.
    fn len(&self) -> usize {
        self.dims.iter().product()
    }

    /// The control functions at node index n.
    #[inline]
    pub fn at(&self, n: usize) -> [f64; K] {
        if self.p.is_empty() {
            (self.node)(&self.dims, &self.param, n)
        } else {
            self.p[n]
        }
    }

    /// True if the values are computed at each use ([`COMPUTED_FROM`]), not stored.
    pub fn is_computed(&self) -> bool {
        self.p.is_empty() && self.len() > 0
    }

    /// The same values stored (computed once, in parallel): the Newton steps' evaluations and
    /// linearizations then read them instead of computing them each time (half of a 1025²
    /// evaluation's time), for 8 K bytes per node more.
    pub fn stored_copy(&self) -> Self {
        use rayon::prelude::*;
        let mut p = vec![[0.0; K]; self.len()];
        p.par_iter_mut()
            .enumerate()
            .for_each(|(n, v)| *v = self.at(n));
        Self::stored(self.dims, p)
    }

    /// True if every value is finite (a degenerate algebraic map gives infinities).
    pub fn all_finite(&self) -> bool {
        use rayon::prelude::*;
        (0..self.len())
            .into_par_iter()
            .all(|n| self.at(n).iter().all(|v| v.is_finite()))
    }
}
