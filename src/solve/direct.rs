//! Sparse direct reference solvers: faer's sparse LU of the assembled nine-point ([`DirectLu`],
//! 2D) or 19-point ([`DirectLu3`], volume blocks) matrix, one wrapper ([`SparseDirect`]) over
//! both stencils.
//!
//! Exact to round-off, so they are the reference the iterative solvers are checked against in
//! tests; the memory grows like N^1.5 log N in 2D, and the fill like N^{4/3} in 3D, so they
//! suit grids up to a few 10⁵ nodes and volume blocks below ~40³ nodes.

use std::marker::PhantomData;

use crate::solve::stencil19::Stencil19;
use crate::solve::stencil9::Stencil9;
use crate::solve::{LinearSolver, SolveControl, SolveError, SolveInfo};
use faer::linalg::solvers::Solve;
use faer::sparse::{linalg::solvers::Lu, SparseColMat, Triplet};

/// faer splits its factorization and triangular solves into as many tasks as its global
/// parallelism says; by default that is rayon's thread count, and the factors' last bits then
/// follow `RAYON_NUM_THREADS`. A fixed two-way split (run one after the other on one thread)
/// keeps the direct solver's results the same whatever the thread count (faer serves only this
/// solver in ellipgrid).
fn fixed_partition() {
    static SET: std::sync::Once = std::sync::Once::new();
    SET.call_once(|| faer::set_global_parallelism(faer::Par::rayon(2)));
}

/// Estimated peak memory of faer's sparse LU of `unknowns` unknowns of a nine-point (`dim`
/// 2) or 19-point (`dim` 3) operator, in bytes: 250 N log₂ N in 2D, 120 N^1.55 in 3D. The
/// measured peaks (`examples/bench_direct_memory.rs`) lie below it at every size measured:
/// 2D from 65² (10 MB, 0.95× of 200 N log₂ N) to 1025² (4.5 GB, 0.93×); 3D from 13³ (7 MB)
/// to 49³ (6.7 GB, 0.95× of 120 N^1.55). A volume block of 81³ nodes would need ~80 GB.
pub fn lu_bytes(unknowns: usize, dim: usize) -> u64 {
    let n = unknowns as f64;
    let b = if dim == 2 {
        250.0 * n * n.log2().max(1.0)
    } else {
        120.0 * n.powf(1.55)
    };
    b as u64
}

/// A factored sparse matrix: faer's LU, shared by the 2D and 3D direct solvers.
pub struct SparseLu {
    lu: Lu<usize, f64>,
    n: usize,
}

impl SparseLu {
    /// Factors the n × n matrix given as triplets (row, column, value).
    pub fn factor(n: usize, t: &[Triplet<usize, usize, f64>]) -> Result<Self, SolveError> {
        fixed_partition();
        use faer::sparse::{linalg::LuError, CreationError, FaerError};
        let oom = |e: &dyn std::fmt::Debug| SolveError::OutOfMemory {
            unknowns: n,
            what: format!("ran out of memory ({e:?})"),
        };
        let m =
            SparseColMat::<usize, f64>::try_new_from_triplets(n, n, t).map_err(|e| match e {
                CreationError::Generic(FaerError::OutOfMemory) => oom(&e),
                _ => SolveError::Singular(format!("{e:?}")),
            })?;
        let lu = m.sp_lu().map_err(|e| match e {
            LuError::Generic(FaerError::OutOfMemory) => oom(&e),
            _ => SolveError::Singular(format!("{e:?}")),
        })?;
        Ok(SparseLu { lu, n })
    }

    /// x = A⁻¹ b.
    pub fn solve(&self, b: &[f64], x: &mut [f64]) -> Result<SolveInfo, SolveError> {
        fixed_partition();
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

/// A structured operator as a sparse matrix: its order and its nonzero entries.
pub trait Assemble {
    /// Number of unknowns (rows and columns).
    fn order(&self) -> usize;

    /// The nonzero entries inside the grid in faer's triplet form (row, column, value).
    fn triplets(&self) -> Vec<Triplet<usize, usize, f64>>;
}

impl Assemble for Stencil9 {
    fn order(&self) -> usize {
        self.len()
    }

    fn triplets(&self) -> Vec<Triplet<usize, usize, f64>> {
        let (nx, ny) = (self.nx(), self.ny());
        let mut t = Vec::with_capacity(9 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let p = i + nx * j;
                for dj in 0..3usize {
                    for di in 0..3usize {
                        let v = self.row(i, j)[di + 3 * dj];
                        let (ii, jj) = ((i + di) as isize - 1, (j + dj) as isize - 1);
                        if v != 0.0
                            && ii >= 0
                            && jj >= 0
                            && (ii as usize) < nx
                            && (jj as usize) < ny
                        {
                            t.push(Triplet::new(p, ii as usize + nx * jj as usize, v));
                        }
                    }
                }
            }
        }
        t
    }
}

impl Assemble for Stencil19 {
    fn order(&self) -> usize {
        self.len()
    }

    fn triplets(&self) -> Vec<Triplet<usize, usize, f64>> {
        let [nx, ny, _] = self.dims();
        let off = self.linear_offsets();
        let mut t = Vec::with_capacity(19 * self.len());
        for (p, row) in self.coefs().iter().enumerate() {
            let ins = self.inside(p % nx, (p / nx) % ny, p / (nx * ny));
            for m in 0..19 {
                if ins[m] && row[m] != 0.0 {
                    t.push(Triplet::new(p, (p as isize + off[m]) as usize, row[m]));
                }
            }
        }
        t
    }
}

/// faer sparse LU of a structured operator `S`, factored on `setup`: [`DirectLu`] for a
/// [`Stencil9`], [`DirectLu3`] for a [`Stencil19`].
pub struct SparseDirect<S> {
    lu: Option<SparseLu>,
    op: PhantomData<fn(&S)>,
}

/// faer sparse LU of a [`Stencil9`] ("direct").
pub type DirectLu = SparseDirect<Stencil9>;

/// faer sparse LU of a [`Stencil19`] ("direct" for volume blocks): exact, for tests and small
/// blocks.
pub type DirectLu3 = SparseDirect<Stencil19>;

impl<S> Default for SparseDirect<S> {
    fn default() -> Self {
        SparseDirect {
            lu: None,
            op: PhantomData,
        }
    }
}

impl<S: Assemble> SparseDirect<S> {
    /// A solver that factors on `setup`.
    pub fn new() -> Self {
        Self::default()
    }

    /// Factors `a` (the solver's `setup`).
    fn factor(&mut self, a: &S) -> Result<(), SolveError> {
        self.lu = Some(SparseLu::factor(a.order(), &a.triplets())?);
        Ok(())
    }

    /// x = A⁻¹ b for the operator of the last `setup`.
    fn apply(&self, b: &[f64], x: &mut [f64]) -> Result<SolveInfo, SolveError> {
        self.lu.as_ref().ok_or(SolveError::NotSetUp)?.solve(b, x)
    }
}

impl<S: Assemble + Send + Sync + 'static> LinearSolver<S> for SparseDirect<S> {
    fn setup(&mut self, a: &S) -> Result<(), SolveError> {
        self.factor(a)
    }

    fn companion(&self) -> Option<Box<dyn LinearSolver<S>>> {
        Some(Box::new(Self::new()))
    }

    fn solve(
        &self,
        b: &[f64],
        x: &mut [f64],
        _ctl: &SolveControl,
    ) -> Result<SolveInfo, SolveError> {
        self.apply(b, x)
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
