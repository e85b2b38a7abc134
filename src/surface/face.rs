//! A four-sided face on a parametrized surface whose sides are any curves on it (not only the
//! sides of the parameter square): a block face on a CAD surface, or a face of a volume
//! topology on a named surface (METHOD.md §5 on top of §2).
//!
//! 1. the (u, v) of the boundary nodes (given, or by closest-point projection);
//! 2. if they lie on the sides of the parameter square in order, the Section 4 pipeline
//!    directly; otherwise the face's parametrization from the unit square: a Section 2 grid
//!    in the surface's (u, v) plane (scaled by the mean |x_u|, |x_v| so that it is close to
//!    isometric) bounded by the four sides, with zero control functions (Winslow: one-to-one
//!    for any simply connected domain), interpolated by bicubic Hermite patches w(ξ, η);
//! 3. the Section 4 pipeline on the composite surface x(w(ξ, η)): the final grid lies on the
//!    surface exactly and its boundary nodes are the given ones.
//!
//! The result depends neither on the surface's parametrization nor on the (u, v) grid, up to
//! the discretization error (tests: `tests/step_faces.rs`, `tests/volume_topology.rs`).

use crate::algebraic::ControlKind;
use crate::elliptic::domain::grid_block;
use crate::elliptic::picard::{PicardInfo, PicardParams};
use crate::grid::boundary::Boundary2;
use crate::grid::{Edge, Grid2};
use crate::solve::LinearSolver;
use crate::surface::pipeline::{grid_surface_orthogonal, SurfaceResult};
use crate::surface::untangle::{folded_cells, untangle};
use crate::{Error, Result};
use ellipgrid_geometry::{HermiteSurface, Surface, SurfaceLocator, SurfacePoint, Vec3};

/// A face on a surface: the grid (with its initial grid and the surface (u, v) of every
/// node) and the Section 2 solve of its (u, v) parametrization, if one was needed.
#[derive(Clone, Debug)]
pub struct FaceResult {
    pub result: SurfaceResult,
    pub uv_picard: Option<PicardInfo>,
}

/// Boundary nodes farther than this (relative to the face's size) from the surface are an
/// error: the edge does not lie on the surface.
pub const ON_SURFACE: f64 = 1e-6;

/// The (u, v) of boundary nodes (E1..E4, a 2D block's sides in index order) by closest-point
/// projection onto a surface over the unit square; nodes off the surface by more than
/// [`ON_SURFACE`] of the face's size are errors naming the side and node.
pub fn project_boundary(
    surface: &dyn Surface,
    points: &[Vec<Vec3>; 4],
    place: &str,
) -> Result<[Vec<[f64; 2]>; 4]> {
    let loc = SurfaceLocator::new(surface, 64, 64).map_err(|source| Error::Geometry {
        place: place.to_string(),
        source,
    })?;
    let size = diameter(points.iter().flatten());
    let tol = ON_SURFACE * size;
    let mut out: [Vec<[f64; 2]>; 4] = Default::default();
    for e in Edge::ALL {
        for (k, &p) in points[e.index()].iter().enumerate() {
            let (u, v) = loc.closest(p);
            let d = (surface.point(u, v) - p).norm();
            if d.is_nan() || d > tol {
                return Err(Error::input(
                    format!("{place}, side {e}"),
                    format!(
                        "node {k} {:?} is {d:.3e} from the surface (tolerance {tol:.1e}); the \
                         face's edges must lie on its surface",
                        [p.x, p.y, p.z]
                    ),
                ));
            }
            out[e.index()].push([u, v]);
        }
    }
    Ok(out)
}

fn diameter<'a>(p: impl Iterator<Item = &'a Vec3>) -> f64 {
    let mut lo = Vec3::repeat(f64::INFINITY);
    let mut hi = Vec3::repeat(f64::NEG_INFINITY);
    for q in p {
        lo = lo.inf(q);
        hi = hi.sup(q);
    }
    (hi - lo).norm()
}

/// The boundary (u, v) snapped onto the sides of the unit square if they lie there (within
/// 1e-9) in the order of the pipeline's edges (E1 on u = 0, E2 on u = 1, E3 on v = 0, E4 on
/// v = 1, each running from 0 to 1): then the face is the surface's own parameter square.
fn on_square_sides(uv: &[Vec<[f64; 2]>; 4]) -> Option<[Vec<[f64; 2]>; 4]> {
    const TOL: f64 = 1e-9;
    let mut out = uv.clone();
    for e in Edge::ALL {
        let (fixed, val, run) = match e {
            Edge::E1 => (0, 0.0, 1),
            Edge::E2 => (0, 1.0, 1),
            Edge::E3 => (1, 0.0, 0),
            Edge::E4 => (1, 1.0, 0),
        };
        let pts = &mut out[e.index()];
        let n = pts.len();
        for (k, p) in pts.iter_mut().enumerate() {
            if (p[fixed] - val).abs() > TOL {
                return None;
            }
            p[fixed] = val;
            if k == 0 || k == n - 1 {
                let end = if k == 0 { 0.0 } else { 1.0 };
                if (p[run] - end).abs() > TOL {
                    return None;
                }
                p[run] = end;
            }
        }
        if !pts.windows(2).all(|w| w[1][run] > w[0][run]) {
            return None;
        }
    }
    Some(out)
}

/// Mean |x_u|, |x_v| at the boundary nodes: the scales that make the (u, v) plane close to
/// isometric for the Section 2 grid of the parametrization.
fn metric_scale(surface: &dyn Surface, uv: &[Vec<[f64; 2]>; 4]) -> [f64; 2] {
    let (mut su, mut sv, mut n) = (0.0, 0.0, 0.0);
    for p in uv.iter().flatten() {
        let q = surface.eval(p[0], p[1]);
        su += q.xu.norm();
        sv += q.xv.norm();
        n += 1.0;
    }
    let s = [su / n, sv / n];
    if s.iter().all(|v| v.is_finite() && *v > 0.0) {
        s
    } else {
        [1.0, 1.0]
    }
}

/// Grids a face on `surface` from its boundary nodes `points` (E1..E4 in index order, corners
/// shared) with their surface parameters `uv`: the Section 4 pipeline directly when the
/// (u, v) are the parameter square's sides, else on the composite of the surface and a
/// Winslow parametrization of the face (module docs). Orthogonality at the chosen sides as in
/// [`grid_surface_orthogonal`]. The boundary nodes of the result are `points` exactly.
///
/// # Errors
/// [`Error::Folded`] if the (u, v) parametrization folds; those of the pipeline.
pub fn grid_face_on(
    surface: &dyn Surface,
    points: &[Vec<Vec3>; 4],
    uv: &[Vec<[f64; 2]>; 4],
    orthogonal: [bool; 4],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<FaceResult> {
    match on_square_sides(uv) {
        Some(sq) => {
            let mut result = grid_surface_orthogonal(surface, &sq, orthogonal, solver, place)?;
            set_boundary(&mut result, points, uv);
            Ok(FaceResult {
                result,
                uv_picard: None,
            })
        }
        None => {
            let scale = metric_scale(surface, uv);
            grid_face_composite(surface, points, uv, scale, orthogonal, solver, place)
        }
    }
}

/// [`grid_face_on`] always through the face's own parametrization (steps 2–3 of the module
/// docs), its (u, v) plane scaled by `scale`.
pub fn grid_face_composite(
    surface: &dyn Surface,
    points: &[Vec<Vec3>; 4],
    uv: &[Vec<[f64; 2]>; 4],
    scale: [f64; 2],
    orthogonal: [bool; 4],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<FaceResult> {
    grid_face_composite_refined(
        surface,
        points,
        uv,
        (uv, 1),
        scale,
        orthogonal,
        solver,
        place,
    )
}

/// [`grid_face_composite`] with the face's (u, v) parametrization made on a grid `refine`
/// times finer than the final one: `fine` holds the sides at `refine` (nᵢ − 1) + 1 and
/// `refine` (nⱼ − 1) + 1 nodes, node k of `uv` being node `refine` k of `fine`. A finer (u, v)
/// grid resolves sharp reentrant corners of a trim where the discrete Winslow grid at the
/// final resolution folds; the final grid still depends on it only by the discretization error.
///
/// # Errors
/// [`Error::Input`] if `fine` does not hold `uv` at every `refine`-th node; those of
/// [`grid_face_composite`].
#[allow(clippy::too_many_arguments)]
pub fn grid_face_composite_refined(
    surface: &dyn Surface,
    points: &[Vec<Vec3>; 4],
    uv: &[Vec<[f64; 2]>; 4],
    (fine, refine): (&[Vec<[f64; 2]>; 4], usize),
    scale: [f64; 2],
    orthogonal: [bool; 4],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<FaceResult> {
    let (ni, nj) = (points[2].len(), points[0].len());
    let nested = refine >= 1
        && Edge::ALL.into_iter().all(|e| {
            let (c, f) = (&uv[e.index()], &fine[e.index()]);
            !c.is_empty()
                && f.len() == refine * (c.len() - 1) + 1
                && c.iter().enumerate().all(|(k, q)| f[refine * k] == *q)
        });
    if !nested {
        return Err(Error::input(
            place,
            format!("the fine (u, v) sides do not hold the final ones at every {refine}-th node"),
        ));
    }
    let (w, picard) = parametrization(fine, scale, solver, place)?;
    let composite = Composite { s: surface, w: &w };
    let side = |n: usize| (0..n).map(move |k| k as f64 / (n - 1) as f64);
    let xi: [Vec<[f64; 2]>; 4] = [
        side(nj).map(|t| [0.0, t]).collect(),
        side(nj).map(|t| [1.0, t]).collect(),
        side(ni).map(|t| [t, 0.0]).collect(),
        side(ni).map(|t| [t, 1.0]).collect(),
    ];
    let mut result = grid_surface_orthogonal(&composite, &xi, orthogonal, solver, place)?;
    for q in result.uv.iter_mut() {
        let p = w.point(q[0], q[1]);
        *q = [p.x, p.y];
    }
    set_boundary(&mut result, points, uv);
    untangle_on(surface, &mut result, scale);
    Ok(FaceResult {
        result,
        uv_picard: Some(picard),
    })
}

/// The final grid's nodes untangled in the surface's (u, v) plane scaled by `scale` where
/// that grid folds (next to a reentrant vertex of the trim the discrete Laplace–Beltrami
/// map and the straight-line target grid can fold as the discrete Winslow grid does); moved
/// nodes are put back on the surface. Boundary nodes never move; a grid that does not fold in
/// (u, v) is not changed.
fn untangle_on(surface: &dyn Surface, r: &mut SurfaceResult, scale: [f64; 2]) {
    let (ni, nj) = (r.grid.ni(), r.grid.nj());
    // the boundary's turning sense in (u, v): the untangling wants counterclockwise cells
    let ring: Vec<usize> = (0..ni - 1)
        .chain((0..nj - 1).map(|j| ni - 1 + ni * j))
        .chain((1..ni).rev().map(|i| i + ni * (nj - 1)))
        .chain((1..nj).rev().map(|j| ni * j))
        .collect();
    let area: f64 = (0..ring.len())
        .map(|k| {
            let (a, b) = (r.uv[ring[k]], r.uv[ring[(k + 1) % ring.len()]]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum();
    let flip = if area < 0.0 { -1.0 } else { 1.0 };
    let at = |n: usize| [r.uv[n][0] * scale[0], flip * r.uv[n][1] * scale[1]];
    let mut g = Grid2::<2>::from_fn(ni, nj, |i, j| at(i + ni * j));
    if folded_cells(&g, FLAT).is_empty() {
        return;
    }
    let before = g.clone();
    untangle(&mut g, FLAT, UNTANGLE_SWEEPS);
    for n in 0..ni * nj {
        let (x, y) = (g.coord(0)[n], g.coord(1)[n]);
        if x != before.coord(0)[n] || y != before.coord(1)[n] {
            let w = [x / scale[0], flip * y / scale[1]];
            let x = surface.point(w[0], w[1]);
            for c in 0..3 {
                r.grid.coords_mut()[c][n] = x[c];
            }
            r.uv[n] = w;
        }
    }
}

/// Boundary nodes exactly at the given points and parameters.
fn set_boundary(r: &mut SurfaceResult, points: &[Vec<Vec3>; 4], uv: &[Vec<[f64; 2]>; 4]) {
    let (ni, nj) = (r.grid.ni(), r.grid.nj());
    for e in Edge::ALL {
        for (k, (p, q)) in points[e.index()].iter().zip(&uv[e.index()]).enumerate() {
            let n = match e {
                Edge::E1 => ni * k,
                Edge::E2 => ni - 1 + ni * k,
                Edge::E3 => k,
                Edge::E4 => k + ni * (nj - 1),
            };
            for c in 0..3 {
                r.grid.coords_mut()[c][n] = p[c];
                r.initial.coords_mut()[c][n] = p[c];
            }
            r.uv[n] = *q;
        }
    }
}

/// Step 2: the face's parametrization w(ξ, η) from the unit square onto its (u, v) region:
/// the Section 2 (Winslow) grid in the (u, v) plane scaled by `scale`, bounded by the sides
/// `uv`, as bicubic Hermite patches.
pub fn parametrization(
    uv: &[Vec<[f64; 2]>; 4],
    scale: [f64; 2],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<(HermiteSurface, PicardInfo)> {
    let (ni, nj) = (uv[2].len(), uv[0].len());
    let scaled = uv.clone().map(|e| {
        e.iter()
            .map(|p| [p[0] * scale[0], p[1] * scale[1]])
            .collect()
    });
    // A side may be one point in (u, v) (a CAD face's cusp gridded as a collapsed side): the
    // cells along it are triangles.
    let b = Boundary2::with_poles(scaled, &format!("{place}, (u, v) grid"))?;
    let params = PicardParams::default();
    let mut uvg = grid_block::<2>(&b, None, ControlKind::Laplace, solver, &params, place)?;
    // The discrete Winslow grid may fold next to a reentrant stretch of the trim, where the
    // continuous map is one-to-one: its nodes there are untangled (module `untangle`).
    untangle(&mut uvg.grid, FLAT, UNTANGLE_SWEEPS);
    check_unfolded(&uvg.grid, place)?;
    let net: Vec<Vec3> = (0..ni * nj)
        .map(|p| {
            Vec3::new(
                uvg.grid.coord(0)[p] / scale[0],
                uvg.grid.coord(1)[p] / scale[1],
                0.0,
            )
        })
        .collect();
    let w = HermiteSurface::new(ni, nj, net).map_err(|source| Error::Geometry {
        place: place.to_string(),
        source,
    })?;
    Ok((w, uvg.picard))
}

/// A corner of a (u, v) cell turning clockwise by less than this (|sin|) is flat, not folded:
/// a corner angle of 180° (a face corner placed inside an edge) to rounding.
const FLAT: f64 = 1e-9;

/// Sweeps of [`untangle`] over a folded (u, v) grid at most.
const UNTANGLE_SWEEPS: usize = 100;

/// The (u, v) grid must not fold: every cell's corners turn counterclockwise. A corner
/// angle of 180° (a face corner placed inside an edge) is degenerate, not folded: rounding
/// may make it turn clockwise by a hair (|sin| below [`FLAT`]).
fn check_unfolded(g: &Grid2<2>, place: &str) -> Result<()> {
    let bad = folded_cells(g, FLAT);
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

/// x(w(ξ, η)): a surface over a face's parametrization from the unit square.
pub struct Composite<'a> {
    pub s: &'a dyn Surface,
    pub w: &'a HermiteSurface,
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
