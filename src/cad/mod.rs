//! STEP in and out (ISO 10303-21) through truck-stepio: B-spline / NURBS faces of a STEP file
//! as [`BSplineSurf`] surfaces for the Section 4 pipeline ([`crate::surface::pipeline`]), and a
//! B-spline surface (e.g. a [`ellipgrid_geometry::HermiteSurface`] control net through
//! `to_bspline`) written as one STEP face so that control nets can go to CAD tools.
//!
//! | entry point | what |
//! |---|---|
//! | [`read_step_faces`] | every face of every shell, in file order, numbered from 1 |
//! | [`step_surface`] | the surface of one gridable face (for case files) |
//! | [`grid_patch`] | Section 4 grid of a four-sided patch with per-direction distributions |
//! | [`write_step_surface`] | one B-spline face bounded by its four iso-parameter sides |
//!
//! A face is *gridable* when its surface is a B-spline or NURBS surface and its boundary is a
//! single loop of edges that lie on the four sides of the surface's parameter square and cover
//! them (an untrimmed four-sided patch). The boundary nodes are then placed on the sides of
//! the surface itself at the requested 3D arclengths ([`crate::surface::pipeline::edge_params`]); they
//! coincide with the face's edge curves to within the check's tolerance
//! ([`FOUR_SIDED_TOL`] of the surface's size). Trimmed faces, faces with holes and faces of
//! other surface types are reported with the reason and not gridded (for now).
//!
//! Limits of truck-stepio 0.3 that show here: faces whose surface or edges it cannot convert
//! are skipped (it prints a line to stderr) and so get no number; its writer prints numbers
//! below 10⁻² in magnitude with 11 significant digits (absolute error below 5·10⁻¹⁴), larger
//! ones exactly; a face with `same_sense = .F.` is read with u and v swapped.

mod prescan;
use crate::case::DistributionSpec;
use crate::grid::Edge;
use crate::solve::LinearSolver;
use crate::surface::pipeline::{
    edge_length, edge_params, grid_surface, surface_edge, SurfaceResult,
};
use crate::{Error, Result};
use ellipgrid_geometry::{project_to_edge, BSplineSurf, Surface, SurfaceEdge, Vec3};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use truck_geometry::prelude::{BSplineCurve, BSplineSurface, ParametricCurve, Point3};
use truck_stepio::out::{CompleteStepDisplay, StepHeaderDescriptor, StepModel};
use truck_stepio::r#in::alias::{Curve3D, Surface as StepSurface};
use truck_stepio::r#in::{ruststep, Table};
use truck_topology::compress::{
    CompressedEdge, CompressedEdgeIndex, CompressedFace, CompressedShell,
};

/// Tolerance of the four-sided check, relative to the diagonal of the surface's bounding box:
/// every boundary edge must lie this close to one side of the parameter square.
pub const FOUR_SIDED_TOL: f64 = 1e-6;

type Shell = CompressedShell<Point3, Curve3D, StepSurface>;

/// One face of a STEP file.
#[derive(Clone, Debug)]
pub struct StepFace {
    /// 1-based number over all shells in file order (shells by entity number).
    pub index: usize,
    /// The surface type: "B-spline", "NURBS", or a phrase naming an elementary (plane,
    /// cylinder, …) or swept surface.
    pub surface_type: &'static str,
    /// The surface, if it is a B-spline or NURBS surface that ellipgrid can evaluate.
    pub surface: Option<BSplineSurf>,
    /// Why a B-spline or NURBS surface cannot be used (degree above
    /// [`BSplineSurf::MAX_DEGREE`], bad knots or weights), if so.
    pub surface_error: Option<String>,
    /// `None` for an untrimmed four-sided patch, else why the face is not one.
    pub trimmed: Option<String>,
}

impl StepFace {
    /// Whether the face can be gridded: a B-spline/NURBS surface, untrimmed and four-sided.
    pub fn is_four_sided_patch(&self) -> bool {
        self.surface.is_some() && self.trimmed.is_none()
    }

    /// The surface of a gridable face.
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
                    "the surface is {}; only B-spline and NURBS faces can be gridded",
                    self.surface_type
                ),
            ));
        };
        match &self.trimmed {
            None => Ok(s),
            Some(why) => Err(Error::input(
                place,
                format!(
                    "not an untrimmed four-sided patch ({why}); such faces are not supported yet"
                ),
            )),
        }
    }
}

/// `f` with its panics caught and not printed: the STEP reader's panics are reported as
/// errors naming the file, not as a panic message on stderr.
fn quietly<T>(f: impl FnOnce() -> T) -> std::thread::Result<T> {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let r = catch_unwind(AssertUnwindSafe(f));
    std::panic::set_hook(hook);
    r
}

/// Reads every face of a STEP file; see the module doc for which faces are gridable.
///
/// # Errors
/// [`Error::Io`] if the file cannot be read; [`Error::Format`] if it is not STEP, has no
/// shell, or truck-stepio fails on it (its panics are caught and reported here).
pub fn read_step_faces(path: &Path) -> Result<Vec<StepFace>> {
    let text = crate::io::read_input_string(path)?;
    prescan::check(&text).map_err(|m| Error::format(path, m))?;
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
    let mut faces = Vec::new();
    for shell in &shells {
        for face in &shell.faces {
            let (surface_type, surface) = match &face.surface {
                StepSurface::BSplineSurface(s) => {
                    ("B-spline", Some(BSplineSurf::from_truck_bspline(s)))
                }
                StepSurface::NurbsSurface(s) => ("NURBS", Some(BSplineSurf::from_truck_nurbs(s))),
                StepSurface::ElementarySurface(_) => (
                    "an elementary surface (plane, cylinder, cone, sphere or torus)",
                    None,
                ),
                StepSurface::SweptCurve(_) => ("a swept surface (extrusion or revolution)", None),
            };
            let index = faces.len() + 1;
            let (surface, surface_error) = match surface.transpose() {
                Ok(s) => (s, None),
                Err(e) => (None, Some(e.to_string())),
            };
            // truck's curve evaluation may panic on odd edges: such a face is not a patch.
            let trimmed = surface.as_ref().and_then(|s| {
                quietly(|| four_sided(s, shell, face))
                    .unwrap_or_else(|_| Err("an edge curve could not be evaluated".into()))
                    .err()
            });
            faces.push(StepFace {
                index,
                surface_type,
                surface,
                surface_error,
                trimmed,
            });
        }
    }
    if faces.is_empty() {
        return Err(Error::format(
            path,
            "no faces found (no shell with a readable face)",
        ));
    }
    Ok(faces)
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

fn parse_shells(text: &str) -> std::result::Result<Vec<Shell>, String> {
    let exchange = ruststep::parser::parse(text).map_err(|e| format!("not a STEP file: {e}"))?;
    let data = exchange
        .data
        .first()
        .ok_or("the STEP file has no DATA section")?;
    let table = Table::from_data_section(data);
    let mut ids: Vec<&u64> = table.shell.keys().collect();
    ids.sort();
    ids.into_iter()
        .map(|id| {
            table
                .to_compressed_shell(&table.shell[id])
                .map_err(|e| format!("shell #{id}: {e}"))
        })
        .collect()
}

/// Checks that the face is bounded by one loop of edges on the sides of the parameter square
/// covering all four; the reason if not.
fn four_sided(
    s: &BSplineSurf,
    shell: &Shell,
    face: &CompressedFace<StepSurface>,
) -> std::result::Result<(), String> {
    let loops = &face.boundaries;
    match loops.len() {
        0 => return Err("no boundary loop".into()),
        1 => {}
        n => return Err(format!("{n} boundary loops (holes)")),
    }
    const NS: usize = 64; // coarse samples of each side, to start Newton from
    let sides = [
        SurfaceEdge::U0,
        SurfaceEdge::U1,
        SurfaceEdge::V0,
        SurfaceEdge::V1,
    ];
    let coarse: Vec<Vec<Vec3>> = sides
        .iter()
        .map(|e| {
            (0..=NS)
                .map(|k| {
                    let (u, v) = e.uv(k as f64 / NS as f64);
                    s.point(u, v)
                })
                .collect()
        })
        .collect();
    let all = coarse.iter().flatten();
    let (lo, hi) = all.fold(
        (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
    );
    let tol = FOUR_SIDED_TOL * (hi - lo).norm().max(f64::MIN_POSITIVE);
    // Parameter of p on side k and its distance, or None if p is not on it.
    let on_side = |k: usize, p: Vec3| -> Option<f64> {
        let (k0, _) = coarse[k]
            .iter()
            .enumerate()
            .map(|(i, q)| (i, (q - p).norm()))
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        let t = project_to_edge(s, sides[k], p, k0 as f64 / NS as f64)?;
        let (u, v) = sides[k].uv(t);
        ((s.point(u, v) - p).norm() <= tol).then_some(t)
    };
    let mut covered: [Vec<(f64, f64)>; 4] = Default::default();
    for (n, ei) in loops[0].iter().enumerate() {
        let Some(edge) = shell.edges.get(ei.index) else {
            return Err(format!("boundary edge {} is missing", n + 1));
        };
        let Some((a, b)) = edge.curve.try_range_tuple() else {
            return Err(format!("boundary edge {} is unbounded", n + 1));
        };
        const NE: usize = 16;
        let pts: Vec<Vec3> = (0..=NE)
            .map(|k| {
                let p = edge.curve.subs(a + (b - a) * k as f64 / NE as f64);
                Vec3::new(p.x, p.y, p.z)
            })
            .collect();
        let side = (0..4).find_map(|k| {
            let ts: Option<Vec<f64>> = pts.iter().map(|p| on_side(k, *p)).collect();
            ts.map(|ts| (k, ts))
        });
        let Some((k, ts)) = side else {
            return Err(format!(
                "boundary edge {} is not on a side of the surface's parameter square",
                n + 1
            ));
        };
        let (t0, t1) = ts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), t| {
                (a.min(*t), b.max(*t))
            });
        covered[k].push((t0, t1));
    }
    for (k, iv) in covered.iter_mut().enumerate() {
        iv.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Sweep: the union of the edges' parameter intervals must be [0, 1] (small gaps are
        // the tolerance of the projection).
        let mut reach = 0.0;
        for &(a, b) in iv.iter() {
            if a > reach + 1e-6 {
                break;
            }
            reach = f64::max(reach, b);
        }
        if reach < 1.0 - 1e-6 {
            let name = ["u = 0", "u = 1", "v = 0", "v = 1"][k];
            return Err(format!(
                "the side {name} of the surface is not covered by its boundary edges"
            ));
        }
    }
    Ok(())
}

/// Section 4 grid of an untrimmed four-sided patch: `ni` nodes along the u sides (E3, E4),
/// `nj` along the v sides (E1, E2), placed on each side by `dist_i` / `dist_j` (spacings are
/// lengths, as in case files), then [`grid_surface`].
///
/// # Errors
/// Bad distributions or node counts ([`Error::Input`] / [`Error::Geometry`] at `place`), and
/// those of [`grid_surface`].
pub fn grid_patch(
    surface: &dyn Surface,
    (ni, nj): (usize, usize),
    dist_i: &DistributionSpec,
    dist_j: &DistributionSpec,
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<SurfaceResult> {
    if ni < 3 || nj < 3 {
        return Err(Error::input(
            place,
            format!("a surface grid needs at least 3 × 3 nodes, got {ni} × {nj}"),
        ));
    }
    let mut uv: [Vec<[f64; 2]>; 4] = Default::default();
    for e in Edge::ALL {
        let (n, d) = match surface_edge(e) {
            SurfaceEdge::V0 | SurfaceEdge::V1 => (ni, dist_i),
            SurfaceEdge::U0 | SurfaceEdge::U1 => (nj, dist_j),
        };
        let at = format!("{place}, edge {e}");
        let sigma = d.sample(n, edge_length(surface, e), &at)?;
        uv[e.index()] = edge_params(surface, e, &sigma);
    }
    grid_surface(surface, &uv, solver, place)
}

/// Writes a B-spline surface as one STEP face (a FACE_SURFACE in the OPEN_SHELL of a
/// SHELL_BASED_SURFACE_MODEL; truck tags lengths as millimetres) bounded by its four
/// iso-parameter sides (B-spline edge curves), atomically.
///
/// # Errors
/// [`Error::Input`] if the surface is not finite or its knot vectors are not clamped (end
/// knots of multiplicity degree + 1, so that the sides are curves of the boundary control
/// points); [`Error::Io`] if the file cannot be written.
pub fn write_step_surface(path: &Path, surface: &BSplineSurface<Point3>) -> Result<()> {
    let place = path.display().to_string();
    BSplineSurf::from_truck_bspline(surface).map_err(|source| Error::Geometry {
        place: place.clone(),
        source,
    })?;
    let cp = surface.control_points();
    let (nu, nv) = (cp.len(), cp[0].len());
    let (uk, vk) = (surface.uknot_vec(), surface.vknot_vec());
    for (dir, k, n) in [("u", uk, nu), ("v", vk, nv)] {
        let p = k.len() - n - 1;
        let clamped = k[..=p].iter().all(|t| *t == k[0]) && k[n..].iter().all(|t| *t == k[n]);
        if !clamped {
            return Err(Error::input(
                place,
                format!("the {dir} knot vector is not clamped (end multiplicity {}): its sides are not curves of its boundary control points", p + 1),
            ));
        }
    }
    let curve = |knots: &truck_geometry::prelude::KnotVec, pts: Vec<Point3>| {
        Curve3D::BSplineCurve(BSplineCurve::new(knots.clone(), pts))
    };
    let column = |j: usize| (0..nu).map(|i| cp[i][j]).collect::<Vec<_>>();
    let row = |i: usize| cp[i].clone();
    // Corners 0 (u0 v0), 1 (u1 v0), 2 (u1 v1), 3 (u0 v1); the loop runs 0 → 1 → 2 → 3 → 0,
    // counterclockwise in (u, v), so the face normal is x_u × x_v.
    let vertices = vec![cp[0][0], cp[nu - 1][0], cp[nu - 1][nv - 1], cp[0][nv - 1]];
    let edges = vec![
        CompressedEdge {
            vertices: (0, 1),
            curve: curve(uk, column(0)),
        },
        CompressedEdge {
            vertices: (1, 2),
            curve: curve(vk, row(nu - 1)),
        },
        CompressedEdge {
            vertices: (3, 2),
            curve: curve(uk, column(nv - 1)),
        },
        CompressedEdge {
            vertices: (0, 3),
            curve: curve(vk, row(0)),
        },
    ];
    let boundary = [(0, true), (1, true), (2, false), (3, false)]
        .map(CompressedEdgeIndex::from)
        .to_vec();
    let shell: Shell = CompressedShell {
        vertices,
        edges,
        faces: vec![CompressedFace {
            boundaries: vec![boundary],
            orientation: true,
            surface: StepSurface::BSplineSurface(Box::new(surface.clone())),
        }],
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let text = CompleteStepDisplay::new(
        StepModel::from(&shell),
        StepHeaderDescriptor {
            file_name: name,
            organization_system: "ellipgrid".into(),
            ..Default::default()
        },
    )
    .to_string();
    crate::io::write_atomic(path, |w| w.write_all(text.as_bytes()))
}
