//! The straight (u, v) lines that cut a face with several holes into strips of one hole each
//! ([`super::holes`], issue #14), in the scaled (u, v) plane.
//!
//! First the old rule: lines u = const (or v = const, whichever direction separates the holes
//! by the widest gaps) halfway between neighbouring holes. Where no such line set works (the
//! holes overlap in both u and v, as on a bolt circle or holes staggered diagonally, or a
//! line crosses the outer loop more than twice) parallel lines in an oblique direction are
//! tried: every direction of [`ANGLES`] steps over 180°, the holes ordered by their extent
//! along its normal, kept if each gap between consecutive holes is open and each line
//! halfway across it crosses the outer loop twice, widest narrowest gap first.

use super::trim::LoopPoint;

/// The straight line n · q = c, n a unit vector (or a coordinate axis).
#[derive(Clone, Copy, Debug)]
pub(super) struct Line {
    pub n: [f64; 2],
    pub c: f64,
}

impl Line {
    /// Signed distance of `q` from the line (positive on the side `n` points to).
    pub fn f(&self, q: [f64; 2]) -> f64 {
        q[0] * self.n[0] + q[1] * self.n[1] - self.c
    }
}

/// A way to cut the face into strips: the holes (loop numbers) in strip order and the line
/// between each two consecutive ones, its normal pointing towards the later hole.
pub(super) type Strips = (Vec<usize>, Vec<Line>);

/// Directions tried for oblique cuts (1° apart over 180°).
pub(super) const ANGLES: usize = 180;
/// Most oblique directions tried for one face (widest gaps first).
const TRIES: usize = 6;

/// The hole extents along `n`: for each hole h ≥ 1 its smallest and largest n · q.
fn extents(polys: &[Vec<(LoopPoint, [f64; 2])>], n: [f64; 2]) -> Vec<[f64; 2]> {
    polys[1..]
        .iter()
        .map(|p| {
            p.iter()
                .fold([f64::INFINITY, f64::NEG_INFINITY], |e, (_, q)| {
                    let x = q[0] * n[0] + q[1] * n[1];
                    [e[0].min(x), e[1].max(x)]
                })
        })
        .collect()
}

/// Holes ordered along `n` with the narrowest gap between consecutive ones and the lines
/// halfway across each gap (the line through the middle of the gap, normal `n`).
fn along(polys: &[Vec<(LoopPoint, [f64; 2])>], n: [f64; 2]) -> (f64, Strips) {
    let ext = extents(polys, n);
    let mut order: Vec<usize> = (1..polys.len()).collect();
    order.sort_by(|x, y| ext[*x - 1][0].total_cmp(&ext[*y - 1][0]));
    let gap = order
        .windows(2)
        .map(|w| ext[w[1] - 1][0] - ext[w[0] - 1][1])
        .fold(f64::INFINITY, f64::min);
    let lines = order
        .windows(2)
        .map(|w| Line {
            n,
            c: 0.5 * (ext[w[0] - 1][1] + ext[w[1] - 1][0]),
        })
        .collect();
    (gap, (order, lines))
}

/// Whether every line crosses the outer loop (polygon 0) exactly twice.
fn crosses_twice(polys: &[Vec<(LoopPoint, [f64; 2])>], lines: &[Line]) -> bool {
    lines
        .iter()
        .all(|l| crossings(&polys[0], |q| l.f(q)).len() == 2)
}

/// The line sets to try, in order: the old rule's u = const or v = const lines (if the holes
/// are separated in u or in v; whether they cross the outer loop twice is checked by the
/// caller, as before), then at most [`TRIES`] oblique directions whose lines all cross the
/// outer loop twice, widest narrowest gap first. `polys[0]` is the outer loop, the others
/// the holes (at least two).
pub(super) fn candidates(polys: &[Vec<(LoopPoint, [f64; 2])>]) -> Vec<Strips> {
    let bbox = |h: usize| {
        polys[h]
            .iter()
            .fold([[f64::INFINITY, f64::NEG_INFINITY]; 2], |mut b, (_, q)| {
                for d in 0..2 {
                    b[d] = [b[d][0].min(q[d]), b[d][1].max(q[d])];
                }
                b
            })
    };
    let nh = polys.len() - 1;
    let mut out = Vec::new();
    // The old rule: the axis whose narrowest gap between consecutive holes is widest.
    let mut best: Option<(f64, usize, Vec<usize>)> = None;
    for d in 0..2 {
        let mut order: Vec<usize> = (1..=nh).collect();
        order.sort_by(|x, y| bbox(*x)[d][0].total_cmp(&bbox(*y)[d][0]));
        let gap = order
            .windows(2)
            .map(|w| bbox(w[1])[d][0] - bbox(w[0])[d][1])
            .fold(f64::INFINITY, f64::min);
        if gap > 0.0 && best.as_ref().is_none_or(|b| gap > b.0) {
            best = Some((gap, d, order));
        }
    }
    if let Some((_, d, order)) = best {
        let mut n = [0.0; 2];
        n[d] = 1.0;
        let lines = order
            .windows(2)
            .map(|w| Line {
                n,
                c: 0.5 * (bbox(w[0])[d][1] + bbox(w[1])[d][0]),
            })
            .collect();
        out.push((order, lines));
    }
    // Oblique directions (the axes among them: their lines are the old rule's).
    let mut oblique: Vec<(f64, Strips)> = (0..ANGLES)
        .filter(|k| k % (ANGLES / 2) != 0)
        .map(|k| {
            let a = std::f64::consts::PI * k as f64 / ANGLES as f64;
            along(polys, [a.cos(), a.sin()])
        })
        .filter(|(gap, (_, lines))| *gap > 0.0 && crosses_twice(polys, lines))
        .collect();
    oblique.sort_by(|x, y| y.0.total_cmp(&x.0));
    out.extend(oblique.into_iter().take(TRIES).map(|x| x.1));
    out
}

/// The polygon segments where `f` changes sign, with whether it increases along the loop.
pub(super) fn crossings(
    poly: &[(LoopPoint, [f64; 2])],
    f: impl Fn([f64; 2]) -> f64,
) -> Vec<(usize, bool)> {
    let n = poly.len();
    (0..n)
        .filter_map(|k| {
            let (a, b) = (f(poly[k].1), f(poly[(k + 1) % n].1));
            ((a < 0.0) != (b < 0.0)).then_some((k, b > a))
        })
        .collect()
}
