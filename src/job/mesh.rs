//! Solver meshes of a job: OpenFOAM, SU2, Gmsh (merged through [`crate::io::mesh`]) and
//! CGNS, with the options `[output]` and `convert` give them.

use super::OutputKind;
use crate::case::LoadedCase;
use crate::io::connectivity::ConnFile;
use crate::io::foam_case::{Flow, FlowInput};
use crate::io::mesh::Mesh;
use crate::io::Block;
use crate::{Error, Result};
use std::path::{Path, PathBuf};

/// The span along z of a planar grid written as an OpenFOAM mesh (one cell thick), unless
/// `[output] span` or `convert --span` say otherwise.
pub const FOAM_SPAN: f64 = 1.0;

/// Options of the solver meshes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshOptions {
    /// Thickness along z of planar grids extruded one cell thick (OpenFOAM; z from 0 to
    /// `span`). Default [`FOAM_SPAN`].
    pub span: f64,
    /// OpenFOAM's binary format instead of ASCII.
    pub foam_binary: bool,
    /// The flow of a runnable OpenFOAM case (`DIR/NAME.foam`).
    pub flow: Flow,
}

impl Default for MeshOptions {
    fn default() -> Self {
        MeshOptions {
            span: FOAM_SPAN,
            foam_binary: false,
            flow: Flow::default(),
        }
    }
}

impl MeshOptions {
    /// Options with the extrusion span `span`, checked (finite, > 0); `place` names where it
    /// was given.
    ///
    /// # Errors
    /// [`Error::Input`] naming `place` for a span that is not a positive number.
    pub fn with_span(span: f64, place: &str) -> Result<MeshOptions> {
        if !(span.is_finite() && span > 0.0) {
            return Err(Error::input(
                place,
                format!("span = {span}: the extrusion span must be a number > 0"),
            ));
        }
        Ok(MeshOptions {
            span,
            ..MeshOptions::default()
        })
    }

    /// These options with OpenFOAM's format named `format` ("ascii" or "binary"); `place`
    /// names where it was given.
    ///
    /// # Errors
    /// [`Error::Input`] naming `place` for another name.
    pub fn with_foam_format(self, format: &str, place: &str) -> Result<MeshOptions> {
        let foam_binary = match format {
            "ascii" => false,
            "binary" => true,
            _ => {
                return Err(Error::input(
                    place,
                    format!("OpenFOAM format '{format}': expected ascii or binary"),
                ))
            }
        };
        Ok(MeshOptions {
            foam_binary,
            ..self
        })
    }
}

/// The solver-mesh options asked for by `[output]` (`span`, `foam_format`) and `[flow]`.
///
/// # Errors
/// [`Error::Input`] naming the case's `[output]` for a span that is not > 0 or an unknown
/// OpenFOAM format, or its `[flow]` and the key of a bad flow value.
pub fn mesh_options(case: &LoadedCase) -> Result<MeshOptions> {
    let place = format!("{}: [output]", case.path.display());
    let o = &case.case.output;
    let m = match o.span {
        Some(s) => MeshOptions::with_span(s, &place)?,
        None => MeshOptions::default(),
    };
    let m = match &o.foam_format {
        Some(f) => m.with_foam_format(f, &place)?,
        None => m,
    };
    let place = format!("{}: [flow]", case.path.display());
    Ok(MeshOptions {
        flow: Flow::from_input(&flow_input(case), &place, str::to_string)?,
        ..m
    })
}

/// The case's `[flow]` values as given (unchecked; [`mesh_options`] checks them).
pub fn flow_input(case: &LoadedCase) -> FlowInput {
    let f = &case.case.flow;
    FlowInput {
        speed: f.speed,
        alpha: f.alpha,
        sideslip: f.sideslip,
        nu: f.nu,
        reynolds: f.reynolds,
        length: f.length,
    }
}

/// `over`'s values where given, else `base`'s: the flow of `convert CASE.toml DIR/NAME.foam`
/// with flags over the case's `[flow]`. The viscosity goes as one group (`nu`, or
/// `reynolds` with `length`): a flag of that group replaces all three of the case's.
pub fn flow_over(base: &FlowInput, over: &FlowInput) -> FlowInput {
    let viscosity = over.nu.is_some() || over.reynolds.is_some() || over.length.is_some();
    let v = if viscosity { over } else { base };
    FlowInput {
        speed: over.speed.or(base.speed),
        alpha: over.alpha.or(base.alpha),
        sideslip: over.sideslip.or(base.sideslip),
        nu: v.nu,
        reynolds: v.reynolds,
        length: v.length,
    }
}

/// Writes a CGNS file (the `cgns` feature), or says how to get one.
fn write_cgns(path: &Path, blocks: &[(String, Block)], conn: &ConnFile) -> Result<()> {
    #[cfg(feature = "cgns")]
    {
        crate::io::cgns::write_cgns(path, blocks, conn)
    }
    #[cfg(not(feature = "cgns"))]
    {
        let _ = (blocks, conn);
        Err(Error::input(path.display().to_string(), NO_CGNS))
    }
}

/// Why a build without the `cgns` feature refuses CGNS files.
pub const NO_CGNS: &str = "this ellipgrid was built without CGNS: build it with `cargo build \
     --release --features cgns` (needs Debian's libcgns-dev and libclang-dev)";

/// Writes `blocks`, connected as `conn` says, as one unstructured solver mesh (OpenFOAM,
/// SU2 or Gmsh; `kind` says which) or as a structured CGNS file. Returns the files written.
///
/// # Errors
/// Those of [`Mesh::build`] and the writers.
pub fn write_mesh(
    path: &Path,
    kind: OutputKind,
    blocks: &[(String, Block)],
    conn: &ConnFile,
    options: &MeshOptions,
) -> Result<Vec<PathBuf>> {
    let place = path.display().to_string();
    match kind {
        OutputKind::Foam => {
            let planar = blocks.iter().any(|(_, b)| matches!(b, Block::Planar(_)));
            let mesh = Mesh::build(&place, blocks, conn, planar.then_some(options.span))?;
            crate::io::foam::write_polymesh_as(path, &mesh, options.foam_binary)?;
            Ok(["points", "faces", "owner", "neighbour", "boundary"]
                .iter()
                .map(|f| path.join(f))
                .collect())
        }
        OutputKind::FoamCase => {
            let planar = blocks.iter().any(|(_, b)| matches!(b, Block::Planar(_)));
            let mesh = Mesh::build(&place, blocks, conn, planar.then_some(options.span))?;
            crate::io::foam_case::write_case(path, &mesh, options.foam_binary, &options.flow)
        }
        OutputKind::Su2 => {
            crate::io::su2::write_su2(path, &Mesh::build(&place, blocks, conn, None)?)?;
            Ok(vec![path.to_path_buf()])
        }
        OutputKind::Msh => {
            crate::io::gmsh::write_msh(path, &Mesh::build(&place, blocks, conn, None)?)?;
            Ok(vec![path.to_path_buf()])
        }
        OutputKind::Cgns => {
            write_cgns(path, blocks, conn)?;
            Ok(vec![path.to_path_buf()])
        }
        _ => Err(Error::input(place, "not a solver mesh format")),
    }
}
