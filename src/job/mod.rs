//! Runs a case: grids every block, measures its quality and writes the outputs.
//!
//! Generation and writing are separate so that a folded grid can be reported without any
//! output file being written.

pub mod floating;
mod mesh;
mod mirror;
pub mod model;
pub mod multiblock;
pub(crate) mod multiblock_wall;
pub mod multivolume;
pub mod smooth;
pub mod verify;
pub mod volume;

pub use mesh::{flow_input, flow_over, mesh_options, write_mesh, MeshOptions, FOAM_SPAN, NO_CGNS};

use crate::algebraic::transform::transfinite;
use crate::case::{BlockKind, LoadedCase};
use crate::elliptic::orthogonal::grid_block_sides;
use crate::elliptic::picard::PicardInfo;
use crate::elliptic::wall2d::{wall_spacings, WallSpacing2};
use crate::grid::Grid2;
use crate::io::connectivity::ConnFile;
use crate::io::plot3d::{self, ByteOrder, Encoding, Plot3dFormat, Precision};
use crate::io::{gltf, obj, vtk, Block};
use crate::quality::{self, QualityReport};
use crate::solve;
use crate::surface::pipeline::{grid_surface_orthogonal, StepTimes};
use crate::{Error, Result};
use ellipgrid_geometry::{Surface, SurfaceLocator, Vec3};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Report of one block: the solve history and the quality of the grid.
#[derive(Clone, Debug, Serialize)]
pub struct BlockReport {
    pub name: String,
    pub ni: usize,
    pub nj: usize,
    /// Wall-clock seconds of the block's generation.
    pub seconds: f64,
    /// The blocks gridded together with this one across floating edges ("a+b"), if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// The Picard history (planar and minimal blocks).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub picard: Option<PicardInfo>,
    /// Seconds per step of the Section 4 pipeline (surface blocks; no Picard iteration).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface_steps: Option<StepTimes>,
    /// Distance of the nodes from the block's `reference` surface, if it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface_distance: Option<SurfaceDistance>,
    /// How far the nodes of a block on a STEP model were moved onto the model at the end
    /// (the distance of its Hermite net's surface from the model there).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_distance: Option<SurfaceDistance>,
    /// The first spacing along each wall edge (`wall`) against its targets.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub wall: Vec<WallSpacing2>,
    pub quality: QualityReport,
}

/// Distance of a grid's nodes from a reference surface (closest-point projection).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SurfaceDistance {
    pub max: f64,
    pub rms: f64,
}

/// The distance of every node of `g` from `surface`: the closest sampled patch through the
/// BVH, then Newton ([`ellipgrid_geometry::SurfaceLocator`]).
pub fn surface_distance(
    g: &Grid2<3>,
    surface: &dyn Surface,
    place: &str,
) -> Result<SurfaceDistance> {
    use rayon::prelude::*;
    let loc = SurfaceLocator::new(surface, 64, 64).map_err(|source| Error::Geometry {
        place: place.to_string(),
        source,
    })?;
    let d: Vec<f64> = (0..g.len())
        .into_par_iter()
        .map(|n| {
            let p = Vec3::new(g.coord(0)[n], g.coord(1)[n], g.coord(2)[n]);
            let (u, v) = loc.closest(p);
            (surface.point(u, v) - p).norm()
        })
        .collect();
    Ok(SurfaceDistance {
        max: d.iter().cloned().fold(0.0, f64::max),
        rms: (d.iter().map(|v| v * v).sum::<f64>() / d.len().max(1) as f64).sqrt(),
    })
}

/// Report of a whole run (what `--report` writes as JSON).
#[derive(Clone, Debug, Serialize)]
pub struct RunReport {
    pub case: String,
    pub blocks: Vec<BlockReport>,
    /// Smoothness across every interior edge of a multi-block case.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub interfaces: Vec<multiblock::InterfaceReport>,
    /// Volume blocks (`[[volume]]`), after the blocks.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub volumes: Vec<crate::job::volume::VolumeReport>,
    /// The faces of a volume topology (`[[face]]`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub faces: Vec<multivolume::FaceReport>,
    /// Smoothness across every interior face of a volume topology.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub face_interfaces: Vec<multivolume::FaceInterfaceReport>,
    /// Files written (empty if nothing was written).
    pub outputs: Vec<String>,
}

impl RunReport {
    /// The first folded block, if any, as an error naming the cells.
    pub fn fold_error(&self) -> Option<Error> {
        self.blocks
            .iter()
            .find(|b| b.quality.is_folded())
            .map(|b| Error::Folded {
                place: format!("{}: block '{}'", self.case, b.name),
                count: b.quality.folded_cells,
                first: b
                    .quality
                    .first_folded
                    .iter()
                    .map(|c| format!("cell ({}, {})", c[0], c[1]))
                    .collect::<Vec<_>>()
                    .join(", "),
            })
            .or_else(|| {
                let v = self.volumes.iter().find(|v| v.quality.is_folded())?;
                Some(Error::Folded {
                    place: format!("{}: volume '{}'", self.case, v.name),
                    count: v.quality.folded_cells,
                    first: v.quality.folded_list(),
                })
            })
            .or_else(|| {
                let f = self.faces.iter().find(|f| f.quality.is_folded())?;
                Some(Error::Folded {
                    place: format!("{}: face '{}'", self.case, f.name),
                    count: f.quality.folded_cells,
                    first: f
                        .quality
                        .first_folded
                        .iter()
                        .map(|c| format!("cell ({}, {})", c[0], c[1]))
                        .collect::<Vec<_>>()
                        .join(", "),
                })
            })
    }
}

/// The grids of a case with their report.
pub struct Generated {
    pub blocks: Vec<(String, Block)>,
    pub report: RunReport,
    /// The 2D multi-block topology (for pictures of it).
    pub topology: Option<crate::grid::topology::Topology>,
    /// The connectivity of a multi-block case (2D or volume topology), for `.conn` files and
    /// solver meshes.
    pub connectivity: Option<ConnFile>,
}

/// A wall spacing is held on planar and minimal blocks (Section 2 and 3), not yet on surface
/// blocks (Section 4).
pub(crate) fn no_surface_wall(wall: [bool; 4], place: &str) -> Result<()> {
    if wall.contains(&true) {
        return Err(Error::input(
            place,
            "a wall spacing (wall) is held on planar and minimal blocks; surface blocks \
             (kind = \"surface\") do not support it yet",
        ));
    }
    Ok(())
}

/// Grids every block of a case. `progress` receives a line per finished block.
pub fn generate(case: &LoadedCase, mut progress: impl FnMut(&BlockReport)) -> Result<Generated> {
    let spec = &case.case;
    let mut blocks = Vec::new();
    let mut reports = Vec::new();
    let mut interfaces = Vec::new();
    if let Some(topo) = &case.topology {
        let g = multiblock::generate(case, topo)?;
        g.reports.iter().for_each(&mut progress);
        (blocks, reports, interfaces) = (g.blocks, g.reports, g.interfaces);
    }
    for k in 0..spec.blocks.len() {
        if case.topology.is_some() {
            break;
        }
        let t0 = Instant::now();
        let place = case.block_place(k);
        let mut solver = solve::select::by_name(&spec.solver.linear)
            .map_err(|m| Error::input(format!("{}: [solver]", case.path.display()), m))?;
        let (ctrl, params) = (spec.solver.control, &spec.solver.picard);
        let sides = case.block_sides(k)?;
        let orth = sides.orthogonal;
        let mut wall = Vec::new();
        let mut surface_steps = None;
        let mut surface_distance = None;
        let mut model_distance = None;
        let (block, picard, quality) = match spec.blocks[k].kind {
            BlockKind::Planar => {
                let b = case.planar_boundary(k)?;
                let r = grid_block_sides(&b, None, sides, ctrl, solver.as_mut(), params, &place)?;
                let q = quality::quality2d(&r.grid);
                wall = wall_spacings(&r.grid, sides.wall);
                (Block::Planar(r.grid), Some(r.picard), q)
            }
            BlockKind::Minimal => {
                let b = case.minimal_boundary(k)?;
                let r = grid_block_sides(&b, None, sides, ctrl, solver.as_mut(), params, &place)?;
                let q = quality::quality_surface(&r.grid);
                wall = wall_spacings(&r.grid, sides.wall);
                if let Some(s) = case.reference_surface(k)? {
                    surface_distance = Some(self::surface_distance(&r.grid, s.as_ref(), &place)?);
                }
                (Block::Surface(r.grid), Some(r.picard), q)
            }
            BlockKind::Surface => {
                no_surface_wall(sides.wall, &place)?;
                let r = if case.is_model_block(k) {
                    // a block face on a STEP model: its net's surface, nodes moved onto the model
                    let m = model::model_block(case, k)?;
                    let mut r =
                        grid_surface_orthogonal(&m.surface, &m.uv, orth, solver.as_mut(), &place)?;
                    model_distance = Some(model::onto_model(&mut r.grid, &m));
                    r
                } else {
                    let (surface, uv) = case.surface_block(k)?;
                    grid_surface_orthogonal(surface.as_ref(), &uv, orth, solver.as_mut(), &place)?
                };
                let q = quality::quality_surface(&r.grid);
                surface_steps = Some(r.times);
                (Block::Surface(r.grid), None, q)
            }
        };
        let dims = block.dims();
        let rep = BlockReport {
            name: case.block_name(k),
            ni: dims[0],
            nj: dims[1],
            seconds: t0.elapsed().as_secs_f64(),
            group: None,
            picard,
            surface_steps,
            surface_distance,
            model_distance,
            wall,
            quality,
        };
        progress(&rep);
        reports.push(rep);
        blocks.push((case.block_name(k), block));
    }
    let mut volumes = Vec::new();
    let (mut faces, mut face_interfaces) = (Vec::new(), Vec::new());
    if let Some(topo) = &case.topology3 {
        let g = multivolume::generate(case, topo)?;
        (blocks, volumes, faces, face_interfaces) = (g.blocks, g.volumes, g.faces, g.interfaces);
    }
    for k in 0..spec.volumes.len() {
        if case.topology3.is_some() {
            break;
        }
        let (name, block, rep) = crate::job::volume::generate_volume(case, k)?;
        volumes.push(rep);
        blocks.push((name, block));
    }
    let connectivity = connectivity(case).or_else(|| model_connectivity(case, &blocks));
    Ok(Generated {
        blocks,
        report: RunReport {
            case: case.path.display().to_string(),
            blocks: reports,
            interfaces,
            volumes,
            faces,
            face_interfaces,
            outputs: vec![],
        },
        topology: case.topology.clone(),
        connectivity,
    })
}

/// The connectivity of blocks on a STEP model gridded apart (a case without topology whose
/// blocks include one on a STEP model): interfaces where their sides coincide node for node
/// (blocks given the same edge get the same nodes on it), every other side a patch of the
/// block's own family, named after it.
fn model_connectivity(case: &LoadedCase, blocks: &[(String, Block)]) -> Option<ConnFile> {
    let any = (0..case.case.blocks.len()).any(|k| case.is_model_block(k));
    (any && case.topology3.is_none())
        .then(|| crate::io::connectivity::of_surface_blocks(blocks, |name| name.to_string()))
}

/// The connectivity of a multi-block case (2D or volume topology), if it has one.
pub fn connectivity(case: &LoadedCase) -> Option<ConnFile> {
    match (&case.topology, &case.topology3) {
        (Some(t), _) => Some(crate::io::connectivity::from_topology(t)),
        (_, Some(t)) => Some(crate::io::connectivity::from_topology3(t)),
        _ => None,
    }
}

/// The algebraic (transfinite) start grids of every block, as the Picard iteration sees them
/// (they may fold: the final grid does not depend on them).
pub fn start_grids(case: &LoadedCase) -> Result<Vec<(String, Block)>> {
    if let Some(topo) = &case.topology3 {
        return multivolume::start_grids(case, topo);
    }
    (0..case.case.blocks.len())
        .map(|k| {
            let start = match case.case.blocks[k].kind {
                BlockKind::Minimal => Block::Surface(transfinite(&case.minimal_boundary(k)?)),
                _ => Block::Planar(transfinite(&case.planar_boundary(k)?)),
            };
            Ok((case.block_name(k), start))
        })
        .chain((0..case.case.volumes.len()).map(|k| crate::job::volume::start_volume(case, k)))
        .collect()
}

/// The Plot3D flavour asked for by `[output]`.
pub fn plot3d_format(case: &LoadedCase) -> Result<Plot3dFormat> {
    let o = &case.case.output;
    let at = format!("{}: [output]", case.path.display());
    let mut f = Plot3dFormat {
        two_d: true,
        ..Plot3dFormat::default()
    };
    if let Some(e) = &o.encoding {
        f.encoding = Encoding::parse(e).ok_or_else(|| {
            Error::input(
                &at,
                format!("encoding '{e}': expected unformatted, formatted or stream"),
            )
        })?;
    }
    if let Some(p) = &o.precision {
        f.precision = Precision::parse(p).ok_or_else(|| {
            Error::input(&at, format!("precision '{p}': expected double or single"))
        })?;
    }
    f.byte_order = ByteOrder::Little;
    if let Some(m) = o.multi_block {
        f.multi_block = m;
    }
    if let Some(t) = o.two_d {
        f.two_d = t;
    }
    Ok(f)
}

/// What kind of file a path names, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputKind {
    Plot3d,
    Vts,
    Vtm,
    /// Binary glTF (`.glb`).
    Glb,
    /// glTF JSON with a `.bin` beside it.
    Gltf,
    /// Wavefront OBJ with a `.mtl` beside it.
    Obj,
    /// A picture (`.png` or `.svg`) with the default plot options.
    Picture,
    /// The connectivity of a multi-block case (`.conn`).
    Connectivity,
    /// An OpenFOAM mesh: a directory named `polyMesh`.
    Foam,
    /// A runnable OpenFOAM case (`DIR/NAME.foam`: mesh, `system/`, `0/` in `DIR`).
    FoamCase,
    /// An SU2 native mesh (`.su2`).
    Su2,
    /// A Gmsh MSH 4.1 mesh (`.msh`).
    Msh,
    /// A CGNS/HDF5 file (`.cgns`; needs the `cgns` feature).
    Cgns,
}

/// The output kind of a path, or an error listing the known extensions.
pub fn output_kind(path: &Path) -> Result<OutputKind> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default();
    if path.file_name().and_then(|n| n.to_str()) == Some("polyMesh") {
        return Ok(OutputKind::Foam);
    }
    match ext.as_str() {
        "x" | "xyz" | "p3d" | "g" | "grd" => Ok(OutputKind::Plot3d),
        "su2" => Ok(OutputKind::Su2),
        "msh" => Ok(OutputKind::Msh),
        "cgns" => Ok(OutputKind::Cgns),
        "foam" => Ok(OutputKind::FoamCase),
        "vts" => Ok(OutputKind::Vts),
        "vtm" => Ok(OutputKind::Vtm),
        "glb" => Ok(OutputKind::Glb),
        "gltf" => Ok(OutputKind::Gltf),
        "obj" => Ok(OutputKind::Obj),
        "png" | "svg" => Ok(OutputKind::Picture),
        "conn" => Ok(OutputKind::Connectivity),
        _ => Err(Error::input(
            path.display().to_string(),
            "unknown output extension: use .x/.xyz/.p3d/.g (Plot3D), .vts or .vtm (VTK), \
             .glb/.gltf (glTF), .obj (OBJ), .png/.svg (picture), .conn (connectivity), \
             .su2 (SU2), .msh (Gmsh), .cgns (CGNS), a directory named polyMesh \
             (OpenFOAM mesh) or DIR/NAME.foam (OpenFOAM case)",
        )),
    }
}

/// Cell quality fields of a block for VTK output.
fn cell_fields(b: &Block) -> Vec<(&'static str, Vec<f64>)> {
    match b {
        Block::Planar(g) => quality::cell_fields2d(g),
        Block::Surface(g) => quality::cell_fields_surface(g),
        Block::Volume(g) => crate::quality::quality3d::cell_fields3d(g),
    }
}

/// Writes blocks to `paths` (each atomically). Returns the files written.
pub fn write_outputs(
    blocks: &[(String, Block)],
    paths: &[PathBuf],
    fmt: &Plot3dFormat,
) -> Result<Vec<PathBuf>> {
    write_outputs_with(blocks, None, paths, fmt, &MeshOptions::default())
}

/// [`write_outputs`] with the connectivity of a multi-block case (for `.conn` files and the
/// solver meshes' families) and the solver meshes' options.
pub fn write_outputs_with(
    blocks: &[(String, Block)],
    topology: Option<&ConnFile>,
    paths: &[PathBuf],
    fmt: &Plot3dFormat,
    mesh: &MeshOptions,
) -> Result<Vec<PathBuf>> {
    // Check every path first, so that a bad name late in the list writes nothing.
    let kinds = paths
        .iter()
        .map(|p| output_kind(p))
        .collect::<Result<Vec<_>>>()?;
    if let Some(p) = paths
        .iter()
        .zip(&kinds)
        .find(|(_, k)| **k == OutputKind::Connectivity && topology.is_none())
    {
        return Err(Error::input(
            p.0.display().to_string(),
            "a connectivity file needs a multi-block case (with [[edge]] or [[face]] tables)",
        ));
    }
    // All or nothing: a failure at the third file must not leave the first two.
    crate::io::staged(|| write_each(blocks, topology, paths, &kinds, fmt, mesh))
}

/// The loop of [`write_outputs_with`], inside its stage.
fn write_each(
    blocks: &[(String, Block)],
    topology: Option<&ConnFile>,
    paths: &[PathBuf],
    kinds: &[OutputKind],
    fmt: &Plot3dFormat,
    mesh: &MeshOptions,
) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for (path, &kind) in paths.iter().zip(kinds) {
        match kind {
            OutputKind::Plot3d => {
                let only: Vec<&Block> = blocks.iter().map(|(_, b)| b).collect();
                let mut f = *fmt;
                if only.len() > 1 {
                    f.multi_block = true;
                }
                if only.iter().any(|b| !matches!(b, &&Block::Planar(_))) {
                    f.two_d = false;
                }
                plot3d::write_plot3d(path, &only, &f, None)?;
                written.push(path.clone());
            }
            OutputKind::Vts => {
                if blocks.len() != 1 {
                    return Err(Error::input(
                        path.display().to_string(),
                        format!("{} blocks do not fit one .vts file: use .vtm", blocks.len()),
                    ));
                }
                write_vts_block(path, &blocks[0].1)?;
                written.push(path.clone());
            }
            OutputKind::Vtm => {
                let stem = path
                    .file_stem()
                    .and_then(|s| s.to_str())
                    .unwrap_or("grid")
                    .to_string();
                let dir = path.parent().unwrap_or(Path::new(""));
                let mut pieces = Vec::new();
                for (k, (name, b)) in blocks.iter().enumerate() {
                    let file = PathBuf::from(format!("{stem}_{}_{name}.vts", k + 1));
                    write_vts_block(&dir.join(&file), b)?;
                    written.push(dir.join(&file));
                    pieces.push((name.clone(), file));
                }
                vtk::write_vtm(path, &pieces)?;
                written.push(path.clone());
            }
            OutputKind::Glb => {
                gltf::write_glb(path, blocks, &gltf::GltfOptions::default())?;
                written.push(path.clone());
            }
            OutputKind::Gltf => {
                gltf::write_gltf(path, blocks, &gltf::GltfOptions::default())?;
                written.push(path.with_extension("bin"));
                written.push(path.clone());
            }
            OutputKind::Obj => {
                obj::write_obj(path, blocks)?;
                written.push(path.with_extension("mtl"));
                written.push(path.clone());
            }
            OutputKind::Connectivity => {
                let conn = topology.expect("checked above");
                crate::io::connectivity::write_file(path, conn)?;
                written.push(path.clone());
            }
            OutputKind::Picture => {
                crate::plot::write_picture(path, blocks, &crate::plot::PlotOptions::default())?;
                written.push(path.clone());
            }
            OutputKind::Foam
            | OutputKind::FoamCase
            | OutputKind::Su2
            | OutputKind::Msh
            | OutputKind::Cgns => {
                let conn = match topology {
                    Some(c) => c.clone(),
                    None => crate::io::mesh::sides_as_patches(blocks),
                };
                written.extend(write_mesh(path, kind, blocks, &conn, mesh)?);
            }
        }
    }
    Ok(written)
}

fn write_vts_block(path: &Path, b: &Block) -> Result<()> {
    let fields = cell_fields(b);
    let cd: Vec<(&str, &[f64])> = fields.iter().map(|(n, v)| (*n, v.as_slice())).collect();
    vtk::write_vts(path, b, &cd, &[])
}
