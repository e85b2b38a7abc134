//! Peak memory of the direct solver (faer's sparse LU, `linear = "direct"`) against the
//! number of unknowns, for the nine-point (2D) and 19-point (volume) operators (issue #17: the
//! estimate `solve::direct::lu_bytes` refuses a direct solve that would not fit before it
//! starts).
//!
//! `cargo run --release --example bench_direct_memory -- [2d|3d|both]`
//!
//! Each size is factored in a child process of its own (this program run with `--child`),
//! which reports its peak resident size (`VmHWM`) before and after the factorization; the
//! difference per unknown is printed next to the estimate.

use ellipgrid::solve::direct::{lu_bytes, DirectLu, DirectLu3};
use ellipgrid::solve::stencil19::Stencil19;
use ellipgrid::solve::stencil9::Stencil9;
use ellipgrid::solve::LinearSolver;
use std::time::Instant;

/// Peak resident size of this process in bytes (`VmHWM` of /proc/self/status).
fn peak() -> u64 {
    let s = std::fs::read_to_string("/proc/self/status").expect("/proc/self/status");
    let line = s.lines().find(|l| l.starts_with("VmHWM:")).expect("VmHWM");
    let kb: u64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    kb * 1024
}

/// Factors the operator of `n` nodes per direction (interior unknowns (n − 2)^dim) and prints
/// "unknowns peak_bytes seconds".
fn child(dim: usize, n: usize) {
    let m = n - 2;
    let before = peak();
    let t0 = Instant::now();
    let unknowns = if dim == 2 {
        let mut a = Stencil9::zeros(m, m);
        for row in a.coefs_mut() {
            *row = [-0.25, -1.0, -0.1, -1.2, 5.0, -0.8, -0.1, -1.0, -0.25];
        }
        a.clip_to_grid();
        let mut s = DirectLu::new();
        s.setup(&a).expect("factor");
        a.len()
    } else {
        let mut a = Stencil19::zeros(m, m, m);
        for row in a.coefs_mut() {
            *row = [-0.5; 19];
            row[ellipgrid::solve::stencil19::C] = 10.0;
        }
        let mut s = DirectLu3::new();
        s.setup(&a).expect("factor");
        a.len()
    };
    let secs = t0.elapsed().as_secs_f64();
    println!("{unknowns} {} {secs}", peak().saturating_sub(before));
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) == Some("--child") {
        child(args[2].parse().unwrap(), args[3].parse().unwrap());
        return;
    }
    let which = args.get(1).map_or("both", String::as_str);
    let mut runs: Vec<(usize, usize)> = Vec::new();
    if which != "3d" {
        runs.extend([65, 129, 257, 513, 1025].map(|n| (2, n)));
    }
    if which != "2d" {
        runs.extend([13, 17, 25, 33, 41, 49].map(|n| (3, n)));
    }
    for (dim, n) in runs {
        let o = std::process::Command::new(&args[0])
            .args(["--child", &dim.to_string(), &n.to_string()])
            .output()
            .expect("child");
        let out = String::from_utf8_lossy(&o.stdout);
        let v: Vec<f64> = out.split_whitespace().map(|t| t.parse().unwrap()).collect();
        let (unknowns, bytes, secs) = (v[0] as usize, v[1], v[2]);
        let est = lu_bytes(unknowns, dim) as f64;
        let shown = if dim == 2 {
            format!("{n}^2")
        } else {
            format!("{n}^3")
        };
        println!(
            "{dim}D {shown:>7}: {unknowns:>8} unknowns, factor {secs:7.2} s, peak +{:8.1} MB \
             ({:6.0} B/unknown), estimate {:8.1} MB ({:.2}x)",
            bytes / 1e6,
            bytes / unknowns as f64,
            est / 1e6,
            est / bytes.max(1.0)
        );
    }
}
