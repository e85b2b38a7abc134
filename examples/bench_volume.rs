//! Benchmark of the volume pipeline (issue #6): a warped, wall-clustered box at n³ nodes,
//! 3D multigrid against Bi-CGSTAB/ILU(0), tolerance 1e-10.
//!
//! `cargo run --release --example bench_volume -- 33 65 129 [--solver multigrid|bicgstab|both]
//! [--modes]`
//!
//! `--write DIR` writes every computed grid (or solution) as raw f64 for `scripts/same-grids.sh`
//! (named with the tolerance if not the default). `--whole-only` skips the first-operator solves; `--tol T` sets
//! the Picard tolerance of the whole solve (default 1e-10; e.g. 1e-13 for a reference grid).
//!
//! Per size and solver (default both): the first Picard operator solved from zero to 1e-10
//! (iterations, mean factor, setup and solve seconds, ns/unknown/iteration), and the whole
//! `grid_volume` with default parameters (nested iteration, inexact Picard) side by side:
//! seconds, work units, Picard steps per level, and per fine Picard step its update, linear
//! iterations (cycles) per coordinate and largest final linear residual. `--modes`: Bi-CGSTAB/ILU(0) with exact linear
//! solves, inexact Picard, and nested iteration (slow: exact solves take ~50 s at 65³).

#[path = "common/dump.rs"]
mod dump;
use ellipgrid::algebraic::control3d::control_for;
use ellipgrid::algebraic::transfinite3d::transfinite;
use ellipgrid::algebraic::ControlKind;
use ellipgrid::elliptic::picard::PicardParams;
use ellipgrid::elliptic::poisson3d::{assemble, gather};
use ellipgrid::elliptic::volume::grid_volume;
use ellipgrid::grid::faces::Faces;
use ellipgrid::quality::quality3d::quality3d;
use ellipgrid::solve::ilu::BiCgStabIlu;
use ellipgrid::solve::multigrid3d::Multigrid3;
use ellipgrid::solve::stencil19::Stencil19;
use ellipgrid::solve::LinearSolver;
use ellipgrid::solve::SolveControl;
use ellipgrid::Grid3;
use std::time::Instant;

/// A warped box with geometric-like clustering (first spacing ~1e-3) towards j = 0.
fn boundary(n: usize) -> Faces {
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

/// Setup and solve of the first Picard operator (coordinate x) with `solver`.
fn first_operator(n: usize, faces: &Faces, solver: &mut dyn LinearSolver<Stencil19>) {
    let x = transfinite(faces);
    let ctrl = control_for(faces, ControlKind::Algebraic, "bench").expect("control");
    let mut a = Stencil19::zeros(n - 2, n - 2, n - 2);
    let mut rhs: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; a.len()]);
    assemble(&x, &ctrl, &mut a, &mut rhs);
    let mut u = vec![0.0; a.len()];
    gather(&x, 0, &mut u);
    let t0 = Instant::now();
    solver.setup(&a).expect("setup");
    let setup = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let ctl = SolveControl {
        rel_tol: 1e-10,
        max_iter: 500,
    };
    let info = solver.solve(&rhs[0], &mut u, &ctl).expect("solve");
    let solve = t1.elapsed().as_secs_f64();
    let its = info.iterations.max(1);
    let last = info.residual_history.last().copied().unwrap_or(0.0);
    println!(
        "{n}^3 first operator, {}: {} iterations to {:.1e} (converged {}), mean factor {:.4}, \
         setup {setup:.3} s, solve {solve:.3} s, {:.0} ns/unknown/iteration",
        solver.name(),
        info.iterations,
        last,
        info.converged,
        last.powf(1.0 / its as f64),
        solve * 1e9 / (a.len() as f64 * its as f64)
    );
}

/// The whole volume solve of the benchmark block with `solver`.
/// The whole generation with the default parameters (nested iteration, inexact Picard):
/// Picard steps per level (coarsest first), seconds, work units.
fn whole(n: usize, faces: &Faces, solver: &mut dyn LinearSolver<Stencil19>, tol: f64) {
    let t0 = Instant::now();
    let r = grid_volume(
        faces,
        None,
        ControlKind::Algebraic,
        solver,
        &PicardParams {
            tolerance: tol,
            ..PicardParams::default()
        },
        "bench",
        &mut |_, _| {},
    )
    .expect("solve");
    let secs = t0.elapsed().as_secs_f64();
    let its: usize = r
        .picard
        .history
        .iter()
        .map(|s| s.linear_iterations.iter().sum::<usize>())
        .sum();
    let mut steps: Vec<String> = r
        .picard
        .coarse_steps
        .iter()
        .map(|s| s.to_string())
        .collect();
    steps.push(r.picard.steps.to_string());
    let c = r.grid.coords();
    dump::dump(
        &if tol == PicardParams::default().tolerance {
            format!("volume_{n}_{}", r.picard.linear_solver)
        } else {
            format!("volume_{n}_{}_tol{tol:e}", r.picard.linear_solver)
        },
        &[&c[0], &c[1], &c[2]],
    );
    let q = quality3d(&r.grid);
    println!(
        "{n}^3 grid_volume, {:<14} {secs:6.2} s, {:6.1} WU, Picard steps {} (converged {}), \
         {its} linear iterations on the finest grid, folded {}, final residual {:.2e}",
        r.picard.linear_solver,
        r.picard.work_units.unwrap_or(f64::NAN),
        steps.join("+"),
        r.picard.converged,
        q.folded_cells,
        r.picard.final_residual
    );
    for (k, s) in r.picard.history.iter().enumerate() {
        println!(
            "    fine step {}: update {:.2e}, linear iterations {:?}, linear residuals {:.1e}",
            k + 1,
            s.update,
            s.linear_iterations,
            s.linear_residual.iter().fold(0.0f64, |a, &b| a.max(b)),
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let solver = args
        .iter()
        .position(|a| a == "--solver")
        .and_then(|i| args.get(i + 1))
        .map_or("both", |s| s.as_str())
        .to_string();
    if !["bicgstab", "multigrid", "both"].contains(&solver.as_str()) {
        eprintln!("--solver: expected multigrid, bicgstab or both");
        std::process::exit(2);
    }
    let modes = args.iter().any(|a| a == "--modes");
    let whole_only = args.iter().any(|a| a == "--whole-only");
    let tol_at = args.iter().position(|a| a == "--tol");
    let tol: f64 = tol_at
        .and_then(|i| args.get(i + 1))
        .map_or(PicardParams::default().tolerance, |t| {
            t.parse().expect("--tol: a number")
        });
    let sizes: Vec<usize> = args
        .iter()
        .enumerate()
        .filter(|(i, _)| tol_at != Some(i.wrapping_sub(1)))
        .filter_map(|(_, a)| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![33, 65]
    } else {
        sizes
    };
    let (mg, bi) = (solver != "bicgstab", solver != "multigrid");
    for n in sizes {
        let faces = boundary(n);
        if mg && !whole_only {
            first_operator(n, &faces, &mut Multigrid3::default());
        }
        if bi && !whole_only {
            first_operator(n, &faces, &mut BiCgStabIlu::new());
        }
        if mg {
            whole(n, &faces, &mut Multigrid3::default(), tol);
        }
        if bi {
            whole(n, &faces, &mut BiCgStabIlu::new(), tol);
        }
        if modes {
            nested_lines(&faces);
        }
    }
}

/// The whole generation with Bi-CGSTAB/ILU(0) three ways (`ellipgrid::elliptic::nested3d`):
/// plain Picard with every linear solve to 1e-10 (`exact`), plain inexact Picard (`inexact`,
/// the forcing term of `PicardParams::linear_forcing`), and nested iteration with inexact
/// Picard (`nested`): Picard steps per level (coarsest first; the last is the finest grid),
/// seconds, work units (one WU = one assembly + residual of [86] on the finest grid).
fn nested_lines(faces: &Faces) {
    use ellipgrid::elliptic::nested3d::grid_volume_nested;
    let n = faces.dims()[0];
    let modes = [
        ("exact", Some(false), 0.0),
        (
            "inexact",
            Some(false),
            PicardParams::default().linear_forcing,
        ),
        ("nested", Some(true), PicardParams::default().linear_forcing),
    ];
    for (name, nested, forcing) in modes {
        let params = PicardParams {
            nested,
            linear_forcing: forcing,
            ..PicardParams::default()
        };
        let (r, info) = grid_volume_nested(
            faces,
            ControlKind::Algebraic,
            &mut BiCgStabIlu::new(),
            &params,
            "bench",
            &mut |_, _| {},
        )
        .expect("solve");
        let steps: Vec<String> = info.levels.iter().map(|l| l.steps.to_string()).collect();
        let its: usize = r
            .picard
            .history
            .iter()
            .map(|s| s.linear_iterations.iter().sum::<usize>())
            .sum();
        println!(
            "{n}^3 {name:>7}: Picard steps {} (converged {}), {:.2} s, {:.1} WU (WU {:.1} ms), \
             {its} Bi-CGSTAB iterations on the finest grid, final residual {:.2e}",
            steps.join("+"),
            r.picard.converged,
            info.seconds,
            info.work_units,
            1e3 * info.work_unit_seconds,
            r.picard.final_residual
        );
    }
}
