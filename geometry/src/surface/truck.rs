//! Any truck surface or curve (planes, cylinders, cones, spheres, tori, swept and B-spline
//! surfaces as truck-stepio reads them from STEP) in its own parameters, with exact
//! derivatives from truck, as a [`Surface`] / [`Curve`].
//!
//! The parameters are *not* mapped to [0, 1]²: CAD faces are trimmed regions of their
//! surface, found by projection ([`super::project_within`] with [`TruckSurface::bounds`]), and
//! the face's own parametrization from the unit square is built on top (ellipgrid's
//! `cad::face`).

use super::{Surface, SurfacePoint};
use crate::{Curve, Vec3};
use std::ops::Bound;
use truck_geometry::prelude::{
    BoundedCurve, ParametricCurve3D, ParametricSurface3D, Point3, Vector3,
};

fn v3(p: Vector3) -> Vec3 {
    Vec3::new(p.x, p.y, p.z)
}

fn p3(p: Point3) -> Vec3 {
    Vec3::new(p.x, p.y, p.z)
}

/// A truck surface in its own parameters (u, v).
#[derive(Clone, Debug)]
pub struct TruckSurface<S>(pub S);

impl<S: ParametricSurface3D> TruckSurface<S> {
    /// The parameter box Newton may move in: the surface's range in bounded directions,
    /// unbounded in periodic ones (a face may straddle the seam) and where truck gives none.
    pub fn bounds(&self) -> [[f64; 2]; 2] {
        let (ru, rv) = self.0.parameter_range();
        let periods = self.periods();
        let b = |r: (Bound<f64>, Bound<f64>), periodic: bool| {
            let lo = match r.0 {
                Bound::Included(a) | Bound::Excluded(a) if !periodic => a,
                _ => f64::NEG_INFINITY,
            };
            let hi = match r.1 {
                Bound::Included(a) | Bound::Excluded(a) if !periodic => a,
                _ => f64::INFINITY,
            };
            [lo, hi]
        };
        [b(ru, periods[0].is_some()), b(rv, periods[1].is_some())]
    }

    /// The periods of u and v, where the surface is periodic.
    pub fn periods(&self) -> [Option<f64>; 2] {
        [self.0.u_period(), self.0.v_period()]
    }
}

impl<S: ParametricSurface3D + Send + Sync> Surface for TruckSurface<S> {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let s = &self.0;
        SurfacePoint {
            x: p3(s.subs(u, v)),
            xu: v3(s.uder(u, v)),
            xv: v3(s.vder(u, v)),
            xuu: v3(s.uuder(u, v)),
            xuv: v3(s.uvder(u, v)),
            xvv: v3(s.vvder(u, v)),
        }
    }

    fn point(&self, u: f64, v: f64) -> Vec3 {
        p3(self.0.subs(u, v))
    }
}

/// A bounded truck curve run over t ∈ [0, 1], forwards or backwards (an oriented edge of a
/// face's boundary loop); `breaks` are its knots in t (where it may be only C¹ or C⁰).
#[derive(Clone, Debug)]
pub struct TruckCurve<C> {
    curve: C,
    a: f64,
    b: f64,
    breaks: Vec<f64>,
}

impl<C: ParametricCurve3D + BoundedCurve> TruckCurve<C> {
    /// The curve over its range, reversed if `forward` is false; `knots` are parameters of the
    /// curve where it is not smooth. `None` if unbounded.
    pub fn new(curve: C, forward: bool, knots: &[f64]) -> Option<TruckCurve<C>> {
        let range = curve.try_range_tuple()?;
        TruckCurve::on(curve, range, forward, knots)
    }
}

impl<C: ParametricCurve3D> TruckCurve<C> {
    /// The curve over the parameter interval `(a, b)` (a < b), reversed if `forward` is false.
    /// `None` if the interval is not finite and non-empty.
    pub fn on(curve: C, (a, b): (f64, f64), forward: bool, knots: &[f64]) -> Option<TruckCurve<C>> {
        if !(a.is_finite() && b.is_finite() && b > a) {
            return None;
        }
        let (a, b) = if forward { (a, b) } else { (b, a) };
        let mut breaks: Vec<f64> = knots
            .iter()
            .map(|k| (k - a) / (b - a))
            .filter(|t| *t > 0.0 && *t < 1.0)
            .collect();
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        Some(TruckCurve {
            curve,
            a,
            b,
            breaks,
        })
    }

    /// The curve's own parameter at t.
    pub fn param(&self, t: f64) -> f64 {
        self.a + (self.b - self.a) * t
    }
}

impl<C: ParametricCurve3D + Send + Sync> Curve for TruckCurve<C> {
    fn point(&self, t: f64) -> Vec3 {
        p3(self.curve.subs(self.a + (self.b - self.a) * t))
    }
    fn derivative(&self, t: f64) -> Vec3 {
        v3(self.curve.der(self.a + (self.b - self.a) * t)) * (self.b - self.a)
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.breaks.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::project_within;
    use crate::ArclengthMap;
    use std::f64::consts::PI;
    use truck_geometry::prelude::*;

    #[test]
    fn truck_sphere_derivatives_and_projection_across_the_seam() {
        let s = TruckSurface(Sphere::new(Point3::new(1.0, 2.0, 3.0), 1.5));
        // Derivatives against central differences.
        let (u, v, h) = (0.7, 1.1, 1e-5);
        let e = s.eval(u, v);
        let fd = (s.point(u + h, v) - s.point(u - h, v)) / (2.0 * h);
        assert!((fd - e.xu).norm() < 1e-8);
        let fd = (s.eval(u, v + h).xv - s.eval(u, v - h).xv) / (2.0 * h);
        assert!((fd - e.xvv).norm() < 1e-7);
        // A point just across the seam from the start is found there, not a period away.
        // truck's sphere: u the polar angle in [0, π], v the longitude, periodic.
        let period = s.periods()[1].expect("the sphere is periodic in v");
        assert!((period - 2.0 * PI).abs() < 1e-12 && s.periods()[0].is_none());
        assert_eq!(s.bounds()[1], [f64::NEG_INFINITY, f64::INFINITY]);
        let target = s.point(1.2, -0.05);
        let (u1, v1) = project_within(&s, target, (1.2, 0.02), s.bounds()).unwrap();
        assert!(
            (u1 - 1.2).abs() < 1e-10 && (v1 + 0.05).abs() < 1e-10,
            "{u1} {v1}"
        );
    }

    #[test]
    fn truck_circle_arc_length_both_ways() {
        let c = BSplineCurve::new(
            KnotVec::bezier_knot(2),
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 1.0, 0.0),
                Point3::new(2.0, 0.0, 0.0),
            ],
        );
        let f = TruckCurve::new(c.clone(), true, &[]).unwrap();
        let b = TruckCurve::new(c, false, &[]).unwrap();
        let (lf, lb) = (
            ArclengthMap::new(&f).length(),
            ArclengthMap::new(&b).length(),
        );
        // x = 2t, y = 2t(1 − t): L = ∫ sqrt(4 + (2 − 4t)²) dt.
        let exact = 2f64.sqrt() + 1f64.asinh();
        assert!(
            (lf - lb).abs() < 1e-13 && (lf - exact).abs() < 1e-12,
            "{lf} {exact}"
        );
        assert!((f.point(0.0) - b.point(1.0)).norm() < 1e-15);
    }
}
