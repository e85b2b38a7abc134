//! The linear solve of a Picard step behind one small trait, so that the direct reference
//! solver and the black-box multigrid are interchangeable.

pub mod direct;

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

    /// A short name for reports ("direct-lu", "multigrid").
    fn name(&self) -> &'static str;
}

/// The linear solver called `name` in case files: "direct" or "multigrid".
pub fn by_name(name: &str) -> Result<Box<dyn LinearSolver>, String> {
    match name {
        "direct" => Ok(Box::new(direct::DirectLu::new())),
        _ => Err(format!("linear solver '{name}': expected \"direct\"")),
    }
}
