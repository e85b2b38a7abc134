//! Prescribed wall spacing along edges of a 2D block (case key `wall`): the 2D counterpart of
//! [`crate::elliptic::wall`], beyond the paper.
//!
//! The edge distributions set the first spacing off a wall only at the two edges that leave it:
//! in between, the first cell height is t₁ |∂X/∂t|, with t₁ the blended parameter step of the
//! algebraic map (the straight-line map [39, 40] or the Hermite blend of Section 2.4, [47]–[49])
//! and X the elliptic map, whose |∂X/∂t| varies along a curved wall. On the RAE2822 C-grid (1e-5
//! chord at both cuts leaving the airfoil) the heights came out 4.7e-6 … 4.2e-5.
//!
//! The fix is the volume blocks' one: keep the composite map x = X(S(ξ)) and change only S in the
//! interior. Each column of nodes leaving the wall gets goal distances d*^ψ d₀^{1−ψ}: d* the
//! side edges' distance-from-wall profiles interpolated geometrically by arclength along the
//! wall (spacings that differ by orders of magnitude, as along a wake, interpolate evenly in
//! their logarithm), d₀ the uncorrected grid's distances, and ψ a half cosine in the node index,
//! 1 and flat at the wall (the first cells keep the side edges' growth) and 0 at [`FADE`] of the
//! column. (The volumes fade in the wall-normal parameter instead,
//! [`crate::elliptic::wall::BLEND_POWER`]; with their former ψ = (1 − v)³ on the RAE2822
//! C-grid that carried the correction far out and bent the lines across the trailing-edge cuts
//! by 11° on average.) Each pass remaps v ← v d_goal / d along every interior column, recomputes
//! the control functions [19] of the remapped parameters and re-solves [24] from the current
//! grid, until every node is within 1 % ([`TOLERANCE`]); two passes on the RAE2822 airfoil
//! blocks. A pass whose solve fails or folds the grid is halved, then dropped.
//!
//! A side may also be a chain of wall and non-wall edges (an airfoil and its wake line,
//! [`WallSide`]): the wall's ends inside the side are anchors too, with the first spacing the
//! topology gives there, and along the non-wall part the correction fades out. Walls on
//! opposite sides share their columns: each corrects the half next to it.

use crate::algebraic::control2d::Control2;
use crate::algebraic::transform::ParamGrid;
use crate::elliptic::picard::{append, PicardInfo, PicardParams};
use crate::elliptic::poisson2d;
use crate::elliptic::wall::remap_column;
use crate::grid::{Edge, Grid2};
use crate::quality::quality_any;
use crate::solve::LinearSolver;
use crate::{Error, Result};
use serde::Serialize;

mod periodic;
mod targets;
pub use periodic::{hold_wall_spacing_periodic, wall_spacing_periodic};
use targets::{blend_targets, Targets};
pub use targets::{WallPart, WallSide};

/// Correction passes at most (each a re-solve from the current grid).
pub const MAX_PASSES: usize = 12;
/// Halvings of a pass's parameter change when its solve fails or folds the grid.
const DAMPINGS: usize = 3;
/// Passes stop once every column node's |ln(goal / distance)| is below this (first spacings
/// within 1 %; 2D passes are cheap, so tighter than the volumes' 5 %).
pub const TOLERANCE: f64 = 0.01;
/// Picard tolerance of the intermediate solves (relative to the block's diameter): the
/// passes remap from these grids, so the final grid is defined to about this tolerance. 2D
/// solves converge in few Newton steps, so tighter than the volumes'
/// ([`crate::elliptic::wall::LOOSE_TOLERANCE`]: the same RAE2822 grid, 18–19 steps either way).
pub const LOOSE_TOLERANCE: f64 = 1e-8;
/// Share of a column (in nodes from the wall) over which the correction fades out: on the
/// RAE2822 C-grid 0.75 keeps the growth ratio off the wall at 1.21 (1.21 uncorrected; 1.28 at
/// 0.5, 1.31 at 0.35) with kinks across the trailing-edge cuts of 1.9° mean (1.4° at 0.5).
pub const FADE: f64 = 0.75;

/// The first spacing achieved along one wall edge of a block.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WallSpacing2 {
    /// "E1" … "E4".
    pub edge: String,
    /// Interior wall nodes measured (the two end nodes lie on the side edges, which set the
    /// targets).
    pub nodes: usize,
    /// Smallest and largest first spacing (length of the first grid line off the wall).
    pub first_min: f64,
    pub first_max: f64,
    /// Smallest and largest ratio of the first spacing to its target.
    pub ratio_min: f64,
    pub ratio_max: f64,
}

/// The columns of nodes leaving wall edge `edge` of an `ni × nj` grid: column `c` runs along the
/// wall (0 and the last are the side edges), `j` away from it.
#[derive(Clone, Copy, Debug)]
struct Columns {
    edge: Edge,
    ni: usize,
    nj: usize,
}

impl Columns {
    /// Columns (nodes along the wall).
    fn count(&self) -> usize {
        if self.edge.runs_along_i() {
            self.ni
        } else {
            self.nj
        }
    }

    /// Nodes per column.
    fn depth(&self) -> usize {
        if self.edge.runs_along_i() {
            self.nj
        } else {
            self.ni
        }
    }

    /// Grid node (i, j) of column `c`, `j` nodes off the wall.
    fn node(&self, c: usize, j: usize) -> (usize, usize) {
        match self.edge {
            Edge::E1 => (j, c),
            Edge::E2 => (self.ni - 1 - j, c),
            Edge::E3 => (c, j),
            Edge::E4 => (c, self.nj - 1 - j),
        }
    }

    /// The wall-normal parameter of node `(i, j)`: 0 at the wall, 1 at the opposite edge.
    fn param(&self, pg: &ParamGrid, p: usize) -> f64 {
        match self.edge {
            Edge::E1 => pg.s[p],
            Edge::E2 => 1.0 - pg.s[p],
            Edge::E3 => pg.t[p],
            Edge::E4 => 1.0 - pg.t[p],
        }
    }

    fn set_param(&self, pg: &mut ParamGrid, p: usize, v: f64) {
        match self.edge {
            Edge::E1 => pg.s[p] = v,
            Edge::E2 => pg.s[p] = 1.0 - v,
            Edge::E3 => pg.t[p] = v,
            Edge::E4 => pg.t[p] = 1.0 - v,
        }
    }
}

fn dist<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    (0..D).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt()
}

/// Distances of the nodes of column `c` from its wall node.
fn column_distances<const D: usize>(g: &Grid2<D>, cols: &Columns, c: usize) -> Vec<f64> {
    let (i0, j0) = cols.node(c, 0);
    let p0 = g.point(i0, j0);
    (0..cols.depth())
        .map(|j| {
            let (i, jj) = cols.node(c, j);
            dist(g.point(i, jj), p0)
        })
        .collect()
}

/// One pass over the interior columns of one wall: remaps the wall-normal parameter of `pg`
/// from the distances in `x` towards the column goals (filled from the first grid seen, the
/// uncorrected one, if empty; columns of strength 0 are left alone). Returns the largest
/// |ln(goal / d)| before the pass.
fn remap_wall<const D: usize>(
    pg: &mut ParamGrid,
    x: &Grid2<D>,
    cols: &Columns,
    targets: &Targets,
    goals: &mut Vec<Vec<f64>>,
    fade: f64,
    half: bool,
) -> f64 {
    // with an opposite wall only the half of each column next to this one moves
    let last = if half {
        (cols.depth() - 1) / 2
    } else {
        cols.depth() - 1
    };
    let mut err = 0.0f64;
    for c in 1..cols.count() - 1 {
        let strength = targets.strength(c);
        if goals.len() < c {
            let d = column_distances(x, cols, c);
            let t: Vec<f64> = (0..cols.depth()).map(|j| targets.at(c, j)).collect();
            goals.push(if strength > 0.0 {
                blend_targets(&d, &t, strength, fade)
            } else {
                Vec::new()
            });
        }
        if goals[c - 1].is_empty() {
            continue;
        }
        let idx: Vec<usize> = (0..cols.depth())
            .map(|j| {
                let (i, jj) = cols.node(c, j);
                x.idx(i, jj)
            })
            .collect();
        let d = column_distances(x, cols, c);
        let mut v: Vec<f64> = idx.iter().map(|&p| cols.param(pg, p)).collect();
        let k = last + 1;
        err = err.max(remap_column(&mut v[..k], &d[..k], &goals[c - 1][..k]));
        for (&p, y) in idx.iter().zip(&v) {
            cols.set_param(pg, p, *y);
        }
    }
    err
}

/// Holds the first spacing off every flagged wall edge (`walls`: E1, E2, E3, E4) of the grid
/// `x` of boundary data fixed in it, solved with the control functions of `pg` (module docs).
/// Returns the corrected grid and the Picard history of its solves (None if no pass was
/// needed: `x` is returned as it came).
///
/// # Errors
/// [`Error::Input`] for a grid of fewer than 3 × 3 nodes, and the errors of the final solve.
pub fn hold_wall_spacing<const D: usize>(
    x: Grid2<D>,
    pg: ParamGrid,
    walls: [bool; 4],
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<(Grid2<D>, Option<PicardInfo>)> {
    let sides: Vec<WallSide> = Edge::ALL
        .into_iter()
        .filter(|e| walls[e.index()])
        .map(WallSide::whole)
        .collect();
    hold_wall_spacing_on(x, pg, &sides, solver, params, place)
}

/// [`hold_wall_spacing`] along wall sides that may be chains of wall and non-wall edges
/// ([`WallSide`], whose docs say how the goals are made along the non-wall parts).
///
/// # Errors
/// As [`hold_wall_spacing`]; [`Error::Input`] for a wall part outside its side.
pub fn hold_wall_spacing_on<const D: usize>(
    x: Grid2<D>,
    pg: ParamGrid,
    sides: &[WallSide],
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<(Grid2<D>, Option<PicardInfo>)> {
    let (ni, nj) = (x.ni(), x.nj());
    let cols: Vec<Columns> = sides
        .iter()
        .map(|s| Columns {
            edge: s.edge,
            ni,
            nj,
        })
        .collect();
    if cols.is_empty() {
        return Ok((x, None));
    }
    if ni < 3 || nj < 3 {
        return Err(Error::input(
            place,
            "a wall spacing needs at least 3 × 3 nodes (interior columns to hold it on)",
        ));
    }
    for (s, c) in sides.iter().zip(&cols) {
        check_part(s, c.count(), place)?;
    }
    // Opposite walls (a slot between two walls) share their columns: each corrects the half
    // next to it and fades out by the middle.
    let opposite: Vec<bool> = sides
        .iter()
        .map(|s| sides.iter().any(|o| o.edge.index() == s.edge.index() ^ 1))
        .collect();
    let fades: Vec<f64> = sides
        .iter()
        .zip(&opposite)
        .map(|(s, &o)| if o { s.fade.min(0.5) } else { s.fade })
        .collect();
    let targets: Vec<Targets> = sides
        .iter()
        .zip(&cols)
        .zip(&fades)
        .map(|((s, c), &f)| Targets::new(&x, c, s.part.as_ref(), f))
        .collect();
    let mut goals: Vec<Vec<Vec<f64>>> = vec![Vec::new(); cols.len()];
    let remap = |trial: &mut ParamGrid, x: &Grid2<D>| {
        cols.iter()
            .zip(&targets)
            .zip(&mut goals)
            .zip(opposite.iter().zip(&fades))
            .map(|(((c, t), g), (&o, &f))| remap_wall(trial, x, c, t, g, f, o))
            .fold(0.0, f64::max)
    };
    let solve = |x: &mut Grid2<D>, pg: &ParamGrid, p: &PicardParams| {
        let ctrl = Control2::from_algebraic(pg);
        if !ctrl.all_finite() {
            return Err(Error::input(
                place,
                "wall pass: control functions not finite",
            ));
        }
        poisson2d::solve_timed(x, &ctrl, solver, p, 0.0, place).map(|(i, t)| (i, Some(t)))
    };
    passes(x, pg, remap, solve, params)
}

/// The correction passes of [`hold_wall_spacing_on`] and of the periodic blocks'
/// [`periodic::hold_wall_spacing_periodic`]: `remap` moves the wall-normal parameters of a
/// trial (returning the largest |ln(goal / d)| before it), `solve` re-solves [24] with the
/// trial's control functions (and the time of one residual evaluation, for the work units).
fn passes<const D: usize>(
    mut x: Grid2<D>,
    mut pg: ParamGrid,
    mut remap: impl FnMut(&mut ParamGrid, &Grid2<D>) -> f64,
    mut solve: impl FnMut(&mut Grid2<D>, &ParamGrid, &PicardParams) -> Result<(PicardInfo, Option<f64>)>,
    params: &PicardParams,
) -> Result<(Grid2<D>, Option<PicardInfo>)> {
    let loose = PicardParams {
        tolerance: params.tolerance.max(LOOSE_TOLERANCE),
        ..params.clone()
    };
    let folded_at_start = quality_any(&x).folded_cells > 0;
    let mut info: Option<PicardInfo> = None;
    // Work units of the passes: their time over the shortest residual evaluation measured.
    let t0 = std::time::Instant::now();
    let mut wu = f64::INFINITY;
    // The last kept pass's starting point and its error: a pass that leaves the spacings
    // further from their goals than before is undone and the passes stop (they oscillate
    // there: the NACA0012 one-block O-grid's trailing-edge base, 1.1e-2 → 6.1e-2).
    let mut last: Option<(f64, Grid2<D>, ParamGrid)> = None;
    for _ in 0..MAX_PASSES {
        let mut trial = pg.clone();
        let err = remap(&mut trial, &x);
        if err <= TOLERANCE {
            break;
        }
        if let Some((e0, x0, pg0)) = last.take() {
            if err > e0 {
                (x, pg) = (x0, pg0);
                break;
            }
        }
        // A pass whose solve fails or folds the grid is not kept: its parameter change is
        // halved (up to DAMPINGS times), then the passes stop.
        let before = x.clone();
        let mut kept = false;
        for _ in 0..=DAMPINGS {
            if let Ok((step, t)) = solve(&mut x, &trial, &loose) {
                wu = wu.min(t.unwrap_or(f64::NAN));
                append(&mut info, step);
                if folded_at_start || quality_any(&x).folded_cells == 0 {
                    kept = true;
                    break;
                }
            }
            x.clone_from(&before);
            for (new, old) in [(&mut trial.s, &pg.s), (&mut trial.t, &pg.t)] {
                for (a, b) in new.iter_mut().zip(old) {
                    *a = b + 0.5 * (*a - b);
                }
            }
        }
        if !kept {
            break;
        }
        last = Some((err, before, std::mem::replace(&mut pg, trial)));
    }
    if info.is_some() && params.tolerance < loose.tolerance {
        let (step, t) = solve(&mut x, &pg, params)?;
        wu = wu.min(t.unwrap_or(f64::NAN));
        append(&mut info, step);
    }
    if let Some(i) = &mut info {
        i.work_units = (wu > 0.0 && wu.is_finite()).then(|| t0.elapsed().as_secs_f64() / wu);
    }
    Ok((x, info))
}

/// The first spacing along wall edge `edge` of grid `g` against its targets (the side edges'
/// profiles interpolated by wall arclength), over the interior wall nodes.
pub fn wall_spacing<const D: usize>(g: &Grid2<D>, edge: Edge) -> WallSpacing2 {
    wall_spacing_on(g, &WallSide::whole(edge))
}

/// The first spacing along the wall part of side `side` of grid `g` against its targets, over
/// the wall nodes that are not block corners.
pub fn wall_spacing_on<const D: usize>(g: &Grid2<D>, side: &WallSide) -> WallSpacing2 {
    let cols = Columns {
        edge: side.edge,
        ni: g.ni(),
        nj: g.nj(),
    };
    let mut out = WallSpacing2 {
        edge: side.edge.to_string(),
        nodes: 0,
        first_min: f64::INFINITY,
        first_max: 0.0,
        ratio_min: f64::INFINITY,
        ratio_max: 0.0,
    };
    if cols.depth() < 2 || cols.count() < 2 || check_part(side, cols.count(), "").is_err() {
        return out;
    }
    let targets = Targets::new(g, &cols, side.part.as_ref(), side.fade);
    for c in (1..cols.count().saturating_sub(1)).filter(|&c| targets.on_wall(c)) {
        let (a, b) = (cols.node(c, 0), cols.node(c, 1));
        let h = dist(g.point(a.0, a.1), g.point(b.0, b.1));
        let r = h / targets.at(c, 1);
        out.nodes += 1;
        out.first_min = out.first_min.min(h);
        out.first_max = out.first_max.max(h);
        out.ratio_min = out.ratio_min.min(r);
        out.ratio_max = out.ratio_max.max(r);
    }
    out
}

/// [`wall_spacing`] for every flagged wall edge (E1, E2, E3, E4).
pub fn wall_spacings<const D: usize>(g: &Grid2<D>, walls: [bool; 4]) -> Vec<WallSpacing2> {
    Edge::ALL
        .into_iter()
        .filter(|e| walls[e.index()])
        .map(|e| wall_spacing(g, e))
        .collect()
}

/// A wall part's runs and ends must lie on its side of `n` nodes, runs ascending.
fn check_part(side: &WallSide, n: usize, place: &str) -> Result<()> {
    let Some(p) = &side.part else { return Ok(()) };
    let runs_ok = p.runs.iter().all(|r| r[0] < r[1] && r[1] < n)
        && p.runs.windows(2).all(|w| w[0][1] < w[1][0])
        && !p.runs.is_empty();
    let ends_ok = p
        .ends
        .iter()
        .all(|&(c, h)| c < n && h > 0.0 && h.is_finite());
    if runs_ok && ends_ok {
        Ok(())
    } else {
        Err(Error::input(
            place,
            format!(
                "side {}: wall runs {:?} and end spacings {:?} do not fit its {n} nodes",
                side.edge, p.runs, p.ends
            ),
        ))
    }
}

#[cfg(test)]
mod tests;
