//! 180° block edges in the transformation of a volume block (the C–O grid's wing-plane edge).
//!
//! Where the two faces of a block that meet along a block edge lie in one plane (the wing
//! plane ahead of a C–O block's tip, where the plane ahead of the leading edge meets the plane
//! beyond the tip), the block's quarter cross-section is mapped onto a half-plane. With edge
//! functions proportional to arclength on both faces, the parameters (s, t, u), harmonic in
//! x for the control functions of [83, 84], behave like r log r at that edge: the grid lines
//! leave both faces far from their normal over many cells (up to 60° three cells away, on the
//! ONERA M6 C–O block). Edge functions that behave like the square root of the distance from
//! the edge make the map near it the conformal w ↦ w² of a quadrant onto a half-plane: the
//! grid lines leave both faces along the normal (parabolas) and the cells at the edge are
//! triangles of good shape. So the edge functions of the edges ending on a flat edge are
//! warped to σ ↦ √σ from that end (a smooth local blend to σ further away was tried and gave
//! up to 20° more at the first nodes off the edge). The faces' nodes are untouched; only
//! their parameters, and with them the control functions, change.

use crate::algebraic::bilinear3d::EdgeFunctions3;
use crate::grid::faces::Faces;

/// Smallest dihedral (degrees, the median along the edge) of a flat block edge.
pub const FLAT_DEG: f64 = 175.0;

/// The flat block edges of a block's faces (0-based edge numbers, E1 = 0): the median over the
/// edge's interior nodes of the angle between the two faces, measured normal to the edge
/// between their grid lines leaving it, is at least [`FLAT_DEG`].
pub fn flat_edges(faces: &Faces) -> Vec<usize> {
    (0..12)
        .filter(|&e| {
            let mut angles = dihedrals(faces, e);
            if angles.is_empty() {
                return false;
            }
            angles.sort_by(f64::total_cmp);
            angles[angles.len() / 2] >= FLAT_DEG
        })
        .collect()
}

/// The axis of edge e and the two other axes with the ends the edge sits at.
fn edge_axes(e: usize) -> (usize, [(usize, usize); 2]) {
    let d = e / 4;
    let (p, q) = match d {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    (d, [(p, e & 1), (q, (e >> 1) & 1)])
}

/// The edge of axis `d` at end `ep` of its first other axis and `eq` of the second.
fn edge_index(d: usize, ends: [(usize, usize); 2]) -> usize {
    let (lo, hi) = if ends[0].0 < ends[1].0 {
        (ends[0], ends[1])
    } else {
        (ends[1], ends[0])
    };
    4 * d + lo.1 + 2 * hi.1
}

/// Dihedral angles (degrees) at the interior nodes of edge e.
fn dihedrals(faces: &Faces, e: usize) -> Vec<f64> {
    let dims = faces.dims();
    let (d, [(p, ep), (q, eq)]) = edge_axes(e);
    let mut base = [0; 3];
    base[p] = if ep == 1 { dims[p] - 1 } else { 0 };
    base[q] = if eq == 1 { dims[q] - 1 } else { 0 };
    let inward = |n: [usize; 3], a: usize, at_end: usize| {
        let mut m = n;
        m[a] = if at_end == 1 { m[a] - 1 } else { m[a] + 1 };
        m
    };
    (1..dims[d] - 1)
        .map(|m| {
            let mut n = base;
            n[d] = m;
            let x = faces.boundary_point(n);
            let (mut before, mut after) = (n, n);
            before[d] -= 1;
            after[d] += 1;
            let t = sub(faces.boundary_point(after), faces.boundary_point(before));
            let perp = |v: [f64; 3]| {
                let s = dot(v, t) / dot(t, t);
                [v[0] - s * t[0], v[1] - s * t[1], v[2] - s * t[2]]
            };
            let u = perp(sub(faces.boundary_point(inward(n, p, ep)), x));
            let w = perp(sub(faces.boundary_point(inward(n, q, eq)), x));
            let c = dot(u, w) / (dot(u, u) * dot(w, w)).sqrt();
            c.clamp(-1.0, 1.0).acos().to_degrees()
        })
        .filter(|a| a.is_finite())
        .collect()
}

/// Warps `sigma` like the square root of the distance from its end `end` (0: σ = 0, 1: σ = 1).
fn warp_end(sigma: &mut [f64], end: usize) {
    for s in sigma.iter_mut() {
        *s = if end == 0 {
            s.max(0.0).sqrt()
        } else {
            1.0 - (1.0 - *s).max(0.0).sqrt()
        };
    }
}

/// Warps the edge functions of the edges that end on the flat edges `flat` (module docs).
pub fn warp_edge_functions(ef: &mut EdgeFunctions3, flat: &[usize]) {
    for &e in flat {
        let (d, [(p, ep), (q, eq)]) = edge_axes(e);
        // Edges of axis p at q's end (both ends along d) are warped near p's end, and the
        // other way round.
        for (a, ea, b, eb) in [(p, ep, q, eq), (q, eq, p, ep)] {
            for ed in 0..2 {
                let edge = edge_index(a, [(b, eb), (d, ed)]);
                let f = match a {
                    0 => &mut ef.s[edge % 4],
                    1 => &mut ef.t[edge % 4],
                    _ => &mut ef.u[edge % 4],
                };
                warp_end(f, ea);
            }
        }
    }
}

/// The edge functions of a block: normalized arclength [30–38], warped at flat edges.
pub fn edge_functions(faces: &Faces) -> EdgeFunctions3 {
    let mut ef = EdgeFunctions3::arclength(faces);
    warp_edge_functions(&mut ef, &flat_edges(faces));
    ef
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Grid3;

    /// The image of the unit square (a, b) under ζ = (a + i b)², extruded along y: a block
    /// whose faces F1 (ζ ≤ 0) and F6 (ζ ≥ 0) meet at 180° along E7 (i = 0, k = nk − 1), with
    /// the conformal grid's nodes on its faces.
    fn conformal_block(n: usize) -> Grid3 {
        Grid3::from_fn(n, 5, n, |i, j, k| {
            let (a, b) = (i as f64 / (n - 1) as f64, 1.0 - k as f64 / (n - 1) as f64);
            [a * a - b * b, 0.25 * j as f64, 2.0 * a * b]
        })
    }

    #[test]
    fn the_wing_plane_edge_of_a_c_o_block_is_flat_and_no_box_edge_is() {
        let faces = Faces::from_grid(&conformal_block(9));
        assert_eq!(flat_edges(&faces), vec![6]);
        let xs: Vec<f64> = (0..5).map(|v| v as f64 * 0.3).collect();
        let boxed = Faces::from_grid(&Grid3::rectilinear(&xs, &xs, &xs));
        assert!(flat_edges(&boxed).is_empty());
    }

    #[test]
    fn edges_ending_on_the_flat_edge_become_the_conformal_parameters() {
        // On F6 and F1 the nodes sit at a² and b² of the edge's length: the square root
        // gives back the conformal parameters a and b exactly, on exactly the four edges
        // that end on E7 (E3, E4 in s near 0; E9, E11 in u near 1).
        let n = 9;
        let faces = Faces::from_grid(&conformal_block(n));
        let plain = EdgeFunctions3::arclength(&faces);
        let ef = edge_functions(&faces);
        let unit: Vec<f64> = (0..n).map(|m| m as f64 / (n - 1) as f64).collect();
        for e in [2, 3] {
            for (v, w) in ef.s[e].iter().zip(&unit) {
                assert!((v - w).abs() < 1e-14, "E{} {:?}", e + 1, ef.s[e]);
            }
        }
        for e in [0, 2] {
            for (v, w) in ef.u[e].iter().zip(&unit) {
                assert!((v - w).abs() < 1e-14, "E{} {:?}", e + 9, ef.u[e]);
            }
        }
        assert_eq!((&ef.s[0], &ef.s[1]), (&plain.s[0], &plain.s[1]));
        assert_eq!((&ef.u[1], &ef.u[3]), (&plain.u[1], &plain.u[3]));
        assert_eq!(ef.t, plain.t);
    }
}
