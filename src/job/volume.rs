//! Runs of volume blocks: generation of a case's `[[volume]]` (with its wall spacing, if any),
//! the transfinite start grid, and the regridding of volume blocks of existing grids.

use crate::algebraic::bilinear3d::ParamGrid3;
use crate::algebraic::control3d::{control_for, Control3};
use crate::algebraic::transfinite3d::transfinite;
use crate::algebraic::ControlKind;
use crate::case::spec::VolumeSpec;
use crate::case::volume::{volume_faces, volume_name, volume_place, wall_face};
use crate::case::LoadedCase;
use crate::elliptic::orthogonal3d::{grid_volume_corrected_with, symmetry_of, FaceCorrections};
use crate::elliptic::picard::{PicardInfo, PicardParams, VolumeResult};
use crate::elliptic::poisson3d;
use crate::elliptic::volume::{grid_volume, progress_enabled};
use crate::elliptic::wall::{check_kind, wall_targets, WallOptions, WallProfiles};
use crate::elliptic::wall_normal::{wall_figure, WallFigure};
use crate::grid::faces::parse_face;
use crate::grid::faces::Faces;
use crate::io::Block;
use crate::quality::quality3d::{quality3d, QualityReport3};
use crate::solve::select::for_block;
use crate::{Error, Grid3, Result};
use serde::Serialize;
use std::time::Instant;

/// Report of one volume block: the solve history and the 3D quality.
#[derive(Clone, Debug, Serialize)]
pub struct VolumeReport {
    pub name: String,
    pub ni: usize,
    pub nj: usize,
    pub nk: usize,
    /// Wall-clock seconds of the block's generation.
    pub seconds: f64,
    pub picard: PicardInfo,
    pub quality: QualityReport3,
    /// With `wall`: the angles of the first grid lines to the wall normal and the wall-normal
    /// distance of the first off-wall nodes over the prescribed spacing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall: Option<WallFigure>,
    /// A mirrored volume (`mirror = "A"`): the volume it is the mirror image of (its Picard
    /// history is A's: it had no solve of its own).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mirror_of: Option<String>,
    /// A mirrored volume: the largest distance of its own boundary nodes (those not on the
    /// faces shared with its original) from the mirror images of the original's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mirror_deviation: Option<f64>,
}

/// A terminal progress bar for a Picard solve, if enabled and stderr is a terminal.
fn progress_bar(name: &str, max: usize) -> Option<indicatif::ProgressBar> {
    use std::io::IsTerminal;
    if !progress_enabled() || !std::io::stderr().is_terminal() {
        return None;
    }
    let pb = indicatif::ProgressBar::new(max as u64);
    pb.set_style(
        indicatif::ProgressStyle::with_template("{prefix} Picard {pos:>3} {msg} [{elapsed}]")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    pb.set_prefix(format!("volume '{name}'"));
    Some(pb)
}

/// Grids volume k of a case: faces, transfinite start, Picard solve, 3D quality.
pub fn generate_volume(case: &LoadedCase, k: usize) -> Result<(String, Block, VolumeReport)> {
    let t0 = Instant::now();
    let faces = volume_faces(case, k, &case.case.solver.picard)?;
    solve_volume(case, k, &faces, &volume_place(case, k), t0)
}

/// Grids volume k of a case from its validated `faces` (the `[[volume]]` table gives the
/// solver, the wall and its options): Picard solve, wall spacing, 3D quality. `t0`: when
/// the block's work began (for its seconds).
pub(crate) fn solve_volume(
    case: &LoadedCase,
    k: usize,
    faces: &Faces,
    place: &str,
    t0: Instant,
) -> Result<(String, Block, VolumeReport)> {
    solve_volume_continued(case, k, faces, Default::default(), place, t0)
}

/// [`solve_volume`] of a volume whose lines continue across some of its faces (`continue`):
/// `lines` the directions the volumes beyond them arrive in.
pub(crate) fn solve_volume_continued(
    case: &LoadedCase,
    k: usize,
    faces: &Faces,
    lines: Continued,
    place: &str,
    t0: Instant,
) -> Result<(String, Block, VolumeReport)> {
    solve_volume_from(case, k, faces, None, None, lines, place, t0)
        .map(|(name, g, rep, _, _)| (name, g, rep))
}

/// The arriving lines of a volume's continued faces (None: not continued).
pub(crate) type Continued = [Option<std::sync::Arc<crate::elliptic::continuation::Lines>>; 6];

/// [`solve_volume`] from `start` (its boundary nodes replaced by the faces'), if given, also
/// returning the control functions the grid solves [86] with (those of the corrected map when
/// the volume has a wall or orthogonal faces, and then the corrected algebraic map they come
/// from, unless frozen). With `frozen` control functions, a start and
/// corrections, one plain Picard solve with those controls instead of the correction passes
/// (the corrections are in the controls).
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_volume_from(
    case: &LoadedCase,
    k: usize,
    faces: &Faces,
    start: Option<Grid3>,
    frozen: Option<Control3>,
    lines: Continued,
    place: &str,
    t0: Instant,
) -> Result<(String, Block, VolumeReport, Control3, Option<ParamGrid3>)> {
    let spec = &case.case;
    let v = &spec.volumes[k];
    let name = volume_name(case, k);
    let params = &spec.solver.picard;
    let mut solver = for_block(&v.linear, faces.dims()).map_err(|m| Error::input(place, m))?;
    let pb = progress_bar(&name, params.max_steps);
    let mut cb = |n: usize, s: &crate::elliptic::picard::PicardStep| {
        if let Some(pb) = &pb {
            pb.set_position(n as u64);
            pb.set_message(format!(
                "update {:.2e} residual {:.2e}",
                s.update, s.residual
            ));
        }
    };
    let wall = wall_face(v, place)?;
    let mut c = corrections(&spec.volumes, v, wall, place)?;
    for (f, &on) in continued_faces(v, place)?.iter().enumerate() {
        if on && lines[f].is_none() {
            return Err(Error::input(
                place,
                format!(
                    "continue = [\"{}\"]: the lines continue those of the volume beyond the \
                     face, gridded first (`run` of a volume topology without floating faces; \
                     the volume beyond neither mirrored nor continuing itself)",
                    crate::grid::faces::FACE_NAMES[f]
                ),
            ));
        }
    }
    c.continued = lines;
    if c.wall.is_some() {
        check_kind(spec.solver.control, place)?;
    }
    let frozen = frozen.filter(|_| c.any());
    let (r, ctrl, param) = if let (Some(ctrl), Some(mut x)) = (frozen, start.clone()) {
        faces.apply_to(&mut x);
        let sym = symmetry_of(faces, &c.symmetry, place)?;
        let picard = poisson3d::solve_symmetric(
            &mut x,
            &ctrl,
            &sym,
            solver.as_mut(),
            params,
            place,
            &mut cb,
        )?;
        (VolumeResult { grid: x, picard }, ctrl, None)
    } else if c.any() {
        let (r, ctrl, pg) =
            grid_volume_corrected_with(faces, &c, start, solver.as_mut(), params, place, &mut cb)?;
        (r, ctrl, Some(pg))
    } else {
        let r = grid_volume(
            faces,
            start,
            spec.solver.control,
            solver.as_mut(),
            params,
            place,
            &mut cb,
        )?;
        (r, control_for(faces, spec.solver.control, place)?, None)
    };
    if let Some(pb) = pb {
        pb.finish_and_clear();
    }
    let q = quality3d(&r.grid);
    let wall = match wall {
        Some(w) => Some(wall_figure(&r.grid, w, &wall_targets(faces, w, place)?)),
        None => None,
    };
    let [ni, nj, nk] = r.grid.dims();
    let rep = VolumeReport {
        name: name.clone(),
        ni,
        nj,
        nk,
        seconds: t0.elapsed().as_secs_f64(),
        picard: r.picard,
        quality: q,
        wall,
        mirror_of: None,
        mirror_deviation: None,
    };
    Ok((name, Block::Volume(r.grid), rep, ctrl, param))
}

/// The corrections a `[[volume]]` table `v` (one of the case's `volumes`) asks for: the wall
/// (`wall`, with `wall_orthogonal`, default true) and the `orthogonal` faces; with the faces
/// it shares with another volume of the topology.
pub(crate) fn corrections(
    volumes: &[VolumeSpec],
    v: &VolumeSpec,
    wall: Option<usize>,
    place: &str,
) -> Result<FaceCorrections> {
    if let Some(a) = &v.mirror {
        return Err(Error::input(
            place,
            format!(
                "mirror = \"{a}\": this volume is mirrored, not solved on its own (`run` of a \
                 volume topology, whose volumes name `[[face]]` tables)"
            ),
        ));
    }
    let mut orthogonal = face_flags(&v.orthogonal, "orthogonal", place)?;
    let profiles = match v.wall_profiles.as_deref() {
        None | Some("edges") => WallProfiles::Edges,
        Some("faces") => WallProfiles::Faces,
        Some(s) => {
            return Err(Error::input(
                place,
                format!("wall_profiles = \"{s}\": expected \"edges\" or \"faces\""),
            ))
        }
    };
    match wall {
        Some(w) => {
            orthogonal[w] |= v
                .wall_orthogonal
                .unwrap_or(WallOptions::default().orthogonal)
        }
        None if v.wall_orthogonal.is_some() || v.wall_profiles.is_some() => {
            return Err(Error::input(
                place,
                "wall_orthogonal and wall_profiles need wall = \"F1\" … \"F6\"",
            ))
        }
        None => {}
    }
    // Orthogonal side faces of the wall are held by the wall's passes (`elliptic::crossing`),
    // which need the wall's tangential shifts and the side faces' profiles.
    if let Some(w) = wall {
        let side = crate::elliptic::crossing::Crossings::side_faces(w)
            .into_iter()
            .find(|&f| orthogonal[f]);
        if let Some(f) = side {
            let name = crate::grid::faces::FACE_NAMES[f];
            if !orthogonal[w] {
                return Err(Error::input(
                    place,
                    format!(
                        "orthogonal = [\"{name}\"]: a side face of the wall is crossed at right \
                         angles by the wall's passes, which need wall_orthogonal = true"
                    ),
                ));
            }
            if profiles != WallProfiles::Faces {
                return Err(Error::input(
                    place,
                    format!(
                        "orthogonal = [\"{name}\"]: a side face of the wall needs wall_profiles = \
                         \"faces\" (the columns next to it follow its profile)"
                    ),
                ));
            }
        }
    }
    let mut symmetry = [false; 6];
    for name in &v.symmetry {
        let f = parse_face(name).ok_or_else(|| {
            Error::input(
                place,
                format!("symmetry = [\"{name}\"]: expected faces F1, …, F6"),
            )
        })?;
        if Some(f) == wall || orthogonal[f] {
            return Err(Error::input(
                place,
                format!("symmetry = [\"{name}\"]: a symmetry face cannot also be the wall or orthogonal"),
            ));
        }
        if let Some(w) = wall.filter(|&w| f != w && f != w ^ 1) {
            return Err(Error::input(
                place,
                format!(
                    "symmetry = [\"{name}\"]: the face shares an edge with the wall {}; the \
                     wall-spacing passes hold the wall's side faces fixed (a sliding one is not \
                     supported yet)",
                    crate::grid::faces::FACE_NAMES[w]
                ),
            ));
        }
        symmetry[f] = true;
    }
    let shared = shared_faces(volumes, v);
    for (f, &on) in continued_faces(v, place)?.iter().enumerate() {
        let name = crate::grid::faces::FACE_NAMES[f];
        let clash = if Some(f) == wall {
            Some("the wall")
        } else if orthogonal[f] {
            Some("orthogonal")
        } else if symmetry[f] {
            Some("a symmetry face")
        } else if !shared[f] {
            Some("not shared with another volume")
        } else {
            None
        };
        if let (true, Some(why)) = (on, clash) {
            return Err(Error::input(
                place,
                format!("continue = [\"{name}\"]: the face is {why}"),
            ));
        }
    }
    Ok(FaceCorrections {
        wall,
        orthogonal,
        profiles,
        symmetry,
        shared,
        continued: Default::default(),
    })
}

/// The faces a `[[volume]]` table `v` continues the grid lines across (`continue`).
pub(crate) fn continued_faces(v: &VolumeSpec, place: &str) -> Result<[bool; 6]> {
    face_flags(&v.continue_faces, "continue", place)
}

/// Flags of the faces named in the list `key` ("F1" … "F6").
fn face_flags(names: &[String], key: &str, place: &str) -> Result<[bool; 6]> {
    let mut on = [false; 6];
    for name in names {
        let f = parse_face(name).ok_or_else(|| {
            Error::input(
                place,
                format!("{key} = [\"{name}\"]: expected faces F1, …, F6"),
            )
        })?;
        on[f] = true;
    }
    Ok(on)
}

/// The faces of volume `v` that another of the `volumes` (or `v` itself, on another side)
/// names too.
fn shared_faces(volumes: &[VolumeSpec], v: &VolumeSpec) -> [bool; 6] {
    v.face_names().map(|name| {
        name.as_ref().is_some_and(|n| {
            volumes
                .iter()
                .flat_map(|u| u.face_names())
                .filter(|m| m.as_deref() == Some(n.as_str()))
                .count()
                > 1
        })
    })
}

/// The transfinite start grid of volume k.
pub fn start_volume(case: &LoadedCase, k: usize) -> Result<(String, Block)> {
    let faces = volume_faces(case, k, &case.case.solver.picard)?;
    Ok((volume_name(case, k), Block::Volume(transfinite(&faces))))
}

/// Regrids a volume block of an existing grid keeping its boundary nodes bit for bit: the
/// interior is the start grid if it is fold-free, else the transfinite one. `linear`:
/// "direct" (faer LU, used only up to 40 000 interior nodes; larger blocks use "auto"),
/// "auto", "bicgstab" or "multigrid" ([`crate::solve::select::for_block`]). Returns the grid, the
/// history, the start used and the solver's name.
pub fn regrid_volume(
    g: &Grid3,
    linear: &str,
    control: ControlKind,
    params: &PicardParams,
    place: &str,
) -> Result<(Grid3, PicardInfo, String)> {
    let d = g.dims();
    if d.iter().any(|&n| n < 3) {
        return Err(Error::input(
            place,
            format!("a volume block needs at least 3 nodes each way, got {d:?}"),
        ));
    }
    if g.coords().iter().any(|c| c.iter().any(|v| !v.is_finite())) {
        return Err(Error::input(place, "the block has non-finite coordinates"));
    }
    let faces = Faces::from_grid(g);
    let inner = (d[0] - 2) * (d[1] - 2) * (d[2] - 2);
    let name = match linear {
        "direct" if inner <= 40_000 => "direct",
        "direct" => "auto",
        o => o,
    };
    let mut solver = for_block(name, d).map_err(|m| Error::input(place, m))?;
    let valid = !quality3d(g).is_folded();
    let start = valid.then(|| g.clone());
    let pb = progress_bar(place, params.max_steps);
    let mut cb = |n: usize, s: &crate::elliptic::picard::PicardStep| {
        if let Some(pb) = &pb {
            pb.set_position(n as u64);
            pb.set_message(format!(
                "update {:.2e} residual {:.2e}",
                s.update, s.residual
            ));
        }
    };
    let r = grid_volume(
        &faces,
        start,
        control,
        solver.as_mut(),
        params,
        place,
        &mut cb,
    )?;
    if let Some(pb) = pb {
        pb.finish_and_clear();
    }
    let how = if valid {
        "existing interior"
    } else {
        "transfinite"
    };
    Ok((r.grid, r.picard, how.into()))
}
