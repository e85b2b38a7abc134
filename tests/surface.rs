//! Surface grids by Section 4 (Laplace–Beltrami + inversion): independence of the
//! parametrization, agreement with Section 2, parametrized CAD-like surfaces.

use ellipgrid::grid::Edge;
use ellipgrid::linsolve::direct::DirectLu;
use ellipgrid::surfgrid::{edge_params, grid_surface};
use ellipgrid::Grid2;
use ellipgrid_geometry::{uniform, HermiteSurface, Surface, TanhBump, Vec3};

/// Deterministic pseudo-random numbers in [0, 1).
fn rng(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Grids a surface with `n × n` nodes, equidistributed (3D arclength) boundary nodes.
fn grid(s: &dyn Surface, n: usize) -> (Grid2<3>, Grid2<3>) {
    let sigma = uniform(n);
    let uv = Edge::ALL.map(|e| edge_params(s, e, &sigma));
    let r = grid_surface(s, &uv, &mut DirectLu::new(), "test").unwrap();
    (r.grid, r.initial)
}

/// A flat unit square as a Hermite net whose interior control points are displaced by up to
/// 30 % of the spacing (paper Fig. 27–28).
fn irregular_flat_net(k: usize) -> HermiteSurface {
    let mut r = rng(11);
    let h = 1.0 / (k - 1) as f64;
    let pts = (0..k * k)
        .map(|n| {
            let (i, j) = (n % k, n / k);
            let (mut x, mut y) = (i as f64 * h, j as f64 * h);
            if i > 0 && j > 0 && i + 1 < k && j + 1 < k {
                x += 0.3 * h * (2.0 * r() - 1.0);
                y += 0.3 * h * (2.0 * r() - 1.0);
            }
            Vec3::new(x, y, 0.0)
        })
        .collect();
    HermiteSurface::new(k, k, pts).unwrap()
}

#[test]
fn flat_square_with_an_irregular_net_gives_the_uniform_grid() {
    let net = irregular_flat_net(9);
    let mut errs = Vec::new();
    for n in [17, 33, 65, 129] {
        let (g, init) = grid(&net, n);
        // (max, rms) distance of the nodes from the uniform grid
        let dev = |g: &Grid2<3>| {
            let d: Vec<f64> = (0..g.len())
                .map(|p| {
                    let (i, j) = (p % n, p / n);
                    let h = 1.0 / (n - 1) as f64;
                    let e = [
                        g.coord(0)[p] - i as f64 * h,
                        g.coord(1)[p] - j as f64 * h,
                        g.coord(2)[p],
                    ];
                    e.iter().map(|v| v * v).sum::<f64>().sqrt()
                })
                .collect();
            let rms = (d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64).sqrt();
            (d.iter().cloned().fold(0.0, f64::max), rms)
        };
        let start = dev(&init);
        assert!(
            start.0 > 0.01,
            "the start grid should be visibly non-uniform: {start:?}"
        );
        errs.push((n, start, dev(&g)));
    }
    eprintln!("(n, start-grid deviation, final deviation from uniform): {errs:?}");
    // rms error ratio ≈ 4 per halving; the max norm converges at the same order, but its
    // sampled maximum approaches the sup of the interpolation error only asymptotically.
    for w in errs.windows(2) {
        let rms = w[0].2 .1 / w[1].2 .1;
        let max = w[0].2 .0 / w[1].2 .0;
        assert!(
            (3.0..5.0).contains(&rms) && max > 2.5,
            "ratios {rms} {max}: {errs:?}"
        );
    }
    let last = errs.last().unwrap().2;
    assert!(last.0 < 5e-4 && last.1 < 1e-4, "{last:?}");
}

/// The tanh bump sampled as a control net on a lattice of (x, y) positions.
fn tanh_net(k: usize, irregular: bool) -> HermiteSurface {
    let bump = TanhBump::default();
    let h = 1.0 / (k - 1) as f64;
    let pts = (0..k * k)
        .map(|n| {
            let (i, j) = (n % k, n / k);
            let (mut u, mut v) = (i as f64 * h, j as f64 * h);
            if irregular {
                // a strongly non-uniform, still monotone lattice
                u = u + 0.12
                    * (std::f64::consts::PI * u).sin()
                    * (2.0 * std::f64::consts::PI * v).cos();
                v = v - 0.1 * (std::f64::consts::PI * v).sin() * (3.0 * u).sin();
            }
            bump.point(u, v)
        })
        .collect();
    HermiteSurface::new(k, k, pts).unwrap()
}

#[test]
fn tanh_surface_grid_does_not_depend_on_the_net() {
    let (a, b) = (tanh_net(161, false), tanh_net(161, true));
    let mut diffs = Vec::new();
    for n in [65, 129, 257] {
        let (ga, ia) = grid(&a, n);
        let (gb, ib) = grid(&b, n);
        let d = |x: &Grid2<3>, y: &Grid2<3>| {
            (0..3)
                .flat_map(|c| {
                    x.coord(c)
                        .iter()
                        .zip(y.coord(c))
                        .map(|(u, v)| (u - v).abs())
                })
                .fold(0.0, f64::max)
        };
        let rms = |x: &Grid2<3>, y: &Grid2<3>| {
            let s: f64 = (0..3)
                .flat_map(|c| {
                    x.coord(c)
                        .iter()
                        .zip(y.coord(c))
                        .map(|(u, v)| (u - v).powi(2))
                })
                .sum();
            (s / x.len() as f64).sqrt()
        };
        diffs.push((n, d(&ia, &ib), d(&ga, &gb), rms(&ga, &gb)));
    }
    eprintln!("(n, start-grid difference, final difference): {diffs:?}");
    for (_, start, fin, _) in &diffs {
        assert!(
            start > &(5.0 * fin),
            "start grids should differ much more than the results"
        );
    }
    // ~4× per halving (max and rms); the steep bump is still slightly pre-asymptotic at 65.
    for w in diffs.windows(2) {
        let (max, rms) = (w[0].2 / w[1].2, w[0].3 / w[1].3);
        assert!(max > 3.2 && rms > 3.2, "ratios {max} {rms}: {diffs:?}");
    }
}
