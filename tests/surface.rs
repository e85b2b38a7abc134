//! Surface grids by Section 4 (Laplace–Beltrami + inversion): independence of the
//! parametrization, agreement with Section 2, parametrized CAD-like surfaces.

use ellipgrid::grid::Edge;
use ellipgrid::solve::direct::DirectLu;
use ellipgrid::surface::pipeline::{edge_params, grid_surface};
use ellipgrid::Grid2;
use ellipgrid_geometry::{uniform, Curve, HermiteSurface, Surface, SurfacePoint, TanhBump, Vec3};

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

/// A planar domain parametrized by the transfinite map of its four edge curves (a Surface
/// whose second derivatives are not needed by the pipeline).
struct Transfinite {
    e: [Box<dyn Curve>; 4],
}

impl Surface for Transfinite {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let [e1, e2, e3, e4] = &self.e;
        let (c00, c10, c01, c11) = (e3.point(0.0), e3.point(1.0), e4.point(0.0), e4.point(1.0));
        let x =
            e1.point(v) * (1.0 - u) + e2.point(v) * u + e3.point(u) * (1.0 - v) + e4.point(u) * v
                - (c00 * (1.0 - u) * (1.0 - v)
                    + c10 * u * (1.0 - v)
                    + c01 * (1.0 - u) * v
                    + c11 * u * v);
        let xu = e2.point(v) - e1.point(v) + e3.derivative(u) * (1.0 - v) + e4.derivative(u) * v
            - ((c10 - c00) * (1.0 - v) + (c11 - c01) * v);
        let xv = e1.derivative(v) * (1.0 - u) + e2.derivative(v) * u + e4.point(u)
            - e3.point(u)
            - ((c01 - c00) * (1.0 - u) + (c11 - c10) * u);
        let z = Vec3::zeros();
        SurfacePoint {
            x,
            xu,
            xv,
            xuu: z,
            xuv: z,
            xvv: z,
        }
    }
}

#[test]
fn section_4_and_section_2_give_the_same_planar_grid() {
    use ellipgrid::algebraic::ControlKind;
    use ellipgrid::case::LoadedCase;
    use ellipgrid::elliptic::domain::grid_block;
    use ellipgrid::elliptic::picard::PicardParams;
    use ellipgrid_geometry::{Arc, Line, Spline};
    // The curved quadrilateral of examples/curved.toml.
    let v = |x: f64, y: f64| Vec3::new(x, y, 0.0);
    let dom = Transfinite {
        e: [
            Box::new(Line::new(v(0.0, 0.0), v(-0.4, 1.5))),
            Box::new(Line::new(v(2.0, 0.0), v(2.5, 1.3))),
            Box::new(Arc::through(v(0.0, 0.0), v(1.0, 0.35), v(2.0, 0.0)).unwrap()),
            Box::new(
                Spline::new(vec![v(-0.4, 1.5), v(0.6, 1.9), v(1.6, 1.6), v(2.5, 1.3)]).unwrap(),
            ),
        ],
    };
    let case = LoadedCase::read(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/curved.toml"),
    )
    .unwrap();
    let mut diffs = Vec::new();
    for n in [17, 33, 65, 129] {
        let (g4, _) = grid(&dom, n);
        let mut c = case.clone();
        c.case.blocks[0].ni = Some(n);
        c.case.blocks[0].nj = Some(n);
        let b = c.planar_boundary(0).unwrap();
        let g2 = grid_block(
            &b,
            None,
            ControlKind::Algebraic,
            &mut DirectLu::new(),
            &PicardParams::default(),
            "s2",
        )
        .unwrap()
        .grid;
        let mut sq = 0.0;
        let mut mx = 0.0f64;
        for p in 0..g2.len() {
            let d = ((g4.coord(0)[p] - g2.coord(0)[p]).powi(2)
                + (g4.coord(1)[p] - g2.coord(1)[p]).powi(2))
            .sqrt();
            sq += d * d;
            mx = mx.max(d);
            if g2.is_boundary(p % n, p / n) {
                assert!(d < 1e-9, "boundary nodes differ by {d}");
            }
        }
        diffs.push((n, mx, (sq / g2.len() as f64).sqrt()));
    }
    eprintln!("(n, max, rms) difference Section 4 vs Section 2: {diffs:?}");
    for w in diffs.windows(2) {
        let rms = w[0].2 / w[1].2;
        assert!((3.0..5.0).contains(&rms), "rms ratio {rms}: {diffs:?}");
    }
}

#[path = "../examples/common/wing_pylon_shape.rs"]
mod wing_pylon;

#[test]
fn wing_pylon_grid_is_fold_free_and_follows_the_boundary_not_the_net() {
    use ellipgrid::case::LoadedCase;
    use ellipgrid::quality::quality_surface;
    let case = LoadedCase::read(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/wing_pylon.toml"),
    )
    .unwrap();
    let (net, uv) = case.surface_block(0).unwrap();
    let r = grid_surface(net.as_ref(), &uv, &mut DirectLu::new(), "wp").unwrap();
    let q = quality_surface(&r.grid);
    assert_eq!(q.folded_cells, 0, "{q}");
    // The same shape as a fine net with uniformly spaced control points: the grids agree to a
    // small fraction of the spacing, while the initial grids (which follow each net) do not.
    let (ni, nj) = (161, 97);
    let fine = HermiteSurface::new(
        ni,
        nj,
        wing_pylon::net(ni, nj, false)
            .into_iter()
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect(),
    )
    .unwrap();
    let sig = |e: Edge| {
        let n = if matches!(e, Edge::E3 | Edge::E4) {
            r.grid.ni()
        } else {
            r.grid.nj()
        };
        // the same boundary nodes: distribute by the case's spacings on the fine net
        let Some(ellipgrid::case::SideSpec::Edge(spec)) = case.case.blocks[0].sides()[e.index()]
        else {
            panic!("an inline edge table")
        };
        let len = ellipgrid::surface::pipeline::edge_length(&fine, e);
        spec.distribution.sample(n, len, "wp").unwrap()
    };
    let uv2 = Edge::ALL.map(|e| edge_params(&fine, e, &sig(e)));
    let r2 = grid_surface(&fine, &uv2, &mut DirectLu::new(), "wp-fine").unwrap();
    let d = |a: &Grid2<3>, b: &Grid2<3>| {
        (0..a.len())
            .map(|p| {
                (0..3)
                    .map(|c| (a.coord(c)[p] - b.coord(c)[p]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .fold(0.0, f64::max)
    };
    let (dg, di) = (d(&r.grid, &r2.grid), d(&r.initial, &r2.initial));
    eprintln!(
        "wing-pylon: final grids differ by {dg:.3e}, initial grids by {di:.3e}, min spacing {:.3e}",
        q.min_spacing
    );
    assert!(di > 10.0 * dg, "initial {di} final {dg}");
    assert!(
        dg < 0.25 * q.min_spacing.max(1e-3),
        "final grids differ by {dg}"
    );
}

#[test]
fn tanh_surface_orthogonal_at_chosen_edges_in_the_tangent_plane() {
    use ellipgrid::quality::quality_surface;
    use ellipgrid::surface::pipeline::grid_surface_orthogonal;
    let bump = TanhBump::default();
    let n = 65;
    // unequal opposite distributions, so that the plain grid leaves the edges at an angle
    let clustered = ellipgrid_geometry::vinokur(n, Some(0.004), None).unwrap();
    let sigma = |e: Edge| match e {
        Edge::E2 | Edge::E4 => clustered.clone(),
        _ => uniform(n),
    };
    let uv = Edge::ALL.map(|e| edge_params(&bump, e, &sigma(e)));
    // deviation from 90° of the first grid line, measured in 3D (the tangent plane to first
    // order), over the middle half of an edge
    let dev = |g: &Grid2<3>, e: Edge| {
        let (ni, nj) = (g.ni(), g.nj());
        let m = if e.runs_along_i() { ni } else { nj };
        (m / 4..3 * m / 4)
            .map(|k| {
                let (wall, prev, next, inner) = match e {
                    Edge::E1 => (
                        g.point(0, k),
                        g.point(0, k - 1),
                        g.point(0, k + 1),
                        g.point(1, k),
                    ),
                    Edge::E2 => (
                        g.point(ni - 1, k),
                        g.point(ni - 1, k - 1),
                        g.point(ni - 1, k + 1),
                        g.point(ni - 2, k),
                    ),
                    Edge::E3 => (
                        g.point(k, 0),
                        g.point(k - 1, 0),
                        g.point(k + 1, 0),
                        g.point(k, 1),
                    ),
                    Edge::E4 => (
                        g.point(k, nj - 1),
                        g.point(k - 1, nj - 1),
                        g.point(k + 1, nj - 1),
                        g.point(k, nj - 2),
                    ),
                };
                let t: Vec<f64> = (0..3).map(|c| next[c] - prev[c]).collect();
                let l: Vec<f64> = (0..3).map(|c| inner[c] - wall[c]).collect();
                let dot: f64 = t.iter().zip(&l).map(|(a, b)| a * b).sum();
                let nt = t.iter().map(|a| a * a).sum::<f64>().sqrt();
                let nl = l.iter().map(|a| a * a).sum::<f64>().sqrt();
                (90.0 - (dot / (nt * nl)).acos().to_degrees()).abs()
            })
            .fold(0.0, f64::max)
    };
    let plain = grid_surface_orthogonal(&bump, &uv, [false; 4], &mut DirectLu::new(), "t").unwrap();
    let orth = grid_surface_orthogonal(
        &bump,
        &uv,
        [true, false, true, false],
        &mut DirectLu::new(),
        "t",
    )
    .unwrap();
    assert_eq!(quality_surface(&orth.grid).folded_cells, 0);
    let report: Vec<(Edge, f64, f64)> = Edge::ALL
        .iter()
        .map(|&e| (e, dev(&plain.grid, e), dev(&orth.grid, e)))
        .collect();
    eprintln!("(edge, plain, orthogonal at E1 and E3) max deviation over the middle half, degrees: {report:?}");
    for (e, p, o) in &report {
        if matches!(e, Edge::E1 | Edge::E3) {
            assert!(*o < 0.5 * p && *o < 2.0, "{e}: {o}° against {p}° plain");
        }
    }
}

#[test]
fn surface_case_with_an_inline_net_and_projected_edge_nodes() {
    use std::process::Command;
    let d = tempfile::tempdir().unwrap();
    // A 3 × 3 net of the saddle z = x y over [0, 1]² (bilinear nets are reproduced exactly).
    let pts: Vec<String> = (0..9)
        .map(|k| {
            let (x, y) = ((k % 3) as f64 / 2.0, (k / 3) as f64 / 2.0);
            format!("[{x}, {y}, {}]", x * y)
        })
        .collect();
    // E3 given as nodes on the surface's edge v = 0 (z = 0), projected onto it.
    let e3: Vec<String> = (0..9)
        .map(|k| format!("[{}, 0.0, 0.0]", (k as f64 / 8.0).powi(2)))
        .collect();
    let case = format!(
        "[[block]]\nkind = \"surface\"\nni = 9\nnj = 7\n\
         surface = {{ type = \"hermite_net\", ni = 3, nj = 3, points = [{}] }}\n\
         [block.E1]\n[block.E2]\n[block.E3]\ncurve = {{ type = \"nodes\", points = [{}] }}\n[block.E4]\n",
        pts.join(", "),
        e3.join(", ")
    );
    std::fs::write(d.path().join("s.toml"), &case).unwrap();
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_ellipgrid"))
            .args(args)
            .current_dir(d.path())
            .output()
            .unwrap()
    };
    let o = run(&["run", "s.toml", "-o", "s.x", "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let f = ellipgrid::io::plot3d::read_plot3d(&d.path().join("s.x")).unwrap();
    let ellipgrid::io::Block::Surface(g) = &f.blocks[0] else {
        panic!()
    };
    for i in 0..9 {
        let p = g.point(i, 0);
        assert!(
            (p[0] - (i as f64 / 8.0).powi(2)).abs() < 1e-12,
            "E3 node {i}: {p:?}"
        );
    }
    for k in 0..g.len() {
        let (x, y, z) = (g.coord(0)[k], g.coord(1)[k], g.coord(2)[k]);
        assert!((z - x * y).abs() < 1e-12, "node off the saddle");
    }
    // A node off the edge is refused, naming the edge.
    std::fs::write(
        d.path().join("bad.toml"),
        case.replace("[0.015625, 0.0, 0.0]", "[0.015625, 0.2, 0.0]"),
    )
    .unwrap();
    let o = run(&["run", "bad.toml", "-o", "b.x"]);
    assert_eq!(o.status.code(), Some(2));
    let msg = String::from_utf8_lossy(&o.stderr);
    assert!(
        msg.contains("edge E3") && msg.contains("away from the surface"),
        "{msg}"
    );
}
