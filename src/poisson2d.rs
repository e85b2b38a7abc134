//! The Poisson grid system [24] on a 2D block (planar domain, D = 2, or minimal surface,
//! D = 3), discretized as in [41]–[44] and solved by Picard iteration.
//!
//! Each Picard step freezes P = g22, Q = −g12, R = g11 and S, T (from the control functions)
//! at the current iterate, assembles the nine-point operator of
//! `P x_ξξ + 2Q x_ξη + R x_ηη + S x_ξ + T x_η = 0` with central differences (index space), and
//! solves it once per coordinate with the same operator.

use crate::boundary::Boundary2;
use crate::control::Control2;
use crate::grid::Grid2;
use crate::linsolve::{LinearSolver, SolveControl};
use crate::stencil::Stencil9;
use crate::{Error, Result};
use rayon::prelude::*;

/// Picard iteration parameters.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PicardParams {
    /// Stop when the largest node update, relative to the domain diameter, is below this.
    /// Default 1e-10.
    pub tolerance: f64,
    /// At most this many Picard steps. Default 200.
    pub max_steps: usize,
    /// Relative residual reduction asked of each linear solve (iterative solvers). Default 1e-10.
    pub linear_tolerance: f64,
    /// At most this many cycles per linear solve (iterative solvers). Default 100.
    pub linear_max_iter: usize,
}

impl Default for PicardParams {
    fn default() -> Self {
        PicardParams {
            tolerance: 1e-10,
            max_steps: 200,
            linear_tolerance: 1e-10,
            linear_max_iter: 100,
        }
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
    let (ni, nx) = (x.ni(), a.nx());
    let diam = x.diameter();
    let mut worst = 0.0f64;
    let mut u = vec![0.0; a.len()];
    let mut r = vec![0.0; a.len()];
    for (c, b) in rhs.iter().enumerate() {
        gather_interior(x.coord(c), ni, nx, &mut u);
        a.residual(b, &u, &mut r);
        for (rv, row) in r.iter().zip(a.coefs()) {
            worst = worst.max((rv / row[crate::stencil::dir::C]).abs());
        }
    }
    worst / diam
}

fn gather_interior(full: &[f64], ni: usize, nx: usize, out: &mut [f64]) {
    for (jj, row) in out.chunks_mut(nx).enumerate() {
        let base = ni * (jj + 1) + 1;
        row.copy_from_slice(&full[base..base + nx]);
    }
}

fn scatter_interior(inner: &[f64], ni: usize, nx: usize, full: &mut [f64]) {
    for (jj, row) in inner.chunks(nx).enumerate() {
        let base = ni * (jj + 1) + 1;
        full[base..base + nx].copy_from_slice(row);
    }
}

/// Solves the grid system [24] by Picard iteration [43, 44] from the start grid `x` (whose
/// boundary nodes are the Dirichlet data and stay untouched).
///
/// `place` names the block in errors. Non-convergence is not an error: it is reported in the
/// returned [`PicardInfo`].
pub fn solve<const D: usize>(
    x: &mut Grid2<D>,
    ctrl: &Control2,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<PicardInfo> {
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
    let (nx, ny) = (ni - 2, nj - 2);
    let diam = x.diameter();
    let mut a = Stencil9::zeros(nx, ny);
    let mut rhs: [Vec<f64>; D] = std::array::from_fn(|_| vec![0.0; nx * ny]);
    let mut u: [Vec<f64>; D] = std::array::from_fn(|_| vec![0.0; nx * ny]);
    let ctl = SolveControl {
        rel_tol: params.linear_tolerance,
        max_iter: params.linear_max_iter,
    };
    let mut history = Vec::new();
    let mut converged = false;
    for _ in 0..params.max_steps {
        assemble(x, ctrl, &mut a, &mut rhs);
        let res = residual(x, &a, &rhs);
        solver.setup(&a).map_err(|source| Error::Solve {
            place: place.to_string(),
            source,
        })?;
        for (c, uc) in u.iter_mut().enumerate() {
            gather_interior(x.coord(c), ni, nx, uc);
        }
        let solver_ref: &dyn LinearSolver = solver;
        let infos: Vec<_> = u
            .par_iter_mut()
            .zip(rhs.par_iter())
            .map(|(uc, bc)| solver_ref.solve(bc, uc, &ctl))
            .collect();
        let mut step = PicardStep {
            update: 0.0,
            residual: res,
            linear_iterations: Vec::with_capacity(D),
            linear_residual: Vec::with_capacity(D),
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
        let mut upd = 0.0f64;
        for (c, uc) in u.iter().enumerate() {
            let full = x.coord_mut(c);
            for (jj, row) in uc.chunks(nx).enumerate() {
                let base = ni * (jj + 1) + 1;
                for (v, o) in row.iter().zip(&full[base..base + nx]) {
                    upd = upd.max((v - o).abs());
                }
            }
            scatter_interior(uc, ni, nx, full);
        }
        step.update = upd / diam;
        history.push(step);
        if !x.all_finite() {
            return Err(Error::Solve {
                place: place.to_string(),
                source: crate::linsolve::SolveError::Diverged(f64::NAN),
            });
        }
        if upd / diam < params.tolerance {
            converged = true;
            break;
        }
    }
    assemble(x, ctrl, &mut a, &mut rhs);
    let final_residual = residual(x, &a, &rhs);
    Ok(PicardInfo {
        linear_solver: solver.name().to_string(),
        steps: history.len(),
        converged,
        tolerance: params.tolerance,
        final_residual,
        history,
    })
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
