//! The x-line half of the zebra smoother ([`crate::solve::multigrid`]'s `relax`): the Thomas
//! factors of every row's tridiagonal system ([`factor_x`]) and the zebra half sweep
//! ([`xzebra`]) that solves the lines of one colour, two at a time ([`xline2`]). Vectors are
//! padded as in `relax`.

use super::relax::{pad, padded_len, pivot_error, Stencils};
use crate::solve::multigrid::{use_par, SharedPtr};
use crate::solve::SolveError;
use rayon::prelude::*;

/// Builds the x-line factors of `a`: per unknown, the Thomas factors of its row's tridiagonal
/// system `(a_W, a_C, a_E)`, `[inv, cp]` with `inv` the inverse pivot and `cp = a_E·inv`. The
/// sweep reads the couplings from `a` itself: a scaled copy of the stencil (as the y-lines
/// keep, [`YLineOp`]) would cost 56 more bytes per unknown, and the x-lines stream `a` in its
/// natural order anyway.
pub(super) fn factor_x(
    a: &[[f64; 9]],
    nx: usize,
    ny: usize,
    xop: &mut Vec<[f64; 2]>,
) -> Result<(), SolveError> {
    xop.resize(nx * ny, [0.0; 2]);
    let work = |(j, (op, a)): (usize, (&mut [[f64; 2]], &Stencils))| {
        let mut cprev = 0.0;
        for i in 0..nx {
            let m = &a[i];
            let piv = m[4] - m[3] * cprev;
            if !(piv.is_finite() && piv != 0.0) {
                return Err(pivot_error(i, j, piv, 'x'));
            }
            let v = 1.0 / piv;
            cprev = m[5] * v;
            op[i] = [v, cprev];
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

/// One x-line of row `j`: solves its tridiagonal system with rows `j ± 1` frozen (`a`: the
/// row's stencils, `fac`: its [`factor_x`] factors).
///
/// # Safety
/// `x` points at unknown `(0, j)` of a padded vector; no other thread reads or writes row `j`
/// or writes rows `j ± 1` meanwhile.
#[inline]
unsafe fn xline(a: &[[f64; 9]], fac: &[[f64; 2]], b: &[f64], x: *mut f64, nx: usize) {
    let s = std::slice::from_raw_parts(x.sub(nx), nx);
    let n = std::slice::from_raw_parts(x.add(nx), nx);
    let c = std::slice::from_raw_parts_mut(x, nx);
    let (a, fac, b) = (&a[..nx], &fac[..nx], &b[..nx]);
    if nx == 1 {
        let m = &a[0];
        c[0] = (b[0] - m[1] * s[0] - m[7] * n[0]) * fac[0][0];
        return;
    }
    // forward elimination, i = 0 (no west neighbours), interior, i = nx - 1 (no east)
    let m = &a[0];
    let mut prev = (b[0] - m[1] * s[0] - m[2] * s[1] - m[7] * n[0] - m[8] * n[1]) * fac[0][0];
    c[0] = prev;
    for i in 1..nx - 1 {
        let m = &a[i];
        prev = (b[i]
            - m[0] * s[i - 1]
            - m[1] * s[i]
            - m[2] * s[i + 1]
            - m[6] * n[i - 1]
            - m[7] * n[i]
            - m[8] * n[i + 1]
            - m[3] * prev)
            * fac[i][0];
        c[i] = prev;
    }
    let i = nx - 1;
    let m = &a[i];
    prev = (b[i] - m[0] * s[i - 1] - m[1] * s[i] - m[6] * n[i - 1] - m[7] * n[i] - m[3] * prev)
        * fac[i][0];
    c[i] = prev;
    // back substitution
    for i in (0..nx - 1).rev() {
        prev = c[i] - fac[i][1] * prev;
        c[i] = prev;
    }
}

/// Two x-lines of one colour at once, rows `j` and `j + 2` ([`xline`] for each, the same
/// arithmetic): the elimination of a line is a chain of dependent multiply–adds, so a core
/// that runs two chains side by side does the pair in little more than the time of one line
/// (`kernel_timings`, one thread, a whole sweep: 4.1 → 2.9 ns per unknown at 255², where the
/// rows are in cache; 9.9 → 8.7 at 1023²).
///
/// # Safety
/// As [`xline`] for both rows; `x` points at unknown `(0, j)` and row `j + 2` is `2 nx` further.
#[inline]
unsafe fn xline2(a: &[[f64; 9]], fac: &[[f64; 2]], b: &[f64], x: *mut f64, nx: usize) {
    if nx < 2 {
        xline(a, fac, b, x, nx);
        xline(
            &a[2 * nx..],
            &fac[2 * nx..],
            &b[2 * nx..],
            x.add(2 * nx),
            nx,
        );
        return;
    }
    let row = |k: usize| {
        let x = x.add(2 * k * nx);
        (
            std::slice::from_raw_parts(x.sub(nx), nx),
            std::slice::from_raw_parts(x.add(nx), nx),
            std::slice::from_raw_parts_mut(x, nx),
        )
    };
    let ((s0, n0, c0), (s1, n1, c1)) = (row(0), row(1));
    let (a0, a1) = (&a[..nx], &a[2 * nx..3 * nx]);
    let (f0, f1) = (&fac[..nx], &fac[2 * nx..3 * nx]);
    let (b0, b1) = (&b[..nx], &b[2 * nx..3 * nx]);
    let (m0, m1) = (&a0[0], &a1[0]);
    let mut p0 = (b0[0] - m0[1] * s0[0] - m0[2] * s0[1] - m0[7] * n0[0] - m0[8] * n0[1]) * f0[0][0];
    let mut p1 = (b1[0] - m1[1] * s1[0] - m1[2] * s1[1] - m1[7] * n1[0] - m1[8] * n1[1]) * f1[0][0];
    c0[0] = p0;
    c1[0] = p1;
    for i in 1..nx - 1 {
        let (m0, m1) = (&a0[i], &a1[i]);
        p0 = (b0[i]
            - m0[0] * s0[i - 1]
            - m0[1] * s0[i]
            - m0[2] * s0[i + 1]
            - m0[6] * n0[i - 1]
            - m0[7] * n0[i]
            - m0[8] * n0[i + 1]
            - m0[3] * p0)
            * f0[i][0];
        p1 = (b1[i]
            - m1[0] * s1[i - 1]
            - m1[1] * s1[i]
            - m1[2] * s1[i + 1]
            - m1[6] * n1[i - 1]
            - m1[7] * n1[i]
            - m1[8] * n1[i + 1]
            - m1[3] * p1)
            * f1[i][0];
        c0[i] = p0;
        c1[i] = p1;
    }
    let i = nx - 1;
    let (m0, m1) = (&a0[i], &a1[i]);
    p0 = (b0[i]
        - m0[0] * s0[i - 1]
        - m0[1] * s0[i]
        - m0[6] * n0[i - 1]
        - m0[7] * n0[i]
        - m0[3] * p0)
        * f0[i][0];
    p1 = (b1[i]
        - m1[0] * s1[i - 1]
        - m1[1] * s1[i]
        - m1[6] * n1[i - 1]
        - m1[7] * n1[i]
        - m1[3] * p1)
        * f1[i][0];
    c0[i] = p0;
    c1[i] = p1;
    for i in (0..nx - 1).rev() {
        p0 = c0[i] - f0[i][1] * p0;
        p1 = c1[i] - f1[i][1] * p1;
        c0[i] = p0;
        c1[i] = p1;
    }
}

/// Zebra x-line half sweep over the rows `j ≡ colour (mod 2)` of operator `a` with its x-line
/// factors `xop`.
#[allow(clippy::too_many_arguments)]
pub(super) fn xzebra(
    a: &[[f64; 9]],
    xop: &[[f64; 2]],
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
            if 2 * q + 1 < count {
                let r = j * nx..(j + 3) * nx;
                xline2(
                    &a[r.clone()],
                    &xop[r.clone()],
                    &b[r],
                    xp.get().add(j * nx),
                    nx,
                )
            } else {
                let r = j * nx..(j + 1) * nx;
                xline(
                    &a[r.clone()],
                    &xop[r.clone()],
                    &b[r],
                    xp.get().add(j * nx),
                    nx,
                )
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
