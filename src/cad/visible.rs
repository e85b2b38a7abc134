//! Corners of a one-hole face that its hole sees (issue #14). A face with one hole is one
//! strip with the corners of a one-loop face ([`FaceLoop::corners`]) and an O-type ring of
//! four blocks whose cuts run straight from the hole to those corners
//! ([`super::holes::rings`]). Where a wall of the outer loop stands between the hole and a
//! corner (an L-shaped plate with its hole next to the reentrant vertex), that cut crosses
//! the outer loop and the blocks' boundaries intersect; there the four corners are picked
//! again among the outer loop's points visible from the hole's centroid.

use super::trim::{FaceLoop, LoopPoint};
use super::uv::{at, centroid};
use std::f64::consts::{PI, TAU};

/// Least turning of a visible corner at a vertex (radians, 20°: as the strips' corners).
const TURN: f64 = 0.35;

/// Least angle between two visible corners as seen from the hole (radians, 45°): four
/// corners bunched on one side would leave a block around most of the hole.
const SPREAD: f64 = PI / 4.0;

/// Whether the straight segment from `m` to `q` crosses the polygon `poly` before it reaches
/// `q` (a point of the polygon: its own segments meet the segment only at its end).
fn blocked(poly: &[(LoopPoint, [f64; 2])], m: [f64; 2], q: [f64; 2]) -> bool {
    let n = poly.len();
    let d = [q[0] - m[0], q[1] - m[1]];
    (0..n).any(|k| {
        let (a, b) = (poly[k].1, poly[(k + 1) % n].1);
        let e = [b[0] - a[0], b[1] - a[1]];
        let den = d[0] * e[1] - d[1] * e[0];
        if den == 0.0 {
            return false;
        }
        let w = [a[0] - m[0], a[1] - m[1]];
        let t = (w[0] * e[1] - w[1] * e[0]) / den;
        let s = (w[0] * d[1] - w[1] * d[0]) / den;
        t > 0.0 && t < 1.0 - 1e-6 && (0.0..=1.0).contains(&s)
    })
}

/// Whether a straight cut from the hole (loop 1, whose polygon is `polys[1]`) to one of the
/// outer loop's `corners` would cross the outer loop.
pub(super) fn hidden(
    loops: &mut [FaceLoop],
    polys: &[Vec<(LoopPoint, [f64; 2])>],
    corners: &[LoopPoint; 4],
    scale: [f64; 2],
) -> Result<bool, String> {
    let m = centroid(&polys[1]);
    for &c in corners {
        if blocked(&polys[0], m, at(&mut loops[0], c, scale)?) {
            return Ok(true);
        }
    }
    Ok(false)
}

/// Four corners on the outer loop (`ccw`: it runs counterclockwise in (u, v)) that the hole
/// sees, in loop order: convex vertices turning by more than [`TURN`], most first, at least
/// [`SPREAD`] apart about the hole's centroid; then, into the widest angular gap between
/// those, the visible polygon sample nearest its middle where the loop does not bend
/// outwards. `None` if the hole does not see four such points.
pub(super) fn corners(
    loops: &mut [FaceLoop],
    polys: &[Vec<(LoopPoint, [f64; 2])>],
    scale: [f64; 2],
    ccw: bool,
) -> Result<Option<[LoopPoint; 4]>, String> {
    let m = centroid(&polys[1]);
    let angle = |q: [f64; 2]| (q[1] - m[1]).atan2(q[0] - m[0]);
    // |a − b| about the centroid, in [0, π]
    let apart = |a: f64, b: f64| {
        let d = (a - b).rem_euclid(TAU);
        d.min(TAU - d)
    };
    let lp = &mut loops[0];
    let mut vertices = Vec::new();
    for edge in 0..lp.len() {
        let p = LoopPoint { edge, sigma: 0.0 };
        let t = lp.turning(edge);
        if t > TURN && !lp.reentrant(edge, ccw) {
            let q = at(lp, p, scale)?;
            if !blocked(&polys[0], m, q) {
                vertices.push((t, p, angle(q)));
            }
        }
    }
    vertices.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.edge.cmp(&b.1.edge)));
    let mut picks: Vec<(LoopPoint, f64)> = Vec::new();
    for (_, p, a) in vertices {
        if picks.len() < 4 && picks.iter().all(|&(_, b)| apart(a, b) >= SPREAD) {
            picks.push((p, a));
        }
    }
    while picks.len() < 4 {
        // the widest gap between the picks' directions (all around if none yet)
        let mut dirs: Vec<f64> = picks.iter().map(|p| p.1).collect();
        dirs.sort_by(f64::total_cmp);
        let (from, width) = match dirs.len() {
            0 => (0.0, TAU),
            k => (0..k)
                .map(|i| (dirs[i], (dirs[(i + 1) % k] - dirs[i]).rem_euclid(TAU)))
                .map(|(a, w)| (a, if w == 0.0 { TAU } else { w }))
                .max_by(|x, y| x.1.total_cmp(&y.1))
                .expect("directions"),
        };
        let target = from + 0.5 * width;
        let mut best: Option<(f64, LoopPoint, f64)> = None;
        for &(p, q) in &polys[0] {
            let a = angle(q);
            let off = (a - from).rem_euclid(TAU);
            // inside the gap, a spread away from both of its ends
            if off < SPREAD.min(0.25 * width) || width - off < SPREAD.min(0.25 * width) {
                continue;
            }
            let miss = apart(a, target);
            if best.is_some_and(|b| b.0 <= miss) || blocked(&polys[0], m, q) || lp.bends_out(p, ccw)
            {
                continue;
            }
            best = Some((miss, p, a));
        }
        match best {
            Some((_, p, a)) => picks.push((p, a)),
            None => return Ok(None),
        }
    }
    let mut pts: Vec<LoopPoint> = picks.into_iter().map(|p| p.0).collect();
    pts.sort_by(|a, b| {
        (a.edge, a.sigma)
            .partial_cmp(&(b.edge, b.sigma))
            .expect("finite")
    });
    Ok(Some([pts[0], pts[1], pts[2], pts[3]]))
}
