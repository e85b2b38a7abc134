//! Benchmark of the black-box multigrid against the sparse direct solver.
//!
//! `cargo run --release --example bench_multigrid -- [--quick]`
//!
//! `--write DIR` writes every computed grid (or solution) as raw f64 for `scripts/same-grids.sh`.
//!
//! For 5- and 9-point Poisson on uniform squares of N² nodes (N − 2 unknowns per direction)
//! and a boundary-layer grid Laplacian (first spacing 1e-5 at the wall, aspect ratio ≈ 1e4 or
//! more): cycles to reduce the residual by 1e-10, mean convergence factor per cycle, setup and
//! solve seconds (the fastest of repeated solves), ns per unknown per cycle, and faer's sparse
//! LU for N ≤ 513.

#[path = "common/dump.rs"]
mod dump;
use ellipgrid::solve::direct::DirectLu;
use ellipgrid::solve::multigrid::{Cycle, MgParams, Multigrid};
use ellipgrid::solve::stencil9::Stencil9;
use ellipgrid::solve::{LinearSolver, SolveControl};
use std::time::Instant;

fn constant(n: usize, m: [f64; 9]) -> Stencil9 {
    let mut a = Stencil9::zeros(n, n);
    for row in a.coefs_mut() {
        *row = m;
    }
    a.clip_to_grid();
    a
}

/// `cells` cells over `[0, 1]` growing geometrically from `d1`.
fn geometric(cells: usize, d1: f64) -> Vec<f64> {
    let total = |r: f64| d1 * (r.powi(cells as i32) - 1.0) / (r - 1.0);
    let (mut lo, mut hi) = (1.0 + 1e-12, 2.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if total(mid) < 1.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let r = 0.5 * (lo + hi);
    let mut x = vec![0.0];
    let mut d = d1;
    for _ in 0..cells {
        x.push(x.last().unwrap() + d);
        d *= r;
    }
    x
}

/// Finite-volume Laplacian on a boundary-layer grid of `nodes²` nodes: x uniform on
/// `[0, lx]`, y clustered at the wall y = 0 with first spacing `d1`.
fn boundary_layer(nodes: usize, d1: f64, lx: f64) -> Stencil9 {
    let xs: Vec<f64> = (0..nodes)
        .map(|i| lx * i as f64 / (nodes - 1) as f64)
        .collect();
    let ys = geometric(nodes - 1, d1);
    let n = nodes - 2;
    let mut a = Stencil9::zeros(n, n);
    for j in 0..n {
        for i in 0..n {
            let (ii, jj) = (i + 1, j + 1);
            let (hw, he) = (xs[ii] - xs[ii - 1], xs[ii + 1] - xs[ii]);
            let (hs, hn) = (ys[jj] - ys[jj - 1], ys[jj + 1] - ys[jj]);
            let (dx, dy) = (0.5 * (hw + he), 0.5 * (hs + hn));
            let m = &mut a.coefs_mut()[i + n * j];
            m[3] = -dy / hw;
            m[5] = -dy / he;
            m[1] = -dx / hs;
            m[7] = -dx / hn;
            m[4] = -(m[1] + m[3] + m[5] + m[7]);
        }
    }
    a.clip_to_grid();
    a
}

fn manufactured(n: usize) -> Vec<f64> {
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|p| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) + (p as f64 * 1e-3).sin()
        })
        .collect()
}

fn rel_err(x: &[f64], xe: &[f64]) -> f64 {
    let d: f64 = x.iter().zip(xe).map(|(a, b)| (a - b).powi(2)).sum();
    let e: f64 = xe.iter().map(|b| b * b).sum();
    (d / e).sqrt()
}

fn run(label: &str, nodes: usize, a: &Stencil9, params: &MgParams, direct: bool) {
    let n = a.len();
    let xe = manufactured(n);
    let mut b = vec![0.0; n];
    a.apply(&xe, &mut b);
    let ctl = SolveControl {
        rel_tol: 1e-10,
        max_iter: 100,
    };
    let mut mg = Multigrid::new(params.clone());
    mg.setup(a).expect("setup");
    // second setup of the same size: the refresh cost (values only)
    let t = Instant::now();
    mg.setup(a).expect("setup");
    let t_setup = t.elapsed().as_secs_f64();
    // a first solve takes the per-solve workspace from the (empty) pool, i.e. allocates it;
    // later solves (other right-hand sides, later Picard steps) reuse it: time one of those
    let mut x = vec![0.0; n];
    mg.solve(&b, &mut x, &ctl).expect("solve");
    // the fastest of repeated solves (at least 5, and at least 1 s in all): a single solve
    // at 257² lasts ~10 ms, where thread wake-ups and other jobs make single timings vary 1.5×
    let (mut t_solve, mut spent, mut reps) = (f64::INFINITY, 0.0, 0);
    let mut info = None;
    while reps < 5 || spent < 1.0 {
        x.fill(0.0);
        let t = Instant::now();
        info = Some(mg.solve(&b, &mut x, &ctl).expect("solve"));
        let dt = t.elapsed().as_secs_f64();
        t_solve = t_solve.min(dt);
        spent += dt;
        reps += 1;
    }
    let info = info.expect("solved");
    dump::dump(
        &format!(
            "mg_{label}_{nodes}_{:?}_{}",
            params.cycle, params.accelerate
        ),
        &[&x],
    );
    let k = info.iterations.max(1);
    let factor = info
        .residual_history
        .last()
        .map_or(0.0, |r| r.powf(1.0 / k as f64));
    let cycles_per_it = if params.accelerate { 2.0 } else { 1.0 };
    let ns = t_solve * 1e9 / (n as f64 * k as f64 * cycles_per_it);
    let kind = format!(
        "{:?}({},{}){}",
        params.cycle,
        params.npre,
        params.npost,
        if params.accelerate { "+BiCGSTAB" } else { "" }
    );
    print!(
        "{label:<14} {nodes:>5}² {kind:<17} it {:>3} conv {} factor {factor:.3}  setup {t_setup:7.3}s  solve {t_solve:7.3}s  {ns:6.1} ns/unk/cycle  err {:.1e}",
        info.iterations,
        if info.converged { "y" } else { "N" },
        rel_err(&x, &xe)
    );
    if direct {
        let t = Instant::now();
        let mut lu = DirectLu::new();
        lu.setup(a).expect("lu");
        let mut xd = vec![0.0; n];
        lu.solve(&b, &mut xd, &ctl).expect("lu solve");
        let t_lu = t.elapsed().as_secs_f64();
        print!(
            "  | faer LU {t_lu:7.3}s  LU/MG {:5.1}",
            t_lu / (t_setup + t_solve)
        );
    }
    println!();
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let sizes: &[usize] = if quick {
        &[257, 513]
    } else {
        &[257, 513, 1025, 2049]
    };
    let bl_sizes: &[usize] = if quick { &[513] } else { &[513, 1025] };
    println!(
        "threads {}; setup = refresh of an allocated hierarchy (new operator, same size); \
         solve = cycles from x = 0 to a 1e-10 residual reduction (workspace reused; fastest of \
         ≥ 5 solves, ≥ 1 s); \
         err = |x - x*|/|x*|; faer LU = factor + solve",
        rayon::current_num_threads()
    );
    let v11 = MgParams {
        cycle: Cycle::V,
        ..MgParams::default()
    };
    let f11 = MgParams::default();
    let acc = MgParams {
        accelerate: true,
        ..MgParams::default()
    };
    for &nodes in sizes {
        let n = nodes - 2;
        let p5 = constant(n, [0.0, -1.0, 0.0, -1.0, 4.0, -1.0, 0.0, -1.0, 0.0]);
        run("poisson5", nodes, &p5, &v11, nodes <= 513);
        run("poisson5", nodes, &p5, &f11, false);
        drop(p5);
        let p9 = constant(n, [-1.0, -4.0, -1.0, -4.0, 20.0, -4.0, -1.0, -4.0, -1.0]);
        run("poisson9", nodes, &p9, &v11, nodes <= 513);
        run("poisson9", nodes, &p9, &f11, false);
    }
    for &nodes in bl_sizes {
        let a = boundary_layer(nodes, 1e-5, 10.0);
        run("boundary-layer", nodes, &a, &v11, nodes <= 513);
        run("boundary-layer", nodes, &a, &f11, false);
        run("boundary-layer", nodes, &a, &acc, false);
    }
}
