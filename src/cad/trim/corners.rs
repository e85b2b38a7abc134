//! A face's four corners by turning angle (METHOD.md §5 step 1 for a trimmed face): the
//! loop's most-turning vertices, with points inside its longest stretches to make four; a
//! pole or a collapsed cusp as the side E1 ([`FaceLoop::corners`]).

use super::{FaceLoop, LoopPoint};

impl FaceLoop<'_> {
    /// Four corners in loop order: the four convex vertices where the loop turns most (by more
    /// than `min_turn` radians: weaker turns are no better than a point inside an edge), or,
    /// with fewer than four such vertices, those plus midpoints (by arclength) of the longest
    /// stretches between them. Reentrant vertices are never corners: the corner cell of a
    /// grid there would fold. Returns the corners and their turning angles (degrees).
    ///
    /// `min_turn = None` is the plain rule: the four vertices turning most whichever way, the
    /// middles of the longest stretches.
    ///
    /// A loop through a pole ([`FaceLoop::pole`]) has the pole as one side: its vertex is
    /// the first corner and the last (turning angle NaN), two more are picked as above; so
    /// has a loop with a collapsed cusp ([`FaceLoop::cusp`]; its turning angle kept).
    pub fn corners(&self, min_turn: Option<f64>) -> ([LoopPoint; 4], [f64; 4]) {
        let n = self.len();
        let ccw = self.signed_area(self.scale) > 0.0;
        let collapsed = self.pole.or(self.cusp);
        let want = if collapsed.is_some() { 3 } else { 4 };
        let mut by_angle: Vec<(usize, f64)> = (0..n)
            .filter(|&k| Some(k) != collapsed)
            .map(|k| {
                let t = self.turning(k);
                let out = min_turn.is_some() && self.reentrant(k, ccw);
                (k, if out { -t } else { t })
            })
            .collect();
        by_angle.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        let mut ks: Vec<usize> = by_angle
            .iter()
            .take(want - usize::from(collapsed.is_some()))
            .filter(|p| min_turn.is_none_or(|m| p.1 > m))
            .map(|p| p.0)
            .collect();
        ks.extend(collapsed);
        if ks.is_empty() {
            ks.push(by_angle[0].0);
        }
        ks.sort_unstable();
        let mut pts: Vec<LoopPoint> = ks
            .into_iter()
            .map(|edge| LoopPoint { edge, sigma: 0.0 })
            .collect();
        while pts.len() < want {
            // Split the longest stretch between consecutive points near its middle, at a point
            // where the loop does not bend outwards (a corner on a concave curve folds its
            // corner cell, whose angle is then above 180°): the nearest such point to the
            // middle within its middle half; if the longest stretch bends outwards all along
            // its middle half, the next longest that does not (a three-sided face whose
            // longest side is concave takes its fourth corner on a straight or convex side).
            let m = pts.len();
            let mut stretches: Vec<(usize, f64)> = (0..m)
                .map(|k| (k, self.chain_length(pts[k], pts[(k + 1) % m])))
                .collect();
            stretches.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
            let at = |(k, len): (usize, f64), t: f64| self.advance(pts[k], t * len);
            let fractions =
                (0..=10).map(|d| 0.5 + if d % 2 == 0 { 0.025 } else { -0.025 } * d as f64);
            let (k, mid) = stretches
                .iter()
                .take(if min_turn.is_some() { m } else { 1 })
                .find_map(|&st| {
                    fractions
                        .clone()
                        .map(|t| at(st, t))
                        .find(|p| min_turn.is_none() || !self.bends_out(*p, ccw))
                        .map(|p| (st.0, p))
                })
                .unwrap_or_else(|| (stretches[0].0, at(stretches[0], 0.5)));
            pts.insert(k + 1, mid);
        }
        // Rotate so that the first corner is the earliest in loop order, or the pole.
        pts.sort_by(|a, b| (a.edge, a.sigma).partial_cmp(&(b.edge, b.sigma)).unwrap());
        if let Some(k) = collapsed {
            let at = pts.iter().position(|p| p.edge == k && p.sigma == 0.0);
            pts.rotate_left(at.unwrap_or(0));
            pts.push(pts[0]);
        }
        let angles = pts.iter().map(|p| {
            if Some(p.edge) == self.pole && p.sigma == 0.0 {
                f64::NAN
            } else if p.sigma == 0.0 {
                self.turning(p.edge).to_degrees()
            } else {
                0.0
            }
        });
        let mut a = [0.0; 4];
        for (d, s) in a.iter_mut().zip(angles) {
            *d = s;
        }
        ([pts[0], pts[1], pts[2], pts[3]], a)
    }
}
