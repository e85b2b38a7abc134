//! The linear solve of a Picard step behind one small trait, so that the direct reference
//! solver and the black-box multigrid are interchangeable.

pub mod direct;
pub mod krylov;

use crate::multigrid::{MgParams, Multigrid};
use crate::stencil::Stencil9;

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
/// above [`krylov::DIVERGED`] or NaN is [`SolveError::Diverged`].
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
        if rel.is_nan() || rel > krylov::DIVERGED {
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
    #[error("linear solver: solve called before setup")]
    NotSetUp,
}

/// A solver for nine-point structured systems `A x = b`.
///
/// `setup` is called once per operator (once per Picard step); several right-hand sides (the
/// coordinates) then share it and may be solved in parallel through `solve(&self, ..)`.
pub trait LinearSolver: Send + Sync {
    /// Prepares the solver for operator `a` (factorization, multigrid hierarchy).
    fn setup(&mut self, a: &Stencil9) -> Result<(), SolveError>;

    /// Solves `A x = b` for the operator of the last `setup`; `x` holds the initial guess.
    fn solve(&self, b: &[f64], x: &mut [f64], ctl: &SolveControl) -> Result<SolveInfo, SolveError>;

    /// Prepares the solver for `a`, a small change of the operator of the last `setup` (a
    /// later step of a converging Picard iteration). Iterative solvers may keep parts of the
    /// last setup (multigrid: its coarse levels) as long as `solve` still solves `A x = b`
    /// for this `a`. Default: a full `setup`.
    fn update(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.setup(a)
    }

    /// A short name for reports ("direct-lu", "multigrid").
    fn name(&self) -> &'static str;
}

/// The linear solver called `name` in case files: "direct" (sparse LU, the reference) or
/// "multigrid" ([`MultigridSafe`] with the default [`MgParams`]: F(1,1) cycles with
/// alternating zebra line Gauss–Seidel, Bi-CGSTAB as the fallback; the default of case files).
pub fn by_name(name: &str) -> Result<Box<dyn LinearSolver>, String> {
    match name {
        "direct" => Ok(Box::new(direct::DirectLu::new())),
        "multigrid" => Ok(Box::new(MultigridSafe::new(MgParams::default()))),
        _ => Err(format!(
            "linear solver '{name}': expected \"direct\" or \"multigrid\""
        )),
    }
}

/// Black-box multigrid ([`Multigrid`]) with a fallback: plain cycles first and, if they
/// diverge or run out of iterations, the solve again from the same initial guess by
/// Bi-CGSTAB preconditioned with one cycle ([`crate::multigrid::bicgstab`]). At most
/// [`MultigridSafe::PLAIN_CYCLES`] plain cycles are tried.
///
/// Why: the plain cycles contract at 0.01–0.05 on every grid system measured since the
/// restriction became `Pᵀ` and the cycle F, but the V-cycle with the adjoint restriction
/// diverged on a boundary-layer system (wall spacing 1e-5 at 1025² nodes) where the same
/// cycle as a Bi-CGSTAB preconditioner still converged fast: the fallback is the safety net
/// for systems nobody has measured yet. `iterations` counts cycles
/// (two per Bi-CGSTAB iteration, plus the plain cycles of an attempt that ran out of
/// iterations; those of an attempt that diverged are not reported by [`Multigrid`]).
#[derive(Debug, Default)]
pub struct MultigridSafe {
    mg: Multigrid,
}

impl MultigridSafe {
    /// Plain cycles tried before the fallback.
    pub const PLAIN_CYCLES: usize = 12;

    /// A solver with multigrid parameters `params` (see [`Multigrid::new`]).
    pub fn new(params: MgParams) -> Self {
        MultigridSafe {
            mg: Multigrid::new(params),
        }
    }

    /// The multigrid solver inside.
    pub fn multigrid(&self) -> &Multigrid {
        &self.mg
    }
}

impl LinearSolver for MultigridSafe {
    fn setup(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.mg.setup(a)
    }

    fn update(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.mg.update(a)
    }

    fn solve(&self, b: &[f64], x: &mut [f64], ctl: &SolveControl) -> Result<SolveInfo, SolveError> {
        let mut y = x.to_vec();
        // plain cycles contract at ≤ 0.05 where they work: 12 of them reach 1e-13, so more
        // would only be a slow or diverging iteration
        let first = SolveControl {
            max_iter: ctl.max_iter.min(Self::PLAIN_CYCLES),
            ..*ctl
        };
        let tried = match self.mg.solve(b, &mut y, &first) {
            Ok(info) if info.converged => {
                x.copy_from_slice(&y);
                return Ok(info);
            }
            Ok(info) => info.iterations,
            Err(SolveError::Diverged(_)) => 0,
            Err(e) => return Err(e),
        };
        let mut info = self.mg.bicgstab(b, x, ctl)?;
        info.iterations = tried + 2 * info.iterations;
        Ok(info)
    }

    fn name(&self) -> &'static str {
        "multigrid"
    }
}
