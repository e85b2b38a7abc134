//! A one-loop face cut by *chords* from its reentrant vertices into four-sided blocks
//! (issue #14: combs and frames of ±90° edges, such as a cylinder wall with slots on both
//! sides of a spine), for faces that fold as one block with every corner set, and whose
//! bisector cuts ([`super::reentrant`]) fold or fail.
//!
//! A grid engineer cuts such a face along the straight continuations of its edges: at a
//! vertex turning outwards by 90° the two continuations split its 270° into three right
//! angles, and a chord that meets a straight edge square, or another such vertex, leaves
//! 90° on both sides there, so that every part is a rectangle-like block with corners only
//! where it turns. Here:
//!
//! - from every reentrant vertex (turning outwards by more than 20°) a ray runs along the
//!   continuation of each of its two edges (in the (u, v) plane scaled as a one-loop face's
//!   parametrization) to where it first meets the loop; it is a chord if it ends at a
//!   reentrant vertex (within 1 % of its length), or inside an edge that it meets within 15°
//!   of square (not near a convex vertex);
//! - all chords are cut at once (none may cross); the parts are the faces of the planar
//!   graph of the loop and the chords, traced with the part on the left;
//! - each part is a block as in [`super::reentrant`]: its chord ends are corners, its convex
//!   vertices turning most make up the four; a part of more than four pieces is refused.
//!
//! Every chord is a whole side of its two blocks, sampled once (nodes shared bit for bit).

use super::face::FaceGrid;
use super::holes::{locate, polygon, Layout};
use super::pieces::{assign, at, cross, four, merged, position, sub, within, Piece};
use super::reentrant::grid_cut;
use super::trim::{FaceLoop, LoopPoint, NS};
use super::StepFace;
use crate::case::DistributionSpec;
use crate::solve::LinearSolver;
use crate::Result;

/// Least outward turning of a reentrant vertex (radians, 20°), as [`super::reentrant`]'s.
const TURN: f64 = 0.35;
/// A ray ends at a vertex closer to its hit than this fraction of its length.
const SNAP: f64 = 0.01;
/// Largest |cos| of the angle at which a ray may end inside an edge (15° off square).
const SQUARE: f64 = 0.26;
/// Most blocks a face is cut into by chords (each ray of a reentrant vertex a cut: twice
/// [`super::MAX_BLOCKS`]).
pub const MAX_CHORD_BLOCKS: usize = 32;

/// The grids of a one-loop face cut by chords between its reentrant vertices (module doc),
/// in the order the parts are traced; each block's normal is the face's.
///
/// # Errors
/// [`crate::Error::Input`] at `place` with the reason if the face is not one loop, has no
/// chord, has chords that cross, or a part that is not four-sided; those of the blocks' grids.
pub fn grid_face_chords(
    face: &StepFace,
    (ni, nj): (usize, usize),
    dist_i: &DistributionSpec,
    dist_j: &DistributionSpec,
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<Vec<FaceGrid>> {
    grid_cut(face, (ni, nj), [dist_i, dist_j], solver, place, layout)
}

fn vertex(edge: usize) -> LoopPoint {
    LoopPoint { edge, sigma: 0.0 }
}

fn unit(d: [f64; 2]) -> [f64; 2] {
    let l = d[0].hypot(d[1]);
    [d[0] / l, d[1] / l]
}

/// The chords of the loop (pairs of loop points, each once), or why there are none.
fn chords(
    lp: &mut FaceLoop,
    ccw: bool,
) -> std::result::Result<Vec<(LoopPoint, LoopPoint)>, String> {
    let s = lp.metric_scale();
    let n = lp.len();
    let poly = polygon(lp, s);
    let m = poly.len();
    let reentrant: Vec<bool> = (0..n)
        .map(|k| lp.reentrant(k, ccw) && lp.turning(k) > TURN)
        .collect();
    let corners: Vec<[f64; 2]> = (0..n)
        .map(|k| at(lp, vertex(k)))
        .collect::<std::result::Result<_, _>>()?;
    let mut out: Vec<(LoopPoint, LoopPoint)> = Vec::new();
    for k in (0..n).filter(|&k| reentrant[k]) {
        let (ea, eb) = (&lp.edges[(k + n - 1) % n].uv, &lp.edges[k].uv);
        let da = unit([0, 1].map(|c| (ea[NS][c] - ea[NS - 1][c]) * s[c]));
        let db = unit([0, 1].map(|c| (eb[1][c] - eb[0][c]) * s[c]));
        let o = corners[k];
        // The vertex's place in the polygon: the segments at it are left out.
        let ro = k * NS;
        for dir in [da, [-db[0], -db[1]]] {
            if dir.iter().any(|d| d.is_nan()) {
                continue;
            }
            let mut hit: Option<(f64, usize)> = None;
            for j in (0..m).filter(|&j| j != ro && (j + 1) % m != ro) {
                let (p, q) = (poly[j].1, poly[(j + 1) % m].1);
                let e = sub(q, p);
                let den = cross(dir, e);
                if den == 0.0 {
                    continue;
                }
                let t = cross(sub(p, o), e) / den;
                let f = cross(sub(p, o), dir) / den;
                if t > 0.0 && (-1e-9..=1.0 + 1e-9).contains(&f) && hit.is_none_or(|h| t < h.0) {
                    hit = Some((t, j));
                }
            }
            let Some((t, j)) = hit else { continue };
            let x = [o[0] + t * dir[0], o[1] + t * dir[1]];
            let near = (0..n)
                .filter(|&w| w != k)
                .map(|w| (sub(corners[w], x)[0].hypot(sub(corners[w], x)[1]), w))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let end = match near {
                Some((d, w)) if d < SNAP * t => {
                    if !reentrant[w] {
                        continue;
                    }
                    vertex(w)
                }
                _ => {
                    // Inside an edge: only where the ray meets it within 15° of square.
                    let e = unit(sub(poly[(j + 1) % m].1, poly[j].1));
                    if (dir[0] * e[0] + dir[1] * e[1]).abs() > SQUARE {
                        continue;
                    }
                    let f = move |q: [f64; 2]| cross(dir, sub(q, o));
                    locate(lp, &poly, j, s, f)?
                }
            };
            let c = (vertex(k), end);
            if !out.iter().any(|&(a, b)| (a, b) == c || (b, a) == c) {
                out.push(c);
            }
        }
    }
    if out.is_empty() {
        return Err("no ray along an edge's continuation from a reentrant vertex".into());
    }
    let pts: Vec<([f64; 2], [f64; 2])> = out
        .iter()
        .map(|&(a, b)| Ok((at(lp, a)?, at(lp, b)?)))
        .collect::<std::result::Result<_, String>>()?;
    for (i, a) in out.iter().enumerate() {
        for (j, b) in out.iter().enumerate().skip(i + 1) {
            let shared = a.0 == b.0 || a.0 == b.1 || a.1 == b.0 || a.1 == b.1;
            let ((p, q), (r, t)) = (pts[i], pts[j]);
            let side = |x: [f64; 2], y: [f64; 2], z: [f64; 2]| cross(sub(y, x), sub(z, x)) > 0.0;
            if !shared && side(p, q, r) != side(p, q, t) && side(r, t, p) != side(r, t, q) {
                return Err(format!(
                    "the cuts from the vertices at the starts of boundary edges {} and {} cross",
                    a.0.edge + 1,
                    b.0.edge + 1
                ));
            }
        }
    }
    Ok(out)
}

/// A directed edge of the graph of the loop and the chords.
#[derive(Clone, Copy, PartialEq)]
enum Arc {
    /// Loop stretch `i` (from chord end `i` forwards to chord end `i + 1`).
    Loop(usize),
    /// Chord `c`, from its second vertex to its first if `rev`.
    Chord(usize, bool),
}

/// The blocks of a one-loop face cut by its chords (module doc).
fn layout(lp: &mut FaceLoop) -> std::result::Result<Layout, String> {
    let scale = lp.metric_scale();
    let ccw = lp.signed_area(scale) > 0.0;
    let chords = chords(lp, ccw)?;
    if chords.len() + 1 > MAX_CHORD_BLOCKS {
        return Err(format!(
            "{} chords: more than {MAX_CHORD_BLOCKS} blocks",
            chords.len()
        ));
    }
    // Chord ends in loop order.
    let mut ends: Vec<LoopPoint> = Vec::new();
    for p in chords.iter().flat_map(|c| [c.0, c.1]) {
        if !ends.contains(&p) {
            ends.push(p);
        }
    }
    ends.sort_by(|a, b| position(lp, *a).total_cmp(&position(lp, *b)));
    let ne = ends.len();
    let slot = |v: LoopPoint| ends.iter().position(|&e| e == v).unwrap_or(0);
    // (u, v) of each end, mirrored for a clockwise loop so that parts lie left of the arcs.
    let flip = |x: [f64; 2]| if ccw { x } else { [-x[0], x[1]] };
    let mut pos = Vec::with_capacity(ne);
    let mut leave = Vec::with_capacity(ne);
    let mut arrive = Vec::with_capacity(ne);
    for i in 0..ne {
        let (a, b) = (ends[i], ends[(i + 1) % ne]);
        let len = if ne == 1 {
            (0..lp.len()).map(|k| lp.length(k)).sum()
        } else {
            (position(lp, b) - position(lp, a))
                .rem_euclid((0..lp.len()).map(|k| lp.length(k)).sum())
        };
        let x = flip(at(lp, a)?);
        let ahead = flip(at(lp, lp.advance(a, 1e-3 * len))?);
        pos.push(x);
        leave.push(unit(sub(ahead, x)));
        let y = flip(at(lp, b)?);
        let before = flip(at(lp, lp.advance(a, (1.0 - 1e-3) * len))?);
        arrive.push(unit(sub(y, before)));
    }
    // The end an arc runs to, its direction there and leaving its start.
    let head = |a: Arc| match a {
        Arc::Loop(i) => (i + 1) % ne,
        Arc::Chord(c, rev) => slot(if rev { chords[c].0 } else { chords[c].1 }),
    };
    let tail = |a: Arc| match a {
        Arc::Loop(i) => i,
        Arc::Chord(c, rev) => slot(if rev { chords[c].1 } else { chords[c].0 }),
    };
    let out_dir = |a: Arc| match a {
        Arc::Loop(i) => leave[i],
        Arc::Chord(..) => unit(sub(pos[head(a)], pos[tail(a)])),
    };
    let in_dir = |a: Arc| match a {
        Arc::Loop(i) => arrive[i],
        Arc::Chord(..) => out_dir(a),
    };
    let mut arcs: Vec<Arc> = (0..ne).map(Arc::Loop).collect();
    for c in 0..chords.len() {
        arcs.push(Arc::Chord(c, false));
        arcs.push(Arc::Chord(c, true));
    }
    let mut used = vec![false; arcs.len()];
    let mut parts = Vec::new();
    for start in 0..arcs.len() {
        if used[start] {
            continue;
        }
        let mut pieces = Vec::new();
        let mut a = start;
        while !used[a] {
            used[a] = true;
            pieces.push(match arcs[a] {
                Arc::Loop(i) => Piece::Loop(ends[i], ends[(i + 1) % ne]),
                Arc::Chord(c, rev) => Piece::Cut(c, rev),
            });
            // The next arc: the first clockwise from the way back.
            let v = head(arcs[a]);
            let d = in_dir(arcs[a]);
            let back = [-d[0], -d[1]];
            let angle = |b: &Arc| {
                let o = out_dir(*b);
                let t = cross(o, back).atan2(o[0] * back[0] + o[1] * back[1]);
                if t <= 1e-12 {
                    t + std::f64::consts::TAU
                } else {
                    t
                }
            };
            a = (0..arcs.len())
                .filter(|&b| tail(arcs[b]) == v && arcs[b] != reverse(arcs[a]))
                .min_by(|x, y| angle(&arcs[*x]).total_cmp(&angle(&arcs[*y])))
                .ok_or("a chord end with no way on")?;
        }
        if a != start {
            return Err("the loop and its chords do not close into parts".into());
        }
        // Start at a chord, so that loop stretches that meet are merged.
        if let Some(c) = pieces.iter().position(|p| matches!(p, Piece::Cut(..))) {
            pieces.rotate_left(c);
        }
        parts.push(merged(pieces));
    }
    if parts.len() != chords.len() + 1 {
        return Err(format!(
            "{} chords made {} parts, not {}",
            chords.len(),
            parts.len(),
            chords.len() + 1
        ));
    }
    let cuts = chords;
    let mut sides = Vec::with_capacity(parts.len());
    for pieces in parts {
        // No reentrant vertex may be left inside a part's loop stretches.
        for k in 0..lp.len() {
            let inside = pieces.iter().any(|p| match *p {
                Piece::Loop(a, b) => within(lp, (a, b), vertex(k)),
                Piece::Cut(..) => false,
            });
            if inside && lp.reentrant(k, ccw) && lp.turning(k) > TURN {
                return Err(format!(
                    "the reentrant vertex at the start of boundary edge {} has no chord",
                    k + 1
                ));
            }
        }
        sides.push(four(lp, pieces, ccw)?);
    }
    Ok(assign(cuts, sides))
}

fn reverse(a: Arc) -> Arc {
    match a {
        Arc::Loop(i) => Arc::Loop(usize::MAX - i),
        Arc::Chord(c, rev) => Arc::Chord(c, !rev),
    }
}
