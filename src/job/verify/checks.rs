//! The differences, observed orders and verdict of every block (see the parent module).

use super::runs::StartRun;
use super::{VerifyOptions, FLOOR, ORDER_MIN, START_LIMIT};
use crate::case::LoadedCase;
use crate::io::Block;
use crate::job::Generated;
use crate::quality::family::{self, observed_order, Difference};
use crate::{Error, Result};
use serde::Serialize;

/// Differences along a sequence of grids and their observed orders.
#[derive(Clone, Debug, Serialize)]
pub struct OrderCheck {
    /// Grid family: grid l against grid l + 1 at the common nodes; parametrization: the two
    /// grids of level l.
    pub differences: Vec<Difference>,
    /// log2 of the ratio of successive differences (rms), None where one is zero.
    pub order_rms: Vec<Option<f64>>,
    /// The same in the max norm (not judged: it sees the O(h) terms at corners).
    pub order_max: Vec<Option<f64>>,
    /// True if the last difference (rms) is below [`FLOOR`] times the tolerance: the grids
    /// agree to the solver's tolerance and there is no order to observe.
    pub at_tolerance: bool,
    pub pass: bool,
}

/// The grid from the scrambled start against the grid from the transfinite start.
#[derive(Clone, Debug, Serialize)]
pub struct StartCheck {
    /// Seed of the scrambled start.
    pub seed: u64,
    /// The blocks gridded together with this one (a row joined by floating edges).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub group: Vec<String>,
    /// Cells of the scrambled start and how many of them fold.
    pub start_cells: usize,
    pub start_folded: usize,
    /// Picard steps from the scrambled start, if the solve succeeded.
    pub picard_steps: Option<usize>,
    pub converged: bool,
    /// The difference of the two grids (None if the solve failed).
    pub difference: Option<Difference>,
    /// The largest max difference that passes: [`START_LIMIT`] × the tolerance (for a volume
    /// with a wall spacing: of its intermediate solves, if larger).
    pub limit: f64,
    /// Why the solve from the scrambled start failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
    pub pass: bool,
}

/// The verdict of one block.
#[derive(Clone, Debug, Serialize)]
pub struct BlockVerdict {
    pub name: String,
    /// "planar", "minimal", "surface" or "volume".
    pub kind: String,
    /// Nodes at every level.
    pub dims: Vec<[usize; 3]>,
    /// Bounding-box diagonal of the level-0 grid (differences are relative to it).
    pub diameter: f64,
    pub family: OrderCheck,
    /// Planar, minimal and volume blocks.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub start: Option<StartCheck>,
    /// Surface blocks.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub parametrization: Option<OrderCheck>,
    pub pass: bool,
    /// Why it fails (empty if it passes).
    pub reasons: Vec<String>,
}

fn coords(b: &Block) -> &[Vec<f64>] {
    match b {
        Block::Planar(g) => g.coords(),
        Block::Surface(g) => g.coords(),
        Block::Volume(g) => g.coords(),
    }
}

/// The orders of `differences` and the verdict on the last one.
fn order_check(differences: Vec<Difference>, floor: f64) -> OrderCheck {
    let orders = |f: fn(&Difference) -> f64| -> Vec<Option<f64>> {
        differences
            .windows(2)
            .map(|w| observed_order(f(&w[0]), f(&w[1])))
            .collect()
    };
    let (order_rms, order_max) = (orders(|d| d.rms), orders(|d| d.max));
    let at_tolerance = differences.last().is_some_and(|d| d.rms <= floor);
    let last = order_rms.last().copied().flatten();
    OrderCheck {
        pass: at_tolerance || last.is_some_and(|p| p >= ORDER_MIN),
        differences,
        order_rms,
        order_max,
        at_tolerance,
    }
}

/// A failed order check as a reason; `levels` names the grids of its last order.
fn order_reason(what: &str, c: &OrderCheck, levels: &str) -> String {
    match c.order_rms.last().copied().flatten() {
        Some(p) => format!("{what}: observed order {p:.2} (rms) < {ORDER_MIN} ({levels})"),
        None => format!("{what}: no order can be observed (a difference is zero, {levels})"),
    }
}

/// The difference of two grids of one block, or an error naming it (never expected: the runs
/// grid the same block with the same counts).
fn diff(a: &Block, b: &Block, diam: f64, nested: bool, place: &str) -> Result<Difference> {
    let d = if nested {
        family::nested_difference(coords(a), a.dims(), coords(b), b.dims(), diam)
    } else if a.dims() == b.dims() {
        family::difference(coords(a), coords(b), a.dims(), diam)
    } else {
        None
    };
    d.ok_or_else(|| {
        Error::input(
            place,
            format!(
                "grids of {:?} and {:?} nodes (diameter {diam}) cannot be compared",
                a.dims(),
                b.dims()
            ),
        )
    })
}

/// Convergence and folding of block b at one level: (converged, folded cells).
fn health(g: &Generated, b: usize) -> (bool, usize) {
    let nb = g.report.blocks.len();
    if b < nb {
        let r = &g.report.blocks[b];
        let conv = r.picard.as_ref().is_none_or(|p| p.converged);
        (conv, r.quality.folded_cells)
    } else {
        let v = &g.report.volumes[b - nb];
        (v.picard.converged, v.quality.folded_cells)
    }
}

/// The verdict of every block.
pub(super) fn verdicts(
    gens: &[&Generated],
    kinds: &[&str],
    warped: &[Vec<(usize, Block)>],
    starts: &[StartRun],
    opts: &VerifyOptions,
    case: &LoadedCase,
) -> Result<Vec<BlockVerdict>> {
    let tol = case.case.solver.picard.tolerance;
    let floor = FLOOR * tol;
    let mut out = Vec::new();
    for (b, (name, block0)) in gens[0].blocks.iter().enumerate() {
        let place = format!("{}: block '{name}'", case.path.display());
        let diam = family::diameter(coords(block0));
        let mut reasons = Vec::new();
        for (l, g) in gens.iter().enumerate() {
            let (conv, folded) = health(g, b);
            if folded > 0 {
                reasons.push(format!("level {l} folds ({folded} cells)"));
            }
            if !conv {
                reasons.push(format!("level {l}: the Picard iteration did not converge"));
            }
        }
        let grids: Vec<&Block> = gens.iter().map(|g| &g.blocks[b].1).collect();
        let diffs = grids
            .windows(2)
            .map(|w| diff(w[0], w[1], diam, true, &place))
            .collect::<Result<Vec<_>>>()?;
        let fam = order_check(diffs, floor);
        if !fam.pass {
            let k = gens.len();
            let at = format!("levels {}–{}", k - 3, k - 1);
            reasons.push(order_reason("grid family", &fam, &at));
        }
        let parametrization = if kinds[b] == "surface" {
            let mut d = Vec::new();
            for (l, w) in warped.iter().enumerate() {
                let Some((_, g)) = w.iter().find(|(k, _)| *k == b) else {
                    continue;
                };
                d.push(diff(grids[l], g, diam, false, &place)?);
            }
            let c = order_check(d, floor);
            if !c.pass {
                let k = c.differences.len();
                let at = format!("levels {} and {}", k.saturating_sub(2), k.saturating_sub(1));
                reasons.push(order_reason("parametrization", &c, &at));
            }
            Some(c)
        } else {
            None
        };
        let start = match starts.iter().find(|s| s.members.contains(&b)) {
            Some(s) => {
                let c = start_check(
                    s,
                    b,
                    block0,
                    diam,
                    opts.seed,
                    START_LIMIT * s.tolerance,
                    gens[0],
                )?;
                if !c.pass {
                    reasons.push(start_reason(&c));
                }
                Some(c)
            }
            None => None,
        };
        out.push(BlockVerdict {
            name: name.clone(),
            kind: kinds[b].to_string(),
            dims: grids.iter().map(|g| g.dims()).collect(),
            diameter: diam,
            family: fam,
            start,
            parametrization,
            pass: reasons.is_empty(),
            reasons,
        });
    }
    Ok(out)
}

/// The start check of block b from its unit's run.
fn start_check(
    s: &StartRun,
    b: usize,
    block0: &Block,
    diam: f64,
    seed: u64,
    limit: f64,
    g0: &Generated,
) -> Result<StartCheck> {
    let difference = match s.members.iter().position(|&m| m == b) {
        Some(i) if i < s.grids.len() => {
            Some(diff(block0, &s.grids[i], diam, false, "scrambled start")?)
        }
        _ => None,
    };
    let converged = s.picard.as_ref().is_some_and(|p| p.converged);
    let group: Vec<String> = if s.members.len() > 1 {
        s.members.iter().map(|&m| g0.blocks[m].0.clone()).collect()
    } else {
        Vec::new()
    };
    Ok(StartCheck {
        seed,
        group,
        start_cells: s.start_cells,
        start_folded: s.start_folded,
        picard_steps: s.picard.as_ref().map(|p| p.steps),
        converged,
        pass: converged && difference.is_some_and(|d| d.max <= limit),
        difference,
        limit,
        failure: s.failure.clone(),
    })
}

/// A failed start check as a reason.
fn start_reason(c: &StartCheck) -> String {
    match (&c.failure, c.difference) {
        (Some(f), _) => format!("start grid: the solve from the scrambled start failed: {f}"),
        (None, Some(d)) if c.converged => format!(
            "start grid: the grids from the transfinite and the scrambled start differ by \
             {:.2e} of the diameter at node {:?} (limit {:.1e})",
            d.max, d.at, c.limit
        ),
        _ => format!(
            "start grid: the Picard iteration from the scrambled start did not converge \
             ({} steps)",
            c.picard_steps.unwrap_or(0)
        ),
    }
}
