//! Global closest-point search on a surface: a BVH over a sampled triangulation picks the
//! start, Newton ([`project`]) finishes (the inverse map of METHOD.md §5 step 5 needs the
//! (u, v) of points that are near, but not on, the surface).

use super::{project, Surface};
use crate::{BoxTree, GeometryError, Vec3};

/// Closest-point locator: the surface sampled on an (n_u + 1) × (n_v + 1) uniform parameter
/// grid, each cell split into two triangles, a [`BoxTree`] over the cells' bounding boxes.
///
/// [`SurfaceLocator::closest`] finds the nearest triangle exactly (best-first BVH search with
/// exact point–triangle distances), maps its closest point to (u, v) by the barycentric
/// coordinates, and refines by Newton. The sampling must resolve the surface well enough
/// that the nearest triangle lies in the basin of the true closest point: for a Hermite net
/// of K × L patches, 2K × 2L cells is a good choice; for analytic or CAD surfaces, enough
/// cells to resolve the smallest radius of curvature.
pub struct SurfaceLocator<S: Surface> {
    surface: S,
    nu: usize,
    nv: usize,
    /// Samples x(i/n_u, j/n_v), i fastest.
    pts: Vec<Vec3>,
    tree: BoxTree,
}

impl<S: Surface> SurfaceLocator<S> {
    /// Samples `surface` on n_u × n_v cells and builds the tree.
    ///
    /// # Errors
    /// n_u or n_v zero, or a non-finite sample.
    pub fn new(surface: S, nu: usize, nv: usize) -> Result<SurfaceLocator<S>, GeometryError> {
        if nu == 0 || nv == 0 {
            return Err(GeometryError::Invalid(format!(
                "surface locator: needs at least 1 × 1 cells, got {nu} × {nv}"
            )));
        }
        let pts: Vec<Vec3> = (0..(nu + 1) * (nv + 1))
            .map(|k| {
                let (i, j) = (k % (nu + 1), k / (nu + 1));
                surface.point(i as f64 / nu as f64, j as f64 / nv as f64)
            })
            .collect();
        if let Some(k) = pts.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            let (u, v) = (
                (k % (nu + 1)) as f64 / nu as f64,
                (k / (nu + 1)) as f64 / nv as f64,
            );
            return Err(GeometryError::Invalid(format!(
                "surface locator: surface not finite at (u, v) = ({u}, {v})"
            )));
        }
        let boxes: Vec<[f64; 6]> = (0..nu * nv)
            .map(|c| cell_box(Self::corners_of(&pts, nu, c)))
            .collect();
        let tree = BoxTree::new(&boxes)?;
        Ok(SurfaceLocator {
            surface,
            nu,
            nv,
            pts,
            tree,
        })
    }

    /// The surface.
    pub fn surface(&self) -> &S {
        &self.surface
    }

    /// Corner points of cell c: (0,0), (1,0), (0,1), (1,1).
    fn corners_of(pts: &[Vec3], nu: usize, c: usize) -> [Vec3; 4] {
        let (i, j) = (c % nu, c / nu);
        let k = i + (nu + 1) * j;
        [pts[k], pts[k + 1], pts[k + nu + 1], pts[k + nu + 2]]
    }

    /// Parameters of the point on the sampled triangulation closest to p, and its distance.
    pub fn closest_sampled(&self, p: Vec3) -> Option<((f64, f64), f64)> {
        let mut best = (f64::INFINITY, (0.5, 0.5));
        let (hu, hv) = (1.0 / self.nu as f64, 1.0 / self.nv as f64);
        self.tree.nearest([p.x, p.y, p.z], |c| {
            let q = Self::corners_of(&self.pts, self.nu, c);
            let (i, j) = ((c % self.nu) as f64, (c / self.nu) as f64);
            // Triangles (00, 10, 11) and (00, 11, 01) with their local (a, b) corners.
            let mut dc = f64::INFINITY;
            for (tri, ab) in [
                ([q[0], q[1], q[3]], [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]),
                ([q[0], q[3], q[2]], [(0.0, 0.0), (1.0, 1.0), (0.0, 1.0)]),
            ] {
                let (x, w) = closest_on_triangle(p, tri);
                let d = (x - p).norm();
                if d < dc {
                    dc = d;
                }
                if d < best.0 {
                    let a = w[0] * ab[0].0 + w[1] * ab[1].0 + w[2] * ab[2].0;
                    let b = w[0] * ab[0].1 + w[1] * ab[1].1 + w[2] * ab[2].1;
                    best = (
                        d,
                        (
                            ((i + a) * hu).clamp(0.0, 1.0),
                            ((j + b) * hv).clamp(0.0, 1.0),
                        ),
                    );
                }
            }
            dc
        })?;
        Some((best.1, best.0))
    }

    /// Parameters (u, v) of the surface point closest to p: the nearest sampled triangle, then
    /// Newton ([`project`]). Falls back to the triangle's parameters if Newton fails (e.g. p
    /// not finite gives (0.5, 0.5)).
    pub fn closest(&self, p: Vec3) -> (f64, f64) {
        let Some((start, _)) = self.closest_sampled(p) else {
            return (0.5, 0.5);
        };
        project(&self.surface, p, start).unwrap_or(start)
    }
}

/// The bounding box [min x, min y, min z, max x, max y, max z] of a cell's corners (a
/// [`BoxTree`] box).
pub(super) fn cell_box(corners: impl IntoIterator<Item = Vec3>) -> [f64; 6] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::INFINITY,
        -f64::INFINITY,
        -f64::INFINITY,
        -f64::INFINITY,
    ];
    for p in corners {
        for d in 0..3 {
            b[d] = b[d].min(p[d]);
            b[d + 3] = b[d + 3].max(p[d]);
        }
    }
    b
}

/// Closest point to p on triangle (a, b, c) and its barycentric coordinates (Ericson,
/// Real-Time Collision Detection, §5.1.5: Voronoi regions of vertices, edges, face).
pub(super) fn closest_on_triangle(p: Vec3, [a, b, c]: [Vec3; 3]) -> (Vec3, [f64; 3]) {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, [1.0, 0.0, 0.0]);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, [0.0, 1.0, 0.0]);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + ab * v, [1.0 - v, v, 0.0]);
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, [0.0, 0.0, 1.0]);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + ac * w, [1.0 - w, 0.0, w]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, [0.0, 1.0 - w, w]);
    }
    let denom = va + vb + vc;
    if denom.is_nan() || denom <= 0.0 {
        // Degenerate (zero-area) triangle: the nearest vertex.
        let k = [a, b, c]
            .iter()
            .map(|q| (q - p).norm_squared())
            .enumerate()
            .fold(
                (0, f64::INFINITY),
                |m, (k, d)| if d < m.1 { (k, d) } else { m },
            )
            .0;
        let mut w = [0.0; 3];
        w[k] = 1.0;
        return ([a, b, c][k], w);
    }
    let (v, w) = (vb / denom, vc / denom);
    (a + ab * v + ac * w, [1.0 - v - w, v, w])
}

#[cfg(test)]
mod tests {
    use super::super::testutil::Rng;
    use super::super::{HermiteSurface, Scherk, TanhBump};
    use super::*;

    fn check<S: Surface>(loc: &SurfaceLocator<S>, offset: f64, seed: u64) {
        let mut rng = Rng::new(seed);
        let mut worst: f64 = 0.0;
        for _ in 0..500 {
            let (u0, v0) = (rng.range(0.01, 0.99), rng.range(0.01, 0.99));
            let e = loc.surface().eval(u0, v0);
            let p = e.x + e.normal() * rng.range(-offset, offset);
            let (u, v) = loc.closest(p);
            worst = worst.max((u - u0).abs().max((v - v0).abs()));
        }
        assert!(worst < 1e-10, "parameter error {worst:e}");
    }

    #[test]
    fn closest_recovers_parameters() {
        check(
            &SurfaceLocator::new(TanhBump::default(), 64, 64).unwrap(),
            0.01,
            1,
        );
        check(
            &SurfaceLocator::new(Scherk::new(1.3).unwrap(), 48, 48).unwrap(),
            0.02,
            2,
        );
        let (ni, nj) = (21, 15);
        let pts = (0..ni * nj)
            .map(|k| {
                let (u, v) = ((k % ni) as f64 / 20.0, (k / ni) as f64 / 14.0);
                Vec3::new(3.0 * u, 2.0 * v, 0.3 * (5.0 * u).sin() * (4.0 * v).cos())
            })
            .collect();
        let h = HermiteSurface::new(ni, nj, pts).unwrap();
        let loc = SurfaceLocator::new(&h, 40, 28).unwrap();
        check(&loc, 0.02, 3);
        // Targets exactly on patch lines and nodes, where the second derivatives jump (C¹).
        let mut rng = Rng::new(4);
        for k in 0..300 {
            let u0 = (1 + k % 19) as f64 / 20.0;
            let v0 = if k % 2 == 0 {
                (1 + k % 13) as f64 / 14.0
            } else {
                rng.range(0.01, 0.99)
            };
            let e = h.eval(u0, v0);
            let p = e.x + e.normal() * rng.range(-0.02, 0.02);
            let (u, v) = loc.closest(p);
            assert!(
                (u - u0).abs() < 1e-10 && (v - v0).abs() < 1e-10,
                "({u0}, {v0}): ({u}, {v})"
            );
            assert!(project(&h, p, (u0 + 0.03, v0 - 0.03)).is_some());
        }
    }

    #[test]
    fn sampled_search_matches_brute_force() {
        let loc = SurfaceLocator::new(TanhBump::default(), 20, 20).unwrap();
        let mut rng = Rng::new(4);
        for _ in 0..200 {
            let p = Vec3::new(
                rng.range(-0.5, 2.5),
                rng.range(-0.5, 2.5),
                rng.range(-1.0, 1.0),
            );
            let (start, d) = loc.closest_sampled(p).unwrap();
            let brute = (0..400)
                .flat_map(|c| {
                    let q = SurfaceLocator::<TanhBump>::corners_of(&loc.pts, 20, c);
                    [[q[0], q[1], q[3]], [q[0], q[3], q[2]]]
                })
                .map(|t| (closest_on_triangle(p, t).0 - p).norm())
                .fold(f64::INFINITY, f64::min);
            assert_eq!(d, brute);
            // Newton only improves on the sampled start.
            let (u, v) = loc.closest(p);
            let d_start = (loc.surface().point(start.0, start.1) - p).norm();
            assert!((loc.surface().point(u, v) - p).norm() <= d_start + 1e-12);
        }
        assert!(SurfaceLocator::new(TanhBump::default(), 0, 3).is_err());
        assert_eq!(loc.closest(Vec3::new(f64::NAN, 0.0, 0.0)), (0.5, 0.5));
    }
}
