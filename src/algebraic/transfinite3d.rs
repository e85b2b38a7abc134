//! The transfinite start grid of a volume block: the 3D counterpart of
//! [`crate::algebraic::transform::transfinite`], from the block's six faces.

use crate::grid::faces::Faces;
use crate::Grid3;

/// Trilinearly blended transfinite interpolation of the six faces, uniform in (ξ, η, ζ): the
/// Boolean sum P_ξ ⊕ P_η ⊕ P_ζ (faces − edges + corners). The start grid of the Picard
/// iteration; it may fold, the final grid does not depend on it.
pub fn transfinite(faces: &Faces) -> Grid3 {
    use rayon::prelude::*;
    let dims = faces.dims();
    let [ni, nj, nk] = dims;
    let (n, m, l) = ((ni - 1) as f64, (nj - 1) as f64, (nk - 1) as f64);
    let bp = |i: usize, j: usize, k: usize| faces.boundary_point([i, j, k]);
    let plane = ni * nj;
    let mut coords: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; plane * nk]);
    let pts: Vec<[f64; 3]> = (0..plane * nk)
        .into_par_iter()
        .map(|p| {
            let (i, j, k) = (p % ni, (p / ni) % nj, p / plane);
            let w = [
                [1.0 - i as f64 / n, i as f64 / n],
                [1.0 - j as f64 / m, j as f64 / m],
                [1.0 - k as f64 / l, k as f64 / l],
            ];
            let (ie, je, ke) = ([0, ni - 1], [0, nj - 1], [0, nk - 1]);
            std::array::from_fn(|c| {
                let mut x = 0.0;
                for a in 0..2 {
                    x += w[0][a] * bp(ie[a], j, k)[c]
                        + w[1][a] * bp(i, je[a], k)[c]
                        + w[2][a] * bp(i, j, ke[a])[c];
                    for b in 0..2 {
                        x -= w[0][a] * w[1][b] * bp(ie[a], je[b], k)[c]
                            + w[0][a] * w[2][b] * bp(ie[a], j, ke[b])[c]
                            + w[1][a] * w[2][b] * bp(i, je[a], ke[b])[c];
                        for d in 0..2 {
                            x += w[0][a] * w[1][b] * w[2][d] * bp(ie[a], je[b], ke[d])[c];
                        }
                    }
                }
                x
            })
        })
        .collect();
    for (p, x) in pts.into_iter().enumerate() {
        for c in 0..3 {
            coords[c][p] = x[c];
        }
    }
    let mut g = Grid3::from_coords(ni, nj, nk, coords);
    faces.apply_to(&mut g);
    g
}
