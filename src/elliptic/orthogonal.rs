//! Orthogonality at chosen edges of a 2D block (planar or minimal surface), Section 2.4
//! (METHOD.md §3): three steps.
//!
//! 1. Grid with straight-line control functions ([`crate::elliptic::domain::grid_block`]).
//! 2. On that grid, solve the Neumann problems of [`crate::elliptic::harmonic::harmonic_st`] (zero normal
//!    flux at the orthogonal edges); their boundary values are the new edge functions [46].
//! 3. Hermite-blend those edge functions ([`crate::algebraic::blend::hermite_blend`], [47]–[49]), take the
//!    control functions [19] of the blend, and solve [24] again from the grid of step 1 (with
//!    nested iteration when step 1 had it: every level starts from step 1's grid sub-sampled
//!    unless a coarser level predicts it, see [`crate::elliptic::nested`]).
//!
//! Corners keep their boundary points: a grid cannot be orthogonal at a corner whose angle is
//! not 90°, so orthogonality is reached away from such corners and improves under refinement.
//! Surfaces given by a parametrization (Section 4) will reuse steps 2–3 with the Laplace–Beltrami
//! solve on the surface grid; that pipeline is not here yet.

use crate::algebraic::blend::hermite_blend;
use crate::algebraic::control2d::Control2;
use crate::algebraic::transform::{straight_line, ParamGrid};
use crate::algebraic::ControlKind;
use crate::elliptic::domain::grid_block;
use crate::elliptic::harmonic::harmonic_st;
use crate::elliptic::nested;
use crate::elliptic::picard::BlockResult;
use crate::elliptic::picard::{PicardInfo, PicardParams};
use crate::elliptic::poisson2d;
use crate::elliptic::wall2d::{hold_wall_spacing_on, WallSide};
use crate::grid::arclength::{chord_length, EdgeFunctions};
use crate::grid::boundary::Boundary2;
use crate::grid::{Edge, Grid2};
use crate::solve::LinearSolver;
use crate::{Error, Result};

/// Everything the three steps produce.
#[derive(Clone, Debug)]
pub struct OrthogonalResult<const D: usize> {
    /// The final grid (step 3).
    pub grid: Grid2<D>,
    /// Picard history of step 3, with step 1's (straight-line control functions) in its
    /// `first`.
    pub picard: PicardInfo,
    /// The edge functions of step 2, eq. [46] (arclength on the edges that are not orthogonal).
    pub edge_functions: EdgeFunctions,
    /// The algebraic parameters whose control functions gave the final grid: the Hermite blend
    /// of step 3, or the straight-line parameters [39, 40] without orthogonal edges.
    pub params: ParamGrid,
}

/// Parses edge names ("E1" … "E4", case-insensitive) into the flags E1, E2, E3, E4.
///
/// # Errors
/// [`Error::Input`] at `place` for an unknown name.
pub fn parse_edges<S: AsRef<str>>(names: &[S], place: &str) -> Result<[bool; 4]> {
    let mut orth = [false; 4];
    for n in names {
        let e = Edge::parse(n.as_ref()).ok_or_else(|| {
            Error::input(
                place,
                format!(
                    "orthogonal: unknown edge '{}': expected E1, E2, E3 or E4",
                    n.as_ref()
                ),
            )
        })?;
        orth[e.index()] = true;
    }
    Ok(orth)
}

/// The new edge functions of eq. [46] from the harmonic (s, t) on grid `g`: s along E3/E4,
/// t along E1/E2. They must increase strictly along each edge. The discrete harmonic solution
/// can fall back by round-off-sized amounts over a few nodes where the step-1 grid is very
/// skewed (a corner with 1e-5 spacing next to a deep concave wall); such short runs (at most
/// [`MAX_DISORDER`] out of order) are bridged by interpolation in arclength (`monotone`),
/// longer or deeper ones are errors.
pub fn edge_functions<const D: usize>(
    g: &Grid2<D>,
    s: &[f64],
    t: &[f64],
    place: &str,
) -> Result<EdgeFunctions> {
    let mut out: Vec<Vec<f64>> = Vec::with_capacity(4);
    for (e, f) in [(Edge::E1, t), (Edge::E2, t), (Edge::E3, s), (Edge::E4, s)] {
        let (mut v, arc) = along_edge(g, e, f);
        if let Err(k) = monotone(&mut v, &arc) {
            return Err(Error::input(
                format!("{place}, edge {e}"),
                format!(
                    "the harmonic solution of the orthogonality step does not increase along \
                     the edge (nodes {k}, {}): refine the grid near this edge",
                    k + 1
                ),
            ));
        }
        out.push(v);
    }
    let [t_e1, t_e2, s_e3, s_e4]: [Vec<f64>; 4] = out.try_into().expect("four edges");
    Ok(EdgeFunctions {
        s_e3,
        s_e4,
        t_e1,
        t_e2,
    })
}

/// How far (relative to the range of the edge function) a node of a harmonic edge function
/// may fall out of order and still be bridged: round-off, not a wrong solution.
pub const MAX_DISORDER: f64 = 1e-6;

/// The values of `f` (one per node of `g`) along edge `e` of `g`, and the edge's cumulative
/// chord length at its nodes.
pub(crate) fn along_edge<const D: usize>(g: &Grid2<D>, e: Edge, f: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let (ni, nj) = (g.ni(), g.nj());
    let v = match e {
        Edge::E1 => (0..nj).map(|j| f[g.idx(0, j)]).collect(),
        Edge::E2 => (0..nj).map(|j| f[g.idx(ni - 1, j)]).collect(),
        Edge::E3 => (0..ni).map(|i| f[g.idx(i, 0)]).collect(),
        Edge::E4 => (0..ni).map(|i| f[g.idx(i, nj - 1)]).collect(),
    };
    (v, chord_length(&g.edge(e)))
}

/// Makes `v` strictly increasing from its first to its last value: an interior node is kept
/// if it lies above the last kept node and below the last value; runs of other nodes are
/// bridged by linear interpolation in arclength `arc` between the kept nodes around them.
/// Runs longer than an eighth of the edge (at least 3 nodes), and nodes out of order by more
/// than [`MAX_DISORDER`] of the range, are refused: `Err(k)` names the node pair (k, k + 1)
/// where such a run starts (as does a last value not above the first).
pub(crate) fn monotone(v: &mut [f64], arc: &[f64]) -> std::result::Result<(), usize> {
    let n = v.len();
    let (first, last) = (v[0], v[n - 1]);
    if last.partial_cmp(&first) != Some(std::cmp::Ordering::Greater) {
        return Err(0);
    }
    let limit = (n / 8).max(3);
    let mut lo = 0;
    for k in 1..n {
        let keep = k == n - 1 || (v[k] > v[lo] && v[k] < last);
        if !keep {
            // out of order by this much: round-off only
            let by = if v[k] <= v[lo] {
                v[lo] - v[k]
            } else {
                v[k] - last
            };
            let small = by.partial_cmp(&(MAX_DISORDER * (last - first)));
            if !small.is_some_and(|o| o.is_le()) {
                return Err(lo);
            }
            continue;
        }
        if k - lo - 1 > limit || arc[k].partial_cmp(&arc[lo]) != Some(std::cmp::Ordering::Greater) {
            return Err(lo);
        }
        for m in lo + 1..k {
            v[m] = v[lo] + (v[k] - v[lo]) * (arc[m] - arc[lo]) / (arc[k] - arc[lo]);
        }
        lo = k;
    }
    Ok(())
}

#[cfg(test)]
mod monotone_tests {
    use super::monotone;

    #[test]
    fn short_dips_are_bridged_and_long_ones_refused() {
        let arc: Vec<f64> = (0..17).map(|k| k as f64).collect();
        let mut v: Vec<f64> = (0..17).map(|k| k as f64 / 16.0).collect();
        v[5] = v[4] - 1e-9; // a dip of two nodes
        v[6] = v[4];
        monotone(&mut v, &arc).unwrap();
        assert!(v.windows(2).all(|w| w[1] > w[0]));
        assert!((v[5] - 5.0 / 16.0).abs() < 1e-12 && (v[6] - 6.0 / 16.0).abs() < 1e-12);
        // An overshoot of the end value next to the end is bridged too.
        let mut over: Vec<f64> = (0..17).map(|k| k as f64 / 16.0).collect();
        over[15] = 1.0 + 1e-8;
        monotone(&mut over, &arc).unwrap();
        assert!(over.windows(2).all(|w| w[1] > w[0]));
        // A dip beyond round-off (1e-4 of the range) is a wrong solution, not bridged.
        let mut deep: Vec<f64> = (0..17).map(|k| k as f64 / 16.0).collect();
        deep[5] = deep[4] - 1e-4;
        assert_eq!(monotone(&mut deep, &arc), Err(4));
        let mut flat = vec![0.0; 17];
        flat[16] = 1.0;
        assert_eq!(monotone(&mut flat, &arc), Err(0));
    }
}

/// The three steps of Section 2.4 with full diagnostics (see the module docs). `orthogonal`
/// flags E1, E2, E3, E4; with no flag set this is step 1 alone.
pub fn orthogonal_steps<const D: usize>(
    b: &Boundary2<D>,
    orthogonal: [bool; 4],
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<OrthogonalResult<D>> {
    steps(b, None, orthogonal, solver, params, place)
}

/// The three steps, step 1 from `start` (transfinite if None).
pub(crate) fn steps<const D: usize>(
    b: &Boundary2<D>,
    start: Option<Grid2<D>>,
    orthogonal: [bool; 4],
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<OrthogonalResult<D>> {
    let t0 = std::time::Instant::now();
    let nested = start.is_none() && params.nested_for(solver.name());
    let step1 = grid_block(b, start, ControlKind::Algebraic, solver, params, place)?;
    if !orthogonal.contains(&true) {
        let edge_functions = EdgeFunctions::arclength(b);
        return Ok(OrthogonalResult {
            grid: step1.grid,
            picard: step1.picard,
            params: straight_line(&edge_functions),
            edge_functions,
        });
    }
    let (s, t) = harmonic_st(&step1.grid, orthogonal, solver, place)?;
    let ef = edge_functions(&step1.grid, &s, &t, place)?;
    let pg = hermite_blend(&ef, orthogonal, place)?;
    let (grid, mut picard) = if nested {
        let (r, _) =
            nested::solve_nested_from(b, step1.grid, pg.clone(), solver, params, place, t0)?;
        (r.grid, r.picard)
    } else {
        let ctrl = Control2::from_algebraic(&pg);
        poisson2d::solve_from(b, step1.grid, &ctrl, solver, params, place)?
    };
    picard.first = Some(Box::new(step1.picard));
    Ok(OrthogonalResult {
        grid,
        picard,
        edge_functions: ef,
        params: pg,
    })
}

/// Grids one block with orthogonality at the flagged edges (E1, E2, E3, E4), Section 2.4:
/// the final grid and the Picard history of step 3 (see [`orthogonal_steps`] for more).
pub fn grid_block_orthogonal<const D: usize>(
    b: &Boundary2<D>,
    orthogonal: [bool; 4],
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<BlockResult<D>> {
    let r = orthogonal_steps(b, orthogonal, solver, params, place)?;
    Ok(BlockResult {
        grid: r.grid,
        picard: r.picard,
    })
}

/// Grids one block with `kind` control functions, or by the three steps of Section 2.4 if
/// any edge is flagged in `orthogonal` (E1, E2, E3, E4): the entry point of case files and
/// `ellipgrid smooth`.
///
/// # Errors
/// [`Error::Input`] for orthogonality with Laplace control functions (the blend needs the
/// algebraic ones), and the errors of the steps.
pub fn grid_block_with<const D: usize>(
    b: &Boundary2<D>,
    start: Option<Grid2<D>>,
    orthogonal: [bool; 4],
    kind: ControlKind,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<BlockResult<D>> {
    let sides = Sides {
        orthogonal,
        wall: [false; 4],
    };
    grid_block_sides(b, start, sides, kind, solver, params, place)
}

/// What a block asks of its sides: orthogonality (Section 2.4) and a held wall spacing
/// ([`crate::elliptic::wall2d`]), flags for E1, E2, E3, E4.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sides {
    pub orthogonal: [bool; 4],
    pub wall: [bool; 4],
}

/// [`grid_block_with`], then the wall spacing held at the `sides.wall` edges
/// ([`crate::elliptic::wall2d`]); the history is that of all solves after step 1.
///
/// # Errors
/// As [`grid_block_with`]; a wall spacing with Laplace control functions.
pub fn grid_block_sides<const D: usize>(
    b: &Boundary2<D>,
    start: Option<Grid2<D>>,
    sides: Sides,
    kind: ControlKind,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<BlockResult<D>> {
    let (orthogonal, walls) = (sides.orthogonal, sides.wall);
    if !orthogonal.contains(&true) && !walls.contains(&true) {
        return grid_block(b, start, kind, solver, params, place);
    }
    let walls: Vec<WallSide> = Edge::ALL
        .into_iter()
        .filter(|e| walls[e.index()])
        .map(WallSide::whole)
        .collect();
    grid_block_walls(b, start, orthogonal, &walls, kind, solver, params, place)
}

/// [`grid_block_sides`] with wall sides that may be chains of wall and non-wall edges
/// ([`WallSide`]): the three steps of Section 2.4 (from `start`, transfinite if None), then
/// the wall passes ([`crate::elliptic::wall2d`]).
///
/// # Errors
/// A wall spacing with Laplace control functions, and the errors of the solves.
#[allow(clippy::too_many_arguments)]
pub fn grid_block_walls<const D: usize>(
    b: &Boundary2<D>,
    start: Option<Grid2<D>>,
    orthogonal: [bool; 4],
    walls: &[WallSide],
    kind: ControlKind,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<BlockResult<D>> {
    if kind != ControlKind::Algebraic {
        return Err(Error::input(
            place,
            "orthogonal edges and wall spacings need the algebraic control functions \
             (control = \"algebraic\")",
        ));
    }
    let r = steps(b, start, orthogonal, solver, params, place)?;
    let (grid, held) = hold_wall_spacing_on(r.grid, r.params, walls, solver, params, place)?;
    let mut picard = r.picard;
    if let Some(h) = held {
        picard.append(h);
    }
    Ok(BlockResult { grid, picard })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::direct::DirectLu;

    #[test]
    fn edge_names_parse_and_unknown_names_are_errors() {
        assert_eq!(
            parse_edges(&["E3", "e1"], "b").unwrap(),
            [true, false, true, false]
        );
        let m = parse_edges(&["E5"], "case: block 'w'")
            .unwrap_err()
            .to_string();
        assert!(m.contains("block 'w'") && m.contains("'E5'"), "{m}");
    }

    #[test]
    fn a_rectangle_is_already_orthogonal_and_stays_the_same_grid() {
        // Equal opposite distributions: the straight-line grid is the tensor product, which
        // is orthogonal; the harmonic edge functions equal the arclength ones and step 3
        // reproduces it.
        let xs: Vec<f64> = (0..11).map(|k| 2.0 * (k as f64 / 10.0).powf(1.3)).collect();
        let ys: Vec<f64> = (0..9).map(|k| (k as f64 / 8.0).powi(2)).collect();
        let exact = Grid2::<2>::from_fn(11, 9, |i, j| [xs[i], ys[j]]);
        let b = Boundary2::from_grid(&exact, "r").unwrap();
        let r = orthogonal_steps(
            &b,
            [true; 4],
            &mut DirectLu::new(),
            &PicardParams::default(),
            "r",
        )
        .unwrap();
        assert!(r.picard.converged);
        // step 1's history travels with step 3's
        let first = r.picard.first.as_deref().expect("step 1's history");
        assert!(first.converged && first.steps > 0 && first.first.is_none());
        for c in 0..2 {
            for (u, v) in r.grid.coord(c).iter().zip(exact.coord(c)) {
                assert!((u - v).abs() < 1e-10, "{u} vs {v}");
            }
        }
    }
}
