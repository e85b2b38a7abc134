//! The parts of a one-loop face cut by straight (u, v) cuts, as four-sided blocks (issue #14):
//! a part's boundary is a cycle of [`Piece`]s (loop stretches and cuts); [`four`] makes up its
//! four sides (cut ends are corners, then the convex vertices turning most, else the middles
//! of the longest loop stretches) and [`assign`] orients the blocks so that every cut runs along
//! the same grid direction in both its blocks. Shared by the reentrant-vertex cuts
//! ([`super::reentrant`]) and the chords ([`super::chords`]), with the loop-walking helpers
//! (arclength positions along the loop, scaled (u, v) of a loop point).

use super::holes::{Cut, Layout, Node, Side};
use super::trim::{FaceLoop, LoopPoint};

/// Least outward (reentrant) or inward (corner) turning of a vertex that counts (radians, 20°).
pub(super) const TURN: f64 = 0.35;
/// A piece of a part's boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Piece {
    /// The loop forwards from the first point to the second (the whole loop if they are equal).
    Loop(LoopPoint, LoopPoint),
    /// Cut `c`, from its end to its start if `rev`.
    Cut(usize, bool),
}

/// Arclength of a loop point from the loop's start.
pub(super) fn position(lp: &FaceLoop, p: LoopPoint) -> f64 {
    (0..p.edge).map(|k| lp.length(k)).sum::<f64>() + p.sigma * lp.length(p.edge)
}

/// The loop's length.
fn total(lp: &FaceLoop) -> f64 {
    (0..lp.len()).map(|k| lp.length(k)).sum()
}

/// Arclength from `a` forwards to `p`.
pub(super) fn ahead(lp: &FaceLoop, a: LoopPoint, p: LoopPoint) -> f64 {
    (position(lp, p) - position(lp, a)).rem_euclid(total(lp))
}

/// Whether `p` lies strictly inside the loop stretch from `a` forwards to `b`.
pub(super) fn within(lp: &FaceLoop, (a, b): (LoopPoint, LoopPoint), p: LoopPoint) -> bool {
    let t = total(lp);
    let span = if a == b { t } else { ahead(lp, a, b) };
    let d = ahead(lp, a, p);
    d > 1e-9 * t && d < span - 1e-9 * t
}

/// (u, v) of a loop point, scaled.
pub(super) fn at(lp: &mut FaceLoop, p: LoopPoint) -> std::result::Result<[f64; 2], String> {
    let s = lp.metric_scale();
    let (_, w) = lp.sample(p, p, &[0.0])?;
    Ok([w[0][0] * s[0], w[0][1] * s[1]])
}

pub(super) fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

pub(super) fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// `pieces` with Loop pieces that meet merged.
pub(super) fn merged(pieces: Vec<Piece>) -> Vec<Piece> {
    let mut out: Vec<Piece> = Vec::with_capacity(pieces.len());
    for p in pieces {
        match (out.last_mut(), p) {
            (Some(Piece::Loop(_, b)), Piece::Loop(c, d)) if *b == c => *b = d,
            _ => out.push(p),
        }
    }
    out
}

/// A part's four sides in loop order: its pieces, loop pieces split at added corners.
pub(super) fn four(
    lp: &FaceLoop,
    mut pieces: Vec<Piece>,
    ccw: bool,
) -> std::result::Result<[Piece; 4], String> {
    if pieces.len() > 4 {
        return Err(format!(
            "a part between cuts has {} cut ends: not a four-sided block",
            pieces.len()
        ));
    }
    while pieces.len() < 4 {
        let inside = |v: LoopPoint| {
            pieces.iter().position(|p| match *p {
                Piece::Loop(a, b) => within(lp, (a, b), v),
                Piece::Cut(..) => false,
            })
        };
        let corner = (0..lp.len())
            .filter(|&k| !lp.reentrant(k, ccw) && lp.turning(k) > TURN)
            .filter_map(|k| {
                let v = LoopPoint {
                    edge: k,
                    sigma: 0.0,
                };
                inside(v).map(|i| (lp.turning(k), i, v))
            })
            .max_by(|x, y| x.0.total_cmp(&y.0));
        let (i, v) = match corner {
            Some((_, i, v)) => (i, v),
            None => {
                let longest = pieces
                    .iter()
                    .enumerate()
                    .filter_map(|(i, p)| match *p {
                        Piece::Loop(a, b) => Some((lp.chain_length(a, b), i, a)),
                        Piece::Cut(..) => None,
                    })
                    .max_by(|x, y| x.0.total_cmp(&y.0))
                    .ok_or("a part between cuts has no loop stretch")?;
                (longest.1, lp.advance(longest.2, 0.5 * longest.0))
            }
        };
        let Piece::Loop(a, b) = pieces[i] else {
            unreachable!("corners are added on loop pieces")
        };
        pieces.splice(i..=i, [Piece::Loop(a, v), Piece::Loop(v, b)]);
    }
    Ok([pieces[0], pieces[1], pieces[2], pieces[3]])
}

/// The layout: each block's sides rotated so that every cut runs along the same grid
/// direction in both its blocks (a walk over the tree of blocks joined by cuts).
pub(super) fn assign(cuts: Vec<(LoopPoint, LoopPoint)>, parts: Vec<[Piece; 4]>) -> Layout {
    let (nc, nb) = (cuts.len(), parts.len());
    // (block, side) of each cut's two occurrences.
    let mut at: Vec<Vec<(usize, usize)>> = vec![Vec::new(); nc];
    for (b, sides) in parts.iter().enumerate() {
        for (k, s) in sides.iter().enumerate() {
            if let Piece::Cut(c, _) = s {
                at[*c].push((b, k));
            }
        }
    }
    let mut rot: Vec<Option<usize>> = vec![None; nb];
    rot[0] = Some(0);
    for _ in 0..nb {
        for occ in &at {
            if let [(b0, k0), (b1, k1)] = occ[..] {
                match (rot[b0], rot[b1]) {
                    (Some(r), None) => rot[b1] = Some((k0 + r + k1) % 2),
                    (None, Some(r)) => rot[b0] = Some((k1 + r + k0) % 2),
                    _ => {}
                }
            }
        }
    }
    let rot: Vec<usize> = rot.into_iter().map(|r| r.unwrap_or(0)).collect();
    let side = |p: Piece| match p {
        Piece::Loop(a, b) => Side::Loop {
            l: 0,
            a,
            b,
            forward: true,
        },
        Piece::Cut(c, rev) => Side::Cut { c, rev },
    };
    let radial: Vec<bool> = at
        .iter()
        .map(|occ| occ.first().is_some_and(|&(b, k)| (k + rot[b]) % 2 == 1))
        .collect();
    let blocks = parts
        .iter()
        .zip(&rot)
        .map(|(s, &r)| {
            let s = |k: usize| side(s[(k + r) % 4]);
            [s(3).rev(), s(1), s(0), s(2).rev()]
        })
        .collect();
    let node = |p: LoopPoint| Node { l: 0, p };
    let cuts = cuts
        .into_iter()
        .zip(radial)
        .map(|((a, b), radial)| Cut {
            from: node(a),
            to: node(b),
            radial,
        })
        .collect();
    Layout { cuts, blocks }
}
