//! Tests of [`HermiteSurface`]: interpolation, C¹ continuity, polynomial reproduction (exact
//! for biquadratics, the known O(h³) error for cubics), the exact B-spline conversion, speed.

use super::super::testutil::{derivative_error, Rng};
use super::*;
use truck_geometry::prelude::ParametricSurface;

/// Net of f sampled at u_i = i/(ni−1), v_j = j/(nj−1).
fn net(ni: usize, nj: usize, f: impl Fn(f64, f64) -> Vec3) -> HermiteSurface {
    let pts = (0..ni * nj)
        .map(|k| {
            f(
                (k % ni) as f64 / (ni - 1) as f64,
                (k / ni) as f64 / (nj - 1) as f64,
            )
        })
        .collect();
    HermiteSurface::new(ni, nj, pts).unwrap()
}

/// A wavy test net (not polynomial).
fn wavy(ni: usize, nj: usize) -> HermiteSurface {
    net(ni, nj, |u, v| {
        Vec3::new(
            2.0 * u + 0.1 * v,
            v + 0.05 * (3.0 * u).sin(),
            (4.0 * u).sin() * (3.0 * v).cos(),
        )
    })
}

#[test]
fn rejects_bad_nets() {
    assert!(HermiteSurface::new(1, 3, vec![Vec3::zeros(); 3]).is_err());
    assert!(HermiteSurface::new(2, 2, vec![Vec3::zeros(); 3]).is_err());
    let mut pts = vec![Vec3::zeros(); 4];
    pts[3].y = f64::NAN;
    let e = HermiteSurface::new(2, 2, pts).unwrap_err();
    assert!(e.to_string().contains("(1, 1)"), "{e}");
}

#[test]
fn interpolates_every_control_point() {
    let s = wavy(13, 7);
    for j in 0..7 {
        for i in 0..13 {
            let x = s.point(i as f64 / 12.0, j as f64 / 6.0);
            assert!((x - s.control_point(i, j)).norm() < 1e-15, "({i}, {j})");
            assert!((s.eval(i as f64 / 12.0, j as f64 / 6.0).x - x).norm() < 1e-15);
        }
    }
}

#[test]
fn c1_across_patch_boundaries() {
    let s = wavy(9, 6);
    let mut rng = Rng::new(1);
    for _ in 0..200 {
        // A u-boundary between patches i−1 and i, at random v inside patch j.
        let (i, j, r) = (
            1 + (rng.next_u64() % 7) as usize,
            (rng.next_u64() % 5) as usize,
            rng.f64(),
        );
        let a = s.eval_patch(i - 1, j, 1.0, r);
        let b = s.eval_patch(i, j, 0.0, r);
        for (p, q) in [(a.x, b.x), (a.xu, b.xu), (a.xv, b.xv), (a.xvv, b.xvv)] {
            assert!(
                (p - q).norm() < 1e-12 * (1.0 + p.norm()),
                "u-boundary {i}: {p} vs {q}"
            );
        }
        let (i, j) = (
            (rng.next_u64() % 8) as usize,
            1 + (rng.next_u64() % 4) as usize,
        );
        let a = s.eval_patch(i, j - 1, r, 1.0);
        let b = s.eval_patch(i, j, r, 0.0);
        for (p, q) in [(a.x, b.x), (a.xu, b.xu), (a.xv, b.xv), (a.xuu, b.xuu)] {
            assert!(
                (p - q).norm() < 1e-12 * (1.0 + p.norm()),
                "v-boundary {j}: {p} vs {q}"
            );
        }
    }
    // The jump in x_uu across a u-boundary is O(h) but not zero: C¹, not C².
    let a = s.eval_patch(3, 2, 1.0, 0.5);
    let b = s.eval_patch(4, 2, 0.0, 0.5);
    assert!((a.xuu - b.xuu).norm() > 1e-3);
}

#[test]
fn derivatives_match_finite_differences() {
    let s = wavy(11, 8);
    let mut rng = Rng::new(2);
    for _ in 0..200 {
        // Stay off the patch lines by more than the difference stencil (2h = 2e-5).
        let (i, j) = ((rng.next_u64() % 10) as f64, (rng.next_u64() % 7) as f64);
        let (u, v) = (
            (i + rng.range(0.01, 0.99)) / 10.0,
            (j + rng.range(0.01, 0.99)) / 7.0,
        );
        let e = derivative_error(&s, u, v, 1e-5);
        assert!(e < 1e-7, "at ({u}, {v}): {e:e}");
    }
}

#[test]
fn reproduces_bilinear_and_biquadratic_exactly() {
    let (a, b, c, d) = (
        Vec3::new(1.0, -2.0, 0.5),
        Vec3::new(3.0, 0.2, -1.0),
        Vec3::new(0.1, 2.0, 0.7),
        Vec3::new(0.4, -0.3, 2.0),
    );
    let bilinear = |u: f64, v: f64| a + b * u + c * v + d * (u * v);
    let q = |u: f64, v: f64| {
        bilinear(u, v)
            + Vec3::new(u * u, 0.3 * v * v, 0.0)
            + Vec3::new(0.5, -1.0, 2.0) * (u * u * v * v)
            + Vec3::new(-0.7, 0.2, 0.9) * (u * v * v)
    };
    // Exact second derivatives of q.
    let qd = |u: f64, v: f64| {
        let k = Vec3::new(0.5, -1.0, 2.0);
        let m = Vec3::new(-0.7, 0.2, 0.9);
        (
            b + d * v + Vec3::new(2.0 * u, 0.0, 0.0) + k * (2.0 * u * v * v) + m * (v * v),
            c + d * u + Vec3::new(0.0, 0.6 * v, 0.0) + k * (2.0 * u * u * v) + m * (2.0 * u * v),
            Vec3::new(2.0, 0.0, 0.0) + k * (2.0 * v * v),
            d + k * (4.0 * u * v) + m * (2.0 * v),
            Vec3::new(0.0, 0.6, 0.0) + k * (2.0 * u * u) + m * (2.0 * u),
        )
    };
    let mut rng = Rng::new(3);
    for (ni, nj) in [(2, 2), (2, 5), (4, 3), (9, 7)] {
        let s = net(ni, nj, bilinear);
        for _ in 0..100 {
            let (u, v) = (rng.f64(), rng.f64());
            let e = s.eval(u, v);
            assert!((e.x - bilinear(u, v)).norm() < 1e-14);
            assert!((e.xu - (b + d * v)).norm() < 1e-13 && (e.xv - (c + d * u)).norm() < 1e-13);
            assert!((e.xuv - d).norm() < 1e-12 && e.xuu.norm() < 1e-12 && e.xvv.norm() < 1e-12);
        }
        if ni < 3 || nj < 3 {
            continue;
        }
        // Biquadratic: the difference formulas (central and Bessel ends) are exact, so the
        // surface is exact everywhere, end patches included.
        let s = net(ni, nj, q);
        for _ in 0..100 {
            let (u, v) = (rng.f64(), rng.f64());
            let e = s.eval(u, v);
            let (xu, xv, xuu, xuv, xvv) = qd(u, v);
            assert!((e.x - q(u, v)).norm() < 1e-13, "{ni}×{nj} at ({u}, {v})");
            assert!((e.xu - xu).norm() < 1e-12 && (e.xv - xv).norm() < 1e-12);
            let tol2 = 1e-11 * (ni * nj) as f64;
            assert!((e.xuu - xuu).norm() < tol2 && (e.xuv - xuv).norm() < tol2);
            assert!((e.xvv - xvv).norm() < tol2);
        }
    }
}

/// f = u³: central tangents err by exactly h² (h·f'''/6 with f''' = 6), the Bessel end tangent
/// at u = 0 by −2h², so the surface error is h³ (T0 + T1) = h³ (2t³ − 3t² + t) on interior
/// patches, h³ (T1 − 2 T0) on the first and h³ (T0 − 2 T1) on the last: known answers.
#[test]
fn cubic_error_is_the_known_third_order_term() {
    for k in [5usize, 10, 20] {
        let h = 1.0 / k as f64;
        let s = net(k + 1, 3, |u, v| Vec3::new(u * u * u, v, 0.0));
        let mut rng = Rng::new(4);
        for _ in 0..200 {
            let u = rng.f64();
            let (i, t) = HermiteSurface::locate(k + 1, u);
            let err = s.point(u, 0.3).x - u * u * u;
            let (t0, t1) = (t - 2.0 * t * t + t * t * t, t * t * t - t * t);
            // Tangent errors (scaled by h): h³ at interior nodes, −2h³ at both ends (the
            // one-sided formula errs by −h² f'''/3 either way round).
            let want = match i {
                0 => h * h * h * (t1 - 2.0 * t0),
                i if i == k - 1 => h * h * h * (t0 - 2.0 * t1),
                _ => h * h * h * (t0 + t1),
            };
            assert!(
                (err - want).abs() < 1e-14,
                "K = {k}, patch {i}: {err:e} vs {want:e}"
            );
        }
    }
}

#[test]
fn bspline_conversion_matches_truck() {
    let s = wavy(7, 5);
    let b = s.to_bspline();
    assert_eq!(b.degrees(), (3, 3));
    assert_eq!(b.control_points().len(), 3 * 6 + 1);
    let mut rng = Rng::new(5);
    let mut worst: f64 = 0.0;
    for _ in 0..500 {
        let (u, v) = (rng.f64(), rng.f64());
        let e = s.eval(u, v);
        let p = b.subs(u, v);
        let (bu, bv) = (b.uder(u, v), b.vder(u, v));
        // truck 0.5.0's uuder/vvder miss the factor p − 1 = 2 (see bspline_tests.rs).
        let (buu, buv, bvv) = (b.uuder(u, v) * 2.0, b.uvder(u, v), b.vvder(u, v) * 2.0);
        let d =
            |a: Vec3, x: f64, y: f64, z: f64| (a - Vec3::new(x, y, z)).norm() / (1.0 + a.norm());
        worst = worst
            .max(d(e.x, p.x, p.y, p.z))
            .max(d(e.xu, bu.x, bu.y, bu.z))
            .max(d(e.xv, bv.x, bv.y, bv.z))
            .max(d(e.xuu, buu.x, buu.y, buu.z))
            .max(d(e.xuv, buv.x, buv.y, buv.z))
            .max(d(e.xvv, bvv.x, bvv.y, bvv.z));
    }
    assert!(worst < 1e-12, "Hermite vs truck B-spline: {worst:e}");
}

/// Prints the evaluation cost (no timing assert): the local evaluation against truck's `subs`,
/// whose cost grows with the whole net.
#[test]
fn evaluation_speed() {
    let s = wavy(301, 226);
    let b = s.to_bspline();
    let mut rng = Rng::new(6);
    let uv: Vec<(f64, f64)> = (0..200_000).map(|_| (rng.f64(), rng.f64())).collect();
    let t = std::time::Instant::now();
    let mut acc = Vec3::zeros();
    for &(u, v) in &uv {
        acc += s.eval(u, v).xuv;
    }
    let eval_ns = t.elapsed().as_nanos() as f64 / uv.len() as f64;
    let t = std::time::Instant::now();
    for &(u, v) in &uv {
        acc += s.point(u, v);
    }
    let point_ns = t.elapsed().as_nanos() as f64 / uv.len() as f64;
    // Coherent access (a grid sweep, as in grid generation): compute-bound.
    let n = 400;
    let t = std::time::Instant::now();
    for j in 0..n {
        for i in 0..n {
            acc += s
                .eval(i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64)
                .xuv;
        }
    }
    let sweep_ns = t.elapsed().as_nanos() as f64 / (n * n) as f64;
    let t = std::time::Instant::now();
    for &(u, v) in &uv[..2000] {
        acc.x += b.subs(u, v).x;
    }
    let truck_ns = t.elapsed().as_nanos() as f64 / 2000.0;
    println!(
        "Hermite 301×226, random (u, v): eval (x + 5 derivatives) {eval_ns:.0} ns, point \
         {point_ns:.0} ns; grid sweep: eval {sweep_ns:.0} ns; truck subs {truck_ns:.0} ns \
         ({:.3e})",
        acc.norm()
    );
    assert!(acc.iter().all(|c| c.is_finite()));
}
