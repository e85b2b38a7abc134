//! `ellipgrid convert IN OUT`: rewrites a grid in another format or Plot3D flavour, and the
//! loading of grid inputs shared with `ellipgrid plot`.

use clap::Args;
use ellipgrid::case::LoadedCase;
use ellipgrid::io::connectivity::ConnFile;
use ellipgrid::io::foam_case::{Flow, FlowInput};
use ellipgrid::io::gltf::{self, GltfOptions};
use ellipgrid::io::patches::CellMetric;
use ellipgrid::io::plot3d::{self, ByteOrder, Encoding, Plot3dFormat, Precision};
use ellipgrid::io::{vtk_read, Block};
use ellipgrid::job::{self, OutputKind};
use ellipgrid::{Error, Result};
use std::path::{Path, PathBuf};

/// Arguments of `ellipgrid convert`.
#[derive(Args, Debug)]
pub struct ConvertArgs {
    /// The input: a Plot3D grid (any flavour, autodetected), a VTK .vts/.vtm structured grid,
    /// a CGNS file (.cgns, with its connectivity; cgns feature), or a case file (.toml, run
    /// first).
    input: PathBuf,
    /// The output, by extension: .x/.xyz/.p3d/.g/.grd (Plot3D), .vts, .vtm, .glb, .gltf, .obj,
    /// .png or .svg, .conn (connectivity), .su2 (SU2), .msh (Gmsh 4.1), .cgns (CGNS, with the
    /// cgns feature), a directory named polyMesh (OpenFOAM; planar grids extruded one unit
    /// along z), or DIR/NAME.foam (a runnable OpenFOAM case in DIR: mesh, system/, 0/).
    output: PathBuf,
    /// Plot3D encoding: unformatted (Fortran records), formatted (ASCII) or stream (C binary).
    /// Default: the input's (unformatted for case files).
    #[arg(long, value_name = "ENC")]
    encoding: Option<String>,
    /// Plot3D precision: single or double. Default: the input's (double for case files).
    #[arg(long, value_name = "P")]
    precision: Option<String>,
    /// Plot3D without the block-count record (one block only).
    #[arg(long, conflicts_with = "multi_block")]
    single_block: bool,
    /// Plot3D with the block-count record.
    #[arg(long)]
    multi_block: bool,
    /// 2D Plot3D (x, y only; planar blocks only).
    #[arg(long, conflicts_with = "three_d")]
    two_d: bool,
    /// 3D Plot3D (planar blocks get z = 0).
    #[arg(long)]
    three_d: bool,
    /// Big-endian binary Plot3D.
    #[arg(long, conflicts_with = "little_endian")]
    big_endian: bool,
    /// Little-endian binary Plot3D.
    #[arg(long)]
    little_endian: bool,
    /// Plot3D with IBLANK (the input's values if it has them, else 1 everywhere).
    #[arg(long, conflicts_with = "no_iblank")]
    iblank: bool,
    /// Plot3D without IBLANK.
    #[arg(long)]
    no_iblank: bool,
    /// glTF: colour the vertices by a cell metric averaged to the nodes (skewness, jacobian or
    /// aspect).
    #[arg(long, value_name = "METRIC")]
    color: Option<String>,
    /// The connectivity of a Plot3D or VTK input (a `.conn` file: interfaces, boundary
    /// patches, families), for solver meshes (.su2, .msh, polyMesh, .foam). Default: the input's
    /// name with `.conn` if that file exists; without one, every block side is its own patch.
    #[arg(long, value_name = "FILE")]
    conn: Option<PathBuf>,
    /// OpenFOAM output of a planar grid: the thickness along z of the one cell it is
    /// extruded by (z from 0 to SPAN). Default: 1.
    #[arg(long, value_name = "SPAN")]
    span: Option<f64>,
    /// OpenFOAM output: "ascii" (default) or "binary" (raw numbers: smaller, faster).
    #[arg(long, value_name = "F")]
    foam_format: Option<String>,
    /// OpenFOAM case (DIR/NAME.foam): the free-stream speed. Default: 1. The flow flags
    /// (and --span, --foam-format) default to a case file input's `[flow]` (and `[output]`).
    #[arg(long, value_name = "V", allow_negative_numbers = true)]
    speed: Option<f64>,
    /// OpenFOAM case: the angle of attack in degrees (in the x–y plane of a planar grid, the
    /// x–z plane of a volume grid). Default: 0.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    alpha: Option<f64>,
    /// OpenFOAM case of a volume grid: the sideslip in degrees (towards +y). Default: 0.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    sideslip: Option<f64>,
    /// OpenFOAM case: the kinematic viscosity. Default: 1e-3 (or from --reynolds).
    #[arg(long, value_name = "NU", allow_negative_numbers = true)]
    nu: Option<f64>,
    /// OpenFOAM case: the Reynolds number speed × length / ν, instead of --nu.
    #[arg(long, value_name = "RE", allow_negative_numbers = true)]
    reynolds: Option<f64>,
    /// OpenFOAM case: the reference length of --reynolds. Default: 1.
    #[arg(long, value_name = "L", allow_negative_numbers = true)]
    length: Option<f64>,
    /// Print only errors.
    #[arg(short, long)]
    quiet: bool,
}

/// A loaded grid: named blocks, and the Plot3D flavour and IBLANK of a Plot3D input.
pub struct Loaded {
    pub blocks: Vec<(String, Block)>,
    pub format: Option<Plot3dFormat>,
    pub iblank: Option<Vec<Vec<i32>>>,
    /// The 2D multi-block topology of a case file (for pictures of it).
    pub topology: Option<ellipgrid::grid::topology::Topology>,
    /// The connectivity a CGNS input or a multi-block case file holds.
    pub conn: Option<ConnFile>,
    /// True for a case file (its topology gives the connectivity; `--conn` is refused).
    pub case: bool,
    /// A case file's solver-mesh options (`[output] span`, `foam_format`, `[flow]`, checked)
    /// and its `[flow]` as given: `convert`'s defaults, under its flags.
    pub case_mesh: Option<(job::MeshOptions, FlowInput)>,
}

/// Reads a grid input: a case file (`.toml`, gridded now; a folded grid is an error unless
/// `allow_folded`, then a warning), a `.vts`/`.vtm` VTK structured grid, or a Plot3D file of
/// any flavour.
pub fn load(path: &Path, allow_folded: bool, quiet: bool) -> Result<Loaded> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default();
    if ext == "toml" {
        let case = LoadedCase::read(path)?;
        let case_mesh = Some((job::mesh_options(&case)?, job::flow_input(&case)));
        let gen = job::generate(&case, |b| {
            if !quiet {
                println!("gridded block '{}' ({} × {})", b.name, b.ni, b.nj);
            }
        })?;
        if let Some(e) = gen.report.fold_error() {
            if !allow_folded {
                return Err(e);
            }
            eprintln!("warning: {e}");
        }
        return Ok(Loaded {
            blocks: gen.blocks,
            format: None,
            iblank: None,
            topology: gen.topology,
            conn: gen.connectivity,
            case: true,
            case_mesh,
        });
    }
    if ext == "vts" || ext == "vtm" {
        let blocks = if ext == "vtm" {
            vtk_read::read_vtm(path)?
        } else {
            let name = path
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or("block1");
            vec![(name.to_string(), vtk_read::read_vts(path)?)]
        };
        return Ok(Loaded {
            blocks,
            format: None,
            iblank: None,
            topology: None,
            conn: None,
            case: false,
            case_mesh: None,
        });
    }
    if ext == "cgns" {
        #[cfg(feature = "cgns")]
        {
            let (blocks, conn) = ellipgrid::io::cgns::read_cgns(path)?;
            return Ok(Loaded {
                blocks,
                format: None,
                iblank: None,
                topology: None,
                conn: Some(conn),
                case: false,
                case_mesh: None,
            });
        }
        #[cfg(not(feature = "cgns"))]
        return Err(Error::input(path.display().to_string(), job::NO_CGNS));
    }
    if matches!(ext.as_str(), "glb" | "gltf" | "obj" | "png" | "svg") {
        return Err(Error::input(
            path.display().to_string(),
            "cannot read this format: inputs are Plot3D grids (.x .xyz .p3d .g .grd, any \
             flavour), VTK structured grids (.vts, .vtm) or case files (.toml)",
        ));
    }
    let file = plot3d::read_plot3d(path)?;
    let blocks = file
        .blocks
        .into_iter()
        .enumerate()
        .map(|(k, b)| (format!("block{}", k + 1), b))
        .collect();
    Ok(Loaded {
        blocks,
        format: Some(file.format),
        iblank: file.iblank,
        topology: None,
        conn: None,
        case: false,
        case_mesh: None,
    })
}

/// Parses a metric name for `--color`.
pub fn metric(s: &str) -> Result<CellMetric> {
    CellMetric::parse(s).ok_or_else(|| {
        Error::input(
            "--color",
            format!("'{s}': expected skewness, jacobian or aspect"),
        )
    })
}

/// Runs `ellipgrid convert`.
pub fn convert(a: &ConvertArgs) -> Result<()> {
    let kind = job::output_kind(&a.output)?;
    let color = a.color.as_deref().map(metric).transpose()?;
    if color.is_some() && !matches!(kind, OutputKind::Glb | OutputKind::Gltf) {
        return Err(Error::input(
            a.output.display().to_string(),
            "--color colours glTF output (.glb, .gltf); pictures: ellipgrid plot --color",
        ));
    }
    if (a.span.is_some() || a.foam_format.is_some())
        && !matches!(kind, OutputKind::Foam | OutputKind::FoamCase)
    {
        return Err(Error::input(
            a.output.display().to_string(),
            "--span and --foam-format are options of OpenFOAM meshes (a directory named \
             polyMesh, or a case DIR/NAME.foam)",
        ));
    }
    let mut mesh = match a.span {
        Some(s) => job::MeshOptions::with_span(s, "--span")?,
        None => job::MeshOptions::default(),
    };
    if let Some(f) = &a.foam_format {
        mesh = mesh.with_foam_format(f, "--foam-format")?;
    }
    let flow = FlowInput {
        speed: a.speed,
        alpha: a.alpha,
        sideslip: a.sideslip,
        nu: a.nu,
        reynolds: a.reynolds,
        length: a.length,
    };
    if flow != FlowInput::default() && kind != OutputKind::FoamCase {
        return Err(Error::input(
            a.output.display().to_string(),
            "--speed, --alpha, --sideslip, --nu, --reynolds and --length set the flow of an \
             OpenFOAM case (DIR/NAME.foam)",
        ));
    }
    mesh.flow = Flow::from_input(&flow, "convert", |k| format!("--{k}"))?;
    let options = plot3d_options_given(a);
    if options && kind != OutputKind::Plot3d {
        return Err(Error::input(
            a.output.display().to_string(),
            "Plot3D options (--encoding, --precision, …) need a Plot3D output",
        ));
    }
    let input = load(&a.input, false, a.quiet)?;
    if let Some((case, case_flow)) = &input.case_mesh {
        // A case file's [output] and [flow] are the defaults; the flags given win.
        if a.span.is_none() {
            mesh.span = case.span;
        }
        if a.foam_format.is_none() {
            mesh.foam_binary = case.foam_binary;
        }
        let both = job::flow_over(case_flow, &flow);
        mesh.flow = Flow::from_input(&both, "convert: [flow] and flags", str::to_string)?;
    }
    let fmt = if options {
        Some(plot3d_format(a, input.format)?)
    } else {
        None
    };
    let blocks = &input.blocks;
    let written = match kind {
        OutputKind::Plot3d => {
            let mut f = fmt.unwrap_or(input.format.unwrap_or(Plot3dFormat {
                two_d: blocks.iter().all(|(_, b)| matches!(b, Block::Planar(_))),
                ..Plot3dFormat::default()
            }));
            if fmt.is_none() && blocks.len() > 1 {
                f.multi_block = true;
            }
            let only: Vec<&Block> = blocks.iter().map(|(_, b)| b).collect();
            let ib = if f.iblank {
                input.iblank.as_deref()
            } else {
                None
            };
            plot3d::write_plot3d(&a.output, &only, &f, ib)?;
            vec![a.output.clone()]
        }
        OutputKind::Glb => {
            gltf::write_glb(&a.output, blocks, &GltfOptions { color })?;
            vec![a.output.clone()]
        }
        OutputKind::Gltf => {
            gltf::write_gltf(&a.output, blocks, &GltfOptions { color })?;
            vec![a.output.with_extension("bin"), a.output.clone()]
        }
        OutputKind::Foam
        | OutputKind::FoamCase
        | OutputKind::Su2
        | OutputKind::Msh
        | OutputKind::Cgns
        | OutputKind::Connectivity => {
            let (conn, from) = connectivity(a, &input)?;
            if kind == OutputKind::Connectivity {
                ellipgrid::io::connectivity::write_file(&a.output, &conn)?;
                vec![a.output.clone()]
            } else {
                ellipgrid::io::staged(|| job::write_mesh(&a.output, kind, blocks, &conn, &mesh))
                    .map_err(|e| match (e, &from) {
                        // a range or family that does not fit the blocks: name the .conn
                        (Error::Input { place, msg }, Some(p)) => {
                            Error::input(format!("{place} (connectivity {})", p.display()), msg)
                        }
                        (e, _) => e,
                    })?
            }
        }
        _ => {
            let base = input.format.unwrap_or_default();
            job::write_outputs(blocks, std::slice::from_ref(&a.output), &base)?
        }
    };
    if !a.quiet {
        for p in &written {
            println!("wrote {}", p.display());
        }
    }
    Ok(())
}

/// The connectivity of the input: a case's topology, `--conn`, the `.conn` beside the input,
/// or every block side a patch of its own; with the file it was read from, if any.
fn connectivity(a: &ConvertArgs, input: &Loaded) -> Result<(ConnFile, Option<PathBuf>)> {
    if input.case && input.conn.is_some() && a.conn.is_some() {
        return Err(Error::input(
            "--conn",
            "a case file's topology gives the connectivity",
        ));
    }
    if let (Some(c), None) = (&input.conn, &a.conn) {
        return Ok((c.clone(), None));
    }
    let beside = a.input.with_extension("conn");
    let path = match &a.conn {
        Some(p) => Some(p.clone()),
        None => beside.is_file().then_some(beside),
    };
    match path {
        Some(p) => {
            let c = ellipgrid::io::connectivity::read(&p)?;
            if !a.quiet {
                println!("connectivity from {}", p.display());
            }
            Ok((c, Some(p)))
        }
        None => Ok((ellipgrid::io::mesh::sides_as_patches(&input.blocks), None)),
    }
}

/// True if any Plot3D flavour option was given (else the input's flavour is kept).
fn plot3d_options_given(a: &ConvertArgs) -> bool {
    a.encoding.is_some()
        || a.precision.is_some()
        || a.single_block
        || a.multi_block
        || a.two_d
        || a.three_d
        || a.big_endian
        || a.little_endian
        || a.iblank
        || a.no_iblank
}

/// The Plot3D flavour asked for: the input's flavour (`base`; case files: unformatted, double,
/// 2D) with the options applied.
fn plot3d_format(a: &ConvertArgs, base: Option<Plot3dFormat>) -> Result<Plot3dFormat> {
    let mut f = base.unwrap_or(Plot3dFormat {
        two_d: true,
        ..Plot3dFormat::default()
    });
    if let Some(e) = &a.encoding {
        f.encoding = Encoding::parse(e).ok_or_else(|| {
            Error::input(
                "--encoding",
                format!("'{e}': expected unformatted, formatted or stream"),
            )
        })?;
    }
    if let Some(p) = &a.precision {
        f.precision = Precision::parse(p).ok_or_else(|| {
            Error::input("--precision", format!("'{p}': expected single or double"))
        })?;
    }
    let set = |on: bool, off: bool, v: &mut bool| {
        if on {
            *v = true;
        } else if off {
            *v = false;
        }
    };
    set(a.multi_block, a.single_block, &mut f.multi_block);
    set(a.two_d, a.three_d, &mut f.two_d);
    set(a.iblank, a.no_iblank, &mut f.iblank);
    if a.big_endian {
        f.byte_order = ByteOrder::Big;
    } else if a.little_endian {
        f.byte_order = ByteOrder::Little;
    }
    Ok(f)
}
