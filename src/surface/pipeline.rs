//! Surface grids on a parametrized surface, Section 4.2 (METHOD.md §5): the grid depends only
//! on the shape of the surface and the boundary distribution, not on the parametrization.
//!
//! 1. boundary nodes → (u, v) on ∂P_uv (known here: they are sampled on the surface's edges);
//! 2. straight-line grid [39, 40] in P_uv → initial grid x^I = x(u^I), fold-free because the
//!    parametrization is one-to-one;
//! 3. Laplace–Beltrami [50–53] for s and t on x^I, Dirichlet data the boundary arclength;
//! 4. straight-line target grid (s, t) in P_st;
//! 5. inversion: locate each target in the (s^I, t^I) mesh, bilinear (α, β), interpolate
//!    (u, v), evaluate the surface.

use crate::algebraic::blend::hermite_blend;
use crate::algebraic::transform::{straight_line, ParamGrid};
use crate::elliptic::harmonic::harmonic_st;
use crate::elliptic::orthogonal::edge_functions;
use crate::grid::arclength::EdgeFunctions;
use crate::grid::boundary::Boundary2;
use crate::grid::{Edge, Grid2};
use crate::solve::LinearSolver;
use crate::surface::inversion::QuadMesh;
use crate::{Error, Result};
use ellipgrid_geometry::{ArclengthMap, Curve, Surface, SurfaceEdge, Vec3};
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;

/// Seconds spent in each step of the pipeline.
#[derive(Clone, Debug, Default, Serialize)]
pub struct StepTimes {
    pub initial_grid: f64,
    pub laplace_beltrami: f64,
    pub target: f64,
    pub inversion: f64,
}

/// A surface grid with the initial grid it was inverted from.
#[derive(Clone, Debug)]
pub struct SurfaceResult {
    pub grid: Grid2<3>,
    /// x^I: the straight-line grid in P_uv mapped onto the surface (parametrization-dependent).
    pub initial: Grid2<3>,
    /// (u, v) of every node of the final grid.
    pub uv: Vec<[f64; 2]>,
    pub times: StepTimes,
}

/// The parameter-square side of a block edge: E1 ↔ u = 0, E2 ↔ u = 1, E3 ↔ v = 0, E4 ↔ v = 1.
pub fn surface_edge(e: Edge) -> SurfaceEdge {
    match e {
        Edge::E1 => SurfaceEdge::U0,
        Edge::E2 => SurfaceEdge::U1,
        Edge::E3 => SurfaceEdge::V0,
        Edge::E4 => SurfaceEdge::V1,
    }
}

/// A side of the parameter square as a curve in R³.
struct EdgeCurve<'a> {
    surface: &'a dyn Surface,
    edge: SurfaceEdge,
}

impl Curve for EdgeCurve<'_> {
    fn point(&self, t: f64) -> Vec3 {
        let (u, v) = self.edge.uv(t);
        self.surface.point(u, v)
    }
    fn derivative(&self, t: f64) -> Vec3 {
        self.edge.curve(self.surface, t).1
    }
    fn breakpoints(&self) -> Vec<f64> {
        let (bu, bv) = self.surface.breaks();
        match self.edge {
            SurfaceEdge::U0 | SurfaceEdge::U1 => bv,
            SurfaceEdge::V0 | SurfaceEdge::V1 => bu,
        }
    }
}

/// Step 1: the (u, v) of nodes along the side of the parameter square under edge `e`, placed
/// at the normalized 3D arclengths `sigma` of the surface's edge curve.
pub fn edge_params(surface: &dyn Surface, e: Edge, sigma: &[f64]) -> Vec<[f64; 2]> {
    edge_params_on(&edge_map(surface, e), e, sigma)
}

/// The arclength table of the surface's edge curve under block edge `e`: build it once where
/// both the length and the parameters are needed (on a B-spline surface of many knot spans
/// it is most of a patch's gridding time).
pub fn edge_map(surface: &dyn Surface, e: Edge) -> ArclengthMap {
    ArclengthMap::new(&EdgeCurve {
        surface,
        edge: surface_edge(e),
    })
}

/// [`edge_params`] from the edge's arclength table `map` ([`edge_map`]).
pub fn edge_params_on(map: &ArclengthMap, e: Edge, sigma: &[f64]) -> Vec<[f64; 2]> {
    let edge = surface_edge(e);
    map.params(sigma)
        .into_iter()
        .map(|t| {
            let (u, v) = edge.uv(t);
            [u, v]
        })
        .collect()
}

/// Length of the surface's edge curve under block edge `e`.
pub fn edge_length(surface: &dyn Surface, e: Edge) -> f64 {
    edge_map(surface, e).length()
}

/// Edge functions of the straight-line grid in P_uv from the boundary (u, v) values:
/// u along E3 and E4, v along E1 and E2 (step 2).
fn uv_edge_functions(uv: &[Vec<[f64; 2]>; 4]) -> EdgeFunctions {
    EdgeFunctions {
        s_e3: uv[Edge::E3.index()].iter().map(|p| p[0]).collect(),
        s_e4: uv[Edge::E4.index()].iter().map(|p| p[0]).collect(),
        t_e1: uv[Edge::E1.index()].iter().map(|p| p[1]).collect(),
        t_e2: uv[Edge::E2.index()].iter().map(|p| p[1]).collect(),
    }
}

/// Checks that the boundary (u, v) lie on the right sides of the unit square, in order.
fn check_uv(uv: &[Vec<[f64; 2]>; 4], place: &str) -> Result<()> {
    let (ni, nj) = (uv[2].len(), uv[0].len());
    if ni < 3 || nj < 3 || uv[3].len() != ni || uv[1].len() != nj {
        return Err(Error::input(
            place,
            "a surface block needs at least 3 × 3 nodes",
        ));
    }
    for e in Edge::ALL {
        let pts = &uv[e.index()];
        let (fixed, val, run) = match e {
            Edge::E1 => (0, 0.0, 1),
            Edge::E2 => (0, 1.0, 1),
            Edge::E3 => (1, 0.0, 0),
            Edge::E4 => (1, 1.0, 0),
        };
        let ok = pts.iter().all(|p| p[fixed] == val)
            && pts.first().map(|p| p[run]) == Some(0.0)
            && pts.last().map(|p| p[run]) == Some(1.0)
            && pts.windows(2).all(|w| w[1][run] > w[0][run]);
        if !ok {
            return Err(Error::input(
                format!("{place}, edge {e}"),
                "boundary parameters must run monotonically along the edge of the unit square",
            ));
        }
    }
    Ok(())
}

/// Grids a surface block by Section 4.2, steps 1–5. `uv` holds the (u, v) of the boundary
/// nodes of E1..E4 in index order (E1 on u = 0, E2 on u = 1, E3 on v = 0, E4 on v = 1).
pub fn grid_surface(
    surface: &dyn Surface,
    uv: &[Vec<[f64; 2]>; 4],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<SurfaceResult> {
    grid_surface_orthogonal(surface, uv, [false; 4], solver, place)
}

/// Section 4.2 with orthogonality at the chosen edges (E1..E4): Neumann conditions in step 3
/// and the Hermite-blended target [47, 48] in step 4 (METHOD.md §5, orthogonal variant).
pub fn grid_surface_orthogonal(
    surface: &dyn Surface,
    uv: &[Vec<[f64; 2]>; 4],
    orthogonal: [bool; 4],
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<SurfaceResult> {
    check_uv(uv, place)?;
    let mut times = StepTimes::default();
    let t0 = Instant::now();
    // Steps 1–2: the straight-line grid in P_uv and its image x^I.
    let puv = straight_line(&uv_edge_functions(uv));
    let (ni, nj) = (puv.ni(), puv.nj());
    let mut initial = Grid2::<3>::zeros(ni, nj);
    evaluate_into(surface, &puv.s, &puv.t, &mut initial);
    let edges = Edge::ALL.map(|e| initial.edge(e));
    // A side may be a pole (collapsed to a point): its nodes differ only in (u, v).
    let boundary = Boundary2::with_poles(edges, place)?;
    boundary.apply_to(&mut initial);
    times.initial_grid = t0.elapsed().as_secs_f64();
    // Step 3: Laplace–Beltrami for s and t on x^I: Dirichlet = boundary arclength, or zero
    // Neumann flux at orthogonal edges.
    let t1 = Instant::now();
    let (si, ti) = harmonic_st(&initial, orthogonal, solver, place)?;
    times.laplace_beltrami = t1.elapsed().as_secs_f64();
    // Step 4: the target grid in P_st, with the edge functions of step 3 [46].
    let t2 = Instant::now();
    let target = if orthogonal.iter().any(|&o| o) {
        let ef = edge_functions(&initial, &si, &ti, place)?;
        hermite_blend(&ef, orthogonal, place)?
    } else {
        straight_line(&EdgeFunctions::arclength(&boundary))
    };
    times.target = t2.elapsed().as_secs_f64();
    // Step 5: inversion.
    let t3 = Instant::now();
    let uvs = invert(&si, &ti, &puv, &target, place)?;
    let mut grid = Grid2::<3>::zeros(ni, nj);
    let (us, vs): (Vec<f64>, Vec<f64>) = uvs.iter().map(|p| (p[0], p[1])).unzip();
    evaluate_into(surface, &us, &vs, &mut grid);
    boundary.apply_to(&mut grid);
    times.inversion = t3.elapsed().as_secs_f64();
    Ok(SurfaceResult {
        grid,
        initial,
        uv: uvs,
        times,
    })
}

/// Step 5: (u, v) at every target node by locating it in the (s^I, t^I) mesh and
/// interpolating the initial grid's (u, v). Boundary nodes keep their own (u, v).
pub fn invert(
    si: &[f64],
    ti: &[f64],
    puv: &ParamGrid,
    target: &ParamGrid,
    place: &str,
) -> Result<Vec<[f64; 2]>> {
    let (ni, nj) = (puv.ni(), puv.nj());
    let mesh = QuadMesh::new(ni, nj, si, ti, place)?;
    let mut out = vec![[0.0; 2]; ni * nj];
    let failed = std::sync::atomic::AtomicUsize::new(usize::MAX);
    out.par_chunks_mut(ni).enumerate().for_each(|(j, row)| {
        let mut scratch = Vec::new();
        let mut prev = (0, j.min(nj - 2));
        for (i, o) in row.iter_mut().enumerate() {
            let n = i + ni * j;
            if i == 0 || j == 0 || i + 1 == ni || j + 1 == nj {
                *o = [puv.s[n], puv.t[n]];
                continue;
            }
            let x = [target.s[n], target.t[n]];
            match mesh.locate(x, prev, &mut scratch) {
                Some(h) => {
                    *o = [mesh.interpolate(&puv.s, &h), mesh.interpolate(&puv.t, &h)];
                    prev = (h.p, h.q);
                }
                None => {
                    failed.fetch_min(n, std::sync::atomic::Ordering::Relaxed);
                }
            }
        }
    });
    let f = failed.into_inner();
    if f != usize::MAX {
        return Err(Error::Folded {
            place: place.to_string(),
            count: 1,
            first: format!(
                "node ({}, {}): its target (s, t) lies in no quad of the Laplace–Beltrami \
                 mesh (the initial grid or the harmonic map folds)",
                f % ni,
                f / ni
            ),
        });
    }
    Ok(out)
}

/// x(u, v) at every node, in parallel.
fn evaluate_into(surface: &dyn Surface, us: &[f64], vs: &[f64], g: &mut Grid2<3>) {
    let pts: Vec<[f64; 3]> = us
        .par_iter()
        .zip(vs.par_iter())
        .map(|(&u, &v)| {
            let p = surface.point(u, v);
            [p.x, p.y, p.z]
        })
        .collect();
    for (c, arr) in g.coords_mut().iter_mut().enumerate() {
        for (a, p) in arr.iter_mut().zip(&pts) {
            *a = p[c];
        }
    }
}
