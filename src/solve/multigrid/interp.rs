//! Matrix-dependent prolongation and restriction (de Zeeuw 1990; Dendy's black box multigrid).
//!
//! # Coarse points
//! Unknowns are numbered interior-only, `i = 0 … nx − 1`. The coarse points are the fine points
//! with odd `i` *and* odd `j`: coarse `(I, J)` sits on fine `(2I + 1, 2J + 1)`, so a grid with
//! `nx` unknowns has `nx / 2` coarse unknowns along x (the Dirichlet boundary, at fine `i = −1`
//! and `i = nx`, is kept by the coarse grid whenever `nx` is odd). When `nx` is even the last
//! fine unknown `i = nx − 1` is itself a coarse point that lies one fine cell (instead of two)
//! from the boundary; the Galerkin coarse operator accounts for the shorter spacing
//! automatically, and no fine point is interpolated from the boundary on that side.
//!
//! # Prolongation weights
//! Each coarse point carries a *star*: the weights with which its value is interpolated to
//! itself (1) and to its eight fine neighbours; entries pointing outside the grid are zero.
//! The weights come from the fine stencil `m`, its adjoint `m*` (`m*_p[k] = m_{p+k}[−k]`), the
//! symmetric part `s = (m + m*)/2` and the antisymmetric part `t = (m − m*)/2`:
//!
//! * a fine point on a coarse row (`i` even, `j` odd) is interpolated along x from its west
//!   and east coarse neighbours. The stencil is collapsed onto the row (Dendy):
//!   `a_W = −(m_SW + m_W + m_NW)`, `a_E = −(…E column)`, `a_C = m_S + m_C + m_N`; the total weight
//!   is `σ = (a_W + a_E)/a_C`, clamped to `[0, 1]` (1 for a zero row sum, less next to a
//!   boundary or for a zeroth-order term). It is split between west and east as in de Zeeuw's
//!   prolongation, `f_W = ½ (1 + (d_W − d_E)/(d_W + d_E) + c/(d_W + d_E + d_N + d_S))`, clamped
//!   to `[0, 1]`, with `d_W = max(|s_SW + s_W + s_NW|, |s_SW|, |s_NW|)` (etc.) and the convective
//!   part `c = Σ t_(E column) − Σ t_(W column)`. Weights: `w_W = σ f_W`, `w_E = σ (1 − f_W)`.
//!   For a symmetric M-matrix this is exactly Dendy's `w_W = a_W / a_C`; for convection it
//!   leans upwind. The collapsed `σ` (instead of de Zeeuw's `½ min(1, |1 − Σm/m_C|)`) keeps
//!   the interpolation right next to the eliminated Dirichlet boundary.
//! * a fine point on a coarse column (`i` odd, `j` even): the same along y.
//! * a fine point in a coarse cell (`i`, `j` even): from the stencil equation with the
//!   neighbours replaced by their interpolants,
//!   `w_K = −(m_(K) + m_(y side) w_K(x-edge) + m_(x side) w_K(y-edge)) / m_C` for each of the four
//!   coarse corners `K`.
//!
//! # Restriction
//! [`crate::solve::multigrid::Restriction::Transpose`] (default): `R = Pᵀ`.
//! [`crate::solve::multigrid::Restriction::Adjoint`] (as MGD9V): the transpose of the prolongation built by the
//! formulas above from the adjoint operator `A*` (the roles of `m` and `m*` swapped), so that
//! the restriction follows the transposed operator for non-symmetric problems. For a
//! symmetric operator both are the same; see [`crate::solve::multigrid::Restriction`] for why `Pᵀ` is the default.

use crate::solve::multigrid::use_par;
use crate::solve::SolveError;
use rayon::prelude::*;

use crate::solve::multigrid::relax::pad;

/// Stencil index of direction (di, dj) ∈ {−1, 0, 1}².
#[inline]
pub(super) const fn k(di: isize, dj: isize) -> usize {
    ((di + 1) + 3 * (dj + 1)) as usize
}

/// The adjoint stencil at (i, j): `m*[k] = m_{(i,j)+d_k}[8 − k]`.
#[inline]
fn adjoint_at(a: &[[f64; 9]], nx: usize, ny: usize, i: usize, j: usize) -> [f64; 9] {
    let p = i + nx * j;
    if i > 0 && j > 0 && i + 1 < nx && j + 1 < ny {
        return [
            a[p - nx - 1][8],
            a[p - nx][7],
            a[p - nx + 1][6],
            a[p - 1][5],
            a[p][4],
            a[p + 1][3],
            a[p + nx - 1][2],
            a[p + nx][1],
            a[p + nx + 1][0],
        ];
    }
    let mut m = [0.0; 9];
    for dj in -1isize..=1 {
        let jj = j as isize + dj;
        if jj < 0 || jj >= ny as isize {
            continue;
        }
        for di in -1isize..=1 {
            let ii = i as isize + di;
            if ii < 0 || ii >= nx as isize {
                continue;
            }
            let kk = k(di, dj);
            m[kk] = a[ii as usize + nx * jj as usize][8 - kk];
        }
    }
    m
}

/// Interpolation weights (minus side, plus side) of a fine point between two coarse points
/// along x (`along_y == false`, sides W/E) or along y (sides S/N), from stencil `m` and its
/// adjoint `ma`: `[prolongation (from m), restriction (from ma)]`. Both share the symmetric
/// part; the antisymmetric part changes sign.
#[inline]
fn edge_weights(m: &[f64; 9], ma: &[f64; 9], along_y: bool) -> [(f64, f64); 2] {
    // index triples: minus side, plus side, centre line, the two perpendicular sides
    const XM: [usize; 3] = [0, 3, 6];
    const XP: [usize; 3] = [2, 5, 8];
    const XC: [usize; 3] = [1, 4, 7];
    const YM: [usize; 3] = [0, 1, 2];
    const YP: [usize; 3] = [6, 7, 8];
    const YC: [usize; 3] = [3, 4, 5];
    let (mi, pl, ce, q1, q2) = if along_y {
        (YM, YP, YC, XM, XP)
    } else {
        (XM, XP, XC, YM, YP)
    };
    let s = |kk: usize| 0.5 * (m[kk] + ma[kk]);
    let t = |kk: usize| 0.5 * (m[kk] - ma[kk]);
    let d = |side: [usize; 3]| {
        let sum = s(side[0]) + s(side[1]) + s(side[2]);
        sum.abs().max(s(side[0]).abs()).max(s(side[2]).abs())
    };
    let (dm, dp) = (d(mi), d(pl));
    let dq = d(q1) + d(q2);
    let c = (t(pl[0]) + t(pl[1]) + t(pl[2])) - (t(mi[0]) + t(mi[1]) + t(mi[2]));
    let weights = |m: &[f64; 9], c: f64| {
        let sum = |side: [usize; 3]| m[side[0]] + m[side[1]] + m[side[2]];
        split_weights(sum(mi), sum(pl), sum(ce), [dm, dp, dq], c)
    };
    [weights(m, c), weights(ma, -c)]
}

/// de Zeeuw's interpolation weights (minus side, plus side) of a fine point between two coarse
/// points, shared by the 2D and the 3D transfers: the collapsed stencil's minus, plus and
/// centre sums `am`, `ap`, `ac` give the total weight σ = −(am + ap)/ac (clamped to [0, 1];
/// 1 for a non-positive centre), the symmetric magnitudes `d = [d₋, d₊, d⊥]` and the
/// antisymmetric part `c` split it, f = ½ (1 + (d₋ − d₊)/(d₋ + d₊) + c/(d₋ + d₊ + d⊥)).
#[inline]
pub(crate) fn split_weights(am: f64, ap: f64, ac: f64, d: [f64; 3], c: f64) -> (f64, f64) {
    let [dm, dp, dq] = d;
    let sigma = -(am + ap) / ac;
    let sigma = if ac > 0.0 && sigma.is_finite() {
        sigma.clamp(0.0, 1.0)
    } else {
        1.0
    };
    let f = if dm + dp > 0.0 {
        0.5 * (1.0 + (dm - dp) / (dm + dp) + c / (dm + dp + dq))
    } else {
        0.5
    };
    let f = if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        0.5
    };
    (sigma * f, sigma * (1.0 - f))
}

/// One coarse row of prolongation and restriction stars (none with `R = Pᵀ`), with its
/// index.
type StarRows<'a> = (usize, (&'a mut [[f64; 9]], Option<&'a mut [[f64; 9]]>));

/// Builds the prolongation stars `p` and restriction stars `r` (one per coarse point) of the
/// fine operator `a` (`nx × ny`). `transpose`: restriction = Pᵀ instead of the adjoint-based
/// one; `r` is then empty and stays so (the restriction stars are the prolongation stars:
/// [`restriction`]).
pub(super) fn build_transfer(
    a: &[[f64; 9]],
    nx: usize,
    ny: usize,
    p: &mut [[f64; 9]],
    r: &mut [[f64; 9]],
    transpose: bool,
) -> Result<(), SolveError> {
    let (ncx, ncy) = (nx / 2, ny / 2);
    assert_eq!(p.len(), ncx * ncy);
    assert_eq!(r.len(), if transpose { 0 } else { ncx * ncy });
    let row = |(jc, (prow, mut rrow)): StarRows| {
        let fj = 2 * jc + 1;
        // weights of the x-edge point west of the current coarse point, carried over from
        // the previous coarse point (for which it was the east point)
        let mut west: Option<[(f64, f64); 2]> = None;
        for ic in 0..ncx {
            let fi = 2 * ic + 1;
            let mut ps = [0.0; 9];
            let mut rs = [0.0; 9];
            ps[4] = 1.0;
            rs[4] = 1.0;
            let edge = |ii: usize, jj: usize, along_y: bool| {
                let ma = adjoint_at(a, nx, ny, ii, jj);
                edge_weights(&a[ii + nx * jj], &ma, along_y)
            };
            // x-edge points W and E: this coarse point is the plus side of W, the minus of E
            let w = west.take().unwrap_or_else(|| edge(fi - 1, fj, false));
            ps[k(-1, 0)] = w[0].1;
            rs[k(-1, 0)] = w[1].1;
            if fi + 1 < nx {
                let e = edge(fi + 1, fj, false);
                ps[k(1, 0)] = e[0].0;
                rs[k(1, 0)] = e[1].0;
                west = Some(e);
            }
            // y-edge points S and N
            let s = edge(fi, fj - 1, true);
            ps[k(0, -1)] = s[0].1;
            rs[k(0, -1)] = s[1].1;
            if fj + 1 < ny {
                let n = edge(fi, fj + 1, true);
                ps[k(0, 1)] = n[0].0;
                rs[k(0, 1)] = n[1].0;
            }
            if transpose {
                rs = ps;
            }
            // cell points
            for (cx, cy) in [(-1isize, -1isize), (1, -1), (-1, 1), (1, 1)] {
                let (ii, jj) = (fi as isize + cx, fj as isize + cy);
                if ii < 0 || jj < 0 || ii >= nx as isize || jj >= ny as isize {
                    continue;
                }
                let (ii, jj) = (ii as usize, jj as usize);
                let m = &a[ii + nx * jj];
                // from the cell point, this coarse point is at (sx, sy) = (−cx, −cy)
                let (sx, sy) = (-cx, -cy);
                let centre = |m: &[f64; 9], st: &[f64; 9]| {
                    -(m[k(sx, sy)] + m[k(0, sy)] * st[k(cx, 0)] + m[k(sx, 0)] * st[k(0, cy)]) / m[4]
                };
                if !(m[4].is_finite() && m[4] != 0.0) {
                    return Err(SolveError::Singular(format!(
                        "multigrid: zero or non-finite diagonal at unknown ({ii}, {jj})"
                    )));
                }
                ps[k(cx, cy)] = centre(m, &ps);
                rs[k(cx, cy)] = if transpose {
                    ps[k(cx, cy)]
                } else {
                    let ma = adjoint_at(a, nx, ny, ii, jj);
                    centre(&ma, &rs)
                };
            }
            prow[ic] = ps;
            if let Some(rrow) = rrow.as_deref_mut() {
                rrow[ic] = rs;
            }
        }
        Ok(())
    };
    if ncx == 0 || ncy == 0 {
        return Ok(());
    }
    match (use_par(nx * ny), transpose) {
        (true, false) => p
            .par_chunks_mut(ncx)
            .zip(r.par_chunks_mut(ncx).map(Some))
            .enumerate()
            .try_for_each(row),
        (true, true) => p
            .par_chunks_mut(ncx)
            .map(|pr| (pr, None))
            .enumerate()
            .try_for_each(row),
        (false, false) => p
            .chunks_mut(ncx)
            .zip(r.chunks_mut(ncx).map(Some))
            .enumerate()
            .try_for_each(row),
        (false, true) => p
            .chunks_mut(ncx)
            .map(|pr| (pr, None))
            .enumerate()
            .try_for_each(row),
    }
}

/// The restriction stars of a level with prolongation stars `p` and restriction stars `r`:
/// `r`, or `p` itself when `r` is empty (`R = Pᵀ`, not stored twice: 18 bytes per fine
/// unknown, #16).
pub(super) fn restriction<'a>(p: &'a [[f64; 9]], r: &'a [[f64; 9]]) -> &'a [[f64; 9]] {
    if r.is_empty() {
        p
    } else {
        r
    }
}

/// `bc = R rf`: restricts the padded fine residual `rf` (`nx × ny`) to the padded coarse
/// right-hand side `bc` with restriction stars `r`.
pub(super) fn restrict(r: &[[f64; 9]], nx: usize, ny: usize, rf: &[f64], bc: &mut [f64]) {
    let (ncx, ncy) = (nx / 2, ny / 2);
    let (pf, pc) = (pad(nx), pad(ncx));
    let bc = &mut bc[pc..pc + ncx * ncy];
    let row = |(jc, (brow, rrow)): (usize, (&mut [f64], &[[f64; 9]]))| {
        let fj = 2 * jc + 1;
        // fine rows fj-1, fj, fj+1 starting one column left of i = 0
        let base = pf + fj * nx;
        let w = &rf[base - nx - 1..base + 2 * nx + 1];
        let (s, c, n) = (&w[..nx + 2], &w[nx..2 * nx + 2], &w[2 * nx..3 * nx + 2]);
        for ic in 0..ncx {
            let st = &rrow[ic];
            let i = 2 * ic + 1; // window index of fine i - 1 is i
            brow[ic] = st[0] * s[i]
                + st[1] * s[i + 1]
                + st[2] * s[i + 2]
                + st[3] * c[i]
                + st[4] * c[i + 1]
                + st[5] * c[i + 2]
                + st[6] * n[i]
                + st[7] * n[i + 1]
                + st[8] * n[i + 2];
        }
    };
    if use_par(nx * ny) {
        bc.par_chunks_mut(ncx)
            .zip(r.par_chunks(ncx))
            .enumerate()
            .for_each(row);
    } else {
        bc.chunks_mut(ncx)
            .zip(r.chunks(ncx))
            .enumerate()
            .for_each(row);
    }
}

/// `xf += P ec`: adds the interpolated padded coarse correction `ec` to the padded fine `xf`.
pub(super) fn prolong_add(p: &[[f64; 9]], nx: usize, ny: usize, ec: &[f64], xf: &mut [f64]) {
    let (ncx, ncy) = (nx / 2, ny / 2);
    let (pf, pc) = (pad(nx), pad(ncx));
    let ec = &ec[pc..pc + ncx * ncy];
    let xf = &mut xf[pf..pf + nx * ny];
    // contribution of coarse row jc (if it exists) to fine row j through star row `dy`
    let row = |(j, out): (usize, &mut [f64])| {
        let add_from = |out: &mut [f64], jc: usize, dy: isize| {
            let e = &ec[jc * ncx..(jc + 1) * ncx];
            let st = &p[jc * ncx..(jc + 1) * ncx];
            for ic in 0..ncx {
                let (w, v) = (&st[ic], e[ic]);
                let fi = 2 * ic + 1;
                out[fi - 1] += w[k(-1, dy)] * v;
                out[fi] += w[k(0, dy)] * v;
                if fi + 1 < nx {
                    out[fi + 1] += w[k(1, dy)] * v;
                }
            }
        };
        if j % 2 == 1 {
            add_from(out, (j - 1) / 2, 0);
        } else {
            if j >= 2 {
                add_from(out, j / 2 - 1, 1);
            }
            if j / 2 < ncy {
                add_from(out, j / 2, -1);
            }
        }
    };
    if ncx == 0 || ncy == 0 {
        return;
    }
    if use_par(nx * ny) {
        xf.par_chunks_mut(nx).enumerate().for_each(row);
    } else {
        xf.chunks_mut(nx).enumerate().for_each(row);
    }
}
