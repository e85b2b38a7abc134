//! Test helpers: a seeded generator and a derivative check against central differences.

use super::Surface;
use crate::Vec3;

/// SplitMix64: small, seeded, reproducible.
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Rng {
        Rng(seed)
    }
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub(crate) fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [a, b).
    pub(crate) fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.f64()
    }
}

/// Largest relative difference between the analytic first and second derivatives of `s` at
/// (u, v) and fourth-order central differences with step h (of x for the first derivatives,
/// of the analytic first derivatives for the second ones). `scale` normalizes the error.
pub(crate) fn derivative_error(s: &dyn Surface, u: f64, v: f64, h: f64) -> f64 {
    let e = s.eval(u, v);
    // Fourth-order central difference of f at 0.
    let d = |f: &dyn Fn(f64) -> Vec3| {
        (f(-2.0 * h) - 8.0 * f(-h) + 8.0 * f(h) - f(2.0 * h)) / (12.0 * h)
    };
    let fu = d(&|t| s.point(u + t, v));
    let fv = d(&|t| s.point(u, v + t));
    let fuu = d(&|t| s.eval(u + t, v).xu);
    let fuv = d(&|t| s.eval(u + t, v).xv);
    let fvu = d(&|t| s.eval(u, v + t).xu);
    let fvv = d(&|t| s.eval(u, v + t).xv);
    let scale = 1.0 + e.xu.norm().max(e.xv.norm());
    let scale2 = 1.0 + e.xuu.norm().max(e.xvv.norm()).max(e.xuv.norm());
    [
        (fu - e.xu).norm() / scale,
        (fv - e.xv).norm() / scale,
        (fuu - e.xuu).norm() / scale2,
        (fuv - e.xuv).norm() / scale2,
        (fvu - e.xuv).norm() / scale2,
        (fvv - e.xvv).norm() / scale2,
        // point() must agree with eval().x
        (s.point(u, v) - e.x).norm() / (1.0 + e.x.norm()),
    ]
    .into_iter()
    .fold(0.0, f64::max)
}
