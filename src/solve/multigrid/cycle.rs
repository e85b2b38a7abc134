//! V, F and W cycles, the per-solve workspace, and the smoothing steps.
//!
//! One smoothing step of [`crate::solve::multigrid::Smoother::AlternatingZebraLine`] is a zebra x-line sweep
//! (both colours) followed by a zebra y-line sweep before the coarse-grid correction, and the
//! reverse (y-lines, then x-lines) after it, so that the cycle is symmetric; each zebra sweep
//! relaxes the even lines (the lines without coarse points) first. This order measured best:
//! V(1,1) reduces the residual of the 63² Poisson problem by 0.007 per cycle, against 0.021
//! with x-then-y in both places. After a zebra half sweep the residual vanishes on the lines
//! it relaxed, so the residual that follows the smoothing is computed on the other half only.
//!
//! `W`: two coarse-grid corrections per level; `F`: an F-cycle then a V-cycle on the next
//! coarser level. The coarsest level is solved exactly.

use crate::solve::multigrid::relax::{pad, padded_len, residual, yzebra, Zeroed};
use crate::solve::multigrid::setup::Hierarchy;
use crate::solve::multigrid::xline::xzebra;
use crate::solve::multigrid::yline::ysweep;
use crate::solve::multigrid::{interp, Cycle, Smoother};

/// Vectors of one level, all padded (see [`crate::solve::multigrid::relax::pad`]).
#[derive(Clone, Debug)]
pub(super) struct LevelVecs {
    pub x: Vec<f64>,
    pub b: Vec<f64>,
    pub r: Vec<f64>,
}

/// Everything one solve needs besides the hierarchy: taken from a pool by `solve`, so that
/// several right-hand sides can be solved at once through `&Multigrid`.
#[derive(Clone, Debug)]
pub(super) struct Workspace {
    pub lv: Vec<LevelVecs>,
    pub band: Vec<f64>,
}

impl Workspace {
    pub(super) fn new(h: &Hierarchy) -> Self {
        let lv = h
            .levels
            .iter()
            .map(|l| {
                let len = padded_len(l.nx, l.ny);
                LevelVecs {
                    x: vec![0.0; len],
                    b: vec![0.0; len],
                    r: vec![0.0; len],
                }
            })
            .collect();
        Workspace {
            lv,
            band: vec![0.0; h.lu.scratch_len()],
        }
    }

    /// Resizes this workspace for `h` in its own buffers (zeroed): the sizes change with every
    /// level of nested iteration, and buffers allocated afresh are mapped and cleared again by
    /// the kernel (as [`Hierarchy::recycled`] for the hierarchy's own).
    pub(super) fn refit(&mut self, h: &Hierarchy) {
        // a buffer too small goes before its replacement is allocated (a reallocation may
        // hold both at once)
        let fit = |v: &mut Vec<f64>, len: usize| crate::solve::zeroed(v, len);
        self.lv.truncate(h.levels.len());
        for (k, l) in h.levels.iter().enumerate() {
            let len = padded_len(l.nx, l.ny);
            match self.lv.get_mut(k) {
                Some(v) => {
                    fit(&mut v.x, len);
                    fit(&mut v.b, len);
                    fit(&mut v.r, len);
                }
                None => self.lv.push(LevelVecs {
                    x: vec![0.0; len],
                    b: vec![0.0; len],
                    r: vec![0.0; len],
                }),
            }
        }
        fit(&mut self.band, h.lu.scratch_len());
    }

    /// True if this workspace was made for a hierarchy of the same sizes.
    pub(super) fn fits(&self, h: &Hierarchy) -> bool {
        self.lv.len() == h.levels.len()
            && self
                .lv
                .iter()
                .zip(&h.levels)
                .all(|(v, l)| v.x.len() == padded_len(l.nx, l.ny))
            && self.band.len() == h.lu.scratch_len()
    }
}

/// Colour relaxed first in a zebra sweep (0: even lines, which are the fine-only lines).
const FIRST_COLOUR: usize = 0;
/// Post-smoothing relaxes y-lines before x-lines.
const POST_REVERSED: bool = true;

impl Hierarchy {
    /// `sweeps` smoothing steps on level `l` (`post`: after the coarse-grid correction).
    /// Returns the lines relaxed last (their residual vanishes).
    pub(super) fn smooth(
        &self,
        l: usize,
        x: &mut [f64],
        b: &[f64],
        sweeps: usize,
        post: bool,
    ) -> Zeroed {
        let lev = &self.levels[l];
        let mut last = Zeroed::None;
        let (nx, ny) = (lev.nx, lev.ny);
        for step in 0..sweeps {
            let (dx, dy) = match self.params.smoother {
                Smoother::AlternatingZebraLine => (true, true),
                Smoother::ZebraLineX => (true, false),
                Smoother::ZebraLineY => (false, true),
                Smoother::ZebraLineXY => {
                    let x_first = (step + post as usize) % 2 == 0;
                    (x_first, !x_first)
                }
            };
            let (first, second) = if post && POST_REVERSED {
                (dy, dx)
            } else {
                (dx, dy)
            };
            for (i, on) in [first, second].into_iter().enumerate() {
                if !on {
                    continue;
                }
                let along_x = (i == 0) != (post && POST_REVERSED);
                if along_x {
                    for c in [FIRST_COLOUR, 1 - FIRST_COLOUR] {
                        xzebra(&lev.a, &lev.xop, nx, ny, x, b, c);
                    }
                    last = Zeroed::Rows(1 - FIRST_COLOUR);
                } else if !lev.ycp.is_empty() {
                    ysweep(&lev.a, &lev.ycp, nx, ny, x, b, FIRST_COLOUR);
                    last = Zeroed::Cols(1 - FIRST_COLOUR);
                } else {
                    for c in [FIRST_COLOUR, 1 - FIRST_COLOUR] {
                        yzebra(&lev.yop, nx, ny, x, b, c);
                    }
                    last = Zeroed::Cols(1 - FIRST_COLOUR);
                }
            }
        }
        last
    }

    /// Exact solve on the coarsest level: `x = A⁻¹ b`.
    fn coarse_solve(&self, v: &mut LevelVecs, band: &mut [f64]) {
        let l = self.levels.last().expect("hierarchy has a level");
        let (pd, n) = (pad(l.nx), l.n());
        self.lu.solve(&v.b[pd..pd + n], &mut v.x[pd..pd + n], band);
    }

    /// One cycle of type `kind` on level `l` for `A_l x = b` (vectors in `lv[l]`); returns
    /// the lines whose residual vanishes afterwards.
    pub(super) fn cycle(
        &self,
        l: usize,
        kind: Cycle,
        lv: &mut [LevelVecs],
        band: &mut [f64],
    ) -> Zeroed {
        let nl = self.levels.len();
        if l + 1 == nl {
            self.coarse_solve(&mut lv[l], band);
            return Zeroed::None;
        }
        let lev = &self.levels[l];
        let (nx, ny) = (lev.nx, lev.ny);
        let npre = self.params.npre;
        let npost = self.params.npost;
        {
            let v = &mut lv[l];
            let zeroed = self.smooth(l, &mut v.x, &v.b, npre, false);
            residual(&lev.a, Some(&lev.yop), nx, ny, &v.x, &v.b, &mut v.r, zeroed);
        }
        {
            let (fine, coarse) = lv.split_at_mut(l + 1);
            let (v, vc) = (&fine[l], &mut coarse[0]);
            interp::restrict(interp::restriction(&lev.p, &lev.r), nx, ny, &v.r, &mut vc.b);
            crate::solve::par_fill(&mut vc.x, 0.0);
        }
        let coarsest_next = l + 2 == nl;
        match kind {
            Cycle::V => {
                self.cycle(l + 1, Cycle::V, lv, band);
            }
            Cycle::W => {
                self.cycle(l + 1, Cycle::W, lv, band);
                if !coarsest_next {
                    self.cycle(l + 1, Cycle::W, lv, band);
                }
            }
            Cycle::F => {
                self.cycle(l + 1, Cycle::F, lv, band);
                if !coarsest_next {
                    self.cycle(l + 1, Cycle::V, lv, band);
                }
            }
        }
        {
            let (fine, coarse) = lv.split_at_mut(l + 1);
            interp::prolong_add(&lev.p, nx, ny, &coarse[0].x, &mut fine[l].x);
        }
        let v = &mut lv[l];
        self.smooth(l, &mut v.x, &v.b, npost, true)
    }
}
