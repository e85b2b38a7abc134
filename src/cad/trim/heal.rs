//! Sloppy CAD data healed: edges whose ends miss each other, or the face's surface, by more
//! than the file's tolerance but by at most [`HEAL`] of the loop's size. Exporters write such
//! loops (a TraceParts sphere whose circle has radius 1.49 and its vertices radius 1.50, a
//! re-approximated OpenCascade patch 1e-2 off at an uncertainty of 5e-4); CAD kernels accept
//! them with tolerant vertices, as meshers built on those kernels do. Each edge's points are
//! then moved by a shift blended linearly in its arclength from the start's correction to the
//! end's, so consecutive edges meet exactly at the mean of their ends; the projection onto the
//! surface accepts points up to [`HEAL`] off. The largest defect closed is reported
//! ([`super::FaceLoop::healed`]).

use ellipgrid_geometry::Vec3;

/// Largest gap between consecutive edges' ends, or distance of a boundary point from the
/// surface, healed (relative to the loop's size): half a percent, about a cell of a 129-node
/// side, so the blended shift bends no grid line visibly. Beyond it the face is refused.
pub const HEAL: f64 = 5e-3;

/// The moves of an edge's start and end.
pub(super) type Shift = [Vec3; 2];

/// Per edge, the shifts of its start and end that make consecutive ends of `ends` (each
/// edge's first and last point, in loop order) meet at their mean, and the largest gap so
/// closed; `Err((k, gap))` names the first edge whose end misses the next edge's start by
/// more than `heal` (a gap within `tol` is closed as well).
pub(super) fn end_shifts(
    ends: &[(Vec3, Vec3)],
    heal: f64,
) -> Result<(Vec<Shift>, f64), (usize, f64)> {
    let n = ends.len();
    let mut shifts = vec![[Vec3::zeros(); 2]; n];
    let mut largest = 0.0_f64;
    for k in 0..n {
        let (end, next) = (ends[k].1, ends[(k + 1) % n].0);
        let miss = (end - next).norm();
        if miss > heal {
            return Err((k, miss));
        }
        largest = largest.max(miss);
        let mid = 0.5 * (end + next);
        shifts[k][1] = mid - end;
        shifts[(k + 1) % n][0] = mid - next;
    }
    Ok((shifts, largest))
}

/// The shift at normalized arclength `sigma` of an edge whose ends move by `shift`.
pub(super) fn blend(shift: &Shift, sigma: f64) -> Vec3 {
    (1.0 - sigma) * shift[0] + sigma * shift[1]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_meet_at_their_mean_and_a_gap_beyond_the_limit_is_named() {
        // a triangle whose second vertex is written 0.01 apart on its two edges
        let a = Vec3::new(0.0, 0.0, 0.0);
        let b = Vec3::new(1.0, 0.0, 0.0);
        let c = Vec3::new(0.0, 1.0, 0.0);
        let d = Vec3::new(0.0, 0.01, 0.0);
        let ends = [(a, b), (b + d, c), (c, a)];
        let (s, gap) = end_shifts(&ends, 0.02).unwrap();
        assert!((gap - 0.01).abs() < 1e-15);
        for k in 0..3 {
            let end = ends[k].1 + blend(&s[k], 1.0);
            let next = ends[(k + 1) % 3].0 + blend(&s[(k + 1) % 3], 0.0);
            assert!((end - next).norm() < 1e-15, "edge {k}");
        }
        assert_eq!(end_shifts(&ends, 0.005).unwrap_err().0, 0);
        // edges that meet are not moved
        let (s, gap) = end_shifts(&[(a, b), (b, c), (c, a)], 0.02).unwrap();
        assert_eq!(gap, 0.0);
        assert!(s.iter().flatten().all(|v| *v == Vec3::zeros()));
    }
}
