//! The smoothers' kernels: half residuals against full ones, and (ignored) timings and
//! factor explorations.

use super::*;

#[test]
#[ignore]
fn kernel_timings() {
    use std::time::Instant;
    let n = 1023;
    let a = poisson9(n, n);
    let mut mg = Multigrid::new(MgParams::default());
    mg.setup(&a).unwrap();
    let h = mg.h.as_ref().unwrap();
    let mut ws = Workspace::new(h);
    let lev = &h.levels[0];
    let b = manufactured(relax::padded_len(n, n));
    let reps = 10;
    let time = |name: &str, f: &mut dyn FnMut()| {
        f();
        let mut s = f64::MAX;
        for _ in 0..reps {
            let t = Instant::now();
            f();
            s = s.min(t.elapsed().as_secs_f64());
        }
        eprintln!("{name:<24} {:7.2} ns/unknown", s * 1e9 / (n * n) as f64);
    };
    let v = &mut ws.lv[0];
    let (x, r) = (&mut v.x, &mut v.r);
    time("copy (stream)", &mut || r.copy_from_slice(&b));
    time("xzebra both", &mut || {
        xline::xzebra(&lev.a, &lev.xop, n, n, x, &b, 0);
        xline::xzebra(&lev.a, &lev.xop, n, n, x, &b, 1);
    });
    time("yzebra both", &mut || {
        relax::yzebra(&lev.yop, n, n, x, &b, 0);
        relax::yzebra(&lev.yop, n, n, x, &b, 1);
    });
    let mut ycp = Vec::new();
    yline::factor_y(&lev.a, n, n, &mut ycp).unwrap();
    time("ysweep both (lean)", &mut || {
        yline::ysweep(&lev.a, &ycp, n, n, x, &b, 0);
    });
    time("residual cols (lean)", &mut || {
        relax::residual(&lev.a, None, n, n, x, &b, r, relax::Zeroed::Cols(1));
    });
    time("residual", &mut || {
        relax::residual(&lev.a, Some(&lev.yop), n, n, x, &b, r, relax::Zeroed::None);
    });
    let mut bc = vec![0.0; relax::padded_len(n / 2, n / 2)];
    time("residual rows", &mut || {
        relax::residual(
            &lev.a,
            Some(&lev.yop),
            n,
            n,
            x,
            &b,
            r,
            relax::Zeroed::Rows(1),
        );
    });
    time("residual cols", &mut || {
        relax::residual(
            &lev.a,
            Some(&lev.yop),
            n,
            n,
            x,
            &b,
            r,
            relax::Zeroed::Cols(1),
        );
    });
    time("restrict", &mut || {
        interp::restrict(interp::restriction(&lev.p, &lev.r), n, n, r, &mut bc)
    });
    time("prolong", &mut || interp::prolong_add(&lev.p, n, n, &bc, x));
    let mut ws = Workspace::new(h);
    time("V cycle", &mut || {
        h.cycle(0, Cycle::V, &mut ws.lv, &mut ws.band);
    });
    let mut m2 = Multigrid::new(MgParams::default());
    time("setup", &mut || m2.setup(&a).unwrap());
}

#[test]
#[ignore]
fn explore_factors() {
    let problems: Vec<(&str, Stencil9)> = vec![
        ("poisson5 63", poisson5(63, 63)),
        ("poisson9 63", poisson9(63, 63)),
        ("poisson5 127", poisson5(127, 127)),
        ("poisson5 64", poisson5(64, 64)),
        ("poisson9 50x37", poisson9(50, 37)),
        ("poisson5 100x23", poisson5(100, 23)),
        ("aniso x", aniso(63, 63, 1e-4, 1.0)),
        ("aniso y", aniso(63, 63, 1.0, 1e-4)),
        ("aniso 1e-2 x", aniso(63, 63, 1e-2, 1.0)),
        ("bl y", boundary_layer(63, 63, 1e-5, 10.0, false)),
        ("bl x", boundary_layer(63, 63, 1e-5, 10.0, true)),
        ("bl y 127", boundary_layer(127, 127, 1e-5, 10.0, false)),
        ("bl y lx=1", boundary_layer(63, 63, 1e-5, 1.0, false)),
        ("mixed .5", mixed(63, 63, 0.5, 1.0, 0.8)),
        ("mixed .8 R10", mixed(63, 63, 0.8, 10.0, 0.8)),
        ("mixed .9 R100 c1.5", mixed(63, 63, 0.9, 100.0, 1.5)),
        ("mixed .5 conv 1.5", mixed(63, 63, 0.5, 1.0, 1.5)),
        ("mixed .5 conv 2", mixed(63, 63, 0.5, 1.0, 2.0)),
        ("mixed .5 conv 2.5", mixed(63, 63, 0.5, 1.0, 2.5)),
        ("mixed .5 conv 3", mixed(63, 63, 0.5, 1.0, 3.0)),
        ("mixed .5 conv 4", mixed(63, 63, 0.5, 1.0, 4.0)),
        ("mixed 0 conv 3", mixed(63, 63, 0.0, 1.0, 3.0)),
    ];
    let configs: Vec<(&str, MgParams)> = vec![
        ("alt V11", MgParams::default()),
        (
            "alt V21",
            MgParams {
                npre: 2,
                ..MgParams::default()
            },
        ),
        (
            "alt F11",
            MgParams {
                cycle: Cycle::F,
                ..MgParams::default()
            },
        ),
        (
            "alt W11",
            MgParams {
                cycle: Cycle::W,
                ..MgParams::default()
            },
        ),
        (
            "alt acc",
            MgParams {
                accelerate: true,
                ..MgParams::default()
            },
        ),
        (
            "alt R=adj",
            MgParams {
                restriction: Restriction::Adjoint,
                ..MgParams::default()
            },
        ),
        (
            "xy V11",
            MgParams {
                smoother: Smoother::ZebraLineXY,
                ..MgParams::default()
            },
        ),
        (
            "xy F11",
            MgParams {
                smoother: Smoother::ZebraLineXY,
                cycle: Cycle::F,
                ..MgParams::default()
            },
        ),
    ];
    eprint!("{:<20}", "");
    for (c, _) in &configs {
        eprint!("{c:>10}");
    }
    eprintln!();
    for (name, a) in &problems {
        eprint!("{name:<20}");
        let n = a.len();
        let xe = manufactured(n);
        let mut b = vec![0.0; n];
        a.apply(&xe, &mut b);
        for (_, p) in &configs {
            let mut mg = Multigrid::new(p.clone());
            mg.setup(a).unwrap();
            let mut x = vec![0.0; n];
            let ctl = SolveControl {
                rel_tol: 1e-10,
                max_iter: 60,
            };
            match mg.solve(&b, &mut x, &ctl) {
                Ok(info) => eprint!("{:>10.4}", mean_factor(&info)),
                Err(_) => eprint!("{:>10}", "div"),
            }
        }
        eprintln!();
    }
}

/// After a zebra half sweep the relaxed lines have a zero residual (to the f32 line factors'
/// rounding), and the half residual (rows from the operator, columns from the y-line
/// operator) equals the full one to that rounding.
#[test]
fn half_residuals_match_full_residual() {
    // the f32 factors solve the lines to ~1e-7 of the equations' terms (values here are O(1))
    let tol = 2e-6;
    for (nx, ny) in [(17, 12), (16, 9), (2, 5)] {
        let (mg, b) = one_level_mixed(nx, ny, false);
        let lev = &mg.h.as_ref().unwrap().levels[0];
        let (len, pd) = (b.len(), relax::pad(nx));
        let mut x = vec![0.0; len];
        let (mut rf, mut rh) = (vec![0.0; len], vec![0.0; len]);
        for colour in [0, 1] {
            xline::xzebra(&lev.a, &lev.xop, nx, ny, &mut x, &b, colour);
            let full = relax::residual(&lev.a, None, nx, ny, &x, &b, &mut rf, relax::Zeroed::None);
            let zeroed = relax::Zeroed::Rows(colour);
            let half = relax::residual(&lev.a, Some(&lev.yop), nx, ny, &x, &b, &mut rh, zeroed);
            for j in (colour..ny).step_by(2) {
                for i in 0..nx {
                    let r = rf[pd + i + nx * j];
                    assert!(r.abs() < tol, "row {j}: {r:e}");
                }
            }
            assert!(rf.iter().zip(&rh).all(|(u, v)| (u - v).abs() < tol));
            assert!((full - half).abs() < 1e-5 * full);
            relax::yzebra(&lev.yop, nx, ny, &mut x, &b, colour);
            relax::residual(&lev.a, None, nx, ny, &x, &b, &mut rf, relax::Zeroed::None);
            let zeroed = relax::Zeroed::Cols(colour);
            relax::residual(&lev.a, Some(&lev.yop), nx, ny, &x, &b, &mut rh, zeroed);
            for j in 0..ny {
                for i in (colour..nx).step_by(2) {
                    let r = rf[pd + i + nx * j];
                    assert!(r.abs() < tol, "column {i}: {r:e}");
                }
            }
            assert!(rf.iter().zip(&rh).all(|(u, v)| (u - v).abs() < tol));
        }
    }
}

/// A one-level hierarchy (y-line operator, or the lean factors) of the mixed operator, and a
/// right-hand side in the smoothers' padded layout: the half-residual tests' setup.
pub(super) fn one_level_mixed(nx: usize, ny: usize, lean_y_lines: bool) -> (Multigrid, Vec<f64>) {
    let a = mixed(nx, ny, 0.5, 1.0, 0.8);
    let mut mg = Multigrid::new(MgParams {
        coarse_enough: 1,
        lean_y_lines,
        ..MgParams::default()
    });
    mg.setup(&a).unwrap();
    let pd = relax::pad(nx);
    let mut b = vec![0.0; relax::padded_len(nx, ny)];
    b[pd..pd + nx * ny].copy_from_slice(&manufactured(nx * ny));
    (mg, b)
}
