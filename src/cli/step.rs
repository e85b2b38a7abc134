//! `ellipgrid step`: list and grid the faces of a STEP file, export a Plot3D surface block
//! (a Hermite control net) to STEP as a bicubic B-spline face. The work is in
//! [`ellipgrid::cad`].

use clap::{Args, Subcommand};
use ellipgrid::cad::{self, StepFace};
use ellipgrid::case::DistributionSpec;
use ellipgrid::io::plot3d::{self, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::quality::quality3d::AnyQuality;
use ellipgrid::{job, quality, solve, Error, Result};
use ellipgrid_geometry::{HermiteSurface, Surface, Vec3};
use std::path::{Path, PathBuf};

/// Arguments of `ellipgrid step`.
#[derive(Args, Debug)]
pub struct StepArgs {
    #[command(subcommand)]
    command: StepCommand,
}

#[derive(Subcommand, Debug)]
enum StepCommand {
    /// List the faces of a STEP file: number, surface type, whether it can be gridded.
    List {
        /// The STEP file (.step/.stp).
        file: PathBuf,
    },
    /// Grid faces of a STEP file by the Section 4 pipeline (untrimmed four-sided B-spline or
    /// NURBS faces; others give an error naming the face).
    Grid(GridArgs),
    /// Write a surface block of a Plot3D file, taken as a Hermite control net, as a bicubic
    /// B-spline face in a STEP file.
    Export {
        /// The control net: a Plot3D file (any flavour) with a surface (or planar) block.
        net: PathBuf,
        /// The block to export (1-based).
        #[arg(long, default_value_t = 1)]
        block: usize,
        /// The STEP file to write.
        #[arg(short, long = "output", value_name = "OUT.step")]
        output: PathBuf,
        /// Print only errors.
        #[arg(short, long)]
        quiet: bool,
    },
}

/// Arguments of `ellipgrid step grid`.
#[derive(Args, Debug)]
struct GridArgs {
    /// The STEP file (.step/.stp).
    file: PathBuf,
    /// The face to grid (1-based, as numbered by `ellipgrid step list`).
    #[arg(long, required_unless_present = "all", conflicts_with = "all")]
    face: Option<usize>,
    /// Grid every face that can be gridded (the others are listed on stderr).
    #[arg(long)]
    all: bool,
    /// Nodes along the u sides of each face (i direction).
    #[arg(long, default_value_t = 65)]
    ni: usize,
    /// Nodes along the v sides of each face (j direction).
    #[arg(long, default_value_t = 49)]
    nj: usize,
    /// First spacing along the u sides (a length; Vinokur stretching; default uniform).
    #[arg(long, value_name = "DS")]
    first_i: Option<f64>,
    /// Last spacing along the u sides (a length).
    #[arg(long, value_name = "DS")]
    last_i: Option<f64>,
    /// First spacing along the v sides (a length).
    #[arg(long, value_name = "DS")]
    first_j: Option<f64>,
    /// Last spacing along the v sides (a length).
    #[arg(long, value_name = "DS")]
    last_j: Option<f64>,
    /// Linear solver of the Laplace–Beltrami step.
    #[arg(long, default_value = "direct")]
    linear: String,
    /// Output file(s): .x/.xyz/.p3d/.g (Plot3D), .vts, .vtm, .glb, .gltf, .obj; one block
    /// per face, named `faceN`.
    #[arg(short, long = "output", value_name = "OUT", required = true)]
    output: Vec<PathBuf>,
    /// Write the grid even if it folds (the exit code is still 3).
    #[arg(long)]
    allow_folded: bool,
    /// Print only errors.
    #[arg(short, long)]
    quiet: bool,
}

/// Runs `ellipgrid step …`.
pub fn step(a: &StepArgs) -> Result<()> {
    match &a.command {
        StepCommand::List { file } => list(file),
        StepCommand::Grid(g) => grid(g),
        StepCommand::Export {
            net,
            block,
            output,
            quiet,
        } => export(net, *block, output, *quiet),
    }
}

fn list(file: &Path) -> Result<()> {
    for f in cad::read_step_faces(file)? {
        let what = match (&f.surface, &f.trimmed) {
            (None, _) => match &f.surface_error {
                Some(e) => format!("not gridable: {e}"),
                None => "not gridable: not a B-spline/NURBS surface".to_string(),
            },
            (Some(_), Some(why)) => format!("not gridable: {why}"),
            (Some(s), None) => {
                let (p, q) = s.degrees();
                format!("four-sided patch, degrees {p} × {q}")
            }
        };
        println!("face {}: {}, {what}", f.index, f.surface_type);
    }
    Ok(())
}

fn spacing(first: Option<f64>, last: Option<f64>) -> DistributionSpec {
    match (first, last) {
        (None, None) => DistributionSpec::Uniform {},
        _ => DistributionSpec::Vinokur { first, last },
    }
}

fn grid(a: &GridArgs) -> Result<()> {
    for p in &a.output {
        job::output_kind(p)?;
    }
    let name = a.file.display().to_string();
    let faces = cad::read_step_faces(&a.file)?;
    let chosen: Vec<&StepFace> = match a.face {
        Some(n) => {
            let f = n.checked_sub(1).and_then(|k| faces.get(k)).ok_or_else(|| {
                Error::input(
                    format!("{name}: face {n}"),
                    format!("no such face: the file has faces 1 to {}", faces.len()),
                )
            })?;
            f.patch(&a.file)?;
            vec![f]
        }
        None => {
            let (ok, skip): (Vec<&StepFace>, Vec<&StepFace>) =
                faces.iter().partition(|f| f.is_four_sided_patch());
            for f in &skip {
                if let Err(e) = f.patch(&a.file) {
                    eprintln!("skipped: {e}");
                }
            }
            if ok.is_empty() {
                return Err(Error::input(
                    name,
                    "no face is an untrimmed four-sided B-spline/NURBS patch",
                ));
            }
            ok
        }
    };
    let mut budget = ellipgrid::case::limits::Budget::default();
    for f in &chosen {
        let at = format!("{name}: face {} (--ni, --nj)", f.index);
        budget.add(
            &at,
            &[a.ni, a.nj],
            ellipgrid::case::limits::BYTES_PER_NODE_2D,
        )?;
    }
    budget.check_memory(&format!("{name} (--ni, --nj)"))?;
    let (di, dj) = (spacing(a.first_i, a.last_i), spacing(a.first_j, a.last_j));
    let mut solver = solve::select::by_name(&a.linear).map_err(|m| Error::input("--linear", m))?;
    let mut blocks = Vec::new();
    let mut fold = None;
    for f in chosen {
        let place = format!("{name}: face {}", f.index);
        let s: &dyn Surface = f.patch(&a.file)?;
        let r = cad::grid_patch(s, (a.ni, a.nj), &di, &dj, solver.as_mut(), &place)?;
        let q = quality::quality_surface(&r.grid);
        if !a.quiet {
            println!("face {} ({} × {} nodes):", f.index, a.ni, a.nj);
            println!("{q}");
        }
        let q = AnyQuality::from(q);
        if fold.is_none() && q.is_folded() {
            fold = Some(Error::Folded {
                place,
                count: q.folded_cells(),
                first: q.folded_list(),
            });
        }
        blocks.push((format!("face{}", f.index), Block::Surface(r.grid)));
    }
    if fold.is_none() || a.allow_folded {
        let written = job::write_outputs(&blocks, &a.output, &Plot3dFormat::default())?;
        if !a.quiet {
            for p in &written {
                println!("wrote {}", p.display());
            }
        }
    }
    match fold {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

fn export(net: &Path, block: usize, output: &Path, quiet: bool) -> Result<()> {
    let file = plot3d::read_plot3d(net)?;
    let place = format!("{}: block {block}", net.display());
    let b = block
        .checked_sub(1)
        .and_then(|k| file.blocks.get(k))
        .ok_or_else(|| {
            Error::input(
                &place,
                format!("no such block: the file has {}", file.blocks.len()),
            )
        })?;
    let [ni, nj, _] = b.dims();
    let pts: Vec<Vec3> = match b {
        Block::Surface(g) => (0..g.len())
            .map(|p| Vec3::new(g.coord(0)[p], g.coord(1)[p], g.coord(2)[p]))
            .collect(),
        Block::Planar(g) => (0..g.len())
            .map(|p| Vec3::new(g.coord(0)[p], g.coord(1)[p], 0.0))
            .collect(),
        Block::Volume(_) => {
            return Err(Error::input(
                place,
                "a volume block is not a control net: give a surface block",
            ))
        }
    };
    let h = HermiteSurface::new(ni, nj, pts).map_err(|source| Error::Geometry {
        place: place.clone(),
        source,
    })?;
    cad::write_step_surface(output, &h.to_bspline())?;
    if !quiet {
        println!(
            "wrote {} ({ni} × {nj} control net as a bicubic B-spline face)",
            output.display()
        );
    }
    Ok(())
}
