//! Ignored diagnostics for [`crate::solve::multigrid3d::Multigrid3`]: timings of the setup phases and sweeps, and
//! whole `grid_volume` runs of the solver variants (`--ignored --nocapture`).

use crate::algebraic::ControlKind;
use crate::elliptic::picard::PicardParams;
use crate::elliptic::volume::grid_volume;
use crate::grid::faces::Faces;
use crate::solve::multigrid3d::tests::picard_operator;
use crate::solve::multigrid3d::*;
use crate::solve::stencil19::Stencil19;
use crate::Grid3;

/// Whole `grid_volume` on the benchmark block at 49³ with the smoother and cycle variants
/// and Bi-CGSTAB/ILU(0) (timings; `--ignored --nocapture`).
#[test]
#[ignore]
fn explore() {
    let faces = Faces::from_grid(&bench_block(49));
    let variant = |p: Mg3Params| Box::new(Multigrid3::new(p)) as Box<dyn LinearSolver<Stencil19>>;
    let runs = [
        ("V(1,1) planes", variant(Mg3Params::default())),
        (
            "V(1,0) planes",
            variant(Mg3Params {
                npost: 0,
                ..Default::default()
            }),
        ),
        (
            "V(1,1) lines",
            variant(Mg3Params {
                smoother: Smoother3::Lines,
                ..Default::default()
            }),
        ),
        ("bicgstab", Box::new(crate::solve::ilu::BiCgStabIlu::new())),
    ];
    for (name, mut solver) in runs {
        let t = std::time::Instant::now();
        let r = grid_volume(
            &faces,
            None,
            ControlKind::Algebraic,
            solver.as_mut(),
            &PicardParams::default(),
            "t",
            &mut |_, _| {},
        )
        .unwrap();
        let its: usize = r
            .picard
            .history
            .iter()
            .map(|s| s.linear_iterations.iter().sum::<usize>())
            .sum();
        eprintln!(
            "{name}: {:.2} s, {} steps, {its} linear iterations, converged {}",
            t.elapsed().as_secs_f64(),
            r.picard.steps,
            r.picard.converged
        );
    }
}

/// The warped benchmark block of `examples/bench_volume.rs` at `n³` nodes (clustered to a
/// first spacing ~1e-3 towards j = 0).
fn bench_block(n: usize) -> Grid3 {
    let s: Vec<f64> = (0..n)
        .map(|t| ((t as f64 / (n - 1) as f64) * 4.0).sinh() / 4f64.sinh())
        .collect();
    let pi = std::f64::consts::PI;
    Grid3::from_fn(n, n, n, |i, j, k| {
        let (x, y, z) = (i as f64 / (n - 1) as f64, s[j], k as f64 / (n - 1) as f64);
        [
            x + 0.1 * (pi * y).sin() * z,
            y + 0.15 * (pi * x).sin() * (1.0 - y),
            z + 0.1 * x * y,
        ]
    })
}

/// Times of the setup phases, of cycles and of single sweeps on the benchmark operator of
/// `N³` nodes (environment variable `N`, default 65; `--ignored --nocapture`).
#[test]
#[ignore]
fn setup_phases() {
    let n: usize = std::env::var("N")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(65);
    let g = bench_block(n);
    let a = picard_operator(&g, true);
    let t = std::time::Instant::now();
    let mut lev = Level::fine(a.dims());
    lev.embed(&a).unwrap();
    eprintln!("embed {:.3}", t.elapsed().as_secs_f64());
    let t = std::time::Instant::now();
    lev.factor_lines().unwrap();
    eprintln!("lines {:.3}", t.elapsed().as_secs_f64());
    let t = std::time::Instant::now();
    transfer::build_transfer(&mut lev, false).unwrap();
    eprintln!("transfer {:.3}", t.elapsed().as_secs_f64());
    let t = std::time::Instant::now();
    let d = lev.dims;
    let mut c = Level::new([d[0] / 2, d[1] / 2, d[2] / 2]);
    rap::galerkin(&lev, &mut c);
    eprintln!("rap {:.3}", t.elapsed().as_secs_f64());
    let t = std::time::Instant::now();
    let mut planes = plane::Planes::default();
    planes.setup(&lev).unwrap();
    eprintln!("planes {:.3}", t.elapsed().as_secs_f64());
    let t = std::time::Instant::now();
    let mut mg = Multigrid3::default();
    mg.setup(&a).unwrap();
    eprintln!("whole setup {:.3}", t.elapsed().as_secs_f64());
    let t = std::time::Instant::now();
    mg.setup(&a).unwrap();
    eprintln!("whole setup again {:.3}", t.elapsed().as_secs_f64());
    let mut x = vec![0.0; a.len()];
    let b = vec![1.0; a.len()];
    let t = std::time::Instant::now();
    let info = mg
        .solve(
            &b,
            &mut x,
            &SolveControl {
                rel_tol: 0.0,
                max_iter: 3,
            },
        )
        .unwrap();
    eprintln!(
        "3 cycles {:.3} {:?}",
        t.elapsed().as_secs_f64(),
        info.residual_history
    );
    let (mut pb, mut px) = (vec![0.0; a.len()], vec![0.0; a.len()]);
    let mut xq = vec![0.0; lev.padded_len()];
    let mut r = vec![0.0; lev.padded_len()];
    for dd in 0..3 {
        let t = std::time::Instant::now();
        planes.sweep(&lev, dd, &mut xq, &b, &mut pb, &mut px);
        eprintln!("plane sweep {dd} {:.3}", t.elapsed().as_secs_f64());
        let t = std::time::Instant::now();
        lev.line_sweep(dd, &mut xq, &b);
        eprintln!("line sweep {dd} {:.3}", t.elapsed().as_secs_f64());
    }
    let t = std::time::Instant::now();
    lev.residual(&xq, &b, &mut r);
    eprintln!("residual {:.3}", t.elapsed().as_secs_f64());
}
