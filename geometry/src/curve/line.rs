//! Straight segment.

use super::Curve;
use crate::Vec3;

/// The straight segment x(u) = from + u (to − from).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// Start point (u = 0).
    pub from: Vec3,
    /// End point (u = 1).
    pub to: Vec3,
}

impl Line {
    /// The segment from `from` to `to`.
    pub fn new(from: Vec3, to: Vec3) -> Line {
        Line { from, to }
    }
}

impl Curve for Line {
    fn point(&self, u: f64) -> Vec3 {
        // Written so that u = 0 and u = 1 give the end points exactly.
        self.from * (1.0 - u) + self.to * u
    }

    fn derivative(&self, _u: f64) -> Vec3 {
        self.to - self.from
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn end_points_exact_and_derivative() {
        let l = Line::new(Vec3::new(0.1, 0.7, -0.3), Vec3::new(1.3, -2.9, 0.3));
        assert_eq!(l.point(0.0), l.from);
        assert_eq!(l.point(1.0), l.to);
        let mid = l.point(0.25);
        assert!((mid - (l.from + 0.25 * (l.to - l.from))).norm() < 1e-15);
        assert_eq!(l.derivative(0.4), l.to - l.from);
    }
}
