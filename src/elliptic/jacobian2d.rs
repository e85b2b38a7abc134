//! The Jacobian of the discrete 2D grid system [24] (planar, D = 2; minimal surfaces, D = 3),
//! for Newton's method ([`crate::elliptic::newton`]).
//!
//! At a node, [24] discretised as in [43, 44] reads, for coordinate c,
//!
//! ```text
//! L_c = P a_c + Q b_c + R c_c,   a_c = x_ξξ + P¹11 x_ξ + P²11 x_η,
//!                                b_c = 2 (x_ξη + P¹12 x_ξ + P²12 x_η),
//!                                c_c = x_ηη + P¹22 x_ξ + P²22 x_η   (all of x_c),
//! P = g22 = Σ_d η_d²,  Q = −g12 = −Σ_d ξ_d η_d,  R = g11 = Σ_d ξ_d²,
//! ξ_d = (x_d,E − x_d,W)/2,  η_d = (x_d,N − x_d,S)/2.
//! ```
//!
//! The Picard operator `A` (assembled by [`crate::elliptic::poisson2d::assemble`], rows
//! multiplied by −1) is the derivative with P, Q, R frozen. Differentiating P, Q, R too adds
//! the coupling
//!
//! ```text
//! G_c δ = Σ_d (2 c_c ξ_d − b_c η_d) δξ_d + (2 a_c η_d − b_c ξ_d) δη_d,
//! ```
//!
//! δξ_d, δη_d the central differences of the correction of coordinate d: it couples the
//! coordinates through the metric coefficients and reaches only the E, W, N, S neighbours.
//! The residual is `r = b − A x = L(x)`, so Newton's correction solves `(A − G) δ = r`;
//! the Picard step drops G. [`Coupling`] stores the 2 D² coefficients per node (with the
//! factor 1/2 of the central differences) and applies `J = A − G` to a correction.

use crate::algebraic::control2d::Control2;
use crate::grid::Grid2;
use crate::solve::multigrid::use_par;
use crate::solve::stencil9::Stencil9;
use rayon::prelude::*;

/// The coupling G of the Jacobian at one iterate, on the `nx × ny` interior nodes.
#[derive(Debug, Default)]
pub(crate) struct Coupling<const D: usize> {
    nx: usize,
    ny: usize,
    /// Per interior node, for every (c, d): [ξ-coefficient, η-coefficient] (times 1/2).
    pub(crate) g: Vec<f64>,
}

impl<const D: usize> Coupling<D> {
    /// Coefficients per node.
    const STRIDE: usize = 2 * D * D;

    /// The coupling of an `nx × ny` interior (zero until [`Coupling::linearize`]).
    pub fn new(nx: usize, ny: usize) -> Self {
        Coupling {
            nx,
            ny,
            g: vec![0.0; nx * ny * Self::STRIDE],
        }
    }

    /// The coefficients of G at iterate `x` with control functions `ctrl` (module docs).
    pub fn linearize(&mut self, x: &Grid2<D>, ctrl: &Control2) {
        let (ni, nx) = (x.ni(), self.nx);
        assert_eq!((x.ni() - 2, x.nj() - 2), (self.nx, self.ny));
        let xs = x.coords();
        self.g
            .par_chunks_mut(nx * Self::STRIDE)
            .enumerate()
            .for_each(|(jj, row)| {
                let j = jj + 1;
                for (ii, gn) in row.chunks_mut(Self::STRIDE).enumerate() {
                    let n = ii + 1 + ni * j;
                    let (e, w, no, so) = (n + 1, n - 1, n + ni, n - ni);
                    let k = ctrl.at(n);
                    let xi: [f64; D] = std::array::from_fn(|d| 0.5 * (xs[d][e] - xs[d][w]));
                    let eta: [f64; D] = std::array::from_fn(|d| 0.5 * (xs[d][no] - xs[d][so]));
                    for c in 0..D {
                        let f = &xs[c];
                        let xx = f[e] - 2.0 * f[n] + f[w];
                        let yy = f[no] - 2.0 * f[n] + f[so];
                        let xy = 0.25 * (f[no + 1] - f[no - 1] - f[so + 1] + f[so - 1]);
                        let a = xx + k[0] * xi[c] + k[1] * eta[c];
                        let b = 2.0 * (xy + k[2] * xi[c] + k[3] * eta[c]);
                        let cc = yy + k[4] * xi[c] + k[5] * eta[c];
                        for d in 0..D {
                            let q = 2 * (c * D + d);
                            gn[q] = 0.5 * (2.0 * cc * xi[d] - b * eta[d]);
                            gn[q + 1] = 0.5 * (2.0 * a * eta[d] - b * xi[d]);
                        }
                    }
                }
            });
    }

    /// `out = A − G_cc`: the Picard operator `a` with coordinate c's coupling to itself,
    /// couplings to the boundary dropped (the diagonal block of J for coordinate c).
    pub fn own_operator(&self, a: &Stencil9, c: usize, out: &mut Stencil9) {
        use crate::solve::stencil9::dir::{E, N, S, W};
        let (nx, ny) = (self.nx, self.ny);
        assert_eq!((out.nx(), out.ny()), (nx, ny));
        let q = 2 * (c * D + c);
        type Rows<'r> = (usize, (&'r mut [[f64; 9]], &'r [[f64; 9]]));
        let row = |(jj, (orow, arow)): Rows<'_>| {
            for (ii, (o, st)) in orow.iter_mut().zip(arow).enumerate() {
                let gn = &self.g[(ii + nx * jj) * Self::STRIDE + q..];
                *o = *st;
                if ii + 1 < nx {
                    o[E] -= gn[0];
                }
                if ii > 0 {
                    o[W] += gn[0];
                }
                if jj + 1 < ny {
                    o[N] -= gn[1];
                }
                if jj > 0 {
                    o[S] += gn[1];
                }
            }
        };
        if use_par(nx * ny) {
            let rows = out
                .coefs_mut()
                .par_chunks_mut(nx)
                .zip(a.coefs().par_chunks(nx));
            rows.enumerate().for_each(row);
        } else {
            let rows = out.coefs_mut().chunks_mut(nx).zip(a.coefs().chunks(nx));
            rows.enumerate().for_each(row);
        }
    }

    /// `w += G_cd z`: the coupling of coordinate c's rows to coordinate d's correction `z`.
    pub fn add_coupling(&self, c: usize, d: usize, z: &[f64], w: &mut [f64]) {
        let (nx, ny) = (self.nx, self.ny);
        let q = 2 * (c * D + d);
        let row = |(jj, wrow): (usize, &mut [f64])| {
            for (ii, wp) in wrow.iter_mut().enumerate() {
                let p = ii + nx * jj;
                let gn = &self.g[p * Self::STRIDE + q..];
                let e = if ii + 1 < nx { z[p + 1] } else { 0.0 };
                let w_ = if ii > 0 { z[p - 1] } else { 0.0 };
                let n = if jj + 1 < ny { z[p + nx] } else { 0.0 };
                let s = if jj > 0 { z[p - nx] } else { 0.0 };
                *wp += gn[0] * (e - w_) + gn[1] * (n - s);
            }
        };
        if use_par(nx * ny) {
            w.par_chunks_mut(nx).enumerate().for_each(row);
        } else {
            w.chunks_mut(nx).enumerate().for_each(row);
        }
    }

    /// `out = (A − G) v` for the Picard operator `a` at the same iterate; `v` and `out` hold
    /// the D coordinates' corrections one after the other (interior numbering, zero
    /// Dirichlet values outside).
    pub fn apply(&self, a: &Stencil9, v: &[f64], out: &mut [f64]) {
        let (nx, ny) = (self.nx, self.ny);
        let n = nx * ny;
        assert_eq!((a.nx(), a.ny()), (nx, ny));
        assert_eq!(v.len(), D * n);
        assert_eq!(out.len(), D * n);
        let vs: [&[f64]; D] = std::array::from_fn(|c| &v[c * n..(c + 1) * n]);
        let mut cols: Vec<std::slice::ChunksMut<'_, f64>> =
            out.chunks_mut(n).map(|o| o.chunks_mut(nx)).collect();
        let rows: Vec<[&mut [f64]; D]> = (0..ny)
            .map(|_| std::array::from_fn(|c| cols[c].next().expect("row of out")))
            .collect();
        let coefs = a.coefs();
        let row = |(jj, orow): (usize, [&mut [f64]; D])| {
            let inner_j = jj > 0 && jj + 1 < ny;
            // ii indexes the row of every coordinate, the operator and the coupling
            #[allow(clippy::needless_range_loop)]
            for ii in 0..nx {
                let p = ii + nx * jj;
                let st = &coefs[p];
                let gn = &self.g[p * Self::STRIDE..(p + 1) * Self::STRIDE];
                if inner_j && ii > 0 && ii + 1 < nx {
                    // all eight neighbours are unknowns: no bounds to check
                    for c in 0..D {
                        let f = vs[c];
                        let (lo, mid, hi) = (&f[p - nx - 1..], &f[p - 1..], &f[p + nx - 1..]);
                        let mut s = st[0] * lo[0]
                            + st[1] * lo[1]
                            + st[2] * lo[2]
                            + st[3] * mid[0]
                            + st[4] * mid[1]
                            + st[5] * mid[2]
                            + st[6] * hi[0]
                            + st[7] * hi[1]
                            + st[8] * hi[2];
                        for (d, fd) in vs.iter().enumerate() {
                            let q = 2 * (c * D + d);
                            s -= gn[q] * (fd[p + 1] - fd[p - 1])
                                + gn[q + 1] * (fd[p + nx] - fd[p - nx]);
                        }
                        orow[c][ii] = s;
                    }
                    continue;
                }
                let at = |f: &[f64], di: isize, dj: isize| -> f64 {
                    let (i, j) = (ii as isize + di, jj as isize + dj);
                    if i < 0 || j < 0 || i >= nx as isize || j >= ny as isize {
                        0.0
                    } else {
                        f[i as usize + nx * j as usize]
                    }
                };
                for c in 0..D {
                    let f = vs[c];
                    let mut s = 0.0;
                    for dj in -1..=1isize {
                        for di in -1..=1isize {
                            s += st[(di + 1 + 3 * (dj + 1)) as usize] * at(f, di, dj);
                        }
                    }
                    for (d, fd) in vs.iter().enumerate() {
                        let q = 2 * (c * D + d);
                        s -= gn[q] * (at(fd, 1, 0) - at(fd, -1, 0))
                            + gn[q + 1] * (at(fd, 0, 1) - at(fd, 0, -1));
                    }
                    orow[c][ii] = s;
                }
            }
        };
        if use_par(n) {
            rows.into_par_iter().enumerate().for_each(row);
        } else {
            rows.into_iter().enumerate().for_each(row);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elliptic::poisson2d::assemble;

    /// A wavy grid with non-zero control functions.
    fn case() -> (Grid2<2>, Control2) {
        let (ni, nj) = (9, 7);
        let g = Grid2::<2>::from_fn(ni, nj, |i, j| {
            let (s, t) = (i as f64 / 8.0, j as f64 / 6.0);
            [
                s + 0.1 * (3.0 * t).sin() + 0.05 * s * t,
                t + 0.08 * (2.0 * s).cos() * t + 0.02 * s * s,
            ]
        });
        let pg = crate::algebraic::transform::straight_line(
            &crate::grid::arclength::EdgeFunctions::arclength(
                &crate::grid::boundary::Boundary2::from_grid(&g, "w").unwrap(),
            ),
        );
        (g, Control2::from_algebraic(&pg))
    }

    /// The residual b − A x at `g` (interior numbering, coordinates one after the other).
    fn residual(g: &Grid2<2>, ctrl: &Control2) -> Vec<f64> {
        let (nx, ny) = (g.ni() - 2, g.nj() - 2);
        let mut a = Stencil9::zeros(nx, ny);
        let mut rhs = [vec![0.0; nx * ny], vec![0.0; nx * ny]];
        assemble(g, ctrl, &mut a, &mut rhs);
        let mut out = Vec::new();
        for (c, b) in rhs.iter().enumerate() {
            let xi: Vec<f64> = (0..nx * ny)
                .map(|p| g.coord(c)[(p % nx + 1) + g.ni() * (p / nx + 1)])
                .collect();
            let mut r = vec![0.0; nx * ny];
            a.residual(b, &xi, &mut r);
            out.extend(r);
        }
        out
    }

    /// J v = −(r(x + ε v) − r(x − ε v)) / 2ε to the truncation error of the difference.
    #[test]
    fn jacobian_matches_central_differences_of_the_residual() {
        let (g, ctrl) = case();
        let (nx, ny) = (g.ni() - 2, g.nj() - 2);
        let n = nx * ny;
        let v: Vec<f64> = (0..2 * n)
            .map(|q| ((q * 7919) % 13) as f64 / 13.0 - 0.4)
            .collect();
        let mut a = Stencil9::zeros(nx, ny);
        let mut rhs = [vec![0.0; n], vec![0.0; n]];
        assemble(&g, &ctrl, &mut a, &mut rhs);
        let mut cp = Coupling::<2>::new(nx, ny);
        cp.linearize(&g, &ctrl);
        let mut jv = vec![0.0; 2 * n];
        cp.apply(&a, &v, &mut jv);
        let eps = 1e-6;
        let moved = |sign: f64| {
            let mut h = g.clone();
            for c in 0..2 {
                for p in 0..n {
                    h.coord_mut(c)[(p % nx + 1) + g.ni() * (p / nx + 1)] +=
                        sign * eps * v[c * n + p];
                }
            }
            residual(&h, &ctrl)
        };
        let (rp, rm) = (moved(1.0), moved(-1.0));
        let scale = jv.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for q in 0..2 * n {
            let fd = -(rp[q] - rm[q]) / (2.0 * eps);
            assert!(
                (fd - jv[q]).abs() < 1e-7 * scale,
                "row {q}: {fd} vs {}",
                jv[q]
            );
        }
        // the coupling is not negligible: the Picard operator alone is off
        let mut av = vec![0.0; n];
        a.apply(&v[..n], &mut av);
        let off = (0..n).fold(0.0f64, |m, p| m.max((av[p] - jv[p]).abs()));
        assert!(off > 1e-3 * scale, "coupling {off}");
    }
}
