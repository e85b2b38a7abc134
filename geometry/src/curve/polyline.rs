//! Piecewise linear curve through points, parametrized by cumulative chord length.

use super::{chord_lengths, knot_interval, Curve};
use crate::{GeometryError, Vec3};

/// Piecewise linear curve; u is the normalized cumulative chord length, so the speed is the
/// constant total length and the interior points are [`Curve::breakpoints`].
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    points: Vec<Vec3>,
    /// Normalized cumulative chord length at each point (first 0, last 1).
    knots: Vec<f64>,
    length: f64,
}

impl Polyline {
    /// Polyline through `points`.
    ///
    /// # Errors
    /// Fewer than 2 points, a non-finite point, or a zero-length segment (the message names the
    /// point index).
    pub fn new(points: Vec<Vec3>) -> Result<Polyline, GeometryError> {
        let cum = chord_lengths(&points, "polyline")?;
        let length = cum[cum.len() - 1];
        let mut knots: Vec<f64> = cum.iter().map(|c| c / length).collect();
        *knots.last_mut().unwrap() = 1.0;
        Ok(Polyline {
            points,
            knots,
            length,
        })
    }

    /// The points it was built from.
    pub fn points(&self) -> &[Vec3] {
        &self.points
    }

    /// Parameter of each point (normalized cumulative chord length).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Total length (exact sum of the segment lengths).
    pub fn length(&self) -> f64 {
        self.length
    }
}

impl Curve for Polyline {
    fn point(&self, u: f64) -> Vec3 {
        let k = knot_interval(&self.knots, u);
        let (t0, t1) = (self.knots[k], self.knots[k + 1]);
        let a = (u - t0) / (t1 - t0);
        if a == 1.0 {
            return self.points[k + 1];
        }
        self.points[k] * (1.0 - a) + self.points[k + 1] * a
    }

    fn derivative(&self, u: f64) -> Vec3 {
        let k = knot_interval(&self.knots, u);
        (self.points[k + 1] - self.points[k]) / (self.knots[k + 1] - self.knots[k])
    }

    fn breakpoints(&self) -> Vec<f64> {
        self.knots[1..self.knots.len() - 1].to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_through_points_at_chord_parameters() {
        let pts = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(3.0, 4.0, 0.0),
            Vec3::new(3.0, 4.0, 5.0),
        ];
        let pl = Polyline::new(pts.clone()).unwrap();
        assert_eq!(pl.length(), 12.0);
        assert_eq!(pl.knots(), &[0.0, 0.25, 7.0 / 12.0, 1.0]);
        for (p, &t) in pts.iter().zip(pl.knots()) {
            assert!((pl.point(t) - p).norm() < 1e-14);
        }
        assert!((pl.point(0.125) - Vec3::new(1.5, 0.0, 0.0)).norm() < 1e-14);
        // Constant speed = total length, direction of the segment.
        assert!((pl.derivative(0.4) - Vec3::new(0.0, 12.0, 0.0)).norm() < 1e-12);
        assert_eq!(pl.breakpoints(), vec![0.25, 7.0 / 12.0]);
    }

    #[test]
    fn errors_name_the_point() {
        let e = Polyline::new(vec![Vec3::zeros()]).unwrap_err();
        assert!(e.to_string().contains("at least 2"));
        let e = Polyline::new(vec![Vec3::zeros(), Vec3::x(), Vec3::x()]).unwrap_err();
        assert!(e.to_string().contains("points 1 and 2"), "{e}");
        let e = Polyline::new(vec![Vec3::zeros(), Vec3::new(f64::NAN, 0.0, 0.0)]).unwrap_err();
        assert!(e.to_string().contains("point 1"), "{e}");
    }
}
