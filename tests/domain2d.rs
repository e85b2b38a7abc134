//! The Section 2 method on planar domains, through the library: exact discrete solutions,
//! independence of the start grid, second-order convergence, boundary layers.

mod common;

use ellipgrid::algebraic::transform::transfinite;
use ellipgrid::algebraic::ControlKind;
use ellipgrid::case::LoadedCase;
use ellipgrid::elliptic::domain::grid_block;
use ellipgrid::elliptic::picard::PicardParams;
use ellipgrid::grid::boundary::Boundary2;
use ellipgrid::quality::quality2d;
use ellipgrid::solve::direct::DirectLu;
use ellipgrid::{Edge, Grid2};
use std::path::Path;

fn load(path: &str) -> LoadedCase {
    LoadedCase::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap()
}

fn with_size(mut case: LoadedCase, ni: usize, nj: usize) -> LoadedCase {
    case.case.blocks[0].ni = Some(ni);
    case.case.blocks[0].nj = Some(nj);
    case
}

fn solve(b: &Boundary2<2>, start: Option<Grid2<2>>, kind: ControlKind) -> Grid2<2> {
    let r = grid_block(
        b,
        start,
        kind,
        &mut DirectLu::new(),
        &PicardParams::default(),
        "t",
    )
    .unwrap();
    assert!(
        r.picard.converged,
        "Picard did not converge: {:?}",
        r.picard.history.last()
    );
    r.grid
}

fn max_diff(a: &Grid2<2>, b: &Grid2<2>) -> f64 {
    common::max_diff(a.coords(), b.coords())
}

#[test]
fn rectangle_with_equal_opposite_distributions_is_reproduced_exactly() {
    // Stretched, different distributions in i and j, equal on opposite edges: the
    // tensor-product grid is an exact discrete solution (Thomas–Middlecoff, [25]–[28]).
    let xs: Vec<f64> = (0..41)
        .map(|k| 3.0 * (1.0 - (k as f64 / 40.0 * 1.3).cos()) / (1.0 - 1.3f64.cos()))
        .collect();
    let ys: Vec<f64> = (0..23)
        .map(|k| 0.5 * ((k as f64 / 22.0) * 3.0).exp_m1() / 3.0f64.exp_m1())
        .collect();
    let exact = Grid2::<2>::from_fn(41, 23, |i, j| [xs[i], ys[j]]);
    let b = Boundary2::from_grid(&exact, "rect").unwrap();
    let g = solve(&b, None, ControlKind::Algebraic);
    assert!(max_diff(&g, &exact) < 1e-12, "{}", max_diff(&g, &exact));
}

#[test]
fn final_grid_does_not_depend_on_a_folded_start_grid() {
    let case = load("examples/curved.toml");
    let b = case.planar_boundary(0).unwrap();
    let tfi = transfinite(&b);
    // A severely folded start: interior nodes scrambled pseudo-randomly over the domain.
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let folded = Grid2::<2>::from_fn(b.ni(), b.nj(), |i, j| {
        let p = tfi.point(i, j);
        if i == 0 || j == 0 || i + 1 == b.ni() || j + 1 == b.nj() {
            p
        } else {
            [-0.5 + 3.0 * rnd(), 2.0 * rnd()]
        }
    });
    let q = quality2d(&folded);
    assert!(
        q.folded_cells > b.ni() * b.nj() / 4,
        "start grid not folded enough: {}",
        q.folded_cells
    );
    let g1 = solve(&b, Some(folded), ControlKind::Algebraic);
    let g2 = solve(&b, None, ControlKind::Algebraic);
    let d = max_diff(&g1, &g2) / g2.diameter();
    assert!(d < 1e-9, "start-grid dependence {d:.3e}");
    assert_eq!(quality2d(&g1).folded_cells, 0);
}

#[test]
fn curved_domain_converges_at_second_order() {
    // Successive grids N, 2N, 4N, 8N sampled at common nodes: rms differences shrink ~4×.
    let sizes = [(17, 13), (33, 25), (65, 49), (129, 97)];
    let grids: Vec<Grid2<2>> = sizes
        .iter()
        .map(|&(ni, nj)| {
            let case = with_size(load("examples/curved.toml"), ni, nj);
            solve(
                &case.planar_boundary(0).unwrap(),
                None,
                ControlKind::Algebraic,
            )
        })
        .collect();
    let coarse = &grids[0];
    let rms_diff = |a: &Grid2<2>, b: &Grid2<2>| {
        // sample both at the nodes of the coarsest grid
        let (ra, rb) = (
            (a.ni() - 1) / (coarse.ni() - 1),
            (b.ni() - 1) / (coarse.ni() - 1),
        );
        let mut s = 0.0;
        for j in 0..coarse.nj() {
            for i in 0..coarse.ni() {
                let (p, q) = (a.point(i * ra, j * ra), b.point(i * rb, j * rb));
                s += (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
            }
        }
        (s / coarse.len() as f64).sqrt()
    };
    let d: Vec<f64> = grids.windows(2).map(|w| rms_diff(&w[0], &w[1])).collect();
    let ratios: Vec<f64> = d.windows(2).map(|w| w[0] / w[1]).collect();
    eprintln!("rms differences {d:?}, ratios {ratios:?}");
    for r in &ratios {
        assert!((3.2..5.0).contains(r), "ratio {r} not ≈ 4: {ratios:?}");
    }
}

/// First-cell heights |x(i,1) − x(i,0)| along E3.
fn first_heights(g: &Grid2<2>) -> Vec<f64> {
    (0..g.ni())
        .map(|i| {
            let (a, b) = (g.point(i, 0), g.point(i, 1));
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
        })
        .collect()
}

#[test]
fn boundary_layer_survives_and_a_laplace_grid_loses_it() {
    let case = load("examples/boundary_layer.toml");
    let b = case.planar_boundary(0).unwrap();
    let e1 = b.edge(Edge::E1);
    let h0 = ((e1[1][0] - e1[0][0]).powi(2) + (e1[1][1] - e1[0][1]).powi(2)).sqrt();
    assert!((h0 - 1e-4).abs() < 1e-12, "wall spacing on E1 is {h0:e}");
    let g = solve(&b, None, ControlKind::Algebraic);
    let h = first_heights(&g);
    let worst = h.iter().map(|v| (v / 1e-4 - 1.0).abs()).fold(0.0, f64::max);
    assert!(
        worst < 0.2,
        "first-cell height off by {:.1} % somewhere",
        100.0 * worst
    );
    assert_eq!(quality2d(&g).folded_cells, 0);
    let lap = solve(&b, None, ControlKind::Laplace);
    let hl = first_heights(&lap);
    let mid = hl[hl.len() / 2];
    assert!(
        mid > 10.0 * 1e-4,
        "the Laplace grid kept the layer: height {mid:.2e}"
    );
}
