//! Runs a volume topology with floating interior faces (`interface = "floating"` on a
//! `[[face]]`): the volumes are solved from the faces as gridded, then rounds of face solves
//! (each floating face by the strip of both its volumes, [`crate::elliptic::floating3d`], the
//! faces one after the other in the case's order) and volume solves (in parallel, each from
//! its last grid) follow until the largest move of a face node in a round is below the solve
//! tolerance, or [`MAX_ROUNDS`] rounds. A volume's report covers all its solves (seconds,
//! Picard steps and history summed over the rounds).
//!
//! A face between two volumes whose walls lie on one face of the strip (the ONERA M6's plane
//! ahead of the leading edge, between the two wing volumes) keeps the wall: its first strip
//! solve is the volume wall correction on the strip as one block (`walled_strip`: the
//! union of the two walls, the goal columns the volumes' own), and its control functions then
//! serve the strip's later solves and, carried back, the two volumes' re-solves (whose grid
//! system is then the strip's: they stay where the strip put them).

use super::volume::{corrections, solve_volume_from, VolumeReport};
use crate::algebraic::bilinear3d::{bilinear, ParamGrid3};
use crate::algebraic::control3d::Control3;
use crate::algebraic::flat_edge::edge_functions;
use crate::case::volume::wall_face;
use crate::case::LoadedCase;
use crate::elliptic::floating3d::{Plane, Strip};
use crate::elliptic::orthogonal3d::{grid_volume_corrected_to, AlgebraicMap, FaceCorrections};
use crate::elliptic::picard::PicardInfo;
use crate::elliptic::wall::WallTargets;
use crate::grid::faces::Faces;
use crate::grid::topology::volume::Topology3;
use crate::grid::Grid2;
use crate::io::Block;
use crate::solve::select::for_block;
use crate::solve::stencil19::Stencil19;
use crate::solve::LinearSolver;
use crate::{Error, Grid3, Result};
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;

/// Rounds of face and volume solves at most.
pub const MAX_ROUNDS: usize = 40;

/// The history of one floating face.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FloatingHistory {
    /// Rounds run (the same for every floating face of a case).
    pub rounds: usize,
    /// True if the round's largest face-node move fell below the solve tolerance.
    pub converged: bool,
    /// The face's largest node move per round, over the diameter of its strip.
    pub updates: Vec<f64>,
    /// Picard steps of the face's strip solves, all rounds.
    pub picard_steps: usize,
    /// True if the face is planar and its nodes slide in its plane.
    pub planar: bool,
    /// Seconds of the face's strip solves, all rounds.
    pub seconds: f64,
}

/// A solved volume: name, grid, report, control functions, the corrected algebraic map.
type Solved = (String, Block, VolumeReport, Control3, Option<ParamGrid3>);

/// The volumes (name, grid, report) and, per face of the topology, a floating face's history.
pub type Floated = (
    Vec<(String, Block, VolumeReport)>,
    Vec<Option<FloatingHistory>>,
);

/// Grids the volumes of `topo` from the face grids `grids`, moving the floating faces' interior
/// nodes (module docs); `grids` ends with the floated faces. Returns the volumes and, per face
/// of the topology, the history of a floating one.
pub fn float(case: &LoadedCase, topo: &Topology3, grids: &mut [Grid2<3>]) -> Result<Floated> {
    let file = case.path.display().to_string();
    let params = &case.case.solver.picard;
    let strips: Vec<Strip> = topo
        .connectivity()
        .interfaces
        .iter()
        .filter(|f| case.case.faces[f.face].floating())
        .map(|f| Strip::new(topo, f, &topo.faces.block_place(&file, f.face)))
        .collect::<Result<_>>()?;
    let planes: Vec<Option<Plane>> = strips
        .iter()
        .map(|s| Plane::of_face(&grids[s.face()]))
        .collect();
    // Per strip: its wall face if both volumes have their wall on one face of it, and the
    // strip's control functions once its wall passes have run.
    let walls: Vec<Option<usize>> = strips
        .iter()
        .map(|s| {
            let w = s
                .volumes()
                .map(|v| wall_face(&case.case.volumes[v], &topo.volume_place(&file, v)).ok()?);
            s.wall_face(w)
        })
        .collect();
    let mut strip_ctrls: Vec<Option<Control3>> = vec![None; strips.len()];
    let mut hist: Vec<FloatingHistory> = planes
        .iter()
        .map(|p| FloatingHistory {
            planar: p.is_some(),
            ..Default::default()
        })
        .collect();
    // The volumes' grids and control functions move from round to round (no copies: the
    // strip's operator is the largest thing alive during a round).
    let mut first = solve_all(case, topo, grids, None, None)?;
    let mut maps = unpack_maps(&mut first);
    // only the volumes of a walled strip need their corrected maps (~24 bytes per node each)
    for (v, m) in maps.iter_mut().enumerate() {
        let walled = |(s, w): (&Strip, &Option<usize>)| w.is_some() && s.volumes().contains(&v);
        if !strips.iter().zip(&walls).any(walled) {
            *m = None;
        }
    }
    let (mut names, mut vols, mut reports, mut ctrls) = unpack(first);
    for round in 1..=MAX_ROUNDS {
        let mut worst = 0.0f64;
        for (n, ((strip, plane), h)) in strips.iter().zip(&planes).zip(&mut hist).enumerate() {
            let t0 = Instant::now();
            let f = strip.face();
            let place = topo.faces.block_place(&file, f);
            let linear = &case.case.volumes[strip.volumes()[0]].linear;
            let mut solver =
                for_block(linear, strip.dims()).map_err(|m| Error::input(&place, m))?;
            let refs: Vec<&Grid3> = vols.iter().collect();
            let (x, info) = match (walls[n], &strip_ctrls[n]) {
                (_, Some(ctrl)) => {
                    strip.solve(topo, &refs, ctrl, solver.as_mut(), params, &place)?
                }
                (Some(w), None) => {
                    let (x, info, ctrl) =
                        walled_strip(case, topo, grids, strip, w, &refs, &maps, solver.as_mut())?;
                    let [a, b] = strip.volumes();
                    [ctrls[a], ctrls[b]] = strip.volume_controls(topo, &ctrl);
                    strip_ctrls[n] = Some(ctrl);
                    (x, info)
                }
                (None, None) => {
                    let refs_c: Vec<&Control3> = ctrls.iter().collect();
                    let ctrl = strip.controls(topo, &refs_c);
                    strip.solve(topo, &refs, &ctrl, solver.as_mut(), params, &place)?
                }
            };
            if !info.converged {
                let [a, b] = strip.volumes().map(|v| topo.volumes[v].name.as_str());
                return Err(Error::input(
                    place,
                    format!(
                        "interface = \"floating\": the grid system across the face (volumes \
                         '{a}' and '{b}' as one block) did not converge in round {round} ({} \
                         Picard steps, residual {:.1e}); make the face fixed",
                        info.steps, info.final_residual
                    ),
                ));
            }
            let moved = strip.scatter(topo, &x, &mut grids[f], plane.as_ref(), &mut vols);
            let update = moved / x.diameter();
            h.updates.push(update);
            h.picard_steps += info.steps;
            h.seconds += t0.elapsed().as_secs_f64();
            worst = worst.max(update);
        }
        let (starts, frozen) = (std::mem::take(&mut vols), std::mem::take(&mut ctrls));
        let next = solve_all(case, topo, grids, Some(starts), Some(frozen))?;
        let (n, v, mut r, c) = unpack(next);
        for (new, old) in r.iter_mut().zip(&reports) {
            accumulate(new, old);
        }
        (names, vols, reports, ctrls) = (n, v, r, c);
        let converged = worst <= params.tolerance;
        for h in &mut hist {
            h.rounds = round;
            h.converged = converged;
        }
        if converged {
            break;
        }
    }
    let mut per_face = vec![None; topo.faces.blocks.len()];
    for (s, h) in strips.iter().zip(hist) {
        per_face[s.face()] = Some(h);
    }
    let done = names
        .into_iter()
        .zip(vols)
        .zip(reports)
        .map(|((name, grid), rep)| (name, Block::Volume(grid), rep))
        .collect();
    Ok((done, per_face))
}

/// The first solve of a strip across a face between two wall volumes: the strip as one
/// block with the wall correction at its wall face `w` (the union of the two walls), the goal
/// columns its volumes' ([`crate::elliptic::floating3d::Strip::wall_targets`]), from the
/// volumes' grids. Returns the strip's grid, history and control functions.
#[allow(clippy::too_many_arguments)]
fn walled_strip(
    case: &LoadedCase,
    topo: &Topology3,
    grids: &[Grid2<3>],
    strip: &Strip,
    w: usize,
    vols: &[&Grid3],
    maps: &[Option<ParamGrid3>],
    solver: &mut dyn LinearSolver<Stencil19>,
) -> Result<(Grid3, PicardInfo, Control3)> {
    let file = case.path.display().to_string();
    let place = topo.faces.block_place(&file, strip.face());
    let mut orthogonal = false;
    let mut targets = Vec::with_capacity(2);
    let mut params = Vec::with_capacity(2);
    for v in strip.volumes() {
        let vplace = topo.volume_place(&file, v);
        let spec = &case.case.volumes[v];
        let vw = wall_face(spec, &vplace)?;
        let c = corrections(&case.case.volumes, spec, vw, &vplace)?;
        let vw = vw.expect("both volumes have a wall (Strip::wall_face)");
        orthogonal |= c.orthogonal[vw];
        let faces = Faces::new(topo.volume_faces(v, grids), &vplace)?;
        targets.push(WallTargets::with_profiles(&faces, vw, c.profiles, &vplace)?);
        params.push(match &maps[v] {
            Some(pg) => pg.clone(),
            None => bilinear(&edge_functions(&faces), &vplace)?,
        });
    }
    let goals = strip.wall_targets(topo, w, [&targets[0], &targets[1]]);
    drop(targets);
    let map = AlgebraicMap {
        param: strip.glued_param(topo, [&params[0], &params[1]]),
        controls: &Control3::from_algebraic,
    };
    drop(params);
    let x = strip.gather(topo, vols);
    let faces = Faces::from_grid(&x);
    let mut c = FaceCorrections {
        wall: Some(w),
        ..Default::default()
    };
    c.orthogonal[w] = orthogonal;
    let (r, ctrl, _) = grid_volume_corrected_to(
        &faces,
        &c,
        Some(goals),
        map,
        Some(x),
        solver,
        &case.case.solver.picard,
        &place,
        &mut |_, _| {},
    )?;
    Ok((r.grid, r.picard, ctrl))
}

/// Solves every volume from the face grids, in parallel, from `starts` if given.
fn solve_all(
    case: &LoadedCase,
    topo: &Topology3,
    grids: &[Grid2<3>],
    starts: Option<Vec<Grid3>>,
    frozen: Option<Vec<Control3>>,
) -> Result<Vec<Solved>> {
    let file = case.path.display().to_string();
    let mut starts: Vec<Option<Grid3>> = match starts {
        Some(s) => s.into_iter().map(Some).collect(),
        None => vec![None; topo.volumes.len()],
    };
    let mut frozen: Vec<Option<Control3>> = match frozen {
        Some(f) => f.into_iter().map(Some).collect(),
        None => vec![None; topo.volumes.len()],
    };
    starts
        .par_iter_mut()
        .zip(frozen.par_iter_mut())
        .enumerate()
        .map(|(v, (start, frozen))| {
            let t0 = Instant::now();
            let place = topo.volume_place(&file, v);
            let f = Faces::new(topo.volume_faces(v, grids), &place)?;
            solve_volume_from(
                case,
                v,
                &f,
                start.take(),
                frozen.take(),
                Default::default(),
                &place,
                t0,
            )
        })
        .collect()
}

/// A volume's report over all its solves: the seconds and Picard steps of the earlier ones
/// added, their history before the last solve's.
fn accumulate(new: &mut VolumeReport, old: &VolumeReport) {
    new.seconds += old.seconds;
    let p = &mut new.picard;
    p.steps += old.picard.steps;
    let mut history = old.picard.history.clone();
    history.append(&mut p.history);
    p.history = history;
}

/// The volumes' names, grids, reports and control functions, moved out of their solves.
type Unpacked = (Vec<String>, Vec<Grid3>, Vec<VolumeReport>, Vec<Control3>);

/// The volumes' corrected algebraic maps (those with a wall or orthogonal faces).
fn unpack_maps(solved: &mut [Solved]) -> Vec<Option<ParamGrid3>> {
    solved.iter_mut().map(|s| s.4.take()).collect()
}

fn unpack(solved: Vec<Solved>) -> Unpacked {
    let mut out: Unpacked = Default::default();
    for (name, block, rep, ctrl, _) in solved {
        let Block::Volume(grid) = block else {
            unreachable!("volumes are volume blocks")
        };
        out.0.push(name);
        out.1.push(grid);
        out.2.push(rep);
        out.3.push(ctrl);
    }
    out
}
