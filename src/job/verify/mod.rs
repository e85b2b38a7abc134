//! `ellipgrid verify`: checks on a user's own case that its grids have the properties the
//! method promises (METHOD.md §7): they converge at second order as the grid is refined, they
//! do not depend on the start grid, and surface grids do not depend on the surface's
//! parametrization.
//!
//! 1. **Grid family**: the case at N, 2N − 1, 4N − 3, … nodes per direction
//!    ([`LoadedCase::refined`]: boundary distributions refined in their own parameter, so the
//!    coarse nodes are every other node of the next grid), each generated as `run` does; the
//!    difference of each grid to the next at the common nodes (max and rms, relative to the
//!    block's diameter; [`crate::quality::family`]) and the observed order p = log2(e_h/e_{h/2}).
//! 2. **Start grid** (planar, minimal and volume blocks, on the case's own grid; a volume
//!    within the faces of its grid): the Picard iteration from a scrambled, folded start ([`crate::algebraic::scramble`], fixed seed) must
//!    end at the grid `run` gives (from the transfinite start) to the solver's tolerance.
//! 3. **Parametrization** (surface blocks, every level): the surface re-parametrized by a
//!    smooth random one-to-one warp of the unit square ([`ellipgrid_geometry::Warp`], fixed
//!    seed) is gridded again; the difference per level must shrink at second order.
//!
//! A block passes when every observed order (rms, of the finest pair of grids) is at least
//! [`ORDER_MIN`] — or the differences are already at the solver's tolerance ([`FLOOR`]) —, the
//! start-grid difference is within [`START_LIMIT`] times the tolerance, no grid folds and every
//! solve converged. The runs (levels, the warped surfaces, the scrambled start) go in parallel
//! when the memory estimate of [`crate::case::limits`] allows it for all of them at once.
//!
//! Files: this one (options, report, the run), `runs` (the grids of each run), `checks` (the
//! differences, orders and verdicts).

mod checks;
mod runs;

use crate::case::{limits, BlockKind, LoadedCase};
use crate::io::Block;
use crate::job::Generated;
use crate::{Error, Result};
use checks::BlockVerdict;
use rayon::prelude::*;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// Observed orders (rms) below this fail a grid family or a parametrization check.
pub const ORDER_MIN: f64 = 1.8;

/// Differences (rms, relative to the diameter) below this many times the solver's tolerance
/// are at the tolerance: the grid is reproduced exactly, and there is no order to observe.
pub const FLOOR: f64 = 100.0;

/// The grids from the transfinite and the scrambled start must agree to this many times the
/// Picard tolerance (max norm, relative to the diameter): each is converged to the tolerance
/// by the a-posteriori estimate of [`crate::elliptic::picard`], which is not a bound. (A
/// block or volume with a wall spacing is defined only to the tolerance of its intermediate solves,
/// [`crate::elliptic::wall::LOOSE_TOLERANCE`], 2D [`crate::elliptic::wall2d::LOOSE_TOLERANCE`], if
/// that is larger.)
pub const START_LIMIT: f64 = 10.0;

/// The seed of the warps and scrambled starts unless one is given.
pub const DEFAULT_SEED: u64 = 20;

/// Strength of the parametrization warp: its factors stretch by 1 ± this
/// ([`ellipgrid_geometry::Warp::new`]).
pub const WARP_STRENGTH: f64 = 0.5;

/// Which grid of a surface block is verified.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceGrid {
    /// The Section 4 grid (Laplace–Beltrami and inversion), what `run` writes.
    #[default]
    Section4,
    /// The initial grid x^I of Section 4 (the straight-line grid in (u, v) mapped onto the
    /// surface), which depends on the parametrization: `verify` must fail it (a check of the
    /// checker).
    Initial,
}

/// What `verify` does.
#[derive(Clone, Debug)]
pub struct VerifyOptions {
    /// Grids in the family (at least 3): N, 2N − 1, 4N − 3, …
    pub levels: usize,
    /// Seed of the parametrization warp and of the scrambled start.
    pub seed: u64,
    /// The grid of surface blocks.
    pub surface_grid: SurfaceGrid,
    /// Run the levels in parallel when memory allows (false: one after the other).
    pub parallel: bool,
}

impl Default for VerifyOptions {
    fn default() -> Self {
        VerifyOptions {
            levels: 3,
            seed: DEFAULT_SEED,
            surface_grid: SurfaceGrid::Section4,
            parallel: true,
        }
    }
}

/// One grid of the family.
#[derive(Clone, Debug, Serialize)]
pub struct LevelReport {
    pub level: usize,
    /// Nodes of every block (ni, nj, nk), in block order.
    pub dims: Vec<[usize; 3]>,
    /// Wall-clock seconds of its generation.
    pub seconds: f64,
}

/// The report of `verify` (what `--report` writes as JSON).
#[derive(Clone, Debug, Serialize)]
pub struct VerifyReport {
    pub case: String,
    pub levels: Vec<LevelReport>,
    /// Seed of the parametrization warp and of the scrambled starts.
    pub seed: u64,
    pub surface_grid: SurfaceGrid,
    /// The Picard tolerance of the case (relative to the diameter).
    pub tolerance: f64,
    /// True if the runs went in parallel.
    pub parallel: bool,
    pub blocks: Vec<BlockVerdict>,
    /// True if every block passes.
    pub pass: bool,
    /// Wall-clock seconds of the whole verification.
    pub seconds: f64,
    /// Family files written (`--write-family`).
    pub family: Vec<String>,
    /// Why no family was written although asked for (a grid folds).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub family_note: Option<String>,
}

impl VerifyReport {
    /// The first failing block as an error (exit code 5), naming the block and the property.
    pub fn failure(&self) -> Option<Error> {
        let b = self.blocks.iter().find(|b| !b.pass)?;
        Some(Error::Property {
            place: format!("{}: block '{}'", self.case, b.name),
            msg: b.reasons.join("; "),
        })
    }
}

/// Where to write the family (`--write-family DIR`): `DIR/<stem>_L<level>.<ext>` for every
/// extension (an OpenFOAM mesh: `DIR/<stem>_L<level>/polyMesh`).
#[derive(Clone, Debug)]
pub struct FamilyOutput {
    pub dir: PathBuf,
    /// Extensions without the dot ("x", "vts", "cgns", "polyMesh", …).
    pub formats: Vec<String>,
}

impl FamilyOutput {
    /// The files of level `level` of case `stem`.
    pub fn paths(&self, stem: &str, level: usize) -> Vec<PathBuf> {
        self.formats
            .iter()
            .map(|ext| {
                if ext == "polyMesh" {
                    self.dir.join(format!("{stem}_L{level}")).join("polyMesh")
                } else {
                    self.dir.join(format!("{stem}_L{level}.{ext}"))
                }
            })
            .collect()
    }
}

/// The kind of every block of the generated order (2D blocks, then volumes).
fn kinds(case: &LoadedCase) -> Vec<&'static str> {
    let kind = |k: BlockKind| match k {
        BlockKind::Planar => "planar",
        BlockKind::Minimal => "minimal",
        BlockKind::Surface => "surface",
    };
    let mut out: Vec<&'static str> = case.case.blocks.iter().map(|b| kind(b.kind)).collect();
    out.extend(case.case.volumes.iter().map(|_| "volume"));
    out
}

/// The node counts of every volume of a case (from its volume topology or its tables).
fn volume_dims(c: &LoadedCase) -> Result<Vec<[usize; 3]>> {
    match &c.topology3 {
        Some(t) => Ok(t.volumes.iter().map(|v| v.dims).collect()),
        None => (0..c.case.volumes.len())
            .map(|k| c.case.volumes[k].dims(&crate::case::volume::volume_place(c, k)))
            .collect(),
    }
}

/// Whether all runs fit in memory at once (parallel), one at a time (sequential), or not at
/// all (an error naming the case and both figures).
fn plan(cases: &[LoadedCase], runs: usize, want_parallel: bool) -> Result<bool> {
    let mut all = limits::Budget::default();
    let place = cases[0].path.display().to_string();
    for c in cases {
        for k in 0..c.case.blocks.len() {
            let d = c.block_dims(k);
            all.add(&place, &d, limits::BYTES_PER_NODE_2D)?;
        }
        for d in volume_dims(c)? {
            all.add(&place, &d, limits::BYTES_PER_NODE_3D)?;
        }
    }
    let Some(avail) = limits::available_memory() else {
        return Ok(want_parallel);
    };
    // every grid of every level is kept (twice with the warped surfaces) until the end
    let kept = all.nodes.saturating_mul(2 * limits::KEPT_BYTES_PER_NODE);
    let threads = rayon::current_num_threads().min(runs).max(1) as u64;
    let parallel = all.largest.saturating_mul(threads).saturating_add(kept);
    if want_parallel && parallel <= avail {
        return Ok(true);
    }
    let one = all.largest.saturating_add(kept);
    if one > avail {
        return Err(Error::input(
            place,
            format!(
                "verifying {} levels needs ~{:.3} GB, the machine has {:.3} GB available \
                 (fewer --levels, or set {} to override)",
                cases.len(),
                one as f64 / 1e9,
                avail as f64 / 1e9,
                limits::MEMORY_VAR
            ),
        ));
    }
    Ok(false)
}

/// Verifies every block of `case` (module docs). Bad input is an error; a property that fails
/// is not (the report says which; [`VerifyReport::failure`]). With `family`, the grids of
/// every level are written (all or nothing; not if a grid folds: the report says so).
pub fn verify(
    case: &LoadedCase,
    opts: &VerifyOptions,
    family: Option<&FamilyOutput>,
) -> Result<VerifyReport> {
    let t0 = Instant::now();
    let place = case.path.display().to_string();
    if !(3..=8).contains(&opts.levels) {
        return Err(Error::input(
            "--levels",
            format!(
                "{} levels: a family needs 3 grids for an observed order, and at most 8",
                opts.levels
            ),
        ));
    }
    if let Some(f) = family {
        // bad names first, before the work
        for p in (0..opts.levels).flat_map(|l| f.paths(&stem(case), l)) {
            crate::job::output_kind(&p)?;
        }
    }
    let cases = (0..opts.levels)
        .map(|l| case.refined(l as u32))
        .collect::<Result<Vec<_>>>()?;
    let kinds = kinds(case);
    let mut tasks: Vec<runs::Task> = (0..opts.levels).map(runs::Task::Family).collect();
    if kinds.contains(&"surface") {
        tasks.extend((0..opts.levels).map(runs::Task::Warped));
    }
    let parallel = plan(&cases, tasks.len(), opts.parallel)?;
    let run = |t: &runs::Task| {
        let t1 = Instant::now();
        runs::run(*t, &cases, opts).map(|o| (o, t1.elapsed().as_secs_f64()))
    };
    let done: Vec<Result<(runs::Output, f64)>> = if parallel {
        tasks.par_iter().map(run).collect()
    } else {
        tasks.iter().map(run).collect()
    };
    let mut levels: Vec<Option<(Generated, f64)>> = (0..opts.levels).map(|_| None).collect();
    let mut warped: Vec<Vec<(usize, Block)>> = vec![Vec::new(); opts.levels];
    let mut starts = Vec::new();
    for (t, r) in tasks.iter().zip(done) {
        let (out, seconds) = r?;
        match (t, out) {
            (runs::Task::Family(l), runs::Output::Family(g, s)) => {
                levels[*l] = Some((*g, seconds));
                if *l == 0 {
                    starts = s;
                }
            }
            (runs::Task::Warped(l), runs::Output::Warped(w)) => warped[*l] = w,
            _ => unreachable!("every task gives its own output"),
        }
    }
    let levels: Vec<(Generated, f64)> = levels
        .into_iter()
        .map(|l| l.expect("every level ran"))
        .collect();
    let gens: Vec<&Generated> = levels.iter().map(|(g, _)| g).collect();
    let blocks = checks::verdicts(&gens, &kinds, &warped, &starts, opts, case)?;
    let pass = blocks.iter().all(|b| b.pass);
    let mut written = Vec::new();
    let folds = gens.iter().position(|g| g.report.fold_error().is_some());
    let family_note = match (family, folds) {
        (Some(_), Some(l)) => Some(format!("no family written: level {l} folds")),
        (Some(f), None) => {
            written = write_family(case, &gens, f)?;
            None
        }
        (None, _) => None,
    };
    Ok(VerifyReport {
        case: place,
        levels: levels
            .iter()
            .enumerate()
            .map(|(l, (g, s))| LevelReport {
                level: l,
                dims: g.blocks.iter().map(|(_, b)| b.dims()).collect(),
                seconds: *s,
            })
            .collect(),
        seed: opts.seed,
        surface_grid: opts.surface_grid,
        tolerance: case.case.solver.picard.tolerance,
        parallel,
        blocks,
        pass,
        seconds: t0.elapsed().as_secs_f64(),
        family: written.iter().map(|p| p.display().to_string()).collect(),
        family_note,
    })
}

/// The file name stem of the case (the family's file names start with it).
fn stem(case: &LoadedCase) -> String {
    case.path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("grid")
        .to_string()
}

/// Writes every level of the family (all files or none).
fn write_family(
    case: &LoadedCase,
    gens: &[&Generated],
    out: &FamilyOutput,
) -> Result<Vec<PathBuf>> {
    let fmt = crate::job::plot3d_format(case)?;
    let mesh = crate::job::mesh_options(case)?;
    let all: Vec<Vec<PathBuf>> = (0..gens.len()).map(|l| out.paths(&stem(case), l)).collect();
    std::fs::create_dir_all(&out.dir).map_err(|e| Error::io(&out.dir, e))?;
    crate::io::staged(|| {
        let mut written = Vec::new();
        for (g, paths) in gens.iter().zip(&all) {
            written.extend(crate::job::write_outputs_with(
                &g.blocks,
                g.connectivity.as_ref(),
                paths,
                &fmt,
                &mesh,
            )?);
        }
        Ok(written)
    })
}

/// The extensions of the case's `[output] files` (Plot3D as "x" when there are none), as the
/// default formats of `--write-family`.
pub fn default_formats(case: &LoadedCase) -> Vec<String> {
    let mut out: Vec<String> = case
        .case
        .output
        .files
        .iter()
        .filter_map(|p: &PathBuf| {
            if p.file_name().and_then(|n| n.to_str()) == Some("polyMesh") {
                return Some("polyMesh".to_string());
            }
            p.extension().and_then(|e| e.to_str()).map(str::to_string)
        })
        .collect();
    if out.is_empty() {
        out.push("x".into());
    }
    if crate::job::connectivity(case).is_some() && !out.iter().any(|e| e == "conn") {
        out.push("conn".into());
    }
    out.dedup();
    out
}
