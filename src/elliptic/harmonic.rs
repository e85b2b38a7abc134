//! Harmonic functions on an existing grid: div(A grad s) = 0 in computational space,
//! eqs. [50]–[52], by the vertex-centred finite volumes of [53] (METHOD.md §3, §8).
//!
//! With the covariant metric g_ij = x_{ξ^i} · x_{ξ^j} and J = √det g,
//! A = (1/J) [[g22, −g12], [−g12, g11]]. The same code is the Laplace equation of a planar grid
//! (D = 2) and the Laplace–Beltrami equation of a surface grid (D = 3).
//!
//! # Discretization
//! The control volume of node (i, j) is [ξ_i ± h/2] × [η_j ± k/2], clipped to a half volume on
//! an edge and a quarter volume in a corner. Each side is split into two half-faces, each inside
//! one cell. On a half-face normal to ξ the flux is (k/2)(A11 s_ξ + A12 s_η), where s_ξ and x_ξ
//! are differences along the cell edge that the half-face crosses and s_η, x_η are cell averages;
//! A is built from the same x_ξ, x_η (likewise normal to η). Index units are used: the fluxes
//! are invariant under the scaling of ξ and η. The result is a nine-point stencil that is the
//! 5-point Laplacian on a uniform grid and reproduces s = x exactly on any unfolded planar grid:
//! each half-face flux is the exact flux of a uniform gradient through the physical segment from
//! an edge midpoint to the cell centroid.
//!
//! # Boundary conditions
//! Per edge either Dirichlet values or zero Neumann flux, (grad s, A n) = 0 [46]: the nodes of a
//! Neumann edge are unknowns whose clipped control volume has no flux through its boundary side.
//! A corner is an unknown only if both edges meeting there are Neumann (zero flux through both
//! sides of its quarter volume); otherwise it takes the Dirichlet value of an adjacent Dirichlet
//! edge, E3/E4 winning over E1/E2 when both are Dirichlet. The unknowns are thus always a
//! rectangle of nodes, which is what [`Stencil9`] holds.
//!
//! Entry points: [`solve_harmonic`] (any conditions) and [`harmonic_st`] (the s and t problems
//! of Section 2.4).

use crate::grid::arclength::edge_arclengths;
use crate::grid::{Edge, Grid2};
use crate::solve::direct::DirectLu;
use crate::solve::stencil9::Stencil9;
use crate::solve::{LinearSolver, SolveControl, SolveError};
use crate::{Error, Result};

/// Boundary condition of one edge.
#[derive(Clone, Debug, PartialEq)]
pub enum EdgeCondition {
    /// Given values at the edge's nodes, in increasing index order (j for E1/E2, i for E3/E4).
    Dirichlet(Vec<f64>),
    /// Zero normal flux, ∂s/∂n = 0 in the physical domain [46].
    Neumann,
}

impl EdgeCondition {
    fn is_neumann(&self) -> bool {
        matches!(self, EdgeCondition::Neumann)
    }
}

/// The unknown nodes: the rectangle [i0, i0 + nx) × [j0, j0 + ny) of the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Unknowns {
    i0: usize,
    j0: usize,
    nx: usize,
    ny: usize,
}

impl Unknowns {
    fn new(ni: usize, nj: usize, conds: &[EdgeCondition; 4]) -> Self {
        let [e1, e2, e3, e4] = conds.each_ref().map(EdgeCondition::is_neumann);
        let i0 = usize::from(!e1);
        let i1 = if e2 { ni - 1 } else { ni - 2 };
        let j0 = usize::from(!e3);
        let j1 = if e4 { nj - 1 } else { nj - 2 };
        Unknowns {
            i0,
            j0,
            nx: i1 + 1 - i0,
            ny: j1 + 1 - j0,
        }
    }

    /// Position of grid node (i, j) in the unknown vector, if it is an unknown.
    #[inline]
    fn pos(&self, i: usize, j: usize) -> Option<usize> {
        let (ii, jj) = (i.wrapping_sub(self.i0), j.wrapping_sub(self.j0));
        // `then`, not `then_some`: the position of a wrapped (outside) index is not computed
        (ii < self.nx && jj < self.ny).then(|| ii + self.nx * jj)
    }
}

/// Stencil slot of the neighbour at offset (di, dj): (di + 1) + 3 (dj + 1).
#[inline]
fn slot(di: isize, dj: isize) -> usize {
    ((di + 1) + 3 * (dj + 1)) as usize
}

#[inline]
fn dot<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    a.iter().zip(b).map(|(u, v)| u * v).sum()
}

/// Coefficients (p, q) of one half-face flux ½(p Δ_n s + q avg_t s), eq. [52]: `xn` is x
/// differenced along the cell edge the half-face crosses, `xt` the cell average of x in the
/// other direction. p = |xt|²/J, q = −(xn·xt)/J; the same form serves both directions
/// (A11, A12 normal to ξ; A22, A21 normal to η). None for a degenerate cell.
#[inline]
fn face_coefs<const D: usize>(xn: &[f64; D], xt: &[f64; D]) -> Option<(f64, f64)> {
    let (nn, tt, nt) = (dot(xn, xn), dot(xt, xt), dot(xn, xt));
    let j2 = nn * tt - nt * nt;
    let j = j2.max(0.0).sqrt();
    let scale = (nn * tt).sqrt();
    if !scale.is_finite() || !j.is_finite() || j <= 1e-14 * scale {
        return None;
    }
    Some((tt / j, -nt / j))
}

/// One half-face: (edge vector, averaged vector, from corner, to corner, avg_t coefficients).
type HalfFace<'a, const D: usize> = (&'a [f64; D], &'a [f64; D], usize, usize, &'a [f64; 4]);

/// The flux balance of every node's control volume, eq. [53]: row n holds −Σ (outward
/// half-face fluxes) as nine coefficients over the neighbours of node n (slot order of
/// [`crate::solve::stencil9::dir`]). Boundary sides carry no flux (the Neumann condition); Dirichlet
/// rows are discarded later. Errors name the first degenerate cell.
pub(crate) fn flux_rows<const D: usize>(g: &Grid2<D>, place: &str) -> Result<Vec<[f64; 9]>> {
    let (ni, nj) = (g.ni(), g.nj());
    let mut rows = vec![[0.0; 9]; ni * nj];
    // Cell corners a, b, c, d at offsets (0,0), (1,0), (0,1), (1,1).
    const OFF: [(isize, isize); 4] = [(0, 0), (1, 0), (0, 1), (1, 1)];
    let sub = |p: [f64; D], q: [f64; D]| -> [f64; D] { std::array::from_fn(|c| p[c] - q[c]) };
    let avg =
        |p: [f64; D], q: [f64; D]| -> [f64; D] { std::array::from_fn(|c| 0.5 * (p[c] + q[c])) };
    for j in 0..nj - 1 {
        for i in 0..ni - 1 {
            let (xa, xb, xc, xd) = (
                g.point(i, j),
                g.point(i + 1, j),
                g.point(i, j + 1),
                g.point(i + 1, j + 1),
            );
            let (eb, et) = (sub(xb, xa), sub(xd, xc));
            let (el, er) = (sub(xc, xa), sub(xd, xb));
            let (mxi, meta) = (avg(eb, et), avg(el, er));
            // a cell of zero area is the limit of a fold: reported as one, so that callers
            // that try other layouts of a folding grid (a CAD face's reentrant cut, other
            // corners) try them here too
            let bad = || Error::Folded {
                place: place.to_string(),
                count: 1,
                first: format!(
                    "cell ({i}, {j}), which is degenerate (zero area): no harmonic solve"
                ),
            };
            // Half-faces: (edge vector, averaged vector, from corner, to corner, Δ_n coefs,
            // avg_t coefs). Normal to ξ: bottom (a→b), top (c→d); normal to η: left (a→c),
            // right (b→d). Flux ½(p Δ_n s + q avg_t s) leaves `from` and enters `to`.
            const AVG_ETA: [f64; 4] = [-0.5, -0.5, 0.5, 0.5];
            const AVG_XI: [f64; 4] = [-0.5, 0.5, -0.5, 0.5];
            let faces: [HalfFace<D>; 4] = [
                (&eb, &meta, 0, 1, &AVG_ETA),
                (&et, &meta, 2, 3, &AVG_ETA),
                (&el, &mxi, 0, 2, &AVG_XI),
                (&er, &mxi, 1, 3, &AVG_XI),
            ];
            // A half-face across a zero-length cell edge on a block side collapsed to a pole
            // joins two Dirichlet nodes (the pole): its flux enters only rows that are
            // discarded, and the cell is a triangle whose other half-faces are regular.
            let on_side = [j == 0, j + 2 == nj, i == 0, i + 2 == ni];
            for (k, (xn, xt, from, to, avg_t)) in faces.into_iter().enumerate() {
                if on_side[k] && dot(xn, xn) == 0.0 {
                    continue;
                }
                let (p, q) = face_coefs(xn, xt).ok_or_else(bad)?;
                let mut f = [0.0; 4];
                for (m, fm) in f.iter_mut().enumerate() {
                    *fm = 0.5 * q * avg_t[m];
                }
                f[from] -= 0.5 * p;
                f[to] += 0.5 * p;
                // Row of `from` gets −F (outward), row of `to` gets +F.
                for (node, sign) in [(from, -1.0), (to, 1.0)] {
                    let (oi, oj) = OFF[node];
                    let n = g.idx(i + oi as usize, j + oj as usize);
                    let row = &mut rows[n];
                    for (m, fm) in f.iter().enumerate() {
                        let (mi, mj) = OFF[m];
                        row[slot(mi - oi, mj - oj)] += sign * fm;
                    }
                }
            }
        }
    }
    Ok(rows)
}

/// Checks the conditions against the grid and returns the Dirichlet values at every node
/// (0 at unknowns); E3/E4 values win at corners shared by two Dirichlet edges.
fn dirichlet_values<const D: usize>(
    g: &Grid2<D>,
    conds: &[EdgeCondition; 4],
    place: &str,
) -> Result<Vec<f64>> {
    let (ni, nj) = (g.ni(), g.nj());
    if ni < 3 || nj < 3 {
        return Err(Error::input(place, "a block needs at least 3 × 3 nodes"));
    }
    if conds.iter().all(EdgeCondition::is_neumann) {
        return Err(Error::input(
            place,
            "Neumann conditions on all four edges leave s undetermined: give one Dirichlet edge",
        ));
    }
    let mut val = vec![0.0; ni * nj];
    for e in Edge::ALL {
        let EdgeCondition::Dirichlet(v) = &conds[e.index()] else {
            continue;
        };
        let n = if e.runs_along_i() { ni } else { nj };
        let at = || format!("{place}, edge {e}");
        if v.len() != n {
            return Err(Error::input(
                at(),
                format!("{} Dirichlet values for {n} nodes", v.len()),
            ));
        }
        if let Some(k) = v.iter().position(|x| !x.is_finite()) {
            return Err(Error::input(
                at(),
                format!("Dirichlet value {k} is not finite"),
            ));
        }
        for (k, &x) in v.iter().enumerate() {
            let node = match e {
                Edge::E1 => g.idx(0, k),
                Edge::E2 => g.idx(ni - 1, k),
                Edge::E3 => g.idx(k, 0),
                Edge::E4 => g.idx(k, nj - 1),
            };
            val[node] = x;
        }
    }
    Ok(val)
}

/// The relative residual accepted when the iteration stalls short of its 1e-12 target.
const ACCEPT: f64 = 1e-9;

/// Unknowns up to which a harmonic problem whose iteration stalls above `ACCEPT` (1e-9) is solved
/// by sparse LU instead ([`DirectLu`]: exact to round-off, memory ~N log N).
pub const DIRECT_FALLBACK: usize = 250_000;

/// Solves div(A grad s) = 0 on grid `g`, eqs. [50]–[53], with one condition per edge
/// (`conds` in the order E1, E2, E3, E4). Returns s at every node (i fastest).
///
/// # Errors
/// [`Error::Input`] (naming `place` and the edge) for a grid smaller than 3 × 3, Dirichlet
/// data of the wrong length or not finite, or Neumann on all edges; [`Error::Folded`] naming
/// the first degenerate (zero-area) cell; [`Error::Solve`] if the linear solver fails or does
/// not converge.
pub fn solve_harmonic<const D: usize>(
    g: &Grid2<D>,
    conds: &[EdgeCondition; 4],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<Vec<f64>> {
    let rows = flux_rows(g, place)?;
    solve_on(g, &rows, conds, solver, &mut None, place)
}

/// [`solve_harmonic`] with the flux rows of `g` given, and `set_up` the operator `solver` was
/// last set up for by this function (if any): an equal operator is not set up again (the s and
/// t problems of [`harmonic_st`] share theirs where their edges' kinds agree).
fn solve_on<const D: usize>(
    g: &Grid2<D>,
    rows: &[[f64; 9]],
    conds: &[EdgeCondition; 4],
    solver: &mut dyn LinearSolver,
    set_up: &mut Option<Stencil9>,
    place: &str,
) -> Result<Vec<f64>> {
    let mut s = dirichlet_values(g, conds, place)?;
    let (a, rhs, u) = assemble(g, rows, &s, conds);
    let solve_err = |source| Error::Solve {
        place: place.to_string(),
        source,
    };
    if set_up.as_ref() != Some(&a) {
        *set_up = None;
        solver.setup(&a).map_err(solve_err)?;
    }
    let mut x = vec![0.0; rhs.len()];
    let ctl = SolveControl {
        rel_tol: 1e-12,
        max_iter: 200,
    };
    let info = krylov_solve(&a, &*solver, &rhs, &mut x, &ctl).map_err(solve_err)?;
    // The iteration aims at 1e-12 but may stall at round-off on strongly stretched grids
    // (1e-5 wall spacing next to 1-chord far-field cells); 1e-9 is far below what the
    // orthogonality step needs.
    let r = info.residual_history.last().copied().unwrap_or(f64::NAN);
    let accepted = r.partial_cmp(&ACCEPT).is_some_and(|o| o.is_le());
    if !info.converged && !accepted {
        // Where the iteration stalls above that (measured: Bi-CGSTAB ending anywhere between
        // 1.4e-11 and 1.7e-9 on the NLR 7301 flap base, 57 × 17 nodes, for step-1 grids that
        // differ by 7e-14 of the diameter), a block small enough is solved by sparse LU.
        if rhs.len() > DIRECT_FALLBACK {
            return Err(solve_err(SolveError::NotConverged {
                iterations: info.iterations,
                residual: r,
            }));
        }
        let mut lu = DirectLu::new();
        lu.setup(&a).map_err(solve_err)?;
        lu.solve(&rhs, &mut x, &ctl).map_err(solve_err)?;
    }
    for jj in 0..u.ny {
        for ii in 0..u.nx {
            s[g.idx(u.i0 + ii, u.j0 + jj)] = x[ii + u.nx * jj];
        }
    }
    *set_up = Some(a);
    Ok(s)
}

/// `a x = rhs` by Bi-CGSTAB right-preconditioned by `solver` (set up for `a`; one multigrid
/// cycle per application, an exact solve for the direct solver), from `x`.
///
/// Why not `solver.solve`: on the t problem of the O-grid blocks (Neumann at both cuts) the
/// plain cycles contract at only ~0.2, so the multigrid's twelve plain cycles missed 1e-12
/// and its Bi-CGSTAB fallback started again from zero: 24–28 cycles, where Bi-CGSTAB from
/// the start takes 8–12 (NACA0012 O-grid, 4 × 257², `examples/bench_multiblock.rs`).
fn krylov_solve(
    a: &Stencil9,
    solver: &dyn LinearSolver,
    rhs: &[f64],
    x: &mut [f64],
    ctl: &SolveControl,
) -> std::result::Result<crate::solve::SolveInfo, SolveError> {
    let mut failed = None;
    let info = crate::solve::krylov::bicgstab(
        &mut |v, out| a.apply(v, out),
        &mut |v, out| {
            if let Err(e) = solver.precondition(v, out) {
                failed.get_or_insert(e);
                out.copy_from_slice(v);
            }
        },
        rhs,
        x,
        ctl,
    );
    match failed {
        Some(e) => Err(e),
        None => info,
    }
}

/// The stencil over the unknown rectangle and its right-hand side (Dirichlet neighbours moved
/// over).
fn assemble<const D: usize>(
    g: &Grid2<D>,
    rows: &[[f64; 9]],
    val: &[f64],
    conds: &[EdgeCondition; 4],
) -> (Stencil9, Vec<f64>, Unknowns) {
    let u = Unknowns::new(g.ni(), g.nj(), conds);
    let mut a = Stencil9::zeros(u.nx, u.ny);
    let mut rhs = vec![0.0; u.nx * u.ny];
    let coefs = a.coefs_mut();
    for jj in 0..u.ny {
        for ii in 0..u.nx {
            let (i, j) = (u.i0 + ii, u.j0 + jj);
            let p = ii + u.nx * jj;
            let row = &rows[g.idx(i, j)];
            for dj in -1isize..=1 {
                for di in -1isize..=1 {
                    let k = slot(di, dj);
                    let (ni_, nj_) = (i as isize + di, j as isize + dj);
                    if row[k] == 0.0 || ni_ < 0 || nj_ < 0 {
                        continue;
                    }
                    let (ni_, nj_) = (ni_ as usize, nj_ as usize);
                    if u.pos(ni_, nj_).is_some() {
                        coefs[p][k] = row[k];
                    } else {
                        rhs[p] -= row[k] * val[g.idx(ni_, nj_)];
                    }
                }
            }
        }
    }
    (a, rhs, u)
}

/// The edge conditions of the s and t problems of [`harmonic_st`] on grid `g`: s = 0 on E1,
/// 1 on E2, t = 0 on E3, 1 on E4; on the other edges the normalized arclength, or zero
/// Neumann flux where `orthogonal` (E1, E2, E3, E4) flags the edge.
pub(crate) fn st_conditions<const D: usize>(
    g: &Grid2<D>,
    orthogonal: [bool; 4],
) -> [[EdgeCondition; 4]; 2] {
    let (ni, nj) = (g.ni(), g.nj());
    let edges = Edge::ALL.map(|e| g.edge(e));
    let arclength = edge_arclengths(edges.each_ref().map(|e| &e[..]));
    let side = |e: Edge| {
        if orthogonal[e.index()] {
            EdgeCondition::Neumann
        } else {
            EdgeCondition::Dirichlet(arclength[e.index()].clone())
        }
    };
    let s_conds = [
        EdgeCondition::Dirichlet(vec![0.0; nj]),
        EdgeCondition::Dirichlet(vec![1.0; nj]),
        side(Edge::E3),
        side(Edge::E4),
    ];
    let t_conds = [
        side(Edge::E1),
        side(Edge::E2),
        EdgeCondition::Dirichlet(vec![0.0; ni]),
        EdgeCondition::Dirichlet(vec![1.0; ni]),
    ];
    [s_conds, t_conds]
}

/// The s and t problems of Section 2.4 on grid `g` (METHOD.md §3): s = 0 on E1, 1 on E2, and
/// on E3/E4 the normalized arclength [30]–[38], or zero Neumann flux where that edge is
/// orthogonal; t = 0 on E3, 1 on E4, and on E1/E2 arclength or Neumann. An edge collapsed to
/// a point (a pole) takes the opposite edge's arclength ([`edge_arclengths`]). `orthogonal` is
/// indexed E1, E2, E3, E4. With no orthogonal edge this is the harmonic map of Section 1 on a
/// given grid (the Laplace–Beltrami step of the Section 4 pipeline).
///
/// Returns (s, t) at every node (i fastest); their boundary values are the new edge functions
/// of eq. [46].
pub fn harmonic_st<const D: usize>(
    g: &Grid2<D>,
    orthogonal: [bool; 4],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let [s_conds, t_conds] = st_conditions(g, orthogonal);
    // (the flux rows' errors name the s problem, the first solved)
    let rows = flux_rows(g, &format!("{place} (harmonic s)"))?;
    let mut set_up = None;
    let s = solve_on(
        g,
        &rows,
        &s_conds,
        solver,
        &mut set_up,
        &format!("{place} (harmonic s)"),
    )?;
    let t = solve_on(
        g,
        &rows,
        &t_conds,
        solver,
        &mut set_up,
        &format!("{place} (harmonic t)"),
    )?;
    Ok((s, t))
}

#[cfg(test)]
mod tests;
