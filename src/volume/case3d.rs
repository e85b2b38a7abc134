//! Volume blocks in case files (`[[volume]]`), their runs and the smoothing of volume blocks
//! of existing grids. README.md, "Volume blocks", is the reference of the case-file syntax.
//!
//! A `[[volume]]` gets its six faces either
//! - from twelve edges `[volume.E1]` … `[volume.E12]` (METHOD.md numbering; each a curve with a
//!   distribution, as the edges of 2D blocks), each face the Coons patch (transfinite
//!   interpolation) of its four edges, blended with the straight-line parameters [39, 40] of
//!   the face's own edge distributions so that clustered edges give clustered faces; with
//!   `face_grids = "elliptic"` every planar face is then regridded by the Section 2 system
//!   (curved faces keep the Coons patch: the minimal surface would change their shape); or
//! - from a Plot3D file of six surface blocks F1 … F6 (`faces = { file, orient }`), each in the
//!   face orientation of [`super::faces`] unless `orient` says otherwise.

use super::faces::{block_node, face_dims, Faces, FACE_NAMES};
use super::quality3d::{quality3d, QualityReport3};
use super::{by_name3, grid_volume, progress_enabled, transfinite};
use crate::arclength::{normalized_arclength, EdgeFunctions};
use crate::case::{EdgeSpec, LoadedCase};
use crate::domain::{grid_block, ControlKind};
use crate::io::Block;
use crate::linsolve::direct::DirectLu;
use crate::poisson2d::{PicardInfo, PicardParams};
use crate::transform::straight_line;
use crate::{Error, Grid2, Grid3, Result};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::time::Instant;

/// `[[volume]]`: one volume block.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumeSpec {
    /// Name used in messages and outputs (default "volume<k>").
    pub name: Option<String>,
    /// Nodes along i (on E1–E4), j (E5–E8), k (E9–E12).
    pub ni: usize,
    pub nj: usize,
    pub nk: usize,
    /// Linear solver of each Picard step: "bicgstab" (default) or "direct" (small blocks).
    #[serde(default = "bicgstab")]
    pub linear: String,
    /// Faces from edges: "tfi" (default; Coons patches) or "elliptic" (planar faces
    /// regridded by the Section 2 system).
    #[serde(default)]
    pub face_grids: Option<String>,
    /// Faces from a Plot3D file instead of edges.
    pub faces: Option<FacesFile>,
    #[serde(rename = "E1")]
    pub e1: Option<EdgeSpec>,
    #[serde(rename = "E2")]
    pub e2: Option<EdgeSpec>,
    #[serde(rename = "E3")]
    pub e3: Option<EdgeSpec>,
    #[serde(rename = "E4")]
    pub e4: Option<EdgeSpec>,
    #[serde(rename = "E5")]
    pub e5: Option<EdgeSpec>,
    #[serde(rename = "E6")]
    pub e6: Option<EdgeSpec>,
    #[serde(rename = "E7")]
    pub e7: Option<EdgeSpec>,
    #[serde(rename = "E8")]
    pub e8: Option<EdgeSpec>,
    #[serde(rename = "E9")]
    pub e9: Option<EdgeSpec>,
    #[serde(rename = "E10")]
    pub e10: Option<EdgeSpec>,
    #[serde(rename = "E11")]
    pub e11: Option<EdgeSpec>,
    #[serde(rename = "E12")]
    pub e12: Option<EdgeSpec>,
}

fn bicgstab() -> String {
    "bicgstab".into()
}

/// `faces = { file = "faces.x", orient = ["ab", …] }`: six surface blocks F1 … F6.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FacesFile {
    /// Plot3D file (any flavour), relative to the case file.
    pub file: PathBuf,
    /// Per face, how the stored block's indices (p, q) run along the face's (a, b) of
    /// [`super::faces`]: "ab" (default: p = a, q = b), "ba" (transposed), with "-" before a
    /// letter for a reversed direction ("-ab", "a-b", "b-a", …).
    pub orient: Option<Vec<String>>,
}

/// Report of one volume block: the solve history and the 3D quality.
#[derive(Clone, Debug, Serialize)]
pub struct VolumeReport {
    pub name: String,
    pub ni: usize,
    pub nj: usize,
    pub nk: usize,
    /// Wall-clock seconds of the block's generation.
    pub seconds: f64,
    pub picard: PicardInfo,
    pub quality: QualityReport3,
}

/// Position of an edge: along axis `d`, at the hi/lo ends of the two other axes of node `n`.
fn edge_of(d: usize, n: [usize; 3], dims: [usize; 3]) -> usize {
    let o: Vec<usize> = (0..3).filter(|&a| a != d).collect();
    let hi = |a: usize| usize::from(n[a] == dims[a] - 1 && n[a] > 0);
    4 * d + hi(o[0]) + 2 * hi(o[1])
}

/// The Coons patch of face f from the twelve edge point lists (module docs).
pub fn coons_face(f: usize, edges: &[Vec<[f64; 3]>; 12], dims: [usize; 3]) -> Grid2<3> {
    let [na, nb] = face_dims(f, dims);
    let ax = f / 2;
    let (ta, tb) = match ax {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    // Edges of the face: along a at b = 0 / end, along b at a = 0 / end.
    let e_a0 = edge_of(ta, block_node(f, 0, 0, dims), dims);
    let e_a1 = edge_of(ta, block_node(f, 0, nb - 1, dims), dims);
    let e_b0 = edge_of(tb, block_node(f, 0, 0, dims), dims);
    let e_b1 = edge_of(tb, block_node(f, na - 1, 0, dims), dims);
    let (ba, ta_, lb, rb) = (&edges[e_a0], &edges[e_a1], &edges[e_b0], &edges[e_b1]);
    let pg = straight_line(&EdgeFunctions {
        s_e3: normalized_arclength(ba),
        s_e4: normalized_arclength(ta_),
        t_e1: normalized_arclength(lb),
        t_e2: normalized_arclength(rb),
    });
    let (c00, c10, c01, c11) = (ba[0], ba[na - 1], ta_[0], ta_[na - 1]);
    Grid2::<3>::from_fn(na, nb, |a, b| {
        let (s, t) = pg.at(a, b);
        std::array::from_fn(|c| {
            (1.0 - s) * lb[b][c] + s * rb[b][c] + (1.0 - t) * ba[a][c] + t * ta_[a][c]
                - ((1.0 - s) * (1.0 - t) * c00[c]
                    + s * (1.0 - t) * c10[c]
                    + (1.0 - s) * t * c01[c]
                    + s * t * c11[c])
        })
    })
}

/// True if every point of a face lies within 1e-9 of its size of the plane through its
/// corners' mean with the normal of its diagonals.
fn is_planar(g: &Grid2<3>) -> bool {
    let (ni, nj) = (g.ni(), g.nj());
    let (p00, p10, p01, p11) = (
        g.point(0, 0),
        g.point(ni - 1, 0),
        g.point(0, nj - 1),
        g.point(ni - 1, nj - 1),
    );
    let d1: [f64; 3] = std::array::from_fn(|c| p11[c] - p00[c]);
    let d2: [f64; 3] = std::array::from_fn(|c| p01[c] - p10[c]);
    let n = [
        d1[1] * d2[2] - d1[2] * d2[1],
        d1[2] * d2[0] - d1[0] * d2[2],
        d1[0] * d2[1] - d1[1] * d2[0],
    ];
    let nn = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if nn == 0.0 {
        return false;
    }
    let o: [f64; 3] = std::array::from_fn(|c| 0.25 * (p00[c] + p10[c] + p01[c] + p11[c]));
    let tol = 1e-9 * g.diameter();
    (0..nj).all(|j| {
        (0..ni).all(|i| {
            let p = g.point(i, j);
            ((0..3).map(|c| (p[c] - o[c]) * n[c]).sum::<f64>() / nn).abs() <= tol
        })
    })
}

/// Maps a stored face grid onto the face orientation by an `orient` string (see
/// [`FacesFile::orient`]).
fn reorient(g: &Grid2<3>, spec: &str, want: [usize; 2], at: &str) -> Result<Grid2<3>> {
    let bad = || {
        Error::input(
            at,
            format!("orient '{spec}': expected ab, ba, -ab, a-b, -a-b, -ba, b-a or -b-a"),
        )
    };
    let mut letters = Vec::new();
    let mut neg = false;
    for ch in spec.chars() {
        match ch {
            '-' if !neg => neg = true,
            'a' | 'b' => {
                letters.push((ch, neg));
                neg = false;
            }
            _ => return Err(bad()),
        }
    }
    if letters.len() != 2 || letters[0].0 == letters[1].0 || neg {
        return Err(bad());
    }
    let sizes = |l: char| if l == 'a' { want[0] } else { want[1] };
    let (np, nq) = (sizes(letters[0].0), sizes(letters[1].0));
    if (g.ni(), g.nj()) != (np, nq) {
        return Err(Error::input(
            at,
            format!(
                "has {} × {} nodes; with orient '{spec}' the block needs {np} × {nq}",
                g.ni(),
                g.nj()
            ),
        ));
    }
    Ok(Grid2::<3>::from_fn(want[0], want[1], |a, b| {
        let idx = |(l, r): (char, bool), n: usize| {
            let v = if l == 'a' { a } else { b };
            if r {
                n - 1 - v
            } else {
                v
            }
        };
        g.point(idx(letters[0], np), idx(letters[1], nq))
    }))
}

impl VolumeSpec {
    fn edge_specs(&self) -> [&Option<EdgeSpec>; 12] {
        [
            &self.e1, &self.e2, &self.e3, &self.e4, &self.e5, &self.e6, &self.e7, &self.e8,
            &self.e9, &self.e10, &self.e11, &self.e12,
        ]
    }
}

/// "file: volume 'name'" of volume k.
pub fn volume_place(case: &LoadedCase, k: usize) -> String {
    format!("{}: volume '{}'", case.path.display(), volume_name(case, k))
}

/// The name of volume k.
pub fn volume_name(case: &LoadedCase, k: usize) -> String {
    case.case.volumes[k]
        .name
        .clone()
        .unwrap_or_else(|| format!("volume{}", k + 1))
}

/// The validated faces of volume k of a case.
pub fn volume_faces(case: &LoadedCase, k: usize, params: &PicardParams) -> Result<Faces> {
    let v = &case.case.volumes[k];
    let place = volume_place(case, k);
    let dims = [v.ni, v.nj, v.nk];
    if dims.iter().any(|&n| n < 3) {
        return Err(Error::input(
            &place,
            format!("ni, nj, nk = {:?}: need at least 3 nodes each way", dims),
        ));
    }
    let specs = v.edge_specs();
    let given = specs.iter().filter(|s| s.is_some()).count();
    if let Some(ff) = &v.faces {
        if given > 0 {
            return Err(Error::input(
                &place,
                "give either faces = { file } or edges E1..E12, not both",
            ));
        }
        let path = case
            .path
            .parent()
            .unwrap_or(std::path::Path::new("."))
            .join(&ff.file);
        let file = crate::io::plot3d::read_plot3d(&path)?;
        let at = format!("{place}: {}", path.display());
        if file.blocks.len() != 6 {
            return Err(Error::input(
                at,
                format!("needs 6 face blocks F1..F6, found {}", file.blocks.len()),
            ));
        }
        let orient = ff.orient.clone().unwrap_or_else(|| vec!["ab".into(); 6]);
        if orient.len() != 6 {
            return Err(Error::input(&at, "orient needs 6 entries, one per face"));
        }
        let mut faces = Vec::with_capacity(6);
        for (f, b) in file.blocks.iter().enumerate() {
            let fat = format!("{at}: face {}", FACE_NAMES[f]);
            let g = match b {
                Block::Surface(g) => g.clone(),
                Block::Planar(g) => Grid2::<3>::from_coords(
                    g.ni(),
                    g.nj(),
                    [g.coord(0).to_vec(), g.coord(1).to_vec(), vec![0.0; g.len()]],
                ),
                Block::Volume(g) if g.dims()[2] == 1 => {
                    let [a, b, _] = g.dims();
                    Grid2::<3>::from_coords(a, b, std::array::from_fn(|c| g.coord(c).to_vec()))
                }
                Block::Volume(_) => return Err(Error::input(fat, "is a volume block, not a face")),
            };
            faces.push(reorient(&g, &orient[f], face_dims(f, dims), &fat)?);
        }
        let faces: [Grid2<3>; 6] = faces.try_into().expect("six faces");
        return Faces::new(faces, &place);
    }
    if given != 12 {
        let missing: Vec<String> = (0..12)
            .filter(|&e| specs[e].is_none())
            .map(|e| format!("E{}", e + 1))
            .collect();
        return Err(Error::input(
            &place,
            format!(
                "missing edges {} (or give faces = {{ file }})",
                missing.join(", ")
            ),
        ));
    }
    let mut edges: [Vec<[f64; 3]>; 12] = Default::default();
    for (e, spec) in specs.iter().enumerate() {
        let n = dims[e / 4];
        let at = format!("{place}, edge E{}", e + 1);
        let pts = case.edge_points(spec.as_ref().expect("checked"), n, &at)?;
        edges[e] = pts.iter().map(|p| [p.x, p.y, p.z]).collect();
    }
    // The three edges at each corner must meet; then they share the corner exactly.
    let size = edges.iter().flatten().fold(0.0f64, |m, p| {
        m.max(p.iter().map(|v| v.abs()).fold(0.0, f64::max))
    });
    let tol = 1e-6 * size.max(f64::MIN_POSITIVE);
    for c in 0..8 {
        let n = [
            (c & 1) * (dims[0] - 1),
            ((c >> 1) & 1) * (dims[1] - 1),
            (c >> 2) * (dims[2] - 1),
        ];
        let ends: Vec<(usize, usize)> = (0..3)
            .map(|d| (edge_of(d, n, dims), usize::from(n[d] > 0) * (dims[d] - 1)))
            .collect();
        let p0 = edges[ends[0].0][ends[0].1];
        for &(e, at) in &ends[1..] {
            let p = edges[e][at];
            let gap = (0..3).map(|i| (p[i] - p0[i]).powi(2)).sum::<f64>().sqrt();
            if gap > tol {
                return Err(Error::input(
                    &place,
                    format!(
                        "edges E{} and E{} do not meet at corner {n:?}: gap {gap:.3e}",
                        ends[0].0 + 1,
                        e + 1
                    ),
                ));
            }
            edges[e][at] = p0;
        }
    }
    let elliptic = match v.face_grids.as_deref() {
        None | Some("tfi") => false,
        Some("elliptic") => true,
        Some(o) => {
            return Err(Error::input(
                &place,
                format!("face_grids '{o}': expected tfi or elliptic"),
            ))
        }
    };
    let mut faces: [Grid2<3>; 6] = std::array::from_fn(|f| coons_face(f, &edges, dims));
    if elliptic {
        for (f, g) in faces.iter_mut().enumerate() {
            if is_planar(g) {
                let fp = format!("{place}, face {}", FACE_NAMES[f]);
                let b = crate::boundary::Boundary2::from_grid(g, &fp)?;
                let r = grid_block(
                    &b,
                    Some(g.clone()),
                    ControlKind::Algebraic,
                    &mut DirectLu::new(),
                    params,
                    &fp,
                )?;
                let mut ng = r.grid;
                for bb in 0..ng.nj() {
                    for a in 0..ng.ni() {
                        if ng.is_boundary(a, bb) {
                            ng.set(a, bb, g.point(a, bb));
                        }
                    }
                }
                *g = ng;
            }
        }
    }
    Faces::new(faces, &place)
}

/// A terminal progress bar for a Picard solve, if enabled and stderr is a terminal.
fn progress_bar(name: &str, max: usize) -> Option<indicatif::ProgressBar> {
    use std::io::IsTerminal;
    if !progress_enabled() || !std::io::stderr().is_terminal() {
        return None;
    }
    let pb = indicatif::ProgressBar::new(max as u64);
    pb.set_style(
        indicatif::ProgressStyle::with_template("{prefix} Picard {pos:>3} {msg} [{elapsed}]")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    pb.set_prefix(format!("volume '{name}'"));
    Some(pb)
}

/// Grids volume k of a case: faces, transfinite start, Picard solve, 3D quality.
pub fn generate_volume(case: &LoadedCase, k: usize) -> Result<(String, Block, VolumeReport)> {
    let t0 = Instant::now();
    let spec = &case.case;
    let v = &spec.volumes[k];
    let place = volume_place(case, k);
    let name = volume_name(case, k);
    let params = &spec.solver.picard;
    let faces = volume_faces(case, k, params)?;
    let mut solver = by_name3(&v.linear).map_err(|m| Error::input(&place, m))?;
    let pb = progress_bar(&name, params.max_steps);
    let mut cb = |n: usize, s: &crate::poisson2d::PicardStep| {
        if let Some(pb) = &pb {
            pb.set_position(n as u64);
            pb.set_message(format!(
                "update {:.2e} residual {:.2e}",
                s.update, s.residual
            ));
        }
    };
    let r = grid_volume(
        &faces,
        None,
        spec.solver.control,
        solver.as_mut(),
        params,
        &place,
        &mut cb,
    )?;
    if let Some(pb) = pb {
        pb.finish_and_clear();
    }
    let q = quality3d(&r.grid);
    let [ni, nj, nk] = r.grid.dims();
    let rep = VolumeReport {
        name: name.clone(),
        ni,
        nj,
        nk,
        seconds: t0.elapsed().as_secs_f64(),
        picard: r.picard,
        quality: q,
    };
    Ok((name, Block::Volume(r.grid), rep))
}

/// The transfinite start grid of volume k.
pub fn start_volume(case: &LoadedCase, k: usize) -> Result<(String, Block)> {
    let faces = volume_faces(case, k, &case.case.solver.picard)?;
    Ok((volume_name(case, k), Block::Volume(transfinite(&faces))))
}

/// Regrids a volume block of an existing grid keeping its boundary nodes bit for bit: the
/// interior is the start grid if it is fold-free, else the transfinite one. `linear`:
/// "direct" (faer LU, used only up to 40 000 interior nodes; larger blocks use Bi-CGSTAB),
/// "bicgstab" or "multigrid" (Bi-CGSTAB until a 3D multigrid exists). Returns the grid, the
/// history, the start used and the solver's name.
pub fn regrid_volume(
    g: &Grid3,
    linear: &str,
    control: ControlKind,
    params: &PicardParams,
    place: &str,
) -> Result<(Grid3, PicardInfo, String)> {
    let d = g.dims();
    if d.iter().any(|&n| n < 3) {
        return Err(Error::input(
            place,
            format!("a volume block needs at least 3 nodes each way, got {d:?}"),
        ));
    }
    if g.coords().iter().any(|c| c.iter().any(|v| !v.is_finite())) {
        return Err(Error::input(place, "the block has non-finite coordinates"));
    }
    let faces = Faces::from_grid(g);
    let inner = (d[0] - 2) * (d[1] - 2) * (d[2] - 2);
    let name = match linear {
        "direct" if inner <= 40_000 => "direct",
        "direct" | "multigrid" | "bicgstab" => "bicgstab",
        o => {
            return Err(Error::input(
                place,
                format!("linear solver '{o}': expected direct, bicgstab or multigrid"),
            ))
        }
    };
    let mut solver = by_name3(name).map_err(|m| Error::input(place, m))?;
    let valid = !quality3d(g).is_folded();
    let start = valid.then(|| g.clone());
    let pb = progress_bar(place, params.max_steps);
    let mut cb = |n: usize, s: &crate::poisson2d::PicardStep| {
        if let Some(pb) = &pb {
            pb.set_position(n as u64);
            pb.set_message(format!(
                "update {:.2e} residual {:.2e}",
                s.update, s.residual
            ));
        }
    };
    let r = grid_volume(
        &faces,
        start,
        control,
        solver.as_mut(),
        params,
        place,
        &mut cb,
    )?;
    if let Some(pb) = pb {
        pb.finish_and_clear();
    }
    let how = if valid {
        "existing interior"
    } else {
        "transfinite"
    };
    Ok((r.grid, r.picard, how.into()))
}

#[cfg(test)]
mod tests {
    use super::super::faces::edge_nodes;
    use super::*;

    #[test]
    fn orient_strings_map_indices() {
        let g = Grid2::<3>::from_fn(3, 2, |p, q| [p as f64, q as f64, 0.0]);
        let t = reorient(&g, "ba", [2, 3], "f").unwrap();
        assert_eq!(t.point(1, 2), [2.0, 1.0, 0.0]);
        let r = reorient(&g, "-ab", [3, 2], "f").unwrap();
        assert_eq!(r.point(0, 1), [2.0, 1.0, 0.0]);
        assert!(reorient(&g, "aa", [3, 2], "f").is_err());
        assert!(reorient(&g, "ab", [2, 3], "f")
            .unwrap_err()
            .to_string()
            .contains("needs 2 × 3"));
    }

    #[test]
    fn coons_faces_of_box_edges_meet() {
        let dims = [4, 3, 5];
        let edges: [Vec<[f64; 3]>; 12] = std::array::from_fn(|e| {
            edge_nodes(e, dims)
                .into_iter()
                .map(|n| [n[0] as f64, (n[1] as f64).powi(2), n[2] as f64 * 0.5])
                .collect()
        });
        let faces: [Grid2<3>; 6] = std::array::from_fn(|f| coons_face(f, &edges, dims));
        let f = Faces::new(faces, "b").unwrap();
        assert_eq!(f.dims(), dims);
        assert_eq!(f.face(3).point(2, 4), [2.0, 4.0, 2.0]);
    }
}
