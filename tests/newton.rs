//! Newton–Krylov steps (`[solver] nonlinear = "newton"`, issue #16): the converged grid is
//! plain Picard's to the tolerance, the stop is honest (the grid is within the tolerance of
//! the discrete solution, here Picard's to 1e-13), the grids do not depend on the thread
//! count, and the setting is reachable and checked through the command line.

mod common;
use common::*;
use ellipgrid::case::LoadedCase;
use ellipgrid::elliptic::picard::Nonlinear;
use ellipgrid::io::plot3d::read_plot3d;
use ellipgrid::io::Block;
use ellipgrid::job;
use std::fs;
use std::path::Path;

/// The shipped example `file`, edited by `edit`, with the nonlinear iteration `nl` and the
/// tolerance `tol`.
fn case(file: &str, edit: fn(&str) -> String, nl: Nonlinear, tol: f64) -> LoadedCase {
    let path = root().join("examples").join(file);
    let text = edit(&fs::read_to_string(&path).unwrap());
    let mut case = LoadedCase::parse(&text, Path::new(&path)).unwrap();
    case.case.solver.picard.nonlinear = Some(nl);
    case.case.solver.picard.tolerance = tol;
    case
}

fn planar(b: &Block) -> &ellipgrid::Grid2<2> {
    match b {
        Block::Planar(g) => g,
        other => panic!("not a planar block: {other:?}"),
    }
}

/// Largest node distance between two generations, per block relative to its diameter.
fn difference(a: &job::Generated, b: &job::Generated) -> f64 {
    let mut worst = 0.0f64;
    for ((_, x), (_, y)) in a.blocks.iter().zip(&b.blocks) {
        let (x, y) = (planar(x), planar(y));
        for c in 0..2 {
            for (u, v) in x.coord(c).iter().zip(y.coord(c)) {
                worst = worst.max((u - v).abs() / x.diameter());
            }
        }
    }
    worst
}

fn same(t: &str) -> String {
    t.to_string()
}

/// The NACA0012 O-grid with the mid-chord cuts floating (as `tests/multiblock_refinement.rs`).
fn floating_mid_cuts(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        out.push_str(line);
        out.push('\n');
        if line == "name = \"cut_up\"" || line == "name = \"cut_lo\"" {
            out.push_str("interface = \"floating\"\n");
        }
    }
    out
}

/// `orthogonal.toml` with the multigrid solver instead of the sparse LU.
fn multigrid(text: &str) -> String {
    text.replace("linear = \"direct\"", "linear = \"multigrid\"")
}

/// The fine steps of all blocks of a generation, each converged.
fn steps(g: &job::Generated) -> usize {
    g.report
        .blocks
        .iter()
        .map(|b| {
            let p = b.picard.as_ref().expect("a Picard report");
            assert!(p.converged, "{}: not converged", b.name);
            p.steps
        })
        .sum()
}

#[test]
fn newton_reaches_the_picard_grid_and_its_stop_is_honest() {
    let tol = 1e-10;
    type Edit = fn(&str) -> String;
    let cases: [(&str, &str, Edit); 6] = [
        // the transfinite start folds in the wavy wall's valleys
        ("folded start", "folding_start.toml", same),
        // a deep mushroom-shaped dent, the transfinite start folds (257², coarse levels of
        // Newton steps stopped at nested::COARSE_STOP_NEWTON)
        ("dented square", "dented_square.toml", same),
        // orthogonality at four edges: three solves (steps 1 and 3 by Newton)
        ("orthogonality, direct", "orthogonal.toml", same),
        ("orthogonality, multigrid", "orthogonal.toml", multigrid),
        // four blocks around an airfoil, orthogonal cuts
        ("NACA0012 O-grid", "naca0012_ogrid.toml", same),
        // two rows of blocks joined by floating interfaces
        (
            "NACA0012 floating cuts",
            "naca0012_ogrid.toml",
            floating_mid_cuts,
        ),
    ];
    for (what, file, edit) in cases {
        let gen = |nl, tol| job::generate(&case(file, edit, nl, tol), |_| {}).unwrap();
        let picard = gen(Nonlinear::Picard, tol);
        let newton = gen(Nonlinear::Newton, tol);
        let exact = gen(Nonlinear::Picard, 1e-13);
        let (sp, sn) = (steps(&picard), steps(&newton));
        let (dp, dn) = (difference(&picard, &exact), difference(&newton, &exact));
        let d = difference(&picard, &newton);
        println!(
            "{what}: steps Picard {sp} Newton {sn}; error Picard {dp:.1e} Newton {dn:.1e}; \
             Picard vs Newton {d:.1e}"
        );
        // the honest stop: within the tolerance of the discrete solution (the orthogonality
        // steps carry step 1's error into the control functions of step 3)
        assert!(
            dn <= tol,
            "{what}: Newton's grid is {dn:e} from the solution"
        );
        assert!(d <= 2.0 * tol, "{what}: Picard and Newton differ by {d:e}");
        // Newton steps begin where Picard steps contract slowly: never more steps, and
        // fewer on the folded start and the airfoil grids
        let slow = !what.starts_with("orthogonality");
        assert!(
            sn < sp || (!slow && sn == sp),
            "{what}: Newton {sn} steps, Picard {sp}"
        );
        for b in &newton.report.blocks {
            assert_eq!(b.quality.folded_cells, 0, "{what}: {} folds", b.name);
        }
    }
}

#[test]
fn newton_grids_are_bit_identical_on_1_and_2_threads() {
    // 257² nodes: the parallel paths of the Krylov vectors, the coupling and the multigrid
    let big = |t: &str| {
        t.replace("ni = 65", "ni = 257")
            .replace("nj = 49", "nj = 257")
    };
    let curved = case("curved.toml", big, Nonlinear::Newton, 1e-10);
    let naca = case("naca0012_ogrid.toml", same, Nonlinear::Newton, 1e-10);
    for (what, case) in [("curved 257²", curved), ("NACA0012", naca)] {
        let run = || format!("{:?}", job::generate(&case, |_| {}).unwrap().blocks);
        let pool = |n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
        };
        let one = pool(1).install(run);
        let two = pool(2).install(run);
        assert!(
            one == two,
            "{what}: the grids differ between 1 and 2 threads"
        );
    }
}

/// Reads the single planar block of a Plot3D file.
fn read(path: &Path) -> ellipgrid::Grid2<2> {
    let f = read_plot3d(path).unwrap();
    planar(&f.blocks[0]).clone()
}

fn max_diff(a: &ellipgrid::Grid2<2>, b: &ellipgrid::Grid2<2>) -> f64 {
    (0..2)
        .flat_map(|c| {
            a.coord(c)
                .iter()
                .zip(b.coord(c))
                .map(|(u, v)| (u - v).abs())
        })
        .fold(0.0, f64::max)
        / a.diameter()
}

#[test]
fn the_command_line_takes_nonlinear_in_case_files_and_smooth() {
    let dir = tempfile::tempdir().unwrap();
    let case = fs::read_to_string(root().join("examples/folding_start.toml")).unwrap();
    let write = |name: &str, solver: &str| {
        let t = case
            .replace("[solver]", &format!("[solver]\n{solver}"))
            .replace("folding_start.x", &format!("{name}.x"));
        fs::write(dir.path().join(format!("{name}.toml")), t).unwrap();
    };
    write("picard", "");
    write("newton", "nonlinear = \"newton\"");
    for args in [
        &["run", "picard.toml", "--write-start", "start.x"][..],
        &["run", "newton.toml"][..],
    ] {
        let o = ellipgrid(dir.path(), args);
        assert!(o.status.success(), "{}", text(&o));
    }
    let (p, n) = (
        read(&dir.path().join("picard.x")),
        read(&dir.path().join("newton.x")),
    );
    assert!(max_diff(&p, &n) <= 2e-10, "run: {:e}", max_diff(&p, &n));
    // smooth the folded start grid both ways
    for nl in ["picard", "newton"] {
        let out = format!("smooth_{nl}.x");
        let o = ellipgrid(
            dir.path(),
            &["smooth", "start.x", "-o", &out, "--nonlinear", nl],
        );
        assert!(o.status.success(), "{}", text(&o));
    }
    let (sp, sn) = (
        read(&dir.path().join("smooth_picard.x")),
        read(&dir.path().join("smooth_newton.x")),
    );
    assert!(
        max_diff(&sp, &sn) <= 2e-10,
        "smooth: {:e}",
        max_diff(&sp, &sn)
    );
    assert!(
        max_diff(&sp, &p) <= 2e-10,
        "smooth vs run: {:e}",
        max_diff(&sp, &p)
    );
}

#[test]
fn bad_nonlinear_settings_exit_2_naming_the_key_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let case = fs::read_to_string(root().join("examples/folding_start.toml")).unwrap();
    for (solver, says) in [
        ("nonlinear = \"fast\"", "nonlinear"),
        ("nonlinear = \"newton\"\nanderson = 5", "anderson = 5"),
    ] {
        fs::write(
            dir.path().join("bad.toml"),
            case.replace("[solver]", &format!("[solver]\n{solver}")),
        )
        .unwrap();
        let o = ellipgrid(dir.path(), &["run", "bad.toml"]);
        assert_eq!(o.status.code(), Some(2), "{solver}: {}", text(&o));
        assert!(text(&o).contains(says), "{solver}: {}", text(&o));
        assert!(!text(&o).contains("panicked"), "{}", text(&o));
        assert!(!dir.path().join("folding_start.x").exists());
    }
    let o = ellipgrid(
        dir.path(),
        &["smooth", "none.x", "-o", "out.x", "--nonlinear", "fast"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--nonlinear"), "{}", text(&o));
    assert!(!dir.path().join("out.x").exists());
}
