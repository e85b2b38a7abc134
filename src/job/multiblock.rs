//! Runs a multi-block case (`[[vertex]]`, `[[edge]]`, blocks naming edges): every group of
//! blocks (a block, or a row joined by floating edges; a ring of them, or a block whose cut
//! floats, as one block periodic in i) is gridded as one block, the groups in parallel;
//! shared edges give bit-identical nodes; the report gives the smoothness of every interface.

use super::multiblock_wall::partial_walls;
use super::{surface_distance, BlockReport};
use crate::algebraic::ControlKind;
use crate::case::{BlockKind, LoadedCase};
use crate::elliptic::orthogonal::grid_block_walls;
use crate::elliptic::orthogonal::{grid_block_sides, Sides};
use crate::elliptic::periodic_orthogonal;
use crate::elliptic::picard::PicardInfo;
use crate::elliptic::wall2d::{
    hold_wall_spacing_periodic, wall_spacing_on, wall_spacing_periodic, wall_spacings, WallSide,
    WallSpacing2,
};
use crate::grid::boundary::Boundary2;
use crate::grid::topology::{Group, Topology};
use crate::grid::{Edge, Grid2};
use crate::io::Block;
use crate::quality;
use crate::quality::interface::{interface_smoothness, InterfaceSmoothness};
use crate::solve;
use crate::surface::face::{grid_face_on, project_boundary};
use crate::{Error, Result};
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;

/// Smoothness of the grid across one interior edge.
#[derive(Clone, Debug, Serialize)]
pub struct InterfaceReport {
    pub edge: String,
    pub blocks: [String; 2],
    /// True if the edge floats (its interior nodes moved with the grid).
    pub floating: bool,
    #[serde(flatten)]
    pub smoothness: InterfaceSmoothness,
}

/// The grids and reports of every block (in case order) and of every interface.
pub(super) struct Gridded {
    pub blocks: Vec<(String, Block)>,
    pub reports: Vec<BlockReport>,
    pub interfaces: Vec<InterfaceReport>,
}

/// Grids every group of a topology.
pub(super) fn generate(case: &LoadedCase, topo: &Topology) -> Result<Gridded> {
    let place = case.path.display().to_string();
    let groups = topo.groups(&place)?;
    case.topology_nodes()?;
    let bar = progress_bar(topo.blocks.len());
    let done: Vec<Vec<(usize, Block, BlockReport)>> = groups
        .par_iter()
        .map(|g| {
            let r = grid_group(case, topo, g);
            if let Some(b) = &bar {
                b.inc(g.pieces.len() as u64);
            }
            r
        })
        .collect::<Result<_>>()?;
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let mut slots: Vec<Option<(Block, BlockReport)>> =
        (0..topo.blocks.len()).map(|_| None).collect();
    for (b, block, rep) in done.into_iter().flatten() {
        slots[b] = Some((block, rep));
    }
    let (blocks, reports): (Vec<_>, Vec<_>) = slots
        .into_iter()
        .map(|s| s.expect("every block is in a group"))
        .map(|(block, rep)| ((rep.name.clone(), block), rep))
        .unzip();
    let interfaces = topo
        .connectivity()
        .interfaces
        .iter()
        .filter_map(|f| {
            let smoothness = match (&blocks[f.a.block].1, &blocks[f.b.block].1) {
                (Block::Planar(a), Block::Planar(b)) => interface_smoothness(a, &f.a, b, &f.b),
                (Block::Surface(a), Block::Surface(b)) => interface_smoothness(a, &f.a, b, &f.b),
                _ => return None,
            };
            Some(InterfaceReport {
                edge: topo.edges[f.edge].name.clone(),
                blocks: [f.a.block, f.b.block].map(|b| topo.blocks[b].name.clone()),
                floating: topo.edges[f.edge].floating,
                smoothness,
            })
        })
        .collect();
    Ok(Gridded {
        blocks,
        reports,
        interfaces,
    })
}

/// A terminal progress bar over the `n` blocks of a topology, if progress is on (not
/// `--quiet`) and stderr is a terminal.
fn progress_bar(n: usize) -> Option<indicatif::ProgressBar> {
    use std::io::IsTerminal;
    if !crate::elliptic::volume::progress_enabled() || !std::io::stderr().is_terminal() {
        return None;
    }
    let pb = indicatif::ProgressBar::new(n as u64);
    pb.set_style(
        indicatif::ProgressStyle::with_template("blocks {bar:30} {pos}/{len} [{elapsed}]")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    pb.enable_steady_tick(std::time::Duration::from_millis(200));
    Some(pb)
}

/// Grids one group and cuts it into its blocks.
fn grid_group(
    case: &LoadedCase,
    topo: &Topology,
    g: &Group,
) -> Result<Vec<(usize, Block, BlockReport)>> {
    let t0 = Instant::now();
    let file = case.path.display().to_string();
    let place = if g.pieces.len() == 1 {
        topo.block_place(&file, g.pieces[0].block)
    } else {
        format!("{file}: blocks {} (joined by floating edges)", g.name)
    };
    let kind = case.case.blocks[g.pieces[0].block].kind;
    if let Some(p) = g
        .pieces
        .iter()
        .find(|p| case.case.blocks[p.block].kind != kind)
    {
        return Err(Error::input(
            place,
            format!(
                "block '{}' is {:?} but '{}' is {:?}; blocks joined by floating edges are of \
                 one kind",
                topo.blocks[p.block].name,
                case.case.blocks[p.block].kind,
                topo.blocks[g.pieces[0].block].name,
                kind
            ),
        ));
    }
    let spec = &case.case.solver;
    let mut solver = solve::select::by_name(&spec.linear)
        .map_err(|m| Error::input(format!("{file}: [solver]"), m))?;
    let lists = case.group_points(g)?;
    let params = &spec.picard;
    // (surface blocks hold no wall: their own error below)
    let partial = match kind {
        BlockKind::Surface => None,
        _ => partial_walls(case, topo, g, &place)?,
    };
    let mut out = Vec::new();
    let mut finish = |b: usize, block: Block, picard: Option<&PicardInfo>, q, d, steps, wall| {
        let dims = block.dims();
        let rep = BlockReport {
            name: topo.blocks[b].name.clone(),
            ni: dims[0],
            nj: dims[1],
            seconds: t0.elapsed().as_secs_f64(),
            group: (g.pieces.len() > 1).then(|| g.name.clone()),
            picard: picard.cloned(),
            surface_steps: steps,
            surface_distance: d,
            model_distance: None,
            wall,
            quality: q,
        };
        out.push((b, block, rep));
    };
    match kind {
        BlockKind::Planar => {
            let bnd = case.planar_from(lists, &place)?;
            let r = solve_group(
                &bnd,
                g,
                case,
                partial.as_deref(),
                solver.as_mut(),
                params,
                &place,
            )?;
            // The wall spacing along the group's sides (a row's pieces share its report).
            let walls = group_walls(&r.grid, &bnd, g, partial.as_deref());
            for p in &g.pieces {
                let grid = p.cut(&r.grid);
                let q = quality::quality2d(&grid);
                let w = walls.clone();
                finish(
                    p.block,
                    Block::Planar(grid),
                    Some(&r.picard),
                    q,
                    None,
                    None,
                    w,
                );
            }
        }
        BlockKind::Minimal => {
            let pts = lists.map(|p| p.iter().map(|q| [q.x, q.y, q.z]).collect());
            let bnd = Boundary2::new(pts, &place)?;
            let r = solve_group(
                &bnd,
                g,
                case,
                partial.as_deref(),
                solver.as_mut(),
                params,
                &place,
            )?;
            // The wall spacing along the group's sides (a row's pieces share its report).
            let walls = group_walls(&r.grid, &bnd, g, partial.as_deref());
            for p in &g.pieces {
                let grid = p.cut(&r.grid);
                let q = quality::quality_surface(&grid);
                let at = topo.block_place(&file, p.block);
                let d = match case.reference_surface(p.block)? {
                    Some(s) => Some(surface_distance(&grid, s.as_ref(), &at)?),
                    None => None,
                };
                let w = walls.clone();
                finish(
                    p.block,
                    Block::Surface(grid),
                    Some(&r.picard),
                    q,
                    d,
                    None,
                    w,
                );
            }
        }
        BlockKind::Surface if g.periodic => {
            return Err(Error::input(
                place,
                "a floating cut (periodic block) is for planar and minimal blocks; on a \
                 surface block fix (do not float) one edge of the ring",
            ));
        }
        BlockKind::Surface => {
            super::no_surface_wall(g.wall, &place)?;
            // Section 4 on the blocks' surface, for any sides lying on it (surface::face); a
            // row joined by floating edges is one face on one surface.
            let surface = group_surface(case, g, &place)?;
            let uv = project_boundary(surface.as_ref(), &lists, &place)?;
            let r = grid_face_on(
                surface.as_ref(),
                &lists,
                &uv,
                g.orthogonal,
                solver.as_mut(),
                &place,
            )?;
            let (grid, times) = (r.result.grid, r.result.times);
            for p in &g.pieces {
                let piece = p.cut(&grid);
                let q = quality::quality_surface(&piece);
                let steps = Some(times.clone());
                finish(
                    p.block,
                    Block::Surface(piece),
                    r.uv_picard.as_ref(),
                    q,
                    None,
                    steps,
                    Vec::new(),
                );
            }
        }
    }
    Ok(out)
}

/// The surface of a group of surface blocks: every block of a row joined by floating edges
/// must name the same `[[surface]]`.
fn group_surface(
    case: &LoadedCase,
    g: &Group,
    place: &str,
) -> Result<Box<dyn ellipgrid_geometry::Surface>> {
    use crate::case::spec::SurfaceRef;
    let first = &case.case.blocks[g.pieces[0].block].surface;
    if g.pieces.len() > 1 {
        let same = g.pieces.iter().all(|p| {
            matches!(
                (&case.case.blocks[p.block].surface, first),
                (Some(SurfaceRef::Named(a)), Some(SurfaceRef::Named(b))) if a == b
            )
        });
        if !same {
            return Err(Error::input(
                place,
                "surface blocks joined by floating edges must name one [[surface]]",
            ));
        }
    }
    case.surface(g.pieces[0].block)
}

fn solve_group<const D: usize>(
    bnd: &Boundary2<D>,
    g: &Group,
    case: &LoadedCase,
    partial: Option<&[WallSide]>,
    solver: &mut dyn solve::LinearSolver,
    params: &crate::elliptic::picard::PicardParams,
    place: &str,
) -> Result<crate::elliptic::picard::Solved<Grid2<D>>> {
    let ctrl = case.case.solver.control;
    if let (Some(walls), false) = (partial, g.periodic) {
        return grid_block_walls(bnd, None, g.orthogonal, walls, ctrl, solver, params, place);
    }
    if g.periodic {
        // the seam floats: periodic in i, its own solver (elliptic::periodic)
        let walls = periodic_walls(g, partial);
        if !walls.is_empty() && ctrl != ControlKind::Algebraic {
            return Err(Error::input(
                place,
                "wall spacings need the algebraic control functions (control = \"algebraic\")",
            ));
        }
        let (r, pg) =
            periodic_orthogonal::grid_block(bnd, None, g.orthogonal, ctrl, params, place)?;
        if walls.is_empty() {
            return Ok(r);
        }
        let (grid, held) = hold_wall_spacing_periodic(r.grid, pg, bnd, &walls, params, place)?;
        let mut picard = r.picard;
        if let Some(h) = held {
            picard.append(h);
        }
        return Ok(crate::elliptic::picard::Solved { grid, picard });
    }
    let sides = Sides {
        orthogonal: g.orthogonal,
        wall: g.wall,
    };
    grid_block_sides(bnd, None, sides, ctrl, solver, params, place)
}

/// The wall spacing along a group's wall sides: the partial walls' if any, else the whole
/// flagged sides'; a periodic group's against its cut's first spacing.
fn group_walls<const D: usize>(
    grid: &Grid2<D>,
    bnd: &Boundary2<D>,
    g: &Group,
    partial: Option<&[WallSide]>,
) -> Vec<WallSpacing2> {
    if g.periodic {
        return periodic_walls(g, partial)
            .iter()
            .map(|s| wall_spacing_periodic(grid, bnd, s.edge))
            .collect();
    }
    match partial {
        Some(w) => w.iter().map(|s| wall_spacing_on(grid, s)).collect(),
        None => wall_spacings(grid, g.wall),
    }
}

/// A periodic group's wall sides: the partial walls' list (it carries `wall_fade`), else
/// the whole flagged sides.
fn periodic_walls(g: &Group, partial: Option<&[WallSide]>) -> Vec<WallSide> {
    match partial {
        Some(w) => w.to_vec(),
        None => Edge::ALL
            .into_iter()
            .filter(|e| g.wall[e.index()])
            .map(WallSide::whole)
            .collect(),
    }
}
