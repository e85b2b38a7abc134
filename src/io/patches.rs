//! What viewers see of a block: its boundary surface as structured patches of quads, with
//! consistent orientation, vertex normals, grid-line segments and node values of a cell quality
//! metric. Shared by the glTF and OBJ writers and the picture renderer.
//!
//! A planar block is one patch at z = 0 whose quads face +z (a left-handed grid is mirrored in
//! i so that its triangles are counter-clockwise seen from +z). A surface block is one patch in
//! its own orientation. A volume block gives its six faces, ordered i = 0, i = N, j = 0, j = M,
//! k = 0, k = N, each oriented so that its normal points out of the block (for a left-handed
//! block too: the signed volume enclosed by the faces decides).

use crate::io::Block;
use crate::quality;
use crate::Grid2;

/// A structured patch of `ni × nj` nodes in R³, node (i, j) at `i + ni·j`.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    /// Nodes along i.
    pub ni: usize,
    /// Nodes along j.
    pub nj: usize,
    /// Node coordinates, i fastest.
    pub points: Vec<[f64; 3]>,
    /// True for a patch of a planar block (cell metrics use the planar definitions).
    pub planar: bool,
}

/// A per-cell quality metric, averaged to the nodes for colouring.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellMetric {
    /// Equiangular skewness (0 for rectangles).
    Skewness,
    /// Smallest scaled corner Jacobian of the cell (1 for right angles, ≤ 0 folded).
    Jacobian,
    /// Aspect ratio, longest over shortest edge.
    Aspect,
}

impl CellMetric {
    /// Parses "skewness", "jacobian" or "aspect".
    pub fn parse(s: &str) -> Option<CellMetric> {
        match s.to_ascii_lowercase().as_str() {
            "skewness" => Some(CellMetric::Skewness),
            "jacobian" | "scaled_jacobian" => Some(CellMetric::Jacobian),
            "aspect" | "aspect_ratio" => Some(CellMetric::Aspect),
            _ => None,
        }
    }

    /// Name as shown in legends.
    pub fn label(self) -> &'static str {
        match self {
            CellMetric::Skewness => "skewness",
            CellMetric::Jacobian => "scaled jacobian",
            CellMetric::Aspect => "aspect ratio",
        }
    }

    /// Name of the per-cell array in [`quality::CELL_FIELDS`].
    fn field(self) -> &'static str {
        match self {
            CellMetric::Skewness => "skewness",
            CellMetric::Jacobian => "scaled_jacobian_min",
            CellMetric::Aspect => "aspect_ratio",
        }
    }
}

impl Patch {
    /// A patch from a node function.
    pub fn from_fn(ni: usize, nj: usize, f: impl Fn(usize, usize) -> [f64; 3]) -> Patch {
        let points = (0..nj)
            .flat_map(|j| (0..ni).map(move |i| (i, j)))
            .map(|(i, j)| f(i, j))
            .collect();
        Patch {
            ni,
            nj,
            points,
            planar: false,
        }
    }

    /// Node (i, j).
    pub fn p(&self, i: usize, j: usize) -> [f64; 3] {
        self.points[i + self.ni * j]
    }

    /// Mirrors the patch in i (reverses its orientation).
    pub fn flip(&mut self) {
        for row in self.points.chunks_mut(self.ni.max(1)) {
            row.reverse();
        }
    }

    /// Quads as node indices (i, j), (i+1, j), (i+1, j+1), (i, j+1): counter-clockwise about
    /// the patch normal x_i × x_j.
    pub fn quads(&self) -> impl Iterator<Item = [usize; 4]> + '_ {
        let ni = self.ni;
        let (ci, cj) = (ni.saturating_sub(1), self.nj.saturating_sub(1));
        (0..cj).flat_map(move |j| {
            (0..ci).map(move |i| {
                let a = i + ni * j;
                [a, a + 1, a + 1 + ni, a + ni]
            })
        })
    }

    /// The cells as polygons (node indices, how many): [`Patch::quads`], except that a cell
    /// with an edge of zero length (two consecutive corners one point: the cells along a block
    /// side collapsed to a point, a pole or a CAD face's cusp) is the triangle it is, that
    /// corner left out; a cell with fewer than three distinct corners in turn is left out.
    /// Writers emit these rather than degenerate faces and triangles.
    pub fn polygons(&self) -> impl Iterator<Item = ([usize; 4], usize)> + '_ {
        self.quads().filter_map(|q| {
            let mut out = [0; 4];
            let mut n = 0;
            for k in 0..4 {
                if self.points[q[k]] != self.points[q[(k + 1) % 4]] {
                    out[n] = q[k];
                    n += 1;
                }
            }
            (n >= 3).then_some((out, n))
        })
    }

    /// Grid-line segments (node index pairs): along i on every j-line, then along j.
    pub fn segments(&self) -> Vec<[usize; 2]> {
        let (ni, nj) = (self.ni, self.nj);
        let mut s = Vec::new();
        for j in 0..nj {
            s.extend((1..ni).map(|i| [i - 1 + ni * j, i + ni * j]));
        }
        for i in 0..ni {
            s.extend((1..nj).map(|j| [i + ni * (j - 1), i + ni * j]));
        }
        s
    }

    /// Area vector of a quad (half the cross product of its diagonals).
    fn quad_area(&self, q: [usize; 4]) -> [f64; 3] {
        let p = |k: usize| self.points[q[k]];
        let d1 = sub(p(2), p(0));
        let d2 = sub(p(3), p(1));
        let c = cross(d1, d2);
        [0.5 * c[0], 0.5 * c[1], 0.5 * c[2]]
    }

    /// Unit vertex normals: the sum of the area vectors of the adjacent quads, normalised.
    /// A node without a usable normal (degenerate cells) gets the patch's mean normal, or +z.
    pub fn normals(&self) -> Vec<[f64; 3]> {
        let mut n = vec![[0.0; 3]; self.points.len()];
        let mut total = [0.0; 3];
        for q in self.quads() {
            let a = self.quad_area(q);
            for &k in &q {
                n[k] = add(n[k], a);
            }
            total = add(total, a);
        }
        let fallback = unit(total).unwrap_or([0.0, 0.0, 1.0]);
        n.iter().map(|&v| unit(v).unwrap_or(fallback)).collect()
    }

    /// Signed volume contribution ∑ p₀·(p₁ × p₂)/6 of the patch's triangles (two per quad).
    fn signed_volume(&self) -> f64 {
        let mut v = 0.0;
        for q in self.quads() {
            let p = |k: usize| self.points[q[k]];
            v += dot(p(0), cross(p(1), p(2))) + dot(p(0), cross(p(2), p(3)));
        }
        v / 6.0
    }

    /// The patch as a surface grid (for the quality metrics).
    pub fn grid(&self) -> Grid2<3> {
        Grid2::from_fn(self.ni, self.nj, |i, j| self.p(i, j))
    }

    /// Per-cell values of `metric`, cell (i, j) at i + (ni − 1) j. Empty for patches smaller
    /// than 2 × 2.
    pub fn cell_values(&self, metric: CellMetric) -> Vec<f64> {
        if self.ni < 2 || self.nj < 2 {
            return vec![];
        }
        let fields = if self.planar {
            quality::cell_fields2d(&Grid2::from_fn(self.ni, self.nj, |i, j| {
                let p = self.p(i, j);
                [p[0], p[1]]
            }))
        } else {
            quality::cell_fields_surface(&self.grid())
        };
        fields
            .into_iter()
            .find(|(n, _)| *n == metric.field())
            .map(|(_, v)| v)
            .unwrap_or_default()
    }

    /// Node values of `metric`: the mean over the (finite) values of the adjacent cells, NaN
    /// where there is none.
    pub fn node_values(&self, metric: CellMetric) -> Vec<f64> {
        let cells = self.cell_values(metric);
        let mut sum = vec![0.0; self.points.len()];
        let mut cnt = vec![0u32; self.points.len()];
        for (q, &c) in self.quads().zip(&cells) {
            if c.is_finite() {
                for &k in &q {
                    sum[k] += c;
                    cnt[k] += 1;
                }
            }
        }
        sum.iter()
            .zip(&cnt)
            .map(|(&s, &c)| if c > 0 { s / c as f64 } else { f64::NAN })
            .collect()
    }

    /// True if every coordinate is finite.
    pub fn all_finite(&self) -> bool {
        self.points.iter().flatten().all(|v| v.is_finite())
    }
}

/// The patches of a block (module docs give their order and orientation).
pub fn block_patches(b: &Block) -> Vec<Patch> {
    match b {
        Block::Planar(g) => {
            let mut p = Patch::from_fn(g.ni(), g.nj(), |i, j| {
                let q = g.point(i, j);
                [q[0], q[1], 0.0]
            });
            p.planar = true;
            let area: f64 = p.quads().map(|q| p.quad_area(q)[2]).sum();
            if area < 0.0 {
                p.flip();
            }
            vec![p]
        }
        Block::Surface(g) => vec![Patch::from_fn(g.ni(), g.nj(), |i, j| g.point(i, j))],
        Block::Volume(g) => {
            let [ni, nj, nk] = g.dims();
            let mut faces = Vec::with_capacity(6);
            for (i, flip) in [(0, true), (ni - 1, false)] {
                let mut p = Patch::from_fn(nj, nk, |j, k| g.point(i, j, k));
                if flip {
                    p.flip();
                }
                faces.push(p);
            }
            for (j, flip) in [(0, false), (nj - 1, true)] {
                let mut p = Patch::from_fn(ni, nk, |i, k| g.point(i, j, k));
                if flip {
                    p.flip();
                }
                faces.push(p);
            }
            for (k, flip) in [(0, true), (nk - 1, false)] {
                let mut p = Patch::from_fn(ni, nj, |i, j| g.point(i, j, k));
                if flip {
                    p.flip();
                }
                faces.push(p);
            }
            // A left-handed block encloses a negative volume with these faces: turn them out.
            let vol: f64 = faces.iter().map(Patch::signed_volume).sum();
            if vol < 0.0 {
                faces.iter_mut().for_each(Patch::flip);
            }
            faces
        }
    }
}

/// Range (min, max) of the finite values; (0, 1) if there is none, widened if min = max.
pub fn value_range<'a>(values: impl IntoIterator<Item = &'a f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &v in values {
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if lo > hi {
        return (0.0, 1.0);
    }
    if hi - lo <= 1e-12 * hi.abs().max(1.0) {
        let w = 0.5 * hi.abs().max(1.0) * 1e-3;
        return (lo - w, hi + w);
    }
    (lo, hi)
}

/// Colour of t ∈ [0, 1] on a viridis-like map (dark blue → green → yellow), sRGB in [0, 1].
/// NaN gives grey.
pub fn colormap(t: f64) -> [f64; 3] {
    const STOPS: [[f64; 3]; 5] = [
        [0.267, 0.005, 0.329],
        [0.230, 0.322, 0.546],
        [0.128, 0.567, 0.551],
        [0.370, 0.789, 0.383],
        [0.993, 0.906, 0.144],
    ];
    if t.is_nan() {
        return [0.6, 0.6, 0.6];
    }
    let x = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let k = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - k as f64;
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    [0, 1, 2].map(|c| a[c] + f * (b[c] - a[c]))
}

/// A distinct colour per block (Tableau 10), sRGB in [0, 1].
pub fn block_color(k: usize) -> [f64; 3] {
    const C: [u32; 10] = [
        0x4e79a7, 0xf28e2b, 0xe15759, 0x76b7b2, 0x59a14f, 0xedc948, 0xb07aa1, 0xff9da7, 0x9c755f,
        0xbab0ac,
    ];
    let c = C[k % C.len()];
    [16, 8, 0].map(|s| ((c >> s) & 0xff) as f64 / 255.0)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = dot(v, v).sqrt();
    (n > 0.0 && n.is_finite()).then(|| [v[0] / n, v[1] / n, v[2] / n])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Grid3;

    fn cube(n: usize, mirror: bool) -> Block {
        let mut g = Grid3::zeros(n, n + 1, n + 2);
        let [a, b, c] = g.dims();
        for k in 0..c {
            for j in 0..b {
                for i in 0..a {
                    let x = i as f64 / (a - 1) as f64;
                    let x = if mirror { -x } else { x };
                    g.set(
                        i,
                        j,
                        k,
                        [x, j as f64 / (b - 1) as f64, k as f64 / (c - 1) as f64],
                    );
                }
            }
        }
        Block::Volume(g)
    }

    #[test]
    fn volume_faces_point_outward_for_either_handedness() {
        for mirror in [false, true] {
            let faces = block_patches(&cube(3, mirror));
            assert_eq!(faces.len(), 6);
            let vol: f64 = faces.iter().map(Patch::signed_volume).sum();
            assert!((vol - 1.0).abs() < 1e-12, "enclosed volume {vol}");
            for f in &faces {
                // Centre of the face minus the cube centre points along the face normal.
                let n = f.normals()[f.ni / 2 + f.ni * (f.nj / 2)];
                let c = f.p(f.ni / 2, f.nj / 2);
                let centre = [if mirror { -0.5 } else { 0.5 }, 0.5, 0.5];
                assert!(dot(n, sub(c, centre)) > 0.4, "inward normal {n:?} at {c:?}");
            }
        }
    }

    /// A sector whose side i = 0 is one point: its cells there are triangles (the point
    /// once), the others quads; every vertex normal is +z (none NaN).
    #[test]
    fn cells_along_a_collapsed_side_are_triangles() {
        let p = Patch::from_fn(4, 3, |i, j| {
            let (r, a) = (i as f64, 0.3 * j as f64);
            [r * a.cos(), r * a.sin(), 0.0]
        });
        let polys: Vec<([usize; 4], usize)> = p.polygons().collect();
        assert_eq!(polys.len(), 6);
        // cells (0, 0), (0, 1): nodes 0, 1, 5 and 4, 5, 9 (node 4 = node 0 dropped, 8 = 4)
        assert_eq!(polys[0], ([0, 1, 5, 0], 3));
        assert_eq!(polys[3], ([4, 5, 9, 0], 3));
        assert!(polys.iter().filter(|q| q.1 == 4).count() == 4);
        assert!(
            p.normals().iter().all(|n| (n[2] - 1.0).abs() < 1e-14),
            "{:?}",
            p.normals()
        );
    }

    #[test]
    fn planar_left_handed_grid_is_flipped_to_face_z() {
        let g = Grid2::<2>::from_fn(4, 3, |i, j| [-(i as f64), j as f64]);
        let p = &block_patches(&Block::Planar(g))[0];
        assert!(p.normals().iter().all(|n| (n[2] - 1.0).abs() < 1e-14));
        assert_eq!(p.p(0, 0), [-3.0, 0.0, 0.0]);
    }

    #[test]
    fn segments_and_node_values() {
        let g = Grid2::<2>::from_fn(4, 3, |i, j| [i as f64 + 0.5 * j as f64, j as f64]);
        let p = &block_patches(&Block::Planar(g))[0];
        assert_eq!(p.segments().len(), 3 * 3 + 4 * 2);
        assert_eq!(p.quads().count(), 6);
        // A uniformly sheared grid: every cell has the same skewness, so every node too.
        let s = p.node_values(CellMetric::Skewness);
        let expect = 0.5f64.atan().to_degrees() / 90.0;
        for v in s {
            assert!((v - expect).abs() < 1e-12, "{v} vs {expect}");
        }
    }

    #[test]
    fn colormap_ends_and_range() {
        assert_eq!(colormap(0.0), [0.267, 0.005, 0.329]);
        assert_eq!(colormap(1.0), [0.993, 0.906, 0.144]);
        assert_eq!(colormap(f64::NAN), [0.6, 0.6, 0.6]);
        assert_eq!(value_range(&[1.0, f64::NAN, 3.0]), (1.0, 3.0));
        let (a, b) = value_range(&[2.0, 2.0]);
        assert!(a < 2.0 && b > 2.0);
    }
}
