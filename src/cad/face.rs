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

use super::trim::{CadSurface, FaceLoop, LoopPoint, CORNER_LIKE, CUSP, TIP};
use super::{quietly, Route, StepFace};
use crate::case::DistributionSpec;
use crate::elliptic::picard::PicardInfo;
use crate::grid::Edge;
use crate::quality::{self, QualityReport};
use crate::solve::LinearSolver;
use crate::surface::face::grid_face_composite_refined;
use crate::surface::pipeline::SurfaceResult;
use crate::{Error, Result};
use ellipgrid_geometry::{TruckSurface, Vec3};
use truck_stepio::r#in::alias::Surface as StepSurface;

/// A boundary point farther than this from the face's surface (relative to the loop's size)
/// is an error: the edge is not on the face.
pub const GAP_TOL: f64 = 1e-3;

/// ... unless it is within this many times the file's distance uncertainty
/// ([`StepFace::uncertainty`]): CAD kernels keep edges within a small multiple of their
/// resolution of the faces (tolerant edges); CATIA's ventilator has edges 1.1–1.4e-2 off
/// their faces at an uncertainty of 5e-3.
pub const UNCERTAINTY_FACTOR: f64 = 3.0;

/// The (relative, absolute) gap tolerances of a face's boundary, and the relative limit of
/// what is healed beyond them ([`StepFace::heal`]).
pub(super) fn gap_tolerance(face: &StepFace) -> (f64, f64, f64) {
    (GAP_TOL, UNCERTAINTY_FACTOR * face.uncertainty, face.heal)
}

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
    /// Largest defect of the file's boundary healed beyond its tolerance (edges whose ends
    /// miss each other, points off the surface; [`StepFace::heal`]), 0 if none.
    pub healed: f64,
    /// The Section 2 solve of the (u, v) grid (none for an untrimmed patch).
    pub uv_picard: Option<PicardInfo>,
    /// The quality report of `result.grid` ([`quality::quality_surface`]), computed once
    /// here: the retry test of [`grid_face`] and the callers' reports share it.
    pub quality: QualityReport,
    /// The lines an untrimmed patch was cut along ([`super::grid_creased`]; every block of
    /// the face has them); empty for a face gridded whole.
    pub patch_cuts: Vec<super::Crease>,
}

impl FaceGrid {
    /// A gridded face and its quality report.
    pub(super) fn new(
        result: SurfaceResult,
        corner_angles: Vec<f64>,
        (gap, healed): (f64, f64),
        uv_picard: Option<PicardInfo>,
    ) -> Self {
        let quality = quality::quality_surface(&result.grid);
        FaceGrid {
            result,
            corner_angles,
            gap,
            healed,
            uv_picard,
            quality,
            patch_cuts: Vec::new(),
        }
    }
}

/// The grid of a face: `ni` nodes along its first and third sides, `nj` along the second and
/// fourth, placed on each by `dist_i` / `dist_j` (lengths).
///
/// A one-loop face is gridded on corners by turning angle ([`Corners::Turning`]); where every
/// such try folds, on corner sets with balanced opposite sides ([`Corners::Balanced`]), then
/// with its cusp as a collapsed side ([`Corners::Collapsed`]), last with its tips collapsed
/// ([`Corners::Tips`]): the first of those that does
/// not fold is the grid, else the first rule's result stands (a face that does not fold on
/// its first corners is never regridded).
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
    let one = grid_face_by(
        face,
        (ni, nj),
        dist_i,
        dist_j,
        solver,
        place,
        Corners::Turning,
    );
    if !folds(&one) || !matches!(face.route(), Route::Trimmed(_)) {
        return one;
    }
    for sets in [Corners::Balanced, Corners::Collapsed, Corners::Tips] {
        let other = grid_face_by(face, (ni, nj), dist_i, dist_j, solver, place, sets);
        if !folds(&other) && other.is_ok() {
            return other;
        }
    }
    one
}

/// Whether a face's grid folds: a folded grid, or a (u, v) grid that folds.
pub(super) fn folds(r: &Result<FaceGrid>) -> bool {
    match r {
        Ok(g) => g.quality.is_folded(),
        Err(e) => matches!(e, Error::Folded { .. }),
    }
}

/// Which corner sets [`grid_face_by`] tries on a one-loop face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Corners {
    /// Corners by turning angle (the loop's most-turning vertices, with the tries of the
    /// corner rules): the first choice of every face.
    Turning,
    /// Corner sets with balanced opposite sides and corner angles near 90°
    /// (`FaceLoop::balanced_corners`): the [`BALANCED`] cheapest that are no try of
    /// [`Corners::Turning`], for faces whose grid folds with those.
    Balanced,
    /// Three corners, the first a cusp (or the sharpest of exactly three corner-like
    /// vertices) gridded as the side E1 collapsed to that point, in (u, v) and in 3D
    /// (`FaceLoop::collapsed_at`; with a second cusp, that one as E2 in the first of the
    /// [`COLLAPSED`] sets): for faces whose grid folds with the corner sets above.
    Collapsed,
    /// As [`Corners::Collapsed`] on the sharpest convex vertex turning by more than 135° (an
    /// interior angle below 45°: a *tip*), a second such tip collapsed as E2 first, the sets
    /// of [`Corners::Collapsed`] left out: the last try, for faces whose every other corner
    /// set folds (bands pointed at both ends by 36° tips).
    Tips,
}

/// Corner sets a face whose grid folds with its corners by turning angle tries at most
/// ([`Corners::Balanced`]).
pub const BALANCED: usize = 3;

/// Corner sets with a collapsed cusp a face tries at most ([`Corners::Collapsed`]): the
/// cusp's neighbours by turning angle, then those with balanced sides along the cusp.
pub const COLLAPSED: usize = 3;

/// [`grid_face`] with the corner sets `corners` only (an untrimmed patch is gridded the same
/// either way).
///
/// # Errors
/// Those of [`grid_face`].
pub fn grid_face_by(
    face: &StepFace,
    (ni, nj): (usize, usize),
    dist_i: &DistributionSpec,
    dist_j: &DistributionSpec,
    solver: &mut dyn LinearSolver,
    place: &str,
    corners: Corners,
) -> Result<FaceGrid> {
    if ni < 3 || nj < 3 {
        return Err(Error::input(
            place,
            format!("a surface grid needs at least 3 × 3 nodes, got {ni} × {nj}"),
        ));
    }
    match face.route() {
        Route::Refused(why) => Err(Error::input(place, why)),
        Route::Holes(n) => Err(Error::input(
            place,
            format!(
                "{n} hole(s): a face with holes is gridded as several blocks \
                 (grid_face_blocks)"
            ),
        )),
        Route::Patch => {
            let s = face
                .surface
                .as_ref()
                .expect("a patch has a B-spline surface");
            let result = super::grid_patch(s, (ni, nj), dist_i, dist_j, solver, place)?;
            Ok(FaceGrid::new(result, Vec::new(), (0.0, 0.0), None))
        }
        Route::Trimmed(_) => trimmed(face, (ni, nj), [dist_i, dist_j], solver, place, corners),
    }
}

/// The parameter box of a face's projection: truck's range for B-spline and NURBS
/// surfaces, unbounded for the others (their ranges in truck are those of the generating
/// curve segment, not of the surface).
pub(super) fn bounds(s: &CadSurface) -> [[f64; 2]; 2] {
    match s.inner() {
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
    sets: Corners,
) -> Result<FaceGrid> {
    let surface = TruckSurface::new(face.cad_surface.clone());
    let edges = match &face.loops {
        Ok(l) => &l[0],
        Err(e) => return Err(Error::input(place, e.clone())),
    };
    // Corners by the plain rule and the (u, v) parametrization on the final grid's resolution
    // first; where its discrete Winslow grid folds or the final grid folds, again with corners
    // only at convex vertices (never reentrant ones), then also on a (u, v) grid 2 times
    // finer, then with corners only at vertices turning by more than 20° (points inside edges
    // otherwise). Faces that grid at once are not changed. (A 4 times finer try as well made
    // the corpus's slowest files several times slower.)
    // A refined try that fails otherwise reports the first try's fold; a folded grid is
    // preferred to a folded (u, v) grid (it can still be written with --allow-folded).
    // The loop on the surface is projected once; each try works on a fresh copy of it. A try
    // whose corners and refinement are an earlier try's would repeat it exactly (that try
    // folded, or there would be no retry): it is left out (on the 40-file corpus the last
    // try's corners were the second's in every face that got there).
    // With `sets` = Balanced the tries are instead the balanced corner sets (on the final
    // grid's resolution), those equal to a try by turning left out.
    let lp = quietly(|| {
        FaceLoop::new(
            &surface,
            edges,
            bounds(&surface),
            gap_tolerance(face),
            false,
        )
        .map_err(|m| Error::input(place, m))
    })
    .unwrap_or_else(|_| Err(truck_failed(place)))?;
    // Other corner sets ([`Corners::Balanced`]): the balanced sets that are no try by
    // turning.
    let mut lp = lp;
    let others: Vec<([LoopPoint; 4], [f64; 4])> = match sets {
        Corners::Turning => Vec::new(),
        // the cusp as side E1 (with a second cusp as E2 first), the other corners by turning
        // (by more than 20°), then balancing the sides along the cusp
        Corners::Collapsed => {
            lp.cusp = lp.collapsed_at();
            let Some(k) = lp.cusp else {
                return Err(Error::input(place, "no cusp to grid as a collapsed side"));
            };
            quietly(|| collapsed_sets(&lp, k, CUSP)).map_err(|_| truck_failed(place))?
        }
        // the sharpest tip as side E1 (with a second tip as E2 first), the sets of
        // Corners::Collapsed left out
        Corners::Tips => {
            let Some(k) = lp.sharpest_tip(TIP) else {
                return Err(Error::input(place, "no tip to grid as a collapsed side"));
            };
            quietly(|| {
                let mut tried = lp.clone();
                tried.cusp = tried.collapsed_at();
                let tried = tried
                    .cusp
                    .map_or(Vec::new(), |c| collapsed_sets(&tried, c, CUSP));
                lp.cusp = Some(k);
                let mut sets = collapsed_sets(&lp, k, TIP);
                sets.retain(|s| !tried.iter().any(|t| t.0 == s.0));
                sets
            })
            .map_err(|_| truck_failed(place))?
        }
        Corners::Balanced => quietly(|| {
            let tried = TRIES.map(|(m, _)| lp.corners(m).0);
            let mut b = lp.balanced_corners(BALANCED + TRIES.len());
            b.retain(|c| !tried.contains(&c.0));
            b.truncate(BALANCED);
            b
        })
        .map_err(|_| truck_failed(place))?,
    };
    let count = match sets {
        Corners::Turning => TRIES.len(),
        Corners::Balanced | Corners::Collapsed | Corners::Tips => others.len(),
    };
    if count == 0 {
        return Err(Error::input(place, "no other corner set on the loop"));
    }
    let mut done: Vec<([LoopPoint; 4], usize)> = Vec::with_capacity(count);
    let mut best: Option<Result<FaceGrid>> = None;
    for t in 0..count {
        let (corners, refine) = match sets {
            Corners::Turning => (
                quietly(|| lp.corners(TRIES[t].0)).map_err(|_| truck_failed(place))?,
                TRIES[t].1,
            ),
            Corners::Balanced | Corners::Collapsed | Corners::Tips => (others[t], 1),
        };
        if done.contains(&(corners.0, refine)) {
            continue;
        }
        done.push((corners.0, refine));
        let r = attempt(
            face,
            &surface,
            lp.clone(),
            corners,
            (ni, nj),
            dist,
            refine,
            solver,
            place,
        );
        let retry = match &r {
            Err(Error::Folded { place: p, .. }) => p.ends_with("(u, v) grid"),
            Err(_) => false,
            Ok(g) => g.quality.is_folded(),
        };
        match best {
            None if !retry => return r,
            None => best = Some(r),
            Some(_) if !retry => return if r.is_ok() { r } else { best.unwrap() },
            Some(Err(_)) if r.is_ok() => best = Some(r),
            Some(_) => {}
        }
    }
    best.expect("at least one try")
}

/// The corner sets with the vertex `k` collapsed (side E1; `lp.cusp` is `k`), at most
/// [`COLLAPSED`]: with a second vertex turning by more than `limit` collapsed as well (E2)
/// first, then the other corners by turning (by more than 20°), then those balancing the
/// sides along `k`.
fn collapsed_sets(lp: &FaceLoop, k: usize, limit: f64) -> Vec<([LoopPoint; 4], [f64; 4])> {
    let mut sets: Vec<_> = lp.two_cusps(k, limit).into_iter().collect();
    sets.push(lp.corners(Some(CORNER_LIKE)));
    for c in lp.collapsed_corners(k, COLLAPSED) {
        if sets.len() < COLLAPSED && !sets.iter().any(|s| s.0 == c.0) {
            sets.push(c);
        }
    }
    sets
}

/// The tries of [`trimmed`] in turn: (least turning of a convex vertex to be a corner
/// (radians), or `None` for the plain rule of [`FaceLoop::corners`]; refinement of the (u, v)
/// grid).
const TRIES: [(Option<f64>, usize); 4] =
    [(None, 1), (Some(1e-3), 1), (Some(1e-3), 2), (Some(0.35), 1)];

/// The error of a panic in truck while the boundary is sampled.
fn truck_failed(place: &str) -> Error {
    Error::input(
        place,
        "truck failed to evaluate a boundary edge or the surface",
    )
}

/// One try of [`trimmed`] on the loop `lp` (not yet sampled) with the corners `corners`
/// ([`FaceLoop::corners`]) and the (u, v) grid `refine` times finer than the final grid.
#[allow(clippy::too_many_arguments)]
fn attempt(
    face: &StepFace,
    surface: &CadSurface,
    lp: FaceLoop,
    corners: ([LoopPoint; 4], [f64; 4]),
    (ni, nj): (usize, usize),
    dist: [&DistributionSpec; 2],
    refine: usize,
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<FaceGrid> {
    let b = quietly(|| boundary(lp, corners, face.orientation, (ni, nj), dist, refine, place))
        .unwrap_or_else(|_| Err(truck_failed(place)))?;
    // Steps 2–3: the face's Winslow parametrization and Section 4 on the composite surface;
    // the final grid lies on the CAD surface exactly, boundary nodes on the CAD edges.
    let coarse =
        |a: &[Vec<[f64; 2]>; 4]| a.clone().map(|e| e.into_iter().step_by(refine).collect());
    let uv: [Vec<[f64; 2]>; 4] = coarse(&b.uv);
    let points: [Vec<Vec3>; 4] = b
        .points
        .clone()
        .map(|e| e.into_iter().step_by(refine).collect());
    let r = quietly(|| {
        grid_face_composite_refined(
            surface,
            &points,
            &uv,
            (&b.uv, refine),
            b.scale,
            [false; 4],
            solver,
            place,
        )
    })
    .unwrap_or_else(|_| {
        Err(Error::input(
            place,
            "truck failed to evaluate the surface inside the face",
        ))
    })?;
    Ok(FaceGrid::new(
        r.result,
        b.angles.to_vec(),
        (b.gap, b.healed),
        r.uv_picard,
    ))
}

/// The four block edges E1..E4 of a face: 3D points on the CAD edges, their (u, v), and
/// (u, v) scaled by `scale`.
struct FaceBoundary {
    points: [Vec<Vec3>; 4],
    uv: [Vec<[f64; 2]>; 4],
    scale: [f64; 2],
    angles: [f64; 4],
    gap: f64,
    healed: f64,
}

/// Step 1: the loop, its corners q0..q3 in the order that makes the grid's normal the face's
/// (counterclockwise in (u, v) when the face's normal is the surface's), and the boundary
/// nodes: E3 = q0 → q1 and E4 = q3 → q2 with `ni` nodes by `dist[0]`, E1 = q0 → q3 and
/// E2 = q1 → q2 with `nj` nodes by `dist[1]`; each gap between them split into `refine`
/// equal arclengths (the nodes are every `refine`-th point).
fn boundary(
    mut lp: FaceLoop,
    (c, angles): ([LoopPoint; 4], [f64; 4]),
    orientation: bool,
    (ni, nj): (usize, usize),
    dist: [&DistributionSpec; 2],
    refine: usize,
    place: &str,
) -> Result<FaceBoundary> {
    let scale = lp.metric_scale();
    let forward = (lp.signed_area(scale) > 0.0) == orientation;
    // A pole or a cusp (corners c[0] = c[3]) is the side E1 either way round.
    let collapsed = lp.pole.is_some() || lp.cusp.is_some();
    let back = if collapsed {
        [0, 2, 1, 3]
    } else {
        [0, 3, 2, 1]
    };
    let (q, angles) = if forward {
        (c, angles)
    } else {
        (back.map(|k| c[k]), back.map(|k| angles[k]))
    };
    // A second cusp (corners c[1] = c[2]) is the side E2.
    let collapsed2 = lp.cusp.is_some() && q[1] == q[2];
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
        if (e == Edge::E1 && collapsed) || (e == Edge::E2 && collapsed2) {
            continue;
        }
        let at = format!("{place}, edge {e}");
        let coarse = d.sample(n, length(&lp, a, b), &at)?;
        let mut sigma: Vec<f64> = coarse
            .windows(2)
            .flat_map(|w| (0..refine).map(move |m| w[0] + (w[1] - w[0]) * m as f64 / refine as f64))
            .collect();
        sigma.extend(coarse.last());
        let f: Vec<f64> = if reversed {
            sigma.iter().map(|s| 1.0 - s).collect()
        } else {
            sigma
        };
        let (x, w) = path(&mut lp, a, b, &f).map_err(|m| Error::input(&at, m))?;
        points[e.index()] = x;
        uv[e.index()] = w;
    }
    if lp.pole.is_some() {
        pole_side(&mut points, &mut uv, lp.tol(), place)?;
    } else if lp.cusp.is_some() {
        let n = refine * (nj - 1) + 1;
        cusp_side(&mut points, &mut uv, (Edge::E1, n), scale, lp.tol(), place)?;
        if collapsed2 {
            cusp_side(&mut points, &mut uv, (Edge::E2, n), scale, lp.tol(), place)?;
        }
    }
    // Each corner ends two block edges, sampled on two CAD edges that meet there only to the
    // file's tolerance: one point and one (u, v) for both (their mean).
    let last = |e: Edge| match e {
        Edge::E1 | Edge::E2 => refine * (nj - 1),
        Edge::E3 | Edge::E4 => refine * (ni - 1),
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
    if collapsed {
        // the pole's corners stay the pole: one point
        let p = points[Edge::E1.index()][1];
        points[Edge::E1.index()][0] = p;
        points[Edge::E3.index()][0] = p;
        points[Edge::E4.index()][0] = p;
    }
    Ok(FaceBoundary {
        points,
        uv,
        scale,
        angles,
        gap: lp.gap,
        healed: lp.healed,
    })
}

/// The side `e` (E1, or E2 for a second cusp) of `n` nodes of a face gridded with its cusp
/// collapsed ([`Corners::Collapsed`]), given E3 and E4: every node the cusp in 3D and in
/// (u, v) (the means of the ends of E3 and E4 there, which must meet).
fn cusp_side(
    points: &mut [Vec<Vec3>; 4],
    uv: &mut [Vec<[f64; 2]>; 4],
    (e, n): (Edge, usize),
    scale: [f64; 2],
    tol: f64,
    place: &str,
) -> Result<()> {
    let (e3, e4) = (Edge::E3.index(), Edge::E4.index());
    let k = if e == Edge::E1 {
        0
    } else {
        points[e3].len() - 1
    };
    let (a, b) = (uv[e3][k], uv[e4][k]);
    let miss = (points[e3][k] - points[e4][k]).norm();
    let uv_miss = (0..2)
        .map(|c| ((a[c] - b[c]) * scale[c]).abs())
        .fold(0.0, f64::max);
    if miss > tol || uv_miss > 10.0 * tol.max(miss) {
        return Err(Error::input(
            place,
            format!(
                "the block edges E3 and E4 do not meet at the cusp ({miss:.3e} apart in space, \
                 {uv_miss:.3e} in the surface's parameters)"
            ),
        ));
    }
    let p = 0.5 * (points[e3][k] + points[e4][k]);
    let w = [0, 1].map(|c| 0.5 * (a[c] + b[c]));
    points[e.index()] = vec![p; n];
    uv[e.index()] = vec![w; n];
    (points[e3][k], points[e4][k]) = (p, p);
    (uv[e3][k], uv[e4][k]) = (w, w);
    Ok(())
}

/// The side E1 of a face whose loop runs through a pole, given E2..E4: every node the pole
/// (the mean of the ends of E3 and E4 there, which must meet), its (u, v) along the straight
/// segment from E3's first (u, v) to E4's first at the fractions of E2's arclength at its
/// nodes, as a collapsed side of a patch takes its opposite side's parameters
/// ([`super::grid_patch`]): the grid lines leave the pole towards E2's nodes.
fn pole_side(
    points: &mut [Vec<Vec3>; 4],
    uv: &mut [Vec<[f64; 2]>; 4],
    tol: f64,
    place: &str,
) -> Result<()> {
    let (e2, e3, e4) = (Edge::E2.index(), Edge::E3.index(), Edge::E4.index());
    let miss = (points[e3][0] - points[e4][0]).norm();
    if miss > tol {
        return Err(Error::input(
            place,
            format!("the block edges E3 and E4 do not meet at the pole ({miss:.3e} apart)"),
        ));
    }
    let p = 0.5 * (points[e3][0] + points[e4][0]);
    let mut s = vec![0.0];
    for w in points[e2].windows(2) {
        s.push(s[s.len() - 1] + (w[1] - w[0]).norm());
    }
    let total = s[s.len() - 1];
    let (a, b) = (uv[e3][0], uv[e4][0]);
    let e1 = Edge::E1.index();
    points[e1] = vec![p; s.len()];
    uv[e1] = s
        .iter()
        .map(|t| {
            let f = if total > 0.0 { t / total } else { 0.0 };
            [0, 1].map(|c| a[c] + f * (b[c] - a[c]))
        })
        .collect();
    let last = s.len() - 1;
    (uv[e1][0], uv[e1][last]) = (a, b);
    Ok(())
}
