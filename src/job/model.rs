//! Surface blocks on a STEP model (`surface = { type = "step", file, faces }`, issue #14 item
//! 4): a block face that need not be a CAD face. Its four edges are curves on the model
//! (lines, polylines or splines projected onto it, iso lines of its faces, the junction with
//! another face traced by [`ellipgrid_geometry::trace_intersection`]); where a projected edge's
//! end misses its neighbour's by less than 2 % of the edge, it is shifted along itself to meet
//! it (an iso line or junction keeps its ends). The edges span the bicubic Hermite net
//! ([`crate::surface::net`]) that Section 4 grids; the grid's nodes are moved onto the model
//! at the end, and how far they moved is reported.

use crate::case::spec::{CurveSpec, SurfaceRef, SurfaceSpec};
use crate::case::LoadedCase;
use crate::grid::{Edge, Grid2};
use crate::surface::net::{at_stations, projected_net, uniform_stations};
use crate::{cad, Error, Result};
use ellipgrid_geometry::{
    intersection_point, trace_intersection, HermiteSurface, ModelLocator, Surface, TruckSurface,
    Vec3,
};
use rayon::prelude::*;
use std::path::PathBuf;

/// Points per edge of the dense polylines that edges are sampled by before resampling.
const DENSE: usize = 2001;
/// Largest gap between two edges' ends that a projected edge is shifted across, relative to
/// the shorter edge.
const MEET: f64 = 0.02;
/// Largest gap between the ends of two exact edges (iso lines, junctions), relative to the
/// model's size.
const EXACT_MEET: f64 = 1e-6;

/// A block face on a STEP model: the Hermite surface of its net, the boundary (u, v) of its
/// nodes on it (E1..E4), and the model.
pub struct ModelBlock {
    /// The bicubic Hermite surface through the projected net.
    pub surface: HermiteSurface,
    /// The (u, v) of the block's boundary nodes on `surface`.
    pub uv: [Vec<[f64; 2]>; 4],
    /// The model (the block's faces).
    pub model: ModelLocator,
    /// The face each edge (E1..E4) is the junction with, if it is one.
    pub junctions: [Option<ModelLocator>; 4],
    /// The corners where the edges meet: (0, 0), (1, 0), (0, 1), (1, 1) in (i, j).
    pub corners: [Vec3; 4],
}

/// Where projected edges go onto the model: along a direction, else to the closest point.
struct Onto<'a> {
    model: &'a ModelLocator,
    along: Option<Vec3>,
}

impl Onto<'_> {
    fn place(&self, p: Vec3) -> Option<Vec3> {
        match self.along {
            Some(d) => self.model.along(p, d),
            None => self.model.closest(p),
        }
        .map(|q| q.x)
    }
}

/// A curve on the model by its own parameter.
type Curve1 = Box<dyn Fn(f64) -> Vec3 + Send + Sync>;

/// How an edge's points are put back on its curve after resampling.
enum Snap {
    /// Onto the model by closest point.
    Model,
    /// Exactly on a parametrized curve (an iso line, a chain of CAD edges): the parameters of
    /// the dense points and the curve.
    Exact(Vec<f64>, Curve1),
    /// Onto the junction with this face (the plane across the edge).
    Junction(ModelLocator),
}

impl Snap {
    fn exact(&self) -> bool {
        !matches!(self, Snap::Model)
    }
}

/// The model block k of `case`; see the module doc.
///
/// # Errors
/// [`Error::Input`] naming the file, block and edge: a face not in the file, an edge that is
/// not a curve on the model, edges whose ends do not meet, a junction that cannot be traced,
/// a net point that cannot be projected; those of reading the STEP file.
pub fn model_block(case: &LoadedCase, k: usize) -> Result<ModelBlock> {
    let place = case.block_place(k);
    let Some(SurfaceRef::Inline(SurfaceSpec::Step {
        file,
        faces,
        net,
        along,
    })) = &case.case.blocks[k].surface
    else {
        return Err(Error::input(place, "not a block on a STEP model"));
    };
    case.check_size(k)?;
    let path: PathBuf = case
        .path
        .parent()
        .unwrap_or(std::path::Path::new("."))
        .join(file);
    let step = cad::read_step(&path)?.faces;
    let file_place = format!("{place}, {}", path.display());
    if faces.is_empty() {
        return Err(Error::input(file_place, "faces = [...] names no face"));
    }
    let model = cad::step_model(&step, faces, &file_place)?;
    let along = match along {
        None => None,
        Some(d) => {
            let d = crate::case::point(d, &file_place, "along")?;
            if d.norm() <= 0.0 {
                return Err(Error::input(
                    file_place,
                    "along = [0, 0, 0] has no direction",
                ));
            }
            Some(d / d.norm())
        }
    };
    let onto = Onto {
        model: &model,
        along,
    };
    let specs = case.edge_specs(k)?;
    let mut edges = Vec::with_capacity(4);
    for (e, spec) in Edge::ALL.into_iter().zip(specs) {
        let at = format!("{place}, edge {e}");
        let Some(curve) = &spec.curve else {
            return Err(Error::input(
                at,
                "an edge on a STEP model needs curve = { type = ... } (line, polyline, spline, \
                 iso or intersection)",
            ));
        };
        let (mut pts, mut snap) = dense_edge(case, &onto, &step, curve, &at)?;
        if spec.reverse {
            pts.reverse();
            if let Snap::Exact(t, _) = &mut snap {
                t.reverse();
            }
        }
        edges.push((pts, snap));
    }
    let corners = meet_at_corners(&onto, &mut edges, &place)?;
    let [ni, nj] = case.block_dims(k);
    let [m, n] = net.unwrap_or([ni, nj]);
    if m < 4 || n < 4 {
        return Err(Error::input(
            file_place,
            format!("net = [{m}, {n}]: at least 4 × 4 points"),
        ));
    }
    let sides: Vec<Vec<Vec3>> = Edge::ALL
        .into_iter()
        .zip(&edges)
        .map(|(e, (pts, snap))| {
            let count = if e.runs_along_i() { m } else { n };
            resample(&onto, pts, snap, count, &format!("{place}, edge {e}"))
        })
        .collect::<Result<_>>()?;
    let closest = |p: Vec3| model.closest(p).map(|q| q.x);
    let pts = projected_net(
        [&sides[0], &sides[1], &sides[2], &sides[3]],
        &closest,
        &place,
    )?;
    let surface = HermiteSurface::new(m, n, pts).map_err(|source| Error::Geometry {
        place: place.clone(),
        source,
    })?;
    let uv = case.surface_uv(k, &surface)?;
    let mut junctions = [None, None, None, None];
    for (e, (_, snap)) in edges.into_iter().enumerate() {
        if let Snap::Junction(other) = snap {
            junctions[e] = Some(other);
        }
    }
    Ok(ModelBlock {
        surface,
        uv,
        model,
        junctions,
        corners,
    })
}

/// The edge's curve as a dense polyline on the model, and how resampled points return to it.
fn dense_edge(
    case: &LoadedCase,
    onto: &Onto,
    step: &[cad::StepFace],
    curve: &CurveSpec,
    at: &str,
) -> Result<(Vec<Vec3>, Snap)> {
    let model = onto.model;
    let on_model = |p: Vec3| {
        onto.place(p)
            .ok_or_else(|| Error::input(at, "a point cannot be projected onto the model"))
    };
    match curve {
        CurveSpec::Line { .. } | CurveSpec::Polyline { .. } | CurveSpec::Spline { .. } => {
            let c = case.curve(curve, at)?;
            let given: Vec<Vec3> = (0..DENSE)
                .map(|q| c.point(q as f64 / (DENSE - 1) as f64))
                .collect();
            let pts = given
                .par_iter()
                .map(|p| on_model(*p))
                .collect::<Result<Vec<_>>>()?;
            // a curve far from the model (wrong coordinates, or faces missing from `faces`)
            // is an error, not a silent projection
            let len: f64 = given.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
            let far = given
                .iter()
                .zip(&pts)
                .map(|(p, q)| (p - q).norm())
                .fold(0.0, f64::max);
            if far > len.max(1e-3 * model.diagonal()) {
                return Err(Error::input(
                    at,
                    format!(
                        "the curve lies up to {far:.3e} from the model, more than its length \
                         {len:.3e}: wrong coordinates, or faces missing from `faces`?"
                    ),
                ));
            }
            Ok((pts, Snap::Model))
        }
        CurveSpec::Iso {
            face,
            u,
            v,
            from,
            to,
        } => {
            let f = step_face(step, *face, at)?;
            let surface: Box<dyn Surface> = match (&f.surface, f.is_four_sided_patch()) {
                (Some(s), true) => Box::new(s.clone()) as Box<dyn Surface>,
                _ => Box::new(TruckSurface::new(f.cad_surface.clone())),
            };
            let (a, b) = (from.unwrap_or(0.0), to.unwrap_or(1.0));
            let eval: Curve1 = match (*u, *v) {
                (Some(u), None) => Box::new(move |t| surface.point(u, t)),
                (None, Some(v)) => Box::new(move |t| surface.point(t, v)),
                _ => return Err(Error::input(at, "an iso line fixes one of u and v")),
            };
            if ![a, b, u.or(*v).unwrap_or(0.0)]
                .iter()
                .all(|t| t.is_finite())
            {
                return Err(Error::input(at, "the iso line's parameters are not finite"));
            }
            Ok(exact((0..DENSE).map(|q| lerp(a, b, q)).collect(), eval))
        }
        CurveSpec::Edges { face, edges } => {
            let chain = cad::EdgeChain::new(step_face(step, *face, at)?, edges, at)?;
            let n = chain.len() as f64;
            let t = (0..DENSE).map(|q| lerp(0.0, n, q)).collect();
            Ok(exact(t, Box::new(move |s| chain.point(s))))
        }
        CurveSpec::Intersection { face, from, to } => {
            step_face(step, *face, at)?;
            let other = cad::step_model(step, &[*face], at)?;
            // the ends first put on the model as projected edges are (then the junction's
            // points nearest them are where a projected neighbour edge ends, not nearest the
            // given points off the model)
            let from = on_model(crate::case::point(from, at, "from")?)?;
            let to = on_model(crate::case::point(to, at, "to")?)?;
            let h = (to - from).norm() / (DENSE - 1) as f64;
            let a = |p: Vec3| model.closest(p).map(|q| (q.x, q.normal));
            let b = |p: Vec3| other.closest(p).map(|q| (q.x, q.normal));
            let pts =
                trace_intersection(&a, &b, from, to, h).map_err(|source| Error::Geometry {
                    place: format!("{at}, the junction with face {face}"),
                    source,
                })?;
            Ok((pts, Snap::Junction(other)))
        }
        _ => Err(Error::input(
            at,
            "on a STEP model an edge is a line, polyline or spline (projected onto the model), \
             an iso line of a face or the intersection with a face",
        )),
    }
}

/// The dense polyline of an exact curve at parameters `t`.
fn exact(t: Vec<f64>, eval: Curve1) -> (Vec<Vec3>, Snap) {
    let pts = t.iter().map(|&s| eval(s)).collect();
    (pts, Snap::Exact(t, eval))
}

fn lerp(a: f64, b: f64, q: usize) -> f64 {
    let t = q as f64 / (DENSE - 1) as f64;
    a + (b - a) * t
}

/// Face `n` (1-based) of the file, or an error naming it.
fn step_face<'a>(step: &'a [cad::StepFace], n: usize, at: &str) -> Result<&'a cad::StepFace> {
    step.iter().find(|f| f.index == n).ok_or_else(|| {
        Error::input(
            at,
            format!("face {n} is not in the file (it has {} faces)", step.len()),
        )
    })
}

/// The corners where edges E1..E4 (index order) meet: E1 and E3 at (0, 0), E3 and E2 at
/// (1, 0), E1 and E4 at (0, 1), E2 and E4 at (1, 1). An exact edge's end wins; two projected
/// ends meet at their mean's projection; each projected edge is then shifted along itself
/// (linearly in arclength, then back onto the model) so that its ends are the corners.
fn meet_at_corners(onto: &Onto, edges: &mut [(Vec<Vec3>, Snap)], place: &str) -> Result<[Vec3; 4]> {
    let len = |p: &[Vec3]| p.windows(2).map(|w| (w[1] - w[0]).norm()).sum::<f64>();
    let names = ["E1", "E2", "E3", "E4"];
    // (edge, at its end?) pairs of each corner
    let pairs = [
        ((0, false), (2, false)),
        ((2, true), (1, false)),
        ((0, true), (3, false)),
        ((1, true), (3, true)),
    ];
    let end = |e: &(Vec<Vec3>, Snap), last: bool| if last { *e.0.last().unwrap() } else { e.0[0] };
    let mut corner = [[None::<Vec3>; 2]; 4]; // per edge: start, end
    let mut corners = Vec::with_capacity(4);
    for ((a, la), (b, lb)) in pairs {
        let (pa, pb) = (end(&edges[a], la), end(&edges[b], lb));
        let gap = (pa - pb).norm();
        let (xa, xb) = (edges[a].1.exact(), edges[b].1.exact());
        let shorter = len(&edges[a].0).min(len(&edges[b].0));
        let limit = if xa && xb {
            EXACT_MEET * onto.model.diagonal()
        } else {
            MEET * shorter
        };
        if gap.is_nan() || gap > limit {
            return Err(Error::input(
                place,
                format!(
                    "edges {} and {} do not meet: their ends are {gap:.3e} apart (more than {})",
                    names[a],
                    names[b],
                    if xa && xb {
                        "the model's 1e-6"
                    } else {
                        "2 % of the shorter edge"
                    }
                ),
            ));
        }
        let c = match (xa, xb) {
            (true, _) => pa,
            (false, true) => pb,
            _ => onto.place(0.5 * (pa + pb)).ok_or_else(|| {
                Error::input(place, "a corner cannot be projected onto the model")
            })?,
        };
        corner[a][la as usize] = Some(c);
        corner[b][lb as usize] = Some(c);
        corners.push(c);
    }
    for (e, (pts, snap)) in edges.iter_mut().enumerate() {
        let [Some(c0), Some(c1)] = corner[e] else {
            continue;
        };
        if snap.exact() {
            continue;
        }
        let (d0, d1) = (c0 - pts[0], c1 - *pts.last().unwrap());
        let total = len(pts).max(f64::MIN_POSITIVE);
        let mut s = 0.0;
        let mut prev = pts[0];
        for p in pts.iter_mut() {
            s += (*p - prev).norm();
            prev = *p;
            let w = s / total;
            *p = onto.place(*p + d0 * (1.0 - w) + d1 * w).ok_or_else(|| {
                Error::input(
                    place,
                    format!("edge {} cannot be shifted onto the model", names[e]),
                )
            })?;
        }
        pts[0] = c0;
        *pts.last_mut().unwrap() = c1;
    }
    Ok([corners[0], corners[1], corners[2], corners[3]])
}

/// `count` points at uniform arclength along the dense polyline, back on the edge's curve;
/// the ends kept.
fn resample(onto: &Onto, pts: &[Vec3], snap: &Snap, count: usize, at: &str) -> Result<Vec<Vec3>> {
    let st = uniform_stations(pts, count);
    let lin = at_stations(pts, &st);
    let mut out = match snap {
        Snap::Model => lin
            .par_iter()
            .map(|p| onto.place(*p))
            .collect::<Option<Vec<_>>>(),
        Snap::Exact(t, eval) => Some(
            st.iter()
                .map(|&(k, w)| eval(t[k] * (1.0 - w) + t.get(k + 1).unwrap_or(&t[k]) * w))
                .collect(),
        ),
        Snap::Junction(other) => {
            let model = onto.model;
            let tol = 1e-13 * (1.0 + model.diagonal());
            let a = |p: Vec3| model.closest(p).map(|q| (q.x, q.normal));
            let b = |p: Vec3| other.closest(p).map(|q| (q.x, q.normal));
            st.par_iter()
                .zip(&lin)
                .map(|(&(k, _), p)| {
                    let t = pts[(k + 1).min(pts.len() - 1)] - pts[k];
                    intersection_point(&a, &b, *p, *p, t / t.norm(), tol)
                })
                .collect()
        }
    }
    .ok_or_else(|| Error::input(at, "a resampled point cannot be put back on the edge"))?;
    out[0] = pts[0];
    out[count - 1] = *pts.last().unwrap();
    Ok(out)
}

/// Every node of `grid` moved onto the model (closest point), the nodes of a junction edge
/// onto the junction (across the edge); the largest and rms distance moved (how far the
/// Hermite net's surface lies from the model there).
pub fn onto_model(grid: &mut Grid2<3>, block: &ModelBlock) -> super::SurfaceDistance {
    let (ni, nj) = (grid.ni(), grid.nj());
    let at = |g: &Grid2<3>, q: usize| Vec3::new(g.coord(0)[q], g.coord(1)[q], g.coord(2)[q]);
    let tol = 1e-13 * (1.0 + block.model.diagonal());
    let a = |p: Vec3| block.model.closest(p).map(|q| (q.x, q.normal));
    let g = &*grid;
    let moved: Vec<(Vec3, f64)> = (0..g.len())
        .into_par_iter()
        .map(|q| {
            let p = at(g, q);
            let (i, j) = (q % ni, q / ni);
            // the junction edge this node lies on, and its neighbours along the edge
            // the corners are the edges' meeting points, kept exactly (so that blocks sharing
            // a corner share it bit for bit)
            let corner = [(0, 0), (ni - 1, 0), (0, nj - 1), (ni - 1, nj - 1)]
                .iter()
                .position(|c| *c == (i, j));
            if let Some(c) = corner {
                return (block.corners[c], (block.corners[c] - p).norm());
            }
            // neighbours along each side, within the side
            let (ip, inx) = (
                if i > 0 { q - 1 } else { q },
                if i + 1 < ni { q + 1 } else { q },
            );
            let (jp, jn) = (
                if j > 0 { q - ni } else { q },
                if j + 1 < nj { q + ni } else { q },
            );
            let on = [
                (i == 0, jp, jn),
                (i == ni - 1, jp, jn),
                (j == 0, ip, inx),
                (j == nj - 1, ip, inx),
            ];
            let snapped = on
                .iter()
                .zip(&block.junctions)
                .find_map(|(&(here, prev, next), o)| {
                    let other = o.as_ref().filter(|_| here)?;
                    let b = |p: Vec3| other.closest(p).map(|q| (q.x, q.normal));
                    let t = at(g, next) - at(g, prev);
                    intersection_point(&a, &b, p, p, t / t.norm(), tol)
                });
            let x = snapped
                .or_else(|| block.model.closest(p).map(|m| m.x))
                .unwrap_or(p);
            (x, (x - p).norm())
        })
        .collect();
    for (q, (p, _)) in moved.iter().enumerate() {
        for d in 0..3 {
            grid.coord_mut(d)[q] = p[d];
        }
    }
    let n = moved.len().max(1) as f64;
    super::SurfaceDistance {
        max: moved.iter().map(|m| m.1).fold(0.0, f64::max),
        rms: (moved.iter().map(|m| m.1 * m.1).sum::<f64>() / n).sqrt(),
    }
}
