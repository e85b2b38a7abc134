//! Differences of grids of one block: of a grid and its refinement at their common nodes (grid
//! families), and of two grids with the same nodes (another start grid, another
//! parametrization); the observed order of convergence from two successive differences.
//!
//! A grid of a family at (N − 1)·2 + 1 nodes per direction has the coarse grid's (ξ, η, ζ) at
//! its even nodes, so e_h = |x_h − x_{h/2}| at those nodes measures the discretization error
//! of x_h (to leading order, for a method of order p > 0), and p = log2(e_h / e_{h/2}). Both
//! norms are given, relative to the block's diameter: the max norm sees the O(h) singular
//! terms at obtuse corners of curved surfaces (METHOD.md §8), the rms norm the bulk of the grid.
//!
//! Grids are given as coordinate arrays (i fastest, then j, then k) with their node counts
//! `[ni, nj, nk]` (nk = 1 for 2D blocks), so one implementation serves planar, surface and
//! volume blocks.

use serde::Serialize;

/// A difference of two grids at their common nodes, relative to the block's diameter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Difference {
    /// Largest distance between corresponding nodes / diameter.
    pub max: f64,
    /// Root mean square of the distances / diameter.
    pub rms: f64,
    /// The node (i, j, k) of the largest distance, in the coarser grid's indices.
    pub at: [usize; 3],
}

/// The bounding-box diagonal of a grid's nodes.
pub fn diameter(coords: &[Vec<f64>]) -> f64 {
    crate::grid::bbox_diameter(coords)
}

/// How many fine intervals one coarse interval spans in each direction, if `fine` refines
/// `coarse` (each count (n − 1)·m + 1 for one m per direction, m = 1 for directions of one
/// node).
pub fn refinement(coarse: [usize; 3], fine: [usize; 3]) -> Option<[usize; 3]> {
    let mut m = [1; 3];
    for d in 0..3 {
        if coarse[d] == 0 || fine[d] == 0 {
            return None;
        }
        if coarse[d] == 1 {
            if fine[d] != 1 {
                return None;
            }
            continue;
        }
        let (c, f) = (coarse[d] - 1, fine[d] - 1);
        if f % c != 0 {
            return None;
        }
        m[d] = f / c;
    }
    Some(m)
}

/// The difference of `coarse` (dims `cdims`) and `fine` (dims `fdims`, a refinement of it:
/// [`refinement`]) at the coarse nodes, relative to `diameter`. None if the counts do not
/// nest or the coordinate arrays do not match them.
pub fn nested_difference(
    coarse: &[Vec<f64>],
    cdims: [usize; 3],
    fine: &[Vec<f64>],
    fdims: [usize; 3],
    diameter: f64,
) -> Option<Difference> {
    let m = refinement(cdims, fdims)?;
    let (nc, nf) = (
        cdims.iter().product::<usize>(),
        fdims.iter().product::<usize>(),
    );
    if coarse.len() != fine.len()
        || coarse.iter().any(|c| c.len() != nc)
        || fine.iter().any(|c| c.len() != nf)
        || diameter.is_nan()
        || diameter <= 0.0
    {
        return None;
    }
    let (mut max, mut sum, mut at) = (0.0f64, 0.0, [0; 3]);
    for k in 0..cdims[2] {
        for j in 0..cdims[1] {
            for i in 0..cdims[0] {
                let c = i + cdims[0] * (j + cdims[1] * k);
                let f = m[0] * i + fdims[0] * (m[1] * j + fdims[1] * m[2] * k);
                let d2: f64 = coarse
                    .iter()
                    .zip(fine)
                    .map(|(a, b)| (a[c] - b[f]).powi(2))
                    .sum();
                sum += d2;
                if d2.sqrt() > max {
                    max = d2.sqrt();
                    at = [i, j, k];
                }
            }
        }
    }
    Some(Difference {
        max: max / diameter,
        rms: (sum / nc as f64).sqrt() / diameter,
        at,
    })
}

/// The difference of two grids with the same nodes (dims `dims`), relative to `diameter`.
pub fn difference(
    a: &[Vec<f64>],
    b: &[Vec<f64>],
    dims: [usize; 3],
    diameter: f64,
) -> Option<Difference> {
    nested_difference(a, dims, b, dims, diameter)
}

/// The observed order log2(e_h / e_{h/2}) of two successive differences, None if either is
/// zero or not finite (a grid reproduced exactly has no order).
pub fn observed_order(coarse: f64, fine: f64) -> Option<f64> {
    (coarse > 0.0 && fine > 0.0 && coarse.is_finite() && fine.is_finite())
        .then(|| (coarse / fine).log2())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// x = (ξ, η, ξη) + c (ξ², η², 0): a 2D "grid" of n × m nodes.
    fn grid(n: usize, m: usize, c: f64) -> (Vec<Vec<f64>>, [usize; 3]) {
        let mut out = vec![Vec::new(), Vec::new(), Vec::new()];
        for j in 0..m {
            for i in 0..n {
                let (x, y) = (i as f64 / (n - 1) as f64, j as f64 / (m - 1) as f64);
                out[0].push(x + c * x * x);
                out[1].push(y + c * y * y);
                out[2].push(x * y);
            }
        }
        (out, [n, m, 1])
    }

    #[test]
    fn second_order_errors_give_order_two() {
        // a discretization error c·h² at every node: the differences of successive grids
        // are (3/4)·c·h², their ratio 4
        let h = |n: usize| 1.0 / (n - 1) as f64;
        let e = |n: usize| 0.1 * h(n) * h(n);
        let (a, da) = grid(9, 5, e(9));
        let (b, db) = grid(17, 9, e(17));
        let (c, dc) = grid(33, 17, e(33));
        let diam = diameter(&a);
        let want = (2.0 * (1.0 + e(9)).powi(2) + 1.0).sqrt();
        assert!((diam - want).abs() < 1e-15, "{diam}");
        let d1 = nested_difference(&a, da, &b, db, diam).unwrap();
        let d2 = nested_difference(&b, db, &c, dc, diam).unwrap();
        let p = observed_order(d1.max, d2.max).unwrap();
        assert!((p - 2.0).abs() < 1e-9, "{p}");
        // (the rms averages over 9 × 5 and 17 × 9 nodes: means of x⁴ that differ by O(h))
        let p_rms = observed_order(d1.rms, d2.rms).unwrap();
        assert!((p_rms - 2.0).abs() < 0.1, "{p_rms}");
        // the largest difference is at (ξ, η) = (1, 1), in coarse indices
        assert_eq!(d1.at, [8, 4, 0]);
        assert!((d1.max * diam - 2f64.sqrt() * (e(9) - e(17))).abs() < 1e-15);
        // the same grid: zero, and no order
        let same = difference(&a, &a, da, diam).unwrap();
        assert_eq!((same.max, same.rms), (0.0, 0.0));
        assert_eq!(observed_order(0.0, 0.0), None);
    }

    #[test]
    fn counts_that_do_not_nest_are_refused() {
        assert_eq!(refinement([9, 5, 1], [17, 9, 1]), Some([2, 2, 1]));
        assert_eq!(refinement([9, 5, 3], [33, 17, 9]), Some([4, 4, 4]));
        assert_eq!(refinement([9, 5, 1], [18, 9, 1]), None);
        assert_eq!(refinement([9, 5, 1], [17, 9, 2]), None);
        let (a, da) = grid(9, 5, 0.0);
        let (b, _) = grid(17, 9, 0.0);
        assert!(nested_difference(&a, da, &b, [17, 10, 1], 1.0).is_none());
        assert!(nested_difference(&a, da, &a, da, 0.0).is_none());
    }
}
