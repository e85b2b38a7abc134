//! `ellipgrid step`: list and grid the faces of a STEP file, export a Plot3D surface block
//! (a Hermite control net) to STEP as a bicubic B-spline face. The work is in
//! [`ellipgrid::cad`].

use clap::{Args, Subcommand};
use ellipgrid::cad::{self, Route, StepFace};
use ellipgrid::case::DistributionSpec;
use ellipgrid::grid::Edge;
use ellipgrid::io::connectivity::{self, ConnFile};
use ellipgrid::io::plot3d::{self, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::job::MeshOptions;
use ellipgrid::quality::quality3d::AnyQuality;
use ellipgrid::{job, solve, Error, Result};
use ellipgrid_geometry::{HermiteSurface, Vec3};
use rayon::prelude::*;
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
        /// Also print each face's outer-loop edges (numbered from 1 in loop order, as case
        /// files name them in `curve = { type = "edges", face, edges }`) with their ends.
        #[arg(long)]
        edges: bool,
    },
    /// Grid faces of a STEP file as four-sided block faces by the Section 4 pipeline: any face
    /// bounded by one loop of edges, on any surface type; a face with holes as an O-type ring
    /// of four blocks around each hole, a closed band without a seam edge as four blocks.
    Grid(GridArgs),
    /// Write a surface block of a Plot3D file, taken as a Hermite control net, as a bicubic
    /// B-spline face in a STEP file (or every block, as the faces of one shell).
    Export {
        /// The control net: a Plot3D file (any flavour) with a surface (or planar) block.
        net: PathBuf,
        /// The block to export (1-based).
        #[arg(long, default_value_t = 1, conflicts_with = "all")]
        block: usize,
        /// Export every block, as faces 1, 2, … of one open shell in the file's block order.
        #[arg(long)]
        all: bool,
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
    /// Grid every face, each on its own and in parallel: the grids of the faces that could be
    /// gridded are written, the others listed on stderr with the reason (exit code 2).
    #[arg(long)]
    all: bool,
    /// Nodes along the first and third sides of each face (i direction; for an untrimmed
    /// patch the sides v = 0 and v = 1).
    #[arg(long, default_value_t = 65)]
    ni: usize,
    /// Nodes along the second and fourth sides of each face (j direction).
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
    /// Linear solver of each face's elliptic steps (its (u, v) parametrization and the
    /// Laplace–Beltrami step): "multigrid" (default) or "direct" (faer's sparse LU).
    #[arg(long, default_value = "multigrid")]
    linear: String,
    /// Output file(s): .x/.xyz/.p3d/.g (Plot3D), .vts, .vtm, .glb, .gltf, .obj; one block
    /// per face, named `faceN` (`faceN.b0`, `faceN.b1`, … for a face of several blocks).
    #[arg(short, long = "output", value_name = "OUT", required = true)]
    output: Vec<PathBuf>,
    /// Cut every one-loop face at its reentrant vertices (where the loop turns outwards by
    /// more than 20°) into blocks, not only those whose one block folds (the face stays one
    /// block where it cannot be cut or its blocks fold).
    #[arg(long)]
    cut_reentrant: bool,
    /// Write the grid even if it folds (the exit code is still 3).
    #[arg(long)]
    allow_folded: bool,
    /// Largest defect of a face's boundary healed, in percent of the loop's size: edges whose
    /// ends miss each other, or points off the face's surface, beyond the file's tolerance
    /// (sloppy exports). Each edge is then moved by a shift blended along it so the edges
    /// meet, and the face's report says how far. 0 refuses any such face.
    #[arg(long, value_name = "PERCENT", default_value_t = 100.0 * cad::HEAL)]
    heal: f64,
    /// Print only errors.
    #[arg(short, long)]
    quiet: bool,
}

/// Runs `ellipgrid step …`.
pub fn step(a: &StepArgs) -> Result<()> {
    match &a.command {
        StepCommand::List { file, edges } => list(file, *edges),
        StepCommand::Grid(g) => grid(g),
        StepCommand::Export {
            net,
            block,
            all,
            output,
            quiet,
        } => export(net, (!*all).then_some(*block), output, *quiet),
    }
}

fn list(file: &Path, edges: bool) -> Result<()> {
    let read = cad::read_step(file)?;
    for f in read.faces {
        let what = match f.route() {
            Route::Patch => {
                let (p, q) = f.surface.as_ref().map_or((0, 0), |s| s.degrees());
                format!("four-sided patch, degrees {p} × {q}{}", creases(&f))
            }
            Route::Trimmed(n) => format!(
                "block face: one loop of {n} edge{}",
                if n == 1 { "" } else { "s" }
            ),
            Route::Holes(n) => format!(
                "{} boundary loops, gridded as several blocks: an O-type ring of 4 around each \
                 hole, or 4 across a closed band",
                n + 1
            ),
            Route::Refused(why) => format!("not gridable: {why}"),
        };
        println!("face {}: {}, {what}", f.index, f.surface_type);
        if edges {
            list_edges(&f);
        }
    }
    for u in &read.unread {
        println!("not read: {u}");
    }
    Ok(())
}

/// `step list --edges`: the face's outer-loop edges, each with its ends and chord.
fn list_edges(f: &StepFace) {
    let n = f
        .loops
        .as_ref()
        .map_or(0, |l| l.first().map_or(0, Vec::len));
    for k in 1..=n {
        let at = format!("face {}, edge {k}", f.index);
        match cad::EdgeChain::new(f, &[k], &at) {
            Ok(c) => {
                let (a, b) = (c.point(0.0), c.point(1.0));
                println!(
                    "  edge {k}: ({:.6}, {:.6}, {:.6}) → ({:.6}, {:.6}, {:.6})",
                    a.x, a.y, a.z, b.x, b.y, b.z
                );
            }
            Err(e) => println!("  edge {k}: {e}"),
        }
    }
}

/// The cut lines of a patch for `step list`: "; creases at u = … (normal turning …)",
/// "; a cut at v = … (a side turns …)" or nothing.
fn creases(f: &StepFace) -> String {
    let cuts = cad::creases(f);
    let c: Vec<String> = cuts.iter().map(|c| c.to_string()).collect();
    let creased =
        (cuts.iter()).all(|c| matches!(c.kind, cad::CutKind::Crease | cad::CutKind::Pole));
    match (c.len(), creased) {
        (0, _) => String::new(),
        (1, true) => format!("; a crease at {}", c[0]),
        (1, false) => format!("; a cut at {}", c[0]),
        (_, true) => format!("; creases at {}", c.join(", ")),
        (_, false) => format!("; cuts at {}", c.join(", ")),
    }
}

/// The sub-patches a patch is cut into, gridded or left out (1 without cuts).
fn crease_pieces(c: &[cad::Crease]) -> usize {
    let n = |d: usize| c.iter().filter(|c| c.dir == d).count() + 1;
    n(0) * n(1)
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
    if !(0.0..=10.0).contains(&a.heal) {
        return Err(Error::input(
            "--heal",
            format!(
                "the percentage healed must be between 0 and 10, got {}",
                a.heal
            ),
        ));
    }
    let cad::StepFaces { mut faces, unread } = cad::read_step(&a.file)?;
    for f in &mut faces {
        f.heal = a.heal / 100.0;
    }
    if a.face.is_none() {
        for u in &unread {
            eprintln!("not read: {name}: {u}");
        }
    }
    let chosen: Vec<&StepFace> = match a.face {
        Some(n) => {
            let f = n.checked_sub(1).and_then(|k| faces.get(k)).ok_or_else(|| {
                Error::input(
                    format!("{name}: face {n}"),
                    format!("no such face: the file has faces 1 to {}", faces.len()),
                )
            })?;
            if let Route::Refused(why) = f.route() {
                return Err(Error::input(format!("{name}: face {n}"), why));
            }
            vec![f]
        }
        None => faces.iter().collect(),
    };
    let mut budget = ellipgrid::case::limits::Budget::default();
    for f in &chosen {
        let at = format!("{name}: face {} (--ni, --nj)", f.index);
        let blocks = match f.route() {
            Route::Holes(n) => 4 * n,
            Route::Patch => cad::creased_blocks(f),
            _ => 1,
        };
        for _ in 0..blocks {
            budget.add_solved(
                &at,
                &[a.ni, a.nj],
                ellipgrid::case::limits::BYTES_PER_NODE_2D,
                &a.linear,
            )?;
        }
    }
    budget.check_memory(&format!("{name} (--ni, --nj)"))?;
    let (di, dj) = (spacing(a.first_i, a.last_i), spacing(a.first_j, a.last_j));
    solve::select::by_name(&a.linear).map_err(|m| Error::input("--linear", m))?;
    // Every face on its own (in parallel): one face's failure does not lose the others.
    let results: Vec<(&StepFace, Result<Vec<cad::FaceGrid>>)> = chosen
        .par_iter()
        .map(|f| {
            let place = format!("{name}: face {}", f.index);
            let r = solve::select::by_name(&a.linear)
                .map_err(|m| Error::input("--linear", m))
                .and_then(|mut solver| {
                    if a.cut_reentrant && matches!(f.route(), Route::Trimmed(_)) {
                        let s = solver.as_mut();
                        let cut = cad::grid_face_split(f, (a.ni, a.nj), &di, &dj, s, &place);
                        if let Ok(gs) = cut {
                            if gs.iter().all(|g| !g.quality.is_folded()) {
                                return Ok(gs);
                            }
                        }
                    }
                    cad::grid_face_blocks(f, (a.ni, a.nj), &di, &dj, solver.as_mut(), &place)
                });
            (*f, r)
        })
        .collect();
    let mut blocks = Vec::new();
    let mut fold: Option<Error> = None;
    let (mut failed, mut folded) = (Vec::new(), Vec::new());
    let mut folded_cells = 0;
    let mut written_faces = 0;
    for (f, r) in results {
        let place = format!("{name}: face {}", f.index);
        let grids = match r {
            Ok(g) => g,
            Err(e) => {
                if a.face.is_some() {
                    return Err(e);
                }
                eprintln!("not gridded: {e}");
                failed.push(f.index);
                continue;
            }
        };
        // A face of several blocks (holes) is written, or left out, as a whole.
        let several = grids.len() > 1;
        let cut = grids.first().filter(|g| !g.patch_cuts.is_empty());
        if let (false, Some(g0)) = (a.quiet, cut) {
            // a patch cut along its creases, kinks or fold-backs (its one block folds)
            let left_out = crease_pieces(&g0.patch_cuts) - grids.len();
            println!(
                "face{}: cut along {} into {} block{}{}",
                f.index,
                (g0.patch_cuts.iter().map(|c| c.to_string()))
                    .collect::<Vec<_>>()
                    .join(", "),
                grids.len(),
                if several { "s" } else { "" },
                if left_out > 0 {
                    format!(" ({left_out} sub-patch(es) left out)")
                } else {
                    String::new()
                }
            );
        }
        let mut face_blocks = Vec::with_capacity(grids.len());
        let mut face_folded = false;
        for (b, g) in grids.into_iter().enumerate() {
            let (place, block) = if several {
                (
                    format!("{place}, block {b}"),
                    format!("face{}.b{b}", f.index),
                )
            } else {
                (place.clone(), format!("face{}", f.index))
            };
            let q = g.quality;
            if !a.quiet {
                println!("{block} ({}, {} × {} nodes):", f.surface_type, a.ni, a.nj);
                if !g.corner_angles.is_empty() {
                    let angles: Vec<String> = g
                        .corner_angles
                        .iter()
                        .map(|d| {
                            if d.is_nan() {
                                "pole".to_string()
                            } else {
                                format!("{d:.0}°")
                            }
                        })
                        .collect();
                    println!(
                        "  corners turning {}; boundary within {:.1e} of the surface",
                        angles.join(", "),
                        g.gap
                    );
                    // a cusp gridded as a collapsed side (a pole says so above)
                    let point = |e: Edge| {
                        let s = g.result.grid.edge(e);
                        s.iter().all(|p| *p == s[0])
                    };
                    if !g.corner_angles[0].is_nan() && point(Edge::E1) {
                        // a cusp turns by more than 150° (an interior angle below 30°); a
                        // sharp vertex collapsed by the last try (`Corners::Tips`) is a tip
                        let name = |turn: f64| if turn > 150.0 { "cusp" } else { "tip" };
                        let first = name(g.corner_angles[0]);
                        let sides = if point(Edge::E2) {
                            let second = name(g.corner_angles[2]);
                            if first == second {
                                format!("sides E1 and E2 collapsed to the {first}s")
                            } else {
                                format!("sides E1 and E2 collapsed to a {first} and a {second}")
                            }
                        } else {
                            format!("side E1 collapsed to the {first}")
                        };
                        println!("  {sides}: the cells there are triangles");
                    }
                }
                if g.healed > 0.0 {
                    println!(
                        "  healed: the file's edges miss each other or the surface by up to \
                         {:.3e}, beyond its tolerance (--heal)",
                        g.healed
                    );
                }
                println!("{q}");
            }
            let q = AnyQuality::from(q);
            if q.is_folded() {
                let e = Error::Folded {
                    place,
                    count: q.folded_cells(),
                    first: q.folded_list(),
                };
                face_folded = true;
                folded_cells += q.folded_cells();
                // With --all the face is left out; the others are still written.
                if !a.allow_folded && a.face.is_none() {
                    eprintln!("not written: {e}");
                }
                fold.get_or_insert(e);
            }
            face_blocks.push((block, Block::Surface(g.result.grid)));
        }
        if face_folded {
            folded.push(f.index);
            if !a.allow_folded && a.face.is_none() {
                continue;
            }
        }
        blocks.extend(face_blocks);
        written_faces += 1;
    }
    let write = a.face.is_none() || fold.is_none() || a.allow_folded;
    if blocks.is_empty() {
        return Err(
            fold.unwrap_or_else(|| Error::input(&name, "no face could be gridded (reasons above)"))
        );
    }
    if write {
        let conn = face_connectivity(&blocks);
        let written = job::write_outputs_with(
            &blocks,
            Some(&conn),
            &a.output,
            &Plot3dFormat::default(),
            &MeshOptions::default(),
        )?;
        if !a.quiet {
            for p in &written {
                println!("wrote {}", p.display());
            }
        }
    }
    if a.face.is_some() {
        return fold.map_or(Ok(()), Err);
    }
    let total = chosen.len();
    if !folded.is_empty() {
        return Err(Error::Folded {
            place: name,
            count: folded_cells,
            first: format!(
                "faces {folded:?} (of {total}; {} written{})",
                written_faces,
                if failed.is_empty() {
                    String::new()
                } else {
                    format!(", faces {failed:?} not gridded")
                }
            ),
        });
    }
    if !failed.is_empty() || !unread.is_empty() {
        let mut why = Vec::new();
        if !failed.is_empty() {
            why.push(format!("not gridded: faces {failed:?}"));
        }
        if !unread.is_empty() {
            let ids: Vec<String> = unread.iter().map(|u| format!("#{}", u.face)).collect();
            why.push(format!("not read: face entities {}", ids.join(", ")));
        }
        return Err(Error::input(
            name,
            format!(
                "{written_faces} of {total} faces gridded and written; {} (reasons above)",
                why.join("; ")
            ),
        ));
    }
    Ok(())
}

/// Relative tolerance (of the grids' bounding-box diagonal) within which block sides of the
/// written faces count as one 1-to-1 interface: a face's cuts are shared bit for bit, faces
/// that share a CAD edge match when they put the same nodes on it.
/// The connectivity of the written face blocks (`.conn`, and the families of the solver
/// meshes): interfaces where block sides coincide node for node, every other side a patch of
/// its face's family `face<N>`.
fn face_connectivity(blocks: &[(String, Block)]) -> ConnFile {
    connectivity::of_surface_blocks(blocks, |name| {
        name.split('.').next().unwrap_or(name).to_string()
    })
}

/// Writes block `block` of the control-net file `net` (every block if `None`) as bicubic
/// B-spline faces of one STEP shell.
fn export(net: &Path, block: Option<usize>, output: &Path, quiet: bool) -> Result<()> {
    let file = plot3d::read_plot3d(net)?;
    let blocks: Vec<usize> = match block {
        Some(k) => vec![k],
        None => (1..=file.blocks.len()).collect(),
    };
    let mut surfaces = Vec::with_capacity(blocks.len());
    let mut sizes = Vec::with_capacity(blocks.len());
    for k in blocks {
        let place = format!("{}: block {k}", net.display());
        let b = k
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
        surfaces.push(h.to_bspline());
        sizes.push(format!("{ni} × {nj}"));
    }
    cad::write_step_surfaces(output, &surfaces)?;
    if !quiet {
        let what = match sizes.as_slice() {
            [one] => format!("{one} control net as a bicubic B-spline face"),
            many => format!(
                "{} control nets ({}) as bicubic B-spline faces",
                many.len(),
                many.join(", ")
            ),
        };
        println!("wrote {} ({what})", output.display());
    }
    Ok(())
}
