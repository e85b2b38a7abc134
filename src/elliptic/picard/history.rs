//! The record of a Picard (or Newton–Krylov) iteration: its steps, what it converged to, and
//! for volume blocks the correction passes it went through ([`Passes`]).

use super::{Nonlinear, PicardParams};

/// One Picard step of the history.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PicardStep {
    /// Largest node update of this step, relative to the domain diameter.
    pub update: f64,
    /// Residual of [24] at the iterate this step started from (see [`crate::elliptic::poisson2d::residual`]).
    pub residual: f64,
    /// Linear iterations (cycles) per coordinate.
    pub linear_iterations: Vec<usize>,
    /// Final relative linear residual per coordinate (0 for a direct solve).
    pub linear_residual: Vec<f64>,
    /// True for a Newton step ([`crate::elliptic::newton`]); absent for a Picard step.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub newton: bool,
    /// The largest error of this Newton step's linear solve, relative to the diameter, where
    /// it was measured (one preconditioner application to the solve's final residual: the
    /// step the stop test would otherwise end on, `error_estimate`); absent elsewhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub linear_error: Option<f64>,
}

/// What the Picard iteration did: part of every result and report.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PicardInfo {
    /// The nonlinear iteration that ran ([`PicardParams::iteration`]; volume blocks always
    /// "picard"). Newton's iteration takes Picard steps while they contract fast.
    #[serde(default)]
    pub nonlinear: Nonlinear,
    /// Depth of the Anderson acceleration of the Picard steps; absent (0) without.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub anderson: usize,
    /// The linear solver used.
    pub linear_solver: String,
    /// Steps taken.
    pub steps: usize,
    /// True if the update fell below the tolerance.
    pub converged: bool,
    /// The tolerance asked for.
    pub tolerance: f64,
    /// Residual of [24] at the final grid.
    pub final_residual: f64,
    /// Cost of the whole grid generation (nested levels included) in work units: one WU is
    /// the time of one evaluation of the residual of [24] on the finest grid, measured in the
    /// same run. Absent where it was not measured.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub work_units: Option<f64>,
    /// Picard steps on each coarser level of a nested-iteration solve, coarsest first.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub coarse_steps: Vec<usize>,
    /// Per-step history.
    pub history: Vec<PicardStep>,
    /// The solve whose grid this one started from, reported with it: step 1 of the
    /// orthogonality of Section 2.4 (straight-line control functions) before the solve with
    /// the blended ones. Its steps are not in `steps` and `history`; its time is in
    /// `work_units` where those were measured.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first: Option<Box<PicardInfo>>,
    /// A volume block with a wall or orthogonal faces: its correction passes
    /// ([`crate::elliptic::orthogonal3d`]), whose solves are in `history`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub passes: Option<Passes>,
}

/// The correction passes of a volume block (`crate::elliptic::orthogonal3d`): how many ran
/// and whose corrected control functions the final grid keeps.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Passes {
    /// Passes run after the uncorrected solve (pass 0), each a solve with corrected control
    /// functions.
    pub run: usize,
    /// The pass the final grid keeps (0: the uncorrected grid).
    pub kept: usize,
    /// Why the final grid is not the last pass's: a later pass folded the grid or its solve
    /// failed, and the grid went back to the fold-free pass `kept` (the one closest to the
    /// orthogonality asked for). Absent when the last pass was kept.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fell_back: Option<String>,
}

impl PicardInfo {
    /// Appends the history of a later solve of the same grid (a correction pass).
    pub fn append(&mut self, later: PicardInfo) {
        self.steps += later.steps;
        self.history.extend(later.history);
        self.converged = later.converged;
        self.final_residual = later.final_residual;
        if let (Some(a), Some(b)) = (self.work_units, later.work_units) {
            self.work_units = Some(a + b);
        }
    }
}

/// Appends `step` to the history of the solves so far, if any.
pub(crate) fn append(all: &mut Option<PicardInfo>, step: PicardInfo) {
    match all {
        None => *all = Some(step),
        Some(a) => a.append(step),
    }
}

/// Serde's test for an absent count.
fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// The report of an iteration by [`super::iterate`] (Picard's `nonlinear` iteration, with the
/// Anderson depth of `params`, or Newton's) with the linear solver `solver`, ending at
/// residual `final_residual` (work units and coarse levels are filled in by nested iteration).
pub(crate) fn info(
    nonlinear: Nonlinear,
    solver: &str,
    params: &PicardParams,
    history: Vec<PicardStep>,
    converged: bool,
    final_residual: f64,
) -> PicardInfo {
    PicardInfo {
        nonlinear,
        anderson: match nonlinear {
            Nonlinear::Picard => params.anderson,
            Nonlinear::Newton => 0,
        },
        linear_solver: solver.to_string(),
        steps: history.len(),
        converged,
        tolerance: params.tolerance,
        final_residual,
        work_units: None,
        coarse_steps: Vec::new(),
        history,
        first: None,
        passes: None,
    }
}
