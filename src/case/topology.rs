//! The multi-block topology of a case file (`[[vertex]]`, `[[edge]]`, blocks naming edges)
//! and the nodes of its edges, each computed once so that shared edges are bit-identical.

use super::{point, BlockKind, Case, CurveSpec, EdgeSpec, LoadedCase, SideSpec};
use crate::grid::topology::{self, BlockSides, Group, TopoEdge, Topology};
use crate::grid::Edge;
use crate::{Error, Result};
use ellipgrid_geometry::Vec3;
use ellipgrid_geometry::{self as geo, Curve};

/// The topology of a case with `[[edge]]` tables (None for a case of independent blocks);
/// every structural error names the file, block and edge. Cases with `[[face]]` tables are
/// volume topologies ([`super::topology3`]).
pub(super) fn build(case: &Case, place: &str) -> Result<Option<Topology>> {
    if case.edges.is_empty() {
        if !case.vertices.is_empty() {
            return Err(Error::input(
                place,
                "the case has [[vertex]] tables but no [[edge]] tables",
            ));
        }
        return Ok(None);
    }
    if !case.faces.is_empty() {
        return Ok(None);
    }
    let (vertices, edges) = topo_edges(case, place)?;
    let mut blocks = Vec::new();
    for (k, b) in case.blocks.iter().enumerate() {
        let name = b.name.clone().unwrap_or_else(|| format!("block{}", k + 1));
        let at = format!("{place}: block '{name}'");
        if b.kind == BlockKind::Surface && b.surface.is_none() {
            return Err(Error::input(
                at,
                "a surface block needs surface = \"name\" of a [[surface]] (or a surface \
                 table); its edges lie on that surface",
            ));
        }
        let sides = side_names(b.sides(), &at)?;
        let orthogonal = crate::elliptic::orthogonal::parse_edges(&b.orthogonal, &at)?;
        let wall = parse_walls(&b.wall, &at)?;
        blocks.push(BlockSides {
            name,
            sides,
            orthogonal,
            wall,
        });
    }
    let mut topo = Topology::new(vertices, edges, &blocks, place)?;
    check_bcs(&topo, place)?;
    // Edge flags: a side is orthogonal if all its edges are (a partly orthogonal chain is an
    // error); a side holds a wall spacing if any of its edges is a wall (on a chain of wall
    // and non-wall edges, on the wall part: job::multiblock_wall).
    for b in 0..topo.blocks.len() {
        for e in Edge::ALL {
            let uses = &topo.blocks[b].sides[e.index()];
            let orth: Vec<bool> = uses.iter().map(|u| topo.edges[u.edge].orthogonal).collect();
            if uses.iter().any(|u| topo.edges[u.edge].wall) {
                topo.blocks[b].wall[e.index()] = true;
            }
            if orth.iter().all(|f| *f) {
                topo.blocks[b].orthogonal[e.index()] = true;
            } else if orth.iter().any(|f| *f) {
                return Err(Error::input(
                    topo.block_place(place, b),
                    format!(
                        "side {e} is the chain {} of which only some edges are orthogonal; \
                         orthogonality holds along a whole side",
                        topo.chain_names(b, e)
                    ),
                ));
            }
        }
        let dims = topo.dims(b);
        let spec = &case.blocks[b];
        for (given, n, what) in [(spec.ni, dims[0], "ni"), (spec.nj, dims[1], "nj")] {
            if given.is_some_and(|g| g != n) {
                return Err(Error::input(
                    topo.block_place(place, b),
                    format!(
                        "{what} = {} but its edges give {n} nodes",
                        given.unwrap_or_default()
                    ),
                ));
            }
        }
    }
    Ok(Some(topo))
}

/// The vertex names and the edges of a case's `[[vertex]]` and `[[edge]]` tables.
pub(super) fn topo_edges(case: &Case, place: &str) -> Result<(Vec<String>, Vec<TopoEdge>)> {
    let vertices: Vec<String> = case.vertices.iter().map(|v| v.name.clone()).collect();
    let vertex = |name: &str, e: &str| {
        vertices.iter().position(|v| v == name).ok_or_else(|| {
            Error::input(
                format!("{place}: edge '{e}'"),
                format!("no vertex named '{name}'"),
            )
        })
    };
    let mut edges = Vec::new();
    for e in &case.edges {
        let floating = match e.interface.as_deref() {
            None | Some("fixed") => false,
            Some("floating") => true,
            Some(other) => {
                return Err(Error::input(
                    format!("{place}: edge '{}'", e.name),
                    format!("interface = '{other}': expected \"fixed\" or \"floating\""),
                ))
            }
        };
        edges.push(TopoEdge {
            name: e.name.clone(),
            from: vertex(&e.from, &e.name)?,
            to: vertex(&e.to, &e.name)?,
            n: e.n,
            orthogonal: e.orthogonal,
            wall: e.wall,
            floating,
            family: e.family.clone().unwrap_or_else(|| e.name.clone()),
            bc: e.bc.clone(),
        });
    }
    Ok((vertices, edges))
}

/// Edge names along one side, each with its forced direction (`Some(true)`: `-name`).
type NamedChain = Vec<(String, Option<bool>)>;

/// The edge names of four sides (E1..E4) with their forced directions (`-name`: reversed);
/// every side must name its edges.
pub(super) fn side_names(sides: [&Option<SideSpec>; 4], at: &str) -> Result<[NamedChain; 4]> {
    let mut out: [NamedChain; 4] = Default::default();
    for (e, side) in Edge::ALL.into_iter().zip(sides) {
        match side {
            Some(SideSpec::Names(names)) if !names.is_empty() => {
                out[e.index()] = names
                    .iter()
                    .map(|n| match n.strip_prefix('-') {
                        Some(rest) => (rest.to_string(), Some(true)),
                        None => (n.clone(), None),
                    })
                    .collect();
            }
            _ => {
                return Err(Error::input(
                    at,
                    format!(
                        "side {e}: in a case with [[edge]] tables, each side names its edges \
                         (E1 = \"name\" or E1 = [\"a\", \"b\"])"
                    ),
                ))
            }
        }
    }
    Ok(out)
}

impl LoadedCase {
    /// The nodes of every topology edge in its own direction, ends exactly on the vertices;
    /// planar edges that cross are errors.
    pub fn topology_nodes(&self) -> Result<Vec<Vec<Vec3>>> {
        let Some(topo) = self.edge_topology() else {
            return Ok(Vec::new());
        };
        if let Some(n) = self.nodes.get() {
            return Ok(n.clone());
        }
        let place = self.path.display().to_string();
        let mut verts = self
            .case
            .vertices
            .iter()
            .map(|v| point(&v.at, &format!("{place}: vertex '{}'", v.name), "at"))
            .collect::<Result<Vec<_>>>()?;
        // Every edge's whole curve (a line between its vertices by default).
        let mut curves: Vec<Option<Box<dyn Curve>>> = Vec::new();
        for spec in &self.case.edges {
            let at = format!("{place}: edge '{}'", spec.name);
            curves.push(match &spec.curve {
                Some(CurveSpec::Nodes { .. }) | None => None,
                Some(c) => Some(self.curve(c, &at)?),
            });
        }
        let diam = bbox_diameter(verts.iter());
        let tol = crate::grid::boundary::CORNER_TOLERANCE * diam;
        for (v, spec) in self.case.vertices.iter().enumerate() {
            let Some(on) = &spec.on else { continue };
            let at = format!("{place}: vertex '{}'", spec.name);
            let e = topo.edges.iter().position(|e| &e.name == on);
            let curve = e.and_then(|e| curves[e].as_deref()).ok_or_else(|| {
                Error::input(
                    &at,
                    format!("on = '{on}': no edge with a curve of that name"),
                )
            })?;
            verts[v] = curve.point(closest_param(curve, verts[v], None));
        }
        let mut all = Vec::new();
        for ((spec, edge), curve) in self.case.edges.iter().zip(&topo.edges).zip(&curves) {
            let at = format!("{place}: edge '{}'", spec.name);
            let (a, b) = (verts[edge.from], verts[edge.to]);
            let es = EdgeSpec {
                curve: spec.curve.clone(),
                distribution: spec.distribution.clone(),
                reverse: spec.reverse,
            };
            let line: Option<Box<dyn Curve>> = spec
                .curve
                .is_none()
                .then(|| Box::new(geo::Line { from: a, to: b }) as Box<dyn Curve>);
            let mut p = match curve.as_ref().or(line.as_ref()) {
                None => self.edge_points(&es, edge.n, &at)?,
                Some(c) => {
                    // The piece of the curve between the vertices (the whole curve, or
                    // reversed, when its ends are the vertices).
                    let ends = if spec.reverse { (1.0, 0.0) } else { (0.0, 1.0) };
                    let ua = closest_param(c.as_ref(), a, Some(ends.0));
                    let ub = closest_param(c.as_ref(), b, Some(ends.1));
                    let es = EdgeSpec {
                        reverse: false,
                        ..es
                    };
                    if (ua, ub) == (0.0, 1.0) {
                        self.points_on(c.as_ref(), &es, edge.n, &at)?
                    } else {
                        let t = Trimmed {
                            c: c.as_ref(),
                            u0: ua,
                            u1: ub,
                        };
                        self.points_on(&t, &es, edge.n, &at)?
                    }
                }
            };
            for (k, v, vname) in [(0, a, &spec.from), (edge.n - 1, b, &spec.to)] {
                let d = (p[k] - v).norm();
                if d > tol {
                    return Err(Error::input(
                        &at,
                        format!(
                            "vertex '{vname}' {:?} is {d:.3e} from the edge's curve (tolerance \
                             {tol:.1e}); a vertex lies on the curves of its edges (give `on = \
                             \"edge\"` to move it onto one)",
                            [v.x, v.y, v.z]
                        ),
                    ));
                }
                p[k] = v;
            }
            all.push(p);
        }
        let planar =
            self.topology.is_some() && self.case.blocks.iter().all(|b| b.kind == BlockKind::Planar);
        if planar {
            let flat: Vec<Vec<[f64; 2]>> = all
                .iter()
                .map(|p| p.iter().map(|q| [q.x, q.y]).collect())
                .collect();
            if let Some((a, b)) = topology::crossing_edges(topo, &flat) {
                let (na, nb) = (&topo.edges[a].name, &topo.edges[b].name);
                return Err(Error::input(
                    place,
                    if a == b {
                        format!("edge '{na}' crosses itself")
                    } else {
                        format!("edges '{na}' and '{nb}' cross")
                    },
                ));
            }
        }
        let _ = self.nodes.set(all.clone());
        Ok(all)
    }

    /// The node lists of a group's four sides (a block, or a row of blocks joined by floating
    /// edges).
    pub fn group_points(&self, g: &Group) -> Result<[Vec<Vec3>; 4]> {
        Ok(topology::chain_points(&g.sides, &self.topology_nodes()?))
    }
}

fn bbox_diameter<'a>(p: impl Iterator<Item = &'a Vec3>) -> f64 {
    let mut lo = Vec3::repeat(f64::INFINITY);
    let mut hi = Vec3::repeat(f64::NEG_INFINITY);
    for q in p {
        lo = lo.inf(q);
        hi = hi.sup(q);
    }
    (hi - lo).norm()
}

/// The parameter of the point of `c` closest to `p`: dense sampling, then golden-section
/// refinement. A point at the curve's start or end (within round-off) gives exactly 0 or 1;
/// at both (a closed curve) `prefer` decides.
fn closest_param(c: &dyn Curve, p: Vec3, prefer: Option<f64>) -> f64 {
    let d = |u: f64| (c.point(u) - p).norm();
    let scale = (c.point(0.0) - c.point(0.5))
        .norm()
        .max((c.point(1.0) - c.point(0.5)).norm());
    let near = |u: f64| d(u) <= 1e-12 * scale.max(p.norm()).max(1e-300);
    match (near(0.0), near(1.0), prefer) {
        (true, true, Some(e)) => return e,
        (true, _, _) => return 0.0,
        (_, true, _) => return 1.0,
        _ => {}
    }
    const N: usize = 4096;
    let k = (0..=N)
        .min_by(|&a, &b| d(a as f64 / N as f64).total_cmp(&d(b as f64 / N as f64)))
        .unwrap_or(0);
    let (mut lo, mut hi) = (
        k.saturating_sub(1) as f64 / N as f64,
        (k + 1).min(N) as f64 / N as f64,
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if d(x1) < d(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    0.5 * (lo + hi)
}

/// The piece of a curve between parameters u0 and u1 (u1 < u0 runs backwards).
struct Trimmed<'a> {
    c: &'a dyn Curve,
    u0: f64,
    u1: f64,
}

impl Curve for Trimmed<'_> {
    fn point(&self, u: f64) -> Vec3 {
        self.c.point(self.u0 + (self.u1 - self.u0) * u)
    }
    fn derivative(&self, u: f64) -> Vec3 {
        self.c.derivative(self.u0 + (self.u1 - self.u0) * u) * (self.u1 - self.u0)
    }
    fn breakpoints(&self) -> Vec<f64> {
        let mut b: Vec<f64> = self
            .c
            .breakpoints()
            .into_iter()
            .map(|v| (v - self.u0) / (self.u1 - self.u0))
            .filter(|v| *v > 0.0 && *v < 1.0)
            .collect();
        b.sort_by(f64::total_cmp);
        b
    }
}

/// Checks the edges' `bc` keys: a known kind, on boundary edges only, one per family.
fn check_bcs(topo: &Topology, place: &str) -> Result<()> {
    use crate::io::connectivity::{BcKind, BC_NAMES};
    let c = topo.connectivity();
    for (k, e) in topo.edges.iter().enumerate() {
        let Some(bc) = &e.bc else { continue };
        let at = format!("{place}: edge '{}'", e.name);
        if BcKind::parse(bc).is_none() {
            return Err(Error::input(
                at,
                format!("bc = '{bc}': expected one of {}", BC_NAMES.join(", ")),
            ));
        }
        if c.interfaces.iter().any(|f| f.edge == k) {
            return Err(Error::input(
                at,
                "bc = … on an edge between two blocks: boundary conditions belong to boundary \
                 edges",
            ));
        }
        let other = topo
            .edges
            .iter()
            .find(|o| o.family == e.family && o.bc.as_ref().is_some_and(|b| b != bc));
        if let Some(o) = other {
            return Err(Error::input(
                at,
                format!(
                    "bc = '{bc}' but edge '{}' of the same family '{}' has bc = '{}'",
                    o.name,
                    e.family,
                    o.bc.as_deref().unwrap_or_default()
                ),
            ));
        }
    }
    Ok(())
}

/// Parses the block key `wall` (edge names E1 … E4) into flags.
pub(crate) fn parse_walls(names: &[String], place: &str) -> Result<[bool; 4]> {
    let mut wall = [false; 4];
    for n in names {
        let e = Edge::parse(n).ok_or_else(|| {
            Error::input(
                place,
                format!("wall: unknown edge '{n}': expected E1, E2, E3 or E4"),
            )
        })?;
        wall[e.index()] = true;
    }
    Ok(wall)
}
