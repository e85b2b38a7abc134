//! What a flow solver needs of a multi-block topology: every 1-to-1 interface (two blocks,
//! index ranges, orientation) and every boundary patch with its family.

use super::Topology;
use crate::grid::Edge;

/// A run of nodes along one side of a block, from `start` to `end` inclusive (0-based
/// (i, j)); it runs in the direction of the edge it belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SideRange {
    pub block: usize,
    pub side: Edge,
    pub start: [usize; 2],
    pub end: [usize; 2],
}

impl SideRange {
    /// Number of nodes.
    pub fn len(&self) -> usize {
        1 + self.start[0].abs_diff(self.end[0]) + self.start[1].abs_diff(self.end[1])
    }

    /// Never empty (a range holds at least its start node).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The k-th node from `start`.
    pub fn node(&self, k: usize) -> [usize; 2] {
        let step = |a: usize, b: usize| {
            if b >= a {
                a + k.min(b - a)
            } else {
                a - k.min(a - b)
            }
        };
        [
            step(self.start[0], self.end[0]),
            step(self.start[1], self.end[1]),
        ]
    }

    /// The node next to the k-th one one step into the block (across the side).
    pub fn inner(&self, k: usize) -> [usize; 2] {
        let [i, j] = self.node(k);
        match self.side {
            Edge::E1 => [i + 1, j],
            Edge::E2 => [i - 1, j],
            Edge::E3 => [i, j + 1],
            Edge::E4 => [i, j - 1],
        }
    }
}

/// Two block sides that share an edge node for node: node k of `a` is node k of `b`.
#[derive(Clone, Debug, PartialEq)]
pub struct Interface {
    pub edge: usize,
    pub a: SideRange,
    pub b: SideRange,
}

/// A block side on the boundary of the grid, with its edge's family.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    pub edge: usize,
    pub family: String,
    pub range: SideRange,
}

/// Interfaces and boundary patches of a topology; together they cover every block side.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Connectivity {
    pub interfaces: Vec<Interface>,
    pub patches: Vec<Patch>,
}

impl Topology {
    /// The connectivity: an interface per edge that two block sides share, a patch per edge
    /// that one side has, in edge order.
    pub fn connectivity(&self) -> Connectivity {
        let mut c = Connectivity::default();
        for (e, edge) in self.edges.iter().enumerate() {
            let ranges: Vec<SideRange> = self
                .uses_of(e)
                .into_iter()
                .map(|(b, side, first, reversed)| {
                    let [ni, nj] = self.dims(b);
                    let pos = |s: usize| match side {
                        Edge::E1 => [0, s],
                        Edge::E2 => [ni - 1, s],
                        Edge::E3 => [s, 0],
                        Edge::E4 => [s, nj - 1],
                    };
                    let last = if reversed {
                        first + 1 - edge.n
                    } else {
                        first + edge.n - 1
                    };
                    SideRange {
                        block: b,
                        side,
                        start: pos(first),
                        end: pos(last),
                    }
                })
                .collect();
            match ranges[..] {
                [a, b] => c.interfaces.push(Interface { edge: e, a, b }),
                [r] => c.patches.push(Patch {
                    edge: e,
                    family: edge.family.clone(),
                    range: r,
                }),
                _ => {}
            }
        }
        c
    }
}
