//! Black-box multigrid for the 19-point systems of a volume Picard step [86–88]: the 3D
//! counterpart of [`crate::solve::multigrid`] (de Zeeuw's MGD9V, Dendy's BoxMG-3D).
//!
//! | phase | file | method |
//! |---|---|---|
//! | levels, line smoother | `level.rs` | 27-point operators on padded vectors; line Gauss–Seidel along x, y, z (4 colours) |
//! | plane smoother (default) | `plane.rs` | plane Gauss–Seidel, each plane by one 2D black-box multigrid cycle |
//! | transfer | `transfer.rs` | operator-dependent prolongation (edge/face/body collapses), restriction from `A*` |
//! | coarse operators | `rap.rs` | Galerkin `R A P`, 27-point on every coarse level |
//! | coarsest | `coarse.rs` | dense LU (faer sparse LU when large) |
//! | cycles | `cycle.rs` | V(1,1) (default) or F cycles, workspace, plain-cycle solve |
//! | acceleration | `crate::solve::krylov` | Bi-CGSTAB with one cycle as right preconditioner |
//!
//! Coarse unknowns are the fine unknowns with odd 0-based interior index in all three
//! directions (`n` unknowns → `n / 2`, any size). Coarsening stops at `coarse_enough`
//! unknowns, when a direction has fewer than 2 unknowns, or at `max_levels`.
//!
//! # Smoothers
//! With full coarsening the smoother must handle every strongly coupled direction. Line
//! relaxation ([`Smoother3::Lines`]) covers one strong direction (the wall-normal one at a
//! clustered wall, aspect ratios 10³–10⁴) but not two: in the outer part of a boundary-layer
//! grid the wall-normal spacing outgrows the tangential ones, the two wall-parallel directions
//! are strong, and the V-cycle factor degrades to 0.3–0.7 (measured: 0.18 on the 33³ benchmark
//! block, 0.53–0.67 on 33³ grids with exponential clustering to 10⁻⁵). Plane relaxation
//! ([`Smoother3::Planes`], default; BoxMG-3D) solves whole planes and covers both cases; each
//! level uses only the plane orientations its operator needs (`plane::orientations`: one for
//! isotropic operators, two for the benchmark block), pre-smoothing x, y, z, post z, y, x.
//!
//! # Solve
//! `solve(&self, …)` takes its per-solve workspace from a pool, so the three coordinates of a
//! Picard step are solved concurrently after one `setup`; the cycles allocate nothing but the
//! one-entry residual history of each 2D plane cycle (Bi-CGSTAB allocates its vectors once
//! per solve). `residual_history[k]` is the relative residual after cycle (or Bi-CGSTAB
//! iteration) `k + 1`; above 1e3 or NaN is [`SolveError::Diverged`]. Measured factors per
//! V(1,1) cycle are listed in `tests.rs`: ≤ 0.07 on every test case, 0.002–0.01 on the
//! boundary-layer Picard operators.
//!
//! # Cost (`examples/bench_volume --solver both`, idle 2-core machine)
//! First Picard operator of the benchmark block: 8–9 V-cycles to 1e-10 (factor 0.043, 0.053,
//! 0.063 at 33³, 65³, 129³ nodes), 280–310 ns per unknown and cycle, setup ≈ 3.5 cycles;
//! Bi-CGSTAB/ILU(0) needs 25, 58, 105 iterations of 76–134 ns. Whole `grid_volume` (nested,
//! inexact Picard): slower than Bi-CGSTAB at 33³ (0.30 s, 130 WU against 0.19 s, 95 WU),
//! faster at 65³ (2.1 s, 98 WU against 3.7 s, 173 WU) and 3.7× faster at 129³ (13.6 s, 72 WU
//! against 50.8 s, 261 WU; 70–77 WU over 9 runs). What brought 129³ from 117 to 72 WU: plane cycles of half the
//! line sweeps (`plane::plane_params`), plane solvers kept by [`Multigrid3::update`], the
//! 19-point rows on the fine level, and a Picard forcing term that lets the last step do with
//! one cycle (`crate::elliptic::picard::forcing`).

mod coarse;
mod cycle;
#[cfg(test)]
mod diagnostics;
mod level;
mod plane;
mod rap;
#[cfg(test)]
mod tests;
mod transfer;

use crate::solve::multigrid::{use_par, Pool, SharedPtr};
use crate::solve::stencil19::Stencil19;
use crate::solve::LinearSolver;
use crate::solve::{SolveControl, SolveError, SolveInfo};
use coarse::CoarseLu;
use cycle::{from_padded, solve_cycles, to_padded, Hierarchy, Workspace};
use level::Level;
use plane::Planes;

/// Cycle type.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Cycle3 {
    /// One coarse-grid correction per level (default).
    #[default]
    V,
    /// An F-cycle then a V-cycle on each coarser level.
    F,
}

/// Smoother.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Smoother3 {
    /// Alternating plane Gauss–Seidel, planes normal to x, y, z, each plane by one 2D
    /// multigrid cycle (default): robust for one or two strong directions.
    #[default]
    Planes,
    /// Alternating line Gauss–Seidel along x, y, z: cheaper, robust for one strong direction.
    Lines,
}

/// Parameters of [`Multigrid3`].
#[derive(Clone, Debug, PartialEq)]
pub struct Mg3Params {
    /// Cycle type. Default V.
    pub cycle: Cycle3,
    /// Smoother. Default [`Smoother3::Planes`].
    pub smoother: Smoother3,
    /// Smoothing steps (x, y, z sweeps each) before the coarse-grid correction. Default 1.
    pub npre: usize,
    /// Smoothing steps (z, y, x) after it. Default 1.
    pub npost: usize,
    /// A grid with at most this many unknowns is the coarsest. Default 512.
    pub coarse_enough: usize,
    /// At most this many levels. Default 20.
    pub max_levels: usize,
    /// Restriction `Pᵀ` instead of the adjoint-based one. Default false.
    pub transpose_restriction: bool,
    /// Bi-CGSTAB preconditioned by one cycle instead of plain cycles. Default false.
    pub accelerate: bool,
}

impl Default for Mg3Params {
    fn default() -> Self {
        Mg3Params {
            cycle: Cycle3::V,
            smoother: Smoother3::Planes,
            npre: 1,
            npost: 1,
            coarse_enough: 512,
            max_levels: 20,
            transpose_restriction: false,
            accelerate: false,
        }
    }
}

/// The hierarchy after `setup`.
#[derive(Clone, Debug, PartialEq)]
pub struct Mg3Info {
    /// Unknowns (nx, ny, nz) from the finest to the coarsest level.
    pub levels: Vec<[usize; 3]>,
    /// Unknowns of all levels divided by the fine unknowns.
    pub grid_complexity: f64,
}

/// Black-box multigrid for [`Stencil19`] systems (module docs).
#[derive(Default)]
pub struct Multigrid3 {
    params: Mg3Params,
    h: Option<Hierarchy>,
    pool: Pool<Workspace>,
}

/// Level sizes for fine size `dims`.
fn level_dims(dims: [usize; 3], p: &Mg3Params) -> Vec<[usize; 3]> {
    let mut out = vec![dims];
    let mut d = dims;
    while out.len() < p.max_levels.max(1)
        && d.iter().product::<usize>() > p.coarse_enough
        && d.iter().all(|&n| n >= 2)
    {
        d = [d[0] / 2, d[1] / 2, d[2] / 2];
        out.push(d);
    }
    out
}

impl Multigrid3 {
    /// A solver with parameters `params`.
    pub fn new(params: Mg3Params) -> Self {
        Multigrid3 {
            params,
            ..Default::default()
        }
    }

    /// The parameters.
    pub fn params(&self) -> &Mg3Params {
        &self.params
    }

    /// Changes the parameters (effective at the next `setup`).
    pub fn set_params(&mut self, params: Mg3Params) {
        self.params = params;
    }

    /// The hierarchy of the last `setup`.
    pub fn info(&self) -> Option<Mg3Info> {
        let h = self.h.as_ref()?;
        let n0 = h.levels[0].n().max(1) as f64;
        Some(Mg3Info {
            levels: h.levels.iter().map(|l| l.dims).collect(),
            grid_complexity: h.levels.iter().map(|l| l.n() as f64).sum::<f64>() / n0,
        })
    }

    fn setup_values(&mut self, a: Fine) -> Result<(), SolveError> {
        let dims = level_dims(a.dims(), &self.params);
        let reuse = self.h.as_ref().is_some_and(|h| {
            h.levels.len() == dims.len() && h.levels.iter().zip(&dims).all(|(l, d)| l.dims == *d)
        });
        let (mut levels, mut planes): (Vec<Level>, Vec<Planes>) = match self.h.take() {
            Some(h) if reuse => (h.levels, h.planes),
            _ => {
                self.pool.clear();
                let levels = dims
                    .iter()
                    .enumerate()
                    .map(|(l, &d)| {
                        if l == 0 {
                            Level::fine(d)
                        } else {
                            Level::new(d)
                        }
                    })
                    .collect();
                (levels, dims.iter().map(|_| Planes::default()).collect())
            }
        };
        a.load(&mut levels[0])?;
        let nl = levels.len();
        for l in 0..nl - 1 {
            let (fine, coarse) = levels.split_at_mut(l + 1);
            let lev = &mut fine[l];
            match self.params.smoother {
                Smoother3::Lines => lev.factor_lines()?,
                Smoother3::Planes => planes[l].setup(lev)?,
            }
            transfer::build_transfer(lev, self.params.transpose_restriction)?;
            rap::galerkin(lev, &mut coarse[0]);
        }
        let coarse = CoarseLu::factor(&levels[nl - 1])?;
        self.h = Some(Hierarchy {
            levels,
            planes,
            coarse,
        });
        Ok(())
    }
}

impl Multigrid3 {
    /// Replaces the operator by `a`, a small change of the last one (a later step of a
    /// converging Picard iteration): only the fine level's copy of `a` is refreshed (and its
    /// line factors with [`Smoother3::Lines`]); the transfers, the coarse operators and the
    /// plane solvers of the last full setup are kept, as in the 2D
    /// [`crate::solve::multigrid::Multigrid::update`]. The cycles still solve `A x = b` for the new
    /// `a` (residuals and plane sweeps use it; see `plane.rs`). Keeping the plane solvers
    /// saves their setup, 0.6 s of a 129³ update. A full setup when there is no hierarchy of
    /// this size.
    pub fn update(&mut self, a: &Stencil19) -> Result<(), SolveError> {
        self.update_values(Fine::Copy(a))
    }

    fn update_values(&mut self, a: Fine) -> Result<(), SolveError> {
        let fits = self
            .h
            .as_ref()
            .is_some_and(|h| h.levels[0].dims == a.dims());
        if !fits {
            return self.setup_checked(a);
        }
        let smoother = self.params.smoother;
        let h = self.h.as_mut().expect("hierarchy checked");
        let res = (|| {
            let single = h.levels.len() == 1;
            let lev = &mut h.levels[0];
            a.load(lev)?;
            if single {
                h.coarse = CoarseLu::factor(&h.levels[0])?;
                return Ok(());
            }
            match smoother {
                Smoother3::Lines => lev.factor_lines(),
                Smoother3::Planes => Ok(()),
            }
        })();
        if res.is_err() {
            self.h = None;
        }
        res
    }
}

impl Multigrid3 {
    /// A full setup for the fine operator `a`; no hierarchy after a failure.
    fn setup_checked(&mut self, a: Fine) -> Result<(), SolveError> {
        if a.dims().iter().product::<usize>() == 0 {
            self.h = None;
            return Err(SolveError::Singular("multigrid: empty operator".into()));
        }
        let res = self.setup_values(a);
        if res.is_err() {
            self.h = None;
        }
        res
    }
}

/// The fine operator of a setup: the caller's, copied, or its rows taken over
/// ([`LinearSolver::adopt`]).
enum Fine<'a> {
    Copy(&'a Stencil19),
    Take([usize; 3], Vec<[f64; 19]>),
}

impl Fine<'_> {
    fn dims(&self) -> [usize; 3] {
        match self {
            Fine::Copy(a) => a.dims(),
            Fine::Take(dims, _) => *dims,
        }
    }

    /// Makes it the operator of the fine level `lev`.
    fn load(self, lev: &mut Level) -> Result<(), SolveError> {
        match self {
            Fine::Copy(a) => lev.embed(a),
            Fine::Take(_, rows) => lev.embed_rows(rows),
        }
    }
}

impl LinearSolver<Stencil19> for Multigrid3 {
    fn update(&mut self, a: &Stencil19) -> Result<(), SolveError> {
        Multigrid3::update(self, a)
    }

    fn setup(&mut self, a: &Stencil19) -> Result<(), SolveError> {
        self.setup_checked(Fine::Copy(a))
    }

    fn adopt(&mut self, a: &mut Stencil19, small: bool) -> Result<(), SolveError> {
        let dims = a.dims();
        let rows = std::mem::replace(a, Stencil19::zeros(0, 0, 0)).into_coefs();
        let fine = Fine::Take(dims, rows);
        if small {
            self.update_values(fine)
        } else {
            self.setup_checked(fine)
        }
    }

    fn give_back(&mut self) -> Option<Stencil19> {
        let l0 = &mut self.h.as_mut()?.levels[0];
        (l0.n() > 0 && l0.a19.len() == l0.n())
            .then(|| Stencil19::from_coefs(l0.dims, l0.take_rows()))
    }

    fn solve(&self, b: &[f64], x: &mut [f64], ctl: &SolveControl) -> Result<SolveInfo, SolveError> {
        let h = self
            .h
            .as_ref()
            .filter(|h| h.levels[0].a19.len() == h.levels[0].n())
            .ok_or(SolveError::NotSetUp)?;
        let l0 = &h.levels[0];
        let n = l0.n();
        if b.len() != n || x.len() != n {
            return Err(SolveError::Singular(format!(
                "multigrid: vectors of length {} and {} for {n} unknowns",
                b.len(),
                x.len()
            )));
        }
        let p = &self.params;
        let mut ws = self.pool.take(|ws| ws.fits(h), || Workspace::new(h));
        let res = if p.accelerate {
            let mut xq = vec![0.0; l0.padded_len()];
            let Workspace { lv, scratch } = &mut ws;
            let mut apply = |v: &[f64], out: &mut [f64]| {
                to_padded(l0, v, &mut xq);
                l0.apply(&xq, out);
            };
            let mut precond = |v: &[f64], out: &mut [f64]| {
                lv[0].b.copy_from_slice(v);
                lv[0].x.fill(0.0);
                h.cycle(0, p.cycle, p, lv, scratch);
                from_padded(l0, &lv[0].x, out);
            };
            crate::solve::krylov::bicgstab(&mut apply, &mut precond, b, x, ctl)
        } else {
            solve_cycles(h, p, &mut ws, b, x, ctl)
        };
        self.pool.put(ws);
        res
    }

    fn companion(&self) -> Option<Box<dyn LinearSolver<Stencil19>>> {
        Some(Box::new(Multigrid3::new(self.params.clone())))
    }

    fn name(&self) -> &'static str {
        "multigrid"
    }
}
