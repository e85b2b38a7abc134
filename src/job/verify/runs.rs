//! The runs of `verify`: each level of the family (as `run` generates it; level 0 also from a
//! scrambled start) and the surface blocks of each level on a warped parametrization.

use super::{SurfaceGrid, VerifyOptions, WARP_STRENGTH};
use crate::algebraic::periodic::{close_seam, periodic_start};
use crate::algebraic::scramble::{scrambled, scrambled3};
use crate::algebraic::transfinite3d;
use crate::algebraic::transform::transfinite;
use crate::case::volume::{volume_place, wall_face};
use crate::case::{BlockKind, LoadedCase};
use crate::elliptic::orthogonal::grid_block_walls;
use crate::elliptic::orthogonal::{grid_block_sides, Sides};
use crate::elliptic::orthogonal3d::grid_volume_corrected;
use crate::elliptic::periodic_orthogonal;
use crate::elliptic::picard::{PicardInfo, PicardParams};
use crate::elliptic::volume::grid_volume;
use crate::elliptic::wall::LOOSE_TOLERANCE;
use crate::elliptic::wall2d::{WallSide, LOOSE_TOLERANCE as LOOSE_TOLERANCE_2D};
use crate::grid::boundary::Boundary2;
use crate::grid::faces::Faces;
use crate::grid::Grid2;
use crate::io::Block;
use crate::job::multiblock_wall::partial_walls;
use crate::job::volume::{continued_faces, corrections};
use crate::job::{generate, Generated};
use crate::quality::quality3d::quality3d;
use crate::quality::{quality2d, quality_surface};
use crate::solve::{self, LinearSolver};
use crate::surface::pipeline::{grid_surface_orthogonal, SurfaceResult};
use crate::{Error, Result};
use ellipgrid_geometry::{Surface, Warp, Warped};

/// One run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Task {
    /// Level l of the family (level 0 then also from the scrambled start).
    Family(usize),
    /// The surface blocks of level l on the warped parametrization.
    Warped(usize),
}

/// What a run gives.
pub(super) enum Output {
    /// The level's grids, and (level 0) the runs from the scrambled start.
    Family(Box<Generated>, Vec<StartRun>),
    /// (block, grid) of every surface block.
    Warped(Vec<(usize, Block)>),
}

/// The grids of one unit (a block, a row of blocks joined by floating edges, a volume) from
/// the scrambled start.
#[derive(Clone, Debug)]
pub struct StartRun {
    /// The blocks of the unit (in the generated order: 2D blocks, then volumes).
    pub members: Vec<usize>,
    /// Their grids, if the solve succeeded.
    pub grids: Vec<Block>,
    /// Cells of the start grid and how many of them fold.
    pub start_cells: usize,
    pub start_folded: usize,
    /// The Picard history from the scrambled start (None if the solve failed).
    pub picard: Option<PicardInfo>,
    /// Why the solve failed.
    pub failure: Option<String>,
    /// The tolerance the grids are defined to: the Picard tolerance, or for a block or volume
    /// with a wall spacing that of its intermediate solves if larger
    /// ([`crate::elliptic::wall::LOOSE_TOLERANCE`], 2D [`crate::elliptic::wall2d::LOOSE_TOLERANCE`]).
    pub tolerance: f64,
}

/// Runs one task on the levels `cases`.
pub(super) fn run(task: Task, cases: &[LoadedCase], opts: &VerifyOptions) -> Result<Output> {
    match task {
        Task::Family(l) => {
            let mut g = generate(&cases[l], |_| {})?;
            if opts.surface_grid == SurfaceGrid::Initial {
                for (k, grid) in surfaces(&cases[l], None, opts)? {
                    g.blocks[k].1 = grid;
                }
            }
            let s = if l == 0 {
                starts(&cases[0], opts.seed, &g)?
            } else {
                Vec::new()
            };
            Ok(Output::Family(Box::new(g), s))
        }
        Task::Warped(l) => {
            let warp = Warp::new(opts.seed, WARP_STRENGTH).map_err(|source| Error::Geometry {
                place: "verify: warp".into(),
                source,
            })?;
            Ok(Output::Warped(surfaces(&cases[l], Some(&warp), opts)?))
        }
    }
}

/// The grid of every surface block (the one `opts` verifies), on its surface or warped.
fn surfaces(
    case: &LoadedCase,
    warp: Option<&Warp>,
    opts: &VerifyOptions,
) -> Result<Vec<(usize, Block)>> {
    let mut out = Vec::new();
    for k in 0..case.case.blocks.len() {
        if case.case.blocks[k].kind != BlockKind::Surface {
            continue;
        }
        let place = case.block_place(k);
        // a block on a STEP model: its net's surface, the nodes moved onto the model at the end
        let model = if case.is_model_block(k) {
            Some(crate::job::model::model_block(case, k)?)
        } else {
            None
        };
        let owned;
        let surface: &dyn Surface = match &model {
            Some(m) => &m.surface,
            None => {
                owned = case.surface(k)?;
                owned.as_ref()
            }
        };
        let orth = case.block_orthogonal(k)?;
        let mut solver = linear(case)?;
        let mut grid = |s: &dyn Surface| -> Result<SurfaceResult> {
            let uv = case.surface_uv(k, s)?;
            grid_surface_orthogonal(s, &uv, orth, solver.as_mut(), &place)
        };
        let mut r = match warp {
            Some(w) => grid(&Warped {
                surface,
                warp: w.clone(),
            })?,
            None => grid(surface)?,
        };
        if let Some(m) = &model {
            crate::job::model::onto_model(&mut r.grid, m);
        }
        let g = match opts.surface_grid {
            SurfaceGrid::Section4 => r.grid,
            SurfaceGrid::Initial => r.initial,
        };
        out.push((k, Block::Surface(g)));
    }
    Ok(out)
}

/// The case's 2D linear solver.
fn linear(case: &LoadedCase) -> Result<Box<dyn LinearSolver>> {
    solve::select::by_name(&case.case.solver.linear)
        .map_err(|m| Error::input(format!("{}: [solver]", case.path.display()), m))
}

/// A grid and its Picard history, or why the solve failed.
type Solve<T> = std::result::Result<(T, PicardInfo), String>;

/// A unit from its scrambled start: the start's cells, how many fold, and the solve.
type Unit<T> = (usize, usize, Solve<T>);

/// A 2D unit (block or group) from the scrambled transfinite start of its boundary.
#[allow(clippy::too_many_arguments)]
fn start_2d<const D: usize>(
    b: &Boundary2<D>,
    sides: Sides,
    partial: Option<&[WallSide]>,
    periodic: bool,
    case: &LoadedCase,
    seed: u64,
    place: &str,
    folded: impl Fn(&Grid2<D>) -> usize,
) -> Result<Unit<Grid2<D>>> {
    let spec = &case.case.solver;
    if periodic {
        // a floating cut: the periodic start scrambled, its seam closed again
        let mut start = scrambled(&periodic_start(b), seed);
        close_seam(&mut start);
        let (cells, bad) = ((start.ni() - 1) * (start.nj() - 1), folded(&start));
        let orth = sides.orthogonal;
        let r = periodic_orthogonal::grid_block(
            b,
            Some(start),
            orth,
            spec.control,
            &spec.picard,
            place,
        );
        return Ok((cells, bad, solved(r.map(|(r, _)| (r.grid, r.picard)))?));
    }
    let start = scrambled(&transfinite(b), seed);
    let cells = (start.ni() - 1) * (start.nj() - 1);
    let bad = folded(&start);
    let mut solver = linear(case)?;
    let r = match partial {
        Some(walls) => grid_block_walls(
            b,
            Some(start),
            sides.orthogonal,
            walls,
            spec.control,
            solver.as_mut(),
            &spec.picard,
            place,
        ),
        None => grid_block_sides(
            b,
            Some(start),
            sides,
            spec.control,
            solver.as_mut(),
            &spec.picard,
            place,
        ),
    };
    Ok((cells, bad, solved(r.map(|r| (r.grid, r.picard)))?))
}

/// The tolerance a 2D grid is defined to: with a wall spacing that of the correction's
/// intermediate solves, if larger (as for volumes).
fn wall_tolerance(tol: f64, sides: Sides) -> f64 {
    if sides.wall.contains(&true) {
        tol.max(LOOSE_TOLERANCE_2D)
    } else {
        tol
    }
}

/// A solve's failure as a property (the start grid made it fail), other errors as errors.
fn solved<T>(r: Result<T>) -> Result<std::result::Result<T, String>> {
    match r {
        Ok(v) => Ok(Ok(v)),
        Err(e @ (Error::Solve { .. } | Error::Folded { .. })) => Ok(Err(e.to_string())),
        Err(e) => Err(e),
    }
}

/// Every 2D block (or group) and volume of `case` from its scrambled start (the volumes
/// within the faces of their grids in `g`, the level's grids).
fn starts(case: &LoadedCase, seed: u64, g: &Generated) -> Result<Vec<StartRun>> {
    let mut out = Vec::new();
    let nblocks = case.case.blocks.len();
    let tol = case.case.solver.picard.tolerance;
    let unit =
        |members: Vec<usize>, cells, folded, r: std::result::Result<_, String>, tolerance| {
            let (grids, picard, failure) = match r {
                Ok((grids, picard)) => (grids, Some(picard), None),
                Err(m) => (Vec::new(), None, Some(m)),
            };
            StartRun {
                members,
                grids,
                start_cells: cells,
                start_folded: folded,
                picard,
                failure,
                tolerance,
            }
        };
    if let Some(topo) = &case.topology {
        let file = case.path.display().to_string();
        for g in topo.groups(&file)? {
            let place = format!("{file}: blocks {} (scrambled start)", g.name);
            let members: Vec<usize> = g.pieces.iter().map(|p| p.block).collect();
            let lists = case.group_points(&g)?;
            let sides = Sides {
                orthogonal: g.orthogonal,
                wall: g.wall,
            };
            let partial = partial_walls(case, topo, &g, &place)?;
            let partial = partial.as_deref();
            let (cells, bad, r) = match case.case.blocks[members[0]].kind {
                BlockKind::Minimal => {
                    let pts = lists.map(|p| p.iter().map(|q| [q.x, q.y, q.z]).collect());
                    let bnd = Boundary2::new(pts, &place)?;
                    let (c, f, r) =
                        start_2d(&bnd, sides, partial, g.periodic, case, seed, &place, |s| {
                            quality_surface(s).folded_cells
                        })?;
                    let cut = |x: Grid2<3>| {
                        let pieces = g.pieces.iter();
                        pieces.map(|p| Block::Surface(p.cut(&x))).collect()
                    };
                    (c, f, r.map(|(x, p)| (cut(x), p)))
                }
                _ => {
                    let bnd = case.planar_from(lists, &place)?;
                    let (c, f, r) =
                        start_2d(&bnd, sides, partial, g.periodic, case, seed, &place, |s| {
                            quality2d(s).folded_cells
                        })?;
                    let cut = |x: Grid2<2>| {
                        let pieces = g.pieces.iter();
                        pieces.map(|p| Block::Planar(p.cut(&x))).collect()
                    };
                    (c, f, r.map(|(x, p)| (cut(x), p)))
                }
            };
            out.push(unit(members, cells, bad, r, wall_tolerance(tol, sides)));
        }
    } else {
        for k in 0..nblocks {
            let place = format!("{} (scrambled start)", case.block_place(k));
            let sides = case.block_sides(k)?;
            let (cells, bad, r) = match case.case.blocks[k].kind {
                BlockKind::Surface => continue,
                BlockKind::Planar => {
                    let b = case.planar_boundary(k)?;
                    let (c, f, r) = start_2d(&b, sides, None, false, case, seed, &place, |s| {
                        quality2d(s).folded_cells
                    })?;
                    (c, f, r.map(|(x, p)| (vec![Block::Planar(x)], p)))
                }
                BlockKind::Minimal => {
                    let b = case.minimal_boundary(k)?;
                    let (c, f, r) = start_2d(&b, sides, None, false, case, seed, &place, |s| {
                        quality_surface(s).folded_cells
                    })?;
                    (c, f, r.map(|(x, p)| (vec![Block::Surface(x)], p)))
                }
            };
            out.push(unit(vec![k], cells, bad, r, wall_tolerance(tol, sides)));
        }
    }
    for k in 0..case.case.volumes.len() {
        let Some((_, Block::Volume(grid))) = g.blocks.get(nblocks + k) else {
            unreachable!("the volumes follow the 2D blocks");
        };
        let (cells, bad, r) = start_volume(case, k, &Faces::from_grid(grid), seed)?;
        let wall = wall_face(&case.case.volumes[k], &volume_place(case, k))?;
        let t = if wall.is_some() {
            tol.max(LOOSE_TOLERANCE)
        } else {
            tol
        };
        out.push(unit(vec![nblocks + k], cells, bad, r, t));
    }
    Ok(out)
}

/// Volume k within `faces` from its scrambled start (with its wall spacing, if any, as `run`
/// grids it).
fn start_volume(case: &LoadedCase, k: usize, faces: &Faces, seed: u64) -> Result<Unit<Vec<Block>>> {
    let place = format!("{} (scrambled start)", volume_place(case, k));
    let v = &case.case.volumes[k];
    let spec = &case.case.solver;
    let params: &PicardParams = &spec.picard;
    let start = scrambled3(&transfinite3d::transfinite(faces), seed);
    let [ni, nj, nk] = start.dims();
    let cells = (ni - 1) * (nj - 1) * (nk - 1);
    let bad = quality3d(&start).folded_cells;
    let mut solver =
        solve::select::for_block(&v.linear, faces.dims()).map_err(|m| Error::input(&place, m))?;
    let c = corrections(&case.case.volumes, v, wall_face(v, &place)?, &place)?;
    if continued_faces(v, &place)?.contains(&true) {
        return Err(Error::input(
            &place,
            "continue: the start-grid check does not support continued faces yet",
        ));
    }
    let r = match c.any() {
        true => grid_volume_corrected(
            faces,
            &c,
            Some(start),
            solver.as_mut(),
            params,
            &place,
            &mut |_, _| {},
        ),
        false => grid_volume(
            faces,
            Some(start),
            spec.control,
            solver.as_mut(),
            params,
            &place,
            &mut |_, _| {},
        ),
    };
    let r = solved(r.map(|r| (vec![Block::Volume(r.grid)], r.picard)))?;
    Ok((cells, bad, r))
}
