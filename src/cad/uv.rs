//! Points of a face's loops in the surface's (u, v) plane scaled by the outer loop's mean
//! |x_u|, |x_v| (close to isometric): a loop point's (u, v), and a polygon's centroid.

use super::trim::{FaceLoop, LoopPoint};

/// The centroid of the area of a closed polygon (its first point if the area is zero).
pub(super) fn centroid(poly: &[(LoopPoint, [f64; 2])]) -> [f64; 2] {
    let n = poly.len();
    let (mut a, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for i in 0..n {
        let (p, q) = (poly[i].1, poly[(i + 1) % n].1);
        let c = p[0] * q[1] - q[0] * p[1];
        a += c;
        cx += (p[0] + q[0]) * c;
        cy += (p[1] + q[1]) * c;
    }
    if a.abs() > 0.0 {
        [cx / (3.0 * a), cy / (3.0 * a)]
    } else {
        poly[0].1
    }
}

/// (u, v) of a loop point, scaled.
pub(super) fn at(lp: &mut FaceLoop, p: LoopPoint, scale: [f64; 2]) -> Result<[f64; 2], String> {
    let (_, w) = lp.sample(p, p, &[0.0])?;
    Ok([w[0][0] * scale[0], w[0][1] * scale[1]])
}
