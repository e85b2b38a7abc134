//! Nested iteration for the grid system [24]: solve it on coarser grids first, so that the
//! Picard iteration [43, 44] on the finest grid starts next to its solution.
//!
//! # Levels
//! Level ℓ keeps every 2^ℓ-th node of the block in each direction. A dimension of `n` nodes
//! coarsens exactly when `n` is odd (`(n − 1) / 2 + 1` nodes); coarsening stops when either
//! dimension is even or would drop below [`MIN_NODES`].
//!
//! # The coarse problems are restrictions of the fine one
//! A coarse block's boundary is the fine boundary sub-sampled, and its control functions
//! [19, 20] come from the *fine* algebraic (s, t) grid [39, 40] sub-sampled, not from the
//! arclength of the coarse boundary: the coarse grid approximates the same continuous map
//! x(ξ, η), so its error against the fine discrete solution is the O(h²) discretization
//! difference only.
//!
//! # Prolongation
//! What is interpolated is the displacement d = x − x_T from the Lagrange transfinite grid
//! x_T (zero on the boundary; x_T of a coarse level is x_T of the fine level sub-sampled), by
//! cubic interpolation in index space. With two coarse levels the displacement on level ℓ + 1
//! is first extrapolated in the manner of Richardson, d ← d_2h + (d_2h − P d_4h) / 4, which
//! removes the O(h²) term of the difference between the levels when the solution is smooth in
//! index space. A coarse level stops at [`COARSE_STOP`] times its first update (or at the
//! Picard tolerance); the finest at the Picard tolerance. A level whose Picard iteration fails
//! or does not converge is skipped: the next level starts from the transfinite grid (as
//! without nesting).
//!
//! Measured (`examples/bench_grid.rs`, curved domain): 3 Picard steps on the finest grid at
//! 257² and 513², 2 at 1025², against 11 for plain Picard (4 against 6 on the boundary layer
//! of aspect ratio 1.5e4); the grids agree with plain Picard's to 1.1e-10 of the diameter.
//!
//! # Work units
//! A work unit (WU) is the time of one evaluation of the residual of [24] with its assembly
//! ([`poisson2d::assemble`] + [`poisson2d::residual`]) on the finest grid, measured in the
//! same run (the shortest of the evaluations of the fine Picard steps); the whole generation,
//! from the boundary to the final grid, is reported in WU.

use crate::algebraic::control2d::Control2;
use crate::algebraic::transform::{straight_line, transfinite, ParamGrid};
use crate::algebraic::ControlKind;
use crate::elliptic::picard::BlockResult;
use crate::elliptic::picard::PicardParams;
use crate::elliptic::poisson2d;
use crate::grid::arclength::EdgeFunctions;
use crate::grid::boundary::Boundary2;
use crate::grid::Grid2;
use crate::solve::LinearSolver;
use crate::Result;
use rayon::prelude::*;
use std::time::Instant;

/// The coarsest level keeps at least this many nodes in each direction.
pub const MIN_NODES: usize = 9;

/// A coarse level stops when its Picard update falls below this fraction of its first update
/// (or below the Picard tolerance): its remaining Picard error is then small against the
/// error of the prediction it will give the next level, which the observed first updates put
/// at a third of this level's first update or more.
pub const COARSE_STOP: f64 = 1e-3;

/// One level of a nested solve.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LevelInfo {
    /// Nodes along i.
    pub ni: usize,
    /// Nodes along j.
    pub nj: usize,
    /// Picard steps on this level.
    pub steps: usize,
    /// True if this level's Picard iteration converged (its grid then starts the next level).
    pub converged: bool,
    /// Wall-clock seconds of this level (prolongation included).
    pub seconds: f64,
}

/// What a (nested) grid generation cost.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NestedInfo {
    /// The levels, coarsest first; the last one is the block itself.
    pub levels: Vec<LevelInfo>,
    /// Wall-clock seconds of the whole generation (edge functions, control functions, start
    /// grid, every level).
    pub seconds: f64,
    /// Seconds of one work unit: one assembly + residual of [24] on the finest grid.
    pub work_unit_seconds: f64,
    /// `seconds / work_unit_seconds`.
    pub work_units: f64,
}

/// Grid sizes of the nested levels, finest first (see the module documentation).
pub fn level_sizes(ni: usize, nj: usize) -> Vec<(usize, usize)> {
    let mut v = vec![(ni, nj)];
    let (mut a, mut b) = (ni, nj);
    while a % 2 == 1 && b % 2 == 1 && (a - 1) / 2 + 1 >= MIN_NODES && (b - 1) / 2 + 1 >= MIN_NODES {
        a = (a - 1) / 2 + 1;
        b = (b - 1) / 2 + 1;
        v.push((a, b));
    }
    v
}

/// Grids one block from its boundary with `kind` control functions, by nested iteration if
/// `params.nested_for(solver.name())` (else plain Picard from the transfinite grid), and
/// reports the cost in work units. The returned [`PicardInfo`](poisson2d::PicardInfo) is that
/// of the finest level.
pub fn grid_block_nested<const D: usize>(
    b: &Boundary2<D>,
    kind: ControlKind,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<(BlockResult<D>, NestedInfo)> {
    let t0 = Instant::now();
    let sizes = if params.nested_for(solver.name()) {
        level_sizes(b.ni(), b.nj())
    } else {
        vec![(b.ni(), b.nj())]
    };
    let pg = match kind {
        ControlKind::Algebraic => Some(straight_line(&EdgeFunctions::arclength(b))),
        ControlKind::Laplace => None,
    };
    let tf = transfinite(b);
    let mut levels = Vec::new();
    // converged displacements of the two previous (coarser) levels, the last one first
    let mut prev: Option<(Grid2<D>, Option<Grid2<D>>)> = None;
    for lev in (0..sizes.len()).rev() {
        let tl = Instant::now();
        let stride = 1 << lev;
        let (ni, nj) = sizes[lev];
        let t_lev = if lev == 0 {
            tf.clone()
        } else {
            subsample(&tf, stride)
        };
        let ctrl = match &pg {
            Some(pg) if lev == 0 => Control2::from_algebraic(pg),
            Some(pg) => Control2::from_algebraic(&subsample_param(pg, stride)),
            None => Control2::zeros([ni, nj]),
        };
        let mut x = match &prev {
            None => t_lev.clone(),
            Some((d2, d4)) => {
                let d = match d4 {
                    Some(d4) => extrapolate(d2, &prolong(d4)),
                    None => d2.clone(),
                };
                add(&t_lev, &prolong(&d))
            }
        };
        let lev_place = if lev == 0 {
            place.to_string()
        } else {
            format!("{place} (nested level {ni} × {nj})")
        };
        let stop = if lev == 0 { 0.0 } else { COARSE_STOP };
        let r = poisson2d::solve_timed(&mut x, &ctrl, solver, params, stop, &lev_place);
        let seconds = tl.elapsed().as_secs_f64();
        if lev == 0 {
            let (picard, wu) = r?;
            levels.push(LevelInfo {
                ni,
                nj,
                steps: picard.steps,
                converged: picard.converged,
                seconds,
            });
            let total = t0.elapsed().as_secs_f64();
            let mut picard = picard;
            picard.work_units = Some(total / wu);
            picard.coarse_steps = levels[..levels.len() - 1].iter().map(|l| l.steps).collect();
            let info = NestedInfo {
                levels,
                seconds: total,
                work_unit_seconds: wu,
                work_units: total / wu,
            };
            return Ok((BlockResult { grid: x, picard }, info));
        }
        let (steps, converged) = match &r {
            Ok((p, _)) => (p.steps, p.converged),
            Err(_) => (0, false),
        };
        levels.push(LevelInfo {
            ni,
            nj,
            steps,
            converged,
            seconds,
        });
        prev = if converged {
            let d = sub(&x, &t_lev);
            Some((d, prev.map(|(d2, _)| d2)))
        } else {
            None
        };
    }
    unreachable!("the finest level returns")
}

/// Every `stride`-th node of `g` in each direction.
fn subsample<const D: usize>(g: &Grid2<D>, stride: usize) -> Grid2<D> {
    let ni = (g.ni() - 1) / stride + 1;
    let nj = (g.nj() - 1) / stride + 1;
    Grid2::from_fn(ni, nj, |i, j| g.point(i * stride, j * stride))
}

/// Every `stride`-th node of an (s, t) grid.
fn subsample_param(pg: &ParamGrid, stride: usize) -> ParamGrid {
    let (fi, fj) = (pg.ni(), pg.nj());
    let (ni, nj) = ((fi - 1) / stride + 1, (fj - 1) / stride + 1);
    let mut s = Vec::with_capacity(ni * nj);
    let mut t = Vec::with_capacity(ni * nj);
    for j in 0..nj {
        for i in 0..ni {
            let (sv, tv) = pg.at(i * stride, j * stride);
            s.push(sv);
            t.push(tv);
        }
    }
    ParamGrid::from_parts(ni, nj, s, t)
}

fn zip_with<const D: usize>(
    a: &Grid2<D>,
    b: &Grid2<D>,
    f: impl Fn(f64, f64) -> f64 + Sync,
) -> Grid2<D> {
    let coords = std::array::from_fn(|c| {
        a.coord(c)
            .par_iter()
            .zip(b.coord(c))
            .map(|(&u, &v)| f(u, v))
            .collect()
    });
    Grid2::from_coords(a.ni(), a.nj(), coords)
}

fn add<const D: usize>(a: &Grid2<D>, b: &Grid2<D>) -> Grid2<D> {
    zip_with(a, b, |u, v| u + v)
}

fn sub<const D: usize>(a: &Grid2<D>, b: &Grid2<D>) -> Grid2<D> {
    zip_with(a, b, |u, v| u - v)
}

/// Richardson extrapolation of the displacement `d2` (level 2h) with `p4` (level 4h
/// interpolated to 2h), assuming an O(h²) difference between the levels.
fn extrapolate<const D: usize>(d2: &Grid2<D>, p4: &Grid2<D>) -> Grid2<D> {
    zip_with(d2, p4, richardson)
}

/// Richardson's step for an O(h²) difference: `d2 + (d2 − p4) / 4` (2D and volume levels).
#[inline]
pub(crate) fn richardson(d2: f64, p4: f64) -> f64 {
    d2 + 0.25 * (d2 - p4)
}

/// Cubic interpolation weights of the midpoint after coarse node `k` of `m` (one-sided at the
/// ends, linear for fewer than 4 nodes): `(first node, weights)`. Shared with the volume levels.
pub(crate) fn mid_weights(k: usize, m: usize) -> (usize, [f64; 4]) {
    const C: f64 = 1.0 / 16.0;
    if m < 4 {
        (k, [0.5, 0.5, 0.0, 0.0])
    } else if k == 0 {
        (0, [5.0 * C, 15.0 * C, -5.0 * C, C])
    } else if k + 2 == m {
        (m - 4, [C, -5.0 * C, 15.0 * C, 5.0 * C])
    } else {
        (k - 1, [-C, 9.0 * C, 9.0 * C, -C])
    }
}

/// Cubic interpolation in index space from a grid to the one with every cell halved.
fn prolong<const D: usize>(g: &Grid2<D>) -> Grid2<D> {
    let (mi, mj) = (g.ni(), g.nj());
    let (fi, fj) = (2 * mi - 1, 2 * mj - 1);
    let coords = std::array::from_fn(|c| {
        let v = g.coord(c);
        // along i: the fine-i values on the coarse rows
        let mut rows = vec![0.0; fi * mj];
        rows.par_chunks_mut(fi).enumerate().for_each(|(j, out)| {
            let src = &v[j * mi..(j + 1) * mi];
            for k in 0..mi {
                out[2 * k] = src[k];
                if k + 1 < mi {
                    let (s0, w) = mid_weights(k, mi);
                    out[2 * k + 1] = (0..4).map(|q| w[q] * src.get(s0 + q).unwrap_or(&0.0)).sum();
                }
            }
        });
        // along j: whole rows
        let mut out = vec![0.0; fi * fj];
        out.par_chunks_mut(fi).enumerate().for_each(|(jf, row)| {
            if jf % 2 == 0 {
                row.copy_from_slice(&rows[(jf / 2) * fi..(jf / 2 + 1) * fi]);
            } else {
                let (s0, w) = mid_weights(jf / 2, mj);
                for (q, wq) in w.iter().enumerate() {
                    if *wq != 0.0 {
                        let src = &rows[(s0 + q) * fi..(s0 + q + 1) * fi];
                        for (o, s) in row.iter_mut().zip(src) {
                            *o += wq * s;
                        }
                    }
                }
            }
        });
        out
    });
    Grid2::from_coords(fi, fj, coords)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn level_sizes_coarsen_odd_sizes_only() {
        assert_eq!(level_sizes(65, 49), vec![(65, 49), (33, 25), (17, 13)]);
        assert_eq!(level_sizes(64, 49), vec![(64, 49)]);
        assert_eq!(level_sizes(9, 9), vec![(9, 9)]);
    }

    #[test]
    fn prolongation_is_exact_for_cubics() {
        let f = |i: f64, j: f64| [i * i * i - 2.0 * i * j * j + j, 0.5 * j * j * j - i];
        let g = Grid2::<2>::from_fn(7, 5, |i, j| f(2.0 * i as f64, 2.0 * j as f64));
        let p = prolong(&g);
        assert_eq!((p.ni(), p.nj()), (13, 9));
        for j in 0..9 {
            for i in 0..13 {
                let (u, v) = (p.point(i, j), f(i as f64, j as f64));
                assert!((u[0] - v[0]).abs() < 1e-10 && (u[1] - v[1]).abs() < 1e-10);
            }
        }
    }
}
