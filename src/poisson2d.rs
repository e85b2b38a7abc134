//! The Poisson grid system [24] on a 2D block (planar domain, D = 2, or minimal surface,
//! D = 3), discretized as in [41]–[44] and solved by Picard iteration.
//!
//! Each Picard step freezes P = g22, Q = −g12, R = g11 and S, T (from the control functions)
//! at the current iterate, assembles the nine-point operator of
//! `P x_ξξ + 2Q x_ξη + R x_ηη + S x_ξ + T x_η = 0` with central differences (index space), and
//! solves it once per coordinate with the same operator (one setup, coordinates in parallel).
//!
//! The linear systems are solved in correction form, A δ = b − A x_k from δ = 0, i.e. from the
//! current iterate, and with an iterative solver only as accurately as the step needs
//! ([`PicardParams::linear_forcing`]): one or two multigrid cycles per step. The stopping test
//! (largest update below the tolerance) is the same for every solver.

use crate::boundary::Boundary2;
use crate::control::Control2;
use crate::grid::Grid2;
use crate::linsolve::{LinearSolver, SolveControl, SolveError, SolveInfo};
use crate::stencil::Stencil9;
use crate::{Error, Result};
use rayon::prelude::*;

/// Picard iteration parameters.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PicardParams {
    /// Stop when the Picard error, relative to the domain diameter, is below this: the
    /// largest node update of the last step, or, once the steps contract (ratio ρ < 0.5),
    /// its a-posteriori estimate ρ/(1 − ρ) · update + the step's linear error
    /// (`poisson2d::error_estimate`). Default 1e-10.
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
    /// vanishes there). 0 solves every step to `linear_tolerance`. Default 0.1.
    pub linear_forcing: f64,
    /// Nested iteration (`crate::nested`): solve on coarser grids first. `None` (default)
    /// means on with the multigrid solver, off with the direct one; volume blocks
    /// (`crate::volume::nested3d::nested_for3`) also default to on with Bi-CGSTAB.
    pub nested: Option<bool>,
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
        }
    }
}

impl PicardParams {
    /// Whether nested iteration is used with the linear solver called `solver_name`.
    pub fn nested_for(&self, solver_name: &str) -> bool {
        self.nested.unwrap_or(solver_name == "multigrid")
    }
}

/// One Picard step of the history.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PicardStep {
    /// Largest node update of this step, relative to the domain diameter.
    pub update: f64,
    /// Residual of [24] at the iterate this step started from (see [`residual`]).
    pub residual: f64,
    /// Linear iterations (cycles) per coordinate.
    pub linear_iterations: Vec<usize>,
    /// Final relative linear residual per coordinate (0 for a direct solve).
    pub linear_residual: Vec<f64>,
}

/// What the Picard iteration did: part of every result and report.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PicardInfo {
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
}

/// Assembles the frozen nine-point operator of [43, 44] at iterate `x` and the right-hand
/// sides (one per coordinate) that carry the Dirichlet boundary values.
///
/// Rows are multiplied by −1 so that the diagonal 2(P + R) is positive.
pub fn assemble<const D: usize>(
    x: &Grid2<D>,
    ctrl: &Control2,
    a: &mut Stencil9,
    rhs: &mut [Vec<f64>; D],
) {
    use crate::stencil::dir::*;
    let (ni, nj) = (x.ni(), x.nj());
    let (nx, ny) = (ni - 2, nj - 2);
    assert_eq!((a.nx(), a.ny()), (nx, ny));
    let xs = x.coords();
    a.coefs_mut()
        .par_chunks_mut(nx)
        .enumerate()
        .for_each(|(jj, arow)| {
            let j = jj + 1;
            for (ii, st) in arow.iter_mut().enumerate() {
                let n = ii + 1 + ni * j;
                let (e, w, no, so) = (n + 1, n - 1, n + ni, n - ni);
                let (mut g11, mut g12, mut g22) = (0.0, 0.0, 0.0);
                for c in xs.iter() {
                    let xi = 0.5 * (c[e] - c[w]);
                    let eta = 0.5 * (c[no] - c[so]);
                    g11 += xi * xi;
                    g12 += xi * eta;
                    g22 += eta * eta;
                }
                let (p, q, r) = (g22, -g12, g11);
                let k = ctrl.at(n);
                let sc = p * k[0] + 2.0 * q * k[2] + r * k[4];
                let tc = p * k[1] + 2.0 * q * k[3] + r * k[5];
                st[C] = 2.0 * (p + r);
                st[E] = -(p + 0.5 * sc);
                st[W] = -(p - 0.5 * sc);
                st[N] = -(r + 0.5 * tc);
                st[S] = -(r - 0.5 * tc);
                st[NE] = -0.5 * q;
                st[SW] = -0.5 * q;
                st[NW] = 0.5 * q;
                st[SE] = 0.5 * q;
            }
        });
    // Known boundary neighbours go to the right-hand side (rows next to the boundary only).
    for b in rhs.iter_mut() {
        b.fill(0.0);
    }
    let coefs = a.coefs_mut();
    let mut row = |ii: usize, jj: usize| {
        let p = ii + nx * jj;
        let (i, j) = (ii + 1, jj + 1);
        for dj in 0..3usize {
            for di in 0..3usize {
                let (ib, jb) = (i + di - 1, j + dj - 1);
                if ib == 0 || jb == 0 || ib == ni - 1 || jb == nj - 1 {
                    let k = di + 3 * dj;
                    let m = ib + ni * jb;
                    for (b, c) in rhs.iter_mut().zip(xs.iter()) {
                        b[p] -= coefs[p][k] * c[m];
                    }
                    coefs[p][k] = 0.0;
                }
            }
        }
    };
    for ii in 0..nx {
        row(ii, 0);
        if ny > 1 {
            row(ii, ny - 1);
        }
    }
    for jj in 1..ny.saturating_sub(1) {
        row(0, jj);
        if nx > 1 {
            row(nx - 1, jj);
        }
    }
}

/// Residual of [24] at grid `x`: the largest |A x − b| over interior nodes, each row divided by
/// its diagonal 2(P + R) and by the domain diameter — a dimensionless number comparable to a
/// relative node update.
pub fn residual<const D: usize>(x: &Grid2<D>, a: &Stencil9, rhs: &[Vec<f64>; D]) -> f64 {
    residual_scaled(x, a, rhs, x.diameter(), None)
}

/// [`residual`] with the diameter given; rows in parallel, straight from the full grid (the
/// boundary couplings of `a` are zero after [`assemble`], so boundary values drop out). With
/// `out`, also stores `b − A x` per coordinate (interior numbering).
fn residual_scaled<const D: usize>(
    x: &Grid2<D>,
    a: &Stencil9,
    rhs: &[Vec<f64>; D],
    diam: f64,
    out: Option<&mut [Vec<f64>; D]>,
) -> f64 {
    let (ni, nx) = (x.ni(), a.nx());
    let xs = x.coords();
    let row = |jj: usize, arow: &[[f64; 9]], mut out: [Option<&mut [f64]>; D]| {
        let mut w = 0.0f64;
        for (ii, st) in arow.iter().enumerate() {
            let (p, n) = (ii + nx * jj, ii + 1 + ni * (jj + 1));
            for (c, (xc, b)) in xs.iter().zip(rhs.iter()).enumerate() {
                let (lo, mid, hi) = (&xc[n - ni - 1..], &xc[n - 1..], &xc[n + ni - 1..]);
                let ax = st[0] * lo[0]
                    + st[1] * lo[1]
                    + st[2] * lo[2]
                    + st[3] * mid[0]
                    + st[4] * mid[1]
                    + st[5] * mid[2]
                    + st[6] * hi[0]
                    + st[7] * hi[1]
                    + st[8] * hi[2];
                let r = b[p] - ax;
                if let Some(o) = out[c].as_deref_mut() {
                    o[ii] = r;
                }
                w = w.max((r / st[4]).abs());
            }
        }
        w
    };
    let rows = a.coefs().par_chunks(nx).enumerate();
    let worst = match out {
        None => rows
            .map(|(jj, arow)| row(jj, arow, std::array::from_fn(|_| None)))
            .reduce(|| 0.0, f64::max),
        Some(out) => {
            let mut chunks: Vec<Vec<&mut [f64]>> = (0..a.ny()).map(|_| Vec::new()).collect();
            for o in out.iter_mut() {
                for (jj, ch) in o.chunks_mut(nx).enumerate() {
                    chunks[jj].push(ch);
                }
            }
            rows.zip(chunks.into_par_iter())
                .map(|((jj, arow), ch)| {
                    let mut it = ch.into_iter();
                    row(jj, arow, std::array::from_fn(|_| it.next()))
                })
                .reduce(|| 0.0, f64::max)
        }
    };
    worst / diam
}

fn add_interior(inner: &[f64], ni: usize, nx: usize, full: &mut [f64]) {
    for (jj, row) in inner.chunks(nx).enumerate() {
        let base = ni * (jj + 1) + 1;
        for (f, d) in full[base..base + nx].iter_mut().zip(row) {
            *f += d;
        }
    }
}

/// Solves the grid system [24] by Picard iteration [43, 44] from the start grid `x` (whose
/// boundary nodes are the Dirichlet data and stay untouched).
///
/// Each step's linear systems start from the current iterate and are solved to the relative
/// residual of the forcing term (see [`PicardParams::linear_forcing`]); the coordinates are
/// solved in parallel with the operator's one setup. `place` names the block in errors.
/// Non-convergence is not an error: it is reported in the returned [`PicardInfo`].
pub fn solve<const D: usize>(
    x: &mut Grid2<D>,
    ctrl: &Control2,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<PicardInfo> {
    solve_timed(x, ctrl, solver, params, 0.0, place).map(|(info, _)| info)
}

/// A Picard step whose update (relative to the diameter) was below this changed the operator
/// so little that the next one is prepared by [`LinearSolver::update`] (multigrid keeps its
/// coarse levels) instead of a full setup.
pub const SMALL_CHANGE: f64 = 1e-5;

/// [`solve`], also returning the shortest time (seconds) of one evaluation of the residual of
/// [24] with its assembly on this grid, measured at every step: the work unit of
/// `crate::nested`. With `relative_stop > 0` the iteration also stops (converged) once the
/// update falls below `relative_stop` times the first update: enough for a coarse level of
/// nested iteration, whose own discretization error dwarfs the Picard tolerance.
pub(crate) fn solve_timed<const D: usize>(
    x: &mut Grid2<D>,
    ctrl: &Control2,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    relative_stop: f64,
    place: &str,
) -> Result<(PicardInfo, f64)> {
    let (ni, nj) = (x.ni(), x.nj());
    if ni < 3 || nj < 3 {
        return Err(Error::input(place, "a block needs at least 3 × 3 nodes"));
    }
    if (ctrl.ni(), ctrl.nj()) != (ni, nj) {
        return Err(Error::input(
            place,
            "control functions and grid differ in size",
        ));
    }
    if !ctrl.all_finite() {
        return Err(Error::input(
            place,
            "the algebraic transformation is degenerate (non-finite control functions)",
        ));
    }
    let solve_err = |source| Error::Solve {
        place: place.to_string(),
        source,
    };
    let (nx, ny) = (ni - 2, nj - 2);
    let diam = x.diameter();
    let mut a = Stencil9::zeros(nx, ny);
    let mut rhs: [Vec<f64>; D] = std::array::from_fn(|_| vec![0.0; nx * ny]);
    // residuals, then corrections, of the coordinates (interior numbering)
    let mut r: [Vec<f64>; D] = std::array::from_fn(|_| vec![0.0; nx * ny]);
    let mut u: [Vec<f64>; D] = std::array::from_fn(|_| vec![0.0; nx * ny]);
    let mut eval_secs = f64::INFINITY;
    let mut evaluate =
        |x: &Grid2<D>, a: &mut Stencil9, rhs: &mut [Vec<f64>; D], r: &mut [Vec<f64>; D]| {
            let t0 = std::time::Instant::now();
            assemble(x, ctrl, a, rhs);
            let res = residual_scaled(x, a, rhs, diam, Some(r));
            eval_secs = eval_secs.min(t0.elapsed().as_secs_f64());
            res
        };
    let mut history: Vec<PicardStep> = Vec::new();
    let mut converged = false;
    for _ in 0..params.max_steps {
        let res = evaluate(x, &mut a, &mut rhs, &mut r);
        match history.last() {
            Some(last) if last.update < SMALL_CHANGE => solver.update(&a),
            _ => solver.setup(&a),
        }
        .map_err(solve_err)?;
        let ctl = SolveControl {
            rel_tol: forcing(params, &history),
            max_iter: params.linear_max_iter,
        };
        let solver_ref: &dyn LinearSolver = solver;
        let (infos, upd) = solve_corrections(&mut u, &r, |rc, uc| solver_ref.solve(rc, uc, &ctl));
        let mut step = step_record(res, infos, place)?;
        for (c, uc) in u.iter().enumerate() {
            add_interior(uc, ni, nx, x.coord_mut(c));
        }
        step.update = upd / diam;
        history.push(step);
        let upd = upd / diam;
        if !upd.is_finite() || !x.all_finite() {
            return Err(solve_err(crate::linsolve::SolveError::Diverged(f64::NAN)));
        }
        if error_estimate(&history) < stop_threshold(params, &history, relative_stop) {
            converged = true;
            break;
        }
    }
    let final_residual = evaluate(x, &mut a, &mut rhs, &mut r);
    let info = PicardInfo {
        linear_solver: solver.name().to_string(),
        steps: history.len(),
        converged,
        tolerance: params.tolerance,
        final_residual,
        work_units: None,
        coarse_steps: Vec::new(),
        history,
    };
    Ok((info, eval_secs))
}

/// The relative linear tolerance of the next Picard step: `linear_tolerance` without forcing,
/// else `clamp(max(0.5 ρ, 0.5 tol / u), linear_tolerance, linear_forcing)` with ρ the last
/// observed Picard contraction and u = ρ · (last update) the predicted next update: no more
/// accurate than the Picard error, and no more than half the Picard tolerance in absolute
/// terms (which also keeps the request above round-off near convergence). The stop test
/// ([`error_estimate`]) counts the linear error η u of the last step, so a looser request can
/// cost a step but never a wrong convergence claim; half (rather than a tenth, as measured
/// before) saves the second cycle of the last step at 129³ (bench_volume: 85 → 77 WU).
/// `linear_forcing` for the first two steps. Shared with the volume Picard iteration
/// (`crate::volume::picard3d`).
pub(crate) fn forcing(params: &PicardParams, history: &[PicardStep]) -> f64 {
    let (floor, cap) = (params.linear_tolerance, params.linear_forcing);
    if cap <= floor {
        return floor;
    }
    match history {
        [.., a, b] if a.update > 0.0 && b.update > 0.0 => {
            let rho = b.update / a.update;
            let predicted = rho * b.update;
            (0.5 * rho)
                .max(0.5 * params.tolerance / predicted)
                .clamp(floor, cap)
        }
        _ => cap,
    }
}

/// The corrections of one Picard step in correction form, A δ = b − A x_k from δ₀ = 0, one
/// coordinate per rayon task with the operator's one setup (`solve(r, δ)`); returns the
/// solves' results and the largest |δ|. The correction form keeps the cycles' round-off
/// relative to δ instead of x: near convergence the residual of x_k is itself at round-off
/// level, and a solve for x would stagnate. Shared with the volume Picard iteration.
pub(crate) fn solve_corrections<F>(
    u: &mut [Vec<f64>],
    r: &[Vec<f64>],
    solve: F,
) -> (Vec<std::result::Result<SolveInfo, SolveError>>, f64)
where
    F: Fn(&[f64], &mut [f64]) -> std::result::Result<SolveInfo, SolveError> + Sync,
{
    let infos = u
        .par_iter_mut()
        .zip(r.par_iter())
        .map(|(uc, rc)| {
            uc.fill(0.0);
            solve(rc, uc)
        })
        .collect();
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
/// is filled in by the caller. Shared by the 2D and the volume Picard iterations.
pub(crate) fn step_record(
    residual: f64,
    infos: Vec<std::result::Result<SolveInfo, SolveError>>,
    place: &str,
) -> Result<PicardStep> {
    let mut step = PicardStep {
        update: 0.0,
        residual,
        linear_iterations: Vec::with_capacity(infos.len()),
        linear_residual: Vec::with_capacity(infos.len()),
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

/// The Picard error after the steps of `history` (relative to the diameter): the last update
/// u, or, once the iteration contracts (ρ = u / previous update < 0.5), the a-posteriori
/// bound of a contraction ρ/(1 − ρ) u plus the error η u of the inexact step (η its largest
/// relative linear residual). With the contraction of 0.01–0.04 seen after nested iteration
/// this saves the last Picard step, whose update would only confirm what the estimate says.
pub(crate) fn error_estimate(history: &[PicardStep]) -> f64 {
    match history {
        [.., a, b] if a.update > 0.0 && b.update < 0.5 * a.update => {
            let rho = b.update / a.update;
            let eta = b.linear_residual.iter().copied().fold(0.0, f64::max);
            (b.update * (rho / (1.0 - rho) + eta)).min(b.update)
        }
        [.., b] => b.update,
        [] => f64::INFINITY,
    }
}

/// The stopping threshold of the Picard iteration after the steps of `history`: the last
/// update (relative to the diameter) must fall below the tolerance, or below
/// `relative_stop` times the first update (a coarse level of nested iteration; 0 = off).
/// Shared by the 2D and the volume Picard iterations.
pub(crate) fn stop_threshold(
    params: &PicardParams,
    history: &[PicardStep],
    relative_stop: f64,
) -> f64 {
    let first = history.first().map_or(0.0, |h| h.update);
    params.tolerance.max(relative_stop * first)
}

/// Convenience: the start grid with the boundary of `b` and the solve of [24] from it.
pub fn solve_from<const D: usize>(
    b: &Boundary2<D>,
    start: Grid2<D>,
    ctrl: &Control2,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<(Grid2<D>, PicardInfo)> {
    let mut x = start;
    b.apply_to(&mut x);
    let info = solve(&mut x, ctrl, solver, params, place)?;
    Ok((x, info))
}
