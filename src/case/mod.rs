//! The case file: a TOML description of blocks (edge curves, point counts, distributions),
//! solver options and outputs. See README.md, "Case files", for the reference.
//!
//! Parsing is strict (unknown keys are errors) and every error names the file, the block and
//! the edge. Relative input paths (airfoil tables) are relative to the case file's folder.

use crate::grid::boundary::Boundary2;
use crate::grid::Edge;
use crate::{Error, Result};
use ellipgrid_geometry::{self as geo, Curve, Vec3};

pub mod limits;
pub mod refine;
pub mod spec;
pub mod surface;
pub mod topology;
pub mod topology3;
pub mod volume;
use crate::grid::topology::volume::Topology3;
use crate::grid::topology::Topology;
pub use spec::{
    BlockKind, BlockSpec, Case, CurveSpec, DistributionSpec, EdgeSpec, FaceKind, FaceSpec,
    OutputSpec, SideSpec, SolverSpec, SurfaceSpec, TopoEdgeSpec, VertexSpec,
};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// A case file read from disk, with its folder for relative input paths.
#[derive(Clone, Debug)]
pub struct LoadedCase {
    pub path: PathBuf,
    pub case: Case,
    /// The multi-block topology (cases with `[[edge]]` tables and blocks).
    pub topology: Option<Topology>,
    /// The volume topology (cases with `[[face]]` tables).
    pub topology3: Option<Topology3>,
    /// The nodes of the topology's edges, computed once.
    nodes: OnceLock<Vec<Vec<Vec3>>>,
    /// The `[[surface]]` tables, each built once when first used.
    surfaces: SurfaceCache,
}

/// Built `[[surface]]` tables (see [`LoadedCase::named_surface`]).
#[derive(Clone, Default)]
struct SurfaceCache(OnceLock<Vec<OnceLock<std::sync::Arc<dyn ellipgrid_geometry::Surface>>>>);

impl std::ops::Deref for SurfaceCache {
    type Target = OnceLock<Vec<OnceLock<std::sync::Arc<dyn ellipgrid_geometry::Surface>>>>;
    fn deref(&self) -> &Self::Target {
        &self.0
    }
}

impl std::fmt::Debug for SurfaceCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SurfaceCache")
    }
}

/// An edge's node count within [`limits::MAX_NODES`] (so that chains of edges add up without
/// overflow).
fn budget_edge(place: &str, name: &str, n: usize) -> Result<()> {
    limits::Budget::default().add(
        &format!("{place}: edge '{name}'"),
        &[n],
        limits::BYTES_PER_NODE_2D,
    )
}

impl LoadedCase {
    /// Reads and parses a case file.
    pub fn read(path: &Path) -> Result<Self> {
        let text = crate::io::read_input_string(path)?;
        Self::parse(&text, path)
    }

    /// Parses case-file text; `path` is used for messages and relative paths.
    pub fn parse(text: &str, path: &Path) -> Result<Self> {
        let case: Case = toml::from_str(text)
            .map_err(|e| Error::input(path.display().to_string(), e.to_string()))?;
        Self::from_case(case, path)
    }

    /// Checks a parsed case (sizes, memory, topology); `path` is used for messages and
    /// relative paths.
    pub fn from_case(case: Case, path: &Path) -> Result<Self> {
        if case.blocks.is_empty() && case.volumes.is_empty() {
            return Err(Error::input(
                path.display().to_string(),
                "the case defines no [[block]] or [[volume]]",
            ));
        }
        let place = path.display().to_string();
        case.solver
            .picard
            .check()
            .map_err(|m| Error::input(format!("{place}: [solver]"), m))?;
        let mut budget = limits::Budget::default();
        for e in &case.edges {
            // before the topology sums chains of edges
            budget_edge(&place, &e.name, e.n)?;
        }
        let topology = topology::build(&case, &place)?;
        let topology3 = topology3::build3(&case, &place)?;
        if let Some(t) = &topology3 {
            for (v, spec) in t.volumes.iter().zip(&case.volumes) {
                let at = format!("{place}: volume '{}'", v.name);
                budget.add_solved(&at, &v.dims, limits::BYTES_PER_NODE_3D, &spec.linear)?;
            }
        }
        match &topology {
            Some(t) => {
                for (b, blk) in t.blocks.iter().enumerate() {
                    let at = format!("{place}: block '{}'", blk.name);
                    let dims = t.dims(b);
                    let linear = &case.solver.linear;
                    budget.add_solved(&at, &dims, limits::BYTES_PER_NODE_2D, linear)?;
                }
            }
            None => {
                for (k, b) in case.blocks.iter().enumerate() {
                    if let (Some(ni), Some(nj)) = (b.ni, b.nj) {
                        let name = b.name.clone().unwrap_or_else(|| format!("block{}", k + 1));
                        let at = format!("{place}: block '{name}'");
                        let linear = &case.solver.linear;
                        budget.add_solved(&at, &[ni, nj], limits::BYTES_PER_NODE_2D, linear)?;
                    }
                }
            }
        }
        for (k, v) in case.volumes.iter().enumerate() {
            if topology3.is_some() {
                break; // counted above, from the faces
            }
            let name = v.name.clone().unwrap_or_else(|| format!("volume{}", k + 1));
            let at = format!("{place}: volume '{name}'");
            if let (Some(ni), Some(nj), Some(nk)) = (v.ni, v.nj, v.nk) {
                budget.add_solved(&at, &[ni, nj, nk], limits::BYTES_PER_NODE_3D, &v.linear)?;
            }
        }
        budget.check_memory(&place)?;
        if topology.is_none() {
            for (k, b) in case.blocks.iter().enumerate() {
                let name = b.name.clone().unwrap_or_else(|| format!("block{}", k + 1));
                let at = format!("{place}: block '{name}'");
                if b.ni.is_none() || b.nj.is_none() {
                    return Err(Error::input(at, "the block needs ni and nj"));
                }
                for (e, side) in Edge::ALL.into_iter().zip(b.sides()) {
                    match side {
                        Some(SideSpec::Edge(_)) => {}
                        Some(SideSpec::Names(_)) => {
                            return Err(Error::input(
                                at,
                                format!("side {e} names edges but the case has no [[edge]] tables"),
                            ))
                        }
                        None => return Err(Error::input(at, format!("missing edge {e}"))),
                    }
                }
            }
        }
        Ok(LoadedCase {
            path: path.to_path_buf(),
            case,
            topology,
            topology3,
            nodes: OnceLock::new(),
            surfaces: SurfaceCache::default(),
        })
    }

    /// The topology whose edges the case's `[[edge]]` tables are: the 2D one, or the faces'
    /// of a volume topology.
    pub fn edge_topology(&self) -> Option<&Topology> {
        self.topology
            .as_ref()
            .or(self.topology3.as_ref().map(|t| &t.faces))
    }

    /// "file: block 'name'" for messages.
    pub fn block_place(&self, k: usize) -> String {
        format!("{}: block '{}'", self.path.display(), self.block_name(k))
    }

    /// The name of block k.
    pub fn block_name(&self, k: usize) -> String {
        self.case.blocks[k]
            .name
            .clone()
            .unwrap_or_else(|| format!("block{}", k + 1))
    }

    /// The `orthogonal` edges of block k as flags E1, E2, E3, E4 (unknown names are errors
    /// naming the block; in a topology, edges marked orthogonal count too).
    pub fn block_orthogonal(&self, k: usize) -> Result<[bool; 4]> {
        if let Some(t) = &self.topology {
            return Ok(t.blocks[k].orthogonal);
        }
        crate::elliptic::orthogonal::parse_edges(
            &self.case.blocks[k].orthogonal,
            &self.block_place(k),
        )
    }

    /// What block k asks of its sides: orthogonality and wall spacings (flags E1 … E4).
    pub fn block_sides(&self, k: usize) -> Result<crate::elliptic::orthogonal::Sides> {
        let wall = match &self.topology {
            Some(t) => t.blocks[k].wall,
            None => topology::parse_walls(&self.case.blocks[k].wall, &self.block_place(k))?,
        };
        Ok(crate::elliptic::orthogonal::Sides {
            orthogonal: self.block_orthogonal(k)?,
            wall,
        })
    }

    /// The validated planar boundary of block k.
    pub fn planar_boundary(&self, k: usize) -> Result<Boundary2<2>> {
        self.planar_from(self.edge_point_lists(k)?, &self.block_place(k))
    }

    /// The validated 3D boundary of a minimal-surface block k.
    pub fn minimal_boundary(&self, k: usize) -> Result<Boundary2<3>> {
        let pts = self
            .edge_point_lists(k)?
            .map(|p| p.iter().map(|q| [q.x, q.y, q.z]).collect());
        Boundary2::new(pts, &self.block_place(k))
    }

    /// Nodes of block k along i and j.
    pub fn block_dims(&self, k: usize) -> [usize; 2] {
        match &self.topology {
            Some(t) => t.dims(k),
            None => {
                let b = &self.case.blocks[k];
                [b.ni.unwrap_or(0), b.nj.unwrap_or(0)]
            }
        }
    }

    /// Rejects a block with fewer than 3 nodes along i or j.
    pub(crate) fn check_size(&self, k: usize) -> Result<()> {
        let [ni, nj] = self.block_dims(k);
        if ni < 3 || nj < 3 {
            return Err(Error::input(
                self.block_place(k),
                format!("ni = {ni}, nj = {nj}: a block needs at least 3 nodes each way"),
            ));
        }
        Ok(())
    }

    /// The inline edge tables of block k (E1..E4; a case without topology).
    pub(crate) fn edge_specs(&self, k: usize) -> Result<[&EdgeSpec; 4]> {
        let mut out = Vec::with_capacity(4);
        for (e, side) in Edge::ALL.into_iter().zip(self.case.blocks[k].sides()) {
            match side {
                Some(SideSpec::Edge(s)) => out.push(s),
                _ => {
                    return Err(Error::input(
                        self.block_place(k),
                        format!("side {e} is not an edge table"),
                    ))
                }
            }
        }
        Ok([out[0], out[1], out[2], out[3]])
    }

    /// The nodes of the four edges of block k (E1..E4), from their curves (or from the
    /// topology's shared edges).
    fn edge_point_lists(&self, k: usize) -> Result<[Vec<Vec3>; 4]> {
        self.check_size(k)?;
        if let Some(t) = &self.topology {
            return Ok(t.side_points(k, &self.topology_nodes()?));
        }
        let place = self.block_place(k);
        let [ni, nj] = self.block_dims(k);
        let mut out: [Vec<Vec3>; 4] = Default::default();
        for (e, spec) in Edge::ALL.into_iter().zip(self.edge_specs(k)?) {
            let n = if e.runs_along_i() { ni } else { nj };
            out[e.index()] = self.edge_points(spec, n, &format!("{place}, edge {e}"))?;
        }
        Ok(out)
    }

    /// The validated planar boundary from four node lists (E1..E4).
    pub fn planar_from(&self, lists: [Vec<Vec3>; 4], place: &str) -> Result<Boundary2<2>> {
        let mut pts: [Vec<[f64; 2]>; 4] = Default::default();
        for (e, p3) in Edge::ALL.into_iter().zip(lists) {
            if let Some(n) = p3.iter().position(|p| p.z != 0.0) {
                return Err(Error::input(
                    format!("{place}, edge {e}"),
                    format!(
                        "point {n} has z = {} but the block is planar (use kind = \"minimal\" \
                         for a surface spanned by 3D edges)",
                        p3[n].z
                    ),
                ));
            }
            pts[e.index()] = p3.iter().map(|p| [p.x, p.y]).collect();
        }
        Boundary2::new(pts, place)
    }

    /// The n nodes of one edge.
    pub fn edge_points(&self, spec: &EdgeSpec, n: usize, at: &str) -> Result<Vec<Vec3>> {
        let Some(curve_spec) = &spec.curve else {
            return Err(Error::input(at, "the edge needs a curve = { type = ... }"));
        };
        if let CurveSpec::Nodes { points } = curve_spec {
            if !matches!(spec.distribution, DistributionSpec::Uniform {}) {
                return Err(Error::input(at, "a 'nodes' edge takes no distribution"));
            }
            let mut p = points
                .iter()
                .enumerate()
                .map(|(k, q)| point(q, at, &format!("points[{k}]")))
                .collect::<Result<Vec<_>>>()?;
            if p.len() != n {
                return Err(Error::input(
                    at,
                    format!(
                        "{} nodes given but the block needs {n} on this edge",
                        p.len()
                    ),
                ));
            }
            if spec.reverse {
                p.reverse();
            }
            return Ok(p);
        }
        let curve = self.curve(curve_spec, at)?;
        self.points_on(curve.as_ref(), spec, n, at)
    }

    /// n nodes on a curve by the spec's distribution (and direction).
    pub(crate) fn points_on(
        &self,
        curve: &dyn Curve,
        spec: &EdgeSpec,
        n: usize,
        at: &str,
    ) -> Result<Vec<Vec3>> {
        let map = geo::ArclengthMap::new(curve);
        let sigma = spec.distribution.sample(n, map.length(), at)?;
        // `first` belongs to the edge's first node; a reversed edge starts at the curve's end,
        // so node k sits at curve arclength 1 − σ_k.
        let at_sigma = |sig: &[f64]| -> Vec<Vec3> {
            map.params(sig)
                .into_iter()
                .map(|u| curve.point(u))
                .collect()
        };
        let p = if spec.reverse {
            let mut p = at_sigma(&geo::reverse(&sigma));
            p.reverse();
            p
        } else {
            at_sigma(&sigma)
        };
        Ok(p)
    }

    /// The geometric curve of a spec.
    pub(crate) fn curve(&self, spec: &CurveSpec, at: &str) -> Result<Box<dyn Curve>> {
        let geo_err = |source| Error::Geometry {
            place: at.to_string(),
            source,
        };
        let pts = |v: &[Vec<f64>]| -> Result<Vec<Vec3>> {
            v.iter()
                .enumerate()
                .map(|(k, q)| point(q, at, &format!("points[{k}]")))
                .collect()
        };
        Ok(match spec {
            CurveSpec::Line { from, to } => Box::new(geo::Line {
                from: point(from, at, "from")?,
                to: point(to, at, "to")?,
            }),
            CurveSpec::Arc {
                center,
                radius,
                start_deg,
                end_deg,
            } => Box::new(
                geo::Arc::new(point(center, at, "center")?, *radius, *start_deg, *end_deg)
                    .map_err(geo_err)?,
            ),
            CurveSpec::ArcThrough { from, mid, to } => Box::new(
                geo::Arc::through(
                    point(from, at, "from")?,
                    point(mid, at, "mid")?,
                    point(to, at, "to")?,
                )
                .map_err(geo_err)?,
            ),
            CurveSpec::Polyline { points } => {
                Box::new(geo::Polyline::new(pts(points)?).map_err(geo_err)?)
            }
            CurveSpec::Spline { points } => {
                Box::new(geo::Spline::new(pts(points)?).map_err(geo_err)?)
            }
            CurveSpec::OnSurface { surface, uv } => {
                let s = self.named_surface(surface, at)?;
                let uv = uv
                    .iter()
                    .enumerate()
                    .map(|(k, p)| match p[..] {
                        [u, v] if u.is_finite() && v.is_finite() => Ok((u, v)),
                        _ => Err(Error::input(
                            at,
                            format!("uv[{k}]: expected [u, v] with finite values"),
                        )),
                    })
                    .collect::<Result<Vec<_>>>()?;
                Box::new(geo::SurfaceLine::new(s, uv).map_err(geo_err)?)
            }
            CurveSpec::Intersection { .. } | CurveSpec::Iso { .. } | CurveSpec::Edges { .. } => {
                return Err(Error::input(
                    at,
                    "intersection, iso and edges curves lie on a STEP model: only edges of a surface \
                     block with surface = { type = \"step\", ... } take them",
                ))
            }
            CurveSpec::Naca4 {
                code,
                chord,
                sharp_te,
                side,
                origin,
            } => {
                let foil = geo::Naca4::new(code, *chord, *sharp_te).map_err(geo_err)?;
                let o = origin_of(origin, at)?;
                match side.as_str() {
                    "both" => Box::new(Shifted(foil, o)),
                    "upper" => Box::new(Shifted(foil.upper(), o)),
                    "lower" => Box::new(Shifted(foil.lower(), o)),
                    s => {
                        return Err(Error::input(
                            at,
                            format!("naca4 side '{s}': expected both, upper or lower"),
                        ))
                    }
                }
            }
            CurveSpec::Airfoil {
                file,
                chord,
                origin,
            } => {
                let path = self.path.parent().unwrap_or(Path::new(".")).join(file);
                let text = within(at, crate::io::read_input_string(&path))?;
                let pts = geo::read_airfoil_dat(&text).map_err(|source| Error::Geometry {
                    place: format!("{at}: {}", path.display()),
                    source,
                })?;
                let o = origin_of(origin, at)?;
                let pts = pts.into_iter().map(|p| p * *chord + o).collect();
                Box::new(geo::airfoil_curve(pts).map_err(geo_err)?)
            }
            CurveSpec::Nodes { .. } => unreachable!("handled by edge_points"),
        })
    }
}

/// A curve moved by a constant offset.
struct Shifted<C>(C, Vec3);

impl<C: Curve> Curve for Shifted<C> {
    fn point(&self, u: f64) -> Vec3 {
        self.0.point(u) + self.1
    }
    fn derivative(&self, u: f64) -> Vec3 {
        self.0.derivative(u)
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.0.breakpoints()
    }
}

fn origin_of(o: &Option<Vec<f64>>, at: &str) -> Result<Vec3> {
    o.as_ref()
        .map(|v| point(v, at, "origin"))
        .transpose()
        .map(|p| p.unwrap_or_else(Vec3::zeros))
}

/// The error of reading a file that the case refers to, prefixed with the place in the case
/// that names it ("case.toml: block 'w', edge E3: naca.dat: No such file"), so that every
/// message names the case file too.
pub(crate) fn within<T>(at: &str, r: Result<T>) -> Result<T> {
    r.map_err(|e| match e {
        Error::Folded { .. } | Error::Solve { .. } => e,
        _ => Error::input(at, e.to_string()),
    })
}

/// A point from `[x, y]` or `[x, y, z]`, finite.
pub(crate) fn point(v: &[f64], at: &str, what: &str) -> Result<Vec3> {
    let p = match v {
        [x, y] => Vec3::new(*x, *y, 0.0),
        [x, y, z] => Vec3::new(*x, *y, *z),
        _ => {
            return Err(Error::input(
                at,
                format!("{what}: a point has 2 or 3 coordinates, got {}", v.len()),
            ))
        }
    };
    if p.iter().any(|c| !c.is_finite()) {
        return Err(Error::input(
            at,
            format!("{what}: coordinate is not finite"),
        ));
    }
    Ok(p)
}
