//! The memory-lean y-lines (`yline.rs`) against the y-line operator.

use super::kernels::one_level_mixed;
use super::*;

/// The lean y-lines (`yline.rs`, one factor per unknown, couplings read from the operator)
/// solve the same lines as the y-line operator: on anisotropic, boundary-layer (clustered in
/// y, the direction the y-lines carry) and non-symmetric problems, odd and even sizes, one
/// thread's block and several, every cycle's residual agrees to 5 % (the line operator is
/// stored in f32, the lean factors in f64: measured up to 1.5e-2 apart, on the x-anisotropic
/// problem at a residual of 5e-11), the iterations are the same, and the solution to 1e-10
/// equals x* and the other smoother's.
#[test]
fn lean_y_lines_solve_the_same_lines() {
    let cases = [
        ("aniso eps_x=1e-4", aniso(63, 63, 1e-4, 1.0)),
        ("aniso eps_y=1e-4 50x37", aniso(50, 37, 1.0, 1e-4)),
        (
            "boundary layer (y)",
            boundary_layer(63, 63, 1e-5, 10.0, false),
        ),
        (
            "boundary layer (y) 300x130",
            boundary_layer(300, 130, 1e-5, 10.0, false),
        ),
        ("mixed 64x47", mixed(64, 47, 0.5, 1.0, 0.8)),
    ];
    for smoother in [Smoother::AlternatingZebraLine, Smoother::ZebraLineY] {
        for (name, a) in &cases {
            if smoother == Smoother::ZebraLineY && name.contains("eps_y") {
                continue; // strong x-coupling: y-lines alone do not smooth it
            }
            let params = MgParams { smoother, ..v11() };
            let lean = MgParams {
                lean_y_lines: true,
                ..params.clone()
            };
            let copy = check(name, a, params, 0.2);
            let info = check(name, a, lean.clone(), 0.2);
            assert_eq!(info.iterations, copy.iterations, "{name} {smoother:?}");
            for (k, (u, v)) in info
                .residual_history
                .iter()
                .zip(&copy.residual_history)
                .enumerate()
            {
                assert!(
                    (u - v).abs() <= 5e-2 * v + 1e-14,
                    "{name} {smoother:?} cycle {k}: {u:e} against {v:e}"
                );
            }
            // the hierarchy keeps the factors only
            let mut mg = Multigrid::new(lean);
            mg.setup(a).unwrap();
            let h = mg.h.as_ref().unwrap();
            assert!(h.levels.iter().all(|l| l.yop.is_empty()));
            assert_eq!(h.levels[0].ycp.len(), a.len());
        }
    }
}

/// After the lean y-line sweep the lines relaxed last have a zero residual, and the half
/// residual (the other columns, read from the operator) equals the full one.
#[test]
fn lean_half_residual_matches_full_residual() {
    for (nx, ny) in [(17, 12), (16, 9), (2, 5)] {
        let (mg, b) = one_level_mixed(nx, ny, true);
        let lev = &mg.h.as_ref().unwrap().levels[0];
        let (len, pd) = (b.len(), relax::pad(nx));
        let mut x = vec![0.0; len];
        let (mut rf, mut rh) = (vec![0.0; len], vec![0.0; len]);
        for first in [0, 1] {
            yline::ysweep(&lev.a, &lev.ycp, nx, ny, &mut x, &b, first);
            let full = relax::residual(&lev.a, None, nx, ny, &x, &b, &mut rf, relax::Zeroed::None);
            let zeroed = relax::Zeroed::Cols(1 - first);
            let half = relax::residual(&lev.a, None, nx, ny, &x, &b, &mut rh, zeroed);
            for j in 0..ny {
                for i in (1 - first..nx).step_by(2) {
                    assert!(rf[pd + i + nx * j].abs() < 1e-13, "column {i}");
                }
            }
            assert!(rf.iter().zip(&rh).all(|(u, v)| (u - v).abs() < 1e-13));
            assert!((full - half).abs() < 1e-12 * full);
        }
    }
}
