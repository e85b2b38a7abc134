//! The shape of the C–O wing block (`examples/wing_m6_co.toml`): the block above the upper
//! surface of the ONERA M6 wing (ONERA D sections, `data/oneraD.dat`, on the M6 planform) that
//! wraps around a rounded tip cap. Shared by `make_wing_co` (which writes the shipped faces
//! file) and `tests/wing_co.rs` (which builds the same faces at reduced size).
//!
//! Block indices: i from the leading edge to the trailing edge along the upper surface, j from
//! the wall to the far dome, k from the root (y = 0) over the tip cap to the tip edge, where the
//! upper and lower surfaces meet in the wing plane z = 0. Faces: F1 the wing plane ahead of the
//! leading edge, F2 the surface rising from the trailing edge, F3 the wall (upper surface and
//! cap), F4 the far dome, F5 the root plane y = 0, F6 the wing plane beyond the tip. F1 and F6
//! are both in z = 0 and meet along E7 at 180°: the flat edge of the C–O topology.
//!
//! Every grid line of the algebraic block leaving the wall is a curve from the wall point W,
//! leaving along a direction D with the prescribed first-cell height, to its point F on the far
//! dome (a circle of 3.3 local chords about the local 0.3-chord point, swung about the span by
//! the wrap angle): the faces are the algebraic block's boundary, the interior is left to the
//! elliptic solver. Along the span the wall's k-lines are y = const inboard and clustered in φ
//! towards the tip edge on the cap ([`span_lambdas`], [`tip_dphi`]): the cells along the flat
//! edge E7 and the thin sections next to the leading and trailing edges want a short last step
//! there (checkMesh's highly skewed faces, docs/WING_CO_BLOCK.md).
#![allow(dead_code)]

use ellipgrid::{Grid2, Grid3};
use ellipgrid_geometry::{
    airfoil_curve, geometric, read_airfoil_dat, vinokur, ArclengthMap, Curve, Spline, Vec3,
};
use std::f64::consts::FRAC_PI_2;

/// Root chord and semi-span (m), leading- and trailing-edge sweep (deg): the M6 planform.
pub const ROOT_CHORD: f64 = 0.8059;
pub const SEMI_SPAN: f64 = 1.1963;
pub const LE_SWEEP_DEG: f64 = 30.0;
pub const TE_SWEEP_DEG: f64 = 15.8;
/// Spanwise extent of the tip cap, fraction of the semi-span: the section thickness is scaled
/// by cos φ with y = y₀ + Δ sin φ (an elliptic cap), so it vanishes at the tip edge y = b.
pub const CAP: f64 = 0.03;
/// Far dome: radius (local chords) about the point at `FAR_CENTER` local chord.
pub const FAR_RADIUS: f64 = 3.3;
pub const FAR_CENTER: f64 = 0.3;
/// Far-dome angle of the trailing-edge grid line (deg, 180 at the leading edge).
pub const FAR_TE_DEG: f64 = 70.0;
/// First-cell height at the leading and trailing edges, in local chords.
pub const H_LE: f64 = 1e-5;
pub const H_TE: f64 = 2e-5;
/// Fraction of the k intervals on the tip cap.
pub const CAP_SHARE: f64 = 0.375;

/// Leading-edge x at span station y.
pub fn x_le(y: f64) -> f64 {
    y * LE_SWEEP_DEG.to_radians().tan()
}

/// Local chord at span station y (the planform is continued up to the tip edge y = b).
pub fn chord(y: f64) -> f64 {
    ROOT_CHORD + y * (TE_SWEEP_DEG.to_radians().tan() - LE_SWEEP_DEG.to_radians().tan())
}

/// Prescribed first-cell height at a wall point p: 1e-5 local chord at the leading edge, 2e-5
/// at the trailing edge, linear in x/c between. The local chord is the planform chord at the
/// point's y (on the cap too, up to the tip chord at the tip edge).
pub fn target_height(p: [f64; 3]) -> f64 {
    let y = p[1].clamp(0.0, SEMI_SPAN);
    let c = chord(y);
    let xc = ((p[0] - x_le(y)) / c).clamp(0.0, 1.0);
    c * (H_LE + (H_TE - H_LE) * xc)
}

/// The upper surface of the unit-chord section, s = 0 at the leading edge, 1 at the trailing
/// edge: a part of the spline through the whole section (so the leading edge is smooth).
struct Upper {
    spline: Spline,
    u_le: f64,
}

impl Curve for Upper {
    fn point(&self, s: f64) -> Vec3 {
        self.spline.point(self.u_le * (1.0 - s))
    }
    fn derivative(&self, s: f64) -> Vec3 {
        -self.u_le * self.spline.derivative(self.u_le * (1.0 - s))
    }
}

/// Upper-surface nodes of the unit-chord section: (x, z) and the outward unit normal (nx, nz).
pub fn upper_nodes(ni: usize) -> Vec<([f64; 2], [f64; 2])> {
    let pts = read_airfoil_dat(include_str!("../../data/oneraD.dat")).expect("oneraD.dat");
    let spline = airfoil_curve(pts).expect("section spline");
    let le = (0..spline.points().len())
        .min_by(|&a, &b| spline.points()[a].x.total_cmp(&spline.points()[b].x))
        .expect("points");
    let upper = Upper {
        u_le: spline.knots()[le],
        spline,
    };
    let map = ArclengthMap::new(&upper);
    let sigma = vinokur(ni, Some(0.002), Some(0.004)).expect("chordwise distribution");
    map.params(&sigma)
        .iter()
        .enumerate()
        .map(|(i, &s)| {
            let p = upper.point(s);
            let d = upper.derivative(s);
            // The section lies in the curve's (x, y) plane.
            let l = (d.x * d.x + d.y * d.y).sqrt();
            let mut n = [-d.y / l, d.x / l];
            let mut x = [p.x, p.y];
            if i == 0 {
                // The leading edge exactly: in the wing plane, normal straight ahead.
                x = [0.0, 0.0];
                n = [-1.0, 0.0];
            }
            (x, n)
        })
        .collect()
}

/// A span station of the wall: y of the section, thickness factor cos φ, wrap angle φ.
#[derive(Clone, Copy, Debug)]
pub struct Station {
    pub y: f64,
    pub tau: f64,
    pub phi: f64,
}

/// The station at span parameter λ ∈ [0, 2]: y = λ y₀ inboard (λ ≤ 1, y₀ = (1 − CAP) b), the
/// cap φ = (λ − 1) π/2 beyond (λ = 2: the tip edge).
pub fn station(lambda: f64) -> Station {
    let y0 = (1.0 - CAP) * SEMI_SPAN;
    if lambda <= 1.0 {
        return Station {
            y: y0 * lambda,
            tau: 1.0,
            phi: 0.0,
        };
    }
    if lambda >= 2.0 {
        return Station {
            y: SEMI_SPAN,
            tau: 0.0,
            phi: FRAC_PI_2,
        };
    }
    let phi = (lambda - 1.0) * FRAC_PI_2;
    Station {
        y: y0 + CAP * SEMI_SPAN * phi.sin(),
        tau: phi.cos(),
        phi,
    }
}

/// The span parameters λ_k of one wall k-line: inboard y from 0 to y₀ (Vinokur, last step
/// matched to the cap's first), then the cap in φ from the uniform step π / (2 n_cap) at its
/// start to `tip_dphi` at the tip edge (Vinokur). Inboard every line has the same λ_k (y =
/// const); on the cap the lines differ by their last step ([`tip_dphi`]).
pub fn span_lambdas(nk: usize, tip_dphi: f64) -> Vec<f64> {
    let y0 = (1.0 - CAP) * SEMI_SPAN;
    let n_cap = cap_intervals(nk);
    let n_in = nk - 1 - n_cap;
    let dphi = FRAC_PI_2 / n_cap as f64;
    let last = (CAP * SEMI_SPAN * dphi / y0).min(0.5 / n_in as f64);
    let mut out = vinokur(n_in + 1, None, Some(last)).expect("span distribution");
    let cap = vinokur(
        n_cap + 1,
        Some(dphi / FRAC_PI_2),
        Some(tip_dphi / FRAC_PI_2),
    )
    .expect("cap distribution");
    out.extend(cap[1..].iter().map(|s| 1.0 + s));
    out
}

/// The cap's last φ step at the trailing edge (deg). Matching the tip edge's last chordwise
/// step there (1.8e-3, φ step 18°) leaves the thin sections next to the trailing edge reaching
/// F6 too flat (checkMesh skewness 4.5 at i = 62); 7.5° (the uniform step) sheared the cells
/// at the tip's trailing edge (growth ratio along k 5.8, faces up to 76° non-orthogonal); 11°
/// and 15° measured as well (docs/WING_CO_BLOCK.md, "Faster wall passes, and the tip's last
/// steps").
pub const TIP_DPHI_TE_DEG: f64 = 13.0;

/// The cap's last φ step (rad) at the leading edge, from the steps on both sides of the 180°
/// block edge E7 (F1 ahead of the leading edge, F6 beyond the tip, both in the wing plane): the
/// cells along it are wedges spanning both faces, and `algebraic::flat_edge` maps them as
/// w ↦ w², which wants the same step on both sides. On the leading-edge line (zero thickness,
/// y = y₀ + Δ sin φ along the swept leading edge) the last spanwise step is
/// Δ (1 − cos δφ) / cos Λ; it is made the tip edge's first chordwise step, chord(b) x₁ (x₁ the
/// section's first node after the leading edge): 3.1°. The thin sections next to the leading
/// edge then also reach the tip edge steeply (their last step Δ (1 − cos δφ) in y against
/// t sin δφ in z) instead of nearly in the wing plane. With every wall line's last step the
/// same fraction of its length (3e-3 at the leading edge, against 6e-5 beyond E7) checkMesh
/// found 166 highly skewed faces on F6, skewness up to 43 (docs/WING_CO_BLOCK.md).
pub fn tip_dphi(x1: f64) -> f64 {
    let step = chord(SEMI_SPAN) * x1;
    let delta = CAP * SEMI_SPAN;
    (1.0 - step * LE_SWEEP_DEG.to_radians().cos() / delta).acos()
}

/// Number of k intervals on the cap.
pub fn cap_intervals(nk: usize) -> usize {
    (((nk - 1) as f64 * CAP_SHARE).round() as usize).clamp(2, nk - 3)
}

/// Wrap angle of the far dome at k: 0 inboard, rising as (π/2) s² (2 − s) over the last
/// `2 n_cap` intervals (s from 0 to 1), so that the dome's spacing along k grows smoothly
/// instead of jumping to the polar spacing of the cap.
fn far_wrap(k: usize, nk: usize) -> f64 {
    let l = nk - 1;
    let n = (2 * cap_intervals(nk)).min(l);
    if k + n <= l {
        return 0.0;
    }
    let s = (k + n - l) as f64 / n as f64;
    FRAC_PI_2 * s * s * (2.0 - s)
}

/// The wall point of section node (x, z) (unit chord) at station `st`.
fn wall_point(xz: [f64; 2], st: &Station) -> [f64; 3] {
    let c = chord(st.y);
    [x_le(st.y) + c * xz[0], st.y, c * st.tau * xz[1]]
}

/// In-plane swing of the grid lines leaving the leading edge (rad) at station `st`, k: 0 at the
/// root (so that F5 stays in y = 0), growing to 30° (normal to the swept leading edge) at the
/// cap, plus 30° along the far dome's wrap ramp ([`far_wrap`]): 60° at the tip edge.
fn swing_le(st: &Station, k: usize, nk: usize) -> f64 {
    let y0 = (1.0 - CAP) * SEMI_SPAN;
    let inboard = 30.0 * (st.y / y0).min(1.0);
    (inboard + 30.0 * far_wrap(k, nk) / FRAC_PI_2).to_radians()
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt()
}

/// One wall column: wall point, direction, far point, first height.
struct Column {
    w: [f64; 3],
    d: [f64; 3],
    f: [f64; 3],
    h: f64,
}

impl Column {
    /// The point at parameter t ∈ [0, 1] (t = 0 wall, 1 far): x = W + (F − W) t² +
    /// L D t (1 − t)², L = |F − W|, leaving W along D at speed L.
    fn at(&self, t: f64) -> [f64; 3] {
        let l = dist(self.f, self.w);
        let (a, b) = (t * t, l * t * (1.0 - t) * (1.0 - t));
        std::array::from_fn(|c| self.w[c] + (self.f[c] - self.w[c]) * a + self.d[c] * b)
    }

    /// nj nodes, the first at height h off the wall, geometric growth.
    fn nodes(&self, nj: usize) -> Vec<[f64; 3]> {
        let l = dist(self.f, self.w);
        let mut first = self.h / l;
        // The curve's speed at the wall is L; one correction for its curvature.
        let h1 = dist(self.at(first), self.w);
        first *= self.h / h1;
        let sig = geometric(nj, first).expect("normal distribution");
        sig.iter().map(|&t| self.at(t)).collect()
    }
}

/// The algebraic block (ni × nj × nk), whose boundary gives the faces.
pub fn algebraic_block(ni: usize, nj: usize, nk: usize) -> Grid3 {
    let sec = upper_nodes(ni);
    // Far-dome angle of grid line i: a blend of arclength and normal turning, so that the
    // nose's lines do not take the whole front of the dome.
    let psi: Vec<f64> = sec.iter().map(|(_, n)| n[1].atan2(n[0])).collect();
    let (p0, p1) = (psi[0], psi[ni - 1]);
    let th_te = FAR_TE_DEG.to_radians();
    let theta: Vec<f64> = (0..ni)
        .map(|i| {
            let s = i as f64 / (ni - 1) as f64;
            let a = (p0 - psi[i]) / (p0 - p1);
            let g = 0.3 * a + 0.7 * s;
            std::f64::consts::PI + (th_te - std::f64::consts::PI) * g
        })
        .collect();
    // The cap's last φ step of each wall line: matched to the step beyond E7 at the leading
    // edge, `TIP_DPHI_TE_DEG` at the trailing edge, linear in x/c between (`tip_dphi`).
    let (le, te) = (tip_dphi(sec[1].0[0]), TIP_DPHI_TE_DEG.to_radians());
    let lams: Vec<Vec<f64>> = sec
        .iter()
        .map(|([x, _], _)| span_lambdas(nk, le + (te - le) * x))
        .collect();
    let mut g = Grid3::zeros(ni, nj, nk);
    for (i, lam) in lams.iter().enumerate() {
        for (k, &l) in lam.iter().enumerate() {
            let st = station(l);
            let c = chord(st.y);
            // Exactly z = 0 at the tip edge (F6 in the wing plane).
            let v = if st.phi == FRAC_PI_2 {
                [0.0, 1.0, 0.0]
            } else {
                [0.0, st.phi.sin(), st.phi.cos()]
            };
            let beta = swing_le(&st, k, nk);
            let center = [x_le(st.y) + FAR_CENTER * c, st.y, 0.0];
            let r = FAR_RADIUS * c;
            let ([x, _], [nx, nz]) = sec[i];
            let w = wall_point(sec[i].0, &st);
            // Swing of the chordwise part: β at the leading edge, none at the trailing edge.
            let bd = beta * (1.0 - x);
            let u = [bd.cos(), -bd.sin(), 0.0];
            let d = unit(std::array::from_fn(|q| nx * u[q] + nz * v[q]));
            // Far point: the section's circle at angle θ, swung about the span by φ (x-axis)
            // and then about z by γ (β at the leading edge, 0 at the trailing edge).
            let ga = beta * (theta[i] - th_te) / (std::f64::consts::PI - th_te);
            // Exactly in the wing plane ahead of the leading edge (F1).
            let (ct, sn) = if i == 0 {
                (-1.0, 0.0)
            } else {
                (theta[i].cos(), theta[i].sin())
            };
            let om = far_wrap(k, nk);
            let vf = if k == nk - 1 {
                [0.0, 1.0, 0.0]
            } else {
                [0.0, om.sin(), om.cos()]
            };
            let e0 = [ct, sn * vf[1], sn * vf[2]];
            let e = [
                e0[0] * ga.cos() + e0[1] * ga.sin(),
                -e0[0] * ga.sin() + e0[1] * ga.cos(),
                e0[2],
            ];
            let f = std::array::from_fn(|q| center[q] + r * e[q]);
            let col = Column {
                w,
                d,
                f,
                h: target_height(w),
            };
            for (j, p) in col.nodes(nj).into_iter().enumerate() {
                g.set(i, j, k, p);
            }
        }
    }
    g
}

/// The six faces F1 … F6 of the block, in the face orientation of `ellipgrid::grid::faces`
/// (F1/F2 (j, k), F3/F4 (i, k), F5/F6 (i, j), first index fastest).
pub fn faces(ni: usize, nj: usize, nk: usize) -> [Grid2<3>; 6] {
    let g = algebraic_block(ni, nj, nk);
    std::array::from_fn(|f| {
        let (na, nb) = match f / 2 {
            0 => (nj, nk),
            1 => (ni, nk),
            _ => (ni, nj),
        };
        Grid2::<3>::from_fn(na, nb, |a, b| {
            let n = match f {
                0 => [0, a, b],
                1 => [ni - 1, a, b],
                2 => [a, 0, b],
                3 => [a, nj - 1, b],
                4 => [a, b, 0],
                _ => [a, b, nk - 1],
            };
            g.point(n[0], n[1], n[2])
        })
    })
}
