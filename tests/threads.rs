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
