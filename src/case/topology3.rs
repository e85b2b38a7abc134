//! The volume topology of a case file: `[[vertex]]`, `[[edge]]`, `[[face]]` tables and
//! `[[volume]]` tables naming six faces; named `[[surface]]` tables that faces lie on and
//! edge curves run along (README.md, "3D multi-block grids").

use super::spec::{FaceKind, FaceSpec};
use super::topology::{side_names, topo_edges};
use super::{Case, LoadedCase, SurfaceSpec};
use crate::grid::faces::FACE_NAMES;
use crate::grid::topology::volume::{Topology3, VolumeFaces};
use crate::grid::topology::{BlockSides, Topology};
use crate::{Error, Result};
use ellipgrid_geometry::Surface;
use std::sync::Arc;

/// The volume topology of a case with `[[face]]` tables (None otherwise, after checking that
/// no volume names faces). Every structural error names the file, volume, face and edge.
pub(super) fn build3(case: &Case, place: &str) -> Result<Option<Topology3>> {
    let names = |v: &super::spec::VolumeSpec| v.face_names().iter().any(|f| f.is_some());
    if case.faces.is_empty() {
        for (k, v) in case.volumes.iter().enumerate() {
            let at = volume_at(case, k, place);
            if names(v) {
                return Err(Error::input(
                    at,
                    "the volume names faces (F1 … F6) but the case has no [[face]] tables",
                ));
            }
            v.dims(&at)?;
        }
        return Ok(None);
    }
    if case.edges.is_empty() {
        return Err(Error::input(
            place,
            "the case has [[face]] tables but no [[edge]] tables: faces name their edges",
        ));
    }
    if !case.blocks.is_empty() {
        return Err(Error::input(
            place,
            "a case with [[face]] tables grids volumes: give its faces as [[face]] tables, not \
             [[block]] tables",
        ));
    }
    if case.volumes.is_empty() {
        return Err(Error::input(
            place,
            "the case has [[face]] tables but no [[volume]] naming them",
        ));
    }
    let (vertices, edges) = topo_edges(case, place)?;
    for (e, spec) in edges.iter().zip(&case.edges) {
        let at = format!("{place}: edge '{}'", e.name);
        if e.floating {
            return Err(Error::input(
                at,
                "floating edges are for 2D topologies; in a volume topology every edge is fixed",
            ));
        }
        if spec.wall {
            return Err(Error::input(
                at,
                "in a volume topology the wall spacing is held at a volume's face (wall = \"F3\" \
                 in its [[volume]] table), not at an edge",
            ));
        }
        if spec.orthogonal {
            return Err(Error::input(
                at,
                "in a volume topology an edge borders many faces: ask for orthogonality on the \
                 face (orthogonal = [\"E3\"] in its [[face]] table)",
            ));
        }
        if spec.family.is_some() || spec.bc.is_some() {
            return Err(Error::input(
                at,
                "in a volume topology the boundary patches are faces: give `family` and `bc` \
                 on the [[face]]",
            ));
        }
    }
    let mut sides = Vec::new();
    for f in &case.faces {
        let at = format!("{place}: face '{}'", f.name);
        check_kind(case, f, &at)?;
        sides.push(BlockSides {
            name: f.name.clone(),
            sides: side_names(f.sides(), &at)?,
            orthogonal: crate::elliptic::orthogonal::parse_edges(&f.orthogonal, &at)?,
            wall: [false; 4],
        });
    }
    let faces = Topology::new_faces(vertices, edges, &sides, place)?;
    let families = case
        .faces
        .iter()
        .map(|f| f.family.clone().unwrap_or_else(|| f.name.clone()))
        .collect();
    let mut volumes = Vec::new();
    for (k, v) in case.volumes.iter().enumerate() {
        let at = volume_at(case, k, place);
        if v.faces.is_some() || v.edge_specs().iter().any(|e| e.is_some()) {
            return Err(Error::input(
                at,
                "in a case with [[face]] tables a volume names its faces F1 … F6, not edges \
                 or a faces file",
            ));
        }
        let mut faces: [String; 6] = Default::default();
        for (s, name) in v.face_names().into_iter().enumerate() {
            faces[s] = name
                .clone()
                .ok_or_else(|| Error::input(&at, format!("missing face {}", FACE_NAMES[s])))?;
        }
        volumes.push(VolumeFaces {
            name: volume_name(case, k),
            faces,
        });
    }
    let bcs = case.faces.iter().map(|f| f.bc.clone()).collect();
    let topo = Topology3::new(faces, families, bcs, &volumes, place)?;
    check_bcs(&topo, place)?;
    check_floating(case, &topo, place)?;
    for (k, v) in case.volumes.iter().enumerate() {
        let dims = topo.volumes[k].dims;
        for (given, n, what) in [
            (v.ni, dims[0], "ni"),
            (v.nj, dims[1], "nj"),
            (v.nk, dims[2], "nk"),
        ] {
            if given.is_some_and(|g| g != n) {
                return Err(Error::input(
                    volume_at(case, k, place),
                    format!(
                        "{what} = {} but its faces give {n} nodes",
                        given.unwrap_or_default()
                    ),
                ));
            }
        }
    }
    Ok(Some(topo))
}

/// Checks the faces' `interface` keys: "fixed" or "floating", floating only on a face that
/// two volumes share (or one volume twice) and that is gridded alone (not on a surface).
fn check_floating(case: &Case, topo: &Topology3, place: &str) -> Result<()> {
    for (f, spec) in case.faces.iter().enumerate() {
        let at = format!("{place}: face '{}'", spec.name);
        match spec.interface.as_deref() {
            None | Some("fixed") => continue,
            Some("floating") => {}
            Some(other) => {
                return Err(Error::input(
                    at,
                    format!("interface = '{other}': expected \"fixed\" or \"floating\""),
                ))
            }
        }
        if topo.uses_of(f).len() != 2 {
            return Err(Error::input(
                at,
                "interface = \"floating\" is for a face between two volumes (or two sides of \
                 one); this face bounds one volume only",
            ));
        }
        if spec.kind == FaceKind::Surface {
            return Err(Error::input(
                at,
                "interface = \"floating\" moves the face's nodes off any surface: give it \
                 kind = \"minimal\" or \"tfi\"",
            ));
        }
    }
    Ok(())
}

/// Checks the faces' `bc` keys: a known kind, on boundary faces only, one per family.
fn check_bcs(topo: &Topology3, place: &str) -> Result<()> {
    use crate::io::connectivity::{BcKind, BC_NAMES};
    for (f, bc) in topo.bcs.iter().enumerate() {
        let Some(bc) = bc else { continue };
        let at = format!("{place}: face '{}'", topo.faces.blocks[f].name);
        if BcKind::parse(bc).is_none() {
            return Err(Error::input(
                at,
                format!("bc = '{bc}': expected one of {}", BC_NAMES.join(", ")),
            ));
        }
        if topo.uses_of(f).len() == 2 {
            return Err(Error::input(
                at,
                "bc = … on a face between two volumes: boundary conditions belong to boundary \
                 faces",
            ));
        }
        let other = (0..topo.bcs.len()).find(|&o| {
            topo.families[o] == topo.families[f] && topo.bcs[o].as_ref().is_some_and(|b| b != bc)
        });
        if let Some(o) = other {
            return Err(Error::input(
                at,
                format!(
                    "bc = '{bc}' but face '{}' of the same family '{}' has bc = '{}'",
                    topo.faces.blocks[o].name,
                    topo.families[f],
                    topo.bcs[o].as_deref().unwrap_or_default()
                ),
            ));
        }
    }
    Ok(())
}

fn volume_name(case: &Case, k: usize) -> String {
    case.volumes[k]
        .name
        .clone()
        .unwrap_or_else(|| format!("volume{}", k + 1))
}

fn volume_at(case: &Case, k: usize, place: &str) -> String {
    format!("{place}: volume '{}'", volume_name(case, k))
}

/// A face's kind against its keys: a surface face names a known `[[surface]]`, the others
/// none; a Coons face has no orthogonal sides.
fn check_kind(case: &Case, f: &FaceSpec, at: &str) -> Result<()> {
    match (f.kind, &f.surface) {
        (FaceKind::Surface, None) => Err(Error::input(
            at,
            "kind = \"surface\" needs surface = \"name\" of a [[surface]] table",
        )),
        (FaceKind::Surface, Some(s)) if !case.surfaces.iter().any(|n| &n.name == s) => Err(
            Error::input(at, format!("surface = '{s}': no [[surface]] named so")),
        ),
        (FaceKind::Tfi | FaceKind::Minimal, Some(_)) => Err(Error::input(
            at,
            "surface = … is for kind = \"surface\" faces",
        )),
        (FaceKind::Tfi, _) if !f.orthogonal.is_empty() => Err(Error::input(
            at,
            "orthogonal sides need an elliptic face: kind = \"minimal\" or \"surface\"",
        )),
        _ => Ok(()),
    }
}

impl LoadedCase {
    /// The `[[surface]]` named `name`, built once per run and shared.
    pub fn named_surface(&self, name: &str, at: &str) -> Result<Arc<dyn Surface>> {
        let k = self
            .case
            .surfaces
            .iter()
            .position(|s| s.name == name)
            .ok_or_else(|| Error::input(at, format!("no [[surface]] named '{name}'")))?;
        let built = self.surfaces.get_or_init(|| {
            (0..self.case.surfaces.len())
                .map(|_| std::sync::OnceLock::new())
                .collect()
        });
        if let Some(s) = built[k].get() {
            return Ok(Arc::clone(s));
        }
        let spec: &SurfaceSpec = &self.case.surfaces[k].surface;
        let place = format!("{}: surface '{name}'", self.path.display());
        let s: Arc<dyn Surface> = Arc::from(self.build_surface(spec, &place)?);
        Ok(Arc::clone(built[k].get_or_init(|| s)))
    }
}
