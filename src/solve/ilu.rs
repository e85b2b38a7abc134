//! Bi-CGSTAB with an ILU(0) preconditioner for the 19-point systems of a volume Picard step
//! ([`Stencil19`]): [`BiCgStabIlu`] ("bicgstab", the default below
//! [`crate::solve::select::AUTO_MULTIGRID_NODES`] nodes).
//!
//! Bi-CGSTAB (van der Vorst 1992, the Krylov half of the paper's THREED) is
//! right-preconditioned by an incomplete LU factorization without fill, ILU(0), in the natural
//! (i fastest) ordering. ILU(0) of a 19-point operator is exact for purely one-dimensional
//! coupling along any of the three index directions (the three-point lines lie inside the
//! pattern), so the strong wall-normal coupling of clustered walls (aspect ratios 10³–10⁴)
//! costs it little.
//!
//! The other volume solvers behind [`LinearSolver`] are [`crate::solve::direct::DirectLu3`]
//! ("direct": faer's sparse LU, the exact reference) and
//! [`crate::solve::multigrid3d::Multigrid3`] ("multigrid", the 3D black-box multigrid).

use crate::solve::stencil19::{Stencil19, C, OFFSETS};
use crate::solve::{LinearSolver, SolveControl, SolveError, SolveInfo};

/// Bi-CGSTAB right-preconditioned by ILU(0) (module docs).
///
/// The factors are stored in single precision, L and U apart: the preconditioner only
/// steers the Krylov iteration, whose residuals use the f64 operator, so the solution is that
/// of the f64 system; the substitutions read a quarter of the bytes of f64 stencil rows
/// (they are bound by memory traffic). Factored in f64, row by row, with the rows still
/// needed (one plane and one line back) in a ring buffer.
#[derive(Default)]
pub struct BiCgStabIlu {
    a: Option<Stencil19>,
    /// L below the diagonal (unit diagonal implied), slots in [`Plan::lower`] order.
    l: Vec<[f32; 9]>,
    /// U above the diagonal in [`Plan::upper`] order, then 1 / the pivot.
    u: Vec<[f32; 10]>,
    /// Unknowns of the factored operator.
    dims: [usize; 3],
}

impl BiCgStabIlu {
    /// A solver that factors on `setup`.
    pub fn new() -> Self {
        Self::default()
    }
}

/// Lexicographic (k, j, i) order of an offset: its column order for any grid size.
fn lex(o: [i8; 3]) -> (i8, i8, i8) {
    (o[2], o[1], o[0])
}

/// The slots of the ILU(0) elimination of a 19-point row.
struct Plan {
    /// Lower slots in increasing column order.
    lower: [usize; 9],
    /// Upper slots.
    upper: [usize; 9],
    /// For each lower slot, the (upper slot of the pivot row, target slot) pairs that stay
    /// inside the 19-point pattern.
    pairs: [Vec<(usize, usize)>; 9],
}

fn plan() -> &'static Plan {
    static PLAN: std::sync::OnceLock<Plan> = std::sync::OnceLock::new();
    PLAN.get_or_init(|| {
        let zero = (0, 0, 0);
        let mut lower: Vec<usize> = (0..19).filter(|&m| lex(OFFSETS[m]) < zero).collect();
        lower.sort_by_key(|&m| lex(OFFSETS[m]));
        let upper: Vec<usize> = (0..19).filter(|&m| lex(OFFSETS[m]) > zero).collect();
        let pairs = std::array::from_fn(|q| {
            let m1 = lower[q];
            upper
                .iter()
                .filter_map(|&m2| {
                    let (a, b) = (OFFSETS[m1], OFFSETS[m2]);
                    let t = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
                    let slot = OFFSETS.iter().position(|&o| o == t)?;
                    (lex(t) > lex(a)).then_some((m2, slot))
                })
                .collect()
        });
        Plan {
            lower: lower.try_into().expect("9 lower slots"),
            upper: upper.try_into().expect("9 upper slots"),
            pairs,
        }
    })
}

impl BiCgStabIlu {
    /// z = (LU)⁻¹ r: forward and backward substitution (sequential: the recurrence runs
    /// through the whole grid; the coordinates are solved in parallel instead).
    fn precondition(&self, a: &Stencil19, r: &[f64], z: &mut [f64]) {
        let [nx, ny, nz] = a.dims();
        let off = a.linear_offsets();
        let plan = plan();
        let lo: [isize; 9] = plan.lower.map(|m| off[m]);
        let up: [isize; 9] = plan.upper.map(|m| off[m]);
        let interior = |i: usize, j: usize, k: usize| {
            i > 0 && j > 0 && k > 0 && i + 1 < nx && j + 1 < ny && k + 1 < nz
        };
        let mut p = 0;
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let f = &self.l[p];
                    let mut s = r[p];
                    if interior(i, j, k) {
                        for (&fm, &o) in f.iter().zip(&lo) {
                            s -= f64::from(fm) * z[(p as isize + o) as usize];
                        }
                    } else {
                        let ins = a.inside(i, j, k);
                        for ((&fm, &o), &m) in f.iter().zip(&lo).zip(&plan.lower) {
                            if ins[m] {
                                s -= f64::from(fm) * z[(p as isize + o) as usize];
                            }
                        }
                    }
                    z[p] = s;
                    p += 1;
                }
            }
        }
        for k in (0..nz).rev() {
            for j in (0..ny).rev() {
                for i in (0..nx).rev() {
                    p -= 1;
                    let f = &self.u[p];
                    let mut s = z[p];
                    if interior(i, j, k) {
                        for (&fm, &o) in f.iter().zip(&up) {
                            s -= f64::from(fm) * z[(p as isize + o) as usize];
                        }
                    } else {
                        let ins = a.inside(i, j, k);
                        for ((&fm, &o), &m) in f.iter().zip(&up).zip(&plan.upper) {
                            if ins[m] {
                                s -= f64::from(fm) * z[(p as isize + o) as usize];
                            }
                        }
                    }
                    z[p] = s * f64::from(f[9]);
                }
            }
        }
    }

    /// ILU(0) of `a` into the single-precision factors (module docs).
    fn factor(&mut self, a: &Stencil19) -> Result<(), SolveError> {
        let [nx, ny, _] = a.dims();
        let n = a.len();
        let off = a.linear_offsets();
        let plan = plan();
        self.dims = [0; 3]; // no factors until this one is complete
                            // The factored rows still needed: the elimination of row p reads rows down to
                            // p − (nx·ny + nx).
        let ring = (nx * ny + nx + 1).min(n.max(1));
        let mut rows = vec![[0.0f64; 19]; ring];
        self.l.resize(n, [0.0; 9]);
        self.u.resize(n, [0.0; 10]);
        for p in 0..n {
            let ins = a.inside(p % nx, (p / nx) % ny, p / (nx * ny));
            let mut w = a.coefs()[p];
            for (&m1, pairs) in plan.lower.iter().zip(&plan.pairs) {
                if !ins[m1] || w[m1] == 0.0 {
                    continue;
                }
                let q = &rows[(p as isize + off[m1]) as usize % ring];
                let l = w[m1] / q[C];
                w[m1] = l;
                for &(m2, t) in pairs {
                    w[t] -= l * q[m2];
                }
            }
            // A vanishing pivot (lost diagonal dominance) would poison the whole sweep:
            // fall back to the matrix diagonal there.
            if w[C].abs() <= 1e-12 * a.coefs()[p][C].abs() || !w[C].is_finite() {
                w[C] = a.coefs()[p][C];
            }
            if !(w[C].is_finite() && w[C] != 0.0) {
                return Err(SolveError::Singular(format!("zero pivot in row {p}")));
            }
            self.l[p] = plan.lower.map(|m| w[m] as f32);
            let mut u = [0.0f32; 10];
            for (o, &m) in u.iter_mut().zip(&plan.upper) {
                *o = w[m] as f32;
            }
            u[9] = (1.0 / w[C]) as f32;
            self.u[p] = u;
            rows[p % ring] = w;
        }
        self.l.truncate(n);
        self.u.truncate(n);
        self.dims = a.dims();
        Ok(())
    }
}

impl LinearSolver<Stencil19> for BiCgStabIlu {
    fn setup(&mut self, a: &Stencil19) -> Result<(), SolveError> {
        self.factor(a)?;
        self.a = Some(a.clone());
        Ok(())
    }

    /// Keeps the factors of the last setup (of a nearby operator: the preconditioner only
    /// steers the iteration, which solves with `a`).
    fn update(&mut self, a: &Stencil19) -> Result<(), SolveError> {
        if self.dims != a.dims() || self.l.is_empty() {
            return self.setup(a);
        }
        self.a = Some(a.clone());
        Ok(())
    }

    /// Takes the operator over: the Picard system and the solver share one copy. With
    /// `small`, the factors are kept as in [`LinearSolver::update`].
    fn adopt(&mut self, a: &mut Stencil19, small: bool) -> Result<(), SolveError> {
        if !(small && self.dims == a.dims() && !self.l.is_empty()) {
            self.factor(a)?;
        }
        self.a = Some(std::mem::replace(a, Stencil19::zeros(0, 0, 0)));
        Ok(())
    }

    fn give_back(&mut self) -> Option<Stencil19> {
        self.a.take()
    }

    fn solve(&self, b: &[f64], x: &mut [f64], ctl: &SolveControl) -> Result<SolveInfo, SolveError> {
        let a = self.a.as_ref().ok_or(SolveError::NotSetUp)?;
        let n = a.len();
        assert_eq!((b.len(), x.len()), (n, n));
        crate::solve::krylov::bicgstab(
            &mut |v, out| a.apply(v, out),
            &mut |v, out| self.precondition(a, v, out),
            b,
            x,
            ctl,
        )
    }

    fn companion(&self) -> Option<Box<dyn LinearSolver<Stencil19>>> {
        Some(Box::new(BiCgStabIlu::new()))
    }

    fn name(&self) -> &'static str {
        "bicgstab-ilu0"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::direct::DirectLu3;

    /// An anisotropic, non-symmetric 19-point operator like a clustered-wall Picard step.
    fn model(nx: usize, ny: usize, nz: usize, aniso: f64) -> Stencil19 {
        let mut a = Stencil19::zeros(nx, ny, nz);
        for (p, row) in a.coefs_mut().iter_mut().enumerate() {
            let w = 1.0 + 0.3 * ((p as f64) * 0.7).sin();
            let (ax, ay, az) = (1.0, aniso * w, 2.0);
            row[C] = 2.0 * (ax + ay + az);
            row[1] = -(ax - 0.2);
            row[2] = -(ax + 0.2);
            row[3] = -(ay - 0.1 * ay);
            row[4] = -(ay + 0.1 * ay);
            row[5] = -az;
            row[6] = -az;
            for (m, s) in [
                (7, -0.1),
                (8, 0.1),
                (9, 0.1),
                (10, -0.1),
                (15, 0.05),
                (18, 0.05),
            ] {
                row[m] = s;
            }
        }
        a.clip_to_grid();
        a
    }

    #[test]
    fn bicgstab_matches_direct_lu_on_anisotropic_systems() {
        for aniso in [1.0, 1e4] {
            let a = model(9, 7, 6, aniso);
            let xe: Vec<f64> = (0..a.len()).map(|p| (p as f64 * 0.37).sin()).collect();
            let mut b = vec![0.0; a.len()];
            a.apply(&xe, &mut b);
            let mut d = DirectLu3::new();
            d.setup(&a).unwrap();
            let mut xd = vec![0.0; a.len()];
            d.solve(&b, &mut xd, &SolveControl::default()).unwrap();
            let mut s = BiCgStabIlu::new();
            s.setup(&a).unwrap();
            let mut xs = vec![0.0; a.len()];
            let ctl = SolveControl {
                rel_tol: 1e-12,
                max_iter: 200,
            };
            let info = s.solve(&b, &mut xs, &ctl).unwrap();
            assert!(info.converged, "{aniso}: {info:?}");
            assert!(
                info.iterations < 40,
                "{aniso}: {} iterations",
                info.iterations
            );
            for ((u, v), w) in xs.iter().zip(&xd).zip(&xe) {
                assert!((u - w).abs() < 1e-9 && (v - w).abs() < 1e-11, "{u} {v} {w}");
            }
        }
    }

    #[test]
    fn adopted_operator_solves_the_same_and_is_given_back() {
        // 9 x 7 x 6 rows: the factorization's ring of rows (one plane and a line) wraps.
        let a = model(9, 7, 6, 1e3);
        let b: Vec<f64> = (0..a.len()).map(|p| (p as f64 * 0.11).cos()).collect();
        let ctl = SolveControl {
            rel_tol: 1e-12,
            max_iter: 200,
        };
        let mut s = BiCgStabIlu::new();
        s.setup(&a).unwrap();
        let mut x1 = vec![0.0; a.len()];
        s.solve(&b, &mut x1, &ctl).unwrap();
        let mut owned = a.clone();
        let mut t = BiCgStabIlu::new();
        t.adopt(&mut owned, false).unwrap();
        assert!(owned.is_empty(), "the solver holds the only copy");
        let mut x2 = vec![0.0; a.len()];
        t.solve(&b, &mut x2, &ctl).unwrap();
        assert_eq!(x1, x2);
        assert_eq!(t.give_back(), Some(a));
        assert!(matches!(
            t.solve(&b, &mut x2, &ctl),
            Err(SolveError::NotSetUp)
        ));
    }
}
