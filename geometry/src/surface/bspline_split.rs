//! A B-spline surface cut along its C0 iso-lines into pieces (no knot insertion in the cut: a knot of
//! multiplicity ≥ the degree already makes the surface interpolate a row of control points
//! there, so each piece is a subset of the control net with its knots clamped at the cut);
//! a cut elsewhere first raises its knot to that multiplicity (Boehm's insertion).

use super::BSplineSurf;
use crate::GeometryError;

impl BSplineSurf {
    /// Interior knots of direction `d` (0: u, 1: v; normalized to [0, 1], increasing,
    /// distinct) of multiplicity at least the degree: iso-lines across which the surface is
    /// at most C0 (it may turn there, or have a gap if the multiplicity exceeds the degree and
    /// the two rows of control points differ).
    pub fn c0_knots(&self, d: usize) -> Vec<f64> {
        let (p, t) = (self.deg[d], &self.knots[d]);
        let mut out = Vec::new();
        let mut k = 0;
        while k < t.len() {
            let m = t[k..].iter().take_while(|x| **x == t[k]).count();
            if t[k] > 0.0 && t[k] < 1.0 && m >= p {
                out.push(t[k]);
            }
            k += m;
        }
        out
    }

    /// The surface cut along the iso-lines of direction `d` at the knots `cuts` (values of
    /// [`BSplineSurf::c0_knots`], increasing) into `cuts.len() + 1` pieces in parameter
    /// order, each reparametrized to [0, 1] in `d` (the other direction unchanged). A piece
    /// evaluates to the surface's own points: the same control points and basis functions.
    ///
    /// # Errors
    /// A cut that is not an interior knot of multiplicity between the degree and the degree
    /// + 1, or cuts not increasing.
    pub fn split_at(&self, d: usize, cuts: &[f64]) -> Result<Vec<BSplineSurf>, GeometryError> {
        let (p, t) = (self.deg[d], &self.knots[d]);
        let bad = |m: String| Err(GeometryError::Invalid(format!("B-spline split: {m}")));
        if cuts.windows(2).any(|w| w[1] <= w[0]) {
            return bad("cuts must increase".into());
        }
        // Each cut's run of knots: first index and multiplicity.
        let mut runs = Vec::with_capacity(cuts.len());
        for &c in cuts {
            let r = t.partition_point(|x| *x < c);
            let m = t[r..].iter().take_while(|x| **x == c).count();
            if !(c > 0.0 && c < 1.0) || m < p || m > p + 1 {
                return bad(format!(
                    "{c} is not an interior knot of multiplicity {p} or {}",
                    p + 1
                ));
            }
            runs.push((r, m));
        }
        let mut pieces = Vec::with_capacity(cuts.len() + 1);
        for k in 0..=cuts.len() {
            let (mut knots, first) = match k.checked_sub(1).map(|a| (cuts[a], runs[a])) {
                None => (Vec::new(), 0),
                Some((c, (r, m))) => (vec![c; p + 1], r + m - p - 1),
            };
            let from = k.checked_sub(1).map_or(0, |a| runs[a].0 + runs[a].1);
            match runs.get(k) {
                None => knots.extend_from_slice(&t[from..]),
                Some(&(r, _)) => {
                    knots.extend_from_slice(&t[from..r]);
                    knots.extend(std::iter::repeat_n(cuts[k], p + 1));
                }
            }
            let n = knots.len() - p - 1;
            let (a, b) = (knots[p], knots[n]);
            for x in &mut knots {
                *x = (*x - a) / (b - a);
            }
            let mut count = self.count;
            count[d] = n;
            let nv = self.count[1];
            let cw: Vec<[f64; 4]> = (0..count[0])
                .flat_map(|i| (0..count[1]).map(move |j| (i, j)))
                .map(|(i, j)| {
                    if d == 0 {
                        self.cw[(first + i) * nv + j]
                    } else {
                        self.cw[i * nv + first + j]
                    }
                })
                .collect();
            let mut all = self.knots.clone();
            all[d] = knots;
            pieces.push(BSplineSurf {
                deg: self.deg,
                count,
                knots: all,
                cw,
                rational: self.rational,
            });
        }
        Ok(pieces)
    }

    /// The same surface with the knot `c` (normalized, interior) of direction `d` raised to
    /// multiplicity at least the degree by Boehm's knot insertion on the homogeneous control
    /// points, so that [`BSplineSurf::split_at`] can cut at `c` (a C0 iso-line of the new
    /// representation; the surface is unchanged up to round-off).
    ///
    /// # Errors
    /// `c` outside (0, 1).
    pub fn with_c0_knot(&self, d: usize, c: f64) -> Result<BSplineSurf, GeometryError> {
        if !(c > 0.0 && c < 1.0) {
            return Err(GeometryError::Invalid(format!(
                "B-spline knot insertion: {c} is not inside (0, 1)"
            )));
        }
        let p = self.deg[d];
        let mut s = self.clone();
        loop {
            let t = &s.knots[d];
            let have = t.iter().filter(|x| **x == c).count();
            if have >= p {
                return Ok(s);
            }
            // the knot span t[k] ≤ c < t[k + 1]
            let k = t.partition_point(|x| *x <= c) - 1;
            let alpha: Vec<f64> = (k + 1 - p..=k)
                .map(|i| (c - t[i]) / (t[i + p] - t[i]))
                .collect();
            let (n, other) = (s.count[d], s.count[1 - d]);
            let at = |cw: &[[f64; 4]], i: usize, j: usize, nv: usize| {
                if d == 0 {
                    cw[i * nv + j]
                } else {
                    cw[j * nv + i]
                }
            };
            let mut count = s.count;
            count[d] = n + 1;
            let (nv_old, nv_new) = (s.count[1], count[1]);
            let mut cw = vec![[0.0; 4]; count[0] * count[1]];
            for j in 0..other {
                for i in 0..=n {
                    let q = if i + p <= k {
                        at(&s.cw, i, j, nv_old)
                    } else if i > k {
                        at(&s.cw, i - 1, j, nv_old)
                    } else {
                        let a = alpha[i + p - k - 1];
                        let (lo, hi) = (at(&s.cw, i - 1, j, nv_old), at(&s.cw, i, j, nv_old));
                        std::array::from_fn(|m| (1.0 - a) * lo[m] + a * hi[m])
                    };
                    if d == 0 {
                        cw[i * nv_new + j] = q;
                    } else {
                        cw[j * nv_new + i] = q;
                    }
                }
            }
            s.knots[d].insert(k + 1, c);
            s.count = count;
            s.cw = cw;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::testutil::Rng;
    use super::*;
    use crate::surface::Surface;
    use crate::Vec3;
    use truck_geometry::prelude::{BSplineSurface, KnotVec, NurbsSurface, Vector4};

    /// NURBS of degrees 2 × 3 on [1, 3] × [0, 2]: in u a double knot (C0) at 1.6, a triple
    /// one (a break: full multiplicity) at 2.2 and a simple one at 2.6; in v a triple knot
    /// (C0) at 0.5.
    fn surface() -> BSplineSurf {
        let mut rng = Rng::new(7);
        let tu = vec![1.0, 1.0, 1.0, 1.6, 1.6, 2.2, 2.2, 2.2, 2.6, 3.0, 3.0, 3.0];
        let tv = vec![0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 2.0, 2.0, 2.0, 2.0];
        let (nu, nv) = (tu.len() - 3, tv.len() - 4);
        let ctrl: Vec<Vec<Vector4>> = (0..nu)
            .map(|i| {
                (0..nv)
                    .map(|j| {
                        let w = rng.range(0.5, 2.0);
                        let z = rng.range(-1.0, 1.0);
                        Vector4::new(w * i as f64, w * j as f64, w * z, w)
                    })
                    .collect()
            })
            .collect();
        let s = BSplineSurface::new((KnotVec::from(tu), KnotVec::from(tv)), ctrl);
        BSplineSurf::from_truck_nurbs(&NurbsSurface::new(s)).unwrap()
    }

    #[test]
    fn c0_knots_are_those_of_multiplicity_at_least_the_degree() {
        let s = surface();
        let u: Vec<f64> = s.c0_knots(0).iter().map(|t| 1.0 + 2.0 * t).collect();
        let v: Vec<f64> = s.c0_knots(1).iter().map(|t| 2.0 * t).collect();
        assert_eq!(u.len(), 2);
        assert!(
            (u[0] - 1.6).abs() < 1e-15 && (u[1] - 2.2).abs() < 1e-15,
            "{u:?}"
        );
        assert!(v.len() == 1 && (v[0] - 0.5).abs() < 1e-15, "{v:?}");
    }

    #[test]
    fn pieces_evaluate_to_the_surface() {
        let s = surface();
        let cu = s.c0_knots(0);
        let cv = s.c0_knots(1);
        let mut rng = Rng::new(3);
        let close = |a: Vec3, b: Vec3| (a - b).norm() <= 1e-13 * (1.0 + b.norm());
        let rows = s.split_at(0, &cu).unwrap();
        assert_eq!(rows.len(), 3);
        let bounds = [0.0, cu[0], cu[1], 1.0];
        for (k, row) in rows.iter().enumerate() {
            let (a, b) = (bounds[k], bounds[k + 1]);
            let pieces = row.split_at(1, &cv).unwrap();
            let vb = [0.0, cv[0], 1.0];
            for (l, piece) in pieces.iter().enumerate() {
                let (c, d) = (vb[l], vb[l + 1]);
                for _ in 0..200 {
                    let (x, y) = (rng.range(0.0, 1.0), rng.range(0.0, 1.0));
                    let (u, v) = (a + x * (b - a), c + y * (d - c));
                    let (e, f) = (piece.eval(x, y), s.eval(u, v));
                    assert!(close(e.x, f.x), "piece ({k}, {l}) at ({x}, {y})");
                    assert!(close(e.xu, f.xu * (b - a)) && close(e.xv, f.xv * (d - c)));
                }
            }
            // The pieces meet along the C0 cut in v; they share its control points.
            for y in [0.0, 0.3, 1.0] {
                assert!(close(pieces[0].point(y, 1.0), pieces[1].point(y, 0.0)));
            }
        }
        // Across the double (C0) knot the rows meet; across the triple one they need not.
        for y in [0.0, 0.25, 0.7, 1.0] {
            assert!(close(rows[0].point(1.0, y), rows[1].point(0.0, y)));
        }
        assert!(!close(rows[1].point(1.0, 0.3), rows[2].point(0.0, 0.3)));
    }

    #[test]
    fn an_inserted_c0_knot_leaves_the_surface_and_splits_it() {
        let s = surface();
        let mut rng = Rng::new(11);
        let close = |a: Vec3, b: Vec3| (a - b).norm() <= 1e-13 * (1.0 + b.norm());
        // inside a span, at a simple knot (u = 2.6 of degree 2), in v (degree 3)
        for (d, c) in [(0, 0.37), (0, 0.8), (1, 0.61), (1, 0.1)] {
            let t = s.with_c0_knot(d, c).unwrap();
            assert!(t.c0_knots(d).contains(&c), "{d} {c}");
            for _ in 0..200 {
                let (u, v) = (rng.range(0.0, 1.0), rng.range(0.0, 1.0));
                let (e, f) = (t.eval(u, v), s.eval(u, v));
                assert!(close(e.x, f.x) && close(e.xu, f.xu) && close(e.xv, f.xv));
            }
            let pieces = t.split_at(d, &[c]).unwrap();
            for y in [0.0, 0.4, 1.0] {
                let (a, b) = if d == 0 {
                    (pieces[0].point(1.0, y), s.point(c, y))
                } else {
                    (pieces[0].point(y, 1.0), s.point(y, c))
                };
                assert!(close(a, b), "{d} {c} {y}");
            }
        }
        assert!(s.with_c0_knot(0, 1.0).is_err() && s.with_c0_knot(1, 0.0).is_err());
    }

    #[test]
    fn split_refuses_knots_that_are_not_c0() {
        let s = surface();
        // u = 2.6 (a simple knot of a degree 2 direction), a non-knot, unordered cuts.
        for cuts in [vec![0.8], vec![0.5], vec![0.6, 0.3]] {
            assert!(s.split_at(0, &cuts).is_err(), "{cuts:?}");
        }
    }
}
