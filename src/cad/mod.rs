//! STEP in and out (ISO 10303-21) through truck-stepio: the faces of a STEP file gridded as
//! four-sided block faces by the Section 4 pipeline ([`crate::surface::pipeline`]), and a
//! B-spline surface (e.g. a [`ellipgrid_geometry::HermiteSurface`] control net through
//! `to_bspline`) written as one STEP face so that control nets can go to CAD tools.
//!
//! | file | what |
//! |---|---|
//! | `mod` | [`read_step_faces`]: every face of every shell, numbered from 1 (or every bare B-spline surface of a file without faces); [`step_surface`] |
//! | `patch` | untrimmed four-sided B-spline/NURBS faces: the check, [`grid_patch`] |
//! | `crease` | an untrimmed patch cut along its creases (C0 iso-lines where the normal turns by more than [`CREASE_TURN`]) into sub-patches, each a block ([`grid_creased`]) |
//! | `boundary_cuts` | the other cuts of a patch whose block folds: where it folds back over itself (the flap left out) and where a side kinks by more than [`KINK_TURN`] |
//! | `cut_line` | a line a patch is cut along and why ([`Crease`], [`CutKind`]) |
//! | `trim` | a face's boundary loop on its surface: (u, v) by projection, corners (by turning angle, `trim/corners`; `trim/balance`: by balanced opposite sides, where those fold; `trim/cusp`: a cusp as a collapsed side, where those fold too, last the tips), four sides |
//! | `face` | [`grid_face`]: any one-loop face as a block face (Section 2 in (u, v), then Section 4) |
//! | `holes` | a face with holes split into blocks: one-hole strips, an O-type ring of four around each hole |
//! | `reentrant` | [`grid_face_split`]: a one-loop face whose one block folds, cut at its reentrant vertices into blocks |
//! | `chords` | [`grid_face_chords`]: a one-loop face whose every other try folds, cut by chords along its edges' continuations from its reentrant vertices (combs, frames) |
//! | `band` | a closed band without a seam edge (two winding loops) split into four blocks |
//! | `blocks` | a split face's blocks gridded as block faces (cuts sampled once, shared bit for bit) |
//! | `split` | [`grid_face_blocks`]: any face as one block or several (cuts shared bit for bit) |
//! | `write` | [`write_step_surfaces`]: B-spline faces of one open shell, each bounded by its four iso-parameter sides ([`write_step_surface`]: one) |
//! | `prescan` | bounds on the STEP text before truck-stepio expands it |
//! | `rewrite` | entity forms truck-stepio loses, rewritten in the text to ones it reads |
//! | `units` | the file's plane angle unit (cone angles to radians) and distance uncertainty |
//!
//! Two routes grid a face ([`Route`]):
//! - an *untrimmed four-sided patch* (a B-spline or NURBS surface whose boundary edges lie on
//!   the four sides of its parameter square, to [`FOUR_SIDED_TOL`] of its size) is gridded on
//!   the surface's own parametrization ([`grid_patch`]);
//! - any other face bounded by *one loop* of edges, on any surface truck reads (planes,
//!   cylinders, cones, spheres, tori, extrusions, revolutions, B-splines of any degree), is
//!   gridded as a block face ([`grid_face`]): four corners picked on the loop, a Section 2
//!   (Winslow) grid in the surface's (u, v) plane bounded by the four sides as the face's
//!   parametrization from the unit square, then the Section 4 pipeline on top, so that the
//!   grid depends on neither parametrization.
//!
//! - a face of several loops ([`Route::Holes`]) is split into four-sided blocks, each gridded
//!   as a block face ([`grid_face_blocks`]): an O-type ring of four blocks around each hole
//!   (the face first cut into one-hole strips between holes), or four blocks across a closed
//!   band without a seam edge (two loops winding around a periodic surface).
//!
//! - a one-loop face whose one-block grid folds and whose loop turns outwards at vertices
//!   (L-shaped plates, pockets, slots) is cut there by straight (u, v) cuts into blocks
//!   ([`grid_face_split`]), gridded as a face with holes' blocks.
//!
//! A file with no face in any shell (OpenVSP writes its components as bare B-spline surfaces
//! in `GEOMETRIC_SET`s) gives its B-spline and NURBS surfaces instead, each the whole surface
//! as an untrimmed four-sided patch. A side collapsed to a point (a pole: the nose of a
//! fuselage, the leading and trailing edge points of a wing cap) stays one: the grid's cells
//! there are triangles, its lines leave the pole along the parameter lines of the opposite
//! side's nodes ([`grid_patch`]). A surface with no area (one point, or a curve: OpenVSP writes
//! such degenerate patches at wing roots and tips) is refused.
//!
//! A one-loop face whose loop runs through a pole of its surface (a cone's apex, a sphere's
//! pole: the loop's (u, v) jump there) has the pole as its side E1, one point, its (u, v)
//! along the pole at the fractions of the opposite side's arclength, as a patch's collapsed
//! side (`trim/pole`, [`grid_face`]).
//!
//! Faces without a boundary, whose one loop winds around the surface (a cap around a pole) or
//! runs through two poles, or that cannot be split into blocks are refused with the reason.
//!
//! Limits of truck-stepio 0.3 that show here: faces whose surface it cannot convert are
//! skipped (it prints a line to stderr) and so get no number; [`read_step`] lists them with
//! their entity ids and the reason (`unread`: `step list` and `step grid` name each); its writer prints numbers
//! below 10⁻² in magnitude with 11 significant digits (absolute error below 5·10⁻¹⁴), larger
//! ones exactly; a face with `same_sense = .F.` is read with u and v swapped.

mod band;
mod blocks;
mod boundary_cuts;
mod chords;
mod complex;
mod crease;
mod cut_line;
mod edge;
mod face;
mod fan;
mod hole_cuts;
mod holes;
mod model;
mod patch;
mod pieces;
mod placement;
mod prescan;
mod reentrant;
mod rewrite;
mod split;
mod trim;
mod units;
mod unread;
mod uv;
mod visible;
mod write;

pub use boundary_cuts::KINK_TURN;
pub use chords::grid_face_chords;
pub use crease::{
    creased_blocks, creases, grid_creased, surface_creases, surface_cuts, Crease, CutKind,
    CREASE_TURN,
};
pub use face::{grid_face, grid_face_by, Corners, FaceGrid, BALANCED, COLLAPSED};
pub use model::{step_model, EdgeChain};
pub use patch::grid_patch;
pub use reentrant::{grid_face_split, MAX_BLOCKS};
pub use split::{grid_face_blocks, CLEARLY_VALID};
pub use trim::HEAL;
pub use unread::Unread;
pub use write::{write_step_surface, write_step_surfaces};

use crate::{Error, Result};
use ellipgrid_geometry::BSplineSurf;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use truck_geometry::prelude::{Matrix4, Point3, SquareMatrix};
use truck_stepio::r#in::alias::{Curve3D, Surface as StepSurface};
use truck_stepio::r#in::{ruststep, Table};
use truck_topology::compress::{CompressedFace, CompressedShell};

/// Tolerance of the four-sided check, relative to the diagonal of the surface's bounding box:
/// every boundary edge must lie this close to one side of the parameter square.
pub const FOUR_SIDED_TOL: f64 = 1e-6;

type Shell = CompressedShell<Point3, Curve3D, StepSurface>;

/// One oriented edge of a face's boundary loop.
#[derive(Clone, Debug)]
pub struct LoopEdge {
    /// The edge's 3D curve.
    pub curve: Curve3D,
    /// The curve's parameters of the edge's vertices, increasing.
    pub range: (f64, f64),
    /// Whether the loop runs along the curve's direction.
    pub forward: bool,
}

/// How a face is gridded, or why it is not.
#[derive(Clone, Debug, PartialEq)]
pub enum Route {
    /// An untrimmed four-sided B-spline/NURBS patch, gridded on its own parametrization.
    Patch,
    /// One boundary loop of this many edges, gridded as a block face ([`grid_face`]).
    Trimmed(usize),
    /// An outer loop and this many holes, gridded as several blocks: an O-type ring of four
    /// around each hole ([`grid_face_blocks`]).
    Holes(usize),
    /// Not gridable, with the reason.
    Refused(String),
}

/// One face of a STEP file.
#[derive(Clone, Debug)]
pub struct StepFace {
    /// 1-based number over all shells in file order (shells by entity number).
    pub index: usize,
    /// The surface type: "B-spline", "NURBS", "plane", "cylinder", … .
    pub surface_type: &'static str,
    /// The surface, if it is a B-spline or NURBS surface that [`BSplineSurf`] can evaluate.
    pub surface: Option<BSplineSurf>,
    /// Why a B-spline or NURBS surface cannot be used by [`BSplineSurf`] (degree above
    /// [`BSplineSurf::MAX_DEGREE`], bad knots or weights), if so.
    pub surface_error: Option<String>,
    /// `None` for an untrimmed four-sided patch, else why the face is not one.
    pub trimmed: Option<String>,
    /// The surface as truck reads it (any type; evaluated through truck).
    pub cad_surface: StepSurface,
    /// The boundary loops; `Err` names an edge that is missing or unbounded.
    pub loops: std::result::Result<Vec<Vec<LoopEdge>>, String>,
    /// Whether the face's normal is the surface's (as read: `same_sense` already applied).
    pub orientation: bool,
    /// The file's distance uncertainty (the largest `distance_accuracy_value` of its
    /// `UNCERTAINTY_MEASURE_WITH_UNIT`s, in its length unit), 0 if it gives none.
    pub uncertainty: f64,
    /// Largest defect of the boundary healed, relative to the loop's size: edges whose ends
    /// miss each other, or points off the surface, beyond the tolerance ([`HEAL`] by
    /// default; 0 refuses any).
    pub heal: f64,
}

impl StepFace {
    /// Whether the face is an untrimmed four-sided B-spline/NURBS patch.
    pub fn is_four_sided_patch(&self) -> bool {
        self.surface.is_some() && self.trimmed.is_none()
    }

    /// How the face is gridded, or why not.
    pub fn route(&self) -> Route {
        if self.is_four_sided_patch() {
            return Route::Patch;
        }
        match &self.loops {
            Err(e) => Route::Refused(e.clone()),
            // a bare surface (no loop) that cannot be evaluated says why
            Ok(l) if l.is_empty() => Route::Refused(
                self.surface_error
                    .clone()
                    .unwrap_or_else(|| "no boundary loop".into()),
            ),
            Ok(l) if l.len() > 1 => Route::Holes(l.len() - 1),
            Ok(l) => Route::Trimmed(l[0].len()),
        }
    }

    /// The surface of an untrimmed four-sided patch (for case files).
    ///
    /// # Errors
    /// [`Error::Input`] naming `file` and the face if the surface is not a B-spline/NURBS
    /// surface or the face is not an untrimmed four-sided patch.
    pub fn patch(&self, file: &Path) -> Result<&BSplineSurf> {
        let place = format!("{}: face {}", file.display(), self.index);
        if let Some(e) = &self.surface_error {
            return Err(Error::input(place, e.clone()));
        }
        let Some(s) = &self.surface else {
            return Err(Error::input(
                place,
                format!(
                    "the surface is a {}; only untrimmed four-sided B-spline and NURBS faces \
                     can be used as surfaces of case-file blocks",
                    self.surface_type
                ),
            ));
        };
        match &self.trimmed {
            None => Ok(s),
            Some(why) => Err(Error::input(
                place,
                format!("not an untrimmed four-sided patch ({why})"),
            )),
        }
    }
}

thread_local! {
    /// Depth of [`quietly`] calls on this thread: panics here are not printed while > 0.
    static QUIET: std::cell::Cell<u32> = const { std::cell::Cell::new(0) };
}

/// `f` with its panics caught and not printed: the STEP reader's and truck's panics are
/// reported as errors naming the file and face, not as a panic message on stderr.
///
/// The process-wide panic hook is wrapped once (it stays silent only on threads inside
/// `quietly`), so faces gridded in parallel cannot leave it swapped: taking and restoring the
/// hook around each call raced between threads and could leave every later panic unprinted.
fn quietly<T>(f: impl FnOnce() -> T) -> std::thread::Result<T> {
    static WRAP: std::sync::Once = std::sync::Once::new();
    WRAP.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if QUIET.with(|q| q.get()) == 0 {
                previous(info);
            }
        }));
    });
    QUIET.with(|q| q.set(q.get() + 1));
    let r = catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(q.get() - 1));
    r
}

/// Reads every face of a STEP file; see the module doc for how each is gridded.
///
/// # Errors
/// [`Error::Io`] if the file cannot be read; [`Error::Format`] if it is not STEP, has no
/// shell, or truck-stepio fails on it (its panics are caught and reported here).
pub fn read_step_faces(path: &Path) -> Result<Vec<StepFace>> {
    Ok(read_step(path)?.faces)
}

/// The faces of a STEP file, and the face entities of its shells that the reader left out.
#[derive(Clone, Debug)]
pub struct StepFaces {
    /// The faces read, numbered from 1 ([`StepFace::index`]).
    pub faces: Vec<StepFace>,
    /// The face entities not read (they get no number), each with the reason.
    pub unread: Vec<Unread>,
}

/// [`read_step_faces`], with the faces the reader left out.
///
/// # Errors
/// As [`read_step_faces`].
pub fn read_step(path: &Path) -> Result<StepFaces> {
    step_from_text(&crate::io::read_input_string(path)?, path)
}

/// [`read_step_faces`] of the text of a STEP file; `path` names it in messages.
///
/// # Errors
/// As [`read_step_faces`].
pub fn step_faces_from_text(text: &str, path: &Path) -> Result<Vec<StepFace>> {
    Ok(step_from_text(text, path)?.faces)
}

/// [`read_step`] of the text of a STEP file; `path` names it in messages.
///
/// # Errors
/// As [`read_step_faces`].
pub fn step_from_text(text: &str, path: &Path) -> Result<StepFaces> {
    prescan::check(text).map_err(|m| Error::format(path, m))?;
    let text = rewrite::empty_lists(text);
    let text = complex::complex_order(&text);
    let text = rewrite::prefer_3d_curves(&text);
    let text = rewrite::unnamed_labels(&text);
    let text = rewrite::untrim_curves(&text);
    let text = rewrite::default_ref_directions(&text);
    let text = units::radian_cone_angles(&text);
    let shells = quietly(|| parse_shells(&text))
        .map_err(|p| {
            let msg = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "unknown error".into());
            Error::format(path, format!("the STEP reader failed: {msg}"))
        })?
        .map_err(|m| Error::format(path, m))?;
    let (shells, bare, unread) = shells;
    // each shell once per instance of its part, placed in the assembly
    let ids: Vec<u64> = shells.iter().map(|(id, _)| *id).collect();
    let placed = placement::shell_placements(&text, &ids).map_err(|m| Error::format(path, m))?;
    let mut faces = Vec::new();
    let placed_faces: usize = shells
        .iter()
        .map(|(id, s)| s.faces.len() * placed[id].len())
        .sum();
    if placed_faces > placement::MAX_FACES {
        return Err(Error::format(
            path,
            format!(
                "the assembly places {placed_faces} faces (at most {} are read)",
                placement::MAX_FACES
            ),
        ));
    }
    for (id, shell) in &shells {
        for m in &placed[id] {
            let moved;
            let shell = if *m == Matrix4::identity() {
                shell
            } else {
                moved = placement::place(shell, *m);
                &moved
            };
            for face in &shell.faces {
                faces.push(step_face(faces.len() + 1, shell, face));
            }
        }
    }
    for surface in bare {
        faces.push(bare_face(faces.len() + 1, surface));
    }
    let uncertainty = units::distance_uncertainty(&text);
    for f in &mut faces {
        f.uncertainty = uncertainty;
    }
    if faces.is_empty() {
        let why = match unread.first() {
            Some(u) => format!("no face could be read ({u})"),
            None => "no faces found (no shell with a readable face)".into(),
        };
        return Err(Error::format(path, why));
    }
    Ok(StepFaces { faces, unread })
}

/// The surface type's name.
fn surface_type(s: &StepSurface) -> &'static str {
    use truck_stepio::r#in::alias::{ElementarySurface as E, SweptCurve as W};
    match s {
        StepSurface::BSplineSurface(_) => "B-spline",
        StepSurface::NurbsSurface(_) => "NURBS",
        StepSurface::ElementarySurface(e) => match **e {
            E::Plane(_) => "plane",
            E::Sphere(_) => "sphere",
            E::CylindricalSurface(_) => "cylinder",
            E::ToroidalSurface(_) => "torus",
            E::ConicalSurface(_) => "cone",
        },
        StepSurface::SweptCurve(w) => match **w {
            W::ExtrudedCurve(_) => "extrusion",
            W::RevolutedCurve(_) => "revolution",
        },
    }
}

/// Distance within which a vertex is on its edge's curve: 1e-4 of the shell's size (real
/// files' gaps reach ~6e-5 of it).
fn vertex_tolerance(shell: &Shell) -> f64 {
    let d = diagonal(shell.vertices.iter());
    if d.is_finite() {
        1e-4 * d + 1e-12
    } else {
        1e-9
    }
}

/// The diagonal of the box of `points` (infinite if there are none, NaN with a NaN point).
fn diagonal<'a>(points: impl Iterator<Item = &'a Point3>) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for (c, v) in [p.x, p.y, p.z].into_iter().enumerate() {
            lo[c] = lo[c].min(v);
            hi[c] = hi[c].max(v);
        }
    }
    (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt()
}

/// The diagonal of the box of the vertices of loop `l` (0 if one is missing).
fn loop_size(shell: &Shell, l: &[truck_topology::compress::CompressedEdgeIndex]) -> f64 {
    let ends = l.iter().flat_map(|ei| {
        let e = shell.edges.get(ei.index);
        [e.map(|e| e.vertices.0), e.map(|e| e.vertices.1)]
    });
    let points: Option<Vec<&Point3>> = ends
        .map(|k| k.and_then(|k| shell.vertices.get(k)))
        .collect();
    let d = points.map_or(0.0, |p| diagonal(p.into_iter()));
    if d.is_finite() {
        d
    } else {
        0.0
    }
}

fn step_face(index: usize, shell: &Shell, face: &CompressedFace<StepSurface>) -> StepFace {
    let surface = match &face.surface {
        StepSurface::BSplineSurface(s) => Some(BSplineSurf::from_truck_bspline(s)),
        StepSurface::NurbsSurface(s) => Some(BSplineSurf::from_truck_nurbs(s)),
        _ => None,
    };
    let (surface, surface_error) = match surface.transpose() {
        Ok(s) => (s, None),
        Err(e) => (None, Some(e.to_string())),
    };
    // truck's curve evaluation may panic on odd edges: such a face is not a patch.
    let trimmed = surface.as_ref().and_then(|s| {
        quietly(|| patch::four_sided(s, shell, face))
            .unwrap_or_else(|_| Err("an edge curve could not be evaluated".into()))
            .err()
    });
    let tol = vertex_tolerance(shell);
    let loops = face
        .boundaries
        .iter()
        .map(|l| {
            // a vertex off its curve within what the loop heals ([`HEAL`]) is the loop's gap
            let heal = tol.max(HEAL * loop_size(shell, l));
            l.iter()
                .enumerate()
                .map(|(n, ei)| {
                    let at = |m: String| format!("boundary edge {}: {m}", n + 1);
                    let edge = shell.edges.get(ei.index).ok_or_else(|| {
                        at("missing (the STEP reader could not convert it)".into())
                    })?;
                    let v = |k: usize| {
                        shell
                            .vertices
                            .get(k)
                            .copied()
                            .ok_or_else(|| at("a vertex is missing".into()))
                    };
                    let ends = (v(edge.vertices.0)?, v(edge.vertices.1)?);
                    let read = |tol: f64| {
                        quietly(|| edge::loop_edge(&edge.curve, ends, ei.orientation, tol))
                            .unwrap_or_else(|_| Err("its curve could not be evaluated".into()))
                    };
                    read(tol)
                        .or_else(|e| if heal > tol { read(heal) } else { Err(e) })
                        .map_err(at)
                })
                .collect()
        })
        .collect();
    StepFace {
        index,
        surface_type: surface_type(&face.surface),
        surface,
        surface_error,
        trimmed,
        cad_surface: face.surface.clone(),
        loops,
        orientation: face.orientation,
        uncertainty: 0.0,
        heal: HEAL,
    }
}

/// A bare surface (no face, no edges) as a face: the whole surface, an untrimmed four-sided
/// patch bounded by its parameter rectangle.
fn bare_face(index: usize, surface: StepSurface) -> StepFace {
    let s = match &surface {
        StepSurface::BSplineSurface(s) => BSplineSurf::from_truck_bspline(s),
        StepSurface::NurbsSurface(s) => BSplineSurf::from_truck_nurbs(s),
        _ => unreachable!("bare surfaces are B-spline or NURBS surfaces"),
    };
    let (surface_ok, surface_error) = match s.map_err(|e| e.to_string()).and_then(|s| {
        patch::has_area(&s)?;
        Ok(s)
    }) {
        Ok(s) => (Some(s), None),
        Err(e) => (None, Some(e)),
    };
    StepFace {
        index,
        surface_type: surface_type(&surface),
        surface: surface_ok,
        surface_error,
        trimmed: None,
        cad_surface: surface,
        loops: Ok(Vec::new()),
        orientation: true,
        uncertainty: 0.0,
        heal: HEAL,
    }
}

/// The surface of face `face` (1-based) of a STEP file, for use as a surface block.
///
/// # Errors
/// Those of [`read_step_faces`]; [`Error::Input`] naming the file and face if there is no
/// such face or it is not gridable ([`StepFace::patch`]).
pub fn step_surface(path: &Path, face: usize) -> Result<BSplineSurf> {
    let faces = read_step_faces(path)?;
    let n = faces.len();
    let f = face
        .checked_sub(1)
        .and_then(|k| faces.get(k))
        .ok_or_else(|| {
            Error::input(
                format!("{}: face {face}", path.display()),
                format!("no such face: the file has faces 1 to {n}"),
            )
        })?;
    f.patch(path).cloned()
}

/// Bare surfaces: B-spline and NURBS surfaces of a file without a face in any shell (OpenVSP
/// writes its components so, in `GEOMETRIC_SET`s), each an untrimmed four-sided patch.
type Bare = Vec<StepSurface>;

/// The shells (with their entity ids) in entity order, the bare surfaces (if no shell has a
/// face) and the faces of the shells the reader leaves out.
type Parsed = (Vec<(u64, Shell)>, Bare, Vec<Unread>);

/// The file's [`Parsed`] shells, surfaces and unread faces.
fn parse_shells(text: &str) -> std::result::Result<Parsed, String> {
    use truck_stepio::r#in::ruststep::tables::EntityTable;
    use truck_stepio::r#in::{
        BSplineSurfaceWithKnotsHolder as Knots, RationalBSplineSurfaceHolder as Rational,
    };
    let exchange = ruststep::parser::parse(text).map_err(|e| format!("not a STEP file: {e}"))?;
    let data = exchange
        .data
        .first()
        .ok_or("the STEP file has no DATA section")?;
    let table = Table::from_data_section(data);
    let mut ids: Vec<&u64> = table.shell.keys().collect();
    ids.sort();
    let shells = ids
        .into_iter()
        .map(|id| {
            table
                .to_compressed_shell(&table.shell[id])
                .map(|s| (*id, s))
                .map_err(|e| format!("shell #{id}: {e}"))
        })
        .collect::<std::result::Result<Vec<(u64, Shell)>, String>>()?;
    // only a shell that lost faces is checked face by face (each surface converted again)
    let unread = shells
        .iter()
        .filter(|(id, s)| s.faces.len() < table.shell[id].cfs_faces.len())
        .flat_map(|(id, _)| unread::unread_faces(&table, *id, &table.shell[id], text))
        .collect();
    let mut bare = Vec::new();
    if shells.iter().all(|(_, s)| s.faces.is_empty()) {
        // Entity order; a surface truck cannot convert is left out, as faces are.
        let mut ids: Vec<u64> = table.b_spline_surface_with_knots.keys().copied().collect();
        ids.extend(table.rational_b_spline_surface.keys());
        ids.sort();
        for id in ids {
            let surface = if table.b_spline_surface_with_knots.contains_key(&id) {
                EntityTable::<Knots>::get_owned(&table, id)
                    .ok()
                    .and_then(|k| (&k).try_into().ok())
                    .map(|s| StepSurface::BSplineSurface(Box::new(s)))
            } else {
                EntityTable::<Rational>::get_owned(&table, id)
                    .ok()
                    .and_then(|r| (&r).try_into().ok())
                    .map(|s| StepSurface::NurbsSurface(Box::new(s)))
            };
            bare.extend(surface);
        }
    }
    Ok((shells, bare, unread))
}
