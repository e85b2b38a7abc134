//! Exact solve on the coarsest level: dense LU with partial pivoting for small grids (no
//! allocation per solve), faer's sparse LU for the rare large coarsest grids (a direction
//! that cannot be coarsened further).

use crate::solve::direct::SparseLu;
use crate::solve::multigrid3d::level::{off27, Level};
use crate::solve::SolveError;
use faer::sparse::Triplet;

/// Coarsest grids up to this many unknowns are factored densely.
const DENSE_MAX: usize = 600;

/// The factored coarsest operator.
pub(super) enum CoarseLu {
    /// Row-major LU factors (unit lower triangle implied) and the row swap of each step.
    Dense {
        n: usize,
        lu: Vec<f64>,
        swap: Vec<usize>,
    },
    Sparse(Box<SparseLu>),
}

impl std::fmt::Debug for CoarseLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CoarseLu::Dense { n, .. } => write!(f, "CoarseLu::Dense({n})"),
            CoarseLu::Sparse(_) => write!(f, "CoarseLu::Sparse"),
        }
    }
}

impl CoarseLu {
    /// Factors the operator of level `lev`.
    pub fn factor(lev: &Level) -> Result<Self, SolveError> {
        let n = lev.n();
        let [nx, ny, nz] = lev.dims;
        let cols = |p: usize| {
            let (i, j, k) = (p % nx, (p / nx) % ny, p / (nx * ny));
            (0..27).filter_map(move |m| {
                let o = off27(m);
                let g = [i as isize + o[0], j as isize + o[1], k as isize + o[2]];
                let ok = g[0] >= 0
                    && g[1] >= 0
                    && g[2] >= 0
                    && (g[0] as usize) < nx
                    && (g[1] as usize) < ny
                    && (g[2] as usize) < nz;
                ok.then(|| (m, g[0] as usize + nx * (g[1] as usize + ny * g[2] as usize)))
            })
        };
        if n > DENSE_MAX {
            let mut t = Vec::with_capacity(27 * n);
            for p in 0..n {
                for (m, c) in cols(p) {
                    let v = lev.coef(p, m);
                    if v != 0.0 {
                        t.push(Triplet::new(p, c, v));
                    }
                }
            }
            return Ok(CoarseLu::Sparse(Box::new(SparseLu::factor(n, &t)?)));
        }
        let mut lu = vec![0.0; n * n];
        for p in 0..n {
            for (m, c) in cols(p) {
                lu[p * n + c] = lev.coef(p, m);
            }
        }
        let mut swap = vec![0; n];
        let scale = lu.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        for c in 0..n {
            let (piv, big) = (c..n)
                .map(|r| (r, lu[r * n + c].abs()))
                .fold((c, -1.0), |b, x| if x.1 > b.1 { x } else { b });
            if big.is_nan() || big <= 1e-14 * scale || !big.is_finite() {
                return Err(SolveError::Singular(format!(
                    "multigrid: singular coarsest operator (pivot {c})"
                )));
            }
            swap[c] = piv;
            if piv != c {
                for t in 0..n {
                    lu.swap(c * n + t, piv * n + t);
                }
            }
            let d = lu[c * n + c];
            let (top, rest) = lu.split_at_mut((c + 1) * n);
            let prow = &top[c * n..];
            for row in rest.chunks_mut(n) {
                let l = row[c] / d;
                if l != 0.0 {
                    row[c] = l;
                    for t in c + 1..n {
                        row[t] -= l * prow[t];
                    }
                }
            }
        }
        Ok(CoarseLu::Dense { n, lu, swap })
    }

    /// `x = A⁻¹ b` (unpadded vectors).
    pub fn solve(&self, b: &[f64], x: &mut [f64]) {
        match self {
            CoarseLu::Sparse(lu) => {
                if lu.solve(b, x).is_err() {
                    x.fill(f64::NAN);
                }
            }
            CoarseLu::Dense { n, lu, swap } => {
                let n = *n;
                x.copy_from_slice(b);
                for (c, &s) in swap.iter().enumerate() {
                    x.swap(c, s);
                }
                for r in 0..n {
                    let row = &lu[r * n..r * n + r];
                    let s: f64 = row.iter().zip(&x[..r]).map(|(l, v)| l * v).sum();
                    x[r] -= s;
                }
                for r in (0..n).rev() {
                    let row = &lu[r * n..(r + 1) * n];
                    let s: f64 = row[r + 1..]
                        .iter()
                        .zip(&x[r + 1..])
                        .map(|(u, v)| u * v)
                        .sum();
                    x[r] = (x[r] - s) / row[r];
                }
            }
        }
    }
}
