//! Benchmark of whole 2D grid generations: multigrid + nested iteration against plain Picard
//! with the sparse direct solver.
//!
//! `cargo run --release --example bench_grid -- [--quick] [--sizes 257,513] [--only curved|bl-1e-5]
//! [--no-plain] [--no-linear] [--newton] [--history] [--levels]`
//!
//! `--levels` prints each nested level's steps and seconds (where a whole generation's time
//! goes).
//!
//! `--write DIR` writes every computed grid (or solution) as raw f64 for `scripts/same-grids.sh`.
//!
//! Cases: the curved quadrilateral of `examples/curved.toml` and the boundary-layer block of
//! `examples/boundary_layer.toml` with wall spacing 1e-5 (`bl-1e-5`; and `bl-ar1e4`, with
//! wall-tangential spacings of 0.15 at both ends: aspect ratios ≥ 1e4), at 257², 513², 1025²
//! nodes (`--quick`: 129², 257²), and the wavy C-block of `examples/folding_start.toml`
//! (`folded`: deep concave valleys, the transfinite start folds) and the unit square with a
//! deep mushroom-shaped dent of `examples/dented_square.toml` (`dented`: its start folds
//! too) at the same sizes. For each:
//! - `linear`: the Picard system at the final grid (both coordinates' right-hand sides, x
//!   from zero): cycles of the default multigrid (F(1,1)) to reduce the residual by 1e-10,
//!   mean factor per cycle, setup (first setup, allocation included) and solve seconds, ns
//!   per unknown per cycle;
//! - `mg+nested`: the whole generation (tolerance 1e-10) by nested iteration with multigrid:
//!   Picard steps per level (coarsest first), seconds, work units (`ellipgrid::elliptic::nested`);
//! - `mg+nested` and `newton` ask for their iteration explicitly (`nonlinear = "picard"`,
//!   `"newton"`; Newton is the default of 2D blocks);
//! - `newton` (with `--newton`): the same by Newton–Krylov steps
//!   ([`ellipgrid::elliptic::newton`]) instead of Picard steps, and the largest difference
//!   from the `mg+nested` grid relative to the diameter;
//! - `mg plain`: plain Picard with multigrid from the transfinite grid;
//! - `direct`: plain Picard with the sparse LU (N ≤ 513), the time ratio to `mg+nested`, and
//!   the largest difference between the two grids relative to the diameter.

#[path = "common/dump.rs"]
mod dump;
use ellipgrid::algebraic::control2d::control_for;
use ellipgrid::algebraic::ControlKind;
use ellipgrid::case::LoadedCase;
use ellipgrid::elliptic::nested::{grid_block_nested, NestedInfo};
use ellipgrid::elliptic::picard::{Nonlinear, PicardParams};
use ellipgrid::elliptic::poisson2d::assemble;
use ellipgrid::grid::boundary::Boundary2;
use ellipgrid::grid::Grid2;
use ellipgrid::solve::direct::DirectLu;
use ellipgrid::solve::multigrid::MultigridSafe;
use ellipgrid::solve::multigrid::{bicgstab, MgParams, Multigrid};
use ellipgrid::solve::stencil9::Stencil9;
use ellipgrid::solve::{LinearSolver, SolveControl};
use std::path::Path;
use std::time::Instant;

fn boundary(file: &str, n: usize, edit: impl Fn(String) -> String) -> Boundary2<2> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(file);
    let text = edit(std::fs::read_to_string(&path).expect("read case"));
    let mut case = LoadedCase::parse(&text, &path).expect("parse case");
    case.case.blocks[0].ni = Some(n);
    case.case.blocks[0].nj = Some(n);
    case.planar_boundary(0).expect("boundary")
}

/// Largest cell aspect ratio (longer / shorter side) of a planar grid.
fn max_aspect(g: &Grid2<2>) -> f64 {
    let d = |p: [f64; 2], q: [f64; 2]| ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
    let mut m = 1.0f64;
    for j in 0..g.nj() - 1 {
        for i in 0..g.ni() - 1 {
            let a = d(g.point(i, j), g.point(i + 1, j));
            let b = d(g.point(i, j), g.point(i, j + 1));
            m = m.max(a.max(b) / a.min(b));
        }
    }
    m
}

fn max_diff(a: &Grid2<2>, b: &Grid2<2>) -> f64 {
    let mut m = 0.0f64;
    for c in 0..2 {
        for (u, v) in a.coord(c).iter().zip(b.coord(c)) {
            m = m.max((u - v).abs());
        }
    }
    m / a.diameter()
}

/// The Picard system at grid `g`, solved by multigrid from zero for both coordinates.
fn linear(label: &str, b: &Boundary2<2>, g: &Grid2<2>) {
    let ctrl = control_for(b, ControlKind::Algebraic);
    let (nx, ny) = (g.ni() - 2, g.nj() - 2);
    let mut a = Stencil9::zeros(nx, ny);
    let mut rhs = [vec![0.0; nx * ny], vec![0.0; nx * ny]];
    assemble(g, &ctrl, &mut a, &mut rhs);
    let mut mg = Multigrid::new(MgParams::default());
    let t = Instant::now();
    mg.setup(&a).expect("setup");
    let t_setup = t.elapsed().as_secs_f64();
    let ctl = SolveControl {
        rel_tol: 1e-10,
        max_iter: 100,
    };
    for (c, bc) in rhs.iter().enumerate() {
        for krylov in [false, true] {
            let mut x = vec![0.0; nx * ny];
            let t = Instant::now();
            let r = if krylov {
                bicgstab(&a, bc, &mut x, &mg, &ctl)
            } else {
                mg.solve(bc, &mut x, &ctl)
            };
            let t_solve = t.elapsed().as_secs_f64();
            let cyc = format!("{:?}", MgParams::default().cycle);
            let what = if krylov {
                format!("BiCGSTAB+{cyc}")
            } else {
                format!("{cyc}-cycles")
            };
            let info = match r {
                Ok(info) => info,
                Err(e) => {
                    println!("{label:<8} {:>5}²  linear   coord {c}: {what}: {e}", g.ni());
                    continue;
                }
            };
            // cycles: one per cycle, two per Bi-CGSTAB iteration
            let k = info.iterations.max(1) * if krylov { 2 } else { 1 };
            let factor = info
                .residual_history
                .last()
                .map_or(0.0, |r| r.powf(1.0 / k as f64));
            let ns = t_solve * 1e9 / ((nx * ny) as f64 * k as f64);
            println!(
                "{label:<8} {:>5}²  linear   coord {c}: {what:<10} cycles {k:>2} factor/cycle {factor:.3}  setup {t_setup:6.3}s  solve {t_solve:6.3}s  {ns:5.1} ns/unk/cycle",
                g.ni(),
            );
        }
    }
}

fn whole(
    label: &str,
    what: &str,
    b: &Boundary2<2>,
    solver: &mut dyn LinearSolver,
    nested: bool,
) -> (Grid2<2>, NestedInfo) {
    let params = PicardParams {
        nested: Some(nested),
        nonlinear: Some(if what == "newton" {
            Nonlinear::Newton
        } else {
            Nonlinear::Picard
        }),
        ..PicardParams::default()
    };
    let (r, info) =
        grid_block_nested(b, ControlKind::Algebraic, solver, &params, label).expect("grid");
    let steps: Vec<String> = info.levels.iter().map(|l| l.steps.to_string()).collect();
    let cycles: usize = r
        .picard
        .history
        .iter()
        .map(|s| s.linear_iterations.iter().max().copied().unwrap_or(0))
        .sum();
    println!(
        "{label:<8} {:>5}²  {what:<9} steps {} (levels {}) conv {}  cycles {cycles:>2}  {:7.3}s  {:6.1} WU (1 WU = {:.2} ms)  res {:.1e}",
        b.ni(),
        r.picard.steps,
        steps.join("/"),
        if r.picard.converged { "y" } else { "N" },
        info.seconds,
        info.work_units,
        info.work_unit_seconds * 1e3,
        r.picard.final_residual,
    );
    if std::env::args().any(|a| a == "--levels") {
        for l in &info.levels {
            println!(
                "    level {:?}: {} steps, {:.3} s",
                l.dims, l.steps, l.seconds
            );
        }
    }
    if std::env::args().any(|a| a == "--history") {
        for st in &r.picard.history {
            println!(
                "           update {:.2e} residual {:.2e} cycles {:?} linear res {:.1e}",
                st.update,
                st.residual,
                st.linear_iterations,
                st.linear_residual.iter().cloned().fold(0.0, f64::max)
            );
        }
    }
    let c = r.grid.coords();
    dump::dump(&format!("grid_{label}_{}_{what}", b.ni()), &[&c[0], &c[1]]);
    (r.grid, info)
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let arg = |name: &str| {
        let v: Vec<String> = std::env::args().collect();
        v.iter().position(|a| a == name).map(|k| v[k + 1].clone())
    };
    let only = arg("--only");
    let custom: Option<Vec<usize>> =
        arg("--sizes").map(|s| s.split(',').map(|v| v.parse().expect("size")).collect());
    let sizes: &[usize] = match &custom {
        Some(v) => v,
        None if quick => &[129, 257],
        None => &[257, 513, 1025],
    };
    let plain = !std::env::args().any(|a| a == "--no-plain");
    println!(
        "rayon threads: {}; Picard tolerance 1e-10 (max update / diameter)",
        rayon::current_num_threads()
    );
    type Case = (&'static str, &'static str, fn(String) -> String);
    let newton = std::env::args().any(|a| a == "--newton");
    let lin = !std::env::args().any(|a| a == "--no-linear");
    let cases: [Case; 5] = [
        ("curved", "curved.toml", |s| s),
        ("bl-1e-5", "boundary_layer.toml", |s| {
            s.replace("first = 1e-4", "first = 1e-5")
        }),
        // wall spacing 1e-5, wall-tangential spacing 0.15 at the in- and outflow ends:
        // aspect ratios 1.5e4 there, as in the far wake of a Navier–Stokes grid
        ("bl-ar1e4", "boundary_layer.toml", |s| {
            s.replace("first = 1e-4", "first = 1e-5")
                .replace("first = 0.01, last = 0.02", "first = 0.15, last = 0.15")
        }),
        ("folded", "folding_start.toml", |s| s),
        ("dented", "dented_square.toml", |s| s),
    ];
    for (label, file, edit) in cases {
        if only.as_deref().is_some_and(|o| o != label) {
            continue;
        }
        for &n in sizes {
            let b = boundary(file, n, edit);
            let mut mg = MultigridSafe::new(MgParams::default());
            let (g, info) = whole(label, "mg+nested", &b, &mut mg, true);
            if label.starts_with("bl") {
                println!(
                    "{label:<8} {n:>5}²  max cell aspect ratio {:.2e}",
                    max_aspect(&g)
                );
            }
            if newton {
                let mut mg = MultigridSafe::new(MgParams::default());
                let (gn, _) = whole(label, "newton", &b, &mut mg, true);
                println!(
                    "{label:<8} {n:>5}²  newton vs mg+nested: max diff {:.1e}",
                    max_diff(&g, &gn)
                );
            }
            if lin {
                linear(label, &b, &g);
            }
            if !plain {
                continue;
            }
            let mut mg = MultigridSafe::new(MgParams::default());
            let (gp, _) = whole(label, "mg plain", &b, &mut mg, false);
            println!(
                "{label:<8} {n:>5}²  mg plain vs mg+nested: max diff {:.1e}",
                max_diff(&g, &gp)
            );
            if n <= 513 {
                let (gd, dinfo) = whole(label, "direct", &b, &mut DirectLu::new(), false);
                println!(
                    "{label:<8} {n:>5}²  direct / (mg+nested) time ratio {:.1}, max diff {:.1e}",
                    dinfo.seconds / info.seconds,
                    max_diff(&g, &gd)
                );
            }
        }
    }
}
