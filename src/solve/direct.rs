//! Sparse direct reference solver: faer's sparse LU of the assembled nine-point matrix.
//!
//! Exact to round-off, so it is the reference the iterative solvers are checked against in
//! tests; its memory grows like N^1.5 log N, so it suits grids up to a few 10⁵ nodes.

use crate::solve::stencil9::Stencil9;
use crate::solve::{LinearSolver, SolveControl, SolveError, SolveInfo};
use faer::linalg::solvers::Solve;
use faer::sparse::{linalg::solvers::Lu, SparseColMat, Triplet};

/// A factored sparse matrix: faer's LU, shared by the 2D and 3D direct solvers.
pub struct SparseLu {
    lu: Lu<usize, f64>,
    n: usize,
}

impl SparseLu {
    /// Factors the n × n matrix given as triplets (row, column, value).
    pub fn factor(n: usize, t: &[Triplet<usize, usize, f64>]) -> Result<Self, SolveError> {
        let m = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, t)
            .map_err(|e| SolveError::Singular(format!("{e:?}")))?;
        let lu = m
            .sp_lu()
            .map_err(|e| SolveError::Singular(format!("{e:?}")))?;
        Ok(SparseLu { lu, n })
    }

    /// x = A⁻¹ b.
    pub fn solve(&self, b: &[f64], x: &mut [f64]) -> Result<SolveInfo, SolveError> {
        assert_eq!(b.len(), self.n);
        x.copy_from_slice(b);
        self.lu
            .solve_in_place(faer::MatMut::from_column_major_slice_mut(x, self.n, 1));
        if x.iter().any(|v| !v.is_finite()) {
            return Err(SolveError::Singular("non-finite solution".into()));
        }
        Ok(SolveInfo {
            iterations: 1,
            residual_history: vec![],
            converged: true,
        })
    }
}

/// faer sparse LU of a [`Stencil9`].
#[derive(Default)]
pub struct DirectLu {
    lu: Option<SparseLu>,
}

impl DirectLu {
    /// A solver that factors on `setup`.
    pub fn new() -> Self {
        Self::default()
    }
}

/// The stencil as a sparse matrix in faer's triplet form.
fn triplets(a: &Stencil9) -> Vec<Triplet<usize, usize, f64>> {
    let (nx, ny) = (a.nx(), a.ny());
    let mut t = Vec::with_capacity(9 * nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            let p = i + nx * j;
            for dj in 0..3usize {
                for di in 0..3usize {
                    let v = a.row(i, j)[di + 3 * dj];
                    let (ii, jj) = ((i + di) as isize - 1, (j + dj) as isize - 1);
                    if v != 0.0 && ii >= 0 && jj >= 0 && (ii as usize) < nx && (jj as usize) < ny {
                        t.push(Triplet::new(p, ii as usize + nx * jj as usize, v));
                    }
                }
            }
        }
    }
    t
}

impl LinearSolver for DirectLu {
    fn setup(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.lu = Some(SparseLu::factor(a.len(), &triplets(a))?);
        Ok(())
    }

    fn solve(
        &self,
        b: &[f64],
        x: &mut [f64],
        _ctl: &SolveControl,
    ) -> Result<SolveInfo, SolveError> {
        self.lu.as_ref().ok_or(SolveError::NotSetUp)?.solve(b, x)
    }

    fn name(&self) -> &'static str {
        "direct-lu"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_nine_point_system() {
        let (nx, ny) = (7, 5);
        let mut a = Stencil9::zeros(nx, ny);
        for (p, row) in a.coefs_mut().iter_mut().enumerate() {
            *row = [
                -0.25,
                -1.0,
                -0.1,
                -1.2,
                5.0 + p as f64 * 0.01,
                -0.8,
                -0.1,
                -1.0,
                -0.25,
            ];
        }
        a.clip_to_grid();
        let xe: Vec<f64> = (0..nx * ny).map(|p| (p as f64 * 0.37).sin()).collect();
        let mut b = vec![0.0; nx * ny];
        a.apply(&xe, &mut b);
        let mut s = DirectLu::new();
        s.setup(&a).unwrap();
        let mut x = vec![0.0; nx * ny];
        s.solve(&b, &mut x, &SolveControl::default()).unwrap();
        for (u, v) in x.iter().zip(&xe) {
            assert!((u - v).abs() < 1e-13);
        }
    }
}
