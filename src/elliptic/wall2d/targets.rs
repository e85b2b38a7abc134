//! The goals of the columns leaving a wall side: the side's wall runs (the whole side, or the
//! wall edges of a chain such as airfoil + wake), their anchor profiles, and the strength of
//! the correction along the side.
//!
//! Anchors are columns whose distance-from-wall profile is known: the side's two ends (the
//! side edges leaving it) and every end of a wall run inside the side, where only the first
//! spacing h is given (by the topology: the edge that continues the grid line through that
//! vertex, e.g. a blunt trailing edge's base). Such an anchor's profile is the column's own
//! uncorrected distances d₀ scaled to first spacing h near the wall, d₀ (h/d₀₁)^(ψ²), with ψ
//! the goals' fade into the uncorrected distances ([`super::FADE`]): scaled by h/d₀₁ alone, the
//! profile moved rows deep in the block (a trailing-edge column at 2.9e-6 asked 1e-5 pushed
//! the lines at mid-depth out by 1.8× and bent them across the next cut by 8° on average). Between two anchors the
//! profiles are interpolated geometrically by arclength along the side. Columns on a wall run
//! have strength 1; along a non-wall part of the side (a wake cut) the strength fades with a
//! half cosine in the node index from 1 at the wall's end to 0 at the side's end (or halfway
//! to the next wall run), so the first spacing leaves the wall's value without a jump and
//! grows into the one the elliptic map gives there.

use super::{column_distances, dist, Columns};
use crate::grid::{Edge, Grid2};

/// Where a wall holds along one side of a block. On a chain of wall and non-wall edges the
/// targets are anchored at the side's ends (the side edges' profiles) and at every wall end
/// inside the side (its first spacing, the column's own distances scaled to it near the wall),
/// interpolated geometrically by arclength in between; along the non-wall part the
/// correction's strength fades with a half cosine in the node index from the wall's end to the
/// side's end, or halfway to the next wall.
#[derive(Clone, Debug, PartialEq)]
pub struct WallSide {
    pub edge: Edge,
    /// None: the whole side is wall.
    pub part: Option<WallPart>,
    /// Share of each column over which the correction fades out ([`super::FADE`] by default;
    /// half of it at most with an opposite wall).
    pub fade: f64,
}

/// The wall part of a side that is a chain of wall and non-wall edges.
#[derive(Clone, Debug, PartialEq)]
pub struct WallPart {
    /// Node ranges `[first, last]` along the side (its index direction) on wall edges,
    /// ascending and disjoint.
    pub runs: Vec<[usize; 2]>,
    /// The first spacing at every run end that is not a block corner: (node, spacing).
    pub ends: Vec<(usize, f64)>,
}

impl WallSide {
    /// The whole side `edge`.
    pub fn whole(edge: Edge) -> Self {
        WallSide {
            edge,
            part: None,
            fade: super::FADE,
        }
    }
}

/// Target distances from the wall along one side: the anchors' profiles interpolated by
/// arclength, and the strength per column.
pub(super) struct Targets {
    /// Anchor columns (ascending, first 0 and last the side's end) with their profiles.
    anchors: Vec<(usize, Vec<f64>)>,
    /// Arclength of each wall node from column 0.
    s: Vec<f64>,
    /// Strength of the correction per column (1 on the wall, 0: not corrected).
    strength: Vec<f64>,
    /// Columns on a wall run.
    on_wall: Vec<bool>,
}

impl Targets {
    pub(super) fn new<const D: usize>(
        g: &Grid2<D>,
        cols: &Columns,
        part: Option<&WallPart>,
        fade: f64,
    ) -> Self {
        let n = cols.count();
        let mut s = vec![0.0; n];
        for c in 1..n {
            let (a, b) = (cols.node(c - 1, 0), cols.node(c, 0));
            s[c] = s[c - 1] + dist(g.point(a.0, a.1), g.point(b.0, b.1));
        }
        let mut anchors = vec![(0, column_distances(g, cols, 0))];
        let (mut strength, mut on_wall) = (vec![1.0; n], vec![true; n]);
        if let Some(p) = part {
            let mut ends = p.ends.clone();
            ends.sort_by_key(|e| e.0);
            for (c, h) in ends.into_iter().filter(|e| e.0 > 0 && e.0 < n - 1) {
                let d = column_distances(g, cols, c);
                let ratio = h / d[1];
                let n = d.len();
                let p = (0..n).map(|j| d[j] * ratio.powf(fade_in_depth(j, n, fade).powi(2)));
                anchors.push((c, p.collect()));
            }
            on_wall = (0..n)
                .map(|c| p.runs.iter().any(|r| r[0] <= c && c <= r[1]))
                .collect();
            strength = fade_along(&on_wall);
        }
        anchors.push((n - 1, column_distances(g, cols, n - 1)));
        Targets {
            anchors,
            s,
            strength,
            on_wall,
        }
    }

    /// The target distance of node `j` of column `c` (before the fade into the uncorrected
    /// distances).
    pub(super) fn at(&self, c: usize, j: usize) -> f64 {
        if j == 0 {
            return 0.0;
        }
        let k = self
            .anchors
            .windows(2)
            .position(|w| c <= w[1].0)
            .unwrap_or(self.anchors.len() - 2);
        let ((ca, pa), (cb, pb)) = (&self.anchors[k], &self.anchors[k + 1]);
        if c == *ca {
            return pa[j];
        }
        let w = (self.s[c] - self.s[*ca]) / (self.s[*cb] - self.s[*ca]);
        pa[j].powf(1.0 - w) * pb[j].powf(w)
    }

    pub(super) fn strength(&self, c: usize) -> f64 {
        self.strength[c]
    }

    pub(super) fn on_wall(&self, c: usize) -> bool {
        self.on_wall[c]
    }
}

/// Strength per column: 1 on the wall, a half cosine in the node index from 1 at a wall
/// run's end to 0 at the side's end, or halfway to the next run.
fn fade_along(on_wall: &[bool]) -> Vec<f64> {
    let n = on_wall.len();
    let mut out = vec![0.0; n];
    let mut c = 0;
    while c < n {
        if on_wall[c] {
            out[c] = 1.0;
            c += 1;
            continue;
        }
        // a stretch c..e of non-wall columns, between wall columns (or the side's ends)
        let mut e = c;
        while e < n && !on_wall[e] {
            e += 1;
        }
        let (left, right) = (c > 0, e < n);
        let len = e - c + 1;
        let reach = if left && right { len / 2 } else { len } as f64;
        for (k, o) in out.iter_mut().enumerate().take(e).skip(c) {
            let from_left = if left {
                (k + 1 - c) as f64
            } else {
                f64::INFINITY
            };
            let from_right = if right { (e - k) as f64 } else { f64::INFINITY };
            let x = (from_left.min(from_right) / reach.max(1.0)).min(1.0);
            *o = 0.5 * (1.0 + (std::f64::consts::PI * x).cos());
        }
        c = e;
    }
    out
}

/// The distances a column should reach: d*^ψ d₀^{1−ψ}, from the uncorrected grid's distances
/// `d0` and the interpolated anchor profile `dstar`, with ψ = `strength` × a half cosine in
/// the node index j, from 1 at the first node off the wall (flat there, so that the spacings
/// near the wall keep the side edges' growth) to 0 at `fade` of the column ([`super::FADE`], or
/// half of it for opposite walls).
pub(super) fn blend_targets(d0: &[f64], dstar: &[f64], strength: f64, fade: f64) -> Vec<f64> {
    let n = d0.len();
    (0..n)
        .map(|j| {
            let psi = fade_in_depth(j, n, fade) * strength;
            dstar[j].powf(psi) * d0[j].powf(1.0 - psi)
        })
        .collect()
}

/// The half cosine of node `j` of a column of `n` nodes: 1 (and flat) at the first node off
/// the wall, 0 from `fade` of the column on.
fn fade_in_depth(j: usize, n: usize, fade: f64) -> f64 {
    let end = (fade * (n - 1) as f64).max(2.0);
    let x = ((j.max(1) - 1) as f64 / (end - 1.0)).min(1.0);
    0.5 * (1.0 + (std::f64::consts::PI * x).cos())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_strength_fades_from_the_wall_to_the_side_end_or_halfway_to_the_next_wall() {
        // wall on columns 0..=4, non-wall 5..=8 (to the side's end)
        let on: Vec<bool> = (0..9).map(|c| c <= 4).collect();
        let f = fade_along(&on);
        assert!(f[..5].iter().all(|x| *x == 1.0));
        // k = 1..4 of reach 5: cos fade, strictly decreasing, still positive at the end
        for w in f[4..].windows(2) {
            assert!(w[1] < w[0], "{f:?}");
        }
        assert!((f[5] - 0.5 * (1.0 + (std::f64::consts::PI / 5.0).cos())).abs() < 1e-15);
        // a gap of three non-wall columns between walls: symmetric, lowest in the middle
        let on = [true, true, false, false, false, true, true];
        let f = fade_along(&on);
        assert_eq!(f[2], f[4]);
        assert!(f[3] < f[2] && f[3] >= 0.0, "{f:?}");
    }
}
