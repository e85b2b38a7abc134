//! Grid lines continued across an interior face of a volume topology (beyond the paper): the
//! volume beyond the face is gridded first, and this volume's lines leave the face in the
//! direction that volume's lines arrive in, so that they cross it without a kink.
//!
//! Orthogonality at both sides is the other way to a smooth crossing, but where the lines
//! cross a face obliquely by nature it asks both volumes to turn: the streamwise lines of a
//! C–O wing grid cross the face behind the swept trailing edge 30–40° off its normal on both
//! sides. Here the goals of [`crate::elliptic::wall_normal`]'s free-face passes are the
//! tangential offsets t_c = h (d − (d·n) n) / (d·n) of a straight line along the arriving
//! direction d at the node's height h = r·n above the face, instead of zero.
//!
//! Next to a side face held by the passes (a symmetry plane, a face shared with another
//! volume) the goals fade over [`HOLD_REACH`] of this volume's node steps off the face,
//! measured along the face: in the thin cells next to a wake sheet a line that continues a
//! lean of a few degrees would have to cross several cells of its neighbour column.

use crate::algebraic::blend::smoothstep;
use crate::grid::faces::{block_node, face_dims, normal, step_in};
use crate::quality::geom::{dot, norm, sub, V3 as V};
use crate::Grid3;

/// Distance along the face from a held side face, in node steps off the face, over which the
/// continuation goals fade in (a smoothstep). Measured on the ONERA M6's wake volume at full
/// size (`te_up` continued, its sides the wake sheet and `waketip`): 4 steps cut the mean kink
/// across `te_up` from 41.9° to 16.8° but left 530 more faces above 70° non-orthogonality in
/// the thin cells next to the sheet; 16 steps: 23.9°, 82 faces fewer than before.
pub const HOLD_REACH: f64 = 16.0;

/// Columns that keep their profile next to a side face shared with another volume and itself
/// corrected in this volume (orthogonal or continued), when the volume continues lines
/// across a face (instead of [`crate::elliptic::wall_normal::SIDE_HOLD`]): two free faces
/// meeting at an edge otherwise move the same nodes' shared parameter towards different
/// goals. The M6's wake volume (`te_up` continued, `waketip` orthogonal), full size: with 2
/// columns a growth ratio of 9.8 along i where the two layers meet; 4: 3.35; 6: 2.33 (waketip's
/// kink 19.1° against 15.1° with `te_up` fixed); 8: 1.57 (20.8°).
pub const CORNER_HOLD: usize = 6;

/// The direction in which the grid lines of the volume beyond a face arrive at each of its
/// nodes, in this volume's face indices (a, b) of [`block_node`]: unit vectors pointing into
/// this volume (zero where unknown, e.g. at a collapsed node).
#[derive(Clone, Debug, PartialEq)]
pub struct Lines {
    na: usize,
    dirs: Vec<V>,
}

impl Lines {
    /// Directions from a function of this volume's face indices (a, b), `na` × `nb` of them:
    /// the vector from the far volume's node one step in to the face node; normalised here.
    pub fn new(na: usize, nb: usize, mut arriving: impl FnMut(usize, usize) -> V) -> Self {
        let mut dirs = Vec::with_capacity(na * nb);
        for b in 0..nb {
            for a in 0..na {
                let d = arriving(a, b);
                let l = norm(d);
                dirs.push(if l > 0.0 && l.is_finite() {
                    d.map(|c| c / l)
                } else {
                    [0.0; 3]
                });
            }
        }
        Lines { na, dirs }
    }

    /// The arriving direction at face node (a, b).
    pub fn at(&self, a: usize, b: usize) -> V {
        self.dirs[a + self.na * b]
    }

    /// Face nodes (a, b) for which the directions are given.
    pub fn dims(&self) -> [usize; 2] {
        [self.na, self.dirs.len() / self.na.max(1)]
    }

    /// The goal offset t_c (module docs) of a node at r from its face node with unit face
    /// normal `n`, arriving direction `d`; None where d is unknown or nearly in the face.
    pub fn offset(d: V, n: V, r: V) -> Option<V> {
        let dn = dot(d, n);
        (dn.abs() > 1e-3).then(|| {
            let h = dot(r, n);
            let t = sub(d, n.map(|c| c * dn));
            t.map(|c| c * h / dn)
        })
    }

    /// The goals' weight factor next to the held side faces: `dists` the node's distances
    /// along the face from the sides a = 0, a = na − 1, b = 0, b = nb − 1, `held` which of them
    /// are held (> 0), `step` this volume's node step off the face there ([`HOLD_REACH`]).
    pub fn side_fade(dists: [f64; 4], held: [usize; 4], step: f64) -> f64 {
        dists
            .into_iter()
            .zip(held)
            .filter(|&(_, h)| h > 0)
            .map(|(s, _)| smoothstep(s / (HOLD_REACH * step)))
            .product()
    }

    /// Distances along a face of na × nb nodes (node (a, b) at `pt(a, b)`) from its sides
    /// a = 0, a = na − 1, b = 0, b = nb − 1, by node (a + na b): the arguments of
    /// [`Lines::side_fade`].
    pub fn side_distances(na: usize, nb: usize, pt: impl Fn(usize, usize) -> V) -> Vec<[f64; 4]> {
        let mut sides = vec![[0.0; 4]; na * nb];
        let step = |p: V, q: V| norm(sub(p, q));
        for b in 0..nb {
            for a in 1..na {
                sides[a + na * b][0] = sides[a - 1 + na * b][0] + step(pt(a, b), pt(a - 1, b));
            }
            for a in (0..na.saturating_sub(1)).rev() {
                sides[a + na * b][1] = sides[a + 1 + na * b][1] + step(pt(a + 1, b), pt(a, b));
            }
        }
        for a in 0..na {
            for b in 1..nb {
                sides[a + na * b][2] = sides[a + na * (b - 1)][2] + step(pt(a, b), pt(a, b - 1));
            }
            for b in (0..nb.saturating_sub(1)).rev() {
                sides[a + na * b][3] = sides[a + na * (b + 1)][3] + step(pt(a, b + 1), pt(a, b));
            }
        }
        sides
    }

    /// Largest and mean angle (degrees) between the first grid line off face `w` of `x` and
    /// the arriving direction, over the face's interior nodes: what the passes aim at.
    pub fn angles(&self, x: &Grid3, w: usize) -> (f64, f64) {
        let dims = x.dims();
        let [na, nb] = face_dims(w, dims);
        let (d, lo) = normal(w);
        let (mut worst, mut sum, mut n) = (0.0f64, 0.0, 0usize);
        for b in 1..nb.saturating_sub(1) {
            for a in 1..na.saturating_sub(1) {
                let f = block_node(w, a, b, dims);
                let i = step_in(f, d, lo);
                let line = sub(x.point(i[0], i[1], i[2]), x.point(f[0], f[1], f[2]));
                let dir = self.at(a, b);
                let l = norm(line) * norm(dir);
                if l > 0.0 {
                    let deg = (dot(line, dir) / l).clamp(-1.0, 1.0).acos().to_degrees();
                    worst = worst.max(deg);
                    sum += deg;
                    n += 1;
                }
            }
        }
        (worst, if n > 0 { sum / n as f64 } else { 0.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_line_along_the_arriving_direction_has_the_goal_offset() {
        // d tilted 30° from the normal z towards x: at height h the line is h tan 30° along x.
        let s = 30f64.to_radians();
        let d = [s.sin(), 0.0, s.cos()];
        let t = Lines::offset(d, [0.0, 0.0, 1.0], [0.7, -0.2, 2.0]).unwrap();
        assert!((t[0] - 2.0 * s.tan()).abs() < 1e-14 && t[1].abs() < 1e-14 && t[2] == 0.0);
        // the normal's sign does not matter; a direction in the face has no goal
        let u = Lines::offset(d, [0.0, 0.0, -1.0], [0.7, -0.2, 2.0]).unwrap();
        assert!((u[0] - t[0]).abs() < 1e-14);
        assert!(Lines::offset([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]).is_none());
    }

    #[test]
    fn the_goals_fade_in_along_the_face_from_held_sides_only() {
        // a 5 × 3 face with unit steps: distances from the four sides
        let d = Lines::side_distances(5, 3, |a, b| [a as f64, 2.0 * b as f64, 0.0]);
        assert_eq!(d[1 + 5], [1.0, 3.0, 2.0, 2.0]);
        // held only at a = 0: full weight from HOLD_REACH steps on, zero on the side
        let step = 0.1;
        assert_eq!(
            Lines::side_fade([0.0, 0.0, 0.0, 0.0], [1, 0, 0, 0], step),
            0.0
        );
        assert_eq!(
            Lines::side_fade([HOLD_REACH * step, 0.0, 0.0, 0.0], [1, 0, 0, 0], step),
            1.0
        );
        let half = Lines::side_fade([0.5 * HOLD_REACH * step, 0.0, 0.0, 0.0], [6, 0, 0, 0], step);
        assert!((half - 0.5).abs() < 1e-15);
        // sides that are not held do not fade
        assert_eq!(Lines::side_fade([0.0; 4], [0; 4], step), 1.0);
    }

    #[test]
    fn directions_are_unit_vectors_by_face_index() {
        let l = Lines::new(3, 2, |a, b| [a as f64, b as f64, 2.0]);
        assert_eq!(l.dims(), [3, 2]);
        let d = l.at(2, 1);
        assert!((norm(d) - 1.0).abs() < 1e-15 && (d[0] / d[2] - 1.0).abs() < 1e-15);
        let z = Lines::new(1, 1, |_, _| [0.0; 3]);
        assert_eq!(z.at(0, 0), [0.0; 3]);
    }
}
