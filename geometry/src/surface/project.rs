//! Closest point on a surface (or on one boundary curve of its parameter square) by a
//! safeguarded Newton iteration on f = ½ |x(u, v) − p|².
//!
//! Gradient g = (r·x_u, r·x_v), r = x − p; Hessian H = JᵀJ + (r·x_uu, r·x_uv; r·x_uv, r·x_vv).
//! Safeguards: where H is not positive definite (far from the surface, near a ridge) the
//! Gauss–Newton matrix JᵀJ is used instead; bounds are handled by an active set (a variable at
//! its bound whose gradient points outward is frozen) and by clamping; a backtracking line
//! search enforces descent while the steps are still large. Convergence: a step below 1e-13 in
//! (u, v), i.e. to rounding in the parameters, with quadratic convergence near the solution.

use super::{Surface, SurfaceEdge};
use crate::Vec3;

/// Newton iteration limit.
const MAX_ITER: usize = 100;
/// Convergence: |Δu| + |Δv| at most this.
const STEP_TOL: f64 = 1e-13;
/// After [`MAX_ITER`] iterations, the answer is still taken if the last step was at most this
/// (the iteration stalls at the rounding level of the surface evaluation).
const STALL_TOL: f64 = 1e-9;
/// Below this step length the Newton step is taken without line search (the quadratic model
/// is accurate there, while f differences drown in rounding).
const FREE_STEP: f64 = 1e-8;

/// Parameters (u, v) ∈ [0, 1]² of the point of `surface` closest to `p`, by Newton from
/// `start` (a local minimum: start near the answer, e.g. from [`super::SurfaceLocator`]).
///
/// Returns `None` if p or the surface is not finite there, or after 100 iterations without
/// convergence.
pub fn project(surface: &dyn Surface, p: Vec3, start: (f64, f64)) -> Option<(f64, f64)> {
    project_within(surface, p, start, [[0.0, 1.0], [0.0, 1.0]])
}

/// [`project`] within the parameter box `bounds` = [[u_lo, u_hi], [v_lo, v_hi]] (infinite
/// bounds allowed: CAD surfaces in their own parameters, periodic directions left free so
/// that the answer continues the start across a seam). Steps are measured relative to
/// 1 + |u| + |v|, so parameters in millimetres or radians converge alike.
///
/// Returns `None` if p or the surface is not finite there, or when 100 iterations end with a
/// step still above 1e-9 (relative): iterations that stall at the rounding level of the
/// surface's evaluation (a few 1e-13) are accepted.
pub fn project_within(
    surface: &dyn Surface,
    p: Vec3,
    start: (f64, f64),
    bounds: [[f64; 2]; 2],
) -> Option<(f64, f64)> {
    if !p.iter().all(|c| c.is_finite()) {
        return None;
    }
    let [[ulo, uhi], [vlo, vhi]] = bounds;
    let fix = |t: f64, lo: f64, hi: f64| {
        if t.is_finite() {
            t.clamp(lo, hi)
        } else if lo.is_finite() && hi.is_finite() {
            0.5 * (lo + hi)
        } else {
            0.0f64.clamp(lo, hi)
        }
    };
    let (mut u, mut v) = (fix(start.0, ulo, uhi), fix(start.1, vlo, vhi));
    let mut last = f64::INFINITY;
    for _ in 0..MAX_ITER {
        let scale = 1.0 + u.abs() + v.abs();
        let s = surface.eval(u, v);
        let r = s.x - p;
        let f = 0.5 * r.norm_squared();
        let g = [r.dot(&s.xu), r.dot(&s.xv)];
        if !(f.is_finite() && g[0].is_finite() && g[1].is_finite()) {
            return None;
        }
        let (a, b, c) = (s.xu.norm_squared(), s.xu.dot(&s.xv), s.xv.norm_squared());
        let full = [a + r.dot(&s.xuu), b + r.dot(&s.xuv), c + r.dot(&s.xvv)];
        // Active set: freeze a variable at a bound whose descent direction leaves the box.
        let free_u = !((u <= ulo && g[0] > 0.0) || (u >= uhi && g[0] < 0.0));
        let free_v = !((v <= vlo && g[1] > 0.0) || (v >= vhi && g[1] < 0.0));
        let d = newton_step(full, g, free_u, free_v)
            .or_else(|| newton_step([a, b, c], g, free_u, free_v))
            .unwrap_or([0.0, 0.0]);
        let slope = g[0] * d[0] + g[1] * d[1];
        let mut t = 1.0;
        let (mut un, mut vn);
        loop {
            un = (u + t * d[0]).clamp(ulo, uhi);
            vn = (v + t * d[1]).clamp(vlo, vhi);
            let step = (un - u).abs() + (vn - v).abs();
            if step <= FREE_STEP * scale || t < 1e-12 {
                break;
            }
            let fnew = 0.5 * (surface.point(un, vn) - p).norm_squared();
            if fnew <= f + 1e-4 * t * slope.min(0.0) {
                break;
            }
            t *= 0.5;
        }
        let step = (un - u).abs() + (vn - v).abs();
        u = un;
        v = vn;
        if step <= STEP_TOL * scale {
            return Some((u, v));
        }
        last = step / scale;
    }
    (last <= STALL_TOL).then_some((u, v))
}

/// Solves H_ff d_f = −g_f over the free variables; `None` if that block is not positive
/// definite. `h` = (H_uu, H_uv, H_vv).
fn newton_step(h: [f64; 3], g: [f64; 2], free_u: bool, free_v: bool) -> Option<[f64; 2]> {
    match (free_u, free_v) {
        (true, true) => {
            let det = h[0] * h[2] - h[1] * h[1];
            // Relative positive-definiteness test (scale-free).
            if !(h[0] > 0.0 && det > 1e-14 * h[0] * h[2]) {
                return None;
            }
            Some([
                (-g[0] * h[2] + g[1] * h[1]) / det,
                (g[0] * h[1] - g[1] * h[0]) / det,
            ])
        }
        (true, false) => (h[0] > 0.0).then(|| [-g[0] / h[0], 0.0]),
        (false, true) => (h[2] > 0.0).then(|| [0.0, -g[1] / h[2]]),
        (false, false) => Some([0.0, 0.0]),
    }
}

/// Parameter t ∈ [0, 1] of the point of the boundary curve `edge` closest to `p`, by 1D
/// Newton from `start` (Gauss–Newton where the curvature term makes the Hessian non-positive,
/// clamping to [0, 1], backtracking while steps are large).
///
/// Returns `None` if p is not finite, the curve is not finite there, or when 100 iterations
/// end with a step above 1e-9 (stalling at the rounding level is accepted, as in
/// [`project_within`]).
pub fn project_to_edge(
    surface: &dyn Surface,
    edge: SurfaceEdge,
    p: Vec3,
    start: f64,
) -> Option<f64> {
    if !p.iter().all(|c| c.is_finite()) {
        return None;
    }
    let mut t = if start.is_finite() {
        start.clamp(0.0, 1.0)
    } else {
        0.5
    };
    let value = |t: f64| {
        let (u, v) = edge.uv(t);
        0.5 * (surface.point(u, v) - p).norm_squared()
    };
    let mut last = f64::INFINITY;
    for _ in 0..MAX_ITER {
        let (x, c1, c2) = edge.curve(surface, t);
        let r = x - p;
        let f = 0.5 * r.norm_squared();
        let g = r.dot(&c1);
        if !(f.is_finite() && g.is_finite()) {
            return None;
        }
        let out = (t <= 0.0 && g > 0.0) || (t >= 1.0 && g < 0.0);
        let mut h = c1.norm_squared() + r.dot(&c2);
        if h <= 0.0 {
            h = c1.norm_squared();
        }
        let d = if out || h <= 0.0 { 0.0 } else { -g / h };
        let mut lambda = 1.0;
        let mut tn;
        loop {
            tn = (t + lambda * d).clamp(0.0, 1.0);
            if (tn - t).abs() <= FREE_STEP || lambda < 1e-12 {
                break;
            }
            if value(tn) <= f + 1e-4 * lambda * (g * d).min(0.0) {
                break;
            }
            lambda *= 0.5;
        }
        let step = (tn - t).abs();
        t = tn;
        if step <= STEP_TOL {
            return Some(t);
        }
        last = step;
    }
    (last <= STALL_TOL).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::super::testutil::Rng;
    use super::super::{Plane, Scherk, TanhBump};
    use super::*;

    /// Random points at a small normal offset from each surface project back to their (u, v).
    #[test]
    fn random_points_project_back() {
        let surfaces: Vec<Box<dyn Surface>> = vec![
            Box::new(TanhBump::default()),
            Box::new(Scherk::new(1.2).unwrap()),
            Box::new(Plane {
                origin: Vec3::zeros(),
                du: Vec3::new(2.0, 0.1, 0.0),
                dv: Vec3::new(0.3, 1.0, 0.5),
            }),
        ];
        let mut rng = Rng::new(11);
        for s in &surfaces {
            let mut worst: f64 = 0.0;
            for _ in 0..300 {
                let (u0, v0) = (rng.range(0.02, 0.98), rng.range(0.02, 0.98));
                let e = s.eval(u0, v0);
                let p = e.x + e.normal() * rng.range(-0.01, 0.01);
                let start = (
                    (u0 + rng.range(-0.02, 0.02)).clamp(0.0, 1.0),
                    (v0 + rng.range(-0.02, 0.02)).clamp(0.0, 1.0),
                );
                let (u, v) = project(s.as_ref(), p, start).expect("converges");
                worst = worst.max((u - u0).abs().max((v - v0).abs()));
            }
            assert!(worst < 1e-10, "parameter error {worst:e}");
        }
    }

    #[test]
    fn outside_points_clamp_to_boundary_and_edges() {
        let plane = Plane {
            origin: Vec3::zeros(),
            du: Vec3::new(1.0, 0.0, 0.0),
            dv: Vec3::new(0.0, 2.0, 0.0),
        };
        // Beyond the corner (1, 1) and beside edge u = 0.
        assert_eq!(
            project(&plane, Vec3::new(3.0, 5.0, 1.0), (0.5, 0.5)),
            Some((1.0, 1.0))
        );
        let (u, v) = project(&plane, Vec3::new(-1.0, 0.6, 0.0), (0.5, 0.5)).unwrap();
        assert_eq!(u, 0.0);
        assert!((v - 0.3).abs() < 1e-15);
        assert!(project(&plane, Vec3::new(f64::NAN, 0.0, 0.0), (0.5, 0.5)).is_none());
        // Edges: a curved edge of the bump (v = 0 is the line y = 0: z ≈ −1/8, x free).
        let bump = TanhBump::default();
        let mut rng = Rng::new(5);
        for edge in [
            SurfaceEdge::U0,
            SurfaceEdge::U1,
            SurfaceEdge::V0,
            SurfaceEdge::V1,
        ] {
            for _ in 0..50 {
                let t0 = rng.range(0.01, 0.99);
                let (x, c1, _) = edge.curve(&bump, t0);
                // Offset perpendicular to the edge tangent.
                let n = c1.cross(&Vec3::new(0.3, -0.7, 0.9)).normalize();
                let t = project_to_edge(&bump, edge, x + 0.05 * n, t0 + 0.03).unwrap();
                assert!((t - t0).abs() < 1e-10, "{edge:?}: {t} vs {t0}");
            }
        }
        // Beyond the end of an edge: clamps to it.
        let t = project_to_edge(&plane, SurfaceEdge::V1, Vec3::new(4.0, 2.0, 0.0), 0.2);
        assert_eq!(t, Some(1.0));
        let t = project_to_edge(&plane, SurfaceEdge::U1, Vec3::new(4.0, 1.0, 0.0), 0.9).unwrap();
        assert!((t - 0.5).abs() < 1e-15);
    }
}
