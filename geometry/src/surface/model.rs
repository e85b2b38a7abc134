//! Closest points on a model made of several surfaces (a CAD model's faces, each a surface with
//! its own parameters): every surface sampled by quad meshes that cover only its face (a
//! trimmed face's region, not its whole parameter box), one BVH over all their cells; the
//! nearest sampled triangle picks the surface and the start, Newton ([`project_within`])
//! finishes. The block faces that are not CAD faces (issue #14) live on such a model.

use super::locate::{cell_box, closest_on_triangle};
use super::{project_within, Surface};
use crate::{BoxTree, GeometryError, Vec3};

/// A quad mesh sampling one surface of a [`ModelLocator`]: `ni × nj` nodes (i fastest), their
/// points and their parameters on that surface.
#[derive(Clone, Debug)]
pub struct ModelSample {
    /// Index of the surface in the model.
    pub surface: usize,
    /// Nodes along i.
    pub ni: usize,
    /// Nodes along j.
    pub nj: usize,
    /// Node points x(u, v).
    pub x: Vec<Vec3>,
    /// Node parameters (u, v).
    pub uv: Vec<[f64; 2]>,
}

/// A point of the model: which surface, its parameters there, the point and unit normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelPoint {
    /// Index of the surface.
    pub surface: usize,
    /// Parameters on that surface.
    pub uv: (f64, f64),
    /// The point.
    pub x: Vec3,
    /// The surface's unit normal there (x_u × x_v normalized).
    pub normal: Vec3,
}

/// One surface of a model and the parameter box Newton is held to (its face's samples' box).
type Member = (Box<dyn Surface>, [[f64; 2]; 2]);

/// Closest-point search over several surfaces; see the module doc.
pub struct ModelLocator {
    surfaces: Vec<Member>,
    samples: Vec<ModelSample>,
    /// (sample, cell) of every BVH box.
    cells: Vec<(usize, usize)>,
    tree: BoxTree,
    diagonal: f64,
}

impl ModelLocator {
    /// The model of `surfaces` sampled by `samples`; Newton is held to each surface's
    /// samples' parameter box.
    ///
    /// # Errors
    /// A sample naming no surface, with fewer than 2 × 2 nodes, mismatched lengths or
    /// non-finite points; no samples at all.
    pub fn new(
        surfaces: Vec<Box<dyn Surface>>,
        samples: Vec<ModelSample>,
    ) -> Result<ModelLocator, GeometryError> {
        let bad = |m: String| Err(GeometryError::Invalid(format!("model: {m}")));
        let mut boxes = vec![[[f64::INFINITY, -f64::INFINITY]; 2]; surfaces.len()];
        let (mut cells, mut cell_boxes) = (Vec::new(), Vec::new());
        let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(-f64::INFINITY));
        for (k, s) in samples.iter().enumerate() {
            if s.surface >= surfaces.len() {
                return bad(format!(
                    "sample {k} names surface {} of {}",
                    s.surface,
                    surfaces.len()
                ));
            }
            let n = s.ni * s.nj;
            if s.ni < 2 || s.nj < 2 || s.x.len() != n || s.uv.len() != n {
                return bad(format!("sample {k} is not a {} × {} mesh", s.ni, s.nj));
            }
            if !s.x.iter().all(|p| p.iter().all(|c| c.is_finite()))
                || !s.uv.iter().all(|q| q.iter().all(|c| c.is_finite()))
            {
                return bad(format!("sample {k} has a point that is not finite"));
            }
            for (p, q) in s.x.iter().zip(&s.uv) {
                lo = lo.inf(p);
                hi = hi.sup(p);
                let b = &mut boxes[s.surface];
                for d in 0..2 {
                    b[d] = [b[d][0].min(q[d]), b[d][1].max(q[d])];
                }
            }
            for c in 0..(s.ni - 1) * (s.nj - 1) {
                let b = cell_box(corners(s.ni, c).map(|n| s.x[n]));
                cells.push((k, c));
                cell_boxes.push(b);
            }
        }
        if cells.is_empty() {
            return bad("no sampled cells".into());
        }
        let tree = BoxTree::new(&cell_boxes)?;
        Ok(ModelLocator {
            surfaces: surfaces.into_iter().zip(boxes).collect(),
            samples,
            cells,
            tree,
            diagonal: (hi - lo).norm(),
        })
    }

    /// Number of surfaces.
    pub fn len(&self) -> usize {
        self.surfaces.len()
    }

    /// True if the model has no surface.
    pub fn is_empty(&self) -> bool {
        self.surfaces.is_empty()
    }

    /// The diagonal of the samples' bounding box (the model's size, for tolerances).
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// Surface k.
    pub fn surface(&self, k: usize) -> &dyn Surface {
        self.surfaces[k].0.as_ref()
    }

    /// The model's point at (u, v) of surface k.
    pub fn point_at(&self, k: usize, (u, v): (f64, f64)) -> ModelPoint {
        let e = self.surfaces[k].0.eval(u, v);
        ModelPoint {
            surface: k,
            uv: (u, v),
            x: e.x,
            normal: e.normal(),
        }
    }

    /// The point of the sampled triangles closest to p: (surface, parameters by the
    /// barycentric coordinates, distance).
    pub fn closest_sampled(&self, p: Vec3) -> Option<(usize, (f64, f64), f64)> {
        let mut best = (usize::MAX, (0.0, 0.0), f64::INFINITY);
        self.tree.nearest([p.x, p.y, p.z], |b| {
            let (k, c) = self.cells[b];
            let s = &self.samples[k];
            let n = corners(s.ni, c);
            let mut dc = f64::INFINITY;
            for t in [[n[0], n[1], n[3]], [n[0], n[3], n[2]]] {
                let (x, w) = closest_on_triangle(p, [s.x[t[0]], s.x[t[1]], s.x[t[2]]]);
                let d = (x - p).norm();
                dc = dc.min(d);
                if d < best.2 {
                    let uv = |a: usize| (0..3).map(|m| w[m] * s.uv[t[m]][a]).sum::<f64>();
                    best = (s.surface, (uv(0), uv(1)), d);
                }
            }
            dc
        })?;
        Some(best)
    }

    /// The model's point closest to p: the nearest sampled triangle, then Newton on its
    /// surface within the surface's box (the triangle's point where Newton fails).
    pub fn closest(&self, p: Vec3) -> Option<ModelPoint> {
        let (k, start, _) = self.closest_sampled(p)?;
        let (surface, bounds) = &self.surfaces[k];
        let uv = project_within(surface.as_ref(), p, start, *bounds).unwrap_or(start);
        Some(self.point_at(k, uv))
    }

    /// The model's point on the line through p along the unit direction d nearest p (a
    /// curve projected along a direction, as CAD tools do): the closest point of p + s d, with
    /// s the height along d of the last point found, repeated until the point settles (at
    /// a rate of about the square of the surface's slope against d). `None` if a projection
    /// fails, or after 100 iterations (the line misses the model or grazes it).
    pub fn along(&self, p: Vec3, d: Vec3) -> Option<ModelPoint> {
        let tol = 1e-13 * (1.0 + p.abs().max());
        let mut x = self.closest(p)?;
        for _ in 0..100 {
            let next = self.closest(p + d * d.dot(&(x.x - p)))?;
            let moved = (next.x - x.x).norm();
            x = next;
            if moved <= tol {
                return Some(x);
            }
        }
        None
    }
}

/// Node indices of cell c of a mesh with `ni` nodes along i: (0,0), (1,0), (0,1), (1,1).
fn corners(ni: usize, c: usize) -> [usize; 4] {
    let (i, j) = (c % (ni - 1), c / (ni - 1));
    let n = i + ni * j;
    [n, n + 1, n + ni, n + ni + 1]
}

#[cfg(test)]
mod tests {
    use super::super::Plane;
    use super::*;

    /// Two planes meeting at a right angle (the floor z = 0 for x ≤ 1 and the wall x = 1):
    /// points are projected onto the nearer one, exactly.
    #[test]
    fn closest_picks_the_nearer_surface() {
        let floor = Plane {
            origin: Vec3::zeros(),
            du: Vec3::new(1.0, 0.0, 0.0),
            dv: Vec3::new(0.0, 1.0, 0.0),
        };
        let wall = Plane {
            origin: Vec3::new(1.0, 0.0, 0.0),
            du: Vec3::new(0.0, 1.0, 0.0),
            dv: Vec3::new(0.0, 0.0, 1.0),
        };
        let sample = |k: usize, s: &Plane| {
            let (ni, nj) = (5, 4);
            let uv: Vec<[f64; 2]> = (0..ni * nj)
                .map(|n| [(n % ni) as f64 / 4.0, (n / ni) as f64 / 3.0])
                .collect();
            let x = uv.iter().map(|q| s.point(q[0], q[1])).collect();
            ModelSample {
                surface: k,
                ni,
                nj,
                x,
                uv,
            }
        };
        let samples = vec![sample(0, &floor), sample(1, &wall)];
        let m = ModelLocator::new(vec![Box::new(floor), Box::new(wall)], samples).unwrap();
        let q = m.closest(Vec3::new(0.3, 0.4, 0.1)).unwrap();
        assert_eq!(q.surface, 0);
        assert!((q.x - Vec3::new(0.3, 0.4, 0.0)).norm() < 1e-14);
        let q = m.closest(Vec3::new(0.95, 0.4, 0.6)).unwrap();
        assert_eq!(q.surface, 1);
        assert!((q.x - Vec3::new(1.0, 0.4, 0.6)).norm() < 1e-14);
        assert!((q.normal - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-14);
        assert!((m.diagonal() - 3f64.sqrt()).abs() < 1e-14);
        // a sample naming a missing surface is refused
        let bad = ModelLocator::new(vec![], vec![sample(0, &floor)]);
        assert!(bad.is_err());
    }

    /// On the tilted plane z = 0.3 x, the point straight below (0.5, 0.5, 1) is (0.5, 0.5,
    /// 0.15), while the closest point is not.
    #[test]
    fn along_a_direction() {
        let tilted = Plane {
            origin: Vec3::zeros(),
            du: Vec3::new(1.0, 0.0, 0.3),
            dv: Vec3::new(0.0, 1.0, 0.0),
        };
        let (ni, nj) = (9, 9);
        let uv: Vec<[f64; 2]> = (0..ni * nj)
            .map(|n| [(n % ni) as f64 / 8.0, (n / ni) as f64 / 8.0])
            .collect();
        let x = uv.iter().map(|q| tilted.point(q[0], q[1])).collect();
        let s = ModelSample {
            surface: 0,
            ni,
            nj,
            x,
            uv,
        };
        let m = ModelLocator::new(vec![Box::new(tilted)], vec![s]).unwrap();
        let p = Vec3::new(0.5, 0.5, 1.0);
        assert!((m.closest(p).unwrap().x.x - 0.5).abs() > 0.1);
        let q = m.along(p, Vec3::new(0.0, 0.0, -1.0)).unwrap();
        assert!((q.x - Vec3::new(0.5, 0.5, 0.15)).norm() < 1e-13, "{q:?}");
    }
}
