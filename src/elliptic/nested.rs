//! Nested iteration for the grid systems [24] (2D blocks) and [86]–[88] (volume blocks): solve
//! them on coarser grids first, so that the Picard iteration [43, 44] on the finest grid starts
//! next to its solution. One level loop (`run`) serves both dimensions; what differs (the grid
//! type's sub-sampling and prolongation, a level's control functions and Picard solve) comes
//! through the traits `LevelGrid` and `Problem`. The volume side is in
//! [`crate::elliptic::nested3d`].
//!
//! # Levels
//! Level ℓ keeps every 2^ℓ-th node of the block in each direction. A dimension of `n` nodes
//! coarsens exactly when `n` is odd (`(n − 1) / 2 + 1` nodes); coarsening stops when any
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
//! index space. A coarse level stops at [`COARSE_STOP`] times its first update
//! ([`COARSE_STOP_NEWTON`] with Newton steps, raised where the first updates of the levels
//! do not fall as fast as on a smooth domain: `picard::stop::stop_threshold`), or at the
//! Picard tolerance; the finest at the Picard tolerance. A level whose Picard iteration fails
//! or does not converge is skipped: the next level starts from the transfinite grid (as
//! without nesting).
//!
//! A full-approximation-scheme correction of the finest level from the level below (its
//! residual restricted as a source of the coarse problem, the coarse change prolonged) was
//! tried on the dented square and not kept: it halves the next fine Newton update at best and
//! saves no fine step (docs/PERFORMANCE.md, "What limits the dented domain").
//!
//! Measured (`examples/bench_grid.rs`, curved domain): 3 Picard steps on the finest grid at
//! 257²–1025², against 11 for plain Picard (4 against 6 on the boundary layer of aspect ratio
//! 1.5e4); the grids agree with plain Picard's to 1.1e-10 of the diameter. (Two steps would
//! do at 1025², but the stop needs two ratios of successive updates: after a prediction the
//! first ratio says nothing of the contraction, see `picard::error_estimate`.)
//!
//! # Work units
//! A work unit (WU) is the time of one evaluation of the residual of [24] with its assembly
//! ([`poisson2d::assemble`] + [`poisson2d::residual`]) on the finest grid, measured in the
//! same run (the shortest of the evaluations of the fine Picard steps); the whole generation,
//! from the boundary to the final grid, is reported in WU.

use crate::algebraic::control2d::Control2;
use crate::algebraic::transform::{straight_line, transfinite, ParamGrid};
use crate::algebraic::ControlKind;
use crate::elliptic::picard::{Nonlinear, PicardInfo, PicardParams, Rules, Solved};
use crate::elliptic::poisson2d;
use crate::grid::arclength::EdgeFunctions;
use crate::grid::boundary::Boundary2;
use crate::grid::Grid2;
use crate::solve::LinearSolver;
use crate::Result;
use rayon::prelude::*;
use std::borrow::Cow;
use std::time::Instant;

/// The coarsest level keeps at least this many nodes in each direction.
pub const MIN_NODES: usize = 9;

/// A coarse level stops when its Picard update falls below this fraction of its first update
/// (or below the Picard tolerance): its remaining Picard error is then small against the
/// error of the prediction it will give the next level, which the observed first updates put
/// at a third of this level's first update or more.
pub const COARSE_STOP: f64 = 1e-3;

/// [`COARSE_STOP`] for Newton steps ([`crate::elliptic::newton`]): a coarse level of Newton
/// steps stops at this fraction of its first update. Its remaining error is then at most a
/// tenth of the prediction error it leaves the next level (a third of this level's first
/// update or more, see [`COARSE_STOP`]), and the next level's Newton steps remove both at
/// the same rate, while Picard steps would remove the slow part of it slowly.
///
/// Measured side by side (`examples/bench_grid.rs --newton`, 1025², and the NACA0012 O-grid
/// of `examples/bench_multiblock.rs` at 4 × 257²): the same fine Newton steps as with
/// [`COARSE_STOP`], one or two Newton steps fewer on every coarse level (folded start:
/// 143 → 114 WU; curved 68 → 51 WU), where Picard steps stopped at 3e-2 (or 1e-2) needed 11
/// fine steps instead of 9 on the folded start.
///
/// Where the first updates fall by less than a third per level (the dented square: 4.3e-3,
/// 3.9e-3, 2.2e-3 at 257², 513², 1025²), the next level starts as far off as this one did and
/// the stop is raised in proportion, up to 0.1 (`picard::stop::PREDICTED_SHARE`): dented
/// square at 1025², coarse steps 4 → 3 on the 129²–513² levels, the same fine steps, 1.95 →
/// 1.86 s (fastest of six runs each, binaries alternating); the other bench cases' fine steps
/// unchanged.
pub const COARSE_STOP_NEWTON: f64 = 3e-2;

/// The relative stop of a level whose stop is `stop` ([`COARSE_STOP`] on a coarse level, 0
/// on the finest) for the nonlinear iteration of `params` on a grid of `D` coordinates.
fn level_stop<const D: usize>(params: &PicardParams, stop: f64) -> f64 {
    if stop > 0.0 && params.iteration(D) == Nonlinear::Newton {
        COARSE_STOP_NEWTON
    } else {
        stop
    }
}

/// One level of a nested solve.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LevelInfo {
    /// Nodes along i, j (and k for a volume block).
    pub dims: Vec<usize>,
    /// Picard steps on this level.
    pub steps: usize,
    /// True if this level's Picard iteration converged (its grid then starts the next level).
    pub converged: bool,
    /// Wall-clock seconds of this level (prolongation and control functions included).
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
    /// Seconds of one work unit: one assembly + residual of [24] (or [86]) on the finest grid.
    pub work_unit_seconds: f64,
    /// `seconds / work_unit_seconds`.
    pub work_units: f64,
}

/// Grid sizes of the nested levels of a block of `dims` nodes, finest first (module docs).
pub(crate) fn sizes<const N: usize>(dims: [usize; N]) -> Vec<[usize; N]> {
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

/// Grid sizes of the nested levels of a 2D block, finest first (see the module documentation).
pub fn level_sizes(ni: usize, nj: usize) -> Vec<(usize, usize)> {
    sizes([ni, nj]).into_iter().map(|[a, b]| (a, b)).collect()
}

/// What nested iteration needs of a grid type ([`Grid2`], [`crate::Grid3`]).
pub(crate) trait LevelGrid: Clone {
    /// Every `stride`-th node in each direction.
    fn subsample(&self, stride: usize) -> Self;
    /// Cubic interpolation in index space to the grid with every cell halved.
    fn prolong(&self) -> Self;
    /// `f` of the coordinates of `self` and `b` (same size), node by node.
    fn zip_with(&self, b: &Self, f: impl Fn(f64, f64) -> f64 + Sync) -> Self;
}

/// One block's nested problem: its finest transfinite grid and its levels' control functions.
pub(crate) trait Problem: Sized {
    type Grid: LevelGrid;
    type Ctrl: Clone;
    /// The transfinite grid x_T of the finest level.
    fn transfinite(&self) -> &Self::Grid;
    /// Control functions of a coarse level `lev ≥ 1` (stride 2^lev) of `dims` nodes; `place`
    /// for errors.
    fn control(&self, lev: usize, dims: &[usize], place: &str) -> Result<Cow<'_, Self::Ctrl>>;
    /// Control functions of the finest level (`dims` nodes); drops everything else of the
    /// problem.
    fn finest_control(self, dims: &[usize], place: &str) -> Result<Self::Ctrl>;
    /// The grid a level starts from when no coarser level has given it one (the coarsest
    /// level, or after a failed level): `None` for the transfinite grid.
    fn start(&self, _lev: usize) -> Option<Self::Grid> {
        None
    }
}

/// `f(u, v)` of two coordinate arrays, element by element (rayon).
pub(crate) fn zip_coords(a: &[f64], b: &[f64], f: &(impl Fn(f64, f64) -> f64 + Sync)) -> Vec<f64> {
    a.par_iter().zip(b).map(|(&u, &v)| f(u, v)).collect()
}

/// The level loop of nested iteration over `sizes` (finest first), `t0` the start of the
/// whole generation. `solve(x, ctrl, relative_stop, place, finest)` is the Picard solve of a
/// level (`poisson2d::solve_timed` / `poisson3d::solve_timed`), returning its info and the
/// work unit in seconds. The returned [`PicardInfo`] is that of the finest level, with
/// `work_units` and `coarse_steps` filled in.
///
/// The finest level takes the problem's control functions by [`Problem::finest_control`],
/// which drops the problem (its transfinite grid, the (s, t) grid): during the finest solve,
/// the largest of the generation, only the grid, its control functions and the solver's own
/// memory are held.
pub(crate) fn run<P: Problem, const N: usize>(
    p: P,
    sizes: &[[usize; N]],
    place: &str,
    t0: Instant,
    mut solve: impl FnMut(&mut P::Grid, &P::Ctrl, f64, &str, bool) -> Result<(PicardInfo, f64)>,
) -> Result<(Solved<P::Grid>, NestedInfo)> {
    let mut levels = Vec::new();
    // converged displacements of the two previous (coarser) levels, the last one first
    let mut prev: Option<(P::Grid, Option<P::Grid>)> = None;
    for lev in (1..sizes.len()).rev() {
        let tl = Instant::now();
        let dims = sizes[lev];
        let t_lev = p.transfinite().subsample(1 << lev);
        let ctrl = p.control(lev, &dims, place)?;
        let mut x = level_start(&p, lev, &t_lev, &prev);
        let n: Vec<String> = dims.iter().map(usize::to_string).collect();
        let lev_place = format!("{place} (nested level {})", n.join(" × "));
        let r = solve(&mut x, &ctrl, COARSE_STOP, &lev_place, false);
        let (steps, converged) = match &r {
            Ok((p, _)) => (p.steps, p.converged),
            Err(_) => (0, false),
        };
        levels.push(LevelInfo {
            dims: dims.to_vec(),
            steps,
            converged,
            seconds: tl.elapsed().as_secs_f64(),
        });
        prev = if converged {
            let d = x.zip_with(&t_lev, |u, v| u - v);
            Some((d, prev.map(|(d2, _)| d2)))
        } else {
            None
        };
    }
    let tl = Instant::now();
    let dims = sizes[0];
    let mut x = level_start(&p, 0, p.transfinite(), &prev);
    drop(prev);
    let ctrl = p.finest_control(&dims, place)?;
    let (mut picard, wu) = solve(&mut x, &ctrl, 0.0, place, true)?;
    levels.push(LevelInfo {
        dims: dims.to_vec(),
        steps: picard.steps,
        converged: picard.converged,
        seconds: tl.elapsed().as_secs_f64(),
    });
    let total = t0.elapsed().as_secs_f64();
    picard.work_units = Some(total / wu);
    picard.coarse_steps = levels[..levels.len() - 1].iter().map(|l| l.steps).collect();
    let info = NestedInfo {
        levels,
        seconds: total,
        work_unit_seconds: wu,
        work_units: total / wu,
    };
    Ok((Solved { grid: x, picard }, info))
}

/// The grid level `lev` starts from: the transfinite grid `t_lev` of the level plus the
/// prolonged (Richardson-extrapolated) displacement of the coarser levels, or without them
/// the problem's start grid ([`Problem::start`]) or `t_lev`.
fn level_start<P: Problem>(
    p: &P,
    lev: usize,
    t_lev: &P::Grid,
    prev: &Option<(P::Grid, Option<P::Grid>)>,
) -> P::Grid {
    match prev {
        None => p.start(lev).unwrap_or_else(|| t_lev.clone()),
        Some((d2, d4)) => {
            let d = match d4 {
                Some(d4) => d2.zip_with(&d4.prolong(), richardson),
                None => d2.clone(),
            };
            t_lev.zip_with(&d.prolong(), |u, v| u + v)
        }
    }
}

/// Richardson's step for an O(h²) difference between the displacement `d2` (level 2h) and
/// `p4` (level 4h interpolated to 2h): `d2 + (d2 − p4) / 4`.
#[inline]
fn richardson(d2: f64, p4: f64) -> f64 {
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

/// A 2D block: its transfinite grid, for algebraic control functions its (s, t) grid, and
/// the grid (if any) that a level starts from instead of the transfinite one.
struct Block<const D: usize> {
    tf: Grid2<D>,
    pg: Option<ParamGrid>,
    start: Option<Grid2<D>>,
}

impl<const D: usize> Problem for Block<D> {
    type Grid = Grid2<D>;
    type Ctrl = Control2;

    fn transfinite(&self) -> &Grid2<D> {
        &self.tf
    }

    /// [19, 20] of the fine (s, t) grid sub-sampled, or zero (Laplace).
    fn control(&self, lev: usize, dims: &[usize], _place: &str) -> Result<Cow<'_, Control2>> {
        Ok(Cow::Owned(match &self.pg {
            Some(pg) => Control2::from_algebraic(&subsample_param(pg, 1 << lev)),
            None => Control2::zeros([dims[0], dims[1]]),
        }))
    }

    /// [19, 20] of the (s, t) grid, or zero (Laplace).
    fn finest_control(self, dims: &[usize], _place: &str) -> Result<Control2> {
        Ok(match &self.pg {
            Some(pg) => Control2::from_algebraic(pg),
            None => Control2::zeros([dims[0], dims[1]]),
        })
    }

    fn start(&self, lev: usize) -> Option<Grid2<D>> {
        self.start.as_ref().map(|g| g.subsample(1 << lev))
    }
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
) -> Result<(crate::elliptic::picard::BlockResult<D>, NestedInfo)> {
    let t0 = Instant::now();
    let sizes = if params.nested_for(solver.name()) {
        sizes([b.ni(), b.nj()])
    } else {
        vec![[b.ni(), b.nj()]]
    };
    let pg = match kind {
        ControlKind::Algebraic => Some(straight_line(&EdgeFunctions::arclength(b))),
        ControlKind::Laplace => None,
    };
    let block = Block {
        tf: transfinite(b),
        pg,
        start: None,
    };
    run(block, &sizes, place, t0, level_solve::<D>(solver, params))
}

/// Solves [24] with the algebraic control functions of the (s, t) grid `pg` (on coarse levels:
/// `pg` sub-sampled), every level without a coarser prediction starting from `start`
/// sub-sampled: step 3 of Section 2.4 ([`crate::elliptic::orthogonal`]), nested as
/// [`grid_block_nested`]. `t0` is the start of the whole generation (for the work units).
pub(crate) fn solve_nested_from<const D: usize>(
    b: &Boundary2<D>,
    start: Grid2<D>,
    pg: ParamGrid,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
    t0: Instant,
) -> Result<(Solved<Grid2<D>>, NestedInfo)> {
    let sizes = if params.nested_for(solver.name()) {
        sizes([b.ni(), b.nj()])
    } else {
        vec![[b.ni(), b.nj()]]
    };
    let block = Block {
        tf: transfinite(b),
        pg: Some(pg),
        start: Some(start),
    };
    run(block, &sizes, place, t0, level_solve::<D>(solver, params))
}

/// The level solve of the 2D nested iterations: [24] to the level's stop ([`level_stop`]).
/// The finest level starts with Newton steps where the level below it took them: the slow
/// Picard contraction that made Newton worth it there is the finest level's too, and the
/// Picard steps that would first observe it again cost the finest level two or three steps
/// (NACA0012 O-grid at 4 × 257²: fine steps 7 → 5 in step 1 of Section 2.4, 6 → 5 in step 3).
/// Coarse levels keep their Picard start: there Newton steps cost more than they save.
fn level_solve<'a, const D: usize>(
    solver: &'a mut dyn LinearSolver,
    params: &'a PicardParams,
) -> impl FnMut(&mut Grid2<D>, &Control2, f64, &str, bool) -> Result<(PicardInfo, f64)> + 'a {
    let mut newton_below = false;
    // the first update of the level below (0 after a failed level)
    let mut coarser_first = 0.0;
    move |x, ctrl, stop, at, finest| {
        let mut rules = Rules::stop(level_stop::<D>(params, stop));
        if params.iteration(D) == Nonlinear::Newton {
            rules.coarser_first = coarser_first;
        }
        let r = poisson2d::solve_level(x, ctrl, solver, params, rules, finest && newton_below, at);
        newton_below = r
            .as_ref()
            .is_ok_and(|(info, _)| info.history.iter().any(|h| h.newton));
        coarser_first = r.as_ref().map_or(0.0, |(info, _)| {
            info.history.first().map_or(0.0, |h| h.update)
        });
        r
    }
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

impl<const D: usize> LevelGrid for Grid2<D> {
    fn subsample(&self, stride: usize) -> Self {
        let ni = (self.ni() - 1) / stride + 1;
        let nj = (self.nj() - 1) / stride + 1;
        Grid2::from_fn(ni, nj, |i, j| self.point(i * stride, j * stride))
    }

    fn zip_with(&self, b: &Self, f: impl Fn(f64, f64) -> f64 + Sync) -> Self {
        let coords = std::array::from_fn(|c| zip_coords(self.coord(c), b.coord(c), &f));
        Grid2::from_coords(self.ni(), self.nj(), coords)
    }

    /// Along i on the coarse rows, then whole rows along j.
    fn prolong(&self) -> Self {
        let (mi, mj) = (self.ni(), self.nj());
        let (fi, fj) = (2 * mi - 1, 2 * mj - 1);
        let coords = std::array::from_fn(|c| {
            let v = self.coord(c);
            // along i: the fine-i values on the coarse rows
            let mut rows = vec![0.0; fi * mj];
            rows.par_chunks_mut(fi).enumerate().for_each(|(j, out)| {
                let src = &v[j * mi..(j + 1) * mi];
                for k in 0..mi {
                    out[2 * k] = src[k];
                    if k + 1 < mi {
                        let (s0, w) = mid_weights(k, mi);
                        out[2 * k + 1] =
                            (0..4).map(|q| w[q] * src.get(s0 + q).unwrap_or(&0.0)).sum();
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
        let p = g.prolong();
        assert_eq!((p.ni(), p.nj()), (13, 9));
        for j in 0..9 {
            for i in 0..13 {
                let (u, v) = (p.point(i, j), f(i as f64, j as f64));
                assert!((u[0] - v[0]).abs() < 1e-10 && (u[1] - v[1]).abs() < 1e-10);
            }
        }
    }
}
