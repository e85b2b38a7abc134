//! Benchmark of the volume pipeline (issue #6): a warped, wall-clustered box at n³ nodes,
//! transfinite start, Picard with Bi-CGSTAB/ILU(0), tolerance 1e-10.
//!
//! `cargo run --release --example bench_volume -- 33 65 129`

use ellipgrid::domain::ControlKind;
use ellipgrid::poisson2d::PicardParams;
use ellipgrid::volume::{grid_volume, quality3d, BiCgStabIlu, Faces};
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

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![33, 65]
    } else {
        sizes
    };
    for n in sizes {
        let faces = boundary(n);
        let t0 = Instant::now();
        let r = grid_volume(
            &faces,
            None,
            ControlKind::Algebraic,
            &mut BiCgStabIlu::new(),
            &PicardParams::default(),
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
        let q = quality3d(&r.grid);
        println!(
            "{n}^3: {secs:.2} s, {} Picard steps (converged {}), {} Bi-CGSTAB iterations in all, \
             {:.2} s/step, folded {}, final residual {:.2e}",
            r.picard.steps,
            r.picard.converged,
            its,
            secs / r.picard.steps as f64,
            q.folded_cells,
            r.picard.final_residual
        );
    }
}
