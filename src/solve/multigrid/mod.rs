//! Black-box multigrid for the nine-point grid systems (in the manner of de Zeeuw's MGD9V,
//! which NLR TP 96338 uses for its linear systems).
//!
//! [`Multigrid`] solves `A x = b` for a [`Stencil9`] on `nx × ny` unknowns. It needs nothing
//! but the matrix:
//!
//! | phase | file | method |
//! |---|---|---|
//! | hierarchy, setup vs refresh | `setup.rs` | coarsening by 2 in both directions down to `coarse_enough` |
//! | transfer operators | `interp.rs` | matrix-dependent prolongation (Dendy's collapse, de Zeeuw's upwind split); restriction `Pᵀ` (or from the adjoint operator) |
//! | coarse operators | `rap.rs` | Galerkin `R A P`, nine-point on every level |
//! | smoother | `relax.rs` | alternating zebra line Gauss–Seidel (Thomas algorithm per line, lines of one colour in parallel) |
//! | cycles | `cycle.rs` | V, F, W; banded LU on the coarsest grid (`coarse.rs`) |
//! | acceleration | `krylov.rs` | Bi-CGSTAB with one cycle as right preconditioner |
//!
//! # Coarsening and grid sizes
//! Coarse unknowns are the fine unknowns with odd `i` and odd `j` (0-based, interior
//! numbering), i.e. the even nodes of the grid including its Dirichlet boundary: `nx`
//! unknowns give `nx / 2` coarse ones. Any size works: odd `nx = 2 n_c + 1` is the classic
//! vertex-centred case; for even `nx = 2 n_c` the last unknown is a coarse point one fine
//! cell from the boundary, which the matrix-dependent transfer and the Galerkin operator
//! absorb (see `interp.rs`). Coarsening stops at `coarse_enough` unknowns, when a direction
//! has fewer than 2 unknowns, or at `max_levels`; the coarsest grid is solved by a banded LU.
//!
//! # Smoother
//! Alternating zebra line Gauss–Seidel: every line's tridiagonal system is solved exactly
//! (Thomas algorithm, factored at setup), so couplings of any strength along x or along y are
//! smoothed; alternating the directions covers anisotropy that changes direction over the grid
//! (boundary-layer grids clustered at any wall). Lines of one colour run in parallel.
//! Pre-smoothing relaxes x-lines then y-lines, post-smoothing y-lines then x-lines.
//!
//! # Setup and refresh
//! [`LinearSolver::setup`] allocates the hierarchy the first time (or when the size or the
//! parameters changed) and otherwise only recomputes its values: line factors, transfer
//! weights, Galerkin operators and the coarsest LU.
//!
//! # Solve
//! `solve(&self, …)` takes a per-solve workspace (all level vectors) from an internal pool
//! and returns it afterwards, so several right-hand sides may be solved concurrently (for
//! example with rayon) after one setup; the cycles themselves allocate nothing. Large grids
//! use rayon inside the smoother, residual, transfers and setup.
//! `SolveInfo::residual_history[k] = ‖r_{k+1}‖₂ / ‖r_0‖₂` after each cycle (or Bi-CGSTAB
//! iteration, which costs two cycles); a relative residual above 1e3 or NaN is
//! [`SolveError::Diverged`]; running out of iterations is `converged: false`.
//!
//! # Range
//! Measured factors per V(1,1) cycle (63² unless noted; `tests.rs`, and the ignored test
//! `explore_factors` prints the full table): Poisson 5- and 9-point 0.007, even or
//! non-power-of-two sizes 0.01–0.04, ε = 1e-4 anisotropy in x or in y < 1e-4, boundary-layer
//! grids (first spacing 1e-5, aspect ratio 1.6e4, clustered at a wall in x or in y) 0.002,
//! non-symmetric mixed-derivative stencils (|Q| ≤ 0.9 √(PR), R/P up to 100, cell Péclet
//! number ≤ 0.8) 0.03–0.09. Central convection with cell Péclet numbers above 1 (positive
//! off-diagonal couplings) degrades the V-cycle (0.18 at 1.5, 0.30 at 3, 0.35 at 4);
//! `accelerate` (Bi-CGSTAB, two V-cycles per iteration) gives ≤ 0.15 per iteration up to 4.
//! With the adjoint restriction the V-cycle is better for mild convection (0.02 for the
//! mixed-derivative case, 0.11 at Péclet 1.5) but fails beyond (0.93 at 3, divergence at 4) and
//! on the boundary-layer Picard system at 1025² — hence `Pᵀ` by default.
//! The actual Picard systems (`examples/bench_grid.rs`): curved domain 0.03–0.05 per cycle
//! from 257² to 2049², boundary layer with wall spacing 1e-5 and 1e-6 about 0.07.

mod coarse;
mod cycle;
mod interp;
pub(crate) use interp::split_weights;
pub mod krylov;
mod rap;
mod relax;
mod safe;
mod setup;
#[cfg(test)]
mod tests;
mod xline;
mod yline;

pub use krylov::bicgstab;
pub use safe::MultigridSafe;

use crate::solve::stencil9::Stencil9;
use crate::solve::{
    par_copy, par_fill, stationary, LinearSolver, SolveControl, SolveError, SolveInfo,
};
use cycle::Workspace;
use relax::{pad, residual, Zeroed};
use serde::{Deserialize, Serialize};
use setup::Hierarchy;
use std::sync::Mutex;

/// Cycle type.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Cycle {
    /// One coarse-grid correction per level.
    V,
    /// An F-cycle then a V-cycle on each coarser level (default): 15–25 % dearer than V,
    /// but it holds 0.03 per cycle on the boundary-layer Picard system with aspect ratios
    /// 1.5e4 at 1025², where the V-cycle's coarse levels let it slip to 0.27.
    #[default]
    F,
    /// Two coarse-grid corrections per level.
    W,
}

/// Smoother.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Smoother {
    /// Zebra x-line Gauss–Seidel then zebra y-line Gauss–Seidel (default): robust for
    /// anisotropy in either direction and for stretching that varies over the grid.
    #[default]
    AlternatingZebraLine,
    /// Zebra x-line Gauss–Seidel only (for coupling strongest along x everywhere).
    ZebraLineX,
    /// Zebra y-line Gauss–Seidel only (for coupling strongest along y everywhere).
    ZebraLineY,
    /// One direction per smoothing step, alternating between steps: pre-smoothing starts
    /// with x-lines, post-smoothing with y-lines (so V(1,1) relaxes x-lines before and y-lines
    /// after the coarse-grid correction). Half the work of [`Smoother::AlternatingZebraLine`].
    ZebraLineXY,
}

/// Restriction operator.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Restriction {
    /// Transpose of the prolongation built from the adjoint operator `Aᵀ` (de Zeeuw's
    /// MGD9V). Equal to `Pᵀ` for a symmetric operator. Slightly better for mild convection,
    /// but its Petrov–Galerkin coarse operators can lose stability: the V-cycle diverged on
    /// the boundary-layer Picard system at 1025² (wall spacing 1e-5) and for cell Péclet
    /// numbers ≥ 4.
    Adjoint,
    /// `R = Pᵀ` (default): Galerkin coarse operators; converged on every case measured
    /// (`tests.rs` `explore_factors`; boundary-layer Picard systems to 1025², spacing 1e-6).
    #[default]
    Transpose,
}

/// Multigrid parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MgParams {
    /// Cycle type. Default [`Cycle::F`].
    pub cycle: Cycle,
    /// Smoothing steps before the coarse-grid correction. Default 1.
    pub npre: usize,
    /// Smoothing steps after the coarse-grid correction. Default 1.
    pub npost: usize,
    /// A grid with at most this many unknowns is the coarsest and is solved directly
    /// (banded LU). Default 64.
    pub coarse_enough: usize,
    /// At most this many levels (including the finest). Default 30.
    pub max_levels: usize,
    /// Smoother. Default [`Smoother::AlternatingZebraLine`].
    pub smoother: Smoother,
    /// Restriction. Default [`Restriction::Transpose`].
    pub restriction: Restriction,
    /// Run Bi-CGSTAB preconditioned by one cycle instead of plain cycles. Default false.
    pub accelerate: bool,
    /// Memory-lean y-lines (`yline.rs`): the y-line smoother keeps only one factor per
    /// unknown and reads the couplings from the operator, instead of a scaled copy of the
    /// stencil (36 → 8 bytes per unknown and level; the lines solved exactly in f64, where
    /// the default's f32 line operator solves them to its rounding). Slower: the y-sweep costs 2–2.5× the line operator's from memory (the
    /// operator read in column strips), a whole 2D grid 16–18 % more CPU time. Default false.
    pub lean_y_lines: bool,
}

impl Default for MgParams {
    fn default() -> Self {
        MgParams {
            cycle: Cycle::F,
            npre: 1,
            npost: 1,
            coarse_enough: 64,
            max_levels: 30,
            smoother: Smoother::AlternatingZebraLine,
            restriction: Restriction::Transpose,
            accelerate: false,
            lean_y_lines: false,
        }
    }
}

/// What the hierarchy looks like after `setup`.
#[derive(Clone, Debug, PartialEq)]
pub struct MgInfo {
    /// Grid sizes `(nx, ny)` from the finest to the coarsest level.
    pub levels: Vec<(usize, usize)>,
    /// Unknowns of all levels divided by the fine unknowns.
    pub grid_complexity: f64,
}

/// Black-box multigrid solver for [`Stencil9`] systems; see the module documentation.
#[derive(Debug, Default)]
pub struct Multigrid {
    params: MgParams,
    h: Option<Hierarchy>,
    pool: Pool<Workspace>,
}

/// True if a grid of `n` unknowns is large enough for rayon to pay (2D and 3D multigrid,
/// Bi-CGSTAB).
#[inline]
pub(crate) fn use_par(n: usize) -> bool {
    n >= 1 << 15 && rayon::current_num_threads() > 1
}

/// Per-solve workspaces kept between solves, so that several right-hand sides can be solved at
/// once through `&self` (2D and 3D multigrid).
#[derive(Debug)]
pub(crate) struct Pool<W>(Mutex<Vec<W>>);

impl<W> Default for Pool<W> {
    fn default() -> Self {
        Pool(Mutex::new(Vec::new()))
    }
}

impl<W> Pool<W> {
    /// A kept workspace that `fits`, or `new()`.
    pub(crate) fn take(&self, fits: impl Fn(&W) -> bool, new: impl FnOnce() -> W) -> W {
        let mut pool = self.0.lock().unwrap_or_else(|e| e.into_inner());
        while let Some(ws) = pool.pop() {
            if fits(&ws) {
                return ws;
            }
        }
        new()
    }

    /// A kept workspace, refitted by `refit` if it does not `fits` (its buffers reused), or
    /// `new()` if none is kept.
    pub(crate) fn take_refit(
        &self,
        fits: impl Fn(&W) -> bool,
        refit: impl FnOnce(&mut W),
        new: impl FnOnce() -> W,
    ) -> W {
        let mut pool = self.0.lock().unwrap_or_else(|e| e.into_inner());
        match pool.iter().rposition(&fits) {
            Some(k) => pool.swap_remove(k),
            None => match pool.pop() {
                Some(mut ws) => {
                    refit(&mut ws);
                    ws
                }
                None => new(),
            },
        }
    }

    /// Keeps `ws` for a later solve.
    pub(crate) fn put(&self, ws: W) {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).push(ws);
    }

    /// Drops the kept workspaces but one (the hierarchy changed size: that one is refitted
    /// by [`Pool::take_refit`]).
    pub(crate) fn keep_one(&mut self) {
        self.0
            .get_mut()
            .unwrap_or_else(|e| e.into_inner())
            .truncate(1);
    }

    /// Drops the kept workspaces (the hierarchy changed size).
    pub(crate) fn clear(&mut self) {
        self.0.get_mut().unwrap_or_else(|e| e.into_inner()).clear();
    }
}

/// Cycle workspaces shared by several [`Multigrid`]s of one size
/// ([`Multigrid::solve_shared`]).
#[derive(Debug, Default)]
pub(crate) struct SharedPool(Pool<Workspace>);

/// A raw pointer that may cross threads; users guarantee disjoint writes.
#[derive(Clone, Copy)]
pub(crate) struct SharedPtr(pub(crate) *mut f64);
// SAFETY: only used for disjoint writes (see the kernels that create one).
unsafe impl Send for SharedPtr {}
unsafe impl Sync for SharedPtr {}

impl SharedPtr {
    #[inline]
    pub(crate) fn get(self) -> *mut f64 {
        self.0
    }
}

impl Multigrid {
    /// A solver with parameters `params`; call [`LinearSolver::setup`] before solving.
    pub fn new(params: MgParams) -> Self {
        Multigrid {
            params,
            h: None,
            pool: Pool::default(),
        }
    }

    /// The parameters.
    pub fn params(&self) -> &MgParams {
        &self.params
    }

    /// Changes the parameters. They take effect at the next `setup`, which rebuilds the
    /// hierarchy only if `coarse_enough`, `max_levels`, `smoother` or `restriction` changed.
    pub fn set_params(&mut self, params: MgParams) {
        self.params = params;
    }

    /// Replaces the operator by `a`, a small change of the last one (the next step of a
    /// converging Picard iteration): only the fine level is refreshed (its copy of `a` and
    /// its line factors), the transfers and coarse operators of the last full
    /// [`LinearSolver::setup`] are kept. The cycle then still solves `A x = b` for the new
    /// `a` (residuals and smoothing use it); only its coarse-grid correction is that of a
    /// nearby operator. Costs about a third of a full setup on large grids. Falls back to
    /// the full setup when there is no hierarchy of this size.
    pub fn update(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        match self.h.as_mut() {
            Some(h) if h.fits(a.nx(), a.ny(), &self.params) => {
                h.params = self.params.clone();
                let res = h.refresh_fine(a);
                if res.is_err() {
                    self.h = None;
                }
                res
            }
            _ => self.setup(a),
        }
    }

    /// Bi-CGSTAB preconditioned by one cycle on the operator of the last setup or update
    /// (its fine-level copy: no second copy of the caller's operator is kept).
    pub fn bicgstab(
        &self,
        b: &[f64],
        x: &mut [f64],
        ctl: &SolveControl,
    ) -> Result<SolveInfo, SolveError> {
        let l0 = &self.hierarchy()?.levels[0];
        krylov::bicgstab_coefs(&l0.a, l0.nx, l0.ny, b, x, self, ctl)
    }

    /// The hierarchy of the last `setup`, if any.
    pub fn info(&self) -> Option<MgInfo> {
        let h = self.h.as_ref()?;
        let n0 = h.levels[0].n().max(1) as f64;
        Some(MgInfo {
            levels: h.levels.iter().map(|l| (l.nx, l.ny)).collect(),
            grid_complexity: h.levels.iter().map(|l| l.n() as f64).sum::<f64>() / n0,
        })
    }

    fn hierarchy(&self) -> Result<&Hierarchy, SolveError> {
        self.h
            .as_ref()
            .filter(|h| h.has_fine())
            .ok_or(SolveError::NotSetUp)
    }

    /// A hierarchy for `nx × ny` in place of the last one, whose buffers it reuses
    /// ([`Hierarchy::recycled`]): the sizes change with every level of nested iteration and
    /// between a block's Poisson and harmonic problems, and buffers allocated afresh each time
    /// were mapped and cleared again by the kernel (perf: 70 % of the page faults of the
    /// NACA0012 O-grid at 4 × 257², in allocating a new hierarchy and the first touch of its buffers).
    /// A larger size (the next level of nested iteration) gets a new hierarchy, the old one
    /// dropped first: grown in place the old buffers left the allocator's heap holding more at
    /// the peak (curved 2049²: 301 against 296 bytes per node, #16's bound is 300), for page
    /// faults 117 k against 51 k on the NACA0012 run (no difference in time measurable).
    fn reshape(&mut self, nx: usize, ny: usize) {
        let spare = match self.h.take() {
            Some(h) if h.levels[0].n() >= nx * ny => h.levels,
            _ => Vec::new(),
        };
        // one cycle workspace is kept to be refitted (`Workspace::refit`); more would be held
        // at the new size even where its solves run one at a time
        self.pool.keep_one();
        self.h = Some(Hierarchy::recycled(nx, ny, &self.params, spare));
    }

    /// [`LinearSolver::adopt`]: the fine level takes the rows of `a` over (no copy).
    fn adopt_rows(&mut self, a: &mut Stencil9, small: bool) -> Result<(), SolveError> {
        let (nx, ny) = (a.nx(), a.ny());
        if nx == 0 || ny == 0 {
            return Err(SolveError::Singular("multigrid: empty operator".into()));
        }
        let fits = self
            .h
            .as_ref()
            .is_some_and(|h| h.fits(nx, ny, &self.params));
        if !fits {
            self.reshape(nx, ny);
        }
        let h = self.h.as_mut().expect("hierarchy allocated");
        h.params = self.params.clone();
        let rows = std::mem::replace(a, Stencil9::zeros(0, 0)).into_coefs();
        let res = h.take_fine(rows).and_then(|()| {
            if small && fits {
                h.refactor_fine()
            } else {
                h.refresh_loaded()
            }
        });
        if res.is_err() {
            self.h = None;
        }
        res
    }

    fn take_workspace(&self, h: &Hierarchy) -> Workspace {
        self.pool
            .take_refit(|ws| ws.fits(h), |ws| ws.refit(h), || Workspace::new(h))
    }

    /// Solves as [`LinearSolver::solve`], the cycles' vectors taken from `pool` instead of
    /// this solver's own: solvers of equal size (the planes of one orientation of a 3D level)
    /// then share as many workspaces as run at once, not one per solver and concurrent solve.
    pub(crate) fn solve_shared(
        &self,
        pool: &SharedPool,
        b: &[f64],
        x: &mut [f64],
        ctl: &SolveControl,
    ) -> Result<SolveInfo, SolveError> {
        let h = self.hierarchy()?;
        assert!(
            !h.params.accelerate,
            "multigrid: shared workspaces serve plain cycles"
        );
        self.solve_cycles(h, &pool.0, b, x, ctl)
    }

    /// `out ≈ A⁻¹ rhs` by one cycle from zero (padded vectors of the fine grid).
    fn precondition(&self, h: &Hierarchy, ws: &mut Workspace, rhs: &[f64], out: &mut [f64]) {
        let v = &mut ws.lv[0];
        par_copy(&mut v.b, rhs);
        par_fill(&mut v.x, 0.0);
        h.cycle(0, h.params.cycle, &mut ws.lv, &mut ws.band);
        par_copy(out, &ws.lv[0].x);
    }

    /// Plain multigrid cycles, in correction form: each cycle solves `A e = r` from `e = 0`
    /// for the residual `r = b − A x` kept in the fine level's right-hand side, and
    /// `x ← x + e`, `r ← r − A e` from the f64 operator ([`relax::correct`]). The fixed point
    /// is `A x = b` whatever the precision of the smoothers' factors (the y-line operator is
    /// stored in f32), and the caller's `x` is the solution vector (no padded copy). On an
    /// error `x` holds the last iterate.
    fn solve_cycles(
        &self,
        h: &Hierarchy,
        pool: &Pool<Workspace>,
        b: &[f64],
        x: &mut [f64],
        ctl: &SolveControl,
    ) -> Result<SolveInfo, SolveError> {
        let l0 = &h.levels[0];
        let (nx, ny, n) = (l0.nx, l0.ny, l0.n());
        let pd = pad(nx);
        let mut ws = pool.take_refit(|ws| ws.fits(h), |ws| ws.refit(h), || Workspace::new(h));
        let res = {
            let v = &mut ws.lv[0];
            par_copy(&mut v.b[pd..pd + n], b);
            let r0 = if x.iter().all(|&xi| xi == 0.0) {
                b.iter().map(|bi| bi * bi).sum::<f64>().sqrt()
            } else {
                par_copy(&mut v.x[pd..pd + n], x);
                let r0 = residual(&l0.a, None, nx, ny, &v.x, &v.b, &mut v.r, Zeroed::None);
                std::mem::swap(&mut v.b, &mut v.r);
                r0.sqrt()
            };
            stationary(r0, ctl, || {
                par_fill(&mut ws.lv[0].x, 0.0);
                h.cycle(0, h.params.cycle, &mut ws.lv, &mut ws.band);
                let v = &mut ws.lv[0];
                relax::correct(&l0.a, nx, ny, &v.x, &mut v.b, x).sqrt()
            })
        };
        pool.put(ws);
        res
    }
}

impl LinearSolver for Multigrid {
    fn setup(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        let (nx, ny) = (a.nx(), a.ny());
        if nx == 0 || ny == 0 {
            return Err(SolveError::Singular("multigrid: empty operator".into()));
        }
        let fits = self
            .h
            .as_ref()
            .is_some_and(|h| h.fits(nx, ny, &self.params));
        if !fits {
            self.reshape(nx, ny);
        }
        let h = self.h.as_mut().expect("hierarchy allocated");
        h.params = self.params.clone();
        let res = h.refresh(a);
        if res.is_err() {
            self.h = None;
        }
        res
    }

    fn solve(&self, b: &[f64], x: &mut [f64], ctl: &SolveControl) -> Result<SolveInfo, SolveError> {
        let h = self.hierarchy()?;
        let n = h.levels[0].n();
        assert_eq!(b.len(), n, "multigrid: right-hand side length");
        assert_eq!(x.len(), n, "multigrid: solution length");
        if h.params.accelerate {
            // the clipped fine operator of the hierarchy is the Krylov operator
            self.bicgstab(b, x, ctl)
        } else {
            self.solve_cycles(h, &self.pool, b, x, ctl)
        }
    }

    fn update(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        Multigrid::update(self, a)
    }

    fn adopt(&mut self, a: &mut Stencil9, small: bool) -> Result<(), SolveError> {
        self.adopt_rows(a, small)
    }

    fn give_back(&mut self) -> Option<Stencil9> {
        self.h.as_mut()?.give_back_fine()
    }

    fn companion(&self) -> Option<Box<dyn LinearSolver>> {
        Some(Box::new(Multigrid::new(self.params.clone())))
    }

    /// One cycle from zero.
    fn precondition(&self, b: &[f64], x: &mut [f64]) -> Result<(), SolveError> {
        let h = self.hierarchy()?;
        let l0 = &h.levels[0];
        let (pd, n) = (pad(l0.nx), l0.n());
        assert_eq!(b.len(), n, "multigrid: right-hand side length");
        assert_eq!(x.len(), n, "multigrid: solution length");
        let mut ws = self.take_workspace(h);
        let v = &mut ws.lv[0];
        par_copy(&mut v.b[pd..pd + n], b);
        par_fill(&mut v.x, 0.0);
        h.cycle(0, h.params.cycle, &mut ws.lv, &mut ws.band);
        par_copy(x, &ws.lv[0].x[pd..pd + n]);
        self.pool.put(ws);
        Ok(())
    }

    fn name(&self) -> &'static str {
        "multigrid"
    }
}
