//! A multi-block grid as one unstructured mesh, the form the solvers' own formats take
//! (OpenFOAM, SU2, Gmsh): the blocks' nodes merged through their 1-to-1 interfaces, the cells
//! (quadrilaterals or hexahedra, each right-handed), the faces where blocks meet (a C-grid's
//! wake cut included) and the boundary faces grouped by family, oriented out of the domain.
//! A planar grid can be extruded one cell thick (OpenFOAM is 3D only), with a `frontAndBack`
//! family on both sides.
//!
//! The connectivity is a [`ConnFile`] (1-based ranges, as `.conn` files hold it): from a case's
//! topology, read from a file beside a Plot3D grid, or [`sides_as_patches`] when nothing says
//! how the blocks meet. Interface nodes must coincide (to 1e-6 of the grid's size).

mod faces;
mod interface;
mod merge;

pub use crate::io::connectivity::{BcKind, FRONT_AND_BACK};
pub use faces::{Face, Join};
pub use interface::{one_to_one, OneToOne};

use crate::io::connectivity::{ConnFile, Range};
use crate::io::Block;
use crate::{Error, Result};

/// What the blocks are made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cells {
    /// Quadrilaterals in the plane (z = 0).
    Planar,
    /// Quadrilaterals on surfaces in space.
    Surface,
    /// Hexahedra (volume blocks, or planar blocks extruded).
    Volume,
}

/// One block of the merged mesh.
#[derive(Clone, Debug)]
pub struct MeshBlock {
    pub name: String,
    /// Node counts (ni, nj, nk); nk = 1 for quadrilateral blocks.
    pub dims: [usize; 3],
    /// Global node id of each block node, i fastest.
    pub ids: Vec<u32>,
    /// Index of the block's first cell; cells run i fastest.
    pub first_cell: usize,
    /// The block is left-handed: its cells' node order is reversed to make them right-handed.
    pub flip: bool,
    /// Id of the block's first node that repeats no earlier node; the block's new nodes
    /// have the ids from here on, in order.
    pub first_point: u32,
    /// Local indices of the nodes that repeat a node met earlier (interfaces), sorted.
    pub dups: Vec<u32>,
}

impl MeshBlock {
    /// Cell counts per direction (1 along k for quadrilateral blocks).
    pub fn cell_dims(&self) -> [usize; 3] {
        let [ni, nj, nk] = self.dims;
        [ni - 1, nj - 1, nk.saturating_sub(1).max(1)]
    }

    /// Number of cells.
    pub fn ncells(&self) -> usize {
        self.cell_dims().iter().product()
    }

    /// Global node id of block node (i, j, k).
    pub fn id(&self, i: usize, j: usize, k: usize) -> u32 {
        self.ids[i + self.dims[0] * (j + self.dims[1] * k)]
    }
}

/// The merged mesh. Its nodes' coordinates stay in the blocks it was built from
/// ([`Mesh::point`], [`Mesh::points_in`]): a merged node is numbered at its first occurrence
/// (blocks in order, i fastest) and has that node's coordinates.
#[derive(Clone, Debug)]
pub struct Mesh<'a> {
    pub cells: Cells,
    /// Planar blocks extruded by this span along z.
    pub extruded: Option<f64>,
    /// The blocks as nodes in space (planar ones extruded).
    views: Vec<View<'a>>,
    /// Number of merged nodes.
    npoints: usize,
    pub blocks: Vec<MeshBlock>,
    /// Faces between cells of different blocks, or across a cut of one block, sorted by
    /// (owner, neighbour).
    pub joins: Vec<Join>,
    /// Family names; [`Mesh::boundary`] holds each family's faces.
    pub families: Vec<String>,
    /// Each family's boundary condition (given, or by its name: [`ConnFile::bc`]).
    pub bcs: Vec<BcKind>,
    pub boundary: Vec<Vec<Face>>,
}

impl<'a> Mesh<'a> {
    /// Number of cells.
    pub fn ncells(&self) -> usize {
        self.blocks.iter().map(MeshBlock::ncells).sum()
    }

    /// Nodes per boundary face: 2 for quadrilateral cells, 4 for hexahedra.
    pub fn face_nodes(&self) -> usize {
        if self.cells == Cells::Volume {
            4
        } else {
            2
        }
    }

    /// Coordinates per point a format should write: 2 for a planar grid, else 3.
    pub fn space_dim(&self) -> usize {
        if self.cells == Cells::Planar {
            2
        } else {
            3
        }
    }

    /// Builds the mesh of `blocks` connected as `conn` says; `extrude` gives planar blocks
    /// that span along z (hexahedra, one layer). `place` names the grid in messages.
    ///
    /// # Errors
    /// [`Error::Input`] naming the block and range for blocks of mixed kinds, a range outside
    /// its block or of the wrong shape, interface sides with different node counts or nodes
    /// apart, a block side neither interface nor patch, a collapsed cell or face, or more than
    /// 2³² − 1 nodes.
    pub fn build(
        place: &str,
        blocks: &'a [(String, Block)],
        conn: &ConnFile,
        extrude: Option<f64>,
    ) -> Result<Mesh<'a>> {
        let bad = |m: String| Error::input(place, m);
        if blocks.is_empty() {
            return Err(bad("no blocks".into()));
        }
        let cells = match &blocks[0].1 {
            Block::Planar(_) if extrude.is_some() => Cells::Volume,
            Block::Planar(_) => Cells::Planar,
            Block::Surface(_) => Cells::Surface,
            Block::Volume(_) => Cells::Volume,
        };
        if let Some((name, b)) = blocks.iter().find(|(_, b)| b.kind() != blocks[0].1.kind()) {
            return Err(bad(format!(
                "block '{name}' is {} but block '{}' is {}: one mesh holds blocks of one kind",
                b.kind(),
                blocks[0].0,
                blocks[0].1.kind()
            )));
        }
        if let Some(span) = extrude {
            if !(span.is_finite() && span > 0.0) {
                return Err(bad(format!("extrusion span {span}: expected > 0")));
            }
        }
        let views: Vec<View> = blocks.iter().map(|(_, b)| View::new(b, extrude)).collect();
        if let Some((k, _)) = views
            .iter()
            .enumerate()
            .find(|(_, v)| v.dims.iter().take(2).any(|&n| n < 2))
        {
            return Err(bad(format!(
                "block '{}' has fewer than 2 nodes along a direction",
                blocks[k].0
            )));
        }
        let mut conn = conn.clone();
        if extrude.is_some() {
            extend_in_k(&mut conn, &views);
        }
        let (merged, npoints) = merge::merge(place, blocks, &views, &conn)?;
        let mut blocks_out = Vec::with_capacity(blocks.len());
        let mut first_cell = 0;
        for ((name, _), (v, m)) in blocks.iter().zip(views.iter().zip(merged)) {
            let b = MeshBlock {
                name: name.clone(),
                dims: v.dims,
                ids: m.ids,
                first_cell,
                flip: v.left_handed(),
                first_point: m.first_point,
                dups: m.dups,
            };
            first_cell += b.ncells();
            blocks_out.push(b);
        }
        let mut mesh = Mesh {
            cells,
            extruded: extrude,
            views: Vec::new(),
            npoints,
            blocks: blocks_out,
            joins: Vec::new(),
            families: Vec::new(),
            bcs: Vec::new(),
            boundary: Vec::new(),
        };
        faces::classify(place, &mut mesh, &views, blocks, &conn)?;
        mesh.views = views;
        Ok(mesh)
    }
}

/// A connectivity where nothing is known of how the blocks meet: every side of every block is
/// a patch of its own family, `BLOCK_E1` … `BLOCK_E4` (planar and surface blocks, the case
/// file's side names) or `BLOCK_F1` … `BLOCK_F6` (volume blocks).
pub fn sides_as_patches(blocks: &[(String, Block)]) -> ConnFile {
    let mut c = ConnFile::default();
    for (b, (name, block)) in blocks.iter().enumerate() {
        let [ni, nj, nk] = block.dims();
        let sides: Vec<(&str, [usize; 3], [usize; 3])> = if matches!(block, Block::Volume(_)) {
            vec![
                ("F1", [1, 1, 1], [1, nj, nk]),
                ("F2", [ni, 1, 1], [ni, nj, nk]),
                ("F3", [1, 1, 1], [ni, 1, nk]),
                ("F4", [1, nj, 1], [ni, nj, nk]),
                ("F5", [1, 1, 1], [ni, nj, 1]),
                ("F6", [1, 1, nk], [ni, nj, nk]),
            ]
        } else {
            vec![
                ("E1", [1, 1, 1], [1, nj, 1]),
                ("E2", [ni, 1, 1], [ni, nj, 1]),
                ("E3", [1, 1, 1], [ni, 1, 1]),
                ("E4", [1, nj, 1], [ni, nj, 1]),
            ]
        };
        for (side, lo, hi) in sides {
            let id = c.families.len() + 1;
            c.families.push((id, format!("{name}_{side}")));
            c.patches.push(((b + 1, lo, hi), id));
        }
    }
    c
}

/// Extends every range of a planar connectivity through the two node layers of the
/// extrusion, and adds the front (k = 1) and back (k = 2) of every block as one family.
fn extend_in_k(c: &mut ConnFile, views: &[View]) {
    for r in c.interfaces.iter_mut().flat_map(|r| r.iter_mut()) {
        r.1[2] = 1;
        r.2[2] = 2;
    }
    for (r, _) in c.patches.iter_mut() {
        r.1[2] = 1;
        r.2[2] = 2;
    }
    let id = c.families.iter().map(|f| f.0).max().unwrap_or(0) + 1;
    c.families.push((id, FRONT_AND_BACK.to_string()));
    for (b, v) in views.iter().enumerate() {
        let [ni, nj, _] = v.dims;
        c.patches.push(((b + 1, [1, 1, 1], [ni, nj, 1]), id));
        c.patches.push(((b + 1, [1, 1, 2], [ni, nj, 2]), id));
    }
}

/// A block seen as nodes (i, j, k) in space; planar blocks extruded get nk = 2.
#[derive(Clone, Debug)]
pub(crate) struct View<'a> {
    block: &'a Block,
    pub dims: [usize; 3],
    span: Option<f64>,
}

impl<'a> View<'a> {
    fn new(block: &'a Block, extrude: Option<f64>) -> Self {
        let mut dims = block.dims();
        let span = match block {
            Block::Planar(_) if extrude.is_some() => {
                dims[2] = 2;
                extrude
            }
            _ => None,
        };
        View { block, dims, span }
    }

    /// Node (i, j, k).
    pub fn point(&self, i: usize, j: usize, k: usize) -> [f64; 3] {
        let [ni, nj, _] = self.dims;
        match self.block {
            Block::Planar(g) => {
                let [x, y] = g.point(i, j);
                [x, y, self.span.map_or(0.0, |s| s * k as f64)]
            }
            Block::Surface(g) => g.point(i, j),
            Block::Volume(g) => {
                let n = i + ni * (j + nj * k);
                [g.coord(0)[n], g.coord(1)[n], g.coord(2)[n]]
            }
        }
    }

    /// Node `n` (local index, i fastest).
    pub fn point_at(&self, n: usize) -> [f64; 3] {
        if let Block::Volume(g) = self.block {
            return [g.coord(0)[n], g.coord(1)[n], g.coord(2)[n]];
        }
        let [ni, nj, _] = self.dims;
        self.point(n % ni, (n / ni) % nj, n / (ni * nj))
    }

    /// The block is left-handed: its cells' signed areas (planar) or volumes sum negative.
    fn left_handed(&self) -> bool {
        let [ni, nj, nk] = self.dims;
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let mut total = 0.0;
        match self.block {
            Block::Planar(_) | Block::Surface(_) if nk == 1 => {
                if matches!(self.block, Block::Surface(_)) {
                    return false; // a surface's orientation is its own
                }
                for j in 0..nj - 1 {
                    for i in 0..ni - 1 {
                        let d1 = sub(self.point(i + 1, j + 1, 0), self.point(i, j, 0));
                        let d2 = sub(self.point(i, j + 1, 0), self.point(i + 1, j, 0));
                        total += d1[0] * d2[1] - d1[1] * d2[0];
                    }
                }
            }
            _ => {
                for k in 0..nk - 1 {
                    for j in 0..nj - 1 {
                        for i in 0..ni - 1 {
                            let o = self.point(i, j, k);
                            let a = sub(self.point(i + 1, j, k), o);
                            let b = sub(self.point(i, j + 1, k), o);
                            let c = sub(self.point(i, j, k + 1), o);
                            total += a[0] * (b[1] * c[2] - b[2] * c[1])
                                - a[1] * (b[0] * c[2] - b[2] * c[0])
                                + a[2] * (b[0] * c[1] - b[1] * c[0]);
                        }
                    }
                }
            }
        }
        total < 0.0
    }
}

/// The diagonal of the bounding box of all nodes.
fn diameter(views: &[View]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in views {
        let [ni, nj, nk] = v.dims;
        for k in 0..nk {
            for j in 0..nj {
                for i in 0..ni {
                    let p = v.point(i, j, k);
                    for c in 0..3 {
                        lo[c] = lo[c].min(p[c]);
                        hi[c] = hi[c].max(p[c]);
                    }
                }
            }
        }
    }
    (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt()
}

/// A range's 0-based corners, checked against the block's node counts and to lie on a side.
pub(crate) fn corners(
    place: &str,
    blocks: &[(String, Block)],
    views: &[View],
    r: &Range,
    what: &str,
) -> Result<(usize, [usize; 3], [usize; 3])> {
    let b = r.0.wrapping_sub(1);
    let Some(v) = views.get(b) else {
        return Err(Error::input(
            place,
            format!(
                "{what}: block {} does not exist ({} blocks)",
                r.0,
                views.len()
            ),
        ));
    };
    let mut lo = [0; 3];
    let mut hi = [0; 3];
    for c in 0..3 {
        let n = v.dims[c];
        let (a, z) = (r.1[c], r.2[c]);
        if a == 0 || z == 0 || a > n || z > n {
            return Err(Error::input(
                place,
                format!(
                    "{what}: range {:?}…{:?} lies outside block '{}' ({} × {} × {} nodes)",
                    r.1, r.2, blocks[b].0, v.dims[0], v.dims[1], v.dims[2]
                ),
            ));
        }
        lo[c] = a - 1;
        hi[c] = z - 1;
    }
    // A side: one index (of a direction with more than one node) stays at its first or last
    // value. Anything else (an interior plane, the whole block) is no interface or patch.
    let on_side =
        (0..3).any(|c| v.dims[c] > 1 && lo[c] == hi[c] && (lo[c] == 0 || lo[c] == v.dims[c] - 1));
    if !on_side {
        return Err(Error::input(
            place,
            format!(
                "{what}: range {:?}…{:?} is not on a side of block '{}' ({} × {} × {} nodes): \
                 one index must stay at 1 or at its last value",
                r.1, r.2, blocks[b].0, v.dims[0], v.dims[1], v.dims[2]
            ),
        ));
    }
    Ok((b, lo, hi))
}
