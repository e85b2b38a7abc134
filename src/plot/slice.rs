//! Cuts of volume grids by a coordinate plane (`ellipgrid plot --slice z=0.05`): the horizontal
//! and vertical planes of the paper's Figs 37–42, which are not grid planes of a C–O grid.
//!
//! Every grid surface of a volume block (i, j or k = const) is a quad mesh; where the plane
//! crosses one of its quads the cut is a segment between the crossings on the quad's edges
//! (linear along each edge; a quad crossed on all four edges is split by the sign at its centre,
//! as in marching squares). The segments of all three families form the grid the plane sees;
//! those on the block's six faces are its boundary.

use super::View;
use crate::Grid3;

/// The coordinate plane x = c (axis 0), y = c (1) or z = c (2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slice {
    /// 0, 1, 2 for x, y, z.
    pub axis: usize,
    /// The plane's coordinate.
    pub at: f64,
}

/// One segment of a cut: its two ends and whether it lies on a face of its block.
pub type Segment = ([f64; 3], [f64; 3], bool);

impl Slice {
    /// Parses "x=0.5", "y=0", "z=-1e-2" (a finite coordinate).
    pub fn parse(s: &str) -> Option<Slice> {
        let (a, v) = s.split_once('=')?;
        let at: f64 = v.trim().parse().ok().filter(|v: &f64| v.is_finite())?;
        let axis = match a.trim().to_ascii_lowercase().as_str() {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return None,
        };
        Some(Slice { axis, at })
    }

    /// The view looking at the plane: xy for z = c, xz for y = c, yz for x = c.
    pub fn view(self) -> View {
        match self.axis {
            0 => View::Yz,
            1 => View::Xz,
            _ => View::Xy,
        }
    }

    /// "z=0.05".
    pub fn label(self) -> String {
        format!("{}={}", ["x", "y", "z"][self.axis], self.at)
    }
}

/// The cut of volume grid `g` by plane `s` (module docs).
pub fn cut(g: &Grid3, s: Slice) -> Vec<Segment> {
    let dims = g.dims();
    let mut out = Vec::new();
    if dims.iter().any(|&n| n < 2) {
        return out;
    }
    for d in 0..3 {
        let (a, b) = ((d + 1) % 3, (d + 2) % 3);
        let node = |n: usize, u: usize, v: usize| {
            let mut m = [0; 3];
            (m[d], m[a], m[b]) = (n, u, v);
            g.point(m[0], m[1], m[2])
        };
        for n in 0..dims[d] {
            let boundary = n == 0 || n + 1 == dims[d];
            for v in 0..dims[b] - 1 {
                for u in 0..dims[a] - 1 {
                    let c = [
                        node(n, u, v),
                        node(n, u + 1, v),
                        node(n, u + 1, v + 1),
                        node(n, u, v + 1),
                    ];
                    quad(c, s, boundary, &mut out);
                }
            }
        }
    }
    out
}

/// The cut of one quad (corners in loop order) by the plane, appended to `out`.
fn quad(c: [[f64; 3]; 4], s: Slice, boundary: bool, out: &mut Vec<Segment>) {
    let f = c.map(|p| p[s.axis] - s.at);
    let below = f.map(|v| v < 0.0);
    if below.iter().all(|&b| b) || below.iter().all(|&b| !b) {
        return;
    }
    // Crossings on edges e = (c_e, c_e+1).
    let mut x: [Option<[f64; 3]>; 4] = [None; 4];
    for (e, xe) in x.iter_mut().enumerate() {
        let (p, q) = (e, (e + 1) % 4);
        if below[p] != below[q] {
            let t = f[p] / (f[p] - f[q]);
            let mut pt: [f64; 3] = std::array::from_fn(|k| c[p][k] + t * (c[q][k] - c[p][k]));
            pt[s.axis] = s.at;
            *xe = Some(pt);
        }
    }
    let hits: Vec<[f64; 3]> = x.iter().flatten().copied().collect();
    if hits.len() == 2 {
        out.push((hits[0], hits[1], boundary));
    } else if let [Some(e0), Some(e1), Some(e2), Some(e3)] = x {
        // Saddle: the centre's side decides which corners are cut off.
        let centre_below = f.iter().sum::<f64>() < 0.0;
        if centre_below == below[0] {
            out.push((e0, e1, boundary));
            out.push((e2, e3, boundary));
        } else {
            out.push((e3, e0, boundary));
            out.push((e1, e2, boundary));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn box_grid(n: usize, warp: f64) -> Grid3 {
        let h = 1.0 / (n - 1) as f64;
        Grid3::from_fn(n, n, n, |i, j, k| {
            let (x, y, z) = (i as f64 * h, j as f64 * h, k as f64 * h);
            [x, y, z + warp * (x - 0.5) * (y - 0.5)]
        })
    }

    #[test]
    fn parse_and_view() {
        assert_eq!(Slice::parse("z=0.5"), Some(Slice { axis: 2, at: 0.5 }));
        assert_eq!(
            Slice::parse(" Y = -1e-2"),
            Some(Slice { axis: 1, at: -0.01 })
        );
        assert_eq!(Slice::parse("k=3"), None);
        assert_eq!(Slice::parse("x=nan"), None);
        assert_eq!(Slice::parse("x="), None);
        assert_eq!(Slice { axis: 0, at: 1.0 }.view(), View::Yz);
        assert_eq!(Slice { axis: 2, at: 1.0 }.view(), View::Xy);
    }

    #[test]
    fn a_box_cut_between_its_k_planes_gives_its_tensor_grid() {
        // 5 × 5 × 5 nodes on the unit cube, z = 0.6: the i and j surfaces cut in 2 × 5 lines of
        // 4 segments each (0.25 long, every end at a node (x_i, y_j)), 16 of them on the faces;
        // the k surfaces do not reach z = 0.6 between their nodes.
        let g = box_grid(5, 0.0);
        let segs = cut(&g, Slice { axis: 2, at: 0.6 });
        assert_eq!(segs.len(), 40);
        assert_eq!(segs.iter().filter(|s| s.2).count(), 16);
        for (p, q, _) in &segs {
            assert_eq!((p[2], q[2]), (0.6, 0.6));
            let len = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
            assert!((len - 0.25).abs() < 1e-14, "{len}");
            for e in [p, q] {
                for c in &e[..2] {
                    assert!((c * 4.0 - (c * 4.0).round()).abs() < 1e-12, "{e:?}");
                }
            }
        }
        // Outside the box: nothing.
        assert!(cut(&g, Slice { axis: 0, at: 1.5 }).is_empty());
    }

    #[test]
    fn a_warped_box_is_cut_on_its_plane_and_inside_its_cells() {
        // The k surfaces bend (z + w(x − ½)(y − ½)): the cut at z = 0.5 crosses them as well.
        // Every end lies on the plane, on a grid edge (between two nodes whose z straddle it).
        let g = box_grid(9, 0.4);
        let s = Slice { axis: 2, at: 0.5 };
        let segs = cut(&g, s);
        assert!(segs.len() > 2 * 9 * 8, "{}", segs.len());
        let k_surface_segments = segs
            .iter()
            .filter(|(p, q, _)| (p[0] - q[0]).abs() > 1e-12 && (p[1] - q[1]).abs() > 1e-12)
            .count();
        assert!(k_surface_segments > 0);
        for (p, q, _) in &segs {
            assert_eq!((p[2], q[2]), (0.5, 0.5));
            for e in [p, q] {
                assert!(e[0] >= -1e-12 && e[0] <= 1.0 + 1e-12 && e[1] >= -1e-12);
            }
        }
    }

    #[test]
    fn a_saddle_quad_is_split_by_the_sign_at_its_centre() {
        // Corners (0,0), (1,0), (1,1), (0,1) at z = 1, −1, 3, −1, cut at z = 0: the centre
        // (z = 0.5) is above, so the two corners below are cut off, each by its own segment.
        let c = [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, -1.0],
            [1.0, 1.0, 3.0],
            [0.0, 1.0, -1.0],
        ];
        let mut out = Vec::new();
        quad(c, Slice { axis: 2, at: 0.0 }, false, &mut out);
        let ends: Vec<[f64; 4]> = out
            .iter()
            .map(|(p, q, _)| [p[0], p[1], q[0], q[1]])
            .collect();
        assert_eq!(ends, vec![[0.5, 0.0, 1.0, 0.25], [0.25, 1.0, 0.0, 0.5]]);
        // With the centre below, the corners above are cut off instead.
        let c = [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, -3.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, -3.0],
        ];
        out.clear();
        quad(c, Slice { axis: 2, at: 0.0 }, false, &mut out);
        let ends: Vec<[f64; 4]> = out
            .iter()
            .map(|(p, q, _)| [p[0], p[1], q[0], q[1]])
            .collect();
        assert_eq!(ends, vec![[0.0, 0.25, 0.25, 0.0], [1.0, 0.75, 0.75, 1.0]]);
    }
}
