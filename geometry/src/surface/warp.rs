//! A smooth random re-parametrization of a surface: x'(u, v) = x(W(u, v)) with W a one-to-one
//! map of the unit square onto itself that keeps each side on itself and the corners fixed.
//! The same surface, another parametrization: the Section 4 grid must not change (METHOD.md
//! §5), which `ellipgrid verify` checks with it.
//!
//! W = W₂ ∘ W₁ with W₁(u, v) = (f(u; v), v) and W₂(p, v) = (p, g(v; p)), where
//!
//! f(x; y) = x + Σ_{k=1}^{K} a_k(y) sin(kπx)/(kπ),  a_k(y) = c_k + d_k cos πy + e_k sin πy,
//!
//! (g alike with its own coefficients). f(0; y) = 0, f(1; y) = 1 and ∂f/∂x = 1 + Σ a_k(y)
//! cos kπx ≥ 1 − Σ_k (|c_k| + |d_k| + |e_k|) > 0, so each factor maps every line y = const
//! one-to-one onto itself, and W is a smooth (analytic) diffeomorphism of the square. The
//! coefficients are random (fixed seed, [`crate::random::SplitMix64`]), scaled so that the
//! sum of their magnitudes is `strength` < 1: ∂f/∂x lies in [1 − strength, 1 + strength].

use super::{Surface, SurfacePoint};
use crate::random::SplitMix64;
use crate::{GeometryError, Vec3};
use std::f64::consts::PI;

/// Modes in each factor of the warp.
const MODES: usize = 3;

/// One factor's function f(x; y) = x + Σ a_k(y) sin(kπx)/(kπ) (module docs).
#[derive(Clone, Debug, PartialEq)]
struct Factor {
    /// (c_k, d_k, e_k) of a_k(y) = c_k + d_k cos πy + e_k sin πy.
    coef: [[f64; 3]; MODES],
}

/// f and its derivatives at (x, y): [f, f_x, f_y, f_xx, f_xy, f_yy].
type Jet = [f64; 6];

impl Factor {
    fn random(rng: &mut SplitMix64, strength: f64) -> Self {
        let mut coef = [[0.0; 3]; MODES];
        for c in coef.iter_mut().flatten() {
            *c = rng.symmetric();
        }
        let sum: f64 = coef.iter().flatten().map(|c| c.abs()).sum();
        for c in coef.iter_mut().flatten() {
            *c *= strength / sum;
        }
        Factor { coef }
    }

    fn jet(&self, x: f64, y: f64) -> Jet {
        let (sy, cy) = (PI * y).sin_cos();
        let mut j = [x, 1.0, 0.0, 0.0, 0.0, 0.0];
        for (k, [c, d, e]) in self.coef.iter().enumerate() {
            let kp = (k + 1) as f64 * PI;
            let (s, co) = (kp * x).sin_cos();
            let a = c + d * cy + e * sy;
            let a1 = PI * (e * cy - d * sy);
            let a2 = -PI * PI * (d * cy + e * sy);
            j[0] += a * s / kp;
            j[1] += a * co;
            j[2] += a1 * s / kp;
            j[3] -= a * kp * s;
            j[4] += a1 * co;
            j[5] += a2 * s / kp;
        }
        j
    }

    /// The x with f(x; y) = t (f increases in x from 0 to 1): bisection to rounding.
    fn inverse(&self, t: f64, y: f64) -> f64 {
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.jet(mid, y)[0] < t {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// A smooth one-to-one map of the unit square onto itself, sides onto themselves (module
/// docs), drawn from a seed.
#[derive(Clone, Debug, PartialEq)]
pub struct Warp {
    /// The seed it was drawn from.
    pub seed: u64,
    f: Factor,
    g: Factor,
}

/// W and its derivatives at (u, v): the point (p, q), and [p_u, p_v, p_uu, p_uv, p_vv] and
/// the same for q.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WarpJet {
    /// W(u, v).
    pub p: f64,
    /// Second component of W(u, v).
    pub q: f64,
    /// ∂p/∂u, ∂p/∂v, ∂²p/∂u², ∂²p/∂u∂v, ∂²p/∂v².
    pub dp: [f64; 5],
    /// The same for q.
    pub dq: [f64; 5],
}

impl Warp {
    /// The warp of `seed` with `strength` in (0, 1): the derivative of each factor along its
    /// lines lies in [1 − strength, 1 + strength].
    ///
    /// # Errors
    /// `strength` not in (0, 1).
    pub fn new(seed: u64, strength: f64) -> Result<Self, GeometryError> {
        if !(strength > 0.0 && strength < 1.0) {
            return Err(GeometryError::Invalid(format!(
                "warp strength must be in (0, 1), got {strength}"
            )));
        }
        let mut rng = SplitMix64::new(seed);
        let f = Factor::random(&mut rng, strength);
        let g = Factor::random(&mut rng, strength);
        Ok(Warp { seed, f, g })
    }

    /// W(u, v) with its first and second derivatives.
    pub fn jet(&self, u: f64, v: f64) -> WarpJet {
        let fj = self.f.jet(u, v);
        let p = fj[0];
        let [pu, pv, puu, puv, pvv] = [fj[1], fj[2], fj[3], fj[4], fj[5]];
        // q = g(v; p(u, v)): g's first argument is v, its second p.
        let gj = self.g.jet(v, p);
        let [q, gv, gp, gvv, gvp, gpp] = gj;
        WarpJet {
            p,
            q,
            dp: [pu, pv, puu, puv, pvv],
            dq: [
                gp * pu,
                gv + gp * pv,
                gpp * pu * pu + gp * puu,
                (gvp + gpp * pv) * pu + gp * puv,
                gvv + 2.0 * gvp * pv + gpp * pv * pv + gp * pvv,
            ],
        }
    }

    /// W(u, v).
    pub fn map(&self, u: f64, v: f64) -> (f64, f64) {
        let p = self.f.jet(u, v)[0];
        (p, self.g.jet(v, p)[0])
    }

    /// The u on the side v = `v` (0 or 1) that W maps to u-value `p` (W keeps the side).
    fn u_on_side(&self, p: f64, v: f64) -> f64 {
        self.f.inverse(p, v)
    }

    /// The v on the side u = `u` (0 or 1) that W maps to v-value `q`.
    fn v_on_side(&self, q: f64, u: f64) -> f64 {
        // On u = 0 or 1, p = u; q = g(v; u).
        self.g.inverse(q, u)
    }
}

/// A surface over a warped parametrization: x'(u, v) = x(W(u, v)) ([`Warp`]).
pub struct Warped<S> {
    /// The surface in its own parameters.
    pub surface: S,
    /// The re-parametrization.
    pub warp: Warp,
}

impl<S: Surface> Surface for Warped<S> {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let w = self.warp.jet(u, v);
        let s = self.surface.eval(w.p, w.q);
        let [pu, pv, puu, puv, pvv] = w.dp;
        let [qu, qv, quu, quv, qvv] = w.dq;
        let second = |a1: f64, b1: f64, a2: f64, b2: f64| -> Vec3 {
            s.xuu * (a1 * a2) + s.xuv * (a1 * b2 + a2 * b1) + s.xvv * (b1 * b2)
        };
        SurfacePoint {
            x: s.x,
            xu: s.xu * pu + s.xv * qu,
            xv: s.xu * pv + s.xv * qv,
            xuu: second(pu, qu, pu, qu) + s.xu * puu + s.xv * quu,
            xuv: second(pu, qu, pv, qv) + s.xu * puv + s.xv * quv,
            xvv: second(pv, qv, pv, qv) + s.xu * pvv + s.xv * qvv,
        }
    }

    fn point(&self, u: f64, v: f64) -> Vec3 {
        let (p, q) = self.warp.map(u, v);
        self.surface.point(p, q)
    }

    /// The surface's break lines pulled back onto the sides of the square (where the
    /// quadratures along edges need them): u-breaks from the sides v = 0 and v = 1, v-breaks
    /// from u = 0 and u = 1 (a break of one side is a harmless extra split on the other).
    fn breaks(&self) -> (Vec<f64>, Vec<f64>) {
        let (bu, bv) = self.surface.breaks();
        let pull = |b: &[f64], f: &dyn Fn(f64, f64) -> f64| {
            let mut out: Vec<f64> = b.iter().flat_map(|&x| [f(x, 0.0), f(x, 1.0)]).collect();
            out.sort_by(f64::total_cmp);
            out.dedup();
            out
        };
        (
            pull(&bu, &|p, side| self.warp.u_on_side(p, side)),
            pull(&bv, &|q, side| self.warp.v_on_side(q, side)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::testutil::derivative_error;
    use crate::{HermiteSurface, TanhBump};

    #[test]
    fn the_warp_keeps_the_sides_and_is_one_to_one() {
        let w = Warp::new(42, 0.6).unwrap();
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            assert_eq!(w.map(0.0, t).0, 0.0);
            assert!((w.map(1.0, t).0 - 1.0).abs() < 1e-15);
            assert!(w.map(t, 0.0).1.abs() < 1e-15);
            assert!((w.map(t, 1.0).1 - 1.0).abs() < 1e-15);
        }
        // a positive Jacobian everywhere, and a real warp (far from the identity)
        let mut moved: f64 = 0.0;
        for i in 0..=40 {
            for j in 0..=40 {
                let (u, v) = (i as f64 / 40.0, j as f64 / 40.0);
                let jt = w.jet(u, v);
                let det = jt.dp[0] * jt.dq[1] - jt.dp[1] * jt.dq[0];
                assert!(det > 0.05, "({u}, {v}): {det}");
                moved = moved.max((jt.p - u).abs().max((jt.q - v).abs()));
            }
        }
        assert!(moved > 0.02, "{moved}");
        assert_ne!(Warp::new(43, 0.6).unwrap(), w);
        assert!(Warp::new(1, 1.0).is_err() && Warp::new(1, 0.0).is_err());
    }

    #[test]
    fn warped_surfaces_have_exact_derivatives_and_pulled_back_breaks() {
        let bump = Warped {
            surface: TanhBump::default(),
            warp: Warp::new(7, 0.6).unwrap(),
        };
        for &(u, v) in &[(0.3, 0.7), (0.51, 0.49), (0.1, 0.9), (0.8, 0.2)] {
            assert!(derivative_error(&bump, u, v, 1e-4) < 1e-7, "({u}, {v})");
            let (p, q) = bump.warp.map(u, v);
            assert!((bump.point(u, v) - bump.surface.point(p, q)).norm() < 1e-15);
        }
        // a Hermite net's patch lines land on the sides where W maps them
        let pts = (0..20)
            .map(|k| {
                let (x, y) = ((k % 5) as f64 / 4.0, (k / 5) as f64 / 3.0);
                Vec3::new(x, y, x * x * y)
            })
            .collect();
        let net = Warped {
            surface: HermiteSurface::new(5, 4, pts).unwrap(),
            warp: Warp::new(9, 0.6).unwrap(),
        };
        let (bu, bv) = net.breaks();
        let (su, sv) = net.surface.breaks();
        assert_eq!((bu.len(), bv.len()), (2 * su.len(), 2 * sv.len()));
        for &u in &bu {
            let hit = [0.0, 1.0].iter().any(|&side| {
                su.iter()
                    .any(|&b| (net.warp.map(u, side).0 - b).abs() < 1e-14)
            });
            assert!(hit, "{u}");
        }
        for &v in &bv {
            let hit = [0.0, 1.0].iter().any(|&side| {
                sv.iter()
                    .any(|&b| (net.warp.map(side, v).1 - b).abs() < 1e-14)
            });
            assert!(hit, "{v}");
        }
    }
}
