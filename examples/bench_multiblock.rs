//! Benchmark of whole multi-block generations (issue #15's targets): the shipped paper cases
//! as they are and refined, timed end to end through `job::generate` (edge nodes, groups in
//! parallel, orthogonality steps, quality), with the Picard steps and work units of every
//! block.
//!
//! `cargo run --release --example bench_multiblock -- [--quick] [--repeat N]
//! [--variants picard,newton,anderson5] [--only LABEL-PREFIX] [--history]`
//!
//! Cases: `naca0012_ogrid` as shipped (4 × 65 × 49) and with every edge at 257 nodes
//! (4 × 257²); `rae2822_cgrid` as shipped and with every node count doubled (minus one);
//! `nlr7301_flap` as shipped and without its `wall = true` lines; `artificial_boundary` as shipped; `naca0012_oneblock` (one block with a
//! periodic cut, 257 × 49; not with `andersonN`, whose steps fold it). `--quick` drops
//! the refined cases.
//! Each case runs `--repeat` times (default 3); the best wall-clock time is printed for each
//! solver variant side by side: `picard` (plain Picard steps, `nonlinear = "picard"`),
//! `newton` (`nonlinear = "newton"`, the default of 2D blocks), `andersonN` (Anderson
//! acceleration of depth N: Picard steps unless the case asks for Newton); default
//! `picard,newton`. `--history` prints every step of every block.

use ellipgrid::case::LoadedCase;
use ellipgrid::elliptic::picard::Nonlinear;
use ellipgrid::job;
use std::path::Path;
use std::time::Instant;

/// `n = K` lines of a case file mapped through `f`.
fn renumber(text: &str, f: impl Fn(usize) -> usize) -> String {
    text.lines()
        .map(
            |l| match l.strip_prefix("n = ").and_then(|v| v.trim().parse().ok()) {
                Some(n) => format!("n = {}", f(n)),
                None => l.to_string(),
            },
        )
        .collect::<Vec<_>>()
        .join("\n")
}

/// The solver variants of `--variants` (default `picard,newton`): `picard`, `newton`, or
/// `andersonN` (Picard with Anderson acceleration of depth N).
fn variants() -> Vec<String> {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == "--variants")
        .and_then(|k| args.get(k + 1))
        .map_or("picard,newton", |v| v.as_str())
        .split(',')
        .map(str::to_string)
        .collect()
}

fn run(label: &str, file: &str, edit: impl Fn(&str) -> String, repeat: usize) {
    run_variants(label, file, edit, repeat, variants());
}

/// [`run`] for the solver variants `vs`.
fn run_variants(
    label: &str,
    file: &str,
    edit: impl Fn(&str) -> String,
    repeat: usize,
    vs: Vec<String>,
) {
    let args: Vec<String> = std::env::args().collect();
    if let Some(only) = args
        .iter()
        .position(|a| a == "--only")
        .and_then(|k| args.get(k + 1))
    {
        if !label.starts_with(only.as_str()) {
            return;
        }
    }
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(file);
    let text = edit(&std::fs::read_to_string(&path).expect("read case"));
    for v in vs {
        let mut case = LoadedCase::parse(&text, &path).expect("parse case");
        let p = &mut case.case.solver.picard;
        match v.as_str() {
            "picard" => p.nonlinear = Some(Nonlinear::Picard),
            "newton" => p.nonlinear = Some(Nonlinear::Newton),
            a => {
                p.anderson = a
                    .strip_prefix("anderson")
                    .and_then(|d| d.parse().ok())
                    .expect("--variants: picard, newton or andersonN")
            }
        }
        time(&format!("{label} ({v})"), &case, repeat);
    }
}

/// Best-of-`repeat` wall clock of one case, with the Picard steps of every block.
fn time(label: &str, case: &LoadedCase, repeat: usize) {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..repeat.max(1) {
        let t = Instant::now();
        let g = job::generate(case, |_| {}).expect("generate");
        best = best.min(t.elapsed().as_secs_f64());
        last = Some(g);
    }
    let g = last.expect("one run");
    let nodes: usize = g.report.blocks.iter().map(|b| b.ni * b.nj).sum();
    println!(
        "{label:<41} {:>2} blocks {nodes:>8} nodes  {best:>7.3} s  (best of {repeat}, {} threads)",
        g.report.blocks.len(),
        rayon::current_num_threads()
    );
    for b in &g.report.blocks {
        let (steps, wu, coarse) = b.picard.as_ref().map_or((0, None, Vec::new()), |p| {
            (p.steps, p.work_units, p.coarse_steps.clone())
        });
        println!(
            "    {:<14} {:>4} x {:<4} {:>3} Picard steps (coarse {:?}) {:>7} work units  {:.3} s  folded {}",
            b.name,
            b.ni,
            b.nj,
            steps,
            coarse,
            wu.map_or("-".into(), |w| format!("{w:.1}")),
            b.seconds,
            b.quality.folded_cells
        );
        if std::env::args().any(|a| a == "--history") {
            for st in b.picard.iter().flat_map(|p| &p.history) {
                println!(
                    "        update {:.2e}  residual {:.2e}  cycles {:?}  linear res {:.1e}",
                    st.update,
                    st.residual,
                    st.linear_iterations,
                    st.linear_residual.iter().cloned().fold(0.0, f64::max)
                );
            }
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let quick = args.iter().any(|a| a == "--quick");
    let repeat = args
        .iter()
        .position(|a| a == "--repeat")
        .and_then(|k| args.get(k + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(3);
    let same = |t: &str| t.to_string();
    run(
        "naca0012_ogrid 4x65x49",
        "naca0012_ogrid.toml",
        same,
        repeat,
    );
    if !quick {
        run(
            "naca0012_ogrid 4x257x257",
            "naca0012_ogrid.toml",
            |t| renumber(t, |_| 257),
            repeat,
        );
    }
    run("rae2822_cgrid", "rae2822_cgrid.toml", same, repeat);
    if !quick {
        run(
            "rae2822_cgrid x2",
            "rae2822_cgrid.toml",
            |t| renumber(t, |n| 2 * n - 1),
            repeat,
        );
    }
    run("nlr7301_flap", "nlr7301_flap.toml", same, repeat);
    // the same without its held wall spacing (the chains' `wall = true`), side by side
    run(
        "nlr7301_flap no wall",
        "nlr7301_flap.toml",
        |t| t.replace("\nwall = true\n", "\n"),
        repeat,
    );
    run(
        "artificial_boundary",
        "artificial_boundary.toml",
        same,
        repeat,
    );
    // Anderson's extrapolated steps fold the periodic block (the LU then fails)
    let no_anderson = variants()
        .into_iter()
        .filter(|v| !v.starts_with("anderson"))
        .collect();
    run_variants(
        "naca0012_oneblock 257x49",
        "naca0012_oneblock.toml",
        same,
        repeat,
        no_anderson,
    );
}
