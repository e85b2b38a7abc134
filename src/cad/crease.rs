//! Untrimmed patches that are really several faces: a B-spline patch whose surface turns
//! sharply across an interior iso-line (OpenVSP writes a whole wing as one patch, its flat
//! root and tip caps as the first and last spanwise knot spans, the skin meeting them at
//! ~90°), cut along those *creases* into sub-patches, each gridded as its own block.
//!
//! A crease is an interior knot of multiplicity ≥ the degree (the surface is at most C0
//! there: [`BSplineSurf::c0_knots`]) where the two sides meet (a C0 line, not a gap) and the
//! surface normal turns by more than [`CREASE_TURN`] at every sample of the iso-line where
//! both sides' normals are defined ([`SAMPLES`] + 1 samples; poles are skipped). Smaller
//! turns (the kinks between the sections of a wing with dihedral or sweep breaks) are not
//! creases.
//!
//! Where the patch has creases, C0 iso-lines along which a sub-patch between them collapses
//! to one point are cut too ([`CutKind::Pole`]): OpenVSP's caps are lenses between the
//! airfoil and its camber line traversed twice, whose leading-edge iso-line is one point; a
//! grid line must run along it, or the cells beside it fold. (Such a line must be a C0 knot,
//! as in OpenVSP's piecewise Bézier sections: no knots are inserted.)
//!
//! The sub-patches ([`BSplineSurf::split_at`]: the same control points, no approximation)
//! are gridded as untrimmed patches ([`grid_patch`]), each with the face's `ni × nj` nodes
//! and distributions (a spacing given at a side's ends applies at each block's ends, the
//! crease too). A sub-patch without area (a row of control points doubled back onto a line
//! or a point) is left out, as [`super::patch::has_area`] refuses such bare patches. Blocks
//! that meet along a crease get the same nodes there: each side is placed by its own
//! arclength on the same curve (the pieces share its control points), and the second
//! block's side is then set to the first's bit for bit (they differ by round-off only;
//! more than [`MATCH`] of the patch's size is an error).

pub use super::cut_line::{Crease, CutKind};
use super::face::FaceGrid;
use super::patch::{grid_patch, has_area};
use super::{Route, StepFace};
use crate::case::DistributionSpec;
use crate::grid::Edge;
use crate::solve::LinearSolver;
use crate::{Error, Result};
use ellipgrid_geometry::{BSplineSurf, Surface, Vec3};
use std::borrow::Cow;

/// Smallest turn of the normal (degrees) across a C0 iso-line, at every sample, that makes
/// it a crease.
pub const CREASE_TURN: f64 = 30.0;

/// Intervals along an iso-line at which its turn is sampled.
pub const SAMPLES: usize = 64;

/// Largest distance (relative to the patch's sampled diameter) between the two sides of a C0
/// iso-line, and between two blocks' nodes on a shared crease before they are made equal.
const MATCH: f64 = 1e-9;

/// The creases of an untrimmed patch (a face whose [`Route`] is a patch), u lines first, in
/// parameter order; none for any other face.
pub fn creases(face: &StepFace) -> Vec<Crease> {
    match (&face.surface, face.route()) {
        (Some(s), Route::Patch) => surface_cuts(s),
        _ => Vec::new(),
    }
}

/// Every line an untrimmed patch is cut along when its one block folds: its creases (and
/// poles, [`surface_creases`]), the lines beyond which it folds back over itself and, if it
/// has no crease, its sides' kinks (`cad::boundary_cuts`); u lines first, each direction
/// in parameter order.
pub fn surface_cuts(s: &BSplineSurf) -> Vec<Crease> {
    let mut out = surface_creases(s);
    let size = diameter(s);
    let folds = super::boundary_cuts::fold_backs(s, size);
    if out.is_empty() {
        out.extend(super::boundary_cuts::kinks(s, size));
    }
    // a kink or crease inside a left-out piece is not cut
    out.retain(|c| {
        !folds.iter().any(|f| match f.kind {
            CutKind::FoldBack { end } if f.dir == c.dir => (c.at > f.at) == (end == 1),
            _ => false,
        })
    });
    out.extend(folds);
    out.sort_by(|a, b| a.dir.cmp(&b.dir).then(a.at.total_cmp(&b.at)));
    out.dedup_by(|a, b| a.dir == b.dir && a.at == b.at);
    out
}

/// The number of blocks [`grid_creased`] grids `face` into: its sub-patches with area (the
/// memory budget of `step grid`); 1 for a face without creases.
pub fn creased_blocks(face: &StepFace) -> usize {
    let creases = creases(face);
    let Some(s) = face.surface.as_ref().filter(|_| !creases.is_empty()) else {
        return 1;
    };
    let size = diameter(s);
    pieces(s, &creases).map_or(1, |rows| {
        let flaps = flaps(&creases);
        let n = (rows.iter().enumerate())
            .flat_map(|(a, row)| row.iter().enumerate().map(move |(b, p)| (a, b, p)))
            .filter(|&(a, b, p)| !left_out(&flaps, (a, b), p, size))
            .count();
        n.max(1)
    })
}

/// The pieces left out beyond fold-back lines: (direction, piece index in it).
fn flaps(creases: &[Crease]) -> Vec<(usize, usize)> {
    creases
        .iter()
        .filter_map(|c| match c.kind {
            CutKind::FoldBack { end } => {
                let n = creases.iter().filter(|d| d.dir == c.dir).count();
                Some((c.dir, if end == 1 { n } else { 0 }))
            }
            _ => None,
        })
        .collect()
}

/// Whether the sub-patch (a, b) (`a`-th in u, `b`-th in v) is not gridded: a flap beyond a
/// fold-back line, or no surface ([`negligible`]).
fn left_out(flaps: &[(usize, usize)], (a, b): (usize, usize), p: &BSplineSurf, size: f64) -> bool {
    flaps.contains(&(0, a)) || flaps.contains(&(1, b)) || negligible(p, size)
}

/// The creases of a B-spline surface and, if it has any, the C0 iso-lines along which a
/// sub-patch between them collapses to a point ([`CutKind::Pole`]); u lines first, each
/// direction in parameter order (see the module doc).
pub fn surface_creases(s: &BSplineSurf) -> Vec<Crease> {
    let size = diameter(s);
    let mut out = Vec::new();
    let mut candidates = [Vec::new(), Vec::new()];
    for (dir, cand) in candidates.iter_mut().enumerate() {
        let cuts = s.c0_knots(dir);
        let Ok(pieces) = s.split_at(dir, &cuts) else {
            continue;
        };
        for (k, &at) in cuts.iter().enumerate() {
            let t = turn(&pieces[k], &pieces[k + 1], dir, size);
            match t {
                Some(turn) if turn[0] > CREASE_TURN => out.push(Crease {
                    dir,
                    at,
                    turn,
                    kind: CutKind::Crease,
                }),
                // a C0 line (no gap), not a crease
                Some(turn) => cand.push((at, turn)),
                None if meets(s, dir, at, size) => cand.push((at, [f64::NAN; 2])),
                None => {}
            }
        }
    }
    if out.is_empty() {
        return out;
    }
    // Lines across which a sub-patch between creases collapses: cut along them too.
    for (dir, cand) in candidates.iter().enumerate() {
        let other = 1 - dir;
        let mut ends: Vec<f64> = out
            .iter()
            .filter(|c| c.dir == other)
            .map(|c| c.at)
            .collect();
        ends.insert(0, 0.0);
        ends.push(1.0);
        for &(at, turn) in cand {
            let collapses = ends.windows(2).any(|w| {
                let p = |t: f64| {
                    let t = w[0] + t * (w[1] - w[0]);
                    if dir == 0 {
                        s.point(at, t)
                    } else {
                        s.point(t, at)
                    }
                };
                let p0 = p(0.0);
                (1..=16).all(|m| (p(m as f64 / 16.0) - p0).norm() <= MATCH * size)
            });
            if collapses {
                out.push(Crease {
                    dir,
                    at,
                    turn,
                    kind: CutKind::Pole,
                });
            }
        }
    }
    out.sort_by(|a, b| a.dir.cmp(&b.dir).then(a.at.total_cmp(&b.at)));
    out
}

/// Whether the two sides of the C0 iso-line `dir` = `at` meet (not a gap) where no sample
/// has both normals.
fn meets(s: &BSplineSurf, dir: usize, at: f64, size: f64) -> bool {
    let Ok(p) = s.split_at(dir, &[at]) else {
        return false;
    };
    (0..=SAMPLES).all(|m| {
        let t = m as f64 / SAMPLES as f64;
        let (a, b) = if dir == 0 {
            (p[0].point(1.0, t), p[1].point(0.0, t))
        } else {
            (p[0].point(t, 1.0), p[1].point(t, 0.0))
        };
        (a - b).norm() <= MATCH * size
    })
}

/// Diameter of a 17 × 17 sample of the surface.
pub(super) fn diameter(s: &dyn Surface) -> f64 {
    let (lo, hi) = (0..=16 * 16 + 16).fold(
        (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
        |(lo, hi), k| {
            let p = s.point((k % 17) as f64 / 16.0, (k / 17) as f64 / 16.0);
            (lo.inf(&p), hi.sup(&p))
        },
    );
    (hi - lo).norm()
}

/// Smallest and largest turn (degrees) of the normal from `a`'s end to `b`'s start in
/// direction `dir`, over the samples where both normals are defined; `None` if the two do not
/// meet (a gap) or no sample has both normals.
fn turn(a: &BSplineSurf, b: &BSplineSurf, dir: usize, size: f64) -> Option<[f64; 2]> {
    let at = |s: &BSplineSurf, end: f64, t: f64| {
        if dir == 0 {
            s.eval(end, t)
        } else {
            s.eval(t, end)
        }
    };
    let mut range = [f64::INFINITY, f64::NEG_INFINITY];
    for m in 0..=SAMPLES {
        let t = m as f64 / SAMPLES as f64;
        let (p, q) = (at(a, 1.0, t), at(b, 0.0, t));
        if (p.x - q.x).norm() > MATCH * size {
            return None;
        }
        let normal = |e: &ellipgrid_geometry::SurfacePoint| {
            let n = e.xu.cross(&e.xv);
            (n.norm() > 1e-8 * e.xu.norm() * e.xv.norm()).then(|| n.normalize())
        };
        if let (Some(n), Some(k)) = (normal(&p), normal(&q)) {
            let deg = n.dot(&k).clamp(-1.0, 1.0).acos().to_degrees();
            range = [range[0].min(deg), range[1].max(deg)];
        }
    }
    range[0].is_finite().then_some(range)
}

/// The sub-patches of `s` cut along `creases`: `rows[a][b]` is the a-th piece in u, b-th in
/// v.
fn pieces(s: &BSplineSurf, creases: &[Crease]) -> Result<Vec<Vec<BSplineSurf>>> {
    let cuts = |d: usize| -> Vec<f64> {
        creases
            .iter()
            .filter(|c| c.dir == d)
            .map(|c| c.at)
            .collect()
    };
    let geo = |e| Error::Geometry {
        place: "crease split".into(),
        source: e,
    };
    let (cu, cv) = (cuts(0), cuts(1));
    // a fold-back line need not be a knot: make it a C0 one first
    let mut s = Cow::Borrowed(s);
    for (d, c) in creases.iter().map(|c| (c.dir, c.at)) {
        if !s.c0_knots(d).contains(&c) {
            s = Cow::Owned(s.with_c0_knot(d, c).map_err(geo)?);
        }
    }
    s.split_at(0, &cu)
        .map_err(geo)?
        .iter()
        .map(|row| row.split_at(1, &cv).map_err(geo))
        .collect()
}

/// A sub-patch whose diameter is at most this fraction of the patch's is one point (the
/// round-off of the split: OpenVSP's caps end in trailing-edge pieces 1e-11 across on a
/// 200-long wing).
const POINT: f64 = 1e-9;

/// Whether a sub-patch of a patch of diameter `size` is left out: it has no area, or it is of
/// round-off size (a cap's trailing-edge point, which [`has_area`] alone takes for a tiny
/// surface).
fn negligible(piece: &dyn Surface, size: f64) -> bool {
    diameter(piece) <= POINT * size || has_area(piece).is_err()
}

/// An untrimmed patch with creases gridded as blocks, one per sub-patch with area, in the
/// order of u pieces, then v pieces within each (see the module doc); the number of
/// sub-patches left out for having no area.
///
/// # Errors
/// [`Error::Input`] at `place` if the face has no creases, no sub-patch has area, or two
/// blocks' nodes on a shared crease differ by more than round-off; those of [`grid_patch`]
/// (at `place, block k`).
pub fn grid_creased(
    face: &StepFace,
    (ni, nj): (usize, usize),
    dist_i: &DistributionSpec,
    dist_j: &DistributionSpec,
    solver: &mut dyn LinearSolver,
    place: &str,
) -> Result<(Vec<FaceGrid>, usize)> {
    let creases = creases(face);
    let Some(s) = face.surface.as_ref().filter(|_| !creases.is_empty()) else {
        return Err(Error::input(place, "not a patch with creases"));
    };
    let size = diameter(s);
    let rows = pieces(s, &creases)?;
    let mut results = Vec::new();
    // the block index of each sub-patch, if gridded
    let mut block: Vec<Vec<Option<usize>>> = Vec::with_capacity(rows.len());
    let mut skipped = 0;
    let flaps = flaps(&creases);
    for (a, row) in rows.iter().enumerate() {
        let mut ids = Vec::with_capacity(row.len());
        for (b, piece) in row.iter().enumerate() {
            if left_out(&flaps, (a, b), piece, size) {
                skipped += 1;
                ids.push(None);
                continue;
            }
            let at = format!("{place}, block {}", results.len());
            results.push(grid_patch(piece, (ni, nj), dist_i, dist_j, solver, &at)?);
            ids.push(Some(results.len() - 1));
        }
        block.push(ids);
    }
    if results.is_empty() {
        return Err(Error::input(
            place,
            "no sub-patch between its creases has area",
        ));
    }
    super::boundary_cuts::snap_fold_backs(s, &creases, &block, &mut results);
    // Shared crease sides: the lower block's E2 (E4) onto the upper block's E1 (E3).
    for (a, ids) in block.iter().enumerate() {
        for (b, id) in ids.iter().enumerate() {
            let Some(k) = *id else { continue };
            let below = [
                (
                    a.checked_sub(1).and_then(|a| block[a][b]),
                    Edge::E2,
                    Edge::E1,
                ),
                (b.checked_sub(1).and_then(|b| ids[b]), Edge::E4, Edge::E3),
            ];
            for (from, e, to) in below {
                let Some(from) = from else { continue };
                let src = results[from].grid.edge(e);
                let g = &mut results[k].grid;
                let far = src
                    .iter()
                    .zip(g.edge(to))
                    .map(|(p, q)| (0..3).map(|c| (p[c] - q[c]).powi(2)).sum::<f64>().sqrt())
                    .fold(0.0, f64::max);
                if far.partial_cmp(&(MATCH * size)) != Some(std::cmp::Ordering::Less) {
                    return Err(Error::input(
                        format!("{place}, block {k}"),
                        format!(
                            "its nodes on the crease are {far:.3e} from block {from}'s \
                             (a bug: they should differ by round-off only)"
                        ),
                    ));
                }
                for (m, p) in src.into_iter().enumerate() {
                    let (i, j) = match to {
                        Edge::E1 => (0, m),
                        _ => (m, 0),
                    };
                    g.set(i, j, p);
                }
            }
        }
    }
    let grids = results
        .into_iter()
        .map(|r| {
            let mut g = FaceGrid::new(r, Vec::new(), (0.0, 0.0), None);
            g.patch_cuts.clone_from(&creases);
            g
        })
        .collect();
    Ok((grids, skipped))
}

#[cfg(test)]
mod tests {
    use super::*;
    use truck_geometry::prelude::{BSplineSurface, KnotVec, Point3};

    fn bilinear(p: [[f64; 3]; 4]) -> BSplineSurf {
        let q = |k: usize| Point3::new(p[k][0], p[k][1], p[k][2]);
        let s = BSplineSurface::new(
            (KnotVec::bezier_knot(1), KnotVec::bezier_knot(1)),
            vec![vec![q(0), q(1)], vec![q(2), q(3)]],
        );
        BSplineSurf::from_truck_bspline(&s).unwrap()
    }

    #[test]
    fn round_off_pieces_are_points() {
        // the trailing-edge piece of the 777 tip cap: a point at (209.6, 35.1, 6.9) with
        // round-off of ~1e-11 between its corners, on a wing ~200 across
        let c = [209.575, 35.05549, 6.92673];
        let e = 1e-11;
        let dot = bilinear([
            c,
            [c[0] + e, c[1], c[2] + 0.3 * e],
            [c[0] - 0.7 * e, c[1], c[2] - e],
            [c[0] + 0.2 * e, c[1], c[2] + e],
        ]);
        // one point to round-off at its coordinates' magnitude: no area either
        assert!(has_area(&dot).is_err());
        assert!(negligible(&dot, 200.0));
        let square = bilinear([
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ]);
        assert!(!negligible(&square, 200.0));
        let line = bilinear([[0.0; 3], [1.0, 0.0, 0.0], [0.0; 3], [1.0, 0.0, 0.0]]);
        assert!(negligible(&line, 1.0));
    }
}
