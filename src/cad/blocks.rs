//! The blocks of a face split into four-sided blocks ([`super::holes`], [`super::band`],
//! [`super::reentrant`]) gridded as block faces (METHOD.md §2 in (u, v), then §5 on the
//! composite surface, as [`super::grid_face`]).
//!
//! Block sides on the face's loops are sampled on the CAD edges (3D arclength, as a one-loop
//! face's sides); cuts are straight lines in (u, v) mapped onto the surface, their nodes at
//! the requested 3D arclengths. Each cut is sampled once and shared by its two blocks, and
//! every block corner is one point computed once, so that neighbouring blocks meet bit for
//! bit.

use super::face::FaceGrid;
use super::holes::{Layout, Node, Side};
use super::trim::{CadSurface, FaceLoop};
use super::StepFace;
use crate::case::DistributionSpec;
use crate::grid::Edge;
use crate::solve::LinearSolver;
use crate::surface::face::grid_face_composite_refined;
use crate::{Error, Result};
use ellipgrid_geometry::{Surface, Vec3};

/// Points and their (u, v) along a side.
type Sampled = (Vec<Vec3>, Vec<[f64; 2]>);

/// The blocks of layout `lay` on the loops `loops` (the outer one first) gridded as block
/// faces: every cut sampled once and shared by its two blocks, every corner one point.
#[allow(clippy::too_many_arguments)]
pub(super) fn grid_layout(
    face: &StepFace,
    surface: &CadSurface,
    loops: &mut [FaceLoop],
    lay: &Layout,
    (ni, nj): (usize, usize),
    dist: [&DistributionSpec; 2],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<Vec<FaceGrid>> {
    let err = |m: String| Error::input(place, m);
    let scale = loops[0].metric_scale();
    let periods = loops[0].periods;
    let gap = loops.iter().map(|lp| lp.gap).fold(0.0, f64::max);
    let healed = loops.iter().map(|lp| lp.healed).fold(0.0, f64::max);
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
        let (a, mut b) = (node(loops, cut.from)?, node(loops, cut.to)?);
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
                        node(loops, Node { l, p: a })?,
                        node(loops, Node { l, p: b })?,
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
        out.push(FaceGrid::new(
            r.result,
            Vec::new(),
            (gap, healed),
            r.uv_picard,
        ));
    }
    Ok(out)
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
