//! Alternating plane Gauss–Seidel (Dendy's BoxMG-3D smoother): every grid plane normal to
//! direction `d` is relaxed at once, its nine in-plane couplings solved approximately by one
//! V-cycle ([`plane_params`]) of the 2D black-box multigrid ([`crate::solve::multigrid::Multigrid`],
//! set up per plane), the 18 off-plane couplings frozen. Planes of one parity of their index
//! do not couple and run in parallel. Unlike line relaxation this also smooths two strongly
//! coupled directions (the wall-parallel directions in the outer part of a boundary-layer
//! grid, where the wall-normal spacing has grown beyond the tangential one).
//!
//! A sweep works in correction form: the residual b − A x of a plane's unknowns (all
//! couplings of the level's current operator), the plane's correction from zero by its 2D
//! cycle, added to x. With current plane solvers this is the same step as solving for the
//! plane's values; but it also keeps the cycle's fixed point exact when the plane solvers
//! lag behind the operator ([`crate::solve::multigrid3d::Multigrid3::update`] keeps them: a Picard step's
//! change of the operator, < 1e-5, does not change how well they smooth).
//!
//! The 2D solves take their workspaces from the 2D solver's pool; each records its one-entry
//! residual history (the only allocation of a smoothing step).

use crate::solve::multigrid::{Cycle, MgParams, Multigrid, SharedPool, Smoother};
use crate::solve::multigrid3d::level::{off27, Level};
use crate::solve::multigrid3d::{use_par, SharedPtr};
use crate::solve::stencil9::Stencil9;
use crate::solve::{LinearSolver, SolveControl, SolveError};
use rayon::prelude::*;

/// In-plane axes (e1 fastest, e2) of the planes normal to `d`.
#[inline]
fn axes(d: usize) -> (usize, usize) {
    [(1, 2), (0, 2), (0, 1)][d]
}

/// The 2D cycle that relaxes a plane: a V-cycle with x-lines before and y-lines after the
/// coarse-grid correction ([`Smoother::ZebraLineXY`]), half the line sweeps of the 2D default
/// (F-cycle, alternating lines). A plane solve is only part of a smoothing step, and the
/// cheaper cycle costs the 3D cycle little convergence: per 3D V-cycle at 129³ (benchmark
/// block, first Picard operator) 0.064 against 0.049, at 309 against 402 ns per unknown; the
/// whole 129³ volume grid 101–104 WU against 117 (`examples/bench_volume`, same machine).
fn plane_params() -> MgParams {
    MgParams {
        cycle: Cycle::V,
        smoother: Smoother::ZebraLineXY,
        ..MgParams::default()
    }
}

/// Columns of one colour per tile of the gather and scatter of x-normal planes.
const TILE: usize = 16;

/// A direction counts as weak at a point if its coupling is within this factor of the
/// weakest one there (see [`orientations`]).
const WEAK: f64 = 8.0;

/// The plane orientations a level needs. A plane normal to `d` smooths well at a point unless
/// `d` is coupled much more strongly than another direction there (then the strong `d`
/// coupling is left to the explicit part). So every point needs one orientation among its
/// weak directions `Q(p) = {d : s_d ≤ 8 min_e s_e}`, with the strength `s_d` the larger
/// magnitude of the two stencil sides collapsed onto direction `d` (mixed-derivative terms
/// cancel in the collapse; the larger side ignores a side cut off by the boundary). The smallest set of orientations meeting every `Q(p)` is used:
/// one for isotropic operators, two for the boundary-layer grids (wall-normal coupling strong
/// at the wall, weak in the outer part), three only when needed.
pub(super) fn orientations(lev: &Level) -> [bool; 3] {
    // the slots of the minus and plus sides of each direction
    let sides: [[Vec<usize>; 2]; 3] =
        std::array::from_fn(|e| [-1, 1].map(|v| (0..27).filter(|&m| off27(m)[e] == v).collect()));
    let mask_of = |row: &[f64; 27]| {
        let st: [f64; 3] = std::array::from_fn(|e| {
            let sum = |s: &Vec<usize>| s.iter().map(|&m| row[m]).sum::<f64>().abs();
            sum(&sides[e][0]).max(sum(&sides[e][1]))
        });
        let min = st[0].min(st[1]).min(st[2]);
        (0..3)
            .filter(|&e| st[e] <= WEAK * min)
            .fold(0usize, |m, e| m | 1 << e)
    };
    let mark = |mut seen: [bool; 8], p: usize| {
        seen[mask_of(&lev.row(p))] = true;
        seen
    };
    let merge = |a: [bool; 8], b: [bool; 8]| std::array::from_fn(|k| a[k] || b[k]);
    let seen: [bool; 8] = if use_par(lev.n()) {
        (0..lev.n())
            .into_par_iter()
            .fold(|| [false; 8], mark)
            .reduce(|| [false; 8], merge)
    } else {
        (0..lev.n()).fold([false; 8], mark)
    };
    // smallest subset (then the one with planes normal to z first: contiguous planes)
    let mut best = 7usize;
    for set in [4usize, 2, 1, 6, 5, 3, 7] {
        if (1..8).all(|mask| !seen[mask] || mask & set != 0) {
            best = set;
            break;
        }
    }
    std::array::from_fn(|d| best & (1 << d) != 0)
}

/// The 2D solvers of the planes normal to x, y and z of one level (only the orientations in
/// `on`).
#[derive(Debug, Default)]
pub(super) struct Planes {
    mg: [Vec<Multigrid>; 3],
    /// The cycle vectors of each orientation's planes (all of one size), shared: as many as
    /// plane solves run at once (one per solve of each plane would hold the level's vectors
    /// once per concurrent 3D solve).
    pools: [SharedPool; 3],
    on: [bool; 3],
}

impl Planes {
    /// Sets up (or refreshes) the 2D solvers of all planes of `lev`.
    pub fn setup(&mut self, lev: &Level) -> Result<(), SolveError> {
        let dims = lev.dims;
        let [nx, ny, _] = dims;
        self.on = orientations(lev);
        for d in 0..3 {
            let (e1, e2) = axes(d);
            let mgs = &mut self.mg[d];
            if !self.on[d] {
                mgs.clear();
                self.pools[d] = SharedPool::default();
                continue;
            }
            if mgs.len() != dims[d] {
                self.pools[d] = SharedPool::default();
                *mgs = (0..dims[d])
                    .map(|_| Multigrid::new(plane_params()))
                    .collect();
            }
            // in-plane slots and their nine-point positions
            let pairs: Vec<(usize, usize)> = (0..27)
                .filter(|&m| off27(m)[d] == 0)
                .map(|m| {
                    let o = off27(m);
                    (m, ((o[e1] + 1) + 3 * (o[e2] + 1)) as usize)
                })
                .collect();
            let one = |(t, mg): (usize, &mut Multigrid)| {
                let mut s = Stencil9::zeros(dims[e1], dims[e2]);
                for v in 0..dims[e2] {
                    for u in 0..dims[e1] {
                        let mut idx = [0; 3];
                        (idx[d], idx[e1], idx[e2]) = (t, u, v);
                        let row = lev.row(idx[0] + nx * (idx[1] + ny * idx[2]));
                        let out = &mut s.coefs_mut()[u + dims[e1] * v];
                        for &(m, k) in &pairs {
                            out[k] = row[m];
                        }
                    }
                }
                mg.setup(&s)
            };
            if use_par(lev.n()) {
                mgs.par_iter_mut().enumerate().try_for_each(one)?;
            } else {
                mgs.iter_mut().enumerate().try_for_each(one)?;
            }
        }
        Ok(())
    }

    /// One plane Gauss–Seidel sweep over the planes normal to `d` (both colours) on padded
    /// `x`; `pb`, `px` are scratch vectors of the level's size.
    pub fn sweep(
        &self,
        lev: &Level,
        d: usize,
        x: &mut [f64],
        b: &[f64],
        pb: &mut [f64],
        px: &mut [f64],
    ) {
        if !self.on[d] {
            return;
        }
        let dims = lev.dims;
        let [nx, ny, _] = dims;
        let (e1, e2) = axes(d);
        let len = dims[e1] * dims[e2];
        let (qo, qo19) = (lev.qoff(), lev.qoff19());
        assert_eq!(x.len(), lev.padded_len());
        assert!(b.len() == lev.n() && pb.len() == lev.n() && px.len() == lev.n());
        let ctl = SolveControl {
            rel_tol: 0.0,
            max_iter: 1,
        };
        let par = use_par(lev.n());
        // Three passes per colour: gather the residuals b − A x of the planes in the natural
        // order of the unknowns (cache-friendly for every d), solve the planes for their
        // corrections from zero, add them back.
        let pos = |idx: [usize; 3]| idx[d] * len + idx[e1] + dims[e1] * idx[e2];
        for colour in 0..2 {
            {
                let (bp, xq) = (SharedPtr(pb.as_mut_ptr()), SharedPtr(px.as_mut_ptr()));
                let x: &[f64] = x;
                // unknowns of this colour: every other i (d = 0), j (d = 1) or k (d = 2)
                let point = |i: usize, j: usize, k: usize| {
                    let p = i + nx * (j + ny * k);
                    let at = pos([i, j, k]);
                    // SAFETY: x is padded (asserted) and lev.q the padded index of (i, j, k);
                    // every unknown has its own position in pb, px, and tasks own k-planes.
                    unsafe {
                        let s = b[p] - lev.times_row(p, x, lev.q(i, j, k), &qo, &qo19);
                        *bp.get().add(at) = s;
                        *xq.get().add(at) = 0.0;
                    }
                };
                let gather = |k: usize| {
                    if d == 2 && k % 2 != colour {
                        return;
                    }
                    if d == 0 {
                        // tiles of TILE columns of this colour, rows j inside: contiguous
                        // reads of the operator rows, TILE contiguous write streams
                        for i0 in (colour..nx).step_by(2 * TILE) {
                            let i1 = (i0 + 2 * TILE).min(nx);
                            for j in 0..ny {
                                for i in (i0..i1).step_by(2) {
                                    point(i, j, k);
                                }
                            }
                        }
                        return;
                    }
                    for j in 0..ny {
                        if d == 1 && j % 2 != colour {
                            continue;
                        }
                        for i in 0..nx {
                            point(i, j, k);
                        }
                    }
                };
                if par {
                    (0..dims[2]).into_par_iter().for_each(gather);
                } else {
                    (0..dims[2]).for_each(gather);
                }
            }
            let solve = |(t, (pb, px)): (usize, (&mut [f64], &mut [f64]))| {
                if t % 2 == colour {
                    // a failed 2D cycle leaves px (a zero correction) untouched
                    let _ = self.mg[d][t].solve_shared(&self.pools[d], pb, px, &ctl);
                }
            };
            if par {
                pb.par_chunks_mut(len)
                    .zip(px.par_chunks_mut(len))
                    .enumerate()
                    .for_each(solve);
            } else {
                pb.chunks_mut(len)
                    .zip(px.chunks_mut(len))
                    .enumerate()
                    .for_each(solve);
            }
            let px: &[f64] = px;
            let scatter = |(k, xk): (usize, &mut [f64])| {
                if d == 2 && k % 2 != colour {
                    return;
                }
                let qj = lev.qstride()[1];
                if d == 0 {
                    // tiles as in the gather
                    for i0 in (colour..nx).step_by(2 * TILE) {
                        let i1 = (i0 + 2 * TILE).min(nx);
                        for j in 0..ny {
                            for i in (i0..i1).step_by(2) {
                                xk[i + 1 + qj * (j + 1)] += px[pos([i, j, k])];
                            }
                        }
                    }
                    return;
                }
                for j in 0..ny {
                    if d == 1 && j % 2 != colour {
                        continue;
                    }
                    let q0 = 1 + qj * (j + 1);
                    for i in 0..nx {
                        xk[q0 + i] += px[pos([i, j, k])];
                    }
                }
            };
            let qs2 = lev.qstride()[2];
            let body = &mut x[qs2..qs2 * (dims[2] + 1)];
            if par {
                body.par_chunks_mut(qs2).enumerate().for_each(scatter);
            } else {
                body.chunks_mut(qs2).enumerate().for_each(scatter);
            }
        }
    }
}
