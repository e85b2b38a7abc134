//! Quality of a volume grid: corner Jacobians (the eight corner tetrahedra of every cell),
//! scaled Jacobian, folded cells, skewness, orthogonality at the six faces, aspect and growth
//! ratios, spacings ([`quality3d`], [`QualityReport3`]); per-cell arrays for VTK from
//! [`cell_fields3d`]. Definitions after notes/FORMATS.md, "Quality metrics".
//!
//! This module holds the report types and their printing; [`metrics`] computes them.
//!
//! - Cell (i, j, k) has lower corner node (i, j, k). The corner Jacobian at a corner is the
//!   triple product e_ξ · (e_η × e_ζ) of the three cell edges leaving it, each pointing in its
//!   index direction (edges that leave towards lower indices are negated), i.e. six times the
//!   volume of the corner tetrahedron; the scaled Jacobian divides it by the three edge lengths
//!   (1: orthogonal corner).
//! - Orientation: the sign held by the majority of corner Jacobians; Jacobians are reported
//!   relative to it (a left-handed grid is valid). A cell is folded iff a corner Jacobian is
//!   ≤ 0 or NaN, unless it is a flat-edge cell.
//! - Flat-edge cell ([`metrics::flat_edge_cell`]): every non-positive corner sits on a block
//!   edge where the two block faces meeting there are coplanar, dihedral ≥ 179° (e.g. edge E7
//!   of a C–O block around a wing tip, where the wing plane ahead of the leading edge meets the
//!   wing plane beyond the tip). Its corner there has three coplanar edges by topology, not by a
//!   fold; such cells are counted apart and do not make the grid folded.
//! - Skewness: the largest equiangular skewness max[(θmax − 90°)/90°, (90° − θmin)/90°] of the
//!   six quadrilateral faces of a cell (corner angles between the face's edges in R³).
//! - Orthogonality at a face: at every face node that is not on the face's rim, the angle
//!   between the first grid line off the face (first interior node − face node) and the face
//!   normal (cross product of the central differences along the face): its deviation from
//!   90° to the face. With it, the first-cell heights (lengths of those lines).
//! - Aspect ratio: longest / shortest of a cell's twelve edges; growth ratio: adjacent
//!   spacings along i-, j-, k-lines, inverted to be ≥ 1.

use std::fmt;

use serde::Serialize;

use crate::quality::display::{cell_list, first_cells, num, table_line};
use crate::quality::{json_f64, QualityReport};

pub mod metrics;
pub use metrics::{cell_fields3d, face_quality, folded_cells3d, quality3d};

pub use crate::quality::MAX_FIRST_FOLDED;

/// Orthogonality and first-cell heights at one face.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FaceQuality {
    /// "F1" … "F6".
    pub face: String,
    /// Face nodes measured (those off the face's rim).
    pub nodes: usize,
    /// Largest deviation from 90° of the first grid line off the face, degrees.
    #[serde(serialize_with = "json_f64::serialize")]
    pub orthogonality_max_deg: f64,
    /// Mean deviation, degrees.
    #[serde(serialize_with = "json_f64::serialize")]
    pub orthogonality_mean_deg: f64,
    /// Shortest first-cell height (length of the first grid line off the face).
    #[serde(serialize_with = "json_f64::serialize")]
    pub first_height_min: f64,
    /// Longest first-cell height.
    #[serde(serialize_with = "json_f64::serialize")]
    pub first_height_max: f64,
}

/// Quality summary of a volume grid (module docs give the definitions).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct QualityReport3 {
    pub ni: usize,
    pub nj: usize,
    pub nk: usize,
    /// (ni − 1)(nj − 1)(nk − 1).
    pub cells: usize,
    /// "right-handed" or "left-handed".
    pub orientation: String,
    #[serde(serialize_with = "json_f64::serialize")]
    pub jacobian_min: f64,
    #[serde(serialize_with = "json_f64::serialize")]
    pub jacobian_max: f64,
    #[serde(serialize_with = "json_f64::serialize")]
    pub scaled_jacobian_min: f64,
    pub folded_cells: usize,
    /// Lower corner nodes (i, j, k) of the first folded cells, in index order.
    pub first_folded: Vec<[usize; 3]>,
    /// Cells degenerate at a flat block edge (180° dihedral, by topology; module docs): not
    /// counted in `folded_cells`.
    pub flat_edge_cells: usize,
    /// Lower corner nodes of the first flat-edge cells, in index order.
    pub first_flat_edge: Vec<[usize; 3]>,
    /// Smallest scaled Jacobian over the cells that are not flat-edge cells.
    #[serde(serialize_with = "json_f64::serialize")]
    pub scaled_jacobian_min_regular: f64,
    #[serde(serialize_with = "json_f64::serialize")]
    pub skewness_max: f64,
    #[serde(serialize_with = "json_f64::serialize")]
    pub skewness_mean: f64,
    /// One entry per face F1 … F6.
    pub faces: Vec<FaceQuality>,
    #[serde(serialize_with = "json_f64::serialize")]
    pub aspect_ratio_max: f64,
    #[serde(serialize_with = "json_f64::serialize")]
    pub growth_i_max: f64,
    #[serde(serialize_with = "json_f64::serialize")]
    pub growth_j_max: f64,
    #[serde(serialize_with = "json_f64::serialize")]
    pub growth_k_max: f64,
    #[serde(serialize_with = "json_f64::serialize")]
    pub min_spacing: f64,
    #[serde(serialize_with = "json_f64::serialize")]
    pub max_spacing: f64,
}

impl QualityReport3 {
    /// True if any cell is folded (or degenerate).
    pub fn is_folded(&self) -> bool {
        self.folded_cells > 0
    }

    /// "cell (i, j, k), …" of the first folded cells.
    pub fn folded_list(&self) -> String {
        cell_list(&self.first_folded)
    }
}

/// Width of the metric names in the volume report.
const NAME_WIDTH: usize = 22;

impl fmt::Display for QualityReport3 {
    /// A compact table like the 2D report's, one line per face for orthogonality.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let status = if self.is_folded() { "FOLDED" } else { "ok" };
        writeln!(
            f,
            "grid quality  {} x {} x {} nodes, {} cells, {}: {}",
            self.ni, self.nj, self.nk, self.cells, self.orientation, status
        )?;
        let line = |name: &str, cols: &[(&str, f64)]| {
            let cols: Vec<(&str, String)> = cols.iter().map(|&(l, v)| (l, num(v))).collect();
            table_line(NAME_WIDTH, name, &cols)
        };
        let count = |name: &str, n: usize| table_line(NAME_WIDTH, name, &[("", n.to_string())]);
        let folded = count("folded cells", self.folded_cells)
            + &first_cells(&self.first_folded, self.folded_cells);
        let mut lines = vec![
            line(
                "jacobian",
                &[("min", self.jacobian_min), ("max", self.jacobian_max)],
            ),
            line("scaled jacobian", &[("min", self.scaled_jacobian_min)]),
            folded,
        ];
        if self.flat_edge_cells > 0 {
            lines.push(format!(
                "{}   (180° block edge, by topology; scaled jacobian min {} off them){}",
                count("flat-edge cells", self.flat_edge_cells),
                num(self.scaled_jacobian_min_regular),
                first_cells(&self.first_flat_edge, self.flat_edge_cells)
            ));
        }
        lines.extend([
            line(
                "skewness",
                &[("max", self.skewness_max), ("mean", self.skewness_mean)],
            ),
            line("aspect ratio", &[("max", self.aspect_ratio_max)]),
            line(
                "growth ratio",
                &[
                    ("i", self.growth_i_max),
                    ("j", self.growth_j_max),
                    ("k", self.growth_k_max),
                ],
            ),
            line(
                "spacing",
                &[("min", self.min_spacing), ("max", self.max_spacing)],
            ),
        ]);
        for l in lines {
            writeln!(f, "{l}")?;
        }
        for q in &self.faces {
            let l = line(
                &format!("orthogonality {} (°)", q.face),
                &[
                    ("max", q.orthogonality_max_deg),
                    ("mean", q.orthogonality_mean_deg),
                ],
            );
            writeln!(
                f,
                "{l}   first height {} .. {}",
                num(q.first_height_min),
                num(q.first_height_max)
            )?;
        }
        Ok(())
    }
}

/// The quality report of a 2D (planar or surface) or a volume block, for reports that hold
/// either (smoothing). Serialized as the inner report.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum AnyQuality {
    Surface(QualityReport),
    Volume(QualityReport3),
}

impl AnyQuality {
    /// True if any cell is folded.
    pub fn is_folded(&self) -> bool {
        match self {
            AnyQuality::Surface(q) => q.is_folded(),
            AnyQuality::Volume(q) => q.is_folded(),
        }
    }

    /// Number of folded cells.
    pub fn folded_cells(&self) -> usize {
        match self {
            AnyQuality::Surface(q) => q.folded_cells,
            AnyQuality::Volume(q) => q.folded_cells,
        }
    }

    /// "cell (i, j[, k]), …" of the first folded cells.
    pub fn folded_list(&self) -> String {
        match self {
            AnyQuality::Surface(q) => crate::quality::cell_list(&q.first_folded),
            AnyQuality::Volume(q) => q.folded_list(),
        }
    }
}

impl From<QualityReport> for AnyQuality {
    fn from(q: QualityReport) -> Self {
        AnyQuality::Surface(q)
    }
}

impl fmt::Display for AnyQuality {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AnyQuality::Surface(q) => q.fmt(f),
            AnyQuality::Volume(q) => q.fmt(f),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Grid3;

    #[test]
    fn box_metrics_are_exact() {
        let g = Grid3::rectilinear(&[0.0, 1.0, 3.0], &[0.0, 0.5], &[0.0, 2.0, 4.0, 8.0]);
        let q = quality3d(&g);
        assert_eq!(q.cells, 2 * 3);
        assert_eq!(q.folded_cells, 0);
        assert_eq!(q.orientation, "right-handed");
        assert!((q.jacobian_min - 1.0).abs() < 1e-14); // 1 × 0.5 × 2
        assert!((q.jacobian_max - 2.0 * 0.5 * 4.0).abs() < 1e-14);
        assert!((q.scaled_jacobian_min - 1.0).abs() < 1e-14);
        assert!(q.skewness_max.abs() < 1e-14);
        assert!((q.aspect_ratio_max - 8.0).abs() < 1e-14); // 4 / 0.5
        assert!((q.growth_i_max - 2.0).abs() < 1e-14 && (q.growth_k_max - 2.0).abs() < 1e-14);
        assert_eq!(q.growth_j_max, 1.0);
        assert!((q.min_spacing - 0.5).abs() < 1e-14 && (q.max_spacing - 4.0).abs() < 1e-14);
        // F5 (k = 0) has one inner node (i = 1, j: none since nj = 2) → no nodes.
        assert_eq!(q.faces[4].nodes, 0);
        assert_eq!(q.faces[0].nodes, 0);
        let s = q.to_string();
        assert!(s.contains("folded cells") && s.contains("F6"), "{s}");
    }

    /// A block whose faces i = 0 and k = last lie in the plane z = 0 on either side of their
    /// shared edge (the C–O tip edge): (x, z) = (a² − b², 2ab), a = i, b = last − k (the map
    /// w = ζ² opens the quadrant to the half-plane), y = j.
    fn flat_edge_block() -> Grid3 {
        let (n, l) = (4, 3);
        Grid3::from_fn(n, 3, l + 1, |i, j, k| {
            let (a, b) = (i as f64, (l - k) as f64);
            [a * a - b * b, j as f64, 2.0 * a * b]
        })
    }

    #[test]
    fn cells_at_a_flat_block_edge_are_counted_apart_from_folded_ones() {
        let g = flat_edge_block();
        let q = quality3d(&g);
        // The two cells along the edge (i = 0, k = 2) have a corner with coplanar edges.
        assert_eq!((q.folded_cells, q.flat_edge_cells), (0, 2), "{q}");
        assert_eq!(q.first_flat_edge, vec![[0, 0, 2], [0, 1, 2]]);
        assert_eq!(q.scaled_jacobian_min, 0.0);
        assert!(q.scaled_jacobian_min_regular > 0.1, "{q}");
        assert!(!q.is_folded() && q.to_string().contains("flat-edge cells"));
        // A real fold in such a cell (its interior node pushed through the plane) is folded.
        let mut f = g.clone();
        let p = f.point(1, 1, 2);
        f.set(1, 1, 2, [p[0], p[1], -0.5]);
        let q = quality3d(&f);
        assert!(q.is_folded() && q.first_folded.contains(&[0, 0, 2]), "{q}");
        // A zero-length edge on the block edge is a degenerate cell, not a flat edge.
        let mut z = g.clone();
        z.set(0, 1, 3, z.point(0, 0, 3));
        assert!(quality3d(&z).is_folded());
        // Both faces tilted down by 0.4° (a dihedral of 180.8° inside the block) still count
        // as flat; by 1° each (182°) the cells are folded.
        let tilt = 0.4f64.to_radians().tan();
        let bent = Grid3::from_fn(4, 3, 4, |i, j, k| {
            let p = g.point(i, j, k);
            [p[0], p[1], p[2] - tilt * p[0].abs()]
        });
        let q = quality3d(&bent);
        assert_eq!((q.folded_cells, q.flat_edge_cells), (0, 2), "{q}");
        let bent = Grid3::from_fn(4, 3, 4, |i, j, k| {
            let p = g.point(i, j, k);
            [p[0], p[1], p[2] - 2.5 * tilt * p[0].abs()]
        });
        let q = quality3d(&bent);
        assert_eq!((q.folded_cells, q.flat_edge_cells), (2, 0), "{q}");
    }

    #[test]
    fn the_fold_count_alone_is_the_reports() {
        let g = flat_edge_block();
        let mut folded = g.clone();
        let p = folded.point(1, 1, 2);
        folded.set(1, 1, 2, [p[0], p[1], -0.5]);
        let mut degenerate = g.clone();
        degenerate.set(0, 1, 3, degenerate.point(0, 0, 3));
        let mut nan = g.clone();
        nan.set(2, 1, 1, [f64::NAN, 0.0, 0.0]);
        let mirrored = Grid3::from_fn(4, 3, 4, |i, j, k| {
            let p = g.point(i, j, k);
            [-p[0], p[1], p[2]]
        });
        for (name, x) in [
            ("flat edge", &g),
            ("folded", &folded),
            ("degenerate", &degenerate),
            ("nan", &nan),
            ("left-handed", &mirrored),
        ] {
            let q = quality3d(x);
            assert_eq!(metrics::folded_cells3d(x), q.folded_cells, "{name}: {q}");
        }
        assert!(metrics::folded_cells3d(&nan) > 0);
    }

    #[test]
    fn a_folded_cell_is_found_and_mirrors_are_valid() {
        let r: Vec<f64> = (0..4).map(|v| v as f64).collect();
        let mut g = Grid3::rectilinear(&r, &r, &r);
        let mirrored = {
            let mut m = g.clone();
            m.coords_mut()[0].iter_mut().for_each(|v| *v = -*v);
            m
        };
        let qm = quality3d(&mirrored);
        assert_eq!(
            (qm.orientation.as_str(), qm.folded_cells),
            ("left-handed", 0)
        );
        g.set(1, 1, 1, [0.2, 0.2, 0.2]); // the (+,+,+) corner of cell (0,0,0) turned inside out
        let q = quality3d(&g);
        assert!(q.is_folded());
        assert_eq!(q.first_folded[0], [0, 0, 0]);
        let f = cell_fields3d(&g);
        assert_eq!(f[0].1.len(), 27);
        assert!(f[0].1[0] < 0.0);
        let face = q.faces[0].clone();
        assert_eq!(face.nodes, 4);
        assert!((face.first_height_min - 1.0).abs() < 1e-14);
    }
}
