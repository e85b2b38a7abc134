//! B-spline surfaces written as STEP faces of one open shell, so that control nets and models
//! made here (e.g. the wing–pylon example) can go to CAD tools.

use super::Shell;
use crate::{Error, Result};
use ellipgrid_geometry::BSplineSurf;
use std::path::Path;
use truck_geometry::prelude::{BSplineCurve, BSplineSurface, KnotVec, Point3};
use truck_stepio::out::{CompleteStepDisplay, StepHeaderDescriptor, StepModel};
use truck_stepio::r#in::alias::{Curve3D, Surface as StepSurface};
use truck_topology::compress::{
    CompressedEdge, CompressedEdgeIndex, CompressedFace, CompressedShell,
};

/// Writes a B-spline surface as one STEP face: [`write_step_surfaces`] of one surface.
///
/// # Errors
/// As [`write_step_surfaces`].
pub fn write_step_surface(path: &Path, surface: &BSplineSurface<Point3>) -> Result<()> {
    write_step_surfaces(path, std::slice::from_ref(surface))
}

/// Writes B-spline surfaces as the faces of one STEP open shell (FACE_SURFACEs in the
/// OPEN_SHELL of a SHELL_BASED_SURFACE_MODEL; truck tags lengths as millimetres), each bounded
/// by its four iso-parameter sides (B-spline edge curves), atomically. The reader numbers the
/// faces 1, 2, … in the order given; each face's normal is x_u × x_v. Corners that coincide
/// exactly are one vertex, and sides with the same corners and the same curve (same knots and
/// control points, either way round) one edge, so faces built to share a side meet in the
/// shell's topology too.
///
/// # Errors
/// [`Error::Input`] if there is no surface, or a surface is not finite or its knot vectors
/// are not clamped (end knots of multiplicity degree + 1, so that the sides are curves of the
/// boundary control points); [`Error::Io`] if the file cannot be written.
pub fn write_step_surfaces(path: &Path, surfaces: &[BSplineSurface<Point3>]) -> Result<()> {
    let file = path.display().to_string();
    if surfaces.is_empty() {
        return Err(Error::input(file, "no surface to write"));
    }
    let mut shell: Shell = CompressedShell {
        vertices: Vec::new(),
        edges: Vec::new(),
        faces: Vec::new(),
    };
    for (k, surface) in surfaces.iter().enumerate() {
        let place = if surfaces.len() == 1 {
            file.clone()
        } else {
            format!("{file}: surface {}", k + 1)
        };
        check(surface, &place)?;
        push_face(&mut shell, surface);
    }
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

/// The surface is finite, evaluable and clamped in both directions.
fn check(surface: &BSplineSurface<Point3>, place: &str) -> Result<()> {
    BSplineSurf::from_truck_bspline(surface).map_err(|source| Error::Geometry {
        place: place.to_string(),
        source,
    })?;
    let cp = surface.control_points();
    let (nu, nv) = (cp.len(), cp[0].len());
    for (dir, k, n) in [
        ("u", surface.uknot_vec(), nu),
        ("v", surface.vknot_vec(), nv),
    ] {
        let p = k.len() - n - 1;
        let clamped = k[..=p].iter().all(|t| *t == k[0]) && k[n..].iter().all(|t| *t == k[n]);
        if !clamped {
            return Err(Error::input(
                place,
                format!("the {dir} knot vector is not clamped (end multiplicity {}): its sides are not curves of its boundary control points", p + 1),
            ));
        }
    }
    Ok(())
}

/// Adds `surface` to `shell` as a face bounded by its four sides, reusing equal vertices and
/// edges of the faces already there (not its own: a closed or collapsed side stays as it was
/// written for one face, two edges or two vertices).
fn push_face(shell: &mut Shell, surface: &BSplineSurface<Point3>) {
    let (old_vertices, old_edges) = (shell.vertices.len(), shell.edges.len());
    let cp = surface.control_points();
    let (nu, nv) = (cp.len(), cp[0].len());
    let (uk, vk) = (surface.uknot_vec(), surface.vknot_vec());
    let column = |j: usize| (0..nu).map(|i| cp[i][j]).collect::<Vec<_>>();
    // Corners 0 (u0 v0), 1 (u1 v0), 2 (u1 v1), 3 (u0 v1); the loop runs 0 → 1 → 2 → 3 → 0,
    // counterclockwise in (u, v), so the face normal is x_u × x_v.
    let c = [cp[0][0], cp[nu - 1][0], cp[nu - 1][nv - 1], cp[0][nv - 1]]
        .map(|p| vertex(shell, old_vertices, p));
    let sides = [
        ((c[0], c[1]), uk, column(0), true),
        ((c[1], c[2]), vk, cp[nu - 1].clone(), true),
        ((c[3], c[2]), uk, column(nv - 1), false),
        ((c[0], c[3]), vk, cp[0].clone(), false),
    ];
    let boundary = sides
        .into_iter()
        .map(|(ends, knots, points, forward)| {
            let (index, same) = edge(shell, old_edges, ends, knots, points);
            CompressedEdgeIndex::from((index, forward == same))
        })
        .collect();
    shell.faces.push(CompressedFace {
        boundaries: vec![boundary],
        orientation: true,
        surface: StepSurface::BSplineSurface(Box::new(surface.clone())),
    });
}

/// The index of the shell's vertex at exactly `p` among its first `old`, added if there is
/// none.
fn vertex(shell: &mut Shell, old: usize, p: Point3) -> usize {
    shell.vertices[..old]
        .iter()
        .position(|q| *q == p)
        .unwrap_or_else(|| {
            shell.vertices.push(p);
            shell.vertices.len() - 1
        })
}

/// The index of the shell's edge (among its first `old`) from `ends.0` to `ends.1` along the
/// B-spline curve (`knots`, `points`), and whether it runs that way (`false`: the same curve
/// reversed); added if there is none.
fn edge(
    shell: &mut Shell,
    old: usize,
    ends: (usize, usize),
    knots: &KnotVec,
    points: Vec<Point3>,
) -> (usize, bool) {
    let reversed_knots: Vec<f64> = {
        let (a, b) = (knots[0], knots[knots.len() - 1]);
        knots.iter().rev().map(|t| a + b - t).collect()
    };
    let found = shell.edges[..old].iter().position(|e| {
        let Curve3D::BSplineCurve(curve) = &e.curve else {
            return false;
        };
        let (k, p) = (curve.knot_vec(), curve.control_points());
        let same = e.vertices == ends && k == knots && *p == points;
        let back = e.vertices == (ends.1, ends.0)
            && k.iter().eq(reversed_knots.iter())
            && p.iter().eq(points.iter().rev());
        same || back
    });
    match found {
        Some(i) => (i, shell.edges[i].vertices == ends),
        None => {
            shell.edges.push(CompressedEdge {
                vertices: ends,
                curve: Curve3D::BSplineCurve(BSplineCurve::new(knots.clone(), points)),
            });
            (shell.edges.len() - 1, true)
        }
    }
}
