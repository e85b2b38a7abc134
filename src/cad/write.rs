//! A B-spline surface written as one STEP face, so that control nets can go to CAD tools.

use super::Shell;
use crate::{Error, Result};
use ellipgrid_geometry::BSplineSurf;
use std::path::Path;
use truck_geometry::prelude::{BSplineCurve, BSplineSurface, Point3};
use truck_stepio::out::{CompleteStepDisplay, StepHeaderDescriptor, StepModel};
use truck_stepio::r#in::alias::{Curve3D, Surface as StepSurface};
use truck_topology::compress::{
    CompressedEdge, CompressedEdgeIndex, CompressedFace, CompressedShell,
};

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
