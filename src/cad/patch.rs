//! Untrimmed four-sided B-spline / NURBS faces: the check that a face's boundary edges lie on
//! the four sides of its surface's parameter square and cover them, and the Section 4 grid of
//! such a patch (boundary nodes on the surface's own sides).

use super::{Shell, FOUR_SIDED_TOL};
use crate::case::DistributionSpec;
use crate::grid::boundary::POLE_TOLERANCE;
use crate::grid::Edge;
use crate::solve::LinearSolver;
use crate::surface::pipeline::{
    edge_map, edge_params_on, grid_surface, surface_edge, SurfaceResult,
};
use crate::{Error, Result};
use ellipgrid_geometry::{project_to_edge, BSplineSurf, Surface, SurfaceEdge, Vec3};
use truck_geometry::prelude::ParametricCurve;
use truck_stepio::r#in::alias::Surface as StepSurface;
use truck_topology::compress::CompressedFace;

/// Checks that the face is bounded by one loop of edges on the sides of the parameter square
/// covering all four; the reason if not.
pub(super) fn four_sided(
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

/// Refuses a surface without area: all of it one point (to round-off: 1e-12 of its
/// coordinates' magnitude), or a curve (OpenVSP writes such degenerate bilinear patches at
/// wing tips and roots, next to the real ones). Measured on a 17 × 17 sample:
/// Σ |diagonal × diagonal| / 2 against the square of the sample's diameter.
pub(super) fn has_area(s: &dyn Surface) -> std::result::Result<(), String> {
    const N: usize = 16;
    let p: Vec<Vec3> = (0..=N)
        .flat_map(|j| (0..=N).map(move |i| (i, j)))
        .map(|(i, j)| s.point(i as f64 / N as f64, j as f64 / N as f64))
        .collect();
    let (lo, hi) = p.iter().fold(
        (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
        |(lo, hi), q| (lo.inf(q), hi.sup(q)),
    );
    let diam = (hi - lo).norm();
    // round-off of the evaluation at the coordinates' magnitude: OpenVSP writes patches whose
    // four control points are one point, evaluated 1e-14 apart
    let noise = 1e-12 * lo.abs().sup(&hi.abs()).norm();
    let at = |i: usize, j: usize| p[i + (N + 1) * j];
    let area: f64 = (0..N)
        .flat_map(|j| (0..N).map(move |i| (i, j)))
        .map(|(i, j)| {
            let d1 = at(i + 1, j + 1) - at(i, j);
            let d2 = at(i, j + 1) - at(i + 1, j);
            0.5 * d1.cross(&d2).norm()
        })
        .sum();
    // Written so that NaN refuses too.
    if diam.partial_cmp(&noise) != Some(std::cmp::Ordering::Greater) {
        Err("the surface is a single point (a degenerate patch, not a face)".into())
    } else if area.partial_cmp(&(1e-10 * diam * diam)) != Some(std::cmp::Ordering::Greater) {
        Err(format!(
            "the surface has no area (a curve of length {diam:.3e}: a degenerate patch, not a face)"
        ))
    } else {
        Ok(())
    }
}

/// Section 4 grid of an untrimmed four-sided patch: `ni` nodes along the u sides (E3, E4),
/// `nj` along the v sides (E1, E2), placed on each side by `dist_i` / `dist_j` (spacings are
/// lengths, as in case files), then [`grid_surface`]. A side collapsed to a point (a pole)
/// takes the parameters of the opposite side's nodes (uniform ones if that is a pole too).
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
    let maps = Edge::ALL.map(|e| edge_map(surface, e));
    let length = maps.each_ref().map(|m| m.length());
    let longest = length.iter().copied().fold(0.0, f64::max);
    // A side collapsed to a point (a pole: the nose of an OpenVSP fuselage, the tip of a
    // wing cap) gets the nodes of the opposite side's parameters, so that the grid lines
    // leave the pole along the iso-parameter lines that reach the opposite side's nodes.
    let pole = length.map(|l| l <= POLE_TOLERANCE * longest);
    let mut uv: [Vec<[f64; 2]>; 4] = Default::default();
    for e in Edge::ALL.into_iter().filter(|e| !pole[e.index()]) {
        let (n, d) = match surface_edge(e) {
            SurfaceEdge::V0 | SurfaceEdge::V1 => (ni, dist_i),
            SurfaceEdge::U0 | SurfaceEdge::U1 => (nj, dist_j),
        };
        let at = format!("{place}, edge {e}");
        let sigma = d.sample(n, length[e.index()], &at)?;
        uv[e.index()] = edge_params_on(&maps[e.index()], e, &sigma);
    }
    for e in Edge::ALL.into_iter().filter(|e| pole[e.index()]) {
        let (k, n, run) = (
            e.index(),
            if e.runs_along_i() { ni } else { nj },
            usize::from(!e.runs_along_i()),
        );
        let fixed = match e {
            Edge::E1 | Edge::E3 => 0.0,
            Edge::E2 | Edge::E4 => 1.0,
        };
        let along: Vec<f64> = if pole[k ^ 1] {
            (0..n).map(|m| m as f64 / (n - 1) as f64).collect()
        } else {
            uv[k ^ 1].iter().map(|p| p[run]).collect()
        };
        uv[k] = along
            .into_iter()
            .map(|a| if run == 0 { [a, fixed] } else { [fixed, a] })
            .collect();
    }
    grid_surface(surface, &uv, solver, place)
}
