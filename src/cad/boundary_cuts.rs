//! Cuts of an untrimmed patch at defects of its boundary, tried (with its creases,
//! [`super::crease`]) when its one block folds:
//!
//! - **Fold-backs.** A patch whose side runs past its end corner and comes back to it (a
//!   spike: OpenVSP's supersonic model writes end caps whose radial sides are quartics
//!   overshooting their last control point, so the patch covers a strip next to that side
//!   twice, once each way). Its boundary nodes then run out and back along the spike and the
//!   cells at the corner fold, whatever the solve. Where the side passes through the end
//!   corner at an interior parameter t_s, heading the other way from how it arrives at the
//!   end, and the iso-line t_s lies within [`FOLD_NEAR`] of the end side, the piece between
//!   them is a flap folded over the rest: the patch is cut at t_s (a knot inserted there) and
//!   the flap left out. The rest covers the face's region once; its block's nodes on the cut
//!   are then moved onto the end side at the same parameters ([`snap_fold_backs`]), so that
//!   the grid ends on the face's own edge (OpenVSP's flaps are not exact: the iso-line is
//!   3.6e-4 to 1.5e-3 of the patch's diameter off that edge, a sixth of a cell at 33 nodes).
//! - **Kinks.** A C0 iso-line of a patch without creases at which one of the two sides it
//!   ends on turns by more than [`KINK_TURN`] (a cranked wing's leading edge in one flat
//!   bilinear patch): a block corner belongs there, and the side turning inside a block's
//!   side folds the cells next to it where the turn is reentrant.

use super::crease::{Crease, CutKind};
use crate::grid::Edge;
use crate::surface::pipeline::SurfaceResult;
use ellipgrid_geometry::{BSplineSurf, Surface, Vec3};

/// Smallest turn (degrees) of a side at a C0 knot that makes the knot's iso-line a cut.
pub const KINK_TURN: f64 = 15.0;

/// Samples along a side in the search for its return to the end corner.
const SAMPLES: usize = 1024;

/// Largest distance (relative to the patch's diameter) between the side's return point and
/// its end corner (and between the two sides of a kink).
const FOLD_MATCH: f64 = 1e-7;

/// Largest distance (relative to the patch's diameter) between the iso-line at a side's
/// return point and the end side, for a fold-back.
pub const FOLD_NEAR: f64 = 2e-3;

/// Smallest excursion of the spike (relative to the diameter): a side that stays within it
/// of its end corner (a pole) has no fold-back.
const SPIKE: f64 = 1e-5;

/// The point of `s` at parameter `t` along direction `d` on the side `o` across it.
fn at(s: &BSplineSurf, d: usize, t: f64, o: f64) -> Vec3 {
    if d == 0 {
        s.point(t, o)
    } else {
        s.point(o, t)
    }
}

/// The derivative along `d` at (`t`, `o`).
fn along(s: &BSplineSurf, d: usize, t: f64, o: f64) -> Vec3 {
    if d == 0 {
        s.eval(t, o).xu
    } else {
        s.eval(o, t).xv
    }
}

/// The parameter at which the side `o` (across direction `d`) returns to its corner at
/// `end` after a spike, if it does (module docs).
fn return_point(s: &BSplineSurf, d: usize, end: f64, o: f64, size: f64) -> Option<f64> {
    let corner = at(s, d, end, o);
    let dist = |t: f64| (at(s, d, t, o) - corner).norm();
    // from the end corner inward
    let t = |m: usize| {
        let x = m as f64 / SAMPLES as f64;
        if end == 1.0 {
            1.0 - x
        } else {
            x
        }
    };
    let mut far = 0.0f64;
    let mut prev = 0.0;
    for m in 1..SAMPLES {
        let here = dist(t(m));
        let next = dist(t(m + 1));
        far = far.max(here);
        if far > SPIKE * size && here <= prev && here <= next && here < 0.1 * far {
            // golden-section search for the minimum between the neighbours
            let (mut a, mut b) = (t(m - 1), t(m + 1));
            let g = (5f64.sqrt() - 1.0) / 2.0;
            for _ in 0..200 {
                let (c, e) = (b - g * (b - a), a + g * (b - a));
                if dist(c) < dist(e) {
                    b = e;
                } else {
                    a = c;
                }
                if (b - a).abs() < 1e-15 {
                    break;
                }
            }
            let ts = 0.5 * (a + b);
            return (dist(ts) <= FOLD_MATCH * size).then_some(ts);
        }
        prev = here;
    }
    None
}

/// The fold-back lines of `s` (module docs), at most one per end of each direction.
pub fn fold_backs(s: &BSplineSurf, size: f64) -> Vec<Crease> {
    let mut out = Vec::new();
    for d in 0..2 {
        for end in [0u8, 1] {
            let e = f64::from(end);
            let found: Vec<(f64, f64)> = [0.0, 1.0]
                .into_iter()
                .filter_map(|o| return_point(s, d, e, o, size).map(|t| (o, t)))
                .collect();
            let Some(&(o, ts)) = found.first() else {
                continue;
            };
            if found.iter().any(|(_, t)| (t - ts).abs() > 1e-6) || !(ts > 0.0 && ts < 1.0) {
                continue;
            }
            // heading away from the end side at t_s, towards it at the end
            let (a, b) = (along(s, d, ts, o), along(s, d, e, o));
            if a.dot(&b) >= 0.0 {
                continue;
            }
            // the iso-line t_s is the end side
            let same = (0..=64).all(|m| {
                let x = m as f64 / 64.0;
                (at(s, d, ts, x) - at(s, d, e, x)).norm() <= FOLD_NEAR * size
            });
            if same {
                out.push(Crease {
                    dir: d,
                    at: ts,
                    turn: [180.0; 2],
                    kind: CutKind::FoldBack { end },
                });
            }
        }
    }
    out
}

/// The kink lines of `s` (module docs): C0 knots at which a side turns by more than
/// [`KINK_TURN`], with the turns of the two sides (smaller, larger).
pub fn kinks(s: &BSplineSurf, size: f64) -> Vec<Crease> {
    let mut out = Vec::new();
    for d in 0..2 {
        for at_knot in s.c0_knots(d) {
            let Ok(p) = s.split_at(d, &[at_knot]) else {
                continue;
            };
            let mut turns = Vec::with_capacity(2);
            for o in [0.0, 1.0] {
                if (at(&p[0], d, 1.0, o) - at(&p[1], d, 0.0, o)).norm() > FOLD_MATCH * size {
                    turns.clear();
                    break; // a gap, not a kink
                }
                let (a, b) = (along(&p[0], d, 1.0, o), along(&p[1], d, 0.0, o));
                if a.norm() > 0.0 && b.norm() > 0.0 {
                    let c = a.dot(&b) / (a.norm() * b.norm());
                    turns.push(c.clamp(-1.0, 1.0).acos().to_degrees());
                }
            }
            let big = turns.iter().copied().fold(0.0, f64::max);
            if big > KINK_TURN {
                let small = turns.iter().copied().fold(f64::INFINITY, f64::min);
                out.push(Crease {
                    dir: d,
                    at: at_knot,
                    turn: [small, big],
                    kind: CutKind::Kink,
                });
            }
        }
    }
    out
}

/// Moves the nodes of each block on a fold-back cut onto the patch's end side there, at the
/// same parameter along it (module docs). `blocks[a][b]` is the result index of the
/// sub-patch a-th in u, b-th in v (none if left out), `cuts` the patch's cut lines.
pub(super) fn snap_fold_backs(
    s: &BSplineSurf,
    cuts: &[Crease],
    blocks: &[Vec<Option<usize>>],
    results: &mut [SurfaceResult],
) {
    // the pieces' parameter ranges in each direction
    let ends = |d: usize| -> Vec<f64> {
        let mut e = vec![0.0];
        e.extend(cuts.iter().filter(|c| c.dir == d).map(|c| c.at));
        e.push(1.0);
        e
    };
    let (eu, ev) = (ends(0), ends(1));
    for c in cuts {
        let CutKind::FoldBack { end } = c.kind else {
            continue;
        };
        let n = if c.dir == 0 { eu.len() } else { ev.len() } - 1;
        // the kept piece next to the flap, and its side on the cut
        let (next, side) = match (c.dir, end) {
            (0, 1) => (n - 2, Edge::E2),
            (0, _) => (1, Edge::E1),
            (_, 1) => (n - 2, Edge::E4),
            _ => (1, Edge::E3),
        };
        for (a, row) in blocks.iter().enumerate() {
            for (b, id) in row.iter().enumerate() {
                let Some(k) = *id else { continue };
                if (c.dir == 0 && a != next) || (c.dir == 1 && b != next) {
                    continue;
                }
                let r = &mut results[k];
                let (ni, nj) = (r.grid.ni(), r.grid.nj());
                let count = if side.index() < 2 { nj } else { ni };
                for m in 0..count {
                    let (i, j) = match side {
                        Edge::E1 => (0, m),
                        Edge::E2 => (ni - 1, m),
                        Edge::E3 => (m, 0),
                        Edge::E4 => (m, nj - 1),
                    };
                    let [pu, pv] = r.uv[r.grid.idx(i, j)];
                    let u = eu[a] + pu * (eu[a + 1] - eu[a]);
                    let v = ev[b] + pv * (ev[b + 1] - ev[b]);
                    let e = f64::from(end);
                    let p = if c.dir == 0 {
                        s.point(e, v)
                    } else {
                        s.point(u, e)
                    };
                    r.grid.set(i, j, [p.x, p.y, p.z]);
                }
            }
        }
    }
}
