//! Walls on part of a block side: a side that is a chain of wall and non-wall edges (an airfoil
//! surface and its wake cut, `E3 = ["main_upper", "wake_1", "wake_2"]`) holds the wall spacing
//! on the wall edges and fades it out along the others ([`crate::elliptic::wall2d`]'s
//! [`WallSide`]).
//!
//! Where a wall run ends inside a side (a trailing-edge vertex in the middle of the chain), the
//! first spacing held there is that of the one other edge at the vertex, the edge that
//! continues the grid line leaving the wall there through the vertex: for a blunt trailing
//! edge, the base's first spacing at that corner. A vertex with no such edge, or with several,
//! is an input error naming the block, side, edge and vertex.

use crate::case::LoadedCase;
use crate::elliptic::wall2d::{WallPart, WallSide, FADE};
use crate::grid::topology::{Group, Topology};
use crate::grid::Edge;
use crate::{Error, Result};

/// The wall sides of group `g` if one of its flagged sides is a chain of wall and non-wall
/// edges or its blocks set `wall_fade` (None: every flagged side is a whole wall, held as
/// before).
///
/// # Errors
/// [`Error::Input`] for a `wall_fade` outside (0, 1] or different on the blocks of a row;
/// [`Error::Input`] naming the block, side, wall edge and vertex where a wall run ends at a
/// vertex inside the side without exactly one other edge there; a partial wall on a row of
/// blocks joined by floating edges.
pub(crate) fn partial_walls(
    case: &LoadedCase,
    topo: &Topology,
    g: &Group,
    place: &str,
) -> Result<Option<Vec<WallSide>>> {
    let fade = wall_fade(case, g, place)?;
    let mut sides = Vec::new();
    let mut partial = fade.is_some();
    let fade = fade.unwrap_or(FADE);
    for e in Edge::ALL.into_iter().filter(|e| g.wall[e.index()]) {
        let chain = &g.sides[e.index()];
        let flags: Vec<bool> = chain.iter().map(|u| topo.edges[u.edge].wall).collect();
        let mixed = flags.iter().any(|f| *f) && !flags.iter().all(|f| *f);
        let named = g.pieces.len() == 1
            && crate::case::topology::parse_walls(&case.case.blocks[g.pieces[0].block].wall, "")
                .is_ok_and(|w| w[e.index()]);
        if !mixed || named {
            sides.push(WallSide {
                fade,
                ..WallSide::whole(e)
            });
            continue;
        }
        if g.pieces.len() > 1 {
            return Err(Error::input(
                place,
                format!(
                    "side {e} of the row is the chain {} of wall and non-wall edges; a wall on \
                     part of a side is held on blocks not joined by floating edges",
                    names(topo, chain)
                ),
            ));
        }
        partial = true;
        sides.push(WallSide {
            edge: e,
            part: Some(wall_part(case, topo, g, e, place)?),
            fade,
        });
    }
    Ok(partial.then_some(sides))
}

/// The blocks' `wall_fade` (one value for a row of blocks), checked to lie in (0, 1].
fn wall_fade(case: &LoadedCase, g: &Group, place: &str) -> Result<Option<f64>> {
    let mut out: Option<f64> = None;
    for p in &g.pieces {
        let Some(f) = case.case.blocks[p.block].wall_fade else {
            continue;
        };
        if !(f > 0.0 && f <= 1.0) {
            return Err(Error::input(
                place,
                format!("wall_fade = {f}: the share of a grid line must lie in (0, 1]"),
            ));
        }
        if out.is_some_and(|o| o != f) {
            return Err(Error::input(
                place,
                "the blocks of a row joined by floating edges set different wall_fade values",
            ));
        }
        out = Some(f);
    }
    Ok(out)
}

fn names(topo: &Topology, chain: &[crate::grid::topology::EdgeUse]) -> String {
    let n: Vec<String> = chain
        .iter()
        .map(|u| format!("'{}'", topo.edges[u.edge].name))
        .collect();
    format!("[{}]", n.join(", "))
}

/// The wall runs of side `e` of a one-block group and the first spacing at every run end
/// inside the side.
fn wall_part(
    case: &LoadedCase,
    topo: &Topology,
    g: &Group,
    e: Edge,
    place: &str,
) -> Result<WallPart> {
    let chain = &g.sides[e.index()];
    let nodes = case.topology_nodes()?;
    let mut runs: Vec<[usize; 2]> = Vec::new();
    let mut ends = Vec::new();
    let mut offset = 0;
    let last = chain.len() - 1;
    for (k, u) in chain.iter().enumerate() {
        let edge = &topo.edges[u.edge];
        let span = [offset, offset + edge.n - 1];
        offset = span[1];
        if !edge.wall {
            continue;
        }
        match runs.last_mut() {
            Some(r) if r[1] == span[0] => r[1] = span[1],
            _ => runs.push(span),
        }
        // run ends inside the side: before this edge (the previous one is not a wall) and
        // after it (the next one is not)
        let (start_v, end_v) = if u.reversed {
            (edge.to, edge.from)
        } else {
            (edge.from, edge.to)
        };
        if k > 0 && !topo.edges[chain[k - 1].edge].wall {
            let h = continuing_spacing(topo, &nodes, [chain[k - 1].edge, u.edge], start_v)
                .map_err(|m| wall_end_error(topo, g, e, u.edge, start_v, &m, place))?;
            ends.push((span[0], h));
        }
        if k < last && !topo.edges[chain[k + 1].edge].wall {
            let h = continuing_spacing(topo, &nodes, [u.edge, chain[k + 1].edge], end_v)
                .map_err(|m| wall_end_error(topo, g, e, u.edge, end_v, &m, place))?;
            ends.push((span[1], h));
        }
    }
    Ok(WallPart { runs, ends })
}

/// The first spacing at vertex `v` of the one edge there other than the two chain edges
/// `along` meeting at it; otherwise what is there instead.
fn continuing_spacing(
    topo: &Topology,
    nodes: &[Vec<ellipgrid_geometry::Vec3>],
    along: [usize; 2],
    v: usize,
) -> std::result::Result<f64, String> {
    let mut others = Vec::new();
    for (k, edge) in topo.edges.iter().enumerate() {
        if along.contains(&k) {
            continue;
        }
        let p = &nodes[k];
        if edge.from == v {
            others.push((k, (p[1] - p[0]).norm()));
        }
        if edge.to == v {
            others.push((k, (p[p.len() - 1] - p[p.len() - 2]).norm()));
        }
    }
    match others.as_slice() {
        [(_, h)] => Ok(*h),
        [] => Err("no other edge".into()),
        many => Err(format!(
            "{} other edges ({})",
            many.len(),
            many.iter()
                .map(|(k, _)| format!("'{}'", topo.edges[*k].name))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

fn wall_end_error(
    topo: &Topology,
    g: &Group,
    e: Edge,
    edge: usize,
    v: usize,
    found: &str,
    place: &str,
) -> Error {
    Error::input(
        place,
        format!(
            "side {e} is the chain {} and wall edge '{}' ends at vertex '{}' inside it; the \
             first spacing held there is that of the one other edge at the vertex (the edge \
             continuing the grid line, e.g. a blunt trailing edge's base), but '{}' has {found}: \
             add that edge, or end the block side at the vertex",
            names(topo, &g.sides[e.index()]),
            topo.edges[edge].name,
            topo.vertices[v],
            topo.vertices[v]
        ),
    )
}
