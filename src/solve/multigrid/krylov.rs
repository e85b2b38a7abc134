//! Bi-CGSTAB (van der Vorst 1992), right-preconditioned by one multigrid cycle: the shared
//! [`crate::solve::krylov::bicgstab`] on this grid's padded vectors.
//!
//! Each iteration applies the preconditioner twice (two cycles from a zero initial guess) and
//! the operator twice. `SolveInfo::iterations` counts Bi-CGSTAB iterations and
//! `residual_history` holds `‖r_k‖₂/‖r_0‖₂` after each of them. When the recursively updated
//! residual reaches the tolerance, the true residual `b − A x` is computed; if it has drifted
//! above the tolerance the iteration restarts from it.

use crate::solve::multigrid::relax::{apply, pad, padded_len};
use crate::solve::multigrid::Multigrid;
use crate::solve::stencil9::Stencil9;
use crate::solve::{krylov, SolveControl, SolveError, SolveInfo};
use std::borrow::Cow;

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
    // The shared Bi-CGSTAB on padded vectors (their padding stays zero), so that the cycles
    // and the operator need no copies.
    let (pd, len) = (pad(nx), padded_len(nx, ny));
    let mut ws = precond.take_workspace(h);
    let (mut xx, mut bb) = (vec![0.0; len], vec![0.0; len]);
    xx[pd..pd + n].copy_from_slice(x);
    bb[pd..pd + n].copy_from_slice(b);
    let res = krylov::bicgstab(
        &mut |v, out| {
            apply(a, nx, ny, v, out);
        },
        &mut |v, out| precond.precondition(h, &mut ws, v, out),
        &bb,
        &mut xx,
        ctl,
    );
    precond.pool.put(ws);
    let info = res?;
    x.copy_from_slice(&xx[pd..pd + n]);
    Ok(info)
}
