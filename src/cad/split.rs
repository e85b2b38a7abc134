//! A CAD face gridded as several blocks: a face with holes split by [`super::holes`] into an
//! O-type ring of four blocks around each hole, every block gridded as a block face
//! (METHOD.md §2 in (u, v), then §5 on the composite surface, as [`super::grid_face`]).
//!
//! Block sides on the face's loops are sampled on the CAD edges (3D arclength, as a one-loop
//! face's sides); cuts are straight lines in (u, v) mapped onto the surface, their nodes at
//! the requested 3D arclengths. Each cut is sampled once and shared by its two blocks, and
//! every block corner is one point computed once, so that neighbouring blocks meet bit for
//! bit. Nodes along a hole and along the outer loop's pieces (and the cuts between strips)
//! are the blocks' i direction (`ni`, `dist_i`); the cuts from a hole outwards are the j
//! direction (`nj`, `dist_j`, its first spacing at the hole).

use super::band::band;
use super::face::{bounds, gap_tolerance, FaceGrid};
use super::holes::{layout, Node, Side};
use super::trim::{CadSurface, FaceLoop};
use super::{quietly, Route, StepFace};
use crate::case::DistributionSpec;
use crate::grid::Edge;
use crate::solve::LinearSolver;
use crate::surface::face::grid_face_composite_refined;
use crate::{Error, Result};
use ellipgrid_geometry::{Surface, TruckSurface, Vec3};

/// Points and their (u, v) along a side.
type Sampled = (Vec<Vec3>, Vec<[f64; 2]>);

/// The grids of a face, one per block: one block for a face of one loop ([`super::grid_face`]),
/// four around each hole for a face with holes, in the order of the holes, each ring's blocks
/// one after the other around the hole; four across a closed band without a seam edge.
/// Blocks run counterclockwise in (u, v) when the face's normal is the surface's, so that
/// every block's normal is the face's.
///
/// # Errors
/// Those of [`super::grid_face`]; [`Error::Input`] at `place` with the reason if a face with
/// holes cannot be split: holes that no straight u or v cut separates, a cut crossing the
/// outer loop more than twice, a hole not star-shaped about its centroid, a band with holes.
pub fn grid_face_blocks(
    face: &StepFace,
    (ni, nj): (usize, usize),
    dist_i: &DistributionSpec,
    dist_j: &DistributionSpec,
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<Vec<FaceGrid>> {
    if !matches!(face.route(), Route::Holes(_)) {
        return super::grid_face(face, (ni, nj), dist_i, dist_j, solver, place).map(|g| vec![g]);
    }
    if ni < 3 || nj < 3 {
        return Err(Error::input(
            place,
            format!("a surface grid needs at least 3 × 3 nodes, got {ni} × {nj}"),
        ));
    }
    let surface = TruckSurface(face.cad_surface.clone());
    quietly(|| holes(face, &surface, (ni, nj), [dist_i, dist_j], solver, place)).unwrap_or_else(
        |_| {
            Err(Error::input(
                place,
                "truck failed to evaluate a boundary edge or the surface",
            ))
        },
    )
}

fn holes(
    face: &StepFace,
    surface: &CadSurface,
    (ni, nj): (usize, usize),
    dist: [&DistributionSpec; 2],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<Vec<FaceGrid>> {
    let err = |m: String| Error::input(place, m);
    let edges = face.loops.as_ref().map_err(|e| err(e.clone()))?;
    let mut loops = Vec::with_capacity(edges.len());
    for (l, e) in edges.iter().enumerate() {
        let lp = FaceLoop::new(surface, e, bounds(surface), gap_tolerance(face), true)
            .map_err(|m| err(format!("loop {}: {m}", l + 1)))?;
        loops.push(lp);
    }
    let scale = loops[0].metric_scale();
    let winds = loops.iter().filter(|l| l.winding.is_some()).count();
    let lay = if winds == 2 && loops.len() == 2 {
        band(&mut loops, scale).map_err(err)?
    } else if winds > 0 {
        return Err(err(
            "a boundary loop winds around the surface (a closed band without a seam edge, \
             or a cap around a pole) and the face has other loops: not split into blocks"
                .into(),
        ));
    } else {
        let scale = outer_first(&mut loops);
        let ccw: Vec<bool> = loops.iter().map(|lp| lp.signed_area(scale) > 0.0).collect();
        layout(&mut loops, &ccw, scale, face.orientation).map_err(err)?
    };
    let scale = loops[0].metric_scale();
    let periods = loops[0].periods;
    let gap = loops.iter().map(|lp| lp.gap).fold(0.0, f64::max);
    let node = |loops: &mut [FaceLoop], n: Node| -> Result<(Vec3, [f64; 2])> {
        let (x, w) = loops[n.l].sample(n.p, n.p, &[0.0]).map_err(err)?;
        Ok((x[0], w[0]))
    };
    let mut cuts = Vec::with_capacity(lay.cuts.len());
    for (c, cut) in lay.cuts.iter().enumerate() {
        let (n, d) = if cut.radial {
            (nj, dist[1])
        } else {
            (ni, dist[0])
        };
        let (a, mut b) = (node(&mut loops, cut.from)?, node(&mut loops, cut.to)?);
        b.1 = unwrap(b.1, a.1, periods);
        cuts.push(straight(
            surface,
            a,
            b,
            n,
            d,
            &format!("{place}, cut {}", c + 1),
        )?);
    }
    let mut out = Vec::with_capacity(lay.blocks.len());
    for (k, sides) in lay.blocks.iter().enumerate() {
        let at = format!("{place}, block {k}");
        let mut points: [Vec<Vec3>; 4] = Default::default();
        let mut uv: [Vec<[f64; 2]>; 4] = Default::default();
        for (e, side) in Edge::ALL.into_iter().zip(sides) {
            let (n, d) = match e {
                Edge::E1 | Edge::E2 => (nj, dist[1]),
                Edge::E3 | Edge::E4 => (ni, dist[0]),
            };
            let (x, w) = match *side {
                Side::Loop { l, a, b, forward } => {
                    let lp = &mut loops[l];
                    let len = if forward {
                        lp.chain_length(a, b)
                    } else {
                        lp.chain_length(b, a)
                    };
                    let sigma = d.sample(n, len, &format!("{at}, edge {e}"))?;
                    let r = if forward {
                        lp.sample(a, b, &sigma)
                    } else {
                        let g: Vec<f64> = sigma.iter().map(|s| 1.0 - s).collect();
                        lp.sample(b, a, &g)
                    };
                    let (x, w) = r.map_err(|m| Error::input(format!("{at}, edge {e}"), m))?;
                    let (p, q) = (
                        node(&mut loops, Node { l, p: a })?,
                        node(&mut loops, Node { l, p: b })?,
                    );
                    ends(x, w, p, q)
                }
                Side::Cut { c, rev } => {
                    let (mut x, mut w) = cuts[c].clone();
                    if rev {
                        x.reverse();
                        w.reverse();
                    }
                    (x, w)
                }
            };
            if x.len() != n || w.len() != n {
                return Err(Error::input(
                    &at,
                    format!("edge {e}: a shared cut has another number of nodes"),
                ));
            }
            points[e.index()] = x;
            uv[e.index()] = w;
        }
        orient(&mut points, &mut uv, periods, scale, face.orientation);
        let r = grid_face_composite_refined(
            surface,
            &points,
            &uv,
            (&uv, 1),
            scale,
            [false; 4],
            solver,
            &at,
        )?;
        out.push(FaceGrid::new(r.result, Vec::new(), gap, r.uv_picard));
    }
    Ok(out)
}

/// Moves the outer loop (largest (u, v) area) first and holes on periodic surfaces by whole
/// periods next to it; returns the outer loop's metric scale.
fn outer_first(loops: &mut Vec<FaceLoop>) -> [f64; 2] {
    let s0 = loops[0].metric_scale();
    let outer = (0..loops.len())
        .max_by(|a, b| {
            let area = |k: usize| loops[k].signed_area(s0).abs();
            area(*a).total_cmp(&area(*b)).then(b.cmp(a))
        })
        .unwrap_or(0);
    let first = loops.remove(outer);
    loops.insert(0, first);
    let mean = |lp: &FaceLoop| {
        let n = lp.edges.iter().map(|e| e.uv.len()).sum::<usize>().max(1) as f64;
        let s = lp
            .edges
            .iter()
            .flat_map(|e| &e.uv)
            .fold([0.0; 2], |s, q| [s[0] + q[0], s[1] + q[1]]);
        [s[0] / n, s[1] / n]
    };
    let m0 = mean(&loops[0]);
    for lp in loops.iter_mut().skip(1) {
        let m = mean(lp);
        for d in 0..2 {
            if let Some(t) = lp.periods[d].filter(|t| *t > 0.0) {
                let shift = t * ((m0[d] - m[d]) / t).round();
                lp.edges
                    .iter_mut()
                    .flat_map(|e| e.uv.iter_mut())
                    .for_each(|q| q[d] += shift);
            }
        }
    }
    loops[0].metric_scale()
}

/// `uv` shifted by whole periods to lie nearest `near`.
fn unwrap(mut uv: [f64; 2], near: [f64; 2], periods: [Option<f64>; 2]) -> [f64; 2] {
    for d in 0..2 {
        if let Some(t) = periods[d].filter(|t| *t > 0.0) {
            uv[d] += t * ((near[d] - uv[d]) / t).round();
        }
    }
    uv
}

/// A block's (u, v) made continuous around its boundary (on a periodic surface its sides
/// may come a period apart), and the block mirrored (E1 ↔ E2, E3 and E4 reversed) unless it
/// runs counterclockwise in (u, v) exactly when `orientation` (the face's normal is the
/// surface's).
fn orient(
    points: &mut [Vec<Vec3>; 4],
    uv: &mut [Vec<[f64; 2]>; 4],
    periods: [Option<f64>; 2],
    scale: [f64; 2],
    orientation: bool,
) {
    let (ni, nj) = (uv[2].len(), uv[0].len());
    let walk: Vec<(usize, usize)> = (0..ni)
        .map(|k| (2, k))
        .chain((0..nj).map(|k| (1, k)))
        .chain((0..ni).rev().map(|k| (3, k)))
        .chain((0..nj).rev().map(|k| (0, k)))
        .collect();
    let mut prev = uv[2][0];
    let mut area = 0.0;
    for &(e, k) in &walk {
        let q = unwrap(uv[e][k], prev, periods);
        uv[e][k] = q;
        area += (prev[0] * q[1] - q[0] * prev[1]) * scale[0] * scale[1];
        prev = q;
    }
    if (area > 0.0) != orientation {
        points.swap(0, 1);
        uv.swap(0, 1);
        for e in [2, 3] {
            points[e].reverse();
            uv[e].reverse();
        }
    }
}

/// A side's samples with its end nodes replaced by the corners `a`, `b` (one value for every
/// block meeting there).
fn ends(
    mut x: Vec<Vec3>,
    mut w: Vec<[f64; 2]>,
    a: (Vec3, [f64; 2]),
    b: (Vec3, [f64; 2]),
) -> Sampled {
    let n = x.len();
    (x[0], w[0]) = a;
    (x[n - 1], w[n - 1]) = b;
    (x, w)
}

/// Panels of the 3D arclength table of a cut.
const PANELS: usize = 512;

/// `n` nodes on the straight (u, v) line from `a` to `b` mapped onto the surface, at the
/// 3D arclengths of distribution `d`; the ends are `a` and `b` exactly.
fn straight(
    surface: &CadSurface,
    a: (Vec3, [f64; 2]),
    b: (Vec3, [f64; 2]),
    n: usize,
    d: &DistributionSpec,
    at: &str,
) -> Result<Sampled> {
    let w = |t: f64| [0, 1].map(|c| a.1[c] + t * (b.1[c] - a.1[c]));
    let p = |t: f64| {
        let q = w(t);
        surface.point(q[0], q[1])
    };
    let mut table = Vec::with_capacity(PANELS + 1);
    table.push(0.0);
    let mut prev = p(0.0);
    for k in 1..=PANELS {
        let x = p(k as f64 / PANELS as f64);
        table.push(table[k - 1] + (x - prev).norm());
        prev = x;
    }
    let len = table[PANELS];
    if !(len.is_finite() && len > 0.0) {
        return Err(Error::input(at, "the cut has no length on the surface"));
    }
    let sigma = d.sample(n, len, at)?;
    let mut xs = Vec::with_capacity(n);
    let mut ws = Vec::with_capacity(n);
    for s in &sigma {
        let target = s.clamp(0.0, 1.0) * len;
        let k = table.partition_point(|v| *v < target).clamp(1, PANELS);
        let (t0, t1) = (table[k - 1], table[k]);
        let f = if t1 > t0 {
            (target - t0) / (t1 - t0)
        } else {
            0.0
        };
        let t = (k as f64 - 1.0 + f) / PANELS as f64;
        let q = w(t);
        xs.push(surface.point(q[0], q[1]));
        ws.push(q);
    }
    Ok(ends(xs, ws, a, b))
}
