//! Restarted flexible GMRES (Saad 1993, FGMRES(m)) over closures: the Krylov solver of the
//! Newton steps ([`crate::elliptic::newton`]), right-preconditioned by the Picard operator's
//! multigrid cycles.
//!
//! Right preconditioning keeps the true residual `‖b − A x‖₂` as the quantity GMRES minimises
//! and reports, and the flexible form stores the preconditioned vectors `z_j = M⁻¹ v_j`, so
//! the update `x += Z y` needs no further preconditioner application (one multigrid cycle per
//! coordinate, the dearest part of an iteration) and `M` may vary between iterations.
//! Orthogonalisation by modified Gram–Schmidt; the small least-squares problem by Givens
//! rotations. Dot products are [`crate::solve::krylov::dot`]: the same bits whatever the
//! thread count. `residual_history[k] = ‖r_{k+1}‖₂ / ‖r_0‖₂` (the GMRES estimate, exact in
//! exact arithmetic); at a restart and at the end the true residual is computed.

use crate::solve::krylov::{dot, update};
use crate::solve::{SolveControl, SolveError, SolveInfo, DIVERGED};

/// The Krylov vectors of [`gmres`], kept between solves of the same size.
#[derive(Debug, Default)]
pub struct GmresWorkspace {
    /// Orthonormal basis v_0 … v_m.
    v: Vec<Vec<f64>>,
    /// Preconditioned basis z_j = M⁻¹ v_j.
    z: Vec<Vec<f64>>,
    /// Scratch for A z and the residual.
    w: Vec<f64>,
}

impl GmresWorkspace {
    /// Vectors of length `n`, the basis emptied on a change of size; the basis vectors are
    /// added as the iterations reach them ([`GmresWorkspace::reach`]), so a solve that
    /// converges in a few iterations holds a few vectors, not `restart`.
    fn fit(&mut self, n: usize) {
        if self.w.len() != n {
            self.v.clear();
            self.z.clear();
            self.w = vec![0.0; n];
        }
        if self.v.is_empty() {
            self.v.push(vec![0.0; n]);
        }
    }

    /// Makes room for iteration `k`: z_k and v_(k+1) (allocates only the first time a solve
    /// with this workspace gets that far).
    fn reach(v: &mut Vec<Vec<f64>>, z: &mut Vec<Vec<f64>>, k: usize, n: usize) {
        while z.len() <= k {
            z.push(vec![0.0; n]);
        }
        while v.len() <= k + 1 {
            v.push(vec![0.0; n]);
        }
    }

    /// Bytes held.
    /// The residual `b − A x` of the last [`gmres`] solve with this workspace, at its
    /// solution (each solve ends by computing it, whether it converged or not).
    pub fn residual(&self) -> &[f64] {
        &self.v[0]
    }

    pub fn bytes(&self) -> usize {
        8 * (self.w.len() * (1 + self.v.len() + self.z.len()))
    }
}

/// Solves `A x = b` by FGMRES(`restart`) with `apply(v, out)`: `out = A v` and
/// `precond(v, out)`: `out ≈ A⁻¹ v`; `x` holds the initial guess. Stops at
/// `‖b − A x‖₂ ≤ ctl.rel_tol ‖b − A x₀‖₂` or after `ctl.max_iter` iterations (`converged:
/// false`, not an error). One iteration = one `precond` and one `apply`.
///
/// # Errors
/// [`SolveError::Diverged`] if a residual is not finite or grows beyond
/// [`crate::solve::DIVERGED`] times the initial one.
pub fn gmres(
    apply: &mut dyn FnMut(&[f64], &mut [f64]),
    precond: &mut dyn FnMut(&[f64], &mut [f64]),
    b: &[f64],
    x: &mut [f64],
    ctl: &SolveControl,
    restart: usize,
    ws: &mut GmresWorkspace,
) -> Result<SolveInfo, SolveError> {
    let n = b.len();
    assert_eq!(x.len(), n, "gmres: solution length");
    let m = restart.max(1);
    ws.fit(n);
    let GmresWorkspace { v, z, w } = ws;
    // r = b − A x into v_0
    let residual =
        |apply: &mut dyn FnMut(&[f64], &mut [f64]), x: &[f64], r: &mut [f64], w: &mut [f64]| {
            apply(x, w);
            update(r, |i, ri| *ri = b[i] - w[i]);
            dot(r, r).sqrt()
        };
    // from zero the residual is b itself: no product with the operator (Newton's corrections
    // start from zero: one product with the Jacobian fewer per Newton step)
    let mut beta = if x.iter().all(|&xi| xi == 0.0) {
        update(&mut v[0], |i, ri| *ri = b[i]);
        dot(&v[0], &v[0]).sqrt()
    } else {
        residual(apply, x, &mut v[0], w)
    };
    let r0 = beta;
    if let Some(done) = SolveInfo::start(r0)? {
        return Ok(done);
    }
    let mut info = SolveInfo::default();
    // Hessenberg columns (rotated), rotations and the rotated right-hand side
    let mut h = vec![vec![0.0f64; m + 1]; m];
    let (mut cs, mut sn) = (vec![0.0f64; m], vec![0.0f64; m]);
    let mut g = vec![0.0f64; m + 1];
    while info.iterations < ctl.max_iter {
        let inv = 1.0 / beta;
        update(&mut v[0], |_, vi| *vi *= inv);
        g.fill(0.0);
        g[0] = beta;
        let mut k = 0;
        while k < m && info.iterations < ctl.max_iter {
            GmresWorkspace::reach(v, z, k, n);
            precond(&v[k], &mut z[k]);
            apply(&z[k], w);
            let col = &mut h[k];
            for (i, vi) in v.iter().enumerate().take(k + 1) {
                let hik = dot(w, vi);
                col[i] = hik;
                update(w, |p, wp| *wp -= hik * vi[p]);
            }
            let hn = dot(w, w).sqrt();
            col[k + 1] = hn;
            if hn > 0.0 {
                let inv = 1.0 / hn;
                update(&mut v[k + 1], |p, vp| *vp = w[p] * inv);
            }
            for i in 0..k {
                let (a, c) = (col[i], col[i + 1]);
                col[i] = cs[i] * a + sn[i] * c;
                col[i + 1] = -sn[i] * a + cs[i] * c;
            }
            let (a, c) = (col[k], col[k + 1]);
            let rr = a.hypot(c);
            (cs[k], sn[k]) = if rr > 0.0 {
                (a / rr, c / rr)
            } else {
                (1.0, 0.0)
            };
            col[k] = rr;
            col[k + 1] = 0.0;
            g[k + 1] = -sn[k] * g[k];
            g[k] *= cs[k];
            k += 1;
            info.iterations += 1;
            let rel = g[k].abs() / r0;
            info.residual_history.push(rel);
            if rel.is_nan() || rel > DIVERGED {
                return Err(SolveError::Diverged(rel));
            }
            if rel <= ctl.rel_tol || hn == 0.0 {
                break;
            }
        }
        // y = H⁻¹ g (upper triangular k × k), x += Z y
        let mut y = vec![0.0f64; k];
        for i in (0..k).rev() {
            let s: f64 = (i + 1..k).map(|q| h[q][i] * y[q]).sum();
            y[i] = if h[i][i] != 0.0 {
                (g[i] - s) / h[i][i]
            } else {
                0.0
            };
        }
        for (zq, yq) in z.iter().zip(&y) {
            update(x, |p, xp| *xp += yq * zq[p]);
        }
        beta = residual(apply, x, &mut v[0], w);
        let rel = beta / r0;
        if let Some(last) = info.residual_history.last_mut() {
            *last = rel;
        }
        if !rel.is_finite() || rel > DIVERGED {
            return Err(SolveError::Diverged(rel));
        }
        if rel <= ctl.rel_tol {
            info.converged = true;
            break;
        }
        if beta == 0.0 {
            info.converged = true;
            break;
        }
    }
    Ok(info)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-symmetric tridiagonal (convection–diffusion) system against its exact solution;
    /// with the exact inverse of its symmetric part as preconditioner GMRES needs few
    /// iterations, without one restarts still converge.
    #[test]
    fn solves_a_nonsymmetric_system_with_and_without_preconditioner() {
        let n = 200;
        let (d, lo, up) = (2.0, -1.3, -0.7);
        let apply = |v: &[f64], out: &mut [f64]| {
            for i in 0..n {
                let l = if i > 0 { v[i - 1] } else { 0.0 };
                let u = if i + 1 < n { v[i + 1] } else { 0.0 };
                out[i] = d * v[i] + lo * l + up * u;
            }
        };
        let exact: Vec<f64> = (0..n).map(|i| ((i as f64) * 0.1).sin()).collect();
        let mut b = vec![0.0; n];
        apply(&exact, &mut b);
        let ctl = SolveControl {
            rel_tol: 1e-10,
            max_iter: 2000,
        };
        let mut ws = GmresWorkspace::default();
        let mut x = vec![0.0; n];
        let plain = gmres(
            &mut |v, o| apply(v, o),
            &mut |v, o| o.copy_from_slice(v),
            &b,
            &mut x,
            &ctl,
            30,
            &mut ws,
        )
        .unwrap();
        assert!(plain.converged, "{plain:?}");
        for (u, e) in x.iter().zip(&exact) {
            assert!((u - e).abs() < 1e-7, "{u} vs {e}");
        }
        // preconditioner: the tridiagonal (2, −1, −1) solved exactly (Thomas)
        let thomas = |r: &[f64], out: &mut [f64]| {
            let mut c = vec![0.0; n];
            let mut dd = vec![0.0; n];
            let (a, bb) = (-1.0, 2.0);
            c[0] = a / bb;
            dd[0] = r[0] / bb;
            for i in 1..n {
                let m = bb - a * c[i - 1];
                c[i] = a / m;
                dd[i] = (r[i] - a * dd[i - 1]) / m;
            }
            out[n - 1] = dd[n - 1];
            for i in (0..n - 1).rev() {
                out[i] = dd[i] - c[i] * out[i + 1];
            }
        };
        let mut x = vec![0.0; n];
        let pre = gmres(
            &mut |v, o| apply(v, o),
            &mut |v, o| thomas(v, o),
            &b,
            &mut x,
            &ctl,
            30,
            &mut ws,
        )
        .unwrap();
        assert!(pre.converged, "{pre:?}");
        assert!(
            pre.iterations < plain.iterations / 2,
            "{} vs {}",
            pre.iterations,
            plain.iterations
        );
        for (u, e) in x.iter().zip(&exact) {
            assert!((u - e).abs() < 1e-7, "{u} vs {e}");
        }
        // the reported relative residual is the true one
        let mut r = vec![0.0; n];
        apply(&x, &mut r);
        let true_rel = r
            .iter()
            .zip(&b)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt()
            / b.iter().map(|v| v * v).sum::<f64>().sqrt();
        let last = *pre.residual_history.last().unwrap();
        assert!(
            (true_rel - last).abs() <= 1e-3 * last.max(1e-14),
            "{true_rel} vs {last}"
        );
    }

    /// The basis holds the vectors the iterations reached, not `restart` (#16: the Newton
    /// steps' Krylov solves converge in a few iterations on most grids).
    #[test]
    fn the_basis_grows_with_the_iterations() {
        let n = 1000;
        let b: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
        let mut ws = GmresWorkspace::default();
        let mut x = vec![0.0; n];
        // A = 2 I, preconditioned by its exact inverse: one iteration
        let info = gmres(
            &mut |v, o| o.iter_mut().zip(v).for_each(|(o, v)| *o = 2.0 * v),
            &mut |v, o| o.iter_mut().zip(v).for_each(|(o, v)| *o = 0.5 * v),
            &b,
            &mut x,
            &SolveControl::default(),
            30,
            &mut ws,
        )
        .unwrap();
        assert!(info.converged && info.iterations == 1, "{info:?}");
        assert!(x.iter().zip(&b).all(|(x, b)| (x - 0.5 * b).abs() < 1e-14));
        // w, v_0, v_1 and z_0
        assert_eq!(ws.bytes(), 8 * n * 4);
    }

    /// From zero the first residual is b, with no product (#16: a Newton step's Krylov solve
    /// of k iterations costs k + 1 products with the Jacobian, not k + 2); from a non-zero
    /// start the residual is computed, and both give the same solution.
    #[test]
    fn a_start_from_zero_takes_no_product_for_the_first_residual() {
        let n = 50;
        let apply = |v: &[f64], out: &mut [f64]| {
            for i in 0..n {
                let l = if i > 0 { v[i - 1] } else { 0.0 };
                let u = if i + 1 < n { v[i + 1] } else { 0.0 };
                out[i] = 3.0 * v[i] - l - 0.5 * u;
            }
        };
        let b: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64 * 0.3).sin()).collect();
        let ctl = SolveControl {
            rel_tol: 1e-12,
            max_iter: 100,
        };
        let mut ws = GmresWorkspace::default();
        let run = |x: &mut Vec<f64>, ws: &mut GmresWorkspace| {
            let mut products = 0usize;
            let info = gmres(
                &mut |v, o| {
                    products += 1;
                    apply(v, o)
                },
                &mut |v, o| o.copy_from_slice(v),
                &b,
                x,
                &ctl,
                100,
                ws,
            )
            .unwrap();
            (info, products)
        };
        let mut x = vec![0.0; n];
        let (info, products) = run(&mut x, &mut ws);
        assert!(info.converged, "{info:?}");
        // one product per iteration and the true residual at the end
        assert_eq!(products, info.iterations + 1);
        // a start of ~0: the first residual computed, the same solution
        let mut y = vec![0.0; n];
        y[7] = 1e-300;
        let (again, more) = run(&mut y, &mut ws);
        assert!(again.converged, "{again:?}");
        assert_eq!(more, again.iterations + 2);
        for (u, v) in x.iter().zip(&y) {
            assert!((u - v).abs() < 1e-10, "{u} vs {v}");
        }
    }

    #[test]
    fn zero_right_hand_side_is_solved_at_once() {
        let mut ws = GmresWorkspace::default();
        let mut x = vec![0.0; 5];
        let info = gmres(
            &mut |v, o| o.copy_from_slice(v),
            &mut |v, o| o.copy_from_slice(v),
            &[0.0; 5],
            &mut x,
            &SolveControl::default(),
            5,
            &mut ws,
        )
        .unwrap();
        assert!(info.converged && info.iterations == 0);
    }
}
