//! Goal profiles of a wall correction from the side faces ([`WallProfiles::Faces`]).
//!
//! The wall correction ([`super::wall`]) moves every interior column towards a profile of
//! distances from the wall. By default that profile is the bilinear interpolation of the four
//! edges leaving the wall, and the side faces are corrected to it first. In a volume topology
//! a side face may be an interface gridded before the volume (the ONERA M6's trailing-edge
//! face between the wing and the wake volumes): it cannot be corrected, and its columns follow
//! its own 2D solution, not the edges' interpolation. The volume's columns next to it were then
//! moved to another profile than the face's (6 % higher at mid-height on the M6 wing), and the
//! grid lines crossing the face kinked by up to 130°.
//!
//! Here the profile of the column at wall node (p, q) (the wall's arclength parameters) is the
//! transfinite interpolation of the four side faces' columns,
//! d(p, q) = (1 − p) d_A0(q) + p d_A1(q) + (1 − q) d_B0(p) + q d_B1(p) − bilinear(edges),
//! which is each side face's own profile on that face and the edges' profile at the corners,
//! then scaled near the wall so that the first-cell height is the edges' interpolation (the
//! prescription): d_j ← d_j r^{w_j}, r = d_edges(1) / d(1), with the weight
//! w_j = e^{−(j − 1) / (R (m − 1))} falling in the node index j of the column's m nodes
//! ([`SCALE_REACH`] R: e-fold over half the column). A column whose interpolation is not
//! increasing keeps the edges' profile.
//!
//! The weight fades in the node index, not in the distance: with (1 − v)^3, v the column's
//! normalized distance, the scaling held to about a third of the column, a chord from the M6
//! wing, and there the columns next to a side face were r times that face's (r ≈ 1.6 next to
//! `te_up` and `ahead`, whose own first heights are not the prescription): a mean kink of 50°
//! across the trailing-edge face, 42° with the index weight (docs/ONERA_M6.md). A weight of
//! the layer index is the same for every column of a layer, so neighbouring columns keep
//! parallel layers (on the M6 case a weight of the distance ratio, (d(1)/d)^{1/3} or
//! (d(1)/d)^{1/4}, left 4120 or 3662 faces above 70° of OpenFOAM's non-orthogonality, most of
//! them in the first wall layers, against 2096 with the index weight of a comparable reach).

use crate::grid::faces::{block_node, face_dims, normal, tangents, Faces};

/// Reach R of the first-height scaling, as a fraction of the column's nodes (module docs):
/// the weight falls by e over half the column. Measured on the M6 case at full size (65
/// nodes per column, reaches of 4, 8, 16, 24 and 32 nodes): checkMesh's faces above 70°
/// non-orthogonality 5400, 3744, 2096, 1572, 1528 (2808 with the former distance weight);
/// mean kinks across `ahead`, `tipplane`, `te_up` 53.7°/61.1°/33.6° at 4 nodes to
/// 53.9°/54.4°/41.8° at 32 (58.1°/63.4°/50.3° before); wall lines at most 0.29° to 0.11°
/// off the normal (0.14° before). At R = 0.5 none of these is worse than before.
pub const SCALE_REACH: f64 = 0.5;

/// The goal columns of every wall face node of wall face `w` (face order, `dims[normal]`
/// distances each) from the side faces of `faces` (module docs); `weights` are the edges'
/// bilinear weights at the wall face nodes and `edges_at(n, j)` the edges' interpolated
/// distance of node j of the column at block node n.
pub(crate) fn face_columns(
    faces: &Faces,
    w: usize,
    weights: &[[f64; 4]],
    edges_at: &dyn Fn([usize; 3], usize) -> f64,
) -> Vec<f64> {
    let dims = faces.dims();
    let (d, lo) = normal(w);
    let (ta, tb) = tangents(w);
    let [na, nb] = face_dims(w, dims);
    let m = dims[d];
    let mut out = Vec::with_capacity(na * nb * m);
    // One column's scratch: the four side faces' profiles and the result.
    let mut side = [vec![0.0; m], vec![0.0; m], vec![0.0; m], vec![0.0; m]];
    let mut col = vec![0.0; m];
    for b in 0..nb {
        for a in 0..na {
            let n = block_node(w, a, b, dims);
            let wt = weights[a + na * b];
            let (p, q) = (wt[1] + wt[3], wt[2] + wt[3]);
            // Side faces: low and high end of axis ta, then of axis tb.
            for (s, prof) in side.iter_mut().enumerate() {
                let axis = if s < 2 { ta } else { tb };
                let f = 2 * axis + s % 2;
                let mut node = n;
                node[axis] = if s % 2 == 0 { 0 } else { dims[axis] - 1 };
                let at = |j: usize, node: &mut [usize; 3]| {
                    node[d] = if lo { j } else { m - 1 - j };
                    faces.face_point(f, *node)
                };
                let p0 = at(0, &mut node);
                for (j, x) in prof.iter_mut().enumerate() {
                    let r = at(j, &mut node);
                    *x = (0..3).map(|c| (r[c] - p0[c]).powi(2)).sum::<f64>().sqrt();
                }
            }
            for (j, x) in col.iter_mut().enumerate() {
                *x = (1.0 - p) * side[0][j]
                    + p * side[1][j]
                    + (1.0 - q) * side[2][j]
                    + q * side[3][j]
                    - edges_at(n, j);
            }
            let (first, last) = (col[1], col[m - 1]);
            let r = edges_at(n, 1) / first;
            let ok = first > 0.0 && last > first && r.is_finite() && {
                let reach = SCALE_REACH * (m - 1) as f64;
                for (j, x) in col.iter_mut().enumerate().skip(1) {
                    *x *= r.powf((-((j - 1) as f64) / reach).exp());
                }
                col.windows(2).all(|c| c[1] > c[0])
            };
            if ok {
                out.extend_from_slice(&col);
            } else {
                out.extend((0..m).map(|j| edges_at(n, j)));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use crate::elliptic::wall::{WallProfiles, WallTargets};
    use crate::grid::faces::{parse_face, Faces};
    use crate::Grid3;

    /// A box whose j-distribution is a power law at i = 0 and that law with a bulge at
    /// mid-height at i = max (the same first step), mixed quadratically in i, constant in k:
    /// the edges' bilinear interpolation (linear in i) is not the box's columns, the side
    /// faces' transfinite interpolation is, and the first heights agree (r = 1). The goal
    /// columns are the box's columns to rounding; at mid-height of the column next to the
    /// i = 0 face the edges' goal is 6 % off (5.7 %).
    #[test]
    fn face_profiles_follow_the_side_faces() {
        let (ni, nj, nk) = (6, 9, 5);
        let v1 = 1.0 / (nj - 1) as f64;
        let pow = |v: f64| v.powf(1.5);
        let bulge =
            |v: f64| pow(v) + 0.3 * (std::f64::consts::PI * v).sin() * (v - v1) / (1.0 - v1);
        let y = |i: usize, j: usize| {
            let (s, v) = (i as f64 / (ni - 1) as f64, j as f64 / (nj - 1) as f64);
            (1.0 - s * s) * pow(v) + s * s * bulge(v)
        };
        let g = Grid3::from_fn(ni, nj, nk, |i, j, k| [i as f64, y(i, j), 0.5 * k as f64]);
        let faces = Faces::from_grid(&g);
        let w = parse_face("F3").unwrap();
        let edges = WallTargets::new(&faces, w, "box").unwrap();
        let t = WallTargets::with_profiles(&faces, w, WallProfiles::Faces, "box").unwrap();
        for k in 0..nk {
            for i in 0..ni {
                let n = [i, 0, k];
                assert!((t.at(n, 1) - edges.at(n, 1)).abs() < 1e-14);
                for j in 1..nj {
                    let want = y(i, j);
                    assert!((t.at(n, j) - want).abs() < 1e-12, "{i} {j} {k}");
                }
            }
        }
        let (n, j) = ([1, 0, 2], nj / 2);
        let off = |v: f64| (v / y(1, j) - 1.0).abs();
        assert!(off(t.at(n, j)) < 1e-12, "{}", off(t.at(n, j)));
        assert!(off(edges.at(n, j)) > 0.03, "{}", off(edges.at(n, j)));
    }

    /// Geometric columns (ratio 1.5, 17 nodes) whose first step at the i = max face grows to
    /// 1 + a = 1.5 times the edges' towards mid-span (mixed linearly in i, so the side faces'
    /// interpolation is the box's columns): the goal column keeps the edges' first height
    /// (the prescription) and returns to the faces' profile up the column. At mid-height the
    /// scaling is e^{-7/8} = 0.42 of its value at the wall in the logarithm; with the former
    /// weight (1 − v)^3 of the distance (v = 0.04 there) it was 0.89.
    #[test]
    fn the_first_height_scaling_fades_within_the_column() {
        let (ni, nj, nk) = (6, 17, 5);
        let geo = |j: usize| (1.5f64.powi(j as i32) - 1.0) / (1.5f64.powi(nj as i32 - 1) - 1.0);
        let bump = |i: usize, k: usize| {
            0.5 * (i as f64 / (ni - 1) as f64)
                * (std::f64::consts::PI * k as f64 / (nk - 1) as f64).sin()
        };
        let y = |i: usize, j: usize, k: usize| {
            let g = geo(j);
            g * (1.0 + bump(i, k) * (1.0 - g).powi(2))
        };
        let g = Grid3::from_fn(ni, nj, nk, |i, j, k| [i as f64, y(i, j, k), 0.5 * k as f64]);
        let faces = Faces::from_grid(&g);
        let w = parse_face("F3").unwrap();
        let edges = WallTargets::new(&faces, w, "box").unwrap();
        let t = WallTargets::with_profiles(&faces, w, WallProfiles::Faces, "box").unwrap();
        let n = [ni - 2, 0, nk / 2];
        let r = edges.at(n, 1) / y(n[0], 1, n[2]);
        assert!(r < 0.8, "{r}");
        assert!((t.at(n, 1) / edges.at(n, 1) - 1.0).abs() < 1e-13);
        let scale = |j: usize| (t.at(n, j) / y(n[0], j, n[2])).ln() / r.ln();
        assert!((scale(1) - 1.0).abs() < 1e-12);
        let mid = scale(nj / 2);
        assert!(mid > 0.3 && mid < 0.55, "{mid}");
        assert!(scale(nj - 2) < 0.25, "{}", scale(nj - 2));
    }
}
