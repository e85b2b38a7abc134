//! Grid quality: folding, scaled Jacobian, equiangular skewness, wall orthogonality, aspect ratio,
//! growth ratio and spacing of a planar grid ([`quality2d`]) or a surface grid
//! ([`quality_surface`]), summarised in a [`QualityReport`]; per-cell arrays for VTK cell data
//! come from [`cell_fields2d`] / [`cell_fields_surface`]. Definitions as the users' tools use them
//! (notes/FORMATS.md, "Quality metrics").
//!
//! # Cells and corner Jacobians
//! Cell (i, j) has lower-left node (i, j) and nodes x₀ = x_{i,j}, x₁ = x_{i+1,j},
//! x₂ = x_{i+1,j+1}, x₃ = x_{i,j+1}, counter-clockwise in (ξ, η). The corner Jacobian at x_k is
//! J_k = ((x_{k+1} − x_k) × (x_{k−1} − x_k)) · n, so at x₀ it is (x_{i+1,j} − x_{i,j}) ×
//! (x_{i,j+1} − x_{i,j}) and all four are positive in a valid right-handed cell. For a planar grid
//! n = +z. For a surface grid n is the cell's unit normal (x₂ − x₀) × (x₃ − x₁) (cross product
//! of the diagonals) and J_k is the component of the corner cross product along it; corner
//! angles (skewness) are measured in the plane normal to n. The scaled Jacobian is
//! J_k / (|x_{k+1} − x_k| |x_{k−1} − x_k|) ∈ [−1, 1].
//!
//! # Orientation and folding
//! A planar grid's orientation is the sign held by the majority of all corner Jacobians:
//! [`Orientation::LeftHanded`] if more are negative than positive (e.g. a mirrored grid), else
//! [`Orientation::RightHanded`]. **All Jacobians in the report and in the cell fields are relative
//! to that orientation** (multiplied by −1 for a left-handed grid), so a consistently
//! left-handed grid is valid with positive Jacobians, and a cell is folded iff one of its corner
//! Jacobians is ≤ 0 (or NaN), except at a *flat* corner: angle 180° to rounding (|J| ≤ 1e-10
//! |a| |b|, both edges of nonzero length), the degenerate but valid quad where a block corner
//! lies inside a straight edge (three-sided CAD faces). A surface grid has no handedness of its own
//! ([`Orientation::Surface`]); its cell normals come from the grid, and a cell is folded if a
//! corner Jacobian is ≤ 0 relative to its own normal (bow-tie, non-convex or collapsed cell) or
//! if its normal points against those of more than half of its edge neighbours (a cell turned
//! over as a whole). That second test assumes neighbouring cells turn by less than 90°.
//!
//! # Degenerate input
//! A block side collapsed to a point (a *pole*: all its nodes within 1e-12 of the diameter of
//! the boundary, [`crate::grid::boundary::collapsed_edges`]) is not degenerate: the cells along
//! it are triangles, evaluated as such (their two corners at the pole are one corner, between
//! the edges leaving it; aspect ratio over the three sides); the zero spacings along a pole and
//! its orthogonality (it has no tangent) are not reported.
//!
//! Nothing here panics. Elsewhere a zero-length edge makes the adjacent corner Jacobians 0 (folded),
//! the scaled Jacobian 0, the corner angle 0° (skewness ≥ 1) and the aspect ratio ∞; a growth
//! ratio with one zero spacing is ∞ (0/0 counts as 1). Grids smaller than 2 × 2 give a report
//! with `cells = 0`, NaN metrics and no folds. Otherwise NaN appears only for the orthogonality of
//! an edge without inner nodes, or if a coordinate is NaN or ∞ (such cells count as folded). In JSON, non-finite values are
//! written as the strings `"inf"`, `"-inf"` and `"nan"` and read back as such.

mod display;
pub mod family;
pub mod interface;
pub(crate) use display::cell_list;
pub(crate) mod geom;
mod json_f64;
pub mod quality3d;
mod stats;
#[cfg(test)]
mod tests;

use std::fmt;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::{Edge, Grid2};
use geom::{angle_deg, corner_jacobians, eval_cell, nmax, nmin, sub, Nodes};
use stats::{lines, CellStats};

/// At most this many folded cells are listed in [`QualityReport::first_folded`].
pub const MAX_FIRST_FOLDED: usize = 10;

/// Orientation of a grid (module docs, "Orientation and folding"); serialized as
/// `"right-handed"`, `"left-handed"` or `"surface"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Orientation {
    /// Planar grid with x_ξ × x_η > 0 (counter-clockwise cells).
    RightHanded,
    /// Planar grid with x_ξ × x_η < 0 (clockwise cells, e.g. mirrored); valid, not folded.
    LeftHanded,
    /// Surface grid: Jacobians are relative to each cell's own normal.
    Surface,
}

impl Orientation {
    /// "right-handed", "left-handed" or "surface".
    pub fn as_str(self) -> &'static str {
        match self {
            Orientation::RightHanded => "right-handed",
            Orientation::LeftHanded => "left-handed",
            Orientation::Surface => "surface",
        }
    }
}

impl fmt::Display for Orientation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Orthogonality of the first off-wall grid line at one block edge.
///
/// At each node of the edge except its two corner nodes: the deviation from 90° of the angle
/// between the off-wall line (first interior node − wall node) and the wall tangent (next − previous
/// node along the edge, a central difference). Angles are taken in R^D; on a surface that is the
/// tangent-plane angle to first order. A zero-length vector counts as a 90° deviation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EdgeOrthogonality {
    /// "E1" … "E4".
    pub edge: String,
    /// Number of nodes measured (edge length in nodes − 2); 0 leaves the statistics NaN.
    pub nodes: usize,
    /// Largest deviation from 90°, degrees.
    #[serde(with = "json_f64")]
    pub max_deg: f64,
    /// Mean deviation from 90°, degrees.
    #[serde(with = "json_f64")]
    pub mean_deg: f64,
}

/// Quality summary of a planar or surface grid (module docs give the definitions and the
/// conventions for orientation, folding and degenerate input).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QualityReport {
    /// Nodes along i.
    pub ni: usize,
    /// Nodes along j.
    pub nj: usize,
    /// Number of cells, (ni − 1)(nj − 1), or 0 for grids smaller than 2 × 2.
    pub cells: usize,
    /// Dominant orientation; Jacobians below are relative to it.
    pub orientation: Orientation,
    /// Smallest corner Jacobian (≤ 0: folded or degenerate).
    #[serde(with = "json_f64")]
    pub jacobian_min: f64,
    /// Largest corner Jacobian.
    #[serde(with = "json_f64")]
    pub jacobian_max: f64,
    /// Smallest scaled corner Jacobian, in [−1, 1] (1: right angle).
    #[serde(with = "json_f64")]
    pub scaled_jacobian_min: f64,
    /// Number of folded cells.
    pub folded_cells: usize,
    /// Cells (i, j) (lower-left node) of the first [`MAX_FIRST_FOLDED`] folded cells, in index
    /// order i + (ni − 1) j.
    pub first_folded: Vec<[usize; 2]>,
    /// Cells along a block side collapsed to a point (a pole, or a CAD face's cusp or tips
    /// gridded as a collapsed side): triangles, evaluated as such (module docs, "Degenerate
    /// input"), counted apart here; 0 without such a side.
    #[serde(default)]
    pub collapsed_cells: usize,
    /// Smallest scaled Jacobian over the cells that are not on a collapsed side (the
    /// triangles' angle at the point is the side's angle shared out among them);
    /// `scaled_jacobian_min` without such a side.
    #[serde(with = "json_f64", default = "json_f64::nan")]
    pub scaled_jacobian_min_regular: f64,
    /// Largest equiangular skewness (0: rectangle; > 1 only for non-convex or folded cells).
    #[serde(with = "json_f64")]
    pub skewness_max: f64,
    /// Mean equiangular skewness over all cells.
    #[serde(with = "json_f64")]
    pub skewness_mean: f64,
    /// Wall orthogonality, one entry per edge E1, E2, E3, E4.
    pub orthogonality: Vec<EdgeOrthogonality>,
    /// Largest cell aspect ratio, longest / shortest edge.
    #[serde(with = "json_f64")]
    pub aspect_ratio_max: f64,
    /// Largest ratio of adjacent spacings along i-lines, inverted to be ≥ 1 (1 if ni < 3).
    #[serde(with = "json_f64")]
    pub growth_i_max: f64,
    /// Largest ratio of adjacent spacings along j-lines, inverted to be ≥ 1 (1 if nj < 3).
    #[serde(with = "json_f64")]
    pub growth_j_max: f64,
    /// Shortest cell edge.
    #[serde(with = "json_f64")]
    pub min_spacing: f64,
    /// Longest cell edge.
    #[serde(with = "json_f64")]
    pub max_spacing: f64,
}

impl QualityReport {
    /// True if any cell is folded (or degenerate).
    pub fn is_folded(&self) -> bool {
        self.folded_cells > 0
    }
}

/// Quality of a planar grid (module docs give the definitions).
pub fn quality2d(g: &Grid2<2>) -> QualityReport {
    report(&Nodes::new(g))
}

/// Quality of a surface grid in R³: Jacobians along each cell's normal, folds by the corner
/// test and the neighbour-flip test (module docs).
pub fn quality_surface(g: &Grid2<3>) -> QualityReport {
    report(&Nodes::new(g))
}

/// Quality of a planar (D = 2) or surface (D = 3) grid, for code generic in D.
pub fn quality_any<const D: usize>(g: &Grid2<D>) -> QualityReport {
    report(&Nodes::new(g))
}

/// Per-cell arrays of a planar grid for VTK cell data, cell (i, j) at i + (ni − 1) j:
/// "jacobian_min", "scaled_jacobian_min", "skewness", "aspect_ratio" (Jacobians relative to the
/// grid's orientation). Empty arrays for grids smaller than 2 × 2.
pub fn cell_fields2d(g: &Grid2<2>) -> Vec<(&'static str, Vec<f64>)> {
    cell_fields(&Nodes::new(g))
}

/// Per-cell arrays of a surface grid, as [`cell_fields2d`]; Jacobians along each cell's normal.
pub fn cell_fields_surface(g: &Grid2<3>) -> Vec<(&'static str, Vec<f64>)> {
    cell_fields(&Nodes::new(g))
}

/// Names of the per-cell arrays, in the order [`cell_fields2d`] returns them.
pub const CELL_FIELDS: [&str; 4] = [
    "jacobian_min",
    "scaled_jacobian_min",
    "skewness",
    "aspect_ratio",
];

/// Orientation and its sign s (Jacobians are multiplied by s).
fn orientation(nd: &Nodes) -> (Orientation, f64) {
    if nd.surface {
        return (Orientation::Surface, 1.0);
    }
    if nd.cells() == 0 {
        return (Orientation::RightHanded, 1.0);
    }
    let n = nd.normal(&nd.cell(0, 0));
    let (pos, neg) = (0..nd.nj - 1)
        .into_par_iter()
        .map(|j| {
            let (mut pos, mut neg) = (0usize, 0usize);
            for i in 0..nd.ni - 1 {
                for jac in corner_jacobians(&nd.cell(i, j), n) {
                    pos += usize::from(jac > 0.0);
                    neg += usize::from(jac < 0.0);
                }
            }
            (pos, neg)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    if neg > pos {
        (Orientation::LeftHanded, -1.0)
    } else {
        (Orientation::RightHanded, 1.0)
    }
}

/// The cells of row j (those with lower-left node in row j of nodes).
fn row(nd: &Nodes, j: usize, s: f64) -> CellStats<2> {
    let mut a = CellStats::new();
    for i in 0..nd.ni - 1 {
        let c = nd.cell(i, j);
        let n = nd.normal(&c);
        let pole = nd.pole_edge(i, j);
        let e = eval_cell(&c, n, s, pole);
        a.add(e.jmin, e.jmax, e.smin, e.skew, e.aspect);
        if pole.is_some() {
            a.collapsed += 1;
        } else {
            a.smin_regular = nmin(a.smin_regular, e.smin);
        }
        let corner_ok = !e.folded;
        if !corner_ok || (nd.surface && nd.flipped(i, j, n)) {
            a.folded.push([i, j]);
        }
    }
    a
}

/// Wall orthogonality of one edge (see [`EdgeOrthogonality`]); needs ni, nj ≥ 2.
fn edge_orthogonality(nd: &Nodes, e: Edge) -> EdgeOrthogonality {
    let (ni, nj) = (nd.ni, nd.nj);
    // Node k along the edge: (wall node, first interior node).
    let at = |k: usize| -> ([usize; 2], [usize; 2]) {
        match e {
            Edge::E1 => ([0, k], [1, k]),
            Edge::E2 => ([ni - 1, k], [ni - 2, k]),
            Edge::E3 => ([k, 0], [k, 1]),
            Edge::E4 => ([k, nj - 1], [k, nj - 2]),
        }
    };
    // A side collapsed to a pole has no tangent: no orthogonality (no nodes).
    let len = match (nd.poles[e.index()], e.runs_along_i()) {
        (true, _) => 0,
        (false, true) => ni,
        (false, false) => nj,
    };
    let (mut max, mut sum, mut nodes) = (f64::NEG_INFINITY, 0.0, 0usize);
    for k in 1..len.saturating_sub(1) {
        let (w, q) = at(k);
        let (wn, _) = at(k + 1);
        let (wp, _) = at(k - 1);
        let off = sub(nd.p(q[0], q[1]), nd.p(w[0], w[1]));
        let tan = sub(nd.p(wn[0], wn[1]), nd.p(wp[0], wp[1]));
        let dev = (90.0 - angle_deg(off, tan)).abs();
        max = nmax(max, dev);
        sum += dev;
        nodes += 1;
    }
    let (max_deg, mean_deg) = if nodes == 0 {
        (f64::NAN, f64::NAN)
    } else {
        (max, sum / nodes as f64)
    };
    EdgeOrthogonality {
        edge: e.to_string(),
        nodes,
        max_deg,
        mean_deg,
    }
}

fn report(nd: &Nodes) -> QualityReport {
    let (orientation, s) = orientation(nd);
    let cells = nd.cells();
    let nan = f64::NAN;
    if cells == 0 {
        return QualityReport {
            ni: nd.ni,
            nj: nd.nj,
            cells,
            orientation,
            jacobian_min: nan,
            jacobian_max: nan,
            scaled_jacobian_min: nan,
            folded_cells: 0,
            first_folded: Vec::new(),
            collapsed_cells: 0,
            scaled_jacobian_min_regular: nan,
            skewness_max: nan,
            skewness_mean: nan,
            orthogonality: Edge::ALL
                .iter()
                .map(|e| EdgeOrthogonality {
                    edge: e.to_string(),
                    nodes: 0,
                    max_deg: nan,
                    mean_deg: nan,
                })
                .collect(),
            aspect_ratio_max: nan,
            growth_i_max: nan,
            growth_j_max: nan,
            min_spacing: nan,
            max_spacing: nan,
        };
    }
    // One accumulator per row of cells, merged in row order so that the first folded cells stay
    // in index order.
    let rows: Vec<CellStats<2>> = (0..nd.nj - 1)
        .into_par_iter()
        .map(|j| row(nd, j, s))
        .collect();
    let a = rows.into_iter().fold(CellStats::new(), |mut a, b| {
        a.merge(b);
        a
    });
    let point = |[i, j]: [usize; 2]| nd.p(i, j);
    // Spacings along a side collapsed to a pole are zero by construction: not counted.
    let [e1, e2, e3, e4] = nd.poles;
    let (gi, gj) = (
        lines([nd.ni, nd.nj], 0, point, |[_, j]| {
            (e3 && j == 0) || (e4 && j + 1 == nd.nj)
        }),
        lines([nd.ni, nd.nj], 1, point, |[i, _]| {
            (e1 && i == 0) || (e2 && i + 1 == nd.ni)
        }),
    );
    QualityReport {
        ni: nd.ni,
        nj: nd.nj,
        cells,
        orientation,
        jacobian_min: a.jmin,
        jacobian_max: a.jmax,
        scaled_jacobian_min: a.smin,
        folded_cells: a.folded.count,
        first_folded: a.folded.first,
        collapsed_cells: a.collapsed,
        scaled_jacobian_min_regular: a.smin_regular,
        skewness_max: a.skew_max,
        skewness_mean: a.skew_sum / cells as f64,
        orthogonality: Edge::ALL
            .iter()
            .map(|&e| edge_orthogonality(nd, e))
            .collect(),
        aspect_ratio_max: a.aspect_max,
        growth_i_max: gi.0,
        growth_j_max: gj.0,
        min_spacing: nmin(gi.1, gj.1),
        max_spacing: nmax(gi.2, gj.2),
    }
}

fn cell_fields(nd: &Nodes) -> Vec<(&'static str, Vec<f64>)> {
    let (_, s) = orientation(nd);
    let cells = nd.cells();
    let mut out: [Vec<f64>; 4] = std::array::from_fn(|_| vec![0.0; cells]);
    if cells > 0 {
        let nci = nd.ni - 1;
        let [jac, scaled, skew, aspect] = &mut out;
        jac.par_chunks_mut(nci)
            .zip(scaled.par_chunks_mut(nci))
            .zip(skew.par_chunks_mut(nci))
            .zip(aspect.par_chunks_mut(nci))
            .enumerate()
            .for_each(|(j, (((jr, sr), kr), ar))| {
                for i in 0..nci {
                    let c = nd.cell(i, j);
                    let e = eval_cell(&c, nd.normal(&c), s, nd.pole_edge(i, j));
                    jr[i] = e.jmin;
                    sr[i] = e.smin;
                    kr[i] = e.skew;
                    ar[i] = e.aspect;
                }
            });
    }
    CELL_FIELDS.into_iter().zip(out).collect()
}
