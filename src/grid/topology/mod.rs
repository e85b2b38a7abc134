//! Multi-block topology: named vertices, edges between two vertices with a node count, and
//! blocks whose four sides are chains of edges, each edge shared by the blocks on either side
//! (ENGRID's domains with common edges, paper §2.5, Figs 7–18).
//!
//! A [`Topology`] is checked on construction: every name known, every side a connected chain,
//! the four sides a closed loop around the block, opposite sides with equal node counts, every
//! vertex and edge used, no edge bordering more than two block sides. Edge orientation inside
//! a block is worked out from the shared vertices. An edge used twice by one block is a cut
//! (a C-grid's wake, an O-grid's periodic cut). It knows names and counts only; the nodes of
//! the edges come from the case (curves and distributions).

mod connect;
mod merge;
pub mod volume;

pub use connect::{Connectivity, Interface, Patch, SideRange};
pub use merge::{Group, GroupPiece, Op};

use crate::grid::Edge;
use crate::{Error, Result};

/// An edge of the topology: from one vertex to another (possibly the same one) with `n` nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct TopoEdge {
    pub name: String,
    pub from: usize,
    pub to: usize,
    pub n: usize,
    /// Grid orthogonal at this edge on every side that has it (Section 2.4).
    pub orthogonal: bool,
    /// The first spacing off this edge is held along it on every side that has it
    /// ([`crate::elliptic::wall2d`]).
    pub wall: bool,
    /// An interior edge whose interior nodes move with the grid (shape and distribution).
    pub floating: bool,
    /// Boundary-patch family (a boundary edge's name for the solver's boundary conditions).
    pub family: String,
    /// The family's boundary condition as the case file names it (checked by `case`), if
    /// given.
    pub bc: Option<String>,
}

/// One edge as a block side uses it: `reversed` if the side runs from the edge's `to` vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeUse {
    pub edge: usize,
    pub reversed: bool,
}

/// A block: its four sides E1, E2, E3, E4 (METHOD.md), each a chain of edge uses in the
/// side's index direction (E1, E2 from E3 to E4; E3, E4 from E1 to E2).
#[derive(Clone, Debug, PartialEq)]
pub struct TopoBlock {
    pub name: String,
    pub sides: [Vec<EdgeUse>; 4],
    /// Orthogonality asked for at each side (block-level flags or edges marked orthogonal).
    pub orthogonal: [bool; 4],
    /// Wall spacing held at each side (block-level flags or edges marked `wall`).
    pub wall: [bool; 4],
}

/// A block as the case file gives it: per side, edge names in index order, each with a forced
/// direction (`-name`: reversed) or none (worked out).
#[derive(Clone, Debug)]
pub struct BlockSides {
    pub name: String,
    pub sides: [Vec<(String, Option<bool>)>; 4],
    pub orthogonal: [bool; 4],
    pub wall: [bool; 4],
}

/// Vertices, edges and blocks.
#[derive(Clone, Debug, PartialEq)]
pub struct Topology {
    pub vertices: Vec<String>,
    pub edges: Vec<TopoEdge>,
    /// The four-sided pieces over the edges: the blocks of a 2D grid, or the faces of a
    /// volume topology ([`volume::Topology3`]), by `noun`.
    pub blocks: Vec<TopoBlock>,
    /// "block", or "face" for the faces of a volume topology (messages; in a volume topology
    /// an edge may border any number of faces).
    pub noun: &'static str,
}

impl Topology {
    /// Resolves names and orientations and checks the topology; `place` names the file.
    pub fn new(
        vertices: Vec<String>,
        edges: Vec<TopoEdge>,
        blocks: &[BlockSides],
        place: &str,
    ) -> Result<Self> {
        Self::build(vertices, edges, blocks, "block", place)
    }

    /// The faces of a volume topology as four-sided pieces over the edges: checked as blocks
    /// are, except that an edge may border any number of faces and none floats.
    pub fn new_faces(
        vertices: Vec<String>,
        edges: Vec<TopoEdge>,
        faces: &[BlockSides],
        place: &str,
    ) -> Result<Self> {
        Self::build(vertices, edges, faces, "face", place)
    }

    fn build(
        vertices: Vec<String>,
        edges: Vec<TopoEdge>,
        blocks: &[BlockSides],
        noun: &'static str,
        place: &str,
    ) -> Result<Self> {
        unique(&vertices, "vertex", place)?;
        unique(
            &edges.iter().map(|e| e.name.clone()).collect::<Vec<_>>(),
            "edge",
            place,
        )?;
        unique(
            &blocks.iter().map(|b| b.name.clone()).collect::<Vec<_>>(),
            noun,
            place,
        )?;
        for e in &edges {
            if e.n < 2 {
                return Err(Error::input(
                    format!("{place}: edge '{}'", e.name),
                    format!("n = {}: an edge needs at least 2 nodes", e.n),
                ));
            }
        }
        let mut topo = Topology {
            vertices,
            edges,
            blocks: Vec::new(),
            noun,
        };
        for b in blocks {
            let block = topo.resolve(b, place)?;
            topo.blocks.push(block);
        }
        topo.check_counts(place)?;
        topo.check_usage(place)?;
        Ok(topo)
    }

    /// The number of nodes along side `e` of block `b`.
    pub fn side_nodes(&self, b: usize, e: Edge) -> usize {
        1 + self.blocks[b].sides[e.index()]
            .iter()
            .map(|u| self.edges[u.edge].n - 1)
            .sum::<usize>()
    }

    /// Nodes of block b along i and j.
    pub fn dims(&self, b: usize) -> [usize; 2] {
        [self.side_nodes(b, Edge::E3), self.side_nodes(b, Edge::E1)]
    }

    /// The node lists of the four sides of block `b` (E1..E4, index order) from the nodes of
    /// every edge (in the edge's own direction): shared edges give bit-identical nodes.
    pub fn side_points<T: Copy>(&self, b: usize, edge_nodes: &[Vec<T>]) -> [Vec<T>; 4] {
        chain_points(&self.blocks[b].sides, edge_nodes)
    }

    /// Every use of edge `e` as (block, side, node offset of the edge's first node on the side
    /// in the side's index direction, reversed).
    pub fn uses_of(&self, e: usize) -> Vec<(usize, Edge, usize, bool)> {
        let mut out = Vec::new();
        for (b, block) in self.blocks.iter().enumerate() {
            for side in Edge::ALL {
                let mut offset = 0;
                for u in &block.sides[side.index()] {
                    let n = self.edges[u.edge].n;
                    if u.edge == e {
                        let first = if u.reversed { offset + n - 1 } else { offset };
                        out.push((b, side, first, u.reversed));
                    }
                    offset += n - 1;
                }
            }
        }
        out
    }

    /// "file: block 'name'" (or "face 'name'").
    pub fn block_place(&self, place: &str, b: usize) -> String {
        format!("{place}: {} '{}'", self.noun, self.blocks[b].name)
    }

    /// Resolves one block's names and edge directions: the sides E3, E2, E4 (backwards), E1
    /// (backwards) must form a closed loop.
    fn resolve(&self, b: &BlockSides, place: &str) -> Result<TopoBlock> {
        let at = format!("{place}: {} '{}'", self.noun, b.name);
        let mut ids: [Vec<(usize, Option<bool>)>; 4] = Default::default();
        for side in Edge::ALL {
            let chain = &b.sides[side.index()];
            if chain.is_empty() {
                return Err(Error::input(&at, format!("side {side} names no edge")));
            }
            for (name, forced) in chain {
                let id = self
                    .edges
                    .iter()
                    .position(|e| &e.name == name)
                    .ok_or_else(|| {
                        Error::input(&at, format!("side {side}: no edge named '{name}'"))
                    })?;
                ids[side.index()].push((id, *forced));
            }
        }
        // The loop: E3 forward, E2 forward, E4 backward, E1 backward.
        let mut lp: Vec<(Edge, usize, Option<bool>, bool)> = Vec::new();
        for (side, backward) in [
            (Edge::E3, false),
            (Edge::E2, false),
            (Edge::E4, true),
            (Edge::E1, true),
        ] {
            let mut chain = ids[side.index()].clone();
            if backward {
                chain.reverse();
            }
            lp.extend(chain.into_iter().map(|(id, f)| (side, id, f, backward)));
        }
        // Try the first edge both ways; everything after follows from the shared vertices.
        let mut first_error = None;
        for start_rev in [false, true] {
            match self.walk(&lp, start_rev) {
                Ok(dirs) => {
                    let mut sides: [Vec<EdgeUse>; 4] = Default::default();
                    for ((side, id, _, backward), loop_rev) in lp.iter().zip(dirs) {
                        // In index direction a backward side's edge runs the other way.
                        sides[side.index()].push(EdgeUse {
                            edge: *id,
                            reversed: loop_rev != *backward,
                        });
                    }
                    for side in [Edge::E4, Edge::E1] {
                        sides[side.index()].reverse();
                    }
                    return Ok(TopoBlock {
                        name: b.name.clone(),
                        sides,
                        orthogonal: b.orthogonal,
                        wall: b.wall,
                    });
                }
                Err(m) if !m.is_empty() => {
                    first_error.get_or_insert(m);
                }
                Err(_) => {}
            }
        }
        Err(Error::input(at, first_error.unwrap_or_default()))
    }

    /// Walks the loop with the first edge's direction given: per edge, whether the loop runs it
    /// backwards (to → from). A forced direction is a direction in the side's index order.
    fn walk(
        &self,
        lp: &[(Edge, usize, Option<bool>, bool)],
        start_rev: bool,
    ) -> std::result::Result<Vec<bool>, String> {
        let mut dirs = Vec::with_capacity(lp.len());
        let ends = |id: usize, rev: bool| {
            let e = &self.edges[id];
            if rev {
                (e.to, e.from)
            } else {
                (e.from, e.to)
            }
        };
        // A closed edge runs along its side in its own direction unless forced.
        let forced_loop = |id: usize, f: Option<bool>, backward: bool| {
            let closed = self.edges[id].from == self.edges[id].to;
            f.or(closed.then_some(false)).map(|r| r != backward)
        };
        let (side0, id0, f0, bw0) = lp[0];
        let rev0 = forced_loop(id0, f0, bw0).unwrap_or(start_rev);
        if rev0 != start_rev {
            return Err(String::new());
        }
        let start = ends(id0, rev0).0;
        let mut cur = ends(id0, rev0).1;
        dirs.push(rev0);
        let mut prev = (side0, id0);
        for &(side, id, f, bw) in &lp[1..] {
            let e = &self.edges[id];
            let rev = match forced_loop(id, f, bw) {
                Some(r) if ends(id, r).0 == cur => r,
                None if e.from == cur => false,
                None if e.to == cur => true,
                _ => {
                    return Err(format!(
                        "the sides do not form a closed loop: edge '{}' (side {side}) does \
                         not start at vertex '{}' where edge '{}' (side {}) ends; the loop \
                         runs E3, E2 forwards and E4, E1 backwards, and each side lists its \
                         edges from E1 to E2 (E3, E4) or from E3 to E4 (E1, E2)",
                        e.name, self.vertices[cur], self.edges[prev.1].name, prev.0
                    ))
                }
            };
            dirs.push(rev);
            cur = ends(id, rev).1;
            prev = (side, id);
        }
        if cur != start {
            return Err(format!(
                "the loop does not close: it starts at vertex '{}' and ends at '{}'",
                self.vertices[start], self.vertices[cur]
            ));
        }
        Ok(dirs)
    }

    fn check_counts(&self, place: &str) -> Result<()> {
        for b in 0..self.blocks.len() {
            for (p, q) in [(Edge::E1, Edge::E2), (Edge::E3, Edge::E4)] {
                let (np, nq) = (self.side_nodes(b, p), self.side_nodes(b, q));
                if np != nq {
                    let names = |e: Edge| self.chain_names(b, e);
                    return Err(Error::input(
                        self.block_place(place, b),
                        format!(
                            "opposite sides {p} ({}) and {q} ({}) have {np} and {nq} nodes; \
                             they must be equal",
                            names(p),
                            names(q)
                        ),
                    ));
                }
                if np < 3 {
                    return Err(Error::input(
                        self.block_place(place, b),
                        format!(
                            "sides {p} and {q} have {np} nodes; a {} needs at least 3",
                            self.noun
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The edge names of a side, comma separated.
    pub fn chain_names(&self, b: usize, e: Edge) -> String {
        self.blocks[b].sides[e.index()]
            .iter()
            .map(|u| format!("'{}'", self.edges[u.edge].name))
            .collect::<Vec<_>>()
            .join(", ")
    }

    fn check_usage(&self, place: &str) -> Result<()> {
        for (e, edge) in self.edges.iter().enumerate() {
            let uses = self.uses_of(e);
            let at = format!("{place}: edge '{}'", edge.name);
            match uses.len() {
                0 => {
                    return Err(Error::input(
                        at,
                        format!(
                            "the edge is used by no {0} (remove it or add it to a {0} side)",
                            self.noun
                        ),
                    ))
                }
                1 | 2 => {}
                _ if self.noun == "face" => {}
                k => {
                    return Err(Error::input(
                        at,
                        format!(
                            "the edge borders {k} block sides ({}); an edge borders at most two",
                            uses.iter()
                                .map(|(b, s, ..)| format!("'{}' {s}", self.blocks[*b].name))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ))
                }
            }
            if edge.floating && uses.len() != 2 {
                return Err(Error::input(
                    at,
                    "a floating edge must be an interior edge (shared by two block sides)",
                ));
            }
        }
        for (v, name) in self.vertices.iter().enumerate() {
            if !self.edges.iter().any(|e| e.from == v || e.to == v) {
                return Err(Error::input(
                    format!("{place}: vertex '{name}'"),
                    "the vertex is used by no edge",
                ));
            }
        }
        Ok(())
    }
}

/// The node lists of four sides (chains of edge uses) from the nodes of every edge.
pub fn chain_points<T: Copy>(sides: &[Vec<EdgeUse>; 4], edge_nodes: &[Vec<T>]) -> [Vec<T>; 4] {
    sides.clone().map(|chain| {
        let mut out: Vec<T> = Vec::new();
        for u in &chain {
            let nodes = &edge_nodes[u.edge];
            let skip = usize::from(!out.is_empty());
            if u.reversed {
                out.extend(nodes.iter().rev().skip(skip));
            } else {
                out.extend(nodes.iter().skip(skip));
            }
        }
        out
    })
}

fn unique(names: &[String], what: &str, place: &str) -> Result<()> {
    for (k, n) in names.iter().enumerate() {
        if n.is_empty() || n.starts_with('-') {
            return Err(Error::input(
                place,
                format!("{what} name '{n}': names are non-empty and do not start with '-'"),
            ));
        }
        if names[..k].contains(n) {
            return Err(Error::input(
                place,
                format!("two {what}s are named '{n}'; names must be unique"),
            ));
        }
    }
    Ok(())
}

/// Edges that cross: the first pair of edges (by index) whose node polylines intersect away
/// from shared vertices, as `(edge a, edge b)`. Planar edges only (x, y).
pub fn crossing_edges(topo: &Topology, nodes: &[Vec<[f64; 2]>]) -> Option<(usize, usize)> {
    let boxes: Vec<[f64; 4]> = nodes.iter().map(|p| bbox(p)).collect();
    for a in 0..nodes.len() {
        for b in a..nodes.len() {
            let (ba, bb) = (boxes[a], boxes[b]);
            if ba[2] < bb[0] || bb[2] < ba[0] || ba[3] < bb[1] || bb[3] < ba[1] {
                continue;
            }
            if polylines_cross(topo, a, b, &nodes[a], &nodes[b]) {
                return Some((a, b));
            }
        }
    }
    None
}

fn bbox(p: &[[f64; 2]]) -> [f64; 4] {
    p.iter().fold(
        [f64::INFINITY, f64::INFINITY, -f64::INFINITY, -f64::INFINITY],
        |b, q| {
            [
                b[0].min(q[0]),
                b[1].min(q[1]),
                b[2].max(q[0]),
                b[3].max(q[1]),
            ]
        },
    )
}

/// True if segments of the two polylines intersect or touch, ignoring the touching of segments that
/// end at a vertex both edges share (and neighbouring segments of one edge).
fn polylines_cross(topo: &Topology, a: usize, b: usize, pa: &[[f64; 2]], pb: &[[f64; 2]]) -> bool {
    let (ea, eb) = (&topo.edges[a], &topo.edges[b]);
    let shared = |ia: usize, ib: usize| {
        // Segment ia of a and ib of b touch at a shared end vertex.
        let va = [
            (ia == 0).then_some(ea.from),
            (ia + 2 == pa.len()).then_some(ea.to),
        ];
        let vb = [
            (ib == 0).then_some(eb.from),
            (ib + 2 == pb.len()).then_some(eb.to),
        ];
        va.iter()
            .flatten()
            .any(|v| vb.iter().flatten().any(|w| v == w))
    };
    for ia in 0..pa.len() - 1 {
        for ib in 0..pb.len() - 1 {
            if a == b && ia + 1 >= ib {
                continue;
            }
            if a == b && ia == 0 && ib + 2 == pb.len() && ea.from == ea.to {
                continue;
            }
            if a != b && shared(ia, ib) {
                continue;
            }
            if crate::grid::boundary::segments_cross(pa[ia], pa[ia + 1], pb[ib], pb[ib + 1]) {
                return true;
            }
        }
    }
    false
}

#[cfg(test)]
mod tests;
