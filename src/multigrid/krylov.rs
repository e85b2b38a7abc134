//! Bi-CGSTAB (van der Vorst 1992), right-preconditioned by one multigrid cycle.
//!
//! Each iteration applies the preconditioner twice (two cycles from a zero initial guess) and
//! the operator twice. `SolveInfo::iterations` counts Bi-CGSTAB iterations and
//! `residual_history` holds `‖r_k‖₂/‖r_0‖₂` after each of them. When the recursively updated
//! residual reaches the tolerance, the true residual `b − A x` is computed; if it has drifted
//! above the tolerance the iteration restarts from it.

use super::relax::{apply, pad, padded_len, residual, Zeroed};
use super::{use_par, Multigrid};
use crate::linsolve::{SolveControl, SolveError, SolveInfo};
use crate::stencil::Stencil9;
use rayon::prelude::*;
use std::borrow::Cow;

/// Relative residual beyond which an iteration counts as diverged.
pub(super) const DIVERGED: f64 = 1e3;

fn dot(a: &[f64], b: &[f64]) -> f64 {
    if use_par(a.len()) {
        a.par_chunks(8192)
            .zip(b.par_chunks(8192))
            .map(|(a, b)| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>())
            .sum()
    } else {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }
}

/// `f(i, …)` over the elements of up to three equally long slices, in parallel when large.
fn zip_mut(out: &mut [f64], f: impl Fn(usize, &mut f64) + Sync + Send) {
    if use_par(out.len()) {
        out.par_chunks_mut(8192).enumerate().for_each(|(c, ch)| {
            for (t, v) in ch.iter_mut().enumerate() {
                f(c * 8192 + t, v);
            }
        });
    } else {
        out.iter_mut().enumerate().for_each(|(i, v)| f(i, v));
    }
}

/// True if every coupling of `a` that points outside the grid is zero.
fn is_clipped(a: &Stencil9) -> bool {
    let (nx, ny) = (a.nx(), a.ny());
    let zero = |p: usize, ks: [usize; 3]| ks.iter().all(|&k| a.coefs()[p][k] == 0.0);
    (0..nx).all(|i| zero(i, [0, 1, 2]) && zero(i + nx * (ny - 1), [6, 7, 8]))
        && (0..ny).all(|j| zero(nx * j, [0, 3, 6]) && zero(nx - 1 + nx * j, [2, 5, 8]))
}

/// Solves `A x = b` by Bi-CGSTAB with one cycle of `precond` (set up for `a`, or for an
/// operator close to it, of the same size) as right preconditioner; `x` holds the initial
/// guess. Stops when `‖b − A x‖₂ ≤ ctl.rel_tol ‖b − A x₀‖₂` or after `ctl.max_iter`
/// iterations (`converged: false`, not an error).
///
/// # Errors
/// [`SolveError::NotSetUp`] if `precond` has no hierarchy; [`SolveError::Diverged`] if the
/// relative residual exceeds 1e3 or becomes NaN.
///
/// # Panics
/// If the sizes of `a`, `b`, `x` and the preconditioner's fine grid differ.
pub fn bicgstab(
    a: &Stencil9,
    b: &[f64],
    x: &mut [f64],
    precond: &Multigrid,
    ctl: &SolveControl,
) -> Result<SolveInfo, SolveError> {
    let coefs: Cow<[[f64; 9]]> = if is_clipped(a) {
        Cow::Borrowed(a.coefs())
    } else {
        let mut c = a.clone();
        c.clip_to_grid();
        Cow::Owned(c.coefs().to_vec())
    };
    bicgstab_coefs(&coefs, a.nx(), a.ny(), b, x, precond, ctl)
}

/// [`bicgstab`] for the clipped coefficients `a` of an `nx × ny` operator.
pub(super) fn bicgstab_coefs(
    a: &[[f64; 9]],
    nx: usize,
    ny: usize,
    b: &[f64],
    x: &mut [f64],
    precond: &Multigrid,
    ctl: &SolveControl,
) -> Result<SolveInfo, SolveError> {
    let h = precond.hierarchy()?;
    assert_eq!(
        (h.levels[0].nx, h.levels[0].ny),
        (nx, ny),
        "bicgstab: size mismatch"
    );
    let n = nx * ny;
    assert_eq!(a.len(), n);
    assert_eq!(b.len(), n);
    assert_eq!(x.len(), n);
    let (pd, len) = (pad(nx), padded_len(nx, ny));
    let mut ws = precond.take_workspace(h);
    let v = || vec![0.0; len];
    let (mut xx, mut bb, mut r, mut rhat) = (v(), v(), v(), v());
    let (mut p, mut vv, mut y, mut z, mut t) = (v(), v(), v(), v(), v());
    xx[pd..pd + n].copy_from_slice(x);
    bb[pd..pd + n].copy_from_slice(b);
    let r0 = residual(a, None, nx, ny, &xx, &bb, &mut r, Zeroed::None).sqrt();
    let mut info = SolveInfo::default();
    if !r0.is_finite() {
        precond.put_workspace(ws);
        return Err(SolveError::Diverged(f64::NAN));
    }
    if r0 == 0.0 {
        info.converged = true;
        precond.put_workspace(ws);
        return Ok(info);
    }
    let mut restart = true;
    let (mut rho_old, mut alpha, mut omega) = (1.0, 1.0, 1.0);
    let mut result = Ok(());
    while info.iterations < ctl.max_iter {
        if restart {
            rhat.copy_from_slice(&r);
            p.fill(0.0);
            vv.fill(0.0);
            (rho_old, alpha, omega) = (1.0, 1.0, 1.0);
            restart = false;
        }
        info.iterations += 1;
        let rho = dot(&rhat, &r);
        let beta = (rho / rho_old) * (alpha / omega);
        zip_mut(&mut p, |i, pi| *pi = r[i] + beta * (*pi - omega * vv[i]));
        precond.precondition(h, &mut ws, &p, &mut y);
        apply(a, nx, ny, &y, &mut vv);
        alpha = rho / dot(&rhat, &vv);
        if !(alpha.is_finite() && rho.is_finite()) || rho == 0.0 {
            // breakdown before any update: restart from the true residual
            let rel = residual(a, None, nx, ny, &xx, &bb, &mut r, Zeroed::None).sqrt() / r0;
            info.residual_history.push(rel);
            restart = true;
            continue;
        }
        // s = r − α v (in r)
        zip_mut(&mut r, |i, ri| *ri -= alpha * vv[i]);
        let s_norm = dot(&r, &r).sqrt() / r0;
        if s_norm <= ctl.rel_tol {
            zip_mut(&mut xx, |i, xi| *xi += alpha * y[i]);
            omega = 0.0;
        } else {
            precond.precondition(h, &mut ws, &r, &mut z);
            apply(a, nx, ny, &z, &mut t);
            let tt = dot(&t, &t);
            omega = if tt > 0.0 { dot(&t, &r) / tt } else { 0.0 };
            zip_mut(&mut xx, |i, xi| *xi += alpha * y[i] + omega * z[i]);
            zip_mut(&mut r, |i, ri| *ri -= omega * t[i]);
        }
        let mut rel = dot(&r, &r).sqrt() / r0;
        if rel <= ctl.rel_tol {
            // confirm with the true residual
            rel = residual(a, None, nx, ny, &xx, &bb, &mut r, Zeroed::None).sqrt() / r0;
            restart = true;
        }
        info.residual_history.push(rel);
        if rel.is_nan() || rel > DIVERGED {
            result = Err(SolveError::Diverged(rel));
            break;
        }
        if rel <= ctl.rel_tol {
            info.converged = true;
            break;
        }
        if omega == 0.0 || !omega.is_finite() {
            // breakdown: restart from the true residual
            residual(a, None, nx, ny, &xx, &bb, &mut r, Zeroed::None);
            restart = true;
        }
        rho_old = rho;
    }
    precond.put_workspace(ws);
    result?;
    x.copy_from_slice(&xx[pd..pd + n]);
    Ok(info)
}
