//! Analytic surfaces with exact derivatives: known answers for the surface pipeline's tests.
//!
//! - [`Plane`]: x = origin + u du + v dv.
//! - [`TanhBump`]: the paper's bump z = (1/8) tanh(15 (1/4 − (x−1)² − (y−1)²)) (TP 96338 §4,
//!   Fig. 31) over an affinely parametrized rectangle in (x, y).
//! - [`Scherk`]: Scherk's first minimal surface z = ln(cos y / cos x) over [−a, a]², a < π/2
//!   (a minimal surface: the mean curvature is zero, so harmonic maps are easy to check).

use super::{Surface, SurfacePoint};
use crate::{GeometryError, Vec3};

/// The plane x = origin + u du + v dv.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// x(0, 0).
    pub origin: Vec3,
    /// ∂x/∂u.
    pub du: Vec3,
    /// ∂x/∂v.
    pub dv: Vec3,
}

impl Surface for Plane {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        SurfacePoint {
            x: self.point(u, v),
            xu: self.du,
            xv: self.dv,
            xuu: Vec3::zeros(),
            xuv: Vec3::zeros(),
            xvv: Vec3::zeros(),
        }
    }
    fn point(&self, u: f64, v: f64) -> Vec3 {
        self.origin + self.du * u + self.dv * v
    }
}

/// The bump z = (1/8) tanh(15 (1/4 − (x−1)² − (y−1)²)) of TP 96338 §4 (Fig. 31).
///
/// (u, v) ↦ (x, y) = (x0 + (x1 − x0) u, y0 + (y1 − y0) v). The bump's centre is fixed at
/// (x, y) = (1, 1) by the paper's formula; the default rectangle [0, 2]² centres it in the
/// parameter square. The surface is (x, y, z(x, y)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TanhBump {
    /// x at u = 0.
    pub x0: f64,
    /// x at u = 1.
    pub x1: f64,
    /// y at v = 0.
    pub y0: f64,
    /// y at v = 1.
    pub y1: f64,
}

impl Default for TanhBump {
    /// The rectangle [0, 2]² (bump centred).
    fn default() -> Self {
        TanhBump {
            x0: 0.0,
            x1: 2.0,
            y0: 0.0,
            y1: 2.0,
        }
    }
}

impl TanhBump {
    /// The height z(x, y) of the bump.
    pub fn height(x: f64, y: f64) -> f64 {
        0.125 * (15.0 * (0.25 - (x - 1.0).powi(2) - (y - 1.0).powi(2))).tanh()
    }
}

impl Surface for TanhBump {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let (a, b) = (self.x1 - self.x0, self.y1 - self.y0);
        let (x, y) = (self.x0 + a * u, self.y0 + b * v);
        let g = 15.0 * (0.25 - (x - 1.0).powi(2) - (y - 1.0).powi(2));
        let (gx, gy) = (-30.0 * (x - 1.0), -30.0 * (y - 1.0)); // g_xx = g_yy = −30, g_xy = 0
        let t = g.tanh();
        let d1 = 1.0 - t * t; // tanh'
        let d2 = -2.0 * t * d1; // tanh''
        let zx = 0.125 * d1 * gx;
        let zy = 0.125 * d1 * gy;
        let zxx = 0.125 * (d2 * gx * gx - 30.0 * d1);
        let zyy = 0.125 * (d2 * gy * gy - 30.0 * d1);
        let zxy = 0.125 * d2 * gx * gy;
        SurfacePoint {
            x: Vec3::new(x, y, 0.125 * t),
            xu: Vec3::new(a, 0.0, a * zx),
            xv: Vec3::new(0.0, b, b * zy),
            xuu: Vec3::new(0.0, 0.0, a * a * zxx),
            xuv: Vec3::new(0.0, 0.0, a * b * zxy),
            xvv: Vec3::new(0.0, 0.0, b * b * zyy),
        }
    }
    fn point(&self, u: f64, v: f64) -> Vec3 {
        let (x, y) = (
            self.x0 + (self.x1 - self.x0) * u,
            self.y0 + (self.y1 - self.y0) * v,
        );
        Vec3::new(x, y, TanhBump::height(x, y))
    }
}

/// Scherk's first minimal surface z = ln(cos y / cos x) over (x, y) ∈ [−a, a]², a < π/2.
///
/// (u, v) ↦ (x, y) = (−a + 2a u, −a + 2a v).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scherk {
    /// a, in (0, π/2).
    pub half_width: f64,
}

impl Scherk {
    /// Scherk surface over [−a, a]².
    ///
    /// # Errors
    /// a not in (0, π/2).
    pub fn new(half_width: f64) -> Result<Scherk, GeometryError> {
        if !(half_width > 0.0 && half_width < std::f64::consts::FRAC_PI_2) {
            return Err(GeometryError::Invalid(format!(
                "Scherk surface: half width {half_width} not in (0, π/2)"
            )));
        }
        Ok(Scherk { half_width })
    }

    /// Vertical distance |z − ln(cos y / cos x)| of p from the surface (see [`scherk_distance`]).
    pub fn distance(&self, p: Vec3) -> f64 {
        scherk_distance(p)
    }
}

/// Vertical distance |z − ln(cos y / cos x)| of p from Scherk's surface: an upper bound of the
/// true distance, and within a factor sqrt(1 + |∇z|²) of it; infinite where |x| or |y| ≥ π/2.
pub fn scherk_distance(p: Vec3) -> f64 {
    let (cx, cy) = (p.x.cos(), p.y.cos());
    if !(cx > 0.0 && cy > 0.0) {
        return f64::INFINITY;
    }
    (p.z - (cy / cx).ln()).abs()
}

impl Surface for Scherk {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let a = self.half_width;
        let (x, y) = (-a + 2.0 * a * u, -a + 2.0 * a * v);
        let (cx, cy) = (x.cos(), y.cos());
        let (tx, ty) = (x.tan(), y.tan());
        let s = 2.0 * a; // dx/du = dy/dv
        SurfacePoint {
            x: Vec3::new(x, y, (cy / cx).ln()),
            xu: Vec3::new(s, 0.0, s * tx),  // z_x = tan x
            xv: Vec3::new(0.0, s, -s * ty), // z_y = −tan y
            xuu: Vec3::new(0.0, 0.0, s * s / (cx * cx)),
            xuv: Vec3::zeros(),
            xvv: Vec3::new(0.0, 0.0, -s * s / (cy * cy)),
        }
    }
    fn point(&self, u: f64, v: f64) -> Vec3 {
        let a = self.half_width;
        let (x, y) = (-a + 2.0 * a * u, -a + 2.0 * a * v);
        Vec3::new(x, y, (y.cos() / x.cos()).ln())
    }
}

#[cfg(test)]
mod tests {
    use super::super::testutil::{derivative_error, Rng};
    use super::*;

    fn check(s: &dyn Surface, h: f64, tol: f64) {
        let mut rng = Rng::new(7);
        let mut worst: f64 = 0.0;
        for _ in 0..200 {
            let (u, v) = (rng.range(0.05, 0.95), rng.range(0.05, 0.95));
            worst = worst.max(derivative_error(s, u, v, h));
        }
        assert!(worst < tol, "derivative error {worst:e}");
    }

    #[test]
    fn plane_derivatives() {
        let p = Plane {
            origin: Vec3::new(1.0, 2.0, 3.0),
            du: Vec3::new(1.0, 0.5, 0.0),
            dv: Vec3::new(-0.2, 1.0, 0.3),
        };
        check(&p, 1e-3, 1e-12);
    }

    #[test]
    fn tanh_bump_derivatives_and_shape() {
        let b = TanhBump::default();
        check(&b, 1e-4, 1e-8);
        let c = TanhBump {
            x0: -1.0,
            x1: 3.0,
            y0: 0.5,
            y1: 1.5,
        };
        check(&c, 1e-4, 1e-8);
        // Centre at (1, 1): z = tanh(15/4)/8; corners nearly at −1/8.
        let centre = b.point(0.5, 0.5);
        assert!((centre - Vec3::new(1.0, 1.0, (3.75f64).tanh() / 8.0)).norm() < 1e-15);
        assert!((b.point(0.0, 0.0).z + 0.125).abs() < 1e-9);
    }

    #[test]
    fn scherk_derivatives_minimal_and_distance() {
        let s = Scherk::new(1.2).unwrap();
        check(&s, 1e-5, 1e-8);
        assert!(Scherk::new(1.6).is_err() && Scherk::new(0.0).is_err());
        // Minimal surface: mean curvature H ∝ E N − 2 F M + G L = 0.
        let mut rng = Rng::new(3);
        for _ in 0..50 {
            let e = s.eval(rng.f64(), rng.f64());
            let n = e.normal();
            let (ee, ff, gg) = (e.xu.dot(&e.xu), e.xu.dot(&e.xv), e.xv.dot(&e.xv));
            let (l, m, nn) = (e.xuu.dot(&n), e.xuv.dot(&n), e.xvv.dot(&n));
            let h = (ee * nn - 2.0 * ff * m + gg * l) / (ee * gg - ff * ff);
            assert!(h.abs() < 1e-12, "mean curvature {h:e}");
            assert!(scherk_distance(e.x) < 1e-14);
            assert!((s.distance(e.x + Vec3::new(0.0, 0.0, 0.25)) - 0.25).abs() < 1e-14);
        }
        assert_eq!(scherk_distance(Vec3::new(2.0, 0.0, 0.0)), f64::INFINITY);
    }
}
