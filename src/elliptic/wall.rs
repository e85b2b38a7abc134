//! Prescribed wall-normal spacing at a wall face (paper Section 5.3: first-cell height 1e-5
//! local chord at the leading edge, 2e-5 at the trailing edge of the M6 wing).
//!
//! The edge functions [70–72] carry the distributions of the four edges leaving the wall only
//! at those edges: elsewhere the first-cell height is t₁ |∂X/∂t|, with t₁ the bilinear blend of
//! the four edges' first parameter steps and X the harmonic map P → D, whose |∂X/∂t| at the wall
//! varies along the wall. On the M6 upper block the heights came out 2.2e-6 … 1.6e-5 against
//! 4.5e-6 … 1.6e-5 prescribed (42 % of the target next to the leading edge).
//!
//! The fix keeps the composite mapping x = X(S(ξ)) and changes only S, the algebraic map C → P,
//! in the interior: X depends on the boundary data alone, so the distance of a node from the
//! wall follows its normal parameter v, locally linearly. Goal distances of the nodes of a
//! column: d*^ψ d₀^{1−ψ} with ψ falling from 1 at the wall to 0 at the opposite face
//! ([`BLEND_POWER`]), d* the bilinear interpolation, in the wall face's parameters, of the four
//! edges' distance-from-wall profiles (so the first-cell height is the interpolation of their
//! first spacings) and d₀, v₀ the uncorrected grid's distances and parameters: the edges'
//! profile at the wall, the elliptic grid towards the opposite face.
//! Each pass remaps v ← v d_goal/d at every interior column node, recomputes the control
//! functions [83, 84] from the remapped S and re-solves from the current grid; two or three
//! passes reach 1 %. The faces that share an edge with the wall are corrected first in the same
//! way (2D: the straight-line parameters of [39, 40]), so that the interior and the faces agree.
//! On the M6 block (65 × 49 × 25) the heights end within 1.2 % of 1e-5 … 2e-5 local chord
//! (linear in x/c), fold-free, at about 5× the time of one solve.
//!
//! The lengths are not the wall-normal distances where the lines leave the wall obliquely (up to
//! 57° on that block, 80° on the C–O block): with [`WallOptions::orthogonal`] (case key
//! `wall_orthogonal`, default on) each pass also shifts the tangential parameters near the wall
//! ([`wall_normal`]), and the v remap then measures wall-normal distances there. As a safeguard
//! a grid that an orthogonal pass folds is not kept: the result is then the fold-free pass with
//! the smallest largest wall angle (not triggered on the two M6 blocks, whose passes were all
//! fold-free; early variants folded intermediate grids of the C–O block).

use crate::algebraic::bilinear3d::{bilinear, EdgeFunctions3, ParamGrid3};
use crate::algebraic::transform::ParamGrid;
use crate::algebraic::ControlKind;
use crate::elliptic::crossing::Crossings;
use crate::elliptic::orthogonal3d::{grid_volume_corrected, FaceCorrections};
use crate::elliptic::picard::VolumeResult;
use crate::elliptic::picard::{PicardParams, PicardStep};
use crate::grid::faces::{block_node, face_dims, normal, step_in, tangents, Faces};
use crate::solve::stencil19::Stencil19;
use crate::solve::LinearSolver;
use crate::{Error, Grid2, Grid3, Result};

use crate::elliptic::wall_normal::{self, fade_weight};

/// Correction passes at most (each a re-solve from the current grid).
pub const MAX_PASSES: usize = 6;
/// Passes stop once every column node's |ln(goal / distance)| is below this (the first-cell
/// heights are then within ~0.5 %).
pub const TOLERANCE: f64 = 0.05;
/// Picard tolerance of the intermediate solves of a volume (relative to the block's
/// diameter). The passes remap from these grids, so the final grid is defined only to about
/// this tolerance (a start grid changes it by that much). Measured on the wing_m6_co C–O block
/// against 1e-8: 57 Picard steps instead of 76, nodes within 6e-7 of the diameter, first
/// spacings within 0.2 %, wall lines 0.17° off the normal instead of 0.06° (1e-7: 65 steps;
/// 1e-5: 55 steps, spacings to 0.998).
pub const LOOSE_TOLERANCE: f64 = 1e-6;
/// Largest change of a node's parameter in one pass (factor).
const MAX_RATIO: f64 = 4.0;
/// With `orthogonal`, passes also stop only once every first off-wall node is within this sine
/// of the angle of its tangential goal (0.3°; [`wall_normal`]). Measured over the first nodes
/// only: the nodes further up a column approach their (fading) goals more slowly, and waiting
/// for them ran every block through all passes for angles at the wall below 0.001° (wing
/// upper block: 62 Picard steps then, 34 now at 0.17°).
pub const ANGLE_TOLERANCE: f64 = 0.005;

/// Options of the wall correction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallOptions {
    /// Also make the grid lines leave the wall along its normal ([`wall_normal`]).
    pub orthogonal: bool,
}

impl Default for WallOptions {
    fn default() -> Self {
        WallOptions { orthogonal: true }
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt()
}

/// The remap g(v) = v r^{(1−v)^q} of a wall-normal parameter v (0 at the wall, 1 at the
/// opposite face): g(0) = 0, g(1) = 1, g'(0) = r, monotone for r < e^{2.5}.
#[inline]
pub fn remap(v: f64, r: f64) -> f64 {
    v * r.powf(fade_weight(v))
}

/// The exponent q of the goal blend ψ = max((1 − v₀)^q, e^{−(v₀/a)²}) (the goals of each column):
/// the edges' profile holds near the wall, the elliptic grid beyond v₀ ≈ 1/q. It was (1 − v₀)³
/// until 2026-11-28, which still gave the profile 73 % of the weight at v₀ = 0.1 (0.3 chord off
/// the ONERA M6 wing): there the wing volumes followed the edges' interpolated profile rather
/// than the elliptic solution (growth ratios along i and k up to 8.4 and 8.1) and their lines
/// bent next to the faces between the volumes. With q = 10 (ψ = 0.35 at v₀ = 0.1), at full size:
/// the same wall figures, growth ratios 3.9 and 5.7, mean kinks across te and tipplane 6° lower,
/// half the faces above 70° non-orthogonality in checkMesh (docs/ONERA_M6.md, "How far the wall
/// correction reaches").
pub const BLEND_POWER: i32 = 10;

/// The width a of the flat part of the goal blend ([`BLEND_POWER`]): ψ ≥ e^{−(v₀/a)²}, so that
/// the first nodes of a coarse column still take the prescribed heights (the lid example's
/// 0.993 … 1.007 of them; 0.977 … 1.027 with (1 − v₀)^10 alone).
pub const BLEND_FLAT: f64 = 0.05;

/// The distances a column should reach: d*^ψ d₀^{1−ψ}, ψ = max((1 − v₀)^q, e^{−(v₀/a)²}) with
/// q = [`BLEND_POWER`] and a = [`BLEND_FLAT`], from its wall-oriented parameters `v0` and
/// distances `d0` of the uncorrected grid and the interpolated edge profile `dstar`: the edges'
/// profile at the wall, the uncorrected grid towards the opposite face.
pub(crate) fn blend_targets(v0: &[f64], d0: &[f64], dstar: &[f64]) -> Vec<f64> {
    v0.iter()
        .zip(d0.iter().zip(dstar))
        .map(|(&v, (&d, &t))| {
            let psi = (1.0 - v)
                .powi(BLEND_POWER)
                .max((-(v / BLEND_FLAT).powi(2)).exp());
            t.powf(psi) * d.powf(1.0 - psi)
        })
        .collect()
}

/// Remaps one column (wall-oriented: `v[0]` = 0 at the wall, last = 1) from its measured
/// distances `d` from the wall towards the targets `t` (v ← v t/d, as X is locally linear in
/// v). Returns the column's largest |ln(t/d)| before the remap. Falls back to the monotone
/// remap of the first node's ratio if the node-wise ratios would break monotonicity.
pub(crate) fn remap_column(v: &mut [f64], d: &[f64], t: &[f64]) -> f64 {
    let n = v.len();
    let ratio = |j: usize| (t[j] / d[j]).clamp(1.0 / MAX_RATIO, MAX_RATIO);
    let err = (1..n - 1)
        .map(|j| (t[j] / d[j]).ln().abs())
        .fold(0.0, f64::max);
    let new: Vec<f64> = (0..n)
        .map(|j| {
            if j == 0 || j == n - 1 {
                v[j]
            } else {
                v[j] * ratio(j)
            }
        })
        .collect();
    if new.windows(2).all(|p| p[1] > p[0]) {
        v.copy_from_slice(&new);
    } else {
        let r = ratio(1);
        for x in &mut v[1..n - 1] {
            *x = remap(*x, r);
        }
    }
    err
}

/// Where the interior columns' goal profiles (distances from the wall) come from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WallProfiles {
    /// The bilinear interpolation of the four edges leaving the wall (module docs).
    #[default]
    Edges,
    /// The transfinite interpolation of the columns of the four side faces
    /// ([`super::wall_profile`]): a column next to a fixed side face (an interface gridded
    /// before the volume) then follows that face's profile, not the edges'.
    Faces,
}

/// Target distances from a wall face (module docs).
#[derive(Clone, Debug)]
pub struct WallTargets {
    w: usize,
    dims: [usize; 3],
    /// Bilinear weights of the four edges at each wall face node (face order).
    weights: Vec<[f64; 4]>,
    /// Distance from the wall of node j (counted from the wall) on the four edges leaving it.
    prof: [Vec<f64>; 4],
    /// With [`WallProfiles::Faces`]: the whole goal column of each wall face node (face
    /// order, `dims[normal]` distances each); empty otherwise.
    cols: Vec<f64>,
}

impl WallTargets {
    /// The targets of wall face `w` of `faces`, from the four edges leaving it.
    pub fn new(faces: &Faces, w: usize, place: &str) -> Result<Self> {
        let dims = faces.dims();
        let (d, lo) = normal(w);
        let (ta, tb) = tangents(w);
        let prof: [Vec<f64>; 4] = std::array::from_fn(|bits| {
            let mut p = faces.edge(4 * d + bits);
            if !lo {
                p.reverse();
            }
            p.iter().map(|q| dist(*q, p[0])).collect()
        });
        // Arclength parameters (not the flat-edge warp of the transformation): the targets
        // interpolate the edges' profiles along the wall.
        let pg = bilinear(&EdgeFunctions3::arclength(faces), place)?;
        let [na, nb] = face_dims(w, dims);
        let mut weights = Vec::with_capacity(na * nb);
        for b in 0..nb {
            for a in 0..na {
                let n = block_node(w, a, b, dims);
                let v = pg.at(n[0] + dims[0] * (n[1] + dims[1] * n[2]));
                let (p, q) = (v[ta], v[tb]);
                weights.push([(1.0 - p) * (1.0 - q), p * (1.0 - q), (1.0 - p) * q, p * q]);
            }
        }
        Ok(WallTargets {
            w,
            dims,
            weights,
            prof,
            cols: Vec::new(),
        })
    }

    /// The targets of wall face `w` with the goal profiles from `profiles`.
    pub fn with_profiles(
        faces: &Faces,
        w: usize,
        profiles: WallProfiles,
        place: &str,
    ) -> Result<Self> {
        let mut t = WallTargets::new(faces, w, place)?;
        if profiles == WallProfiles::Faces {
            t.cols =
                super::wall_profile::face_columns(faces, w, &t.weights, &|n, j| t.edges_at(n, j));
        }
        Ok(t)
    }

    /// Targets given column by column: `cols` holds, for each node of wall face `w` of a block
    /// of `dims` nodes (face order), the goal distances of its `dims[normal]` column nodes
    /// (the columns of a floating face's strip, gathered from its volumes' targets).
    pub fn from_columns(w: usize, dims: [usize; 3], cols: Vec<f64>) -> Self {
        let [na, nb] = face_dims(w, dims);
        debug_assert_eq!(cols.len(), na * nb * dims[normal(w).0]);
        WallTargets {
            w,
            dims,
            weights: Vec::new(),
            prof: std::array::from_fn(|_| Vec::new()),
            cols,
        }
    }

    /// The target of the edges' bilinear interpolation (whatever the profiles).
    #[inline]
    pub(crate) fn edges_at(&self, n: [usize; 3], j: usize) -> f64 {
        let (ta, tb) = tangents(self.w);
        let na = face_dims(self.w, self.dims)[0];
        let wt = &self.weights[n[ta] + na * n[tb]];
        (0..4).map(|e| wt[e] * self.prof[e][j]).sum()
    }

    /// Target distance from the wall of the j-th node (from the wall) of the column at the
    /// wall node of block index `n`.
    #[inline]
    pub fn at(&self, n: [usize; 3], j: usize) -> f64 {
        if self.cols.is_empty() {
            return self.edges_at(n, j);
        }
        let (ta, tb) = tangents(self.w);
        let na = face_dims(self.w, self.dims)[0];
        let m = self.dims[normal(self.w).0];
        self.cols[(n[ta] + na * n[tb]) * m + j]
    }

    /// Target first-cell heights at the nodes of the wall face (face order).
    pub fn first_heights(&self) -> Vec<f64> {
        let [na, nb] = face_dims(self.w, self.dims);
        let mut out = Vec::with_capacity(na * nb);
        for b in 0..nb {
            for a in 0..na {
                out.push(self.at(block_node(self.w, a, b, self.dims), 1));
            }
        }
        out
    }
}

/// Target first-cell heights at the nodes of wall face `w` (face order (a, b), a fastest):
/// the bilinear interpolation, in the wall face's parameters from the bilinear transformation
/// of the edges, of the first spacings of the four edges leaving the wall.
pub fn wall_targets(faces: &Faces, w: usize, place: &str) -> Result<Vec<f64>> {
    Ok(WallTargets::new(faces, w, place)?.first_heights())
}

/// First-cell heights at the nodes of face `w` of a grid (face order): the lengths of the
/// first grid lines off the face.
pub fn first_heights(g: &Grid3, w: usize) -> Vec<f64> {
    let dims = g.dims();
    let (d, lo) = normal(w);
    let [na, nb] = face_dims(w, dims);
    let mut out = Vec::with_capacity(na * nb);
    for b in 0..nb {
        for a in 0..na {
            let n = block_node(w, a, b, dims);
            let m = step_in(n, d, lo);
            out.push(dist(g.point(n[0], n[1], n[2]), g.point(m[0], m[1], m[2])));
        }
    }
    out
}

/// Largest relative deviation |h / target − 1| of the first-cell heights at wall face `w`.
pub fn height_error(g: &Grid3, w: usize, targets: &[f64]) -> f64 {
    first_heights(g, w)
        .iter()
        .zip(targets)
        .map(|(h, t)| (h / t - 1.0).abs())
        .fold(0.0, f64::max)
}

/// Corrects the faces of a block that share an edge with wall face `w` (module docs).
/// `params(f)` gives face f's straight-line parameters and `eval(f, pg, g)` regrids face f
/// from remapped parameters `pg`, starting from its current grid `g`.
pub fn correct_side_faces(
    faces: &Faces,
    w: usize,
    place: &str,
    params: &mut dyn FnMut(usize) -> ParamGrid,
    eval: &mut dyn FnMut(usize, &ParamGrid, &Grid2<3>) -> Result<Grid2<3>>,
) -> Result<Faces> {
    let dims = faces.dims();
    let targets = WallTargets::new(faces, w, place)?;
    let (d, lo) = normal(w);
    let mut out: [Grid2<3>; 6] = std::array::from_fn(|f| faces.face(f).clone());
    for (f, face) in out.iter_mut().enumerate() {
        if f / 2 == d {
            continue;
        }
        // The face's column direction (along d) is its a or its b.
        let along_a = tangents(f).0 == d;
        let [na, nb] = face_dims(f, dims);
        let (ncol, nrow) = if along_a { (nb, na) } else { (na, nb) };
        // Face node of column `col`, `j` nodes off the wall.
        let node = |col: usize, j: usize| {
            let row = if lo { j } else { nrow - 1 - j };
            if along_a {
                (row, col)
            } else {
                (col, row)
            }
        };
        let mut pg = params(f);
        let mut g = face.clone();
        let mut best: Option<(f64, Grid2<3>)> = None;
        let mut goal: Vec<Vec<f64>> = Vec::new();
        for _ in 0..=MAX_PASSES {
            let v = if along_a { &mut pg.s } else { &mut pg.t };
            let mut err = 0.0f64;
            for col in 1..ncol - 1 {
                let idx: Vec<usize> = (0..nrow)
                    .map(|j| {
                        let (a, b) = node(col, j);
                        a + na * b
                    })
                    .collect();
                let (a0, b0) = node(col, 0);
                let wall_node = block_node(f, a0, b0, dims);
                let p0 = g.point(a0, b0);
                let dm: Vec<f64> = (0..nrow)
                    .map(|j| {
                        let (a, b) = node(col, j);
                        dist(g.point(a, b), p0)
                    })
                    .collect();
                let mut col_v: Vec<f64> = idx
                    .iter()
                    .map(|&p| if lo { v[p] } else { 1.0 - v[p] })
                    .collect();
                if goal.len() < col {
                    let tg: Vec<f64> = (0..nrow).map(|j| targets.at(wall_node, j)).collect();
                    goal.push(blend_targets(&col_v, &dm, &tg));
                }
                err = err.max(remap_column(&mut col_v, &dm, &goal[col - 1]));
                for (&p, x) in idx.iter().zip(&col_v) {
                    v[p] = if lo { *x } else { 1.0 - x };
                }
            }
            // A pass that does not improve the face ends the loop (a Coons face may not
            // follow its parameters near the wall).
            match &best {
                Some((e, _)) if err >= *e => break,
                _ => best = Some((err, g.clone())),
            }
            if err <= TOLERANCE {
                break;
            }
            g = eval(f, &pg, &g)?;
        }
        *face = best.map(|b| b.1).unwrap_or(g);
    }
    Faces::new(out, place)
}

/// One correction pass over the interior columns of a volume: remaps the normal parameter of
/// `pg` from the distances in `x` towards the column goals (filled from the first grid seen,
/// the uncorrected one, if empty). Returns the largest |ln(goal/d)| before the pass.
/// With `ortho`, distances are measured as [`wall_normal::TangentGoals::distance`]; with
/// `crossings`, the goals of the columns next to the crossed side faces follow them
/// ([`Crossings::goal_distances`]).
pub(crate) fn remap_volume(
    pg: &mut ParamGrid3,
    x: &Grid3,
    targets: &WallTargets,
    goal: &mut Vec<Vec<f64>>,
    ortho: Option<&wall_normal::TangentGoals>,
    crossings: Option<&Crossings>,
) -> f64 {
    let dims = pg.dims();
    let w = targets.w;
    let (d, lo) = normal(w);
    let [na, nb] = face_dims(w, dims);
    let n_col = dims[d];
    let v = match d {
        0 => &mut pg.s,
        1 => &mut pg.t,
        _ => &mut pg.u,
    };
    let mut err = 0.0f64;
    for b in 1..nb - 1 {
        for a in 1..na - 1 {
            let wall_node = block_node(w, a, b, dims);
            let mut nodes = Vec::with_capacity(n_col);
            let mut n = wall_node;
            nodes.push(n);
            for _ in 1..n_col {
                n = step_in(n, d, lo);
                nodes.push(n);
            }
            let idx: Vec<usize> = nodes
                .iter()
                .map(|n| n[0] + dims[0] * (n[1] + dims[1] * n[2]))
                .collect();
            let p0 = x.point(wall_node[0], wall_node[1], wall_node[2]);
            let c = (a - 1) + (na - 2) * (b - 1);
            let nrm = ortho.and_then(|_| wall_normal::wall_normal(x, w, a, b));
            let dm: Vec<f64> = nodes
                .iter()
                .enumerate()
                .map(|(j, n)| {
                    let q = x.point(n[0], n[1], n[2]);
                    match ortho {
                        Some(o) => {
                            let r = std::array::from_fn(|e| q[e] - p0[e]);
                            o.distance(c, j, r, nrm)
                        }
                        None => dist(q, p0),
                    }
                })
                .collect();
            let mut col_v: Vec<f64> = idx
                .iter()
                .map(|&p| if lo { v[p] } else { 1.0 - v[p] })
                .collect();
            if goal.len() <= c {
                let tg: Vec<f64> = (0..n_col).map(|j| targets.at(wall_node, j)).collect();
                let mut g = blend_targets(&col_v, &dm, &tg);
                if let Some(cr) = crossings {
                    let measure = |j: usize, r: [f64; 3]| match ortho {
                        Some(o) => o.distance(c, j, r, nrm),
                        None => (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt(),
                    };
                    cr.goal_distances(x, [a, b], &mut g, &measure);
                }
                goal.push(g);
            }
            err = err.max(remap_column(&mut col_v, &dm, &goal[c]));
            for (&p, y) in idx.iter().zip(&col_v) {
                v[p] = if lo { *y } else { 1.0 - y };
            }
        }
    }
    err
}

/// [`grid_volume_wall_with`] with the default [`WallOptions`].
pub fn grid_volume_wall(
    faces: &Faces,
    w: usize,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<VolumeResult> {
    let opts = WallOptions::default();
    grid_volume_wall_with(faces, w, opts, solver, params, place, progress)
}

/// Grids a volume block as [`crate::elliptic::volume::grid_volume`] and then holds the wall-normal distances
/// of the interior columns of wall face `w` to [`WallTargets`] (module docs), with
/// `opts.orthogonal` also the directions of the lines leaving the wall ([`wall_normal`]): at
/// most [`MAX_PASSES`] remaps of the algebraic parameters, each followed by a Picard solve from
/// the current grid ([`crate::elliptic::orthogonal3d`]). The returned history is the
/// concatenation of all solves.
pub fn grid_volume_wall_with(
    faces: &Faces,
    w: usize,
    opts: WallOptions,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<VolumeResult> {
    let mut orthogonal = [false; 6];
    orthogonal[w] = opts.orthogonal;
    let c = FaceCorrections {
        wall: Some(w),
        orthogonal,
        ..Default::default()
    };
    grid_volume_corrected(faces, &c, None, solver, params, place, progress)
}

/// A wall spacing needs algebraic control functions (Laplace grids lose it).
pub fn check_kind(kind: ControlKind, place: &str) -> Result<()> {
    match kind {
        ControlKind::Algebraic => Ok(()),
        ControlKind::Laplace => Err(Error::input(
            place,
            "wall needs control = \"algebraic\" (Laplace grids lose the wall spacing)",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::faces::parse_face;

    #[test]
    fn a_box_with_equal_distributions_needs_no_correction() {
        // The tensor-product box is the exact discrete solution and its columns follow the
        // edges' profiles: the wall pass must stop at once and return the box.
        let xs: Vec<f64> = (0..7).map(|k| 2.0 * (k as f64 / 6.0).powf(1.5)).collect();
        let ys: Vec<f64> = (0..8)
            .map(|k| ((k as f64 / 7.0) * 3.0).sinh() / 3f64.sinh())
            .collect();
        let zs: Vec<f64> = (0..6).map(|k| 0.4 * k as f64 / 5.0).collect();
        let mut exact = Grid3::zeros(7, 8, 6);
        for (k, z) in zs.iter().enumerate() {
            for (j, y) in ys.iter().enumerate() {
                for (i, x) in xs.iter().enumerate() {
                    exact.set(i, j, k, [*x, *y, *z]);
                }
            }
        }
        let faces = Faces::from_grid(&exact);
        let w = parse_face("F3").unwrap();
        let t = wall_targets(&faces, w, "box").unwrap();
        assert!(t.iter().all(|h| (h - ys[1]).abs() < 1e-15));
        let r = grid_volume_wall(
            &faces,
            w,
            &mut crate::solve::direct::DirectLu3::new(),
            &PicardParams::default(),
            "box",
            &mut |_, _| {},
        )
        .unwrap();
        assert!(r.picard.converged);
        assert!(height_error(&r.grid, w, &t) < 1e-12);
        for c in 0..3 {
            for (u, v) in r.grid.coord(c).iter().zip(exact.coord(c)) {
                assert!((u - v).abs() < 1e-12, "{u} vs {v}");
            }
        }
        assert!(parse_face("F7").is_none());
    }

    #[test]
    fn remap_scales_the_first_step_and_keeps_the_ends() {
        for r in [0.3, 1.0, 2.5, 4.0] {
            assert_eq!(remap(0.0, r), 0.0);
            assert!((remap(1.0, r) - 1.0).abs() < 1e-15);
            let v = 1e-6;
            assert!((remap(v, r) / v - r).abs() < 1e-5 * r);
            let mut prev = 0.0;
            for k in 1..=1000 {
                let g = remap(k as f64 / 1000.0, r);
                assert!(g > prev, "not monotone for r = {r}");
                prev = g;
            }
        }
    }
}
