//! The inexact Picard iteration shared by the 2D ([`crate::elliptic::poisson2d`]) and the volume
//! ([`crate::elliptic::poisson3d`]) grid systems: beyond the paper's fixed number of exactly
//! solved steps, each step's linear systems are solved only as accurately as the step needs
//! (`forcing`), in correction form (`solve_corrections`), and the iteration stops on an
//! a-posteriori estimate of its error (`error_estimate`) instead of one confirming step
//! more. `iterate` runs the steps; the system (assembly, solver, grid) is the caller's.

use crate::elliptic::anderson::Anderson;
use crate::solve::{LinearSolver, SolveControl, SolveError, SolveInfo};
use crate::{Error, Result};
use rayon::prelude::*;

/// Picard iteration parameters.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PicardParams {
    /// Stop when the Picard error, relative to the domain diameter, is below this: the
    /// largest node update of the last step, or, once the steps contract (ratio ρ < 0.5),
    /// its a-posteriori estimate ρ/(1 − ρ) · update + the step's linear error
    /// (`picard::error_estimate`). Default 1e-10.
    pub tolerance: f64,
    /// At most this many Picard steps. Default 200.
    pub max_steps: usize,
    /// Relative residual reduction asked of each linear solve (iterative solvers). Default 1e-10.
    pub linear_tolerance: f64,
    /// At most this many cycles per linear solve (iterative solvers). Default 100.
    pub linear_max_iter: usize,
    /// Forcing term of the inexact Picard iteration (iterative solvers): a step's linear
    /// system is solved only to the relative residual
    /// `η = clamp(0.5 ρ, linear_tolerance, linear_forcing)`, ρ = the last ratio of
    /// successive Picard updates (the observed Picard contraction), like an inexact Newton
    /// forcing term: a linear error much below the Picard error would be wasted. The
    /// fixed point is unchanged (the linear error is relative to the Picard residual, which
    /// vanishes there). 0 solves every step to `linear_tolerance`. Default 0.1. Nested
    /// volume solves with the multigrid use 3 ρ instead of 0.5 ρ
    /// ([`crate::elliptic::nested3d::MULTIGRID_FORCING_RATIO`]).
    pub linear_forcing: f64,
    /// Nested iteration (`crate::elliptic::nested`): solve on coarser grids first. `None` (default)
    /// means on with the multigrid solver, off with the direct one; volume blocks
    /// (`crate::elliptic::nested3d::nested_for3`) also default to on with Bi-CGSTAB.
    pub nested: Option<bool>,
    /// Depth of the Anderson acceleration of the Picard steps ([`crate::elliptic::anderson`]):
    /// the number of earlier steps combined; 0 is plain Picard. Default 0: measured on the
    /// paper's multi-block cases (`examples/bench_multiblock.rs`) depth 5 saves 10–25 % of
    /// the fine Picard steps but not wall-clock time (the stop can no longer use the
    /// contraction estimate, and the mixing costs ~6 % of a step).
    pub anderson: usize,
    /// The nonlinear iteration asked for: Picard steps [43, 44] or Newton–Krylov steps
    /// ([`crate::elliptic::newton`]; planar, periodic and minimal-surface blocks). `None`
    /// (default): Newton on planar and periodic blocks, Picard on minimal surfaces or if
    /// `anderson` > 0; resolved by [`PicardParams::iteration`]. Volume blocks always take
    /// Picard steps.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nonlinear: Option<Nonlinear>,
}

/// The nonlinear iteration of a grid system (`[solver] nonlinear`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Nonlinear {
    /// Picard iteration [43, 44]: the metric coefficients frozen at each step (the default
    /// of a report read without the field; as a setting, see [`PicardParams::iteration`]).
    #[default]
    Picard,
    /// Newton's method on [24], GMRES preconditioned by the Picard operator's solver
    /// ([`crate::elliptic::newton`]): the default of planar and periodic blocks.
    Newton,
}

impl<'de> serde::Deserialize<'de> for Nonlinear {
    /// "picard" or "newton"; any other value is refused naming the key (the table is
    /// flattened into `[solver]`, whose error would otherwise only list the variants).
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        match s.as_str() {
            "picard" => Ok(Nonlinear::Picard),
            "newton" => Ok(Nonlinear::Newton),
            _ => Err(serde::de::Error::custom(format!(
                "nonlinear = \"{s}\": must be \"picard\" or \"newton\""
            ))),
        }
    }
}

impl Default for PicardParams {
    fn default() -> Self {
        PicardParams {
            tolerance: 1e-10,
            max_steps: 200,
            linear_tolerance: 1e-10,
            linear_max_iter: 100,
            linear_forcing: 0.1,
            nested: None,
            anderson: 0,
            nonlinear: None,
        }
    }
}

/// Most Picard steps, linear iterations per solve, and Anderson depth a setting may ask for.
pub const MAX_STEPS: usize = 100_000;
/// Largest Anderson depth accepted.
pub const MAX_ANDERSON: usize = 50;

impl PicardParams {
    /// Checks every setting (finite and in range); the message names the key and its value.
    ///
    /// # Errors
    /// The message for the first bad setting.
    pub fn check(&self) -> std::result::Result<(), String> {
        let open01 = |key: &str, v: f64| {
            if v.is_finite() && v > 0.0 && v < 1.0 {
                Ok(())
            } else {
                Err(format!("{key} = {v}: must be a number in (0, 1)"))
            }
        };
        let count = |key: &str, v: usize, lo: usize, hi: usize| {
            if (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(format!("{key} = {v}: must be {lo} to {hi}"))
            }
        };
        open01("tolerance", self.tolerance)?;
        open01("linear_tolerance", self.linear_tolerance)?;
        count("max_steps", self.max_steps, 1, MAX_STEPS)?;
        count("linear_max_iter", self.linear_max_iter, 1, MAX_STEPS)?;
        count("anderson", self.anderson, 0, MAX_ANDERSON)?;
        if self.anderson > 0 && self.nonlinear == Some(Nonlinear::Newton) {
            return Err(format!(
                "anderson = {}: accelerates Picard steps only, and nonlinear = \"newton\" is set: \
                 remove nonlinear (anderson alone selects Picard steps) or set anderson = 0",
                self.anderson
            ));
        }
        let f = self.linear_forcing;
        if !(f.is_finite() && (0.0..1.0).contains(&f)) {
            return Err(format!(
                "linear_forcing = {f}: must be a number in [0, 1) (0: no forcing)"
            ));
        }
        Ok(())
    }

    /// The nonlinear iteration of a 2D block whose grid has `coordinates` coordinates (2:
    /// planar, also periodic; 3: a minimal surface): the one set in `nonlinear`, else Picard
    /// steps if Anderson acceleration is asked for (`anderson` > 0) or on a minimal surface,
    /// else Newton–Krylov steps. The one place the default is resolved; volume blocks
    /// ignore it (always Picard). Measured side by side (README "Nonlinear solve";
    /// `examples/bench_multiblock.rs`, `examples/bench_grid.rs --newton`): on planar blocks
    /// Newton wins or ties on every bench case but the NLR 7301 flap (~10 % slower), on the
    /// Scherk minimal surface it costs 1.5–1.8× Picard's work units at 129² to 513².
    pub fn iteration(&self, coordinates: usize) -> Nonlinear {
        match self.nonlinear {
            Some(n) => n,
            None if self.anderson > 0 || coordinates != 2 => Nonlinear::Picard,
            None => Nonlinear::Newton,
        }
    }

    /// Whether nested iteration is used with the linear solver called `solver_name`.
    pub fn nested_for(&self, solver_name: &str) -> bool {
        self.nested.unwrap_or(solver_name == "multigrid")
    }
}

/// A Picard step whose update (relative to the diameter) was below this changed the operator
/// so little that the next one is prepared by [`crate::solve::LinearSolver::update`] (multigrid keeps its
/// coarse levels) instead of a full setup.
pub const SMALL_CHANGE: f64 = 1e-5;

/// Where a Picard solve runs decides three of its rules: a coarse level of nested iteration
/// also stops at a fraction of its first update, and the volume multigrid's nested solves
/// ([`crate::elliptic::nested3d`]) force their linear solves more loosely and keep the
/// multigrid's coarse levels over larger changes of the operator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rules {
    /// Stop (converged) once the update falls below this times the first update; 0: off.
    pub relative_stop: f64,
    /// The first update of the next coarser level of nested iteration (0: none or not used):
    /// where this level's first update is more than [`PREDICTED_SHARE`] of it, the next
    /// level's start will be as far off, and `relative_stop` is raised in proportion
    /// (`stop::stop_threshold`).
    pub coarser_first: f64,
    /// The ratio c of the forcing term to the observed Picard contraction ([`forcing`]).
    pub forcing_ratio: f64,
    /// After a step whose update (relative to the diameter) was below this the linear solver
    /// is only updated ([`LinearSolver::update`]), not set up afresh.
    pub small_change: f64,
}

impl Rules {
    /// The rules of every Picard solve but the volume multigrid's nested ones, stopping at
    /// `relative_stop` times the first update too (0: off).
    pub(crate) fn stop(relative_stop: f64) -> Self {
        Rules {
            relative_stop,
            coarser_first: 0.0,
            forcing_ratio: FORCING_RATIO,
            small_change: SMALL_CHANGE,
        }
    }
}

/// A generated grid with the history of its solve.
#[derive(Clone, Debug)]
pub struct Solved<G> {
    pub grid: G,
    pub picard: PicardInfo,
}

/// A generated 2D block (planar, D = 2, or a minimal surface, D = 3).
pub type BlockResult<const D: usize> = Solved<crate::grid::Grid2<D>>;

/// A generated volume block.
pub type VolumeResult = Solved<crate::grid::Grid3>;

/// What the system's part of one Picard step returns to [`iterate`].
pub(crate) struct StepWork {
    /// Residual of the grid equations at the iterate the step started from.
    pub residual: f64,
    /// The linear solves of the step, one per coordinate.
    pub solves: Vec<std::result::Result<SolveInfo, SolveError>>,
    /// Largest correction relative to the diameter (NaN if the grid became non-finite).
    pub update: f64,
    /// True if this was a Newton step.
    pub newton: bool,
    /// [`PicardStep::linear_error`].
    pub linear_error: Option<f64>,
}

/// One grid system's part of a Picard step: the 2D system [24]
/// ([`crate::elliptic::poisson2d`]) or the volume system [86] ([`crate::elliptic::poisson3d`]),
/// each holding its iterate, operator, right-hand sides and linear solver.
pub(crate) trait System {
    /// The operator of the linear systems (`Stencil9` or `Stencil19`).
    type Op;
    /// Assembles the operator at the current iterate and the residuals b − A x (interior
    /// numbering); returns the residual of the grid equations relative to the diameter.
    fn evaluate(&mut self) -> f64;
    /// The linear solver, the operator, the residuals and the corrections.
    fn linear(&mut self) -> Linear<'_, Self::Op>;
    /// Adds the corrections to the iterate; returns `largest` (the largest correction)
    /// relative to the diameter, NaN if the grid became non-finite.
    fn apply(&mut self, largest: f64) -> f64;
    /// The length that updates are relative to (the domain diameter).
    fn diameter(&self) -> f64;
    /// Sets the linear solver up for the operator of the last `evaluate` (only updates it
    /// if `small`). Default: [`prepare`] from `linear()`; a system may instead let the solver
    /// take its operator over ([`LinearSolver::adopt`]) and take it back at the next
    /// `evaluate`.
    fn prepare(&mut self, small: bool) -> std::result::Result<(), SolveError> {
        let lin = self.linear();
        prepare(lin.solver, lin.a, small)
    }
}

/// The linear part of a [`System`], borrowed for one step.
pub(crate) struct Linear<'s, A> {
    pub solver: &'s mut dyn LinearSolver<A>,
    pub a: &'s A,
    pub r: &'s [Vec<f64>],
    pub u: &'s mut [Vec<f64>],
    /// Per coordinate, the solver of its own operator, if not `solver` (the coordinate
    /// normal to a volume's symmetry faces, [`crate::elliptic::symmetry3d`]).
    pub others: [Option<&'s dyn LinearSolver<A>>; 3],
}

impl<'s, A> Linear<'s, A> {
    pub fn new(
        solver: &'s mut dyn LinearSolver<A>,
        a: &'s A,
        r: &'s [Vec<f64>],
        u: &'s mut [Vec<f64>],
    ) -> Self {
        Linear {
            solver,
            a,
            r,
            u,
            others: [None; 3],
        }
    }

    /// The same with `others` (see the field).
    pub fn with_others(self, others: [Option<&'s dyn LinearSolver<A>>; 3]) -> Self {
        Linear { others, ..self }
    }
}

/// Sets `solver` up for the operator `a`, or only updates it if `small`.
pub(crate) fn prepare<A>(
    solver: &mut dyn LinearSolver<A>,
    a: &A,
    small: bool,
) -> std::result::Result<(), SolveError> {
    if small {
        solver.update(a)
    } else {
        solver.setup(a)
    }
}

/// The checks of a Picard solve's input shared by 2D and 3D: the grid has at least three
/// nodes each way (`small` is the message if not), the control functions are of its size and
/// finite.
pub(crate) fn check_input(
    place: &str,
    large_enough: bool,
    small: &str,
    same_size: bool,
    finite: bool,
) -> Result<()> {
    if !large_enough {
        return Err(Error::input(place, small));
    }
    if !same_size {
        return Err(Error::input(
            place,
            "control functions and grid differ in size",
        ));
    }
    if !finite {
        return Err(Error::input(
            place,
            "the algebraic transformation is degenerate (non-finite control functions)",
        ));
    }
    Ok(())
}

/// Runs the Picard iteration of `sys` ([`iterate`]) and evaluates the final residual. Returns
/// the report and the shortest time (seconds) of one evaluation (assembly + residual): the
/// work unit of nested iteration.
pub(crate) fn run<S: System>(
    sys: &mut S,
    params: &PicardParams,
    rules: Rules,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<(PicardInfo, f64)> {
    let mut eval_secs = f64::INFINITY;
    let mut evaluate = |sys: &mut S| {
        let t0 = std::time::Instant::now();
        let res = sys.evaluate();
        eval_secs = eval_secs.min(t0.elapsed().as_secs_f64());
        res
    };
    params.check().map_err(|m| Error::input(place, m))?;
    let diam = sys.diameter();
    let mut anderson = (params.anderson > 0).then(|| Anderson::new(params.anderson));
    // largest applied step (relative) of the last step: the operator changed that much
    let mut moved = f64::INFINITY;
    let (history, converged) = iterate(
        params,
        rules,
        place,
        |small, ctl, threshold| {
            let residual = evaluate(&mut *sys);
            let small = small && moved < rules.small_change;
            sys.prepare(small).map_err(|source| Error::Solve {
                place: place.to_string(),
                source,
            })?;
            let lin = sys.linear();
            let (solves, largest) =
                solve_corrections_with(&*lin.solver, &lin.others, lin.u, lin.r, ctl);
            moved = largest / diam;
            if let Some(aa) = anderson.as_mut() {
                // the step that may stop the iteration is a plain Picard step: the error
                // estimate is that of a Picard step
                if largest / diam > threshold {
                    moved = aa.mix(lin.u, largest) / diam;
                }
            }
            Ok(StepWork {
                residual,
                solves,
                update: sys.apply(largest),
                newton: false,
                linear_error: None,
            })
        },
        progress,
    )?;
    let final_residual = evaluate(&mut *sys);
    let info = info(
        Nonlinear::Picard,
        sys.linear().solver.name(),
        params,
        history,
        converged,
        final_residual,
    );
    Ok((info, eval_secs))
}

/// Runs Picard steps until the error estimate falls below the tolerance (or below
/// `rules.relative_stop` times the first update, a coarse level of nested iteration) or
/// `params.max_steps` are done. `step(small, ctl)` does one step's work: evaluate the
/// operator at the current iterate, set up the linear solver (only update it if `small`: the
/// last update was below `rules.small_change`), solve the corrections to `ctl` (forced by
/// `rules.forcing_ratio`) and apply them.
/// `progress` sees every step. Returns the history and whether the iteration converged; a
/// failed linear solve or a non-finite update is an error naming `place`.
pub(crate) fn iterate(
    params: &PicardParams,
    rules: Rules,
    place: &str,
    mut step: impl FnMut(bool, &SolveControl, f64) -> Result<StepWork>,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<(Vec<PicardStep>, bool)> {
    let mut history: Vec<PicardStep> = Vec::new();
    for step_no in 0..params.max_steps {
        let small = history
            .last()
            .is_some_and(|last| last.update < rules.small_change);
        let ctl = SolveControl {
            rel_tol: forcing(params, &history, rules.forcing_ratio),
            max_iter: params.linear_max_iter,
        };
        let threshold = if history.is_empty() {
            f64::INFINITY
        } else {
            stop_threshold(params, &history, &rules)
        };
        let work = step(small, &ctl, threshold)?;
        let mut record = step_record(work.residual, work.solves, place)?;
        record.update = work.update;
        record.newton = work.newton;
        record.linear_error = work.linear_error;
        progress(step_no + 1, &record);
        history.push(record);
        if !work.update.is_finite() {
            return Err(Error::Solve {
                place: place.to_string(),
                source: SolveError::Diverged(f64::NAN),
            });
        }
        // With Anderson's steps the ratio of successive corrections is not the Picard
        // contraction: the stop needs the correction itself below the threshold (the step
        // is then a plain Picard step, whose error is below its correction for a
        // contraction under 1/2).
        // A coarse level of nested iteration keeps the contraction bound: it stops on a
        // fraction of its first update, and a level one Newton step shorter predicts the
        // next one worse (folding_start: the fine level's first update doubled).
        let estimate = if params.anderson > 0 {
            history.last().map_or(f64::INFINITY, |h| h.update)
        } else if rules.relative_stop > 0.0 {
            contraction_estimate(&history)
        } else {
            error_estimate(&history)
        };
        if estimate < stop_threshold(params, &history, &rules) {
            return Ok((history, true));
        }
    }
    Ok((history, false))
}

/// From this many unknowns the coordinates of a Picard step are solved one after the other
/// (each solve parallel inside: the multigrid's smoothers, residuals and transfers), so that
/// one cycle workspace serves them all instead of one per coordinate (#16: 32 bytes per node
/// in 2D, ~47 per node and coordinate in 3D). Below, the coordinates run concurrently,
/// which keeps both cores busy on grids too small for the solver's own parallelism.
pub(crate) const ONE_AT_A_TIME: usize = 1 << 18;

/// The corrections of one Picard step in correction form, A δ = b − A x_k from δ₀ = 0, one
/// coordinate per rayon task with the operator's one setup of `solver`; returns the
/// solves' results and the largest |δ|. The correction form keeps the cycles' round-off
/// relative to δ instead of x: near convergence the residual of x_k is itself at round-off
/// level, and a solve for x would stagnate.
pub(crate) fn solve_corrections<A>(
    solver: &dyn LinearSolver<A>,
    u: &mut [Vec<f64>],
    r: &[Vec<f64>],
    ctl: &SolveControl,
) -> (Vec<std::result::Result<SolveInfo, SolveError>>, f64) {
    solve_corrections_with(solver, &[], u, r, ctl)
}

/// [`solve_corrections`], coordinate c with `others[c]` instead of `solver` where given.
pub(crate) fn solve_corrections_with<A>(
    solver: &dyn LinearSolver<A>,
    others: &[Option<&dyn LinearSolver<A>>],
    u: &mut [Vec<f64>],
    r: &[Vec<f64>],
    ctl: &SolveControl,
) -> (Vec<std::result::Result<SolveInfo, SolveError>>, f64) {
    let one = |(c, (uc, rc)): (usize, (&mut Vec<f64>, &Vec<f64>))| {
        uc.fill(0.0);
        others
            .get(c)
            .copied()
            .flatten()
            .unwrap_or(solver)
            .solve(rc, uc, ctl)
    };
    let infos = if u.first().map_or(0, Vec::len) >= ONE_AT_A_TIME {
        u.iter_mut().zip(r.iter()).enumerate().map(one).collect()
    } else {
        u.par_iter_mut()
            .zip(r.par_iter())
            .enumerate()
            .map(one)
            .collect()
    };
    let largest = u
        .iter()
        .map(|uc| {
            uc.par_iter()
                .fold(|| 0.0f64, |m, v| m.max(v.abs()))
                .reduce(|| 0.0, f64::max)
        })
        .fold(0.0f64, f64::max);
    (infos, largest)
}

/// The record of one Picard step that started at residual `residual`, from the per-coordinate
/// results of its linear solves (the first failure is the error, naming `place`); the update
/// is filled in by the caller.
fn step_record(
    residual: f64,
    infos: Vec<std::result::Result<SolveInfo, SolveError>>,
    place: &str,
) -> Result<PicardStep> {
    let mut step = PicardStep {
        update: 0.0,
        residual,
        linear_iterations: Vec::with_capacity(infos.len()),
        linear_residual: Vec::with_capacity(infos.len()),
        newton: false,
        linear_error: None,
    };
    for info in infos {
        let info = info.map_err(|source| Error::Solve {
            place: place.to_string(),
            source,
        })?;
        step.linear_iterations.push(info.iterations);
        step.linear_residual
            .push(info.residual_history.last().copied().unwrap_or(0.0));
    }
    Ok(step)
}

mod history;
pub(crate) use history::{append, info};
pub use history::{Passes, PicardInfo, PicardStep};
mod stop;
use stop::{contraction_estimate, stop_threshold};
pub(crate) use stop::{error_estimate, forcing, FORCING_RATIO};

#[cfg(test)]
mod tests;
