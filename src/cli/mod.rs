//! clap definitions and the subcommands. Exit codes: 0 success, 2 bad input (unreadable or
//! malformed files, inconsistent edges, …), 3 folded grid, 4 solver failure, 5 a property
//! `verify` checks fails.

mod convert;
mod plot;
mod print;
mod step;
mod verify;

use clap::{Parser, Subcommand};
use ellipgrid::case::LoadedCase;
use ellipgrid::elliptic::picard::{Nonlinear, PicardParams};
use ellipgrid::io::plot3d;
use ellipgrid::io::Block;
use ellipgrid::job;
use ellipgrid::job::smooth::{smooth_blocks, SmoothOptions, SurfaceMethod};
use ellipgrid::quality;
use ellipgrid::quality::quality3d::AnyQuality;
use ellipgrid::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Elliptic structured grid generation (Spekreijse & Boerstoel, NLR TP 96338).
#[derive(Parser, Debug)]
#[command(name = "ellipgrid", version, about, long_about = None)]
struct Opts {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Generate the grids of a case file and write them.
    Run {
        /// The case file (TOML; see README.md, "Case files").
        case: PathBuf,
        /// Output file(s), replacing `[output] files` of the case: .x/.xyz/.p3d/.g (Plot3D),
        /// .vts or .vtm (VTK). Repeat for several.
        #[arg(short, long = "output", value_name = "OUT")]
        output: Vec<PathBuf>,
        /// Write the run report (Picard history and quality of every block) as JSON.
        #[arg(long, value_name = "FILE.json")]
        report: Option<PathBuf>,
        /// Write the grid even if it folds (the exit code is still 3).
        #[arg(long)]
        allow_folded: bool,
        /// Also write the algebraic start grid of every block (it may fold) to this file.
        #[arg(long, value_name = "START")]
        write_start: Option<PathBuf>,
        /// Print only errors.
        #[arg(short, long)]
        quiet: bool,
    },
    /// Keep the boundary nodes of existing blocks and regrid their interiors elliptically.
    ///
    /// Planar blocks (and surface blocks with z = const) by the Poisson system of Section 2,
    /// curved surface blocks by the minimal-surface system of Section 3. Unselected blocks pass
    /// through unchanged; the output has the input's Plot3D flavour.
    Smooth {
        /// The input grid (Plot3D, any flavour; or CGNS with the cgns feature, whose block
        /// names and connectivity the outputs keep).
        input: PathBuf,
        /// The output grid (.x/.xyz/.p3d/.g Plot3D in the input's flavour, or .vts/.vtm, or
        /// any other output format).
        #[arg(short, long = "output", value_name = "OUT", required = true)]
        output: Vec<PathBuf>,
        /// Regrid only these blocks (1-based, comma separated), e.g. `--blocks 1,3`.
        #[arg(long, value_delimiter = ',', value_name = "K,..")]
        blocks: Option<Vec<usize>>,
        /// Linear solver of each Picard step: "multigrid" (default), "multigrid-lean" (less
        /// memory, slower) or "direct".
        #[arg(long, default_value = "multigrid")]
        linear: String,
        /// Picard tolerance (max node update / block diameter).
        #[arg(long, default_value_t = 1e-10)]
        tolerance: f64,
        /// Nonlinear iteration: "newton" (Newton–Krylov, the default of planar blocks) or
        /// "picard" (the default of minimal surfaces; README "Nonlinear solve"); volume blocks
        /// always take Picard steps.
        #[arg(long, value_parser = ["picard", "newton"])]
        nonlinear: Option<String>,
        /// Make the grid orthogonal at these edges (Section 2.4), e.g. `--orthogonal E1,E3`.
        #[arg(long, value_delimiter = ',', value_name = "E,..")]
        orthogonal: Vec<String>,
        /// Curved surface blocks: "poisson" regrids them as minimal surfaces spanned by their
        /// boundary (Section 3); "surface" keeps them on their own surface (a bicubic Hermite
        /// surface through the existing nodes) and regrids by Section 4.
        #[arg(long, default_value = "poisson", value_parser = ["poisson", "surface"])]
        method: String,
        /// Write the report (per block: method, start grid, Picard history, quality) as JSON.
        #[arg(long, value_name = "FILE.json")]
        report: Option<PathBuf>,
        /// Write the grid even if a regridded block folds (the exit code is still 3).
        #[arg(long)]
        allow_folded: bool,
        /// Print only errors.
        #[arg(short, long)]
        quiet: bool,
    },
    /// Print the quality report of every block of a Plot3D grid file (exit 3 if any folds).
    Check {
        /// The grid file (Plot3D, any flavour: autodetected).
        grid: PathBuf,
        /// Write the report as JSON.
        #[arg(long, value_name = "FILE.json")]
        report: Option<PathBuf>,
    },
    /// Convert a grid to another format or Plot3D flavour (Plot3D, VTK, glTF, OBJ, picture).
    Convert(convert::ConvertArgs),
    /// Draw a grid as a picture (.png or .svg): grid lines, close-ups, quality colours.
    Plot(plot::PlotArgs),
    /// STEP files: list and grid B-spline faces, export a control net as a B-spline face.
    Step(step::StepArgs),
    /// Check a case's grids under refinement: grid families (N, 2N − 1, 4N − 3) and their
    /// observed order, independence of the start grid and of the surface parametrization
    /// (exit 5 if a property fails).
    Verify(verify::VerifyArgs),
}

/// Parses the command line and runs it.
pub fn main() -> ExitCode {
    let opts = Opts::parse();
    let r = match opts.command {
        Command::Run {
            case,
            output,
            report,
            allow_folded,
            write_start,
            quiet,
        } => run(
            &case,
            &output,
            report.as_deref(),
            write_start.as_deref(),
            allow_folded,
            quiet,
        ),
        Command::Check { grid, report } => check(&grid, report.as_deref()),
        Command::Convert(a) => convert::convert(&a),
        Command::Plot(a) => plot::plot(&a),
        Command::Step(a) => step::step(&a),
        Command::Verify(a) => verify::run(&a),
        Command::Smooth {
            input,
            output,
            blocks,
            linear,
            tolerance,
            nonlinear,
            orthogonal,
            method,
            report,
            allow_folded,
            quiet,
        } => (|| {
            let orthogonal =
                ellipgrid::elliptic::orthogonal::parse_edges(&orthogonal, "--orthogonal")?;
            let opts = SmoothOptions {
                blocks,
                linear,
                picard: PicardParams {
                    tolerance,
                    nonlinear: nonlinear.map(|n| {
                        if n == "newton" {
                            Nonlinear::Newton
                        } else {
                            Nonlinear::Picard
                        }
                    }),
                    ..PicardParams::default()
                },
                orthogonal,
                method: if method == "surface" {
                    SurfaceMethod::Surface
                } else {
                    SurfaceMethod::Poisson
                },
                ..SmoothOptions::default()
            };
            opts.picard
                .check()
                .map_err(|m| ellipgrid::Error::input("--tolerance", m))?;
            smooth(
                &input,
                &output,
                &opts,
                report.as_deref(),
                allow_folded,
                quiet,
            )
        })(),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

fn write_json<T: serde::Serialize>(path: &Path, value: &T) -> Result<()> {
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Error::input(path.display().to_string(), e.to_string()))?;
    ellipgrid::io::write_atomic(path, |w| w.write_all(text.as_bytes()))
}

fn run(
    case_path: &Path,
    output: &[PathBuf],
    report: Option<&Path>,
    write_start: Option<&Path>,
    allow_folded: bool,
    quiet: bool,
) -> Result<()> {
    let case = LoadedCase::read(case_path)?;
    let paths: Vec<PathBuf> = if output.is_empty() {
        case.case.output.files.clone()
    } else {
        output.to_vec()
    };
    if paths.is_empty() {
        return Err(Error::input(
            case_path.display().to_string(),
            "no output: give -o OUT or [output] files = [...]",
        ));
    }
    for p in &paths {
        job::output_kind(p)?;
    }
    let fmt = job::plot3d_format(&case)?;
    let mesh = job::mesh_options(&case)?;
    if let Some(p) = write_start {
        job::output_kind(p)?;
    }
    // The start grid and the outputs are renamed into place together, at the end, and only
    // if the run succeeds (or folds with --allow-folded): a failed run leaves no grid. The
    // JSON report is written either way (it says why the run failed).
    let mut messages = Vec::new();
    let mut gen = None;
    let staged = ellipgrid::io::staged(|| {
        if let Some(p) = write_start {
            let start = job::start_grids(&case)?;
            for w in job::write_outputs(&start, &[p.to_path_buf()], &fmt)? {
                messages.push(format!("wrote start grid {}", w.display()));
            }
        }
        ellipgrid::elliptic::volume::set_progress(!quiet);
        let g = gen.insert(job::generate(&case, |b| {
            if !quiet {
                print::block(b);
            }
        })?);
        if !quiet {
            print::faces(&g.report.faces);
            g.report.volumes.iter().for_each(print::volume);
            print::interfaces(&g.report.interfaces);
            print::face_interfaces(&g.report.face_interfaces);
        }
        let fold = g.report.fold_error();
        match fold {
            Some(e) if !allow_folded => return Err(e),
            _ => {}
        }
        let written =
            job::write_outputs_with(&g.blocks, g.connectivity.as_ref(), &paths, &fmt, &mesh)?;
        g.report.outputs = written.iter().map(|p| p.display().to_string()).collect();
        messages.extend(written.iter().map(|p| format!("wrote {}", p.display())));
        Ok(fold)
    });
    // The staged files exist only if the run succeeded (or folded with --allow-folded).
    if !quiet && staged.is_ok() {
        messages.iter().for_each(|m| println!("{m}"));
    }
    let Some(gen) = gen else {
        return staged.map(|_| ());
    };
    if let Some(r) = report {
        write_json(r, &gen.report)?;
    }
    if !quiet {
        print::not_converged(&gen.report);
    }
    match staged {
        Ok(Some(fold)) => Err(fold),
        Ok(None) => Ok(()),
        Err(e) => Err(e),
    }
}

fn smooth(
    input: &Path,
    output: &[PathBuf],
    opts: &SmoothOptions,
    report: Option<&Path>,
    allow_folded: bool,
    quiet: bool,
) -> Result<()> {
    for p in output {
        job::output_kind(p)?;
    }
    // A CGNS input (the cgns feature) keeps its block names and connectivity for the
    // outputs: smoothing moves no boundary node, so the interfaces still match.
    let (file, names, conn) = if input
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("cgns"))
    {
        let l = convert::load(input, true, true)?;
        let (names, blocks): (Vec<String>, Vec<Block>) = l.blocks.into_iter().unzip();
        let format = plot3d::Plot3dFormat {
            multi_block: true,
            two_d: blocks.iter().all(|b| matches!(b, Block::Planar(_))),
            ..plot3d::Plot3dFormat::default()
        };
        let file = plot3d::Plot3dFile {
            blocks,
            format,
            iblank: None,
        };
        (file, names, l.conn)
    } else {
        let file = plot3d::read_plot3d(input)?;
        let names = (1..=file.blocks.len())
            .map(|k| format!("block{k}"))
            .collect();
        (file, names, None)
    };
    let name = input.display().to_string();
    let (blocks, reports) = smooth_blocks(&file.blocks, &name, opts)?;
    if !quiet {
        for r in &reports {
            print::smoothed(r);
        }
    }
    let fold = reports
        .iter()
        .find(|r| r.quality.is_folded())
        .map(|r| Error::Folded {
            place: format!("{name}: block {}", r.block),
            count: r.quality.folded_cells(),
            first: r.quality.folded_list(),
        });
    let mut written = Vec::new();
    if fold.is_none() || allow_folded {
        for p in output {
            if job::output_kind(p)? == job::OutputKind::Plot3d {
                let ib = file.iblank.as_deref();
                plot3d::write_plot3d(p, &blocks, &file.format, ib)?;
                written.push(p.clone());
            } else {
                let named: Vec<(String, Block)> =
                    names.iter().cloned().zip(blocks.iter().cloned()).collect();
                let kind = job::output_kind(p)?;
                let mesh = matches!(
                    kind,
                    job::OutputKind::Foam
                        | job::OutputKind::FoamCase
                        | job::OutputKind::Su2
                        | job::OutputKind::Msh
                        | job::OutputKind::Cgns
                );
                match &conn {
                    Some(c) if mesh => written.extend(job::write_mesh(
                        p,
                        kind,
                        &named,
                        c,
                        &job::MeshOptions::default(),
                    )?),
                    _ => written.extend(job::write_outputs(
                        &named,
                        std::slice::from_ref(p),
                        &file.format,
                    )?),
                }
            }
        }
        if !quiet {
            for p in &written {
                println!("wrote {}", p.display());
            }
        }
    }
    if let Some(r) = report {
        let out: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        write_json(
            r,
            &serde_json::json!({ "input": name, "blocks": reports, "outputs": out }),
        )?;
    }
    match fold {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

fn check(grid: &Path, report: Option<&Path>) -> Result<()> {
    let file = if grid
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("cgns"))
    {
        // a CGNS grid (the cgns feature), in the same form as a Plot3D file
        let blocks = convert::load(grid, true, true)?.blocks;
        plot3d::Plot3dFile {
            blocks: blocks.into_iter().map(|(_, b)| b).collect(),
            format: plot3d::Plot3dFormat::default(),
            iblank: None,
        }
    } else {
        plot3d::read_plot3d(grid)?
    };
    let mut reports: Vec<(String, AnyQuality)> = Vec::new();
    for (k, b) in file.blocks.iter().enumerate() {
        let q: AnyQuality = match b {
            Block::Planar(g) => quality::quality2d(g).into(),
            Block::Surface(g) => quality::quality_surface(g).into(),
            Block::Volume(g) => AnyQuality::Volume(ellipgrid::quality::quality3d::quality3d(g)),
        };
        let d = b.dims();
        if let Block::Volume(_) = b {
            println!("block {} ({} × {} × {}):", k + 1, d[0], d[1], d[2]);
        } else {
            println!("block {} ({} × {}):", k + 1, d[0], d[1]);
        }
        println!("{q}");
        reports.push((format!("block{}", k + 1), q));
    }
    if let Some(r) = report {
        let v: Vec<serde_json::Value> = reports
            .iter()
            .map(|(n, q)| serde_json::json!({ "name": n, "quality": q }))
            .collect();
        write_json(
            r,
            &serde_json::json!({ "grid": grid.display().to_string(), "blocks": v }),
        )?;
    }
    let folded: Vec<&(String, AnyQuality)> =
        reports.iter().filter(|(_, q)| q.is_folded()).collect();
    if let Some((name, q)) = folded.first() {
        return Err(Error::Folded {
            place: format!("{}: {name}", grid.display()),
            count: q.folded_cells(),
            first: q.folded_list(),
        });
    }
    Ok(())
}
