//! Nested iteration for the volume grid system [86]–[88]: the volume side of
//! [`crate::elliptic::nested`], whose level loop, rules and [`NestedInfo`] it uses; here are
//! what differs in 3D: the control functions of a coarse level and the tensor-product
//! prolongation.
//!
//! # Levels
//! Coarsening goes on while all three dimensions are odd and the coarser level keeps at least
//! [`MIN_NODES`](crate::elliptic::nested::MIN_NODES) nodes each way; a block with an even
//! dimension is solved by plain Picard.
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
//! The displacement d = x − x_T from the transfinite grid is interpolated by tensor-product
//! cubic interpolation in index space (one direction after the other), then as in 2D
//! (Richardson's step with two coarse levels, [`COARSE_STOP`](crate::elliptic::nested::COARSE_STOP)
//! on coarse levels, failed levels skipped).
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
use crate::algebraic::flat_edge::edge_functions;
use crate::algebraic::transfinite3d::transfinite;
use crate::algebraic::ControlKind;
use crate::elliptic::nested::{
    mid_weights, run, sizes, zip_coords, LevelGrid, LevelInfo, NestedInfo, Problem,
};
use crate::elliptic::picard::VolumeResult;
use crate::elliptic::picard::{PicardParams, PicardStep, Rules};
use crate::elliptic::poisson3d;
use crate::grid::faces::Faces;
use crate::solve::stencil19::Stencil19;
use crate::solve::LinearSolver;
use crate::{Grid3, Result};
use rayon::prelude::*;
use std::borrow::Cow;
use std::time::Instant;

/// One level of a nested volume solve (the same as a 2D one's).
pub type LevelInfo3 = LevelInfo;

/// What a (nested) volume grid generation cost (the same as a 2D one's).
pub type NestedInfo3 = NestedInfo;

/// Whether nested iteration is used for a volume block with the solver called `solver_name`:
/// `params.nested` if set, else [`PicardParams::nested_for`] (on with "multigrid") or the
/// Bi-CGSTAB/ILU(0) solver ("bicgstab-ilu0"), for which it measured faster (module docs).
pub fn nested_for3(params: &PicardParams, solver_name: &str) -> bool {
    params.nested_for(solver_name) || (params.nested.is_none() && solver_name == "bicgstab-ilu0")
}

/// Grid sizes of the nested levels, finest first (module docs).
pub fn level_sizes3(dims: [usize; 3]) -> Vec<[usize; 3]> {
    sizes(dims)
}

/// A volume block: its transfinite grid, its arclength edge functions (algebraic control
/// functions) and the finest level's control functions.
struct Volume {
    tf: Grid3,
    ef: Option<EdgeFunctions3>,
    fine_ctrl: Control3,
}

impl Problem for Volume {
    type Grid = Grid3;
    type Ctrl = Control3;

    fn transfinite(&self) -> &Grid3 {
        &self.tf
    }

    /// [83, 84] of the bilinear (s, t, u) grid of the sub-sampled edge functions, or zero.
    fn control(&self, lev: usize, dims: &[usize], place: &str) -> Result<Cow<'_, Control3>> {
        Ok(match &self.ef {
            Some(ef) => Cow::Owned(Control3::from_algebraic(&bilinear(
                &subsample_edges(ef, 1 << lev),
                place,
            )?)),
            None => Cow::Owned(Control3::zeros([dims[0], dims[1], dims[2]])),
        })
    }

    /// The finest level's control functions, computed up front (see [`grid_volume_nested`]).
    fn finest_control(self, _dims: &[usize], _place: &str) -> Result<Control3> {
        Ok(self.fine_ctrl)
    }
}

/// Grids one volume block from its faces with `kind` control functions, by nested iteration
/// if [`nested_for3`] (else plain Picard from the transfinite grid), and reports the cost in
/// work units. The returned [`PicardInfo`](crate::elliptic::picard::PicardInfo) is that of the finest
/// level, with `work_units` and `coarse_steps` filled in; `progress` sees the finest level's
/// steps only.
pub fn grid_volume_nested(
    faces: &Faces,
    kind: ControlKind,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<(VolumeResult, NestedInfo)> {
    let t0 = Instant::now();
    let sizes = if nested_for3(params, solver.name()) {
        sizes(faces.dims())
    } else {
        vec![faces.dims()]
    };
    let ef = match kind {
        ControlKind::Algebraic => Some(edge_functions(faces)),
        ControlKind::Laplace => None,
    };
    // The finest level's control functions first: a degenerate bilinear transformation is
    // reported at its fine node (the coarse (s, t, u) grids are sub-samples of it).
    let fine_ctrl = match &ef {
        Some(ef) => Control3::from_algebraic(&bilinear(ef, place)?),
        None => Control3::zeros(faces.dims()),
    };
    let volume = Volume {
        tf: transfinite(faces),
        ef,
        fine_ctrl,
    };
    let multigrid = solver.name() == "multigrid";
    run(volume, &sizes, place, t0, |x, ctrl, stop, at, finest| {
        let rules = level_rules(multigrid, stop);
        if finest {
            poisson3d::solve_timed(x, ctrl, solver, params, rules, at, progress)
        } else {
            poisson3d::solve_timed(x, ctrl, solver, params, rules, at, &mut |_, _| {})
        }
    })
}

/// The nested volume multigrid's forcing ratio: a fine step's linear solves stop at
/// `η = min(3 ρ, linear_forcing)` of their residual (ρ the observed Picard contraction)
/// instead of 0.5 ρ. With the contraction of 0.04–0.1 seen after nested iteration that is one
/// V-cycle per coordinate and step (a cycle leaves 4–9e-2 of the residual): the 129³ warped
/// box of `examples/bench_memory.rs` takes 5 fine steps of 3 cycles (15) where 0.5 ρ took 4
/// steps of 18 cycles, and a step (one assembly + residual, ~1 WU) costs less than the three
/// cycles (~2.2 WU each) it saves. The stop counts the linear error (`picard::error_estimate`):
/// true error 1.1e-11 of the diameter there against 7.8e-12 before (a 1e-13 solution as the
/// reference).
pub const MULTIGRID_FORCING_RATIO: f64 = 3.0;

/// The nested volume multigrid's coarse levels stop at this fraction of their first update
/// (the 2D and Bi-CGSTAB levels at [`COARSE_STOP`](crate::elliptic::nested::COARSE_STOP),
/// 1e-3): 2 steps instead of 3 on the 65³ and 33³ levels of the 129³ box, the fine updates
/// the same to two digits (7.33e-6, 2.64e-7 against 7.33e-6, 2.65e-7).
pub const MULTIGRID_COARSE_STOP: f64 = 3e-2;

/// The nested volume multigrid's levels set the multigrid up afresh only after a step whose
/// update was above this (relative to the diameter; else they keep its coarse levels and plane
/// smoothers, [`LinearSolver::update`]); [`picard::SMALL_CHANGE`](crate::elliptic::picard::SMALL_CHANGE)
/// (1e-5) elsewhere. The solves are in correction form, so a smoother of the operator of the
/// step before only changes the cycles' rate, not the solution: the second step of the 65³
/// level of the 129³ box (update 3.5e-5 before it) took one cycle per coordinate either way and
/// saved its setup (0.3 s CPU); the 65³ box as the finest level, the same: 2.93, 2.99 → 2.55,
/// 2.57 s CPU, the grid 1.3e-13 of the diameter from before.
pub const MULTIGRID_SMALL_CHANGE: f64 = 1e-3;

/// The Picard rules of a level that stops at `stop` times its first update (0 on the finest
/// level) with the multigrid (`multigrid`) or another solver.
fn level_rules(multigrid: bool, stop: f64) -> Rules {
    match (multigrid, stop > 0.0) {
        (false, _) => Rules::stop(stop),
        (true, coarse) => Rules {
            relative_stop: if coarse { MULTIGRID_COARSE_STOP } else { 0.0 },
            coarser_first: 0.0,
            forcing_ratio: MULTIGRID_FORCING_RATIO,
            small_change: MULTIGRID_SMALL_CHANGE,
        },
    }
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

impl LevelGrid for Grid3 {
    fn subsample(&self, stride: usize) -> Self {
        let d = self.dims().map(|n| (n - 1) / stride + 1);
        Grid3::from_fn(d[0], d[1], d[2], |i, j, k| {
            self.point(i * stride, j * stride, k * stride)
        })
    }

    fn zip_with(&self, b: &Self, f: impl Fn(f64, f64) -> f64 + Sync) -> Self {
        let [ni, nj, nk] = self.dims();
        let coords = std::array::from_fn(|c| zip_coords(self.coord(c), b.coord(c), &f));
        Grid3::from_coords(ni, nj, nk, coords)
    }

    /// Tensor-product: along i, then j, then k.
    fn prolong(&self) -> Self {
        let mut dims = self.dims();
        let coords = std::array::from_fn(|c| {
            let (mut v, mut d) = (self.coord(c).to_vec(), self.dims());
            for ax in 0..3 {
                (v, d) = prolong_axis(&v, d, ax);
            }
            dims = d;
            v
        });
        Grid3::from_coords(dims[0], dims[1], dims[2], coords)
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The warped box of `examples/bench_volume.rs`, clustered to a first spacing ~1e-3 at
    /// j = 0, at n³ nodes.
    fn warped_box(n: usize) -> Faces {
        let h = (n - 1) as f64;
        let g = Grid3::from_fn(n, n, n, |i, j, k| {
            let (x, z) = (i as f64 / h, k as f64 / h);
            let y = ((j as f64 / h) * 4.0).sinh() / 4f64.sinh();
            [
                x + 0.1 * (std::f64::consts::PI * y).sin() * z,
                y + 0.15 * (std::f64::consts::PI * x).sin() * (1.0 - y),
                z + 0.1 * x * y,
            ]
        });
        Faces::from_grid(&g)
    }

    /// The nested multigrid's looser rules (one V-cycle per coordinate and fine step, coarse
    /// levels stopped at 3e-2 of their first update) keep the stop honest: the grid is within
    /// its reported error estimate (below the tolerance) of a solution to 1e-13, and within
    /// the tolerance of Bi-CGSTAB's nested solve, which keeps the default rules.
    #[test]
    fn nested_multigrid_rules_keep_an_honest_stop() {
        use crate::elliptic::picard::error_estimate;
        use crate::solve::{ilu::BiCgStabIlu, multigrid3d::Multigrid3};
        let faces = warped_box(65);
        let solve = |solver: &mut dyn LinearSolver<Stencil19>, tolerance: f64| {
            let params = PicardParams {
                tolerance,
                ..PicardParams::default()
            };
            grid_volume_nested(
                &faces,
                ControlKind::Algebraic,
                solver,
                &params,
                "box",
                &mut |_, _| {},
            )
            .unwrap()
        };
        let (mg, info) = solve(&mut Multigrid3::default(), 1e-10);
        let (exact, _) = solve(&mut Multigrid3::default(), 1e-13);
        let (bi, _) = solve(&mut BiCgStabIlu::new(), 1e-10);
        assert!(mg.picard.converged && exact.picard.converged && bi.picard.converged);
        let diam = mg.grid.diameter();
        let off = |g: &Grid3| {
            (0..3)
                .flat_map(|c| mg.grid.coord(c).iter().zip(g.coord(c)))
                .fold(0.0f64, |m, (u, v)| m.max((u - v).abs()))
                / diam
        };
        let (err, estimate) = (off(&exact.grid), error_estimate(&mg.picard.history));
        let steps: Vec<usize> = info.levels.iter().map(|l| l.steps).collect();
        eprintln!(
            "65³ nested multigrid: steps {steps:?}, error {err:.2e} (estimate {estimate:.2e}), \
             {:.2e} from Bi-CGSTAB's",
            off(&bi.grid)
        );
        assert!(
            estimate < 1e-10 && err <= estimate + 1e-13,
            "{err:e} {estimate:e}"
        );
        assert!(off(&bi.grid) <= 1e-10);
        // the rules are in force: one cycle per coordinate and fine step, two steps on the
        // 33³ level (three with the default coarse stop)
        for s in &mg.picard.history {
            assert_eq!(s.linear_iterations, [1, 1, 1], "{:?}", mg.picard.history);
        }
        assert_eq!(mg.picard.coarse_steps.last(), Some(&2), "{steps:?}");
    }

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
        let p = g.prolong();
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
