//! Normalized point distributions σ_0 = 0 < σ_1 < … < σ_{n−1} = 1 on [0, 1].
//!
//! They feed the boundary point distribution of METHOD.md [30–38]: the nodes of an edge are the
//! curve points at these normalized arclengths ([`crate::sample`]). Spacings are fractions of
//! the edge length. `uniform`, `geometric` (constant ratio) and `vinokur` (\[Vinokur 1983\]
//! tanh/tan stretching that hits requested end spacings exactly); clustering at the end of an
//! edge is asked for by `last`, and [`reverse`] mirrors a distribution.

mod vinokur;

pub use vinokur::{vinokur, vinokur_refined};

use crate::GeometryError;

/// A point distribution rule; [`Distribution::sample`] gives the σ values for n nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Distribution {
    /// Equal spacing.
    Uniform,
    /// Constant growth ratio with the given first spacing (fraction of the length).
    Geometric {
        /// First spacing σ_1 − σ_0.
        first: f64,
    },
    /// Vinokur stretching with optional first and last spacings (fractions of the length).
    Vinokur {
        /// First spacing σ_1 − σ_0, if prescribed.
        first: Option<f64>,
        /// Last spacing σ_{n−1} − σ_{n−2}, if prescribed.
        last: Option<f64>,
    },
}

impl Distribution {
    /// The n node values (n ≥ 2).
    ///
    /// # Errors
    /// n < 2 or spacings that cannot be realised (see [`geometric`], [`vinokur`]).
    pub fn sample(&self, n: usize) -> Result<Vec<f64>, GeometryError> {
        check_n(n)?;
        match *self {
            Distribution::Uniform => Ok(uniform(n)),
            Distribution::Geometric { first } => geometric(n, first),
            Distribution::Vinokur { first, last } => vinokur(n, first, last),
        }
    }

    /// The distribution of n nodes refined `level` times in its own parameter, with
    /// (n − 1)·2^level + 1 nodes: node i·2^level equals node i of
    /// [`Distribution::sample`]`(n)` bit for bit, the nodes in between lie on the same
    /// continuous function σ(ξ) (grid families for convergence studies: the coarse nodes are
    /// every 2^level-th node of the fine ones).
    ///
    /// - uniform: the uniform distribution of the finer count;
    /// - geometric: σ(k + τ) = σ_k + Δ_k (r^τ − 1)/(r − 1) between nodes k and k + 1, which is
    ///   the geometric distribution with ratio r^(1/2^level) (first spacing ~first/2^level);
    /// - Vinokur: the fitted stretching function at the finer ξ ([`vinokur_refined`]).
    ///
    /// # Errors
    /// Those of [`Distribution::sample`], and a node count that overflows.
    pub fn sample_refined(&self, n: usize, level: u32) -> Result<Vec<f64>, GeometryError> {
        check_n(n)?;
        let fine = refined_intervals(n - 1, level)?;
        match *self {
            Distribution::Uniform => Ok(uniform(fine + 1)),
            Distribution::Geometric { first } => {
                let sigma = geometric(n, first)?;
                let r = if n > 2 {
                    geometric_ratio(n - 1, first)
                } else {
                    1.0
                };
                fill(sigma, level, |tau| {
                    if r == 1.0 {
                        tau
                    } else {
                        (tau * r.ln()).exp_m1() / r.ln().exp_m1()
                    }
                })
            }
            Distribution::Vinokur { first, last } => vinokur_refined(n, first, last, level),
        }
    }
}

/// (intervals)·2^level, or an error if it does not fit.
pub(crate) fn refined_intervals(intervals: usize, level: u32) -> Result<usize, GeometryError> {
    1usize
        .checked_shl(level)
        .filter(|_| level < usize::BITS)
        .and_then(|m| intervals.checked_mul(m))
        .filter(|&f| f < usize::MAX)
        .ok_or_else(|| {
            GeometryError::Invalid(format!(
                "{intervals} intervals refined {level} times overflow the node count"
            ))
        })
}

/// The nodes σ refined `level` times by f(τ) within each interval (f(0) = 0, f(1) = 1,
/// increasing): σ_k + (σ_{k+1} − σ_k) f(j/2^level), the coarse nodes kept bit for bit.
fn fill(sigma: Vec<f64>, level: u32, f: impl Fn(f64) -> f64) -> Result<Vec<f64>, GeometryError> {
    let m = 1usize << level;
    let mut out = Vec::with_capacity(refined_intervals(sigma.len() - 1, level)? + 1);
    for w in sigma.windows(2) {
        out.push(w[0]);
        for j in 1..m {
            out.push(w[0] + (w[1] - w[0]) * f(j as f64 / m as f64));
        }
    }
    out.push(sigma[sigma.len() - 1]);
    check_sigma("refined distribution", out)
}

/// The nodes σ refined `level` times linearly within each interval.
pub(crate) fn fill_linear(sigma: Vec<f64>, level: u32) -> Result<Vec<f64>, GeometryError> {
    fill(sigma, level, |tau| tau)
}

/// σ_i = i/(n − 1).
///
/// # Panics
/// If n < 2.
pub fn uniform(n: usize) -> Vec<f64> {
    assert!(n >= 2, "a distribution needs at least 2 nodes, got {n}");
    let m = (n - 1) as f64;
    (0..n).map(|i| i as f64 / m).collect()
}

/// Geometric growth Δ_k = first · r^k, k = 0 … n − 2, with r from Σ Δ_k = 1 (FORMATS.md).
///
/// r < 1 when `first` > 1/(n − 1), r > 1 when smaller, r = 1 when equal. σ_1 = `first` exactly;
/// the rounding of Σ Δ_k (≈ 1e-16) is absorbed by the last interval.
///
/// # Errors
/// n < 2, `first` not in (0, 1) (for n = 2: not 1), or spacings too small to represent.
pub fn geometric(n: usize, first: f64) -> Result<Vec<f64>, GeometryError> {
    check_n(n)?;
    if n == 2 {
        if (first - 1.0).abs() <= 1e-12 {
            return Ok(vec![0.0, 1.0]);
        }
        return Err(GeometryError::Invalid(format!(
            "geometric distribution: 2 nodes have one interval of length 1, requested first spacing {first}"
        )));
    }
    check_spacing("geometric distribution", "first", first)?;
    let intervals = n - 1;
    let r = geometric_ratio(intervals, first);
    let mut sigma = Vec::with_capacity(n);
    sigma.push(0.0);
    let mut delta = first;
    for _ in 1..intervals {
        let next = sigma[sigma.len() - 1] + delta;
        sigma.push(next);
        delta *= r;
    }
    sigma.push(1.0);
    check_sigma("geometric distribution", sigma)
}

/// Ratio r of N intervals with first spacing d and total 1: ln(d Σ_{k<N} r^k) = 0, in λ = ln r.
///
/// h(λ) = ln Σ e^{kλ} + ln d is increasing and convex, bracketed by [ln(1 − d), −ln d/(N − 1)]:
/// safeguarded Newton converges to machine precision.
fn geometric_ratio(intervals: usize, d: f64) -> f64 {
    let nf = intervals as f64;
    if (d * nf - 1.0).abs() <= 1e-15 {
        return 1.0;
    }
    let h = |lam: f64| {
        // Σ e^{kλ} and Σ k e^{kλ}, summed with the largest term scaled to 1 (no overflow).
        let kmax = if lam > 0.0 { nf - 1.0 } else { 0.0 };
        let (mut s0, mut s1) = (0.0, 0.0);
        for k in 0..intervals {
            let e = ((k as f64 - kmax) * lam).exp();
            s0 += e;
            s1 += k as f64 * e;
        }
        (s0.ln() + kmax * lam + d.ln(), s1 / s0)
    };
    let (mut lo, mut hi) = if d * nf < 1.0 {
        (0.0, -d.ln() / (nf - 1.0))
    } else {
        ((-d).ln_1p(), 0.0)
    };
    let mut lam = 0.5 * (lo + hi);
    for _ in 0..200 {
        let (f, df) = h(lam);
        if f == 0.0 {
            break;
        }
        if f > 0.0 {
            hi = lam;
        } else {
            lo = lam;
        }
        let mut next = lam - f / df;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - lam).abs() <= 1e-17 * lam.abs().max(1e-300) || hi - lo <= 1e-17 * lam.abs() {
            lam = next;
            break;
        }
        lam = next;
    }
    lam.exp()
}

/// The mirrored distribution: 1 − σ in reverse order (clustering moves to the other end).
pub fn reverse(sigma: &[f64]) -> Vec<f64> {
    sigma.iter().rev().map(|s| 1.0 - s).collect()
}

fn check_n(n: usize) -> Result<(), GeometryError> {
    if n < 2 {
        return Err(GeometryError::Invalid(format!(
            "a distribution needs at least 2 nodes, got {n}"
        )));
    }
    Ok(())
}

/// A requested spacing must be finite and in (0, 1).
fn check_spacing(what: &str, name: &str, d: f64) -> Result<(), GeometryError> {
    if !(d.is_finite() && d > 0.0 && d < 1.0) {
        return Err(GeometryError::Invalid(format!(
            "{what}: {name} spacing must be in (0, 1) as a fraction of the length, got {d}"
        )));
    }
    Ok(())
}

/// Final guard: endpoints exactly 0 and 1, finite, strictly increasing.
fn check_sigma(what: &str, sigma: Vec<f64>) -> Result<Vec<f64>, GeometryError> {
    let n = sigma.len();
    let ok_ends = sigma[0] == 0.0 && sigma[n - 1] == 1.0;
    if let Some(i) =
        (1..n).find(|&i| sigma[i] <= sigma[i - 1] || !sigma[i].is_finite() || sigma[i - 1].is_nan())
    {
        return Err(GeometryError::Invalid(format!(
            "{what}: node {i} is not above node {} (spacing too small to represent?)",
            i - 1
        )));
    }
    if !ok_ends {
        return Err(GeometryError::Invalid(format!(
            "{what}: end values are not 0 and 1"
        )));
    }
    Ok(sigma)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_is_uniform() {
        let s = uniform(5);
        assert_eq!(s, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
        assert_eq!(Distribution::Uniform.sample(2).unwrap(), vec![0.0, 1.0]);
        assert!(Distribution::Uniform.sample(1).is_err());
    }

    #[test]
    fn geometric_hits_first_with_constant_ratio() {
        for &n in &[3usize, 4, 17, 33, 65, 129, 257, 513] {
            for &first in &[1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.05, 0.3, 0.6] {
                let s = match geometric(n, first) {
                    Ok(s) => s,
                    Err(e) => {
                        // Only when the decaying spacings underflow σ's resolution near 1:
                        // first 0.6 gives r ≈ 0.4, Δ_min = 0.6·0.4^(n−2) < 1e-16 for n ≥ 40.
                        assert!(first >= 0.3 && n >= 40, "n {n} first {first}: {e}");
                        continue;
                    }
                };
                assert_eq!(s.len(), n);
                assert_eq!(s[0], 0.0);
                assert_eq!(s[n - 1], 1.0);
                assert_eq!(s[1] - s[0], first);
                let d: Vec<f64> = s.windows(2).map(|w| w[1] - w[0]).collect();
                assert!(d.iter().all(|&x| x > 0.0));
                let r = d[1] / d[0];
                // Differences of σ near 1 carry ~1e-16 absolute rounding.
                for k in 1..d.len() {
                    let tol = 1e-15 * k as f64 / d[k].min(d[k - 1]) + 1e-12;
                    assert!(
                        (d[k] / d[k - 1] - r).abs() <= tol * r,
                        "n {n} first {first} k {k}"
                    );
                }
                // The geometric sum identity holds for the fitted ratio.
                let total = if (r - 1.0).abs() < 1e-12 {
                    first * (n - 1) as f64
                } else {
                    first * (r.powi(n as i32 - 1) - 1.0) / (r - 1.0)
                };
                assert!((total - 1.0).abs() < 1e-11, "n {n} first {first}: {total}");
                assert_eq!(first < 1.0 / (n - 1) as f64, r > 1.0);
            }
        }
        let s = geometric(5, 0.25).unwrap();
        for (a, b) in s.iter().zip(uniform(5)) {
            assert!((a - b).abs() < 1e-15);
        }
    }

    #[test]
    fn geometric_errors() {
        assert!(geometric(10, 0.0).is_err());
        assert!(geometric(10, 1.0).is_err());
        assert!(geometric(10, -0.1).is_err());
        assert!(geometric(10, f64::NAN).is_err());
        assert!(geometric(2, 0.5).is_err());
        assert_eq!(geometric(2, 1.0).unwrap(), vec![0.0, 1.0]);
        assert!(geometric(1, 0.5).is_err());
    }

    #[test]
    fn reverse_mirrors() {
        let s = geometric(6, 0.05).unwrap();
        let r = reverse(&s);
        assert_eq!(r[0], 0.0);
        assert_eq!(r[5], 1.0);
        assert!((r[5] - r[4] - 0.05).abs() < 1e-15);
        let enum_sampled = Distribution::Geometric { first: 0.05 }.sample(6).unwrap();
        assert_eq!(enum_sampled, s);
    }

    #[test]
    fn refined_distributions_nest_and_keep_their_shape() {
        for d in [
            Distribution::Uniform,
            Distribution::Geometric { first: 1e-3 },
            Distribution::Geometric { first: 0.2 },
            Distribution::Vinokur {
                first: Some(1e-3),
                last: None,
            },
        ] {
            let coarse = d.sample(17).unwrap();
            assert_eq!(d.sample_refined(17, 0).unwrap(), coarse);
            let fine = d.sample_refined(17, 2).unwrap();
            assert_eq!(fine.len(), 65);
            for (i, c) in coarse.iter().enumerate() {
                assert_eq!(fine[4 * i], *c, "{d:?} node {i}");
            }
            assert!(fine.windows(2).all(|w| w[1] > w[0]));
        }
        // geometric: the refined nodes are geometric with ratio r^(1/4)
        let fine = Distribution::Geometric { first: 1e-3 }
            .sample_refined(17, 2)
            .unwrap();
        let d: Vec<f64> = fine.windows(2).map(|w| w[1] - w[0]).collect();
        let q = d[1] / d[0];
        for k in 1..d.len() {
            assert!((d[k] / d[k - 1] / q - 1.0).abs() < 1e-9, "k {k}");
        }
        let r = geometric_ratio(16, 1e-3);
        assert!((q.powi(4) / r - 1.0).abs() < 1e-12);
        assert_eq!(
            Distribution::Uniform.sample_refined(5, 1).unwrap(),
            uniform(9)
        );
        assert!(Distribution::Uniform.sample_refined(5, 64).is_err());
    }
}
