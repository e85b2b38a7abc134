//! The smoothers' line factors in f32 (`relax::YLineOp`, `xline::factor_x`) against f64.

use super::*;

/// With the line factors in f32 the smoothers solve their lines only to ~1e-7 of the
/// equations' terms, but the plain cycles run in correction form (residual and update from
/// the f64 operator), so their fixed point is the f64 solution: on anisotropic problems
/// (where |A||x| ≫ |A x|), boundary-layer grids clustered in x and in y and a non-symmetric
/// operator, the cycles reach a true relative residual of 1e-12 (a smoother iterated on its
/// own stalls at the factors' rounding: measured with the f32 factors in plain, not
/// correction-form, cycles, the x-anisotropic case stalls at 8.2e-7), the solution equals the direct LU's
/// to 1e-10, and from a nonzero start (half the solution: r₀ = b / 2) the same.
#[test]
fn f32_line_factors_keep_the_f64_fixed_point() {
    let cases = [
        ("aniso eps_x=1e-4", aniso(63, 63, 1e-4, 1.0)),
        ("aniso eps_y=1e-4 50x37", aniso(50, 37, 1.0, 1e-4)),
        (
            "boundary layer (y)",
            boundary_layer(63, 63, 1e-5, 10.0, false),
        ),
        (
            "boundary layer (x)",
            boundary_layer(63, 63, 1e-5, 10.0, true),
        ),
        ("mixed 64x47", mixed(64, 47, 0.5, 1.0, 0.8)),
    ];
    for (name, a) in &cases {
        let n = a.len();
        let b = manufactured(n);
        let mut lu = DirectLu::new();
        lu.setup(a).unwrap();
        let ctl = SolveControl {
            rel_tol: 1e-12,
            max_iter: 40,
        };
        let mut xd = vec![0.0; n];
        lu.solve(&b, &mut xd, &ctl).unwrap();
        let mut mg = Multigrid::new(v11());
        mg.setup(a).unwrap();
        assert!(mg.h.as_ref().unwrap().levels[0].yop.op.len() == n);
        // from zero, and from a nonzero start (the residual computed first)
        for start in [0.0, 1.0_f64] {
            let x0: Vec<f64> = xd.iter().map(|v| start * 0.5 * v).collect();
            let mut x = x0.clone();
            let info = mg.solve(&b, &mut x, &ctl).unwrap();
            let mut r = vec![0.0; n];
            a.residual(&b, &x, &mut r);
            let mut r0 = vec![0.0; n];
            a.residual(&b, &x0, &mut r0);
            let (rel, err) = (norm(&r) / norm(&r0), rel_diff(&x, &xd));
            eprintln!(
                "{name:<24} start {start}: {} cycles, true residual {rel:.1e}, against LU {err:.1e}",
                info.iterations
            );
            assert!(info.converged, "{name}: {:?}", info.residual_history);
            // the recursively updated residual is the true one
            assert!(
                rel <= 1.5e-12,
                "{name} start {start}: true residual {rel:e}"
            );
            assert!(
                err <= 1e-10,
                "{name} start {start}: differs from LU by {err:e}"
            );
        }
    }
}
