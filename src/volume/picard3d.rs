//! The volume grid system [86]–[88] discretized on the 19-point stencil and solved by Picard
//! iteration (METHOD.md §6).
//!
//! Each Picard step freezes α^ij (J² times the contravariant metric, from the covariant
//! metric g_ij of the current iterate by central differences) and the first-derivative
//! coefficients Σ_ij α^ij P^k_ij, assembles the 19-point operator of
//! `Σ_ij α^ij x_{ξiξj} + Σ_k (Σ_ij α^ij P^k_ij) x_{ξk} = 0` (central differences in index space;
//! mixed derivatives by the 4-corner formula that [`super::control3d`] uses, so the
//! tensor-product box is an exact discrete solution), and solves it once per coordinate with
//! the same operator. The stopping rule and the history are those of [`crate::poisson2d`].

use super::control3d::Control3;
use super::solver3d::LinearSolver3;
use super::stencil19::{Stencil19, C, OFFSETS};
use crate::linsolve::{SolveControl, SolveError};
use crate::poisson2d::{PicardInfo, PicardParams, PicardStep};
use crate::{Error, Grid3, Result};
use rayon::prelude::*;

/// The six α^ij of [88] in the order 11, 12, 13, 22, 23, 33, from g_ij.
#[inline]
pub fn alphas(g: [[f64; 3]; 3]) -> [f64; 6] {
    [
        g[1][1] * g[2][2] - g[1][2] * g[1][2],
        g[0][2] * g[1][2] - g[0][1] * g[2][2],
        g[0][1] * g[1][2] - g[0][2] * g[1][1],
        g[0][0] * g[2][2] - g[0][2] * g[0][2],
        g[0][2] * g[0][1] - g[0][0] * g[1][2],
        g[0][0] * g[1][1] - g[0][1] * g[0][1],
    ]
}

/// Assembles the frozen 19-point operator of [86] at iterate `x` and the right-hand sides
/// (one per coordinate) that carry the Dirichlet boundary values. Rows are multiplied by −1 so
/// that the diagonal 2(α11 + α22 + α33) is positive.
pub fn assemble(x: &Grid3, ctrl: &Control3, a: &mut Stencil19, rhs: &mut [Vec<f64>; 3]) {
    let [ni, nj, nk] = x.dims();
    let [nx, ny, nz] = [ni - 2, nj - 2, nk - 2];
    assert_eq!(a.dims(), [nx, ny, nz]);
    let (plane, uplane) = (ni * nj, nx * ny);
    let st = [1isize, ni as isize, plane as isize];
    let xs = x.coords();
    // For each slot: its nonzero axes (t, t) for a face neighbour, (p, r) for an edge one.
    let axes: [[usize; 2]; 19] = std::array::from_fn(|m| {
        let o = OFFSETS[m];
        let nz: Vec<usize> = (0..3).filter(|&t| o[t] != 0).collect();
        match nz.len() {
            1 => [nz[0], nz[0]],
            2 => [nz[0], nz[1]],
            _ => [0, 0],
        }
    });
    let [r0, r1, r2] = rhs;
    a.coefs_mut()
        .par_chunks_mut(uplane)
        .zip(r0.par_chunks_mut(uplane))
        .zip(r1.par_chunks_mut(uplane))
        .zip(r2.par_chunks_mut(uplane))
        .enumerate()
        .for_each(|(kk, (((arow, b0), b1), b2))| {
            let k = kk + 1;
            let mut bs = [b0, b1, b2];
            for jj in 0..ny {
                let j = jj + 1;
                for ii in 0..nx {
                    let i = ii + 1;
                    let n = i + ni * j + plane * k;
                    let q = ii + nx * jj;
                    // Covariant metric g_ab = x_a · x_b, central differences.
                    let mut d = [[0.0; 3]; 3];
                    for (c, xc) in xs.iter().enumerate() {
                        for (ax, s) in st.iter().enumerate() {
                            d[c][ax] = 0.5
                                * (xc[(n as isize + s) as usize] - xc[(n as isize - s) as usize]);
                        }
                    }
                    let g: [[f64; 3]; 3] = std::array::from_fn(|p| {
                        std::array::from_fn(|r| (0..3).map(|c| d[c][p] * d[c][r]).sum())
                    });
                    let al = alphas(g);
                    let pk = ctrl.at(n);
                    let w = [1.0, 2.0, 2.0, 1.0, 2.0, 1.0];
                    let sk: [f64; 3] =
                        std::array::from_fn(|c| (0..6).map(|m| w[m] * al[m] * pk[3 * m + c]).sum());
                    let diag = [al[0], al[3], al[5]];
                    let mixed = |p: usize, r: usize| al[[[9, 1, 2], [1, 9, 4], [2, 4, 9]][p][r]];
                    let row = &mut arow[q];
                    row[C] = 2.0 * (diag[0] + diag[1] + diag[2]);
                    for (m, o) in OFFSETS.iter().enumerate().skip(1) {
                        let [p, r] = axes[m];
                        row[m] = if p == r {
                            -(diag[p] + 0.5 * o[p] as f64 * sk[p])
                        } else {
                            -0.5 * mixed(p, r) * (o[p] * o[r]) as f64
                        };
                    }
                    // Known boundary neighbours go to the right-hand side.
                    for b in bs.iter_mut() {
                        b[q] = 0.0;
                    }
                    if i == 1 || j == 1 || k == 1 || i == ni - 2 || j == nj - 2 || k == nk - 2 {
                        for (m, o) in OFFSETS.iter().enumerate().skip(1) {
                            let (ib, jb, kb) = (
                                (i as isize + o[0] as isize) as usize,
                                (j as isize + o[1] as isize) as usize,
                                (k as isize + o[2] as isize) as usize,
                            );
                            if ib == 0
                                || jb == 0
                                || kb == 0
                                || ib == ni - 1
                                || jb == nj - 1
                                || kb == nk - 1
                            {
                                let nb = ib + ni * jb + plane * kb;
                                for (b, xc) in bs.iter_mut().zip(xs.iter()) {
                                    b[q] -= row[m] * xc[nb];
                                }
                                row[m] = 0.0;
                            }
                        }
                    }
                }
            }
        });
}

/// Residual of [86] at grid `x`: the largest |A x − b| over interior nodes, each row divided
/// by its diagonal and by the domain diameter (as [`crate::poisson2d::residual`]).
pub fn residual(x: &Grid3, a: &Stencil19, rhs: &[Vec<f64>; 3], diam: f64) -> f64 {
    let mut worst = 0.0f64;
    let mut u = vec![0.0; a.len()];
    let mut r = vec![0.0; a.len()];
    for (c, b) in rhs.iter().enumerate() {
        gather(x, c, &mut u);
        a.residual(b, &u, &mut r);
        let w = r
            .par_iter()
            .zip(a.coefs())
            .map(|(rv, row)| (rv / row[C]).abs())
            .reduce(|| 0.0, f64::max);
        worst = worst.max(w);
    }
    worst / diam
}

/// Interior values of coordinate c into `out` (unknown order).
pub fn gather(x: &Grid3, c: usize, out: &mut [f64]) {
    let [ni, nj, _] = x.dims();
    let nx = ni - 2;
    let full = x.coord(c);
    for (q, row) in out.chunks_mut(nx).enumerate() {
        let (jj, kk) = (q % (nj - 2), q / (nj - 2));
        let base = 1 + ni * (jj + 1) + ni * nj * (kk + 1);
        row.copy_from_slice(&full[base..base + nx]);
    }
}

/// Writes interior values back; returns the largest change.
fn scatter(x: &mut Grid3, c: usize, inner: &[f64]) -> f64 {
    let [ni, nj, _] = x.dims();
    let nx = ni - 2;
    let full = &mut x.coords_mut()[c];
    let mut upd = 0.0f64;
    for (q, row) in inner.chunks(nx).enumerate() {
        let (jj, kk) = (q % (nj - 2), q / (nj - 2));
        let base = 1 + ni * (jj + 1) + ni * nj * (kk + 1);
        for (o, v) in full[base..base + nx].iter_mut().zip(row) {
            upd = upd.max((v - *o).abs());
            *o = *v;
        }
    }
    upd
}

/// Solves the grid system [86] by Picard iteration from the start grid `x` (whose boundary
/// nodes are the Dirichlet data and stay untouched). `progress` is called after every step
/// with the step number and its record. Non-convergence is not an error: it is reported in
/// the returned [`PicardInfo`].
pub fn solve(
    x: &mut Grid3,
    ctrl: &Control3,
    solver: &mut dyn LinearSolver3,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<PicardInfo> {
    let dims = x.dims();
    if dims.iter().any(|&n| n < 3) {
        return Err(Error::input(
            place,
            "a volume block needs at least 3 × 3 × 3 nodes",
        ));
    }
    if ctrl.dims() != dims {
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
    let diam = diameter(x);
    let mut a = Stencil19::zeros(dims[0] - 2, dims[1] - 2, dims[2] - 2);
    let n = a.len();
    let mut rhs: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; n]);
    let mut u: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; n]);
    let ctl = SolveControl {
        rel_tol: params.linear_tolerance,
        max_iter: params.linear_max_iter,
    };
    let solve_err = |source| Error::Solve {
        place: place.to_string(),
        source,
    };
    let mut history = Vec::new();
    let mut converged = false;
    for step_no in 0..params.max_steps {
        assemble(x, ctrl, &mut a, &mut rhs);
        let res = residual(x, &a, &rhs, diam);
        solver.setup(&a).map_err(solve_err)?;
        for (c, uc) in u.iter_mut().enumerate() {
            gather(x, c, uc);
        }
        let sref: &dyn LinearSolver3 = solver;
        let infos: Vec<_> = u
            .par_iter_mut()
            .zip(rhs.par_iter())
            .map(|(uc, bc)| sref.solve(bc, uc, &ctl))
            .collect();
        let mut step = PicardStep {
            update: 0.0,
            residual: res,
            linear_iterations: Vec::with_capacity(3),
            linear_residual: Vec::with_capacity(3),
        };
        for info in infos {
            let info = info.map_err(solve_err)?;
            step.linear_iterations.push(info.iterations);
            step.linear_residual
                .push(info.residual_history.last().copied().unwrap_or(0.0));
        }
        let mut upd = 0.0f64;
        for (c, uc) in u.iter().enumerate() {
            upd = upd.max(scatter(x, c, uc));
        }
        step.update = upd / diam;
        progress(step_no + 1, &step);
        history.push(step);
        if !upd.is_finite() {
            return Err(solve_err(SolveError::Diverged(f64::NAN)));
        }
        if upd / diam < params.tolerance {
            converged = true;
            break;
        }
    }
    assemble(x, ctrl, &mut a, &mut rhs);
    let final_residual = residual(x, &a, &rhs, diam);
    Ok(PicardInfo {
        linear_solver: solver.name().to_string(),
        steps: history.len(),
        converged,
        tolerance: params.tolerance,
        final_residual,
        work_units: None,
        coarse_steps: Vec::new(),
        history,
    })
}

/// Bounding-box diagonal of a volume grid.
fn diameter(x: &Grid3) -> f64 {
    x.coords()
        .iter()
        .map(|c| {
            let (lo, hi) = c
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                    (lo.min(v), hi.max(v))
                });
            (hi - lo).powi(2)
        })
        .sum::<f64>()
        .sqrt()
}
