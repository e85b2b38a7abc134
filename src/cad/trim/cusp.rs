//! A face's cusp gridded as a collapsed side (issue #14): a one-loop face with a vertex whose
//! interior angle is small (two edges meeting almost tangentially: the CATIA ventilator's
//! three-edge slivers meet at ~3°), or with exactly three corner-like vertices, is a block
//! whose side E1 is that vertex, one point in (u, v) and in 3D: the block degenerates to a
//! triangle there (as a C–O grid's pole, or a sharp trailing edge's H-topology), its grid
//! lines fanning out of the point towards the opposite side. Four corners on such a face put
//! one corner inside a smooth edge and leave the cusp a corner cell of a few degrees, which
//! folds. Last, where every other try folds, a vertex turning by more than 135° (a *tip*)
//! is collapsed the same way, two of them (E1 and E2) first: a band pointed at both ends.

use super::{FaceLoop, LoopPoint};

/// A convex vertex turning by more than this (radians: an interior angle below 30°) is a
/// cusp.
pub const CUSP: f64 = 150.0 * std::f64::consts::PI / 180.0;

/// A convex vertex turning by more than this (radians: an interior angle below 45°) is a
/// tip: the last try of a face whose every other corner set folds has its sharpest tip
/// collapsed (with a second tip as well first: a band pointed at both ends).
pub const TIP: f64 = 135.0 * std::f64::consts::PI / 180.0;

/// A convex vertex turning by more than this (radians, 20°) is corner-like (the weakest turn
/// of a corner in [`FaceLoop::corners`]'s last rule).
pub const CORNER_LIKE: f64 = 0.35;

impl FaceLoop<'_> {
    /// The vertex (start of an edge) to grid as a collapsed side: the convex vertex turning
    /// most, if it is a cusp ([`CUSP`]) or one of exactly three corner-like vertices
    /// ([`CORNER_LIKE`]); `None` otherwise, and for a loop through a pole (which is already a
    /// collapsed side).
    pub fn collapsed_at(&self) -> Option<usize> {
        let n = self.len();
        if self.pole.is_some() || n < 2 {
            return None;
        }
        let ccw = self.signed_area(self.scale) > 0.0;
        let convex: Vec<(usize, f64)> = (0..n)
            .filter(|&k| !self.reentrant(k, ccw))
            .map(|k| (k, self.turning(k)))
            .filter(|p| p.1 > CORNER_LIKE)
            .collect();
        let sharpest = convex
            .iter()
            .copied()
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))?;
        (sharpest.1 > CUSP || convex.len() == 3).then_some(sharpest.0)
    }

    /// Up to `count` corner sets with the vertex `k` collapsed (corners [k, a, b, k] in loop
    /// order, turning angles in degrees), cheapest first: `a` and `b` among the candidate
    /// corners of [`FaceLoop::balanced_corners`], a set costing
    /// |ln(L3 / L4)| + the costs of `a` and `b` (their interior angles' distance from 90°, 1
    /// inside an edge), with L3, L4 the 3D lengths of the sides from the cusp (k → a and
    /// b → k): balanced sides along the cusp. Sets differing from the ones before in a
    /// corner's vertex or edge.
    pub fn collapsed_corners(&self, k: usize, count: usize) -> Vec<([LoopPoint; 4], [f64; 4])> {
        let Some((cands, total)) = self.candidates() else {
            return Vec::new();
        };
        let at: f64 = (0..k).map(|e| self.length(e)).sum();
        let min = 1e-6 * total;
        // (distance from the cusp along the loop, candidate)
        let mut after: Vec<(f64, usize)> = cands
            .iter()
            .enumerate()
            .map(|(m, c)| ((c.pos - at).rem_euclid(total), m))
            .filter(|&(r, _)| r > min && r < total - min)
            .collect();
        after.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut sets: Vec<(f64, usize, usize)> = Vec::new();
        for (x, &(ra, a)) in after.iter().enumerate() {
            for &(rb, b) in &after[x + 1..] {
                let (l3, l2, l4) = (ra, rb - ra, total - rb);
                if l2 <= min || l4 <= min {
                    continue;
                }
                sets.push(((l3 / l4).ln().abs() + cands[a].cost + cands[b].cost, a, b));
            }
        }
        sets.sort_by(|p, q| p.0.total_cmp(&q.0).then((p.1, p.2).cmp(&(q.1, q.2))));
        let cusp = LoopPoint {
            edge: k,
            sigma: 0.0,
        };
        let deg = self.turning(k).to_degrees();
        let kind = |m: usize| (cands[m].at.edge, cands[m].at.sigma == 0.0);
        let mut out: Vec<([LoopPoint; 4], [f64; 4])> = Vec::with_capacity(count);
        let mut picked: Vec<(usize, usize)> = Vec::with_capacity(count);
        for (_, a, b) in sets {
            if out.len() == count {
                break;
            }
            if picked
                .iter()
                .any(|&(p, q)| kind(p) == kind(a) && kind(q) == kind(b))
            {
                continue;
            }
            picked.push((a, b));
            let (ca, cb) = (cands[a], cands[b]);
            out.push(([cusp, ca.at, cb.at, cusp], [deg, ca.deg, cb.deg, deg]));
        }
        out
    }

    /// The sharpest convex vertex turning by more than `limit` (radians; [`TIP`]), if any.
    pub fn sharpest_tip(&self, limit: f64) -> Option<usize> {
        let ccw = self.signed_area(self.scale) > 0.0;
        if self.pole.is_some() {
            return None;
        }
        (0..self.len())
            .filter(|&k| !self.reentrant(k, ccw))
            .map(|k| (k, self.turning(k)))
            .filter(|p| p.1 > limit)
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))
            .map(|p| p.0)
    }

    /// The corner set [k, m, m, k] with the cusp `k` and a second cusp `m` (the other convex
    /// vertex turning most, if by more than `limit` radians: [`CUSP`], or [`TIP`] in the last
    /// try) as the collapsed sides E1 and E2: a lens between two tangent edges, as SolidWorks
    /// writes cone faces ending in two cusps, or a band pointed at both ends.
    pub fn two_cusps(&self, k: usize, limit: f64) -> Option<([LoopPoint; 4], [f64; 4])> {
        let ccw = self.signed_area(self.scale) > 0.0;
        let (m, t) = (0..self.len())
            .filter(|&m| m != k && !self.reentrant(m, ccw))
            .map(|m| (m, self.turning(m)))
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))?;
        if t <= limit {
            return None;
        }
        let at = |edge| LoopPoint { edge, sigma: 0.0 };
        let (dk, dm) = (self.turning(k).to_degrees(), t.to_degrees());
        Some(([at(k), at(m), at(m), at(k)], [dk, dm, dm, dk]))
    }
}
