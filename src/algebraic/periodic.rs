//! The algebraic transformation, start grid and control functions [19, 20] of a block that is
//! periodic in ξ (an O-grid whose cut E1 = E2 floats, [`crate::elliptic::periodic`]).
//!
//! In a periodic direction there are no ξ = const boundaries: the cut is not a boundary, its
//! nodes are unknowns. What the straight-line transformation [5, 6] still takes from it is
//! its distribution: t_E1 = t_E2 = the normalized arclength of the cut's given nodes, the
//! same function on both copies of the seam, so t = t_cut(η) on every ξ-line and
//! s = s_E3(ξ) (1 − t) + s_E4(ξ) t. The control functions [19] follow from this (s, t) by
//! central differences that wrap around the seam: s jumps by 1 across the seam (an
//! angle-like coordinate), so the node west of column 0 is column N − 1 with s − 1. The
//! cut's distribution thus sets the spacing away from E3 (a wall's first spacing, as on a
//! fixed cut); where its nodes lie is not used.
//!
//! Why not t = η: without the cut's clustering nothing controls the spacing normal to E3,
//! and about a NACA0012 with a sharp trailing edge the grid then folds at the trailing edge
//! (cells 0.003 along the wall, 0.05 across it: Picard stalls and diverges, measured).

use crate::algebraic::blend::Blend;
use crate::algebraic::control2d::Control2;
use crate::algebraic::transform::ParamGrid;
use crate::algebraic::{ControlKind, Controls};
use crate::grid::arclength::normalized_arclength;
use crate::grid::boundary::Boundary2;
use crate::grid::{Edge, Grid2};
use rayon::prelude::*;

/// The periodic straight-line (s, t) grid: t = t_cut(η), the normalized arclength of the
/// cut E1 (= E2), and s interpolated linearly in t between the normalized arclengths of E3
/// and E4.
pub fn periodic_param<const D: usize>(b: &Boundary2<D>) -> ParamGrid {
    periodic_blend(
        &normalized_arclength(b.edge(Edge::E3)),
        &normalized_arclength(b.edge(Edge::E4)),
        &normalized_arclength(b.edge(Edge::E1)),
        Blend::Linear,
    )
}

/// The (s, t) grid of a periodic block from the edge functions `s3`, `s4` of E3 and E4 and
/// the cut's `t_cut`: t = t_cut(η) on every ξ-line and s = s3(ξ) B0(t) + s4(ξ) B1(t), eqs.
/// [47]–[49] with t independent of s (`bl` linear: the straight-line map; zero slope at an
/// orthogonal side: Section 2.4, [`crate::elliptic::periodic_orthogonal`]).
pub fn periodic_blend(s3: &[f64], s4: &[f64], t_cut: &[f64], bl: Blend) -> ParamGrid {
    let (ni, nj) = (s3.len(), t_cut.len());
    let mut s = Vec::with_capacity(ni * nj);
    let mut t = Vec::with_capacity(ni * nj);
    for (j, &tv) in t_cut.iter().enumerate() {
        let w = bl.b1(tv).0;
        for i in 0..ni {
            s.push(if j == 0 {
                s3[i]
            } else if j + 1 == nj {
                s4[i]
            } else {
                s3[i] * (1.0 - w) + s4[i] * w
            });
            t.push(tv);
        }
    }
    ParamGrid::from_parts(ni, nj, s, t)
}

/// The start grid of a periodic block: along every ξ = const line the straight segment from
/// E3 to E4, nodes at the cut's normalized arclength t_cut (the transfinite grid between the
/// two η boundaries). Column N is column 0 bit for bit.
pub fn periodic_start<const D: usize>(b: &Boundary2<D>) -> Grid2<D> {
    let (ni, nj) = (b.ni(), b.nj());
    let (e3, e4) = (b.edge(Edge::E3), b.edge(Edge::E4));
    let tc = normalized_arclength(b.edge(Edge::E1));
    let mut g = Grid2::<D>::from_fn(ni, nj, |i, j| {
        let i = if i + 1 == ni { 0 } else { i };
        let v = tc[j];
        std::array::from_fn(|c| {
            if j == 0 {
                e3[i][c]
            } else if j + 1 == nj {
                e4[i][c]
            } else {
                (1.0 - v) * e3[i][c] + v * e4[i][c]
            }
        })
    });
    close_seam(&mut g);
    g
}

/// Copies column 0 onto column N (the seam's two copies bit-identical).
pub fn close_seam<const D: usize>(g: &mut Grid2<D>) {
    let ni = g.ni();
    for c in g.coords_mut().iter_mut() {
        for row in c.chunks_mut(ni) {
            row[ni - 1] = row[0];
        }
    }
}

/// Control functions [19, 20] of a periodic (s, t) grid: as
/// [`Control2::from_algebraic`], at every node of the rows 1..M − 1 including the seam
/// (column N holds column 0's values), with the i-differences wrapping around (s − 1 west of
/// column 0).
pub fn periodic_control(pg: &ParamGrid) -> Control2 {
    let (ni, nj) = (pg.ni(), pg.nj());
    let nc = ni - 1;
    let mut p = vec![[0.0; 6]; ni * nj];
    p.par_chunks_mut(ni).enumerate().for_each(|(j, row)| {
        if j == 0 || j + 1 >= nj {
            return;
        }
        // value of f (period `per`) at column i + di − 1 of row jj, unwrapped around the seam
        let at = |f: &[f64], per: f64, i: usize, di: usize, jj: usize| {
            if i == 0 && di == 0 {
                f[nc - 1 + ni * jj] - per
            } else {
                f[i + di - 1 + ni * jj]
            }
        };
        for i in 0..nc {
            let d = |f: &[f64], per: f64| {
                let (w, c, e) = (at(f, per, i, 0, j), f[i + ni * j], at(f, per, i, 2, j));
                let (so, no) = (f[i + ni * (j - 1)], f[i + ni * (j + 1)]);
                let fx = 0.5 * (e - w);
                let fy = 0.5 * (no - so);
                let fxx = e - 2.0 * c + w;
                let fyy = no - 2.0 * c + so;
                let fxy = 0.25
                    * (at(f, per, i, 2, j + 1) - at(f, per, i, 0, j + 1) - at(f, per, i, 2, j - 1)
                        + at(f, per, i, 0, j - 1));
                (fx, fy, fxx, fxy, fyy)
            };
            let (sx, sy, sxx, sxy, syy) = d(&pg.s, 1.0);
            let (tx, ty, txx, txy, tyy) = d(&pg.t, 0.0);
            let det = sx * ty - sy * tx;
            let solve = |a: f64, b: f64| [-(ty * a - sy * b) / det, -(-tx * a + sx * b) / det];
            let p11 = solve(sxx, txx);
            let p12 = solve(sxy, txy);
            let p22 = solve(syy, tyy);
            row[i] = [p11[0], p11[1], p12[0], p12[1], p22[0], p22[1]];
        }
        row[nc] = row[0];
    });
    Controls::stored([ni, nj], p)
}

/// The control functions of a periodic block for the chosen kind.
pub fn periodic_control_for<const D: usize>(b: &Boundary2<D>, kind: ControlKind) -> Control2 {
    match kind {
        ControlKind::Algebraic => periodic_control(&periodic_param(b)),
        ControlKind::Laplace => Control2::zeros([b.ni(), b.nj()]),
    }
}

/// Rings for the tests of periodic blocks (here, in `elliptic::periodic_orthogonal` and in
/// `elliptic::wall2d`).
#[cfg(test)]
pub(crate) mod rings {
    use crate::grid::boundary::Boundary2;

    /// `n` nodes from 0 to `len`, geometric with first step `h`.
    pub(crate) fn geometric(n: usize, len: f64, h: f64) -> Vec<f64> {
        let sum = |r: f64| (0..n - 1).map(|k| h * r.powi(k as i32)).sum::<f64>();
        let (mut lo, mut hi) = (1.0, 2.0);
        while sum(hi) < len {
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if sum(mid) < len {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let r = 0.5 * (lo + hi);
        let mut out = vec![0.0];
        for k in 0..n - 1 {
            out.push(out[k] + h * r.powi(k as i32));
        }
        let last = out[n - 1];
        out.iter().map(|x| x * len / last).collect()
    }

    /// `ni` nodes round the ellipse x²/a² + y²/b² = 1 from (a, 0), uniform in its angle
    /// parameter, node N = node 0 (a circle for a = b).
    pub(crate) fn ellipse(ni: usize, a: f64, b: f64) -> Vec<[f64; 2]> {
        (0..ni)
            .map(|i| {
                let t = std::f64::consts::TAU * (i % (ni - 1)) as f64 / (ni - 1) as f64;
                [a * t.cos(), b * t.sin()]
            })
            .collect()
    }

    /// A ring between an ellipse (semi-axes 1, 0.3) and the circle of radius 5, periodic in
    /// i (E1 = E2 the cut along +x), `ni` × `nj` nodes, the cut geometric from `h`.
    pub(crate) fn ellipse_ring(ni: usize, nj: usize, h: f64) -> Boundary2<2> {
        let cut: Vec<[f64; 2]> = geometric(nj, 4.0, h)
            .iter()
            .map(|&r| [1.0 + r, 0.0])
            .collect();
        let (e3, e4) = (ellipse(ni, 1.0, 0.3), ellipse(ni, 5.0, 5.0));
        Boundary2::new([cut.clone(), cut, e3, e4], "ring").unwrap()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_circles_give_zero_control_and_a_polar_start() {
        // Two concentric circles with uniform nodes and a uniform cut: s = ξ, t = η, so every
        // control function vanishes, also at the seam (where s jumps by 1).
        let (ni, nj) = (17, 6);
        let circle = |r: f64| rings::ellipse(ni, r, r);
        let cut: Vec<[f64; 2]> = (0..nj)
            .map(|j| [1.0 + 2.0 * j as f64 / (nj - 1) as f64, 0.0])
            .collect();
        let b = Boundary2::new([cut.clone(), cut, circle(1.0), circle(3.0)], "ring").unwrap();
        let c = periodic_control_for(&b, ControlKind::Algebraic);
        assert!(c.p.iter().flatten().all(|v| v.abs() < 1e-12));
        let g = periodic_start(&b);
        for j in 0..nj {
            assert_eq!(g.point(0, j), g.point(ni - 1, j));
            let r = (g.point(3, j)[0].powi(2) + g.point(3, j)[1].powi(2)).sqrt();
            assert!((r - (1.0 + 2.0 * j as f64 / (nj - 1) as f64)).abs() < 1e-12);
        }
    }
}
