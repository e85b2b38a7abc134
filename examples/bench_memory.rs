//! Benchmark of the memory of whole grid generations (#16, item 2): peak resident set size
//! (Linux `VmHWM`) per node, with seconds and work units, one case per process.
//!
//! `cargo run --release --example bench_memory -- [CASE:N …]`
//!
//! Cases: `curved:N` (the curved quadrilateral of `examples/curved.toml`, N² nodes), `dented:N`
//! (the unit square with a deep mushroom-shaped dent in its top side, whose transfinite start
//! folds, N² nodes) and `box:N` (the warped, wall-clustered box of `bench_volume.rs`, N³
//! nodes), each gridded by the library as the CLI does it (default solver and parameters:
//! multigrid, nested iteration, tolerance 1e-10; `curved-lean:N`, `dented-lean:N`: with
//! `linear = "multigrid-lean"`, the multigrid's memory-lean y-lines). Default:
//! `curved:2049 dented:2049 box:129`.
//! Every case runs in a fresh process of this example (the peak of a process only grows), and
//! prints one line: nodes, seconds, work units, Picard steps per level, folded cells, peak RSS
//! in MB and in bytes per node. The peak includes the boundary, the final grid and the
//! program itself (a few MB).

#[path = "common/square_cap.rs"]
mod square_cap;
use ellipgrid::algebraic::ControlKind;
use ellipgrid::case::LoadedCase;
use ellipgrid::elliptic::nested::grid_block_nested;
use ellipgrid::elliptic::picard::PicardParams;
use ellipgrid::elliptic::volume::grid_volume;
use ellipgrid::grid::boundary::Boundary2;
use ellipgrid::grid::faces::Faces;
use ellipgrid::quality::quality2d;
use ellipgrid::quality::quality3d::quality3d;
use ellipgrid::solve::select::{by_name, by_name3};
use ellipgrid::Grid3;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// Peak resident set size of this process in bytes (`VmHWM` of `/proc/self/status`).
fn peak_rss() -> u64 {
    let s = std::fs::read_to_string("/proc/self/status").expect("read /proc/self/status");
    let line = s
        .lines()
        .find(|l| l.starts_with("VmHWM:"))
        .expect("VmHWM in /proc/self/status");
    let kb: u64 = line
        .split_whitespace()
        .nth(1)
        .and_then(|v| v.parse().ok())
        .expect("VmHWM value");
    kb * 1024
}

fn curved(n: usize) -> Boundary2<2> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/curved.toml");
    let text = std::fs::read_to_string(&path).expect("read case");
    let mut case = LoadedCase::parse(&text, &path).expect("parse case");
    case.case.blocks[0].ni = Some(n);
    case.case.blocks[0].nj = Some(n);
    case.planar_boundary(0).expect("boundary")
}

/// The unit square whose top side (E4) dips into a mushroom-shaped dent: a stem of width 0.1
/// from y = 1 down to 0.55, a cap of width 0.5 from 0.55 down to 0.3; corners rounded by
/// moving averages, nodes equally spaced in arclength along every side.
fn dented(n: usize) -> Boundary2<2> {
    let top = square_cap::square_cap_top(n);
    let line = |a: [f64; 2], b: [f64; 2]| -> Vec<[f64; 2]> {
        (0..n)
            .map(|k| {
                let t = k as f64 / (n - 1) as f64;
                [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
            })
            .collect()
    };
    Boundary2::new(
        [
            line([0.0, 0.0], [0.0, 1.0]),
            line([1.0, 0.0], [1.0, 1.0]),
            line([0.0, 0.0], [1.0, 0.0]),
            top,
        ],
        "dented",
    )
    .expect("dented boundary")
}

/// The warped box with clustering towards j = 0 of `bench_volume.rs`.
fn warped_box(n: usize) -> Faces {
    let mut g = Grid3::zeros(n, n, n);
    let h = (n - 1) as f64;
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let (x, z) = (i as f64 / h, k as f64 / h);
                let y = ((j as f64 / h) * 4.0).sinh() / 4f64.sinh();
                g.set(
                    i,
                    j,
                    k,
                    [
                        x + 0.1 * (std::f64::consts::PI * y).sin() * z,
                        y + 0.15 * (std::f64::consts::PI * x).sin() * (1.0 - y),
                        z + 0.1 * x * y,
                    ],
                );
            }
        }
    }
    Faces::from_grid(&g)
}

/// Prints a case's line; `peak` is the peak RSS right after the generation (before the
/// quality report, whose cell fields are not part of the generation).
fn report(case: &str, nodes: usize, secs: f64, wu: f64, steps: String, folded: usize, peak: u64) {
    println!(
        "{case:<12} {nodes:>10} nodes  {secs:7.2} s  {wu:6.1} WU  Picard steps {steps:<14} \
         folded {folded}  peak RSS {:8.1} MB = {:6.1} bytes/node",
        peak as f64 / 1e6,
        peak as f64 / nodes as f64
    );
}

fn steps(coarse: &[usize], fine: usize) -> String {
    let mut s: Vec<String> = coarse.iter().map(|s| s.to_string()).collect();
    s.push(fine.to_string());
    s.join("+")
}

fn run_one(spec: &str) {
    let (name, n) = spec.split_once(':').expect("CASE:N");
    let n: usize = n.parse().expect("N");
    let params = PicardParams::default();
    if name == "box" {
        let faces = warped_box(n);
        let mut solver = by_name3("multigrid").expect("solver");
        let t0 = Instant::now();
        let r = grid_volume(
            &faces,
            None,
            ControlKind::Algebraic,
            solver.as_mut(),
            &params,
            "box",
            &mut |_, _| {},
        )
        .expect("volume");
        let secs = t0.elapsed().as_secs_f64();
        let peak = peak_rss();
        let folded = quality3d(&r.grid).folded_cells;
        report(
            &format!("box {n}^3"),
            n * n * n,
            secs,
            r.picard.work_units.unwrap_or(f64::NAN),
            steps(&r.picard.coarse_steps, r.picard.steps),
            folded,
            peak,
        );
        return;
    }
    let (name, lean) = match name.strip_suffix("-lean") {
        Some(base) => (base, true),
        None => (name, false),
    };
    let b = match name {
        "curved" => curved(n),
        "dented" => dented(n),
        _ => panic!("unknown case {name} (curved, dented, box)"),
    };
    // `curved-lean:N`, `dented-lean:N`: the multigrid with lean y-lines
    let mut solver = by_name(if lean { "multigrid-lean" } else { "multigrid" }).expect("solver");
    let t0 = Instant::now();
    let (r, info) = grid_block_nested(&b, ControlKind::Algebraic, solver.as_mut(), &params, name)
        .expect("grid");
    let secs = t0.elapsed().as_secs_f64();
    let peak = peak_rss();
    let folded = quality2d(&r.grid).folded_cells;
    report(
        &format!("{name}{} {n}^2", if lean { "-lean" } else { "" }),
        n * n,
        secs,
        info.work_units,
        steps(&r.picard.coarse_steps, r.picard.steps),
        folded,
        peak,
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Some(spec) = args.iter().find_map(|a| a.strip_prefix("--child=")) {
        run_one(spec);
        return;
    }
    let cases: Vec<String> = if args.is_empty() {
        ["curved:2049", "dented:2049", "box:129"]
            .map(String::from)
            .to_vec()
    } else {
        args
    };
    println!(
        "rayon threads: {}; peak RSS = VmHWM of a fresh process per case",
        rayon::current_num_threads()
    );
    let exe = std::env::current_exe().expect("current exe");
    for c in cases {
        let status = Command::new(&exe)
            .arg(format!("--child={c}"))
            .status()
            .expect("run child");
        assert!(status.success(), "case {c} failed");
    }
}
