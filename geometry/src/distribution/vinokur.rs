//! Vinokur's stretching functions \[Vinokur 1983\], fitted to hit the end spacings exactly.
//!
//! Two-sided (FORMATS.md "Stretching"): with B = 1/√(DS₀DS₁), A = √(DS₁/DS₀), DS = Δs·N,
//! u(ξ) = ½[1 + tanh(δ(ξ − ½))/tanh(δ/2)] where sinh δ/δ = B (B > 1), or with tan and
//! sin δ/δ = B (B < 1), and σ = u/(A + (1 − A)u). One-sided (only Δs₀): u(ξ) = 1 +
//! tanh(δ(ξ − 1)/2)/tanh(δ/2), sinh δ/δ = 1/DS₀ (tan/sin when DS₀ > 1).
//!
//! These formulas match the end *slopes* dσ/dξ; the first *interval* σ₁ − σ₀ differs by
//! O(1/N²) relative. So (ln B, ln A) are treated as free parameters and a 2×2 (1×1 one-sided)
//! Newton iteration with a finite-difference Jacobian drives ln σ₁ − ln Δs₀ and
//! ln(1 − σ_{N−1}) − ln Δs₁ to rounding level. The slope formulas give the starting point.
//!
//! Every closed form is rewritten without cancellation (tanh a ± tanh b = sinh(a ± b)/(cosh a
//! cosh b)), and both u and 1 − u are computed directly, so tiny spacings at either end keep
//! full relative accuracy (only the final rounding of σ near 1, ≤ 5.6e-17 absolute, remains).

use super::{check_n, check_sigma, check_spacing, uniform};
use crate::GeometryError;

/// Which branch of the stretching function, with its δ.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    /// B = 1: the identity.
    Uniform,
    /// B > 1: sinh δ / δ = B.
    Hyper(f64),
    /// B < 1: sin δ / δ = B, 0 < δ < π.
    Trig(f64),
}

/// Largest δ used (sinh(δ) stays finite); corresponds to spacings far below 1e-300.
const DELTA_MAX: f64 = 700.0;

/// sinh δ / δ − 1 (hyperbolic) or sin δ / δ − 1 (trig, sign = −1) by its series, for δ < 1.
fn sinc_m1_series(delta: f64, sign: f64) -> f64 {
    let d2 = sign * delta * delta;
    let (mut term, mut sum) = (1.0, 0.0);
    for j in 1..20 {
        term *= d2 / ((2 * j) as f64 * (2 * j + 1) as f64);
        sum += term;
        if term.abs() <= 1e-18 * sum.abs() {
            break;
        }
    }
    sum
}

/// ln(sinh δ / δ), accurate for small and large δ.
fn ln_sinhc(delta: f64) -> f64 {
    if delta < 1.0 {
        sinc_m1_series(delta, 1.0).ln_1p()
    } else {
        delta + (-(-2.0 * delta).exp_m1()).ln() - std::f64::consts::LN_2 - delta.ln()
    }
}

/// ln(sin δ / δ) for 0 < δ < π.
fn ln_sinc(delta: f64) -> f64 {
    if delta < 1.0 {
        sinc_m1_series(delta, -1.0).ln_1p()
    } else {
        (delta.sin() / delta).ln()
    }
}

/// δ from ln B: solves ln(sinh δ/δ) = ln B or ln(sin δ/δ) = ln B by safeguarded Newton.
fn shape(ln_b: f64) -> Shape {
    if ln_b == 0.0 {
        return Shape::Uniform;
    }
    let hyper = ln_b > 0.0;
    let f = |d: f64| {
        if hyper {
            ln_sinhc(d) - ln_b
        } else {
            ln_sinc(d) - ln_b
        }
    };
    // f' = coth δ − 1/δ (hyperbolic) or cot δ − 1/δ (trig); only steers Newton.
    let df = |d: f64| {
        if d < 1e-3 {
            if hyper {
                d / 3.0
            } else {
                -d / 3.0
            }
        } else if hyper {
            1.0 / d.tanh() - 1.0 / d
        } else {
            1.0 / d.tan() - 1.0 / d
        }
    };
    // Bracket with f(lo) < 0 < f(hi) for the hyperbolic branch (f increasing), reversed for trig.
    let (mut lo, mut hi) = if hyper {
        let mut hi = 1.0;
        while f(hi) < 0.0 && hi < DELTA_MAX {
            hi *= 2.0;
        }
        (0.0, hi.min(DELTA_MAX))
    } else {
        (0.0, std::f64::consts::PI)
    };
    // Start: δ ≈ √(6 |ln B|) (small δ), else the middle of the bracket.
    let mut d = (6.0 * ln_b.abs()).sqrt();
    if !(d > lo && d < hi) {
        d = 0.5 * (lo + hi);
    }
    for _ in 0..200 {
        let r = f(d);
        if r == 0.0 {
            break;
        }
        // r > 0: δ too big on the hyperbolic branch (f increasing), too small on the trig one.
        if (r > 0.0) == hyper {
            hi = d;
        } else {
            lo = d;
        }
        let mut next = d - r / df(d);
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        let done = (next - d).abs() <= 2.0 * f64::EPSILON * d;
        d = next;
        if done {
            break;
        }
    }
    if d == 0.0 {
        Shape::Uniform
    } else if hyper {
        Shape::Hyper(d)
    } else {
        Shape::Trig(d)
    }
}

/// Two-sided u and 1 − u at ξ = i/N (cancellation free).
fn two_sided(shape: Shape, i: usize, intervals: usize) -> (f64, f64) {
    let nf = intervals as f64;
    let (xi, xi_c) = (i as f64 / nf, (intervals - i) as f64 / nf);
    let centered = (2.0 * i as f64 - nf) / (2.0 * nf);
    match shape {
        Shape::Uniform => (xi, xi_c),
        Shape::Hyper(d) => {
            let den = 2.0 * (0.5 * d).sinh() * (d * centered).cosh();
            ((d * xi).sinh() / den, (d * xi_c).sinh() / den)
        }
        Shape::Trig(d) => {
            let den = 2.0 * (0.5 * d).sin() * (d * centered).cos();
            ((d * xi).sin() / den, (d * xi_c).sin() / den)
        }
    }
}

/// One-sided (clustered at ξ = 0) u and 1 − u at ξ = i/N (cancellation free).
fn one_sided(shape: Shape, i: usize, intervals: usize) -> (f64, f64) {
    let nf = intervals as f64;
    let (xi, xi_c) = (i as f64 / nf, (intervals - i) as f64 / nf);
    match shape {
        Shape::Uniform => (xi, xi_c),
        Shape::Hyper(d) => (
            (0.5 * d * xi).sinh() / ((0.5 * d).sinh() * (0.5 * d * xi_c).cosh()),
            (0.5 * d * xi_c).tanh() / (0.5 * d).tanh(),
        ),
        Shape::Trig(d) => (
            (0.5 * d * xi).sin() / ((0.5 * d).sin() * (0.5 * d * xi_c).cos()),
            (0.5 * d * xi_c).tan() / (0.5 * d).tan(),
        ),
    }
}

/// σ and 1 − σ of the two-sided map: σ = u/(A(1 − u) + u), 1 − σ = A(1 − u)/(A(1 − u) + u).
fn two_sided_sigma(shape: Shape, a: f64, i: usize, intervals: usize) -> (f64, f64) {
    let (u, w) = two_sided(shape, i, intervals);
    let den = a * w + u;
    (u / den, a * w / den)
}

/// The node value from an accurate pair (σ, 1 − σ): whichever keeps more digits.
fn pick(pair: (f64, f64)) -> f64 {
    if pair.0 <= 0.5 {
        pair.0
    } else {
        1.0 - pair.1
    }
}

/// Vinokur stretching on n nodes with optional first and last spacings (fractions of the
/// length), hit to rounding level: relative error ~1e-15 for the first spacing, and ≤ 5.6e-17
/// absolute for the last (the rounding of σ_{n−2} near 1). Uniform when neither is given.
///
/// # Errors
/// n < 2; a spacing not finite or not in (0, 1); first + last ≥ 1 (for n = 3: ≠ 1); n = 2 with
/// a spacing; or an unattainable combination (the fit does not converge).
pub fn vinokur(n: usize, first: Option<f64>, last: Option<f64>) -> Result<Vec<f64>, GeometryError> {
    vinokur_refined(n, first, last, 0)
}

/// The stretching function fitted for `n` nodes ([`vinokur`]), sampled `level` times finer in
/// its parameter ξ: (n − 1)·2^level + 1 nodes at ξ = i/((n − 1)·2^level). Node i·2^level is
/// bit for bit node i of `vinokur(n, first, last)` (ξ scaled by a power of two is exact), so
/// the coarse nodes are every 2^level-th node of the fine ones, and the end spacings shrink by
/// ~2^level (to first order; the function, not the spacing, is kept). With n = 3 and both
/// spacings (no stretching function, σ = [0, first, 1]) the fine nodes are linear in between.
///
/// # Errors
/// Those of [`vinokur`], and a node count that overflows.
pub fn vinokur_refined(
    n: usize,
    first: Option<f64>,
    last: Option<f64>,
    level: u32,
) -> Result<Vec<f64>, GeometryError> {
    const WHAT: &str = "Vinokur distribution";
    check_n(n)?;
    for (name, d) in [("first", first), ("last", last)] {
        if let Some(d) = d {
            check_spacing(WHAT, name, d)?;
        }
    }
    let intervals = n - 1;
    let fine = super::refined_intervals(intervals, level)?;
    if intervals == 1 && (first.is_some() || last.is_some()) {
        return Err(GeometryError::Invalid(format!(
            "{WHAT}: 2 nodes have a single interval of length 1; no end spacing can be prescribed"
        )));
    }
    let finish = |mut sigma: Vec<f64>| {
        sigma[0] = 0.0;
        sigma[fine] = 1.0;
        check_sigma(WHAT, sigma)
    };
    match (first, last) {
        (None, None) => Ok(uniform(fine + 1)),
        (Some(d0), Some(d1)) => {
            if intervals == 2 {
                if (d0 + d1 - 1.0).abs() > 1e-12 {
                    return Err(GeometryError::Invalid(format!(
                        "{WHAT}: with 3 nodes first + last must be 1, got {d0} + {d1}"
                    )));
                }
                return super::fill_linear(check_sigma(WHAT, vec![0.0, d0, 1.0])?, level);
            }
            if d0 + d1 >= 1.0 {
                return Err(GeometryError::Invalid(format!(
                    "{WHAT}: first + last spacing = {} must be below 1 (the whole length)",
                    d0 + d1
                )));
            }
            let (shape, a) = fit_two_sided(intervals, d0, d1)?;
            finish(
                (0..=fine)
                    .map(|i| pick(two_sided_sigma(shape, a, i, fine)))
                    .collect(),
            )
        }
        (Some(d0), None) => {
            let shape = fit_one_sided(intervals, d0)?;
            finish(
                (0..=fine)
                    .map(|i| pick(one_sided(shape, i, fine)))
                    .collect(),
            )
        }
        (None, Some(d1)) => {
            // Mirror of the one-sided map: σ_i = 1 − u(ξ_{N−i}), from the accurate pair.
            let shape = fit_one_sided(intervals, d1)?;
            finish(
                (0..=fine)
                    .map(|i| {
                        let (u, w) = one_sided(shape, fine - i, fine);
                        pick((w, u))
                    })
                    .collect(),
            )
        }
    }
}

/// Newton on ln B for the one-sided map: ln σ₁ = ln Δs₀.
fn fit_one_sided(intervals: usize, d0: f64) -> Result<Shape, GeometryError> {
    let residual = |ln_b: f64| one_sided(shape(ln_b), 1, intervals).0.ln() - d0.ln();
    let x0 = -(d0 * intervals as f64).ln();
    let x = newton(2.0 * f64::EPSILON, x0, 0.0, |x| (residual(x[0]), 0.0), true)
        .map_err(|(it, r)| no_convergence("one-sided", it, r))?;
    Ok(shape(x[0]))
}

/// 2×2 Newton on (ln B, ln A): ln σ₁ = ln Δs₀ and ln(1 − σ_{N−1}) = ln Δs₁.
fn fit_two_sided(intervals: usize, d0: f64, d1: f64) -> Result<(Shape, f64), GeometryError> {
    let (ds0, ds1) = (d0 * intervals as f64, d1 * intervals as f64);
    let residual = |x: [f64; 2]| {
        let (sh, a) = (shape(x[0]), x[1].exp());
        let first = two_sided_sigma(sh, a, 1, intervals).0;
        let last = two_sided_sigma(sh, a, intervals - 1, intervals).1;
        (first.ln() - d0.ln(), last.ln() - d1.ln())
    };
    let x = newton(
        2.0 * f64::EPSILON,
        -0.5 * (ds0 * ds1).ln(),
        0.5 * (ds1 / ds0).ln(),
        residual,
        false,
    )
    .map_err(|(it, r)| no_convergence("two-sided", it, r))?;
    Ok((shape(x[0]), x[1].exp()))
}

fn no_convergence(kind: &str, iterations: usize, residual: f64) -> GeometryError {
    GeometryError::NoConvergence {
        what: format!("Vinokur {kind} fit to the requested spacings (unattainable?)"),
        iterations,
        residual,
    }
}

/// Damped Newton with a central-difference Jacobian on F(x) = 0, x ∈ R² (or R¹ when `scalar`).
///
/// Stops at ‖F‖∞ ≤ tol or when no step reduces ‖F‖∞; succeeds if ‖F‖∞ ≤ 1e-12 (relative
/// spacing error). Err gives (iterations, residual).
fn newton<F>(tol: f64, x0: f64, y0: f64, f: F, scalar: bool) -> Result<[f64; 2], (usize, f64)>
where
    F: Fn([f64; 2]) -> (f64, f64),
{
    let norm = |r: (f64, f64)| r.0.abs().max(r.1.abs());
    let mut x = [x0, y0];
    let mut r = f(x);
    let mut it = 0;
    while it < 100 && norm(r) > tol && norm(r).is_finite() {
        it += 1;
        let h = 1e-6;
        let col = |k: usize| {
            let (mut xp, mut xm) = (x, x);
            xp[k] += h;
            xm[k] -= h;
            let (p, m) = (f(xp), f(xm));
            ((p.0 - m.0) / (2.0 * h), (p.1 - m.1) / (2.0 * h))
        };
        let step = if scalar {
            [r.0 / col(0).0, 0.0]
        } else {
            let (c0, c1) = (col(0), col(1));
            let det = c0.0 * c1.1 - c1.0 * c0.1;
            [
                (r.0 * c1.1 - c1.0 * r.1) / det,
                (c0.0 * r.1 - r.0 * c0.1) / det,
            ]
        };
        if !(step[0].is_finite() && step[1].is_finite()) {
            break;
        }
        // Halve the step until the residual decreases.
        let mut lambda = 1.0;
        let mut accepted = false;
        for _ in 0..40 {
            let trial = [x[0] - lambda * step[0], x[1] - lambda * step[1]];
            let rt = f(trial);
            if norm(rt) < norm(r) {
                x = trial;
                r = rt;
                accepted = true;
                break;
            }
            lambda *= 0.5;
        }
        if !accepted {
            break;
        }
    }
    if norm(r) <= 1e-12 {
        Ok(x)
    } else {
        Err((it, norm(r)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative error of a spacing.
    fn rel(got: f64, want: f64) -> f64 {
        (got - want).abs() / want
    }

    /// Monotone, exact ends, spacings hit; the last one up to the rounding of σ near 1.
    fn check(n: usize, first: Option<f64>, last: Option<f64>) {
        let s = vinokur(n, first, last).unwrap_or_else(|e| panic!("n {n} {first:?} {last:?}: {e}"));
        assert_eq!(s.len(), n);
        assert_eq!(s[0], 0.0);
        assert_eq!(s[n - 1], 1.0);
        assert!(
            s.windows(2).all(|w| w[1] > w[0]),
            "not monotone: n {n} {first:?} {last:?}"
        );
        if let Some(d0) = first {
            assert!(
                rel(s[1] - s[0], d0) < 1e-13,
                "first n {n} {first:?} {last:?}: {}",
                s[1]
            );
        }
        if let Some(d1) = last {
            let tol = 1e-13 + 0.6e-16 / d1;
            assert!(
                rel(s[n - 1] - s[n - 2], d1) < tol.min(1e-10),
                "last n {n} {first:?} {last:?}"
            );
        }
    }

    #[test]
    fn strong_clustering_one_and_two_sided() {
        for &n in &[33usize, 65, 129, 257, 513] {
            for &d0 in &[1e-4, 1e-5, 1e-6] {
                check(n, Some(d0), None);
                check(n, None, Some(d0 * 10.0));
                for &d1 in &[1e-5, 1e-4, 1e-3, 1e-2, 0.05] {
                    check(n, Some(d0), Some(d1));
                }
            }
        }
    }

    #[test]
    fn many_combinations_incl_coarser_than_uniform() {
        // Spacings above uniform (B < 1, the sin/tan branch), mixed, and near uniform.
        for &n in &[3usize, 4, 5, 9, 17, 33, 100, 513] {
            let uni = 1.0 / (n - 1) as f64;
            for &f0 in &[0.01, 0.3, 0.9, 1.0, 1.000_001, 1.1, 2.0, 5.0] {
                for &f1 in &[None, Some(0.01), Some(0.5), Some(1.0), Some(1.3), Some(3.0)] {
                    let d0 = f0 * uni;
                    let d1 = f1.map(|f: f64| f * uni);
                    let total = d0 + d1.unwrap_or(0.0);
                    if d0 >= 1.0 || total >= 1.0 || (n == 3 && d1.is_some()) {
                        continue;
                    }
                    check(n, Some(d0), d1);
                    check(n, d1, Some(d0));
                }
            }
        }
        check(3, Some(0.3), Some(0.7));
    }

    #[test]
    fn larger_than_uniform_both_ends_is_trig_branch() {
        let (n, d) = (33, 0.05); // uniform 0.03125
        let s = vinokur(n, Some(d), Some(d)).unwrap();
        assert!(rel(s[1], d) < 1e-14 && rel(1.0 - s[n - 2], d) < 1e-14);
        // Symmetric request → symmetric distribution, smallest spacing in the middle.
        for i in 0..n {
            assert!((s[i] + s[n - 1 - i] - 1.0).abs() < 1e-15);
        }
        let mid = s[n / 2 + 1] - s[n / 2];
        assert!(mid < 1.0 / 32.0 && mid < s[1]);
        assert!(matches!(shape(-0.1), Shape::Trig(_)));
    }

    #[test]
    fn fit_matters_slope_formula_alone_misses() {
        // The starting point (pure slope matching) is off by much more than 1e-10; the fit fixes it.
        let (n, d0, d1) = (33usize, 1e-4, 1e-2);
        let nn = (n - 1) as f64;
        let ln_b = -0.5 * (d0 * nn * d1 * nn).ln();
        let a = (d1 / d0).sqrt();
        let raw = two_sided_sigma(shape(ln_b), a, 1, n - 1).0;
        assert!(rel(raw, d0) > 1e-4, "{raw}");
        check(n, Some(d0), Some(d1));
    }

    #[test]
    fn uniform_cases() {
        assert_eq!(vinokur(9, None, None).unwrap(), uniform(9));
        let s = vinokur(9, Some(0.125), Some(0.125)).unwrap();
        for (a, b) in s.iter().zip(uniform(9)) {
            assert!((a - b).abs() < 1e-15);
        }
        // ln(sinh δ/δ) = δ²/6 − δ⁴/180 + O(δ⁶).
        assert!((ln_sinhc(1e-4) - (1e-8 / 6.0 - 1e-16 / 180.0)).abs() < 1e-24);
        assert!((ln_sinc(0.5) - (0.5f64.sin() / 0.5).ln()).abs() < 1e-16);
        // δ solves its equation to rounding, relative to ln B, on both branches.
        for &lb in &[1e-12, 1e-3, 0.7, 5.0, 20.0] {
            let Shape::Hyper(d) = shape(lb) else { panic!() };
            assert!((ln_sinhc(d) - lb).abs() < 1e-13 * lb, "{lb}");
            let lt = if lb > 3.0 { 3.0 } else { lb };
            let Shape::Trig(d) = shape(-lt) else { panic!() };
            assert!((ln_sinc(d) + lt).abs() < 1e-13 * lt, "{lt}");
        }
    }

    #[test]
    fn impossible_requests_are_errors() {
        assert!(vinokur(1, None, None).is_err());
        assert!(vinokur(2, Some(0.5), None).is_err());
        assert!(vinokur(10, Some(1.0), None).is_err());
        assert!(vinokur(10, Some(1.5), None).is_err());
        assert!(vinokur(10, Some(0.0), None).is_err());
        assert!(vinokur(10, Some(-1e-3), None).is_err());
        assert!(vinokur(10, Some(f64::NAN), None).is_err());
        assert!(vinokur(10, None, Some(f64::INFINITY)).is_err());
        assert!(vinokur(10, Some(0.6), Some(0.4)).is_err());
        assert!(vinokur(10, Some(0.6), Some(0.5)).is_err());
        assert!(vinokur(3, Some(0.2), Some(0.3)).is_err());
        let e = vinokur(10, Some(0.6), Some(0.4)).unwrap_err().to_string();
        assert!(e.contains("below 1"), "{e}");
    }

    #[test]
    fn refined_samples_nest_the_coarse_nodes_bit_for_bit() {
        for (first, last) in [
            (None, None),
            (Some(1e-4), None),
            (None, Some(1e-3)),
            (Some(2e-3), Some(1e-2)),
            (Some(0.05), Some(0.05)), // the trig branch
        ] {
            let coarse = vinokur(33, first, last).unwrap();
            for level in 1..4u32 {
                let fine = vinokur_refined(33, first, last, level).unwrap();
                let step = 1 << level;
                assert_eq!(fine.len(), 32 * step + 1);
                for (i, c) in coarse.iter().enumerate() {
                    assert_eq!(
                        fine[i * step],
                        *c,
                        "{first:?} {last:?} level {level} node {i}"
                    );
                }
                assert!(fine.windows(2).all(|w| w[1] > w[0]));
                // the end spacings shrink like 2^-level (the function's slope at the ends)
                if let Some(d0) = first {
                    let r = d0 / fine[1];
                    // (intervals, not slopes: off by the curvature of σ near the end)
                    assert!((r / step as f64 - 1.0).abs() < 0.15, "{r}");
                }
            }
        }
        let three = vinokur_refined(3, Some(0.3), Some(0.7), 1).unwrap();
        for (a, b) in three.iter().zip([0.0, 0.15, 0.3, 0.65, 1.0]) {
            assert!((a - b).abs() < 1e-15, "{three:?}");
        }
        assert!(vinokur_refined(33, Some(1e-3), None, 70).is_err());
    }
}
