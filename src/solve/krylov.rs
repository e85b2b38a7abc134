//! Bi-CGSTAB (van der Vorst 1992) over closures, right-preconditioned, for any operator and
//! preconditioner: one cycle of the 2D multigrid ([`crate::solve::multigrid::bicgstab`]) or of the 3D
//! one, or ILU(0) ([`crate::solve::ilu::BiCgStabIlu`]), the Krylov half of the paper's THREED.
//! `residual_history` holds `‖r_k‖₂/‖r_0‖₂` after each iteration (two preconditioner
//! applications); when the recursive residual reaches the tolerance the true residual is
//! checked and the iteration restarts from it if it drifted.

use crate::solve::multigrid::use_par;
use crate::solve::{SolveControl, SolveError, SolveInfo};
use rayon::prelude::*;

/// Σ a_i b_i over fixed chunks of 8192 terms, the chunks' sums added in chunk order, in
/// parallel when large: the same bits whatever the thread count.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let chunk = |(a, b): (&[f64], &[f64])| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    if use_par(a.len()) {
        in_order(a.par_chunks(8192).zip(b.par_chunks(8192)).map(chunk))
    } else {
        a.chunks(8192).zip(b.chunks(8192)).map(chunk).sum()
    }
}

/// The sum of a parallel iterator's values in their order (as the sequential `sum` adds
/// them), not in rayon's thread-dependent reduction tree: outputs stay bit-identical across
/// runs and thread counts. For the few values of chunked reductions.
pub(crate) fn in_order<T: Send + std::iter::Sum<T>>(
    values: impl IndexedParallelIterator<Item = T>,
) -> T {
    values.collect::<Vec<T>>().into_iter().sum()
}

/// `f(i, &mut out[i])` for every element, in parallel chunks when large.
pub(crate) fn update(out: &mut [f64], f: impl Fn(usize, &mut f64) + Sync + Send) {
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

/// Solves `A x = b` with `apply(v, out)`: `out = A v`, and `precond(v, out)`: `out ≈ A⁻¹ v`.
/// `x` holds the initial guess. Stops at `‖r‖ ≤ rel_tol ‖r₀‖` or after `max_iter` iterations
/// (`converged: false`); relative residual above 1e3 or NaN is [`SolveError::Diverged`].
pub fn bicgstab(
    apply: &mut dyn FnMut(&[f64], &mut [f64]),
    precond: &mut dyn FnMut(&[f64], &mut [f64]),
    b: &[f64],
    x: &mut [f64],
    ctl: &SolveControl,
) -> Result<SolveInfo, SolveError> {
    let n = b.len();
    let v = || vec![0.0; n];
    let (mut r, mut rhat, mut p, mut vv, mut y, mut z, mut t) = (v(), v(), v(), v(), v(), v(), v());
    let true_residual =
        |apply: &mut dyn FnMut(&[f64], &mut [f64]), x: &[f64], r: &mut [f64], t: &mut [f64]| {
            apply(x, t);
            update(r, |i, ri| *ri = b[i] - t[i]);
            dot(r, r).sqrt()
        };
    // Correction form starts from zero: then r = b without a product.
    let r0 = if x.par_iter().all(|&v| v == 0.0) {
        r.copy_from_slice(b);
        dot(&r, &r).sqrt()
    } else {
        true_residual(apply, x, &mut r, &mut t)
    };
    if let Some(done) = SolveInfo::start(r0)? {
        return Ok(done);
    }
    let mut info = SolveInfo::default();
    let mut restart = true;
    let (mut rho_old, mut alpha, mut omega) = (1.0, 1.0, 1.0);
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
        update(&mut p, |i, pi| *pi = r[i] + beta * (*pi - omega * vv[i]));
        precond(&p, &mut y);
        apply(&y, &mut vv);
        alpha = rho / dot(&rhat, &vv);
        if !(alpha.is_finite() && rho.is_finite()) || rho == 0.0 {
            let rel = true_residual(apply, x, &mut r, &mut t) / r0;
            info.residual_history.push(rel);
            if rel.is_nan() || rel > crate::solve::DIVERGED {
                return Err(SolveError::Diverged(rel));
            }
            restart = true;
            continue;
        }
        update(&mut r, |i, ri| *ri -= alpha * vv[i]);
        if dot(&r, &r).sqrt() / r0 <= ctl.rel_tol {
            update(x, |i, xi| *xi += alpha * y[i]);
            omega = 0.0;
        } else {
            precond(&r, &mut z);
            apply(&z, &mut t);
            let tt = dot(&t, &t);
            omega = if tt > 0.0 { dot(&t, &r) / tt } else { 0.0 };
            update(x, |i, xi| *xi += alpha * y[i] + omega * z[i]);
            update(&mut r, |i, ri| *ri -= omega * t[i]);
        }
        let mut rel = dot(&r, &r).sqrt() / r0;
        if rel <= ctl.rel_tol || omega == 0.0 || !omega.is_finite() {
            rel = true_residual(apply, x, &mut r, &mut t) / r0;
            restart = true;
        }
        info.residual_history.push(rel);
        if rel.is_nan() || rel > crate::solve::DIVERGED {
            return Err(SolveError::Diverged(rel));
        }
        if rel <= ctl.rel_tol {
            info.converged = true;
            break;
        }
        rho_old = rho;
    }
    Ok(info)
}
