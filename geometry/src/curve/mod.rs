//! Parametric curves x(u), u ∈ [0, 1], in R³, and their arclength parametrization.
//!
//! One file per curve type (`line`, `arc`, `polyline`, `spline`, `naca`, `surface_line`); `arclength` holds the
//! generic algorithm that every curve uses: [`ArclengthMap`] (normalized arclength σ ↔ u) and
//! [`sample`] (points at given σ, as needed for the boundary distributions of METHOD.md [30–38]).

mod arc;
mod arclength;
mod line;
mod naca;
mod polyline;
mod spline;
mod surface_line;

pub use arc::Arc;
pub use arclength::{sample, ArclengthMap};
pub use line::Line;
pub use naca::{Naca4, Naca4Side};
pub use polyline::Polyline;
pub use spline::Spline;
pub use surface_line::SurfaceLine;

use crate::{GeometryError, Vec3};

/// A parametric curve x(u) in R³ for u ∈ [0, 1].
///
/// Implementations may extrapolate outside [0, 1]; callers should not rely on it.
pub trait Curve: Send + Sync {
    /// The point x(u).
    fn point(&self, u: f64) -> Vec3;

    /// The derivative dx/du. At a breakpoint either one-sided value may be returned.
    fn derivative(&self, u: f64) -> Vec3;

    /// Parameters in (0, 1) where the curve is not smooth (kinks, knots of piecewise curves,
    /// non-analytic points). Quadratures split there so that they stay spectrally accurate.
    fn breakpoints(&self) -> Vec<f64> {
        vec![]
    }
}

impl<C: Curve + ?Sized> Curve for &C {
    fn point(&self, u: f64) -> Vec3 {
        (**self).point(u)
    }
    fn derivative(&self, u: f64) -> Vec3 {
        (**self).derivative(u)
    }
    fn breakpoints(&self) -> Vec<f64> {
        (**self).breakpoints()
    }
}

impl<C: Curve + ?Sized> Curve for Box<C> {
    fn point(&self, u: f64) -> Vec3 {
        (**self).point(u)
    }
    fn derivative(&self, u: f64) -> Vec3 {
        (**self).derivative(u)
    }
    fn breakpoints(&self) -> Vec<f64> {
        (**self).breakpoints()
    }
}

impl<C: Curve + ?Sized> Curve for std::sync::Arc<C> {
    fn point(&self, u: f64) -> Vec3 {
        (**self).point(u)
    }
    fn derivative(&self, u: f64) -> Vec3 {
        (**self).derivative(u)
    }
    fn breakpoints(&self) -> Vec<f64> {
        (**self).breakpoints()
    }
}

/// Checks that there are at least two finite points and no zero-length segment, and returns
/// the cumulative chord lengths (first 0, last the total length).
///
/// Shared by [`Polyline`] and [`Spline`]; errors name the offending point index.
fn chord_lengths(points: &[Vec3], what: &str) -> Result<Vec<f64>, GeometryError> {
    if points.len() < 2 {
        return Err(GeometryError::Invalid(format!(
            "{what}: needs at least 2 points, got {}",
            points.len()
        )));
    }
    if let Some(i) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(GeometryError::Invalid(format!(
            "{what}: point {i} is not finite: ({}, {}, {})",
            points[i].x, points[i].y, points[i].z
        )));
    }
    let mut cum = Vec::with_capacity(points.len());
    cum.push(0.0);
    for i in 1..points.len() {
        let d = (points[i] - points[i - 1]).norm();
        // Relative test: a segment below rounding level of the coordinates is a duplicate.
        let scale = points[i].amax().max(points[i - 1].amax());
        if d <= 4.0 * f64::EPSILON * scale || d == 0.0 {
            return Err(GeometryError::Invalid(format!(
                "{what}: zero-length segment between points {} and {i} (a duplicate point)",
                i - 1
            )));
        }
        cum.push(cum[i - 1] + d);
    }
    Ok(cum)
}

/// Index k of the knot interval [t_k, t_{k+1}] that contains u (clamped to the end intervals).
fn knot_interval(t: &[f64], u: f64) -> usize {
    let k = t.partition_point(|&tk| tk <= u);
    k.saturating_sub(1).min(t.len() - 2)
}
