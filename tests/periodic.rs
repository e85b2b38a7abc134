//! Periodic (floating) cuts (#15): a block whose cut E1 = E2 is one floating edge, and a ring
//! of blocks joined by floating edges, are gridded as one block periodic in ξ — the cut's
//! nodes are unknowns and the stencils wrap around the seam (`src/elliptic/periodic.rs`).
//! Known answers on an annulus (every ξ-line a ray at uniform angles, the seam no different),
//! independence of the cut's given nodes, the NACA0012 O-grid as one block and as a ring of
//! four, the shipped example through the command line, and bad input.

mod common;
use common::*;
use ellipgrid::algebraic::periodic::periodic_start;
use ellipgrid::algebraic::transform::transfinite;
use ellipgrid::algebraic::ControlKind;
use ellipgrid::case::LoadedCase;
use ellipgrid::elliptic::periodic;
use ellipgrid::elliptic::picard::PicardParams;
use ellipgrid::io::Block;
use ellipgrid::job;
use ellipgrid::Grid2;
use std::f64::consts::TAU;
use std::path::Path;

/// Rays and uniform angles are asserted to this (radians, and relative to the radius).
const RAY_TOL: f64 = 1e-10;

fn generate(text: &str) -> job::Generated {
    let case = LoadedCase::parse(text, Path::new("periodic.toml")).unwrap();
    job::generate(&case, |_| {}).unwrap()
}

fn planar(b: &Block) -> &Grid2<2> {
    match b {
        Block::Planar(g) => g,
        _ => panic!("a planar block"),
    }
}

/// An annulus 1 < r < 5 as one block: E3 the inner circle, E4 the outer one (both closed,
/// uniform, `n` nodes), E1 = E2 the cut along y = 0 (`m` nodes, `cut` its extra lines).
fn annulus(n: usize, m: usize, cut: &str) -> String {
    format!(
        r#"
[[vertex]]
name = "in"
at = [1, 0]
[[vertex]]
name = "out"
at = [5, 0]
[[edge]]
name = "inner"
from = "in"
to = "in"
n = {n}
curve = {{ type = "arc", center = [0, 0], radius = 1, start_deg = 0, end_deg = 360 }}
[[edge]]
name = "outer"
from = "out"
to = "out"
n = {n}
curve = {{ type = "arc", center = [0, 0], radius = 5, start_deg = 0, end_deg = 360 }}
[[edge]]
name = "cut"
from = "in"
to = "out"
n = {m}
{cut}
[[block]]
name = "ring"
E1 = "cut"
E2 = "cut"
E3 = "inner"
E4 = "outer"
"#
    )
}

/// Every ξ-line of `g` is a ray at angle 2π i / (ni − 1), every η-line a circle.
fn assert_polar(g: &Grid2<2>) {
    let (ni, nj) = (g.ni(), g.nj());
    for j in 0..nj {
        let r0 = g.point(0, j)[0].hypot(g.point(0, j)[1]);
        for i in 0..ni {
            let [x, y] = g.point(i, j);
            let want = TAU * (i % (ni - 1)) as f64 / (ni - 1) as f64;
            let d = (y.atan2(x) - want).rem_euclid(TAU);
            let d = d.min(TAU - d);
            assert!(d < RAY_TOL, "node ({i}, {j}) is {d:e} rad off its ray");
            let r = x.hypot(y);
            assert!(
                (r - r0).abs() < RAY_TOL * r0,
                "row {j}: r {r} at i = {i}, {r0} at the seam"
            );
        }
    }
}

#[test]
fn an_annulus_with_a_floating_cut_has_straight_rays_at_uniform_angles() {
    let r = generate(&annulus(33, 13, "interface = \"floating\""));
    let g = planar(&r.blocks[0].1);
    assert_eq!((g.ni(), g.nj()), (33, 13));
    let picard = r.report.blocks[0].picard.as_ref().unwrap();
    assert!(picard.converged, "{picard:?}");
    assert_polar(g);
    // The seam's two copies are bit-identical, and the rows are circles whose radii grow
    // (the discrete log-spacing of a Laplace grid between the η boundaries).
    for j in 0..g.nj() {
        assert_eq!(g.point(0, j), g.point(g.ni() - 1, j));
    }
    let radii: Vec<f64> = (0..g.nj()).map(|j| g.point(5, j)[0].hypot(g.point(5, j)[1])).collect();
    let steps: Vec<f64> = radii.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(steps.windows(2).all(|w| w[1] > w[0]), "{radii:?}");
    // The connectivity lists the seam as a 1-to-1 interface of the block with itself.
    let conn = r.connectivity.unwrap();
    assert_eq!(conn.interfaces.len(), 1);
}

#[test]
fn the_cut_s_given_nodes_do_not_matter() {
    let uniform = generate(&annulus(33, 13, "interface = \"floating\""));
    let clustered = generate(&annulus(
        33,
        13,
        "interface = \"floating\"\ndistribution = { type = \"geometric\", first = 0.01 }",
    ));
    let (a, b) = (planar(&uniform.blocks[0].1), planar(&clustered.blocks[0].1));
    assert_polar(b);
    for c in 0..2 {
        for (u, v) in a.coord(c).iter().zip(b.coord(c)) {
            assert!((u - v).abs() < RAY_TOL, "{u} vs {v}");
        }
    }
    // Through the library from a different start: the fixed-cut transfinite grid with the
    // clustered cut (its nodes are unknowns now), against the periodic start.
    let case = LoadedCase::parse(
        &annulus(
            33,
            13,
            "interface = \"floating\"\ndistribution = { type = \"geometric\", first = 0.01 }",
        ),
        Path::new("p.toml"),
    )
    .unwrap();
    let topo = case.topology.as_ref().unwrap();
    let g = &topo.groups("p").unwrap()[0];
    assert!(g.periodic);
    let b = case
        .planar_from(case.group_points(g).unwrap(), "p")
        .unwrap();
    // both to 1e-13, against the run's default 1e-10 (of the diameter 10)
    let p = PicardParams {
        tolerance: 1e-13,
        ..PicardParams::default()
    };
    let from_tf = periodic::grid_block(&b, Some(transfinite(&b)), [false; 4], ControlKind::Algebraic, &p, "p").unwrap();
    let from_ps = periodic::grid_block(&b, Some(periodic_start(&b)), [false; 4], ControlKind::Algebraic, &p, "p").unwrap();
    for c in 0..2 {
        for ((u, v), w) in from_tf.grid.coord(c).iter().zip(from_ps.grid.coord(c)).zip(a.coord(c)) {
            assert!((u - v).abs() < RAY_TOL && (v - w).abs() < 1e-9, "{u} {v} {w}");
        }
    }
}

#[test]
fn a_fixed_cut_keeps_its_nodes() {
    // Without `interface = "floating"` the cut is Dirichlet data, as before.
    let r = generate(&annulus(
        33,
        13,
        "distribution = { type = \"geometric\", first = 0.01 }",
    ));
    let g = planar(&r.blocks[0].1);
    let first = g.point(0, 1)[0] - g.point(0, 0)[0];
    assert!((first - 0.01).abs() < 1e-9, "{first}");
}
