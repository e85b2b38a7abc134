//! Fast local evaluation of truck-geometry B-spline and NURBS surfaces.
//!
//! truck-geometry stays the data model (knots, control points, weights, STEP I/O), but its
//! `subs` costs time proportional to the whole control net per call. [`BSplineSurf`] copies
//! the data once and evaluates only the (p+1)(q+1) control points of the knot span: the
//! non-vanishing basis functions and their first two derivatives by Piegl & Tiller's
//! algorithm A2.3 (The NURBS Book, 1997), then the tensor contraction in homogeneous
//! coordinates and, for NURBS, the quotient rule:
//! x = A/w, x_u = (A_u − w_u x)/w, x_uu = (A_uu − 2 w_u x_u − w_uu x)/w,
//! x_uv = (A_uv − w_u x_v − w_v x_u − w_uv x)/w.
//!
//! The parameter domain [t_p, t_n] of each direction (degree p, n control points; for the
//! usual clamped knot vectors this is truck's `parameter_range`) is mapped affinely onto
//! [0, 1]; derivatives are with respect to the normalized parameters.

use super::{Surface, SurfacePoint};
use crate::{GeometryError, Vec3};
use truck_geometry::prelude::{BSplineSurface, NurbsSurface, Point3, Vector4};

/// Highest supported degree (fixed-size scratch arrays keep evaluation allocation-free).
/// OpenVSP writes piecewise Bézier fuselage surfaces of degree 22.
const MAX_DEGREE: usize = 31;
/// Scratch sizes for degrees up to 3 (bicubic and lower: most CAD surfaces; zeroing the
/// scratch of size 12 was a tenth of an OpenVSP model's gridding), up to 11 (every common CAD
/// surface) and for the rest. The arithmetic is the same in each.
const CUBIC: usize = 4;
const SMALL: usize = 12;
const LARGE: usize = MAX_DEGREE + 1;

/// A B-spline or NURBS surface with local evaluation; see the module doc.
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineSurf {
    /// Degrees (p, q).
    deg: [usize; 2],
    /// Control point counts (n_u, n_v).
    count: [usize; 2],
    /// Knot vectors, normalized so that the domain is [0, 1].
    knots: [Vec<f64>; 2],
    /// Homogeneous control points (w x, w y, w z, w), index i_u · n_v + i_v.
    cw: Vec<[f64; 4]>,
    rational: bool,
}

impl BSplineSurf {
    /// Highest supported degree in each direction (31).
    pub const MAX_DEGREE: usize = MAX_DEGREE;

    /// Copies a truck B-spline surface (`control_points()[i_u][i_v]`).
    ///
    /// # Errors
    /// See [`BSplineSurf::from_truck_nurbs`].
    pub fn from_truck_bspline(s: &BSplineSurface<Point3>) -> Result<BSplineSurf, GeometryError> {
        let cw = s
            .control_points()
            .iter()
            .flatten()
            .map(|p| [p.x, p.y, p.z, 1.0])
            .collect();
        Self::build(s.uknot_vec(), s.vknot_vec(), s.control_points(), cw, false)
    }

    /// Copies a truck NURBS surface (homogeneous control points (w x, w y, w z, w)).
    ///
    /// # Errors
    /// A degree below 1 or above [`BSplineSurf::MAX_DEGREE`], inconsistent sizes, decreasing or non-finite
    /// knots, an empty parameter domain, non-finite control points or non-positive weights.
    pub fn from_truck_nurbs(s: &NurbsSurface<Vector4>) -> Result<BSplineSurf, GeometryError> {
        let cw = s
            .control_points()
            .iter()
            .flatten()
            .map(|p| [p.x, p.y, p.z, p.w])
            .collect();
        Self::build(s.uknot_vec(), s.vknot_vec(), s.control_points(), cw, true)
    }

    fn build<P>(
        tu: &[f64],
        tv: &[f64],
        rows: &[Vec<P>],
        cw: Vec<[f64; 4]>,
        rational: bool,
    ) -> Result<BSplineSurf, GeometryError> {
        let bad = |msg: String| Err(GeometryError::Invalid(format!("B-spline surface: {msg}")));
        let nu = rows.len();
        let nv = rows.first().map_or(0, |r| r.len());
        if nu == 0 || nv == 0 || rows.iter().any(|r| r.len() != nv) {
            return bad("empty or ragged control net".into());
        }
        let mut knots = [Vec::new(), Vec::new()];
        let mut deg = [0; 2];
        for (d, (t, n)) in [(tu, nu), (tv, nv)].into_iter().enumerate() {
            let dir = ["u", "v"][d];
            if t.len() <= n + 1 || t.len() - n - 1 > MAX_DEGREE {
                return bad(format!(
                    "{dir}: {} knots and {n} control points give degree {}, not in 1..={MAX_DEGREE}",
                    t.len(),
                    t.len() as isize - n as isize - 1
                ));
            }
            let p = t.len() - n - 1;
            if t.iter().any(|x| !x.is_finite()) || t.windows(2).any(|w| w[1] < w[0]) {
                return bad(format!("{dir}: knots must be finite and non-decreasing"));
            }
            let (a, b) = (t[p], t[n]);
            if b <= a {
                return bad(format!("{dir}: empty parameter domain [{a}, {b}]"));
            }
            knots[d] = t.iter().map(|x| (x - a) / (b - a)).collect();
            // (x − a)/(b − a) is exactly 0 at a and exactly 1 at b: ends need no fix-up.
            deg[d] = p;
        }
        if let Some(k) = cw
            .iter()
            .position(|c| !c.iter().all(|x| x.is_finite()) || c[3] <= 0.0)
        {
            return bad(format!(
                "control point ({}, {}) is not finite or has a non-positive weight",
                k / nv,
                k % nv
            ));
        }
        Ok(BSplineSurf {
            deg,
            count: [nu, nv],
            knots,
            cw,
            rational,
        })
    }

    /// Degrees (p, q).
    pub fn degrees(&self) -> (usize, usize) {
        (self.deg[0], self.deg[1])
    }

    /// Knot span k (t_k ≤ u < t_{k+1}, non-empty) in direction d; the end spans extrapolate.
    #[inline]
    fn span(&self, d: usize, u: f64) -> usize {
        let (p, n, t) = (self.deg[d], self.count[d], &self.knots[d]);
        let mut k = (p + t[p + 1..n].partition_point(|&x| x <= u)).min(n - 1);
        while k > p && t[k] >= t[k + 1] {
            k -= 1;
        }
        while k < n - 1 && t[k] >= t[k + 1] {
            k += 1;
        }
        k
    }

    /// Homogeneous sums S_kl = Σ N_i^(k) M_j^(l) P^w_ij for (k, l) ∈ {00, 10, 01, 20, 11, 02}.
    #[inline]
    #[allow(clippy::needless_range_loop)] // index arithmetic on spans reads best as loops
    fn homogeneous<const M: usize>(&self, u: f64, v: f64) -> [[f64; 4]; 6] {
        let (p, q) = (self.deg[0], self.deg[1]);
        let (ku, kv) = (self.span(0, u), self.span(1, v));
        let mut nu = [[0.0; M]; 3];
        let mut nv = [[0.0; M]; 3];
        basis_ders(&self.knots[0], ku, p, u, &mut nu);
        basis_ders(&self.knots[1], kv, q, v, &mut nv);
        let mut s = [[0.0; 4]; 6];
        for i in 0..=p {
            let row = (ku - p + i) * self.count[1] + kv - q;
            let mut r = [[0.0; 4]; 3]; // Σ_j M^(l)_j P_ij, l = 0, 1, 2
            for j in 0..=q {
                let c = &self.cw[row + j];
                for (l, rl) in r.iter_mut().enumerate() {
                    for (x, cx) in rl.iter_mut().zip(c) {
                        *x += nv[l][j] * cx;
                    }
                }
            }
            for c in 0..4 {
                s[0][c] += nu[0][i] * r[0][c];
                s[1][c] += nu[1][i] * r[0][c];
                s[2][c] += nu[0][i] * r[1][c];
                s[3][c] += nu[2][i] * r[0][c];
                s[4][c] += nu[1][i] * r[1][c];
                s[5][c] += nu[0][i] * r[2][c];
            }
        }
        s
    }
}

/// Non-zero B-spline basis functions N_{k−p..k, p}(u) (Piegl & Tiller A2.2).
#[inline]
fn basis<const M: usize>(t: &[f64], k: usize, p: usize, u: f64, n: &mut [f64; M]) {
    let mut left = [0.0; M];
    let mut right = [0.0; M];
    n[0] = 1.0;
    for j in 1..=p {
        left[j] = u - t[k + 1 - j];
        right[j] = t[k + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = n[r] / (right[r + 1] + left[j - r]);
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
    }
}

/// Non-zero B-spline basis functions N_{k−p..k, p}(u) and their first two derivatives in
/// `ders[0..3][0..=p]` (Piegl & Tiller A2.3; knot span k must be non-empty).
#[inline]
fn basis_ders<const M: usize>(t: &[f64], k: usize, p: usize, u: f64, ders: &mut [[f64; M]; 3]) {
    let mut ndu = [[0.0; M]; M];
    let mut left = [0.0; M];
    let mut right = [0.0; M];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = u - t[k + 1 - j];
        right[j] = t[k + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j][r] = right[r + 1] + left[j - r]; // knot differences (> 0 on a non-empty span)
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for j in 0..=p {
        ders[0][j] = ndu[j][p];
    }
    let nd = p.min(2);
    let mut a = [[0.0; M]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0, 1);
        a[0][0] = 1.0;
        for kk in 1..=nd {
            let mut d = 0.0;
            let rk = r as isize - kk as isize;
            let pk = p - kk;
            if rk >= 0 {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk as usize];
                d = a[s2][0] * ndu[rk as usize][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if r as isize - 1 <= pk as isize {
                kk - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                d += a[s2][j] * ndu[idx][pk];
            }
            if r <= pk {
                a[s2][kk] = -a[s1][kk - 1] / ndu[pk + 1][r];
                d += a[s2][kk] * ndu[r][pk];
            }
            ders[kk][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
        for row in ders.iter_mut().skip(nd + 1) {
            row[r] = 0.0; // derivatives above the degree vanish
        }
    }
    let mut f = p as f64;
    for (kk, row) in ders.iter_mut().enumerate().take(nd + 1).skip(1) {
        for x in row.iter_mut().take(p + 1) {
            *x *= f;
        }
        f *= (p - kk) as f64;
    }
}

impl Surface for BSplineSurf {
    fn breaks(&self) -> (Vec<f64>, Vec<f64>) {
        let interior = |t: &[f64]| {
            let mut k: Vec<f64> = t.iter().copied().filter(|&x| x > 0.0 && x < 1.0).collect();
            k.dedup();
            k
        };
        (interior(&self.knots[0]), interior(&self.knots[1]))
    }

    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let top = self.deg[0].max(self.deg[1]);
        let s = if top < CUBIC {
            self.homogeneous::<CUBIC>(u, v)
        } else if top < SMALL {
            self.homogeneous::<SMALL>(u, v)
        } else {
            self.homogeneous::<LARGE>(u, v)
        };
        let v3 = |c: &[f64; 4]| Vec3::new(c[0], c[1], c[2]);
        // Derivatives with respect to the normalized parameters already (normalized knots).
        let [a, au, av, auu, auv, avv] = s.map(|c| v3(&c));
        if !self.rational {
            return SurfacePoint {
                x: a,
                xu: au,
                xv: av,
                xuu: auu,
                xuv: auv,
                xvv: avv,
            };
        }
        let [w, wu, wv, wuu, wuv, wvv] = s.map(|c| c[3]);
        let x = a / w;
        let xu = (au - x * wu) / w;
        let xv = (av - x * wv) / w;
        SurfacePoint {
            x,
            xu,
            xv,
            xuu: (auu - xu * (2.0 * wu) - x * wuu) / w,
            xuv: (auv - xv * wu - xu * wv - x * wuv) / w,
            xvv: (avv - xv * (2.0 * wv) - x * wvv) / w,
        }
    }

    fn point(&self, u: f64, v: f64) -> Vec3 {
        let top = self.deg[0].max(self.deg[1]);
        if top < CUBIC {
            self.point_with::<CUBIC>(u, v)
        } else if top < SMALL {
            self.point_with::<SMALL>(u, v)
        } else {
            self.point_with::<LARGE>(u, v)
        }
    }
}

impl BSplineSurf {
    /// [`Surface::point`] with scratch arrays of size `M` (> both degrees).
    fn point_with<const M: usize>(&self, u: f64, v: f64) -> Vec3 {
        let (p, q) = (self.deg[0], self.deg[1]);
        let (ku, kv) = (self.span(0, u), self.span(1, v));
        let mut nu = [0.0; M];
        let mut nv = [0.0; M];
        basis(&self.knots[0], ku, p, u, &mut nu);
        basis(&self.knots[1], kv, q, v, &mut nv);
        let mut s = [0.0; 4];
        for (i, &bu) in nu.iter().enumerate().take(p + 1) {
            let row = (ku - p + i) * self.count[1] + kv - q;
            let mut r = [0.0; 4];
            for (c, &bv) in self.cw[row..=row + q].iter().zip(&nv) {
                for (x, cx) in r.iter_mut().zip(c) {
                    *x += bv * cx;
                }
            }
            for (x, rx) in s.iter_mut().zip(r) {
                *x += bu * rx;
            }
        }
        if self.rational {
            Vec3::new(s[0] / s[3], s[1] / s[3], s[2] / s[3])
        } else {
            Vec3::new(s[0], s[1], s[2])
        }
    }
}

#[path = "bspline_split.rs"]
mod split;

#[cfg(test)]
#[path = "bspline_tests.rs"]
mod tests;
