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
