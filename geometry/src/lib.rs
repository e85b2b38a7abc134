//! Geometry for ellipgrid: curves, boundary point distributions, airfoils (and, later, surfaces).
//!
//! | module | what | entry points |
//! |---|---|---|
//! | [`curve`] | parametric curves in R³ on u ∈ [0, 1], arclength maps | [`Curve`], [`ArclengthMap`], [`sample`] |
//! | [`distribution`] | normalized point distributions on [0, 1] (METHOD.md [30–38]) | [`Distribution`], [`vinokur`], [`geometric`] |
//! | [`airfoil`] | Selig / Lednicer `.dat` files | [`read_airfoil_dat`], [`airfoil_curve`] |
//! | [`surface`] | parametric surfaces on (u, v) ∈ [0, 1]² with 2nd derivatives; closest point (one surface or a model of several); surface–surface intersection | [`Surface`], [`HermiteSurface`], [`BSplineSurf`], [`project`], [`SurfaceLocator`], [`ModelLocator`], [`trace_intersection`] |
//! | [`bvh`] | conservative f64 box hierarchy over obvhs | [`BoxTree`] |
//! | [`random`] | a fixed-seed generator (random warps, scrambled starts) | [`random::SplitMix64`] |
//!
//! A boundary edge is a [`Curve`] plus a [`Distribution`]:
//!
//! ```
//! use ellipgrid_geometry::{sample, ArclengthMap, Distribution, Naca4};
//! let upper = Naca4::new("0012", 1.0, true)?.upper(); // LE (u = 0) → TE (u = 1)
//! let sigma = Distribution::Vinokur { first: Some(1e-4), last: Some(1e-2) }.sample(65)?;
//! let pts = sample(&upper, &sigma);
//! let arc_len = ArclengthMap::new(&upper).length();
//! // The first node spacing is 1e-4 of the arclength (the chord of a short arc).
//! assert!(((pts[1] - pts[0]).norm() / arc_len - 1e-4).abs() < 1e-8);
//! # Ok::<(), ellipgrid_geometry::GeometryError>(())
//! ```
//!
//! # Bibliography
//! - \[Vinokur 1983\] M. Vinokur, On one-dimensional stretching functions for finite-difference
//!   calculations, J. Comput. Phys. 50 (1983) 215–234.
//! - \[Abbott & von Doenhoff\] Theory of Wing Sections, Dover 1959 (NACA 4-digit sections).
//! - \[TP 96338\] J. Spekreijse, J. W. Boerstoel, Multiblock grid generation, NLR TP 96338.
//! - \[Piegl & Tiller\] L. Piegl, W. Tiller, The NURBS Book, 2nd ed., Springer 1997 (A2.3:
//!   B-spline basis derivatives; rational derivatives, [`BSplineSurf`]).
//! - \[Steele et al. 2014\] G. L. Steele, D. Lea, C. H. Flood, Fast splittable pseudorandom
//!   number generators, OOPSLA 2014 (SplitMix64, [`random::SplitMix64`]).
//! - \[Ericson\] C. Ericson, Real-Time Collision Detection, Morgan Kaufmann 2005 (§5.1.5:
//!   closest point on a triangle, [`SurfaceLocator`]).
#![warn(missing_docs)]

pub mod airfoil;
pub mod bvh;
pub mod curve;
pub mod distribution;
pub mod random;
pub mod surface;

pub use airfoil::{airfoil_curve, read_airfoil_dat};
pub use bvh::BoxTree;
pub use curve::{
    sample, Arc, ArclengthMap, Curve, Line, Naca4, Naca4Side, Polyline, Spline, SurfaceLine,
};
pub use distribution::{geometric, reverse, uniform, vinokur, vinokur_refined, Distribution};
pub use surface::{
    intersection_point, project, project_to_edge, project_within, scherk_distance,
    trace_intersection, BSplineSurf, HermiteSurface, ModelLocator, ModelPoint, ModelSample, Plane,
    Projector, Scherk, Surface, SurfaceEdge, SurfaceLocator, SurfacePoint, TanhBump, TruckCurve,
    TruckSurface, Warp, Warped,
};

/// A point or vector in R³; planar curves have z = 0.
pub type Vec3 = nalgebra::Vector3<f64>;

/// Errors of the geometry crate.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum GeometryError {
    /// Invalid input (bad parameters, degenerate geometry); the message names the culprit.
    #[error("{0}")]
    Invalid(String),
    /// A text file (airfoil `.dat`) could not be parsed; `line` is 1-based.
    #[error("line {line}: {message}")]
    Parse {
        /// 1-based line number.
        line: usize,
        /// What is wrong with that line.
        message: String,
    },
    /// An iteration (e.g. fitting Vinokur's parameters to the requested spacings) did not converge.
    #[error("{what}: no convergence after {iterations} iterations (residual {residual:e})")]
    NoConvergence {
        /// Which iteration.
        what: String,
        /// Iterations done.
        iterations: usize,
        /// Last residual (relative).
        residual: f64,
    },
}
