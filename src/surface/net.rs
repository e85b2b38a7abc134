//! The bicubic Hermite control net of a block face lying on a model of several surfaces (a
//! CAD model's faces; the paper's wing–pylon patches, METHOD.md §5): the four edges sampled at
//! uniform arclength, the interior by transfinite interpolation of the edges [5, 6] moved onto
//! the model by closest-point projection. The net's Hermite surface is then gridded by the
//! Section 4 pipeline, so the grid depends on the model, not on this net's parametrization.

use crate::{Error, Result};
use ellipgrid_geometry::Vec3;
use rayon::prelude::*;

/// Where n stations at uniform arclength fall on a polyline: for each, the segment k and the
/// weight w of its end (the station is (1 − w) p_k + w p_(k+1)); the first station is the
/// first point, the last the last. Zero-length polylines put every station at the start.
pub fn uniform_stations(points: &[Vec3], n: usize) -> Vec<(usize, f64)> {
    let mut cum = Vec::with_capacity(points.len());
    let mut s = 0.0;
    cum.push(0.0);
    for w in points.windows(2) {
        s += (w[1] - w[0]).norm();
        cum.push(s);
    }
    let last = points.len().saturating_sub(2);
    let mut k = 0;
    (0..n)
        .map(|i| {
            if points.len() < 2 || s == 0.0 {
                return (0, 0.0);
            }
            if i + 1 == n {
                return (last, 1.0);
            }
            let target = s * i as f64 / (n - 1) as f64;
            while k < last && cum[k + 1] < target {
                k += 1;
            }
            let len = cum[k + 1] - cum[k];
            let w = if len > 0.0 {
                (target - cum[k]) / len
            } else {
                0.0
            };
            (k, w.clamp(0.0, 1.0))
        })
        .collect()
}

/// Linear interpolation of a polyline at stations of [`uniform_stations`].
pub fn at_stations(points: &[Vec3], stations: &[(usize, f64)]) -> Vec<Vec3> {
    stations
        .iter()
        .map(|&(k, w)| match points.get(k + 1) {
            Some(q) => points[k] * (1.0 - w) + q * w,
            None => points[k],
        })
        .collect()
}

/// The m × n net (i fastest) spanned by edges E1 (i = 0) and E2 (i = m − 1), n points each,
/// E3 (j = 0) and E4 (j = n − 1), m points each, all in index order and meeting at the
/// corners, points at uniform arclength: the edges kept, every interior point the transfinite
/// interpolation moved by `project` onto the model.
///
/// # Errors
/// [`Error::Input`] at `place` if the edges' lengths do not match, or naming the first net
/// point that `project` cannot place.
pub fn projected_net(
    [e1, e2, e3, e4]: [&[Vec3]; 4],
    project: &(dyn Fn(Vec3) -> Option<Vec3> + Sync),
    place: &str,
) -> Result<Vec<Vec3>> {
    let (m, n) = (e3.len(), e1.len());
    if m < 2 || n < 2 || e4.len() != m || e2.len() != n {
        return Err(Error::input(
            place,
            format!(
                "the net's edges have {}, {}, {}, {} points (E1, E2 must match, E3, E4 too; at least 2)",
                e1.len(),
                e2.len(),
                e3.len(),
                e4.len()
            ),
        ));
    }
    let (c00, c10, c01, c11) = (e3[0], e3[m - 1], e4[0], e4[m - 1]);
    let net: Vec<Option<Vec3>> = (0..m * n)
        .into_par_iter()
        .map(|q| {
            let (i, j) = (q % m, q / m);
            if j == 0 {
                return Some(e3[i]);
            }
            if j == n - 1 {
                return Some(e4[i]);
            }
            if i == 0 {
                return Some(e1[j]);
            }
            if i == m - 1 {
                return Some(e2[j]);
            }
            let (s, t) = (i as f64 / (m - 1) as f64, j as f64 / (n - 1) as f64);
            let x = e3[i] * (1.0 - t) + e4[i] * t + e1[j] * (1.0 - s) + e2[j] * s
                - (c00 * ((1.0 - s) * (1.0 - t))
                    + c10 * (s * (1.0 - t))
                    + c01 * ((1.0 - s) * t)
                    + c11 * (s * t));
            project(x)
        })
        .collect();
    net.into_iter()
        .enumerate()
        .map(|(q, p)| {
            p.ok_or_else(|| {
                Error::input(
                    place,
                    format!(
                        "net point ({}, {}) cannot be projected onto the model",
                        q % m,
                        q / m
                    ),
                )
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On the unit sphere, a net between four arcs: every point on the sphere, the edges kept,
    /// and on a great-circle polyline the stations split its length evenly.
    #[test]
    fn net_on_a_sphere() {
        let arc = |a: Vec3, b: Vec3, k: usize| -> Vec<Vec3> {
            (0..k)
                .map(|q| {
                    let t = q as f64 / (k - 1) as f64;
                    let p = a * (1.0 - t) + b * t;
                    p / p.norm()
                })
                .collect()
        };
        let dense = arc(Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), 2001);
        let st = uniform_stations(&dense, 5);
        let p = at_stations(&dense, &st);
        for (q, x) in p.iter().enumerate() {
            let angle = x.y.atan2(x.x);
            assert!(
                (angle - std::f64::consts::FRAC_PI_8 * q as f64).abs() < 1e-6,
                "{q}"
            );
        }
        let c = [
            Vec3::new(1.0, 0.2, 0.1),
            Vec3::new(0.3, 1.0, 0.1),
            Vec3::new(1.0, 0.2, 0.6),
            Vec3::new(0.3, 1.0, 0.7),
        ]
        .map(|p| p / p.norm());
        let (m, n) = (9, 7);
        let e = [
            arc(c[0], c[2], n),
            arc(c[1], c[3], n),
            arc(c[0], c[1], m),
            arc(c[2], c[3], m),
        ];
        let on_sphere = |p: Vec3| Some(p / p.norm());
        let net = projected_net([&e[0], &e[1], &e[2], &e[3]], &on_sphere, "test").unwrap();
        assert_eq!(net.len(), m * n);
        assert!(net.iter().all(|p| (p.norm() - 1.0).abs() < 1e-15));
        assert_eq!(net[m * (n - 1) + 3], e[3][3]);
        assert_eq!(net[m * 2 + m - 1], e[1][2]);
        let fail = |_: Vec3| None;
        let err = projected_net([&e[0], &e[1], &e[2], &e[3]], &fail, "test").unwrap_err();
        assert!(err.to_string().contains("net point (1, 1)"), "{err}");
    }
}
