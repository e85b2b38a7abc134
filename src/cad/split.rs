//! A CAD face gridded as several blocks: a face with holes split by [`super::holes`] into an
//! O-type ring of four blocks around each hole, or a one-loop face whose one block folds cut
//! at its reentrant vertices by [`super::reentrant`]; every block gridded as a block face
//! ([`super::blocks`]: cuts shared bit for bit). Nodes along a hole and along the outer
//! loop's pieces (and the cuts between strips) are the blocks' i direction (`ni`, `dist_i`);
//! the cuts from a hole outwards are the j direction (`nj`, `dist_j`, its first spacing at
//! the hole).

use super::band::band;
use super::blocks::grid_layout;
use super::chords::grid_face_chords;
use super::face::{bounds, folds, gap_tolerance, grid_face_by, Corners, FaceGrid};
use super::fan::fan;
use super::holes::layout;
use super::reentrant::grid_face_split;
use super::trim::{CadSurface, FaceLoop};
use super::{quietly, Route, StepFace};
use crate::case::DistributionSpec;
use crate::solve::LinearSolver;
use crate::{Error, Result};
use ellipgrid_geometry::TruckSurface;

/// The grids of a face, one per block: one block for a face of one loop ([`super::grid_face`])
/// or, where that block folds, the face cut at its reentrant vertices into blocks
/// ([`super::grid_face_split`], if those do not fold), else one block with other corners
/// ([`Corners::Balanced`], then [`Corners::Collapsed`], then [`Corners::Tips`]; the first
/// whose smallest scaled Jacobian is at least [`CLEARLY_VALID`]), else the face cut by chords
/// between its reentrant vertices ([`super::grid_face_chords`]) or the fold-free grid of
/// those with the largest smallest scaled Jacobian,
/// four around each hole for a face with holes, in the order of the holes, each ring's blocks
/// one after the other around the hole; four across a closed band without a seam edge.
/// An untrimmed patch whose one block folds and that has creases (or kinks) is cut along them
/// into blocks ([`super::grid_creased`]) if those have fewer folded cells in all (sub-patches
/// without area left out); one that folds back over itself is cut there whether its one
/// block's fold test fails or not (the flap left out), if the blocks do not fold.
/// Blocks run counterclockwise in (u, v) when the face's normal is the surface's, so that
/// every block's normal is the face's.
///
/// # Errors
/// Those of [`super::grid_face`]; [`Error::Input`] at `place` with the reason if a face with
/// holes cannot be split: holes that neither parallel straight cuts nor a fan of cuts about a
/// central hole separate, a cut crossing the outer loop more than twice, a hole not
/// star-shaped about its centroid, a band with holes.
pub fn grid_face_blocks(
    face: &StepFace,
    (ni, nj): (usize, usize),
    dist_i: &DistributionSpec,
    dist_j: &DistributionSpec,
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<Vec<FaceGrid>> {
    if let Route::Trimmed(_) = face.route() {
        // A one-loop face whose one block folds is cut at its reentrant vertices into
        // blocks, if that gives a grid that does not fold; faces that do not fold are
        // never cut.
        let d = (dist_i, dist_j);
        let one = grid_face_by(face, (ni, nj), d.0, d.1, solver, place, Corners::Turning);
        if folds(&one) {
            let cut = grid_face_split(face, (ni, nj), dist_i, dist_j, solver, place);
            if let Ok(gs) = cut {
                if gs.iter().all(|g| !g.quality.is_folded()) {
                    return Ok(gs);
                }
            }
            // Neither the corners by turning angle nor the cut: one block with other corners,
            // then with its cusp as a collapsed side, then its tips. The first whose smallest
            // scaled Jacobian reaches CLEARLY_VALID is taken; one below it is kept while the
            // others and the chords are tried, the best of those that do not fold taken.
            let mut best: Option<(f64, Vec<FaceGrid>)> = None;
            let keep = |gs: Vec<FaceGrid>, best: &mut Option<(f64, Vec<FaceGrid>)>| {
                let q = smallest_scaled_jacobian(&gs);
                if best.as_ref().is_none_or(|(b, _)| q > *b) {
                    *best = Some((q, gs));
                }
            };
            for sets in [Corners::Balanced, Corners::Collapsed, Corners::Tips] {
                let other = grid_face_by(face, (ni, nj), d.0, d.1, solver, place, sets);
                match other {
                    Ok(g) if !g.quality.is_folded() => {
                        if smallest_scaled_jacobian(std::slice::from_ref(&g)) >= CLEARLY_VALID {
                            return Ok(vec![g]);
                        }
                        keep(vec![g], &mut best);
                    }
                    _ => {}
                }
            }
            // Last, the face cut by chords between its reentrant vertices.
            let chords = grid_face_chords(face, (ni, nj), dist_i, dist_j, solver, place);
            if let Ok(gs) = chords {
                if gs.iter().all(|g| !g.quality.is_folded()) {
                    keep(gs, &mut best);
                }
            }
            if let Some((_, gs)) = best {
                return Ok(gs);
            }
        }
        return one.map(|g| vec![g]);
    }
    if let Route::Patch = face.route() {
        // An untrimmed patch whose one block folds is cut along its creases into blocks
        // ([`super::crease`]), if those fold less; patches that do not fold are never cut,
        // but for one that folds back over itself: its one block would cover part of the
        // face twice, a fold the fold test cannot see where the surface's normal turns over
        // with the grid (`cad::boundary_cuts`).
        let cuts = super::creases(face);
        if (cuts.iter()).any(|c| matches!(c.kind, super::CutKind::FoldBack { .. })) {
            let cut = super::grid_creased(face, (ni, nj), dist_i, dist_j, solver, place);
            if let Ok((gs, _)) = cut {
                if gs.iter().all(|g| !g.quality.is_folded()) {
                    return Ok(gs);
                }
            }
        }
        let one = super::grid_face(face, (ni, nj), dist_i, dist_j, solver, place);
        if folds(&one) && !cuts.is_empty() {
            let cut = super::grid_creased(face, (ni, nj), dist_i, dist_j, solver, place);
            if let Ok((gs, _)) = cut {
                let cells =
                    |gs: &[FaceGrid]| -> usize { gs.iter().map(|g| g.quality.folded_cells).sum() };
                let before = one
                    .as_ref()
                    .map_or(usize::MAX, |g| cells(std::slice::from_ref(g)));
                if cells(&gs) < before {
                    return Ok(gs);
                }
            }
        }
        return one.map(|g| vec![g]);
    }
    if !matches!(face.route(), Route::Holes(_)) {
        return super::grid_face(face, (ni, nj), dist_i, dist_j, solver, place).map(|g| vec![g]);
    }
    if ni < 3 || nj < 3 {
        return Err(Error::input(
            place,
            format!("a surface grid needs at least 3 × 3 nodes, got {ni} × {nj}"),
        ));
    }
    let surface = TruckSurface::new(face.cad_surface.clone());
    quietly(|| holes(face, &surface, (ni, nj), [dist_i, dist_j], solver, place)).unwrap_or_else(
        |_| {
            Err(Error::input(
                place,
                "truck failed to evaluate a boundary edge or the surface",
            ))
        },
    )
}

/// The smallest scaled Jacobian of a one-block grid with other corners that is taken at once
/// ([`grid_face_blocks`]); below it the chords are tried as well and the better kept. On the
/// 40-file corpus at 33² (`bench_step`) the 83 faces gridded with other corners had smallest
/// scaled Jacobians (over the cells off a collapsed side) of at most 5.1e-3 (10 faces: six
/// below 5e-13 in size, flat cells at corners inside edges; 3.4e-6, 3.5e-5, 8.3e-4, 5.1e-3) or at
/// least 0.10 (73); the comb of `tests/step_chords.rs` at 65² with balanced corners, 6.3e-4.
pub const CLEARLY_VALID: f64 = 1e-2;

/// The smallest scaled Jacobian over the blocks' cells that are not on a collapsed side.
fn smallest_scaled_jacobian(gs: &[FaceGrid]) -> f64 {
    gs.iter()
        .map(|g| g.quality.scaled_jacobian_min_regular)
        .fold(f64::INFINITY, f64::min)
}

fn holes(
    face: &StepFace,
    surface: &CadSurface,
    (ni, nj): (usize, usize),
    dist: [&DistributionSpec; 2],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<Vec<FaceGrid>> {
    let err = |m: String| Error::input(place, m);
    let edges = face.loops.as_ref().map_err(|e| err(e.clone()))?;
    let mut loops = Vec::with_capacity(edges.len());
    for (l, e) in edges.iter().enumerate() {
        let lp = FaceLoop::new(surface, e, bounds(surface), gap_tolerance(face), true)
            .map_err(|m| err(format!("loop {}: {m}", l + 1)))?;
        loops.push(lp);
    }
    let scale = loops[0].metric_scale();
    let winds = loops.iter().filter(|l| l.winding.is_some()).count();
    let lay = if winds == 2 && loops.len() == 2 {
        band(&mut loops, scale).map_err(err)?
    } else if winds > 0 {
        return Err(err(
            "a boundary loop winds around the surface (a closed band without a seam edge, \
             or a cap around a pole) and the face has other loops: not split into blocks"
                .into(),
        ));
    } else {
        let scale = outer_first(&mut loops);
        let ccw: Vec<bool> = loops.iter().map(|lp| lp.signed_area(scale) > 0.0).collect();
        layout(&mut loops, &ccw, scale, face.orientation, fan).map_err(err)?
    };
    grid_layout(
        face,
        surface,
        &mut loops,
        &lay,
        (ni, nj),
        dist,
        solver,
        place,
    )
}

/// Moves the outer loop (largest (u, v) area) first and holes on periodic surfaces by whole
/// periods next to it; returns the outer loop's metric scale.
fn outer_first(loops: &mut Vec<FaceLoop>) -> [f64; 2] {
    let s0 = loops[0].metric_scale();
    let outer = (0..loops.len())
        .max_by(|a, b| {
            let area = |k: usize| loops[k].signed_area(s0).abs();
            area(*a).total_cmp(&area(*b)).then(b.cmp(a))
        })
        .unwrap_or(0);
    let first = loops.remove(outer);
    loops.insert(0, first);
    let mean = |lp: &FaceLoop| {
        let n = lp.edges.iter().map(|e| e.uv.len()).sum::<usize>().max(1) as f64;
        let s = lp
            .edges
            .iter()
            .flat_map(|e| &e.uv)
            .fold([0.0; 2], |s, q| [s[0] + q[0], s[1] + q[1]]);
        [s[0] / n, s[1] / n]
    };
    let m0 = mean(&loops[0]);
    for lp in loops.iter_mut().skip(1) {
        let m = mean(lp);
        for d in 0..2 {
            if let Some(t) = lp.periods[d].filter(|t| *t > 0.0) {
                let shift = t * ((m0[d] - m[d]) / t).round();
                lp.edges
                    .iter_mut()
                    .flat_map(|e| e.uv.iter_mut())
                    .for_each(|q| q[d] += shift);
            }
        }
    }
    loops[0].metric_scale()
}
