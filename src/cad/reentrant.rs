//! A one-loop face cut at its reentrant vertices into four-sided blocks (issue #14: L-shaped
//! plates, pockets, slots), for faces whose one-block grid folds there: next to a reentrant
//! vertex inside a side the discrete Winslow grid folds although the continuous map does not.
//! The layout is made in the surface's (u, v) plane scaled by the loop's mean |x_u|, |x_v|
//! (as a one-loop face's parametrization); the blocks are gridded as a face with holes' blocks
//! ([`super::blocks`]: every cut sampled once and shared by its two blocks, every corner one
//! point).
//!
//! - A *reentrant vertex* is a vertex where the loop turns outwards by more than 20°.
//! - It is cut off by a straight (u, v) cut along the bisector of its interior angle to where
//!   the ray first meets the boundary (both sides then have angles below 180° there); a cut
//!   ending closer to a loop vertex than 15 % of its length ends at the vertex (no sliver of
//!   a side). The cut must meet the loop, not an earlier cut, and cross nothing on its way;
//!   where it does not, the ray is turned by up to 80 % of the way to where the angle on one
//!   side would be 180°.
//! - Each part is cut again at its own reentrant vertices, the sharpest first, until no part
//!   has one inside its boundary's loop stretches (at most [`MAX_BLOCKS`] parts).
//! - Each part is a block: its cut ends are corners (a cut is a whole side of both its blocks);
//!   with fewer than four, the convex vertices inside its loop stretches turning most (by more
//!   than 20°), else the middles of its longest loop stretches, make up the four. A part with
//!   more than four cut ends is refused.
//! - Each cut runs along the same grid direction (i or j) in both its blocks: the blocks are a
//!   tree joined by the cuts, and a walk over it picks which pair of each block's sides is i.

use super::blocks::grid_layout;
use super::face::{bounds, gap_tolerance, FaceGrid};
use super::holes::{polygon, Layout};
use super::pieces::{ahead, assign, at, cross, four, merged, sub, within, Piece, TURN};
use super::trim::{CadSurface, FaceLoop, LoopPoint, NS};
use super::{quietly, Route, StepFace};
use crate::case::DistributionSpec;
use crate::solve::LinearSolver;
use crate::{Error, Result};
use ellipgrid_geometry::TruckSurface;

/// Most blocks a face is cut into.
pub const MAX_BLOCKS: usize = 16;
/// A cut ending closer to a loop vertex than this fraction of its length ends at the vertex.
const SNAP: f64 = 0.15;

/// The grids of a one-loop face cut at its reentrant vertices into blocks (at most
/// [`MAX_BLOCKS`]), in the order of [`super::grid_face_blocks`]'s blocks: each block's normal
/// is the face's, cuts are shared node for node. Used by [`super::grid_face_blocks`] where the
/// face's one-block grid folds; on its own it cuts any such face.
///
/// # Errors
/// [`Error::Input`] at `place` with the reason if the face is not one loop, has no reentrant
/// vertex, or cannot be cut (a ray meeting a cut first, a part with more than four cut ends,
/// too many parts); those of the blocks' grids.
pub fn grid_face_split(
    face: &StepFace,
    (ni, nj): (usize, usize),
    dist_i: &DistributionSpec,
    dist_j: &DistributionSpec,
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<Vec<FaceGrid>> {
    grid_cut(face, (ni, nj), [dist_i, dist_j], solver, place, layout)
}

/// The grids of a one-loop face cut into the blocks of `layout` (made in its scaled (u, v)).
pub(super) fn grid_cut(
    face: &StepFace,
    (ni, nj): (usize, usize),
    [dist_i, dist_j]: [&DistributionSpec; 2],
    solver: &mut dyn LinearSolver,
    place: &str,
    layout: fn(&mut FaceLoop) -> std::result::Result<Layout, String>,
) -> Result<Vec<FaceGrid>> {
    let err = |m: String| Error::input(place, m);
    if !matches!(face.route(), Route::Trimmed(_)) {
        return Err(err(
            "only a face of one loop is cut at reentrant vertices".into()
        ));
    }
    if ni < 3 || nj < 3 {
        return Err(err(format!(
            "a surface grid needs at least 3 × 3 nodes, got {ni} × {nj}"
        )));
    }
    let edges = face.loops.as_ref().map_err(|e| err(e.clone()))?;
    let surface = TruckSurface::new(face.cad_surface.clone());
    let surface: &CadSurface = &surface;
    quietly(|| {
        let mut lp = FaceLoop::new(
            surface,
            &edges[0],
            bounds(surface),
            gap_tolerance(face),
            false,
        )
        .map_err(err)?;
        if lp.pole.is_some() {
            return Err(err("the loop runs through a pole: not cut".into()));
        }
        let lay = layout(&mut lp).map_err(err)?;
        let dist = [dist_i, dist_j];
        grid_layout(
            face,
            surface,
            std::slice::from_mut(&mut lp),
            &lay,
            (ni, nj),
            dist,
            solver,
            place,
        )
    })
    .unwrap_or_else(|_| {
        Err(err(
            "truck failed to evaluate a boundary edge or the surface".into(),
        ))
    })
}

/// A part's boundary polygon in scaled (u, v): each point with its piece and its loop point
/// (none for a cut's start); segment k runs from point k to the next.
type Outline = Vec<([f64; 2], usize, Option<LoopPoint>)>;

fn outline(
    lp: &mut FaceLoop,
    poly: &[(LoopPoint, [f64; 2])],
    pieces: &[Piece],
    cuts: &[(LoopPoint, LoopPoint)],
) -> std::result::Result<Outline, String> {
    let mut out = Vec::new();
    for (i, piece) in pieces.iter().enumerate() {
        match *piece {
            Piece::Loop(a, b) => {
                out.push((at(lp, a)?, i, Some(a)));
                let mut inner: Vec<(f64, LoopPoint, [f64; 2])> = poly
                    .iter()
                    .filter(|(p, _)| within(lp, (a, b), *p))
                    .map(|(p, q)| (ahead(lp, a, *p), *p, *q))
                    .collect();
                inner.sort_by(|x, y| x.0.total_cmp(&y.0));
                out.extend(inner.into_iter().map(|(_, p, q)| (q, i, Some(p))));
            }
            Piece::Cut(c, rev) => {
                let p = if rev { cuts[c].1 } else { cuts[c].0 };
                out.push((at(lp, p)?, i, None));
            }
        }
    }
    Ok(out)
}

/// Whether the segment `a`–`b` properly crosses a segment of `out` other than those `skip`s.
fn crosses(out: &Outline, a: [f64; 2], b: [f64; 2], skip: impl Fn(usize) -> bool) -> bool {
    let n = out.len();
    (0..n).filter(|k| !skip(*k)).any(|k| {
        let (p, q) = (out[k].0, out[(k + 1) % n].0);
        let d = sub(b, a);
        let side = |x: [f64; 2]| cross(d, sub(x, a));
        let e = sub(q, p);
        let other = |x: [f64; 2]| cross(e, sub(x, p));
        (side(p) > 0.0) != (side(q) > 0.0) && (other(a) > 0.0) != (other(b) > 0.0)
    })
}

/// Distance from `x` to the segment `p`–`q`.
fn distance(x: [f64; 2], p: [f64; 2], q: [f64; 2]) -> f64 {
    let e = sub(q, p);
    let l2 = e[0] * e[0] + e[1] * e[1];
    let t = if l2 > 0.0 {
        ((sub(x, p)[0] * e[0] + sub(x, p)[1] * e[1]) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let y = [p[0] + t * e[0], p[1] + t * e[1]];
    (x[0] - y[0]).hypot(x[1] - y[1])
}

/// A cut from vertex `k` (reentrant, inside loop piece `i` of the part) along the bisector:
/// the piece it ends in and its end, or `None` where the ray meets a cut first or the cut
/// would cross the boundary.
fn cut_from(
    lp: &mut FaceLoop,
    out: &Outline,
    pieces: &[Piece],
    (k, turn): (usize, f64),
    ccw: bool,
    size: f64,
) -> std::result::Result<Option<(usize, LoopPoint)>, String> {
    let s = lp.metric_scale();
    let n = lp.len();
    let (ea, eb) = (&lp.edges[(k + n - 1) % n].uv, &lp.edges[k].uv);
    let unit = |d: [f64; 2]| {
        let l = d[0].hypot(d[1]);
        [d[0] / l, d[1] / l]
    };
    let da = unit([0, 1].map(|c| (ea[NS][c] - ea[NS - 1][c]) * s[c]));
    let db = unit([0, 1].map(|c| (eb[1][c] - eb[0][c]) * s[c]));
    // The sum of the sides' inward normals (left of a counterclockwise loop).
    let sign = if ccw { 1.0 } else { -1.0 };
    let dir = [sign * -(da[1] + db[1]), sign * (da[0] + db[0])];
    let len = dir[0].hypot(dir[1]);
    if len.is_nan() || len <= 1e-6 {
        return Ok(None);
    }
    let dir = unit(dir);
    let (sin, cos) = turn.sin_cos();
    let dir = [cos * dir[0] - sin * dir[1], sin * dir[0] + cos * dir[1]];
    let r = LoopPoint {
        edge: k,
        sigma: 0.0,
    };
    let m = out.len();
    // The vertex is a point of the outline (inside a loop piece); the segments at it are
    // left out.
    let Some(ro) = out.iter().position(|x| x.2 == Some(r)) else {
        return Ok(None);
    };
    let o = out[ro].0;
    let tol = 1e-9 * size;
    let mut hit: Option<(f64, usize)> = None;
    for j in 0..m {
        let (p, q) = (out[j].0, out[(j + 1) % m].0);
        let e = sub(q, p);
        let den = cross(dir, e);
        if den == 0.0 || j == ro || (j + 1) % m == ro {
            continue;
        }
        let t = cross(sub(p, o), e) / den;
        let f = cross(sub(p, o), dir) / den;
        if t > tol && (0.0..=1.0).contains(&f) && hit.is_none_or(|h| t < h.0) {
            hit = Some((t, j));
        }
    }
    let Some((_, j)) = hit else {
        return Ok(None);
    };
    let piece = out[j].1;
    let Piece::Loop(a, b) = pieces[piece] else {
        return Ok(None);
    };
    // The segment's ends on the loop; the crossing by bisection along it.
    let p0 = out[j].2.unwrap_or(a);
    let p1 = match out.get(j + 1) {
        Some(x) if x.1 == piece => x.2.unwrap_or(b),
        _ => b,
    };
    let len = lp.chain_length(p0, p1);
    let g = |x: [f64; 2]| cross(dir, sub(x, o));
    let g0 = g(at(lp, p0)?);
    let (mut lo, mut hi) = (0.0, len);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        let v = g(at(lp, lp.advance(p0, mid))?);
        if (v < 0.0) == (g0 < 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let mut p = lp.advance(p0, 0.5 * (lo + hi));
    let end = at(lp, p)?;
    let reach = sub(end, o)[0].hypot(sub(end, o)[1]);
    // A loop vertex close by ends the cut instead.
    let mut best: Option<(f64, LoopPoint)> = None;
    for v in 0..n {
        let vp = LoopPoint {
            edge: v,
            sigma: 0.0,
        };
        if !within(lp, (a, b), vp) {
            continue;
        }
        let x = sub(at(lp, vp)?, end);
        let d = x[0].hypot(x[1]);
        if d < SNAP * reach && best.is_none_or(|b| d < b.0) {
            best = Some((d, vp));
        }
    }
    if let Some((_, vp)) = best {
        p = vp;
    }
    // The segments at either end of the cut are left out: the cut ends on the loop's
    // curve, which its polygon's chords only approximate.
    let e = at(lp, p)?;
    let skip = |s: usize| {
        let (x, y) = (out[s].0, out[(s + 1) % m].0);
        s == j || s == ro || (s + 1) % m == ro || distance(e, x, y) <= 1e-3 * reach
    };
    if !within(lp, (a, b), p) || crosses(out, o, e, skip) {
        return Ok(None);
    }
    Ok(Some((piece, p)))
}

/// The two parts of `pieces` cut from `r` (inside piece `i`) to `p` (inside piece `j`) by cut
/// `c`: from `r` to `p` closed by the cut run backwards, and from `p` to `r`.
fn split(
    lp: &FaceLoop,
    pieces: &[Piece],
    (i, r): (usize, LoopPoint),
    (j, p): (usize, LoopPoint),
    c: usize,
) -> (Vec<Piece>, Vec<Piece>) {
    let mut seq = Vec::with_capacity(pieces.len() + 3);
    let (mut ir, mut ip) = (0, 0);
    for (k, piece) in pieces.iter().enumerate() {
        let Piece::Loop(a, b) = *piece else {
            seq.push(*piece);
            continue;
        };
        let mut at = vec![];
        if k == i {
            at.push((ahead(lp, a, r), r, true));
        }
        if k == j {
            at.push((ahead(lp, a, p), p, false));
        }
        at.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut from = a;
        for (_, x, is_r) in at {
            seq.push(Piece::Loop(from, x));
            if is_r {
                ir = seq.len();
            } else {
                ip = seq.len();
            }
            from = x;
        }
        seq.push(Piece::Loop(from, b));
    }
    let n = seq.len();
    let run = |s: usize, e: usize| (0..(e + n - s) % n).map(|d| seq[(s + d) % n]).collect();
    let mut one: Vec<Piece> = run(ir, ip);
    one.push(Piece::Cut(c, true));
    let mut two: Vec<Piece> = run(ip, ir);
    two.push(Piece::Cut(c, false));
    (merged(one), merged(two))
}

/// The blocks of a one-loop face cut at its reentrant vertices (module doc).
fn layout(lp: &mut FaceLoop) -> std::result::Result<Layout, String> {
    let scale = lp.metric_scale();
    let ccw = lp.signed_area(scale) > 0.0;
    let poly = polygon(lp, scale);
    let (lo, hi) = poly.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), (_, q)| {
            (
                [lo[0].min(q[0]), lo[1].min(q[1])],
                [hi[0].max(q[0]), hi[1].max(q[1])],
            )
        },
    );
    let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let n = lp.len();
    let mut cuts: Vec<(LoopPoint, LoopPoint)> = Vec::new();
    let start = LoopPoint {
        edge: 0,
        sigma: 0.5,
    };
    let mut todo = vec![vec![Piece::Loop(start, start)]];
    let mut parts = Vec::new();
    while let Some(pieces) = todo.pop() {
        // Reentrant vertices inside the part's loop pieces, sharpest first.
        let mut rs: Vec<(f64, usize, usize)> = (0..n)
            .filter(|&k| lp.reentrant(k, ccw) && lp.turning(k) > TURN)
            .filter_map(|k| {
                let v = LoopPoint {
                    edge: k,
                    sigma: 0.0,
                };
                pieces.iter().enumerate().find_map(|(i, p)| match *p {
                    Piece::Loop(a, b) if within(lp, (a, b), v) => Some((lp.turning(k), k, i)),
                    _ => None,
                })
            })
            .collect();
        if rs.is_empty() {
            parts.push(pieces);
            continue;
        }
        if parts.len() + todo.len() + 2 > MAX_BLOCKS {
            return Err(format!(
                "more than {MAX_BLOCKS} blocks needed to cut off every reentrant vertex"
            ));
        }
        rs.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
        let out = outline(lp, &poly, &pieces, &cuts)?;
        let mut found = None;
        'vertices: for &(t, k, i) in &rs {
            // The bisector, else turned by up to 80 % of the way to where one side's angle
            // would be 180°.
            for f in [0.0, 0.5, -0.5, 0.8, -0.8] {
                let turn = f * 0.5 * (std::f64::consts::PI - t);
                if let Some(end) = cut_from(lp, &out, &pieces, (k, turn), ccw, size)? {
                    found = Some((k, i, end));
                    break 'vertices;
                }
            }
        }
        let Some((k, i, (j, p))) = found else {
            return Err(format!(
                "no straight cut from the reentrant vertex at the start of boundary edge {} \
                 meets the loop",
                rs[0].1 + 1
            ));
        };
        let r = LoopPoint {
            edge: k,
            sigma: 0.0,
        };
        cuts.push((r, p));
        let (one, two) = split(lp, &pieces, (i, r), (j, p), cuts.len() - 1);
        todo.push(one);
        todo.push(two);
    }
    if cuts.is_empty() {
        return Err("the loop has no reentrant vertex".into());
    }
    let mut sides = Vec::with_capacity(parts.len());
    for pieces in parts {
        sides.push(four(lp, pieces, ccw)?);
    }
    Ok(assign(cuts, sides))
}
