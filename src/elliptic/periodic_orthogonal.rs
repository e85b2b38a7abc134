//! Orthogonality (Section 2.4, METHOD.md §3) at the ring sides E3 and E4 of a periodic block
//! (an O-grid whose cut E1 = E2 floats, [`crate::elliptic::periodic`]): the paper's three steps
//! with the seam wrapped.
//!
//! 1. Grid the ring with the periodic straight-line control functions
//!    ([`crate::elliptic::periodic::grid_block`]).
//! 2. On that grid solve the harmonic problem [50]–[53] for the angle-like s: s jumps by 1
//!    across the seam (node i = N is node i = 0 with s + 1), zero normal flux [46] at the
//!    orthogonal sides, the normalized arclength at the others. Its values on E3 and E4 are the
//!    new edge functions. There is no t problem: t = t_cut(η), the cut's distribution, on
//!    every ξ-line, as in [`crate::algebraic::periodic`].
//! 3. Blend s in t with zero slope at the orthogonal sides ([`periodic_blend`], eqs.
//!    [47]–[49] with t independent of s, so each node is explicit), take the control
//!    functions [19] of the blend ([`periodic_control`]) and solve [24] again from the grid
//!    of step 1.
//!
//! With both sides orthogonal s is fixed up to a constant: the wall's seam node is held at 0.
//! The cut carries no condition of its own (it is not a boundary), so `orthogonal` on E1/E2 is
//! refused.

use crate::algebraic::blend::Blend;
use crate::algebraic::periodic::{periodic_blend, periodic_control, periodic_param};
use crate::algebraic::transform::ParamGrid;
use crate::algebraic::ControlKind;
use crate::elliptic::harmonic::flux_rows;
use crate::elliptic::orthogonal::{along_edge, monotone};
use crate::elliptic::periodic;
use crate::elliptic::picard::{BlockResult, PicardParams};
use crate::grid::arclength::normalized_arclength;
use crate::grid::boundary::Boundary2;
use crate::grid::{Edge, Grid2};
use crate::solve::periodic9::{DirectLuPeriodic, Periodic9};
use crate::solve::{LinearSolver, SolveControl};
use crate::{Error, Result};

/// Grids one periodic block with orthogonality at the flagged ring sides (`orthogonal`
/// indexed E1, E2, E3, E4; the cut's flags must be false): step 1 from `start` (the periodic
/// start if None), then steps 2–3 (module docs) if E3 or E4 is flagged. Returns the grid, the
/// Picard history of step 3 with step 1's as its `first`, and the (s, t) whose control
/// functions gave it (the wall passes remap these).
///
/// # Errors
/// Orthogonality on the cut or with Laplace control functions, a harmonic edge function that
/// does not increase round the ring, and the errors of [`periodic::grid_block`] and
/// [`periodic::solve`].
pub fn grid_block<const D: usize>(
    b: &Boundary2<D>,
    start: Option<Grid2<D>>,
    orthogonal: [bool; 4],
    kind: ControlKind,
    params: &PicardParams,
    place: &str,
) -> Result<(BlockResult<D>, ParamGrid)> {
    if let Some(e) = [Edge::E1, Edge::E2]
        .into_iter()
        .find(|e| orthogonal[e.index()])
    {
        return Err(Error::input(
            format!("{place}, edge {e}"),
            "orthogonality at a periodic block's floating cut: the cut is not a boundary (the \
             grid runs across it smoothly); `orthogonal` applies to the ring's sides E3 and E4",
        ));
    }
    let sides = [orthogonal[2], orthogonal[3]];
    if sides.contains(&true) && kind != ControlKind::Algebraic {
        return Err(Error::input(
            place,
            "orthogonal edges need the algebraic control functions (control = \"algebraic\")",
        ));
    }
    let step1 = periodic::grid_block(b, start, [false; 4], kind, params, place)?;
    if !sides.contains(&true) {
        return Ok((step1, periodic_param(b)));
    }
    let s = harmonic_s(&step1.grid, sides, place)?;
    let (s3, s4) = ring_edge_functions(&step1.grid, &s, place)?;
    let bl = Blend::from_edges(sides[0], sides[1]);
    let pg = periodic_blend(&s3, &s4, &normalized_arclength(b.edge(Edge::E1)), bl);
    let mut grid = step1.grid;
    let mut picard = periodic::solve(&mut grid, &periodic_control(&pg), params, place)?;
    picard.first = Some(Box::new(step1.picard));
    Ok((BlockResult { grid, picard }, pg))
}

/// Step 2: the harmonic s of the ring grid `g` (column N = column 0), s + 1 across the seam,
/// zero flux at the sides flagged in `neumann` (E3, E4), normalized arclength at the others.
/// Returns s at every node (column N holds column 0's s + 1).
///
/// # Errors
/// A degenerate cell (zero area), a failed LU.
pub fn harmonic_s<const D: usize>(
    g: &Grid2<D>,
    neumann: [bool; 2],
    place: &str,
) -> Result<Vec<f64>> {
    let (ni, nj) = (g.ni(), g.nj());
    let nc = ni - 1;
    let rows = flux_rows(g, place)?;
    let arc = [
        normalized_arclength(&g.edge(Edge::E3)),
        normalized_arclength(&g.edge(Edge::E4)),
    ];
    // the unknown rows j0..=j1: a Neumann side's row is unknown too
    let j0 = usize::from(!neumann[0]);
    let j1 = if neumann[1] { nj - 1 } else { nj - 2 };
    let ny = j1 + 1 - j0;
    let mut a = Periodic9::zeros(nc, ny);
    let mut rhs = vec![0.0; nc * ny];
    for jj in 0..ny {
        let j = j0 + jj;
        for i in 0..nc {
            let p = i + nc * jj;
            // column 0's control volume is the halves of the seam's two copies, 0 and N
            let copies: &[usize] = if i == 0 { &[0, nc] } else { &[i] };
            for &gi in copies {
                let row = &rows[g.idx(gi, j)];
                for (k, &v) in row.iter().enumerate() {
                    let (di, dj) = (k % 3, k / 3);
                    let (gc, gj) = ((gi + di).wrapping_sub(1), (j + dj).wrapping_sub(1));
                    if v == 0.0 || gc > nc || gj >= nj {
                        continue;
                    }
                    // column N is column 0 one period on
                    let jump = if gc == nc { 1.0 } else { 0.0 };
                    if (j0..=j1).contains(&gj) {
                        a.coefs_mut()[p][k] += v;
                        rhs[p] -= v * jump;
                    } else {
                        let side = usize::from(gj != 0);
                        rhs[p] -= v * arc[side][gc];
                    }
                }
            }
        }
    }
    if neumann == [true, true] {
        // s up to a constant: the wall's seam node holds s = 0
        a.coefs_mut()[0] = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        rhs[0] = 0.0;
    }
    let mut lu = DirectLuPeriodic::new();
    let solve_err = |source| Error::Solve {
        place: format!("{place} (harmonic s)"),
        source,
    };
    lu.setup(&a).map_err(solve_err)?;
    let mut x = vec![0.0; nc * ny];
    let ctl = SolveControl {
        rel_tol: 1e-12,
        max_iter: 1,
    };
    lu.solve(&rhs, &mut x, &ctl).map_err(solve_err)?;
    let mut s = vec![0.0; ni * nj];
    for j in 0..nj {
        for i in 0..ni {
            let c = if i == nc { 0 } else { i };
            let v = if (j0..=j1).contains(&j) {
                x[c + nc * (j - j0)]
            } else {
                arc[usize::from(j != 0)][c]
            };
            s[g.idx(i, j)] = v + if i == nc { 1.0 } else { 0.0 };
        }
    }
    Ok(s)
}

/// The new edge functions of E3 and E4 [46]: s along each side, 0..=N (last = first + 1),
/// made strictly increasing where round-off disorders it ([`monotone`]).
///
/// # Errors
/// [`Error::Input`] naming the side where s falls back beyond round-off.
fn ring_edge_functions<const D: usize>(
    g: &Grid2<D>,
    s: &[f64],
    place: &str,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let side = |e: Edge| -> Result<Vec<f64>> {
        let (mut v, arc) = along_edge(g, e, s);
        monotone(&mut v, &arc).map_err(|k| {
            Error::input(
                format!("{place}, edge {e}"),
                format!(
                    "the harmonic solution of the orthogonality step does not increase round \
                     the ring (nodes {k}, {}): refine the grid near this edge",
                    k + 1
                ),
            )
        })?;
        Ok(v)
    };
    Ok((side(Edge::E3)?, side(Edge::E4)?))
}

#[cfg(test)]
mod tests;
