//! The merge of block nodes through interfaces, lean enough for large grids: a union-find over
//! the interface nodes only (a map, not an array over all nodes), one u32 id per block node,
//! and the coordinates left in the blocks. A merged node is numbered, and keeps the
//! coordinates, at its first occurrence (blocks in order, i fastest); the nodes of a block
//! that repeat an earlier one are its *duplicates*, listed sorted, so that the merged points
//! are read straight from the blocks by skipping them.

use super::{interface, Mesh, View};
use crate::io::connectivity::ConnFile;
use crate::io::Block;
use crate::{Error, Result};
use std::collections::HashMap;
use std::ops::Range;

/// Merged node ids of one block.
pub(super) struct MergedBlock {
    /// Global node id of each block node, i fastest.
    pub ids: Vec<u32>,
    /// Id of the block's first node that is not a duplicate.
    pub first_point: u32,
    /// Local indices of the nodes that repeat an earlier node, sorted.
    pub dups: Vec<u32>,
}

/// Merges the nodes that interfaces pair; returns the blocks' ids and the number of merged
/// nodes.
pub(super) fn merge(
    place: &str,
    blocks: &[(String, Block)],
    views: &[View],
    conn: &ConnFile,
) -> Result<(Vec<MergedBlock>, usize)> {
    let mut offsets = Vec::with_capacity(views.len() + 1);
    offsets.push(0usize);
    for v in views {
        offsets.push(offsets.last().unwrap_or(&0) + v.dims.iter().product::<usize>());
    }
    // Union-find over the interface nodes only; the smaller global index is the root, so a
    // node keeps its first occurrence.
    let mut parent: HashMap<usize, usize> = HashMap::new();
    fn root(p: &mut HashMap<usize, usize>, a: usize) -> usize {
        let mut r = a;
        while let Some(&q) = p.get(&r) {
            if q == r {
                break;
            }
            r = q;
        }
        let mut x = a; // path compression
        while x != r {
            let next = p[&x];
            p.insert(x, r);
            x = next;
        }
        r
    }
    let scale = super::diameter(views);
    for (n, [a, b]) in conn.interfaces.iter().enumerate() {
        let pairs = interface::correspond(place, blocks, views, n, a, b, scale)?.1;
        for [p, q] in pairs {
            let (p, q) = (offsets[p.0] + p.1, offsets[q.0] + q.1);
            parent.entry(p).or_insert(p);
            parent.entry(q).or_insert(q);
            let (rp, rq) = (root(&mut parent, p), root(&mut parent, q));
            parent.insert(rp.max(rq), rp.min(rq));
        }
    }
    // Every node that is not its own root, with its root, in node order.
    let keys: Vec<usize> = parent.keys().copied().collect();
    let mut dup_of: Vec<(usize, usize)> = keys
        .into_iter()
        .map(|g| (g, root(&mut parent, g)))
        .filter(|(g, r)| g != r)
        .collect();
    dup_of.sort_unstable();
    drop(parent);
    let total = *offsets.last().unwrap_or(&0);
    let npoints = total - dup_of.len();
    if npoints > u32::MAX as usize - 1 {
        return Err(Error::input(place, "more than 2³² − 1 nodes"));
    }
    let mut out: Vec<MergedBlock> = Vec::with_capacity(views.len());
    let mut next = 0u32;
    let mut d = dup_of.iter().peekable();
    for (b, v) in views.iter().enumerate() {
        let n = offsets[b + 1] - offsets[b];
        let first_point = next;
        let mut ids = Vec::with_capacity(n);
        let mut dups = Vec::new();
        let mut local = 0;
        while local < n {
            // a run of nodes up to the next duplicate: consecutive new ids
            let stop = d.peek().map_or(n, |(g, _)| (g - offsets[b]).min(n));
            ids.extend(next..next + (stop - local) as u32);
            next += (stop - local) as u32;
            local = stop;
            if local < n {
                let (_, r) = d.next().unwrap_or(&(0, 0));
                let rb = offsets.partition_point(|&o| o <= *r) - 1;
                let id = if rb == b {
                    ids[r - offsets[b]]
                } else {
                    out[rb].ids[r - offsets[rb]]
                };
                ids.push(id);
                dups.push(local as u32);
                local += 1;
            }
        }
        debug_assert_eq!(ids.len(), v.dims.iter().product::<usize>());
        out.push(MergedBlock {
            ids,
            first_point,
            dups,
        });
    }
    Ok((out, npoints))
}

impl Mesh<'_> {
    /// Number of merged nodes.
    pub fn npoints(&self) -> usize {
        self.npoints
    }

    /// Coordinates of merged node `id`.
    ///
    /// # Panics
    /// If `id >= self.npoints()`.
    pub fn point(&self, id: u32) -> [f64; 3] {
        assert!(
            (id as usize) < self.npoints,
            "node {id} of {}",
            self.npoints
        );
        let b = self.blocks.partition_point(|m| m.first_point <= id) - 1;
        let local = self.blocks[b].local_of(id - self.blocks[b].first_point);
        self.views[b].point_at(local)
    }

    /// Calls `f(id, point)` for the merged nodes `ids`, in order, reading them from the
    /// blocks (a binary search to start, then a walk).
    pub fn points_in(&self, ids: Range<usize>, mut f: impl FnMut(usize, [f64; 3])) {
        let mut id = ids.start;
        if id >= ids.end.min(self.npoints) {
            return;
        }
        let mut b = self
            .blocks
            .partition_point(|m| m.first_point as usize <= id)
            - 1;
        let mut local = self.blocks[b].local_of((id - self.blocks[b].first_point as usize) as u32);
        while id < ids.end.min(self.npoints) {
            let mb = &self.blocks[b];
            let n = mb.ids.len();
            let mut dup = mb.dups.partition_point(|&x| (x as usize) < local);
            while local < n && id < ids.end {
                if mb.dups.get(dup) == Some(&(local as u32)) {
                    dup += 1;
                } else {
                    f(id, self.views[b].point_at(local));
                    id += 1;
                }
                local += 1;
            }
            b += 1;
            local = 0;
        }
    }

    /// Coordinates of node `local` of block `b` as merged (a duplicate gets the coordinates
    /// of the node it repeats), for every node of the block in order.
    pub fn block_points(&self, b: usize, mut f: impl FnMut([f64; 3])) {
        let mb = &self.blocks[b];
        let mut dup = 0;
        for local in 0..mb.ids.len() {
            if mb.dups.get(dup) == Some(&(local as u32)) {
                dup += 1;
                f(self.point(mb.ids[local]));
            } else {
                f(self.views[b].point_at(local));
            }
        }
    }
}

impl super::MeshBlock {
    /// The local index of the block's `r`-th node that is not a duplicate.
    fn local_of(&self, r: u32) -> usize {
        // dups[k] − k counts the new nodes before dups[k]; it never decreases with k
        let (mut lo, mut hi) = (0usize, self.dups.len());
        while lo < hi {
            let mid = (lo + hi) / 2;
            if self.dups[mid] as usize - mid <= r as usize {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        r as usize + lo
    }
}
