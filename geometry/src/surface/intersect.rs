//! The curve where two surfaces meet (a wing–pylon junction), traced by predictor–corrector
//! marching: a step along the tangent n_a × n_b, then Newton on three planes (the tangent
//! planes of both surfaces at the closest points of the current point, and the plane through
//! the predicted point normal to the step), which converges quadratically where the surfaces
//! cross at an angle. The surfaces enter only through their closest-point maps, so either may
//! be a model of several faces ([`super::ModelLocator`]).

use crate::{GeometryError, Vec3};
use nalgebra::Matrix3;

/// A surface's closest-point map: p ↦ (closest point, unit normal there), `None` where it
/// fails.
pub type Projector<'a> = &'a dyn Fn(Vec3) -> Option<(Vec3, Vec3)>;

/// Newton iterations of [`intersection_point`].
const MAX_NEWTON: usize = 50;
/// Largest turn of the tangent over one marching step (radians, 3°): the chords stay within
/// h² κ / 8 ≈ 0.007 h of the curve; resampled points are corrected onto it anyway.
const MAX_TURN: f64 = 0.052;
/// Sines of crossing angles below this count as tangent surfaces (no transversal junction).
const MIN_SINE: f64 = 1e-3;

/// The point where surfaces `a` and `b` meet in the plane through `c` normal to `t`, by
/// Newton from `q0` (see the module doc); converged when a step is below `tol`. `None` where
/// a projection fails, the surfaces are tangent there, or Newton does not converge.
pub fn intersection_point(
    a: Projector,
    b: Projector,
    q0: Vec3,
    c: Vec3,
    t: Vec3,
    tol: f64,
) -> Option<Vec3> {
    let mut q = q0;
    for _ in 0..MAX_NEWTON {
        let (pa, na) = a(q)?;
        let (pb, nb) = b(q)?;
        if na.cross(&nb).norm() < MIN_SINE {
            return None;
        }
        let m = Matrix3::from_rows(&[na.transpose(), nb.transpose(), t.transpose()]);
        let r = Vec3::new(na.dot(&pa), nb.dot(&pb), t.dot(&c));
        let next = m.lu().solve(&r)?;
        let step = (next - q).norm();
        q = next;
        if !step.is_finite() {
            return None;
        }
        if step <= tol {
            return Some(q);
        }
    }
    None
}

/// The unit tangent n_a × n_b of the junction at q (on both surfaces), or `None`.
fn tangent(a: Projector, b: Projector, q: Vec3) -> Option<Vec3> {
    let (_, na) = a(q)?;
    let (_, nb) = b(q)?;
    let t = na.cross(&nb);
    let n = t.norm();
    (n >= MIN_SINE).then(|| t / n)
}

/// The junction of `a` and `b` from near `from` to near `to`: its points (on both surfaces
/// to rounding), from the junction's point nearest `from` to the one nearest `to`, at most
/// about `h` apart (closer where it turns by more than 3° per step).
///
/// # Errors
/// [`GeometryError::Invalid`] where no junction passes near `from` or `to`, the surfaces
/// are tangent, the marching jumps or turns back, or it does not reach `to` within
/// 100 × |to − from| / h steps.
pub fn trace_intersection(
    a: Projector,
    b: Projector,
    from: Vec3,
    to: Vec3,
    h: f64,
) -> Result<Vec<Vec3>, GeometryError> {
    let err = |m: String| GeometryError::Invalid(format!("intersection: {m}"));
    let span = (to - from).norm();
    if !(span > 0.0 && h > 0.0 && h.is_finite()) {
        return Err(err(
            "`from` and `to` must differ and the step be positive".into()
        ));
    }
    let tol = 1e-13 * (1.0 + from.abs().max().max(to.abs().max()));
    let chord = (to - from) / span;
    // The ends: the junction's points nearest `from` and `to` ((q − p) normal to the
    // junction's tangent at q): first in the plane across the chord, then across the tangent
    // until q settles.
    let end_point = |p: Vec3, name: &str| -> Result<(Vec3, Vec3), GeometryError> {
        let fail = || {
            err(format!(
                "the surfaces do not meet near `{name}` ({:.6?})",
                p.as_slice()
            ))
        };
        let mut q = intersection_point(a, b, p, p, chord, tol).ok_or_else(fail)?;
        for _ in 0..MAX_NEWTON {
            let mut t = tangent(a, b, q).ok_or_else(fail)?;
            if t.dot(&chord) < 0.0 {
                t = -t;
            }
            let next = intersection_point(a, b, q, p, t, tol).ok_or_else(fail)?;
            let moved = (next - q).norm();
            q = next;
            if moved <= 100.0 * tol {
                return Ok((q, t));
            }
        }
        Err(fail())
    };
    let (start, mut t) = end_point(from, "from")?;
    let (end, _) = end_point(to, "to")?;
    let mut pts = vec![start];
    let mut q = start;
    let mut step = h;
    let max_steps = (100.0 * span / h).ceil() as usize + 1000;
    for _ in 0..max_steps {
        let left = t.dot(&(end - q));
        let gap = (end - q).norm();
        if left <= step {
            if gap > 3.0 * h {
                return Err(err(format!(
                    "the junction traced from `from` passes `to` {gap:.3e} away from it"
                )));
            }
            if gap < 0.05 * h {
                pts.pop();
            }
            pts.push(end);
            if pts.len() < 2 {
                return Err(err(
                    "the junction's points nearest `from` and `to` coincide: it has no length"
                        .into(),
                ));
            }
            return Ok(pts);
        }
        let s = step.min(0.5 * left.max(step / 1.5));
        let pred = q + s * t;
        let next = intersection_point(a, b, pred, pred, t, tol)
            .filter(|n| (n - pred).norm() < s)
            .and_then(|n| tangent(a, b, n).map(|tn| (n, if tn.dot(&t) < 0.0 { -tn } else { tn })));
        match next {
            Some((n, tn)) if tn.dot(&t).clamp(-1.0, 1.0).acos() <= MAX_TURN => {
                pts.push(n);
                q = n;
                t = tn;
                step = (2.0 * step).min(h);
            }
            _ if step > h / 4096.0 => step *= 0.5,
            _ => {
                return Err(err(format!(
                    "the marching stops at {:.6?} (the surfaces tangent, or the junction turns \
                     sharply there)",
                    q.as_slice()
                )))
            }
        }
    }
    Err(err(format!(
        "no arrival at `to` after {max_steps} steps of {h:.3e}"
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sphere of radius 1 and the plane z = 0.5 meet in the circle of radius √0.75: every
    /// traced point lies on it to rounding, from the point nearest `from` to the one nearest
    /// `to`, along the shorter arc.
    #[test]
    fn sphere_and_plane_meet_in_a_circle() {
        let sphere = |p: Vec3| Some((p / p.norm(), p / p.norm()));
        let plane = |p: Vec3| Some((Vec3::new(p.x, p.y, 0.5), Vec3::new(0.0, 0.0, 1.0)));
        let r = 0.75f64.sqrt();
        let pts = trace_intersection(
            &sphere,
            &plane,
            Vec3::new(1.0, 0.0, 0.4),
            Vec3::new(0.0, 1.0, 0.6),
            0.01,
        )
        .unwrap();
        for p in &pts {
            assert!((p.z - 0.5).abs() < 1e-13);
            assert!(((p.x * p.x + p.y * p.y).sqrt() - r).abs() < 1e-13);
        }
        assert!((pts[0] - Vec3::new(r, 0.0, 0.5)).norm() < 1e-12);
        assert!((pts.last().unwrap() - Vec3::new(0.0, r, 0.5)).norm() < 1e-12);
        // a quarter circle of length π r / 2 in steps of at most 0.01
        let len: f64 = pts.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        assert!(
            (len - std::f64::consts::FRAC_PI_2 * r).abs() < 1e-4,
            "{len}"
        );
        assert!(pts.windows(2).all(|w| (w[1] - w[0]).norm() <= 0.0101));
        // ends whose junction points coincide (1e-9 apart, steps of 0.01): no curve
        let e = trace_intersection(
            &sphere,
            &plane,
            Vec3::new(r, -1e-9, 0.5),
            Vec3::new(r, 1e-9, 0.5),
            0.01,
        );
        assert!(format!("{e:?}").contains("no length"), "{e:?}");
        // the plane z = 2 does not meet the sphere
        let high = |p: Vec3| Some((Vec3::new(p.x, p.y, 2.0), Vec3::new(0.0, 0.0, 1.0)));
        let e = trace_intersection(
            &sphere,
            &high,
            Vec3::new(1.0, 0.0, 2.0),
            Vec3::new(0.0, 1.0, 2.0),
            0.01,
        );
        assert!(e.is_err());
    }
}
