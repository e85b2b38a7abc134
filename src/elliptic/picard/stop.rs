//! When the Picard (or Newton) iteration stops, and how accurately each step's linear
//! systems are solved: the a-posteriori error estimate of the iterate ([`error_estimate`]) and
//! the forcing term of the inexact steps ([`forcing`]).

use super::{PicardParams, PicardStep, Rules};

/// The ratio of the forcing term to the observed Picard contraction ([`forcing`]) of every
/// Picard iteration but the volume multigrid's nested one
/// ([`crate::elliptic::nested3d::MULTIGRID_FORCING_RATIO`]).
pub(crate) const FORCING_RATIO: f64 = 0.5;

/// The relative linear tolerance of the next Picard step: `linear_tolerance` without forcing,
/// else `clamp(max(c ρ, 0.5 tol / u), linear_tolerance, linear_forcing)` with `c` =
/// `forcing_ratio` ([`FORCING_RATIO`] but in nested volume multigrid solves), ρ the last
/// observed Picard contraction and u = ρ · (last update) the predicted next update: no more
/// accurate than the Picard error, and no more than half the Picard tolerance in absolute
/// terms (which also keeps the request above round-off near convergence). The stop test
/// ([`error_estimate`]) counts the linear error η u of the last step, so a looser request can
/// cost a step but never a wrong convergence claim; half (rather than a tenth, as measured
/// before) saves the second cycle of the last step at 129³ (bench_volume: 85 → 77 WU).
/// `linear_forcing` for the first two steps.
pub(crate) fn forcing(params: &PicardParams, history: &[PicardStep], forcing_ratio: f64) -> f64 {
    let (floor, cap) = (params.linear_tolerance, params.linear_forcing);
    if cap <= floor {
        return floor;
    }
    match history {
        [.., a, b] if a.update > 0.0 && b.update > 0.0 => {
            let rho = b.update / a.update;
            let predicted = rho * b.update;
            (forcing_ratio * rho)
                .max(0.5 * params.tolerance / predicted)
                .clamp(floor, cap)
        }
        _ => cap,
    }
}

/// Steps over which [`error_estimate`] also measures the mean contraction (longer than the
/// ~14-step period of the update norms of the damped periodic iteration).
const CONTRACTION_WINDOW: usize = 20;

/// The Picard error after the steps of `history` (relative to the diameter): the last update
/// u, or, once the iteration contracts, the a-posteriori bound of a contraction ρ/(1 − ρ) u plus
/// the error η u of the inexact step (η its largest relative linear residual). ρ is the larger
/// of the last two ratios of successive updates (one ratio alone is not enough: after a nested
/// prediction the first step removes the prolongation error, and the ratio of the next update
/// to it says nothing of the Picard contraction — measured: an estimate of 1e-10 for a true
/// error of 8e-10) and of the mean ratio over the last [`CONTRACTION_WINDOW`] steps after the
/// first two (update norms that oscillate, as in the damped steps of a periodic block, can
/// grow for a step while the error shrinks by ~0.85 per step: stopping on u alone there left
/// the grid 7.7e-10 of the diameter off at the tolerance 1e-10). With the contraction of
/// 0.01–0.04 seen after nested iteration the bound is below u and saves the last Picard step,
/// whose update would only confirm it (from the third step on).
///
/// After two Newton steps that contract (ratio r = u_k / u_{k−1} < 1/2) the error is that of
/// Newton's quadratic convergence instead: the next update is K u_k² + η u_k, and
/// K ≤ u_k / u_{k−1}² (the last update holds K u_{k−1}² plus its own linear error), so the
/// bound is u_k (r² + η) / (1 − r) (the updates after the next shrink by r at least), taken
/// where it is below the contraction's (NACA0012 O-grid at 4 × 257², step 1:
/// 3.2e-7 · (1.1e-4 + 9.3e-5) / 0.99 = 6.6e-11 after step 4, where the contraction bound,
/// 4.1e-9, waited for a fifth step whose update was 2.3e-11). Only the finest level of nested
/// iteration stops on it ([`super::iterate`]).
///
/// η u understates the linear error where the solve's remaining residual is smoother than
/// the right-hand side it started from (η is a ratio of scaled 2-norms; a smooth residual
/// hides a large error): the folded start at 1025² with coarse levels stopped at 0.2 of
/// their first update ended 2.1e-10 of the diameter from the discrete solution on a bound
/// of 3.6e-11 (updates 4.4e-6, 3.0e-7, 1.2e-8, η 1.6e-3: the error was 11 η u). So where the
/// bound would stop the iteration, the Newton step measures its linear error e instead
/// ([`PicardStep::linear_error`]) and the bound is (u r² + e) / (1 − r).
pub(crate) fn error_estimate(history: &[PicardStep]) -> f64 {
    let n = history.len();
    let Some(b) = history.last() else {
        return f64::INFINITY;
    };
    if n >= 2 && b.newton && history[n - 2].newton && history[n - 2].update > 0.0 {
        let r = b.update / history[n - 2].update;
        if r < 0.5 {
            let newton = match b.linear_error {
                Some(e) => (b.update * r * r + e) / (1.0 - r),
                None => {
                    let eta = b.linear_residual.iter().copied().fold(0.0, f64::max);
                    b.update * (r * r + eta) / (1.0 - r)
                }
            };
            return newton.min(contraction_estimate(history));
        }
    }
    contraction_estimate(history)
}

/// [`error_estimate`] of a linear contraction (Picard steps, or Newton steps before they
/// contract).
pub(super) fn contraction_estimate(history: &[PicardStep]) -> f64 {
    let n = history.len();
    let Some(b) = history.last() else {
        return f64::INFINITY;
    };
    if n < 3 || history[n - 2].update <= 0.0 || history[n - 3].update <= 0.0 {
        return b.update;
    }
    let (z, a) = (&history[n - 3], &history[n - 2]);
    let short = (b.update / a.update).max(a.update / z.update);
    let from = 2.max(n.saturating_sub(CONTRACTION_WINDOW + 1)).min(n - 3);
    let steps = (n - 1 - from) as f64;
    let mean = if history[from].update > 0.0 {
        (b.update / history[from].update).powf(1.0 / steps)
    } else {
        f64::INFINITY
    };
    let rho = if short < 1.0 { short.max(mean) } else { mean };
    if rho.is_nan() || rho >= 1.0 {
        return b.update;
    }
    let eta = b.linear_residual.iter().copied().fold(0.0, f64::max);
    let bound = b.update * (rho / (1.0 - rho) + eta);
    if rho < 0.5 {
        bound.min(b.update)
    } else {
        bound
    }
}

/// The share of a coarse level's first update that the next level's first update is assumed
/// to be when a level's stop ([`Rules::relative_stop`]) is chosen: the observed first updates of
/// smooth domains fall by 3–4× per level (second order), so that a stop at 3e-2 of the first
/// update leaves a tenth of the next level's prediction error
/// ([`crate::elliptic::nested::COARSE_STOP_NEWTON`]).
pub(crate) const PREDICTED_SHARE: f64 = 0.3;

/// The stopping threshold of the Picard iteration after the steps of `history`: the last
/// update (relative to the diameter) must fall below the tolerance, or below
/// `relative_stop` times the first update (a coarse level of nested iteration; 0 = off).
///
/// Where the first updates do not fall by [`PREDICTED_SHARE`] from the coarser level's
/// ([`Rules::coarser_first`]), the next level's start will be as far off as this level's
/// was, and this level's remaining error can be larger in proportion: `relative_stop` is
/// multiplied by q / [`PREDICTED_SHARE`], q the ratio of the two first updates (at most 1).
/// The dented square at 1025² (first updates 4.34e-3, 3.86e-3, 2.24e-3 at 257², 513²,
/// 1025², the corners of the dent limiting the convergence under refinement): the 513² level
/// stops after one Newton step instead of two (its next update was 3.9e-6 against a start
/// error of 2.2e-3 for the finest level), the same fine steps.
pub(super) fn stop_threshold(params: &PicardParams, history: &[PicardStep], rules: &Rules) -> f64 {
    let first = history.first().map_or(0.0, |h| h.update);
    let mut fraction = rules.relative_stop;
    if fraction > 0.0 && rules.coarser_first > 0.0 {
        let q = (first / rules.coarser_first).min(1.0);
        fraction *= (q / PREDICTED_SHARE).max(1.0);
    }
    params.tolerance.max(fraction * first)
}
