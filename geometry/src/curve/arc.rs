//! Circular arc: x(u) = c + r (cos φ e₁ + sin φ e₂), φ = u Δφ, in the plane spanned by e₁, e₂.

use super::Curve;
use crate::{GeometryError, Vec3};
use std::f64::consts::PI;

/// A circular arc in R³, traversed at constant speed r |Δφ|.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    center: Vec3,
    radius: f64,
    /// Unit vector from the center to the start point.
    e1: Vec3,
    /// Unit vector in the arc's plane, 90° ahead of e1 in the positive sense.
    e2: Vec3,
    /// Signed sweep angle in radians.
    sweep: f64,
}

impl Arc {
    /// Arc in the xy-plane at the center's z, from `start_deg` to `end_deg` (degrees from +x).
    ///
    /// Counter-clockwise when `end_deg > start_deg`, clockwise otherwise.
    ///
    /// # Errors
    /// Radius not positive and finite, angles not finite, zero sweep or |sweep| > 360°.
    pub fn new(
        center: Vec3,
        radius: f64,
        start_deg: f64,
        end_deg: f64,
    ) -> Result<Arc, GeometryError> {
        if !center.iter().all(|c| c.is_finite()) {
            return Err(GeometryError::Invalid("arc: center is not finite".into()));
        }
        if !(radius.is_finite() && radius > 0.0) {
            return Err(GeometryError::Invalid(format!(
                "arc: radius must be positive, got {radius}"
            )));
        }
        let sweep_deg = end_deg - start_deg;
        if !(start_deg.is_finite() && end_deg.is_finite())
            || sweep_deg == 0.0
            || sweep_deg.abs() > 360.0
        {
            return Err(GeometryError::Invalid(format!(
                "arc: need finite angles with 0 < |end - start| <= 360 degrees, got {start_deg} .. {end_deg}"
            )));
        }
        let a = start_deg.to_radians();
        let (s, c) = a.sin_cos();
        Ok(Arc {
            center,
            radius,
            e1: Vec3::new(c, s, 0.0),
            e2: Vec3::new(-s, c, 0.0),
            sweep: sweep_deg.to_radians(),
        })
    }

    /// The arc from `from` through `mid` to `to` (any plane in R³).
    ///
    /// # Errors
    /// Non-finite, coincident or collinear points.
    pub fn through(from: Vec3, mid: Vec3, to: Vec3) -> Result<Arc, GeometryError> {
        if ![from, mid, to]
            .iter()
            .all(|p| p.iter().all(|c| c.is_finite()))
        {
            return Err(GeometryError::Invalid(
                "arc through 3 points: a point is not finite".into(),
            ));
        }
        // Circumcenter relative to `to`: ((|a|² b − |b|² a) × (a × b)) / (2 |a × b|²).
        let a = from - to;
        let b = mid - to;
        let w = a.cross(&b);
        let scale = a.norm() * b.norm() * (a - b).norm();
        let w2 = w.norm_squared();
        // |a × b| / (|a||b|) is the sine of the angle at `to`; 1e-12 means collinear in practice.
        if scale == 0.0 || w2.sqrt() <= 1e-12 * a.norm() * b.norm() {
            return Err(GeometryError::Invalid(
                "arc through 3 points: the points are coincident or collinear".into(),
            ));
        }
        let center = to + (a.norm_squared() * b - b.norm_squared() * a).cross(&w) / (2.0 * w2);
        let ra = from - center;
        let radius = ra.norm();
        let e1 = ra / radius;
        // Orientation: a→m→b counter-clockwise about n; an inscribed triangle's orientation
        // equals the cyclic order of its vertices, so going positively from `from` meets `mid`
        // before `to`.
        let n = (mid - from).cross(&(to - mid)).normalize();
        let e2 = n.cross(&e1);
        let rt = to - center;
        let mut sweep = rt.dot(&e2).atan2(rt.dot(&e1));
        if sweep <= 0.0 {
            sweep += 2.0 * PI;
        }
        Ok(Arc {
            center,
            radius,
            e1,
            e2,
            sweep,
        })
    }

    /// Center of the circle.
    pub fn center(&self) -> Vec3 {
        self.center
    }

    /// Radius of the circle.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Signed sweep angle in radians (positive: counter-clockwise about e₁ × e₂).
    pub fn sweep(&self) -> f64 {
        self.sweep
    }

    /// Arc length r |Δφ|.
    pub fn length(&self) -> f64 {
        self.radius * self.sweep.abs()
    }
}

impl Curve for Arc {
    fn point(&self, u: f64) -> Vec3 {
        let (s, c) = (u * self.sweep).sin_cos();
        self.center + self.radius * (c * self.e1 + s * self.e2)
    }

    fn derivative(&self, u: f64) -> Vec3 {
        let (s, c) = (u * self.sweep).sin_cos();
        self.radius * self.sweep * (-s * self.e1 + c * self.e2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOL: f64 = 1e-12;

    #[test]
    fn xy_arc_orientation_and_ends() {
        let c = Vec3::new(1.0, 2.0, 3.0);
        let ccw = Arc::new(c, 2.0, 0.0, 90.0).unwrap();
        assert!((ccw.point(0.0) - Vec3::new(3.0, 2.0, 3.0)).norm() < TOL);
        assert!((ccw.point(1.0) - Vec3::new(1.0, 4.0, 3.0)).norm() < TOL);
        assert!(
            (ccw.point(0.5) - (c + 2.0 * Vec3::new(0.5f64.sqrt(), 0.5f64.sqrt(), 0.0))).norm()
                < TOL
        );
        let cw = Arc::new(c, 2.0, 0.0, -90.0).unwrap();
        assert!((cw.point(1.0) - Vec3::new(1.0, 0.0, 3.0)).norm() < TOL);
        assert!((ccw.length() - PI).abs() < TOL);
    }

    #[test]
    fn derivative_matches_central_difference() {
        let arc = Arc::new(Vec3::zeros(), 1.5, 30.0, 250.0).unwrap();
        let h = 1e-6;
        for &u in &[0.1, 0.37, 0.9] {
            let fd = (arc.point(u + h) - arc.point(u - h)) / (2.0 * h);
            assert!((fd - arc.derivative(u)).norm() < 1e-8);
        }
    }

    #[test]
    fn through_three_points_in_3d() {
        // A circle of radius 2 about (1, -1, 0.5) in a tilted plane; pick points at 10°, 100°, 300°.
        let c = Vec3::new(1.0, -1.0, 0.5);
        let e1 = Vec3::new(1.0, 1.0, 1.0).normalize();
        let e2 = Vec3::new(1.0, -1.0, 0.0).normalize();
        let p = |deg: f64| c + 2.0 * (deg.to_radians().cos() * e1 + deg.to_radians().sin() * e2);
        let arc = Arc::through(p(10.0), p(100.0), p(300.0)).unwrap();
        assert!((arc.center() - c).norm() < 1e-12);
        assert!((arc.radius() - 2.0).abs() < 1e-12);
        assert!((arc.sweep() - 290f64.to_radians()).abs() < 1e-12);
        assert!((arc.point(0.0) - p(10.0)).norm() < 1e-12);
        assert!((arc.point(1.0) - p(300.0)).norm() < 1e-12);
        assert!((arc.point(90.0 / 290.0) - p(100.0)).norm() < 1e-12);
        // The reverse order goes the other way round: through p(100) again, sweep 290°.
        let back = Arc::through(p(300.0), p(100.0), p(10.0)).unwrap();
        assert!((back.sweep() - 290f64.to_radians()).abs() < 1e-12);
        assert!((back.point(200.0 / 290.0) - p(100.0)).norm() < 1e-12);
    }

    #[test]
    fn errors() {
        let o = Vec3::zeros();
        assert!(Arc::new(o, 0.0, 0.0, 90.0).is_err());
        assert!(Arc::new(o, 1.0, 10.0, 10.0).is_err());
        assert!(Arc::new(o, 1.0, 0.0, 361.0).is_err());
        assert!(Arc::new(o, f64::NAN, 0.0, 90.0).is_err());
        let x = Vec3::x();
        assert!(Arc::through(o, x, 2.0 * x).is_err());
        assert!(Arc::through(o, o, x).is_err());
    }
}
