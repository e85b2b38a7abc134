//! Grid lines that cross a wall's side faces at right angles (#18): orthogonality at a face
//! that shares an edge with the wall, carried by the wall's own correction passes.
//!
//! A side face of a wall (the ONERA M6 wing volumes' `ahead` and `tipplane`, in the plane
//! z = 0 ahead of and beyond the wing) is gridded before the volume, and the volume's lines
//! reach it wherever the volume's map puts them: with the wall correction, 30–40° off its
//! normal, which the mirror-image volume beyond it doubles into a kink. The separate
//! orthogonality passes of a face ([`super::orthogonal3d`], shifting the parameters tangential
//! to that face) cannot be used there: next to the wall they move the same parameter of the
//! same nodes as the wall's v remap, and the two corrections undo each other (the passes
//! diverged on the M6; docs/ONERA_M6.md).
//!
//! Here the nodes next to a crossing face are the wall's own column nodes, and their goals are
//! set from the face: node j of the wall column m columns from the face is to lie on the line
//! through the face's node of the same row along the face's normal, at its current height
//! above the face ([`Crossings::goal`]). The wall's passes hold that goal with their own
//! means: the tangential shifts ([`super::wall_normal`]) blend the column's tangential goal
//! towards it with the weight φ = e^{−(m−1)/[`REACH`]}, and the v remap ([`super::wall`])
//! takes the goal's distance from the wall beyond [`LAYER`] wall cell widths of the column's
//! foot (in that layer the foot is not the face's foot, and the wall's prescription holds).
//! Near a side face that is not crossed the weight fades ([`CORNER`]), so that the columns
//! there keep that face's profile. Needs `wall_profiles = "faces"`, so that near the wall the
//! columns next to the face follow the face's rows: with the edges' profiles the kink across
//! the M6's `ahead` rose from 57° to 63° instead of falling.
//!
//! Measured on the ONERA M6 four-block grid (`orthogonal = ["F2", "F6"]` in the upper wing
//! volume, whose mirror image the lower one is), mean kinks: `ahead` 53.9 → 23.4°, `tipplane`
//! 54.4 → 40.5° at full size, part of the turn moving to the lines' first node off the face
//! (mean 21.1 → 34.7° at `ahead`); the wall lines within 0.18° of the normal (0.11°), the first
//! nodes within 0.2 % of the prescription, fold-free; 68 Picard steps instead of 60, ~10 % more
//! run time (docs/ONERA_M6.md, "Crossing faces").

use crate::algebraic::blend::smoothstep;
use crate::grid::faces::{block_node, face_dims, normal, step_in, tangents};
use crate::quality::geom::{cross, dot, norm, sub, V3 as V};
use crate::Grid3;

/// Reach of a crossing face into the wall's columns: weight e^{−(m−1)/REACH} for the column m
/// columns from the face (1 next to it). The lines then turn at their first node off the face
/// instead of at the face; a longer reach does not spread that turn, the passes reach the
/// goals less: at 33 × 33 × 25 on the M6, mean kink across `ahead` / turn at the first node
/// off it 29.0° / 31.8° with 1, 35.5° / 26.8° with 2, 55.5° / 29.1° with 3, and with 5 the
/// passes fold and fall back (56.8° / 19.7° without crossings).
pub const REACH: f64 = 1.0;

/// Near a side face that is not crossed the weight is multiplied by the smoothstep of
/// (m′ − 1)/CORNER, m′ the column's distance from that face (0 next to it, 1 from CORNER + 1
/// columns on), so that the columns there keep that face's profile. Without it (in an earlier
/// variant) the columns next to the M6's `te_up` at the tip followed `tipplane` (the first
/// spacings across `te_up` 20-fold apart); with 1 − e^{−(m′−1)/2} instead, the growth ratio
/// along i at that corner was 4.9 at 33 × 33 × 25 (2.2 without crossings), with this 2.3.
pub const CORNER: f64 = 4.0;

/// The goal's distance from the wall replaces the column's goal distance with the weight
/// 1 − 1 / (1 + (d / (LAYER w))²), d the goal's distance from the column's foot, w the
/// smaller wall cell width there; never at the first node. In an earlier variant (33 × 33 ×
/// 25 on the M6, the first node not yet excluded) 2, 4, 8 and 16 gave first nodes up to 1.31,
/// 1.08, 1.02 and 1.006 of the prescription and kinks across `ahead` of 24.7–25.8°.
pub const LAYER: f64 = 8.0;

fn dist(a: V, b: V) -> f64 {
    norm(sub(a, b))
}

/// The side faces of a wall face that the grid lines are to cross at right angles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Crossings {
    wall: usize,
    /// Side faces at a = 0, a = na − 1, b = 0, b = nb − 1 of the wall face (a, b its
    /// tangential indices, [`tangents`]).
    sides: [bool; 4],
}

impl Crossings {
    /// The block faces (0-based, F1 = 0) at a = 0, a = na − 1, b = 0, b = nb − 1 of wall `w`.
    pub fn side_faces(w: usize) -> [usize; 4] {
        let (ta, tb) = tangents(w);
        [2 * ta, 2 * ta + 1, 2 * tb, 2 * tb + 1]
    }

    /// The crossing faces among `flagged` (0-based block faces) that are side faces of wall
    /// `w`; None if there are none.
    pub fn new(w: usize, flagged: &[bool; 6]) -> Option<Self> {
        let sides = Self::side_faces(w).map(|f| flagged[f]);
        sides
            .contains(&true)
            .then_some(Crossings { wall: w, sides })
    }

    /// True if block face `f` (0-based) is one of the crossing faces.
    pub fn crosses(&self, f: usize) -> bool {
        Self::side_faces(self.wall)
            .iter()
            .zip(self.sides)
            .any(|(&s, on)| on && s == f)
    }

    /// The weights φ_s of the four sides (0 for a side not crossed) for the wall column at
    /// (a, b) of a block of `dims` nodes (module docs); [`Crossings::goal`] takes
    /// φ = min(1, Σ φ_s).
    fn weights(&self, dims: [usize; 3], a: usize, b: usize) -> [f64; 4] {
        let [na, nb] = face_dims(self.wall, dims);
        let m = [a, na - 1 - a, b, nb - 1 - b].map(|m| m as f64 - 1.0);
        std::array::from_fn(|s| {
            if !self.sides[s] {
                return 0.0;
            }
            // The two perpendicular sides: a's are b's and b's are a's.
            let across = if s < 2 { [2, 3] } else { [0, 1] };
            across
                .iter()
                .filter(|&&o| !self.sides[o])
                .fold((-m[s] / REACH).exp(), |w, &o| w * smoothstep(m[o] / CORNER))
        })
    }

    /// Weight φ and goal point of node j (1 … n − 2, counted from the wall) of the interior
    /// wall column at (a, b) in grid `x`: the crossing faces' nodes of row j, each moved off
    /// its face along the face's normal by the node's height above the face, averaged with
    /// the weights of [`REACH`] and [`CORNER`]. None where no crossing face reaches.
    pub fn goal(&self, x: &Grid3, a: usize, b: usize, j: usize) -> Option<(f64, V)> {
        let dims = x.dims();
        let w = self.wall;
        let (d, lo) = normal(w);
        let (ta, tb) = tangents(w);
        let [na, nb] = face_dims(w, dims);
        let up = |n: [usize; 3]| (0..j).fold(n, |n, _| step_in(n, d, lo));
        let pt = |n: [usize; 3]| x.point(n[0], n[1], n[2]);
        let node = pt(up(block_node(w, a, b, dims)));
        let feet = [(0, b), (na - 1, b), (a, 0), (a, nb - 1)];
        let (mut sum, mut total) = ([0.0; 3], 0.0);
        for (s, &phi) in self.weights(dims, a, b).iter().enumerate() {
            if phi < 1e-3 {
                continue;
            }
            // The face node of row j, and the face's normal there from its central differences
            // along the column (axis d) and along the face's other axis.
            let f = up(block_node(w, feet[s].0, feet[s].1, dims));
            let along = if s < 2 { tb } else { ta };
            let step = |n: [usize; 3], e: usize, k: isize| {
                let mut m = n;
                m[e] = (m[e] as isize + k) as usize;
                pt(m)
            };
            let nf = cross(
                sub(step(f, d, 1), step(f, d, -1)),
                sub(step(f, along, 1), step(f, along, -1)),
            );
            let l = dot(nf, nf).sqrt();
            if !(l > 0.0 && l.is_finite()) {
                continue;
            }
            let nf = nf.map(|c| c / l);
            let xf = pt(f);
            let h = dot(sub(node, xf), nf);
            for (e, acc) in sum.iter_mut().enumerate() {
                *acc += phi * (xf[e] + h * nf[e]);
            }
            total += phi;
        }
        (total > 0.0).then(|| (total.min(1.0), sum.map(|c| c / total)))
    }

    /// Goal distances of the wall column at (a, b) (node j counted from the wall; `goal` the
    /// wall correction's, `distance` how the v remap measures the offset of a point from the
    /// column's foot): beyond [`LAYER`] wall cell widths of the foot, towards the crossing
    /// goal's distance with the weight φ; the first node keeps the wall's goal.
    pub(crate) fn goal_distances(
        &self,
        x: &Grid3,
        [a, b]: [usize; 2],
        goal: &mut [f64],
        distance: &dyn Fn(usize, V) -> f64,
    ) {
        let dims = x.dims();
        let w = self.wall;
        let pt = |a: usize, b: usize| {
            let n = block_node(w, a, b, dims);
            x.point(n[0], n[1], n[2])
        };
        let x0 = pt(a, b);
        let width = 0.5 * dist(pt(a + 1, b), pt(a - 1, b)).min(dist(pt(a, b + 1), pt(a, b - 1)));
        let n = goal.len();
        for (j, gj) in goal.iter_mut().enumerate().take(n - 1).skip(2) {
            let Some((phi, g)) = self.goal(x, a, b, j) else {
                continue;
            };
            let off = dist(g, x0) / (LAYER * width);
            let f = phi * (1.0 - 1.0 / (1.0 + off * off));
            let d = gj.powf(1.0 - f) * distance(j, sub(g, x0)).powf(f);
            if d.is_finite() && d > 0.0 {
                *gj = d;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A box x ∈ [0, 1], y ∈ [0, 1] (the wall y = 0, F3), z ∈ [0, 1], with its nodes at
    /// x = i/(n−1) + `lean` y: the lines of constant (j, k) leave the face x = 0 (F1) sheared.
    fn sheared(n: usize, lean: f64) -> Grid3 {
        let t = |i: usize| i as f64 / (n - 1) as f64;
        let mut g = Grid3::zeros(n, n, n);
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let y = t(j);
                    let x = if i == 0 {
                        0.0
                    } else {
                        t(i) + lean * y * (1.0 - t(i))
                    };
                    g.set(i, j, k, [x, y, t(k)]);
                }
            }
        }
        g
    }

    /// [`sheared`] at 9 nodes with F1 crossed (the wall F3).
    fn crossing_f1() -> (Grid3, Crossings) {
        let mut flagged = [false; 6];
        flagged[0] = true;
        (sheared(9, 0.3), Crossings::new(2, &flagged).unwrap())
    }

    #[test]
    fn side_faces_of_a_wall_are_found() {
        let mut flagged = [false; 6];
        assert_eq!(Crossings::new(2, &flagged), None);
        flagged[3] = true; // F4, opposite the wall F3: not a side face
        assert_eq!(Crossings::new(2, &flagged), None);
        flagged[0] = true; // F1
        let c = Crossings::new(2, &flagged).expect("F1 is a side face of F3");
        assert!(c.crosses(0) && !c.crosses(1) && !c.crosses(3));
        assert_eq!(Crossings::side_faces(2), [0, 1, 4, 5]);
    }

    #[test]
    fn the_goal_lies_on_the_face_normal_through_the_face_node() {
        let (g, c) = crossing_f1();
        // The column next to F1 (a = 1), row j = 4: the goal is the face node (0, y, z) moved
        // along x by the node's own x, so it keeps the node's height and drops the shear.
        let (phi, goal) = c.goal(&g, 1, 4, 4).unwrap();
        let node = g.point(1, 4, 4);
        let face = g.point(0, 4, 4);
        assert!((goal[0] - node[0]).abs() < 1e-12, "{goal:?} {node:?}");
        assert!((goal[1] - face[1]).abs() < 1e-12 && (goal[2] - face[2]).abs() < 1e-12);
        // The weight: e^{-(a-1)/REACH}, faded towards the faces F5, F6 (b = 0, 8), which are
        // not crossed (CORNER).
        let want = |a: usize, b: usize| {
            let fade = |m: usize| smoothstep((m as f64 - 1.0) / CORNER);
            (-(a as f64 - 1.0) / REACH).exp() * fade(b) * fade(8 - b)
        };
        assert!((phi - want(1, 4)).abs() < 1e-12, "{phi}");
        assert!(phi > 0.5);
        for (a, b) in [(3, 4), (1, 2), (2, 6)] {
            let (p, _) = c.goal(&g, a, b, 4).unwrap();
            assert!((p - want(a, b)).abs() < 1e-12, "{a} {b}: {p}");
        }
        assert!(c.goal(&g, 1, 1, 4).is_none(), "next to F5 nothing is left");
    }

    #[test]
    fn goal_distances_keep_the_first_node_and_follow_the_goal_off_the_wall() {
        let (g, c) = crossing_f1();
        let x0 = g.point(1, 0, 4);
        let profile: Vec<f64> = (0..9).map(|j| j as f64 / 8.0).collect();
        let mut goal = profile.clone();
        let len = |_: usize, r: V| dot(r, r).sqrt();
        c.goal_distances(&g, [1, 4], &mut goal, &len);
        // The first node keeps the wall's goal (the face's profile here).
        assert_eq!(goal[1], profile[1]);
        // Off the wall, between the face's profile and the crossing goal's distance, closer
        // to the goal the further from the wall.
        let mut last = 0.0;
        for j in 2..8 {
            let (_, gp) = c.goal(&g, 1, 4, j).unwrap();
            let want = dist(gp, x0);
            let (lo, hi) = (want.min(profile[j]), want.max(profile[j]));
            assert!(
                goal[j] >= lo - 1e-12 && goal[j] <= hi + 1e-12,
                "{j}: {}",
                goal[j]
            );
            let share = (goal[j] / profile[j]).ln() / (want / profile[j]).ln();
            assert!(share > last, "{j}: {share} after {last}");
            last = share;
        }
        assert!(last > 0.3, "{last}");
        assert_eq!(goal[0], 0.0);
        assert_eq!(goal[8], 1.0);
    }
}
