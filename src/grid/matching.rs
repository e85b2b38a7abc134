//! Block sides that coincide node for node: the 1-to-1 interfaces of 2D blocks gridded apart
//! (the blocks of a CAD face with holes, which share their cuts bit for bit; faces of a solid
//! that share a CAD edge with the same nodes on it).
//!
//! Sides are paired whole (a side that matches part of another is a boundary side), forward or
//! reversed, when every node of one lies within `tol` of the corresponding node of the other.
//! A side shorter than `tol` (a pole) is never paired. Candidates are found through a hash of
//! the sides' end nodes on a lattice of spacing `2 tol`, so the search is linear in the sides.

use crate::grid::{Edge, Grid2};
use std::collections::HashMap;

/// One side of a 2D block: block index and edge.
pub type Side = (usize, Edge);

/// Two sides with the same nodes: `b`'s nodes run against `a`'s if `reversed`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SideMatch {
    pub a: Side,
    pub b: Side,
    pub reversed: bool,
}

/// The nodes of side `e` of `g`, with growing index.
pub fn side_nodes<const D: usize>(g: &Grid2<D>, e: Edge) -> Vec<[f64; D]> {
    let (ni, nj) = (g.ni(), g.nj());
    match e {
        Edge::E1 => (0..nj).map(|j| g.point(0, j)).collect(),
        Edge::E2 => (0..nj).map(|j| g.point(ni - 1, j)).collect(),
        Edge::E3 => (0..ni).map(|i| g.point(i, 0)).collect(),
        Edge::E4 => (0..ni).map(|i| g.point(i, nj - 1)).collect(),
    }
}

fn dist<const D: usize>(p: &[f64; D], q: &[f64; D]) -> f64 {
    p.iter()
        .zip(q)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt()
}

/// Lattice cell of a point (spacing `h`).
fn cell<const D: usize>(p: &[f64; D], h: f64) -> [i64; D] {
    std::array::from_fn(|c| (p[c] / h).floor() as i64)
}

/// The pairs of sides of `grids` whose nodes coincide within `tol` (module docs), each side in
/// at most one pair, in order of the first side (block, then E1 … E4).
pub fn matching_sides<const D: usize>(grids: &[&Grid2<D>], tol: f64) -> Vec<SideMatch> {
    let sides: Vec<(Side, Vec<[f64; D]>)> = grids
        .iter()
        .enumerate()
        .flat_map(|(b, g)| Edge::ALL.map(|e| ((b, e), side_nodes(g, e))))
        .collect();
    let h = 2.0 * tol.max(f64::MIN_POSITIVE);
    let length = |n: &[[f64; D]]| n.windows(2).map(|w| dist(&w[0], &w[1])).sum::<f64>();
    // Sides by the lattice cell of their first node.
    let mut by_cell: HashMap<[i64; D], Vec<usize>> = HashMap::new();
    for (s, (_, nodes)) in sides.iter().enumerate() {
        if length(nodes) > tol {
            by_cell.entry(cell(&nodes[0], h)).or_default().push(s);
        }
    }
    let mut taken = vec![false; sides.len()];
    let mut out = Vec::new();
    for (s, (side, nodes)) in sides.iter().enumerate() {
        if taken[s] || length(nodes) <= tol {
            continue;
        }
        let n = nodes.len();
        // b's first node lies at a's first node (forward) or at its last (reversed).
        let found = [(false, &nodes[0]), (true, &nodes[n - 1])]
            .into_iter()
            .find_map(|(reversed, end)| {
                let c = cell(end, h);
                neighbours(c)
                    .find_map(|nc| {
                        by_cell.get(&nc)?.iter().copied().find(|&t| {
                            let other = &sides[t].1;
                            t != s
                                && !taken[t]
                                && other.len() == n
                                && (0..n).all(|k| {
                                    let q = if reversed {
                                        &other[n - 1 - k]
                                    } else {
                                        &other[k]
                                    };
                                    dist(&nodes[k], q) <= tol
                                })
                        })
                    })
                    .map(|t| (t, reversed))
            });
        if let Some((t, reversed)) = found {
            taken[s] = true;
            taken[t] = true;
            out.push(SideMatch {
                a: *side,
                b: sides[t].0,
                reversed,
            });
        }
    }
    out
}

/// The 3^D lattice cells around `c` (c included).
fn neighbours<const D: usize>(c: [i64; D]) -> impl Iterator<Item = [i64; D]> {
    (0..3usize.pow(D as u32)).map(move |m| {
        let mut k = m;
        std::array::from_fn(|d| {
            let o = (k % 3) as i64 - 1;
            k /= 3;
            c[d] + o
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x0: f64, x1: f64, y0: f64, y1: f64, ni: usize, nj: usize) -> Grid2<3> {
        Grid2::<3>::from_fn(ni, nj, |i, j| {
            let (s, t) = (i as f64 / (ni - 1) as f64, j as f64 / (nj - 1) as f64);
            [x0 + (x1 - x0) * s, y0 + (y1 - y0) * t, 0.0]
        })
    }

    #[test]
    fn neighbouring_rectangles_share_their_common_side() {
        let a = rect(0.0, 1.0, 0.0, 1.0, 5, 4);
        let b = rect(1.0, 2.0, 0.0, 1.0, 3, 4);
        // c's E3 runs along a's E4 the other way: c is a upside down.
        let c = Grid2::<3>::from_fn(5, 3, |i, j| {
            let x = 1.0 - i as f64 / 4.0;
            [x, 2.0 - 0.5 * j as f64, 0.0]
        });
        let m = matching_sides(&[&a, &b, &c], 1e-12);
        assert_eq!(
            m,
            vec![
                SideMatch {
                    a: (0, Edge::E2),
                    b: (1, Edge::E1),
                    reversed: false
                },
                SideMatch {
                    a: (0, Edge::E4),
                    b: (2, Edge::E4),
                    reversed: true
                },
            ]
        );
    }

    #[test]
    fn different_counts_offsets_beyond_the_tolerance_and_poles_do_not_match() {
        let a = rect(0.0, 1.0, 0.0, 1.0, 5, 4);
        let b = rect(1.0, 2.0, 0.0, 1.0, 3, 5);
        let c = rect(1.0 + 1e-6, 2.0, 0.0, 1.0, 3, 4);
        assert!(matching_sides(&[&a, &b], 1e-9).is_empty());
        assert!(matching_sides(&[&a, &c], 1e-9).is_empty());
        assert_eq!(matching_sides(&[&a, &c], 1e-5).len(), 1);
        // Two triangles with a pole at the same point: their poles are not an interface.
        let tri = |y: f64| {
            Grid2::<3>::from_fn(3, 3, |i, j| {
                let t = j as f64 / 2.0;
                [(1.0 - t) * (i as f64 / 2.0), y * t, 0.0]
            })
        };
        let (p, q) = (tri(1.0), tri(-1.0));
        let m = matching_sides(&[&p, &q], 1e-12);
        assert_eq!(
            m,
            vec![SideMatch {
                a: (0, Edge::E3),
                b: (1, Edge::E3),
                reversed: false
            }]
        );
    }

    #[test]
    fn a_closed_band_is_an_interface_of_its_block_with_itself() {
        let g = Grid2::<3>::from_fn(9, 3, |i, j| {
            let a = std::f64::consts::TAU * i as f64 / 8.0;
            [a.cos(), a.sin(), j as f64]
        });
        let m = matching_sides(&[&g], 1e-12);
        assert_eq!(
            m,
            vec![SideMatch {
                a: (0, Edge::E1),
                b: (0, Edge::E2),
                reversed: false
            }]
        );
    }
}
