//! Parametric surfaces x(u, v) on the unit parameter square (u, v) ∈ [0, 1]² (METHOD.md §4–5).
//!
//! The surface-grid pipeline needs, at any (u, v), the point and its first and second
//! derivatives (the metric g_ij = x_i · x_j and the Laplace–Beltrami coefficients), plus the
//! inverse map: the parameters of the surface point closest to a given point.
//!
//! | file | what |
//! |---|---|
//! | `hermite` | [`HermiteSurface`]: C¹ bicubic Hermite (Ferguson) patches through a control net |
//! | `bspline` | [`BSplineSurf`]: fast local evaluation of truck B-spline / NURBS surfaces |
//! | `analytic` | [`Plane`], [`TanhBump`] (paper Fig. 31), [`Scherk`] minimal surface |
//! | `project` | [`project`], [`project_within`], [`project_to_edge`]: safeguarded Newton for the closest point |
//! | `truck` | [`TruckSurface`], [`TruckCurve`]: any truck surface / curve in its own parameters (a surface that closes on itself periodic there) |
//! | `locate` | [`SurfaceLocator`]: BVH of sampled cells ([`crate::BoxTree`]) + Newton |
//! | `model` | [`ModelLocator`]: closest points on several surfaces (a CAD model's faces), one BVH over their samples |
//! | `intersect` | [`trace_intersection`]: the curve where two surfaces meet, by predictor–corrector marching |
//! | `warp` | [`Warp`], [`Warped`]: a smooth random re-parametrization x(W(u, v)) (fixed seed) |
//!
//! Every impl gives exact derivatives; the tests check them against central differences.
//!
//! ```
//! use ellipgrid_geometry::{project, HermiteSurface, Surface, SurfaceLocator, Vec3};
//! // A 5 × 4 control net of the bilinear surface z = x y: reproduced exactly.
//! let pts = (0..20)
//!     .map(|k| {
//!         let (x, y) = ((k % 5) as f64 / 4.0, (k / 5) as f64 / 3.0);
//!         Vec3::new(x, y, x * y)
//!     })
//!     .collect();
//! let s = HermiteSurface::new(5, 4, pts)?;
//! let e = s.eval(0.3, 0.7);
//! assert!((e.x - Vec3::new(0.3, 0.7, 0.21)).norm() < 1e-14);
//! assert!((e.xuv - Vec3::new(0.0, 0.0, 1.0)).norm() < 1e-12);
//! // The closest point of a point off the surface: global search, then Newton.
//! let p = e.x + 0.01 * e.normal();
//! let (u, v) = SurfaceLocator::new(&s, 8, 6)?.closest(p);
//! assert!((u - 0.3).abs() < 1e-12 && (v - 0.7).abs() < 1e-12);
//! let (u2, v2) = project(&s, p, (0.25, 0.75)).unwrap(); // Newton from a nearby start
//! assert!((u2 - u).abs() < 1e-13 && (v2 - v).abs() < 1e-13);
//! # Ok::<(), ellipgrid_geometry::GeometryError>(())
//! ```

mod analytic;
mod bspline;
mod hermite;
mod intersect;
mod locate;
mod model;
mod project;
#[cfg(test)]
pub(crate) mod testutil;
mod truck;
mod warp;

pub use analytic::{scherk_distance, Plane, Scherk, TanhBump};
pub use bspline::BSplineSurf;
pub use hermite::HermiteSurface;
pub use intersect::{intersection_point, trace_intersection, Projector};
pub use locate::SurfaceLocator;
pub use model::{ModelLocator, ModelPoint, ModelSample};
pub use project::{project, project_to_edge, project_within};
pub use truck::{TruckCurve, TruckSurface};
pub use warp::{Warp, WarpJet, Warped};

use crate::Vec3;

/// A surface point with its first and second parameter derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// x(u, v).
    pub x: Vec3,
    /// ∂x/∂u.
    pub xu: Vec3,
    /// ∂x/∂v.
    pub xv: Vec3,
    /// ∂²x/∂u².
    pub xuu: Vec3,
    /// ∂²x/∂u∂v.
    pub xuv: Vec3,
    /// ∂²x/∂v².
    pub xvv: Vec3,
}

impl SurfacePoint {
    /// Unit normal x_u × x_v / |x_u × x_v| (NaN where the surface is singular).
    pub fn normal(&self) -> Vec3 {
        let n = self.xu.cross(&self.xv);
        n / n.norm()
    }
}

/// A parametric surface x(u, v) on (u, v) ∈ [0, 1]².
///
/// Implementations may extrapolate outside the square; callers should not rely on it.
/// At a patch or knot line either one-sided derivative may be returned.
pub trait Surface: Send + Sync {
    /// Point and first and second derivatives at (u, v).
    fn eval(&self, u: f64, v: f64) -> SurfacePoint;

    /// The point x(u, v) (override when it is cheaper than [`Surface::eval`]).
    fn point(&self, u: f64, v: f64) -> Vec3 {
        self.eval(u, v).x
    }

    /// Parameter lines (u values, v values) across which the surface is only C¹ or C⁰ (patch
    /// or knot lines): quadratures along the surface split there. Default: none.
    fn breaks(&self) -> (Vec<f64>, Vec<f64>) {
        (vec![], vec![])
    }
}

macro_rules! forward_surface {
    ($($t:ty),*) => {$(
        impl<S: Surface + ?Sized> Surface for $t {
            fn eval(&self, u: f64, v: f64) -> SurfacePoint {
                (**self).eval(u, v)
            }
            fn point(&self, u: f64, v: f64) -> Vec3 {
                (**self).point(u, v)
            }
            fn breaks(&self) -> (Vec<f64>, Vec<f64>) {
                (**self).breaks()
            }
        }
    )*};
}
forward_surface!(&S, Box<S>, std::sync::Arc<S>);

/// One boundary curve of the parameter square.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SurfaceEdge {
    /// u = 0, parametrized by v.
    U0,
    /// u = 1, parametrized by v.
    U1,
    /// v = 0, parametrized by u.
    V0,
    /// v = 1, parametrized by u.
    V1,
}

impl SurfaceEdge {
    /// The (u, v) of edge parameter t.
    pub fn uv(self, t: f64) -> (f64, f64) {
        match self {
            SurfaceEdge::U0 => (0.0, t),
            SurfaceEdge::U1 => (1.0, t),
            SurfaceEdge::V0 => (t, 0.0),
            SurfaceEdge::V1 => (t, 1.0),
        }
    }

    /// Point, first and second derivative of the edge curve at edge parameter t.
    pub fn curve(self, surface: &dyn Surface, t: f64) -> (Vec3, Vec3, Vec3) {
        let (u, v) = self.uv(t);
        let s = surface.eval(u, v);
        match self {
            SurfaceEdge::U0 | SurfaceEdge::U1 => (s.x, s.xv, s.xvv),
            SurfaceEdge::V0 | SurfaceEdge::V1 => (s.x, s.xu, s.xuu),
        }
    }
}
