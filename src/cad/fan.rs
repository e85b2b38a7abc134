//! A face with a central hole and others around it (a flange: a bore and its bolt circle)
//! cut by a *fan* of straight (u, v) cuts into one-hole sectors (issue #14), where no set
//! of parallel lines separates the holes ([`super::hole_cuts`]).
//!
//! Seen from the centroid m of a central hole C (tried largest first), every other hole
//! spans an interval of directions; if these intervals leave open gaps between consecutive
//! holes, a ray from m along the middle of each gap runs from C (where it leaves C, once) to
//! the outer loop (where it leaves it, once) and misses every hole. Each cut is such a ray
//! from C to the outer loop; the sector between two consecutive cuts holds one hole and has
//! four corners (the cuts' ends), and gets its O-type ring of four blocks as a strip does
//! ([`super::holes::rings`]). The cuts run along the sectors' i direction, as the cuts
//! between strips.

use super::hole_cuts::crossings;
use super::holes::{locate, rings, Cut, Layout, Node, Part, Side};
use super::trim::{FaceLoop, LoopPoint};
use super::uv::{at, centroid};
use std::f64::consts::{PI, TAU};

/// Most central holes tried (largest (u, v) area first).
const CENTRES: usize = 3;
/// Least angular gap between the holes around the centre (radians, about 0.6°).
const GAP: f64 = 0.01;

/// The polygon's area in the scaled (u, v) plane (unsigned).
fn area(poly: &[(LoopPoint, [f64; 2])]) -> f64 {
    let n = poly.len();
    let a: f64 = (0..n)
        .map(|i| {
            let (p, q) = (poly[i].1, poly[(i + 1) % n].1);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum();
    0.5 * a.abs()
}

/// The layout of a face whose holes lie around a central one (module doc), in the scaled
/// (u, v) plane of `polys` (the outer loop first); conventions as [`super::holes::layout`].
///
/// # Errors
/// Why no hole can be the centre of a fan: the other holes' directions overlap, or a ray
/// leaves the central hole or the outer loop more than once.
pub(super) fn fan(
    loops: &mut [FaceLoop],
    ccw: &[bool],
    scale: [f64; 2],
    orientation: bool,
    polys: &[Vec<(LoopPoint, [f64; 2])>],
) -> Result<Layout, String> {
    let nh = polys.len() - 1;
    if nh < 3 {
        return Err("too few holes for a fan of cuts about a central hole".into());
    }
    let mut by_area: Vec<usize> = (1..=nh).collect();
    by_area.sort_by(|a, b| area(&polys[*b]).total_cmp(&area(&polys[*a])));
    let mut first = None;
    for &c in by_area.iter().take(CENTRES) {
        match about(loops, ccw, scale, orientation, polys, c) {
            Ok(lay) => return Ok(lay),
            Err(e) => {
                first.get_or_insert(e);
            }
        }
    }
    Err(first.unwrap_or_default())
}

/// The fan about hole `c`.
fn about(
    loops: &mut [FaceLoop],
    ccw: &[bool],
    scale: [f64; 2],
    orientation: bool,
    polys: &[Vec<(LoopPoint, [f64; 2])>],
    c: usize,
) -> Result<Layout, String> {
    let m = centroid(&polys[c]);
    let angle = |q: [f64; 2]| (q[1] - m[1]).atan2(q[0] - m[0]);
    let wrap = |a: f64| a - TAU * (a / TAU).round();
    // Each other hole's interval of directions [start, end], start in [0, 2π).
    let mut spans: Vec<(f64, f64, usize)> = Vec::new();
    for (h, poly) in polys.iter().enumerate().skip(1) {
        if h == c {
            continue;
        }
        let mid = angle(centroid(poly));
        let (lo, hi) = poly.iter().fold((0.0f64, 0.0f64), |(lo, hi), (_, q)| {
            let d = wrap(angle(*q) - mid);
            (lo.min(d), hi.max(d))
        });
        if hi - lo >= PI {
            return Err(format!(
                "hole (loop {}) surrounds the centroid of hole (loop {})",
                h + 1,
                c + 1
            ));
        }
        let start = (mid + lo).rem_euclid(TAU);
        spans.push((start, start + hi - lo, h));
    }
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = spans.len();
    // Ray i along the middle of the gap after hole i.
    let mut dirs = Vec::with_capacity(n);
    for i in 0..n {
        let next = if i + 1 < n {
            spans[i + 1].0
        } else {
            spans[0].0 + TAU
        };
        let gap = next - spans[i].1;
        if gap < GAP {
            return Err(format!(
                "seen from the centroid of hole (loop {}), holes (loops {} and {}) overlap",
                c + 1,
                spans[i].2 + 1,
                spans[(i + 1) % n].2 + 1
            ));
        }
        let a = spans[i].1 + 0.5 * gap;
        dirs.push([a.cos(), a.sin()]);
    }
    let mut cuts = Vec::with_capacity(n);
    for r in &dirs {
        let f = |q: [f64; 2]| (q[0] - m[0]) * r[1] - (q[1] - m[1]) * r[0];
        let ahead = |q: [f64; 2]| (q[0] - m[0]) * r[0] + (q[1] - m[1]) * r[1] > 0.0;
        let mut ends = [Node {
            l: 0,
            p: LoopPoint {
                edge: 0,
                sigma: 0.0,
            },
        }; 2];
        for (e, l) in [c, 0].into_iter().enumerate() {
            let poly = &polys[l];
            let x: Vec<usize> = crossings(poly, f)
                .into_iter()
                .map(|k| k.0)
                .filter(|&k| ahead(poly[k].1) || ahead(poly[(k + 1) % poly.len()].1))
                .collect();
            if x.len() != 1 {
                return Err(format!(
                    "a cut of the fan about hole (loop {}) leaves loop {} {} times, not once",
                    c + 1,
                    l + 1,
                    x.len()
                ));
            }
            ends[e] = Node {
                l,
                p: locate(&mut loops[l], poly, x[0], scale, f)?,
            };
        }
        // The cut must leave the central hole before it reaches the outer loop.
        let (pi, po) = (
            at(&mut loops[c], ends[0].p, scale)?,
            at(&mut loops[0], ends[1].p, scale)?,
        );
        let dist = |q: [f64; 2]| (q[0] - m[0]) * r[0] + (q[1] - m[1]) * r[1];
        if dist(pi) >= dist(po) {
            return Err(format!(
                "a cut of the fan about hole (loop {}) meets the outer loop first",
                c + 1
            ));
        }
        cuts.push(Cut {
            from: ends[0],
            to: ends[1],
            radial: false,
        });
    }
    // Sector i, between cuts i − 1 and i, holds hole i: corners (inner, outer) of cut i − 1,
    // then of cut i, counterclockwise.
    let parts: Vec<Part> = (0..n)
        .map(|i| {
            let j = (i + n - 1) % n;
            let (a, b) = (cuts[j], cuts[i]);
            (
                spans[i].2,
                (
                    [a.from, a.to, b.to, b.from],
                    [
                        Side::Cut { c: j, rev: false },
                        Side::Loop {
                            l: 0,
                            a: a.to.p,
                            b: b.to.p,
                            forward: ccw[0],
                        },
                        Side::Cut { c: i, rev: true },
                        Side::Loop {
                            l: c,
                            a: b.from.p,
                            b: a.from.p,
                            forward: !ccw[c],
                        },
                    ],
                ),
            )
        })
        .collect();
    rings(loops, ccw, scale, orientation, polys, cuts, parts)
}
