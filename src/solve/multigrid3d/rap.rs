//! Galerkin coarse operator `A_c = R A P`, computed stencil-wise.
//!
//! Row `K` of `R A` is a 5 × 5 × 5 fine stencil `t` around the fine image `F` of `K` (the
//! 27-point restriction star times the 27-point operator rows it touches); the coarse coupling
//! to `K + D`, `D ∈ {−1, 0, 1}³`, is `Σ_o t[2D + o] P_{K+D}(o)` over the prolongation star of
//! `K + D` (only offsets `o` with `2D + o` inside the 5³ box). Each coarse row is computed on
//! its own, so coarse planes run in parallel without shared writes.

use crate::solve::multigrid3d::level::{off27, s27, Level};
use crate::solve::multigrid3d::use_par;
use rayon::prelude::*;

#[inline]
fn t5(s: [isize; 3]) -> usize {
    ((s[0] + 2) + 5 * (s[1] + 2) + 25 * (s[2] + 2)) as usize
}

/// Computes the coarse rows `coarse.a` from fine level `fine` (its operator and stars), in
/// f64, stored in single precision.
pub(super) fn galerkin(fine: &Level, coarse: &mut Level) {
    let dims = fine.dims;
    let nc = coarse.dims;
    let pl = nc[0] * nc[1];
    if pl * nc[2] == 0 {
        return;
    }
    let [nx, ny, _] = dims;
    let plane = |(kc, out): (usize, &mut [[f32; 27]])| {
        for jc in 0..nc[1] {
            for ic in 0..nc[0] {
                let kk = [ic, jc, kc];
                let f = [2 * ic + 1, 2 * jc + 1, 2 * kc + 1];
                let rs = &fine.r[ic + nc[0] * (jc + nc[1] * kc)];
                let mut t = [0.0f64; 125];
                for (c, &w) in rs.iter().enumerate() {
                    let w = f64::from(w);
                    if w == 0.0 {
                        continue;
                    }
                    let oc = off27(c);
                    let g: [isize; 3] = std::array::from_fn(|d| f[d] as isize + oc[d]);
                    if (0..3).any(|d| g[d] < 0 || g[d] >= dims[d] as isize) {
                        continue;
                    }
                    let row = fine.row(g[0] as usize + nx * (g[1] as usize + ny * g[2] as usize));
                    for (m, v) in row.iter().enumerate() {
                        let om = off27(m);
                        t[t5([oc[0] + om[0], oc[1] + om[1], oc[2] + om[2]])] += w * v;
                    }
                }
                let mut st = [0.0; 27];
                for (dm, out) in st.iter_mut().enumerate() {
                    let dd = off27(dm);
                    let nb: [isize; 3] = std::array::from_fn(|d| kk[d] as isize + dd[d]);
                    if (0..3).any(|d| nb[d] < 0 || nb[d] >= nc[d] as isize) {
                        continue;
                    }
                    let ps =
                        &fine.p[nb[0] as usize + nc[0] * (nb[1] as usize + nc[1] * nb[2] as usize)];
                    // star offsets o with 2 dd + o in [-2, 2]
                    let range = |v: isize| {
                        if v < 0 {
                            0..=1
                        } else if v > 0 {
                            -1..=0
                        } else {
                            -1..=1
                        }
                    };
                    let mut sum = 0.0;
                    for o2 in range(dd[2]) {
                        for o1 in range(dd[1]) {
                            for o0 in range(dd[0]) {
                                let pw = f64::from(ps[s27(o0, o1, o2)]);
                                if pw != 0.0 {
                                    sum += pw
                                        * t[t5([2 * dd[0] + o0, 2 * dd[1] + o1, 2 * dd[2] + o2])];
                                }
                            }
                        }
                    }
                    *out = sum;
                }
                // stored rounded (Level::a)
                out[ic + nc[0] * jc] = st.map(|v| v as f32);
            }
        }
    };
    if use_par(fine.n()) {
        coarse.a.par_chunks_mut(pl).enumerate().for_each(plane);
    } else {
        coarse.a.chunks_mut(pl).enumerate().for_each(plane);
    }
}
