//! Elliptic regridding of existing blocks: keep every boundary node bit for bit, regrid the
//! interior by the paper's method. Planar blocks (and surface blocks lying in a plane
//! z = const) by the Section 2 Poisson system; curved surface blocks by the minimal-surface
//! system of Section 3 (the same system [24] with x ∈ R³: the boundary alone defines them).

use crate::algebraic::ControlKind;
use crate::elliptic::picard::{PicardInfo, PicardParams};
use crate::grid::boundary::Boundary2;
use crate::grid::Grid2;
use crate::io::Block;
use crate::quality::{quality2d, quality_surface};
use crate::solve;
use crate::{Error, Result};
use serde::Serialize;

/// Options of a smoothing run.
#[derive(Clone, Debug)]
pub struct SmoothOptions {
    /// 1-based indices of the blocks to regrid; `None`: all.
    pub blocks: Option<Vec<usize>>,
    /// Linear solver name ("direct", "multigrid").
    pub linear: String,
    /// Control functions.
    pub control: ControlKind,
    /// Picard parameters.
    pub picard: PicardParams,
    /// Edges made orthogonal (Section 2.4) in every regridded block: flags E1, E2, E3, E4.
    pub orthogonal: [bool; 4],
    /// How curved surface blocks are regridded.
    pub method: SurfaceMethod,
}

/// How `smooth` regrids a curved surface block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SurfaceMethod {
    /// The minimal-surface system of Section 3: the boundary alone defines the new surface.
    #[default]
    Poisson,
    /// Section 4 on the block's own surface: a bicubic Hermite surface through the existing
    /// nodes (C¹, through every node) is regridded by Laplace–Beltrami and inversion, so the
    /// new nodes stay on the existing surface.
    Surface,
}

impl Default for SmoothOptions {
    fn default() -> Self {
        SmoothOptions {
            blocks: None,
            linear: "direct".into(),
            control: ControlKind::Algebraic,
            picard: PicardParams::default(),
            orthogonal: [false; 4],
            method: SurfaceMethod::Poisson,
        }
    }
}

/// What was done to one block.
#[derive(Clone, Debug, Serialize)]
pub struct SmoothReport {
    /// 1-based block index.
    pub block: usize,
    /// "planar", "planar (z = const)" or "minimal surface".
    pub method: String,
    /// "existing interior" if the input interior was a valid start grid, else "transfinite".
    pub start: String,
    /// The Picard history (absent for `--method surface`, which has no Picard iteration).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub picard: Option<PicardInfo>,
    pub quality: crate::quality::quality3d::AnyQuality,
}

/// Regrids the selected blocks of `blocks` (read from `file`, used in messages). Unselected
/// blocks are returned unchanged.
pub fn smooth_blocks(
    blocks: &[Block],
    file: &str,
    opts: &SmoothOptions,
) -> Result<(Vec<Block>, Vec<SmoothReport>)> {
    if let Some(sel) = &opts.blocks {
        if let Some(&k) = sel.iter().find(|&&k| k == 0 || k > blocks.len()) {
            return Err(Error::input(
                file,
                format!(
                    "--blocks: block {k} does not exist (the file has {})",
                    blocks.len()
                ),
            ));
        }
    }
    let selected = |k: usize| opts.blocks.as_ref().is_none_or(|s| s.contains(&(k + 1)));
    // The memory of the regridding (a direct solve's LU above all) before any of it starts;
    // volume blocks take the direct solver only when small (`regrid_volume`).
    let mut budget = crate::case::limits::Budget::default();
    for (k, b) in blocks.iter().enumerate().filter(|(k, _)| selected(*k)) {
        use crate::case::limits::{BYTES_PER_NODE_2D, BYTES_PER_NODE_3D};
        let at = format!("{file}: block {}", k + 1);
        match b {
            Block::Volume(_) => budget.add(&at, &b.dims(), BYTES_PER_NODE_3D)?,
            _ => budget.add_solved(&at, &b.dims()[..2], BYTES_PER_NODE_2D, &opts.linear)?,
        }
    }
    budget.check_memory(file)?;
    let mut out = Vec::with_capacity(blocks.len());
    let mut reports = Vec::new();
    for (k, b) in blocks.iter().enumerate() {
        let selected = selected(k);
        if !selected {
            out.push(b.clone());
            continue;
        }
        let place = format!("{file}: block {}", k + 1);
        let (nb, rep) = match b {
            Block::Planar(g) => {
                let (g2, picard, start) = regrid(g, opts, &place)?;
                let q = quality2d(&g2);
                (
                    Block::Planar(g2),
                    (String::from("planar"), start, Some(picard), q.into()),
                )
            }
            Block::Surface(g) if is_flat(g) => {
                let flat = Grid2::<2>::from_coords(
                    g.ni(),
                    g.nj(),
                    [g.coord(0).to_vec(), g.coord(1).to_vec()],
                );
                let (g2, picard, start) = regrid(&flat, opts, &place)?;
                let q = quality2d(&g2);
                let [x, y] = g2.coords().clone();
                let s = Grid2::<3>::from_coords(g.ni(), g.nj(), [x, y, g.coord(2).to_vec()]);
                (
                    Block::Surface(s),
                    ("planar (z = const)".into(), start, Some(picard), q.into()),
                )
            }
            Block::Surface(g) if opts.method == SurfaceMethod::Surface => {
                let g2 = regrid_on_surface(g, opts, &place)?;
                let q = quality_surface(&g2);
                (
                    Block::Surface(g2),
                    (
                        "surface (Section 4 on the block's Hermite surface)".into(),
                        "none (no Picard iteration)".into(),
                        None,
                        q.into(),
                    ),
                )
            }
            Block::Surface(g) => {
                let (g2, picard, start) = regrid(g, opts, &place)?;
                let q = quality_surface(&g2);
                (
                    Block::Surface(g2),
                    ("minimal surface".into(), start, Some(picard), q.into()),
                )
            }
            Block::Volume(g) => {
                let (g2, picard, start) = crate::job::volume::regrid_volume(
                    g,
                    &opts.linear,
                    opts.control,
                    &opts.picard,
                    &place,
                )?;
                let q = crate::quality::quality3d::quality3d(&g2);
                let method = format!("volume (Section 5, {})", picard.linear_solver);
                let q = crate::quality::quality3d::AnyQuality::Volume(q);
                (Block::Volume(g2), (method, start, Some(picard), q))
            }
        };
        out.push(nb);
        reports.push(SmoothReport {
            block: k + 1,
            method: rep.0,
            start: rep.1,
            picard: rep.2,
            quality: rep.3,
        });
    }
    Ok((out, reports))
}

/// Regrids a surface block on its own surface: the existing nodes are the control net of a
/// bicubic Hermite surface, the boundary nodes keep their parameters (i/(ni−1), j/(nj−1)),
/// and Section 4 places the interior (with orthogonality at the chosen edges).
fn regrid_on_surface(g: &Grid2<3>, opts: &SmoothOptions, place: &str) -> Result<Grid2<3>> {
    if !g.all_finite() {
        return Err(Error::input(place, "the block has non-finite coordinates"));
    }
    let (ni, nj) = (g.ni(), g.nj());
    let pts = (0..g.len())
        .map(|n| ellipgrid_geometry::Vec3::new(g.coord(0)[n], g.coord(1)[n], g.coord(2)[n]))
        .collect();
    let net =
        ellipgrid_geometry::HermiteSurface::new(ni, nj, pts).map_err(|source| Error::Geometry {
            place: place.to_string(),
            source,
        })?;
    let along = |n: usize| (0..n).map(move |k| k as f64 / (n - 1) as f64);
    let uv = [
        along(nj).map(|v| [0.0, v]).collect(),
        along(nj).map(|v| [1.0, v]).collect(),
        along(ni).map(|u| [u, 0.0]).collect(),
        along(ni).map(|u| [u, 1.0]).collect(),
    ];
    let mut solver = solve::select::by_name(&opts.linear).map_err(|m| Error::input(place, m))?;
    let r = crate::surface::pipeline::grid_surface_orthogonal(
        &net,
        &uv,
        opts.orthogonal,
        solver.as_mut(),
        place,
    )?;
    let mut grid = r.grid;
    copy_boundary(g, &mut grid);
    Ok(grid)
}

/// True if every z is the same value.
fn is_flat(g: &Grid2<3>) -> bool {
    let z = g.coord(2);
    z.iter().all(|&v| v == z[0])
}

/// Regrids one block with its own boundary; the interior is the start grid if it is valid.
fn regrid<const D: usize>(
    g: &Grid2<D>,
    opts: &SmoothOptions,
    place: &str,
) -> Result<(Grid2<D>, PicardInfo, String)> {
    if !g.all_finite() {
        return Err(Error::input(place, "the block has non-finite coordinates"));
    }
    let b = Boundary2::from_grid(g, place)?;
    let valid = if D == 2 {
        let flat =
            Grid2::<2>::from_coords(g.ni(), g.nj(), [g.coord(0).to_vec(), g.coord(1).to_vec()]);
        !quality2d(&flat).is_folded()
    } else {
        let s =
            Grid2::<3>::from_coords(g.ni(), g.nj(), std::array::from_fn(|c| g.coord(c).to_vec()));
        !quality_surface(&s).is_folded()
    };
    let start = valid.then(|| g.clone());
    let mut solver = solve::select::by_name(&opts.linear).map_err(|m| Error::input(place, m))?;
    let r = crate::elliptic::orthogonal::grid_block_with(
        &b,
        start,
        opts.orthogonal,
        opts.control,
        solver.as_mut(),
        &opts.picard,
        place,
    )?;
    // Boundary nodes bit for bit (Boundary2 snaps corners; the grid's own corners are
    // single nodes, so this only restores what was there).
    let mut grid = r.grid;
    copy_boundary(g, &mut grid);
    let how = if valid {
        "existing interior"
    } else {
        "transfinite"
    };
    Ok((grid, r.picard, how.into()))
}

fn copy_boundary<const D: usize>(from: &Grid2<D>, to: &mut Grid2<D>) {
    for j in 0..from.nj() {
        for i in 0..from.ni() {
            if from.is_boundary(i, j) {
                to.set(i, j, from.point(i, j));
            }
        }
    }
}
