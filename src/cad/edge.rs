//! A face's edge curves as CAD files write them, made usable: each curve cut to the part
//! between its two vertices (B-spline edge curves often extend beyond them, unclamped ones
//! are undefined outside [t_p, t_n]), and the workaround for truck-stepio's pcurves.

use super::LoopEdge;
use truck_geometry::prelude::{ParametricCurve, Point3};
use truck_stepio::r#in::alias::{Curve2D, Curve3D};

/// (first, last knot of the valid range, all knots) of a B-spline or NURBS curve, 3D or 2D
/// under a pcurve.
fn spline_knots(c: &Curve3D) -> Option<(f64, f64, Vec<f64>)> {
    let from = |k: &[f64], p: usize| {
        let n = k.len().checked_sub(p + 1)?;
        (p < n).then(|| (k[p], k[n], k.to_vec()))
    };
    match c {
        Curve3D::BSplineCurve(b) => from(b.knot_vec(), b.degree()),
        Curve3D::NurbsCurve(b) => from(b.knot_vec(), b.degree()),
        Curve3D::PCurve(pc) => match &**pc.curve() {
            Curve2D::BSplineCurve(b) => from(b.knot_vec(), b.degree()),
            Curve2D::NurbsCurve(b) => from(b.knot_vec(), b.degree()),
            _ => None,
        },
        _ => None,
    }
}

/// Knots of a curve (where it may be only C¹ or C⁰).
pub(super) fn knots(c: &Curve3D) -> Vec<f64> {
    spline_knots(c).map(|k| k.2).unwrap_or_default()
}

/// The range where the curve is defined: [t_p, t_n] for B-splines (also unclamped ones),
/// truck's range otherwise.
fn valid_range(c: &Curve3D) -> Option<(f64, f64)> {
    spline_knots(c)
        .map(|k| (k.0, k.1))
        .or_else(|| c.try_range_tuple())
        .filter(|(a, b)| a.is_finite() && b.is_finite() && b > a)
}

/// The curve's type, for messages.
fn kind(c: &Curve3D) -> &'static str {
    match c {
        Curve3D::Line(_) => "line",
        Curve3D::Polyline(_) => "polyline",
        Curve3D::Conic(_) => "conic",
        Curve3D::BSplineCurve(_) => "B-spline",
        Curve3D::PCurve(_) => "pcurve",
        Curve3D::NurbsCurve(_) => "NURBS",
    }
}

fn dist(c: &Curve3D, t: f64, p: Point3) -> f64 {
    let q = c.subs(t);
    ((q.x - p.x).powi(2) + (q.y - p.y).powi(2) + (q.z - p.z).powi(2)).sqrt()
}

/// Parameter of the point of `c` on [a, b] nearest `p`: the best of 256 samples, then Newton.
fn nearest(c: &Curve3D, (a, b): (f64, f64), p: Point3) -> f64 {
    const N: usize = 256;
    let mut best = (f64::INFINITY, a);
    for k in 0..=N {
        let t = a + (b - a) * k as f64 / N as f64;
        let d = dist(c, t, p);
        if d < best.0 {
            best = (d, t);
        }
    }
    let mut t = best.1;
    for _ in 0..50 {
        let (q, d1, d2) = (c.subs(t), c.der(t), c.der2(t));
        let r = q - p;
        let g = r.x * d1.x + r.y * d1.y + r.z * d1.z;
        let mut h = d1.x * d1.x + d1.y * d1.y + d1.z * d1.z;
        let curv = r.x * d2.x + r.y * d2.y + r.z * d2.z;
        if h + curv > 0.0 {
            h += curv;
        }
        if !(g.is_finite() && h > 0.0) {
            break;
        }
        let next = (t - g / h).clamp(a, b);
        let step = (next - t).abs();
        t = next;
        if step <= 1e-14 * (1.0 + t.abs()) {
            break;
        }
    }
    if dist(c, t, p) <= best.0 {
        t
    } else {
        best.1
    }
}

/// The edge `curve` from vertex `p0` to vertex `p1` as a loop edge (`forward` as the loop
/// runs): the curve's range if its ends are the vertices, else the part between the
/// vertices' nearest parameters (the whole period for a closed edge on a closed curve).
///
/// # Errors
/// No finite range, or a vertex farther than `tol` from the curve.
pub(super) fn loop_edge(
    curve: &Curve3D,
    (p0, p1): (Point3, Point3),
    forward: bool,
    tol: f64,
) -> Result<LoopEdge, String> {
    let Some((a, b)) = valid_range(curve) else {
        return Err(format!(
            "its curve ({}) has no finite parameter range: {:?}",
            kind(curve),
            curve.try_range_tuple()
        ));
    };
    let near = |t: f64, p: Point3| dist(curve, t, p) <= tol;
    if near(a, p0) && near(b, p1) {
        return Ok(LoopEdge {
            curve: curve.clone(),
            range: (a, b),
            forward,
        });
    }
    let (t0, mut t1) = (nearest(curve, (a, b), p0), nearest(curve, (a, b), p1));
    for (t, p) in [(t0, p0), (t1, p1)] {
        let d = dist(curve, t, p);
        if d.is_nan() || d > tol {
            return Err(format!("a vertex lies {d:.3e} from its curve"));
        }
    }
    let closed = dist(curve, a, curve.subs(b)) <= tol;
    let (mut lo, mut hi, mut fw) = (t0, t1, forward);
    if closed && t1 <= t0 + 1e-12 * (b - a) {
        // A closed curve: the edge runs on from t0 past the seam (a whole period if p0 = p1).
        t1 += b - a;
        hi = t1;
    } else if t1 < t0 {
        (lo, hi, fw) = (t1, t0, !forward);
    }
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return Err("its vertices are the same point of an open curve".into());
    }
    Ok(LoopEdge {
        curve: curve.clone(),
        range: (lo, hi),
        forward: fw,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use truck_geometry::prelude::{BSplineCurve, KnotVec};

    #[test]
    fn edges_are_cut_to_their_vertices() {
        // y = x² for x ∈ [0, 2] as a Bézier curve; the edge runs from x = 0.5 to x = 1.5.
        let c = Curve3D::BSplineCurve(BSplineCurve::new(
            KnotVec::bezier_knot(2),
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(2.0, 4.0, 0.0),
            ],
        ));
        let (p, q) = (Point3::new(0.5, 0.25, 0.0), Point3::new(1.5, 2.25, 0.0));
        let e = loop_edge(&c, (p, q), true, 1e-9).unwrap();
        assert!((e.range.0 - 0.25).abs() < 1e-13 && (e.range.1 - 0.75).abs() < 1e-13);
        assert!(e.forward);
        // Vertices given against the curve's direction: the same piece, run backwards.
        let r = loop_edge(&c, (q, p), true, 1e-9).unwrap();
        assert_eq!((r.range, r.forward), (e.range, false));
        // A vertex off the curve is an error.
        assert!(loop_edge(&c, (p, Point3::new(1.5, 2.0, 0.0)), true, 1e-6).is_err());
        // The whole curve: its range as is.
        let w = loop_edge(&c, (c.subs(0.0), c.subs(1.0)), false, 1e-9).unwrap();
        assert_eq!((w.range, w.forward), ((0.0, 1.0), false));
    }
}
