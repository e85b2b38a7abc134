//! Untangling of a planar grid whose discrete Winslow solution folds near a reentrant part
//! of its boundary (a CAD face's (u, v) parametrization, [`super::face`]): the continuous
//! Winslow map is one-to-one, its discretization on a coarse grid need not be.
//!
//! Interior nodes near the folded cells are moved one at a time (Gauss–Seidel order, fixed,
//! so the result is the same in every run) to the position that maximizes the smallest
//! corner Jacobian of the cells around them (Freitag & Plassmann's max-min untangling, 2000):
//! a corner Jacobian J = (c − b) × (a − b) of the corner triangle (a, b, c) is affine in each
//! of its nodes, so for one free node P the twelve corner Jacobians of its four cells are
//! affine functions g_k · P + h_k, and max_P min_k is a linear program in (P, t) whose
//! optimum is a vertex where three of them are equal. Boundary nodes never move.
//!
//! A block side collapsed to a point (a pole, or a CAD face's cusp gridded as a collapsed
//! side: [`collapsed_edges`]) makes the cells along it triangles: their two corners at the
//! point have a cell edge of zero length and are left out; the triangle is folded if one of
//! its other two corners is.

use crate::grid::boundary::collapsed_edges;
use crate::grid::{Edge, Grid2};

/// Block sides E1..E4 of `g` collapsed to a point ([`collapsed_edges`]).
fn poles(g: &Grid2<2>) -> [bool; 4] {
    let edges = Edge::ALL.map(|e| g.edge(e));
    collapsed_edges(edges.each_ref().map(|e| &e[..]))
}

/// The edge (k: from node k to node k + 1 of [`cell_nodes`]) of cell (i, j) on a collapsed
/// block side, if any, when it has zero length: the cell is a triangle and its corners k and
/// k + 1 (at the collapsed side's point) are not corners.
fn pole_edge(g: &Grid2<2>, poles: [bool; 4], i: usize, j: usize) -> Option<usize> {
    let (ni, nj) = (g.ni(), g.nj());
    let [e1, e2, e3, e4] = poles;
    let k = if e3 && j == 0 {
        0
    } else if e2 && i + 2 == ni {
        1
    } else if e4 && j + 2 == nj {
        2
    } else if e1 && i == 0 {
        3
    } else {
        return None;
    };
    let n = cell_nodes(ni, i, j);
    let (a, b) = (n[k], n[(k + 1) % 4]);
    let (x, y) = (g.coord(0), g.coord(1));
    (x[a] == x[b] && y[a] == y[b]).then_some(k)
}

/// Cells (i, j) (lower-left node) with a corner Jacobian ≤ −`tol` |a| |b| (the fold test of
/// the face's parametrization; `tol` lets a corner of 180° to rounding pass), in row order.
pub fn folded_cells(g: &Grid2<2>, tol: f64) -> Vec<(usize, usize)> {
    let (ni, nj) = (g.ni(), g.nj());
    let poles = poles(g);
    let mut bad = Vec::new();
    for j in 0..nj - 1 {
        for i in 0..ni - 1 {
            if cell_folded(g, i, j, tol, pole_edge(g, poles, i, j)) {
                bad.push((i, j));
            }
        }
    }
    bad
}

fn cell_nodes(ni: usize, i: usize, j: usize) -> [usize; 4] {
    [
        i + ni * j,
        i + 1 + ni * j,
        i + 1 + ni * (j + 1),
        i + ni * (j + 1),
    ]
}

/// Whether cell (i, j) folds; `pole` its zero-length edge on a collapsed side
/// ([`pole_edge`]), whose two corners are left out.
fn cell_folded(g: &Grid2<2>, i: usize, j: usize, tol: f64, pole: Option<usize>) -> bool {
    let (x, y) = (g.coord(0), g.coord(1));
    let n = cell_nodes(g.ni(), i, j);
    let corner = |k: usize| pole.is_none_or(|q| k != q && k != (q + 1) % 4);
    (0..4).filter(|&k| corner(k)).any(|k| {
        let (a, b, c) = (n[(k + 3) % 4], n[k], n[(k + 1) % 4]);
        let (ux, uy) = (x[c] - x[b], y[c] - y[b]);
        let (vx, vy) = (x[a] - x[b], y[a] - y[b]);
        let cross = ux * vy - uy * vx;
        let scale = (ux * ux + uy * uy).sqrt() * (vx * vx + vy * vy).sqrt();
        cross.partial_cmp(&(-tol * scale)) != Some(std::cmp::Ordering::Greater) || scale == 0.0
    })
}

/// The affine corner Jacobians g · P + h of the cells around interior node `p` as functions
/// of its position P: for a corner triangle in cyclic order (P, q, r),
/// J = P × (q − r) + q × r.
///
/// In a triangle on a collapsed side (`poles`, [`pole_edge`]) the corner at the side's point
/// (J ≡ 0) is replaced by the corner at p, which p always has there.
fn constraints(g: &Grid2<2>, i: usize, j: usize, poles: [bool; 4]) -> [([f64; 2], f64); 12] {
    let ni = g.ni();
    let (x, y) = (g.coord(0), g.coord(1));
    let p = i + ni * j;
    let mut out = [([0.0; 2], 0.0); 12];
    let mut m = 0;
    for (ci, cj) in [(i - 1, j - 1), (i, j - 1), (i, j), (i - 1, j)] {
        let n = cell_nodes(ni, ci, cj);
        let at = n.iter().position(|&q| q == p).expect("node of its cell");
        let pole = pole_edge(g, poles, ci, cj);
        // the three corners of this cell that involve p: at p, after p, before p
        for k in [at, (at + 1) % 4, (at + 3) % 4] {
            let k = match pole {
                Some(q) if k == q || k == (q + 1) % 4 => at,
                _ => k,
            };
            let tri = [n[(k + 3) % 4], n[k], n[(k + 1) % 4]];
            let s = tri.iter().position(|&q| q == p).expect("p in its corner");
            let (q, r) = (tri[(s + 1) % 3], tri[(s + 2) % 3]);
            let w = [x[q] - x[r], y[q] - y[r]];
            // P × w = Px wy − Py wx
            out[m] = ([w[1], -w[0]], x[q] * y[r] - y[q] * x[r]);
            m += 1;
        }
    }
    out
}

fn worst(c: &[([f64; 2], f64); 12], p: [f64; 2]) -> f64 {
    c.iter()
        .map(|(g, h)| g[0] * p[0] + g[1] * p[1] + h)
        .fold(f64::INFINITY, f64::min)
}

/// The max-min position of one node (or its current one if no vertex of the linear program
/// within `reach` of it is better).
fn best_position(c: &[([f64; 2], f64); 12], now: [f64; 2], reach: f64) -> [f64; 2] {
    let mut best = (worst(c, now), now);
    for k in 0..12 {
        for l in k + 1..12 {
            for m in l + 1..12 {
                let (gk, hk) = c[k];
                let (gl, hl) = c[l];
                let (gm, hm) = c[m];
                let a = [gk[0] - gl[0], gk[1] - gl[1], hl - hk];
                let b = [gk[0] - gm[0], gk[1] - gm[1], hm - hk];
                let det = a[0] * b[1] - a[1] * b[0];
                // |det| ≤ 1e-12 |a| |b| (nearly parallel lines), squared: no square roots in
                // this loop of 220 candidates per node (they were most of the time).
                let size2 = (a[0] * a[0] + a[1] * a[1]) * (b[0] * b[0] + b[1] * b[1]);
                if det * det <= 1e-24 * size2 || size2 == 0.0 {
                    continue;
                }
                let p = [
                    (a[2] * b[1] - a[1] * b[2]) / det,
                    (a[0] * b[2] - a[2] * b[0]) / det,
                ];
                let (dx, dy) = (p[0] - now[0], p[1] - now[1]);
                let d2 = dx * dx + dy * dy;
                if d2.is_nan() || d2 > reach * reach {
                    continue;
                }
                let v = worst(c, p);
                if v > best.0 {
                    best = (v, p);
                }
            }
        }
    }
    best.1
}

/// Sweeps without fewer folded cells than before after which [`untangle`] gives up.
const STALL: usize = 15;

/// A grid with more than one in this many cells folded (and more than [`HOPELESS_MIN`]) is not
/// untangled: on the 40-file STEP corpus no such (u, v) grid came out fold-free (the most that
/// did: 72 of 1024 cells), and their sweeps were half of the slowest file's time (each folded
/// more the longer it ran).
const HOPELESS: usize = 8;
const HOPELESS_MIN: usize = 64;

/// Moves interior nodes within two cells of a folded cell to their max-min positions, sweep
/// after sweep, until no cell is folded (by [`folded_cells`] with `tol`), `max_sweeps`
/// sweeps are done, or 15 sweeps in a row did not lower the fewest folded cells yet; not at all
/// if more than an eighth of the cells (and more than 64) are folded.
///
/// A grid it cannot untangle is left in its best state: the one with the fewest folded cells
/// met (the first of them; the grid as given if no sweep lowered the count), not the last
/// sweep's (sweeps that stall can fold a grid further). Returns the number of folded cells
/// left.
pub fn untangle(g: &mut Grid2<2>, tol: f64, max_sweeps: usize) -> usize {
    let (ni, nj) = (g.ni(), g.nj());
    let mut bad = folded_cells(g, tol);
    let hopeless = bad.len() > HOPELESS_MIN && bad.len() * HOPELESS > (ni - 1) * (nj - 1);
    if ni < 3 || nj < 3 || hopeless {
        return bad.len();
    }
    let (mut fewest, mut since) = (bad.len(), 0);
    // the best state so far (fewest folded cells), and the nodes free in a sweep
    let mut best = g.coords().clone();
    let mut free = vec![false; ni * nj];
    for _ in 0..max_sweeps {
        if bad.is_empty() || since >= STALL {
            break;
        }
        sweep(g, &bad, &mut free);
        bad = folded_cells(g, tol);
        if bad.len() < fewest {
            (fewest, since) = (bad.len(), 0);
            for (b, c) in best.iter_mut().zip(g.coords()) {
                b.copy_from_slice(c);
            }
        } else {
            since += 1;
        }
    }
    if since > 0 {
        for (c, b) in g.coords_mut().iter_mut().zip(&best) {
            c.copy_from_slice(b);
        }
    }
    fewest
}

/// One Gauss–Seidel sweep of [`untangle`]: the interior nodes within two cells of the cells
/// `bad` moved to their max-min positions; `free` is scratch of one flag per node.
fn sweep(g: &mut Grid2<2>, bad: &[(usize, usize)], free: &mut [bool]) {
    let (ni, nj) = (g.ni(), g.nj());
    let poles = poles(g);
    free.fill(false);
    for &(ci, cj) in bad {
        for j in cj.saturating_sub(2)..=(cj + 3).min(nj - 2) {
            for i in ci.saturating_sub(2)..=(ci + 3).min(ni - 2) {
                if i >= 1 && j >= 1 {
                    free[i + ni * j] = true;
                }
            }
        }
    }
    for j in 1..nj - 1 {
        for i in 1..ni - 1 {
            let p = i + ni * j;
            if !free[p] {
                continue;
            }
            let c = constraints(g, i, j, poles);
            let (x, y) = (g.coord(0), g.coord(1));
            let now = [x[p], y[p]];
            let reach = [p - 1, p + 1, p - ni, p + ni]
                .iter()
                .map(|&q| (x[q] - now[0]).hypot(y[q] - now[1]))
                .fold(0.0, f64::max);
            let q = best_position(&c, now, 2.0 * reach);
            let xy = g.coords_mut();
            xy[0][p] = q[0];
            xy[1][p] = q[1];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 9 × 9 grid of a square whose interior nodes are thrown about by up to a cell (a fixed
    /// seed): 33 folded cells, then, sweep after sweep, 15 14 5 3 3 5 7 2 2 2 **1** 2 2 2 …:
    /// the sweeps after the best state fold a cell again and stall at 2. The untangling
    /// returns the state with 1 folded cell (it used to return the last, with 2).
    #[test]
    fn a_grid_that_stays_folded_is_left_in_its_best_state() {
        let n = 9;
        let mut state = 32u64;
        let mut rnd = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64) / ((1u64 << 53) as f64) - 0.5
        };
        let mut g = Grid2::<2>::from_fn(n, n, |i, j| [i as f64, j as f64]);
        for j in 1..n - 1 {
            for i in 1..n - 1 {
                let p = i + n * j;
                g.coords_mut()[0][p] += 2.0 * rnd();
                g.coords_mut()[1][p] += 2.0 * rnd();
            }
        }
        assert_eq!(folded_cells(&g, 1e-9).len(), 33);
        // the sweeps themselves: the fewest folded cells (1) come before the last state (2)
        let mut h = g.clone();
        let mut free = vec![false; n * n];
        let mut counts = Vec::new();
        for _ in 0..30 {
            let bad = folded_cells(&h, 1e-9);
            sweep(&mut h, &bad, &mut free);
            counts.push(folded_cells(&h, 1e-9).len());
        }
        assert_eq!(counts.iter().min(), Some(&1));
        assert_eq!(counts.last(), Some(&2));
        // untangle returns the best state, its count true of the grid it leaves
        assert_eq!(untangle(&mut g, 1e-9, 100), 1);
        assert_eq!(folded_cells(&g, 1e-9).len(), 1);
        // a grid no sweep improves is left as it was given
        let mut h = g.clone();
        let before = g.clone();
        assert_eq!(untangle(&mut h, 1e-9, 100), 1);
        assert_eq!(h, before);
    }

    /// A 5 × 5 grid of the unit square with its centre node thrown outside its cells: four
    /// folded cells, untangled in one sweep, the centre back inside.
    #[test]
    fn a_node_thrown_out_of_its_cells_is_moved_back() {
        let mut g = Grid2::<2>::from_fn(5, 5, |i, j| [i as f64 / 4.0, j as f64 / 4.0]);
        let c = 2 + 5 * 2;
        g.coords_mut()[0][c] = 0.9;
        g.coords_mut()[1][c] = 0.1;
        assert!(!folded_cells(&g, 1e-9).is_empty());
        assert_eq!(untangle(&mut g, 1e-9, 20), 0);
        let (x, y) = (g.coord(0)[c], g.coord(1)[c]);
        assert!(
            (0.25..0.75).contains(&x) && (0.25..0.75).contains(&y),
            "{x} {y}"
        );
    }

    /// A square whose boundary nodes are fixed and whose interior nodes all start at one
    /// point: most cells folded or degenerate; untangled to none.
    #[test]
    fn a_collapsed_interior_is_untangled() {
        let n = 5;
        let mut g = Grid2::<2>::from_fn(n, n, |i, j| [i as f64, j as f64]);
        for j in 1..n - 1 {
            for i in 1..n - 1 {
                let p = i + n * j;
                g.coords_mut()[0][p] = 0.3;
                g.coords_mut()[1][p] = 0.2;
            }
        }
        assert!(folded_cells(&g, 1e-9).len() > 4);
        assert_eq!(untangle(&mut g, 1e-9, 50), 0);
    }

    /// A sector of 20° as a grid whose side E1 (i = 0) is one point, the apex: the cells along
    /// it are triangles, not folded (every corner at the apex has an edge of zero length, which
    /// made each of the 8 a folded cell before collapsed sides were known here). An interior
    /// node next to the apex thrown across the sector's edge folds its cells; the untangling
    /// moves it back (with the apex corners counted it could not: their J ≡ 0).
    #[test]
    fn cells_along_a_side_collapsed_to_a_point_are_triangles() {
        let n = 9;
        let sector = |i: usize, j: usize| {
            let (r, a) = (i as f64 / 8.0, (20.0f64).to_radians() * j as f64 / 8.0);
            [r * a.cos(), r * a.sin()]
        };
        let mut g = Grid2::<2>::from_fn(n, n, sector);
        assert_eq!(poles(&g), [true, false, false, false]);
        assert!(folded_cells(&g, 1e-9).is_empty());
        let p = 1 + n * 4;
        g.coords_mut()[1][p] = -0.05;
        let bad = folded_cells(&g, 1e-9);
        assert!(bad.contains(&(0, 3)), "{bad:?}"); // a triangle at the apex folds
        assert_eq!(untangle(&mut g, 1e-9, 20), 0);
        let (x, y) = (g.coord(0)[p], g.coord(1)[p]);
        assert!(y > 0.0 && y < x * (20.0f64).to_radians().tan(), "{x} {y}");
    }

    /// A 33 × 33 grid with a fifth of its cells folded (a band of rows mirrored) is returned as
    /// it is, its folded cells counted; with a few rows fewer folded it is worked on.
    #[test]
    fn a_grid_folded_in_more_than_an_eighth_of_its_cells_is_left_alone() {
        let folded_rows = |rows: usize| {
            let mut g = Grid2::<2>::from_fn(33, 33, |i, j| [i as f64, j as f64]);
            for j in 10..10 + rows {
                for i in 1..32 {
                    g.coords_mut()[1][i + 33 * j] = 20.0 - j as f64;
                }
            }
            g
        };
        let mut g = folded_rows(7);
        let before = g.clone();
        let n = folded_cells(&g, 1e-9).len();
        assert!(n * HOPELESS > 32 * 32 && n > HOPELESS_MIN, "{n}");
        assert_eq!(untangle(&mut g, 1e-9, 100), n);
        assert_eq!(g, before);
        let mut g = folded_rows(2);
        let n = folded_cells(&g, 1e-9).len();
        assert!(n * HOPELESS < 32 * 32, "{n}");
        assert!(untangle(&mut g, 1e-9, 100) < n);
    }
}
