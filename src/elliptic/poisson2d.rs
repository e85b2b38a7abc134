//! The Poisson grid system [24] on a 2D block (planar domain, D = 2, or minimal surface,
//! D = 3), discretized as in [41]–[44] and solved by Picard iteration.
//!
//! Each Picard step freezes P = g22, Q = −g12, R = g11 and S, T (from the control functions)
//! at the current iterate, assembles the nine-point operator of
//! `P x_ξξ + 2Q x_ξη + R x_ηη + S x_ξ + T x_η = 0` with central differences (index space), and
//! solves it once per coordinate with the same operator (one setup, coordinates in parallel).
//!
//! The linear systems are solved in correction form, A δ = b − A x_k from δ = 0, i.e. from the
//! current iterate, and with an iterative solver only as accurately as the step needs
//! ([`PicardParams::linear_forcing`]): one or two multigrid cycles per step. The steps and the
//! stopping test (an error estimate below the tolerance) are those of `src/elliptic/picard.rs`, the
//! same for every solver and for the volume system.

use crate::algebraic::control2d::Control2;
use crate::elliptic::jacobian2d::Coupling;
use crate::elliptic::newton::{self, NewtonSystem};
use crate::elliptic::picard::{self, Nonlinear, PicardInfo, PicardParams};
use crate::grid::boundary::Boundary2;
use crate::grid::Grid2;
use crate::solve::multigrid::use_par;
use crate::solve::stencil9::Stencil9;
use crate::solve::{LinearSolver, SolveError};
use crate::Result;
use rayon::prelude::*;
use std::borrow::Cow;

/// The frozen nine-point stencil of [43, 44] at a node whose east, west, north and south
/// neighbours are `e, w, no, so` (flat indices into `xs`; a periodic block wraps e and w),
/// with the node's six control-function terms `k`; the row multiplied by −1, so that the
/// diagonal 2(P + R) is positive.
#[inline]
pub(crate) fn stencil_at<const D: usize>(
    xs: &[Vec<f64>; D],
    k: &[f64; 6],
    [e, w, no, so]: [usize; 4],
) -> [f64; 9] {
    use crate::solve::stencil9::dir::*;
    let (mut g11, mut g12, mut g22) = (0.0, 0.0, 0.0);
    for c in xs.iter() {
        let xi = 0.5 * (c[e] - c[w]);
        let eta = 0.5 * (c[no] - c[so]);
        g11 += xi * xi;
        g12 += xi * eta;
        g22 += eta * eta;
    }
    let (p, q, r) = (g22, -g12, g11);
    let sc = p * k[0] + 2.0 * q * k[2] + r * k[4];
    let tc = p * k[1] + 2.0 * q * k[3] + r * k[5];
    let mut st = [0.0; 9];
    st[C] = 2.0 * (p + r);
    st[E] = -(p + 0.5 * sc);
    st[W] = -(p - 0.5 * sc);
    st[N] = -(r + 0.5 * tc);
    st[S] = -(r - 0.5 * tc);
    st[NE] = -0.5 * q;
    st[SW] = -0.5 * q;
    st[NW] = 0.5 * q;
    st[SE] = 0.5 * q;
    st
}

/// Assembles the frozen nine-point operator of [43, 44] at iterate `x` and the right-hand
/// sides (one per coordinate) that carry the Dirichlet boundary values.
///
/// Rows are multiplied by −1 so that the diagonal 2(P + R) is positive.
pub fn assemble<const D: usize>(
    x: &Grid2<D>,
    ctrl: &Control2,
    a: &mut Stencil9,
    rhs: &mut [Vec<f64>; D],
) {
    let (ni, nj) = (x.ni(), x.nj());
    let (nx, ny) = (ni - 2, nj - 2);
    assert_eq!((a.nx(), a.ny()), (nx, ny));
    let xs = x.coords();
    a.coefs_mut()
        .par_chunks_mut(nx)
        .enumerate()
        .for_each(|(jj, arow)| {
            let j = jj + 1;
            for (ii, st) in arow.iter_mut().enumerate() {
                let n = ii + 1 + ni * j;
                let (e, w, no, so) = (n + 1, n - 1, n + ni, n - ni);
                *st = stencil_at(xs, &ctrl.at(n), [e, w, no, so]);
            }
        });
    // Known boundary neighbours go to the right-hand side (rows next to the boundary only).
    for b in rhs.iter_mut() {
        crate::solve::par_fill(b, 0.0);
    }
    let coefs = a.coefs_mut();
    let mut row = |ii: usize, jj: usize| {
        let p = ii + nx * jj;
        let (i, j) = (ii + 1, jj + 1);
        for dj in 0..3usize {
            for di in 0..3usize {
                let (ib, jb) = (i + di - 1, j + dj - 1);
                if ib == 0 || jb == 0 || ib == ni - 1 || jb == nj - 1 {
                    let k = di + 3 * dj;
                    let m = ib + ni * jb;
                    for (b, c) in rhs.iter_mut().zip(xs.iter()) {
                        b[p] -= coefs[p][k] * c[m];
                    }
                    coefs[p][k] = 0.0;
                }
            }
        }
    };
    for ii in 0..nx {
        row(ii, 0);
        if ny > 1 {
            row(ii, ny - 1);
        }
    }
    for jj in 1..ny.saturating_sub(1) {
        row(0, jj);
        if nx > 1 {
            row(nx - 1, jj);
        }
    }
}

/// Residual of [24] at grid `x`: the largest |A x − b| over interior nodes, each row divided by
/// its diagonal 2(P + R) and by the domain diameter — a dimensionless number comparable to a
/// relative node update.
pub fn residual<const D: usize>(x: &Grid2<D>, a: &Stencil9, rhs: &[Vec<f64>; D]) -> f64 {
    residual_scaled(x, a, rhs, x.diameter(), None)
}

/// [`residual`] with the diameter given; rows in parallel, straight from the full grid (the
/// boundary couplings of `a` are zero after [`assemble`], so boundary values drop out). With
/// `out`, also stores `b − A x` per coordinate (interior numbering).
fn residual_scaled<const D: usize>(
    x: &Grid2<D>,
    a: &Stencil9,
    rhs: &[Vec<f64>; D],
    diam: f64,
    out: Option<&mut [Vec<f64>; D]>,
) -> f64 {
    let (ni, nx) = (x.ni(), a.nx());
    let xs = x.coords();
    let row = |jj: usize, arow: &[[f64; 9]], mut out: [Option<&mut [f64]>; D]| {
        let mut w = 0.0f64;
        for (ii, st) in arow.iter().enumerate() {
            let (p, n) = (ii + nx * jj, ii + 1 + ni * (jj + 1));
            for (c, (xc, b)) in xs.iter().zip(rhs.iter()).enumerate() {
                let (lo, mid, hi) = (&xc[n - ni - 1..], &xc[n - 1..], &xc[n + ni - 1..]);
                let ax = st[0] * lo[0]
                    + st[1] * lo[1]
                    + st[2] * lo[2]
                    + st[3] * mid[0]
                    + st[4] * mid[1]
                    + st[5] * mid[2]
                    + st[6] * hi[0]
                    + st[7] * hi[1]
                    + st[8] * hi[2];
                let r = b[p] - ax;
                if let Some(o) = out[c].as_deref_mut() {
                    o[ii] = r;
                }
                w = w.max((r / st[4]).abs());
            }
        }
        w
    };
    let rows = a.coefs().par_chunks(nx).enumerate();
    let worst = match out {
        None => rows
            .map(|(jj, arow)| row(jj, arow, std::array::from_fn(|_| None)))
            .reduce(|| 0.0, f64::max),
        Some(out) => {
            let mut chunks: Vec<Vec<&mut [f64]>> = (0..a.ny()).map(|_| Vec::new()).collect();
            for o in out.iter_mut() {
                for (jj, ch) in o.chunks_mut(nx).enumerate() {
                    chunks[jj].push(ch);
                }
            }
            rows.zip(chunks.into_par_iter())
                .map(|((jj, arow), ch)| {
                    let mut it = ch.into_iter();
                    row(jj, arow, std::array::from_fn(|_| it.next()))
                })
                .reduce(|| 0.0, f64::max)
        }
    };
    worst / diam
}

fn add_interior(inner: &[f64], ni: usize, nx: usize, full: &mut [f64]) {
    let add = |(row, d): (&mut [f64], &[f64])| {
        for (f, d) in row[1..=nx].iter_mut().zip(d) {
            *f += d;
        }
    };
    // grid row jj + 1 holds interior row jj at columns 1..=nx
    let rows = &mut full[ni..ni * (inner.len() / nx + 1)];
    if use_par(inner.len()) {
        rows.par_chunks_mut(ni)
            .zip(inner.par_chunks(nx))
            .for_each(add);
    } else {
        rows.chunks_mut(ni).zip(inner.chunks(nx)).for_each(add);
    }
}

/// Solves the grid system [24] by Picard iteration [43, 44] from the start grid `x` (whose
/// boundary nodes are the Dirichlet data and stay untouched).
///
/// Each step's linear systems start from the current iterate and are solved to the relative
/// residual of the forcing term (see [`PicardParams::linear_forcing`]); the coordinates are
/// solved in parallel with the operator's one setup. `place` names the block in errors.
/// Non-convergence is not an error: it is reported in the returned [`PicardInfo`].
pub fn solve<const D: usize>(
    x: &mut Grid2<D>,
    ctrl: &Control2,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<PicardInfo> {
    solve_timed(x, ctrl, solver, params, 0.0, place).map(|(info, _)| info)
}

/// [`solve`], also returning the shortest time (seconds) of one evaluation of the residual of
/// [24] with its assembly on this grid, measured at every step: the work unit of
/// `crate::elliptic::nested`. With `relative_stop > 0` the iteration also stops (converged) once the
/// update falls below `relative_stop` times the first update: enough for a coarse level of
/// nested iteration, whose own discretization error dwarfs the Picard tolerance.
pub(crate) fn solve_timed<const D: usize>(
    x: &mut Grid2<D>,
    ctrl: &Control2,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    relative_stop: f64,
    place: &str,
) -> Result<(PicardInfo, f64)> {
    let rules = picard::Rules::stop(relative_stop);
    solve_level(x, ctrl, solver, params, rules, false, place)
}

/// [`solve_timed`] for a level of nested iteration: with `newton_now` (the coarser level took
/// Newton steps) and Newton's iteration, Newton steps from the first step instead of Picard
/// steps until they are seen to contract slowly (`crate::elliptic::newton`).
pub(crate) fn solve_level<const D: usize>(
    x: &mut Grid2<D>,
    ctrl: &Control2,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    rules: picard::Rules,
    newton_now: bool,
    place: &str,
) -> Result<(PicardInfo, f64)> {
    let (ni, nj) = (x.ni(), x.nj());
    picard::check_input(
        place,
        ni >= 3 && nj >= 3,
        "a block needs at least 3 × 3 nodes",
        (ctrl.ni(), ctrl.nj()) == (ni, nj),
        ctrl.all_finite(),
    )?;
    let (nx, ny) = (ni - 2, nj - 2);
    let diam = x.diameter();
    let mut sys = System2 {
        x,
        ctrl: Cow::Borrowed(ctrl),
        solver,
        a: Stencil9::zeros(nx, ny),
        rhs: std::array::from_fn(|_| vec![0.0; nx * ny]),
        r: std::array::from_fn(|_| vec![0.0; nx * ny]),
        u: std::array::from_fn(|_| vec![0.0; nx * ny]),
        diam,
        coupling: None,
        own: Vec::new(),
        scratch: None,
        blocks: false,
    };
    match params.iteration(D) {
        Nonlinear::Picard => picard::run(&mut sys, params, rules, place, &mut |_, _| {}),
        Nonlinear::Newton => {
            // the coupling is allocated by the first Newton step (`linearize`)
            newton::run(&mut sys, params, rules, newton_now, place, &mut |_, _| {})
        }
    }
}

/// The Picard system of one 2D block: iterate, frozen operator, right-hand sides, and the
/// residuals and corrections of the coordinates (interior numbering).
struct System2<'a, const D: usize> {
    x: &'a mut Grid2<D>,
    /// Borrowed, or (Newton steps on a large grid) the caller's computed values stored
    /// ([`Control2::stored_copy`]).
    ctrl: Cow<'a, Control2>,
    solver: &'a mut dyn LinearSolver,
    a: Stencil9,
    rhs: [Vec<f64>; D],
    r: [Vec<f64>; D],
    u: [Vec<f64>; D],
    diam: f64,
    /// The Jacobian's coupling (Newton's method only).
    coupling: Option<Coupling<D>>,
    /// Newton's preconditioner: the solvers of coordinates 1.. (`solver` serves coordinate
    /// 0), each set up for its diagonal block A − G_cc of the Jacobian; empty while the
    /// preconditioner is `solver` on A for every coordinate.
    own: Vec<Box<dyn LinearSolver>>,
    /// The buffer of a block for solvers that copy it rather than take it over.
    scratch: Option<Stencil9>,
    /// True while the solvers hold the blocks A − G_cc (block Gauss–Seidel).
    blocks: bool,
}

impl<const D: usize> picard::System for System2<'_, D> {
    type Op = Stencil9;

    fn evaluate(&mut self) -> f64 {
        if self.a.is_empty() {
            // the solver took the operator over at the last `prepare`
            let (nx, ny) = (self.x.ni() - 2, self.x.nj() - 2);
            self.a = match self.solver.give_back() {
                Some(a) if (a.nx(), a.ny()) == (nx, ny) => a,
                _ => Stencil9::zeros(nx, ny),
            };
        }
        assemble(self.x, &self.ctrl, &mut self.a, &mut self.rhs);
        residual_scaled(self.x, &self.a, &self.rhs, self.diam, Some(&mut self.r))
    }

    /// The solver takes the operator over (one copy, not two; taken back by `evaluate`).
    fn prepare(&mut self, small: bool) -> std::result::Result<(), SolveError> {
        self.solver.adopt(&mut self.a, small)
    }

    fn linear(&mut self) -> picard::Linear<'_, Stencil9> {
        picard::Linear::new(&mut *self.solver, &self.a, &self.r, &mut self.u)
    }

    fn apply(&mut self, largest: f64) -> f64 {
        let (ni, nx) = (self.x.ni(), self.x.ni() - 2);
        for (c, uc) in self.u.iter().enumerate() {
            add_interior(uc, ni, nx, self.x.coord_mut(c));
        }
        if self.x.all_finite() {
            largest / self.diam
        } else {
            f64::NAN
        }
    }

    fn diameter(&self) -> f64 {
        self.diam
    }
}

impl<const D: usize> System2<'_, D> {
    /// Sets up (or with `refresh` updates, [`LinearSolver::update`]) each coordinate's solver
    /// for its diagonal block A − G_cc of the Jacobian (`solver` for coordinate 0, `own` for
    /// the others). Each block is written into the buffer its solver held the last one in and
    /// handed over ([`LinearSolver::adopt`]): the multigrids' fine levels hold the only copies
    /// (dented square at 1025²: no 75 MB scratch operator, and no copy of it per coordinate
    /// and Newton step).
    fn load_blocks(&mut self, refresh: bool) -> std::result::Result<(), SolveError> {
        let cp = self
            .coupling
            .as_ref()
            .expect("linearize before the preconditioner");
        let (nx, ny) = (self.a.nx(), self.a.ny());
        for c in 0..D {
            let solver: &mut dyn LinearSolver = if c == 0 {
                &mut *self.solver
            } else {
                &mut *self.own[c - 1]
            };
            let fits = |s: &Stencil9| (s.nx(), s.ny()) == (nx, ny);
            let mut op = match solver.give_back().filter(fits) {
                Some(op) => op,
                None => match self.scratch.take().filter(fits) {
                    Some(op) => op,
                    None => Stencil9::zeros(nx, ny),
                },
            };
            cp.own_operator(&self.a, c, &mut op);
            let res = solver.adopt(&mut op, refresh);
            if !op.is_empty() {
                // a solver that copies: the buffer serves the next block
                self.scratch = Some(op);
            }
            res?;
        }
        Ok(())
    }
}

impl<const D: usize> NewtonSystem for System2<'_, D> {
    fn coordinates(&self) -> usize {
        D
    }

    fn nodes(&self) -> usize {
        self.a.len()
    }

    /// At the first Newton step, computed control functions ([`Control2::is_computed`]) are
    /// stored for the rest of the solve: a Newton step evaluates and linearizes at every
    /// iterate, and computing them is half of an evaluation's time (dented square at 1025²:
    /// a whole generation ~8 % faster), for 48 bytes per node on top of the Newton steps'
    /// own ~400 (the Picard-only solves of smooth domains keep computing them).
    fn linearize(&mut self) {
        if self.ctrl.is_computed() {
            self.ctrl = Cow::Owned(self.ctrl.stored_copy());
        }
        let cp = self
            .coupling
            .get_or_insert_with(|| Coupling::new(self.a.nx(), self.a.ny()));
        cp.linearize(self.x, &self.ctrl);
    }

    fn apply_jacobian(&self, v: &[f64], out: &mut [f64]) {
        self.coupling
            .as_ref()
            .expect("linearize before apply_jacobian")
            .apply(&self.a, v, out);
    }

    fn diagonal(&self, out: &mut [f64]) {
        use crate::solve::stencil9::dir::C;
        out.par_iter_mut()
            .zip(self.a.coefs().par_iter())
            .for_each(|(o, st)| *o = st[C]);
    }

    fn setup_preconditioner(&mut self) -> std::result::Result<(), SolveError> {
        while self.own.len() + 1 < D {
            match self.solver.companion() {
                Some(s) => self.own.push(s),
                None => break,
            }
        }
        if self.own.len() + 1 < D {
            self.blocks = false;
            return self.solver.setup(&self.a);
        }
        self.load_blocks(false)?;
        self.blocks = true;
        Ok(())
    }

    /// The blocks A − G_cc at the current iterate into the solvers' fine levels
    /// ([`LinearSolver::update`]), their coarse levels kept from the last setup; a full setup
    /// where the solvers do not hold the blocks (after a Picard step).
    fn refresh_preconditioner(&mut self) -> std::result::Result<(), SolveError> {
        if !self.blocks {
            return self.setup_preconditioner();
        }
        self.load_blocks(true)
    }

    fn precondition(&self, v: &mut [f64], out: &mut [f64]) -> std::result::Result<(), SolveError> {
        let n = self.a.len();
        if !self.blocks {
            return out
                .par_chunks_mut(n)
                .zip(v.par_chunks(n))
                .map(|(oc, vc)| self.solver.precondition(vc, oc))
                .collect();
        }
        // block Gauss–Seidel over the coordinates: (A − G_cc) z_c = v_c + Σ_{d<c} G_cd z_d
        let cp = self
            .coupling
            .as_ref()
            .expect("linearize before the preconditioner");
        for c in 0..D {
            let (done, rest) = out.split_at_mut(c * n);
            let w = &mut v[c * n..(c + 1) * n];
            for (d, zd) in done.chunks(n).enumerate() {
                cp.add_coupling(c, d, zd, w);
            }
            let solver: &dyn LinearSolver = if c == 0 {
                &*self.solver
            } else {
                &*self.own[c - 1]
            };
            solver.precondition(w, &mut rest[..n])?;
        }
        Ok(())
    }

    fn picard_ready(&mut self) {
        self.blocks = false;
    }
}

/// Convenience: the start grid with the boundary of `b` and the solve of [24] from it.
pub fn solve_from<const D: usize>(
    b: &Boundary2<D>,
    start: Grid2<D>,
    ctrl: &Control2,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<(Grid2<D>, PicardInfo)> {
    let mut x = start;
    b.apply_to(&mut x);
    let info = solve(&mut x, ctrl, solver, params, place)?;
    Ok((x, info))
}
