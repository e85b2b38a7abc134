//! Minimal surfaces (Section 3): the Poisson system [24] with x ∈ R³ spanned by four 3D edges.

mod common;
use common::*;
use ellipgrid::algebraic::ControlKind;
use ellipgrid::elliptic::domain::grid_block;
use ellipgrid::elliptic::picard::PicardParams;
use ellipgrid::grid::boundary::Boundary2;
use ellipgrid::quality::quality_surface;
use ellipgrid::solve::direct::DirectLu;
use ellipgrid::Grid2;
use std::fs;

const A: f64 = 1.2;

fn scherk(x: f64, y: f64) -> f64 {
    (y.cos() / x.cos()).ln()
}

/// Four edges on Scherk's surface z = ln(cos y / cos x) over [−A, A]², uniform in x and y.
fn scherk_boundary(n: usize) -> Boundary2<3> {
    let c = |k: usize| -A + 2.0 * A * k as f64 / (n - 1) as f64;
    let p = |x: f64, y: f64| [x, y, scherk(x, y)];
    Boundary2::new(
        [
            (0..n).map(|j| p(-A, c(j))).collect(),
            (0..n).map(|j| p(A, c(j))).collect(),
            (0..n).map(|i| p(c(i), -A)).collect(),
            (0..n).map(|i| p(c(i), A)).collect(),
        ],
        "scherk",
    )
    .unwrap()
}

fn distances(g: &Grid2<3>) -> (f64, f64) {
    let d: Vec<f64> = (0..g.len())
        .map(|n| {
            let (x, y, z) = (g.coord(0)[n], g.coord(1)[n], g.coord(2)[n]);
            (z - scherk(x, y)).abs()
        })
        .collect();
    let max = d.iter().cloned().fold(0.0, f64::max);
    let rms = (d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64).sqrt();
    (max, rms)
}

#[test]
fn scherk_surface_is_recovered_at_second_order() {
    let params = PicardParams {
        tolerance: 1e-12,
        max_steps: 400,
        ..PicardParams::default()
    };
    let mut errs = Vec::new();
    for n in [17, 33, 65, 129] {
        let b = scherk_boundary(n);
        let r = grid_block(
            &b,
            None,
            ControlKind::Algebraic,
            &mut DirectLu::new(),
            &params,
            "s",
        )
        .unwrap();
        assert!(r.picard.converged, "n = {n}: {:?}", r.picard.history.last());
        assert_eq!(quality_surface(&r.grid).folded_cells, 0);
        errs.push((n, r.picard.steps, distances(&r.grid)));
    }
    eprintln!("(n, Picard steps, (max, rms) distance to Scherk's surface): {errs:?}");
    for w in errs.windows(2) {
        let ratio = w[0].2 .0 / w[1].2 .0;
        assert!(
            (3.3..5.0).contains(&ratio),
            "max-distance ratio {ratio}: {errs:?}"
        );
    }
}

#[test]
fn a_planar_boundary_in_3d_gives_a_planar_grid() {
    // A curved quadrilateral in the tilted plane z = 0.3 x − 0.2 y.
    let n = 17;
    let pl = |x: f64, y: f64| [x, y, 0.3 * x - 0.2 * y];
    let u = |k: usize| k as f64 / (n - 1) as f64;
    let b = Boundary2::new(
        [
            (0..n)
                .map(|j| pl(0.1 * (std::f64::consts::PI * u(j)).sin(), u(j)))
                .collect(),
            (0..n).map(|j| pl(1.0, u(j))).collect(),
            (0..n).map(|i| pl(u(i), 0.0)).collect(),
            (0..n)
                .map(|i| pl(u(i), 1.0 + 0.2 * (std::f64::consts::PI * u(i)).sin()))
                .collect(),
        ],
        "plane",
    )
    .unwrap();
    let r = grid_block(
        &b,
        None,
        ControlKind::Algebraic,
        &mut DirectLu::new(),
        &PicardParams::default(),
        "p",
    )
    .unwrap();
    for k in 0..r.grid.len() {
        let (x, y, z) = (r.grid.coord(0)[k], r.grid.coord(1)[k], r.grid.coord(2)[k]);
        assert!((z - (0.3 * x - 0.2 * y)).abs() < 1e-12);
    }
}

#[test]
fn minimal_block_runs_from_a_case_file() {
    let d = tempfile::tempdir().unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            root().join("examples/scherk.toml").to_str().unwrap(),
            "-o",
            "s.x",
            "--report",
            "r.json",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    assert_eq!(r["blocks"][0]["picard"]["converged"], true);
    assert_eq!(r["blocks"][0]["quality"]["folded_cells"], 0);
    let dist = r["blocks"][0]["surface_distance"]["max"].as_f64().unwrap();
    assert!(
        dist > 1e-6 && dist < 2e-3,
        "reported distance from Scherk's surface {dist}"
    );
    let f = ellipgrid::io::plot3d::read_plot3d(&d.path().join("s.x")).unwrap();
    let ellipgrid::io::Block::Surface(g) = &f.blocks[0] else {
        panic!("not a surface")
    };
    let (max, _) = distances(g);
    assert!(max < 2e-3, "distance to Scherk's surface {max}");
}
