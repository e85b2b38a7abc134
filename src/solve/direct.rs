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
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::{linalg::lu, SparseColMat, Triplet};

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

/// A factored sparse matrix: faer's LU, shared by the 2D and 3D direct solvers. It keeps
/// the symbolic factorization (fill-reducing ordering, elimination structure) and the
/// numeric factors' storage, so that [`SparseLu::refactor`] of a matrix with the same
/// sparsity pattern (the next Picard step's operator) only redoes the numeric part.
pub struct SparseLu {
    symbolic: lu::SymbolicLu<usize>,
    numeric: lu::NumericLu<usize, f64>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    n: usize,
}

/// The error of a failed factorization step of n unknowns.
fn lu_error(n: usize, e: &dyn std::fmt::Debug, oom: bool) -> SolveError {
    if oom {
        SolveError::OutOfMemory {
            unknowns: n,
            what: format!("ran out of memory ({e:?})"),
        }
    } else {
        SolveError::Singular(format!("{e:?}"))
    }
}

impl SparseLu {
    /// Factors the n × n matrix given as triplets (row, column, value).
    pub fn factor(n: usize, t: &[Triplet<usize, usize, f64>]) -> Result<Self, SolveError> {
        fixed_partition();
        let m = Self::matrix(n, t)?;
        let symbolic = Self::analyse(&m)?;
        let mut lu = SparseLu {
            symbolic,
            numeric: lu::NumericLu::new(),
            col_ptr: m.symbolic().col_ptr().to_vec(),
            row_idx: m.symbolic().row_idx().to_vec(),
            n,
        };
        lu.numeric_factor(&m)?;
        Ok(lu)
    }

    /// Factors the matrix `t` (of the same order) in place of this one: the symbolic
    /// factorization is kept when the sparsity pattern is the same, and the numeric
    /// factors' storage is reused.
    pub fn refactor(&mut self, t: &[Triplet<usize, usize, f64>]) -> Result<(), SolveError> {
        fixed_partition();
        let m = Self::matrix(self.n, t)?;
        let s = m.symbolic();
        if s.col_ptr() != self.col_ptr.as_slice() || s.row_idx() != self.row_idx.as_slice() {
            self.symbolic = Self::analyse(&m)?;
            self.col_ptr = s.col_ptr().to_vec();
            self.row_idx = s.row_idx().to_vec();
        }
        self.numeric_factor(&m)
    }

    fn matrix(
        n: usize,
        t: &[Triplet<usize, usize, f64>],
    ) -> Result<SparseColMat<usize, f64>, SolveError> {
        use faer::sparse::{CreationError, FaerError};
        SparseColMat::<usize, f64>::try_new_from_triplets(n, n, t).map_err(|e| {
            let oom = matches!(e, CreationError::Generic(FaerError::OutOfMemory));
            lu_error(n, &e, oom)
        })
    }

    fn analyse(m: &SparseColMat<usize, f64>) -> Result<lu::SymbolicLu<usize>, SolveError> {
        lu::factorize_symbolic_lu(m.symbolic(), Default::default()).map_err(|e| {
            let oom = matches!(e, faer::sparse::FaerError::OutOfMemory);
            lu_error(m.nrows(), &e, oom)
        })
    }

    fn numeric_factor(&mut self, m: &SparseColMat<usize, f64>) -> Result<(), SolveError> {
        use faer::sparse::{linalg::LuError, FaerError};
        let par = faer::get_global_parallelism();
        let n = self.n;
        let req = self
            .symbolic
            .factorize_numeric_lu_scratch::<f64>(par, Default::default());
        let mut mem = MemBuffer::try_new(req).map_err(|e| lu_error(n, &e, true))?;
        self.symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                m.as_ref(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map(|_| ())
            .map_err(|e| {
                let oom = matches!(e, LuError::Generic(FaerError::OutOfMemory));
                lu_error(n, &e, oom)
            })
    }

    /// x = A⁻¹ b.
    pub fn solve(&self, b: &[f64], x: &mut [f64]) -> Result<SolveInfo, SolveError> {
        fixed_partition();
        assert_eq!(b.len(), self.n);
        x.copy_from_slice(b);
        let par = faer::get_global_parallelism();
        let req = self.symbolic.solve_in_place_scratch::<f64>(1, par);
        lu::LuRef::new_unchecked(&self.symbolic, &self.numeric).solve_in_place_with_conj(
            faer::Conj::No,
            faer::MatMut::from_column_major_slice_mut(x, self.n, 1),
            par,
            MemStack::new(&mut MemBuffer::new(req)),
        );
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
                        // zeros too: the pattern stays the same from step to step
                        if ii >= 0 && jj >= 0 && (ii as usize) < nx && (jj as usize) < ny {
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
                if ins[m] {
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
        let t = a.triplets();
        match self.lu.as_mut() {
            Some(lu) if lu.n == a.order() => {
                if let Err(e) = lu.refactor(&t) {
                    self.lu = None;
                    return Err(e);
                }
            }
            _ => {
                self.lu = None; // the old factors go before the new ones are made
                self.lu = Some(SparseLu::factor(a.order(), &t)?);
            }
        }
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

    /// A nine-point operator whose values depend on `k`; its corner coefficients are zero
    /// when `zero_corners`.
    fn operator(nx: usize, ny: usize, k: f64, zero_corners: bool) -> Stencil9 {
        let mut a = Stencil9::zeros(nx, ny);
        for (p, row) in a.coefs_mut().iter_mut().enumerate() {
            let c = if zero_corners { 0.0 } else { -0.1 - 0.05 * k };
            let q = p as f64;
            *row = [
                c,
                -1.0 - 0.1 * k,
                c,
                -1.2,
                5.0 + q * 0.01 * k,
                -0.8,
                c,
                -1.0,
                c,
            ];
        }
        a.clip_to_grid();
        a
    }

    #[test]
    fn refactoring_reuses_the_pattern_and_solves_each_new_matrix_exactly() {
        let (nx, ny) = (9, 6);
        let xe: Vec<f64> = (0..nx * ny).map(|p| (p as f64 * 0.37).sin()).collect();
        let mut s = DirectLu::new();
        // New values on the same pattern, then zero corners (the same pattern: structural
        // zeros are kept), then a new order: every solve is exact for its own matrix.
        for (k, zero, n) in [
            (1.0, false, nx),
            (2.0, false, nx),
            (3.0, true, nx),
            (1.5, false, 5),
        ] {
            let a = operator(n, ny, k, zero);
            let mut b = vec![0.0; n * ny];
            a.apply(&xe[..n * ny], &mut b);
            s.setup(&a).unwrap();
            let mut x = vec![0.0; n * ny];
            s.solve(&b, &mut x, &SolveControl::default()).unwrap();
            for (u, v) in x.iter().zip(&xe) {
                assert!((u - v).abs() < 1e-13, "k = {k}: {u} vs {v}");
            }
            let lu = s.lu.as_ref().unwrap();
            assert_eq!(
                lu.row_idx.len(),
                9 * n * ny - 6 * (n + ny) + 4,
                "structural zeros kept"
            );
        }
    }
}
