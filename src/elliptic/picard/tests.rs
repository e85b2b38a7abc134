//! Tests of the Picard iteration's stop.

use super::*;

/// Steps whose updates fall by `rho` per step from 1, with linear residual `eta`.
fn history(rho: f64, steps: usize, eta: f64) -> Vec<PicardStep> {
    (0..steps)
        .map(|k| PicardStep {
            update: rho.powi(k as i32),
            residual: 0.0,
            linear_iterations: vec![1],
            linear_residual: vec![eta],
            newton: false,
            linear_error: None,
        })
        .collect()
}

#[test]
fn the_estimate_bounds_the_remaining_error_of_a_slow_contraction() {
    // Updates u_k = ρ^k leave the error Σ_{m>k} ρ^m = u_k ρ / (1 − ρ) after step k.
    for rho in [0.5, 0.7, 0.85, 0.95] {
        let h = history(rho, 12, 0.0);
        let u = h.last().unwrap().update;
        let error = u * rho / (1.0 - rho);
        let est = error_estimate(&h);
        assert!(est >= error * (1.0 - 1e-12), "ρ {rho}: {est} < {error}");
        assert!(est <= error * (1.0 + 1e-12), "ρ {rho}: {est} > {error}");
    }
}

#[test]
fn oscillating_update_norms_are_judged_by_their_mean_contraction() {
    // Updates falling by 0.85 per step on average, with a 14-step wave of ±40 % on top
    // (the damped periodic iteration's pattern): where the wave makes the last update grow,
    // the estimate still holds the mean contraction, ρ/(1 − ρ) ≈ 5.7 times the update.
    let h: Vec<PicardStep> = (0..60)
        .map(|k| PicardStep {
            update: 0.85f64.powi(k)
                * (1.0 + 0.4 * (2.0 * std::f64::consts::PI * k as f64 / 14.0).sin()),
            residual: 0.0,
            linear_iterations: vec![1],
            linear_residual: vec![0.0],
            newton: false,
            linear_error: None,
        })
        .collect();
    let grows = (3..60)
        .find(|&n| h[n - 1].update > h[n - 2].update)
        .unwrap();
    let u = h[grows - 1].update;
    assert!(error_estimate(&h[..grows]) > 4.0 * u);
    assert!(error_estimate(&h) > 4.0 * h[59].update);
}

#[test]
fn a_fast_contraction_saves_the_confirming_step_and_growth_falls_back_to_the_update() {
    let h = history(0.03, 4, 1e-3);
    let u = h.last().unwrap().update;
    let est = error_estimate(&h);
    assert!(est < 0.05 * u && est > 0.03 * u, "{est} against {u}");
    // Growing updates: no contraction to speak of, the last update.
    let h = history(1.2, 4, 0.0);
    assert_eq!(error_estimate(&h), h.last().unwrap().update);
    // One ratio alone (two steps): the last update.
    let h = history(0.01, 2, 0.0);
    assert_eq!(error_estimate(&h), h.last().unwrap().update);
}

/// Newton steps of the recorded (update, linear residual) pairs.
fn newton_steps(steps: &[(f64, f64)]) -> Vec<PicardStep> {
    steps
        .iter()
        .map(|&(update, eta)| PicardStep {
            update,
            residual: 0.0,
            linear_iterations: vec![2],
            linear_residual: vec![eta],
            newton: true,
            linear_error: None,
        })
        .collect()
}

/// Newton steps whose updates fall quadratically, u_{k+1} = K u_k² + η u_k.
fn newton_history(k: f64, eta: f64, steps: usize) -> Vec<PicardStep> {
    let mut u = 0.3 / k;
    (0..steps)
        .map(|_| {
            let h = PicardStep {
                update: u,
                residual: 0.0,
                linear_iterations: vec![2],
                linear_residual: vec![eta],
                newton: true,
                linear_error: None,
            };
            u = k * u * u + eta * u;
            h
        })
        .collect()
}

#[test]
fn quadratic_newton_updates_are_judged_by_their_quadratic_bound() {
    for (k, eta) in [(30.0, 1e-3), (300.0, 1e-4), (5.0, 1e-2)] {
        let h = newton_history(k, eta, 8);
        for n in 3..8 {
            if h[n - 1].update < 1e-14 {
                break;
            }
            let est = error_estimate(&h[..n]);
            // the remaining error: the updates still to come
            let rest: f64 = newton_history(k, eta, 12)[n..]
                .iter()
                .map(|s| s.update)
                .sum();
            assert!(est >= rest, "K {k} η {eta}, {n} steps: {est:e} < {rest:e}");
            // below the contraction bound once the steps accelerate (that is what saves a step)
            let contraction = contraction_estimate(&h[..n]);
            assert!(est <= contraction, "{est:e} > {contraction:e}");
        }
    }
    // On the NACA0012 O-grid's step-1 history (4 × 257², upper_fore) the bound stops after
    // step 4, where the contraction bound asked for a fifth step (whose update was 2.3e-11).
    let steps = [
        (8.613e-3, 6.25e-2),
        (2.474e-3, 3.84e-2),
        (3.077e-5, 8.29e-3),
        (3.214e-7, 9.30e-5),
    ];
    let h = newton_steps(&steps);
    assert!(error_estimate(&h) < 1e-10 && contraction_estimate(&h) > 1e-10);
    assert!(error_estimate(&h) > 2.3e-11);
    // Picard steps with the same updates keep the contraction bound.
    let picard: Vec<PicardStep> = h
        .iter()
        .map(|s| PicardStep {
            newton: false,
            ..s.clone()
        })
        .collect();
    assert_eq!(error_estimate(&picard), contraction_estimate(&picard));
}

#[test]
fn a_measured_linear_error_replaces_eta_times_the_update() {
    // The folded start's fine level at 1025² with coarse levels stopped at 0.2 of their first
    // update: η u gave a bound of 3.6e-11 where the grid was 2.1e-10 from the solution.
    let steps = [(4.39e-6, 1.3e-2), (3.04e-7, 1.5e-2), (1.15e-8, 1.6e-3)];
    let mut h = newton_steps(&steps);
    let by_eta = error_estimate(&h);
    assert!(by_eta < 1e-10, "{by_eta:e}");
    // the measured linear error (11 η u) enters the bound instead, which then holds the error
    h[2].linear_error = Some(2.0e-10);
    let measured = error_estimate(&h);
    assert!(measured > 2.0e-10 && measured < 2.5e-10, "{measured:e}");
    // a measured error below η u lowers the bound (it is the better estimate)
    h[2].linear_error = Some(1e-12);
    assert!(error_estimate(&h) < by_eta);
}

#[test]
fn a_coarse_stop_grows_with_the_ratio_of_the_first_updates() {
    // a coarse level stopping at 3e-2 of its first update 1e-3 (tolerance 1e-10)
    let params = PicardParams::default();
    let h = history(0.1, 2, 0.0);
    let h: Vec<PicardStep> = h
        .into_iter()
        .map(|s| PicardStep {
            update: 1e-3 * s.update,
            ..s
        })
        .collect();
    let mut rules = Rules::stop(3e-2);
    let plain = stop_threshold(&params, &h, &rules);
    assert!((plain - 3e-5).abs() < 1e-18, "{plain}");
    // the level below's first update four times this one's (second order): unchanged
    rules.coarser_first = 4e-3;
    assert_eq!(stop_threshold(&params, &h, &rules), plain);
    // first updates falling by 0.6 per level: the stop raised to 0.6 / 0.3 = 2 times
    rules.coarser_first = 1e-3 / 0.6;
    let raised = stop_threshold(&params, &h, &rules);
    assert!((raised - 6e-5).abs() < 1e-15, "{raised}");
    // not falling at all (or growing): at most 1 / 0.3 times
    for coarser in [1e-3, 5e-4] {
        rules.coarser_first = coarser;
        let most = stop_threshold(&params, &h, &rules);
        assert!((most - 1e-4).abs() < 1e-15, "{most}");
    }
    // the finest level (no relative stop) stops at the tolerance whatever the trend
    let mut finest = Rules::stop(0.0);
    finest.coarser_first = 1e-3;
    assert_eq!(stop_threshold(&params, &h, &finest), params.tolerance);
}
