//! Outputs do not depend on the thread count (issue #17): every parallel reduction adds its
//! chunks in a fixed order, and faer's sparse LU splits its work two ways whatever the pool. Each case is solved in a 1-thread and in a 2-thread rayon pool and
//! the grids are compared bit for bit; the sizes are large enough (≥ 2¹⁵ unknowns) for the
//! solvers to take their parallel paths with 2 threads.

use ellipgrid::algebraic::ControlKind;
use ellipgrid::case::LoadedCase;
use ellipgrid::elliptic::picard::PicardParams;
use ellipgrid::elliptic::volume::grid_volume;
use ellipgrid::grid::faces::Faces;
use ellipgrid::solve::direct::DirectLu3;
use ellipgrid::solve::ilu::BiCgStabIlu;
use ellipgrid::solve::multigrid3d::Multigrid3;
use ellipgrid::solve::stencil19::Stencil19;
use ellipgrid::solve::LinearSolver;
use ellipgrid::Grid3;
use std::path::Path;

fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

fn bits(coords: &[Vec<f64>]) -> Vec<u64> {
    coords.iter().flatten().map(|v| v.to_bits()).collect()
}

/// The warped, wall-clustered box of `examples/bench_volume.rs`.
fn warped_box(n: usize) -> Faces {
    let pi = std::f64::consts::PI;
    let h = (n - 1) as f64;
    let g = Grid3::from_fn(n, n, n, |i, j, k| {
        let (x, z) = (i as f64 / h, k as f64 / h);
        let y = ((j as f64 / h) * 4.0).sinh() / 4f64.sinh();
        [
            x + 0.1 * (pi * y).sin() * z,
            y + 0.15 * (pi * x).sin() * (1.0 - y),
            z + 0.1 * x * y,
        ]
    });
    Faces::from_grid(&g)
}

#[test]
fn volume_grids_are_bit_identical_on_1_and_2_threads() {
    type Make = fn() -> Box<dyn LinearSolver<Stencil19>>;
    // 33³ = 35 937 interior unknowns for the iterative solvers; the direct one (faer's
    // supernodal LU, parallel in its own way) at 23³
    let solvers: [(&str, Make, usize); 3] = [
        ("bicgstab", || Box::new(BiCgStabIlu::new()), 35),
        ("multigrid", || Box::new(Multigrid3::default()), 35),
        ("direct", || Box::new(DirectLu3::new()), 25),
    ];
    for (name, make, n) in solvers {
        let faces = warped_box(n);
        let run = || {
            let mut solver = make();
            let r = grid_volume(
                &faces,
                None,
                ControlKind::Algebraic,
                solver.as_mut(),
                &PicardParams::default(),
                name,
                &mut |_, _| {},
            )
            .unwrap();
            assert!(r.picard.converged, "{name}");
            bits(r.grid.coords())
        };
        let one = in_pool(1, run);
        let two = in_pool(2, run);
        let differ = one.iter().zip(&two).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{name}: {differ} coordinates differ");
    }
}

#[test]
fn case_grids_are_bit_identical_on_1_and_2_threads() {
    // planar (multigrid, 257² nodes), minimal surface, parametrized surface, orthogonality
    for (file, size) in [
        ("curved.toml", Some(257)),
        ("scherk.toml", None),
        ("wing_pylon.toml", None),
        ("orthogonal.toml", None),
    ] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples")
            .join(file);
        let mut case = LoadedCase::read(&path).unwrap();
        if let Some(n) = size {
            case.case.blocks[0].ni = Some(n);
            case.case.blocks[0].nj = Some(n);
        }
        let run = || {
            let g = ellipgrid::job::generate(&case, |_| {}).unwrap();
            format!("{:?}", g.blocks)
        };
        let one = in_pool(1, run);
        let two = in_pool(2, run);
        assert!(
            one == two,
            "{file}: the grids differ between 1 and 2 threads"
        );
    }
}

/// `ellipgrid run` of `case` (written into `dir`) with `RAYON_NUM_THREADS=threads`: the
/// bytes of the Plot3D file written.
fn run_with_threads(dir: &Path, case: &str, threads: &str) -> Vec<u8> {
    std::fs::write(dir.join("c.toml"), case).unwrap();
    let out = dir.join(format!("g{threads}.x"));
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_ellipgrid"))
        .args(["run", "c.toml", "-q", "-o"])
        .arg(&out)
        .current_dir(dir)
        .env("RAYON_NUM_THREADS", threads)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    std::fs::read(out).unwrap()
}

/// The thread matrix through the command line (issue #17): a planar case, a surface case
/// and a volume case, each with every linear solver that applies to it (2D: multigrid and
/// direct; volume: Bi-CGSTAB, multigrid and direct), run with 1 and with 2 threads: the
/// written files are identical byte for byte. Sizes: at least 2¹⁵ unknowns per solve, so
/// that the iterative solvers take their parallel paths with 2 threads (faer's LU splits its
/// work the same way at any size).
#[test]
fn cli_outputs_are_bit_identical_on_1_and_2_threads_for_every_solver() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let data = root.join("data").display().to_string();
    let example = |f: &str| {
        std::fs::read_to_string(root.join("examples").join(f))
            .unwrap()
            .replace("../data", &data)
    };
    let sized = |text: String, from: &[&str], to: &[&str]| {
        from.iter().zip(to).fold(text, |t, (a, b)| {
            assert!(t.contains(a), "'{a}' not in the example");
            t.replacen(a, b, 1)
        })
    };
    // planar: 185² nodes (33 489 unknowns); surface: 261 × 129 nodes (32 893 unknowns in the
    // Laplace–Beltrami solves); volume: 35³ nodes (35 937 unknowns), 23³ for the direct LU
    let planar = sized(
        example("curved.toml"),
        &["ni = 65", "nj = 49", "[solver]\n"],
        &["ni = 185", "nj = 185", "[solver]\nlinear = \"LINEAR\"\n"],
    );
    let surface = format!(
        "[solver]\nlinear = \"LINEAR\"\n{}",
        sized(
            example("wing_pylon.toml"),
            &["ni = 129", "nj = 65"],
            &["ni = 261", "nj = 129"]
        )
    );
    let volume = |n: usize| {
        let to = [
            format!("ni = {n}"),
            format!("nj = {n}"),
            format!("nk = {n}"),
            "linear = \"LINEAR\"".to_string(),
        ];
        let to: Vec<&str> = to.iter().map(String::as_str).collect();
        sized(
            example("volume_warped_cube.toml"),
            &["ni = 25", "nj = 25", "nk = 25", "linear = \"bicgstab\""],
            &to,
        )
    };
    let cases = [
        ("planar", "multigrid", planar.clone()),
        ("planar", "direct", planar),
        ("surface", "multigrid", surface.clone()),
        ("surface", "direct", surface),
        ("volume", "bicgstab", volume(35)),
        ("volume", "multigrid", volume(35)),
        ("volume", "direct", volume(23)),
    ];
    let d = tempfile::tempdir().unwrap();
    for (kind, linear, case) in cases {
        let case = case.replace("LINEAR", linear);
        let one = run_with_threads(d.path(), &case, "1");
        let two = run_with_threads(d.path(), &case, "2");
        assert!(!one.is_empty());
        let differ = one.iter().zip(&two).filter(|(a, b)| a != b).count();
        assert!(
            one.len() == two.len() && differ == 0,
            "{kind} with {linear}: {differ} bytes differ between 1 and 2 threads"
        );
    }
}
