//! Smoothers and the residual kernel: zebra line Gauss–Seidel along x and y lines.
//!
//! A zebra half sweep relaxes every second line (one colour) exactly: the line's tridiagonal
//! system (its coefficients along the line) is solved by the Thomas algorithm with the other
//! colour's values frozen. Lines of one colour are independent, so they run in parallel.
//! The Thomas pivots are factored once per operator: for x-lines the inverse pivots and the
//! modified upper coefficients (`xline::factor_x`, the sweep reads the stencil itself), for y-lines
//! a *line operator* (the stencil scaled by the inverse pivots, [`factor_y`]); a sweep only
//! eliminates the right-hand side. Both are stored in f32 (computed in f64 and rounded; the
//! sweeps compute in f64): they solve the lines to ~1e-7 of the equations' terms, which the
//! plain cycles' correction form (`Multigrid::solve_cycles`, [`correct`]) keeps out of the
//! solution. The y-line operator is stored by column blocks ([`YLineOp`]): within a block of
//! [`YLineOp::W`] columns, one colour's records of all rows are contiguous, so that a half
//! sweep streams through memory while the block's columns stay in cache between the forward
//! elimination and the back substitution. With [`crate::solve::multigrid::MgParams`]`::lean_y_lines`
//! the y-lines keep no line operator and read the stencil itself (`yline`): 28 bytes per
//! unknown less, but slower (see there).
//!
//! All vectors here are *padded*: point `p = i + nx j` lives at `v[pad + p]` with
//! `pad = nx + 1` zeros before row 0 and after row `ny − 1` (see [`pad`]), so that the nine
//! neighbours of every grid point are in range and the first and last rows need no branches.
//! The operator's couplings that point outside the grid are zero, so the values read there
//! (padding, or the wrapped-around end of the neighbouring row) never matter.

use crate::solve::krylov::in_order;
use crate::solve::multigrid::{use_par, SharedPtr};
use crate::solve::SolveError;
use rayon::prelude::*;

/// Zeros before and after the unknowns of an `nx`-wide grid in a padded vector.
#[inline]
pub(super) fn pad(nx: usize) -> usize {
    nx + 1
}

/// Length of a padded vector for `nx × ny` unknowns.
#[inline]
pub(super) fn padded_len(nx: usize, ny: usize) -> usize {
    nx * ny + 2 * pad(nx)
}

pub(super) fn pivot_error(i: usize, j: usize, piv: f64, dir: char) -> SolveError {
    SolveError::Singular(format!(
        "multigrid: {dir}-line pivot {piv:e} at unknown ({i}, {j}) (zero or non-finite diagonal?)"
    ))
}

/// Rows of stencils.
pub(super) type Stencils = [[f64; 9]];

/// Storage of the line smoothers' factors (computed in f64, rounded to this type).
pub(super) type Fac = f32;

/// The y-line operator: per unknown, the stencil scaled by the inverse Thomas pivot of its
/// column's tridiagonal system `(a_S, a_C, a_N)`, `op = [SW, S, SE, W]·inv, inv, [E, NW, NE]·inv`,
/// and the modified upper coefficient `cp = a_N·inv` (kept apart: the back substitution reads
/// only `cp`), all rounded to f32 (36 bytes per unknown, against 72 in f64).
///
/// Layout: column blocks `[i0, i1)` of `W` columns (the last may be narrower) one after the
/// other; inside a block, colour 0 (even `i`) for all rows, then colour 1; inside a colour, row
/// by row. A block occupies `[i0 ny, i1 ny)`.
#[derive(Clone, Debug, Default)]
pub(super) struct YLineOp {
    pub op: Vec<[Fac; 8]>,
    pub cp: Vec<Fac>,
}

impl YLineOp {
    /// Columns per block.
    pub(super) const W: usize = 32;

    pub(super) fn resize(&mut self, n: usize) {
        self.op.resize(n, [0.0; 8]);
        self.cp.resize(n, 0.0);
    }

    /// `n` zero rows, the buffers' capacity kept ([`super::setup::Hierarchy::recycled`]).
    pub(super) fn zeroed(&mut self, n: usize) {
        crate::solve::zeroed(&mut self.op, n);
        crate::solve::zeroed(&mut self.cp, n);
    }

    pub(super) fn is_empty(&self) -> bool {
        self.op.is_empty()
    }

    /// Columns of `colour` in the block `[i0, i1)` (`i0` even).
    #[inline]
    fn count(i0: usize, i1: usize, colour: usize) -> usize {
        (i1 - i0 + 1 - colour) / 2
    }

    /// Offset, inside its block, of the records of `colour`.
    #[inline]
    fn colour_base(i0: usize, i1: usize, colour: usize, ny: usize) -> usize {
        if colour == 0 {
            0
        } else {
            Self::count(i0, i1, 0) * ny
        }
    }
}

/// Runs `f(i0, i1, op_block, cp_block)` over the column blocks of a y-line operator, in
/// parallel when large, and sums the results.
fn for_blocks<T: std::iter::Sum<T> + Send>(
    nx: usize,
    ny: usize,
    op: &[[Fac; 8]],
    cp: &[Fac],
    f: impl Fn(usize, usize, &[[Fac; 8]], &[Fac]) -> T + Sync + Send,
) -> T {
    let chunk = YLineOp::W * ny;
    let g = |(b, (op, cp)): (usize, (&[[Fac; 8]], &[Fac]))| {
        let i0 = b * YLineOp::W;
        f(i0, (i0 + YLineOp::W).min(nx), op, cp)
    };
    if use_par(nx * ny) {
        in_order(
            op.par_chunks(chunk)
                .zip(cp.par_chunks(chunk))
                .enumerate()
                .map(g),
        )
    } else {
        op.chunks(chunk)
            .zip(cp.chunks(chunk))
            .enumerate()
            .map(g)
            .sum()
    }
}

/// Builds the y-line operator of `a`.
pub(super) fn factor_y(
    a: &[[f64; 9]],
    nx: usize,
    ny: usize,
    yop: &mut YLineOp,
) -> Result<(), SolveError> {
    yop.resize(nx * ny);
    let chunk = YLineOp::W * ny;
    let work = |(b, (op, cp)): (usize, (&mut [[Fac; 8]], &mut [Fac]))| {
        let i0 = b * YLineOp::W;
        let i1 = (i0 + YLineOp::W).min(nx);
        for colour in 0..2 {
            let cnt = YLineOp::count(i0, i1, colour);
            let base = YLineOp::colour_base(i0, i1, colour, ny);
            for j in 0..ny {
                for t in 0..cnt {
                    let i = i0 + colour + 2 * t;
                    let m = &a[i + nx * j];
                    let q = base + j * cnt + t;
                    // the pivot from the stored (rounded) factor below: the Thomas
                    // factorization of the tridiagonal system the sweep solves
                    let cprev = if j > 0 { f64::from(cp[q - cnt]) } else { 0.0 };
                    let piv = m[4] - m[1] * cprev;
                    if !(piv.is_finite() && piv != 0.0) {
                        return Err(pivot_error(i, j, piv, 'y'));
                    }
                    let v = 1.0 / piv;
                    let c = m[7] * v;
                    if !(v as Fac).is_finite() || !(c as Fac).is_finite() {
                        return Err(pivot_error(i, j, piv, 'y'));
                    }
                    op[q] = [
                        (m[0] * v) as Fac,
                        (m[1] * v) as Fac,
                        (m[2] * v) as Fac,
                        (m[3] * v) as Fac,
                        v as Fac,
                        (m[5] * v) as Fac,
                        (m[6] * v) as Fac,
                        (m[8] * v) as Fac,
                    ];
                    cp[q] = c as Fac;
                }
            }
        }
        Ok(())
    };
    if use_par(nx * ny) {
        yop.op
            .par_chunks_mut(chunk)
            .zip(yop.cp.par_chunks_mut(chunk))
            .enumerate()
            .try_for_each(work)
    } else {
        yop.op
            .chunks_mut(chunk)
            .zip(yop.cp.chunks_mut(chunk))
            .enumerate()
            .try_for_each(work)
    }
}

/// Rows ahead whose strip of `x` and `b` a y-line sweep (and the residual on columns)
/// prefetches: the strip of a column block (W columns, 256 bytes) lies on a new 4 KB page in
/// every row, where the hardware prefetcher does not follow. Measured at 2049² (kernel
/// timings, 3 runs each): a y-line sweep 7.0–7.5 ns per unknown against 8.3–9.1 without;
/// 2 to 16 rows ahead all alike.
const PREFETCH_ROWS: usize = 3;

/// Asks for the cache lines of `len` values from `p` (a hint; no effect off x86-64).
#[inline(always)]
fn prefetch_span(p: *const f64, len: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let mut k = 0;
        while k < len {
            // SAFETY: prefetch is a hint and never faults; the address is only computed
            unsafe { _mm_prefetch(p.wrapping_add(k) as *const i8, _MM_HINT_T0) };
            k += 8;
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (p, len);
}

/// Zebra y-line half sweep over the columns `i ≡ colour (mod 2)` with the y-line operator.
pub(super) fn yzebra(yop: &YLineOp, nx: usize, ny: usize, x: &mut [f64], b: &[f64], colour: usize) {
    let pd = pad(nx);
    assert_eq!(x.len(), padded_len(nx, ny));
    assert_eq!(b.len(), padded_len(nx, ny));
    assert_eq!(yop.op.len(), nx * ny);
    assert_eq!(yop.cp.len(), nx * ny);
    let xp = SharedPtr(unsafe { x.as_mut_ptr().add(pd) });
    let b = &b[pd..pd + nx * ny];
    for_blocks(nx, ny, &yop.op, &yop.cp, |i0, i1, op, cp| {
        let first = i0 + colour;
        if first >= i1 {
            return 0.0;
        }
        let cnt = YLineOp::count(i0, i1, colour);
        let base = YLineOp::colour_base(i0, i1, colour, ny);
        let (op, cp) = (&op[base..base + cnt * ny], &cp[base..base + cnt * ny]);
        let x = xp.get();
        // SAFETY: a block writes only the columns of `colour` in [i0, i1) and reads the
        // other colour; reads across the left/right grid edge are skipped (they would wrap
        // onto a column of the same colour); rows -1 and ny are padding.
        unsafe {
            for (j, ops) in op.chunks_exact(cnt).enumerate() {
                let row = j * nx;
                if j + PREFETCH_ROWS < ny {
                    let ahead = row + PREFETCH_ROWS * nx + first;
                    prefetch_span(x.add(ahead + nx), 2 * cnt);
                    prefetch_span(b.as_ptr().add(ahead), 2 * cnt);
                }
                for (t, m) in ops.iter().enumerate() {
                    let m = m.map(f64::from);
                    let i = first + 2 * t;
                    let p = row + i;
                    let xq = x.add(p);
                    let mut r = m[4] * *b.get_unchecked(p) - m[1] * *xq.sub(nx);
                    if i > 0 {
                        r -= m[0] * *xq.sub(nx + 1) + m[3] * *xq.sub(1) + m[6] * *xq.add(nx - 1);
                    }
                    if i + 1 < nx {
                        r -= m[2] * *xq.sub(nx - 1) + m[5] * *xq.add(1) + m[7] * *xq.add(nx + 1);
                    }
                    *xq = r;
                }
            }
            for j in (0..ny.saturating_sub(1)).rev() {
                let row = j * nx;
                let cps = &cp[j * cnt..(j + 1) * cnt];
                for (t, &c) in cps.iter().enumerate() {
                    let xq = x.add(row + first + 2 * t);
                    *xq -= f64::from(c) * *xq.add(nx);
                }
            }
        }
        0.0
    });
}

/// One row of `out = b − A x` (or `A x` when `b` is `None`) at the columns
/// `i ≡ colour (mod 2)` (every column if `colour` is 2; 0 at the others); returns Σ out².
/// `base` is the padded index of the row's first unknown.
#[inline]
fn row_residual(
    a: &[[f64; 9]],
    x: &[f64],
    base: usize,
    nx: usize,
    b: Option<&[f64]>,
    out: &mut [f64],
    colour: usize,
) -> f64 {
    // window of x covering the row and its neighbours: x[base - nx - 1 .. base + 2 nx + 1]
    let w = &x[base - nx - 1..base + 2 * nx + 1];
    let (s, c, n) = (&w[..nx + 2], &w[nx..2 * nx + 2], &w[2 * nx..3 * nx + 2]);
    let a = &a[..nx];
    let out = &mut out[..nx];
    let mut ss = 0.0;
    let mut cell = |i: usize| {
        let m = &a[i];
        let v = m[0] * s[i]
            + m[1] * s[i + 1]
            + m[2] * s[i + 2]
            + m[3] * c[i]
            + m[4] * c[i + 1]
            + m[5] * c[i + 2]
            + m[6] * n[i]
            + m[7] * n[i + 1]
            + m[8] * n[i + 2];
        let r = match b {
            Some(b) => b[i] - v,
            None => v,
        };
        out[i] = r;
        ss += r * r;
    };
    if colour < 2 {
        for i in (colour..nx).step_by(2) {
            cell(i);
        }
        for i in (1 - colour..nx).step_by(2) {
            out[i] = 0.0;
        }
    } else {
        for i in 0..nx {
            cell(i);
        }
    }
    ss
}

/// Lines on which the residual is known to vanish: the lines relaxed by the last zebra half
/// sweep (their equations hold exactly).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Zeroed {
    /// Nothing known.
    None,
    /// Rows `j ≡ colour (mod 2)`.
    Rows(usize),
    /// Columns `i ≡ colour (mod 2)`.
    Cols(usize),
}

/// Runs `row(j, out_row) -> Σ out_row²` over the rows of the padded output `r` (in parallel
/// when large) and returns the sum.
fn for_rows(
    nx: usize,
    ny: usize,
    r: &mut [f64],
    row: impl Fn(usize, &mut [f64]) -> f64 + Sync + Send,
) -> f64 {
    let pd = pad(nx);
    let n = nx * ny;
    assert_eq!(r.len(), padded_len(nx, ny));
    let rr = &mut r[pd..pd + n];
    let rows_per_task = (8192 / nx).max(1);
    let work = |(t, out): (usize, &mut [f64])| {
        let j0 = t * rows_per_task;
        out.chunks_mut(nx)
            .enumerate()
            .map(|(jj, out)| row(j0 + jj, out))
            .sum::<f64>()
    };
    let chunk = rows_per_task * nx;
    if use_par(n) {
        in_order(rr.par_chunks_mut(chunk).enumerate().map(work))
    } else {
        rr.chunks_mut(chunk).enumerate().map(work).sum()
    }
}

/// `r = b − A x` on padded vectors; returns ‖r‖₂². `zeroed` names lines whose residual is
/// known to vanish: they are set to 0 without being computed (rows from `a`, columns from the
/// y-line operator `yop` if there is one, so that only half of an operator is read, else from
/// `a`).
#[allow(clippy::too_many_arguments)]
pub(super) fn residual(
    a: &[[f64; 9]],
    yop: Option<&YLineOp>,
    nx: usize,
    ny: usize,
    x: &[f64],
    b: &[f64],
    r: &mut [f64],
    zeroed: Zeroed,
) -> f64 {
    let pd = pad(nx);
    assert_eq!(x.len(), padded_len(nx, ny));
    assert_eq!(b.len(), padded_len(nx, ny));
    assert_eq!(a.len(), nx * ny);
    match (zeroed, yop) {
        (Zeroed::Cols(zc), Some(yop)) if yop.op.len() == nx * ny => {
            residual_cols(yop, nx, ny, x, b, r, 1 - zc)
        }
        _ => {
            // the columns computed: all, or those of the colour not relaxed last
            let colour = match zeroed {
                Zeroed::Cols(zc) => 1 - zc,
                _ => 2,
            };
            for_rows(nx, ny, r, |j, out| {
                if zeroed == Zeroed::Rows(j % 2) {
                    out.fill(0.0);
                    0.0
                } else {
                    let bb = &b[pd + j * nx..pd + (j + 1) * nx];
                    let a = &a[j * nx..(j + 1) * nx];
                    row_residual(a, x, pd + j * nx, nx, Some(bb), out, colour)
                }
            })
        }
    }
}

/// `r = b − A x` at the columns `i ≡ colour (mod 2)`, 0 at the others, from the y-line
/// operator: with `ŝ = inv · m`, `inv · a_C = 1 + ŝ_S cp_(j−1)` and `inv · a_N = cp`.
fn residual_cols(
    yop: &YLineOp,
    nx: usize,
    ny: usize,
    x: &[f64],
    b: &[f64],
    r: &mut [f64],
    colour: usize,
) -> f64 {
    let pd = pad(nx);
    assert_eq!(r.len(), padded_len(nx, ny));
    let rp = SharedPtr(unsafe { r.as_mut_ptr().add(pd) });
    let b = &b[pd..pd + nx * ny];
    for_blocks(nx, ny, &yop.op, &yop.cp, |i0, i1, op, cp| {
        let rp = rp.get();
        let first = i0 + colour;
        let other = i0 + 1 - colour;
        let cnt = YLineOp::count(i0, i1, colour);
        let base = YLineOp::colour_base(i0, i1, colour, ny);
        let (op, cp) = (&op[base..base + cnt * ny], &cp[base..base + cnt * ny]);
        let mut ss = 0.0;
        // SAFETY: a block writes only the entries of its own columns; x is padded, so the
        // nine neighbours of every unknown are in range.
        unsafe {
            for j in 0..ny {
                let row = j * nx;
                if j + PREFETCH_ROWS < ny {
                    let ahead = row + PREFETCH_ROWS * nx + i0;
                    prefetch_span(x.as_ptr().add(pd + ahead + nx), i1 - i0);
                    prefetch_span(b.as_ptr().add(ahead), i1 - i0);
                }
                let mut i = other;
                while i < i1 {
                    *rp.add(row + i) = 0.0;
                    i += 2;
                }
                if cnt == 0 {
                    continue;
                }
                let ops = &op[j * cnt..(j + 1) * cnt];
                let cps = &cp[j * cnt..(j + 1) * cnt];
                let below = if j > 0 {
                    &cp[(j - 1) * cnt..j * cnt]
                } else {
                    cps
                };
                for (t, m) in ops.iter().enumerate() {
                    let m = m.map(f64::from);
                    let p = row + first + 2 * t;
                    let cpb = if j > 0 { f64::from(below[t]) } else { 0.0 };
                    let xq = x.as_ptr().add(pd + p);
                    let v = m[4] * *b.get_unchecked(p)
                        - (m[0] * *xq.sub(nx + 1) + m[1] * *xq.sub(nx) + m[2] * *xq.sub(nx - 1))
                        - (m[3] * *xq.sub(1) + (1.0 + m[1] * cpb) * *xq + m[5] * *xq.add(1))
                        - (m[6] * *xq.add(nx - 1)
                            + f64::from(cps[t]) * *xq.add(nx)
                            + m[7] * *xq.add(nx + 1));
                    let res = v / m[4];
                    *rp.add(p) = res;
                    ss += res * res;
                }
            }
        }
        ss
    })
}

/// After a cycle for the correction `e` (padded) of the residual equation `A e = r`:
/// `r ← r − A e` (padded, from the f64 operator `a`) and `x ← x + e` (`x` unpadded, the
/// caller's solution); returns ‖r‖₂². The residual so kept is the true `b − A x` up to the
/// round-off of the updates, whatever the smoothers' precision.
pub(super) fn correct(
    a: &[[f64; 9]],
    nx: usize,
    ny: usize,
    e: &[f64],
    r: &mut [f64],
    x: &mut [f64],
) -> f64 {
    let pd = pad(nx);
    let n = nx * ny;
    assert_eq!(e.len(), padded_len(nx, ny));
    assert_eq!(r.len(), padded_len(nx, ny));
    assert_eq!(a.len(), n);
    assert_eq!(x.len(), n);
    let rows_per_task = (8192 / nx).max(1);
    let chunk = rows_per_task * nx;
    let work = |(t, (rr, xx)): (usize, (&mut [f64], &mut [f64]))| {
        let j0 = t * rows_per_task;
        let mut ss = 0.0;
        for (jj, (rr, xx)) in rr.chunks_mut(nx).zip(xx.chunks_mut(nx)).enumerate() {
            let j = j0 + jj;
            let base = pd + j * nx;
            let w = &e[base - nx - 1..base + 2 * nx + 1];
            let (s, c, nn) = (&w[..nx + 2], &w[nx..2 * nx + 2], &w[2 * nx..3 * nx + 2]);
            let a = &a[j * nx..(j + 1) * nx];
            for i in 0..nx {
                let m = &a[i];
                let v = m[0] * s[i]
                    + m[1] * s[i + 1]
                    + m[2] * s[i + 2]
                    + m[3] * c[i]
                    + m[4] * c[i + 1]
                    + m[5] * c[i + 2]
                    + m[6] * nn[i]
                    + m[7] * nn[i + 1]
                    + m[8] * nn[i + 2];
                let ri = rr[i] - v;
                rr[i] = ri;
                ss += ri * ri;
                xx[i] += c[i + 1];
            }
        }
        ss
    };
    let rr = &mut r[pd..pd + n];
    if use_par(n) {
        in_order(
            rr.par_chunks_mut(chunk)
                .zip(x.par_chunks_mut(chunk))
                .enumerate()
                .map(work),
        )
    } else {
        rr.chunks_mut(chunk)
            .zip(x.chunks_mut(chunk))
            .enumerate()
            .map(work)
            .sum()
    }
}

/// `y = A x` on padded vectors; returns ‖y‖₂².
pub(super) fn apply(a: &[[f64; 9]], nx: usize, ny: usize, x: &[f64], y: &mut [f64]) -> f64 {
    let pd = pad(nx);
    assert_eq!(x.len(), padded_len(nx, ny));
    assert_eq!(a.len(), nx * ny);
    for_rows(nx, ny, y, |j, out| {
        row_residual(&a[j * nx..(j + 1) * nx], x, pd + j * nx, nx, None, out, 2)
    })
}
