//! Runs a volume topology with floating interior faces (`interface = "floating"` on a
//! `[[face]]`): the volumes are solved from the faces as gridded, then rounds of face solves
//! (each floating face by the strip of both its volumes, [`crate::elliptic::floating3d`], the
//! faces one after the other in the case's order) and volume solves (in parallel, each from
//! its last grid) follow until the largest move of a face node in a round is below the solve
//! tolerance, or [`MAX_ROUNDS`] rounds. A volume's report covers all its solves (seconds,
//! Picard steps and history summed over the rounds).

use super::volume::{solve_volume_from, VolumeReport};
use crate::algebraic::control3d::Control3;
use crate::case::LoadedCase;
use crate::elliptic::floating3d::{Plane, Strip};
use crate::grid::faces::Faces;
use crate::grid::topology::volume::Topology3;
use crate::grid::Grid2;
use crate::io::Block;
use crate::solve::select::for_block;
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

/// A solved volume: name, grid, report, control functions.
type Solved = (String, Block, VolumeReport, Control3);

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
    let mut hist: Vec<FloatingHistory> = planes
        .iter()
        .map(|p| FloatingHistory {
            planar: p.is_some(),
            ..Default::default()
        })
        .collect();
    // The volumes' grids and control functions move from round to round (no copies: the
    // strip's operator is the largest thing alive during a round).
    let (mut names, mut vols, mut reports, mut ctrls) =
        unpack(solve_all(case, topo, grids, None, None)?);
    for round in 1..=MAX_ROUNDS {
        let mut worst = 0.0f64;
        for ((strip, plane), h) in strips.iter().zip(&planes).zip(hist.iter_mut()) {
            let t0 = Instant::now();
            let f = strip.face();
            let place = topo.faces.block_place(&file, f);
            let refs: Vec<&Control3> = ctrls.iter().collect();
            let ctrl = strip.controls(topo, &refs);
            let linear = &case.case.volumes[strip.volumes()[0]].linear;
            let mut solver =
                for_block(linear, strip.dims()).map_err(|m| Error::input(&place, m))?;
            let refs: Vec<&Grid3> = vols.iter().collect();
            let (x, info) = strip.solve(topo, &refs, &ctrl, solver.as_mut(), params, &place)?;
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
            solve_volume_from(case, v, &f, start.take(), frozen.take(), &place, t0)
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

fn unpack(solved: Vec<Solved>) -> Unpacked {
    let mut out: Unpacked = Default::default();
    for (name, block, rep, ctrl) in solved {
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
