//! Nested iteration for the volume grid system [86]–[88]: solve it on coarser grids first, so
//! that the Picard iteration ([`crate::elliptic::poisson3d`]) on the finest grid starts next to its
//! solution. The 3D counterpart of [`crate::elliptic::nested`], with the same rules.
//!
//! # Levels
//! Level ℓ keeps every 2^ℓ-th node of the block in each direction. Coarsening goes on while
//! all three dimensions are odd and the coarser level keeps at least
//! [`MIN_NODES`] nodes each way; a block with an even dimension is
//! solved by plain Picard.
//!
//! # The coarse problems are restrictions of the fine one
//! A coarse block's faces are the fine faces sub-sampled, and its control functions [83, 84]
//! come from the *fine* algebraic (s, t, u) grid of the bilinear transformation [70]–[72]
//! sub-sampled. That grid is solved node by node from the edge-function values at (i, j, k),
//! so it is computed from the fine arclength edge functions sub-sampled (bit for bit the fine
//! grid's nodes), not from the arclength of the coarse edges: every level approximates the same
//! continuous map x(ξ, η, ζ), and the error of a coarse solution against the fine discrete one
//! is the O(h²) discretization difference only.
//!
//! # Prolongation
//! What is interpolated is the displacement d = x − x_T from the transfinite grid x_T (zero on
//! the boundary; x_T of a coarse level is x_T of the fine level sub-sampled, exactly), by
//! tensor-product cubic interpolation in index space (one direction after the other). With two
//! coarse levels the displacement on level ℓ + 1 is first extrapolated in the manner of
//! Richardson, d ← d_2h + (d_2h − P d_4h) / 4. A coarse level stops at
//! [`COARSE_STOP`] times its first update (or at the Picard
//! tolerance); the finest at the Picard tolerance. A level whose Picard iteration fails or does
//! not converge is skipped: the next level starts from the transfinite grid.
//!
//! # Work units
//! A work unit (WU) is the time of one evaluation of the residual of [86] with its assembly
//! (`poisson3d::assemble` + residual) on the finest grid, measured in the same run (the
//! shortest of the evaluations of the fine Picard steps). The whole generation, from the faces
//! to the final grid, is reported in WU.
//!
//! # Measured
//! `examples/bench_volume.rs` (warped box clustered to a first spacing ~1e-3, Bi-CGSTAB/ILU(0),
//! tolerance 1e-10; 2 cores shared with other jobs, so seconds vary by ±50 %):
//!
//! | n³ | exact linear solves | inexact Picard | nested + inexact |
//! |---|---|---|---|
//! | 33³ | 9, 0.9–2.4 s, 415–770 WU | 9, 0.23–0.41 s, 106–151 WU | 4+4+8, 0.20–0.36 s, 84–120 WU |
//! | 65³ | 9, 44–54 s, 1180–2140 WU | 10, 7.1–11.5 s, 270–350 WU | 4+4+5+8, 4.3–7.7 s, 180–205 WU |
//!
//! (Picard steps per level, coarsest first; seconds; work units.) The grids agree to 1e-9 of
//! the diameter (`tests/volume.rs`). The Picard iteration of [86] contracts by only ~0.1 per
//! step even with exact linear solves, ~0.3 in the first inexact steps after the prolongation,
//! so the prediction (first fine update 2.7e-5 at 65³ against 1.6e-2 from the transfinite grid,
//! 8.4e-5 without the Richardson step) saves 2 of 10 fine steps, not most of them as in 2D; but
//! the fine steps left are cheaper (158 against 258 Bi-CGSTAB iterations in all at 65³), the
//! coarse levels cost ~2 % of the whole, and nesting was faster at both sizes in every run: on
//! by default with Bi-CGSTAB too ([`nested_for3`]).

use crate::algebraic::bilinear3d::{bilinear, EdgeFunctions3};
use crate::algebraic::control3d::Control3;
use crate::algebraic::ControlKind;
use crate::elliptic::nested::{mid_weights, richardson, COARSE_STOP, MIN_NODES};
use crate::elliptic::picard::VolumeResult;
use crate::elliptic::picard::{PicardParams, PicardStep};
use crate::elliptic::poisson3d;
use crate::grid::faces::{transfinite, Faces};
use crate::solve::LinearSolver3;
use crate::{Grid3, Result};
use rayon::prelude::*;
use std::time::Instant;

/// One level of a nested volume solve.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LevelInfo3 {
    pub ni: usize,
    pub nj: usize,
    pub nk: usize,
    /// Picard steps on this level.
    pub steps: usize,
    /// True if this level's Picard iteration converged (its grid then starts the next level).
    pub converged: bool,
    /// Wall-clock seconds of this level (prolongation and control functions included).
    pub seconds: f64,
}

/// What a (nested) volume grid generation cost.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NestedInfo3 {
    /// The levels, coarsest first; the last one is the block itself.
    pub levels: Vec<LevelInfo3>,
    /// Wall-clock seconds of the whole generation.
    pub seconds: f64,
    /// Seconds of one work unit: one assembly + residual of [86] on the finest grid.
    pub work_unit_seconds: f64,
    /// `seconds / work_unit_seconds`.
    pub work_units: f64,
}

/// Whether nested iteration is used for a volume block with the solver called `solver_name`:
/// `params.nested` if set, else [`PicardParams::nested_for`] (on with "multigrid") or the
/// Bi-CGSTAB/ILU(0) solver ("bicgstab-ilu0"), for which it measured faster (module docs).
pub fn nested_for3(params: &PicardParams, solver_name: &str) -> bool {
    params.nested_for(solver_name) || (params.nested.is_none() && solver_name == "bicgstab-ilu0")
}

/// Grid sizes of the nested levels, finest first (module docs).
pub fn level_sizes3(dims: [usize; 3]) -> Vec<[usize; 3]> {
    let mut v = vec![dims];
    let mut d = dims;
    while d
        .iter()
        .all(|&n| n % 2 == 1 && (n - 1) / 2 + 1 >= MIN_NODES)
    {
        d = d.map(|n| (n - 1) / 2 + 1);
        v.push(d);
    }
    v
}

/// Grids one volume block from its faces with `kind` control functions, by nested iteration
/// if [`nested_for3`] (else plain Picard from the transfinite grid), and reports the cost in
/// work units. The returned [`PicardInfo`](crate::elliptic::picard::PicardInfo) is that of the finest
/// level, with `work_units` and `coarse_steps` filled in; `progress` sees the finest level's
/// steps only.
pub fn grid_volume_nested(
    faces: &Faces,
    kind: ControlKind,
    solver: &mut dyn LinearSolver3,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<(VolumeResult, NestedInfo3)> {
    let t0 = Instant::now();
    let sizes = if nested_for3(params, solver.name()) {
        level_sizes3(faces.dims())
    } else {
        vec![faces.dims()]
    };
    let ef = match kind {
        ControlKind::Algebraic => Some(EdgeFunctions3::arclength(faces)),
        ControlKind::Laplace => None,
    };
    // The finest level's control functions first: a degenerate bilinear transformation is
    // reported at its fine node (the coarse (s, t, u) grids are sub-samples of it).
    let fine_ctrl = match &ef {
        Some(ef) => Control3::from_algebraic(&bilinear(ef, place)?),
        None => Control3::zeros(faces.dims()),
    };
    let tf = transfinite(faces);
    let mut levels = Vec::new();
    // converged displacements of the two previous (coarser) levels, the last one first
    let mut prev: Option<(Grid3, Option<Grid3>)> = None;
    for lev in (0..sizes.len()).rev() {
        let tl = Instant::now();
        let stride = 1 << lev;
        let [ni, nj, nk] = sizes[lev];
        let t_lev = if lev == 0 {
            tf.clone()
        } else {
            subsample(&tf, stride)
        };
        let lev_place = if lev == 0 {
            place.to_string()
        } else {
            format!("{place} (nested level {ni} × {nj} × {nk})")
        };
        let coarse_ctrl;
        let ctrl = match &ef {
            _ if lev == 0 => &fine_ctrl,
            Some(ef) => {
                coarse_ctrl =
                    Control3::from_algebraic(&bilinear(&subsample_edges(ef, stride), place)?);
                &coarse_ctrl
            }
            None => {
                coarse_ctrl = Control3::zeros(sizes[lev]);
                &coarse_ctrl
            }
        };
        let mut x = match &prev {
            None => t_lev.clone(),
            Some((d2, d4)) => {
                let d = match d4 {
                    Some(d4) => extrapolate(d2, &prolong(d4)),
                    None => d2.clone(),
                };
                zip_with(&t_lev, &prolong(&d), |u, v| u + v)
            }
        };
        if lev == 0 {
            let (mut picard, wu) =
                poisson3d::solve_timed(&mut x, ctrl, solver, params, 0.0, place, progress)?;
            levels.push(LevelInfo3 {
                ni,
                nj,
                nk,
                steps: picard.steps,
                converged: picard.converged,
                seconds: tl.elapsed().as_secs_f64(),
            });
            let total = t0.elapsed().as_secs_f64();
            picard.work_units = Some(total / wu);
            picard.coarse_steps = levels[..levels.len() - 1].iter().map(|l| l.steps).collect();
            let info = NestedInfo3 {
                levels,
                seconds: total,
                work_unit_seconds: wu,
                work_units: total / wu,
            };
            return Ok((VolumeResult { grid: x, picard }, info));
        }
        let r = poisson3d::solve_timed(
            &mut x,
            ctrl,
            solver,
            params,
            COARSE_STOP,
            &lev_place,
            &mut |_, _| {},
        );
        let (steps, converged) = match &r {
            Ok((p, _)) => (p.steps, p.converged),
            Err(_) => (0, false),
        };
        levels.push(LevelInfo3 {
            ni,
            nj,
            nk,
            steps,
            converged,
            seconds: tl.elapsed().as_secs_f64(),
        });
        prev = if converged {
            let d = zip_with(&x, &t_lev, |u, v| u - v);
            Some((d, prev.map(|(d2, _)| d2)))
        } else {
            None
        };
    }
    unreachable!("the finest level returns")
}

/// Every `stride`-th node of `g` in each direction.
fn subsample(g: &Grid3, stride: usize) -> Grid3 {
    let d = g.dims().map(|n| (n - 1) / stride + 1);
    Grid3::from_fn(d[0], d[1], d[2], |i, j, k| {
        g.point(i * stride, j * stride, k * stride)
    })
}

/// Every `stride`-th value of the twelve edge functions.
fn subsample_edges(ef: &EdgeFunctions3, stride: usize) -> EdgeFunctions3 {
    let sub = |v: &[Vec<f64>; 4]| -> [Vec<f64>; 4] {
        std::array::from_fn(|e| v[e].iter().step_by(stride).copied().collect())
    };
    EdgeFunctions3 {
        s: sub(&ef.s),
        t: sub(&ef.t),
        u: sub(&ef.u),
    }
}

fn zip_with(a: &Grid3, b: &Grid3, f: impl Fn(f64, f64) -> f64 + Sync) -> Grid3 {
    let [ni, nj, nk] = a.dims();
    let coords = std::array::from_fn(|c| {
        a.coord(c)
            .par_iter()
            .zip(b.coord(c))
            .map(|(&u, &v)| f(u, v))
            .collect()
    });
    Grid3::from_coords(ni, nj, nk, coords)
}

/// Richardson extrapolation of the displacement `d2` (level 2h) with `p4` (level 4h
/// interpolated to 2h), assuming an O(h²) difference between the levels.
fn extrapolate(d2: &Grid3, p4: &Grid3) -> Grid3 {
    zip_with(d2, p4, richardson)
}

/// Cubic interpolation in index space along axis `ax` of the array `v` of dims `d` to the
/// array with that axis's cells halved (rayon over output k-planes).
fn prolong_axis(v: &[f64], d: [usize; 3], ax: usize) -> (Vec<f64>, [usize; 3]) {
    let mut e = d;
    e[ax] = 2 * d[ax] - 1;
    let plane = e[0] * e[1];
    let mut out = vec![0.0; plane * e[2]];
    let at = |s: [usize; 3]| v[s[0] + d[0] * (s[1] + d[1] * s[2])];
    out.par_chunks_mut(plane).enumerate().for_each(|(k, op)| {
        for j in 0..e[1] {
            for i in 0..e[0] {
                let mut s = [i, j, k];
                let m = s[ax];
                op[i + e[0] * j] = if m % 2 == 0 {
                    s[ax] = m / 2;
                    at(s)
                } else {
                    let (s0, w) = mid_weights(m / 2, d[ax]);
                    let mut acc = 0.0;
                    for (q, wq) in w.iter().enumerate() {
                        if *wq != 0.0 {
                            s[ax] = s0 + q;
                            acc += wq * at(s);
                        }
                    }
                    acc
                };
            }
        }
    });
    (out, e)
}

/// Tensor-product cubic interpolation in index space from a grid to the one with every cell
/// halved in each direction.
fn prolong(g: &Grid3) -> Grid3 {
    let mut dims = g.dims();
    let coords = std::array::from_fn(|c| {
        let (mut v, mut d) = (g.coord(c).to_vec(), g.dims());
        for ax in 0..3 {
            (v, d) = prolong_axis(&v, d, ax);
        }
        dims = d;
        v
    });
    Grid3::from_coords(dims[0], dims[1], dims[2], coords)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn level_sizes_coarsen_odd_sizes_only() {
        assert_eq!(level_sizes3([65, 33, 17]), vec![[65, 33, 17], [33, 17, 9]]);
        assert_eq!(
            level_sizes3([33, 33, 33]),
            vec![[33, 33, 33], [17, 17, 17], [9, 9, 9]]
        );
        assert_eq!(level_sizes3([33, 32, 33]), vec![[33, 32, 33]]);
        assert_eq!(level_sizes3([9, 9, 9]), vec![[9, 9, 9]]);
    }

    #[test]
    fn prolongation_is_exact_for_tricubics() {
        let f = |i: f64, j: f64, k: f64| {
            [
                i * i * i - 2.0 * i * j * k + k * k,
                0.5 * j * j * j - i * k * k,
                k * k * k + i * j * j - 3.0 * j,
            ]
        };
        let g = Grid3::from_fn(7, 5, 4, |i, j, k| {
            f(2.0 * i as f64, 2.0 * j as f64, 2.0 * k as f64)
        });
        let p = prolong(&g);
        assert_eq!(p.dims(), [13, 9, 7]);
        for k in 0..7 {
            for j in 0..9 {
                for i in 0..13 {
                    let (u, v) = (p.point(i, j, k), f(i as f64, j as f64, k as f64));
                    for c in 0..3 {
                        assert!((u[c] - v[c]).abs() < 1e-10, "{u:?} vs {v:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn subsampled_edge_functions_give_the_subsampled_bilinear_grid() {
        let g = Grid3::from_fn(9, 9, 9, |i, j, k| {
            let (x, y, z) = (i as f64 / 8.0, (j as f64 / 8.0).powi(2), k as f64 / 8.0);
            [x + 0.2 * y * z, y + 0.1 * x * x, z + 0.15 * x * y]
        });
        let ef = EdgeFunctions3::arclength(&Faces::from_grid(&g));
        let fine = bilinear(&ef, "b").unwrap();
        let coarse = bilinear(&subsample_edges(&ef, 2), "b").unwrap();
        for k in 0..5 {
            for j in 0..5 {
                for i in 0..5 {
                    let (pc, pf) = (i + 5 * (j + 5 * k), 2 * i + 9 * (2 * j + 9 * 2 * k));
                    assert_eq!(coarse.at(pc), fine.at(pf));
                }
            }
        }
    }
}
