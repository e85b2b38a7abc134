//! [`MultigridSafe`]: the 2D multigrid with a Bi-CGSTAB fallback and, for systems neither
//! solves, a sparse LU: the default linear solver of case files.

use crate::solve::direct::DirectLu;
use crate::solve::multigrid::{MgParams, Multigrid};
use crate::solve::stencil9::Stencil9;
use crate::solve::{LinearSolver, SolveControl, SolveError, SolveInfo};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

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
///
/// Where the Bi-CGSTAB diverges too (measured: the artificial boundary of Figs 19–22 at
/// 385 × 257 nodes with its wall spacing held, block `sector_2`, whose every run stopped with
/// "the iteration diverged"), a system of at most [`MultigridSafe::DIRECT_LIMIT`] unknowns is
/// solved by faer's sparse LU of the multigrid's fine operator, and so is every later system
/// of this solver (its preconditioner too: the exact inverse), without trying the cycles again.
#[derive(Default)]
pub struct MultigridSafe {
    mg: Multigrid,
    /// Set once the cycles and their Bi-CGSTAB diverged: the LU from then on.
    direct: AtomicBool,
    /// The LU of the operator, made when first needed, and whether it is the current
    /// operator's (after an update it is refactored on the next direct solve, keeping the
    /// symbolic factorization: the pattern is the same).
    lu: Mutex<(Option<DirectLu>, bool)>,
}

impl std::fmt::Debug for MultigridSafe {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MultigridSafe")
            .field("mg", &self.mg)
            .field("direct", &self.is_direct())
            .finish_non_exhaustive()
    }
}

impl MultigridSafe {
    /// Plain cycles tried before the fallback.
    pub const PLAIN_CYCLES: usize = 12;
    /// Largest system solved by the sparse LU when the cycles and the Bi-CGSTAB diverge (as
    /// `crate::elliptic::harmonic`'s fallback; ~1 GB of factors for a 500 × 500 grid system).
    pub const DIRECT_LIMIT: usize = 250_000;

    /// True once this solver has turned to the sparse LU (its systems diverged the cycles).
    pub fn is_direct(&self) -> bool {
        self.direct.load(Ordering::Relaxed)
    }

    /// The LU for a system of `n` unknowns: once turned to it, and small enough (a finer level
    /// of nested iteration above the limit tries the multigrid again).
    fn use_direct(&self, n: usize) -> bool {
        self.is_direct() && n <= Self::DIRECT_LIMIT
    }

    /// `x = A⁻¹ b` by the sparse LU of the fine operator (factored on the first call after
    /// each setup).
    fn solve_direct(&self, b: &[f64], x: &mut [f64]) -> Result<SolveInfo, SolveError> {
        let mut guard = self.lu.lock().unwrap_or_else(|e| e.into_inner());
        let (lu, current) = &mut *guard;
        if lu.is_none() || !*current {
            let l0 = &self.mg.hierarchy()?.levels[0];
            let a = Stencil9::from_coefs(l0.nx, l0.ny, l0.a.clone());
            // refactored in place: the ordering (COLAMD) of the same pattern is kept
            let d = lu.get_or_insert_with(DirectLu::new);
            if let Err(e) = d.setup(&a) {
                *lu = None;
                return Err(e);
            }
            *current = true;
        }
        let d = lu.as_ref().expect("factored above");
        d.solve(b, x, &SolveControl::default())
    }

    /// The operator changed to one of `n` unknowns: the LU factors are stale (refactored when
    /// next needed; held only where the LU will solve it, so that a larger system solved by
    /// the multigrid does not hold a smaller one's factors).
    fn forget_factors(&mut self, n: usize) {
        let keep = self.use_direct(n);
        let (lu, current) = self.lu.get_mut().unwrap_or_else(|e| e.into_inner());
        *current = false;
        if !keep {
            *lu = None;
        }
    }

    /// A solver with multigrid parameters `params` (see [`Multigrid::new`]).
    pub fn new(params: MgParams) -> Self {
        MultigridSafe {
            mg: Multigrid::new(params),
            ..Default::default()
        }
    }

    /// The multigrid solver inside.
    pub fn multigrid(&self) -> &Multigrid {
        &self.mg
    }
}

impl LinearSolver for MultigridSafe {
    fn setup(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.forget_factors(a.len());
        self.mg.setup(a)
    }

    fn update(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.forget_factors(a.len());
        self.mg.update(a)
    }

    fn adopt(&mut self, a: &mut Stencil9, small: bool) -> Result<(), SolveError> {
        self.forget_factors(a.len());
        self.mg.adopt(a, small)
    }

    fn give_back(&mut self) -> Option<Stencil9> {
        self.mg.give_back()
    }

    fn solve(&self, b: &[f64], x: &mut [f64], ctl: &SolveControl) -> Result<SolveInfo, SolveError> {
        if self.use_direct(b.len()) {
            return self.solve_direct(b, x);
        }
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
        // a correction whose residual is not below the right-hand side's is worse than none:
        // not returned (applied, it threw a Picard step 1.3e3 diameters off, measured)
        let useless =
            |i: &SolveInfo| !i.converged && !i.residual_history.last().is_some_and(|&r| r < 1.0);
        match self.mg.bicgstab(b, x, ctl) {
            Ok(info) if useless(&info) && b.len() <= Self::DIRECT_LIMIT => {
                self.direct.store(true, Ordering::Relaxed);
                self.solve_direct(b, x)
            }
            Ok(mut info) => {
                info.iterations = tried + 2 * info.iterations;
                Ok(info)
            }
            Err(SolveError::Diverged(_)) if b.len() <= Self::DIRECT_LIMIT => {
                self.direct.store(true, Ordering::Relaxed);
                self.solve_direct(b, x)
            }
            Err(e) => Err(e),
        }
    }

    fn companion(&self) -> Option<Box<dyn LinearSolver>> {
        Some(Box::new(MultigridSafe::new(self.mg.params().clone())))
    }

    /// One cycle of the multigrid (no fallback: a preconditioner need not converge).
    fn precondition(&self, b: &[f64], x: &mut [f64]) -> Result<(), SolveError> {
        if self.use_direct(b.len()) {
            return self.solve_direct(b, x).map(|_| ());
        }
        LinearSolver::precondition(&self.mg, b, x)
    }

    fn name(&self) -> &'static str {
        "multigrid"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An indefinite Helmholtz operator on 31 × 31 unknowns (diagonal 4 − 7) and a
    /// right-hand side.
    fn helmholtz() -> (Stencil9, Vec<f64>) {
        let mut a = Stencil9::zeros(31, 31);
        for row in a.coefs_mut() {
            *row = [0.0, -1.0, 0.0, -1.0, 4.0 - 7.0, -1.0, 0.0, -1.0, 0.0];
        }
        a.clip_to_grid();
        let b = (0..a.len())
            .map(|p| ((p * 7919) % 101) as f64 / 101.0 - 0.4)
            .collect();
        (a, b)
    }

    /// |b − a x| / |b|.
    fn relative_residual(a: &Stencil9, b: &[f64], x: &[f64]) -> f64 {
        let mut r = vec![0.0; b.len()];
        a.residual(b, x, &mut r);
        r.iter().map(|v| v * v).sum::<f64>().sqrt() / b.iter().map(|v| v * v).sum::<f64>().sqrt()
    }

    #[test]
    fn a_system_the_cycles_and_bicgstab_diverge_on_is_solved_by_the_lu() {
        // An indefinite Helmholtz operator (diagonal 4 − 7): the plain cycles blow up and so
        // does their Bi-CGSTAB (relative residual 1.1e3 at 31 × 31, measured); the LU solves it
        // to round-off, and the next solve and the preconditioner go to the LU at once.
        let (a, b) = helmholtz();
        let n = a.len();
        let mut plain = Multigrid::new(MgParams::default());
        plain.setup(&a).unwrap();
        let mut x = vec![0.0; n];
        assert!(matches!(
            plain.bicgstab(&b, &mut x, &SolveControl::default()),
            Err(SolveError::Diverged(_))
        ));
        let mut safe = MultigridSafe::new(MgParams::default());
        safe.setup(&a).unwrap();
        assert!(!safe.is_direct());
        let mut x = vec![0.0; n];
        safe.solve(&b, &mut x, &SolveControl::default()).unwrap();
        assert!(safe.is_direct());
        let rel = relative_residual(&a, &b, &x);
        assert!(rel < 1e-10, "relative residual {rel:e}");
        let mut y = vec![0.0; n];
        safe.precondition(&b, &mut y).unwrap();
        assert_eq!(x, y);
        // a new operator: new factors (the identity solves to b)
        let mut id = Stencil9::zeros(31, 31);
        for row in id.coefs_mut() {
            *row = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        }
        safe.setup(&id).unwrap();
        safe.solve(&b, &mut y, &SolveControl::default()).unwrap();
        assert!(y.iter().zip(&b).all(|(u, v)| (u - v).abs() < 1e-14));
        // an update of the values (the pattern kept: refactored in place, the ordering
        // reused): twice the Helmholtz operator solves to half the first solution
        let mut twice = a.clone();
        for row in twice.coefs_mut() {
            row.iter_mut().for_each(|c| *c *= 2.0);
        }
        safe.update(&twice).unwrap();
        safe.solve(&b, &mut y, &SolveControl::default()).unwrap();
        let off = y
            .iter()
            .zip(&x)
            .map(|(u, v)| (u - 0.5 * v).abs())
            .fold(0.0, f64::max);
        assert!(off < 1e-10, "{off:e}");
    }

    #[test]
    fn a_solve_that_ends_worse_than_it_started_goes_to_the_lu() {
        // The same indefinite operator with two iterations allowed: the cycles and their
        // Bi-CGSTAB stop without a verdict, their residual above the right-hand side's (a
        // correction worse than none). The LU answers instead.
        let (a, b) = helmholtz();
        let n = a.len();
        let ctl = SolveControl {
            rel_tol: 1e-12,
            max_iter: 2,
        };
        let mut plain = Multigrid::new(MgParams::default());
        plain.setup(&a).unwrap();
        let mut x = vec![0.0; n];
        let info = plain.bicgstab(&b, &mut x, &ctl).unwrap();
        assert!(!info.converged && *info.residual_history.last().unwrap() >= 1.0);
        let mut safe = MultigridSafe::new(MgParams::default());
        safe.setup(&a).unwrap();
        let mut x = vec![0.0; n];
        safe.solve(&b, &mut x, &ctl).unwrap();
        assert!(safe.is_direct());
        let rel = relative_residual(&a, &b, &x);
        assert!(rel < 1e-10, "relative residual {rel:e}");
    }
}
