//! [`MultigridSafe`]: the 2D multigrid with a Bi-CGSTAB fallback, the default linear solver
//! of case files.

use crate::solve::multigrid::{MgParams, Multigrid};
use crate::solve::stencil9::Stencil9;
use crate::solve::{LinearSolver, SolveControl, SolveError, SolveInfo};

/// Black-box multigrid ([`Multigrid`]) with a fallback: plain cycles first and, if they
/// diverge or run out of iterations, the solve again from the same initial guess by
/// Bi-CGSTAB preconditioned with one cycle ([`crate::solve::multigrid::bicgstab`]). At most
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

    fn adopt(&mut self, a: &mut Stencil9, small: bool) -> Result<(), SolveError> {
        self.mg.adopt(a, small)
    }

    fn give_back(&mut self) -> Option<Stencil9> {
        self.mg.give_back()
    }

    fn solve(&self, b: &[f64], x: &mut [f64], ctl: &SolveControl) -> Result<SolveInfo, SolveError> {
        // the fallback restarts from the initial guess: kept only when it is not zero (a
        // Picard correction starts from zero; a copy would cost 8 bytes per unknown and
        // concurrent solve)
        let start = x.iter().any(|&v| v != 0.0).then(|| x.to_vec());
        // plain cycles contract at ≤ 0.05 where they work: 12 of them reach 1e-13, so more
        // would only be a slow or diverging iteration
        let first = SolveControl {
            max_iter: ctl.max_iter.min(Self::PLAIN_CYCLES),
            ..*ctl
        };
        let tried = match self.mg.solve(b, x, &first) {
            Ok(info) if info.converged => return Ok(info),
            Ok(info) => info.iterations,
            Err(SolveError::Diverged(_)) => 0,
            Err(e) => return Err(e),
        };
        match &start {
            Some(s) => x.copy_from_slice(s),
            None => x.fill(0.0),
        }
        let mut info = self.mg.bicgstab(b, x, ctl)?;
        info.iterations = tried + 2 * info.iterations;
        Ok(info)
    }

    fn companion(&self) -> Option<Box<dyn LinearSolver>> {
        Some(Box::new(MultigridSafe::new(self.mg.params().clone())))
    }

    /// One cycle of the multigrid (no fallback: a preconditioner need not converge).
    fn precondition(&self, b: &[f64], x: &mut [f64]) -> Result<(), SolveError> {
        LinearSolver::precondition(&self.mg, b, x)
    }

    fn name(&self) -> &'static str {
        "multigrid"
    }
}
