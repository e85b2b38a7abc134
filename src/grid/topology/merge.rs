//! Floating interfaces: blocks joined by floating edges are gridded as one block, so the grid
//! crosses those edges as smoothly as it runs inside a block, and split again afterwards.
//!
//! The blocks of a group must line up as one structured block: each floating edge is a whole
//! side of both its blocks, and the floating edges join the blocks in a row (no branching).
//! Each block is brought into the row's indexing by symmetries of its index square. A row
//! whose floating edges close a ring (an O-grid of several blocks, or one block whose cut
//! E1 = E2 floats) is one block periodic in i ([`Group::periodic`]): its E1 and E2 are the
//! same edge, gridded by [`crate::elliptic::periodic`].

use super::{EdgeUse, Topology};
use crate::grid::{Edge, Grid2};
use crate::{Error, Result};

/// A symmetry of a block's index square.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    /// (i, j) → (j, i).
    Transpose,
    /// i → N − i.
    FlipI,
    /// j → M − j.
    FlipJ,
}

impl Op {
    /// The sides (E1..E4, in index direction) after the op.
    fn sides(self, s: &[Vec<EdgeUse>; 4]) -> [Vec<EdgeUse>; 4] {
        let rev = |c: &Vec<EdgeUse>| -> Vec<EdgeUse> {
            c.iter()
                .rev()
                .map(|u| EdgeUse {
                    edge: u.edge,
                    reversed: !u.reversed,
                })
                .collect()
        };
        match self {
            Op::Transpose => [s[2].clone(), s[3].clone(), s[0].clone(), s[1].clone()],
            Op::FlipI => [s[1].clone(), s[0].clone(), rev(&s[2]), rev(&s[3])],
            Op::FlipJ => [rev(&s[0]), rev(&s[1]), s[3].clone(), s[2].clone()],
        }
    }

    /// Per-side flags after the op.
    fn flags(self, f: [bool; 4]) -> [bool; 4] {
        match self {
            Op::Transpose => [f[2], f[3], f[0], f[1]],
            Op::FlipI => [f[1], f[0], f[2], f[3]],
            Op::FlipJ => [f[0], f[1], f[3], f[2]],
        }
    }

    /// The grid after the op (each op is its own inverse).
    pub fn grid<const D: usize>(self, g: &Grid2<D>) -> Grid2<D> {
        let (ni, nj) = (g.ni(), g.nj());
        match self {
            Op::Transpose => Grid2::from_fn(nj, ni, |i, j| g.point(j, i)),
            Op::FlipI => Grid2::from_fn(ni, nj, |i, j| g.point(ni - 1 - i, j)),
            Op::FlipJ => Grid2::from_fn(ni, nj, |i, j| g.point(i, nj - 1 - j)),
        }
    }
}

/// One block of a group: the ops that bring its indexing into the group's (applied in order)
/// and the first i of its nodes in the group's grid.
#[derive(Clone, Debug, PartialEq)]
pub struct GroupPiece {
    pub block: usize,
    pub ops: Vec<Op>,
    pub offset: usize,
    pub ni: usize,
}

impl GroupPiece {
    /// The block's own grid cut from the group's grid.
    pub fn cut<const D: usize>(&self, g: &Grid2<D>) -> Grid2<D> {
        let mut piece = Grid2::from_fn(self.ni, g.nj(), |i, j| g.point(self.offset + i, j));
        for op in self.ops.iter().rev() {
            piece = op.grid(&piece);
        }
        piece
    }
}

/// Blocks gridded as one: a single block (no floating edge) or a row of blocks joined by
/// floating edges, with the row's four sides.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    pub name: String,
    pub pieces: Vec<GroupPiece>,
    pub sides: [Vec<EdgeUse>; 4],
    pub orthogonal: [bool; 4],
    /// Wall spacing held at each side of the group.
    pub wall: [bool; 4],
    /// True if the floating edges close a ring: the group is periodic in i, its E1 and E2
    /// are the same floating edge (the seam), and its grid's column N is column 0.
    pub periodic: bool,
}

impl Topology {
    /// The groups of blocks gridded together, in the order of their first block; every block
    /// is in exactly one.
    pub fn groups(&self, place: &str) -> Result<Vec<Group>> {
        // The floating joins: (block, side) pairs.
        let mut joins: Vec<(usize, [(usize, Edge); 2])> = Vec::new();
        for (e, edge) in self.edges.iter().enumerate().filter(|(_, e)| e.floating) {
            let at = format!("{place}: edge '{}'", edge.name);
            let uses = self.uses_of(e);
            let (b1, s1, ..) = uses[0];
            let (b2, s2, ..) = uses[1];
            if b1 == b2 && s1.index() / 2 != s2.index() / 2 {
                return Err(Error::input(
                    at,
                    format!(
                        "the edge is a cut of block '{}' on adjacent sides {s1} and {s2}; a \
                         floating cut of one block joins opposite sides (E1 and E2, or E3 and E4)",
                        self.blocks[b1].name
                    ),
                ));
            }
            for (b, s) in [(b1, s1), (b2, s2)] {
                if self.blocks[b].sides[s.index()].len() != 1 {
                    return Err(Error::input(
                        at,
                        format!(
                            "a floating edge must be a whole side of both blocks, but side {s} \
                             of block '{}' is the chain {}",
                            self.blocks[b].name,
                            self.chain_names(b, s)
                        ),
                    ));
                }
            }
            joins.push((e, [(b1, s1), (b2, s2)]));
        }
        let mut done = vec![false; self.blocks.len()];
        let mut groups = Vec::new();
        for b0 in 0..self.blocks.len() {
            if done[b0] {
                continue;
            }
            // The component of b0.
            let mut comp = vec![b0];
            let mut k = 0;
            while k < comp.len() {
                for (_, [(x, _), (y, _)]) in &joins {
                    for (p, q) in [(*x, *y), (*y, *x)] {
                        if p == comp[k] && !comp.contains(&q) {
                            comp.push(q);
                        }
                    }
                }
                k += 1;
            }
            for &b in &comp {
                done[b] = true;
            }
            groups.push(self.row(&comp, &joins, place)?);
        }
        Ok(groups)
    }

    /// Lines up the blocks of one component in a row.
    fn row(
        &self,
        comp: &[usize],
        joins: &[(usize, [(usize, Edge); 2])],
        place: &str,
    ) -> Result<Group> {
        let mine: Vec<&(usize, [(usize, Edge); 2])> = joins
            .iter()
            .filter(|(_, j)| comp.contains(&j[0].0))
            .collect();
        let names = comp
            .iter()
            .map(|&b| format!("'{}'", self.blocks[b].name))
            .collect::<Vec<_>>()
            .join(", ");
        let at = format!("{place}: blocks {names}");
        // A tree of joins is a row (checked below); one join more closes a ring.
        let ring = mine.len() == comp.len();
        let floating_sides = |b: usize| -> Vec<(usize, Edge)> {
            mine.iter()
                .flat_map(|(e, j)| j.iter().filter(|(x, _)| *x == b).map(|(_, s)| (*e, *s)))
                .collect()
        };
        for &b in comp {
            let f = floating_sides(b);
            if f.len() > 2 || (f.len() == 2 && f[0].1.index() / 2 != f[1].1.index() / 2) {
                return Err(Error::input(
                    at,
                    format!(
                        "block '{}' floats at sides {}: the floating edges must join the \
                         blocks in a row (at most two per block, on opposite sides)",
                        self.blocks[b].name,
                        f.iter()
                            .map(|(_, s)| s.to_string())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            }
        }
        let first = if ring {
            comp[0]
        } else {
            *comp
                .iter()
                .find(|&&b| floating_sides(b).len() <= 1)
                .expect("a row has an end")
        };
        let to_e2 = |s: Edge| match s {
            Edge::E1 => vec![Op::FlipI],
            Edge::E2 => vec![],
            Edge::E3 => vec![Op::Transpose, Op::FlipI],
            Edge::E4 => vec![Op::Transpose],
        };
        let to_e1 = |s: Edge| match s {
            Edge::E1 => vec![],
            Edge::E2 => vec![Op::FlipI],
            Edge::E3 => vec![Op::Transpose],
            Edge::E4 => vec![Op::Transpose, Op::FlipI],
        };
        let apply = |b: usize, ops: &[Op]| {
            let blk = &self.blocks[b];
            ops.iter().fold(
                (blk.sides.clone(), blk.orthogonal, blk.wall),
                |(s, f, w), op| (op.sides(&s), op.flags(f), op.flags(w)),
            )
        };
        // The first block keeps its own indexing where it can: of a ring's two floating
        // sides, the one at E2 (or E4) leads on.
        let lead = floating_sides(first);
        let lead = lead
            .iter()
            .find(|(_, s)| matches!(s, Edge::E2 | Edge::E4))
            .or(lead.first());
        let mut ops = lead.map_or(vec![], |(_, s)| to_e2(*s));
        let (mut sides, mut orth, mut wall) = apply(first, &ops);
        let mut pieces = Vec::new();
        let mut block = first;
        let mut offset = 0;
        let mut own_e3 = sides[2].clone();
        loop {
            let ni = 1 + own_e3
                .iter()
                .map(|u| self.edges[u.edge].n - 1)
                .sum::<usize>();
            pieces.push(GroupPiece {
                block,
                ops: ops.clone(),
                offset,
                ni,
            });
            offset += ni - 1;
            // The floating edge at E2 leads to the next block.
            let e2 = sides[1][0];
            let Some((_, j)) = mine
                .iter()
                .find(|(e, j)| *e == e2.edge && j.iter().any(|(b, _)| *b == block))
            else {
                break;
            };
            // the other end of the join (a block's own cut: its other side)
            let (next, s) = if j[0].0 == j[1].0 {
                (block, j[0].1)
            } else {
                *j.iter()
                    .find(|(b, _)| *b != block)
                    .expect("a join of two blocks")
            };
            if ring && next == first {
                // The ring closes on the first block's E1: the same edge, the same way round
                // (else the ring is twisted, a Möbius strip, and has no periodic indexing).
                if sides[0][0].edge != e2.edge || sides[0][0].reversed != e2.reversed {
                    return Err(Error::input(
                        &at,
                        format!(
                            "the floating edges close a twisted ring at edge '{}': going round, \
                             the blocks' E3 sides do not stay on one side of the ring",
                            self.edges[e2.edge].name
                        ),
                    ));
                }
                break;
            }
            ops = to_e1(s);
            let (ns, ..) = apply(next, &ops);
            if ns[0][0].reversed != e2.reversed {
                ops.push(Op::FlipJ);
            }
            let (ns, nf, nw) = apply(next, &ops);
            for (k, side) in [(2, Edge::E3), (3, Edge::E4)] {
                if nw[k] != wall[k] {
                    return Err(Error::input(
                        &at,
                        format!(
                            "blocks '{}' and '{}' are joined by floating edge '{}' but only \
                             one holds a wall spacing along their common side {side} (of the \
                             row); a wall spacing holds along a whole side of the row",
                            self.blocks[block].name,
                            self.blocks[next].name,
                            self.edges[e2.edge].name
                        ),
                    ));
                }
                if nf[k] != orth[k] {
                    return Err(Error::input(
                        &at,
                        format!(
                            "blocks '{}' and '{}' are joined by floating edge '{}' but only \
                             one asks for orthogonality along their common side {side} (of \
                             the row); orthogonality holds along a whole side of the row",
                            self.blocks[block].name,
                            self.blocks[next].name,
                            self.edges[e2.edge].name
                        ),
                    ));
                }
            }
            own_e3 = ns[2].clone();
            sides[2].extend(ns[2].iter().copied());
            sides[3].extend(ns[3].iter().copied());
            sides[1] = ns[1].clone();
            orth[1] = nf[1];
            wall[1] = nw[1];
            block = next;
        }
        if ring {
            // the seam is inside the periodic block, not a side
            orth[0] = false;
            orth[1] = false;
            wall[0] = false;
            wall[1] = false;
        }
        Ok(Group {
            name: pieces
                .iter()
                .map(|p| self.blocks[p.block].name.clone())
                .collect::<Vec<_>>()
                .join("+"),
            pieces,
            sides,
            orthogonal: orth,
            wall,
            periodic: ring,
        })
    }
}
