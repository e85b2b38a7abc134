//! One row of the volume grid system [86]: the metric coefficients α^ij [88] from the
//! covariant metric and the row of the 19-point operator they give (METHOD.md §6), shared by
//! the interior nodes ([`crate::elliptic::poisson3d`]) and those of symmetry faces
//! ([`crate::elliptic::symmetry3d`]).

/// The six α^ij of [88] in the order 11, 12, 13, 22, 23, 33, from g_ij.
#[inline]
pub fn alphas(g: [[f64; 3]; 3]) -> [f64; 6] {
    [
        g[1][1] * g[2][2] - g[1][2] * g[1][2],
        g[0][2] * g[1][2] - g[0][1] * g[2][2],
        g[0][1] * g[1][2] - g[0][2] * g[1][1],
        g[0][0] * g[2][2] - g[0][2] * g[0][2],
        g[0][2] * g[0][1] - g[0][0] * g[1][2],
        g[0][0] * g[1][1] - g[0][1] * g[0][1],
    ]
}

/// One row of the (negated) operator in the slot order of [`crate::solve::stencil19::OFFSETS`], divided by its
/// diagonal 2(α¹¹ + α²² + α³³) (the row is left as it is if that is zero): the centre 1, the
/// face neighbours −(α^tt ± ½ s_t) along axis t, and the edge neighbours ∓½ α^pr of the
/// 4-corner mixed derivatives (sign −o_p o_r), with s the first-derivative coefficients
/// Σ_ij α^ij P^k_ij.
///
/// Why the rows are scaled: α^ij scales with the fourth power of the local spacing, so at a
/// clustered wall the rows are 1e-6 of the far field's (ONERA M6: diagonal 4e-11 next to the
/// tip's trailing edge against 1e-5 in the far field). A Bi-CGSTAB solve of an inexact Picard
/// step stops at a relative 2-norm of the residual, which then ignores the near-wall rows: the
/// corrections there were left wrong by many local cell heights, the next iterate degenerate
/// and its correction up to 5 block diameters (the M6 wing volumes' spikes after every wall
/// pass, 314 Picard steps). Scaled rows weigh every node's equation alike, as the Picard
/// residual [24] does (each row divided by its diagonal); the fixed point is the same.
#[inline]
pub(crate) fn row_coefficients(row: &mut [f64; 19], al: [f64; 6], sk: [f64; 3]) {
    let [d0, d1, d2] = [al[0], al[3], al[5]];
    let diag = 2.0 * (d0 + d1 + d2);
    let scale = if diag > 0.0 { 1.0 / diag } else { 1.0 };
    let [d0, d1, d2] = [d0, d1, d2].map(|v| v * scale);
    let (h01, h02, h12) = (
        0.5 * scale * al[1],
        0.5 * scale * al[2],
        0.5 * scale * al[4],
    );
    let [s0, s1, s2] = sk.map(|v| 0.5 * scale * v);
    *row = [
        if diag > 0.0 { 1.0 } else { diag },
        -(d0 - s0),
        -(d0 + s0),
        -(d1 - s1),
        -(d1 + s1),
        -(d2 - s2),
        -(d2 + s2),
        -h01,
        h01,
        h01,
        -h01,
        -h02,
        h02,
        h02,
        -h02,
        -h12,
        h12,
        h12,
        -h12,
    ];
}
