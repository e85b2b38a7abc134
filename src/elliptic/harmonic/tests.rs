use crate::elliptic::harmonic::*;
use crate::grid::arclength::normalized_arclength;
use crate::solve::direct::DirectLu;
use std::f64::consts::PI;

/// A smoothly distorted planar grid of the unit square's topology; boundary nodes slide along
/// the straight sides x = 0, x = 1, y = 0, y = 1.
fn distorted(ni: usize, nj: usize) -> Grid2<2> {
    Grid2::from_fn(ni, nj, |i, j| {
        let (u, v) = (i as f64 / (ni - 1) as f64, j as f64 / (nj - 1) as f64);
        let u2 = u * u * (3.0 - 2.0 * u) * 0.6 + 0.4 * u; // stretched
        [
            u2 + 0.1 * (PI * u).sin() * (2.0 * PI * v).cos(),
            v + 0.08 * (PI * v).sin() * (2.0 * PI * u).sin(),
        ]
    })
}

fn dirichlet_from(g: &Grid2<2>, f: impl Fn([f64; 2]) -> f64) -> [EdgeCondition; 4] {
    Edge::ALL.map(|e| EdgeCondition::Dirichlet(g.edge(e).into_iter().map(&f).collect()))
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(u, v)| (u - v).abs())
        .fold(0.0, f64::max)
}

#[test]
fn five_point_laplacian_on_a_uniform_grid() {
    let g = Grid2::<2>::from_fn(5, 4, |i, j| [0.3 * i as f64, 0.3 * j as f64]);
    let rows = flux_rows(&g, "t").unwrap();
    let five = [0.0, -1.0, 0.0, -1.0, 4.0, -1.0, 0.0, -1.0, 0.0];
    let near = |r: &[f64; 9], e: &[f64; 9]| r.iter().zip(e).all(|(a, b)| (a - b).abs() < 1e-14);
    assert!(near(&rows[g.idx(2, 1)], &five), "{:?}", rows[g.idx(2, 1)]);
    // Half volume on E3: zero flux through the boundary side.
    let half = [0.0, 0.0, 0.0, -0.5, 2.0, -0.5, 0.0, -1.0, 0.0];
    assert!(near(&rows[g.idx(2, 0)], &half), "{:?}", rows[g.idx(2, 0)]);
    // Quarter volume at the corner (0, 0).
    let quarter = [0.0, 0.0, 0.0, 0.0, 1.0, -0.5, 0.0, -0.5, 0.0];
    assert!(near(&rows[0], &quarter), "{:?}", rows[0]);
    // Anisotropic cells: A = diag(hy/hx, hx/hy).
    let g = Grid2::<2>::from_fn(4, 4, |i, j| [2.0 * i as f64, 0.5 * j as f64]);
    let r = flux_rows(&g, "t").unwrap()[g.idx(1, 1)];
    let aniso = [0.0, -4.0, 0.0, -0.25, 8.5, -0.25, 0.0, -4.0, 0.0];
    assert!(near(&r, &aniso), "{r:?}");
}

#[test]
fn linear_functions_are_exact_on_a_distorted_planar_grid() {
    let g = distorted(17, 13);
    for f in [
        |p: [f64; 2]| p[0],
        |p: [f64; 2]| 2.0 * p[1] - 0.3 * p[0] + 1.0,
    ] {
        let s = solve_harmonic(&g, &dirichlet_from(&g, f), &mut DirectLu::new(), "t").unwrap();
        let exact: Vec<f64> = (0..g.len())
            .map(|n| f([g.coord(0)[n], g.coord(1)[n]]))
            .collect();
        assert!(max_abs_diff(&s, &exact) < 1e-12);
    }
}

#[test]
fn laplace_beltrami_on_a_tilted_plane_is_exact_for_linear_functions() {
    let g2 = distorted(15, 11);
    // Rotate the plane into R³: x' = R (x, y, 0).
    let (ca, sa, cb, sb) = (0.8f64, 0.6f64, 0.6f64.cos(), 0.6f64.sin());
    let g3 = Grid2::<3>::from_fn(15, 11, |i, j| {
        let [x, y] = g2.point(i, j);
        [ca * x - sa * cb * y, sa * x + ca * cb * y, sb * y]
    });
    let f = |p: [f64; 2]| p[0] + 0.5 * p[1];
    let conds = dirichlet_from(&g2, f);
    let s3 = solve_harmonic(&g3, &conds, &mut DirectLu::new(), "t").unwrap();
    let s2 = solve_harmonic(&g2, &conds, &mut DirectLu::new(), "t").unwrap();
    let exact: Vec<f64> = (0..g2.len())
        .map(|n| f([g2.coord(0)[n], g2.coord(1)[n]]))
        .collect();
    assert!(max_abs_diff(&s3, &exact) < 1e-12);
    assert!(max_abs_diff(&s2, &s3) < 1e-12);
}

#[test]
fn neumann_edges_keep_s_equal_to_x() {
    // Boundary nodes slide along y = 0 and y = 1, where ∂x/∂n = 0: s = x exactly.
    let g = distorted(21, 15);
    let (ni, nj) = (g.ni(), g.nj());
    let conds = [
        EdgeCondition::Dirichlet(vec![0.0; nj]),
        EdgeCondition::Dirichlet(vec![1.0; nj]),
        EdgeCondition::Neumann,
        EdgeCondition::Neumann,
    ];
    let s = solve_harmonic(&g, &conds, &mut DirectLu::new(), "t").unwrap();
    assert!(max_abs_diff(&s, g.coord(0)) < 1e-12);
    // The Neumann nodes really were unknowns: E3 values are x, not the arclength of E3.
    let mid = g.idx(ni / 2, 0);
    assert!((s[mid] - g.coord(0)[mid]).abs() < 1e-12);
}

#[test]
fn corners_between_two_neumann_edges_are_unknowns() {
    let g = distorted(9, 7);
    let conds = [
        EdgeCondition::Dirichlet(vec![0.7; 7]),
        EdgeCondition::Neumann,
        EdgeCondition::Neumann,
        EdgeCondition::Neumann,
    ];
    let u = Unknowns::new(9, 7, &conds);
    assert_eq!((u.i0, u.j0, u.nx, u.ny), (1, 0, 8, 7));
    let s = solve_harmonic(&g, &conds, &mut DirectLu::new(), "t").unwrap();
    assert!(s.iter().all(|v| (v - 0.7).abs() < 1e-13));
}

/// A cylinder patch of radius r over θ ∈ [0, 1.5], z ∈ [0, 1], with nodes at θ(ξ, η), z(ξ, η).
fn cylinder(n: usize, wobble: f64) -> Grid2<3> {
    let r = 0.8;
    Grid2::from_fn(n + 1, n + 1, |i, j| {
        let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
        let th = 1.5 * (u * u * 0.5 + 0.5 * u + wobble * (PI * u).sin() * (PI * v).sin());
        let z = v.powf(1.3) + wobble * (PI * v).sin() * (2.0 * PI * u).sin();
        [r * th.cos(), r * th.sin(), z]
    })
}

#[test]
fn laplace_beltrami_on_a_cylinder_gives_arclength_coordinates() {
    // Tensor-product nodes: the discrete solution is the normalized chord length, exactly.
    let g = cylinder(12, 0.0);
    let (ni, nj) = (g.ni(), g.nj());
    let conds = [
        EdgeCondition::Dirichlet(vec![0.0; nj]),
        EdgeCondition::Dirichlet(vec![1.0; nj]),
        EdgeCondition::Neumann,
        EdgeCondition::Neumann,
    ];
    let s = solve_harmonic(&g, &conds, &mut DirectLu::new(), "t").unwrap();
    let chord = normalized_arclength(&g.edge(Edge::E3));
    for j in 0..nj {
        for i in 0..ni {
            assert!((s[g.idx(i, j)] - chord[i]).abs() < 1e-12);
        }
    }
    // Distorted nodes: the harmonic coordinate θ/1.5 is approached at second order.
    let err = |n: usize| {
        let g = cylinder(n, 0.05);
        let conds = [
            EdgeCondition::Dirichlet(vec![0.0; n + 1]),
            EdgeCondition::Dirichlet(vec![1.0; n + 1]),
            EdgeCondition::Neumann,
            EdgeCondition::Neumann,
        ];
        let s = solve_harmonic(&g, &conds, &mut DirectLu::new(), "t").unwrap();
        (0..g.len())
            .map(|k| (s[k] - g.coord(1)[k].atan2(g.coord(0)[k]) / 1.5).abs())
            .fold(0.0, f64::max)
    };
    let (e1, e2) = (err(16), err(32));
    assert!(e2 < 1e-3 && e1 / e2 > 3.5, "errors {e1:.3e} {e2:.3e}");
}

#[test]
fn harmonic_st_on_a_rectangle_is_the_tensor_product() {
    let xs: Vec<f64> = (0..9).map(|k| 2.0 * (k as f64 / 8.0).powf(1.4)).collect();
    let ys: Vec<f64> = (0..6).map(|k| (k as f64 / 5.0).sqrt()).collect();
    let g = Grid2::<2>::from_fn(9, 6, |i, j| [xs[i], ys[j]]);
    for orth in [[false; 4], [true; 4], [false, true, true, false]] {
        let (s, t) = harmonic_st(&g, orth, &mut DirectLu::new(), "t").unwrap();
        for j in 0..6 {
            for i in 0..9 {
                assert!((s[g.idx(i, j)] - xs[i] / 2.0).abs() < 1e-12);
                assert!((t[g.idx(i, j)] - ys[j]).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn bad_input_is_an_error_naming_the_place() {
    let g = distorted(6, 5);
    let all_neumann = std::array::from_fn(|_| EdgeCondition::Neumann);
    let m = solve_harmonic(&g, &all_neumann, &mut DirectLu::new(), "blk")
        .unwrap_err()
        .to_string();
    assert!(m.starts_with("blk") && m.contains("Dirichlet"), "{m}");
    let mut conds = dirichlet_from(&g, |p| p[0]);
    conds[2] = EdgeCondition::Dirichlet(vec![0.0; 3]);
    let m = solve_harmonic(&g, &conds, &mut DirectLu::new(), "blk")
        .unwrap_err()
        .to_string();
    assert!(
        m.contains("edge E3") && m.contains("3 Dirichlet values"),
        "{m}"
    );
    let mut flat = g.clone();
    flat.set(2, 2, flat.point(3, 2));
    flat.set(2, 3, flat.point(3, 3));
    let m = solve_harmonic(
        &flat,
        &dirichlet_from(&g, |p| p[0]),
        &mut DirectLu::new(),
        "blk",
    )
    .unwrap_err()
    .to_string();
    assert!(m.contains("cell (2, 1)") && m.contains("degenerate"), "{m}");
}

#[test]
fn nodes_outside_the_unknowns_have_no_position() {
    // Found by fuzzing (issue #17): `pos` computed `ii + nx·jj` for a wrapped (outside)
    // index before testing it, which overflows in builds with overflow checks.
    let d = EdgeCondition::Dirichlet(vec![0.0; 5]);
    let u = Unknowns::new(5, 5, &[d.clone(), d.clone(), d.clone(), d]);
    assert_eq!(u.pos(0, 3), None);
    assert_eq!(u.pos(3, 0), None);
    assert_eq!(u.pos(4, 4), None);
    assert_eq!(u.pos(1, 1), Some(0));
    assert_eq!(u.pos(3, 3), Some(8));
}

#[test]
fn multigrid_and_direct_solves_agree_on_a_stretched_block_with_neumann_cuts() {
    // The t and s problems of an O-grid block (a quarter annulus, radii 1 to 21, cells
    // clustered at the inner wall): Neumann at both cuts E1, E2 (t) or at the walls E3, E4
    // (s). The multigrid's plain cycles contract slowly on the t problem; the Krylov solve
    // must still reach the direct solution.
    let (ni, nj) = (65, 49);
    let g = Grid2::<2>::from_fn(ni, nj, |i, j| {
        let (u, v) = (i as f64 / (ni - 1) as f64, j as f64 / (nj - 1) as f64);
        let r = 1.0 + 20.0 * (6.0 * v).exp_m1() / 6.0f64.exp_m1();
        let th = 0.5 * PI * u;
        [r * th.cos(), r * th.sin()]
    });
    let t_conds = [
        EdgeCondition::Neumann,
        EdgeCondition::Neumann,
        EdgeCondition::Dirichlet(vec![0.0; ni]),
        EdgeCondition::Dirichlet(vec![1.0; ni]),
    ];
    let s_conds = [
        EdgeCondition::Dirichlet(vec![0.0; nj]),
        EdgeCondition::Dirichlet(vec![1.0; nj]),
        EdgeCondition::Neumann,
        EdgeCondition::Neumann,
    ];
    use crate::solve::multigrid::{MgParams, MultigridSafe};
    for conds in [t_conds, s_conds] {
        let exact = solve_harmonic(&g, &conds, &mut DirectLu::new(), "lu").unwrap();
        let mut mg = MultigridSafe::new(MgParams::default());
        let s = solve_harmonic(&g, &conds, &mut mg, "mg").unwrap();
        let d = max_abs_diff(&s, &exact);
        assert!(d < 1e-9, "multigrid and LU differ by {d:e}");
        // t depends on the radius alone (the cuts are radial), s on the angle alone
        let (a, b) = (g.idx(3, nj / 2), g.idx(ni - 4, nj / 2));
        let (c, e) = (g.idx(ni / 2, 3), g.idx(ni / 2, nj - 4));
        assert!((s[a] - s[b]).abs() < 1e-9 || (s[c] - s[e]).abs() < 1e-9);
    }
}

/// A solver that counts its set-ups (the multigrid behind it).
struct Counting(crate::solve::multigrid::MultigridSafe, usize);

impl LinearSolver for Counting {
    fn name(&self) -> &'static str {
        "counting"
    }
    fn setup(&mut self, a: &Stencil9) -> Result<(), SolveError> {
        self.1 += 1;
        self.0.setup(a)
    }
    fn solve(
        &self,
        b: &[f64],
        x: &mut [f64],
        ctl: &SolveControl,
    ) -> Result<crate::solve::SolveInfo, SolveError> {
        self.0.solve(b, x, ctl)
    }
    fn precondition(&self, b: &[f64], x: &mut [f64]) -> Result<(), SolveError> {
        self.0.precondition(b, x)
    }
}

/// The s and t problems of `harmonic_st` share one operator where all four edges are
/// Dirichlet (one multigrid set-up, not two) and give bit for bit what two separate solves
/// give; with a Neumann edge their operators differ and each is set up.
#[test]
fn harmonic_st_sets_up_a_shared_operator_once_and_gives_the_same_bits() {
    let g = distorted(33, 33);
    let fresh = || {
        Counting(
            crate::solve::multigrid::MultigridSafe::new(Default::default()),
            0,
        )
    };
    for (orth, setups) in [([false; 4], 1), ([false, false, true, false], 2)] {
        let mut shared = fresh();
        let (s, t) = harmonic_st(&g, orth, &mut shared, "t").unwrap();
        assert_eq!(shared.1, setups, "{orth:?}");
        // the same problems solved apart, each with a solver of its own
        let [s_conds, t_conds] = st_conditions(&g, orth);
        assert_eq!(solve_harmonic(&g, &s_conds, &mut fresh(), "t").unwrap(), s);
        assert_eq!(solve_harmonic(&g, &t_conds, &mut fresh(), "t").unwrap(), t);
    }
}
