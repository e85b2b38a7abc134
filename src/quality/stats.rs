//! Pieces shared by the planar/surface report and the volume report: the running extremes of
//! the per-cell measures, the first flagged cells, and spacings and growth ratios along grid
//! lines, all over a grid of any dimension N (cells and nodes as [usize; N] indices).

use rayon::prelude::*;

use crate::quality::geom::{growth_ratio, nmax, nmin, norm, sub, V3};
use crate::quality::MAX_FIRST_FOLDED;

/// Cells counted by some test (folded, flat-edge) and the first [`MAX_FIRST_FOLDED`] of them.
pub(super) struct Listed<const N: usize> {
    pub count: usize,
    pub first: Vec<[usize; N]>,
}

impl<const N: usize> Listed<N> {
    pub fn new() -> Self {
        Listed {
            count: 0,
            first: Vec::new(),
        }
    }

    /// Counts `cell`, which comes after those counted so far in index order.
    pub fn push(&mut self, cell: [usize; N]) {
        self.count += 1;
        if self.first.len() < MAX_FIRST_FOLDED {
            self.first.push(cell);
        }
    }

    /// Merges `b`, which covers cells after those of `self` in index order.
    pub fn merge(&mut self, b: Self) {
        self.count += b.count;
        let room = MAX_FIRST_FOLDED - self.first.len();
        self.first.extend(b.first.into_iter().take(room));
    }
}

/// Running extremes and sums of the per-cell measures over a part of the grid, and its folded
/// cells.
pub(super) struct CellStats<const N: usize> {
    pub jmin: f64,
    pub jmax: f64,
    pub smin: f64,
    pub skew_max: f64,
    pub skew_sum: f64,
    pub aspect_max: f64,
    pub folded: Listed<N>,
    /// Cells on a block side collapsed to a point, and the smallest scaled Jacobian over
    /// the others (planar and surface reports).
    pub collapsed: usize,
    pub smin_regular: f64,
}

impl<const N: usize> CellStats<N> {
    pub fn new() -> Self {
        CellStats {
            jmin: f64::INFINITY,
            jmax: f64::NEG_INFINITY,
            smin: f64::INFINITY,
            skew_max: f64::NEG_INFINITY,
            skew_sum: 0.0,
            aspect_max: f64::NEG_INFINITY,
            folded: Listed::new(),
            collapsed: 0,
            smin_regular: f64::INFINITY,
        }
    }

    /// Adds one cell's Jacobian extremes, smallest scaled Jacobian, skewness and aspect ratio.
    pub fn add(&mut self, jmin: f64, jmax: f64, smin: f64, skew: f64, aspect: f64) {
        self.jmin = nmin(self.jmin, jmin);
        self.jmax = nmax(self.jmax, jmax);
        self.smin = nmin(self.smin, smin);
        self.skew_max = nmax(self.skew_max, skew);
        self.skew_sum += skew;
        self.aspect_max = nmax(self.aspect_max, aspect);
    }

    /// Merges `b`, which covers cells after those of `self` in index order.
    pub fn merge(&mut self, b: Self) {
        self.jmin = nmin(self.jmin, b.jmin);
        self.jmax = nmax(self.jmax, b.jmax);
        self.smin = nmin(self.smin, b.smin);
        self.skew_max = nmax(self.skew_max, b.skew_max);
        self.skew_sum += b.skew_sum;
        self.aspect_max = nmax(self.aspect_max, b.aspect_max);
        self.folded.merge(b.folded);
        self.collapsed += b.collapsed;
        self.smin_regular = nmin(self.smin_regular, b.smin_regular);
    }
}

/// Spacings along the grid lines of axis `a` of a grid of `dims` nodes whose node n is
/// `point(n)`: (largest growth ratio of adjacent spacings, inverted to be ≥ 1 (1 without two
/// adjacent spacings); shortest spacing; longest spacing). Segments from a node where
/// `on_pole` holds (a side collapsed to a point) are left out. Line by line, each spacing
/// measured once.
pub(super) fn lines<const N: usize>(
    dims: [usize; N],
    a: usize,
    point: impl Fn([usize; N]) -> V3 + Sync,
    on_pole: impl Fn([usize; N]) -> bool + Sync,
) -> (f64, f64, f64) {
    let len = dims[a];
    let start = (1.0, f64::INFINITY, f64::NEG_INFINITY);
    if len < 2 || dims.contains(&0) {
        return start;
    }
    let merge =
        |u: (f64, f64, f64), v: (f64, f64, f64)| (nmax(u.0, v.0), nmin(u.1, v.1), nmax(u.2, v.2));
    // one line per node with n[a] = 0
    let count = dims.iter().product::<usize>() / len;
    (0..count)
        .into_par_iter()
        .map(|mut q| {
            let mut n: [usize; N] = std::array::from_fn(|c| {
                if c == a {
                    return 0;
                }
                let v = q % dims[c];
                q /= dims[c];
                v
            });
            let mut acc = start;
            let mut here = point(n);
            // the spacing of the previous segment if it is counted
            let mut prev: Option<f64> = None;
            for k in 0..len - 1 {
                let counted = !on_pole(n);
                n[a] = k + 1;
                let next = point(n);
                let h = norm(sub(next, here));
                if let Some(hp) = prev {
                    acc.0 = nmax(acc.0, growth_ratio(hp, h));
                }
                if counted {
                    acc.1 = nmin(acc.1, h);
                    acc.2 = nmax(acc.2, h);
                }
                prev = counted.then_some(h);
                here = next;
            }
            acc
        })
        .reduce(|| start, merge)
}
