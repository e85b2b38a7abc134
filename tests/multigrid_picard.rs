//! The multigrid solver inside the Picard iteration of [24], and nested iteration
//! (`ellipgrid::elliptic::nested`): the grids equal those of the direct solver and of plain Picard to
//! the Picard tolerance, and the finest grid needs few Picard steps.

use ellipgrid::algebraic::ControlKind;
use ellipgrid::case::{LoadedCase, SolverSpec};
use ellipgrid::elliptic::domain::grid_block;
use ellipgrid::elliptic::nested::{grid_block_nested, level_sizes};
use ellipgrid::elliptic::picard::{Nonlinear, PicardParams};
use ellipgrid::grid::boundary::Boundary2;
use ellipgrid::solve::multigrid::MgParams;
use ellipgrid::solve::multigrid::MultigridSafe;
use ellipgrid::solve::select::by_name;
use ellipgrid::solve::{direct::DirectLu, LinearSolver};
use ellipgrid::Grid2;
use std::path::Path;

const TOL: f64 = 1e-10;

/// The first block of an example case at `n × m` nodes; `edit` changes the case text.
fn boundary(file: &str, n: usize, m: usize, edit: impl Fn(String) -> String) -> Boundary2<2> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(file);
    let text = edit(std::fs::read_to_string(&path).unwrap());
    let mut case = LoadedCase::parse(&text, &path).unwrap();
    case.case.blocks[0].ni = Some(n);
    case.case.blocks[0].nj = Some(m);
    case.planar_boundary(0).unwrap()
}

fn curved(n: usize, m: usize) -> Boundary2<2> {
    boundary("curved.toml", n, m, |s| s)
}

/// The boundary-layer block with wall spacing 1e-5 (cell aspect ratios in the thousands).
fn boundary_layer(n: usize, m: usize) -> Boundary2<2> {
    boundary("boundary_layer.toml", n, m, |s| {
        s.replace("first = 1e-4", "first = 1e-5")
    })
}

/// Picard steps (set explicitly: these tests are about the Picard iteration, whose steps
/// they count; Newton–Krylov, the default of 2D blocks, is `tests/newton.rs`'s).
fn params(nested: bool) -> PicardParams {
    PicardParams {
        tolerance: TOL,
        nested: Some(nested),
        nonlinear: Some(Nonlinear::Picard),
        ..PicardParams::default()
    }
}

/// Largest node distance between two grids relative to the diameter.
fn max_diff(a: &Grid2<2>, b: &Grid2<2>) -> f64 {
    let mut m = 0.0f64;
    for c in 0..2 {
        for (u, v) in a.coord(c).iter().zip(b.coord(c)) {
            m = m.max((u - v).abs());
        }
    }
    m / a.diameter()
}

fn grid(b: &Boundary2<2>, solver: &mut dyn LinearSolver, nested: bool) -> Grid2<2> {
    let r = grid_block(
        b,
        None,
        ControlKind::Algebraic,
        solver,
        &params(nested),
        "test",
    )
    .unwrap();
    assert!(r.picard.converged, "{:?}", r.picard.history);
    assert!(
        r.picard.final_residual < 1e-11,
        "{}",
        r.picard.final_residual
    );
    r.grid
}

/// The Picard iterations stop at an update below TOL and contract at ≤ 0.2 per step, so two
/// converged grids agree to a few TOL; 10 TOL leaves room without hiding a wrong grid (the
/// start grids are 1e-2 away).
const SAME: f64 = 10.0 * TOL;

#[test]
fn multigrid_default_and_names() {
    assert_eq!(SolverSpec::default().linear, "multigrid");
    assert_eq!(by_name("multigrid").unwrap().name(), "multigrid");
    assert!(by_name("gauss").is_err());
    let p = PicardParams::default();
    assert!(p.nested_for("multigrid") && !p.nested_for("direct-lu"));
    // the lean y-lines are the multigrid too (nested iteration by default)
    assert_eq!(by_name("multigrid-lean").unwrap().name(), "multigrid");
}

/// The memory-lean y-lines (`MgParams::lean_y_lines`, "multigrid-lean") give the grid of the
/// direct solver and of the default multigrid on the boundary-layer block (y-lines carry the
/// wall-normal coupling there), in the same Picard steps as the default multigrid.
#[test]
fn lean_y_lines_give_the_same_grids() {
    let b = boundary_layer(97, 65);
    let direct = grid(&b, &mut DirectLu::new(), false);
    let run = |name: &str| {
        let mut solver = by_name(name).unwrap();
        let r = grid_block(
            &b,
            None,
            ControlKind::Algebraic,
            solver.as_mut(),
            &params(true),
            "test",
        )
        .unwrap();
        assert!(r.picard.converged, "{:?}", r.picard.history);
        r
    };
    let (default, lean) = (run("multigrid"), run("multigrid-lean"));
    assert!(max_diff(&direct, &lean.grid) < SAME);
    assert!(max_diff(&default.grid, &lean.grid) < SAME);
    assert_eq!(default.picard.steps, lean.picard.steps);
    assert_eq!(default.picard.coarse_steps, lean.picard.coarse_steps);
}

#[test]
fn multigrid_grids_equal_direct_grids_curved() {
    let b = curved(65, 49);
    let direct = grid(&b, &mut DirectLu::new(), false);
    let plain = grid(&b, by_name("multigrid").unwrap().as_mut(), false);
    let nested = grid(&b, by_name("multigrid").unwrap().as_mut(), true);
    let d = (max_diff(&direct, &plain), max_diff(&direct, &nested));
    assert!(d.0 < SAME && d.1 < SAME, "{d:?}");
}

#[test]
fn multigrid_grids_equal_direct_grids_boundary_layer() {
    let b = boundary_layer(97, 65);
    let direct = grid(&b, &mut DirectLu::new(), false);
    let plain = grid(&b, by_name("multigrid").unwrap().as_mut(), false);
    let nested = grid(&b, by_name("multigrid").unwrap().as_mut(), true);
    let d = (max_diff(&direct, &plain), max_diff(&direct, &nested));
    assert!(d.0 < SAME && d.1 < SAME, "{d:?}");
    // the wall spacing survives: first cell 1e-5 on the side edges, kept inside
    let h = nested.point(48, 1)[1] - nested.point(48, 0)[1];
    assert!(h > 0.0 && h < 1e-4, "{h}");
}

#[test]
fn nested_iteration_matches_plain_picard_with_the_direct_solver() {
    // the nesting does not depend on the linear solver
    let b = curved(33, 25);
    let plain = grid(&b, &mut DirectLu::new(), false);
    let nested = grid(&b, &mut DirectLu::new(), true);
    assert!(max_diff(&plain, &nested) < SAME);
}

#[test]
fn nested_iteration_needs_few_fine_picard_steps() {
    // 257² curved: 6 levels (257, 129, …, 9); measured 4 fine steps (6 at 129², 3 at 1025²,
    // examples/bench_grid.rs), against 13 steps of plain Picard. The coarse-to-fine
    // difference, hence the fine start error, shrinks with the grid size.
    let b = curved(257, 257);
    assert_eq!(level_sizes(257, 257).len(), 6);
    let mut mg = MultigridSafe::new(MgParams::default());
    let (r, info) =
        grid_block_nested(&b, ControlKind::Algebraic, &mut mg, &params(true), "t").unwrap();
    assert!(r.picard.converged);
    assert_eq!(info.levels.len(), 6);
    assert!(info.levels.iter().all(|l| l.converged));
    assert!(r.picard.steps <= 4, "{} fine steps", r.picard.steps);
    // each fine step costs one or two cycles per coordinate (the forcing term)
    for s in &r.picard.history {
        assert!(s.linear_iterations.iter().all(|&k| (1..=2).contains(&k)));
    }
    // the same without nesting takes far more fine steps
    let mut mg = MultigridSafe::new(MgParams::default());
    let (p, pinfo) =
        grid_block_nested(&b, ControlKind::Algebraic, &mut mg, &params(false), "t").unwrap();
    assert!(p.picard.steps >= r.picard.steps + 5, "{}", p.picard.steps);
    assert!(max_diff(&p.grid, &r.grid) < SAME);
    // work units: total time over one residual evaluation, positive and finite
    assert!(info.work_units.is_finite() && info.work_units > 1.0);
    assert!(pinfo.work_units.is_finite() && pinfo.work_unit_seconds > 0.0);
}

#[test]
fn even_sizes_are_not_coarsened() {
    assert_eq!(level_sizes(64, 49), vec![(64, 49)]);
    let b = curved(20, 15);
    let mut mg = MultigridSafe::new(MgParams::default());
    let (r, info) =
        grid_block_nested(&b, ControlKind::Algebraic, &mut mg, &params(true), "t").unwrap();
    assert_eq!(info.levels.len(), 1);
    let direct = grid(&b, &mut DirectLu::new(), false);
    assert!(max_diff(&r.grid, &direct) < SAME);
}

/// The Picard systems that broke earlier defaults, at the size where they broke: the
/// boundary-layer block at 1025² with wall spacing 1e-5, once as shipped (aspect ratios 2e3;
/// the V-cycle with the adjoint restriction diverged) and once with wall-tangential spacings
/// of 0.15 at both ends (aspect ratios 1.5e4; the V-cycle with `Pᵀ` slipped to 0.27 per
/// cycle). Plain cycles of the default multigrid, no Krylov help, from zero to 1e-10: at
/// most 0.15 per cycle (measured 0.03–0.05).
#[test]
fn default_cycles_converge_on_boundary_layer_picard_systems_at_1025() {
    use ellipgrid::algebraic::control2d::control_for;
    use ellipgrid::elliptic::poisson2d::assemble;
    use ellipgrid::solve::multigrid::Multigrid;
    use ellipgrid::solve::stencil9::Stencil9;
    use ellipgrid::solve::SolveControl;
    type Edit = fn(String) -> String;
    let cases: [(&str, Edit); 2] = [
        ("aspect 2e3", |s| s.replace("first = 1e-4", "first = 1e-5")),
        ("aspect 1.5e4", |s| {
            s.replace("first = 1e-4", "first = 1e-5")
                .replace("first = 0.01, last = 0.02", "first = 0.15, last = 0.15")
        }),
    ];
    for (label, edit) in cases {
        let b = boundary("boundary_layer.toml", 1025, 1025, edit);
        let mut mg = MultigridSafe::new(MgParams::default());
        let (r, _) =
            grid_block_nested(&b, ControlKind::Algebraic, &mut mg, &params(true), "bl").unwrap();
        assert!(r.picard.converged, "{label}: {:?}", r.picard);
        let g = r.grid;
        let ctrl = control_for(&b, ControlKind::Algebraic);
        let (nx, ny) = (g.ni() - 2, g.nj() - 2);
        let mut a = Stencil9::zeros(nx, ny);
        let mut rhs = [vec![0.0; nx * ny], vec![0.0; nx * ny]];
        assemble(&g, &ctrl, &mut a, &mut rhs);
        let mut mg = Multigrid::new(MgParams::default());
        mg.setup(&a).unwrap();
        let ctl = SolveControl {
            rel_tol: 1e-10,
            max_iter: 30,
        };
        for (c, bc) in rhs.iter().enumerate() {
            let mut x = vec![0.0; nx * ny];
            let info = mg.solve(bc, &mut x, &ctl).unwrap();
            let k = info.iterations as f64;
            let factor = info.residual_history.last().unwrap().powf(1.0 / k);
            assert!(info.converged, "{label} coord {c}: {info:?}");
            assert!(factor <= 0.15, "{label} coord {c}: factor {factor}");
        }
    }
}

/// A rectangle with stretched, equal opposite distributions at 517 × 515 nodes: its
/// tensor-product grid is an exact discrete solution (Thomas–Middlecoff, METHOD.md §8). The
/// size is above the thresholds of the memory-saving paths of #16 (control functions
/// computed at each use from 2^18 nodes, coordinates solved one after the other from 2^18
/// unknowns; the multigrid takes the Picard operator over and its y-lines read the stencil):
/// the nested multigrid solve reproduces the exact grid to the Picard tolerance, in few fine
/// steps.
#[test]
fn large_grid_memory_paths_reproduce_an_exact_discrete_solution() {
    let (ni, nj) = (517, 515);
    assert!((ni - 2) * (nj - 2) >= 1 << 18);
    let xs: Vec<f64> = (0..ni)
        .map(|k| 3.0 * (1.0 - (k as f64 / (ni - 1) as f64 * 1.3).cos()) / (1.0 - 1.3f64.cos()))
        .collect();
    let ys: Vec<f64> = (0..nj)
        .map(|k| 0.5 * ((k as f64 / (nj - 1) as f64) * 3.0).exp_m1() / 3.0f64.exp_m1())
        .collect();
    let exact = Grid2::<2>::from_fn(ni, nj, |i, j| [xs[i], ys[j]]);
    let b = Boundary2::from_grid(&exact, "rect").unwrap();
    let mut solver = by_name("multigrid").unwrap();
    let (r, _) = grid_block_nested(
        &b,
        ControlKind::Algebraic,
        solver.as_mut(),
        &params(true),
        "rect",
    )
    .unwrap();
    assert!(r.picard.converged, "{:?}", r.picard.history);
    let d = max_diff(&r.grid, &exact);
    assert!(d < SAME, "{d:.2e}");
    assert!(r.picard.steps <= 4, "{} fine steps", r.picard.steps);
}
