//! Surface blocks of a case file (`kind = "surface"`, Section 4): the surface, and the (u, v)
//! of the boundary nodes distributed by 3D arclength along the surface's own edges.

use crate::case::spec::{SurfaceRef, SurfaceSpec};
use crate::case::{point, LoadedCase};
use crate::grid::Edge;
use crate::io::{plot3d, Block};
use crate::surface::pipeline::{edge_length, edge_map, edge_params_on};
use crate::{Error, Result};
use ellipgrid_geometry::{self as geo, Surface, Vec3};
use std::path::Path;

impl LoadedCase {
    /// The surface of block k, boxed.
    pub fn surface(&self, k: usize) -> Result<Box<dyn Surface>> {
        let place = self.block_place(k);
        match &self.case.blocks[k].surface {
            Some(SurfaceRef::Inline(spec)) => self.build_surface(spec, &place),
            Some(SurfaceRef::Named(name)) => Ok(Box::new(self.named_surface(name, &place)?)),
            None => Err(Error::input(
                place,
                "a surface block needs surface = { type = ... } (or the name of a [[surface]])",
            )),
        }
    }

    /// The `reference` surface of block k, if any: the report gives the distance of the
    /// grid's nodes from it (e.g. Scherk's surface for a minimal-surface block).
    pub fn reference_surface(&self, k: usize) -> Result<Option<Box<dyn Surface>>> {
        let place = format!("{}, reference", self.block_place(k));
        self.case.blocks[k]
            .reference
            .as_ref()
            .map(|spec| self.build_surface(spec, &place))
            .transpose()
    }

    /// A surface from its spec (`place` names it in errors).
    pub(crate) fn build_surface(
        &self,
        spec: &SurfaceSpec,
        place: &str,
    ) -> Result<Box<dyn Surface>> {
        let place = place.to_string();
        let geo_err = |source| Error::Geometry {
            place: place.clone(),
            source,
        };
        Ok(match spec {
            SurfaceSpec::HermiteNet {
                file: Some(file),
                block,
                ni: None,
                nj: None,
                points: None,
            } => {
                let path = self.path.parent().unwrap_or(Path::new(".")).join(file);
                Box::new(crate::case::within(
                    &place,
                    read_net(&path, block.unwrap_or(1)),
                )?)
            }
            SurfaceSpec::HermiteNet {
                file: None,
                block: None,
                ni: Some(ni),
                nj: Some(nj),
                points: Some(points),
            } => {
                // ni × nj overflow-safe: 2³² × 2³² must not wrap to a count that matches
                if ni.checked_mul(*nj) != Some(points.len()) {
                    return Err(Error::input(
                        place,
                        format!(
                            "hermite_net: {} points given, ni × nj = {ni} × {nj}",
                            points.len(),
                        ),
                    ));
                }
                let pts = points
                    .iter()
                    .enumerate()
                    .map(|(k, q)| point(q, &place, &format!("points[{k}]")))
                    .collect::<Result<Vec<_>>>()?;
                Box::new(geo::HermiteSurface::new(*ni, *nj, pts).map_err(geo_err)?)
            }
            SurfaceSpec::HermiteNet { .. } => {
                return Err(Error::input(
                    place,
                    "hermite_net takes either file (and block) or ni, nj and points",
                ))
            }
            SurfaceSpec::Plane { origin, du, dv } => Box::new(geo::Plane {
                origin: point(origin, &place, "origin")?,
                du: point(du, &place, "du")?,
                dv: point(dv, &place, "dv")?,
            }),
            SurfaceSpec::TanhBump {} => Box::new(geo::TanhBump::default()),
            SurfaceSpec::Scherk { half_width } => {
                Box::new(geo::Scherk::new(*half_width).map_err(geo_err)?)
            }
            SurfaceSpec::Step { .. } => {
                return Err(Error::input(
                    place,
                    "a STEP model (type = \"step\") is the surface of a block whose four edges \
                     lie on it: give it inline as a surface block's surface (`ellipgrid run`), \
                     not as a named or reference surface",
                ))
            }
        })
    }

    /// Whether block k is a block face on a STEP model (`surface = { type = "step", ... }`).
    pub fn is_model_block(&self, k: usize) -> bool {
        matches!(
            self.case.blocks[k].surface,
            Some(SurfaceRef::Inline(SurfaceSpec::Step { .. }))
        )
    }

    /// The surface of block k and the (u, v) of its boundary nodes (E1..E4, index order),
    /// placed by each edge's distribution along the surface's edge curve.
    #[allow(clippy::type_complexity)]
    pub fn surface_block(&self, k: usize) -> Result<(Box<dyn Surface>, [Vec<[f64; 2]>; 4])> {
        let surface = self.surface(k)?;
        let uv = self.surface_uv(k, surface.as_ref())?;
        Ok((surface, uv))
    }

    /// The (u, v) of the boundary nodes of surface block k (E1..E4, index order) on `surface`
    /// (the block's own surface, or the same surface re-parametrized): each edge's
    /// distribution by 3D arclength along the surface's edge curve, or its nodes projected.
    pub fn surface_uv(&self, k: usize, surface: &dyn Surface) -> Result<[Vec<[f64; 2]>; 4]> {
        let place = self.block_place(k);
        self.check_size(k)?;
        let mut uv: [Vec<[f64; 2]>; 4] = Default::default();
        let [ni, nj] = self.block_dims(k);
        // On a STEP model the edges' curves made the net; its own sides carry them now.
        let on_model = self.is_model_block(k);
        for (e, spec) in Edge::ALL.into_iter().zip(self.edge_specs(k)?) {
            let at = format!("{place}, edge {e}");
            let n = if e.runs_along_i() { ni } else { nj };
            let curve = if on_model {
                (&None, false)
            } else {
                (&spec.curve, spec.reverse)
            };
            uv[e.index()] = match curve {
                (None, false) => {
                    let map = edge_map(surface, e);
                    let sigma = spec.distribution.sample(n, map.length(), &at)?;
                    edge_params_on(&map, e, &sigma)
                }
                (Some(crate::case::CurveSpec::Nodes { points }), false)
                    if matches!(spec.distribution, crate::case::DistributionSpec::Uniform {}) =>
                {
                    project_nodes(surface, e, points, n, &at)?
                }
                _ => {
                    return Err(Error::input(
                        at,
                        "the edges of a surface block are the surface's own edges: give a \
                         distribution, or the edge's nodes as curve = { type = \"nodes\", \
                         points = [...] } (projected onto the surface's edge)",
                    ))
                }
            };
        }
        Ok(uv)
    }
}

/// The (u, v) of given edge nodes, each projected onto the surface's edge curve by Newton
/// (Section 4.2 step 1); the nodes must lie on that curve (within 1e-6 of its length) and
/// run along it in order, the ends at the corners.
fn project_nodes(
    surface: &dyn Surface,
    e: Edge,
    points: &[Vec<f64>],
    n: usize,
    at: &str,
) -> Result<Vec<[f64; 2]>> {
    if points.len() != n {
        return Err(Error::input(
            at,
            format!(
                "{} nodes given but the block needs {n} on this edge",
                points.len()
            ),
        ));
    }
    let side = crate::surface::pipeline::surface_edge(e);
    let len = edge_length(surface, e);
    let mut out = Vec::with_capacity(n);
    let mut prev = 0.0f64;
    for (k, q) in points.iter().enumerate() {
        let p = point(q, at, &format!("points[{k}]"))?;
        let t = if k == 0 {
            0.0
        } else if k + 1 == n {
            1.0
        } else {
            geo::project_to_edge(surface, side, p, prev).ok_or_else(|| {
                Error::input(at, format!("node {k} could not be projected onto the edge"))
            })?
        };
        let (u, v) = side.uv(t);
        let d = (surface.point(u, v) - p).norm();
        if d > 1e-6 * len {
            return Err(Error::input(
                at,
                format!("node {k} is {d:.3e} away from the surface's edge"),
            ));
        }
        if k > 0 && t <= prev {
            return Err(Error::input(
                at,
                format!("node {k} does not advance along the edge"),
            ));
        }
        prev = t;
        out.push([u, v]);
    }
    Ok(out)
}

/// A Hermite control net from block `block` (1-based) of a Plot3D file.
pub fn read_net(path: &Path, block: usize) -> Result<geo::HermiteSurface> {
    let file = plot3d::read_plot3d(path)?;
    let place = format!("{}: block {block}", path.display());
    let b = file.blocks.get(block.wrapping_sub(1)).ok_or_else(|| {
        Error::input(
            &place,
            format!("the file has {} block(s)", file.blocks.len()),
        )
    })?;
    let (ni, nj, pts): (usize, usize, Vec<Vec3>) = match b {
        Block::Surface(g) => (
            g.ni(),
            g.nj(),
            (0..g.len())
                .map(|n| Vec3::new(g.coord(0)[n], g.coord(1)[n], g.coord(2)[n]))
                .collect(),
        ),
        Block::Planar(g) => (
            g.ni(),
            g.nj(),
            (0..g.len())
                .map(|n| Vec3::new(g.coord(0)[n], g.coord(1)[n], 0.0))
                .collect(),
        ),
        Block::Volume(_) => {
            return Err(Error::input(
                place,
                "a control net must be a surface block (nk = 1)",
            ))
        }
    };
    geo::HermiteSurface::new(ni, nj, pts).map_err(|source| Error::Geometry { place, source })
}
