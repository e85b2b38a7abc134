//! Benchmark of the Section 4 pipeline: point location in an (s, t) quad mesh by the walk
//! from the previous target, by the BVH, and the bilinear Newton inversion, at 10⁶ quads; and
//! the whole surface pipeline for a 1025² grid on the wing–pylon net, by step; and the
//! wing–pylon block on its STEP model (`examples/wing_pylon_step.toml`: model, junction, net,
//! pipeline, nodes onto the model) beside the same block on the analytic Hermite net.
//!
//! `cargo run --release --example bench_surface [-- --quick]`
//!
//! `--write DIR` writes every computed grid (or solution) as raw f64 for `scripts/same-grids.sh`.

#[path = "common/dump.rs"]
mod dump;
use ellipgrid::grid::Edge;
use ellipgrid::solve::select::by_name;
use ellipgrid::surface::inversion::{bilinear_inverse, QuadMesh};
use ellipgrid::surface::pipeline::{edge_params, grid_surface};
use ellipgrid_geometry::uniform;
use std::time::Instant;

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let n = if quick { 257 } else { 1001 };
    // A distorted, fold-free mesh of the unit square with (n−1)² quads.
    let (mut s, mut t) = (vec![0.0; n * n], vec![0.0; n * n]);
    for j in 0..n {
        for i in 0..n {
            let (u, v) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
            let w = 0.08 * (std::f64::consts::PI * u).sin() * (std::f64::consts::PI * v).sin();
            s[i + n * j] = u + w * (3.0 * v).cos();
            t[i + n * j] = v + w * (2.0 * u).sin();
        }
    }
    let t0 = Instant::now();
    let mesh = QuadMesh::new(n, n, &s, &t, "bench").unwrap();
    let build = t0.elapsed().as_secs_f64();
    // Targets: a structured sweep over a slightly different uniform lattice.
    let m = n - 1;
    let targets: Vec<[f64; 2]> = (0..m * m)
        .map(|k| {
            let (i, j) = (k % m, k / m);
            [(i as f64 + 0.37) / m as f64, (j as f64 + 0.61) / m as f64]
        })
        .collect();
    let mut scratch = Vec::new();
    let t1 = Instant::now();
    let mut prev = (0, 0);
    let mut found = 0usize;
    for x in &targets {
        if let Some(h) = mesh.walk(*x, prev) {
            prev = (h.p, h.q);
            found += 1;
        }
    }
    let walk = t1.elapsed().as_secs_f64() / targets.len() as f64;
    let t2 = Instant::now();
    let mut found_bvh = 0usize;
    for x in &targets {
        found_bvh += mesh.search(*x, &mut scratch).is_some() as usize;
    }
    let bvh = t2.elapsed().as_secs_f64() / targets.len() as f64;
    let quad = [[0.0, 0.0], [1.1, 0.1], [0.05, 0.9], [1.2, 1.05]];
    let t3 = Instant::now();
    let mut acc = 0.0;
    for x in &targets {
        let (a, b) = bilinear_inverse(&quad, *x).unwrap();
        acc += a + b;
    }
    let newton = t3.elapsed().as_secs_f64() / targets.len() as f64;
    println!(
        "point location, {} quads: BVH build {:.3} s; walk {:.0} ns/query ({} found); BVH {:.0} ns/query ({} found); bilinear Newton {:.0} ns ({acc:.1})",
        (n - 1) * (n - 1),
        build,
        walk * 1e9,
        found,
        bvh * 1e9,
        found_bvh,
        newton * 1e9
    );
    // The whole pipeline on the wing–pylon net.
    let nn = if quick { 257 } else { 1025 };
    let case = ellipgrid::case::LoadedCase::read(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/wing_pylon.toml"
    )))
    .unwrap();
    let surf = case.surface(0).unwrap();
    for linear in ["multigrid", "direct"] {
        if linear == "direct" && nn > 513 {
            continue;
        }
        let Ok(mut solver) = by_name(linear) else {
            continue;
        };
        let t4 = Instant::now();
        let sigma = uniform(nn);
        let uv = Edge::ALL.map(|e| edge_params(surf.as_ref(), e, &sigma));
        let bnd = t4.elapsed().as_secs_f64();
        let r = grid_surface(surf.as_ref(), &uv, solver.as_mut(), "bench").unwrap();
        let all = t4.elapsed().as_secs_f64();
        let c = r.grid.coords();
        dump::dump(
            &format!("surface_{nn}_{}", solver.name()),
            &[&c[0], &c[1], &c[2]],
        );
        let tm = &r.times;
        println!(
            "surface pipeline {nn}² ({}): boundary {:.3} s, initial grid {:.3} s, Laplace–Beltrami {:.3} s, target {:.3} s, inversion {:.3} s, total {:.3} s",
            solver.name(),
            bnd,
            tm.initial_grid,
            tm.laplace_beltrami,
            tm.target,
            tm.inversion,
            all
        );
    }
    // The wing–pylon block on its STEP model against the same block on the Hermite net.
    for (ni, nj) in [(129, 65), (513, 257)] {
        let read = |name: &str| {
            let path = std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/examples"))
                .join(name);
            let text = std::fs::read_to_string(&path)
                .unwrap()
                .replace("ni = 129", &format!("ni = {ni}"))
                .replace("nj = 65", &format!("nj = {nj}"));
            ellipgrid::case::LoadedCase::parse(&text, &path).unwrap()
        };
        let (model_case, net_case) = (read("wing_pylon_step.toml"), read("wing_pylon.toml"));
        let mut solver = by_name("multigrid").unwrap();
        let t0 = Instant::now();
        let m = ellipgrid::job::model::model_block(&model_case, 0).unwrap();
        let t1 = Instant::now();
        let mut r = grid_surface(&m.surface, &m.uv, solver.as_mut(), "bench").unwrap();
        let t2 = Instant::now();
        let moved = ellipgrid::job::model::onto_model(&mut r.grid, &m);
        let t3 = Instant::now();
        let (surf, uv) = net_case.surface_block(0).unwrap();
        let h = grid_surface(surf.as_ref(), &uv, solver.as_mut(), "bench").unwrap();
        let t4 = Instant::now();
        let s = |a: Instant, b: Instant| (b - a).as_secs_f64();
        println!(
            "wing–pylon {ni} × {nj} on the STEP model: model + junction + net {:.3} s, pipeline {:.3} s, onto the model {:.3} s (moved ≤ {:.2e}), total {:.3} s; on the analytic net: {:.3} s ({} nodes)",
            s(t0, t1),
            s(t1, t2),
            s(t2, t3),
            moved.max,
            s(t0, t3),
            s(t3, t4),
            h.grid.len()
        );
    }
}
