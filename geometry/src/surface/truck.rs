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

/// A truck surface in its own parameters (u, v). Where its two boundary curves of one
/// direction coincide (a B-spline tube closed by equal first and last control rows, a ring
/// revolved from a closed profile), the surface closes on itself there and is taken as
/// periodic in that direction ([`TruckSurface::periods`]), evaluated with the parameter
/// wrapped into its range: a face's loop may then cross that seam as it crosses a cylinder's.
#[derive(Clone, Debug)]
pub struct TruckSurface<S> {
    surface: S,
    /// (start, period) of each direction in which the surface closes but truck has no period.
    closed: [Option<(f64, f64)>; 2],
}

/// Samples along a boundary curve to compare it with the opposite one.
const CLOSURE_SAMPLES: usize = 17;
/// Two boundary curves farther apart than this fraction of the surface's size are not one.
const CLOSURE_TOL: f64 = 1e-9;

impl<S: ParametricSurface3D> TruckSurface<S> {
    /// The surface, with the directions in which it closes on itself found.
    pub fn new(surface: S) -> TruckSurface<S> {
        let closed = closure(&surface);
        TruckSurface { surface, closed }
    }

    /// The truck surface.
    pub fn inner(&self) -> &S {
        &self.surface
    }

    /// (u, v) wrapped into the range of the directions in which the surface closes.
    fn wrap(&self, u: f64, v: f64) -> (f64, f64) {
        let w = |x: f64, c: Option<(f64, f64)>| match c {
            Some((a, t)) if x.is_finite() => a + (x - a).rem_euclid(t),
            _ => x,
        };
        (w(u, self.closed[0]), w(v, self.closed[1]))
    }

    /// The parameter box Newton may move in: the surface's range in bounded directions,
    /// unbounded in periodic ones (a face may straddle the seam) and where truck gives none.
    pub fn bounds(&self) -> [[f64; 2]; 2] {
        let (ru, rv) = self.surface.parameter_range();
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

    /// The periods of u and v, where the surface is periodic or closes on itself.
    pub fn periods(&self) -> [Option<f64>; 2] {
        let p = [self.surface.u_period(), self.surface.v_period()];
        [0, 1].map(|d| p[d].or(self.closed[d].map(|c| c.1)))
    }
}

/// A finite parameter range.
fn finite(r: (Bound<f64>, Bound<f64>)) -> Option<(f64, f64)> {
    match r {
        (Bound::Included(a) | Bound::Excluded(a), Bound::Included(b) | Bound::Excluded(b))
            if a.is_finite() && b.is_finite() && b > a =>
        {
            Some((a, b))
        }
        _ => None,
    }
}

/// (start, period) of each direction of a bounded, non-periodic range whose two boundary
/// curves coincide (within [`CLOSURE_TOL`] of the surface's size) and are not one point.
fn closure<S: ParametricSurface3D>(s: &S) -> [Option<(f64, f64)>; 2] {
    let (ru, rv) = s.parameter_range();
    let periods = [s.u_period(), s.v_period()];
    let ranges = [finite(ru), finite(rv)];
    // the other direction's samples: its range, or one period of it
    let across = |d: usize| -> Option<(f64, f64)> {
        ranges[d].or_else(|| periods[d].filter(|t| *t > 0.0).map(|t| (0.0, t)))
    };
    let at = |d: usize, x: f64, y: f64| p3(if d == 0 { s.subs(x, y) } else { s.subs(y, x) });
    [0, 1].map(|d| {
        let (a, b) = ranges[d].filter(|_| periods[d].is_none())?;
        let (c0, c1) = across(1 - d)?;
        let n = CLOSURE_SAMPLES;
        let ts: Vec<f64> = (0..n)
            .map(|k| c0 + (c1 - c0) * k as f64 / (n - 1) as f64)
            .collect();
        let (lo, hi): (Vec<Vec3>, Vec<Vec3>) =
            ts.iter().map(|&t| (at(d, a, t), at(d, b, t))).unzip();
        // the surface's size from a coarse net of points
        let (mut min, mut max) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
        for i in 0..n {
            let x = a + (b - a) * i as f64 / (n - 1) as f64;
            for &t in &ts {
                let q = at(d, x, t);
                min = min.inf(&q);
                max = max.sup(&q);
            }
        }
        let size = (max - min).norm();
        let length: f64 = lo.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        let apart = lo
            .iter()
            .zip(&hi)
            .map(|(p, q)| (p - q).norm())
            .fold(0.0, f64::max);
        (size.is_finite() && size > 0.0 && length > 1e-6 * size && apart <= CLOSURE_TOL * size)
            .then_some((a, b - a))
    })
}

impl<S: ParametricSurface3D + Send + Sync> Surface for TruckSurface<S> {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let (u, v) = self.wrap(u, v);
        let s = &self.surface;
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
        let (u, v) = self.wrap(u, v);
        p3(self.surface.subs(u, v))
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
        let s = TruckSurface::new(Sphere::new(Point3::new(1.0, 2.0, 3.0), 1.5));
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
    fn a_bspline_tube_closed_on_itself_is_periodic_there_and_a_disc_is_not() {
        // A polygonal tube: u around a square (first and last rows equal), v along z.
        let ring = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0), (1.0, 0.0)];
        let rows = |z: [f64; 2]| -> Vec<Vec<Point3>> {
            ring.iter()
                .map(|&(x, y)| z.iter().map(|&z| Point3::new(x, y, z)).collect())
                .collect()
        };
        let knots = || (KnotVec::uniform_knot(1, 4), KnotVec::bezier_knot(1));
        let tube = TruckSurface::new(BSplineSurface::new(knots(), rows([0.0, 2.0])));
        assert_eq!(tube.periods(), [Some(1.0), None]);
        assert_eq!(tube.bounds()[0], [f64::NEG_INFINITY, f64::INFINITY]);
        // evaluated a period away, and across the seam, as inside the range
        for (u, v) in [(0.1, 0.3), (0.95, 0.7)] {
            for k in [-2.0, -1.0, 1.0, 3.0] {
                let (a, b) = (tube.eval(u, v), tube.eval(u + k, v));
                assert!((a.x - b.x).norm() < 1e-14 && (a.xu - b.xu).norm() < 1e-12);
            }
        }
        // a point just across the seam is found there, not at the far end of the range
        let target = tube.point(0.02, 0.5);
        let (u1, v1) = project_within(&tube, target, (-0.03, 0.5), tube.bounds()).unwrap();
        assert!(
            (u1 + 1.0 - 1.02).abs() < 1e-10 || (u1 - 0.02).abs() < 1e-10,
            "{u1}"
        );
        assert!((tube.point(u1, v1) - target).norm() < 1e-12);
        // the same rows shifted a little apart at the end: open
        let mut open = rows([0.0, 2.0]);
        open[4][0].y += 1e-6;
        let open = TruckSurface::new(BSplineSurface::new(knots(), open));
        assert_eq!(open.periods(), [None, None]);
        // a disc's end rows are one point each (its centre and rim differ): not closed in v
        let disc: Vec<Vec<Point3>> = ring
            .iter()
            .map(|&(x, y)| vec![Point3::new(0.0, 0.0, 0.0), Point3::new(x, y, 0.0)])
            .collect();
        let disc = TruckSurface::new(BSplineSurface::new(knots(), disc));
        assert_eq!(disc.periods(), [Some(1.0), None]);
        // a patch whose two u-ends collapse to one and the same point: not closed in u
        let lens: Vec<Vec<Point3>> = (0..3)
            .map(|i| {
                let (r, z) = if i == 1 { (1.0, 1.0) } else { (0.0, 0.0) };
                vec![Point3::new(-r, 0.0, z), Point3::new(r, 0.0, z)]
            })
            .collect();
        let lens = TruckSurface::new(BSplineSurface::new(
            (KnotVec::uniform_knot(1, 2), KnotVec::bezier_knot(1)),
            lens,
        ));
        assert_eq!(lens.periods(), [None, None]);
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
