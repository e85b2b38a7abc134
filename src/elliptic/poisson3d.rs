//! The volume grid system [86]–[88] discretized on the 19-point stencil and solved by Picard
//! iteration (METHOD.md §6).
//!
//! Each Picard step freezes α^ij (J² times the contravariant metric, from the covariant
//! metric g_ij of the current iterate by central differences) and the first-derivative
//! coefficients Σ_ij α^ij P^k_ij, assembles the 19-point operator of
//! `Σ_ij α^ij x_{ξiξj} + Σ_k (Σ_ij α^ij P^k_ij) x_{ξk} = 0` (central differences in index space;
//! mixed derivatives by the 4-corner formula that [`crate::algebraic::control3d`] uses, so the
//! tensor-product box is an exact discrete solution), and solves it once per coordinate with
//! the same operator. The steps, the stopping rule and the history are those of the 2D
//! system (`src/elliptic/picard.rs`).
//!
//! The linear systems are solved in correction form, A δ = b − A x_k from δ = 0, and only as
//! accurately as the step needs: the inexact Picard iteration of [`crate::elliptic::poisson2d`], with the
//! same forcing term η = clamp(0.5 ρ, linear_tolerance, linear_forcing) (ρ the observed Picard
//! contraction; `PicardParams::linear_forcing`, 0 = every step to `linear_tolerance`). A step
//! then costs a few Bi-CGSTAB iterations instead of a solve to 1e-10, and the fixed point, the
//! discrete solution of [86], is unchanged. `solve_timed` also measures the work unit of
//! nested iteration ([`crate::elliptic::nested3d`]).

use crate::algebraic::control3d::Control3;
pub use crate::elliptic::metric3d::alphas;
use crate::elliptic::metric3d::row_coefficients;
use crate::elliptic::picard;
use crate::elliptic::picard::{PicardInfo, PicardParams, PicardStep};
use crate::elliptic::symmetry3d::{face_row, Symmetry};
use crate::solve::stencil19::{Stencil19, C, OFFSETS};
use crate::solve::{LinearSolver, SolveError};
use crate::{Grid3, Result};
use rayon::prelude::*;

/// Assembles the frozen 19-point operator of [86] at iterate `x` and the right-hand sides
/// (one per coordinate) that carry the Dirichlet boundary values. Rows are multiplied by −1 so
/// that the diagonal 2(α11 + α22 + α33) is positive, and divided by it (`row_coefficients`: why).
pub fn assemble(x: &Grid3, ctrl: &Control3, a: &mut Stencil19, rhs: &mut [Vec<f64>; 3]) {
    assemble_with(x, ctrl, &Symmetry::none(), a, rhs)
}

/// [`assemble`] with symmetry faces, whose nodes are unknowns too
/// ([`crate::elliptic::symmetry3d`]): the operator's unknowns are the box
/// [`Symmetry::unknown_box`].
pub fn assemble_with(
    x: &Grid3,
    ctrl: &Control3,
    sym: &Symmetry,
    a: &mut Stencil19,
    rhs: &mut [Vec<f64>; 3],
) {
    let dims = x.dims();
    let [ni, nj, _] = dims;
    let (lo, [nx, ny, nz]) = sym.unknown_box(dims);
    assert_eq!(a.dims(), [nx, ny, nz]);
    let (plane, uplane) = (ni * nj, nx * ny);
    let st = [1isize, ni as isize, plane as isize];
    let xs = x.coords();
    let [r0, r1, r2] = rhs;
    let unknown = |p: [usize; 3]| (0..3).all(|d| p[d] >= lo[d] && p[d] < lo[d] + [nx, ny, nz][d]);
    a.coefs_mut()
        .par_chunks_mut(uplane)
        .zip(r0.par_chunks_mut(uplane))
        .zip(r1.par_chunks_mut(uplane))
        .zip(r2.par_chunks_mut(uplane))
        .enumerate()
        .for_each(|(kk, (((arow, b0), b1), b2))| {
            let k = kk + lo[2];
            let mut bs = [b0, b1, b2];
            for jj in 0..ny {
                let j = jj + lo[1];
                for ii in 0..nx {
                    let i = ii + lo[0];
                    let n = i + ni * j + plane * k;
                    let q = ii + nx * jj;
                    let row = &mut arow[q];
                    if !sym.is_empty() {
                        match sym.on(dims, [i, j, k]) {
                            Ok(None) => {}
                            Ok(Some(f)) => {
                                let mut b = [0.0; 3];
                                let own = sym.control(f, dims, [i, j, k]);
                                face_row(
                                    x,
                                    ctrl,
                                    own,
                                    &sym.faces()[f],
                                    [i, j, k],
                                    unknown,
                                    row,
                                    &mut b,
                                );
                                for (bc, v) in bs.iter_mut().zip(b) {
                                    bc[q] = v;
                                }
                                continue;
                            }
                            Err(()) => {
                                // held: δ = 0 (b − A x = 0)
                                *row = [0.0; 19];
                                row[C] = 1.0;
                                for (bc, xc) in bs.iter_mut().zip(xs.iter()) {
                                    bc[q] = xc[n];
                                }
                                continue;
                            }
                        }
                    }
                    // Covariant metric g_ab = x_a · x_b, central differences.
                    let mut d = [[0.0; 3]; 3];
                    for (c, xc) in xs.iter().enumerate() {
                        for (ax, s) in st.iter().enumerate() {
                            d[c][ax] = 0.5
                                * (xc[(n as isize + s) as usize] - xc[(n as isize - s) as usize]);
                        }
                    }
                    let g: [[f64; 3]; 3] = std::array::from_fn(|p| {
                        std::array::from_fn(|r| (0..3).map(|c| d[c][p] * d[c][r]).sum())
                    });
                    let al = alphas(g);
                    let pk = ctrl.at(n);
                    let w = [1.0, 2.0, 2.0, 1.0, 2.0, 1.0];
                    let sk: [f64; 3] =
                        std::array::from_fn(|c| (0..6).map(|m| w[m] * al[m] * pk[3 * m + c]).sum());
                    row_coefficients(row, al, sk);
                    // Known boundary neighbours go to the right-hand side.
                    for b in bs.iter_mut() {
                        b[q] = 0.0;
                    }
                    if ii == 0 || jj == 0 || kk == 0 || ii == nx - 1 || jj == ny - 1 || kk == nz - 1
                    {
                        for (m, o) in OFFSETS.iter().enumerate().skip(1) {
                            let p = [
                                (i as isize + o[0] as isize) as usize,
                                (j as isize + o[1] as isize) as usize,
                                (k as isize + o[2] as isize) as usize,
                            ];
                            if !unknown(p) {
                                let nb = p[0] + ni * p[1] + plane * p[2];
                                for (b, xc) in bs.iter_mut().zip(xs.iter()) {
                                    b[q] -= row[m] * xc[nb];
                                }
                                row[m] = 0.0;
                            }
                        }
                    }
                }
            }
        });
}

/// Residual of [86] at grid `x`: the largest |A x − b| over interior nodes, each row divided
/// by its diagonal and by the domain diameter (as [`crate::elliptic::poisson2d::residual`]).
pub fn residual(x: &Grid3, a: &Stencil19, rhs: &[Vec<f64>; 3], diam: f64) -> f64 {
    let mut r: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; a.len()]);
    let mut u = vec![0.0; a.len()];
    residual_into(x, a, rhs, diam, &mut r, &mut u)
}

/// [`residual`] that also stores `b − A x` per coordinate in `r` (interior numbering), with
/// `u` as scratch for the gathered coordinates: no allocation.
fn residual_into(
    x: &Grid3,
    a: &Stencil19,
    rhs: &[Vec<f64>; 3],
    diam: f64,
    r: &mut [Vec<f64>; 3],
    u: &mut [f64],
) -> f64 {
    let mut worst = 0.0f64;
    for (c, (b, rc)) in rhs.iter().zip(r.iter_mut()).enumerate() {
        gather(x, c, u);
        a.residual(b, u, rc);
        let w = rc
            .par_iter()
            .zip(a.coefs())
            .map(|(rv, row)| (rv / row[C]).abs())
            .reduce(|| 0.0, f64::max);
        worst = worst.max(w);
    }
    worst / diam
}

/// Interior values of coordinate c into `out` (unknown order).
pub fn gather(x: &Grid3, c: usize, out: &mut [f64]) {
    gather_in(x, &Symmetry::none(), c, out)
}

/// Values of coordinate c at the unknowns (interior nodes and those of symmetry faces, `sym`)
/// into `out` (unknown order).
fn gather_in(x: &Grid3, sym: &Symmetry, c: usize, out: &mut [f64]) {
    let (len, starts) = box_rows(x.dims(), sym);
    let full = x.coord(c);
    for (row, at) in out.chunks_mut(len).zip(starts) {
        row.copy_from_slice(&full[at..at + len]);
    }
}

/// Adds the correction `inner` (unknown numbering) to coordinate c of `x`.
fn add_interior(x: &mut Grid3, sym: &Symmetry, c: usize, inner: &[f64]) {
    let (len, starts) = box_rows(x.dims(), sym);
    let full = &mut x.coords_mut()[c];
    for (row, at) in inner.chunks(len).zip(starts) {
        for (o, d) in full[at..at + len].iter_mut().zip(row) {
            *o += d;
        }
    }
}

/// The unknown box's rows along i ([`Symmetry::unknown_box`]): their length and, in the
/// unknowns' order, the grid index of each row's first node.
fn box_rows(dims: [usize; 3], sym: &Symmetry) -> (usize, impl Iterator<Item = usize>) {
    let [ni, nj, _] = dims;
    let (lo, n) = sym.unknown_box(dims);
    let starts = (0..n[1] * n[2]).map(move |q| {
        let (jj, kk) = (q % n[1], q / n[1]);
        lo[0] + ni * (jj + lo[1]) + ni * nj * (kk + lo[2])
    });
    (n[0], starts)
}

/// Solves the grid system [86] by Picard iteration from the start grid `x` (whose boundary
/// nodes are the Dirichlet data and stay untouched). `progress` is called after every step
/// with the step number and its record. Non-convergence is not an error: it is reported in
/// the returned [`PicardInfo`].
///
/// Each step solves its three linear systems in correction form, A δ = b − A x_k from δ = 0,
/// in parallel with the operator's one setup, and only to the relative residual of the
/// forcing term of the inexact Picard iteration (`PicardParams::linear_forcing`, the rule of
/// [`crate::elliptic::poisson2d`]): the fixed point is that of the exact iteration, since the linear
/// error is relative to the Picard residual, which vanishes there.
pub fn solve(
    x: &mut Grid3,
    ctrl: &Control3,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<PicardInfo> {
    solve_symmetric(x, ctrl, &Symmetry::none(), solver, params, place, progress)
}

/// [`solve`] with symmetry faces ([`crate::elliptic::symmetry3d`]): their nodes slide in
/// their planes and the grid lines meet them at right angles. The nodes of `x` on those
/// faces must lie on their planes (they are the start of their iteration).
pub fn solve_symmetric(
    x: &mut Grid3,
    ctrl: &Control3,
    sym: &Symmetry,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<PicardInfo> {
    solve_in(
        x,
        ctrl,
        sym,
        solver,
        params,
        picard::Rules::stop(0.0),
        place,
        progress,
    )
    .map(|(info, _)| info)
}

/// [`solve`], also returning the shortest time (seconds) of one evaluation of the residual of
/// [86] with its assembly ([`assemble`] + residual) on this grid, measured at every step: the
/// work unit of [`crate::elliptic::nested3d`]. With `rules.relative_stop > 0` the iteration also stops
/// (converged) once the update falls below that times the first update (a coarse
/// level of nested iteration).
pub(crate) fn solve_timed(
    x: &mut Grid3,
    ctrl: &Control3,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    rules: picard::Rules,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<(PicardInfo, f64)> {
    solve_in(
        x,
        ctrl,
        &Symmetry::none(),
        solver,
        params,
        rules,
        place,
        progress,
    )
}

/// [`solve_timed`] with symmetry faces.
#[allow(clippy::too_many_arguments)]
fn solve_in(
    x: &mut Grid3,
    ctrl: &Control3,
    sym: &Symmetry,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    rules: picard::Rules,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<(PicardInfo, f64)> {
    let dims = x.dims();
    picard::check_input(
        place,
        dims.iter().all(|&n| n >= 3),
        "a volume block needs at least 3 × 3 × 3 nodes",
        ctrl.dims() == dims,
        ctrl.all_finite(),
    )?;
    let diam = x.diameter();
    let mut groups = Vec::new();
    for (m, (gsym, coords)) in sym.groups().into_iter().enumerate() {
        let (_, [nx, ny, nz]) = gsym.unknown_box(dims);
        let n = nx * ny * nz;
        let own = if m == 0 {
            None
        } else {
            Some(solver.companion().ok_or_else(|| {
                crate::Error::input(
                    place,
                    format!(
                        "symmetry faces need a linear solver that can make a second one, not {}",
                        solver.name()
                    ),
                )
            })?)
        };
        groups.push(Group {
            sym: gsym,
            coords,
            a: Stencil19::zeros(nx, ny, nz),
            rhs: std::array::from_fn(|_| vec![0.0; n]),
            solver: own,
        });
    }
    let len = |c: usize| {
        let g = groups
            .iter()
            .find(|g| g.coords.contains(&c))
            .expect("every coordinate");
        g.a.len()
    };
    let most = (0..3).map(len).max().unwrap_or(0);
    let mut sys = System3 {
        r: std::array::from_fn(|c| vec![0.0; len(c)]),
        u: std::array::from_fn(|c| vec![0.0; len(c)]),
        x,
        ctrl,
        solver,
        groups,
        scratch: vec![0.0; most],
        diam,
    };
    picard::run(&mut sys, params, rules, place, progress)
}

/// Coordinates solved with one operator: those whose symmetry faces (the faces they slide
/// along, [`Symmetry::groups`]) are the same. The first group's solver is the block's own.
struct Group {
    sym: Symmetry,
    coords: Vec<usize>,
    a: Stencil19,
    rhs: [Vec<f64>; 3],
    solver: Option<Box<dyn LinearSolver<Stencil19>>>,
}

/// The Picard system of one volume block: iterate, frozen operators, right-hand sides, and
/// the residuals b − A x_k and corrections δ of the coordinates (unknown numbering of each
/// coordinate's group).
struct System3<'a> {
    x: &'a mut Grid3,
    ctrl: &'a Control3,
    solver: &'a mut dyn LinearSolver<Stencil19>,
    groups: Vec<Group>,
    r: [Vec<f64>; 3],
    u: [Vec<f64>; 3],
    scratch: Vec<f64>,
    diam: f64,
}

impl picard::System for System3<'_> {
    type Op = Stencil19;

    fn evaluate(&mut self) -> f64 {
        let mut worst = 0.0f64;
        for g in self.groups.iter_mut() {
            if g.a.is_empty() {
                // the solver took the operator over at the last `prepare`
                let (_, dims) = g.sym.unknown_box(self.x.dims());
                let back = match &mut g.solver {
                    Some(s) => s.give_back(),
                    None => self.solver.give_back(),
                };
                g.a = match back {
                    Some(a) if a.dims() == dims => a,
                    _ => Stencil19::zeros(dims[0], dims[1], dims[2]),
                };
            }
            assemble_with(self.x, self.ctrl, &g.sym, &mut g.a, &mut g.rhs);
            for &c in &g.coords {
                let u = &mut self.scratch[..g.a.len()];
                gather_in(self.x, &g.sym, c, u);
                g.a.residual(&g.rhs[c], u, &mut self.r[c]);
                let w = self.r[c]
                    .par_iter()
                    .zip(g.a.coefs())
                    .map(|(rv, row)| (rv / row[C]).abs())
                    .reduce(|| 0.0, f64::max);
                worst = worst.max(w);
            }
        }
        worst / self.diam
    }

    fn linear(&mut self) -> picard::Linear<'_, Stencil19> {
        let mut others: [Option<&dyn LinearSolver<Stencil19>>; 3] = [None; 3];
        for g in &self.groups {
            if let Some(s) = &g.solver {
                for &c in &g.coords {
                    others[c] = Some(s.as_ref());
                }
            }
        }
        picard::Linear::new(&mut *self.solver, &self.groups[0].a, &self.r, &mut self.u)
            .with_others(others)
    }

    /// The solvers take the operators over (one copy, not two; taken back by `evaluate`).
    fn prepare(&mut self, small: bool) -> std::result::Result<(), SolveError> {
        for g in &mut self.groups {
            match &mut g.solver {
                Some(s) => s.adopt(&mut g.a, small)?,
                None => self.solver.adopt(&mut g.a, small)?,
            }
        }
        Ok(())
    }

    fn apply(&mut self, largest: f64) -> f64 {
        for g in &self.groups {
            for &c in &g.coords {
                add_interior(self.x, &g.sym, c, &self.u[c]);
            }
        }
        largest / self.diam
    }

    fn diameter(&self) -> f64 {
        self.diam
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebraic::control3d::control_for;
    use crate::algebraic::ControlKind;
    use crate::grid::faces::Faces;
    use crate::solve::ilu::BiCgStabIlu;

    /// Node k of n along an axis of length 1 clustered towards 0 (`b` = 9.9: first spacing
    /// about 1e-4; 15: about 1e-6, a wall).
    fn clustered(k: usize, n: usize, b: f64) -> f64 {
        ((k as f64 / (n - 1) as f64) * b).sinh() / b.sinh()
    }

    const N: [usize; 3] = [41, 37, 33];
    const B: [f64; 3] = [9.9, 15.0, 9.9];

    /// A box clustered towards its corner (0, 0, 0) in all three directions, as the wing
    /// volumes next to the M6 tip's trailing edge: unscaled, the operator's rows there are
    /// ~1e-20 of those at the far corner (α^ij scale with the fourth power of the spacing).
    fn corner_box() -> Grid3 {
        Grid3::from_fn(N[0], N[1], N[2], |i, j, k| {
            [
                clustered(i, N[0], B[0]),
                clustered(j, N[1], B[1]),
                clustered(k, N[2], B[2]),
            ]
        })
    }

    /// Every row of the assembled operator has diagonal 1 (the rows are scaled alike, so that
    /// a linear solve's relative residual weighs the small cells' equations as the large
    /// ones'), its 19 coefficients sum to zero (the rows of a consistent operator) and the
    /// tensor-product box stays the exact discrete solution.
    #[test]
    fn rows_are_scaled_to_unit_diagonal_and_the_box_stays_exact() {
        let x = corner_box();
        let faces = Faces::from_grid(&x);
        let ctrl = control_for(&faces, ControlKind::Algebraic, "box").unwrap();
        let mut a = Stencil19::zeros(N[0] - 2, N[1] - 2, N[2] - 2);
        let mut rhs: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; a.len()]);
        assemble(&x, &ctrl, &mut a, &mut rhs);
        for row in a.coefs() {
            assert_eq!(row[C], 1.0);
        }
        // Before the boundary columns moved to the right-hand side: an interior row.
        let mut row = [0.0; 19];
        row_coefficients(
            &mut row,
            [1e-20, 3e-22, -2e-22, 4e-20, 1e-22, 2e-20],
            [1e-20, -3e-20, 0.0],
        );
        assert_eq!(row[C], 1.0);
        assert!(row.iter().sum::<f64>().abs() < 1e-15, "{row:?}");
        assert!(residual(&x, &a, &rhs, x.diameter()) < 1e-12);
    }

    /// One inexact Picard step (Bi-CGSTAB/ILU(0) to the forcing term 0.1) from the corner box
    /// with every interior node moved by 0.2 of its smallest neighbour gap brings every node
    /// closer, measured in its own gaps (0.2 → 0.043).
    #[test]
    fn one_inexact_step_corrects_the_small_cells_of_a_clustered_corner() {
        let exact = corner_box();
        let faces = Faces::from_grid(&exact);
        let ctrl = control_for(&faces, ControlKind::Algebraic, "box").unwrap();
        let gap = |i: usize, j: usize, k: usize| {
            let idx = [i, j, k];
            (0..3)
                .map(|a| {
                    let x = |m: usize| clustered(m, N[a], B[a]);
                    (x(idx[a]) - x(idx[a] - 1)).min(x(idx[a] + 1) - x(idx[a]))
                })
                .fold(f64::INFINITY, f64::min)
        };
        let interior = || {
            (1..N[2] - 1).flat_map(|k| {
                (1..N[1] - 1).flat_map(move |j| (1..N[0] - 1).map(move |i| (i, j, k)))
            })
        };
        let error = |g: &Grid3| {
            interior()
                .map(|(i, j, k)| {
                    let (p, q) = (g.point(i, j, k), exact.point(i, j, k));
                    let d = (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0, f64::max);
                    d / gap(i, j, k)
                })
                .fold(0.0, f64::max)
        };
        let mut x = exact.clone();
        for (i, j, k) in interior() {
            let h = 0.2 * gap(i, j, k);
            let p = exact.point(i, j, k);
            let s = (i * 7 + j * 3 + k * 5) as f64;
            x.set(
                i,
                j,
                k,
                [
                    p[0] + h * s.sin(),
                    p[1] + h * s.cos(),
                    p[2] - h * (0.5 * s).sin(),
                ],
            );
        }
        let before = error(&x);
        let params = PicardParams {
            max_steps: 1,
            ..PicardParams::default()
        };
        solve(
            &mut x,
            &ctrl,
            &mut BiCgStabIlu::new(),
            &params,
            "box",
            &mut |_, _| {},
        )
        .unwrap();
        let after = error(&x);
        assert!(before > 0.15, "{before}");
        assert!(after < 0.5 * before, "{before} -> {after}");
    }
}
