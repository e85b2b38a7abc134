//! The six boundary faces of a volume block, their shared edges and index arithmetic.
//!
//! # Face orientation
//! Faces follow METHOD.md: F1 ξ = 0, F2 ξ = 1, F3 η = 0, F4 η = 1, F5 ζ = 0, F6 ζ = 1. Each face
//! is a `Grid2<3>` whose two indices (a, b) run along the block's two remaining index
//! directions in increasing order, the lower one first (fastest):
//!
//! | face | a | b | face node (a, b) is block node |
//! |---|---|---|---|
//! | F1, F2 | j | k | (0, a, b), (N, a, b) |
//! | F3, F4 | i | k | (a, 0, b), (a, M, b) |
//! | F5, F6 | i | j | (a, b, 0), (a, b, L) |
//!
//! This is the order in which a face sits in a Plot3D volume record, so faces cut out of a
//! volume grid need no reordering. Edges (METHOD.md): E1–E4 along ξ at (η, ζ) = (0,0), (1,0),
//! (0,1), (1,1); E5–E8 along η at (ξ, ζ) = …; E9–E12 along ζ at (ξ, η) = ….

use crate::{Error, Grid2, Grid3, Result};

/// Face names, in the order of [`Faces`].
pub const FACE_NAMES: [&str; 6] = ["F1", "F2", "F3", "F4", "F5", "F6"];

/// For each edge E1..E12: the two faces that share it (0-based).
pub const EDGE_FACES: [[usize; 2]; 12] = [
    [2, 4],
    [3, 4],
    [2, 5],
    [3, 5],
    [0, 4],
    [1, 4],
    [0, 5],
    [1, 5],
    [0, 2],
    [1, 2],
    [0, 3],
    [1, 3],
];

/// Six validated faces of an `ni × nj × nk` block.
#[derive(Clone, Debug, PartialEq)]
pub struct Faces {
    dims: [usize; 3],
    faces: [Grid2<3>; 6],
}

/// Face-node (a, b) → block node (i, j, k) of face `f` in a block of `dims`.
#[inline]
pub fn block_node(f: usize, a: usize, b: usize, dims: [usize; 3]) -> [usize; 3] {
    let [ni, nj, nk] = dims;
    match f {
        0 => [0, a, b],
        1 => [ni - 1, a, b],
        2 => [a, 0, b],
        3 => [a, nj - 1, b],
        4 => [a, b, 0],
        _ => [a, b, nk - 1],
    }
}

/// The (ni, nj) a face must have in a block of `dims`.
pub fn face_dims(f: usize, dims: [usize; 3]) -> [usize; 2] {
    let [ni, nj, nk] = dims;
    match f / 2 {
        0 => [nj, nk],
        1 => [ni, nk],
        _ => [ni, nj],
    }
}

/// Block nodes (i, j, k) of edge `e` (0-based, E1 = 0), in increasing index order.
pub fn edge_nodes(e: usize, dims: [usize; 3]) -> Vec<[usize; 3]> {
    let [ni, nj, nk] = dims;
    let hi = |n: usize, up: bool| if up { n - 1 } else { 0 };
    let (b1, b2) = ((e % 4) & 1 == 1, (e % 4) & 2 == 2);
    match e / 4 {
        0 => (0..ni).map(|i| [i, hi(nj, b1), hi(nk, b2)]).collect(),
        1 => (0..nj).map(|j| [hi(ni, b1), j, hi(nk, b2)]).collect(),
        _ => (0..nk).map(|k| [hi(ni, b1), hi(nj, b2), k]).collect(),
    }
}

impl Faces {
    /// Validates six faces (orientation in the module docs): every face at least 2 × 2 nodes
    /// with counts that fit one block, finite coordinates, and each of the twelve edges the
    /// same on both faces that share it, within `1e-6` of the block's size. `place` names the
    /// block in errors; errors name the faces and the edge.
    pub fn new(faces: [Grid2<3>; 6], place: &str) -> Result<Self> {
        let [f1, _, f3, ..] = &faces;
        let dims = [f3.ni(), f1.ni(), f1.nj()];
        if dims.iter().any(|&n| n < 3) {
            return Err(Error::input(
                place,
                format!(
                    "a volume block needs at least 3 nodes each way, got {} × {} × {}",
                    dims[0], dims[1], dims[2]
                ),
            ));
        }
        for (f, g) in faces.iter().enumerate() {
            let want = face_dims(f, dims);
            if [g.ni(), g.nj()] != want {
                return Err(Error::input(
                    place,
                    format!(
                        "face {} has {} × {} nodes but the block ({} × {} × {}) needs {} × {}",
                        FACE_NAMES[f],
                        g.ni(),
                        g.nj(),
                        dims[0],
                        dims[1],
                        dims[2],
                        want[0],
                        want[1]
                    ),
                ));
            }
            if !g.all_finite() {
                return Err(Error::input(
                    place,
                    format!("face {} has non-finite coordinates", FACE_NAMES[f]),
                ));
            }
        }
        let size = faces.iter().map(|g| g.diameter()).fold(0.0, f64::max);
        if size <= 0.0 {
            return Err(Error::input(place, "the faces have zero size"));
        }
        let tol = 1e-6 * size;
        let out = Faces { dims, faces };
        for (e, [fa, fb]) in EDGE_FACES.iter().enumerate() {
            for (n, node) in edge_nodes(e, dims).into_iter().enumerate() {
                let (pa, pb) = (out.face_point(*fa, node), out.face_point(*fb, node));
                let d = (0..3).map(|c| (pa[c] - pb[c]).powi(2)).sum::<f64>().sqrt();
                if d > tol {
                    return Err(Error::input(
                        place,
                        format!(
                            "faces {} and {} do not meet on edge E{}: node {n} differs by \
                             {d:.3e} (tolerance {tol:.1e})",
                            FACE_NAMES[*fa],
                            FACE_NAMES[*fb],
                            e + 1
                        ),
                    ));
                }
            }
        }
        Ok(out)
    }

    /// The six faces of a volume grid (its boundary).
    pub fn from_grid(g: &Grid3) -> Self {
        let dims = g.dims();
        let faces = std::array::from_fn(|f| {
            let [na, nb] = face_dims(f, dims);
            Grid2::<3>::from_fn(na, nb, |a, b| {
                let [i, j, k] = block_node(f, a, b, dims);
                g.point(i, j, k)
            })
        });
        Faces { dims, faces }
    }

    /// Node counts (ni, nj, nk) of the block.
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// Face `f` (0 = F1, …, 5 = F6).
    pub fn face(&self, f: usize) -> &Grid2<3> {
        &self.faces[f]
    }

    /// The point of face `f` at block node `n` (which must lie on that face).
    #[inline]
    pub fn face_point(&self, f: usize, n: [usize; 3]) -> [f64; 3] {
        let (a, b) = match f / 2 {
            0 => (n[1], n[2]),
            1 => (n[0], n[2]),
            _ => (n[0], n[1]),
        };
        self.faces[f].point(a, b)
    }

    /// The boundary point at block node `n` (on some face): from the first face holding it.
    #[inline]
    pub fn boundary_point(&self, n: [usize; 3]) -> [f64; 3] {
        let [ni, nj, nk] = self.dims;
        let f = if n[0] == 0 {
            0
        } else if n[0] == ni - 1 {
            1
        } else if n[1] == 0 {
            2
        } else if n[1] == nj - 1 {
            3
        } else if n[2] == 0 {
            4
        } else {
            debug_assert_eq!(n[2], nk - 1);
            5
        };
        self.face_point(f, n)
    }

    /// The points of edge `e` (0-based), in increasing index order.
    pub fn edge(&self, e: usize) -> Vec<[f64; 3]> {
        let f = EDGE_FACES[e][0];
        edge_nodes(e, self.dims)
            .into_iter()
            .map(|n| self.face_point(f, n))
            .collect()
    }

    /// Writes the boundary nodes of `g` from the faces (interior untouched).
    pub fn apply_to(&self, g: &mut Grid3) {
        assert_eq!(g.dims(), self.dims);
        for f in (0..6).rev() {
            let [na, nb] = face_dims(f, self.dims);
            for b in 0..nb {
                for a in 0..na {
                    let [i, j, k] = block_node(f, a, b, self.dims);
                    g.set(i, j, k, self.faces[f].point(a, b));
                }
            }
        }
    }

    /// Bounding-box diagonal of the faces: the length scale of relative tolerances.
    pub fn diameter(&self) -> f64 {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for g in &self.faces {
            for c in 0..3 {
                for &v in g.coord(c) {
                    lo[c] = lo[c].min(v);
                    hi[c] = hi[c].max(v);
                }
            }
        }
        (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt()
    }
}

/// Position of a block edge (0-based, E1 = 0): the edge along axis `d` through block node `n`
/// (at the low or high end of the two other axes).
pub fn edge_of(d: usize, n: [usize; 3], dims: [usize; 3]) -> usize {
    let o: Vec<usize> = (0..3).filter(|&a| a != d).collect();
    let hi = |a: usize| usize::from(n[a] == dims[a] - 1 && n[a] > 0);
    4 * d + hi(o[0]) + 2 * hi(o[1])
}

/// The four block edges (0-based) bounding face `f`, as the sides of the face's (a, b) index
/// square: along a at b = 0, along a at b = end, along b at a = 0, along b at a = end (the
/// order of a 2D block's E3, E4, E1, E2).
pub fn face_edges(f: usize) -> [usize; 4] {
    let dims = [2, 2, 2];
    let (ta, tb) = tangents(f);
    [
        edge_of(ta, block_node(f, 0, 0, dims), dims),
        edge_of(ta, block_node(f, 0, 1, dims), dims),
        edge_of(tb, block_node(f, 0, 0, dims), dims),
        edge_of(tb, block_node(f, 1, 0, dims), dims),
    ]
}

/// How a face grid's own indices (p, q) run along a block face's indices (a, b): p runs along
/// b if `transpose` (else along a), q along the other; `rev_p`, `rev_q` reverse them. The
/// eight symmetries of the index square; the `orient` strings of a faces file ("ab", "-ba",
/// …) name the same eight.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Orient {
    pub transpose: bool,
    pub rev_p: bool,
    pub rev_q: bool,
}

impl Orient {
    /// p = a, q = b.
    pub const IDENTITY: Orient = Orient {
        transpose: false,
        rev_p: false,
        rev_q: false,
    };

    /// The eight orientations, the identity first.
    pub fn all() -> [Orient; 8] {
        std::array::from_fn(|m| Orient {
            transpose: m & 4 != 0,
            rev_p: m & 1 != 0,
            rev_q: m & 2 != 0,
        })
    }

    /// Parses "ab", "ba", "-ab", "a-b", "-a-b", "-ba", "b-a", "-b-a": the letters name the
    /// block-face index along the face's p and q, a "-" before a letter reverses it.
    pub fn parse(spec: &str) -> Option<Orient> {
        let mut letters = Vec::new();
        let mut neg = false;
        for ch in spec.chars() {
            match ch {
                '-' if !neg => neg = true,
                'a' | 'b' => {
                    letters.push((ch, neg));
                    neg = false;
                }
                _ => return None,
            }
        }
        match letters[..] {
            [(p, rp), (q, rq)] if p != q && !neg => Some(Orient {
                transpose: p == 'b',
                rev_p: rp,
                rev_q: rq,
            }),
            _ => None,
        }
    }

    /// The face's node counts (np, nq) from the block face's (na, nb).
    pub fn face_dims(self, [na, nb]: [usize; 2]) -> [usize; 2] {
        if self.transpose {
            [nb, na]
        } else {
            [na, nb]
        }
    }

    /// The block face's node counts (na, nb) from the face's (np, nq).
    pub fn block_dims(self, [np, nq]: [usize; 2]) -> [usize; 2] {
        self.face_dims([np, nq])
    }

    /// Face node (p, q) of block-face node (a, b); `face` = the face's (np, nq).
    #[inline]
    pub fn face_node(self, a: usize, b: usize, face: [usize; 2]) -> [usize; 2] {
        let (u, v) = if self.transpose { (b, a) } else { (a, b) };
        [
            if self.rev_p { face[0] - 1 - u } else { u },
            if self.rev_q { face[1] - 1 - v } else { v },
        ]
    }

    /// Block-face node (a, b) of face node (p, q) (the inverse of [`Orient::face_node`]).
    #[inline]
    pub fn block_face_node(self, p: usize, q: usize, face: [usize; 2]) -> [usize; 2] {
        let u = if self.rev_p { face[0] - 1 - p } else { p };
        let v = if self.rev_q { face[1] - 1 - q } else { q };
        if self.transpose {
            [v, u]
        } else {
            [u, v]
        }
    }

    /// The face grid `g` (np × nq) seen in block-face indices (na × nb).
    pub fn to_block_face(self, g: &Grid2<3>) -> Grid2<3> {
        let face = [g.ni(), g.nj()];
        let [na, nb] = self.block_dims(face);
        Grid2::<3>::from_fn(na, nb, |a, b| {
            let [p, q] = self.face_node(a, b, face);
            g.point(p, q)
        })
    }
}

/// Parses a face name "F1" … "F6" into 0 … 5.
pub fn parse_face(s: &str) -> Option<usize> {
    FACE_NAMES
        .iter()
        .position(|f| f.eq_ignore_ascii_case(s.trim()))
}

/// Normal axis of face f (0 = i, 1 = j, 2 = k) and whether the face is at the low end.
pub fn normal(f: usize) -> (usize, bool) {
    (f / 2, f % 2 == 0)
}

/// Tangential axes (a, b) of face f.
pub fn tangents(f: usize) -> (usize, usize) {
    match f / 2 {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

/// The wall-side neighbour of block node n along axis d (one step into the block).
pub fn step_in(n: [usize; 3], d: usize, lo: bool) -> [usize; 3] {
    let mut m = n;
    if lo {
        m[d] += 1;
    } else {
        m[d] -= 1;
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebraic::transfinite3d::transfinite;

    fn warped(i: usize, j: usize, k: usize) -> [f64; 3] {
        let (x, y, z) = (i as f64 / 4.0, j as f64 / 3.0, k as f64 / 5.0);
        [x + 0.1 * y * z, y + 0.05 * x * x, z + 0.1 * x * y]
    }

    #[test]
    fn faces_of_a_grid_round_trip_and_tfi_reproduces_trilinear_maps() {
        let mut g = Grid3::zeros(5, 4, 6);
        for k in 0..6 {
            for j in 0..4 {
                for i in 0..5 {
                    g.set(i, j, k, warped(i, j, k));
                }
            }
        }
        let f = Faces::from_grid(&g);
        let f2 = Faces::new(f.faces.clone(), "b").unwrap();
        assert_eq!(f, f2);
        // The map is trilinear-plus-quadratic in i only along faces: TFI reproduces it.
        let t = transfinite(&f);
        for c in 0..3 {
            for (u, v) in t.coord(c).iter().zip(g.coord(c)) {
                assert!((u - v).abs() < 1e-14);
            }
        }
        assert_eq!(f.edge(8).len(), 6);
        // A face cut out in any orientation comes back in block-face indices.
        for o in Orient::all() {
            let stored =
                Grid2::<3>::from_fn(o.face_dims([5, 6])[0], o.face_dims([5, 6])[1], |p, q| {
                    let [a, b] = o.block_face_node(p, q, o.face_dims([5, 6]));
                    f.face(2).point(a, b)
                });
            assert_eq!(&o.to_block_face(&stored), f.face(2), "{o:?}");
        }
        assert_eq!(face_edges(2), [0, 2, 8, 9]);
        assert_eq!(face_edges(4), [0, 1, 4, 5]);
        assert_eq!(
            Orient::parse("-ba"),
            Some(Orient {
                transpose: true,
                rev_p: true,
                rev_q: false
            })
        );
        assert_eq!(Orient::parse("aa"), None);
        assert_eq!(f.edge(8)[2], warped(0, 0, 2));
    }

    #[test]
    fn faces_that_do_not_meet_are_named() {
        let g = Grid3::from_coords(
            3,
            3,
            3,
            std::array::from_fn(|c| (0..27).map(|p| ((p / [1, 3, 9][c]) % 3) as f64).collect()),
        );
        let mut f = Faces::from_grid(&g).faces;
        f[3].set(0, 1, [5.0, 5.0, 5.0]); // F4 node (i = 0, k = 1): on edge E11 with F1
        let e = Faces::new(f, "case: block 'b'").unwrap_err().to_string();
        assert!(e.contains("F1 and F4") && e.contains("E11"), "{e}");
    }
}
