//! Orthogonality at chosen faces of a volume block and the wall spacing at a wall face: the
//! 3D counterpart of Section 2.4 (METHOD.md §3) through the algebraic map, the interior still
//! the elliptic solution of [86–88].
//!
//! The composite mapping x = X(S(ξ)) is kept; only S, the algebraic map C → P [70–72],
//! changes near the chosen faces: at a wall face the normal parameter is remapped column by
//! column so that the distances from the wall follow the edges' profiles ([`super::wall`]),
//! and at every orthogonal face (the wall with `wall_orthogonal`, and interior faces of a
//! volume topology, so that grid lines cross them without a kink when both volumes are made
//! orthogonal there) the tangential parameters of the nodes near the face are shifted so that
//! the grid lines leave it along its normal ([`super::wall_normal`]), or at a continued face
//! along the lines of the volume beyond it ([`super::continuation`]). Each pass re-solves from
//! the current grid; passes stop when the heights are within [`TOLERANCE`] and the first lines
//! within [`ANGLE_TOLERANCE`] of the normal at every chosen face, after at most
//! [`MAX_PASSES`] (a volume without a wall: once a pass changes the mean angle at its
//! orthogonal faces by less than [`SETTLED`]). A pass whose solve fails (a remap from a folded or strongly oblique grid
//! can make the operator singular) is retried with its parameter update halved, up to three
//! times. A pass that folds the grid is not kept: the result is then the fold-free
//! pass with the smallest largest angle at the chosen faces, and the history says so
//! ([`Passes`]: passes run, the one kept, why).

use crate::algebraic::bilinear3d::{bilinear, ParamGrid3};
use crate::algebraic::control3d::Control3;
use crate::algebraic::flat_edge::edge_functions;
use crate::algebraic::transfinite3d::transfinite;
use crate::algebraic::ControlKind;
use crate::elliptic::continuation::{Lines, CORNER_HOLD};
use crate::elliptic::crossing::Crossings;
use crate::elliptic::picard::{append, Passes, PicardInfo, PicardParams, PicardStep, VolumeResult};
use crate::elliptic::symmetry3d::{Symmetry, SymmetryFace};
use crate::elliptic::wall::{
    remap_volume, WallProfiles, WallTargets, ANGLE_TOLERANCE, LOOSE_TOLERANCE, MAX_PASSES,
    TOLERANCE,
};
use crate::elliptic::wall_normal::{shift_tangential, TangentGoals, LAYER_CUTOFF, SIDE_HOLD};
use crate::elliptic::{nested3d, poisson3d};
use crate::grid::faces::{face_dims, Faces, FACE_NAMES};
use crate::solve::stencil19::Stencil19;
use crate::solve::LinearSolver;
use crate::{Error, Grid3, Result};

/// Halvings of a pass's parameter update tried when its solve fails.
const DAMPINGS: usize = 3;

/// A volume without a wall stops its passes once one changes the mean angle of the grid lines
/// at its orthogonal faces by less than this (degrees): their goals fade next to held side
/// faces ([`crate::elliptic::wall_normal::SIDE_FADE`]), so the angle the wall's stop asks for
/// is not their aim. The M6's wake volume at 33 × 33 × 25 (`waketip`): mean angle 33.3°, then
/// 14.19°, 13.49°, 13.28°, 13.20°, 13.17° after passes 1–5; stopped after pass 3, the kink
/// across `waketip` 26.6° against 26.3° after six passes, 66 Picard steps against 90 (1°: 2
/// passes, 27.0°); at full size 90 steps against 107, the run 18.3–18.8 s against 20.7–21.0 s.
/// The sheared box of `tests/volume_topology.rs` stops after its first pass either way.
pub const SETTLED: f64 = 0.5;

/// What a volume block's passes hold: the wall spacing at `wall`, orthogonality at the faces
/// flagged in `orthogonal` (F1 … F6).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FaceCorrections {
    pub wall: Option<usize>,
    pub orthogonal: [bool; 6],
    /// Where the wall columns' goal profiles come from ([`WallProfiles`]).
    pub profiles: WallProfiles,
    /// Faces that are symmetry planes ([`crate::elliptic::symmetry3d`]): every solve lets
    /// their nodes slide in their planes.
    pub symmetry: [bool; 6],
    /// Faces shared with another volume of a topology: an orthogonal face that is not the
    /// wall keeps their profile in the columns next to them, as next to symmetry faces
    /// ([`crate::elliptic::wall_normal::SIDE_HOLD`], [`crate::elliptic::wall_normal::SIDE_FADE`]).
    pub shared: [bool; 6],
    /// Faces whose grid lines continue those of the volume beyond them, gridded first: the
    /// directions they arrive in ([`crate::elliptic::continuation`]).
    pub continued: [Option<std::sync::Arc<Lines>>; 6],
}

impl FaceCorrections {
    /// True if there is anything to correct (or a symmetry face to slide).
    pub fn any(&self) -> bool {
        self.wall.is_some()
            || self.orthogonal.contains(&true)
            || self.symmetry.contains(&true)
            || self.continued.iter().any(Option::is_some)
    }
}

/// Grids a volume block with the corrections `c` (module docs), from `start` (boundary nodes
/// replaced by the faces') or, without one, from the nested solve of the uncorrected block
/// (the plain one from the transfinite grid if that fails).
/// The returned history is the concatenation of all solves.
#[allow(clippy::too_many_arguments)]
pub fn grid_volume_corrected(
    faces: &Faces,
    c: &FaceCorrections,
    start: Option<Grid3>,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<VolumeResult> {
    grid_volume_corrected_with(faces, c, start, solver, params, place, progress).map(|r| r.0)
}

/// [`grid_volume_corrected`], also returning the control functions of the final solve (those
/// of the corrected algebraic map: the grid is the solution of [86] with them) and that map.
#[allow(clippy::too_many_arguments)]
pub fn grid_volume_corrected_with(
    faces: &Faces,
    c: &FaceCorrections,
    start: Option<Grid3>,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<(VolumeResult, Control3, ParamGrid3)> {
    let targets = c
        .wall
        .map(|w| WallTargets::with_profiles(faces, w, c.profiles, place))
        .transpose()?;
    let map = AlgebraicMap {
        param: bilinear(&edge_functions(faces), place)?,
        controls: &Control3::from_algebraic,
    };
    grid_volume_corrected_to(
        faces, c, targets, map, start, solver, params, place, progress,
    )
}

/// The symmetry faces flagged in `flags` of the block of `faces`, each on its plane.
pub fn symmetry_of(faces: &Faces, flags: &[bool; 6], place: &str) -> Result<Symmetry> {
    if !flags.contains(&true) {
        return Ok(Symmetry::none());
    }
    let mut x = Grid3::zeros(faces.dims()[0], faces.dims()[1], faces.dims()[2]);
    faces.apply_to(&mut x);
    (0..6)
        .filter(|&f| flags[f])
        .map(|f| SymmetryFace::of_grid(&x, f + 1, place))
        .collect::<Result<Vec<_>>>()
        .map(Symmetry::new)
}

/// The algebraic map S a block's passes correct and how its control functions follow from
/// it: a volume's own ([`bilinear`] of its edge functions, [`Control3::from_algebraic`]), or
/// the strip across a floating face glued from its volumes' maps, its controls at the face
/// the mean of the two sides' ([`crate::elliptic::floating3d`]).
pub struct AlgebraicMap<'a> {
    pub param: ParamGrid3,
    pub controls: &'a dyn Fn(&ParamGrid3) -> Control3,
}

/// What every solve of a block's passes shares: how the control functions follow from the
/// algebraic map, the symmetry faces and the block's name for errors.
struct Solves<'a> {
    controls: &'a dyn Fn(&ParamGrid3) -> Control3,
    sym: &'a Symmetry,
    place: &'a str,
}

impl Solves<'_> {
    /// Solves [86] for `x` with the control functions of `pg` (the symmetry faces' from `pg`
    /// continued across them), starting from `x`.
    fn run(
        &self,
        x: &mut Grid3,
        pg: &ParamGrid3,
        solver: &mut dyn LinearSolver<Stencil19>,
        params: &PicardParams,
        progress: &mut dyn FnMut(usize, &PicardStep),
    ) -> Result<PicardInfo> {
        let ctrl = (self.controls)(pg);
        let sym = self.sym.with_controls(pg);
        poisson3d::solve_symmetric(x, &ctrl, &sym, solver, params, self.place, progress)
    }
}

/// [`grid_volume_corrected_with`] with the wall's goal columns given (`targets`, for
/// `c.wall`) instead of taken from the faces: the strip across a floating face between two
/// wall volumes holds its volumes' goals ([`crate::elliptic::floating3d`]).
#[allow(clippy::too_many_arguments)]
pub fn grid_volume_corrected_to(
    faces: &Faces,
    c: &FaceCorrections,
    targets: Option<WallTargets>,
    map: AlgebraicMap,
    start: Option<Grid3>,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<(VolumeResult, Control3, ParamGrid3)> {
    // Orthogonal side faces of an orthogonal wall are held by the wall's own passes
    // (`elliptic::crossing`): separate passes at them would move the parameters the wall's remap sets.
    let crossings = c
        .wall
        .filter(|&w| c.orthogonal[w])
        .and_then(|w| Crossings::new(w, &c.orthogonal));
    let ortho: Vec<usize> = (0..6)
        .filter(|&f| {
            (c.orthogonal[f] && !crossings.is_some_and(|cr| cr.crosses(f)))
                || c.continued[f].is_some()
        })
        .collect();
    // The angles the passes aim at: to the face's normal, or to the arriving lines at a
    // continued face (largest, mean).
    let face_angles = |x: &Grid3, f: usize| match &c.continued[f] {
        Some(l) => l.angles(x, f),
        None => {
            let q = crate::quality::quality3d::face_quality(x, f);
            (q.orthogonality_max_deg, q.orthogonality_mean_deg)
        }
    };
    let continuing = c.continued.iter().any(Option::is_some);
    for (f, l) in c.continued.iter().enumerate() {
        let want = face_dims(f, faces.dims());
        if let Some(got) = l.as_ref().map(|l| l.dims()).filter(|&d| d != want) {
            return Err(Error::input(
                place,
                format!(
                    "continue = [\"{}\"]: the arriving lines are given at {got:?} nodes, the \
                     face has {want:?}",
                    FACE_NAMES[f]
                ),
            ));
        }
    }
    let AlgebraicMap {
        param: mut pg,
        controls,
    } = map;
    // Intermediate solves only need the near-face positions to well under the tolerances.
    let loose = PicardParams {
        tolerance: params.tolerance.max(LOOSE_TOLERANCE),
        ..params.clone()
    };
    let mut info: Option<PicardInfo> = None;
    let sym = symmetry_of(faces, &c.symmetry, place)?;
    let solves = Solves {
        controls,
        sym: &sym,
        place,
    };
    // Pass 0: the uncorrected grid (nested iteration from the faces, or from `start`; with
    // symmetry faces, the plain iteration from the transfinite grid).
    let start = match start {
        None if !sym.is_empty() => Some(transfinite(faces)),
        s => s,
    };
    let mut x = match start {
        Some(g) if g.dims() == faces.dims() => {
            let mut x = g;
            faces.apply_to(&mut x);
            append(
                &mut info,
                solves.run(&mut x, &pg, solver, &loose, progress)?,
            );
            x
        }
        Some(g) => {
            return Err(Error::input(
                place,
                format!(
                    "start grid has {:?} nodes but the faces need {:?}",
                    g.dims(),
                    faces.dims()
                ),
            ))
        }
        None => match nested3d::grid_volume_nested(
            faces,
            ControlKind::Algebraic,
            solver,
            &loose,
            place,
            progress,
        ) {
            Ok((r, _)) => {
                append(&mut info, r.picard);
                r.grid
            }
            // A coarse level's start can be degenerate where the finest one is not: then
            // the plain iteration from the transfinite grid.
            Err(_) => {
                let mut x = transfinite(faces);
                faces.apply_to(&mut x);
                append(
                    &mut info,
                    solves.run(&mut x, &pg, solver, &loose, progress)?,
                );
                x
            }
        },
    };
    if !c.any() {
        let ctrl = controls(&pg);
        return Ok((
            VolumeResult {
                grid: x,
                picard: info.expect("one solve"),
            },
            ctrl,
            pg,
        ));
    }
    let mut goal = Vec::new();
    let mut tangent_goals: Vec<(usize, TangentGoals)> = Vec::new();
    // The fold-free grid with the smallest largest angle at the orthogonal faces, the pass
    // it came from and its parameters (the fallback if a later pass folds the grid).
    let mut best: Option<(f64, usize, ParamGrid3, Grid3)> = None;
    // passes solved so far, and why the grid went back to `best` (if it did)
    let mut run = 0;
    let mut fell_back: Option<(usize, String)> = None;
    let score = |x: &Grid3| {
        use crate::quality::quality3d::folded_cells3d;
        let worst = ortho
            .iter()
            .map(|&f| face_angles(x, f).0)
            .fold(0.0, f64::max);
        (folded_cells3d(x), worst)
    };
    if !ortho.is_empty() {
        if let (0, s) = score(&x) {
            best = Some((s, 0, pg.clone(), x.clone()));
        }
    }
    // the mean angle at the orthogonal faces (the stop of a volume without a wall: SETTLED)
    let mean_angle = |x: &Grid3| {
        let sum: f64 = ortho.iter().map(|&f| face_angles(x, f).1).sum();
        sum / ortho.len().max(1) as f64
    };
    let mut prev_mean = mean_angle(&x);
    let mut settled = false;
    for pass in 1..=MAX_PASSES {
        let last = pass == MAX_PASSES;
        let mut trial = pg.clone();
        if tangent_goals.is_empty() {
            tangent_goals = ortho
                .iter()
                .map(|&f| {
                    let wall = Some(f) == c.wall;
                    let cr = crossings.as_ref().filter(|_| wall);
                    // a free face fades next to side faces shared with another volume
                    // and next to symmetry faces (`wall_normal::SIDE_FADE`)
                    let held = Crossings::side_faces(f).map(|s| {
                        if c.symmetry[s] {
                            1
                        } else if c.shared[s]
                            && continuing
                            && (c.orthogonal[s] || c.continued[s].is_some())
                        {
                            CORNER_HOLD
                        } else if c.shared[s] {
                            SIDE_HOLD
                        } else {
                            0
                        }
                    });
                    let mut g =
                        TangentGoals::new(&pg, &x, f, !wall, held, cr, c.continued[f].as_deref());
                    if ortho.len() > 1 {
                        g.cutoff = LAYER_CUTOFF;
                    }
                    (f, g)
                })
                .collect();
        }
        let err = match (&targets, c.wall) {
            (Some(t), Some(w)) => {
                let tg = tangent_goals.iter().find(|(f, _)| *f == w).map(|g| &g.1);
                remap_volume(&mut trial, &x, t, &mut goal, tg, crossings.as_ref())
            }
            _ => 0.0,
        };
        let angle = tangent_goals
            .iter()
            .map(|(f, g)| shift_tangential(&pg, &mut trial, &x, *f, g))
            .fold(0.0, f64::max);
        let done = (err <= TOLERANCE && angle <= ANGLE_TOLERANCE) || settled;
        let prev = pg.clone();
        if !done {
            pg = trial;
            run += 1;
        }
        if done || last {
            // A final solve to the asked tolerance from the current grid.
            let step = solves.run(&mut x, &pg, solver, params, progress);
            let folded = if step.is_ok() && !ortho.is_empty() {
                score(&x).0
            } else {
                0
            };
            let (why, bpass, bpg, bx) = match (step, best.take()) {
                (Ok(step), _) if folded == 0 => {
                    append(&mut info, step);
                    break;
                }
                (Ok(step), None) => {
                    append(&mut info, step);
                    break;
                }
                (Err(e), None) => return Err(e),
                (Ok(_), Some((_, bp, bpg, bx))) => {
                    (format!("pass {run} folded {folded} cells"), bp, bpg, bx)
                }
                (Err(e), Some((_, bp, bpg, bx))) => (
                    format!("pass {run}'s solve failed ({})", cause(&e)),
                    bp,
                    bpg,
                    bx,
                ),
            };
            // The last pass folded the grid or its solve failed: back to the best fold-free
            // one.
            fell_back = Some((bpass, why));
            (pg, x) = (bpg, bx);
            append(
                &mut info,
                solves.run(&mut x, &pg, solver, params, progress)?,
            );
            break;
        }
        // The pass's solve; if it fails (a remap from a folded or strongly oblique grid can
        // make the operator singular), the parameter update is halved up to DAMPINGS times.
        let mut attempt = |pg: &ParamGrid3, x: &mut Grid3| {
            let ctrl = controls(pg);
            if !ctrl.all_finite() {
                let faces: Vec<&str> = ortho
                    .iter()
                    .chain(c.wall.iter())
                    .map(|&f| FACE_NAMES[f])
                    .collect();
                return Err(Error::input(
                    place,
                    format!(
                        "the correction at {} made the control functions singular",
                        faces.join(", ")
                    ),
                ));
            }
            let sym = sym.with_controls(pg);
            poisson3d::solve_symmetric(x, &ctrl, &sym, solver, &loose, place, progress)
        };
        let x_before = x.clone();
        let mut solved = attempt(&pg, &mut x);
        for _ in 0..DAMPINGS {
            if solved.is_ok() {
                break;
            }
            for (new, old) in [
                (&mut pg.s, &prev.s),
                (&mut pg.t, &prev.t),
                (&mut pg.u, &prev.u),
            ] {
                for (a, b) in new.iter_mut().zip(old) {
                    *a = b + 0.5 * (*a - b);
                }
            }
            x.clone_from(&x_before);
            solved = attempt(&pg, &mut x);
        }
        match solved {
            Ok(step) => append(&mut info, step),
            Err(e) => match best.take() {
                // A failed orthogonal pass: finish from the best fold-free grid.
                Some((_, bp, bpg, bx)) => {
                    fell_back = Some((bp, format!("pass {run}'s solve failed ({})", cause(&e))));
                    (pg, x) = (bpg, bx);
                    let step = solves.run(&mut x, &pg, solver, params, progress)?;
                    append(&mut info, step);
                    break;
                }
                _ => return Err(e),
            },
        }
        if !ortho.is_empty() {
            let (folded, s) = score(&x);
            if folded == 0 && best.as_ref().is_none_or(|b| s < b.0) {
                best = Some((s, run, pg.clone(), x.clone()));
            }
            let m = mean_angle(&x);
            settled = c.wall.is_none() && (prev_mean - m).abs() < SETTLED;
            prev_mean = m;
        }
    }
    let ctrl = controls(&pg);
    let mut picard = info.expect("at least one solve");
    let (kept, fell_back) = match fell_back {
        Some((kept, why)) => (kept, Some(why)),
        None => (run, None),
    };
    picard.passes = (c.wall.is_some() || !ortho.is_empty()).then_some(Passes {
        run,
        kept,
        fell_back,
    });
    Ok((VolumeResult { grid: x, picard }, ctrl, pg))
}

/// What made a pass's solve fail, without the block's name (the report is the block's).
fn cause(e: &Error) -> String {
    match e {
        Error::Solve { source, .. } => source.to_string(),
        e => e.to_string(),
    }
}
