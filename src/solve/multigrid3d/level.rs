//! One level of the hierarchy: the 27-point operator, padded vector layout, residual and the
//! alternating line Gauss–Seidel smoother.
//!
//! Vectors `x` and `r` of a level are *padded*: one ghost layer of zeros around the
//! `nx × ny × nz` unknowns, so that no kernel of a cycle needs boundary tests (operator
//! couplings that leave the grid are zero and read a zero ghost). Right-hand sides `b` are
//! unpadded.
//!
//! # Line Gauss–Seidel
//! A sweep along direction `d` solves, for every line of unknowns along `d`, the tridiagonal
//! system of its three in-line couplings with all other neighbours frozen (Thomas algorithm,
//! factored at setup). The 27-point stencil couples a line to its 8 neighbouring lines, so
//! lines are coloured by the parities of their two other indices (4 colours); the lines of
//! one colour are independent and run in parallel.

use crate::solve::krylov::in_order;
use crate::solve::multigrid3d::{use_par, SharedPtr};
use crate::solve::stencil19::{Stencil19, OFFSETS};
use crate::solve::SolveError;
use rayon::prelude::*;

/// Index of offset (di, dj, dk) ∈ {−1, 0, 1}³ in a 27-point stencil.
#[inline]
pub(super) const fn s27(di: isize, dj: isize, dk: isize) -> usize {
    ((di + 1) + 3 * (dj + 1) + 9 * (dk + 1)) as usize
}

/// Centre slot of a 27-point stencil; the opposite of slot `m` is `26 − m`.
pub(super) const CTR: usize = 13;

/// The 27-point slot of each of the 19 slots of [`Stencil19`].
const SLOTS19: [usize; 19] = {
    let mut t = [0; 19];
    let mut m = 0;
    while m < 19 {
        let o = OFFSETS[m];
        t[m] = s27(o[0] as isize, o[1] as isize, o[2] as isize);
        m += 1;
    }
    t
};

/// The 19-point slot of each 27-point slot, if any.
const INDEX19: [Option<usize>; 27] = {
    let mut t = [None; 27];
    let mut m = 0;
    while m < 19 {
        t[SLOTS19[m]] = Some(m);
        m += 1;
    }
    t
};

/// Offset of slot `m`.
#[inline]
pub(super) const fn off27(m: usize) -> [isize; 3] {
    [
        (m % 3) as isize - 1,
        ((m / 3) % 3) as isize - 1,
        (m / 9) as isize - 1,
    ]
}

/// One level: operator, line factors and (if not the coarsest) the transfer stars to the next.
#[derive(Debug)]
pub(super) struct Level {
    pub dims: [usize; 3],
    /// Rows of the 27-point operator (unpadded numbering, i fastest); empty on the fine
    /// level, whose operator is `a19` (its 27-point rows, [`Level::row`], are expanded where
    /// a setup needs them: keeping them would cost 216 bytes per fine unknown). Single
    /// precision (#16): a coarse level only computes corrections, so its rounded Galerkin
    /// operator changes the coarse-grid correction a little, never the cycle's fixed point;
    /// its residuals, smoothers and the next Galerkin product all read the rounded rows.
    pub a: Vec<[f32; 27]>,
    /// The fine level's operator as given, 19-point rows (couplings leaving the grid zeroed;
    /// empty on coarse levels): the residuals and plane sweeps of a cycle read these, 152
    /// instead of 216 bytes and 19 instead of 27 products per unknown ([`Level::times_row`]).
    pub a19: Vec<[f64; 19]>,
    /// Thomas factors `[c'_t, 1/(b_t − a_t c'_{t−1})]` of the lines along x, y, z (line
    /// smoother only; allocated by `factor_lines`).
    pub fac: [Vec<[f64; 2]>; 3],
    /// Prolongation stars (one per coarse unknown): weight of the coarse value at each of
    /// its 27 fine neighbours. Single precision (#16): they only move corrections and
    /// residuals, so rounding them changes the coarse-grid correction a little, never the
    /// cycle's fixed point (the fine residual and smoother stay f64; the Galerkin operator
    /// is built from the rounded stars). 54 bytes per fine unknown with `r` instead of 108.
    pub p: Vec<[f32; 27]>,
    /// Restriction stars: weight of each of the 27 fine neighbours' residuals (single
    /// precision, as `p`).
    pub r: Vec<[f32; 27]>,
}

impl Level {
    pub fn new(dims: [usize; 3]) -> Self {
        let n = dims.iter().product();
        Level {
            dims,
            a: vec![[0.0; 27]; n],
            a19: Vec::new(),
            fac: std::array::from_fn(|_| Vec::new()),
            p: Vec::new(),
            r: Vec::new(),
        }
    }

    /// The fine level of a hierarchy: no 27-point rows (see [`Level::a`]); [`Level::embed`]
    /// gives it its operator.
    pub fn fine(dims: [usize; 3]) -> Self {
        Level {
            dims,
            a: Vec::new(),
            a19: Vec::new(),
            fac: std::array::from_fn(|_| Vec::new()),
            p: Vec::new(),
            r: Vec::new(),
        }
    }

    pub fn n(&self) -> usize {
        self.dims.iter().product()
    }

    /// Row `p` of the operator as 27 couplings: a coarse level's row, or the fine level's
    /// 19-point row expanded (the slots outside the 19-point stencil are zero).
    #[inline]
    pub fn row(&self, p: usize) -> [f64; 27] {
        if self.a19.is_empty() {
            self.a[p].map(f64::from)
        } else {
            let src = &self.a19[p];
            let mut r = [0.0; 27];
            for (m, &v) in src.iter().enumerate() {
                r[SLOTS19[m]] = v;
            }
            r
        }
    }

    /// Coupling `m` (27-point slot) of row `p`.
    #[inline]
    pub fn coef(&self, p: usize, m: usize) -> f64 {
        if self.a19.is_empty() {
            f64::from(self.a[p][m])
        } else {
            match INDEX19[m] {
                Some(t) => self.a19[p][t],
                None => 0.0,
            }
        }
    }

    /// Length of a padded vector.
    pub fn padded_len(&self) -> usize {
        let [nx, ny, nz] = self.dims;
        (nx + 2) * (ny + 2) * (nz + 2)
    }

    /// Padded strides along x, y, z.
    #[inline]
    pub fn qstride(&self) -> [usize; 3] {
        let [nx, ny, _] = self.dims;
        [1, nx + 2, (nx + 2) * (ny + 2)]
    }

    /// Padded index of unknown (i, j, k).
    #[inline]
    pub fn q(&self, i: usize, j: usize, k: usize) -> usize {
        let s = self.qstride();
        (i + 1) + s[1] * (j + 1) + s[2] * (k + 1)
    }

    /// Padded linear offsets of the 27 slots.
    pub fn qoff(&self) -> [isize; 27] {
        std::array::from_fn(|m| self.qshift(off27(m)))
    }

    /// Padded linear offset of the neighbour at `o`.
    #[inline]
    fn qshift(&self, o: [isize; 3]) -> isize {
        let s = self.qstride();
        o[0] + s[1] as isize * o[1] + s[2] as isize * o[2]
    }

    /// Padded linear offsets of the 19 slots of [`Stencil19`].
    pub fn qoff19(&self) -> [isize; 19] {
        std::array::from_fn(|m| self.qshift(OFFSETS[m].map(isize::from)))
    }

    /// Row `p` of the operator times padded `x` around padded index `q`: from the 19-point
    /// rows on the fine level, the 27-point rows elsewhere (`qo`, `qo19`: [`Level::qoff`],
    /// [`Level::qoff19`]).
    ///
    /// # Safety
    /// `x` is a padded vector of this level and `q` the padded index of an unknown (all its
    /// neighbours, ghosts included, are then inside `x`).
    #[inline(always)]
    pub unsafe fn times_row(
        &self,
        p: usize,
        x: &[f64],
        q: usize,
        qo: &[isize; 27],
        qo19: &[isize; 19],
    ) -> f64 {
        debug_assert!(x.len() == self.padded_len() && q < x.len());
        let xq = x.as_ptr().add(q);
        let mut s = 0.0;
        if self.a19.is_empty() {
            let row = &self.a[p];
            for m in 0..27 {
                s += f64::from(row[m]) * *xq.offset(qo[m]);
            }
        } else {
            let row = &self.a19[p];
            for m in 0..19 {
                s += row[m] * *xq.offset(qo19[m]);
            }
        }
        s
    }

    /// Copies the 19-point operator into the 19-point rows of the fine level (couplings
    /// leaving the grid dropped) and drops its 27-point rows, if any.
    pub fn embed(&mut self, a: &Stencil19) -> Result<(), SolveError> {
        assert_eq!(a.dims(), self.dims);
        self.a19.clear();
        self.a19.extend_from_slice(a.coefs());
        self.clip_fine()
    }

    /// Takes the rows of a 19-point operator of this level's size over as the fine level's
    /// (no copy; [`crate::solve::LinearSolver::adopt`]), couplings leaving the grid dropped.
    pub fn embed_rows(&mut self, rows: Vec<[f64; 19]>) -> Result<(), SolveError> {
        assert_eq!(rows.len(), self.n());
        self.a19 = rows;
        self.clip_fine()
    }

    /// Hands the fine level's 19-point rows back, leaving it without an operator.
    pub fn take_rows(&mut self) -> Vec<[f64; 19]> {
        std::mem::take(&mut self.a19)
    }

    /// Zeroes the couplings of the 19-point rows that leave the grid, drops the 27-point
    /// rows, and rejects a non-finite coefficient.
    fn clip_fine(&mut self) -> Result<(), SolveError> {
        let dims = self.dims;
        let [nx, ny, _] = dims;
        let plane = nx * ny;
        let n = self.n();
        self.a = Vec::new();
        let fill = |(k, rows19): (usize, &mut [[f64; 19]])| {
            let mut bad = None;
            for (q, row19) in rows19.iter_mut().enumerate() {
                let ins = Stencil19::inside_of(dims, q % nx, q / nx, k);
                for m in 0..19 {
                    if !ins[m] {
                        row19[m] = 0.0;
                    }
                }
                if bad.is_none() && !row19.iter().all(|v| v.is_finite()) {
                    bad = Some(k * plane + q);
                }
            }
            bad
        };
        let bad = if use_par(n) {
            self.a19
                .par_chunks_mut(plane)
                .enumerate()
                .filter_map(fill)
                .min()
        } else {
            self.a19
                .chunks_mut(plane)
                .enumerate()
                .filter_map(fill)
                .min()
        };
        match bad {
            Some(p) => Err(SolveError::Singular(format!(
                "multigrid: non-finite coefficient in row {p}"
            ))),
            None => Ok(()),
        }
    }

    /// Factors the tridiagonal line systems of all three directions.
    pub fn factor_lines(&mut self) -> Result<(), SolveError> {
        let [nx, ny, nz] = self.dims;
        let dims = self.dims;
        let n = self.n();
        let mut facs = std::mem::take(&mut self.fac);
        let lev: &Level = self;
        for (d, fac) in facs.iter_mut().enumerate() {
            fac.resize(n, [0.0; 2]);
            let (sub, sup) = line_slots(d);
            let stride = [1, nx, nx * ny][d];
            let len = dims[d];
            let line_starts: Vec<usize> = (0..nx * ny * nz)
                .filter(|&p| [p % nx, (p / nx) % ny, p / (nx * ny)][d] == 0)
                .collect();
            let fp = SharedFac(fac.as_mut_ptr());
            let one = |&p0: &usize| -> Result<(), SolveError> {
                let mut cp = 0.0;
                for t in 0..len {
                    let p = p0 + t * stride;
                    let (ctr, up) = (lev.coef(p, CTR), lev.coef(p, sup));
                    let lo = if t > 0 { lev.coef(p, sub) } else { 0.0 };
                    let den = ctr - lo * cp;
                    if !(den.is_finite() && den.abs() > 1e-300) || den.abs() <= 1e-14 * ctr.abs() {
                        return Err(SolveError::Singular(format!(
                            "multigrid: singular line system at unknown {p}"
                        )));
                    }
                    let inv = 1.0 / den;
                    cp = if t + 1 < len { up * inv } else { 0.0 };
                    // SAFETY: every unknown lies on exactly one line of direction d.
                    unsafe { *fp.get().add(p) = [cp, inv] };
                }
                Ok(())
            };
            let res = if use_par(n) {
                line_starts.par_iter().try_for_each(one)
            } else {
                line_starts.iter().try_for_each(one)
            };
            if let Err(e) = res {
                self.fac = facs;
                return Err(e);
            }
        }
        self.fac = facs;
        Ok(())
    }

    /// `r = b − A x` on padded `x`, `r` (ghosts of `r` stay zero); returns ‖r‖₂².
    pub fn residual(&self, x: &[f64], b: &[f64], r: &mut [f64]) -> f64 {
        self.rows_into(x, Some(b), r, true)
    }

    /// `y = A x` for padded `x` and unpadded `y`.
    pub fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.rows_into(x, None, y, false);
    }

    /// `out = b − A x` (or `A x` without `b`), padded or unpadded `out`; returns ‖out‖₂².
    fn rows_into(&self, x: &[f64], b: Option<&[f64]>, out: &mut [f64], padded: bool) -> f64 {
        let [nx, ny, nz] = self.dims;
        assert_eq!(x.len(), self.padded_len());
        let (qo, qo19) = (self.qoff(), self.qoff19());
        let qs = self.qstride();
        let plane = |k: usize, rp: &mut [f64]| -> f64 {
            let mut ss = 0.0;
            for j in 0..ny {
                for i in 0..nx {
                    let p = i + nx * (j + ny * k);
                    let q = (i + 1) + qs[1] * (j + 1);
                    let qa = q + qs[2] * (k + 1);
                    // SAFETY: x is padded (asserted) and qa the padded index of (i, j, k)
                    let mut s = unsafe { self.times_row(p, x, qa, &qo, &qo19) };
                    if let Some(b) = b {
                        s = b[p] - s;
                    }
                    rp[if padded { q } else { i + nx * j }] = s;
                    ss += s * s;
                }
            }
            ss
        };
        let (body, chunk) = if padded {
            (&mut out[qs[2]..qs[2] * (nz + 1)], qs[2])
        } else {
            (&mut out[..], nx * ny)
        };
        if use_par(self.n()) {
            in_order(
                body.par_chunks_mut(chunk)
                    .enumerate()
                    .map(|(k, rp)| plane(k, rp)),
            )
        } else {
            body.chunks_mut(chunk)
                .enumerate()
                .map(|(k, rp)| plane(k, rp))
                .sum()
        }
    }

    /// One line Gauss–Seidel sweep along direction `d` (all four colours) on padded `x`.
    pub fn line_sweep(&self, d: usize, x: &mut [f64], b: &[f64]) {
        let dims = self.dims;
        let [nx, ny, _] = dims;
        let (e1, e2) = [(1, 2), (0, 2), (0, 1)][d];
        let (sub, sup) = line_slots(d);
        let mut others = [0usize; 24];
        for (o, m) in others
            .iter_mut()
            .zip((0..27).filter(|&m| m != sub && m != sup && m != CTR))
        {
            *o = m;
        }
        let qo = self.qoff();
        let qsd = self.qstride()[d];
        let ps = [1, nx, nx * ny];
        let len = dims[d];
        let fac = &self.fac[d];
        let xp = SharedPtr(x.as_mut_ptr());
        // Colours: the lines without coarse points first, the coarse lines last.
        for (c1, c2) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let line = |u: usize, v: usize| {
                let mut idx = [0usize; 3];
                idx[e1] = u;
                idx[e2] = v;
                let p0 = idx[0] + nx * (idx[1] + ny * idx[2]);
                let q0 = self.q(idx[0], idx[1], idx[2]);
                let x = xp.get();
                // SAFETY: lines of one colour do not couple (they differ by ≥ 2 in an
                // index), so each task writes its own line and reads only other colours.
                unsafe {
                    let mut prev = 0.0;
                    for t in 0..len {
                        let (p, q) = (p0 + t * ps[d], q0 + t * qsd);
                        let row = self.row(p);
                        let mut s = b[p];
                        for &m in &others {
                            s -= row[m] * *x.offset(q as isize + qo[m]);
                        }
                        s -= row[sub] * prev;
                        prev = s * fac[p][1];
                        *x.add(q) = prev;
                    }
                    let mut next = 0.0;
                    for t in (0..len).rev() {
                        let (p, q) = (p0 + t * ps[d], q0 + t * qsd);
                        next = *x.add(q) - fac[p][0] * next;
                        *x.add(q) = next;
                    }
                }
            };
            let outer = |v: usize| {
                for u in (c1..dims[e1]).step_by(2) {
                    line(u, v);
                }
            };
            if use_par(self.n()) {
                (c2..dims[e2]).into_par_iter().step_by(2).for_each(outer);
            } else {
                (c2..dims[e2]).step_by(2).for_each(outer);
            }
        }
    }
}

/// Sub- and super-diagonal slots of the lines along direction `d`.
#[inline]
pub(super) fn line_slots(d: usize) -> (usize, usize) {
    match d {
        0 => (s27(-1, 0, 0), s27(1, 0, 0)),
        1 => (s27(0, -1, 0), s27(0, 1, 0)),
        _ => (s27(0, 0, -1), s27(0, 0, 1)),
    }
}

#[derive(Clone, Copy)]
struct SharedFac(*mut [f64; 2]);
// SAFETY: used only for disjoint writes (one line per task).
unsafe impl Send for SharedFac {}
unsafe impl Sync for SharedFac {}

impl SharedFac {
    #[inline]
    fn get(self) -> *mut [f64; 2] {
        self.0
    }
}
