//! `ellipgrid verify CASE.toml`: grid families, observed orders, start-grid and
//! parametrization independence of every block (see `ellipgrid::job::verify`). Exit 0 when
//! every block passes, 5 when a property fails.

use clap::Args;
use ellipgrid::case::LoadedCase;
use ellipgrid::job::verify::{
    default_formats, verify, FamilyOutput, SurfaceGrid, VerifyOptions, VerifyReport, DEFAULT_SEED,
    ORDER_MIN,
};
use ellipgrid::quality::family::Difference;
use ellipgrid::Result;
use std::path::PathBuf;

/// Arguments of `ellipgrid verify`.
#[derive(Args, Debug)]
pub struct VerifyArgs {
    /// The case file (TOML; see README.md, "Case files").
    case: PathBuf,
    /// Grids in the family: N, 2N − 1, 4N − 3, … nodes per direction (3 to 8).
    #[arg(long, default_value_t = 3)]
    levels: usize,
    /// Write the report (differences, orders, verdict of every block) as JSON.
    #[arg(long, value_name = "FILE.json")]
    report: Option<PathBuf>,
    /// Write the grids of the family to DIR as <case>_L<level>.<ext>, for a solver
    /// convergence study (the formats of the case's [output] files, Plot3D if none).
    #[arg(long, value_name = "DIR")]
    write_family: Option<PathBuf>,
    /// Formats of --write-family instead: extensions, comma separated (x, vts, vtm, cgns,
    /// su2, msh, polyMesh, conn, …).
    #[arg(long, value_delimiter = ',', value_name = "EXT,..")]
    family_format: Vec<String>,
    /// Seed of the parametrization warp and of the scrambled start.
    #[arg(long, default_value_t = DEFAULT_SEED)]
    seed: u64,
    /// The grid of surface blocks that is verified: "section4" (the grid `run` writes) or
    /// "initial" (the initial grid x^I of Section 4, which depends on the parametrization:
    /// verify must fail it; a check of the checker).
    #[arg(long, default_value = "section4", value_parser = ["section4", "initial"])]
    surface_grid: String,
    /// Run the levels one after the other (default: in parallel where memory allows).
    #[arg(long)]
    sequential: bool,
    /// Print only errors and failures.
    #[arg(short, long)]
    quiet: bool,
}

/// Runs `ellipgrid verify`.
pub fn run(a: &VerifyArgs) -> Result<()> {
    let case = LoadedCase::read(&a.case)?;
    let opts = VerifyOptions {
        levels: a.levels,
        seed: a.seed,
        surface_grid: if a.surface_grid == "initial" {
            SurfaceGrid::Initial
        } else {
            SurfaceGrid::Section4
        },
        parallel: !a.sequential,
    };
    let family = a.write_family.as_ref().map(|dir| FamilyOutput {
        dir: dir.clone(),
        formats: if a.family_format.is_empty() {
            default_formats(&case)
        } else {
            a.family_format.clone()
        },
    });
    let report = verify(&case, &opts, family.as_ref())?;
    if !a.quiet {
        print(&report);
    }
    if let Some(r) = &a.report {
        super::write_json(r, &report)?;
    }
    match report.failure() {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

fn dims(d: &[usize; 3]) -> String {
    if d[2] == 1 {
        format!("{} × {}", d[0], d[1])
    } else {
        format!("{} × {} × {}", d[0], d[1], d[2])
    }
}

fn order(p: Option<f64>) -> String {
    p.map(|p| format!("{p:.2}")).unwrap_or_else(|| "—".into())
}

fn at_tolerance(yes: bool) -> &'static str {
    if yes {
        ": the grids agree to the solver's tolerance (no order to observe)"
    } else {
        ""
    }
}

fn diff(d: &Difference) -> String {
    format!("{:.2e} / {:.2e}", d.rms, d.max)
}

/// Prints the report as tables.
fn print(r: &VerifyReport) {
    println!(
        "verify {}: {} levels{}, seed {}, {:.2} s",
        r.case,
        r.levels.len(),
        if r.parallel { " in parallel" } else { "" },
        r.seed,
        r.seconds
    );
    for l in &r.levels {
        let sizes: Vec<String> = l.dims.iter().map(dims).collect();
        println!(
            "  level {}: {} nodes, {:.3} s",
            l.level,
            sizes.join(", "),
            l.seconds
        );
    }
    if r.surface_grid == SurfaceGrid::Initial {
        println!("  surface blocks: their initial grid x^I (parametrization-dependent)");
    }
    println!("differences relative to the block's diameter, rms / max; orders p = log2(e_h / e_h/2), rms / max");
    for b in &r.blocks {
        println!(
            "block '{}' ({}, {}): {}",
            b.name,
            b.kind,
            dims(&b.dims[0]),
            if b.pass { "pass" } else { "FAIL" }
        );
        println!("  grid family{}", at_tolerance(b.family.at_tolerance));
        for (l, d) in b.family.differences.iter().enumerate() {
            let p = if l == 0 {
                String::new()
            } else {
                format!(
                    "   p = {} / {}",
                    order(b.family.order_rms[l - 1]),
                    order(b.family.order_max[l - 1])
                )
            };
            println!(
                "    {:>15} → {:<15} {}{p}",
                dims(&b.dims[l]),
                dims(&b.dims[l + 1]),
                diff(d)
            );
        }
        if let Some(c) = &b.parametrization {
            println!(
                "  parametrization (warp seed {}){}",
                r.seed,
                at_tolerance(c.at_tolerance)
            );
            for (l, d) in c.differences.iter().enumerate() {
                let p = if l == 0 {
                    String::new()
                } else {
                    format!(
                        "   p = {} / {}",
                        order(c.order_rms[l - 1]),
                        order(c.order_max[l - 1])
                    )
                };
                println!("    {:>15}   {:<15} {}{p}", dims(&b.dims[l]), "", diff(d));
            }
        }
        if let Some(s) = &b.start {
            let group = if s.group.is_empty() {
                String::new()
            } else {
                format!(", gridded as one with {}", s.group.join("+"))
            };
            println!(
                "  start grid: scrambled (seed {}, {} of {} cells folded{group}), {}",
                s.seed,
                s.start_folded,
                s.start_cells,
                match (&s.difference, s.picard_steps) {
                    (Some(d), Some(n)) => format!(
                        "{n} Picard steps{}, differs by {:.2e} (max; limit {:.1e})",
                        if s.converged { "" } else { " (not converged)" },
                        d.max,
                        s.limit
                    ),
                    _ => "failed".into(),
                }
            );
        }
        for m in &b.reasons {
            println!("  fails: {m}");
        }
    }
    let failed = r.blocks.iter().filter(|b| !b.pass).count();
    println!(
        "{}: {} of {} blocks pass (orders ≥ {ORDER_MIN} in rms, start-grid differences within \
         the limit)",
        if failed == 0 { "pass" } else { "FAIL" },
        r.blocks.len() - failed,
        r.blocks.len()
    );
    for f in &r.family {
        println!("wrote {f}");
    }
    if let Some(n) = &r.family_note {
        println!("{n}");
    }
}
