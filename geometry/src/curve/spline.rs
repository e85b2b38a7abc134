//! Interpolating C² cubic spline, chord-length parametrization, natural end conditions.
//!
//! On [t_k, t_{k+1}] with h = t_{k+1} − t_k, a = (t_{k+1} − u)/h, b = 1 − a:
//! x(u) = a p_k + b p_{k+1} + h²/6 [(a³ − a) M_k + (b³ − b) M_{k+1}],
//! where the second derivatives M solve the usual tridiagonal system with M_0 = M_n = 0.

use super::{chord_lengths, knot_interval, Curve};
use crate::{GeometryError, Vec3};

/// C² cubic spline through points; u is the normalized cumulative chord length.
#[derive(Debug, Clone, PartialEq)]
pub struct Spline {
    points: Vec<Vec3>,
    knots: Vec<f64>,
    /// Second derivatives d²x/du² at the knots.
    m: Vec<Vec3>,
}

impl Spline {
    /// Natural cubic spline through `points` (two points give a straight line).
    ///
    /// # Errors
    /// Fewer than 2 points, a non-finite point, or a zero-length segment (names the point index).
    pub fn new(points: Vec<Vec3>) -> Result<Spline, GeometryError> {
        let cum = chord_lengths(&points, "spline")?;
        let total = cum[cum.len() - 1];
        let mut knots: Vec<f64> = cum.iter().map(|c| c / total).collect();
        *knots.last_mut().unwrap() = 1.0;
        let m = second_derivatives(&points, &knots);
        Ok(Spline { points, knots, m })
    }

    /// The interpolated points.
    pub fn points(&self) -> &[Vec3] {
        &self.points
    }

    /// Parameter of each point (normalized cumulative chord length).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Second derivative d²x/du² (continuous: the spline is C²).
    pub fn second_derivative(&self, u: f64) -> Vec3 {
        let (k, _, a) = self.locate(u);
        self.m[k] * a + self.m[k + 1] * (1.0 - a)
    }

    /// Interval k, its width h and the weight a = (t_{k+1} − u)/h.
    fn locate(&self, u: f64) -> (usize, f64, f64) {
        let k = knot_interval(&self.knots, u);
        let h = self.knots[k + 1] - self.knots[k];
        (k, h, (self.knots[k + 1] - u) / h)
    }
}

/// Solves h_{k−1} M_{k−1} + 2(h_{k−1} + h_k) M_k + h_k M_{k+1} = 6 (d_k − d_{k−1}) with
/// d_k = (p_{k+1} − p_k)/h_k and M_0 = M_n = 0 (Thomas algorithm; diagonally dominant).
fn second_derivatives(p: &[Vec3], t: &[f64]) -> Vec<Vec3> {
    let n = p.len() - 1;
    let mut m = vec![Vec3::zeros(); n + 1];
    if n < 2 {
        return m;
    }
    let h: Vec<f64> = (0..n).map(|k| t[k + 1] - t[k]).collect();
    let d: Vec<Vec3> = (0..n).map(|k| (p[k + 1] - p[k]) / h[k]).collect();
    // Forward elimination over the unknowns M_1 .. M_{n−1}.
    let mut diag = vec![0.0; n];
    let mut rhs = vec![Vec3::zeros(); n];
    for k in 1..n {
        diag[k] = 2.0 * (h[k - 1] + h[k]);
        rhs[k] = 6.0 * (d[k] - d[k - 1]);
        if k > 1 {
            let f = h[k - 1] / diag[k - 1];
            diag[k] -= f * h[k - 1];
            rhs[k] = rhs[k] - f * rhs[k - 1];
        }
    }
    for k in (1..n).rev() {
        let upper = if k + 1 < n {
            h[k] * m[k + 1]
        } else {
            Vec3::zeros()
        };
        m[k] = (rhs[k] - upper) / diag[k];
    }
    m
}

impl Curve for Spline {
    fn point(&self, u: f64) -> Vec3 {
        let (k, h, a) = self.locate(u);
        let b = 1.0 - a;
        self.points[k] * a
            + self.points[k + 1] * b
            + (self.m[k] * (a * a * a - a) + self.m[k + 1] * (b * b * b - b)) * (h * h / 6.0)
    }

    fn derivative(&self, u: f64) -> Vec3 {
        let (k, h, a) = self.locate(u);
        let b = 1.0 - a;
        (self.points[k + 1] - self.points[k]) / h
            + (self.m[k + 1] * (3.0 * b * b - 1.0) - self.m[k] * (3.0 * a * a - 1.0)) * (h / 6.0)
    }

    fn breakpoints(&self) -> Vec<f64> {
        // The third derivative jumps at the knots.
        self.knots[1..self.knots.len() - 1].to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wavy() -> Vec<Vec3> {
        (0..9)
            .map(|i| {
                let x = i as f64 * 0.37 + 0.05 * (i * i) as f64;
                Vec3::new(x, (1.3 * x).sin(), 0.2 * x * x)
            })
            .collect()
    }

    #[test]
    fn interpolates_points() {
        let pts = wavy();
        let s = Spline::new(pts.clone()).unwrap();
        for (p, &t) in pts.iter().zip(s.knots()) {
            assert!((s.point(t) - p).norm() < 1e-14, "{t}");
        }
        assert_eq!(s.point(0.0), pts[0]);
        assert!((s.point(1.0) - pts[8]).norm() < 1e-14);
    }

    #[test]
    fn c2_at_knots_and_natural_ends() {
        let s = Spline::new(wavy()).unwrap();
        let e = 1e-12;
        for &t in &s.knots()[1..8] {
            let (l, r) = (t - e, t + e);
            // Value, first and second derivatives agree from both sides (to O(e) · bound).
            assert!((s.point(l) - s.point(r)).norm() < 1e-9);
            assert!((s.derivative(l) - s.derivative(r)).norm() < 1e-8);
            assert!((s.second_derivative(l) - s.second_derivative(r)).norm() < 1e-6);
        }
        // The third derivative does jump (it is a spline, not a single cubic).
        let t = s.knots()[4];
        let h = 1e-4;
        let third = |u: f64| (s.second_derivative(u + h) - s.second_derivative(u)) / h;
        assert!((third(t) - third(t - 2.0 * h)).norm() > 1e-3);
        assert!(s.second_derivative(0.0).norm() < 1e-12);
        assert!(s.second_derivative(1.0).norm() < 1e-12);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let s = Spline::new(wavy()).unwrap();
        let h = 1e-6;
        for &u in &[0.03, 0.31, 0.5, 0.77, 0.98] {
            let fd = (s.point(u + h) - s.point(u - h)) / (2.0 * h);
            assert!((fd - s.derivative(u)).norm() < 1e-6 * s.derivative(u).norm());
            let fd2 = (s.derivative(u + h) - s.derivative(u - h)) / (2.0 * h);
            assert!(
                (fd2 - s.second_derivative(u)).norm()
                    < 1e-5 * s.second_derivative(u).norm().max(1.0)
            );
        }
    }

    #[test]
    fn reproduces_a_cubic_exactly_interior() {
        // Points on a straight line at uneven spacing: the spline is that line (M = 0).
        let pts: Vec<Vec3> = [0.0, 0.1, 0.5, 0.6, 2.0]
            .iter()
            .map(|&x| Vec3::new(x, 2.0 * x, 0.0))
            .collect();
        let s = Spline::new(pts).unwrap();
        for &u in &[0.1, 0.33, 0.8] {
            let p = s.point(u);
            assert!((p.y - 2.0 * p.x).abs() < 1e-14);
            assert!((p.x - 2.0 * u).abs() < 1e-14);
        }
        let two = Spline::new(vec![Vec3::zeros(), Vec3::new(1.0, 1.0, 0.0)]).unwrap();
        assert!((two.point(0.5) - Vec3::new(0.5, 0.5, 0.0)).norm() < 1e-15);
    }

    #[test]
    fn rejects_duplicates() {
        let e = Spline::new(vec![Vec3::zeros(), Vec3::x(), Vec3::x(), Vec3::y()]).unwrap_err();
        assert!(e.to_string().contains("points 1 and 2"), "{e}");
    }
}
