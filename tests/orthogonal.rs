//! Orthogonality at chosen boundary edges (issue #5, paper Section 2.4), through the library
//! and the command line.

mod common;
use common::*;
use ellipgrid::algebraic::ControlKind;
use ellipgrid::elliptic::domain::grid_block;
use ellipgrid::elliptic::orthogonal::orthogonal_steps;
use ellipgrid::elliptic::picard::PicardParams;
use ellipgrid::grid::boundary::Boundary2;
use ellipgrid::io::plot3d::read_plot3d;
use ellipgrid::io::Block;
use ellipgrid::quality::{quality2d, quality_surface};
use ellipgrid::solve::direct::DirectLu;
use ellipgrid::{Edge, Grid2};
use std::f64::consts::PI;
use std::fs;

fn params() -> PicardParams {
    PicardParams {
        tolerance: 1e-9,
        ..PicardParams::default()
    }
}

/// Points p + u (q − p) + bulge sin(πu) n, n the left normal of q − p, at u_k = k/(n−1).
fn bulged(p: [f64; 2], q: [f64; 2], bulge: f64, n: usize) -> Vec<[f64; 2]> {
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let l = dx.hypot(dy);
    let nn = [-dy / l, dx / l];
    (0..n)
        .map(|k| {
            let u = k as f64 / (n - 1) as f64;
            let b = bulge * (PI * u).sin();
            [p[0] + u * dx + b * nn[0], p[1] + u * dy + b * nn[1]]
        })
        .collect()
}

/// A curved quadrilateral: four curved edges meeting at corners of about 63°, 117°, 108° and
/// 72°.
fn curved(n: usize) -> Boundary2<2> {
    let (p00, p10, p01, p11) = ([0.0, 0.0], [2.0, 0.3], [-0.6, 1.2], [2.3, 1.6]);
    Boundary2::new(
        [
            bulged(p00, p01, 0.15, n),
            bulged(p10, p11, -0.2, n),
            bulged(p00, p10, 0.25, n),
            bulged(p01, p11, 0.2, n),
        ],
        "curved",
    )
    .unwrap()
}

/// Largest deviation from 90° (degrees) of the first grid line at edge `e`, skipping the
/// nodes within `skip` (fraction of the edge) of each corner. The off-wall direction is the
/// first grid line (x₁ − x₀), the wall tangent a central difference, as in the quality report.
/// With `second_order`, the off-wall direction is the one-sided second-order tangent
/// −3x₀ + 4x₁ − x₂ of the grid line instead.
fn deviation<const D: usize>(g: &Grid2<D>, e: Edge, skip: f64, second_order: bool) -> f64 {
    let (ni, nj) = (g.ni(), g.nj());
    // Node k of the edge and the nodes m = 1, 2 in from it.
    let node = |k: usize, m: usize| -> (usize, usize) {
        match e {
            Edge::E1 => (m, k),
            Edge::E2 => (ni - 1 - m, k),
            Edge::E3 => (k, m),
            Edge::E4 => (k, nj - 1 - m),
        }
    };
    let x = |(i, j): (usize, usize)| g.point(i, j);
    let len = if e.runs_along_i() { ni } else { nj };
    let k0 = ((skip * (len - 1) as f64).ceil() as usize).max(1);
    let sub = |a: [f64; D], b: [f64; D]| -> [f64; D] { std::array::from_fn(|c| a[c] - b[c]) };
    let dot = |a: &[f64; D], b: &[f64; D]| -> f64 { (0..D).map(|c| a[c] * b[c]).sum() };
    let mut worst = 0.0f64;
    for k in k0..len - k0 {
        let (x0, x1) = (x(node(k, 0)), x(node(k, 1)));
        let off: [f64; D] = if second_order {
            let x2 = x(node(k, 2));
            std::array::from_fn(|c| -3.0 * x0[c] + 4.0 * x1[c] - x2[c])
        } else {
            sub(x1, x0)
        };
        let tan = sub(x(node(k + 1, 0)), x(node(k - 1, 0)));
        let c = dot(&off, &tan) / (dot(&off, &off) * dot(&tan, &tan)).sqrt();
        worst = worst.max((90.0 - c.clamp(-1.0, 1.0).acos().to_degrees()).abs());
    }
    worst
}

fn devs<const D: usize>(g: &Grid2<D>, skip: f64, second_order: bool) -> [f64; 4] {
    Edge::ALL.map(|e| deviation(g, e, skip, second_order))
}

fn fmt(d: &[f64; 4]) -> String {
    d.iter()
        .map(|v| format!("{v:6.3}°"))
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn orthogonal_at_all_four_edges_of_a_curved_domain_converges() {
    // Deviation from 90° of the first grid line at E1..E4, away from the corners (which are not
    // right angles, so no grid is orthogonal there). The first-line angle of the quality report
    // converges like O(h) (an O(h²) position error at distance h); the grid line's own angle,
    // from a second-order one-sided tangent, is below it.
    let mut first = Vec::new();
    let mut second = Vec::new();
    for n in [32usize, 64, 128, 256] {
        let b = curved(n + 1);
        let r = orthogonal_steps(&b, [true; 4], &mut DirectLu::new(), &params(), "c").unwrap();
        assert!(r.picard.converged && !quality2d(&r.grid).is_folded());
        let (d1, d2) = (devs(&r.grid, 0.25, false), devs(&r.grid, 0.125, true));
        println!(
            "N = {n:3}: first line (skip 1/4) {}   second-order tangent (skip 1/8) {}   \
             Picard steps {} + {}",
            fmt(&d1),
            fmt(&d2),
            r.picard.first.as_ref().map_or(0, |f| f.steps),
            r.picard.steps
        );
        if n == 32 {
            let plain = grid_block(
                &b,
                None,
                ControlKind::Algebraic,
                &mut DirectLu::new(),
                &params(),
                "c",
            )
            .unwrap();
            let d0 = devs(&plain.grid, 0.25, false);
            println!("N =  32 without orthogonality: first line {}", fmt(&d0));
            assert!((0..4).all(|e| d1[e] < 0.3 * d0[e]), "{d1:?} vs {d0:?}");
        }
        first.push(d1);
        second.push(d2);
    }
    for w in first.windows(2).chain(second.windows(2)) {
        assert!(
            (0..4).all(|e| w[1][e] < 0.75 * w[0][e]),
            "no shrinking: {w:?}"
        );
    }
    assert!(first[3].iter().all(|&d| d < 1.0), "{:?}", first[3]);
    assert!(second[3].iter().all(|&d| d < 1.0), "{:?}", second[3]);
}

#[test]
fn orthogonal_at_one_edge_leaves_the_other_edges_alone() {
    let b = curved(65);
    let r = orthogonal_steps(
        &b,
        [false, false, true, false],
        &mut DirectLu::new(),
        &params(),
        "c",
    )
    .unwrap();
    let plain = grid_block(
        &b,
        None,
        ControlKind::Algebraic,
        &mut DirectLu::new(),
        &params(),
        "c",
    )
    .unwrap();
    let (d, d0) = (devs(&r.grid, 0.125, false), devs(&plain.grid, 0.125, false));
    println!("E3 orthogonal: {}\nplain:         {}", fmt(&d), fmt(&d0));
    assert!(d[2] < 1.0 && d[2] < 0.1 * d0[2]);
    for e in [0, 1, 3] {
        assert!(
            (d[e] - d0[e]).abs() < 0.15 * d0[e] + 0.2,
            "edge {e}: {d:?} vs {d0:?}"
        );
    }
    // Only s_E3 changed: the other edge functions are the arclength ones.
    let arc = ellipgrid::grid::arclength::EdgeFunctions::arclength(&b);
    assert_eq!(
        (&r.edge_functions.t_e1, &r.edge_functions.t_e2),
        (&arc.t_e1, &arc.t_e2)
    );
    assert_eq!(r.edge_functions.s_e4, arc.s_e4);
    assert!(r.edge_functions.s_e3 != arc.s_e3);
    assert!(!quality2d(&r.grid).is_folded());
}

/// A bump of chord 1 and 12% height in a channel from x = −1 to 2, height 1.5, with the first
/// spacing 1e-5 chord at the wall E3 on E1 and E2 (Vinokur).
fn bump_wall(ni: usize, nj: usize) -> Boundary2<2> {
    let h = 1.5;
    let sigma = ellipgrid_geometry::Distribution::Vinokur {
        first: Some(1e-5 / h),
        last: None,
    }
    .sample(nj)
    .unwrap();
    let wall = |x: f64| {
        if (0.0..=1.0).contains(&x) {
            0.12 * (PI * x).sin().powi(2)
        } else {
            0.0
        }
    };
    let xs: Vec<f64> = (0..ni)
        .map(|k| -1.0 + 3.0 * k as f64 / (ni - 1) as f64)
        .collect();
    Boundary2::new(
        [
            sigma.iter().map(|&v| [-1.0, h * v]).collect(),
            sigma.iter().map(|&v| [2.0, h * v]).collect(),
            xs.iter().map(|&x| [x, wall(x)]).collect(),
            xs.iter().map(|&x| [x, h]).collect(),
        ],
        "bump",
    )
    .unwrap()
}

#[test]
fn a_strongly_clustered_wall_becomes_orthogonal_without_folding() {
    let b = bump_wall(97, 65);
    let plain = grid_block(
        &b,
        None,
        ControlKind::Algebraic,
        &mut DirectLu::new(),
        &params(),
        "w",
    )
    .unwrap();
    let r = orthogonal_steps(
        &b,
        [false, false, true, false],
        &mut DirectLu::new(),
        &params(),
        "w",
    )
    .unwrap();
    let q = quality2d(&r.grid);
    let (d, d0) = (
        deviation(&r.grid, Edge::E3, 0.0, false),
        deviation(&plain.grid, Edge::E3, 0.0, false),
    );
    println!(
        "wall E3: {d:.4}° (plain {d0:.3}°), first spacing {:.3e}, min scaled Jacobian {:.3}, \
         Picard {} + {}",
        q.min_spacing,
        q.scaled_jacobian_min,
        r.picard.first.as_ref().map_or(0, |f| f.steps),
        r.picard.steps
    );
    assert!(r.picard.converged);
    assert_eq!(q.folded_cells, 0);
    assert!(d0 > 10.0 && d < 0.5, "{d} vs {d0}");
    // The wall spacing survives: first spacing 1e-5 on E1, and nowhere a collapsed cell.
    let e1 = b.edge(Edge::E1);
    assert!((e1[1][1] - e1[0][1] - 1e-5).abs() < 1e-9);
    assert!(q.min_spacing > 0.5e-5 && q.scaled_jacobian_min > 0.9);
}

/// Scherk's minimal surface z = ln(cos y / cos x) over |x|, |y| ≤ 1.2: the four boundary
/// curves, uniform in x (or y).
fn scherk(n: usize) -> Boundary2<3> {
    let a = 1.2f64;
    let z = |x: f64, y: f64| (y.cos() / x.cos()).ln();
    let u: Vec<f64> = (0..n)
        .map(|k| -a + 2.0 * a * k as f64 / (n - 1) as f64)
        .collect();
    Boundary2::new(
        [
            u.iter().map(|&y| [-a, y, z(-a, y)]).collect(),
            u.iter().map(|&y| [a, y, z(a, y)]).collect(),
            u.iter().map(|&x| [x, -a, z(x, -a)]).collect(),
            u.iter().map(|&x| [x, a, z(x, a)]).collect(),
        ],
        "scherk",
    )
    .unwrap()
}

#[test]
fn minimal_surface_orthogonal_at_chosen_edges() {
    // Orthogonality at E1 and E3, measured in R³ (the tangent plane to first order); the grid
    // stays on Scherk's surface.
    let orth = [true, false, true, false];
    let mut prev = [f64::INFINITY; 2];
    for n in [24usize, 48] {
        let b = scherk(n + 1);
        let r = orthogonal_steps(&b, orth, &mut DirectLu::new(), &params(), "s").unwrap();
        let plain = grid_block(
            &b,
            None,
            ControlKind::Algebraic,
            &mut DirectLu::new(),
            &params(),
            "s",
        )
        .unwrap();
        let (d, d0) = (devs(&r.grid, 0.25, false), devs(&plain.grid, 0.25, false));
        let off = (0..r.grid.len())
            .map(|k| {
                let (x, y, z) = (r.grid.coord(0)[k], r.grid.coord(1)[k], r.grid.coord(2)[k]);
                (z - (y.cos() / x.cos()).ln()).abs()
            })
            .fold(0.0, f64::max);
        let mid = devs(&r.grid, 0.375, false);
        println!(
            "Scherk N = {n}: skip 1/4 {} (plain {}), middle quarter {}, off-surface {off:.2e}",
            fmt(&d),
            fmt(&d0),
            fmt(&mid)
        );
        assert!(mid[0] < 0.25 * d0[0] && mid[2] < 0.25 * d0[2], "{mid:?}");
        assert!(!quality_surface(&r.grid).is_folded());
        assert!(d[0] < 0.5 * d0[0] && d[2] < 0.5 * d0[2], "{d:?} vs {d0:?}");
        assert!(d[0] < prev[0] && d[2] < prev[1]);
        assert!(off < 0.05);
        prev = [d[0], d[2]];
    }
}

/// Mean orthogonality deviation per edge (E1..E4) of block 0 from a run report.
fn report_means(path: &std::path::Path) -> Vec<f64> {
    let v: serde_json::Value = serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap();
    v["blocks"][0]["quality"]["orthogonality"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["mean_deg"].as_f64().unwrap())
        .collect()
}

#[test]
fn cli_runs_the_orthogonal_examples() {
    let dir = tempfile::tempdir().unwrap();
    let run = |case: &str, rep: &str| {
        let c = root().join("examples").join(case);
        let o = ellipgrid(
            dir.path(),
            &[
                "run",
                c.to_str().unwrap(),
                "-o",
                "g.x",
                "--report",
                rep,
                "-q",
            ],
        );
        assert!(o.status.success(), "{}", text(&o));
        report_means(&dir.path().join(rep))
    };
    let plain = run("curved.toml", "plain.json");
    let orth = run("orthogonal.toml", "orth.json");
    println!("mean deviation plain {plain:?}\northogonal {orth:?}");
    assert!(
        (0..4).all(|e| orth[e] < 0.15 * plain[e]),
        "{orth:?} vs {plain:?}"
    );
    let wall = run("airfoil_wall.toml", "wall.json");
    assert!(wall[2] < 0.05, "{wall:?}");
    // The bump's channel passes checkMesh's aspect-ratio check (385 nodes along the wall:
    // 2326 with 121), and its floor is flat: with the nearest spline points 0.1 from the bump
    // the spline overshot there and the floor dipped 4.2e-4, 40 wall spacings.
    let grid = read_plot3d(&dir.path().join("g.x")).unwrap();
    let Block::Planar(g) = &grid.blocks[0] else {
        panic!("a planar block")
    };
    let (ar, i, j) = foam_aspect_ratio_max(g);
    assert!(ar < 1000.0, "aspect ratio {ar} at cell ({i}, {j})");
    let dip = (0..g.ni())
        .map(|i| g.point(i, 0))
        .filter(|p| p[0] < 0.0 || p[0] > 1.0)
        .map(|p| p[1].abs())
        .fold(0.0, f64::max);
    assert!(dip < 2e-5, "the flat floor is {dip} off y = 0");
}

#[test]
fn cli_rejects_unknown_edge_names() {
    let dir = tempfile::tempdir().unwrap();
    let case = square_case(9, 9).replace("nj = 9\n", "nj = 9\northogonal = [\"E3\", \"E5\"]\n");
    fs::write(dir.path().join("c.toml"), case).unwrap();
    let o = ellipgrid(dir.path(), &["run", "c.toml", "-o", "g.x"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("block 'b'") && text(&o).contains("'E5'"),
        "{}",
        text(&o)
    );
    assert!(!dir.path().join("g.x").exists());
}

#[test]
fn cli_smooth_makes_chosen_edges_orthogonal() {
    let dir = tempfile::tempdir().unwrap();
    let c = root().join("examples/curved.toml");
    let o = ellipgrid(
        dir.path(),
        &["run", c.to_str().unwrap(), "-o", "in.x", "-q"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let smooth = |extra: &[&str], rep: &str| {
        let mut args = vec!["smooth", "in.x", "-o", "out.x", "--report", rep, "-q"];
        args.extend_from_slice(extra);
        let o = ellipgrid(dir.path(), &args);
        assert!(o.status.success(), "{}", text(&o));
        report_means(&dir.path().join(rep))
    };
    let plain = smooth(&[], "p.json");
    let orth = smooth(&["--orthogonal", "E3,e4"], "o.json");
    assert!(
        orth[2] < 0.15 * plain[2] && orth[3] < 0.15 * plain[3],
        "{orth:?} vs {plain:?}"
    );
    let o = ellipgrid(
        dir.path(),
        &["smooth", "in.x", "-o", "bad.x", "--orthogonal", "E7"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("--orthogonal") && text(&o).contains("'E7'"),
        "{}",
        text(&o)
    );
}
