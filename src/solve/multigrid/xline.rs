//! The x-line half of the zebra smoother ([`crate::solve::multigrid`]'s `relax`): the Thomas
//! factors of every row's tridiagonal system ([`factor_x`]) and the zebra half sweep
//! ([`xzebra`]) that solves the lines of one colour, two at a time ([`xlines`]). Vectors are
//! padded as in `relax`.

use super::relax::{pad, padded_len, pivot_error, Fac, Stencils};
use crate::solve::multigrid::{use_par, SharedPtr};
use crate::solve::SolveError;
use rayon::prelude::*;

/// Builds the x-line factors of `a`: per unknown, the Thomas factors of its row's tridiagonal
/// system `(a_W, a_C, a_E)`, `[inv, cp]` with `inv` the inverse pivot and `cp = a_E·inv`,
/// rounded to f32 (each pivot from the rounded `cp` of its left neighbour). The
/// sweep reads the couplings from `a` itself: a scaled copy of the stencil (as the y-lines
/// keep, [`YLineOp`]) would cost 28 more bytes per unknown in f32, and the x-lines stream `a` in its
/// natural order anyway.
pub(super) fn factor_x(
    a: &[[f64; 9]],
    nx: usize,
    ny: usize,
    xop: &mut Vec<[Fac; 2]>,
) -> Result<(), SolveError> {
    xop.resize(nx * ny, [0.0; 2]);
    let work = |(j, (op, a)): (usize, (&mut [[Fac; 2]], &Stencils))| {
        let mut cprev = 0.0;
        for i in 0..nx {
            let m = &a[i];
            let piv = m[4] - m[3] * cprev;
            if !(piv.is_finite() && piv != 0.0) {
                return Err(pivot_error(i, j, piv, 'x'));
            }
            let v = 1.0 / piv;
            let c = m[5] * v;
            if !(v as Fac).is_finite() || !(c as Fac).is_finite() {
                return Err(pivot_error(i, j, piv, 'x'));
            }
            op[i] = [v as Fac, c as Fac];
            // the next pivot from the stored (rounded) factor: the Thomas factorization of
            // the tridiagonal system the sweep solves
            cprev = f64::from(op[i][1]);
        }
        Ok(())
    };
    if use_par(nx * ny) {
        xop.par_chunks_mut(nx)
            .zip(a.par_chunks(nx))
            .enumerate()
            .try_for_each(work)
    } else {
        xop.chunks_mut(nx)
            .zip(a.chunks(nx))
            .enumerate()
            .try_for_each(work)
    }
}

/// `N` x-lines of one colour, rows `j, j + 2, …`, each solved with its neighbour rows
/// frozen (`a`: the rows' stencils, `fac`: their [`factor_x`] factors, both from row `j` on).
/// The elimination of a line is a chain of dependent multiply–adds; `N` = 2 runs two chains
/// side by side, which a core does in little more than the time of one (`kernel_timings`, one
/// thread, a whole sweep: 4.1 → 2.9 ns per unknown at 255², where the rows are in cache;
/// 9.9 → 8.7 at 1023²). Every line gets the same arithmetic whatever `N`.
///
/// # Safety
/// `x` points at unknown `(0, j)` of a padded vector and line `l` is row `j + 2l`; no other
/// thread reads or writes those rows or writes the rows next to them meanwhile.
#[inline]
unsafe fn xlines<const N: usize>(
    a: &[[f64; 9]],
    fac: &[[Fac; 2]],
    b: &[f64],
    x: *mut f64,
    nx: usize,
) {
    let row = |l: usize| 2 * l * nx..(2 * l + 1) * nx;
    let s: [&[f64]; N] =
        std::array::from_fn(|l| std::slice::from_raw_parts(x.add(2 * l * nx).sub(nx), nx));
    let n: [&[f64]; N] =
        std::array::from_fn(|l| std::slice::from_raw_parts(x.add((2 * l + 1) * nx), nx));
    let c: [&mut [f64]; N] =
        std::array::from_fn(|l| std::slice::from_raw_parts_mut(x.add(2 * l * nx), nx));
    let a: [&[[f64; 9]]; N] = std::array::from_fn(|l| &a[row(l)]);
    let f: [&[[Fac; 2]]; N] = std::array::from_fn(|l| &fac[row(l)]);
    let b: [&[f64]; N] = std::array::from_fn(|l| &b[row(l)]);
    if nx == 1 {
        for l in 0..N {
            let m = &a[l][0];
            c[l][0] = (b[l][0] - m[1] * s[l][0] - m[7] * n[l][0]) * f64::from(f[l][0][0]);
        }
        return;
    }
    // forward elimination, i = 0 (no west neighbours), interior, i = nx - 1 (no east)
    let mut prev = [0.0; N];
    for l in 0..N {
        let (m, s, n) = (&a[l][0], s[l], n[l]);
        prev[l] = (b[l][0] - m[1] * s[0] - m[2] * s[1] - m[7] * n[0] - m[8] * n[1])
            * f64::from(f[l][0][0]);
        c[l][0] = prev[l];
    }
    for i in 1..nx - 1 {
        for l in 0..N {
            let (m, s, n) = (&a[l][i], s[l], n[l]);
            prev[l] = (b[l][i]
                - m[0] * s[i - 1]
                - m[1] * s[i]
                - m[2] * s[i + 1]
                - m[6] * n[i - 1]
                - m[7] * n[i]
                - m[8] * n[i + 1]
                - m[3] * prev[l])
                * f64::from(f[l][i][0]);
            c[l][i] = prev[l];
        }
    }
    let i = nx - 1;
    for l in 0..N {
        let (m, s, n) = (&a[l][i], s[l], n[l]);
        prev[l] = (b[l][i]
            - m[0] * s[i - 1]
            - m[1] * s[i]
            - m[6] * n[i - 1]
            - m[7] * n[i]
            - m[3] * prev[l])
            * f64::from(f[l][i][0]);
        c[l][i] = prev[l];
    }
    // back substitution
    for i in (0..nx - 1).rev() {
        for l in 0..N {
            prev[l] = c[l][i] - f64::from(f[l][i][1]) * prev[l];
            c[l][i] = prev[l];
        }
    }
}

/// Zebra x-line half sweep over the rows `j ≡ colour (mod 2)` of operator `a` with its x-line
/// factors `xop`.
#[allow(clippy::too_many_arguments)]
pub(super) fn xzebra(
    a: &[[f64; 9]],
    xop: &[[Fac; 2]],
    nx: usize,
    ny: usize,
    x: &mut [f64],
    b: &[f64],
    colour: usize,
) {
    let pd = pad(nx);
    assert_eq!(x.len(), padded_len(nx, ny));
    assert_eq!(b.len(), padded_len(nx, ny));
    assert_eq!(xop.len(), nx * ny);
    assert_eq!(a.len(), nx * ny);
    let xp = SharedPtr(unsafe { x.as_mut_ptr().add(pd) });
    let b = &b[pd..pd + nx * ny];
    let count = (ny + 1 - colour) / 2;
    // lines t = 2q and 2q + 1 of this colour (rows j and j + 2) together
    let pair = |q: usize| {
        let j = colour + 4 * q;
        // SAFETY: rows of one colour are disjoint and read only rows of the other colour;
        // rows -1 and ny lie in the padding.
        unsafe {
            let x = xp.get().add(j * nx);
            if 2 * q + 1 < count {
                let r = j * nx..(j + 3) * nx;
                xlines::<2>(&a[r.clone()], &xop[r.clone()], &b[r], x, nx)
            } else {
                let r = j * nx..(j + 1) * nx;
                xlines::<1>(&a[r.clone()], &xop[r.clone()], &b[r], x, nx)
            }
        }
    };
    let pairs = count.div_ceil(2);
    if use_par(nx * ny) {
        let min_len = (2048 / nx).max(1);
        (0..pairs)
            .into_par_iter()
            .with_min_len(min_len)
            .for_each(pair);
    } else {
        (0..pairs).for_each(pair);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A zebra x-line half sweep solves every line of its colour: afterwards the nine-point
    /// equations of those rows hold to the f32 factors' rounding with the other rows' values (odd and
    /// even row counts: lines paired two at a time, and a last line alone).
    #[test]
    fn an_x_line_half_sweep_solves_its_lines() {
        for (nx, ny) in [(7, 9), (6, 10), (2, 5), (1, 4)] {
            let val = |k: usize, salt: usize| ((k * 7919 + salt * 104_729) % 1000) as f64 / 1000.0;
            let a: Vec<[f64; 9]> = (0..nx * ny)
                .map(|p| {
                    let mut m = [0.0; 9];
                    for (d, c) in m.iter_mut().enumerate() {
                        *c = if d == 4 {
                            9.0 + val(p, d)
                        } else {
                            -0.5 - val(p, d)
                        };
                    }
                    m
                })
                .collect();
            let mut xop = Vec::new();
            factor_x(&a, nx, ny, &mut xop).unwrap();
            let len = padded_len(nx, ny);
            let pd = pad(nx);
            let b: Vec<f64> = (0..len).map(|k| val(k, 11) - 0.5).collect();
            for colour in 0..2 {
                let mut x: Vec<f64> = (0..len).map(|k| val(k, 13)).collect();
                x[..pd].fill(0.0);
                x[pd + nx * ny..].fill(0.0);
                xzebra(&a, &xop, nx, ny, &mut x, &b, colour);
                let at = |i: isize, j: isize| {
                    if i < 0 || j < 0 || i >= nx as isize || j >= ny as isize {
                        0.0
                    } else {
                        x[pd + i as usize + nx * j as usize]
                    }
                };
                for j in (colour..ny).step_by(2) {
                    for i in 0..nx {
                        let m = &a[i + nx * j];
                        let mut r = b[pd + i + nx * j];
                        let mut scale = r.abs();
                        for dj in -1isize..=1 {
                            for di in -1isize..=1 {
                                let k = ((dj + 1) * 3 + di + 1) as usize;
                                let t = m[k] * at(i as isize + di, j as isize + dj);
                                r -= t;
                                scale += t.abs();
                            }
                        }
                        // the factors are stored in f32: exact to their rounding (2⁻²⁴)
                        assert!(
                            r.abs() < 1e-6 * scale,
                            "{nx}×{ny} colour {colour}: row {j} node {i}: {r:e} of {scale:e}"
                        );
                    }
                }
            }
        }
    }
}
