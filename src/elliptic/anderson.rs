//! Anderson acceleration of the Picard iteration [43, 44] (Walker & Ni 2011, "type II"),
//! in correction form.
//!
//! The Picard step is a fixed-point map x ↦ G(x) = x + f(x), f the (inexactly solved)
//! correction. With the last `m` differences of corrections ΔF = [f_{i+1} − f_i] and of
//! iterates ΔX = [x_{i+1} − x_i], Anderson's step is
//!
//!   γ = argmin ‖f_k − ΔF γ‖₂,   x_{k+1} = x_k + f_k − (ΔX + ΔF) γ,
//!
//! the combination of the last m + 1 Picard images whose linearised correction is smallest:
//! a GMRES-like acceleration of the Picard contraction (0.3–0.45 per step on strongly
//! stretched blocks) that needs neither the Jacobian of [24] nor more than one correction
//! solve per step. The fixed point is the Picard one: only the path changes.
//!
//! Safeguards: the history restarts when the correction grows (the mixed step did worse
//! than Picard would have) or when the least-squares coefficients are not finite or
//! exceed [`MAX_COEFFICIENT`]; the step that stops the iteration is a plain Picard step (see
//! [`crate::elliptic::picard`]), so the reported error estimate bounds the returned grid's.
//!
//! Memory: the differences are stored in f32 (2m + 2 vectors per coordinate): they only
//! choose the combination; the correction f_k itself is f64, and the fixed point does not
//! depend on them.

use crate::solve::krylov::in_order;
use rayon::prelude::*;
use std::collections::VecDeque;

/// Least-squares coefficients beyond this (in absolute value) mean nearly dependent columns:
/// the history restarts.
pub const MAX_COEFFICIENT: f64 = 1e3;

/// One vector per coordinate (interior numbering).
type Coords = Vec<Vec<f64>>;

/// Anderson's history over the coordinates of one block (interior numbering).
pub(crate) struct Anderson {
    depth: usize,
    /// Columns ΔF (per coordinate), newest last.
    df: VecDeque<Vec<Vec<f32>>>,
    /// Columns ΔX + ΔF = ΔG (per coordinate), newest last.
    dg: VecDeque<Vec<Vec<f32>>>,
    /// Gram matrix ΔFᵀ ΔF, row by row in column order (kept up to date column by column).
    gram: VecDeque<VecDeque<f64>>,
    /// The last raw correction f_{k−1} and the last applied step x_k − x_{k−1}.
    last: Option<(Coords, Coords)>,
    /// Largest |f| of the last step (restart if the correction grows).
    last_size: f64,
}

impl Anderson {
    /// An empty history of `depth` columns.
    pub fn new(depth: usize) -> Self {
        Anderson {
            depth,
            df: VecDeque::new(),
            dg: VecDeque::new(),
            gram: VecDeque::new(),
            last: None,
            last_size: f64::INFINITY,
        }
    }

    /// Forgets the history (the next step is a plain Picard step).
    pub fn restart(&mut self) {
        self.clear_columns();
        self.last = None;
        self.last_size = f64::INFINITY;
    }

    /// Replaces the raw correction `f` (largest entry `size`) by Anderson's step and
    /// remembers both; returns the largest entry of the applied step.
    pub fn mix(&mut self, f: &mut [Vec<f64>], size: f64) -> f64 {
        if size > self.last_size {
            self.restart();
        }
        if let Some((f_prev, step_prev)) = self.last.take() {
            let df: Vec<Vec<f32>> = f
                .par_iter()
                .zip(&f_prev)
                .map(|(a, b)| a.iter().zip(b).map(|(a, b)| (a - b) as f32).collect())
                .collect();
            let dg: Vec<Vec<f32>> = df
                .par_iter()
                .zip(&step_prev)
                .map(|(d, s)| d.iter().zip(s).map(|(d, s)| d + *s as f32).collect())
                .collect();
            if self.df.len() == self.depth {
                self.df.pop_front();
                self.dg.pop_front();
                self.gram.pop_front();
                self.gram.iter_mut().for_each(|row| {
                    row.pop_front();
                });
            }
            let mut row: VecDeque<f64> = self.df.iter().map(|c| dot32(c, &df)).collect();
            row.push_back(dot32(&df, &df));
            for (r, v) in self.gram.iter_mut().zip(&row) {
                r.push_back(*v);
            }
            self.gram.push_back(row);
            self.df.push_back(df);
            self.dg.push_back(dg);
        }
        let raw: Coords = f.to_vec();
        if let Some(gamma) = self.coefficients(f) {
            for (k, g) in gamma.iter().enumerate() {
                f.par_iter_mut().zip(&self.dg[k]).for_each(|(fc, dc)| {
                    fc.iter_mut()
                        .zip(dc)
                        .for_each(|(v, d)| *v -= g * f64::from(*d));
                });
            }
        } else {
            self.clear_columns();
        }
        let applied = f
            .iter()
            .map(|c| c.iter().fold(0.0f64, |m, v| m.max(v.abs())))
            .fold(0.0f64, f64::max);
        self.last = Some((raw, f.to_vec()));
        self.last_size = size;
        applied
    }

    fn clear_columns(&mut self) {
        self.df.clear();
        self.dg.clear();
        self.gram.clear();
    }

    /// γ = argmin ‖f − ΔF γ‖ by the normal equations (m ≤ 10 columns, Cholesky with a
    /// relative diagonal shift), or None if there are no columns or γ is unusable.
    fn coefficients(&self, f: &[Vec<f64>]) -> Option<Vec<f64>> {
        let m = self.df.len();
        if m == 0 {
            return None;
        }
        let mut gram = nalgebra::DMatrix::<f64>::from_fn(m, m, |p, q| self.gram[p][q]);
        let mut rhs = nalgebra::DVector::<f64>::zeros(m);
        for p in 0..m {
            rhs[p] = self.df[p]
                .iter()
                .zip(f)
                .map(|(x, y)| fixed_dot(x, y, |v| *v))
                .sum();
        }
        let scale = (0..m).map(|p| gram[(p, p)]).fold(0.0f64, f64::max);
        if !(scale.is_finite() && scale > 0.0) {
            return None;
        }
        for p in 0..m {
            gram[(p, p)] += 1e-10 * scale;
        }
        let gamma = gram.cholesky()?.solve(&rhs);
        let ok = gamma
            .iter()
            .all(|g| g.is_finite() && g.abs() <= MAX_COEFFICIENT);
        ok.then(|| gamma.iter().copied().collect())
    }
}

/// Σ over coordinates of a · b, accumulated in f64.
fn dot32(a: &[Vec<f32>], b: &[Vec<f32>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| fixed_dot(x, y, |v| f64::from(*v)))
        .sum()
}

/// Σ x_i y_i over fixed chunks of 8192 terms added in chunk order (as
/// [`crate::solve::krylov::dot`]): the same bits whatever the thread count.
fn fixed_dot<T: Sync>(x: &[f32], y: &[T], f: impl Fn(&T) -> f64 + Sync) -> f64 {
    let chunk = |(a, b): (&[f32], &[T])| {
        a.iter()
            .zip(b)
            .map(|(u, v)| f64::from(*u) * f(v))
            .sum::<f64>()
    };
    in_order(x.par_chunks(8192).zip(y.par_chunks(8192)).map(chunk))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The linear map x ↦ G x + b with a slow contraction: Picard needs ~ 40 steps for
    /// 1e-8, Anderson (depth ≥ the number of slow modes) a handful.
    #[test]
    fn anderson_accelerates_a_slow_linear_contraction() {
        let rates = [0.9, 0.7, 0.5, 0.1];
        let b = [1.0, -2.0, 0.5, 3.0];
        let fixed: Vec<f64> = rates.iter().zip(&b).map(|(r, b)| b / (1.0 - r)).collect();
        let run = |depth: usize| {
            let mut x = vec![0.0; 4];
            let mut aa = Anderson::new(depth);
            for k in 0..200 {
                let mut f = vec![(0..4)
                    .map(|i| rates[i] * x[i] + b[i] - x[i])
                    .collect::<Vec<f64>>()];
                let size = f[0].iter().fold(0.0f64, |m, v| m.max(v.abs()));
                if size < 1e-8 {
                    return (k, x);
                }
                if depth > 0 {
                    aa.mix(&mut f, size);
                }
                x.iter_mut().zip(&f[0]).for_each(|(x, f)| *x += f);
            }
            (200, x)
        };
        let (plain, _) = run(0);
        let (accelerated, x) = run(4);
        assert!(plain > 150, "plain Picard took {plain} steps");
        assert!(accelerated <= 12, "Anderson took {accelerated} steps");
        for (x, e) in x.iter().zip(&fixed) {
            assert!((x - e).abs() < 1e-6 * e.abs().max(1.0), "{x} vs {e}");
        }
    }

    #[test]
    fn a_growing_correction_restarts_the_history() {
        let mut aa = Anderson::new(3);
        let mut f = vec![vec![1.0, 0.0]];
        aa.mix(&mut f, 1.0);
        let mut f = vec![vec![0.5, 0.1]];
        aa.mix(&mut f, 0.5);
        assert_eq!(aa.df.len(), 1);
        let mut f = vec![vec![2.0, 0.0]];
        let applied = aa.mix(&mut f, 2.0);
        assert_eq!(aa.df.len(), 0);
        assert_eq!(
            f[0],
            vec![2.0, 0.0],
            "a restart applies the plain correction"
        );
        assert_eq!(applied, 2.0);
    }
}
