//! The grid hierarchy: sizes and buffers (the *structural* setup, fixed for a grid size) and
//! their values (the *numeric* setup, refreshed for every new operator of the same size).
//!
//! Coarsening stops when a grid has at most `coarse_enough` unknowns, when either direction
//! has fewer than two unknowns (it could not be halved), or after `max_levels` levels.

use crate::solve::multigrid::coarse::BandLu;
use crate::solve::multigrid::interp::{build_transfer, restriction};
use crate::solve::multigrid::rap::galerkin;
use crate::solve::multigrid::relax::{factor_y, Fac, YLineOp};
use crate::solve::multigrid::use_par;
use crate::solve::multigrid::xline::factor_x;
use crate::solve::multigrid::yline;
use crate::solve::multigrid::{MgParams, Restriction, Smoother};
use crate::solve::stencil9::Stencil9;
use crate::solve::{par_copy, zeroed, SolveError};
use rayon::prelude::*;

/// One grid of the hierarchy.
#[derive(Clone, Debug, Default)]
pub(super) struct Level {
    pub nx: usize,
    pub ny: usize,
    /// The operator (level 0: a clipped copy of the caller's, or the caller's own rows taken
    /// over by `adopt`; empty after `give_back`).
    pub a: Vec<[f64; 9]>,
    /// x-line factors and y-line operator of the smoother (see `relax.rs`; empty if the
    /// smoother does not use them, and on the coarsest level), or with lean y-lines their
    /// factors `ycp` instead of `yop` (see `yline.rs`).
    pub xop: Vec<[Fac; 2]>,
    pub yop: YLineOp,
    pub ycp: Vec<f64>,
    /// Prolongation and restriction stars to the next coarser level (one per coarse point;
    /// empty on the coarsest level; `r` also empty with `R = Pᵀ`, see
    /// `interp::restriction`).
    pub p: Vec<[f64; 9]>,
    pub r: Vec<[f64; 9]>,
}

impl Level {
    pub(super) fn n(&self) -> usize {
        self.nx * self.ny
    }
}

/// Levels from fine (0) to coarsest, and the direct solver of the coarsest.
#[derive(Clone, Debug, Default)]
pub(super) struct Hierarchy {
    pub levels: Vec<Level>,
    pub lu: BandLu,
    /// The parameters of the last setup.
    pub params: MgParams,
}

/// Grid sizes of the hierarchy for an `nx × ny` fine grid.
pub(super) fn level_sizes(nx: usize, ny: usize, params: &MgParams) -> Vec<(usize, usize)> {
    let mut sizes = vec![(nx, ny)];
    let (mut cx, mut cy) = (nx, ny);
    while cx * cy > params.coarse_enough.max(1)
        && cx >= 2
        && cy >= 2
        && sizes.len() < params.max_levels.max(1)
    {
        cx /= 2;
        cy /= 2;
        sizes.push((cx, cy));
    }
    sizes
}

impl Hierarchy {
    /// Allocates the hierarchy for `nx × ny` (no values yet) in the buffers of `spare` (an old
    /// hierarchy's levels, fine first; empty for new ones): level l reuses the vectors of old
    /// level l, zeroed and resized (no new mapping where their capacity suffices; a buffer
    /// too small is freed before its replacement is allocated). `Multigrid::reshape` passes
    /// spare levels only for a size no larger than the old one's.
    pub(super) fn recycled(nx: usize, ny: usize, params: &MgParams, spare: Vec<Level>) -> Self {
        let sizes = level_sizes(nx, ny, params);
        let nl = sizes.len();
        let mut spare = spare.into_iter();
        let levels = sizes
            .iter()
            .enumerate()
            .map(|(l, &(nx, ny))| {
                let coarsest = l + 1 == nl;
                let nc = if coarsest { 0 } else { (nx / 2) * (ny / 2) };
                let (uses_x, uses_y) = (params.smoother.uses_x(), params.smoother.uses_y());
                let lines = |used: bool| if used && !coarsest { nx * ny } else { 0 };
                let mut lev = spare.next().unwrap_or_default();
                lev.nx = nx;
                lev.ny = ny;
                // level 0's operator is loaded or taken over at each setup: its old buffer
                // goes now
                if l == 0 {
                    lev.a = Vec::new();
                } else {
                    zeroed(&mut lev.a, nx * ny);
                }
                zeroed(&mut lev.p, nc);
                // R = Pᵀ is read from p (interp::restriction)
                let own_r = params.restriction != Restriction::Transpose;
                zeroed(&mut lev.r, if own_r { nc } else { 0 });
                zeroed(&mut lev.xop, lines(uses_x));
                zeroed(&mut lev.ycp, lines(uses_y && params.lean_y_lines));
                lev.yop.zeroed(lines(uses_y && !params.lean_y_lines));
                lev
            })
            .collect();
        Hierarchy {
            levels,
            lu: BandLu::default(),
            params: params.clone(),
        }
    }

    /// True if this hierarchy's structure (sizes and buffers) serves an operator of size
    /// `nx × ny` under `params`; the cycle parameters may differ.
    pub(super) fn fits(&self, nx: usize, ny: usize, params: &MgParams) -> bool {
        let (p, q) = (&self.params, params);
        self.levels[0].nx == nx
            && self.levels[0].ny == ny
            && p.coarse_enough == q.coarse_enough
            && p.max_levels == q.max_levels
            && p.smoother == q.smoother
            && p.restriction == q.restriction
            && p.lean_y_lines == q.lean_y_lines
    }

    /// Copies `a` (same size as level 0) into level 0, clipped; rejects a bad diagonal.
    fn load_fine(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        let l0 = &mut self.levels[0];
        assert_eq!((l0.nx, l0.ny), (a.nx(), a.ny()));
        if l0.a.len() == a.len() {
            par_copy(&mut l0.a, a.coefs());
        } else {
            // written by the threads that copy (a fresh buffer's pages mapped by them)
            l0.a.clear();
            l0.a.par_extend(a.coefs().par_iter().copied());
        }
        self.check_fine()
    }

    /// Takes the rows `a` of the fine operator over (level 0's size, no copy), clipped;
    /// rejects a bad diagonal ([`crate::solve::LinearSolver::adopt`]).
    pub(super) fn take_fine(&mut self, a: Vec<[f64; 9]>) -> Result<(), SolveError> {
        let l0 = &mut self.levels[0];
        assert_eq!(a.len(), l0.n());
        l0.a = a;
        self.check_fine()
    }

    /// Clips level 0's operator and checks its diagonal.
    fn check_fine(&mut self) -> Result<(), SolveError> {
        let l0 = &mut self.levels[0];
        let nx = l0.nx;
        clip(&mut l0.a, nx, l0.ny);
        match first_bad_diagonal(&l0.a, nx) {
            Some((i, j)) => Err(SolveError::Singular(format!(
                "multigrid: zero or non-finite diagonal {:e} at unknown ({i}, {j})",
                l0.a[i + nx * j][4]
            ))),
            None => Ok(()),
        }
    }

    /// Hands the fine operator back ([`crate::solve::LinearSolver::give_back`]), leaving
    /// level 0 without one; `None` if it has none.
    pub(super) fn give_back_fine(&mut self) -> Option<Stencil9> {
        let l0 = &mut self.levels[0];
        (l0.n() > 0 && l0.a.len() == l0.n())
            .then(|| Stencil9::from_coefs(l0.nx, l0.ny, std::mem::take(&mut l0.a)))
    }

    /// True if level 0 holds its operator (not handed back).
    pub(super) fn has_fine(&self) -> bool {
        self.levels[0].a.len() == self.levels[0].n()
    }

    /// Replaces the fine operator by `a` (same size as level 0) and refactors the fine
    /// smoother, keeping the transfer and coarse operators of the last [`Hierarchy::refresh`]
    /// (see [`crate::solve::multigrid::Multigrid::update`]).
    pub(super) fn refresh_fine(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.load_fine(a)?;
        self.refactor_fine()
    }

    /// Refactors the fine smoother for the operator just loaded into level 0, keeping the
    /// rest of the last full setup (all of it, on a single level).
    pub(super) fn refactor_fine(&mut self) -> Result<(), SolveError> {
        if self.levels.len() == 1 {
            return self.refresh_loaded();
        }
        let l0 = &mut self.levels[0];
        let (nx, ny) = (l0.nx, l0.ny);
        if !l0.xop.is_empty() {
            factor_x(&l0.a, nx, ny, &mut l0.xop)?;
        }
        if !l0.yop.is_empty() {
            factor_y(&l0.a, nx, ny, &mut l0.yop)?;
        }
        if !l0.ycp.is_empty() {
            yline::factor_y(&l0.a, nx, ny, &mut l0.ycp)?;
        }
        Ok(())
    }

    /// Computes every value of the hierarchy for operator `a` (same size as level 0).
    pub(super) fn refresh(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.load_fine(a)?;
        self.refresh_loaded()
    }

    /// Computes every value of the hierarchy for the operator loaded into level 0.
    pub(super) fn refresh_loaded(&mut self) -> Result<(), SolveError> {
        let transpose = self.params.restriction == Restriction::Transpose;
        let nl = self.levels.len();
        for l in 0..nl {
            let (fine, rest) = self.levels.split_at_mut(l + 1);
            let lev = &mut fine[l];
            if l + 1 == nl {
                self.lu.factor(&lev.a, lev.nx, lev.ny)?;
                break;
            }
            if !lev.xop.is_empty() {
                factor_x(&lev.a, lev.nx, lev.ny, &mut lev.xop)?;
            }
            if !lev.yop.is_empty() {
                factor_y(&lev.a, lev.nx, lev.ny, &mut lev.yop)?;
            }
            if !lev.ycp.is_empty() {
                yline::factor_y(&lev.a, lev.nx, lev.ny, &mut lev.ycp)?;
            }
            build_transfer(&lev.a, lev.nx, lev.ny, &mut lev.p, &mut lev.r, transpose)?;
            let r = restriction(&lev.p, &lev.r);
            galerkin(&lev.a, lev.nx, lev.ny, &lev.p, r, &mut rest[0].a);
        }
        Ok(())
    }
}

/// Zeroes the couplings of the `nx × ny` rows `out` that point outside the grid.
fn clip(out: &mut [[f64; 9]], nx: usize, ny: usize) {
    let clip = |row: &mut [f64; 9], ks: &[usize]| {
        for &kk in ks {
            row[kk] = 0.0;
        }
    };
    for i in 0..nx {
        clip(&mut out[i], &[0, 1, 2]);
        clip(&mut out[i + nx * (ny - 1)], &[6, 7, 8]);
    }
    for j in 0..ny {
        clip(&mut out[nx * j], &[0, 3, 6]);
        clip(&mut out[nx - 1 + nx * j], &[2, 5, 8]);
    }
}

/// The first unknown whose diagonal is zero or not finite.
fn first_bad_diagonal(a: &[[f64; 9]], nx: usize) -> Option<(usize, usize)> {
    let bad = |m: &[f64; 9]| !(m[4].is_finite() && m[4] != 0.0);
    if use_par(a.len()) {
        a.par_iter().position_first(bad)
    } else {
        a.iter().position(bad)
    }
    .map(|p| (p % nx, p / nx))
}

impl Smoother {
    pub(super) fn uses_x(self) -> bool {
        !matches!(self, Smoother::ZebraLineY)
    }

    pub(super) fn uses_y(self) -> bool {
        !matches!(self, Smoother::ZebraLineX)
    }
}
