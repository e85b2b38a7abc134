//! Poles on a face's boundary loop: a vertex where the surface's parametrization is singular
//! (a cone's apex, a sphere's pole, a collapsed B-spline side), the loop's (u, v) jumping
//! along the pole there. The pole is then a side of the face of zero length
//! ([`FaceLoop::pole`]).

use super::{CadSurface, FaceLoop, NS};
use ellipgrid_geometry::{Surface, Vec3};

/// The surface's parametrization is singular where one of |x_u|, |x_v| is at most this
/// fraction of the other (a pole: a cone's apex, a sphere's pole, a collapsed B-spline side).
const SINGULAR: f64 = 1e-8;

/// Whether the parametrization of `surface` is singular at `uv` ([`SINGULAR`]), and the
/// parameter (0: u, 1: v) that moves no point there.
pub(super) fn singular(surface: &CadSurface, uv: [f64; 2]) -> Option<usize> {
    let s = surface.eval(uv[0], uv[1]);
    let (a, b) = (s.xu.norm(), s.xv.norm());
    (a.min(b) <= SINGULAR * a.max(b)).then_some(usize::from(b < a))
}

impl FaceLoop<'_> {
    /// Whether the loop runs through a pole at the start of edge `k` (its (u, v) there
    /// singular, [`singular`]).
    pub(super) fn is_pole(&self, uv: &[Vec<[f64; 2]>], k: usize) -> bool {
        singular(self.surface, uv[k][0]).is_some()
    }

    /// The two ends of the pole at the start of edge `k`, point `p`: the parameter that moves
    /// no point there taken from the edges' samples next to it (linear extrapolation), the
    /// other as projected. `Some(k)` if the (u, v) jump there, `None` if the loop only
    /// touches the pole; an error if the straight (u, v) segment between the ends leaves the
    /// point.
    pub(super) fn pole_ends(
        &self,
        uv: &mut [Vec<[f64; 2]>],
        k: usize,
        p: Vec3,
        size: f64,
    ) -> Result<Option<usize>, String> {
        let n = uv.len();
        let before = (k + n - 1) % n;
        let limit = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
            let mut q = a;
            if let Some(d) = singular(self.surface, a) {
                q[d] = 2.0 * b[d] - c[d];
            }
            q
        };
        let (out, into) = (&uv[k], &uv[before]);
        let b = limit(out[0], out[1], out[2]);
        let a = limit(into[NS], into[NS - 1], into[NS - 2]);
        uv[k][0] = b;
        uv[before][NS] = a;
        let s = self.mean_scale(uv);
        let jump = (0..2)
            .map(|c| ((b[c] - a[c]) * s[c]).abs())
            .fold(0.0, f64::max);
        if jump <= 1e-6 * size {
            return Ok(None);
        }
        for t in [0.25, 0.5, 0.75] {
            let q = [0, 1].map(|c| a[c] + t * (b[c] - a[c]));
            let off = (self.surface.point(q[0], q[1]) - p).norm();
            if off.is_nan() || off > self.tol {
                return Err(format!(
                    "starts at a singular point of the surface's parametrization, but its \
                     (u, v) there do not all give that point ({off:.3e} off): not a pole"
                ));
            }
        }
        Ok(Some(k))
    }
}
