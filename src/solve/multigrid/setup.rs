//! The grid hierarchy: sizes and buffers (the *structural* setup, fixed for a grid size) and
//! their values (the *numeric* setup, refreshed for every new operator of the same size).
//!
//! Coarsening stops when a grid has at most `coarse_enough` unknowns, when either direction
//! has fewer than two unknowns (it could not be halved), or after `max_levels` levels.

use crate::solve::multigrid::coarse::BandLu;
use crate::solve::multigrid::interp::build_transfer;
use crate::solve::multigrid::rap::galerkin;
use crate::solve::multigrid::relax::{factor_x, factor_y, YLineOp};
use crate::solve::multigrid::{MgParams, Restriction, Smoother};
use crate::solve::stencil9::Stencil9;
use crate::solve::SolveError;

/// One grid of the hierarchy.
#[derive(Clone, Debug, Default)]
pub(super) struct Level {
    pub nx: usize,
    pub ny: usize,
    /// The operator (level 0: a clipped copy of the caller's).
    pub a: Vec<[f64; 9]>,
    /// x-line factors and y-line operator of the smoother (see `relax.rs`; empty if the
    /// smoother does not use them, and on the coarsest level).
    pub xop: Vec<[f64; 2]>,
    pub yop: YLineOp,
    /// Prolongation and restriction stars to the next coarser level (one per coarse point;
    /// empty on the coarsest level).
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
    /// Allocates the hierarchy for `nx × ny` (no values yet).
    pub(super) fn new(nx: usize, ny: usize, params: &MgParams) -> Self {
        let sizes = level_sizes(nx, ny, params);
        let nl = sizes.len();
        let levels = sizes
            .iter()
            .enumerate()
            .map(|(l, &(nx, ny))| {
                let coarsest = l + 1 == nl;
                let nc = if coarsest { 0 } else { (nx / 2) * (ny / 2) };
                let mut lev = Level {
                    nx,
                    ny,
                    a: vec![[0.0; 9]; nx * ny],
                    p: vec![[0.0; 9]; nc],
                    r: vec![[0.0; 9]; nc],
                    ..Default::default()
                };
                if !coarsest {
                    if params.smoother.uses_x() {
                        lev.xop.resize(nx * ny, [0.0; 2]);
                    }
                    if params.smoother.uses_y() {
                        lev.yop.resize(nx * ny);
                    }
                }
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
    }

    /// Copies `a` (same size as level 0) into level 0, clipped; rejects a bad diagonal.
    fn load_fine(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        let (nx, ny) = (a.nx(), a.ny());
        let l0 = &mut self.levels[0];
        assert_eq!((l0.nx, l0.ny), (nx, ny));
        copy_clipped(a, &mut l0.a);
        match first_bad_diagonal(&l0.a, nx) {
            Some((i, j)) => Err(SolveError::Singular(format!(
                "multigrid: zero or non-finite diagonal {:e} at unknown ({i}, {j})",
                l0.a[i + nx * j][4]
            ))),
            None => Ok(()),
        }
    }

    /// Replaces the fine operator by `a` (same size as level 0) and refactors the fine
    /// smoother, keeping the transfer and coarse operators of the last [`Hierarchy::refresh`]
    /// (see [`crate::solve::multigrid::Multigrid::update`]).
    pub(super) fn refresh_fine(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        if self.levels.len() == 1 {
            return self.refresh(a);
        }
        self.load_fine(a)?;
        let l0 = &mut self.levels[0];
        let (nx, ny) = (l0.nx, l0.ny);
        if !l0.xop.is_empty() {
            factor_x(&l0.a, nx, ny, &mut l0.xop)?;
        }
        if !l0.yop.is_empty() {
            factor_y(&l0.a, nx, ny, &mut l0.yop)?;
        }
        Ok(())
    }

    /// Computes every value of the hierarchy for operator `a` (same size as level 0).
    pub(super) fn refresh(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.load_fine(a)?;
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
            build_transfer(&lev.a, lev.nx, lev.ny, &mut lev.p, &mut lev.r, transpose)?;
            galerkin(&lev.a, lev.nx, lev.ny, &lev.p, &lev.r, &mut rest[0].a);
        }
        Ok(())
    }
}

/// Copies the caller's operator, zeroing couplings that point outside the grid.
fn copy_clipped(a: &Stencil9, out: &mut [[f64; 9]]) {
    let (nx, ny) = (a.nx(), a.ny());
    out.copy_from_slice(a.coefs());
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
    a.iter()
        .position(|m| !(m[4].is_finite() && m[4] != 0.0))
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
