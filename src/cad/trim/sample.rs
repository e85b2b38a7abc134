//! A face's loop walked: chains of edge pieces between two loop points, their arclength, and
//! the loop sampled at fractions of it (the block sides' nodes and their (u, v)).

use super::{FaceLoop, LoopPoint, NS};
use ellipgrid_geometry::Vec3;

impl FaceLoop<'_> {
    /// The pieces (edge, σ from, σ to) of the loop from `a` forwards to `b`.
    fn chain(&self, a: LoopPoint, b: LoopPoint) -> Vec<(usize, f64, f64)> {
        let n = self.len();
        if a.edge == b.edge && a.sigma < b.sigma {
            return vec![(a.edge, a.sigma, b.sigma)];
        }
        let mut out = Vec::new();
        if a.sigma < 1.0 {
            out.push((a.edge, a.sigma, 1.0));
        }
        let mut k = (a.edge + 1) % n;
        while k != b.edge {
            out.push((k, 0.0, 1.0));
            k = (k + 1) % n;
        }
        if b.sigma > 0.0 {
            out.push((b.edge, 0.0, b.sigma));
        }
        out
    }

    /// Arclength from `a` forwards to `b`.
    pub fn chain_length(&self, a: LoopPoint, b: LoopPoint) -> f64 {
        self.chain(a, b)
            .iter()
            .map(|&(k, s0, s1)| (s1 - s0) * self.length(k))
            .sum()
    }

    /// The loop point `s` (arclength) forwards from `a`.
    pub fn advance(&self, a: LoopPoint, mut s: f64) -> LoopPoint {
        let n = self.len();
        let mut p = a;
        for _ in 0..=n {
            let rest = (1.0 - p.sigma) * self.length(p.edge);
            if s < rest {
                return LoopPoint {
                    edge: p.edge,
                    sigma: p.sigma + s / self.length(p.edge),
                };
            }
            s -= rest;
            p = LoopPoint {
                edge: (p.edge + 1) % n,
                sigma: 0.0,
            };
        }
        p
    }

    /// Points and their (u, v) at the fractions `f` ∈ [0, 1] of the 3D arclength along the
    /// loop from `a` forwards to `b`.
    ///
    /// # Errors
    /// A point off the surface or a projection that fails, naming the edge.
    pub fn sample(
        &mut self,
        a: LoopPoint,
        b: LoopPoint,
        f: &[f64],
    ) -> Result<(Vec<Vec3>, Vec<[f64; 2]>), String> {
        let pieces = self.chain(a, b);
        let lens: Vec<f64> = pieces
            .iter()
            .map(|&(k, s0, s1)| (s1 - s0) * self.length(k))
            .collect();
        let total: f64 = lens.iter().sum();
        let mut xs = Vec::with_capacity(f.len());
        let mut uvs = Vec::with_capacity(f.len());
        for &fr in f {
            let mut s = fr.clamp(0.0, 1.0) * total;
            let mut at = pieces.len() - 1;
            for (i, l) in lens.iter().enumerate() {
                if s <= *l || i + 1 == lens.len() {
                    at = i;
                    break;
                }
                s -= l;
            }
            let (k, s0, s1) = pieces[at];
            let sigma = if lens[at] > 0.0 {
                (s0 + (s1 - s0) * (s / lens[at]).clamp(0.0, 1.0)).clamp(0.0, 1.0)
            } else {
                s0
            };
            let e = &self.edges[k];
            let x = e.point(sigma);
            // Start from the samples' (u, v), interpolated at σ.
            let pos = sigma * NS as f64;
            let i = (pos.floor() as usize).min(NS - 1);
            let w = pos - i as f64;
            let hint = [0, 1].map(|c| (1.0 - w) * e.uv[i][c] + w * e.uv[i + 1][c]);
            let uv = self.project(x, hint, e.number)?;
            xs.push(x);
            uvs.push(uv);
        }
        Ok((xs, uvs))
    }
}
