//! The linear solve of a Picard step behind one small trait, so that the direct reference
//! solver and the black-box multigrid are interchangeable.

pub mod direct;
pub mod gmres;
pub mod ilu;
pub mod krylov;
pub mod multigrid;
pub mod multigrid3d;
pub mod periodic9;
pub mod select;
pub mod stencil19;
pub mod stencil9;

use crate::solve::stencil9::Stencil9;

/// `dst = src`, in parallel chunks when large (one thread copies ~10 GB/s: a 1025² grid's
/// vectors and operators are copied at every preconditioner call and setup).
pub(crate) fn par_copy<T: Copy + Send + Sync>(dst: &mut [T], src: &[T]) {
    assert_eq!(dst.len(), src.len(), "par_copy: lengths");
    if multigrid::use_par(dst.len()) {
        use rayon::prelude::*;
        dst.par_chunks_mut(8192)
            .zip(src.par_chunks(8192))
            .for_each(|(d, s)| d.copy_from_slice(s));
    } else {
        dst.copy_from_slice(src);
    }
}

/// Every element of `dst` set to `v`, in parallel chunks when large.
pub(crate) fn par_fill<T: Copy + Send + Sync>(dst: &mut [T], v: T) {
    if multigrid::use_par(dst.len()) {
        use rayon::prelude::*;
        dst.par_chunks_mut(8192).for_each(|d| d.fill(v));
    } else {
        dst.fill(v);
    }
}

/// `v` resized to `n` default (zero) values. A buffer too small is freed first and replaced
/// by a fresh zeroed allocation, whose pages the kernel maps at their first write (by the
/// parallel kernel that fills them, not here, one thread); a large enough one is cleared in
/// parallel, its capacity kept.
pub(crate) fn zeroed<T: Copy + Default + Send + Sync>(v: &mut Vec<T>, n: usize) {
    if v.capacity() < n {
        *v = Vec::new();
        *v = vec![T::default(); n];
    } else {
        v.truncate(n);
        par_fill(v, T::default());
        v.resize(n, T::default());
    }
}

/// Relative residual beyond which an iteration (cycles or Bi-CGSTAB) counts as diverged.
pub const DIVERGED: f64 = 1e3;

/// How accurately one linear system is to be solved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveControl {
    /// Stop when ‖b − A x‖₂ ≤ rel_tol · ‖b − A x₀‖₂ (iterative solvers).
    pub rel_tol: f64,
    /// At most this many iterations (cycles) (iterative solvers).
    pub max_iter: usize,
}

impl Default for SolveControl {
    fn default() -> Self {
        SolveControl {
            rel_tol: 1e-10,
            max_iter: 100,
        }
    }
}

/// What a linear solve did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SolveInfo {
    /// Iterations (cycles) done; 1 for a direct solve.
    pub iterations: usize,
    /// ‖r_k‖₂ / ‖r_0‖₂ after each iteration.
    pub residual_history: Vec<f64>,
    /// True if the requested reduction was reached.
    pub converged: bool,
}

impl SolveInfo {
    /// The start of an iteration at initial residual norm `r0`: [`SolveError::Diverged`] if
    /// it is not finite, a converged empty result if it is zero, otherwise `None` (iterate).
    pub(crate) fn start(r0: f64) -> Result<Option<SolveInfo>, SolveError> {
        if !r0.is_finite() {
            return Err(SolveError::Diverged(f64::NAN));
        }
        Ok((r0 == 0.0).then(|| SolveInfo {
            converged: true,
            ..SolveInfo::default()
        }))
    }
}

/// A stationary iteration from residual norm `r0` (plain multigrid cycles, 2D and 3D):
/// `step()` does one iteration and returns the new residual norm. Stops at
/// `‖r‖ ≤ rel_tol ‖r₀‖` or after `max_iter` steps (`converged: false`); a relative residual
/// above [`DIVERGED`] or NaN is [`SolveError::Diverged`].
pub(crate) fn stationary(
    r0: f64,
    ctl: &SolveControl,
    mut step: impl FnMut() -> f64,
) -> Result<SolveInfo, SolveError> {
    if let Some(done) = SolveInfo::start(r0)? {
        return Ok(done);
    }
    let mut info = SolveInfo::default();
    while info.iterations < ctl.max_iter {
        let rel = step() / r0;
        info.iterations += 1;
        info.residual_history.push(rel);
        if rel.is_nan() || rel > DIVERGED {
            return Err(SolveError::Diverged(rel));
        }
        if rel <= ctl.rel_tol {
            info.converged = true;
            break;
        }
    }
    Ok(info)
}

/// Why a linear solve failed.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum SolveError {
    #[error("linear solver: the matrix is singular or could not be factored ({0})")]
    Singular(String),
    #[error("linear solver: the iteration diverged (relative residual {0:.3e})")]
    Diverged(f64),
    #[error(
        "linear solver: no convergence in {iterations} iterations (relative residual {residual:.3e})"
    )]
    NotConverged { iterations: usize, residual: f64 },
    #[error("linear solver: solve called before setup")]
    NotSetUp,
    /// The direct solver's LU does not fit in memory; `what` says by how much, or that the
    /// factorization ran out.
    #[error(
        "linear solver: the direct LU of {unknowns} unknowns {what}: use linear = \"multigrid\" \
         (or \"bicgstab\" for a volume block)"
    )]
    OutOfMemory { unknowns: usize, what: String },
}

/// A solver for structured systems `A x = b` with the operator `A`: nine-point
/// ([`Stencil9`], 2D blocks, the default) or 19-point ([`Stencil19`](crate::solve::stencil19::Stencil19), volume blocks).
///
/// `setup` is called once per operator (once per Picard step); several right-hand sides (the
/// coordinates) then share it and may be solved in parallel through `solve(&self, ..)`.
pub trait LinearSolver<A = Stencil9>: Send + Sync {
    /// Prepares the solver for operator `a` (factorization, multigrid hierarchy).
    fn setup(&mut self, a: &A) -> Result<(), SolveError>;

    /// Solves `A x = b` for the operator of the last `setup`; `x` holds the initial guess.
    fn solve(&self, b: &[f64], x: &mut [f64], ctl: &SolveControl) -> Result<SolveInfo, SolveError>;

    /// Prepares the solver for `a`, a small change of the operator of the last `setup` (a
    /// later step of a converging Picard iteration). Iterative solvers may keep parts of the
    /// last setup (multigrid: its coarse levels) as long as `solve` still solves `A x = b`
    /// for this `a`. Default: a full `setup`.
    fn update(&mut self, a: &A) -> Result<(), SolveError> {
        self.setup(a)
    }

    /// Prepares the solver for the operator in `a` as [`LinearSolver::setup`] does (only as
    /// [`LinearSolver::update`] if `small`), but may take the operator over instead of
    /// copying it, leaving `a` empty (no unknowns): a solver that keeps the fine operator
    /// anyway (the multigrids: their fine level) then holds the only copy, and a Picard
    /// system and its solver share one operator. The caller takes it back with
    /// [`LinearSolver::give_back`] before it assembles the next one. Default: `setup` or
    /// `update` from `a`, which stays with the caller.
    fn adopt(&mut self, a: &mut A, small: bool) -> Result<(), SolveError> {
        if small {
            self.update(a)
        } else {
            self.setup(a)
        }
    }

    /// The operator taken over by the last [`LinearSolver::adopt`], handed back: the solver
    /// cannot solve again before its next setup (`solve` is then [`SolveError::NotSetUp`]).
    /// `None` if it holds none (the default).
    fn give_back(&mut self) -> Option<A> {
        None
    }

    /// `x ≈ A⁻¹ b` as a preconditioner for the operator of the last `setup` or `update`: a
    /// fixed linear map, cheap rather than exact (multigrid: one cycle from zero). Default:
    /// a solve from zero to the default [`SolveControl`] (the direct solver: exact).
    fn precondition(&self, b: &[f64], x: &mut [f64]) -> Result<(), SolveError> {
        x.fill(0.0);
        self.solve(b, x, &SolveControl::default()).map(|_| ())
    }

    /// A new solver of the same kind and parameters, not set up, for a second operator of
    /// the same size (Newton's per-coordinate preconditioners, [`crate::elliptic::newton`]);
    /// `None` (the default) if this solver cannot make one.
    fn companion(&self) -> Option<Box<dyn LinearSolver<A>>> {
        None
    }

    /// A short name for reports ("direct-lu", "multigrid").
    fn name(&self) -> &'static str;
}
