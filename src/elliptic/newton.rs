//! Newton–Krylov for the grid systems ([`crate::elliptic::poisson2d`]): Newton's method on the
//! discrete system [24], each correction solved by GMRES ([`crate::solve::gmres`])
//! right-preconditioned by the Picard operator's linear solver (one multigrid cycle per
//! coordinate), inside the same step loop, forcing term and stopping test as the Picard
//! iteration ([`crate::elliptic::picard`]).
//!
//! # Why
//! On stretched O- and C-grids the Picard steps contract by only ~0.4 each, even with exact
//! linear solves: the metric coefficients P, Q, R that Picard freezes carry the slow modes.
//! Newton differentiates them too (`elliptic::jacobian2d`: J = A − G, G couples the
//! coordinates); with the Picard operator A as preconditioner the Krylov method only has to
//! resolve A⁻¹G, whose few large eigenvalues are exactly the modes Picard is slow on.
//!
//! # A step
//! 1. Evaluate A, b and r = b − A x at the iterate (reused from the last line search).
//! 2. Linearise (the coupling G) and set up the preconditioner: a multigrid per coordinate
//!    on J's diagonal block A − G_cc. It is kept while the Krylov solves converge fast
//!    ([`KEEP_RATE`]) and A's diagonal moves little ([`KEEP_CHANGE`]); where the diagonal
//!    moved, a kept preconditioner is refreshed rather than set up again (its fine level at
//!    the new iterate, its coarse levels kept: dented square at 1025², the same fine steps and
//!    GMRES iterations, the second step's setup 0.45 → 0.13 s).
//! 3. Solve J δ = r by FGMRES (from zero: no product for the first residual) to the forcing term
//!    (`forcing`: Eisenstat–Walker), rows scaled by A's diagonal, so that the Krylov
//!    residual weighs every node as the reported residual does.
//! 4. Line search: accept x + λδ for λ = 1, then ½, if the residual of [24] (max over nodes,
//!    relative, as reported) falls by the Armijo factor 1 − 10⁻⁴ λ; the evaluation at the
//!    accepted point is the next step's. Otherwise go back to x and take the Picard step
//!    instead (A δ = r with the solver already set up; the step is then a Picard step).
//!
//! Steps start as Picard steps, and Newton steps begin once two successive Picard updates
//! contract by more than [`SLOW_PICARD`]: where Picard converges fast (smooth domains, a
//! nested level predicted well by the coarser one) its steps are cheaper than Newton's
//! (measured at 1025²: the same step counts, ~1.5× the work units), where it is slow
//! (stretched O- and C-grids, ~0.4 per step) Newton needs a third of the steps. The finest
//! level of nested iteration starts with Newton steps if the level below it took them
//! (`newton_now`, `crate::elliptic::nested`). After a rejected Newton step, Picard steps follow
//! until the updates are ten times smaller.
//!
//! # Stop
//! `picard::error_estimate`: the last update, or once the updates contract, the
//! a-posteriori bound of a contraction with the larger of the last two ratios of successive
//! updates plus the step's linear error; after two Newton steps that contract, on the finest
//! level, the bound of quadratic convergence u (r² + η) / (1 − r) with r the last ratio where
//! that is smaller (it saves the confirming step: NACA0012 O-grid at 4 × 257², steps 1 and 3
//! of the orthogonality, fine Newton steps 5 + 5 → 4 + 4 or 4 + 5 per block). Where that
//! bound would stop, the step's linear error is measured (the preconditioner applied to the
//! Krylov solve's final residual: 1.8e-10 where η u said 1.9e-11, folded start at 1025² with
//! looser coarse levels) and replaces η u, so the stop stays honest; this costs one
//! preconditioner application per solve.

use crate::elliptic::picard::{self, PicardInfo, PicardParams, PicardStep, StepWork, System};
use crate::solve::gmres::{gmres, GmresWorkspace};
use crate::solve::{SolveControl, SolveError, SolveInfo};
use crate::{Error, Result};
use rayon::prelude::*;
use std::sync::Mutex;

/// After a rejected Newton step, Picard steps are taken until the update is below a tenth of
/// the last one or of ten times this (relative to the diameter).
pub const NEWTON_BELOW: f64 = 1e-2;

/// Newton steps begin once a Picard update is more than this times the one before (module
/// docs).
pub const SLOW_PICARD: f64 = 0.2;

/// At most this many GMRES iterations (preconditioner cycles per coordinate) per Newton step;
/// also the restart length, so the Krylov basis holds at most this many vectors.
pub const KRYLOV_MAX: usize = 12;

/// A preconditioner whose Krylov solve converged at this rate per iteration or better is
/// kept for the next Newton step (its setup costs about as much as a Krylov iteration);
/// otherwise it is set up again at the next iterate.
pub const KEEP_RATE: f64 = 0.25;

/// The preconditioner is set up again when the operator's diagonal changed by more than
/// this fraction at some node since its setup (the grid moved by a sizeable part of a cell).
pub const KEEP_CHANGE: f64 = 0.1;

/// Armijo's sufficient decrease: the residual must fall by at least this fraction of the
/// step length λ.
const ARMIJO: f64 = 1e-4;

/// What Newton's method needs of a grid system beyond a Picard step.
pub(crate) trait NewtonSystem: System + Sync {
    /// Coordinates (2 for a planar block, 3 on a surface or in a volume).
    fn coordinates(&self) -> usize;
    /// Unknowns per coordinate (interior nodes).
    fn nodes(&self) -> usize;
    /// The Jacobian at the current iterate; called after `evaluate`.
    fn linearize(&mut self);
    /// `out = J v`, the coordinates one after the other.
    fn apply_jacobian(&self, v: &[f64], out: &mut [f64]);
    /// The diagonal of the Picard operator at each interior node.
    fn diagonal(&self, out: &mut [f64]);
    /// Sets up the preconditioner of the Newton correction at the current iterate (after
    /// `linearize`): the linear solvers for the diagonal blocks A − G_cc of J.
    fn setup_preconditioner(&mut self) -> std::result::Result<(), SolveError>;
    /// The preconditioner of the last `setup_preconditioner` brought to the current iterate
    /// where that is cheaper than a new setup (multigrid: the fine level's operator and line
    /// factors refreshed, the transfers and coarse levels kept,
    /// [`crate::solve::LinearSolver::update`]). Default: a new setup.
    fn refresh_preconditioner(&mut self) -> std::result::Result<(), SolveError> {
        self.setup_preconditioner()
    }
    /// `out ≈ J⁻¹ v` by the preconditioner (block Gauss–Seidel over the coordinates, one
    /// cycle per block); `v` is overwritten.
    fn precondition(&self, v: &mut [f64], out: &mut [f64]) -> std::result::Result<(), SolveError>;
    /// The linear solver was set up for the Picard operator A (a Picard step).
    fn picard_ready(&mut self);
    /// Sets the corrections to `f` times the stacked `delta` (the coordinates one after the
    /// other) and applies them ([`System::apply`]); returns its result.
    fn apply_scaled(&mut self, delta: &[f64], f: f64, largest: f64) -> f64 {
        let n = self.nodes();
        for (c, uc) in self.linear().u.iter_mut().enumerate() {
            uc.par_iter_mut()
                .zip(&delta[c * n..(c + 1) * n])
                .for_each(|(u, d)| *u = f * d);
        }
        self.apply(largest)
    }
}

/// Buffers of the Newton steps of one solve, the coordinates one after the other.
struct Buffers {
    /// The residual r at the base iterate (scaled rows for GMRES).
    rhs: Vec<f64>,
    /// The Newton correction.
    delta: Vec<f64>,
    /// 1 / diagonal of A per node.
    scale: Vec<f64>,
    /// `scale` when the preconditioner was set up.
    setup_scale: Vec<f64>,
    /// Scratch of the preconditioner.
    tmp: Vec<f64>,
    krylov: GmresWorkspace,
}

/// Runs the Newton–Krylov iteration of `sys` (module docs), with Newton steps from the first
/// if `newton_now`; as [`picard::run`] returns the report and the shortest time (seconds) of
/// one evaluation.
pub(crate) fn run<S: NewtonSystem>(
    sys: &mut S,
    params: &PicardParams,
    rules: picard::Rules,
    newton_now: bool,
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
    let (d, n) = (sys.coordinates(), sys.nodes());
    // allocated at the first Newton step: a solve whose steps all stay Picard steps (smooth
    // domains) holds no more than the Picard iteration
    let mut buffers: Option<Buffers> = None;
    let mut moved = f64::INFINITY;
    // the residual of the current iterate if the last line search evaluated it
    let mut cached: Option<f64> = None;
    let mut last_update = f64::INFINITY;
    let mut prev_update = f64::INFINITY;
    // the update of the last step before a rejected Newton step: Picard steps until the
    // updates are ten times smaller
    let mut rejected_at: Option<f64> = None;
    // Picard steps were seen to contract slowly: Newton steps from now on
    let mut slow = newton_now;
    // the preconditioner is set up for a Newton step (kept until a Picard step or a slow
    // Krylov solve)
    let mut ready = false;
    // the last step was a Newton step (the stop's quadratic bound needs two)
    let mut prev_newton = false;
    let solve_error = |source: SolveError| Error::Solve {
        place: place.to_string(),
        source,
    };
    let (history, converged) = picard::iterate(
        params,
        rules,
        place,
        |small, ctl, threshold| {
            let residual = match cached.take() {
                Some(r) => r,
                None => evaluate(&mut *sys),
            };
            slow = slow || (prev_update.is_finite() && last_update > SLOW_PICARD * prev_update);
            let newton = slow && rejected_at.is_none_or(|u| last_update < 0.1 * u);
            if newton {
                rejected_at = None;
                let buf = buffers.get_or_insert_with(|| Buffers {
                    rhs: vec![0.0; d * n],
                    delta: vec![0.0; d * n],
                    scale: vec![0.0; n],
                    setup_scale: vec![0.0; n],
                    tmp: vec![0.0; d * n],
                    krylov: GmresWorkspace::default(),
                });
                sys.linearize();
                let ctl = SolveControl {
                    rel_tol: forcing(params, prev_update, last_update),
                    ..*ctl
                };
                let ctl = &ctl;
                scaled_residual(sys, buf);
                let fresh = !ready || changed(&buf.scale, &buf.setup_scale) > KEEP_CHANGE;
                if fresh {
                    // a kept preconditioner whose operator moved: its coarse levels still
                    // serve (dented square 1025²: the same GMRES iterations, a third of the
                    // setup's time)
                    if ready {
                        sys.refresh_preconditioner().map_err(solve_error)?;
                    } else {
                        sys.setup_preconditioner().map_err(solve_error)?;
                    }
                    buf.setup_scale.copy_from_slice(&buf.scale);
                }
                let mut info = krylov(sys, buf, ctl, true).map_err(solve_error)?;
                if !info.converged && !fresh {
                    // the kept preconditioner is too far from J: set it up at this iterate
                    // and go on from the correction so far
                    sys.setup_preconditioner().map_err(solve_error)?;
                    buf.setup_scale.copy_from_slice(&buf.scale);
                    let done = info.residual_history.last().copied().unwrap_or(1.0);
                    let more = SolveControl {
                        rel_tol: (ctl.rel_tol / done).min(1.0),
                        ..*ctl
                    };
                    let next = krylov(sys, buf, &more, false).map_err(solve_error)?;
                    info.iterations += next.iterations;
                    info.residual_history
                        .extend(next.residual_history.iter().map(|r| r * done));
                    info.converged = next.converged;
                }
                // keep the preconditioner while it makes the Krylov solve fast
                let rate = info
                    .residual_history
                    .last()
                    .map_or(1.0, |r| r.powf(1.0 / info.iterations.max(1) as f64));
                ready = info.converged && rate <= KEEP_RATE;
                let largest = max_abs(&buf.delta);
                for lambda in [1.0, 0.5] {
                    let update = sys.apply_scaled(&buf.delta, lambda, lambda * largest);
                    if update.is_finite() {
                        let trial = evaluate(&mut *sys);
                        if trial <= (1.0 - ARMIJO * lambda) * residual || update <= params.tolerance
                        {
                            cached = Some(trial);
                            moved = update;
                            // where the stop's quadratic bound would end the finest level on
                            // η u, the linear error itself (picard::error_estimate)
                            let r = update / last_update;
                            let eta = info.residual_history.last().copied().unwrap_or(0.0);
                            let linear_error = if rules.relative_stop == 0.0
                                && prev_newton
                                && lambda == 1.0
                                && r < 0.5
                                && update * (r * r + eta) / (1.0 - r) < threshold
                            {
                                Some(linear_error(&*sys, buf).map_err(solve_error)?)
                            } else {
                                None
                            };
                            prev_update = last_update;
                            last_update = update;
                            prev_newton = true;
                            return Ok(StepWork {
                                residual,
                                solves: vec![Ok(info)],
                                update,
                                newton: true,
                                linear_error,
                            });
                        }
                    }
                    sys.apply_scaled(&buf.delta, -lambda, lambda * largest);
                }
                // rejected: a Picard step from the base iterate instead (A, r and the
                // solver at the base iterate again)
                rejected_at = Some(last_update.min(10.0 * NEWTON_BELOW));
                evaluate(&mut *sys);
            }
            ready = false;
            // the solver takes the operator over (`System::prepare`, one copy, not two;
            // the next `evaluate` takes it back)
            let small = !newton && small && moved < picard::SMALL_CHANGE;
            sys.prepare(small).map_err(solve_error)?;
            sys.picard_ready();
            // the Picard step in the system's own arrays, as `picard::run` takes it (large
            // grids solve the coordinates one after the other: one cycle workspace)
            let lin = sys.linear();
            let (solves, largest) = picard::solve_corrections(&*lin.solver, lin.u, lin.r, ctl);
            let update = sys.apply(largest);
            moved = update;
            prev_update = last_update;
            last_update = update;
            prev_newton = false;
            Ok(StepWork {
                residual,
                solves,
                update,
                newton: false,
                linear_error: None,
            })
        },
        progress,
    )?;
    let final_residual = match cached {
        Some(r) => r,
        None => evaluate(&mut *sys),
    };
    let info = picard::info(
        picard::Nonlinear::Newton,
        sys.linear().solver.name(),
        params,
        history,
        converged,
        final_residual,
    );
    Ok((info, eval_secs))
}

/// The largest error of the last Krylov solve's correction, relative to the diameter: the
/// preconditioner applied once to the solve's final residual (rows scaled as in [`krylov`],
/// unscaled for the preconditioner as there). η, the ratio of the scaled residuals' 2-norms,
/// understates it where the residual left is smoother than the one the solve started from
/// (`picard::error_estimate`).
fn linear_error<S: NewtonSystem>(
    sys: &S,
    buf: &mut Buffers,
) -> std::result::Result<f64, SolveError> {
    let n = sys.nodes();
    let Buffers {
        rhs,
        scale,
        tmp,
        krylov,
        ..
    } = buf;
    let scale = &*scale;
    tmp.par_chunks_mut(n)
        .zip(krylov.residual().par_chunks(n))
        .for_each(|(tc, rc)| {
            for ((t, r), s) in tc.iter_mut().zip(rc).zip(scale) {
                *t = r / s;
            }
        });
    sys.precondition(tmp, rhs)?;
    Ok(max_abs(rhs) / sys.diameter())
}

/// Largest |a_i / b_i − 1|: how much the row scales `a` moved from `b`.
fn changed(a: &[f64], b: &[f64]) -> f64 {
    a.par_chunks(8192)
        .zip(b.par_chunks(8192))
        .map(|(x, y)| {
            x.iter()
                .zip(y)
                .fold(0.0f64, |m, (u, v)| m.max((u / v - 1.0).abs()))
        })
        .reduce(|| 0.0, f64::max)
}

/// Largest |v_i|.
fn max_abs(v: &[f64]) -> f64 {
    v.par_chunks(8192)
        .map(|c| c.iter().fold(0.0f64, |m, x| m.max(x.abs())))
        .reduce(|| 0.0, f64::max)
}

/// The residual r of the current iterate, rows divided by A's diagonal, into `buf.rhs`, and
/// the row scales into `buf.scale`.
fn scaled_residual<S: NewtonSystem>(sys: &mut S, buf: &mut Buffers) {
    let n = sys.nodes();
    sys.diagonal(&mut buf.scale);
    buf.scale.par_iter_mut().for_each(|s| *s = 1.0 / *s);
    let lin = sys.linear();
    for (c, rc) in lin.r.iter().enumerate() {
        let out = &mut buf.rhs[c * n..(c + 1) * n];
        out.par_iter_mut()
            .zip(rc.par_iter())
            .zip(buf.scale.par_iter())
            .for_each(|((o, r), s)| *o = r * s);
    }
}

/// The Newton correction into `buf.delta` (from zero if `from_zero`, else from its value):
/// J δ = r by FGMRES with the rows scaled by A's diagonal ([`scaled_residual`]),
/// right-preconditioned by the system's preconditioner.
fn krylov<S: NewtonSystem>(
    sys: &S,
    buf: &mut Buffers,
    ctl: &SolveControl,
    from_zero: bool,
) -> std::result::Result<SolveInfo, SolveError> {
    let n = sys.nodes();
    let Buffers {
        rhs,
        delta,
        scale,
        tmp,
        krylov,
        ..
    } = buf;
    let scale = &*scale;
    let failed: Mutex<Option<SolveError>> = Mutex::new(None);
    if from_zero {
        crate::solve::par_fill(delta, 0.0);
    }
    let ctl = SolveControl {
        max_iter: KRYLOV_MAX,
        ..*ctl
    };
    let info = gmres(
        &mut |v, out| {
            sys.apply_jacobian(v, out);
            out.par_chunks_mut(n).for_each(|oc| {
                oc.iter_mut().zip(scale).for_each(|(o, s)| *o *= s);
            });
        },
        &mut |v, out| {
            tmp.par_chunks_mut(n)
                .zip(v.par_chunks(n))
                .for_each(|(tc, vc)| {
                    for ((t, x), s) in tc.iter_mut().zip(vc).zip(scale) {
                        *t = x / s;
                    }
                });
            if let Err(e) = sys.precondition(tmp, out) {
                *failed.lock().unwrap_or_else(|e| e.into_inner()) = Some(e);
            }
        },
        rhs,
        delta,
        &ctl,
        KRYLOV_MAX,
        krylov,
    )?;
    if let Some(e) = failed.into_inner().unwrap_or_else(|e| e.into_inner()) {
        return Err(e);
    }
    Ok(info)
}

/// The relative Krylov tolerance of a Newton step after updates `prev` and `last` (relative
/// to the diameter; infinite before the first steps): Eisenstat and Walker's choice η = ρ²
/// with ρ = last / prev the observed contraction, i.e. the step's linear error matched to the
/// quadratic convergence Newton can deliver, but not below half the Picard tolerance over the
/// predicted update (no linear accuracy beyond what the stop can use), clamped to
/// [`PicardParams::linear_tolerance`, `PicardParams::linear_forcing`]; `linear_forcing` for
/// the first two steps.
fn forcing(params: &PicardParams, prev: f64, last: f64) -> f64 {
    let floor = params.linear_tolerance;
    let cap = params.linear_forcing.max(floor);
    if !(prev.is_finite() && last.is_finite() && prev > 0.0 && last > 0.0) {
        return cap;
    }
    let rho = last / prev;
    (rho * rho)
        .max(0.5 * params.tolerance / (rho * last))
        .clamp(floor, cap)
}
