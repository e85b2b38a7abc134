//! The memory-lean y-lines ([`crate::solve::multigrid::MgParams`]`::lean_y_lines`): the
//! Thomas factors of every column's tridiagonal system ([`factor_y`]) and the zebra sweep
//! ([`ysweep`]) that solves the lines of both colours, one colour after the other. Vectors are
//! padded as in `relax`.
//!
//! The sweep reads the couplings from the operator itself, like the x-lines: the factors are
//! only the modified upper coefficients `cp = a_N / piv` (8 bytes per unknown, against 36 for
//! `relax`'s line operator, a scaled copy of the stencil in f32 stored colour by colour), and the
//! pivot `piv = a_C − a_S · cp_(j−1)` is recomputed from them, bit for bit the one of the
//! factorization. A y-line reads one stencil in each row, whose cache lines hold the stencils
//! of both colours; so that the operator comes from memory once per sweep and not once per
//! colour, the columns are taken in blocks of [`W`] and the second colour follows the first
//! block by block, while the block is still in cache: the lines of the second colour whose
//! neighbours of the first colour are final are solved right after each block.
//!
//! Measured (one thread, 2049², both colours): 13–16 ns per unknown against 5.5–6.5 for the
//! line operator's sweep, whatever the block width (8 to 64 columns), the prefetch distance or
//! huge pages: the operator's rows are read in strips of W stencils, 147 KB apart, where the
//! line operator is read as one stream. In cache (257²) 4.7–5.4 against 3.1 ns.

use super::relax::{pad, padded_len, pivot_error};
use crate::solve::multigrid::{use_par, SharedPtr};
use crate::solve::SolveError;
use rayon::prelude::*;

/// Columns per block: a block's stencils (W · ny · 72 bytes, 1.2 MB at ny = 1025) stay in the
/// cache between its two colours.
pub(super) const W: usize = 16;

/// Builds the y-line factors of `a` (natural order, `cp[i + nx j]`): `cp = a_N / piv` with
/// `piv = a_C − a_S cp_(j−1)` the Thomas pivot of column `i`'s system `(a_S, a_C, a_N)`.
pub(super) fn factor_y(
    a: &[[f64; 9]],
    nx: usize,
    ny: usize,
    cp: &mut Vec<f64>,
) -> Result<(), SolveError> {
    cp.resize(nx * ny, 0.0);
    let out = SharedPtr(cp.as_mut_ptr());
    let work = |blk: usize| {
        let (i0, i1) = (blk * W, ((blk + 1) * W).min(nx));
        let out = out.get();
        for j in 0..ny {
            for i in i0..i1 {
                let p = i + nx * j;
                let m = &a[p];
                // SAFETY: a block writes only its own columns, and reads the row below of them
                let cprev = if j > 0 {
                    unsafe { *out.add(p - nx) }
                } else {
                    0.0
                };
                let piv = m[4] - m[1] * cprev;
                if !(piv.is_finite() && piv != 0.0) {
                    return Err(pivot_error(i, j, piv, 'y'));
                }
                unsafe { *out.add(p) = m[7] * (1.0 / piv) };
            }
        }
        Ok(())
    };
    let blocks = nx.div_ceil(W);
    if use_par(nx * ny) {
        (0..blocks).into_par_iter().try_for_each(work)
    } else {
        (0..blocks).try_for_each(work)
    }
}

/// Rows ahead whose stencils, `x`, `b` and factors a y-line sweep prefetches: the strip of a
/// column block lies on new 4 KB pages in every row, where the hardware prefetcher does not
/// follow.
const PREFETCH_ROWS: usize = 3;

/// Asks for the cache lines of `bytes` bytes from `p` (a hint; no effect off x86-64).
#[inline(always)]
pub(super) fn prefetch_bytes(p: *const u8, bytes: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let mut k = 0;
        while k < bytes {
            // SAFETY: prefetch is a hint and never faults; the address is only computed
            unsafe { _mm_prefetch(p.wrapping_add(k) as *const i8, _MM_HINT_T0) };
            k += 64;
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (p, bytes);
}

/// The y-lines `i ≡ colour (mod 2)` with `s ≤ i < e`, each solved exactly with its
/// neighbour columns frozen.
///
/// # Safety
/// `x` points at unknown (0, 0) of a padded vector; no other thread reads or writes the
/// columns solved here or writes their neighbour columns meanwhile.
#[allow(clippy::too_many_arguments)]
unsafe fn lines(
    a: &[[f64; 9]],
    cp: &[f64],
    nx: usize,
    ny: usize,
    x: *mut f64,
    b: &[f64],
    colour: usize,
    s: usize,
    e: usize,
) {
    let first = s + (s + colour) % 2;
    if first >= e {
        return;
    }
    let last = e - 1 - (e - 1 + colour) % 2; // the last column of the colour below e
    let (lo, hi) = (first.saturating_sub(1), (last + 2).min(nx)); // columns read
    for j in 0..ny {
        let row = j * nx;
        if j + PREFETCH_ROWS < ny {
            let ahead = row + PREFETCH_ROWS * nx;
            prefetch_bytes(
                a.as_ptr().add(ahead + first) as *const u8,
                (last + 1 - first) * 72,
            );
            prefetch_bytes(x.add(ahead + nx + lo) as *const u8, (hi - lo) * 8);
            prefetch_bytes(b.as_ptr().add(ahead + lo) as *const u8, (hi - lo) * 8);
            prefetch_bytes(
                cp.as_ptr().add(ahead + first) as *const u8,
                (last + 1 - first) * 8,
            );
        }
        let mut i = first;
        while i <= last {
            let p = row + i;
            let m = a.get_unchecked(p);
            let cprev = if j > 0 {
                *cp.get_unchecked(p - nx)
            } else {
                0.0
            };
            let inv = 1.0 / (m[4] - m[1] * cprev);
            let xq = x.add(p);
            let mut r = *b.get_unchecked(p) - m[1] * *xq.sub(nx);
            if i > 0 {
                r -= m[0] * *xq.sub(nx + 1) + m[3] * *xq.sub(1) + m[6] * *xq.add(nx - 1);
            }
            if i + 1 < nx {
                r -= m[2] * *xq.sub(nx - 1) + m[5] * *xq.add(1) + m[8] * *xq.add(nx + 1);
            }
            *xq = r * inv;
            i += 2;
        }
    }
    for j in (0..ny.saturating_sub(1)).rev() {
        let row = j * nx;
        let mut i = first;
        while i <= last {
            let xq = x.add(row + i);
            *xq -= *cp.get_unchecked(row + i) * *xq.add(nx);
            i += 2;
        }
    }
}

/// Zebra y-line sweep with the factors `cp` of [`factor_y`]: the columns `i ≡ first (mod 2)`,
/// then the others, each line solved exactly with its neighbour columns frozen (the same
/// values as two half sweeps one after the other, in any order of the blocks).
///
/// Columns are split into tasks of whole blocks. Inside a task, after the first colour of a
/// block, the second colour's lines whose right neighbour is final are solved; the two lines
/// of the second colour next to a task boundary wait until every task is done.
#[allow(clippy::too_many_arguments)]
pub(super) fn ysweep(
    a: &[[f64; 9]],
    cp: &[f64],
    nx: usize,
    ny: usize,
    x: &mut [f64],
    b: &[f64],
    first: usize,
) {
    let pd = pad(nx);
    assert_eq!(x.len(), padded_len(nx, ny));
    assert_eq!(b.len(), padded_len(nx, ny));
    assert_eq!(a.len(), nx * ny);
    assert_eq!(cp.len(), nx * ny);
    let second = 1 - first;
    let xp = SharedPtr(unsafe { x.as_mut_ptr().add(pd) });
    let b = &b[pd..pd + nx * ny];
    let blocks = nx.div_ceil(W);
    let tasks = if use_par(nx * ny) {
        (4 * rayon::current_num_threads()).min(blocks)
    } else {
        1
    };
    // task t: blocks [t·blocks/tasks, (t+1)·blocks/tasks)
    let start = |t: usize| (t * blocks / tasks * W).min(nx);
    let task = |t: usize| {
        let (c0, c1) = (start(t), start(t + 1));
        let x = xp.get();
        // the second colour at c0 waits for the task on the left (column c0 − 1)
        let mut s2 = if c0 == 0 { 0 } else { c0 + 1 };
        let mut i0 = c0;
        // SAFETY: a task writes the first colour in [c0, c1) and the second colour in
        // [c0 + 1, c1 − 1), whose neighbours are its own; the columns c0 and c1 − 1 of the
        // second colour are solved after every task is done.
        unsafe {
            while i0 < c1 {
                let i1 = (i0 + W).min(c1);
                lines(a, cp, nx, ny, x, b, first, i0, i1);
                let e2 = if i1 == nx { nx } else { i1 - 1 };
                lines(a, cp, nx, ny, x, b, second, s2, e2);
                s2 = e2.max(s2);
                i0 = i1;
            }
        }
    };
    if tasks > 1 {
        (0..tasks).into_par_iter().for_each(task);
    } else {
        task(0);
    }
    // the second colour at the task boundaries: columns c − 1 and c
    for t in 1..tasks {
        let c = start(t);
        // SAFETY: every task is done; one thread
        unsafe { lines(a, cp, nx, ny, xp.get(), b, second, c - 1, (c + 1).min(nx)) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A zebra y-line sweep solves every line of the colour relaxed second exactly, and the
    /// first colour's lines exactly against the second colour's old values: afterwards the
    /// nine-point equations of the second colour's columns hold to round-off, and sweeping
    /// the first colour alone from the same start gives the same first-colour values (odd and
    /// even sizes, one block and many, one task and several).
    #[test]
    fn a_y_line_sweep_solves_its_lines() {
        for (nx, ny) in [(7, 9), (6, 10), (2, 5), (1, 4), (301, 7), (300, 120)] {
            let val = |k: usize, salt: usize| ((k * 7919 + salt * 104_729) % 1000) as f64 / 1000.0;
            let a: Vec<[f64; 9]> = (0..nx * ny)
                .map(|p| {
                    let (i, j) = (p % nx, p / nx);
                    let mut m = [0.0; 9];
                    for (d, c) in m.iter_mut().enumerate() {
                        let (di, dj) = (d % 3, d / 3);
                        let outside = (di == 0 && i == 0)
                            || (di == 2 && i + 1 == nx)
                            || (dj == 0 && j == 0)
                            || (dj == 2 && j + 1 == ny);
                        *c = if d == 4 {
                            9.0 + val(p, d)
                        } else if outside {
                            0.0
                        } else {
                            -0.5 - val(p, d)
                        };
                    }
                    m
                })
                .collect();
            let mut cp = Vec::new();
            factor_y(&a, nx, ny, &mut cp).unwrap();
            let len = padded_len(nx, ny);
            let pd = pad(nx);
            let b: Vec<f64> = (0..len).map(|k| val(k, 11) - 0.5).collect();
            for first in 0..2 {
                let mut x0: Vec<f64> = (0..len).map(|k| val(k, 13)).collect();
                x0[..pd].fill(0.0);
                x0[pd + nx * ny..].fill(0.0);
                let mut x = x0.clone();
                ysweep(&a, &cp, nx, ny, &mut x, &b, first);
                let at = |x: &[f64], i: isize, j: isize| {
                    if i < 0 || j < 0 || i >= nx as isize || j >= ny as isize {
                        0.0
                    } else {
                        x[pd + i as usize + nx * j as usize]
                    }
                };
                let res = |x: &[f64], i: usize, j: usize| {
                    let m = &a[i + nx * j];
                    let mut r = b[pd + i + nx * j];
                    for dj in -1isize..=1 {
                        for di in -1isize..=1 {
                            let k = ((dj + 1) * 3 + di + 1) as usize;
                            r -= m[k] * at(x, i as isize + di, j as isize + dj);
                        }
                    }
                    r
                };
                for j in 0..ny {
                    for i in (1 - first..nx).step_by(2) {
                        let r = res(&x, i, j);
                        assert!(
                            r.abs() < 1e-13,
                            "{nx}×{ny} first {first}: ({i}, {j}): {r:e}"
                        );
                    }
                }
                // the first colour's lines against the old second colour
                let mut z = x0.clone();
                for j in 0..ny {
                    for i in (first..nx).step_by(2) {
                        z[pd + i + nx * j] = x[pd + i + nx * j];
                    }
                }
                for j in 0..ny {
                    for i in (first..nx).step_by(2) {
                        let r = res(&z, i, j);
                        assert!(
                            r.abs() < 1e-13,
                            "{nx}×{ny} first {first}, ({i}, {j}): {r:e}"
                        );
                    }
                }
            }
        }
    }
}
