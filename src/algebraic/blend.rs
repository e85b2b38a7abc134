//! Hermite-blended algebraic transformation C → P, eqs. [47]–[49] (METHOD.md §3).
//!
//! ```text
//! s = s_E3(ξ) B0(t) + s_E4(ξ) B1(t),   t = t_E1(η) C0(s) + t_E2(η) C1(s).
//! ```
//!
//! The blend of each pair of opposite edges has zero slope at exactly the orthogonal edges, so
//! the ξ-lines (η-lines) of P meet those edges at right angles: both edges → Hermite cubics
//! (H0, H1) = ((1 + 2s)(1 − s)², (3 − 2s)s²); only the first → (1 − s², s²); only the second →
//! ((1 − s)², 1 − (1 − s)²); neither → (1 − s, s), the straight-line map [39, 40].
//!
//! Per node, (s, t) is the intersection of two curves. Eliminating s = f(t) leaves
//! φ(t) = t − g(f(t)) on [0, 1], solved by Newton from the straight-line solution, safeguarded by
//! bisection. Edge functions in [0, 1] give φ(0) ≤ 0 ≤ φ(1), so a root exists; it is unique when
//! max|f'| max|g'| < 1 (then φ' > 0). Otherwise φ is sampled to count the sign changes, and two
//! intersections (possible for cubics) are an error naming the node.

use crate::algebraic::transform::ParamGrid;
use crate::grid::arclength::EdgeFunctions;
use crate::{Error, Result};

/// Blending pair of one direction: which end(s) are orthogonal (zero slope).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Blend {
    /// (1 − u, u): straight lines.
    Linear,
    /// (1 − u², u²): zero slope at u = 0.
    First,
    /// ((1 − u)², 1 − (1 − u)²): zero slope at u = 1.
    Second,
    /// Hermite cubics (H0, H1): zero slope at both ends.
    Both,
}

impl Blend {
    /// The blend for orthogonality at the first (u = 0) and second (u = 1) edge of a pair.
    pub fn from_edges(first: bool, second: bool) -> Self {
        match (first, second) {
            (false, false) => Blend::Linear,
            (true, false) => Blend::First,
            (false, true) => Blend::Second,
            (true, true) => Blend::Both,
        }
    }

    /// B1(u) (B0 = 1 − B1) and its derivative.
    #[inline]
    pub fn b1(self, u: f64) -> (f64, f64) {
        match self {
            Blend::Linear => (u, 1.0),
            Blend::First => (u * u, 2.0 * u),
            Blend::Second => (1.0 - (1.0 - u) * (1.0 - u), 2.0 * (1.0 - u)),
            Blend::Both => ((3.0 - 2.0 * u) * u * u, 6.0 * u * (1.0 - u)),
        }
    }

    /// max |B1'| on [0, 1].
    fn max_slope(self) -> f64 {
        match self {
            Blend::Linear => 1.0,
            Blend::First | Blend::Second => 2.0,
            Blend::Both => 1.5,
        }
    }
}

/// Samples of φ when uniqueness is not guaranteed by the slope bound.
const SAMPLES: usize = 64;

/// Why a node has no usable intersection.
#[derive(Debug, PartialEq)]
enum NodeFailure {
    None,
    Two(f64, f64),
}

/// (s, t) at one node: a = s_E3, b = s_E4, c = t_E1, d = t_E2; `t0` the straight-line guess.
fn node(
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    bs: Blend,
    bt: Blend,
    t0: f64,
) -> Result<(f64, f64), NodeFailure> {
    // s = f(t) = a + (b − a) B1(t); t = g(s) = c + (d − c) C1(s).
    let f = |t: f64| {
        let (v, dv) = bs.b1(t);
        (a + (b - a) * v, (b - a) * dv)
    };
    let phi = |t: f64| {
        let (s, ds) = f(t);
        let (v, dv) = bt.b1(s);
        (t - c - (d - c) * v, 1.0 - (d - c) * dv * ds)
    };
    let unique = (b - a).abs() * (d - c).abs() * bs.max_slope() * bt.max_slope() < 1.0;
    let (mut lo, mut hi) = (0.0, 1.0);
    let (plo, phi_hi) = (phi(lo).0, phi(hi).0);
    if !(unique && plo <= 0.0 && phi_hi >= 0.0) {
        // Count the roots of φ on a sample grid: zeros at samples and strict sign changes.
        let mut roots = Vec::new();
        let mut prev = (0.0, plo);
        if plo == 0.0 {
            roots.push((0.0, 0.0));
        }
        for k in 1..=SAMPLES {
            let tk = k as f64 / SAMPLES as f64;
            let p = phi(tk).0;
            if p == 0.0 {
                roots.push((tk, tk));
            } else if prev.1 * p < 0.0 {
                roots.push((prev.0, tk));
            }
            prev = (tk, p);
        }
        match roots.len() {
            0 => return Err(NodeFailure::None),
            1 => (lo, hi) = roots[0],
            _ => return Err(NodeFailure::Two(f(roots[0].0).0, f(roots[1].1).0)),
        }
    }
    // Safeguarded Newton on φ in [lo, hi], with φ(lo) ≤ 0 ≤ φ(hi) orientation tracked.
    let rising = phi(lo).0 <= phi(hi).0;
    let mut t = t0.clamp(lo, hi);
    for _ in 0..100 {
        let (p, dp) = phi(t);
        if p == 0.0 {
            break;
        }
        if (p < 0.0) == rising {
            lo = t;
        } else {
            hi = t;
        }
        let mut tn = t - p / dp;
        if !(tn > lo && tn < hi) {
            tn = 0.5 * (lo + hi);
        }
        let done = (tn - t).abs() <= 1e-15 * (1.0 + t.abs()) || hi - lo <= 1e-16;
        t = tn;
        if done {
            break;
        }
    }
    Ok((f(t).0, t))
}

/// The smoothstep t²(3 − 2t) of t clamped to [0, 1]: the cubic Hermite blend B1 of [47–49]
/// with zero slope at both ends, the fade of the volume passes' goals next to faces they do
/// not correct ([`crate::elliptic::crossing`], [`crate::elliptic::wall_normal`],
/// [`crate::elliptic::continuation`]).
#[inline]
pub fn smoothstep(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The Hermite-blended transformation [47]–[49] of edge functions `ef` (new edge functions
/// from the harmonic solution [46], or arclength), with zero slope at the edges marked in
/// `orthogonal` (E1, E2, E3, E4). With no orthogonal edge it is the straight-line map.
///
/// Boundary values are set exactly from `ef`. `place` names the block in errors.
///
/// # Errors
/// [`Error::Input`] naming the node (i, j) if its two curves do not intersect in the unit
/// square or intersect twice, or naming the edge if an edge function leaves [0, 1].
pub fn hermite_blend(ef: &EdgeFunctions, orthogonal: [bool; 4], place: &str) -> Result<ParamGrid> {
    let (ni, nj) = (ef.ni(), ef.nj());
    for (name, v) in [
        ("E1", &ef.t_e1),
        ("E2", &ef.t_e2),
        ("E3", &ef.s_e3),
        ("E4", &ef.s_e4),
    ] {
        if let Some(k) = v.iter().position(|x| !(0.0..=1.0).contains(x)) {
            return Err(Error::input(
                format!("{place}, edge {name}"),
                format!("edge function value {} at node {k} is outside [0, 1]", v[k]),
            ));
        }
    }
    let bs = Blend::from_edges(orthogonal[2], orthogonal[3]);
    let bt = Blend::from_edges(orthogonal[0], orthogonal[1]);
    let mut s = vec![0.0; ni * nj];
    let mut t = vec![0.0; ni * nj];
    for j in 0..nj {
        let (c, d) = (ef.t_e1[j], ef.t_e2[j]);
        for i in 0..ni {
            let (a, b) = (ef.s_e3[i], ef.s_e4[i]);
            // Straight-line guess, eqs. [39, 40] in closed form.
            let s0 = (a + (b - a) * c) / (1.0 - (b - a) * (d - c));
            let t0 = c + (d - c) * s0;
            let t0 = if t0.is_finite() { t0 } else { 0.5 };
            let (sv, tv) = node(a, b, c, d, bs, bt, t0).map_err(|e| {
                let msg = match e {
                    NodeFailure::None => "the blended curves do not intersect in the unit \
                                          square"
                        .to_string(),
                    NodeFailure::Two(s1, s2) => format!(
                        "the blended curves intersect twice (near s = {s1:.4} and s = {s2:.4}): \
                         the edge functions of opposite edges differ too much for orthogonality \
                         here"
                    ),
                };
                Error::input(place, format!("node ({i}, {j}): {msg}"))
            })?;
            s[i + ni * j] = sv;
            t[i + ni * j] = tv;
        }
    }
    crate::algebraic::transform::set_edge_values(ef, &mut s, &mut t);
    Ok(ParamGrid::from_parts(ni, nj, s, t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebraic::transform::straight_line;

    fn ef() -> EdgeFunctions {
        let p = |n: usize, e: f64| {
            (0..n)
                .map(|k| (k as f64 / (n - 1) as f64).powf(e))
                .collect()
        };
        EdgeFunctions {
            s_e3: p(9, 1.5),
            s_e4: p(9, 0.8),
            t_e1: p(7, 2.0),
            t_e2: p(7, 1.2),
        }
    }

    #[test]
    fn blends_have_zero_slope_at_exactly_the_orthogonal_ends() {
        for (b, z0, z1) in [
            (Blend::Linear, false, false),
            (Blend::First, true, false),
            (Blend::Second, false, true),
            (Blend::Both, true, true),
        ] {
            assert_eq!(b.b1(0.0).0, 0.0);
            assert_eq!(b.b1(1.0).0, 1.0);
            assert_eq!(b.b1(0.0).1 == 0.0, z0, "{b:?}");
            assert_eq!(b.b1(1.0).1 == 0.0, z1, "{b:?}");
            // Derivative against a central difference, and the slope bound.
            for k in 1..10 {
                let u = k as f64 / 10.0;
                let fd = (b.b1(u + 1e-6).0 - b.b1(u - 1e-6).0) / 2e-6;
                assert!((fd - b.b1(u).1).abs() < 1e-8);
                assert!(b.b1(u).1 <= b.max_slope() + 1e-15);
            }
        }
    }

    #[test]
    fn no_orthogonal_edge_is_the_straight_line_map() {
        let e = ef();
        let h = hermite_blend(&e, [false; 4], "b").unwrap();
        let sl = straight_line(&e);
        for (u, v) in h.s.iter().zip(&sl.s).chain(h.t.iter().zip(&sl.t)) {
            assert!((u - v).abs() < 1e-14);
        }
    }

    #[test]
    fn every_node_solves_the_blended_equations() {
        let e = ef();
        for orth in [
            [true; 4],
            [false, false, true, false],
            [true, false, false, true],
        ] {
            let h = hermite_blend(&e, orth, "b").unwrap();
            let bs = Blend::from_edges(orth[2], orth[3]);
            let bt = Blend::from_edges(orth[0], orth[1]);
            for j in 0..e.nj() {
                for i in 0..e.ni() {
                    let (s, t) = h.at(i, j);
                    let rs = s - e.s_e3[i] - (e.s_e4[i] - e.s_e3[i]) * bs.b1(t).0;
                    let rt = t - e.t_e1[j] - (e.t_e2[j] - e.t_e1[j]) * bt.b1(s).0;
                    assert!(rs.abs() < 1e-14 && rt.abs() < 1e-14, "{orth:?} ({i},{j})");
                }
            }
        }
    }

    #[test]
    fn two_intersections_and_bad_edge_functions_are_errors() {
        // Steep opposite edge functions: s = f(t) and t = g(s) cross three times at the
        // centre node of this 3 × 3 map.
        assert!(matches!(
            node(0.0, 1.0, 0.0, 1.0, Blend::Both, Blend::Both, 0.5),
            Err(NodeFailure::Two(..))
        ));
        let e = EdgeFunctions {
            s_e3: vec![0.0, 0.02, 1.0],
            s_e4: vec![0.0, 0.98, 1.0],
            t_e1: vec![0.0, 0.02, 1.0],
            t_e2: vec![0.0, 0.98, 1.0],
        };
        let m = hermite_blend(&e, [true; 4], "blk").unwrap_err().to_string();
        assert!(
            m.contains("blk") && m.contains("node (1, 1)") && m.contains("twice"),
            "{m}"
        );
        let mut e = ef();
        e.s_e4[3] = 1.2;
        let m = hermite_blend(&e, [true; 4], "blk").unwrap_err().to_string();
        assert!(m.contains("edge E4") && m.contains("outside [0, 1]"), "{m}");
    }
}
