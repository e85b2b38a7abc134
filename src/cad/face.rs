//! A CAD face bounded by one loop of edges, on any surface, gridded as a four-sided block face
//! (METHOD.md §5 on top of §2).
//!
//! 1. the loop on the surface ([`super::trim::FaceLoop`]): (u, v) of its edges by projection,
//!    four corners, four sides; boundary nodes at the requested 3D arclengths on the edges;
//! 2. the face's parametrization from the unit square: a Section 2 grid in the surface's
//!    (u, v) plane (scaled by the mean |x_u|, |x_v| so that it is close to isometric) bounded
//!    by the four sides, with zero control functions (Winslow: one-to-one for any
//!    simply connected domain, also a non-convex trim), interpolated by bicubic Hermite
//!    patches w(ξ, η);
//! 3. the Section 4 pipeline on the composite surface x(w(ξ, η)): the initial grid is the
//!    (u, v) grid's image, the final grid comes from the Laplace–Beltrami map and inversion
//!    and lies on the CAD surface exactly; boundary nodes are the points on the CAD edges.
//!
//! The result depends on neither the CAD parametrization nor the (u, v) grid, up to the
//! discretization error (tests: `tests/step_faces.rs`).

use super::trim::{CadSurface, FaceLoop, LoopPoint};
use super::{quietly, Route, StepFace};
use crate::algebraic::ControlKind;
use crate::case::DistributionSpec;
use crate::elliptic::domain::grid_block;
use crate::elliptic::picard::{PicardInfo, PicardParams};
use crate::grid::boundary::Boundary2;
use crate::grid::{Edge, Grid2};
use crate::solve::LinearSolver;
use crate::surface::pipeline::{grid_surface, SurfaceResult};
use crate::{Error, Result};
use ellipgrid_geometry::{HermiteSurface, Surface, SurfacePoint, TruckSurface, Vec3};
use truck_stepio::r#in::alias::Surface as StepSurface;

/// A boundary point farther than this from the face's surface (relative to the loop's size)
/// is an error: the edge is not on the face.
pub const GAP_TOL: f64 = 1e-3;

/// A gridded CAD face.
#[derive(Clone, Debug)]
pub struct FaceGrid {
    /// The grid, its initial grid, the surface (u, v) of every node (for an untrimmed patch:
    /// normalized to [0, 1]²), step times.
    pub result: SurfaceResult,
    /// Turning angles of the loop at the four corners (degrees; 0 at a corner placed inside
    /// an edge). Empty for an untrimmed patch.
    pub corner_angles: Vec<f64>,
    /// Largest distance between a boundary point and the surface (the file's gaps).
    pub gap: f64,
    /// The Section 2 solve of the (u, v) grid (none for an untrimmed patch).
    pub uv_picard: Option<PicardInfo>,
}

/// The grid of a face: `ni` nodes along its first and third sides, `nj` along the second and
/// fourth, placed on each by `dist_i` / `dist_j` (lengths).
///
/// # Errors
/// [`Error::Input`] at `place` with the reason if the face is refused ([`Route::Refused`]) or
/// its boundary is unusable (edges off the surface or not meeting, a loop around the
/// surface); [`Error::Folded`] if the (u, v) grid folds; those of the pipeline.
pub fn grid_face(
    face: &StepFace,
    (ni, nj): (usize, usize),
    dist_i: &DistributionSpec,
    dist_j: &DistributionSpec,
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<FaceGrid> {
    if ni < 3 || nj < 3 {
        return Err(Error::input(
            place,
            format!("a surface grid needs at least 3 × 3 nodes, got {ni} × {nj}"),
        ));
    }
    match face.route() {
        Route::Refused(why) => Err(Error::input(place, why)),
        Route::Patch => {
            let s = face
                .surface
                .as_ref()
                .expect("a patch has a B-spline surface");
            let result = super::grid_patch(s, (ni, nj), dist_i, dist_j, solver, place)?;
            Ok(FaceGrid {
                result,
                corner_angles: Vec::new(),
                gap: 0.0,
                uv_picard: None,
            })
        }
        Route::Trimmed(_) => trimmed(face, (ni, nj), [dist_i, dist_j], solver, place),
    }
}

/// The parameter box of a face's projection: truck's range for B-spline and NURBS
/// surfaces, unbounded for the others (their ranges in truck are those of the generating
/// curve segment, not of the surface).
fn bounds(s: &CadSurface) -> [[f64; 2]; 2] {
    match s.0 {
        StepSurface::BSplineSurface(_) | StepSurface::NurbsSurface(_) => s.bounds(),
        _ => [[f64::NEG_INFINITY, f64::INFINITY]; 2],
    }
}

fn trimmed(
    face: &StepFace,
    (ni, nj): (usize, usize),
    dist: [&DistributionSpec; 2],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<FaceGrid> {
    let surface = TruckSurface(face.cad_surface.clone());
    let edges = match &face.loops {
        Ok(l) => &l[0],
        Err(e) => return Err(Error::input(place, e.clone())),
    };
    let boundary = quietly(|| boundary(&surface, edges, face.orientation, (ni, nj), dist, place))
        .unwrap_or_else(|_| {
        Err(Error::input(
            place,
            "truck failed to evaluate a boundary edge or the surface",
        ))
    })?;
    // Step 2: the Section 2 grid in the scaled (u, v) plane.
    let b = Boundary2::new(boundary.uv_scaled.clone(), &format!("{place}, (u, v) grid"))?;
    let params = PicardParams::default();
    let uvg = grid_block::<2>(&b, None, ControlKind::Laplace, solver, &params, place)?;
    check_unfolded(&uvg.grid, place)?;
    let sc = boundary.scale;
    let net: Vec<Vec3> = (0..ni * nj)
        .map(|p| {
            Vec3::new(
                uvg.grid.coord(0)[p] / sc[0],
                uvg.grid.coord(1)[p] / sc[1],
                0.0,
            )
        })
        .collect();
    let w = HermiteSurface::new(ni, nj, net).map_err(|source| Error::Geometry {
        place: place.to_string(),
        source,
    })?;
    // Step 3: Section 4 on the composite surface, boundary nodes at the (ξ, η) grid nodes.
    let composite = Composite { s: &surface, w: &w };
    let side = |n: usize| (0..n).map(move |k| k as f64 / (n - 1) as f64);
    let xi: [Vec<[f64; 2]>; 4] = [
        side(nj).map(|t| [0.0, t]).collect(),
        side(nj).map(|t| [1.0, t]).collect(),
        side(ni).map(|t| [t, 0.0]).collect(),
        side(ni).map(|t| [t, 1.0]).collect(),
    ];
    let mut result =
        quietly(|| grid_surface(&composite, &xi, solver, place)).unwrap_or_else(|_| {
            Err(Error::input(
                place,
                "truck failed to evaluate the surface inside the face",
            ))
        })?;
    // The CAD (u, v) of every node; boundary nodes exactly on the CAD edges.
    for q in result.uv.iter_mut() {
        let p = w.point(q[0], q[1]);
        *q = [p.x, p.y];
    }
    for e in Edge::ALL {
        let (x, uv) = (&boundary.points[e.index()], &boundary.uv[e.index()]);
        for (k, (p, q)) in x.iter().zip(uv).enumerate() {
            let n = match e {
                Edge::E1 => ni * k,
                Edge::E2 => ni - 1 + ni * k,
                Edge::E3 => k,
                Edge::E4 => k + ni * (nj - 1),
            };
            for c in 0..3 {
                result.grid.coords_mut()[c][n] = p[c];
                result.initial.coords_mut()[c][n] = p[c];
            }
            result.uv[n] = *q;
        }
    }
    Ok(FaceGrid {
        result,
        corner_angles: boundary.angles.to_vec(),
        gap: boundary.gap,
        uv_picard: Some(uvg.picard),
    })
}

/// The four block edges E1..E4 of a face: 3D points on the CAD edges, their (u, v), and
/// (u, v) scaled by `scale`.
struct FaceBoundary {
    points: [Vec<Vec3>; 4],
    uv: [Vec<[f64; 2]>; 4],
    uv_scaled: [Vec<[f64; 2]>; 4],
    scale: [f64; 2],
    angles: [f64; 4],
    gap: f64,
}

/// Step 1: the loop, its corners q0..q3 in the order that makes the grid's normal the face's
/// (counterclockwise in (u, v) when the face's normal is the surface's), and the boundary
/// nodes: E3 = q0 → q1 and E4 = q3 → q2 with `ni` nodes by `dist[0]`, E1 = q0 → q3 and
/// E2 = q1 → q2 with `nj` nodes by `dist[1]`.
fn boundary(
    surface: &CadSurface,
    edges: &[super::LoopEdge],
    orientation: bool,
    (ni, nj): (usize, usize),
    dist: [&DistributionSpec; 2],
    place: &str,
) -> Result<FaceBoundary> {
    let err = |m: String| Error::input(place, m);
    let mut lp = FaceLoop::new(surface, edges, bounds(surface), GAP_TOL).map_err(err)?;
    let (c, angles) = lp.corners();
    let scale = lp.metric_scale();
    let forward = (lp.signed_area(scale) > 0.0) == orientation;
    let (q, angles) = if forward {
        (c, angles)
    } else {
        (
            [c[0], c[3], c[2], c[1]],
            [angles[0], angles[3], angles[2], angles[1]],
        )
    };
    // The loop from a to b in the traversal direction, at arclength fractions f.
    let path = |lp: &mut FaceLoop, a: LoopPoint, b: LoopPoint, f: &[f64]| {
        if forward {
            lp.sample(a, b, f)
        } else {
            let g: Vec<f64> = f.iter().map(|t| 1.0 - t).collect();
            lp.sample(b, a, &g)
        }
    };
    let length = |lp: &FaceLoop, a: LoopPoint, b: LoopPoint| {
        if forward {
            lp.chain_length(a, b)
        } else {
            lp.chain_length(b, a)
        }
    };
    // (from, to, reversed, nodes, distribution) of E1..E4; a reversed edge is the path
    // `to → from` read backwards.
    let spec = [
        (q[3], q[0], true, nj, dist[1]),
        (q[1], q[2], false, nj, dist[1]),
        (q[0], q[1], false, ni, dist[0]),
        (q[2], q[3], true, ni, dist[0]),
    ];
    let mut points: [Vec<Vec3>; 4] = Default::default();
    let mut uv: [Vec<[f64; 2]>; 4] = Default::default();
    for (e, (a, b, reversed, n, d)) in Edge::ALL.into_iter().zip(spec) {
        let at = format!("{place}, edge {e}");
        let sigma = d.sample(n, length(&lp, a, b), &at)?;
        let f: Vec<f64> = if reversed {
            sigma.iter().map(|s| 1.0 - s).collect()
        } else {
            sigma
        };
        let (x, w) = path(&mut lp, a, b, &f).map_err(|m| Error::input(&at, m))?;
        points[e.index()] = x;
        uv[e.index()] = w;
    }
    // Each corner ends two block edges, sampled on two CAD edges that meet there only to the
    // file's tolerance: one point and one (u, v) for both (their mean).
    let last = |e: Edge| match e {
        Edge::E1 | Edge::E2 => nj - 1,
        Edge::E3 | Edge::E4 => ni - 1,
    };
    let corners = [
        ((Edge::E1, 0), (Edge::E3, 0)),
        ((Edge::E3, last(Edge::E3)), (Edge::E2, 0)),
        ((Edge::E2, last(Edge::E2)), (Edge::E4, last(Edge::E4))),
        ((Edge::E4, 0), (Edge::E1, last(Edge::E1))),
    ];
    for ((ea, ka), (eb, kb)) in corners {
        let (a, b) = (ea.index(), eb.index());
        let x = 0.5 * (points[a][ka] + points[b][kb]);
        let w = [0, 1].map(|c| 0.5 * (uv[a][ka][c] + uv[b][kb][c]));
        let miss = (points[a][ka] - points[b][kb]).norm();
        let uv_miss = (0..2)
            .map(|c| ((uv[a][ka][c] - uv[b][kb][c]) * scale[c]).abs())
            .fold(0.0, f64::max);
        if miss > lp.tol() || uv_miss > 10.0 * lp.tol().max(miss) {
            return Err(Error::input(
                place,
                format!(
                    "the block edges {ea} and {eb} do not meet at their corner ({miss:.3e} apart \
                     in space, {uv_miss:.3e} in the surface's parameters)"
                ),
            ));
        }
        (points[a][ka], points[b][kb]) = (x, x);
        (uv[a][ka], uv[b][kb]) = (w, w);
    }
    let uv_scaled = uv.clone().map(|e| {
        e.iter()
            .map(|p| [p[0] * scale[0], p[1] * scale[1]])
            .collect()
    });
    Ok(FaceBoundary {
        points,
        uv,
        uv_scaled,
        scale,
        angles,
        gap: lp.gap,
    })
}

/// The (u, v) grid must not fold: every cell's corners turn counterclockwise. A corner
/// angle of 180° (a face corner placed inside an edge) is degenerate, not folded: rounding
/// may make it turn clockwise by a hair (|sin| below 1e-9).
fn check_unfolded(g: &Grid2<2>, place: &str) -> Result<()> {
    let (ni, nj) = (g.ni(), g.nj());
    let (x, y) = (g.coord(0), g.coord(1));
    let mut bad = Vec::new();
    for j in 0..nj - 1 {
        for i in 0..ni - 1 {
            let n = [
                i + ni * j,
                i + 1 + ni * j,
                i + 1 + ni * (j + 1),
                i + ni * (j + 1),
            ];
            let folded = (0..4).any(|k| {
                let (a, b, c) = (n[(k + 3) % 4], n[k], n[(k + 1) % 4]);
                let (ux, uy) = (x[c] - x[b], y[c] - y[b]);
                let (vx, vy) = (x[a] - x[b], y[a] - y[b]);
                let cross = ux * vy - uy * vx;
                let scale = (ux * ux + uy * uy).sqrt() * (vx * vx + vy * vy).sqrt();
                cross.partial_cmp(&(-1e-9 * scale)) != Some(std::cmp::Ordering::Greater)
                    || scale == 0.0
            });
            if folded {
                bad.push((i, j));
            }
        }
    }
    if bad.is_empty() {
        return Ok(());
    }
    Err(Error::Folded {
        place: format!("{place}, (u, v) grid"),
        count: bad.len(),
        first: format!(
            "cell {:?}: the face's parametrization (a Section 2 grid in the surface's (u, v) \
             plane) folds",
            bad[0]
        ),
    })
}

/// x(w(ξ, η)): the CAD surface over the face's parametrization from the unit square.
struct Composite<'a> {
    s: &'a CadSurface,
    w: &'a HermiteSurface,
}

impl Surface for Composite<'_> {
    fn eval(&self, xi: f64, eta: f64) -> SurfacePoint {
        let w = self.w.eval(xi, eta);
        let s = self.s.eval(w.x.x, w.x.y);
        let (ua, va, ub, vb) = (w.xu.x, w.xu.y, w.xv.x, w.xv.y);
        SurfacePoint {
            x: s.x,
            xu: s.xu * ua + s.xv * va,
            xv: s.xu * ub + s.xv * vb,
            xuu: s.xuu * (ua * ua)
                + s.xuv * (2.0 * ua * va)
                + s.xvv * (va * va)
                + s.xu * w.xuu.x
                + s.xv * w.xuu.y,
            xuv: s.xuu * (ua * ub)
                + s.xuv * (ua * vb + ub * va)
                + s.xvv * (va * vb)
                + s.xu * w.xuv.x
                + s.xv * w.xuv.y,
            xvv: s.xuu * (ub * ub)
                + s.xuv * (2.0 * ub * vb)
                + s.xvv * (vb * vb)
                + s.xu * w.xvv.x
                + s.xv * w.xvv.y,
        }
    }

    fn point(&self, xi: f64, eta: f64) -> Vec3 {
        let w = self.w.point(xi, eta);
        self.s.point(w.x, w.y)
    }

    fn breaks(&self) -> (Vec<f64>, Vec<f64>) {
        self.w.breaks()
    }
}
