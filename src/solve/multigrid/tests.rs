//! Manufactured problems with known discrete solutions.

use crate::solve::direct::DirectLu;
use crate::solve::multigrid::*;

/// Nine-point operator with constant stencil `m` (clipped at the boundary).
fn constant(nx: usize, ny: usize, m: [f64; 9]) -> Stencil9 {
    let mut a = Stencil9::zeros(nx, ny);
    for row in a.coefs_mut() {
        *row = m;
    }
    a.clip_to_grid();
    a
}

fn poisson5(nx: usize, ny: usize) -> Stencil9 {
    constant(nx, ny, [0.0, -1.0, 0.0, -1.0, 4.0, -1.0, 0.0, -1.0, 0.0])
}

fn poisson9(nx: usize, ny: usize) -> Stencil9 {
    constant(
        nx,
        ny,
        [-1.0, -4.0, -1.0, -4.0, 20.0, -4.0, -1.0, -4.0, -1.0],
    )
}

/// `−ex u_xx − ey u_yy`.
fn aniso(nx: usize, ny: usize, ex: f64, ey: f64) -> Stencil9 {
    constant(
        nx,
        ny,
        [0.0, -ey, 0.0, -ex, 2.0 * (ex + ey), -ex, 0.0, -ey, 0.0],
    )
}

/// `n + 1` cells over `[0, len]` growing geometrically from `d1`.
fn geometric(n: usize, d1: f64, len: f64) -> Vec<f64> {
    let cells = n + 1;
    let total = |r: f64| d1 * (r.powi(cells as i32) - 1.0) / (r - 1.0);
    let (mut lo, mut hi) = (1.0 + 1e-12, 2.0);
    while total(hi) < len {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if total(mid) < len {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let r = 0.5 * (lo + hi);
    let mut x = vec![0.0];
    let mut d = d1;
    for _ in 0..cells {
        x.push(x.last().unwrap() + d);
        d *= r;
    }
    x
}

/// Vertex-centred finite-volume Laplacian on the tensor grid `xs × ys` (boundary nodes
/// included), e.g. a boundary-layer grid.
fn tensor_laplacian(xs: &[f64], ys: &[f64]) -> Stencil9 {
    let (nx, ny) = (xs.len() - 2, ys.len() - 2);
    let mut a = Stencil9::zeros(nx, ny);
    for j in 0..ny {
        for i in 0..nx {
            let (ii, jj) = (i + 1, j + 1);
            let (hw, he) = (xs[ii] - xs[ii - 1], xs[ii + 1] - xs[ii]);
            let (hs, hn) = (ys[jj] - ys[jj - 1], ys[jj + 1] - ys[jj]);
            let (dx, dy) = (0.5 * (hw + he), 0.5 * (hs + hn));
            let m = &mut a.coefs_mut()[i + nx * j];
            *m = [0.0; 9];
            m[3] = -dy / hw;
            m[5] = -dy / he;
            m[1] = -dx / hs;
            m[7] = -dx / hn;
            m[4] = -(m[1] + m[3] + m[5] + m[7]);
        }
    }
    a.clip_to_grid();
    a
}

/// Boundary-layer grid: x uniform on `[0, lx]`, y clustered at y = 0 with first spacing `d1`
/// on `[0, 1]`; `transpose` swaps the roles of x and y.
fn boundary_layer(nx: usize, ny: usize, d1: f64, lx: f64, transpose: bool) -> Stencil9 {
    if transpose {
        let xs = geometric(nx, d1, 1.0);
        let ys: Vec<f64> = (0..ny + 2)
            .map(|j| lx * j as f64 / (ny + 1) as f64)
            .collect();
        tensor_laplacian(&xs, &ys)
    } else {
        let xs: Vec<f64> = (0..nx + 2)
            .map(|i| lx * i as f64 / (nx + 1) as f64)
            .collect();
        let ys = geometric(ny, d1, 1.0);
        tensor_laplacian(&xs, &ys)
    }
}

/// Central differences of `−(P u_xx + 2Q u_xy + R u_yy + S u_x + T u_y)` (unit spacing) with
/// smoothly varying coefficients, `|Q| ≤ q_ratio sqrt(PR)`, `R ≈ r_scale P`.
fn mixed(nx: usize, ny: usize, q_ratio: f64, r_scale: f64, conv: f64) -> Stencil9 {
    let mut a = Stencil9::zeros(nx, ny);
    for j in 0..ny {
        for i in 0..nx {
            let (x, y) = (i as f64 / nx as f64, j as f64 / ny as f64);
            let p = 1.0 + 0.5 * (3.0 * x + 1.0).sin() * (2.0 * y).cos();
            let r = r_scale * (1.0 + 0.5 * (2.0 * x - 3.0 * y).cos());
            let q = q_ratio * (p * r).sqrt() * (4.0 * x + 2.0 * y).sin();
            let s = conv * (3.0 * y + 0.5).cos();
            let t = conv * r_scale.sqrt() * (2.0 * x - 1.0).sin();
            a.coefs_mut()[i + nx * j] = [
                -0.5 * q,
                -(r - 0.5 * t),
                0.5 * q,
                -(p - 0.5 * s),
                2.0 * (p + r),
                -(p + 0.5 * s),
                0.5 * q,
                -(r + 0.5 * t),
                -0.5 * q,
            ];
        }
    }
    a.clip_to_grid();
    a
}

/// A deterministic vector with all frequencies.
fn manufactured(n: usize) -> Vec<f64> {
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..n)
        .map(|p| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) + (p as f64 * 0.01).sin()
        })
        .collect()
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    norm(&d) / norm(b)
}

/// Mean reduction factor per iteration.
fn mean_factor(info: &SolveInfo) -> f64 {
    info.residual_history
        .last()
        .map_or(0.0, |r| r.powf(1.0 / info.residual_history.len() as f64))
}

/// Solves `A x = A x*` from zero to 1e-10 and checks the factor, x* and the direct solution.
fn check(name: &str, a: &Stencil9, params: MgParams, max_factor: f64) -> SolveInfo {
    let n = a.len();
    let xe = manufactured(n);
    let mut b = vec![0.0; n];
    a.apply(&xe, &mut b);
    let mut mg = Multigrid::new(params);
    mg.setup(a).unwrap();
    let mut x = vec![0.0; n];
    let ctl = SolveControl {
        rel_tol: 1e-10,
        max_iter: 60,
    };
    let info = mg.solve(&b, &mut x, &ctl).unwrap();
    let f = mean_factor(&info);
    let mut xd = vec![0.0; n];
    let mut lu = DirectLu::new();
    lu.setup(a).unwrap();
    lu.solve(&b, &mut xd, &ctl).unwrap();
    // the 1e-10 residual bounds the error by cond(A)·1e-10; a few more cycles take the
    // residual to round-off, where the solution must match x* and the direct solution
    let e10 = rel_diff(&x, &xe);
    let mut xt = x.clone();
    let more = SolveControl {
        rel_tol: 1e-4,
        max_iter: 8,
    };
    mg.solve(&b, &mut xt, &more).unwrap();
    let (ex, ed) = (rel_diff(&xt, &xe), rel_diff(&xt, &xd));
    eprintln!(
        "{name:<30} {:>4}x{:<4} iters {:>2} factor {f:.4} err(x*) {e10:.1e} -> {ex:.1e} err(LU) {ed:.1e} levels {}",
        a.nx(),
        a.ny(),
        info.iterations,
        mg.info().unwrap().levels.len()
    );
    assert!(
        info.converged,
        "{name}: not converged: {:?}",
        info.residual_history
    );
    assert!(*info.residual_history.last().unwrap() <= 1e-10);
    // the reported residual is the true one
    let mut r = vec![0.0; n];
    a.residual(&b, &x, &mut r);
    let mut r0 = b.clone();
    a.residual(&b, &vec![0.0; n], &mut r0);
    assert!(norm(&r) / norm(&r0) <= 1.0001e-10);
    assert!(f <= max_factor, "{name}: factor {f} > {max_factor}");
    assert!(ex <= 1e-9, "{name}: differs from x* by {ex}");
    assert!(ed <= 1e-9, "{name}: differs from LU by {ed}");
    info
}

fn v11() -> MgParams {
    MgParams::default()
}

#[test]
fn poisson5_63() {
    check("poisson5", &poisson5(63, 63), v11(), 0.15);
}

#[test]
fn poisson9_63() {
    check("poisson9", &poisson9(63, 63), v11(), 0.15);
}

#[test]
fn poisson_sizes_not_power_of_two() {
    for (nx, ny) in [
        (50, 37),
        (100, 23),
        (23, 100),
        (64, 64),
        (2, 77),
        (5, 3),
        (1, 300),
    ] {
        check("poisson5 odd sizes", &poisson5(nx, ny), v11(), 0.15);
        check("poisson9 odd sizes", &poisson9(nx, ny), v11(), 0.15);
    }
}

#[test]
fn anisotropic_x_and_y() {
    check("aniso eps_x=1e-4", &aniso(63, 63, 1e-4, 1.0), v11(), 0.15);
    check("aniso eps_y=1e-4", &aniso(63, 63, 1.0, 1e-4), v11(), 0.15);
    check(
        "aniso eps_x=1e-4 50x37",
        &aniso(50, 37, 1e-4, 1.0),
        v11(),
        0.15,
    );
}

#[test]
fn boundary_layer_grids() {
    // first spacing 1e-5 next to the wall, aspect ratio hx/hy ≈ 1e4 at the wall
    let a = boundary_layer(63, 63, 1e-5, 10.0, false);
    let ar = aspect_ratio(&a);
    assert!(ar >= 1e4, "aspect ratio {ar}");
    check("boundary layer (y)", &a, v11(), 0.15);
    check(
        "boundary layer (x)",
        &boundary_layer(63, 63, 1e-5, 10.0, true),
        v11(),
        0.15,
    );
    check(
        "boundary layer 50x37",
        &boundary_layer(50, 37, 1e-5, 10.0, false),
        v11(),
        0.15,
    );
}

/// Largest ratio of the x and y couplings (either way) over the grid.
fn aspect_ratio(a: &Stencil9) -> f64 {
    let mut ar: f64 = 1.0;
    for j in 1..a.ny() - 1 {
        for i in 1..a.nx() - 1 {
            let m = a.row(i, j);
            let r = (m[3] / m[1]).abs();
            ar = ar.max(r).max(1.0 / r);
        }
    }
    ar.sqrt()
}

#[test]
fn nonsymmetric_mixed_derivative() {
    check("mixed q=0.5", &mixed(63, 63, 0.5, 1.0, 0.8), v11(), 0.15);
    check(
        "mixed q=0.8 R=10P",
        &mixed(63, 63, 0.8, 10.0, 0.8),
        v11(),
        0.15,
    );
    check("mixed 50x37", &mixed(50, 37, 0.5, 1.0, 0.8), v11(), 0.15);
}

#[test]
fn cycles_and_acceleration() {
    let problems = [
        ("poisson9", poisson9(50, 37)),
        ("boundary layer", boundary_layer(50, 37, 1e-5, 10.0, false)),
        ("mixed", mixed(50, 37, 0.5, 1.0, 0.8)),
    ];
    for (name, a) in &problems {
        for cycle in [Cycle::V, Cycle::F, Cycle::W] {
            for accelerate in [false, true] {
                let params = MgParams {
                    cycle,
                    accelerate,
                    ..MgParams::default()
                };
                // a Bi-CGSTAB iteration costs two cycles: bound its factor by 0.15²
                let bound = if accelerate { 0.0225 } else { 0.15 };
                let label = format!("{name} {cycle:?} acc={accelerate}");
                check(&label, a, params, bound);
            }
        }
    }
}

#[test]
fn every_smoother_and_cycle() {
    let a = poisson5(31, 31);
    for smoother in [
        Smoother::AlternatingZebraLine,
        Smoother::ZebraLineX,
        Smoother::ZebraLineY,
        Smoother::ZebraLineXY,
    ] {
        for cycle in [Cycle::V, Cycle::F, Cycle::W] {
            for restriction in [Restriction::Adjoint, Restriction::Transpose] {
                let params = MgParams {
                    smoother,
                    cycle,
                    restriction,
                    ..MgParams::default()
                };
                let bound = if smoother == Smoother::AlternatingZebraLine {
                    0.15
                } else {
                    0.5
                };
                check(
                    &format!("{smoother:?} {cycle:?} {restriction:?}"),
                    &a,
                    params,
                    bound,
                );
            }
        }
    }
    // one-direction line smoothers suffice for anisotropy along their lines
    let px = MgParams {
        smoother: Smoother::ZebraLineX,
        ..MgParams::default()
    };
    check("ZebraLineX eps_y=1e-4", &aniso(63, 63, 1.0, 1e-4), px, 0.15);
}

#[test]
fn setup_refresh_matches_fresh_solver() {
    let (nx, ny) = (50, 37);
    let a1 = poisson9(nx, ny);
    let a2 = mixed(nx, ny, 0.5, 1.0, 0.8);
    let xe = manufactured(nx * ny);
    let mut b = vec![0.0; nx * ny];
    a2.apply(&xe, &mut b);
    let ctl = SolveControl {
        rel_tol: 1e-10,
        max_iter: 50,
    };
    let mut reused = Multigrid::new(MgParams::default());
    reused.setup(&a1).unwrap();
    let mut x1 = vec![0.0; nx * ny];
    reused.solve(&b, &mut x1, &ctl).unwrap();
    reused.setup(&a2).unwrap();
    let mut fresh = Multigrid::new(MgParams::default());
    fresh.setup(&a2).unwrap();
    let (mut xr, mut xf) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
    let ir = reused.solve(&b, &mut xr, &ctl).unwrap();
    let if_ = fresh.solve(&b, &mut xf, &ctl).unwrap();
    assert_eq!(ir, if_);
    assert_eq!(xr, xf);
    assert!(rel_diff(&xr, &xe) < 1e-8);
    // new cycle parameters take effect at the next setup, without a rebuild
    reused.set_params(MgParams {
        cycle: Cycle::F,
        accelerate: true,
        ..MgParams::default()
    });
    reused.setup(&a2).unwrap();
    let mut fresh = Multigrid::new(reused.params().clone());
    fresh.setup(&a2).unwrap();
    let (mut xr, mut xf) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
    let ir = reused.solve(&b, &mut xr, &ctl).unwrap();
    assert_eq!(ir, fresh.solve(&b, &mut xf, &ctl).unwrap());
    assert_eq!(xr, xf);
    // a different size rebuilds the hierarchy
    let a3 = poisson5(31, 20);
    reused.setup(&a3).unwrap();
    assert_eq!(reused.info().unwrap().levels[0], (31, 20));
    let mut x3 = vec![0.0; 31 * 20];
    let b3 = vec![1.0; 31 * 20];
    assert!(reused.solve(&b3, &mut x3, &ctl).unwrap().converged);
    // the cycle workspace was refitted, not allocated beside the old one
    {
        let kept = reused.pool.0.lock().unwrap();
        assert_eq!(kept.len(), 1);
        assert!(kept[0].fits(reused.hierarchy().unwrap()));
        // (its fine vectors hold the larger size's capacity)
        assert!(kept[0].lv[0].x.capacity() >= nx * ny);
    }
    // in the larger hierarchy's and workspace's buffers (recycled, with their old values): the
    // fresh solver's solution bit for bit, and so after growing back
    let mut fresh3 = Multigrid::new(reused.params().clone());
    fresh3.setup(&a3).unwrap();
    let mut xf3 = vec![0.0; 31 * 20];
    fresh3.solve(&b3, &mut xf3, &ctl).unwrap();
    assert_eq!(x3, xf3);
    reused.setup(&a2).unwrap();
    let (mut xr, mut xf) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
    let ir = reused.solve(&b, &mut xr, &ctl).unwrap();
    assert_eq!(ir, fresh.solve(&b, &mut xf, &ctl).unwrap());
    assert_eq!(xr, xf);
}

/// `update` (fine level refreshed, coarse levels of the previous operator kept) solves the
/// new system exactly as well: the cycle still converges fast, to the new solution. The
/// operator changes by 2 % (more than a Picard step near convergence changes it).
#[test]
fn update_keeps_coarse_levels_and_solves_the_new_operator() {
    let (nx, ny) = (50, 37);
    let a1 = mixed(nx, ny, 0.5, 1.0, 0.3);
    let mut a2 = a1.clone();
    for (p, row) in a2.coefs_mut().iter_mut().enumerate() {
        let s = 1.0 + 0.02 * (p as f64 * 0.37).sin();
        for v in row.iter_mut() {
            *v *= s;
        }
    }
    let xe = manufactured(nx * ny);
    let mut b = vec![0.0; nx * ny];
    a2.apply(&xe, &mut b);
    let ctl = SolveControl {
        rel_tol: 1e-10,
        max_iter: 50,
    };
    let mut mg = Multigrid::new(MgParams::default());
    mg.setup(&a1).unwrap();
    mg.update(&a2).unwrap();
    let mut x = vec![0.0; nx * ny];
    let info = mg.solve(&b, &mut x, &ctl).unwrap();
    assert!(info.converged, "{info:?}");
    assert!(mean_factor(&info) < 0.15, "{info:?}");
    assert!(rel_diff(&x, &xe) < 1e-8);
    // the Krylov fallback works on the updated operator too
    x.fill(0.0);
    let info = mg.bicgstab(&b, &mut x, &ctl).unwrap();
    assert!(info.converged && rel_diff(&x, &xe) < 1e-8, "{info:?}");
    // without a hierarchy of that size, update is a full setup
    let a3 = poisson5(31, 20);
    mg.update(&a3).unwrap();
    assert_eq!(mg.info().unwrap().levels[0], (31, 20));
}

#[test]
fn parallel_right_hand_sides() {
    use rayon::prelude::*;
    let a = boundary_layer(63, 40, 1e-5, 10.0, false);
    let n = a.len();
    let mut mg = Multigrid::new(MgParams::default());
    mg.setup(&a).unwrap();
    let ctl = SolveControl::default();
    let rhs: Vec<Vec<f64>> = (0..6)
        .map(|k| manufactured(n).iter().map(|v| v * (k + 1) as f64).collect())
        .collect();
    let par: Vec<(Vec<f64>, SolveInfo)> = rhs
        .par_iter()
        .map(|b| {
            let mut x = vec![0.0; n];
            let info = mg.solve(b, &mut x, &ctl).unwrap();
            (x, info)
        })
        .collect();
    for (b, (x, info)) in rhs.iter().zip(&par) {
        let mut xs = vec![0.0; n];
        let is = mg.solve(b, &mut xs, &ctl).unwrap();
        assert!(is.converged);
        assert_eq!(&is, info);
        assert_eq!(&xs, x);
    }
}

#[test]
fn direct_on_tiny_grids_and_errors() {
    // one level: the banded LU solves in one cycle
    let a = mixed(7, 5, 0.5, 1.0, 0.8);
    let mut mg = Multigrid::new(MgParams::default());
    let mut x = vec![0.0; a.len()];
    let b = manufactured(a.len());
    assert_eq!(
        mg.solve(&b, &mut x, &SolveControl::default()),
        Err(SolveError::NotSetUp)
    );
    mg.setup(&a).unwrap();
    assert_eq!(mg.info().unwrap().levels.len(), 1);
    let info = mg.solve(&b, &mut x, &SolveControl::default()).unwrap();
    assert_eq!(info.iterations, 1);
    let mut r = vec![0.0; a.len()];
    a.residual(&b, &x, &mut r);
    assert!(norm(&r) < 1e-12 * norm(&b));
    // long thin grid: coarsening stops at one line, banded LU of 500 unknowns
    check("poisson5 1000x3", &poisson5(1000, 3), v11(), 0.15);
    // a zero diagonal is reported at setup
    let mut z = poisson5(9, 9);
    z.coefs_mut()[10][4] = 0.0;
    assert!(matches!(mg.setup(&z), Err(SolveError::Singular(_))));
    // the zero right-hand side converges at once
    mg.setup(&a).unwrap();
    let mut x0 = vec![0.0; a.len()];
    let info = mg
        .solve(&vec![0.0; a.len()], &mut x0, &SolveControl::default())
        .unwrap();
    assert!(info.converged && info.iterations == 0);
}

#[test]
fn not_converged_and_diverged() {
    let a = poisson5(63, 63);
    let n = a.len();
    let mut mg = Multigrid::new(MgParams::default());
    mg.setup(&a).unwrap();
    let b = manufactured(n);
    let mut x = vec![0.0; n];
    let ctl = SolveControl {
        rel_tol: 1e-10,
        max_iter: 2,
    };
    let info = mg.solve(&b, &mut x, &ctl).unwrap();
    assert!(!info.converged);
    assert_eq!(info.iterations, 2);
    assert_eq!(info.residual_history.len(), 2);
    // strongly indefinite Helmholtz operator: plain cycles blow up
    let h = constant(
        63,
        63,
        [0.0, -1.0, 0.0, -1.0, 4.0 - 6.0, -1.0, 0.0, -1.0, 0.0],
    );
    let mut mg = Multigrid::new(MgParams::default());
    mg.setup(&h).unwrap();
    let mut x = vec![0.0; n];
    let res = mg.solve(&b, &mut x, &SolveControl::default());
    assert!(matches!(res, Err(SolveError::Diverged(_))), "{res:?}");
}

/// The public Bi-CGSTAB with a preconditioner set up for a nearby operator (as when the
/// hierarchy of the previous Picard step is kept), and with an unclipped operator.
#[test]
fn bicgstab_with_lagged_preconditioner() {
    let (nx, ny) = (50, 37);
    let a_old = mixed(nx, ny, 0.5, 1.0, 0.8);
    let a_new = mixed(nx, ny, 0.6, 1.3, 0.5);
    let mut mg = Multigrid::new(MgParams::default());
    mg.setup(&a_old).unwrap();
    let xe = manufactured(nx * ny);
    let mut b = vec![0.0; nx * ny];
    a_new.apply(&xe, &mut b);
    let mut x = vec![0.0; nx * ny];
    let ctl = SolveControl {
        rel_tol: 1e-10,
        max_iter: 40,
    };
    let info = bicgstab(&a_new, &b, &mut x, &mg, &ctl).unwrap();
    eprintln!(
        "lagged: {} iterations, factor {:.3}",
        info.iterations,
        mean_factor(&info)
    );
    assert!(info.converged);
    assert!(mean_factor(&info) < 0.15);
    assert!(rel_diff(&x, &xe) < 1e-8);
    // coefficients pointing outside the grid are ignored, as in `Stencil9::apply`
    let mut dirty = a_new.clone();
    for j in 0..ny {
        dirty.coefs_mut()[nx * j][3] = 7.0;
    }
    let mut x2 = vec![0.0; nx * ny];
    let info2 = bicgstab(&dirty, &b, &mut x2, &mg, &ctl).unwrap();
    assert_eq!(info, info2);
    assert_eq!(x, x2);
    // no setup: an error, not a panic
    let fresh = Multigrid::default();
    assert_eq!(
        bicgstab(&a_new, &b, &mut x2, &fresh, &ctl),
        Err(SolveError::NotSetUp)
    );
}

/// `adopt` takes the operator over (the caller's is left empty), solves exactly as `setup`
/// from a copy does (bit for bit), and `give_back` returns the same rows; afterwards the
/// solver is not set up until its next setup. The Picard systems rely on this to keep one
/// operator, not two (#16).
#[test]
fn adopt_solves_as_setup_and_gives_the_operator_back() {
    let a = mixed(37, 29, 0.8, 3.0, 0.5);
    let n = a.len();
    let b: Vec<f64> = (0..n).map(|p| ((p * 7919) % 101) as f64 - 50.0).collect();
    let ctl = SolveControl {
        rel_tol: 1e-9,
        max_iter: 30,
    };
    let mut copy = MultigridSafe::new(MgParams::default());
    copy.setup(&a).unwrap();
    let mut x_copy = vec![0.0; n];
    let info_copy = copy.solve(&b, &mut x_copy, &ctl).unwrap();
    for small in [false, true] {
        let mut taken = MultigridSafe::new(MgParams::default());
        let mut own = a.clone();
        taken.setup(&a).unwrap();
        taken.adopt(&mut own, small).unwrap();
        assert!(own.is_empty(), "adopt leaves the caller's operator empty");
        let mut x = vec![0.0; n];
        let info = taken.solve(&b, &mut x, &ctl).unwrap();
        assert_eq!(info, info_copy);
        assert_eq!(x, x_copy, "adopt (small = {small}) solves as setup does");
        assert_eq!(taken.give_back(), Some(a.clone()), "the same rows back");
        assert_eq!(taken.give_back(), None, "given back once");
        assert_eq!(
            taken.solve(&b, &mut x, &ctl),
            Err(SolveError::NotSetUp),
            "no operator, no solve"
        );
        // a setup from a copy works again after the operator went back
        taken.update(&a).unwrap();
        let mut y = vec![0.0; n];
        taken.solve(&b, &mut y, &ctl).unwrap();
        assert_eq!(y, x_copy);
    }
}

mod kernels;
mod lean;
mod precision;
