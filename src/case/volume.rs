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
//!   face orientation of [`crate::grid::faces`] unless `orient` says otherwise.
//!
//! Files: this one (the `[[volume]]` table, faces from edges or from a file), [`coons`] (the
//! Coons patches of the faces), [`run`] (generation, start grids and smoothing of volume blocks).

use crate::algebraic::coons::{coons_eval, coons_face, coons_params, is_planar};
use crate::algebraic::transform::ParamGrid;
use crate::algebraic::ControlKind;
use crate::case::spec::VolumeSpec;
use crate::case::LoadedCase;
use crate::elliptic::domain::grid_block;
use crate::elliptic::picard::PicardParams;
use crate::elliptic::wall::correct_side_faces;
use crate::grid::faces::{edge_of, parse_face, Orient};
use crate::grid::faces::{face_dims, Faces, FACE_NAMES};
use crate::io::Block;
use crate::solve::direct::DirectLu;
use crate::{Error, Grid2, Result};

/// Maps a stored face grid onto the face orientation by an `orient` string (see
/// [`crate::case::spec::FacesFile::orient`] and [`Orient`]).
fn reorient(g: &Grid2<3>, spec: &str, want: [usize; 2], at: &str) -> Result<Grid2<3>> {
    let o = Orient::parse(spec).ok_or_else(|| {
        Error::input(
            at,
            format!("orient '{spec}': expected ab, ba, -ab, a-b, -a-b, -ba, b-a or -b-a"),
        )
    })?;
    let [np, nq] = o.face_dims(want);
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
    Ok(o.to_block_face(g))
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
    let dims = v.dims(&place)?;
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
        let file = crate::case::within(&place, crate::io::plot3d::read_plot3d(&path))?;
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
                let b = crate::grid::boundary::Boundary2::from_grid(g, &fp)?;
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
    let faces = Faces::new(faces, &place)?;
    match wall_face(v, &place)? {
        None => Ok(faces),
        Some(w) => {
            let mut params_of = |f: usize| coons_params(f, &edges, dims);
            let mut eval = |f: usize, pg: &ParamGrid, g: &Grid2<3>| -> Result<Grid2<3>> {
                let coons = coons_eval(f, &edges, dims, pg);
                if !(elliptic && is_planar(&coons)) {
                    return Ok(coons);
                }
                let fp = format!("{place}, face {}", FACE_NAMES[f]);
                let mut x = g.clone();
                let ctrl = crate::algebraic::control2d::Control2::from_algebraic(pg);
                crate::elliptic::poisson2d::solve(
                    &mut x,
                    &ctrl,
                    &mut DirectLu::new(),
                    params,
                    &fp,
                )?;
                Ok(x)
            };
            correct_side_faces(&faces, w, &place, &mut params_of, &mut eval)
        }
    }
}

/// The wall face of a volume spec, if any.
pub(crate) fn wall_face(v: &VolumeSpec, place: &str) -> Result<Option<usize>> {
    v.wall
        .as_deref()
        .map(|s| {
            parse_face(s)
                .ok_or_else(|| Error::input(place, format!("wall = '{s}': expected F1, …, F6")))
        })
        .transpose()
}

#[cfg(test)]
mod tests {
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
}
