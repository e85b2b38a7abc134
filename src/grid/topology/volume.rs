//! Volume (3D multi-block) topology: named faces, each four sides of edges (the blocks of a 2D
//! [`Topology`] whose pieces are faces), and volumes by six faces F1 … F6 (METHOD.md
//! numbering), every face shared by the volumes on either side of it (ENGRID's blocks with
//! common faces, paper §5.3, Figs 37–42).
//!
//! A face's grid is computed once in its own indices (p, q) (p along its sides E3/E4, q along
//! E1/E2); a volume sees it through an [`Orient`] worked out from the vertices: the volume's
//! corner (i, j, k) ∈ {0, end}³ is the one vertex that the three faces meeting there have in
//! common, and each face's orientation is the symmetry of the index square that puts its
//! corners there. Each of the volume's twelve edges must then be the same chain of edges on
//! both faces that share it. A [`Topology3`] knows names and counts only; the nodes come from
//! the case.

use super::{TopoBlock, Topology};
use crate::grid::faces::{block_node, face_dims, face_edges, Orient, EDGE_FACES, FACE_NAMES};
use crate::grid::Edge;
use crate::{Error, Grid2, Result};

/// A face as a volume uses it: the face and how its indices run along the volume face's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaceUse {
    pub face: usize,
    pub orient: Orient,
}

/// A volume: its six faces F1 … F6 and its node counts (ni, nj, nk).
#[derive(Clone, Debug, PartialEq)]
pub struct TopoVolume {
    pub name: String,
    pub faces: [FaceUse; 6],
    pub dims: [usize; 3],
}

/// A volume as the case file gives it: the names of its faces F1 … F6.
#[derive(Clone, Debug)]
pub struct VolumeFaces {
    pub name: String,
    pub faces: [String; 6],
}

/// Faces (over vertices and edges) and the volumes they bound.
#[derive(Clone, Debug, PartialEq)]
pub struct Topology3 {
    /// Vertices, edges and faces (the faces are this topology's "blocks").
    pub faces: Topology,
    /// Boundary-patch family of each face.
    pub families: Vec<String>,
    pub volumes: Vec<TopoVolume>,
}

impl Topology3 {
    /// Resolves every volume's faces and their orientations and checks the topology:
    /// unknown or repeated faces, corners where the three faces share no single vertex, edges
    /// that two faces of a volume do not share, faces used by no volume or by more than two
    /// volume sides. `place` names the file.
    pub fn new(
        faces: Topology,
        families: Vec<String>,
        volumes: &[VolumeFaces],
        place: &str,
    ) -> Result<Self> {
        let mut names: Vec<&str> = Vec::new();
        for v in volumes {
            if v.name.is_empty() || names.contains(&v.name.as_str()) {
                return Err(Error::input(
                    place,
                    format!("volume name '{}': names are non-empty and unique", v.name),
                ));
            }
            names.push(&v.name);
        }
        let mut topo = Topology3 {
            faces,
            families,
            volumes: Vec::new(),
        };
        for v in volumes {
            let vol = topo.resolve(v, place)?;
            topo.volumes.push(vol);
        }
        for (f, face) in topo.faces.blocks.iter().enumerate() {
            let uses = topo.uses_of(f);
            let at = format!("{place}: face '{}'", face.name);
            match uses.len() {
                0 => {
                    return Err(Error::input(
                        at,
                        "the face is used by no volume (remove it or name it in a volume)",
                    ))
                }
                1 | 2 => {}
                k => {
                    return Err(Error::input(
                        at,
                        format!(
                            "the face bounds {k} volume sides ({}); a face bounds at most two",
                            uses.iter()
                                .map(|(v, s)| format!(
                                    "'{}' {}",
                                    topo.volumes[*v].name, FACE_NAMES[*s]
                                ))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ))
                }
            }
        }
        Ok(topo)
    }

    /// Every use of face `f` as (volume, side 0 … 5).
    pub fn uses_of(&self, f: usize) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (v, vol) in self.volumes.iter().enumerate() {
            for (s, u) in vol.faces.iter().enumerate() {
                if u.face == f {
                    out.push((v, s));
                }
            }
        }
        out
    }

    /// "file: volume 'name'".
    pub fn volume_place(&self, place: &str, v: usize) -> String {
        format!("{place}: volume '{}'", self.volumes[v].name)
    }

    /// The six boundary faces of volume `v` in its own face orientation
    /// ([`crate::grid::faces`]) from the grids of every face (each in its own indices).
    pub fn volume_faces(&self, v: usize, grids: &[Grid2<3>]) -> [Grid2<3>; 6] {
        let vol = &self.volumes[v];
        std::array::from_fn(|s| {
            let u = vol.faces[s];
            u.orient.to_block_face(&grids[u.face])
        })
    }

    /// Node counts (np, nq) of face `f` in its own indices.
    pub fn face_dims(&self, f: usize) -> [usize; 2] {
        self.faces.dims(f)
    }

    /// The volume node (i, j, k) of node (p, q) of the face on side `s` of volume `v`.
    pub fn volume_node(&self, v: usize, s: usize, p: usize, q: usize) -> [usize; 3] {
        let vol = &self.volumes[v];
        let u = vol.faces[s];
        let [a, b] = u.orient.block_face_node(p, q, self.face_dims(u.face));
        block_node(s, a, b, vol.dims)
    }

    /// The corner vertices of face `f` in its own indices: `c[p][q]`, p, q ∈ {0 (start),
    /// 1 (end)}.
    fn corners(&self, f: usize) -> [[usize; 2]; 2] {
        let t = &self.faces;
        let b: &TopoBlock = &t.blocks[f];
        let start = |side: Edge| {
            let u = b.sides[side.index()][0];
            let e = &t.edges[u.edge];
            if u.reversed {
                e.to
            } else {
                e.from
            }
        };
        let end = |side: Edge| {
            let u = *b.sides[side.index()].last().expect("sides are not empty");
            let e = &t.edges[u.edge];
            if u.reversed {
                e.from
            } else {
                e.to
            }
        };
        [
            [start(Edge::E3), end(Edge::E1)],
            [end(Edge::E3), end(Edge::E2)],
        ]
    }

    /// The chain of (edge, reversed) along side `side` of a face (E1 … E4 of its own
    /// indices), in the direction of its index.
    fn chain(&self, f: usize, side: Edge) -> Vec<(usize, bool)> {
        self.faces.blocks[f].sides[side.index()]
            .iter()
            .map(|u| (u.edge, u.reversed))
            .collect()
    }

    /// The chain of edges along one of the four sides of a volume face in the volume's
    /// index order: `which` = 0 along a at b = 0, 1 along a at b = end, 2 along b at a = 0,
    /// 3 along b at a = end (the order of [`face_edges`]).
    fn volume_face_chain(&self, u: FaceUse, which: usize) -> Vec<(usize, bool)> {
        let o = u.orient;
        // Along a (which 0, 1) or along b (2, 3); the fixed index at its low or high end.
        let along_a = which < 2;
        let high = which % 2 == 1;
        // In the face's own indices: a runs along p unless transposed.
        let along_p = along_a != o.transpose;
        // The fixed face index (q if running along p) at its low or high end.
        let fixed_rev = if along_p { o.rev_q } else { o.rev_p };
        let fixed_high = high != fixed_rev;
        let side = match (along_p, fixed_high) {
            (true, false) => Edge::E3,
            (true, true) => Edge::E4,
            (false, false) => Edge::E1,
            (false, true) => Edge::E2,
        };
        let run_rev = if along_p { o.rev_p } else { o.rev_q };
        let mut c = self.chain(u.face, side);
        if run_rev {
            c.reverse();
            for x in &mut c {
                x.1 = !x.1;
            }
        }
        c
    }

    fn resolve(&self, v: &VolumeFaces, place: &str) -> Result<TopoVolume> {
        let at = format!("{place}: volume '{}'", v.name);
        let mut ids = [0usize; 6];
        for (s, name) in v.faces.iter().enumerate() {
            ids[s] = self
                .faces
                .blocks
                .iter()
                .position(|b| &b.name == name)
                .ok_or_else(|| {
                    Error::input(&at, format!("{}: no face named '{name}'", FACE_NAMES[s]))
                })?;
        }
        for s in 0..6 {
            if let Some(t) = (0..s).find(|&t| ids[t] == ids[s]) {
                return Err(Error::input(
                    &at,
                    format!(
                        "face '{}' is both {} and {}; a volume's six faces are distinct",
                        v.faces[s], FACE_NAMES[t], FACE_NAMES[s]
                    ),
                ));
            }
        }
        let corner_set = |s: usize| -> Vec<usize> {
            let c = self.corners(ids[s]);
            vec![c[0][0], c[0][1], c[1][0], c[1][1]]
        };
        // Corner (ci, cj, ck): the vertex common to faces F(1+ci), F(3+cj), F(5+ck).
        let mut corner = [[[0usize; 2]; 2]; 2];
        for n in 0..8 {
            let (ci, cj, ck) = (n & 1, (n >> 1) & 1, n >> 2);
            let (a, b, c) = (corner_set(ci), corner_set(2 + cj), corner_set(4 + ck));
            let mut common: Vec<usize> = a
                .iter()
                .copied()
                .filter(|x| b.contains(x) && c.contains(x))
                .collect();
            common.sort_unstable();
            common.dedup();
            let names = [FACE_NAMES[ci], FACE_NAMES[2 + cj], FACE_NAMES[4 + ck]];
            match common[..] {
                [x] => corner[ci][cj][ck] = x,
                [] => {
                    return Err(Error::input(
                        &at,
                        format!(
                            "faces {} ('{}'), {} ('{}') and {} ('{}') share no corner vertex; \
                             the three faces meeting at a corner of a volume share one",
                            names[0],
                            v.faces[ci],
                            names[1],
                            v.faces[2 + cj],
                            names[2],
                            v.faces[4 + ck]
                        ),
                    ))
                }
                _ => {
                    return Err(Error::input(
                        &at,
                        format!(
                            "faces {}, {} and {} share {} corner vertices ({}); the corner is \
                             ambiguous (collapsed edges are not supported)",
                            names[0],
                            names[1],
                            names[2],
                            common.len(),
                            common
                                .iter()
                                .map(|&x| format!("'{}'", self.faces.vertices[x]))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ))
                }
            }
        }
        // Each face's orientation: its corners at the volume's.
        let dims2 = [2, 2, 2];
        let mut faces = [FaceUse {
            face: 0,
            orient: Orient::IDENTITY,
        }; 6];
        for s in 0..6 {
            let own = self.corners(ids[s]);
            let want = |a: usize, b: usize| {
                let [i, j, k] = block_node(s, a, b, dims2);
                corner[i][j][k]
            };
            let fits: Vec<Orient> = Orient::all()
                .into_iter()
                .filter(|o| {
                    (0..4).all(|m| {
                        let (a, b) = (m & 1, m >> 1);
                        let [p, q] = o.face_node(a, b, [2, 2]);
                        own[p][q] == want(a, b)
                    })
                })
                .collect();
            // Several fit only if corners repeat: the edge chains decide below.
            let ok: Vec<Orient> = fits
                .into_iter()
                .filter(|&o| {
                    let u = FaceUse {
                        face: ids[s],
                        orient: o,
                    };
                    self.chains_fit(s, u, &corner)
                })
                .collect();
            faces[s] = match ok[..] {
                [o, ..] => FaceUse {
                    face: ids[s],
                    orient: o,
                },
                [] => {
                    return Err(Error::input(
                        &at,
                        format!(
                            "face {} ('{}') does not fit: its corner vertices ({}) are not the \
                             volume's corners where {} lies",
                            FACE_NAMES[s],
                            v.faces[s],
                            [own[0][0], own[1][0], own[1][1], own[0][1]]
                                .iter()
                                .map(|&x| format!("'{}'", self.faces.vertices[x]))
                                .collect::<Vec<_>>()
                                .join(", "),
                            FACE_NAMES[s]
                        ),
                    ))
                }
            };
        }
        // Node counts, and every volume edge the same chain on its two faces.
        let fd = |s: usize| faces[s].orient.block_dims(self.faces.dims(faces[s].face));
        let dims = [fd(4)[0], fd(4)[1], fd(0)[1]];
        for (s, u) in faces.iter().enumerate() {
            let have = u.orient.block_dims(self.faces.dims(u.face));
            let want = face_dims(s, dims);
            if have != want {
                return Err(Error::input(
                    &at,
                    format!(
                        "face {} ('{}') has {} × {} nodes along the volume's directions, the \
                         volume ({} × {} × {}) needs {} × {}",
                        FACE_NAMES[s],
                        v.faces[s],
                        have[0],
                        have[1],
                        dims[0],
                        dims[1],
                        dims[2],
                        want[0],
                        want[1]
                    ),
                ));
            }
        }
        for (e, [fa, fb]) in EDGE_FACES.iter().enumerate() {
            let side = |f: usize| face_edges(f).iter().position(|&x| x == e).expect("edge");
            let (ca, cb) = (
                self.volume_face_chain(faces[*fa], side(*fa)),
                self.volume_face_chain(faces[*fb], side(*fb)),
            );
            if ca != cb {
                let names = |c: &[(usize, bool)]| {
                    c.iter()
                        .map(|(x, _)| format!("'{}'", self.faces.edges[*x].name))
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                return Err(Error::input(
                    &at,
                    format!(
                        "faces {} ('{}') and {} ('{}') do not share the volume's edge E{}: \
                         along it one has the edges {} and the other {}",
                        FACE_NAMES[*fa],
                        v.faces[*fa],
                        FACE_NAMES[*fb],
                        v.faces[*fb],
                        e + 1,
                        names(&ca),
                        names(&cb)
                    ),
                ));
            }
        }
        if dims.iter().any(|&n| n < 3) {
            return Err(Error::input(
                &at,
                format!("a volume needs at least 3 nodes each way, got {dims:?}"),
            ));
        }
        Ok(TopoVolume {
            name: v.name.clone(),
            faces,
            dims,
        })
    }

    /// True if each of the four sides of face `u` on side `s` runs between the volume's
    /// corners of that side (breaks ties between orientations that fit the corners).
    fn chains_fit(&self, s: usize, u: FaceUse, corner: &[[[usize; 2]; 2]; 2]) -> bool {
        // A side's chain must start and end at the volume's corners of that side.
        let dims2 = [2, 2, 2];
        (0..4).all(|which| {
            let c = self.volume_face_chain(u, which);
            let (a0, b0, a1, b1) = match which {
                0 => (0, 0, 1, 0),
                1 => (0, 1, 1, 1),
                2 => (0, 0, 0, 1),
                _ => (1, 0, 1, 1),
            };
            let [i0, j0, k0] = block_node(s, a0, b0, dims2);
            let [i1, j1, k1] = block_node(s, a1, b1, dims2);
            let first = c[0];
            let last = c[c.len() - 1];
            let e0 = &self.faces.edges[first.0];
            let e1 = &self.faces.edges[last.0];
            let from = if first.1 { e0.to } else { e0.from };
            let to = if last.1 { e1.from } else { e1.to };
            from == corner[i0][j0][k0] && to == corner[i1][j1][k1]
        })
    }

    /// The connectivity: a 1-to-1 interface per face two volumes share, a boundary patch per
    /// face one volume has (with the face's family), in face order.
    pub fn connectivity(&self) -> Connectivity3 {
        let mut c = Connectivity3::default();
        let side = |(volume, side): (usize, usize)| VolumeSide { volume, side };
        for f in 0..self.faces.blocks.len() {
            match self.uses_of(f)[..] {
                [a, b] => c.interfaces.push(FaceInterface {
                    face: f,
                    a: side(a),
                    b: side(b),
                }),
                [a] => c.patches.push(FacePatch {
                    face: f,
                    side: side(a),
                    family: self.families[f].clone(),
                }),
                _ => {}
            }
        }
        c
    }
}

/// One side (F1 … F6 as 0 … 5) of a volume.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VolumeSide {
    pub volume: usize,
    pub side: usize,
}

/// A face that two volume sides share node for node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaceInterface {
    pub face: usize,
    pub a: VolumeSide,
    pub b: VolumeSide,
}

/// A face on the boundary of the grid, with its family.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FacePatch {
    pub face: usize,
    pub side: VolumeSide,
    pub family: String,
}

/// Interfaces and boundary patches of a volume topology; together they cover every volume
/// side.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Connectivity3 {
    pub interfaces: Vec<FaceInterface>,
    pub patches: Vec<FacePatch>,
}
