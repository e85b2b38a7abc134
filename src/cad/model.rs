//! A STEP model as one surface for block faces that are not CAD faces (issue #14, item 4):
//! chosen faces of the file, each sampled over its own region, behind one closest-point
//! search ([`ModelLocator`]: a BVH over every face's sampled cells, then Newton on the face's
//! surface).

use super::{grid_face_blocks, StepFace};
use crate::case::DistributionSpec;
use crate::{Error, Result};
use ellipgrid_geometry::{
    Curve, ModelLocator, ModelSample, Surface, TruckCurve, TruckSurface, Vec3,
};
use truck_stepio::r#in::alias::Curve3D;

/// Cells per side of an untrimmed patch's uniform (u, v) sampling.
const PATCH_CELLS: usize = 64;
/// Nodes per side of the block grid that samples a trimmed face (its region, not its box).
const FACE_NODES: usize = 33;

/// The model made of `pick` (1-based face numbers, [`StepFace::index`]) of `faces`: an
/// untrimmed four-sided patch on its normalized (u, v) ∈ [0, 1]² sampled on 64 × 64 cells;
/// any other face on its surface's own parameters, sampled by its block grids at 33 × 33
/// ([`grid_face_blocks`]), so that the search stays inside its trimmed region (Newton is held
/// to the region's parameter box).
///
/// # Errors
/// [`Error::Input`] at `place` naming a face number not in the file, or a face that cannot be
/// sampled (with the reason).
pub fn step_model(faces: &[StepFace], pick: &[usize], place: &str) -> Result<ModelLocator> {
    let mut surfaces: Vec<Box<dyn Surface>> = Vec::with_capacity(pick.len());
    let mut samples = Vec::new();
    for (k, &n) in pick.iter().enumerate() {
        let at = format!("{place}, face {n}");
        let face = faces.iter().find(|f| f.index == n).ok_or_else(|| {
            Error::input(
                place,
                format!("face {n} is not in the file (it has {} faces)", faces.len()),
            )
        })?;
        if let (true, Some(s)) = (face.is_four_sided_patch(), &face.surface) {
            let m = PATCH_CELLS + 1;
            let uv: Vec<[f64; 2]> = (0..m * m)
                .map(|q| [(q % m) as f64, (q / m) as f64].map(|t| t / PATCH_CELLS as f64))
                .collect();
            let x = uv.iter().map(|q| s.point(q[0], q[1])).collect();
            samples.push(ModelSample {
                surface: k,
                ni: m,
                nj: m,
                x,
                uv,
            });
            surfaces.push(Box::new(s.clone()));
            continue;
        }
        let mut solver =
            crate::solve::select::by_name("multigrid").map_err(|m| Error::input(at.clone(), m))?;
        let u = DistributionSpec::Uniform {};
        let grids = grid_face_blocks(face, (FACE_NODES, FACE_NODES), &u, &u, solver.as_mut(), &at)
            .map_err(|e| Error::input(at.clone(), format!("cannot be sampled: {e}")))?;
        for g in grids {
            let grid = &g.result.grid;
            let x = (0..grid.len())
                .map(|q| Vec3::new(grid.coord(0)[q], grid.coord(1)[q], grid.coord(2)[q]))
                .collect();
            samples.push(ModelSample {
                surface: k,
                ni: grid.ni(),
                nj: grid.nj(),
                x,
                uv: g.result.uv.clone(),
            });
        }
        surfaces.push(Box::new(TruckSurface::new(face.cad_surface.clone())));
    }
    ModelLocator::new(surfaces, samples).map_err(|source| Error::Geometry {
        place: place.to_string(),
        source,
    })
}

/// Edges of a face's outer loop run one after the other as one curve (a block edge made of CAD
/// edges): [`EdgeChain::point`] at s ∈ [0, n] is edge ⌊s⌋ at the fraction s − ⌊s⌋ of its own
/// parameter, each edge in the loop's direction.
pub struct EdgeChain {
    curves: Vec<TruckCurve<Curve3D>>,
}

impl EdgeChain {
    /// Edges `edges` (1-based numbers in the face's outer loop, in loop order, as `step list
    /// --edges` prints them) of `face`.
    ///
    /// # Errors
    /// [`Error::Input`] at `place` if the face has no usable loop, an edge number is not in
    /// it, an edge is unbounded, or two consecutive edges do not meet (ends farther apart
    /// than 1e-3 of the chain's length).
    pub fn new(face: &StepFace, edges: &[usize], place: &str) -> Result<EdgeChain> {
        let outer = match &face.loops {
            Ok(l) if !l.is_empty() => &l[0],
            Ok(_) => {
                return Err(Error::input(
                    place,
                    format!("face {} has no loop", face.index),
                ))
            }
            Err(e) => return Err(Error::input(place, e.clone())),
        };
        if edges.is_empty() {
            return Err(Error::input(place, "edges = [...] names no edge"));
        }
        let mut curves = Vec::with_capacity(edges.len());
        for &n in edges {
            let e = n.checked_sub(1).and_then(|k| outer.get(k)).ok_or_else(|| {
                Error::input(
                    place,
                    format!(
                        "edge {n} is not in face {}'s loop (it has {} edges)",
                        face.index,
                        outer.len()
                    ),
                )
            })?;
            let c = TruckCurve::on(
                e.curve.clone(),
                e.range,
                e.forward,
                &super::edge::knots(&e.curve),
            )
            .ok_or_else(|| Error::input(place, format!("edge {n} is unbounded")))?;
            curves.push(c);
        }
        let chain = EdgeChain { curves };
        let len: f64 = chain
            .curves
            .iter()
            .map(|c| (c.point(1.0) - c.point(0.0)).norm())
            .sum();
        for (k, w) in chain.curves.windows(2).enumerate() {
            let gap = (w[1].point(0.0) - w[0].point(1.0)).norm();
            if gap.is_nan() || gap > 1e-3 * len {
                return Err(Error::input(
                    place,
                    format!(
                        "edges {} and {} of face {} do not meet ({gap:.3e} apart): give a \
                         chain of consecutive edges in loop order",
                        edges[k],
                        edges[k + 1],
                        face.index
                    ),
                ));
            }
        }
        Ok(chain)
    }

    /// Number of edges.
    pub fn len(&self) -> usize {
        self.curves.len()
    }

    /// True if the chain has no edge (never: [`EdgeChain::new`] refuses it).
    pub fn is_empty(&self) -> bool {
        self.curves.is_empty()
    }

    /// The chain's point at s ∈ [0, n].
    pub fn point(&self, s: f64) -> Vec3 {
        let n = self.curves.len();
        let k = (s.max(0.0).floor() as usize).min(n - 1);
        self.curves[k].point((s - k as f64).clamp(0.0, 1.0))
    }
}
