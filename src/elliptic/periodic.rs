//! The grid system [24] on a block that is periodic in ξ: an O-grid whose cut (E1 = E2, one
//! edge) floats. Node i = 0 and node i = N are one node; the cut's interior nodes are
//! unknowns like any other, and the nine-point stencils [43, 44] of columns 0 and N − 1 wrap
//! around the seam. Only E3 and E4 (the airfoil and the far field, say) carry Dirichlet data.
//!
//! The unknowns are the columns 0..N − 1 of the rows 1..M − 1 ([`Periodic9`]); column N is
//! column 0 copied bit for bit after every step, so the written block has its seam
//! duplicated exactly. The algebraic transformation, the start grid and the control functions
//! come from the two η boundaries only ([`crate::algebraic::periodic`]): the cut's given nodes
//! are not used.
//!
//! The Picard steps, their stop and the report are those of [`crate::elliptic::picard`],
//! damped by [`DAMPING`]; with `nonlinear = "newton"` the steps of
//! [`crate::elliptic::newton`], the Jacobian applied by a forward difference of the residual.
//! Each step's linear systems are solved by faer's sparse LU ([`DirectLuPeriodic`]) whatever
//! `[solver] linear` says: the black-box multigrid is not periodic. Orthogonality (Section
//! 2.4) at the ring's sides is [`crate::elliptic::periodic_orthogonal`]; nested iteration is
//! not used.

use crate::algebraic::control2d::Control2;
use crate::algebraic::periodic::{close_seam, periodic_control_for, periodic_start};
use crate::algebraic::ControlKind;
use crate::elliptic::newton::{self, NewtonSystem};
use crate::elliptic::picard::{self, BlockResult, Nonlinear, PicardInfo, PicardParams};
use crate::elliptic::poisson2d;
use crate::grid::boundary::Boundary2;
use crate::grid::{Edge, Grid2};
use crate::solve::periodic9::{DirectLuPeriodic, Periodic9};
use crate::solve::{LinearSolver, SolveError};
use crate::{Error, Result};
use rayon::prelude::*;
use std::sync::Mutex;

/// Each Picard step moves the nodes by this fraction of its correction (under-relaxation).
/// Measured on the one-block NACA0012 O-grid (`examples/naca0012_oneblock.toml`): full steps
/// fold the grid at the trailing edge after a few steps and diverge (the frozen operator
/// becomes singular); half steps converge, fold-free, in ~150 steps. Annuli converge either
/// way. The fixed point is the same; the stop's error estimate sees the slower contraction.
pub const DAMPING: f64 = 0.5;

/// Assembles the frozen nine-point operator of [43, 44] at iterate `x` (a periodic block,
/// column N = column 0) and the right-hand sides carrying the Dirichlet values of E3 and E4.
/// Rows are multiplied by −1 so that the diagonal 2(P + R) is positive, as in
/// [`crate::elliptic::poisson2d::assemble`].
pub fn assemble<const D: usize>(
    x: &Grid2<D>,
    ctrl: &Control2,
    a: &mut Periodic9,
    rhs: &mut [Vec<f64>; D],
) {
    let (ni, nj) = (x.ni(), x.nj());
    let nc = ni - 1;
    assert_eq!((a.nx(), a.ny()), (nc, nj - 2));
    let xs = x.coords();
    a.coefs_mut()
        .par_chunks_mut(nc)
        .enumerate()
        .for_each(|(jj, arow)| {
            let j = jj + 1;
            for (i, st) in arow.iter_mut().enumerate() {
                let n = i + ni * j;
                // east of column nc − 1 is column nc (= column 0), west of column 0 is nc − 1
                let (e, w) = (n + 1, if i == 0 { nc - 1 + ni * j } else { n - 1 });
                let (no, so) = (n + ni, n - ni);
                *st = poisson2d::stencil_at(xs, &ctrl.at(n), [e, w, no, so]);
            }
        });
    // E3 and E4 neighbours go to the right-hand side (first and last row of unknowns).
    for b in rhs.iter_mut() {
        b.fill(0.0);
    }
    let ny = nj - 2;
    for (jj, dj, jb) in [(0, 0, 0), (ny - 1, 2, nj - 1)] {
        for i in 0..nc {
            let p = i + nc * jj;
            for di in 0..3 {
                let k = di + 3 * dj;
                let m = a.wrap(i, di) + ni * jb;
                let v = a.coefs()[p][k];
                for (b, c) in rhs.iter_mut().zip(xs.iter()) {
                    b[p] -= v * c[m];
                }
                a.coefs_mut()[p][k] = 0.0;
            }
        }
    }
}

/// The residual b − A x of every unknown (per coordinate, into `out`) and its largest value
/// relative to the row's diagonal and to `diam`, as [`crate::elliptic::poisson2d::residual`].
fn residual<const D: usize>(
    x: &Grid2<D>,
    a: &Periodic9,
    rhs: &[Vec<f64>; D],
    diam: f64,
    out: &mut [Vec<f64>; D],
) -> f64 {
    let (ni, nc) = (x.ni(), a.nx());
    let xs = x.coords();
    let mut worst = 0.0f64;
    for (o, (xc, b)) in out.iter_mut().zip(xs.iter().zip(rhs.iter())) {
        let w = o
            .par_chunks_mut(nc)
            .zip(a.coefs().par_chunks(nc))
            .enumerate()
            .map(|(jj, (orow, arow))| {
                let j = jj + 1;
                let mut w = 0.0f64;
                for (i, (r, st)) in orow.iter_mut().zip(arow).enumerate() {
                    let mut ax = 0.0;
                    for dj in 0..3 {
                        let row = ni * (j + dj - 1);
                        for di in 0..3 {
                            ax += st[di + 3 * dj] * xc[row + a.wrap(i, di)];
                        }
                    }
                    *r = b[i + nc * jj] - ax;
                    w = w.max((*r / st[4]).abs());
                }
                w
            })
            .reduce(|| 0.0, f64::max);
        worst = worst.max(w);
    }
    worst / diam
}

/// The Picard system of one periodic block.
struct SystemP<'a, const D: usize> {
    x: &'a mut Grid2<D>,
    ctrl: &'a Control2,
    solver: DirectLuPeriodic,
    a: Periodic9,
    rhs: [Vec<f64>; D],
    r: [Vec<f64>; D],
    u: [Vec<f64>; D],
    diam: f64,
    /// The fraction of the correction applied: [`DAMPING`] for Picard steps, 1 for Newton
    /// steps (their line search picks the length).
    damp: f64,
    /// The perturbed iterate and its operator, right-hand sides and residual, for the
    /// finite-difference Jacobian (Newton steps only).
    fd: Option<Mutex<Perturbed<D>>>,
}

/// Scratch of [`SystemP::apply_jacobian`].
struct Perturbed<const D: usize> {
    x: Grid2<D>,
    a: Periodic9,
    rhs: [Vec<f64>; D],
    r: [Vec<f64>; D],
}

impl<const D: usize> picard::System for SystemP<'_, D> {
    type Op = Periodic9;

    fn evaluate(&mut self) -> f64 {
        assemble(self.x, self.ctrl, &mut self.a, &mut self.rhs);
        residual(self.x, &self.a, &self.rhs, self.diam, &mut self.r)
    }

    fn linear(&mut self) -> picard::Linear<'_, Periodic9> {
        picard::Linear::new(&mut self.solver, &self.a, &self.r, &mut self.u)
    }

    fn apply(&mut self, largest: f64) -> f64 {
        let (ni, nc) = (self.x.ni(), self.a.nx());
        let damp = self.damp;
        for uc in self.u.iter_mut() {
            uc.par_iter_mut().for_each(|v| *v *= damp);
        }
        for (c, uc) in self.u.iter().enumerate() {
            let full = self.x.coord_mut(c);
            for (jj, row) in uc.chunks(nc).enumerate() {
                let base = ni * (jj + 1);
                for (f, d) in full[base..base + nc].iter_mut().zip(row) {
                    *f += d;
                }
            }
        }
        close_seam(self.x);
        if self.x.all_finite() {
            self.damp * largest / self.diam
        } else {
            f64::NAN
        }
    }

    fn diameter(&self) -> f64 {
        self.diam
    }
}

/// Newton steps on a periodic block (`nonlinear = "newton"`): the Jacobian J = −∂r/∂x of the
/// residual r = b − A x is applied by a forward difference of r along the Krylov vector (the
/// metric coefficients couple the coordinates and wrap around the seam; the difference
/// needs no second assembly code), and the preconditioner is the Picard operator's LU, one
/// solve per coordinate. The damped Picard steps converge at ~0.8 per step because of an
/// oscillating mode (undamped Picard diverges); Newton resolves it.
impl<const D: usize> NewtonSystem for SystemP<'_, D> {
    fn coordinates(&self) -> usize {
        D
    }

    fn nodes(&self) -> usize {
        self.a.len()
    }

    fn linearize(&mut self) {
        self.damp = 1.0;
        if self.fd.is_none() {
            let (nc, ny) = (self.a.nx(), self.a.ny());
            self.fd = Some(Mutex::new(Perturbed {
                x: self.x.clone(),
                a: Periodic9::zeros(nc, ny),
                rhs: std::array::from_fn(|_| vec![0.0; nc * ny]),
                r: std::array::from_fn(|_| vec![0.0; nc * ny]),
            }));
        }
    }

    fn apply_jacobian(&self, v: &[f64], out: &mut [f64]) {
        let (ni, nc, n) = (self.x.ni(), self.a.nx(), self.a.len());
        let vmax = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if vmax == 0.0 {
            out.fill(0.0);
            return;
        }
        // a step of ~√ε relative to the block's size along v
        let eps = 1.5e-8 * self.diam / vmax;
        let mut guard = self.fd.as_ref().expect("linearize first").lock();
        let p = guard.as_deref_mut().expect("no panic holds the scratch");
        for (c, (pc, xc)) in p.x.coords_mut().iter_mut().zip(self.x.coords()).enumerate() {
            pc.copy_from_slice(xc);
            for (jj, vrow) in v[c * n..(c + 1) * n].chunks(nc).enumerate() {
                let base = ni * (jj + 1);
                for (q, d) in pc[base..base + nc].iter_mut().zip(vrow) {
                    *q += eps * d;
                }
            }
        }
        close_seam(&mut p.x);
        assemble(&p.x, self.ctrl, &mut p.a, &mut p.rhs);
        residual(&p.x, &p.a, &p.rhs, self.diam, &mut p.r);
        for (c, (rp, r0)) in p.r.iter().zip(&self.r).enumerate() {
            out[c * n..(c + 1) * n]
                .par_iter_mut()
                .zip(rp.par_iter().zip(r0))
                .for_each(|(o, (a, b))| *o = (b - a) / eps);
        }
    }

    fn diagonal(&self, out: &mut [f64]) {
        out.par_iter_mut()
            .zip(self.a.coefs().par_iter())
            .for_each(|(o, st)| *o = st[4]);
    }

    fn setup_preconditioner(&mut self) -> std::result::Result<(), SolveError> {
        self.damp = 1.0;
        self.solver.setup(&self.a)
    }

    fn precondition(&self, v: &mut [f64], out: &mut [f64]) -> std::result::Result<(), SolveError> {
        let n = self.a.len();
        for (oc, vc) in out.chunks_mut(n).zip(v.chunks(n)) {
            self.solver.precondition(vc, oc)?;
        }
        Ok(())
    }

    fn picard_ready(&mut self) {
        self.damp = DAMPING;
    }
}

/// Solves the periodic grid system [24] by Picard iteration from `x` (its rows j = 0 and
/// j = M are the Dirichlet data; column N is overwritten by column 0). `place` names the
/// block in errors; non-convergence is reported in the returned [`PicardInfo`].
///
/// # Errors
/// A block of fewer than 4 × 3 nodes, control functions of another size or not finite,
/// a failed linear solve.
pub fn solve<const D: usize>(
    x: &mut Grid2<D>,
    ctrl: &Control2,
    params: &PicardParams,
    place: &str,
) -> Result<PicardInfo> {
    let (ni, nj) = (x.ni(), x.nj());
    picard::check_input(
        place,
        ni >= 4 && nj >= 3,
        "a periodic block needs at least 4 × 3 nodes",
        (ctrl.ni(), ctrl.nj()) == (ni, nj),
        ctrl.all_finite(),
    )?;
    close_seam(x);
    let (nc, ny) = (ni - 1, nj - 2);
    let diam = x.diameter();
    let mut sys = SystemP {
        x,
        ctrl,
        solver: DirectLuPeriodic::new(),
        a: Periodic9::zeros(nc, ny),
        rhs: std::array::from_fn(|_| vec![0.0; nc * ny]),
        r: std::array::from_fn(|_| vec![0.0; nc * ny]),
        u: std::array::from_fn(|_| vec![0.0; nc * ny]),
        diam,
        damp: DAMPING,
        fd: None,
    };
    let solved = if params.iteration(D) == Nonlinear::Newton {
        newton::run(
            &mut sys,
            params,
            picard::Rules::stop(0.0),
            false,
            place,
            &mut |_, _| {},
        )
    } else {
        picard::run(
            &mut sys,
            params,
            picard::Rules::stop(0.0),
            place,
            &mut |_, _| {},
        )
    };
    solved.map(|(info, _)| info)
}

/// Grids one periodic block (E1 = E2 the floating cut): the start grid between E3 and E4
/// ([`periodic_start`]), or `start` (its E3 and E4 rows replaced by `b`'s), control functions
/// of `kind` from the η boundaries ([`periodic_control_for`]), Picard iteration of [24].
/// `orthogonal` (E1, E2, E3, E4) must be all false: orthogonality is
/// [`crate::elliptic::periodic_orthogonal::grid_block`], which calls this for its step 1.
///
/// # Errors
/// Orthogonality asked for, E3 or E4 not closed (its first and last nodes apart), and the
/// errors of [`solve`].
pub fn grid_block<const D: usize>(
    b: &Boundary2<D>,
    start: Option<Grid2<D>>,
    orthogonal: [bool; 4],
    kind: ControlKind,
    params: &PicardParams,
    place: &str,
) -> Result<BlockResult<D>> {
    if let Some(e) = Edge::ALL.into_iter().find(|e| orthogonal[e.index()]) {
        return Err(Error::input(
            format!("{place}, edge {e}"),
            "orthogonality is not available on a periodic block (a floating cut) yet: \
             remove `orthogonal` from its edges, or fix the cut",
        ));
    }
    for e in [Edge::E3, Edge::E4] {
        let p = b.edge(e);
        let gap = (0..D)
            .map(|c| (p[0][c] - p[p.len() - 1][c]).powi(2))
            .sum::<f64>()
            .sqrt();
        if gap > 1e-6 * b.diameter() {
            return Err(Error::input(
                format!("{place}, edge {e}"),
                format!("a periodic block's {e} must be closed, but its ends are {gap:.3e} apart"),
            ));
        }
    }
    let mut x = match start {
        Some(mut g) => {
            b.apply_to(&mut g);
            g
        }
        None => periodic_start(b),
    };
    let ctrl = periodic_control_for(b, kind);
    let picard = solve(&mut x, &ctrl, params, place)?;
    Ok(BlockResult { grid: x, picard })
}
