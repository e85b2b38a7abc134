//! Direct solve on the coarsest grid: banded LU with partial pivoting (LAPACK `gbtrf` layout).
//!
//! The unknowns are ordered along the longer grid direction first, so the half bandwidth is
//! `min(nx, ny) + 1`; the cost is `n · bw²`, small for the few nodes of a coarsest grid (and
//! still cheap for long thin grids that stop coarsening at one line).

use crate::solve::SolveError;

/// Largest band storage (in f64) the coarsest solve accepts.
const MAX_BAND_STORAGE: usize = 50_000_000;

/// Banded LU of a nine-point operator.
#[derive(Clone, Debug, Default)]
pub(super) struct BandLu {
    nx: usize,
    ny: usize,
    /// Ordering `q = j + ny i` (instead of `i + nx j`).
    transposed: bool,
    n: usize,
    kl: usize,
    ld: usize,
    ab: Vec<f64>,
    piv: Vec<usize>,
}

impl BandLu {
    #[inline]
    fn at(&self, i: usize, j: usize) -> usize {
        // A(i, j) for j − kv ≤ i ≤ j + kl, kv = 2 kl
        j * self.ld + (2 * self.kl + i) - j
    }

    #[inline]
    fn order(&self, i: usize, j: usize) -> usize {
        if self.transposed {
            j + self.ny * i
        } else {
            i + self.nx * j
        }
    }

    /// Factors the `nx × ny` operator `a` (storage reused when the size is unchanged).
    pub(super) fn factor(
        &mut self,
        a: &[[f64; 9]],
        nx: usize,
        ny: usize,
    ) -> Result<(), SolveError> {
        let n = nx * ny;
        self.nx = nx;
        self.ny = ny;
        self.n = n;
        self.transposed = nx > ny;
        self.kl = nx.min(ny) + 1;
        let kl = self.kl;
        self.ld = 3 * kl + 1;
        if n.saturating_mul(self.ld) > MAX_BAND_STORAGE {
            return Err(SolveError::Singular(format!(
                "multigrid: coarsest grid {nx}×{ny} too large for the banded direct solve \
                 (raise max_levels or lower coarse_enough)"
            )));
        }
        self.ab.clear();
        self.ab.resize(n * self.ld, 0.0);
        self.piv.resize(n, 0);
        for j in 0..ny {
            for i in 0..nx {
                let row = self.order(i, j);
                let m = &a[i + nx * j];
                for dj in -1isize..=1 {
                    for di in -1isize..=1 {
                        let (ii, jj) = (i as isize + di, j as isize + dj);
                        if ii < 0 || jj < 0 || ii >= nx as isize || jj >= ny as isize {
                            continue;
                        }
                        let col = self.order(ii as usize, jj as usize);
                        let idx = self.at(row, col);
                        self.ab[idx] = m[((di + 1) + 3 * (dj + 1)) as usize];
                    }
                }
            }
        }
        let kv = 2 * kl;
        for c in 0..n {
            let km = kl.min(n - 1 - c);
            let mut p = c;
            let mut best = self.ab[self.at(c, c)].abs();
            for r in c + 1..=c + km {
                let v = self.ab[self.at(r, c)].abs();
                if v > best {
                    best = v;
                    p = r;
                }
            }
            self.piv[c] = p;
            if !(best > 0.0 && best.is_finite()) {
                return Err(SolveError::Singular(format!(
                    "multigrid: coarsest-grid operator {nx}×{ny} is singular (pivot {c})"
                )));
            }
            let last = (c + kv).min(n - 1);
            if p != c {
                for j in c..=last {
                    let (x, y) = (self.at(c, j), self.at(p, j));
                    self.ab.swap(x, y);
                }
            }
            let d = 1.0 / self.ab[self.at(c, c)];
            for r in c + 1..=c + km {
                let idx = self.at(r, c);
                self.ab[idx] *= d;
            }
            for j in c + 1..=last {
                let u = self.ab[self.at(c, j)];
                if u == 0.0 {
                    continue;
                }
                for r in c + 1..=c + km {
                    let l = self.ab[self.at(r, c)];
                    let idx = self.at(r, j);
                    self.ab[idx] -= l * u;
                }
            }
        }
        Ok(())
    }

    /// Length of the scratch vector [`BandLu::solve`] needs.
    pub(super) fn scratch_len(&self) -> usize {
        self.n
    }

    /// Solves `A x = b` for the unpadded vectors of the grid; `x` and `b` may not alias.
    pub(super) fn solve(&self, b: &[f64], x: &mut [f64], w: &mut [f64]) {
        let (n, kl) = (self.n, self.kl);
        let kv = 2 * kl;
        let w = &mut w[..n];
        for j in 0..self.ny {
            for i in 0..self.nx {
                w[self.order(i, j)] = b[i + self.nx * j];
            }
        }
        for c in 0..n {
            let p = self.piv[c];
            if p != c {
                w.swap(c, p);
            }
            let v = w[c];
            let end = (c + kl).min(n - 1);
            if end > c {
                // column c of L below the diagonal is contiguous in the band storage
                let l = &self.ab[self.at(c + 1, c)..=self.at(end, c)];
                for (wr, l) in w[c + 1..=end].iter_mut().zip(l) {
                    *wr -= l * v;
                }
            }
        }
        for c in (0..n).rev() {
            let v = w[c] / self.ab[self.at(c, c)];
            w[c] = v;
            let start = c.saturating_sub(kv);
            if start < c {
                let u = &self.ab[self.at(start, c)..self.at(c, c)];
                for (wr, u) in w[start..c].iter_mut().zip(u) {
                    *wr -= u * v;
                }
            }
        }
        for j in 0..self.ny {
            for i in 0..self.nx {
                x[i + self.nx * j] = w[self.order(i, j)];
            }
        }
    }
}
