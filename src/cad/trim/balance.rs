//! Corner sets of a face's loop ranked by how well they make a four-sided block face (issue
//! #14): for faces whose corners by turning angle ([`FaceLoop::corners`]) fold, e.g. a thin
//! band whose most-turning vertices pair a long side with a short one, or a three-edge face
//! whose fourth corner sits badly.
//!
//! Candidate corners are the loop's vertices that do not turn outwards and points inside its
//! longest edges (at 1/4, 1/2, 3/4 of their arclength, where the loop does not bend
//! outwards). A set of four, in loop order, costs
//!
//! ```text
//! |ln(L0 / L2)| + |ln(L1 / L3)| + Σ |90° − interior angle| / 90°
//! ```
//!
//! with L0..L3 the 3D arclengths of its four sides (opposite sides balanced) and the interior
//! angle of the loop at each corner (180° inside an edge): a rectangle's corners cost 0.

use super::{FaceLoop, LoopPoint};
use std::f64::consts::FRAC_PI_2;

/// Most vertices taken as candidates (those with the interior angles nearest 90°).
const MAX_VERTICES: usize = 24;
/// Edges whose inner points are candidates (the longest).
const MAX_EDGES: usize = 8;
/// Fractions of an edge's arclength where inner candidates sit.
const INNER: [f64; 3] = [0.25, 0.5, 0.75];
/// A vertex turning outwards by more than this (radians) is never a corner.
const OUTWARD: f64 = 1e-3;

/// A candidate corner: the loop point, its arclength from the loop's start, its cost and its
/// turning angle (degrees; 0 inside an edge).
#[derive(Clone, Copy)]
pub(super) struct Candidate {
    pub at: LoopPoint,
    pub pos: f64,
    pub cost: f64,
    pub deg: f64,
}

impl FaceLoop<'_> {
    /// Up to `count` corner sets (corners in loop order, their turning angles in degrees as
    /// [`FaceLoop::corners`] gives them), cheapest first, each differing from the ones before
    /// in at least one corner's vertex or edge; none for a loop through a pole.
    pub fn balanced_corners(&self, count: usize) -> Vec<([LoopPoint; 4], [f64; 4])> {
        if self.pole.is_some() || count == 0 {
            return Vec::new();
        }
        let Some((cands, total)) = self.candidates() else {
            return Vec::new();
        };
        let ranked = rank(&cands, total);
        let mut out: Vec<([LoopPoint; 4], [f64; 4])> = Vec::with_capacity(count);
        let mut picked: Vec<[usize; 4]> = Vec::with_capacity(count);
        for (_, set) in ranked {
            let alike = |p: &[usize; 4]| {
                (0..4).all(|i| {
                    cands[p[i]].at.edge == cands[set[i]].at.edge
                        && (cands[p[i]].at.sigma == 0.0) == (cands[set[i]].at.sigma == 0.0)
                })
            };
            if picked.iter().any(alike) {
                continue;
            }
            picked.push(set);
            out.push((set.map(|i| cands[i].at), set.map(|i| cands[i].deg)));
            if out.len() == count {
                break;
            }
        }
        out
    }

    /// The candidate corners ([`Candidate`]) sorted by their position along the loop, and the
    /// loop's length; `None` for an empty loop or one without length.
    pub(super) fn candidates(&self) -> Option<(Vec<Candidate>, f64)> {
        let n = self.len();
        if n == 0 {
            return None;
        }
        let ccw = self.signed_area(self.scale) > 0.0;
        let starts: Vec<f64> = (0..n)
            .scan(0.0, |s, k| {
                let a = *s;
                *s += self.length(k);
                Some(a)
            })
            .collect();
        let total: f64 = (0..n).map(|k| self.length(k)).sum();
        if total.is_nan() || total <= 0.0 {
            return None;
        }
        let mut vertices: Vec<Candidate> = (0..n)
            .filter_map(|k| {
                let t = self.turning(k);
                if self.reentrant(k, ccw) && t > OUTWARD {
                    return None;
                }
                Some(Candidate {
                    at: LoopPoint {
                        edge: k,
                        sigma: 0.0,
                    },
                    pos: starts[k],
                    cost: (FRAC_PI_2 - t).abs() / FRAC_PI_2,
                    deg: t.to_degrees(),
                })
            })
            .collect();
        vertices.sort_by(|a, b| a.cost.total_cmp(&b.cost).then(a.at.edge.cmp(&b.at.edge)));
        vertices.truncate(MAX_VERTICES);
        let mut long: Vec<usize> = (0..n).collect();
        long.sort_by(|a, b| self.length(*b).total_cmp(&self.length(*a)).then(a.cmp(b)));
        long.truncate(MAX_EDGES);
        let mut cands = vertices;
        for &k in &long {
            for f in INNER {
                let at = LoopPoint { edge: k, sigma: f };
                if !self.bends_out(at, ccw) {
                    cands.push(Candidate {
                        at,
                        pos: starts[k] + f * self.length(k),
                        cost: 1.0,
                        deg: 0.0,
                    });
                }
            }
        }
        cands.sort_by(|a, b| a.pos.total_cmp(&b.pos));
        Some((cands, total))
    }
}

/// Every set of four candidates (indices into `c`, sorted by position along a loop of length
/// `total`) with four sides longer than 10⁻⁶ of the loop, cheapest first (ties: the earlier
/// set in lexicographic order). Keeps the 64 cheapest.
fn rank(c: &[Candidate], total: f64) -> Vec<(f64, [usize; 4])> {
    const KEEP: usize = 64;
    let m = c.len();
    let min = 1e-6 * total;
    let mut best: Vec<(f64, [usize; 4])> = Vec::with_capacity(KEEP + 1);
    for a in 0..m {
        for b in a + 1..m {
            let l0 = c[b].pos - c[a].pos;
            if l0 <= min {
                continue;
            }
            for d in b + 1..m {
                let l1 = c[d].pos - c[b].pos;
                if l1 <= min {
                    continue;
                }
                let partial = c[a].cost + c[b].cost + c[d].cost;
                for e in d + 1..m {
                    let l2 = c[e].pos - c[d].pos;
                    let l3 = total - (c[e].pos - c[a].pos);
                    if l2 <= min || l3 <= min {
                        continue;
                    }
                    let cost = (l0 / l2).ln().abs() + (l1 / l3).ln().abs() + partial + c[e].cost;
                    if best.len() == KEEP && cost >= best[KEEP - 1].0 {
                        continue;
                    }
                    let at = best.partition_point(|x| x.0 <= cost);
                    best.insert(at, (cost, [a, b, d, e]));
                    best.truncate(KEEP);
                }
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cand(pos: f64, cost: f64) -> Candidate {
        Candidate {
            at: LoopPoint {
                edge: 0,
                sigma: 0.0,
            },
            pos,
            cost,
            deg: 0.0,
        }
    }

    /// A 10 × 1 rectangle's loop with its four right-angled corners and three more candidates
    /// (a 45° chamfer-like vertex and two points inside the long sides): the rectangle's own
    /// corners cost 0 and come first; pairing a long side with a short one costs ln 10 twice.
    #[test]
    fn rectangle_corners_first() {
        let c = [
            cand(0.0, 0.0),
            cand(5.0, 1.0),
            cand(10.0, 0.0),
            cand(11.0, 0.0),
            cand(11.5, 0.5),
            cand(21.0, 0.0),
            cand(16.0, 1.0),
        ];
        let mut c = c.to_vec();
        c.sort_by(|a, b| a.pos.total_cmp(&b.pos));
        let r = rank(&c, 22.0);
        let pos = |s: [usize; 4]| s.map(|i| c[i].pos);
        assert_eq!(pos(r[0].1), [0.0, 10.0, 11.0, 21.0]);
        assert!(r[0].0.abs() < 1e-12);
        // the set {0, 10, 11, 11.5}: sides 10, 1, 0.5, 10.5
        let skew = r
            .iter()
            .find(|x| pos(x.1) == [0.0, 10.0, 11.0, 11.5])
            .expect("ranked");
        let want = (10.0f64 / 0.5).ln() + (1.0f64 / 10.5).ln().abs() + 0.5;
        assert!((skew.0 - want).abs() < 1e-12, "{} vs {want}", skew.0);
    }
}
