//! The wall spacing on a periodic block (an O-grid's ring whose cut E1 = E2 floats, module
//! [`crate::elliptic::periodic`]): the same passes as the other blocks' (module docs of
//! `wall2d`), with two differences. The columns run all around the ring, the seam's too
//! (column N is column 0), and there are no side edges whose distance-from-wall profiles
//! could be interpolated: every column's goal is the cut's own profile, the distances of its
//! given nodes from its wall end, so the cut's distribution sets the spacing off the wall all
//! around (with the fade and the blend of the uncorrected distances as elsewhere). The
//! control functions [19] of the remapped parameters wrap around the seam
//! ([`periodic_control`]) and each pass re-solves [24] with the periodic solver.

use super::targets::blend_targets;
use super::{column_distances, dist, passes, Columns, WallSide, WallSpacing2};
use crate::algebraic::periodic::periodic_control;
use crate::algebraic::transform::ParamGrid;
use crate::elliptic::periodic;
use crate::elliptic::picard::{PicardInfo, PicardParams};
use crate::elliptic::wall::remap_column;
use crate::grid::boundary::Boundary2;
use crate::grid::{Edge, Grid2};
use crate::{Error, Result};

/// Holds the first spacing off the wall sides `sides` (E3 and/or E4, whole sides) of the
/// periodic grid `x` of the block `b`, solved with the control functions of `pg` (the
/// periodic straight-line parameters, or the blend of the orthogonality step) (module docs).
/// Returns the corrected grid and the
/// Picard history of its solves (None if no pass was needed).
///
/// # Errors
/// [`Error::Input`] for a wall on the cut (E1, E2) or on part of a side, a grid of fewer than
/// 4 × 3 nodes; the errors of the final solve.
pub fn hold_wall_spacing_periodic<const D: usize>(
    x: Grid2<D>,
    pg: ParamGrid,
    b: &Boundary2<D>,
    sides: &[WallSide],
    params: &PicardParams,
    place: &str,
) -> Result<(Grid2<D>, Option<PicardInfo>)> {
    let (ni, nj) = (x.ni(), x.nj());
    for s in sides {
        if !s.edge.runs_along_i() || s.part.is_some() {
            return Err(Error::input(
                format!("{place}, edge {}", s.edge),
                "on a periodic block (a floating cut) a wall spacing is held on whole sides \
                 E3 and E4 only (the ring's sides), not on the cut or part of a side",
            ));
        }
    }
    if sides.is_empty() {
        return Ok((x, None));
    }
    if ni < 4 || nj < 3 {
        return Err(Error::input(
            place,
            "a wall spacing on a periodic block needs at least 4 × 3 nodes",
        ));
    }
    let both = sides.len() > 1;
    let walls: Vec<(Columns, Vec<f64>, f64)> = sides
        .iter()
        .map(|s| {
            let cols = Columns {
                edge: s.edge,
                ni,
                nj,
            };
            let fade = if both { s.fade.min(0.5) } else { s.fade };
            (cols, cut_profile(b, s.edge), fade)
        })
        .collect();
    let mut goals: Vec<Vec<Vec<f64>>> = vec![Vec::new(); walls.len()];
    let remap = |trial: &mut ParamGrid, x: &Grid2<D>| {
        walls
            .iter()
            .zip(&mut goals)
            .map(|((c, prof, fade), g)| remap_ring(trial, x, c, prof, g, *fade, both))
            .fold(0.0, f64::max)
    };
    let solve = |x: &mut Grid2<D>, pg: &ParamGrid, p: &PicardParams| {
        let ctrl = periodic_control(pg);
        periodic::solve(x, &ctrl, p, place).map(|i| (i, None))
    };
    passes(x, pg, remap, solve, params)
}

/// Distances of the cut's given nodes from its end on wall `edge` (E3: j = 0, E4: j = M),
/// ordered from the wall.
fn cut_profile<const D: usize>(b: &Boundary2<D>, edge: Edge) -> Vec<f64> {
    let mut cut = b.edge(Edge::E1).to_vec();
    if edge == Edge::E4 {
        cut.reverse();
    }
    cut.iter().map(|p| dist(*p, cut[0])).collect()
}

/// One pass over every column of the ring (the seam's copy, column N, follows column 0):
/// remaps the wall-normal parameter of `pg` towards the goals (filled from `x`, the
/// uncorrected grid, on the first pass). Returns the largest |ln(goal / d)| before the pass.
fn remap_ring<const D: usize>(
    pg: &mut ParamGrid,
    x: &Grid2<D>,
    cols: &Columns,
    profile: &[f64],
    goals: &mut Vec<Vec<f64>>,
    fade: f64,
    half: bool,
) -> f64 {
    let depth = cols.depth();
    let last = if half { (depth - 1) / 2 } else { depth - 1 };
    let nc = cols.count() - 1;
    let mut err = 0.0f64;
    for c in 0..nc {
        let d = column_distances(x, cols, c);
        if goals.len() <= c {
            goals.push(blend_targets(&d, profile, 1.0, fade));
        }
        let idx: Vec<usize> = (0..depth)
            .map(|j| {
                let (i, jj) = cols.node(c, j);
                x.idx(i, jj)
            })
            .collect();
        let mut v: Vec<f64> = idx.iter().map(|&p| cols.param(pg, p)).collect();
        let k = last + 1;
        err = err.max(remap_column(&mut v[..k], &d[..k], &goals[c][..k]));
        for (j, (&p, y)) in idx.iter().zip(&v).enumerate() {
            cols.set_param(pg, p, *y);
            // the seam's copy (column N) carries column 0's parameters
            if c == 0 {
                let (i, jj) = cols.node(nc, j);
                cols.set_param(pg, x.idx(i, jj), *y);
            }
        }
    }
    err
}

/// The first spacing along wall side `edge` of the periodic grid `g` against the cut's first
/// spacing (the goal of [`hold_wall_spacing_periodic`]), over every node of the ring.
pub fn wall_spacing_periodic<const D: usize>(
    g: &Grid2<D>,
    b: &Boundary2<D>,
    edge: Edge,
) -> WallSpacing2 {
    let cols = Columns {
        edge,
        ni: g.ni(),
        nj: g.nj(),
    };
    let goal = cut_profile(b, edge)[1];
    let mut out = WallSpacing2 {
        edge: edge.to_string(),
        nodes: 0,
        first_min: f64::INFINITY,
        first_max: 0.0,
        ratio_min: f64::INFINITY,
        ratio_max: 0.0,
    };
    for c in 0..cols.count() - 1 {
        let (a, b) = (cols.node(c, 0), cols.node(c, 1));
        let h = dist(g.point(a.0, a.1), g.point(b.0, b.1));
        out.nodes += 1;
        out.first_min = out.first_min.min(h);
        out.first_max = out.first_max.max(h);
        out.ratio_min = out.ratio_min.min(h / goal);
        out.ratio_max = out.ratio_max.max(h / goal);
    }
    out
}
