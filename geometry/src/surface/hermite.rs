//! C¹ bicubic Hermite (Ferguson) surface through a control-point net (METHOD.md §4).
//!
//! The net x_ij, i = 0..K, j = 0..L, sits at the uniform parameters u_i = i/K, v_j = j/L.
//! Each cell [u_i, u_{i+1}] × [v_j, v_{j+1}] is a bicubic Hermite patch fixed by x, x_u, x_v and
//! the twist x_uv at its four corners; neighbouring patches share the corner data, so the
//! surface is C¹.
//!
//! Node derivatives come from finite differences of the net (with h = 1/K in u, 1/L in v):
//! - interior nodes: central differences (x_{i+1} − x_{i−1}) / 2h;
//! - end nodes: the second-order one-sided (−3 x_0 + 4 x_1 − x_2) / 2h, which is the slope of
//!   the parabola through the first three nodes, i.e. Bessel's end condition. It is chosen
//!   because it has the same (second) order as the interior formula, so the surface
//!   reproduces biquadratic nets exactly everywhere, boundaries included, and it needs no
//!   global solve (the surface stays local: moving one node changes ≤ 3 × 3 nodes' data);
//! - K = 1 (two points) uses the one-sided first difference, exact for lines;
//! - twists: the u-difference of the v-differences (tensor product of the same formulas).
//!
//! Accuracy: exact for any function of degree ≤ 2 in each of u and v (when K, L ≥ 2), hence
//! for bilinear ones always. For a cubic the tangents err by h² f'''/6 (interior) and
//! −h² f'''/3 (ends), so the surface error is O(h³), e.g. u³ gives exactly
//! h³ (2t³ − 3t² + t) on interior patches (t the local parameter).
//!
//! Evaluation is O(1): a floor locates the patch, then 16 corner vectors are contracted with
//! the cubic Hermite weights. [`HermiteSurface::to_bspline`] gives the exact bicubic B-spline
//! (each Hermite patch is a Bézier patch; interior knots of multiplicity 3).

use super::{Surface, SurfacePoint};
use crate::{GeometryError, Vec3};
use truck_geometry::prelude::{BSplineSurface, KnotVec, Point3};

/// Bicubic Hermite surface through a (K+1) × (L+1) control net; see the module doc.
#[derive(Debug, Clone, PartialEq)]
pub struct HermiteSurface {
    ni: usize,
    nj: usize,
    /// Per node (i fastest): [x, h_u x_u, h_v x_v, h_u h_v x_uv] (derivatives in the
    /// patch-local parameters).
    nodes: Vec<[Vec3; 4]>,
}

impl HermiteSurface {
    /// Surface through `points` (ni × nj, i fastest) at u_i = i/(ni − 1), v_j = j/(nj − 1).
    ///
    /// # Errors
    /// ni or nj below 2, a point count other than ni·nj, or a non-finite point.
    pub fn new(ni: usize, nj: usize, points: Vec<Vec3>) -> Result<HermiteSurface, GeometryError> {
        if ni < 2 || nj < 2 {
            return Err(GeometryError::Invalid(format!(
                "Hermite surface: the control net needs at least 2 × 2 points, got {ni} × {nj}"
            )));
        }
        if points.len() != ni * nj {
            return Err(GeometryError::Invalid(format!(
                "Hermite surface: {ni} × {nj} net needs {} points, got {}",
                ni * nj,
                points.len()
            )));
        }
        if let Some(k) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(GeometryError::Invalid(format!(
                "Hermite surface: control point (i, j) = ({}, {}) is not finite",
                k % ni,
                k / ni
            )));
        }
        let at = |i: usize, j: usize| i + ni * j;
        // h·x_u and h·x_v at every node, then the twist as the u-difference of h·x_v.
        let xu: Vec<Vec3> = (0..ni * nj)
            .map(|k| diff(ni, k % ni, |i| points[at(i, k / ni)]))
            .collect();
        let xv: Vec<Vec3> = (0..ni * nj)
            .map(|k| diff(nj, k / ni, |j| points[at(k % ni, j)]))
            .collect();
        let nodes = (0..ni * nj)
            .map(|k| {
                let w = diff(ni, k % ni, |i| xv[at(i, k / ni)]);
                [points[k], xu[k], xv[k], w]
            })
            .collect();
        Ok(HermiteSurface { ni, nj, nodes })
    }

    /// Net size (ni, nj) = (K + 1, L + 1).
    pub fn dims(&self) -> (usize, usize) {
        (self.ni, self.nj)
    }

    /// Control point (i, j).
    ///
    /// # Panics
    /// If (i, j) is outside the net.
    pub fn control_point(&self, i: usize, j: usize) -> Vec3 {
        assert!(
            i < self.ni && j < self.nj,
            "control point ({i}, {j}) outside the net"
        );
        self.nodes[i + self.ni * j][0]
    }

    /// Patch index and local parameter for u along a direction with n nodes.
    #[inline]
    fn locate(n: usize, u: f64) -> (usize, f64) {
        let k = (n - 1) as f64;
        let s = u * k;
        // NaN maps to patch 0 (and stays NaN in t).
        let i = (s.floor().max(0.0) as usize).min(n - 2);
        (i, s - i as f64)
    }

    /// Coordinate k of the 4 × 4 corner data of patch (i, j): c[α][β], α = (value, u-tangent)
    /// at node a = 0, then at a = 1; β likewise in v. Entries are x, h_u x_u, h_v x_v,
    /// h_u h_v x_uv of the corner nodes.
    #[inline]
    fn corner_data(&self, i: usize, j: usize, k: usize) -> [[f64; 4]; 4] {
        let n0 = i + self.ni * j;
        let n1 = n0 + self.ni;
        let (n00, n10, n01, n11) = (
            &self.nodes[n0],
            &self.nodes[n0 + 1],
            &self.nodes[n1],
            &self.nodes[n1 + 1],
        );
        [
            [n00[0][k], n00[2][k], n01[0][k], n01[2][k]],
            [n00[1][k], n00[3][k], n01[1][k], n01[3][k]],
            [n10[0][k], n10[2][k], n11[0][k], n11[2][k]],
            [n10[1][k], n10[3][k], n11[1][k], n11[3][k]],
        ]
    }

    /// The exact bicubic B-spline of this surface on [0, 1]² (interior knots i/K of
    /// multiplicity 3). The Bézier net around node (3i, 3j) is
    /// x + a h_u/3 x_u + b h_v/3 x_v + a b h_u h_v/9 x_uv, a, b ∈ {−1, 0, 1}.
    pub fn to_bspline(&self) -> BSplineSurface<Point3> {
        let knots = |n: usize| {
            let k = n - 1;
            let mut t = vec![0.0; 4];
            for i in 1..k {
                t.extend([i as f64 / k as f64; 3]);
            }
            t.extend([1.0; 4]);
            KnotVec::from(t)
        };
        let (mu, mv) = (3 * (self.ni - 1) + 1, 3 * (self.nj - 1) + 1);
        let ctrl: Vec<Vec<Point3>> = (0..mu)
            .map(|ci| {
                (0..mv)
                    .map(|cj| {
                        // Nearest node and offsets a, b ∈ {−1, 0, 1}.
                        let (i, j) = ((ci + 1) / 3, (cj + 1) / 3);
                        let a = ci as f64 - 3.0 * i as f64;
                        let b = cj as f64 - 3.0 * j as f64;
                        let [x, u, v, w] = self.nodes[i + self.ni * j];
                        let p = x + u * (a / 3.0) + v * (b / 3.0) + w * (a * b / 9.0);
                        Point3::new(p.x, p.y, p.z)
                    })
                    .collect()
            })
            .collect();
        BSplineSurface::new((knots(self.ni), knots(self.nj)), ctrl)
    }

    /// Evaluation of patch (i, j) at local (t, s) ∈ [0, 1]².
    ///
    /// Per coordinate (plain f64 loops vectorize better than Vec3 arithmetic): contract the
    /// corner data with the v-weights and their derivatives, then with the u-weights.
    #[inline]
    #[allow(clippy::needless_range_loop)] // k indexes the coordinate in six outputs
    fn eval_patch(&self, i: usize, j: usize, t: f64, s: f64) -> SurfacePoint {
        let (bu, du, ddu) = hermite_weights(t);
        let bv = hermite_weights(s);
        let (ku, kv) = ((self.ni - 1) as f64, (self.nj - 1) as f64);
        let mut out = [[0.0; 3]; 6];
        for k in 0..3 {
            let c = self.corner_data(i, j, k);
            // r[l][α] = Σ_β c[α][β] (d/ds)^l weight_β(s)
            let mut r = [[0.0; 4]; 3];
            for (rl, w) in r.iter_mut().zip([&bv.0, &bv.1, &bv.2]) {
                for (x, ca) in rl.iter_mut().zip(&c) {
                    *x = dot4(ca, w);
                }
            }
            out[0][k] = dot4(&r[0], &bu);
            out[1][k] = dot4(&r[0], &du) * ku;
            out[2][k] = dot4(&r[1], &bu) * kv;
            out[3][k] = dot4(&r[0], &ddu) * (ku * ku);
            out[4][k] = dot4(&r[1], &du) * (ku * kv);
            out[5][k] = dot4(&r[2], &bu) * (kv * kv);
        }
        let [x, xu, xv, xuu, xuv, xvv] = out.map(Vec3::from);
        SurfacePoint {
            x,
            xu,
            xv,
            xuu,
            xuv,
            xvv,
        }
    }
}

#[inline]
fn dot4(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

/// Cubic Hermite weights (P0, T0, P1, T1) at t and their first and second derivatives:
/// P0 = 1 − 3t² + 2t³, T0 = t − 2t² + t³, P1 = 3t² − 2t³, T1 = t³ − t².
#[inline]
fn hermite_weights(t: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let t2 = t * t;
    let t3 = t2 * t;
    (
        [
            1.0 - 3.0 * t2 + 2.0 * t3,
            t - 2.0 * t2 + t3,
            3.0 * t2 - 2.0 * t3,
            t3 - t2,
        ],
        [
            6.0 * (t2 - t),
            1.0 - 4.0 * t + 3.0 * t2,
            6.0 * (t - t2),
            3.0 * t2 - 2.0 * t,
        ],
        [12.0 * t - 6.0, 6.0 * t - 4.0, 6.0 - 12.0 * t, 6.0 * t - 2.0],
    )
}

/// h · df/dk at node k of n ≥ 2 equally spaced samples f(0..n): central differences inside,
/// second-order one-sided (Bessel) at the ends, first difference when n = 2.
#[inline]
fn diff(n: usize, k: usize, f: impl Fn(usize) -> Vec3) -> Vec3 {
    if n == 2 {
        f(1) - f(0)
    } else if k == 0 {
        (f(1) * 4.0 - f(0) * 3.0 - f(2)) * 0.5
    } else if k == n - 1 {
        (f(n - 1) * 3.0 - f(n - 2) * 4.0 + f(n - 3)) * 0.5
    } else {
        (f(k + 1) - f(k - 1)) * 0.5
    }
}

impl Surface for HermiteSurface {
    fn breaks(&self) -> (Vec<f64>, Vec<f64>) {
        let lines = |n: usize| (1..n - 1).map(|k| k as f64 / (n - 1) as f64).collect();
        (lines(self.ni), lines(self.nj))
    }

    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let (i, t) = Self::locate(self.ni, u);
        let (j, s) = Self::locate(self.nj, v);
        self.eval_patch(i, j, t, s)
    }

    fn point(&self, u: f64, v: f64) -> Vec3 {
        let (i, t) = Self::locate(self.ni, u);
        let (j, s) = Self::locate(self.nj, v);
        let (bu, _, _) = hermite_weights(t);
        let (bv, _, _) = hermite_weights(s);
        let mut x = [0.0; 3];
        for (k, xk) in x.iter_mut().enumerate() {
            let c = self.corner_data(i, j, k);
            *xk = dot4(
                &[
                    dot4(&c[0], &bv),
                    dot4(&c[1], &bv),
                    dot4(&c[2], &bv),
                    dot4(&c[3], &bv),
                ],
                &bu,
            );
        }
        Vec3::from(x)
    }
}

#[cfg(test)]
#[path = "hermite_tests.rs"]
mod tests;
