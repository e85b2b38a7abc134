//! Near-wall orthogonality at a wall face (in the spirit of the paper's Section 2.4,
//! METHOD.md §3: orthogonality through the algebraic map, the interior still the elliptic
//! solution): the grid lines leave the wall along its normal, so that the first off-wall node
//! sits at the prescribed wall-NORMAL distance.
//!
//! [`super`] holds the first-cell lengths by remapping the wall-normal parameter v of the
//! algebraic map S (composite mapping x = X(S(ξ)), [70–72]) and leaves the directions to the
//! elliptic solution. Here each pass also moves the TANGENTIAL parameters (a, b) of the nodes of
//! the interior wall columns. X depends on the boundary data alone, so near a node
//! x(S + δS) ≈ x + M δS, M = ∂x/∂S = (∂x/∂ξ)(∂S/∂ξ)⁻¹ (central differences of the current grid
//! and of S in index space). Node j of a column, with wall foot x₀ and unit wall normal n there
//! (cross product of the central differences along the wall face, the normal of the quality
//! report's orthogonality), has the tangential offset t = r − (r·n) n, r = x_j − x₀. Its goal is
//! t* = (1 − ψ) t⁰, t⁰ from the uncorrected grid, with the weight
//! ψ = (1 − v⁰)^q / (1 + (|r⁰| / (K w))²): the v remap's fading weight (q = 3) times a layer of
//! K = [`LAYER`] wall cell widths w (the smaller width of the wall cells at the foot; the normals
//! of a curved wall fan out or converge on that scale, beyond it the elliptic grid is kept). A
//! pass solves [M_a M_b] (δa, δb) ≈ t* − t' in the least-squares sense, t' the offset after the
//! same pass's v remap (x + M_v δv: along an oblique line v moves the node sideways too, and
//! leaving that out cost two extra passes and folded intermediate grids), clamps the result to
//! [`CLAMP`] of the uncorrected gaps to the neighbours (S stays monotone along every parameter
//! line, X is one-to-one), and the control functions [83, 84] follow from the shifted S as
//! before. In the layer the v remap measures (1 − ψ)|r| + ψ |r·n|, the normal distance where the
//! line is made normal. Rim columns are the side faces' lines and stay as given.
//!
//! [`wall_figure`] measures the result: the angle of the first off-wall line to the wall normal
//! (the quality report's orthogonality of the face) and the wall-normal distance of the first
//! off-wall node over its target, at the wall nodes off the rim.

use crate::algebraic::bilinear3d::ParamGrid3;
use crate::algebraic::blend::smoothstep;
use crate::elliptic::continuation::Lines;
use crate::elliptic::crossing::Crossings;
use crate::grid::faces::{block_node, face_dims, normal, step_in, tangents};
use crate::Grid3;

/// Largest total shift of a tangential parameter, as a fraction of the uncorrected gap to the
/// neighbour it moves towards (< 1/2 keeps every parameter line monotone; larger shifts
/// folded the C–O wing block near its wall face's corners).
pub const CLAMP: f64 = 0.25;

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V) -> f64 {
    dot(a, a).sqrt()
}

/// Node index of block node n.
#[inline]
fn flat(n: [usize; 3], dims: [usize; 3]) -> usize {
    n[0] + dims[0] * (n[1] + dims[1] * n[2])
}

/// Unit normal of wall face `w` at its node (a, b) off the rim: cross product of the central
/// differences along the face (the normal of the quality report's orthogonality). None if
/// degenerate.
pub fn wall_normal(g: &Grid3, w: usize, a: usize, b: usize) -> Option<V> {
    let dims = g.dims();
    let at = |a: usize, b: usize| {
        let n = block_node(w, a, b, dims);
        g.point(n[0], n[1], n[2])
    };
    let c = cross(
        sub(at(a + 1, b), at(a - 1, b)),
        sub(at(a, b + 1), at(a, b - 1)),
    );
    let l = norm(c);
    (l > 0.0 && l.is_finite()).then(|| c.map(|x| x / l))
}

/// The parameter (s, t or u) of axis d.
fn param_mut(pg: &mut ParamGrid3, d: usize) -> &mut Vec<f64> {
    match d {
        0 => &mut pg.s,
        1 => &mut pg.t,
        _ => &mut pg.u,
    }
}

fn param(pg: &ParamGrid3, d: usize) -> &[f64] {
    match d {
        0 => &pg.s,
        1 => &pg.t,
        _ => &pg.u,
    }
}

/// Inverse of a 3 × 3 matrix given by its rows (the adjugate over the determinant); None if
/// singular.
fn inverse(m: [V; 3]) -> Option<[V; 3]> {
    let c0 = cross(m[1], m[2]);
    let det = dot(m[0], c0);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let c1 = cross(m[2], m[0]);
    let c2 = cross(m[0], m[1]);
    // inverse = adj / det, adj columns = the cross products.
    Some(std::array::from_fn(|r| {
        [c0[r] / det, c1[r] / det, c2[r] / det]
    }))
}

/// Height of the orthogonal layer in wall cell widths: the weight of the tangential shift
/// falls as 1 / (1 + (d / (K w))²) with the distance d from the wall, w the smaller width of the
/// wall face's cells at the column's foot (normal lines of a curved wall fan out or converge on
/// that scale; beyond it the elliptic solution is kept). The smooth fall (over about a decade of
/// d, i.e. several cells of a stretched column) matters: a cut-off within two cells gave the
/// C–O block folded intermediate grids at the layer's edge.
pub const LAYER: f64 = 2.0;

/// Tangential offsets t⁰ and weights ψ of the interior nodes of the interior wall columns
/// (module docs; goals t* = (1 − ψ) t⁰), from the first (uncorrected) grid; slot
/// ((b − 1)(na − 2) + a − 1)(n − 2) + j − 1.
#[derive(Clone, Debug)]
pub struct TangentGoals {
    t0: Vec<V>,
    weight: Vec<f64>,
    /// Nodes per column (n − 2).
    per_col: usize,
    /// The uncorrected parameters: shifts are clamped to a fraction of their gaps.
    start: ParamGrid3,
    /// Shifts limited only by keeping each parameter line monotone (every gap at least
    /// [`MIN_GAP`] of the uncorrected one), not to [`CLAMP`] of the gaps: for interior faces,
    /// whose lines may have to turn by the whole angle of a neighbouring volume's lines.
    free: bool,
    /// Nodes held mostly by a crossing face's goal ([`Crossings`]): their error counts in the
    /// passes' stop as the first nodes' does.
    cross: Vec<bool>,
    /// At a continued face ([`crate::elliptic::continuation`]): the goal offsets t_c the
    /// goals blend to instead of zero, t* = (1 − ψ) t⁰ + ψ t_c.
    tc: Option<Vec<V>>,
    /// Nodes whose weight ψ is at most this are left alone (0: every node of the columns
    /// moves towards its goal, the uncorrected offset where ψ is small). With several faces
    /// corrected in one block, each moves only the nodes of its own layer
    /// ([`LAYER_CUTOFF`]): a face's goals elsewhere would undo another face's shifts.
    pub cutoff: f64,
}

/// At a free (interior) face, the goals' weight is multiplied by the smoothstep of
/// (m − h)/SIDE_FADE next to a held side face, m the column's distance in columns from it (1
/// next to it), h the columns that keep their profile there ([`SIDE_HOLD`] next to a fixed face
/// shared with another volume, 1 next to a symmetry face): the spacing and the lines across
/// that face stay those the volume beyond it sees, and the lines turn to the face's normal over
/// the columns in between. Measured on the M6's wake volume at 33 × 33 × 25 (`orthogonal =
/// ["F6"]`, `waketip`, its sides `te_up` shared and fixed, the wake sheet a symmetry face),
/// mean kink across `waketip` / turn at the first node off it / growth ratio along i: 66.6° /
/// 8.6° / 1.40 uncorrected; without the fade the passes fold from the second on (back to pass
/// 0); one column held at both, fading over 4: 19.5° / 15.3° / 4.58; over 6: 24.4° / 14.7° /
/// 2.56 (but one face in the wing plane at the tip with checkMesh skewness 4.28; 3.62 at full
/// size); two columns held at both: 28.9° / 14.3° / 2.23 (full size: a face of 4.09); shipped
/// (2 at `te_up`, 1 at the sheet): 26.3° / 14.4° / 2.23, every face below 4 at both sizes.
/// Fading next to every side (the box's boundary faces too) gives 17.3° over 2 columns but
/// growth 10.9, and over 4 columns it undoes the sheared box's correction at 9 nodes
/// (`tests/volume_topology.rs`: 29.5° against 11.2°).
pub const SIDE_FADE: f64 = 6.0;

/// Columns next to a fixed side face shared with another volume that keep their profile
/// ([`SIDE_FADE`]).
pub const SIDE_HOLD: usize = 2;

/// [`TangentGoals::cutoff`] when several faces of a block are corrected.
pub const LAYER_CUTOFF: f64 = 0.01;

/// With free goals (interior faces): the smallest gap between neighbouring parameters along a line,
/// as a fraction of the uncorrected gap (the gap [`CLAMP`] keeps at the least).
pub const MIN_GAP: f64 = 1.0 - 2.0 * CLAMP;

/// Visits the interior nodes j = 1 … n − 2 of the interior columns of wall face `w`: `f(slot,
/// column (a, b), j, block node, r = x_j − x₀, unit normal at the foot)`.
fn for_nodes(
    x: &Grid3,
    w: usize,
    mut f: impl FnMut(usize, [usize; 2], usize, [usize; 3], V, Option<V>),
) {
    let dims = x.dims();
    let (d, lo) = normal(w);
    let [na, nb] = face_dims(w, dims);
    let mut slot = 0;
    for b in 1..nb - 1 {
        for a in 1..na - 1 {
            let foot = block_node(w, a, b, dims);
            let x0 = x.point(foot[0], foot[1], foot[2]);
            let nrm = wall_normal(x, w, a, b);
            let mut n = foot;
            for j in 1..dims[d] - 1 {
                n = step_in(n, d, lo);
                f(slot, [a, b], j, n, sub(x.point(n[0], n[1], n[2]), x0), nrm);
                slot += 1;
            }
        }
    }
}

/// The tangential offset r − (r·n) n.
fn tangential(r: V, n: V) -> V {
    let h = dot(r, n);
    sub(r, n.map(|c| c * h))
}

impl TangentGoals {
    /// Offsets t⁰ and weights ψ from grid `x` and its parameters `pg` (module docs); with
    /// `free` (interior faces) the shifts are bounded by monotonicity only, and the weights
    /// fade next to the side faces at a = 0, a = na − 1, b = 0, b = nb − 1 where `held` gives
    /// the columns that keep their profile there (0: not held; [`SIDE_FADE`]). With `crossings` (a wall's side faces to be crossed at right angles) the
    /// offsets of the columns next to them are blended towards the crossing goals
    /// ([`Crossings::goal`]). With `lines` (a continued face) the goals are the offsets of the
    /// arriving lines ([`Lines::offset`]), faded in along the face next to the held sides
    /// ([`Lines::side_fade`]).
    pub fn new(
        pg: &ParamGrid3,
        x: &Grid3,
        w: usize,
        free: bool,
        held: [usize; 4],
        crossings: Option<&Crossings>,
        lines: Option<&Lines>,
    ) -> Self {
        let dims = x.dims();
        let [na, nb] = face_dims(w, dims);
        let (d, lo) = normal(w);
        let pt = |a: usize, b: usize| {
            let n = block_node(w, a, b, dims);
            x.point(n[0], n[1], n[2])
        };
        let (mut t0, mut weight, mut cross) = (Vec::new(), Vec::new(), Vec::new());
        let mut tc = lines.map(|_| Vec::new());
        // distances along the face from its four sides, for the continuation's side fade
        let sides = match lines {
            Some(_) => Lines::side_distances(na, nb, pt),
            None => Vec::new(),
        };
        for_nodes(x, w, |_, [a, b], j, n, r, nrm| {
            let width = 0.5
                * norm(sub(pt(a + 1, b), pt(a - 1, b))).min(norm(sub(pt(a, b + 1), pt(a, b - 1))));
            let v = pg.at(flat(n, dims))[d];
            let v = if lo { v } else { 1.0 - v };
            // A wall layer of LAYER wall cell widths; at a free (interior) face the first
            // node is made normal and the goal fades over LAYER nodes.
            let fade = if free {
                1.0 / (1.0 + ((j - 1) as f64 / LAYER).powi(2))
            } else {
                1.0 / (1.0 + (norm(r) / (LAYER * width)).powi(2))
            };
            let mut psi = fade_weight(v.clamp(0.0, 1.0)) * fade;
            if free {
                for (m, h) in [a, na - 1 - a, b, nb - 1 - b].into_iter().zip(held) {
                    if h > 0 {
                        psi *= smoothstep((m as f64 - h as f64) / SIDE_FADE);
                    }
                }
            }
            if lines.is_some() {
                psi *= Lines::side_fade(sides[a + na * b], held, norm(r) / j as f64);
            }
            let (psi, mut t) = match nrm {
                Some(nv) if psi.is_finite() => (psi, tangential(r, nv)),
                _ => (0.0, [0.0; 3]),
            };
            // The first line stays the wall's (normal): the crossing goals start at j = 2.
            let mut crossed = false;
            if let (Some(nv), Some((phi, g))) = (
                nrm,
                crossings.filter(|_| j > 1).and_then(|c| c.goal(x, a, b, j)),
            ) {
                let tc = tangential(sub(g, pt(a, b)), nv);
                t = std::array::from_fn(|e| (1.0 - phi) * t[e] + phi * tc[e]);
                crossed = phi >= 0.5;
            }
            cross.push(crossed);
            if let (Some(tc), Some(l)) = (tc.as_mut(), lines) {
                let c = nrm.and_then(|nv| Lines::offset(l.at(a, b), nv, r));
                tc.push(c.unwrap_or(t));
            }
            t0.push(t);
            weight.push(psi);
        });
        TangentGoals {
            t0,
            weight,
            per_col: dims[d] - 2,
            start: pg.clone(),
            free,
            cross,
            tc,
            cutoff: 0.0,
        }
    }

    /// Distance of a column node from the wall as the v remap measures it: (1 − ψ)|r| + ψ|r·n|
    /// (the wall-normal distance where the line is made normal, the length elsewhere).
    pub(super) fn distance(&self, col: usize, j: usize, r: V, nrm: Option<V>) -> f64 {
        let len = norm(r);
        match nrm {
            Some(nv) if j >= 1 && j <= self.per_col => {
                let psi = self.weight[col * self.per_col + j - 1];
                (1.0 - psi) * len + psi * dot(r, nv).abs()
            }
            _ => len,
        }
    }
}

/// One tangential pass (module docs): shifts the tangential parameters of `trial` (S of
/// `old`, its v already remapped) so that the nodes of the interior wall columns of face `w`
/// in grid `x` (solved with `old`) move towards their goals. Returns the largest
/// |t − t*| / |x_j − x₀| before the pass over the first off-wall nodes (j = 1: the sine of the
/// angle at the wall still to remove) and the nodes held by a crossing face.
pub fn shift_tangential(
    old: &ParamGrid3,
    trial: &mut ParamGrid3,
    x: &Grid3,
    w: usize,
    goals: &TangentGoals,
) -> f64 {
    let dims = old.dims();
    let (ta, tb) = tangents(w);
    let st = [1, dims[0], dims[0] * dims[1]];
    let (d, _) = normal(w);
    let remapped: &ParamGrid3 = trial;
    let mut err = 0.0f64;
    let mut shifts: Vec<(usize, f64, f64)> = Vec::new();
    let pt = |n: [usize; 3]| x.point(n[0], n[1], n[2]);
    for_nodes(x, w, |slot, _, j, n, r, nrm| {
        let (t0, psi) = (goals.t0[slot], goals.weight[slot]);
        let goal: V = match &goals.tc {
            Some(tc) => std::array::from_fn(|e| t0[e] * (1.0 - psi) + tc[slot][e] * psi),
            None => t0.map(|c| c * (1.0 - psi)),
        };
        let Some(nv) = nrm else { return };
        if psi <= goals.cutoff {
            return;
        }
        let len = norm(r);
        if len > 0.0 && (j == 1 || goals.cross[slot]) {
            err = err.max(norm(sub(goal, tangential(r, nv))) / len);
        }
        let p = flat(n, dims);
        // M = Jx JS⁻¹: ∂x/∂S_c = Σ_e ∂x/∂ξ_e (JS⁻¹)_ec, central differences in index space.
        let jx: [V; 3] = std::array::from_fn(|e| {
            let (mut u, mut m) = (n, n);
            u[e] += 1;
            m[e] -= 1;
            sub(pt(u), pt(m))
        });
        let js: [V; 3] = std::array::from_fn(|c| {
            let q = param(old, c);
            std::array::from_fn(|e| q[p + st[e]] - q[p - st[e]])
        });
        let Some(inv) = inverse(js) else { return };
        let col =
            |c: usize| -> V { std::array::from_fn(|k| (0..3).map(|e| jx[e][k] * inv[e][c]).sum()) };
        let (ma, mb) = (col(ta), col(tb));
        // The offset after the v remap of this pass (it moves the node along its current line).
        let dv = param(remapped, d)[p] - param(old, d)[p];
        let mv = col(d);
        let moved = std::array::from_fn(|k| r[k] + mv[k] * dv);
        let want = sub(goal, tangential(moved, nv));
        // Least squares [M_a M_b] (δa, δb) ≈ t* − t' (normal equations).
        let (aa, ab, bb) = (dot(ma, ma), dot(ma, mb), dot(mb, mb));
        let det = aa * bb - ab * ab;
        if det.is_nan() || det <= 1e-12 * aa * bb {
            return;
        }
        let (ra, rb) = (dot(ma, want), dot(mb, want));
        let da = (bb * ra - ab * rb) / det;
        let db = (aa * rb - ab * ra) / det;
        if da.is_finite() && db.is_finite() {
            shifts.push((p, da, db));
        }
    });
    // Increments on the parameters of this pass so far (another face's pass may have moved
    // this axis: the wall's normal remap, or its own tangential shift). The total shift of
    // this face is clamped to CLAMP of the uncorrected gaps (and of the current ones where this
    // pass moved the axis before), so that every parameter line stays monotone through all
    // passes; `free` goals only keep every gap at MIN_GAP of the uncorrected one.
    for (axis, pick) in [(ta, 0usize), (tb, 1)] {
        let q0 = param(&goals.start, axis);
        let q = param(old, axis);
        let base = param(trial, axis).to_vec();
        let out = param_mut(trial, axis);
        let s = st[axis];
        for &(p, da, db) in &shifts {
            let dv = if pick == 0 { da } else { db };
            let moved = base[p] - q[p];
            let (mut lo_gap, mut hi_gap) = (q0[p] - q0[p - s], q0[p + s] - q0[p]);
            if moved != 0.0 {
                lo_gap = lo_gap.min(base[p] - base[p - s]);
                hi_gap = hi_gap.min(base[p + s] - base[p]);
            }
            if lo_gap.is_nan() || hi_gap.is_nan() || lo_gap <= 0.0 || hi_gap <= 0.0 {
                continue;
            }
            out[p] = if goals.free {
                base[p] + dv
            } else {
                (base[p] + dv).clamp(
                    q0[p] + moved - CLAMP * lo_gap,
                    q0[p] + moved + CLAMP * hi_gap,
                )
            };
        }
        if goals.free {
            // Monotone again: upwards along the axis, then downwards (the shifted nodes are
            // interior nodes; their line's ends are face nodes and stay).
            let mut idx: Vec<usize> = shifts.iter().map(|x| x.0).collect();
            idx.sort_unstable();
            for &p in &idx {
                let floor = out[p - s] + MIN_GAP * (q0[p] - q0[p - s]);
                if out[p].is_nan() || out[p] < floor {
                    out[p] = floor;
                }
            }
            for &p in idx.iter().rev() {
                let ceil = out[p + s] - MIN_GAP * (q0[p + s] - q0[p]);
                if out[p].is_nan() || out[p] > ceil {
                    out[p] = ceil;
                }
            }
        }
    }
    err
}

/// Near-wall figure of a grid at wall face `w` ([`wall_figure`]): in the run report of a block
/// with `wall = "F…"`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct WallFigure {
    /// The wall face ("F1" … "F6").
    pub face: String,
    /// Wall nodes measured (those off the wall face's rim).
    pub nodes: usize,
    /// Largest and mean angle between the first off-wall grid line and the wall normal, degrees
    /// (the quality report's orthogonality of that face).
    pub angle_max_deg: f64,
    pub angle_mean_deg: f64,
    /// Smallest and largest wall-normal distance of the first off-wall node over its target.
    pub ratio_min: f64,
    pub ratio_max: f64,
}

/// Wall-normal distances of the first off-wall nodes at face `w` (face order, a fastest; NaN
/// on the rim and where the normal is degenerate).
pub fn normal_heights(g: &Grid3, w: usize) -> Vec<f64> {
    let dims = g.dims();
    let (d, lo) = normal(w);
    let [na, nb] = face_dims(w, dims);
    let mut out = vec![f64::NAN; na * nb];
    for b in 1..nb.saturating_sub(1) {
        for a in 1..na.saturating_sub(1) {
            let n0 = block_node(w, a, b, dims);
            let n1 = step_in(n0, d, lo);
            if let Some(nv) = wall_normal(g, w, a, b) {
                let r = sub(g.point(n1[0], n1[1], n1[2]), g.point(n0[0], n0[1], n0[2]));
                out[a + na * b] = dot(r, nv).abs();
            }
        }
    }
    out
}

/// The near-wall figure at face `w` against the target first heights `targets` (face order,
/// e.g. [`crate::elliptic::wall::wall_targets`]): the quality report's orthogonality of that face (reused
/// from [`crate::quality::quality3d`]) and the wall-normal distances of the first off-wall
/// nodes relative to the targets, both at the wall nodes off the rim.
pub fn wall_figure(g: &Grid3, w: usize, targets: &[f64]) -> WallFigure {
    let q = crate::quality::quality3d::quality3d(g);
    let f = &q.faces[w];
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (h, t) in normal_heights(g, w).iter().zip(targets) {
        if h.is_finite() {
            lo = lo.min(h / t);
            hi = hi.max(h / t);
        }
    }
    WallFigure {
        face: crate::grid::faces::FACE_NAMES[w].to_string(),
        nodes: f.nodes,
        angle_max_deg: f.orthogonality_max_deg,
        angle_mean_deg: f.orthogonality_mean_deg,
        ratio_min: lo,
        ratio_max: hi,
    }
}

/// The exponent q of the weight (1 − v)^q: the correction fades out at v ≈ 1/q.
const REMAP_POWER: i32 = 3;

/// The remap weight (1 − v)^q.
#[inline]
pub(crate) fn fade_weight(v: f64) -> f64 {
    (1.0 - v).powi(REMAP_POWER)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elliptic::picard::PicardParams;
    use crate::elliptic::wall::{grid_volume_wall_with, wall_targets, WallOptions};
    use crate::grid::faces::parse_face;
    use crate::grid::faces::Faces;
    use crate::solve::direct::DirectLu3;

    /// A sheared box: flat wall y = 0 (F3), side faces F1, F2 leaning by `lean` (x = ξ + lean
    /// y), clustered towards the wall.
    fn sheared_box(lean: f64) -> Faces {
        let d = [11, 13, 9];
        let h = d.map(|n| (n - 1) as f64);
        let g = Grid3::from_fn(d[0], d[1], d[2], |i, j, k| {
            let y = ((j as f64 / h[1]) * 12.0).sinh() / 12f64.sinh();
            [i as f64 / h[0] + lean * y, y, 0.8 * k as f64 / h[2]]
        });
        Faces::from_grid(&g)
    }

    /// A free face's goals fade next to a held side face: zero in the [`SIDE_HOLD`] columns
    /// next to it, rising by the smoothstep over [`SIDE_FADE`] columns, untouched beyond and
    /// next to the sides that are not held.
    #[test]
    fn free_goals_fade_next_to_held_side_faces() {
        use crate::algebraic::bilinear3d::bilinear;
        use crate::algebraic::flat_edge::edge_functions;
        use crate::algebraic::transfinite3d::transfinite;
        let faces = sheared_box(0.4);
        let x = transfinite(&faces);
        let pg = bilinear(&edge_functions(&faces), "box").unwrap();
        let f5 = parse_face("F5").unwrap();
        let plain = TangentGoals::new(&pg, &x, f5, true, [0; 4], None, None);
        let held = TangentGoals::new(&pg, &x, f5, true, [SIDE_HOLD, 0, 0, 0], None, None);
        let [na, nb] = face_dims(f5, x.dims());
        let per = plain.per_col;
        let mut seen = 0;
        for b in 1..nb - 1 {
            for a in 1..na - 1 {
                for j in 0..per {
                    let slot = ((b - 1) * (na - 2) + a - 1) * per + j;
                    let (p, h) = (plain.weight[slot], held.weight[slot]);
                    let t = ((a as f64 - SIDE_HOLD as f64) / SIDE_FADE).clamp(0.0, 1.0);
                    let want = p * t * t * (3.0 - 2.0 * t);
                    assert!(
                        (h - want).abs() <= 1e-15,
                        "a {a} b {b} j {j}: {h} vs {want}"
                    );
                    if a <= SIDE_HOLD {
                        assert_eq!(h, 0.0);
                    } else if a as f64 >= SIDE_HOLD as f64 + SIDE_FADE {
                        assert_eq!(h, p);
                    } else if p > 0.0 {
                        assert!(h > 0.0 && h < p);
                        seen += 1;
                    }
                }
            }
        }
        assert!(seen > 0);
        // the wall's goals (not free) do not fade
        let wall = TangentGoals::new(&pg, &x, f5, false, [SIDE_HOLD; 4], None, None);
        let wall_plain = TangentGoals::new(&pg, &x, f5, false, [0; 4], None, None);
        assert_eq!(wall.weight, wall_plain.weight);
    }

    #[test]
    fn lines_off_a_flat_wall_become_normal_inside_a_sheared_box() {
        let faces = sheared_box(0.4);
        let w = parse_face("F3").unwrap();
        let t = wall_targets(&faces, w, "box").unwrap();
        let run = |orthogonal: bool| {
            let opts = WallOptions { orthogonal };
            let r = grid_volume_wall_with(
                &faces,
                w,
                opts,
                &mut DirectLu3::new(),
                &PicardParams::default(),
                "box",
                &mut |_, _| {},
            )
            .unwrap();
            (wall_figure(&r.grid, w, &t), r)
        };
        let (before, _) = run(false);
        let (after, r) = run(true);
        eprintln!("sheared box: {before:?} -> {after:?}");
        // The sheared box is the tensor-product solution: every line leans by atan 0.4.
        assert!((before.angle_max_deg - 0.4f64.atan().to_degrees()).abs() < 0.1);
        assert!(after.angle_max_deg < 2.0, "{after:?}");
        assert!(
            after.ratio_min > 0.95 && after.ratio_max < 1.05,
            "{after:?}"
        );
        assert_eq!(
            crate::quality::quality3d::quality3d(&r.grid).folded_cells,
            0
        );
    }
}
