//! A scrambled, folded start grid (fixed seed): the grid of METHOD.md §7's claim "the final
//! grid does not depend on the initial grid, even a severely folded one", as `ellipgrid
//! verify` puts it to the test.
//!
//! From a start grid (the transfinite one), every interior node takes the place of its mirror
//! image in i, node (N − i, j, k), so that every interior cell is inverted, and is then moved
//! by a random vector with components uniform in ±(the local cell size at that node). The
//! boundary nodes are kept. One implementation for 2D and 3D blocks (coordinate arrays, i
//! fastest, with the node counts `[ni, nj, nk]`).

use crate::grid::{Grid2, Grid3};
use ellipgrid_geometry::random::SplitMix64;

/// The scrambled copy of the coordinate arrays `x` of a block of `dims` nodes (module docs).
fn scramble(x: &[Vec<f64>], dims: [usize; 3], seed: u64) -> Vec<Vec<f64>> {
    let [ni, nj, nk] = dims;
    let idx = |i: usize, j: usize, k: usize| i + ni * (j + nj * k);
    let interior = |n: usize, l: usize| nk == 1 && l == 0 || l > 0 && l + 1 < n;
    let mut rng = SplitMix64::new(seed);
    let mut out = x.to_vec();
    for k in 0..nk {
        for j in 0..nj {
            for i in 0..ni {
                if !(i > 0 && i + 1 < ni && j > 0 && j + 1 < nj && interior(nk, k)) {
                    continue;
                }
                let m = idx(ni - 1 - i, j, k);
                // the local cell size: the mean distance to the index neighbours of m
                let (mut h, mut count) = (0.0, 0.0);
                let (mi, mj, mk) = (ni - 1 - i, j, k);
                let mut near = |a: usize, b: usize, c: usize| {
                    let d2: f64 = x.iter().map(|c0| (c0[idx(a, b, c)] - c0[m]).powi(2)).sum();
                    h += d2.sqrt();
                    count += 1.0;
                };
                near(mi - 1, mj, mk);
                near(mi + 1, mj, mk);
                near(mi, mj - 1, mk);
                near(mi, mj + 1, mk);
                if nk > 1 {
                    near(mi, mj, mk - 1);
                    near(mi, mj, mk + 1);
                }
                let h = h / count;
                let n = idx(i, j, k);
                for (o, c0) in out.iter_mut().zip(x) {
                    o[n] = c0[m] + h * rng.symmetric();
                }
            }
        }
    }
    out
}

/// A scrambled, folded copy of a 2D grid (planar or surface), boundary kept (module docs).
pub fn scrambled<const D: usize>(start: &Grid2<D>, seed: u64) -> Grid2<D> {
    let x = scramble(start.coords(), [start.ni(), start.nj(), 1], seed);
    let coords: [Vec<f64>; D] = std::array::from_fn(|c| x[c].clone());
    Grid2::from_coords(start.ni(), start.nj(), coords)
}

/// A scrambled, folded copy of a volume grid, boundary kept (module docs).
pub fn scrambled3(start: &Grid3, seed: u64) -> Grid3 {
    let [ni, nj, nk] = start.dims();
    let mut x = scramble(start.coords(), [ni, nj, nk], seed).into_iter();
    let mut next = || x.next().unwrap_or_default();
    Grid3::from_coords(ni, nj, nk, [next(), next(), next()])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::quality2d;

    #[test]
    fn the_scrambled_grid_keeps_its_boundary_and_folds() {
        let g = Grid2::<2>::from_fn(17, 9, |i, j| [i as f64 / 16.0, 0.5 * j as f64 / 8.0]);
        let s = scrambled(&g, 20);
        for j in 0..9 {
            for i in 0..17 {
                if g.is_boundary(i, j) {
                    assert_eq!(s.point(i, j), g.point(i, j));
                } else {
                    // near the mirror node, within a cell
                    let m = g.point(16 - i, j);
                    let p = s.point(i, j);
                    assert!((p[0] - m[0]).abs() <= 1.0 / 16.0 && (p[1] - m[1]).abs() <= 1.0 / 16.0);
                }
            }
        }
        let q = quality2d(&s);
        assert!(q.folded_cells > 64, "{}", q.folded_cells);
        assert_eq!(scrambled(&g, 20), s);
        assert_ne!(scrambled(&g, 21), s);
        let v = Grid3::rectilinear(&[0.0, 1.0, 2.0, 3.0], &[0.0, 1.0, 2.0], &[0.0, 1.0, 2.0]);
        let s3 = scrambled3(&v, 5);
        assert_eq!(s3.point(0, 1, 1), v.point(0, 1, 1));
        let p = s3.point(1, 1, 1);
        let m = v.point(2, 1, 1);
        assert!((0..3).all(|c| (p[c] - m[c]).abs() <= 1.0) && p != m);
    }
}
