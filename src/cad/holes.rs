//! A face with holes split into four-sided blocks (issue #14): the layout in the surface's
//! (u, v) plane, scaled by the outer loop's mean |x_u|, |x_v| so that it is close to isometric.
//!
//! - The outer loop is the loop of largest (u, v) area; every other loop is a hole and must lie
//!   inside it (holes on periodic surfaces are moved by whole periods next to the outer loop).
//! - Several holes: the face is cut into *strips* of one hole each by straight (u, v) lines
//!   u = const (or v = const, whichever direction separates the holes by the widest gaps),
//!   halfway between the holes; each line must cross the outer loop exactly twice. Where
//!   that fails, parallel oblique lines ([`super::hole_cuts`]), then a fan of cuts from a
//!   central hole into one-hole sectors ([`super::fan`]).
//! - Each strip has four corners: the ends of its cuts, and on the outer loop the convex
//!   vertices turning most (by more than 20°), else the points farthest from the chord of
//!   the stretch they split (a fillet's middle), else the middle of the longest stretch. A
//!   face with one hole is one strip with the corners of a one-loop face
//!   ([`FaceLoop::corners`], convex vertices first).
//! - Around each hole an O-type ring of four blocks: straight (u, v) cuts from four points on
//!   the hole (where the rays from its centroid to the strip's corners leave it) to the
//!   strip's corners. Block k is bounded by the hole (its E3: j = 0 on the hole), the cuts k
//!   and k + 1 (E2, E1, running from the hole outwards) and the strip's side k (E4).

use super::hole_cuts::{candidates, crossings, Strips};
use super::trim::{FaceLoop, LoopPoint, NS};
use super::uv::{at, centroid};

/// A side of a block, from one of its corners to the next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Side {
    /// Loop `l` (0 the outer loop) from `a` to `b`, along the loop's own direction if
    /// `forward`, else against it.
    Loop {
        l: usize,
        a: LoopPoint,
        b: LoopPoint,
        forward: bool,
    },
    /// Cut `c` of [`Layout::cuts`], from its end to its start if `rev`.
    Cut { c: usize, rev: bool },
}

impl Side {
    /// The same side run the other way.
    pub fn rev(self) -> Side {
        match self {
            Side::Loop { l, a, b, forward } => Side::Loop {
                l,
                a: b,
                b: a,
                forward: !forward,
            },
            Side::Cut { c, rev } => Side::Cut { c, rev: !rev },
        }
    }
}

/// A point of loop `l`: a corner of blocks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Node {
    pub l: usize,
    pub p: LoopPoint,
}

/// A straight (u, v) cut from one loop point to another. A cut between two strips runs along
/// the blocks' i direction (`radial` false), a cut from a hole outwards along j.
#[derive(Clone, Copy, Debug)]
pub(super) struct Cut {
    pub from: Node,
    pub to: Node,
    pub radial: bool,
}

/// The blocks of a face with holes.
pub(super) struct Layout {
    pub cuts: Vec<Cut>,
    /// Each block's sides E1, E2, E3, E4 (E1, E2 from E3's ends to E4's; E3, E4 in i order).
    pub blocks: Vec<[Side; 4]>,
}

/// Least turning of a strip corner at a vertex of the outer loop (radians, 20°).
const CORNER_TURN: f64 = 0.35;

/// A loop's polygon in scaled (u, v): every sample but each edge's last, with its loop point.
pub(super) fn polygon(lp: &FaceLoop, scale: [f64; 2]) -> Vec<(LoopPoint, [f64; 2])> {
    lp.edges
        .iter()
        .enumerate()
        .flat_map(|(edge, e)| {
            (0..NS).map(move |i| {
                let p = LoopPoint {
                    edge,
                    sigma: i as f64 / NS as f64,
                };
                (p, [e.uv[i][0] * scale[0], e.uv[i][1] * scale[1]])
            })
        })
        .collect()
}

fn inside(poly: &[(LoopPoint, [f64; 2])], x: [f64; 2]) -> bool {
    let n = poly.len();
    let mut c = false;
    for i in 0..n {
        let (p, q) = (poly[i].1, poly[(i + 1) % n].1);
        if (p[1] > x[1]) != (q[1] > x[1])
            && x[0] < p[0] + (q[0] - p[0]) * (x[1] - p[1]) / (q[1] - p[1])
        {
            c = !c;
        }
    }
    c
}

/// The loop point on polygon segment `k` (to the next sample) where `f` of the scaled
/// (u, v) changes sign, by bisection on the edge's arclength.
pub(super) fn locate(
    lp: &mut FaceLoop,
    poly: &[(LoopPoint, [f64; 2])],
    k: usize,
    scale: [f64; 2],
    f: impl Fn([f64; 2]) -> f64,
) -> Result<LoopPoint, String> {
    let p = poly[k].0;
    // The segment ends at the next sample of the same edge, else at the edge's end (also
    // where the polygon closes on a loop of one edge).
    let next = poly.get(k + 1).map(|q| q.0);
    let s1 = match next {
        Some(q) if q.edge == p.edge => q.sigma,
        _ => 1.0,
    };
    let (mut lo, mut hi) = (p.sigma, s1);
    let f0 = f(poly[k].1);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let v = f(at(
            lp,
            LoopPoint {
                edge: p.edge,
                sigma: mid,
            },
            scale,
        )?);
        if (v < 0.0) == (f0 < 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let sigma = 0.5 * (lo + hi);
    Ok(if sigma >= 1.0 {
        LoopPoint {
            edge: (p.edge + 1) % lp.len(),
            sigma: 0.0,
        }
    } else {
        LoopPoint {
            edge: p.edge,
            sigma,
        }
    })
}

/// Arclength position of a loop point from the loop's start.
fn position(lp: &FaceLoop, p: LoopPoint) -> f64 {
    (0..p.edge).map(|k| lp.length(k)).sum::<f64>() + p.sigma * lp.length(p.edge)
}

/// Arclength from `a` to `b` going along the loop if `forward`, else against it.
fn distance(lp: &FaceLoop, a: LoopPoint, b: LoopPoint, forward: bool) -> f64 {
    let total: f64 = (0..lp.len()).map(|k| lp.length(k)).sum();
    let d = if forward {
        position(lp, b) - position(lp, a)
    } else {
        position(lp, a) - position(lp, b)
    };
    d.rem_euclid(total)
}

/// Two more corners strictly between `a` and `b` on the outer loop (running `forward` along
/// it or not), in order: convex vertices turning by more than [`CORNER_TURN`], most first;
/// else the sample farthest from the chord of the stretch it splits (if by more than 5 % of
/// the chord), else the middle of the longest stretch.
fn two_corners(
    lp: &mut FaceLoop,
    (a, b): (LoopPoint, LoopPoint),
    forward: bool,
    ccw: bool,
    scale: [f64; 2],
) -> Result<Vec<LoopPoint>, String> {
    let span = distance(lp, a, b, forward);
    let inner = |lp: &FaceLoop, p: LoopPoint| {
        let d = distance(lp, a, p, forward);
        d > 1e-9 * span && d < span * (1.0 - 1e-9)
    };
    let mut cand: Vec<(f64, LoopPoint)> = (0..lp.len())
        .map(|edge| LoopPoint { edge, sigma: 0.0 })
        .filter(|p| inner(lp, *p))
        .map(|p| (lp.turning(p.edge), p))
        .filter(|(t, p)| *t > CORNER_TURN && !lp.reentrant(p.edge, ccw))
        .collect();
    cand.sort_by(|x, y| y.0.total_cmp(&x.0));
    let mut pts: Vec<LoopPoint> = cand.into_iter().take(2).map(|c| c.1).collect();
    let poly = polygon(lp, scale);
    while pts.len() < 2 {
        let mut ends = vec![a];
        pts.sort_by(|x, y| distance(lp, a, *x, forward).total_cmp(&distance(lp, a, *y, forward)));
        ends.extend(&pts);
        ends.push(b);
        let mut best: Option<(f64, LoopPoint)> = None;
        let mut longest = (0.0, a);
        for w in ends.windows(2) {
            let (x, y) = (w[0], w[1]);
            let len = distance(lp, x, y, forward);
            if len > longest.0 {
                let mid = if forward { x } else { y };
                longest = (len, lp.advance(mid, 0.5 * len));
            }
            let (px, py) = (at(lp, x, scale)?, at(lp, y, scale)?);
            let chord = [py[0] - px[0], py[1] - px[1]];
            let cl = chord[0].hypot(chord[1]);
            for (p, q) in &poly {
                let d = distance(lp, x, *p, forward);
                if d <= 1e-9 * len || d >= len * (1.0 - 1e-9) || cl == 0.0 {
                    continue;
                }
                let h = ((q[0] - px[0]) * chord[1] - (q[1] - px[1]) * chord[0]).abs() / cl;
                if h > 0.05 * cl && best.is_none_or(|b| h > b.0) {
                    best = Some((h, *p));
                }
            }
        }
        pts.push(best.map_or(longest.1, |b| b.1));
    }
    pts.sort_by(|x, y| distance(lp, a, *x, forward).total_cmp(&distance(lp, a, *y, forward)));
    Ok(pts)
}

/// The layout of a face whose loops are `loops` (the outer one first, holes already moved
/// next to it), in (u, v) scaled by `scale`; `ccw[l]`: loop l runs counterclockwise. Blocks
/// run counterclockwise in (u, v) if `orientation` (the face's normal is the surface's), else
/// clockwise (mirrored).
///
/// # Errors
/// Why the face cannot be split this way (holes not separable by straight cuts, a cut
/// crossing the outer loop more than twice, a hole not star-shaped about its centroid).
pub(super) fn layout(
    loops: &mut [FaceLoop],
    ccw: &[bool],
    scale: [f64; 2],
    orientation: bool,
    last: Fallback,
) -> Result<Layout, String> {
    let nh = loops.len() - 1;
    let polys: Vec<_> = loops.iter().map(|lp| polygon(lp, scale)).collect();
    for h in 1..=nh {
        if !inside(&polys[0], polys[h][0].1) {
            return Err(format!(
                "loop {} (a hole) does not lie inside the outer loop",
                h + 1
            ));
        }
    }
    if nh == 1 {
        return strips(
            loops,
            ccw,
            scale,
            orientation,
            &polys,
            (vec![1], Vec::new()),
        );
    }
    // The old rule's u = const or v = const lines first, then oblique ones: the first line
    // set whose strips and rings can be made (faces split before keep their blocks).
    let mut first = None;
    for cand in candidates(&polys) {
        match strips(loops, ccw, scale, orientation, &polys, cand) {
            Ok(lay) => return Ok(lay),
            Err(e) => {
                first.get_or_insert(e);
            }
        }
    }
    // Last, `last` (the caller's fan of cuts about a central hole: a flange's bore and its
    // bolt circle).
    if let Ok(lay) = last(loops, ccw, scale, orientation, &polys) {
        return Ok(lay);
    }
    Err(first.unwrap_or_else(|| {
        "the holes overlap in every direction: no straight (u, v) cuts separate them, nor a fan \
         of cuts about a central hole"
            .into()
    }))
}

/// The layout of strips cut by `lines` between the holes `order` (a single hole: one strip
/// with the outer loop's corners), an O-type ring of four blocks in each.
fn strips(
    loops: &mut [FaceLoop],
    ccw: &[bool],
    scale: [f64; 2],
    orientation: bool,
    polys: &[Vec<(LoopPoint, [f64; 2])>],
    (order, lines): Strips,
) -> Result<Layout, String> {
    let nh = order.len();
    let outer_ccw = ccw[0];
    let mut cuts: Vec<Cut> = Vec::new();
    // Strip corners and sides, counterclockwise in (u, v).
    let mut strips: Vec<([Node; 4], [Side; 4])> = Vec::new();
    let node = |p: LoopPoint| Node { l: 0, p };
    let along = |a: LoopPoint, b: LoopPoint| Side::Loop {
        l: 0,
        a,
        b,
        forward: outer_ccw,
    };
    if nh == 1 {
        let (mut c, _) = loops[0].corners(Some(1e-3));
        // a corner behind a wall of the outer loop: corners the hole sees (only there, so
        // every face whose cuts are clear keeps its blocks)
        if super::visible::hidden(loops, polys, &c, scale)? {
            if let Some(v) = super::visible::corners(loops, polys, scale, outer_ccw)? {
                c = v;
            }
        }
        let c = if outer_ccw {
            c
        } else {
            [c[0], c[3], c[2], c[1]]
        };
        strips.push((
            c.map(node),
            [0, 1, 2, 3].map(|k| along(c[k], c[(k + 1) % 4])),
        ));
    } else {
        // Cut s (between the holes order[s] and order[s + 1]) from P+ to P−: where the outer
        // loop, run counterclockwise, crosses the line with the coordinate increasing (P+)
        // and decreasing (P−).
        let mut ends = Vec::new();
        for (w, line) in order.windows(2).zip(&lines) {
            let f = |q: [f64; 2]| line.f(q);
            let x = crossings(&polys[0], f);
            if x.len() != 2 {
                return Err(format!(
                    "the cut between holes (loops {} and {}) crosses the outer loop {} times, \
                     not twice",
                    w[0] + 1,
                    w[1] + 1,
                    x.len()
                ));
            }
            let mut plus = None;
            let mut minus = None;
            for (k, up) in x {
                let p = locate(&mut loops[0], &polys[0], k, scale, f)?;
                if up == outer_ccw {
                    plus = Some(p);
                } else {
                    minus = Some(p);
                }
            }
            let (Some(p), Some(m)) = (plus, minus) else {
                return Err("a cut between holes does not cross the outer loop".into());
            };
            cuts.push(Cut {
                from: node(p),
                to: node(m),
                radial: false,
            });
            ends.push((p, m));
        }
        let last = ends.len() - 1;
        for s in 0..nh {
            let strip = if s == 0 {
                let (p, m) = ends[0];
                let x = two_corners(&mut loops[0], (m, p), outer_ccw, outer_ccw, scale)?;
                (
                    [m, x[0], x[1], p].map(node),
                    [
                        along(m, x[0]),
                        along(x[0], x[1]),
                        along(x[1], p),
                        Side::Cut { c: 0, rev: false },
                    ],
                )
            } else if s == nh - 1 {
                let (p, m) = ends[last];
                let x = two_corners(&mut loops[0], (p, m), outer_ccw, outer_ccw, scale)?;
                (
                    [p, x[0], x[1], m].map(node),
                    [
                        along(p, x[0]),
                        along(x[0], x[1]),
                        along(x[1], m),
                        Side::Cut { c: last, rev: true },
                    ],
                )
            } else {
                let ((p0, m0), (p1, m1)) = (ends[s - 1], ends[s]);
                (
                    [p0, p1, m1, m0].map(node),
                    [
                        along(p0, p1),
                        Side::Cut { c: s, rev: false },
                        along(m1, m0),
                        Side::Cut {
                            c: s - 1,
                            rev: true,
                        },
                    ],
                )
            };
            strips.push(strip);
        }
    }
    let strips = order.iter().copied().zip(strips).collect();
    rings(loops, ccw, scale, orientation, polys, cuts, strips)
}

/// A layout tried where no line set works: loops, ccw, scale, orientation as
/// [`layout`]'s, and the loops' polygons.
pub(super) type Fallback = fn(
    &mut [FaceLoop],
    &[bool],
    [f64; 2],
    bool,
    &[Vec<(LoopPoint, [f64; 2])>],
) -> Result<Layout, String>;

/// A part of a face holding one hole: the hole's loop, the part's four corners and its four
/// sides (side k from corner k to corner k + 1), counterclockwise in (u, v).
pub(super) type Part = (usize, ([Node; 4], [Side; 4]));

/// The layout of `parts` (cut from the face by `cuts`): an O-type ring of four blocks
/// around each part's hole, the cuts from the hole to the part's corners added to `cuts`.
pub(super) fn rings(
    loops: &mut [FaceLoop],
    ccw: &[bool],
    scale: [f64; 2],
    orientation: bool,
    polys: &[Vec<(LoopPoint, [f64; 2])>],
    mut cuts: Vec<Cut>,
    parts: Vec<Part>,
) -> Result<Layout, String> {
    let mut blocks = Vec::new();
    for (h, (corners, sides)) in parts {
        let ring = ring(loops, polys, h, &corners, scale)?;
        let first = cuts.len();
        for k in 0..4 {
            cuts.push(Cut {
                from: Node { l: h, p: ring[k] },
                to: corners[k],
                radial: true,
            });
        }
        for k in 0..4 {
            let k1 = (k + 1) % 4;
            // Counterclockwise: hole point k+1 → hole point k → corner k → corner k+1.
            let q = [
                Side::Loop {
                    l: h,
                    a: ring[k1],
                    b: ring[k],
                    forward: !ccw[h],
                },
                Side::Cut {
                    c: first + k,
                    rev: false,
                },
                sides[k],
                Side::Cut {
                    c: first + k1,
                    rev: true,
                },
            ];
            let q = if orientation {
                q
            } else {
                [q[0].rev(), q[3].rev(), q[2].rev(), q[1].rev()]
            };
            blocks.push([q[3].rev(), q[1], q[0], q[2].rev()]);
        }
    }
    Ok(Layout { cuts, blocks })
}

/// The four points on hole `h` where the rays from its centroid to the strip's corners leave
/// it; the corners must turn once around the centroid, counterclockwise, and each ray must
/// leave the hole once.
fn ring(
    loops: &mut [FaceLoop],
    polys: &[Vec<(LoopPoint, [f64; 2])>],
    h: usize,
    corners: &[Node; 4],
    scale: [f64; 2],
) -> Result<[LoopPoint; 4], String> {
    let m = centroid(&polys[h]);
    let mut dirs = [[0.0; 2]; 4];
    for (k, c) in corners.iter().enumerate() {
        let q = at(&mut loops[c.l], c.p, scale)?;
        dirs[k] = [q[0] - m[0], q[1] - m[1]];
    }
    let turns = (0..4).map(|k| {
        let (a, b) = (dirs[k], dirs[(k + 1) % 4]);
        (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1])
    });
    // Each turn counterclockwise in (0, 2π): a corner may lie more than half a turn on (a
    // part's side running round a corner of the outer loop past the hole), as long as the
    // four go once around.
    let turn: f64 = turns
        .map(|t| match t {
            t if t > 0.0 => t,
            t if t < 0.0 => t + std::f64::consts::TAU,
            _ => f64::NAN,
        })
        .sum();
    if (turn - std::f64::consts::TAU).abs().partial_cmp(&1e-6) != Some(std::cmp::Ordering::Less) {
        return Err(format!(
            "the corners of the blocks around hole (loop {}) do not surround it in order",
            h + 1
        ));
    }
    let mut out = [LoopPoint {
        edge: 0,
        sigma: 0.0,
    }; 4];
    for (k, r) in dirs.iter().enumerate() {
        // Side of the ray's line, on the half-plane ahead of the centroid.
        let f = |q: [f64; 2]| (q[0] - m[0]) * r[1] - (q[1] - m[1]) * r[0];
        let ahead = |q: [f64; 2]| (q[0] - m[0]) * r[0] + (q[1] - m[1]) * r[1] > 0.0;
        let poly = &polys[h];
        let x: Vec<usize> = crossings(poly, f)
            .into_iter()
            .map(|c| c.0)
            .filter(|&i| ahead(poly[i].1) || ahead(poly[(i + 1) % poly.len()].1))
            .collect();
        if x.len() != 1 {
            return Err(format!(
                "hole (loop {}) is not star-shaped about its centroid: a ray to a block corner \
                 leaves it {} times",
                h + 1,
                x.len()
            ));
        }
        out[k] = locate(&mut loops[h], poly, x[0], scale, f)?;
    }
    Ok(out)
}
