//! The nine-point operator of a block that is periodic in i (an O-grid's floating cut): the
//! linear systems of one Picard step of [`crate::elliptic::periodic`].
//!
//! A [`Periodic9`] holds the coefficients of a [`Stencil9`] on `nx × ny` unknowns (i fastest),
//! but its i-neighbours wrap around: the west neighbour of column 0 is column `nx − 1` and the
//! east neighbour of column `nx − 1` is column 0 (node i = 0 and node i = N of the block are
//! one node). Only j is bounded: couplings to the rows j = 0 and j = M (the block's E3, E4)
//! are moved to the right-hand side by the assembler.
//!
//! Its solver is the sparse LU of faer ([`DirectLuPeriodic`]): the black-box multigrid of
//! [`crate::solve::multigrid`] coarsens and relaxes with bounded lines in i and is not made
//! periodic.

use crate::solve::direct::{Assemble, SparseDirect};
use crate::solve::stencil9::Stencil9;
use faer::sparse::Triplet;

/// Nine-point operator on `nx × ny` unknowns, periodic in i (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Periodic9 {
    st: Stencil9,
}

/// faer sparse LU of a [`Periodic9`] ("direct-lu"): the solver of periodic blocks.
pub type DirectLuPeriodic = SparseDirect<Periodic9>;

impl Periodic9 {
    /// The zero operator on `nx × ny` unknowns.
    ///
    /// # Panics
    /// If `nx < 3` (the wrapped neighbours of a column would coincide).
    pub fn zeros(nx: usize, ny: usize) -> Self {
        assert!(nx >= 3, "a periodic operator needs at least 3 columns");
        Periodic9 {
            st: Stencil9::zeros(nx, ny),
        }
    }

    /// Unknowns along i (the columns of the period).
    pub fn nx(&self) -> usize {
        self.st.nx()
    }

    /// Unknowns along j.
    pub fn ny(&self) -> usize {
        self.st.ny()
    }

    /// Number of unknowns.
    pub fn len(&self) -> usize {
        self.st.len()
    }

    /// True for an operator without unknowns.
    pub fn is_empty(&self) -> bool {
        self.st.is_empty()
    }

    /// Coefficients of all rows (slot `(di + 1) + 3 (dj + 1)` as in [`Stencil9`]).
    pub fn coefs(&self) -> &[[f64; 9]] {
        self.st.coefs()
    }

    /// Coefficients of all rows, mutable.
    pub fn coefs_mut(&mut self) -> &mut [[f64; 9]] {
        self.st.coefs_mut()
    }

    /// The column `i + di − 1` of the period (`di` in 0..3).
    #[inline]
    pub fn wrap(&self, i: usize, di: usize) -> usize {
        let nx = self.st.nx();
        (i + nx + di - 1) % nx
    }

    /// y = A x.
    pub fn apply(&self, x: &[f64], y: &mut [f64]) {
        let (nx, ny) = (self.nx(), self.ny());
        assert_eq!(x.len(), self.len());
        assert_eq!(y.len(), self.len());
        for j in 0..ny {
            for i in 0..nx {
                let a = &self.coefs()[i + nx * j];
                let mut s = 0.0;
                for dj in 0..3usize {
                    if (j == 0 && dj == 0) || (j + 1 == ny && dj == 2) {
                        continue;
                    }
                    let row = nx * (j + dj - 1);
                    for di in 0..3usize {
                        s += a[di + 3 * dj] * x[row + self.wrap(i, di)];
                    }
                }
                y[i + nx * j] = s;
            }
        }
    }
}

impl Assemble for Periodic9 {
    fn order(&self) -> usize {
        self.len()
    }

    fn triplets(&self) -> Vec<Triplet<usize, usize, f64>> {
        let (nx, ny) = (self.nx(), self.ny());
        let mut t = Vec::with_capacity(9 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let p = i + nx * j;
                let a = &self.coefs()[p];
                for dj in 0..3usize {
                    if (j == 0 && dj == 0) || (j + 1 == ny && dj == 2) {
                        continue;
                    }
                    for di in 0..3usize {
                        // zeros too: the pattern stays the same from step to step
                        let v = a[di + 3 * dj];
                        t.push(Triplet::new(p, self.wrap(i, di) + nx * (j + dj - 1), v));
                    }
                }
            }
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::{LinearSolver, SolveControl};

    #[test]
    fn the_lu_solves_a_system_that_wraps_around_in_i() {
        let (nx, ny) = (6, 4);
        let mut a = Periodic9::zeros(nx, ny);
        for (p, row) in a.coefs_mut().iter_mut().enumerate() {
            *row = [
                -0.2,
                -1.0,
                -0.1,
                -1.1,
                5.0 + 0.01 * p as f64,
                -0.9,
                -0.1,
                -1.0,
                -0.2,
            ];
        }
        // The stencil of column 0 reaches column nx − 1 and back: a known answer through apply.
        let xe: Vec<f64> = (0..nx * ny).map(|p| (0.7 * p as f64).cos()).collect();
        let mut b = vec![0.0; nx * ny];
        a.apply(&xe, &mut b);
        let p = nx; // (0, 1)
        let want: f64 = (0..9)
            .map(|k| {
                let (di, dj) = (k % 3, k / 3);
                let col = (di + nx - 1) % nx; // di = 0: column nx − 1
                a.coefs()[p][k] * xe[col + nx * dj]
            })
            .sum();
        assert!((b[p] - want).abs() < 1e-14, "{} vs {want}", b[p]);
        let mut s = DirectLuPeriodic::new();
        s.setup(&a).unwrap();
        let mut x = vec![0.0; nx * ny];
        s.solve(&b, &mut x, &SolveControl::default()).unwrap();
        for (u, v) in x.iter().zip(&xe) {
            assert!((u - v).abs() < 1e-13);
        }
    }
}
