//! Galerkin coarse operator `A_c = R A P`, computed stencil-wise.
//!
//! Row `J` of `R A` is a 5 × 5 fine stencil around the fine image of `J` (a 3 × 3 restriction
//! star times 3 × 3 operator stencils); multiplying by the 3 × 3 prolongation stars of the
//! coarse neighbours `K = J + (−1…1)²` folds it back into a nine-point coarse stencil, since
//! the stars of coarse points two coarse cells apart never overlap it.

use crate::solve::multigrid::interp::k;
use crate::solve::multigrid::use_par;
use rayon::prelude::*;

/// Computes the coarse stencils `ac` (`nx/2 × ny/2`) of fine operator `a` (`nx × ny`) with
/// prolongation stars `p` and restriction stars `r`.
pub(super) fn galerkin(
    a: &[[f64; 9]],
    nx: usize,
    ny: usize,
    p: &[[f64; 9]],
    r: &[[f64; 9]],
    ac: &mut [[f64; 9]],
) {
    let (ncx, ncy) = (nx / 2, ny / 2);
    assert_eq!(ac.len(), ncx * ncy);
    if ncx == 0 || ncy == 0 {
        return;
    }
    let row = |(jc, out): (usize, &mut [[f64; 9]])| {
        for ic in 0..ncx {
            let (fi, fj) = (2 * ic + 1, 2 * jc + 1);
            let rs = &r[ic + ncx * jc];
            // t[sy][sx] = (R A)(J, f + (sx − 2, sy − 2))
            let mut t = [[0.0f64; 5]; 5];
            for ay in -1isize..=1 {
                let qj = fj as isize + ay;
                if qj < 0 || qj >= ny as isize {
                    continue;
                }
                for ax in -1isize..=1 {
                    let w = rs[k(ax, ay)];
                    let qi = fi as isize + ax;
                    if w == 0.0 || qi < 0 || qi >= nx as isize {
                        continue;
                    }
                    let m = &a[qi as usize + nx * qj as usize];
                    for dy in 0..3 {
                        let tr = &mut t[(ay + 1) as usize + dy];
                        for dx in 0..3 {
                            tr[(ax + 1) as usize + dx] += w * m[dx + 3 * dy];
                        }
                    }
                }
            }
            let mut st = [0.0; 9];
            for ky in -1isize..=1 {
                let kj = jc as isize + ky;
                if kj < 0 || kj >= ncy as isize {
                    continue;
                }
                // star rows o_y with s_y = o_y + 2 k_y in [-2, 2]
                let (oy0, oy1) = (if ky < 0 { 0 } else { -1 }, if ky > 0 { 0 } else { 1 });
                for kx in -1isize..=1 {
                    let ki = ic as isize + kx;
                    if ki < 0 || ki >= ncx as isize {
                        continue;
                    }
                    let (ox0, ox1) = (if kx < 0 { 0 } else { -1 }, if kx > 0 { 0 } else { 1 });
                    let ps = &p[ki as usize + ncx * kj as usize];
                    let mut sum = 0.0;
                    for oy in oy0..=oy1 {
                        let tr = &t[(oy + 2 * ky + 2) as usize];
                        for ox in ox0..=ox1 {
                            sum += tr[(ox + 2 * kx + 2) as usize] * ps[k(ox, oy)];
                        }
                    }
                    st[k(kx, ky)] = sum;
                }
            }
            out[ic] = st;
        }
    };
    if use_par(nx * ny) {
        ac.par_chunks_mut(ncx).enumerate().for_each(row);
    } else {
        ac.chunks_mut(ncx).enumerate().for_each(row);
    }
}
