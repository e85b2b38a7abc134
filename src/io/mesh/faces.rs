//! Faces of the merged mesh: interface node pairing, the cells' outward faces on block
//! sides, their classification into joins (two cells) and boundary faces (one cell, a
//! family), and the internal faces of a hexahedral mesh in OpenFOAM's upper-triangular order.

use super::{corners, Cells, Mesh, MeshBlock, View};
use crate::io::connectivity::{ConnFile, Range};
use crate::io::Block;
use crate::{Error, Result};
use std::collections::HashMap;

/// A face between two cells: `nodes` (2 for quadrilateral cells, then `u32::MAX`) run so
/// that the face's normal points out of `owner` into `neighbour` (`owner < neighbour`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Join {
    pub owner: usize,
    pub neighbour: usize,
    pub nodes: [u32; 4],
}

/// A boundary face of `cell`, its normal out of the domain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Face {
    pub cell: usize,
    pub nodes: [u32; 4],
}

/// Side names for messages: i = 0, i = N, j = 0, j = M, k = 0, k = L.
const SIDE: [&str; 6] = ["i = 1", "i = max", "j = 1", "j = max", "k = 1", "k = max"];

impl MeshBlock {
    /// The eight nodes of hexahedron (i, j, k) in VTK/OpenFOAM order (bottom face 0-3, top
    /// 4-7), right-handed; for a quadrilateral block the four nodes of cell (i, j),
    /// counter-clockwise (seen from +z for planar blocks), then `u32::MAX`.
    pub fn cell_nodes(&self, i: usize, j: usize, k: usize) -> [u32; 8] {
        let c = |a, b, d| self.id(i + a, j + b, k + d);
        if self.dims[2] == 1 {
            let q = if self.flip {
                [c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(1, 0, 0)]
            } else {
                [c(0, 0, 0), c(1, 0, 0), c(1, 1, 0), c(0, 1, 0)]
            };
            return [
                q[0],
                q[1],
                q[2],
                q[3],
                u32::MAX,
                u32::MAX,
                u32::MAX,
                u32::MAX,
            ];
        }
        let h = [
            c(0, 0, 0),
            c(1, 0, 0),
            c(1, 1, 0),
            c(0, 1, 0),
            c(0, 0, 1),
            c(1, 0, 1),
            c(1, 1, 1),
            c(0, 1, 1),
        ];
        if self.flip {
            [h[0], h[3], h[2], h[1], h[4], h[7], h[6], h[5]]
        } else {
            h
        }
    }

    /// The face of cell (i, j, k) on `side` (0..6: i-, i+, j-, j+, k-, k+), its nodes running
    /// so that the normal points out of the cell (quadrilateral cells: sides 0..4, 2 nodes).
    pub fn cell_face(&self, i: usize, j: usize, k: usize, side: usize) -> [u32; 4] {
        let c = |a, b, d| self.id(i + a, j + b, k + d);
        let x = u32::MAX;
        let mut f = if self.dims[2] == 1 {
            match side {
                0 => [c(0, 1, 0), c(0, 0, 0), x, x],
                1 => [c(1, 0, 0), c(1, 1, 0), x, x],
                2 => [c(0, 0, 0), c(1, 0, 0), x, x],
                _ => [c(1, 1, 0), c(0, 1, 0), x, x],
            }
        } else {
            match side {
                0 => [c(0, 0, 0), c(0, 0, 1), c(0, 1, 1), c(0, 1, 0)],
                1 => [c(1, 0, 0), c(1, 1, 0), c(1, 1, 1), c(1, 0, 1)],
                2 => [c(0, 0, 0), c(1, 0, 0), c(1, 0, 1), c(0, 0, 1)],
                3 => [c(0, 1, 0), c(0, 1, 1), c(1, 1, 1), c(1, 1, 0)],
                4 => [c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(1, 0, 0)],
                _ => [c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)],
            }
        };
        if self.flip {
            let n = if self.dims[2] == 1 { 2 } else { 4 };
            f[..n].reverse();
        }
        f
    }

    /// Global index of cell (i, j, k).
    pub fn cell(&self, i: usize, j: usize, k: usize) -> usize {
        let [ci, cj, _] = self.cell_dims();
        self.first_cell + i + ci * (j + cj * k)
    }

    /// Cells (i, j, k) along `side`, with their face on it.
    fn side_cells(&self, side: usize) -> impl Iterator<Item = [usize; 3]> + '_ {
        let [ci, cj, ck] = self.cell_dims();
        let axis = side / 2;
        let at = if side % 2 == 0 {
            0
        } else {
            [ci, cj, ck][axis] - 1
        };
        let n = [ci, cj, ck];
        let (p, q) = match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        (0..n[q]).flat_map(move |t| {
            (0..n[p]).map(move |s| {
                let mut c = [0; 3];
                c[axis] = at;
                c[p] = s;
                c[q] = t;
                c
            })
        })
    }
}

/// The nodes of face `f` sorted, as a key that both sides of a face share.
fn key(f: [u32; 4]) -> [u32; 4] {
    let mut k = f;
    k.sort_unstable();
    k
}

/// A cell face on a block side: (cell, outward nodes, block, side).
type SideFace = (usize, [u32; 4], usize, usize);

/// The faces of the cells along a patch range, as keys.
fn patch_keys(
    place: &str,
    mesh: &Mesh,
    views: &[View],
    blocks: &[(String, Block)],
    r: &Range,
    what: &str,
) -> Result<Vec<[u32; 4]>> {
    let (b, f, l) = corners(place, blocks, views, r, what)?;
    let mb = &mesh.blocks[b];
    let lo = [f[0].min(l[0]), f[1].min(l[1]), f[2].min(l[2])];
    let hi = [f[0].max(l[0]), f[1].max(l[1]), f[2].max(l[2])];
    let fixed: Vec<usize> = (0..3)
        .filter(|&c| lo[c] == hi[c] && mb.dims[c] > 1)
        .collect();
    let side = match fixed[..] {
        [c] if lo[c] == 0 => 2 * c,
        [c] if lo[c] == mb.dims[c] - 1 => 2 * c + 1,
        _ => {
            return Err(Error::input(
                place,
                format!(
                    "{what}: range {:?}…{:?} is not part of a side of block '{}'",
                    r.1, r.2, mb.name
                ),
            ))
        }
    };
    let mut keys = Vec::new();
    let top = |c: usize| {
        if c == side / 2 {
            lo[c] + 1
        } else {
            hi[c].max(lo[c] + 1)
        }
    };
    let [ci, cj, ck] = mb.cell_dims();
    for k in lo[2]..top(2) {
        for j in lo[1]..top(1) {
            for i in lo[0]..top(0) {
                let at = [i.min(ci - 1), j.min(cj - 1), k.min(ck - 1)];
                keys.push(key(mb.cell_face(at[0], at[1], at[2], side)));
            }
        }
    }
    Ok(keys)
}

/// Fills the mesh's joins, families and boundary faces from the block sides' faces.
pub(super) fn classify(
    place: &str,
    mesh: &mut Mesh,
    views: &[View],
    blocks: &[(String, Block)],
    conn: &ConnFile,
) -> Result<()> {
    let nf = mesh.face_nodes();
    // Patches: face key → family index.
    let mut family_of: HashMap<[u32; 4], (usize, bool)> = HashMap::new();
    let fams: Vec<(usize, String)> = conn.families.clone();
    mesh.families = fams.iter().map(|f| f.1.clone()).collect();
    mesh.bcs = fams.iter().map(|f| conn.bc(f.0, &f.1)).collect();
    mesh.boundary = vec![Vec::new(); fams.len()];
    for (n, (r, id)) in conn.patches.iter().enumerate() {
        let what = format!("patch {}", n + 1);
        let fam = fams.iter().position(|f| f.0 == *id).ok_or_else(|| {
            Error::input(
                place,
                format!("{what}: family {id} is not in the family list"),
            )
        })?;
        for k in patch_keys(place, mesh, views, blocks, r, &what)? {
            family_of.insert(k, (fam, false));
        }
    }
    // Cell faces on block sides, by key.
    let mut sides: HashMap<[u32; 4], Vec<SideFace>> = HashMap::new();
    let nsides = if mesh.cells == Cells::Volume { 6 } else { 4 };
    for (b, mb) in mesh.blocks.iter().enumerate() {
        for (side, side_name) in SIDE.iter().enumerate().take(nsides) {
            for [i, j, k] in mb.side_cells(side) {
                let f = mb.cell_face(i, j, k, side);
                let kf = key(f);
                if kf[..nf].windows(2).any(|w| w[0] == w[1]) {
                    return Err(Error::input(
                        place,
                        format!(
                            "block '{}', side {}: the face of cell ({}, {}, {}) is collapsed \
                             (repeated nodes)",
                            mb.name,
                            side_name,
                            i + 1,
                            j + 1,
                            k + 1
                        ),
                    ));
                }
                sides
                    .entry(kf)
                    .or_default()
                    .push((mb.cell(i, j, k), f, b, side));
            }
        }
    }
    let mut entries: Vec<_> = sides.into_iter().collect();
    entries.sort_unstable_by_key(|(_, v)| (v[0].0, v[0].3));
    for (kf, v) in entries {
        let name = |e: &SideFace| format!("block '{}' side {}", mesh.blocks[e.2].name, SIDE[e.3]);
        match v[..] {
            [one] => {
                let Some(fam) = family_of.get_mut(&kf) else {
                    return Err(Error::input(
                        place,
                        format!(
                            "{}: a face neither on an interface nor on a boundary patch",
                            name(&one)
                        ),
                    ));
                };
                fam.1 = true;
                mesh.boundary[fam.0].push(Face {
                    cell: one.0,
                    nodes: one.1,
                });
            }
            [p, q] => {
                if family_of.contains_key(&kf) {
                    return Err(Error::input(
                        place,
                        format!(
                            "{} and {}: a face both on an interface and on a patch",
                            name(&p),
                            name(&q)
                        ),
                    ));
                }
                let (o, nb) = if p.0 <= q.0 { (p, q) } else { (q, p) };
                if o.0 == nb.0 {
                    return Err(Error::input(
                        place,
                        format!("{}: a cell meets itself across the face", name(&p)),
                    ));
                }
                mesh.joins.push(Join {
                    owner: o.0,
                    neighbour: nb.0,
                    nodes: o.1,
                });
            }
            _ => {
                return Err(Error::input(
                    place,
                    format!("{}: {} block faces coincide there", name(&v[0]), v.len()),
                ))
            }
        }
    }
    if family_of.values().any(|f| !f.1) {
        return Err(Error::input(
            place,
            "a boundary patch lies inside the grid (its faces join two blocks or are not on a \
             block side)",
        ));
    }
    mesh.joins.sort_unstable_by_key(|j| (j.owner, j.neighbour));
    Ok(())
}

impl Mesh<'_> {
    /// Calls `f(nodes, owner, neighbour)` for every face between two cells of a hexahedral
    /// mesh, in upper-triangular order: by owner, then by neighbour (OpenFOAM's order).
    pub fn for_each_internal_face(&self, mut f: impl FnMut(&[u32; 4], usize, usize)) {
        for (b, mb) in self.blocks.iter().enumerate() {
            self.internal_faces_in(b, 0..mb.ncells(), &mut f);
        }
    }

    /// The cells of every block in pieces of at most `size`: (block, local cell range), in
    /// cell order, for writers that format pieces in parallel.
    pub fn cell_chunks(&self, size: usize) -> Vec<(usize, std::ops::Range<usize>)> {
        let mut v = Vec::new();
        for (b, mb) in self.blocks.iter().enumerate() {
            let n = mb.ncells();
            v.extend((0..n.div_ceil(size)).map(|c| (b, c * size..((c + 1) * size).min(n))));
        }
        v
    }

    /// [`Mesh::for_each_internal_face`] for the faces owned by the cells `cells` (local
    /// indices, i fastest) of block `b`.
    pub fn internal_faces_in(
        &self,
        b: usize,
        cells: std::ops::Range<usize>,
        mut f: impl FnMut(&[u32; 4], usize, usize),
    ) {
        let mb = &self.blocks[b];
        let [ci, cj, ck] = mb.cell_dims();
        let first = mb.first_cell + cells.start;
        let start = self.joins.partition_point(|jn| jn.owner < first);
        let mut joins = self.joins[start..].iter().peekable();
        // a hexahedron has six faces, each listed once (classify)
        let mut near: [(usize, [u32; 4]); 6] = [(0, [0; 4]); 6];
        for local in cells {
            let (i, j, k) = (local % ci, (local / ci) % cj, local / (ci * cj));
            let c = mb.first_cell + local;
            let mut n = 0;
            let mut add = |x: (usize, [u32; 4]), n: &mut usize| {
                near[*n] = x;
                *n += 1;
            };
            if i + 1 < ci {
                add((c + 1, mb.cell_face(i, j, k, 1)), &mut n);
            }
            if j + 1 < cj {
                add((c + ci, mb.cell_face(i, j, k, 3)), &mut n);
            }
            if k + 1 < ck {
                add((c + ci * cj, mb.cell_face(i, j, k, 5)), &mut n);
            }
            while let Some(jn) = joins.next_if(|jn| jn.owner == c) {
                add((jn.neighbour, jn.nodes), &mut n);
            }
            near[..n].sort_unstable_by_key(|x| x.0);
            for (nb, nodes) in &near[..n] {
                f(nodes, c, *nb);
            }
        }
    }

    /// Number of faces between two cells (internal faces of the blocks and joins).
    pub fn ninternal_faces(&self) -> usize {
        let inner: usize = self
            .blocks
            .iter()
            .map(|b| {
                let [ci, cj, ck] = b.cell_dims();
                if self.cells == Cells::Volume {
                    (ci - 1) * cj * ck + ci * (cj - 1) * ck + ci * cj * (ck - 1)
                } else {
                    (ci - 1) * cj + ci * (cj - 1)
                }
            })
            .sum();
        inner + self.joins.len()
    }
}
