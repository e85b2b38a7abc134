//! Arclength s(u) = ∫₀ᵘ |x'(v)| dv of any [`Curve`] and its inverse u(σ), σ = s/L.
//!
//! [0, 1] is split at the curve's [`Curve::breakpoints`] and then into panels by adaptive
//! bisection. On each panel the speed |x'| is sampled at 20 Gauss–Legendre nodes and expanded in
//! Legendre polynomials; a panel is accepted when its two highest coefficients times its width
//! are below 1e-13 of the curve's largest speed: the error of s(u) inside the panel, not only
//! of its integral, is then below 1e-13 of the curve's speed scale. Round-off noise in the
//! speed (B-spline derivatives far from the origin: ~1e-11 relative) is thereby accepted once
//! the panels are narrow enough for it not to matter, instead of being bisected without end;
//! the work is bounded besides by a panel cap ([`MAX_PANELS`]) and a width floor.
//! The integral of the expansion gives s(u) inside a panel in closed form, so the map keeps no
//! reference to the curve, and u(σ) is found by a safeguarded Newton iteration on it.

use super::Curve;
use crate::Vec3;
use std::sync::OnceLock;

/// Gauss–Legendre nodes per panel.
const M: usize = 20;
/// Accept a panel when its trailing Legendre coefficients times its width are below this times
/// the curve's largest speed.
const REL_TOL: f64 = 1e-13;
/// At most this many panels per curve (bounded work whatever the curve); beyond it the
/// remaining panels are accepted as they are.
pub const MAX_PANELS: usize = 1 << 14;
/// A curve whose largest speed is below this times its largest |x| is a point to round-off.
const POINT_LIKE: f64 = 1e-12;
/// Stop bisecting below this panel width (non-smooth points that were not declared).
const MIN_WIDTH: f64 = 1.0 / (1u64 << 40) as f64;

/// Gauss–Legendre rule on [−1, 1] and the discrete Legendre transform for it.
struct Rule {
    nodes: [f64; M],
    weights: [f64; M],
    /// c_k = Σ_j transform[k][j] f(x_j) for f of degree < M.
    transform: [[f64; M]; M],
}

/// Legendre polynomials P_0 .. P_{M} at x (three-term recurrence).
fn legendre_all(x: f64) -> [f64; M + 1] {
    let mut p = [0.0; M + 1];
    p[0] = 1.0;
    p[1] = x;
    for k in 1..M {
        p[k + 1] = ((2 * k + 1) as f64 * x * p[k] - k as f64 * p[k - 1]) / (k + 1) as f64;
    }
    p
}

fn rule() -> &'static Rule {
    static RULE: OnceLock<Rule> = OnceLock::new();
    RULE.get_or_init(|| {
        let mut nodes = [0.0; M];
        let mut weights = [0.0; M];
        for i in 0..M {
            // Newton on P_M from the usual asymptotic guess; converges to machine precision.
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (M as f64 + 0.5)).cos();
            let derivative = |x: f64| {
                let p = legendre_all(x);
                (p[M], M as f64 * (x * p[M] - p[M - 1]) / (x * x - 1.0))
            };
            for _ in 0..100 {
                let (p, dp) = derivative(x);
                let dx = p / dp;
                x -= dx;
                if dx.abs() < 1e-17 {
                    break;
                }
            }
            let dp = derivative(x).1;
            nodes[i] = x;
            weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
        }
        let mut transform = [[0.0; M]; M];
        for j in 0..M {
            let p = legendre_all(nodes[j]);
            for (k, row) in transform.iter_mut().enumerate() {
                row[j] = (2 * k + 1) as f64 / 2.0 * weights[j] * p[k];
            }
        }
        Rule {
            nodes,
            weights,
            transform,
        }
    })
}

/// One accepted panel [a, b] with s(a) and the Legendre coefficients of the speed on it.
#[derive(Debug, Clone, PartialEq)]
struct Panel {
    a: f64,
    b: f64,
    s_a: f64,
    coef: [f64; M],
}

impl Panel {
    /// ∫ from a to the local coordinate t ∈ [−1, 1], and the speed there.
    fn integral_and_speed(&self, t: f64) -> (f64, f64) {
        let p = legendre_all(t);
        // ∫_{−1}^t P_0 = t + 1;  ∫_{−1}^t P_k = (P_{k+1} − P_{k−1}) / (2k + 1).
        let mut int = self.coef[0] * (t + 1.0);
        let mut speed = self.coef[0];
        for k in 1..M {
            int += self.coef[k] * (p[k + 1] - p[k - 1]) / (2 * k + 1) as f64;
            speed += self.coef[k] * p[k];
        }
        let half = 0.5 * (self.b - self.a);
        (half * int, speed)
    }
}

/// Arclength table of a curve: length, σ → u and u → σ without further curve evaluations.
#[derive(Debug, Clone, PartialEq)]
pub struct ArclengthMap {
    panels: Vec<Panel>,
    length: f64,
}

impl ArclengthMap {
    /// Builds the table for `curve` on u ∈ [0, 1] (adaptive Gauss–Legendre, split at breakpoints).
    pub fn new(curve: &dyn Curve) -> ArclengthMap {
        let mut cuts: Vec<f64> = curve
            .breakpoints()
            .into_iter()
            .filter(|b| *b > 0.0 && *b < 1.0)
            .collect();
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        cuts.insert(0, 0.0);
        cuts.push(1.0);
        // At least ~16 starting panels so that narrow features are not missed by the sampling.
        let mut todo: Vec<(f64, f64)> = Vec::new();
        for w in cuts.windows(2).rev() {
            let k = ((16.0 * (w[1] - w[0])).ceil() as usize).max(1);
            for i in (0..k).rev() {
                let a = w[0] + (w[1] - w[0]) * i as f64 / k as f64;
                let b = if i + 1 == k {
                    w[1]
                } else {
                    w[0] + (w[1] - w[0]) * (i + 1) as f64 / k as f64
                };
                todo.push((a, b));
            }
        }
        let rule = rule();
        // The curve's speed scale: panels are resolved to REL_TOL of it, so that a stretch of
        // near-zero speed (where |x'| is all round-off) is not bisected without end.
        let fscale = (0..=64)
            .map(|k| curve.derivative(k as f64 / 64.0).norm())
            .filter(|v| v.is_finite())
            .fold(0.0f64, f64::max);
        // A curve that is a point to round-off (a collapsed side of a patch: a pole) has a
        // speed that is all round-off, which no panel resolves: its starting panels are taken
        // as they are (they were bisected to MAX_PANELS, most of an OpenVSP model's time).
        let xscale = (0..=4)
            .map(|k| curve.point(k as f64 / 4.0).norm())
            .filter(|v| v.is_finite())
            .fold(0.0f64, f64::max);
        let point_like = fscale <= POINT_LIKE * xscale;
        let mut panels = Vec::new();
        let mut s = 0.0;
        // Depth-first from the left, so panels come out ordered.
        while let Some((a, b)) = todo.pop() {
            let half = 0.5 * (b - a);
            let mid = 0.5 * (a + b);
            let f: Vec<f64> = rule
                .nodes
                .iter()
                .map(|x| curve.derivative(mid + half * x).norm())
                .collect();
            let mut coef = [0.0; M];
            for (c, row) in coef.iter_mut().zip(&rule.transform) {
                *c = row.iter().zip(&f).map(|(t, v)| t * v).sum();
            }
            let fmax = f.iter().fold(0.0f64, |m, v| m.max(*v));
            let tail = coef[M - 1].abs() + coef[M - 2].abs();
            // Converged, or down at the round-off floor of the speed samples (without this
            // guard a noisy speed would be bisected to MIN_WIDTH everywhere).
            let floor = 16.0 * f64::EPSILON * f.iter().map(|v| v.abs()).sum::<f64>();
            let resolved = point_like
                || tail * (b - a) <= REL_TOL * fmax.max(fscale)
                || tail <= floor
                || !tail.is_finite();
            if resolved || b - a <= MIN_WIDTH || panels.len() + todo.len() >= MAX_PANELS {
                let len: f64 = half * rule.weights.iter().zip(&f).map(|(w, v)| w * v).sum::<f64>();
                panels.push(Panel { a, b, s_a: s, coef });
                s += len;
            } else {
                todo.push((mid, b));
                todo.push((a, mid));
            }
        }
        ArclengthMap { panels, length: s }
    }

    /// Total arclength L.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Number of quadrature panels (diagnostics).
    pub fn panel_count(&self) -> usize {
        self.panels.len()
    }

    /// Arclength from u = 0 to `u` (u clamped to [0, 1]).
    pub fn arclength_at(&self, u: f64) -> f64 {
        if u <= 0.0 {
            return 0.0;
        }
        if u >= 1.0 {
            return self.length;
        }
        let i = self
            .panels
            .partition_point(|p| p.b <= u)
            .min(self.panels.len() - 1);
        let p = &self.panels[i];
        let t = (2.0 * (u - p.a) / (p.b - p.a) - 1.0).clamp(-1.0, 1.0);
        p.s_a + p.integral_and_speed(t).0
    }

    /// Normalized arclength σ(u) = s(u)/L.
    pub fn sigma_at(&self, u: f64) -> f64 {
        if self.length > 0.0 {
            self.arclength_at(u) / self.length
        } else {
            u.clamp(0.0, 1.0)
        }
    }

    /// Parameter u at normalized arclength σ (clamped to [0, 1]); σ = 0 and 1 give exactly 0 and 1.
    ///
    /// Newton on the panel's closed-form s(u), safeguarded by bisection (so zero speed is fine).
    /// A curve of zero length maps σ to u = σ.
    pub fn param_at(&self, sigma: f64) -> f64 {
        if sigma.is_nan() {
            return f64::NAN;
        }
        if sigma <= 0.0 {
            return 0.0;
        }
        if sigma >= 1.0 {
            return 1.0;
        }
        if self.length.is_nan() || self.length <= 0.0 {
            return sigma;
        }
        let target = sigma * self.length;
        let i = self
            .panels
            .partition_point(|p| p.s_a <= target)
            .saturating_sub(1);
        let p = &self.panels[i];
        let half = 0.5 * (p.b - p.a);
        let s_b = self.panels.get(i + 1).map_or(self.length, |q| q.s_a);
        // Bracket [lo, hi] with g(lo) ≤ 0 ≤ g(hi); start from linear interpolation.
        let (mut lo, mut hi) = (-1.0f64, 1.0f64);
        let mut t = if s_b > p.s_a {
            -1.0 + 2.0 * (target - p.s_a) / (s_b - p.s_a)
        } else {
            0.0
        };
        t = t.clamp(-1.0, 1.0);
        for _ in 0..100 {
            let (int, speed) = p.integral_and_speed(t);
            let r = p.s_a + int - target;
            if r == 0.0 {
                break;
            }
            if r < 0.0 {
                lo = t;
            } else {
                hi = t;
            }
            let step = r / (half * speed);
            let mut next = t - step;
            let inside = speed > 0.0 && next > lo && next < hi;
            if !inside {
                next = 0.5 * (lo + hi);
            }
            if (next - t).abs() <= 1e-16 * (1.0 + t.abs()) || hi - lo <= 4.0 * f64::EPSILON {
                t = next;
                break;
            }
            t = next;
        }
        (p.a + half * (t + 1.0)).clamp(0.0, 1.0)
    }

    /// Parameters u at the given normalized arclengths.
    pub fn params(&self, sigma: &[f64]) -> Vec<f64> {
        sigma.iter().map(|&s| self.param_at(s)).collect()
    }
}

/// Points of `curve` at the normalized arclengths `sigma` (clamped to [0, 1]).
///
/// σ = 0 and σ = 1 give exactly `curve.point(0.0)` and `curve.point(1.0)`.
pub fn sample(curve: &dyn Curve, sigma: &[f64]) -> Vec<Vec3> {
    let map = ArclengthMap::new(curve);
    sigma
        .iter()
        .map(|&s| curve.point(map.param_at(s)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::{Arc, Naca4, Polyline};
    use std::f64::consts::PI;

    /// Deterministic round-off-like noise in [−a/2, a/2] at parameter `u`.
    fn noise(u: f64, a: f64) -> f64 {
        let h = u.to_bits().wrapping_mul(0x9E37_79B9_7F4A_7C15);
        ((h >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * a
    }

    /// Test curve given by closures, with optional breakpoints.
    struct Fn3<P, D> {
        p: P,
        d: D,
        breaks: Vec<f64>,
    }
    impl<P, D> Curve for Fn3<P, D>
    where
        P: Fn(f64) -> Vec3 + Send + Sync,
        D: Fn(f64) -> Vec3 + Send + Sync,
    {
        fn point(&self, u: f64) -> Vec3 {
            (self.p)(u)
        }
        fn derivative(&self, u: f64) -> Vec3 {
            (self.d)(u)
        }
        fn breakpoints(&self) -> Vec<f64> {
            self.breaks.clone()
        }
    }

    #[test]
    fn gauss_rule_is_exact_for_degree_2m_minus_1() {
        let r = rule();
        let sum_w: f64 = r.weights.iter().sum();
        assert!((sum_w - 2.0).abs() < 1e-14);
        let x38: f64 = r
            .nodes
            .iter()
            .zip(&r.weights)
            .map(|(x, w)| w * x.powi(38))
            .sum();
        assert!((x38 - 2.0 / 39.0).abs() < 1e-14);
    }

    #[test]
    fn quarter_circle_length() {
        let r = 2.5;
        let arc = Arc::new(Vec3::new(1.0, -2.0, 0.0), r, 0.0, 90.0).unwrap();
        let map = ArclengthMap::new(&arc);
        assert!(
            (map.length() - PI * r / 2.0).abs() < 1e-12,
            "{}",
            map.length()
        );
    }

    #[test]
    fn arc_samples_at_equal_angles() {
        let c = Vec3::new(0.3, 0.4, 1.0);
        let arc = Arc::new(c, 0.7, 20.0, -200.0).unwrap();
        let sigma = [0.0, 1e-7, 0.1, 0.333, 0.5, 0.9, 1.0 - 1e-9, 1.0];
        let pts = sample(&arc, &sigma);
        for (p, s) in pts.iter().zip(sigma) {
            let ang = (20.0 - 220.0 * s).to_radians();
            let want = c + 0.7 * Vec3::new(ang.cos(), ang.sin(), 0.0);
            assert!((p - want).norm() < 1e-12, "sigma {s}");
        }
        assert_eq!(pts[0], arc.point(0.0));
        assert_eq!(pts[7], arc.point(1.0));
    }

    #[test]
    fn polyline_with_kink_is_exact() {
        // Segments of length 1 and 3 at a right angle.
        let poly = Polyline::new(vec![Vec3::zeros(), Vec3::x(), Vec3::new(1.0, 3.0, 0.0)]).unwrap();
        let map = ArclengthMap::new(&poly);
        assert!((map.length() - 4.0).abs() < 1e-14);
        let p = sample(&poly, &[0.125, 0.25, 0.5])
            .into_iter()
            .map(|p| p - Vec3::new(0.5, 0.0, 0.0))
            .collect::<Vec<_>>();
        assert!(p[0].norm() < 1e-14 && (p[1] - Vec3::new(0.5, 0.0, 0.0)).norm() < 1e-14);
        assert!((p[2] - Vec3::new(0.5, 1.0, 0.0)).norm() < 1e-14);
        let q = Fn3 {
            p: |u: f64| poly.point(u * u),
            d: |u: f64| 2.0 * u * poly.derivative(u * u),
            breaks: vec![0.5],
        };
        let mq = ArclengthMap::new(&q);
        // The same polyline traversed with uneven speed, u ↦ poly(u²), kink at u = 0.5.
        assert!((mq.length() - 4.0).abs() < 1e-13);
        assert!((mq.param_at(0.25) - 0.5).abs() < 1e-13);
        // σ = 0.625: 1.5 along the second segment, polyline parameter 0.625 = u².
        assert!((mq.param_at(0.625) - 0.625f64.sqrt()).abs() < 1e-13);
    }

    #[test]
    fn undeclared_kink_still_accurate() {
        // V shape (u, |u − 0.3|) without breakpoints: the adaptive bisection must localise it.
        let v = Fn3 {
            p: |u: f64| Vec3::new(u, (u - 0.3).abs(), 0.0),
            d: |u: f64| Vec3::new(1.0, (u - 0.3).signum(), 0.0),
            breaks: vec![],
        };
        let map = ArclengthMap::new(&v);
        assert!(
            (map.length() - 2f64.sqrt()).abs() < 1e-11,
            "{}",
            map.length()
        );
        assert!(map.panel_count() < 500);
    }

    #[test]
    fn noisy_speed_is_not_bisected_without_end() {
        // A unit segment whose speed carries deterministic round-off-like noise of 1e-11
        // relative (as B-spline derivatives far from the origin do): the table must stay
        // small and the length right to the noise level.
        let noise = |u: f64| noise(u, 2e-11);
        let c = Fn3 {
            p: |u: f64| Vec3::new(u, 0.0, 0.0),
            d: move |u: f64| Vec3::new(1.0 + noise(u), 0.0, 0.0),
            breaks: vec![],
        };
        let map = ArclengthMap::new(&c);
        assert!(map.panel_count() <= 256, "{} panels", map.panel_count());
        assert!((map.length() - 1.0).abs() < 1e-11, "{}", map.length());
        assert!((map.param_at(0.3) - 0.3).abs() < 1e-11);
    }

    #[test]
    fn a_point_to_round_off_is_not_bisected_and_a_short_curve_still_is_resolved() {
        // A collapsed patch side (OpenVSP's wing-cap poles): the point (5, −3, 2) whose
        // derivative is round-off noise of 1e-16. It took MAX_PANELS panels before.
        let noise = |u: f64| noise(u, 4e-16);
        let pole = Fn3 {
            p: |_| Vec3::new(5.0, -3.0, 2.0),
            d: move |u: f64| Vec3::new(noise(u), noise(1.0 - u), 0.0),
            breaks: vec![],
        };
        let map = ArclengthMap::new(&pole);
        assert!(map.panel_count() <= 16, "{} panels", map.panel_count());
        assert!(map.length() < 1e-15, "{}", map.length());
        // A quarter circle of radius 1e-9 at the same place is a curve (speed 1.6e-9, 2.5e-10
        // of |x|): resolved to the relative accuracy of the table.
        let r = 1e-9;
        let arc = Arc::new(Vec3::new(5.0, -3.0, 2.0), r, 0.0, 90.0).unwrap();
        let map = ArclengthMap::new(&arc);
        assert!(
            (map.length() / (0.5 * PI * r) - 1.0).abs() < 1e-12,
            "{}",
            map.length()
        );
    }

    #[test]
    fn parabola_against_closed_form() {
        let par = Fn3 {
            p: |u: f64| Vec3::new(u, u * u, 0.0),
            d: |u: f64| Vec3::new(1.0, 2.0 * u, 0.0),
            breaks: vec![],
        };
        let s = |u: f64| 0.5 * u * (1.0 + 4.0 * u * u).sqrt() + 0.25 * (2.0 * u).asinh();
        let map = ArclengthMap::new(&par);
        assert!((map.length() - s(1.0)).abs() < 1e-14);
        for i in 0..=100 {
            let u = i as f64 / 100.0;
            assert!((map.arclength_at(u) - s(u)).abs() < 1e-14);
            let sig = s(u) / s(1.0);
            assert!((map.param_at(sig) - u).abs() < 1e-13, "{u}");
        }
    }

    #[test]
    fn zero_speed_at_start() {
        // The unit segment traversed as x = u³: σ = u³, so u(σ) = σ^(1/3).
        let cubic = Fn3 {
            p: |u: f64| Vec3::new(u * u * u, 0.0, 0.0),
            d: |u: f64| Vec3::new(3.0 * u * u, 0.0, 0.0),
            breaks: vec![],
        };
        let map = ArclengthMap::new(&cubic);
        for &sig in &[1e-9, 1e-6, 0.01, 0.3, 0.999] {
            let u: f64 = map.param_at(sig);
            assert!(
                (u - f64::cbrt(sig)).abs() < 1e-12 * f64::cbrt(sig),
                "{sig}: {u}"
            );
        }
    }

    #[test]
    fn naca_leading_edge_monotone_round_trip() {
        let a = Naca4::new("0012", 1.0, true).unwrap();
        let map = ArclengthMap::new(&a);
        let mut prev = -1.0;
        for i in 0..=4000 {
            // Dense near the leading edge u = 0.5.
            let u = 0.5 + 0.5 * ((i as f64 - 2000.0) / 2000.0).powi(3);
            let s = map.sigma_at(u);
            assert!(s > prev || (i == 0 && s == 0.0), "not monotone at u = {u}");
            prev = s;
            let back = map.sigma_at(map.param_at(s));
            assert!((back - s).abs() < 1e-12, "sigma {s}");
        }
        for i in 0..=1000 {
            let s = i as f64 / 1000.0;
            assert!((map.sigma_at(map.param_at(s)) - s).abs() < 1e-12);
        }
        // Cross-checks: upper + lower (other parametrization) = contour; a fine chord sum.
        let halves =
            ArclengthMap::new(&a.upper()).length() + ArclengthMap::new(&a.lower()).length();
        assert!((halves - map.length()).abs() < 1e-13 * map.length());
        let n = 200_000;
        let chords: f64 = (0..n)
            .map(|i| (a.point((i + 1) as f64 / n as f64) - a.point(i as f64 / n as f64)).norm())
            .sum();
        assert!(
            chords < map.length() && map.length() - chords < 1e-9,
            "{chords}"
        );
        // Independent of the parametrization: the cambered contour reparametrized by the
        // non-linear g(u) = u − 0.9 sin(2πu)/(2π), without declared breakpoints.
        let c = Naca4::new("2412", 1.0, true).unwrap();
        let g = |u: f64| u - 0.9 * (2.0 * PI * u).sin() / (2.0 * PI);
        let re = Fn3 {
            p: |u: f64| c.point(g(u)),
            d: |u: f64| c.derivative(g(u)) * (1.0 - 0.9 * (2.0 * PI * u).cos()),
            breaks: vec![],
        };
        let (mc, mr) = (ArclengthMap::new(&c), ArclengthMap::new(&re));
        assert!((mc.length() - mr.length()).abs() < 1e-14 * mc.length());
        for i in 0..=200 {
            let u = i as f64 / 200.0;
            assert!((mr.sigma_at(u) - mc.sigma_at(g(u))).abs() < 1e-14);
        }
        // The leading edge is at half the length for a symmetric section.
        assert!((map.sigma_at(0.5) - 0.5).abs() < 1e-14);
    }
}
