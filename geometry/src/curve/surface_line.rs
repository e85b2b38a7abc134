//! A curve on a surface: a polyline in the surface's parameters (u, v) mapped onto it, the
//! usual way CAD gives an edge that lies on a face (an iso-parameter line, or a straight line
//! in (u, v)).

use super::Curve;
use crate::{GeometryError, Surface, Vec3};

/// x(t) = S(w(t)) with w the polyline through `uv`, each of its n segments taking an equal
/// share 1/n of t ∈ [0, 1].
pub struct SurfaceLine<S> {
    surface: S,
    uv: Vec<(f64, f64)>,
}

impl<S: Surface> SurfaceLine<S> {
    /// The line through at least two finite parameter points, no two successive ones equal.
    pub fn new(surface: S, uv: Vec<(f64, f64)>) -> Result<Self, GeometryError> {
        if uv.len() < 2 {
            return Err(GeometryError::Invalid(format!(
                "surface line: {} parameter point(s), need at least 2",
                uv.len()
            )));
        }
        for (k, w) in uv.windows(2).enumerate() {
            if !(w[0].0.is_finite()
                && w[0].1.is_finite()
                && w[1].0.is_finite()
                && w[1].1.is_finite())
                || w[0] == w[1]
            {
                return Err(GeometryError::Invalid(format!(
                    "surface line: parameter points {k} and {} are equal or not finite",
                    k + 1
                )));
            }
        }
        Ok(SurfaceLine { surface, uv })
    }

    /// The segment holding t and the local parameter in it.
    fn at(&self, t: f64) -> (usize, f64) {
        let n = self.uv.len() - 1;
        let x = t.clamp(0.0, 1.0) * n as f64;
        let k = (x.floor() as usize).min(n - 1);
        (k, x - k as f64)
    }
}

impl<S: Surface> Curve for SurfaceLine<S> {
    fn point(&self, t: f64) -> Vec3 {
        let (k, s) = self.at(t);
        let (a, b) = (self.uv[k], self.uv[k + 1]);
        self.surface
            .point(a.0 + s * (b.0 - a.0), a.1 + s * (b.1 - a.1))
    }

    fn derivative(&self, t: f64) -> Vec3 {
        let (k, s) = self.at(t);
        let (a, b) = (self.uv[k], self.uv[k + 1]);
        let n = (self.uv.len() - 1) as f64;
        let p = self
            .surface
            .eval(a.0 + s * (b.0 - a.0), a.1 + s * (b.1 - a.1));
        (p.xu * (b.0 - a.0) + p.xv * (b.1 - a.1)) * n
    }

    fn breakpoints(&self) -> Vec<f64> {
        let n = self.uv.len() - 1;
        let (bu, bv) = self.surface.breaks();
        let mut out: Vec<f64> = (1..n).map(|k| k as f64 / n as f64).collect();
        // Where a segment crosses a knot line of the surface.
        for k in 0..n {
            let (a, b) = (self.uv[k], self.uv[k + 1]);
            for (lines, (pa, pb)) in [(&bu, (a.0, b.0)), (&bv, (a.1, b.1))] {
                for &x in lines.iter() {
                    let s = (x - pa) / (pb - pa);
                    if s > 0.0 && s < 1.0 {
                        out.push((k as f64 + s) / n as f64);
                    }
                }
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Plane;

    #[test]
    fn a_line_on_a_plane_is_straight_and_its_derivative_matches() {
        let p = Plane {
            origin: Vec3::new(1.0, 0.0, 0.0),
            du: Vec3::new(2.0, 0.0, 0.0),
            dv: Vec3::new(0.0, 3.0, 0.0),
        };
        let c = SurfaceLine::new(&p, vec![(0.0, 0.0), (0.5, 0.5), (1.0, 0.5)]).unwrap();
        assert_eq!(c.point(0.5), Vec3::new(2.0, 1.5, 0.0));
        assert_eq!(c.point(1.0), Vec3::new(3.0, 1.5, 0.0));
        let h = 1e-6;
        for t in [0.1, 0.3, 0.7, 0.9] {
            let fd = (c.point(t + h) - c.point(t - h)) / (2.0 * h);
            assert!((fd - c.derivative(t)).norm() < 1e-8);
        }
        assert_eq!(c.breakpoints(), vec![0.5]);
        assert!(SurfaceLine::new(&p, vec![(0.0, 0.0)]).is_err());
        assert!(SurfaceLine::new(&p, vec![(0.0, 0.0), (0.0, 0.0)]).is_err());
    }
}
