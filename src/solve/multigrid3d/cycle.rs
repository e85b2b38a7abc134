//! Cycles, the per-solve workspace and the plain-cycle solve loop.
//!
//! One V-cycle on level `l`: smoothing (x, y, z sweeps), residual, restriction, the coarse
//! correction (F-cycle: an F-cycle then a V-cycle), prolongation, smoothing (z, y, x); the
//! coarsest level is solved exactly.

use crate::solve::multigrid3d::coarse::CoarseLu;
use crate::solve::multigrid3d::level::Level;
use crate::solve::multigrid3d::plane::Planes;
use crate::solve::multigrid3d::{transfer, Cycle3, Mg3Params, Smoother3};
use crate::solve::stationary;
use crate::solve::{SolveControl, SolveError, SolveInfo};

#[derive(Debug)]
pub(super) struct Hierarchy {
    pub levels: Vec<Level>,
    /// The plane smoother of each level but the coarsest (empty with line smoothing).
    pub planes: Vec<Planes>,
    pub coarse: CoarseLu,
}

/// Vectors of one level: `x`, `r` padded, `b` and the plane scratch `pb`, `px` unpadded.
pub(super) struct LevelVecs {
    pub x: Vec<f64>,
    pub b: Vec<f64>,
    pub r: Vec<f64>,
    pub pb: Vec<f64>,
    pub px: Vec<f64>,
}

pub(super) struct Workspace {
    pub lv: Vec<LevelVecs>,
    pub scratch: Vec<f64>,
}

impl Workspace {
    pub fn new(h: &Hierarchy) -> Self {
        let lv = h
            .levels
            .iter()
            .map(|l| LevelVecs {
                x: vec![0.0; l.padded_len()],
                b: vec![0.0; l.n()],
                r: vec![0.0; l.padded_len()],
                pb: vec![0.0; l.n()],
                px: vec![0.0; l.n()],
            })
            .collect();
        let nc = h.levels.last().map_or(0, Level::n);
        Workspace {
            lv,
            scratch: vec![0.0; nc],
        }
    }

    pub fn fits(&self, h: &Hierarchy) -> bool {
        self.lv.len() == h.levels.len()
            && self
                .lv
                .iter()
                .zip(&h.levels)
                .all(|(v, l)| v.b.len() == l.n())
    }
}

impl Hierarchy {
    fn smooth(&self, l: usize, v: &mut LevelVecs, p: &Mg3Params, post: bool) {
        let lev = &self.levels[l];
        let sweeps = if post { p.npost } else { p.npre };
        for _ in 0..sweeps {
            for t in 0..3 {
                let d = if post { 2 - t } else { t };
                match p.smoother {
                    Smoother3::Lines => lev.line_sweep(d, &mut v.x, &v.b),
                    Smoother3::Planes => {
                        self.planes[l].sweep(lev, d, &mut v.x, &v.b, &mut v.pb, &mut v.px)
                    }
                }
            }
        }
    }

    /// One cycle on level `l` for `A_l x = b` (vectors in `lv[l]`).
    pub fn cycle(
        &self,
        l: usize,
        kind: Cycle3,
        p: &Mg3Params,
        lv: &mut [LevelVecs],
        scratch: &mut [f64],
    ) {
        let nl = self.levels.len();
        if l + 1 == nl {
            let v = &mut lv[l];
            self.coarse.solve(&v.b, scratch);
            to_padded(&self.levels[l], scratch, &mut v.x);
            return;
        }
        let lev = &self.levels[l];
        {
            let v = &mut lv[l];
            self.smooth(l, v, p, false);
            lev.residual(&v.x, &v.b, &mut v.r);
        }
        {
            let (fine, coarse) = lv.split_at_mut(l + 1);
            transfer::restrict(lev, &fine[l].r, &mut coarse[0].b);
            coarse[0].x.fill(0.0);
        }
        self.cycle(l + 1, kind, p, lv, scratch);
        if kind == Cycle3::F && l + 2 < nl {
            self.cycle(l + 1, Cycle3::V, p, lv, scratch);
        }
        {
            let (fine, coarse) = lv.split_at_mut(l + 1);
            transfer::prolong_add(lev, &self.levels[l + 1], &coarse[0].x, &mut fine[l].x);
        }
        self.smooth(l, &mut lv[l], p, true);
    }
}

/// Copies unpadded `u` into the interior of padded `q` of level `lev`.
pub(super) fn to_padded(lev: &Level, u: &[f64], q: &mut [f64]) {
    let [nx, ny, nz] = lev.dims;
    for k in 0..nz {
        for j in 0..ny {
            let (a, s) = (lev.q(0, j, k), nx * (j + ny * k));
            q[a..a + nx].copy_from_slice(&u[s..s + nx]);
        }
    }
}

/// Copies the interior of padded `q` of level `lev` into unpadded `u`.
pub(super) fn from_padded(lev: &Level, q: &[f64], u: &mut [f64]) {
    let [nx, ny, nz] = lev.dims;
    for k in 0..nz {
        for j in 0..ny {
            let (a, s) = (lev.q(0, j, k), nx * (j + ny * k));
            u[s..s + nx].copy_from_slice(&q[a..a + nx]);
        }
    }
}

/// Plain cycles from the initial guess `x`.
pub(super) fn solve_cycles(
    h: &Hierarchy,
    p: &Mg3Params,
    ws: &mut Workspace,
    b: &[f64],
    x: &mut [f64],
    ctl: &SolveControl,
) -> Result<SolveInfo, SolveError> {
    let l0 = &h.levels[0];
    let Workspace { lv, scratch } = ws;
    lv[0].b.copy_from_slice(b);
    lv[0].x.fill(0.0);
    to_padded(l0, x, &mut lv[0].x);
    let v = &mut lv[0];
    let r0 = l0.residual(&v.x, &v.b, &mut v.r).sqrt();
    let info = stationary(r0, ctl, || {
        h.cycle(0, p.cycle, p, lv, scratch);
        let v = &mut lv[0];
        l0.residual(&v.x, &v.b, &mut v.r).sqrt()
    })?;
    from_padded(l0, &lv[0].x, x);
    Ok(info)
}
