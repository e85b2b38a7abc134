//! The case file's schema: the TOML tables as serde types, strict (unknown keys are errors).
//! README.md, "Case files", is the reference; the builders that turn a spec into boundaries,
//! surfaces and faces are [`crate::case::LoadedCase`], [`crate::case::surface`] and
//! [`crate::case::volume`].

use crate::algebraic::ControlKind;
use crate::elliptic::picard::PicardParams;
use crate::{Error, Result};
use ellipgrid_geometry as geo;
use serde::Deserialize;
use std::path::PathBuf;

mod surfaces;
pub use surfaces::{NamedSurface, SurfaceRef, SurfaceSpec};

/// A whole case file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Where and how to write the grid.
    #[serde(default)]
    pub output: OutputSpec,
    /// Solver options shared by all blocks.
    #[serde(default)]
    pub solver: SolverSpec,
    /// The free stream of a runnable OpenFOAM case (`DIR/NAME.foam` outputs).
    #[serde(default)]
    pub flow: FlowSpec,
    /// The blocks, written in this order.
    #[serde(rename = "block", default)]
    pub blocks: Vec<BlockSpec>,
    /// Named vertices of a multi-block topology (`[[vertex]]`).
    #[serde(rename = "vertex", default)]
    pub vertices: Vec<VertexSpec>,
    /// Named edges of a multi-block topology (`[[edge]]`), shared by the blocks that name them.
    #[serde(rename = "edge", default)]
    pub edges: Vec<TopoEdgeSpec>,
    /// Volume blocks (`[[volume]]`, see `volume::case3d`), written after the blocks.
    #[serde(rename = "volume", default)]
    pub volumes: Vec<VolumeSpec>,
    /// Named faces of a volume topology (`[[face]]`), shared by the volumes that name them.
    #[serde(rename = "face", default)]
    pub faces: Vec<FaceSpec>,
    /// Named surfaces (`[[surface]]`) that faces lie on and edge curves run along.
    #[serde(rename = "surface", default)]
    pub surfaces: Vec<NamedSurface>,
}

/// `[output]`: files to write and the Plot3D flavour.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Output files, by extension: `.x`, `.xyz`, `.p3d`, `.g` Plot3D; `.vts` VTK (one block);
    /// `.vtm` VTK multi-block. Relative to the current directory. `-o` replaces them.
    #[serde(default)]
    pub files: Vec<PathBuf>,
    /// Plot3D encoding: "unformatted" (Fortran records, default), "formatted" (ASCII) or
    /// "stream" (C binary).
    pub encoding: Option<String>,
    /// Plot3D precision: "double" (default) or "single".
    pub precision: Option<String>,
    /// Write the block count record (default true).
    pub multi_block: Option<bool>,
    /// Write planar blocks as 2D Plot3D (x, y only; default true). False writes z = 0, nk = 1.
    pub two_d: Option<bool>,
    /// Thickness along z of planar grids written as OpenFOAM meshes (extruded one cell
    /// thick, z from 0 to `span`; default 1).
    pub span: Option<f64>,
    /// OpenFOAM meshes in "ascii" (default) or "binary".
    pub foam_format: Option<String>,
}

/// `[flow]`: the free stream of a runnable OpenFOAM case (checked by
/// [`crate::io::foam_case::Flow::from_input`]; every key optional).
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlowSpec {
    /// Free-stream speed (default 1).
    pub speed: Option<f64>,
    /// Angle of attack in degrees (default 0): in the x–y plane of planar grids, the x–z
    /// plane of volumes.
    pub alpha: Option<f64>,
    /// Sideslip in degrees, towards +y (volume grids; default 0).
    pub sideslip: Option<f64>,
    /// Kinematic viscosity (default 1e-3), or else:
    pub nu: Option<f64>,
    /// the Reynolds number `speed * length / nu`,
    pub reynolds: Option<f64>,
    /// with the reference length (default 1).
    pub length: Option<f64>,
}

/// `[solver]`: options of the elliptic solve.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSpec {
    /// Linear solver of each Picard step: "multigrid" (default; with nested iteration unless
    /// `nested = false`), "multigrid-lean" (the same with less memory and more time,
    /// `MgParams::lean_y_lines`) or "direct" (sparse LU).
    pub linear: String,
    /// Control functions: "algebraic" (the paper's, default) or "laplace" (all zero).
    pub control: ControlKind,
    /// Picard iteration parameters.
    #[serde(flatten)]
    pub picard: PicardParams,
}

impl Default for SolverSpec {
    fn default() -> Self {
        SolverSpec {
            linear: "multigrid".into(),
            control: ControlKind::Algebraic,
            picard: PicardParams::default(),
        }
    }
}

/// `[[block]]`: one block with its four edges: inline edge tables, or (in a case with
/// `[[edge]]` tables) the names of the edges along each side.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    /// Name used in messages and outputs (default `block<k>`).
    pub name: Option<String>,
    /// What the block is: "planar" (default; Section 2), "minimal" (a soap film spanned by
    /// four 3D edges; Section 3) or "surface" (a grid on a parametrized surface; Section 4).
    #[serde(default)]
    pub kind: BlockKind,
    /// Nodes along i (on E3 and E4); with named edges, optional (then checked).
    pub ni: Option<usize>,
    /// Nodes along j (on E1 and E2); with named edges, optional (then checked).
    pub nj: Option<usize>,
    /// Edges at which the grid is made orthogonal (Section 2.4), e.g. `["E3"]`; default none.
    #[serde(default)]
    pub orthogonal: Vec<String>,
    /// Edges along which the first spacing off the edge is held to the side edges'
    /// distributions ([`crate::elliptic::wall2d`]), e.g. `"E3"` or `["E3", "E1"]`; default none.
    #[serde(default, deserialize_with = "one_or_more")]
    pub wall: Vec<String>,
    /// Share of each grid line leaving this block's walls over which the held wall spacing
    /// fades into the elliptic map's (0 < f ≤ 1; default [`crate::elliptic::wall2d::FADE`]).
    /// Shorter for deep concave valleys, where a long fade shears the cells
    /// (`examples/artificial_boundary.toml`).
    pub wall_fade: Option<f64>,
    #[serde(rename = "E1")]
    pub e1: Option<SideSpec>,
    #[serde(rename = "E2")]
    pub e2: Option<SideSpec>,
    #[serde(rename = "E3")]
    pub e3: Option<SideSpec>,
    #[serde(rename = "E4")]
    pub e4: Option<SideSpec>,
    /// The surface of a `kind = "surface"` block: a table (its edges are the surface's own
    /// edges) or, in a case with `[[edge]]` tables, the name of a `[[surface]]` (the edges lie
    /// on it).
    pub surface: Option<SurfaceRef>,
    /// A reference surface: the report gives the distance of the grid's nodes from it (for
    /// example Scherk's surface for a minimal-surface block spanned by edges on it).
    pub reference: Option<SurfaceSpec>,
}

/// A string or a list of strings.
fn one_or_more<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> std::result::Result<Vec<String>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum OneOrMore {
        One(String),
        More(Vec<String>),
    }
    Ok(match OneOrMore::deserialize(d)? {
        OneOrMore::One(s) => vec![s],
        OneOrMore::More(v) => v,
    })
}

impl BlockSpec {
    /// The four sides E1..E4.
    pub fn sides(&self) -> [&Option<SideSpec>; 4] {
        [&self.e1, &self.e2, &self.e3, &self.e4]
    }
}

/// A block side: an inline edge table, or the name(s) of topology edges along it, in index
/// order (`"-name"` forces the edge to run backwards along the side).
#[derive(Clone, Debug)]
pub enum SideSpec {
    Edge(EdgeSpec),
    Names(Vec<String>),
}

impl<'de> Deserialize<'de> for SideSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = SideSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an edge table, an edge name or a list of edge names")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<SideSpec, E> {
                Ok(SideSpec::Names(vec![v.to_string()]))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                seq: A,
            ) -> std::result::Result<SideSpec, A::Error> {
                Vec::<String>::deserialize(SeqAccessDeserializer::new(seq)).map(SideSpec::Names)
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> std::result::Result<SideSpec, A::Error> {
                EdgeSpec::deserialize(MapAccessDeserializer::new(map)).map(SideSpec::Edge)
            }
        }
        d.deserialize_any(V)
    }
}

/// `[[vertex]]`: a named point of a multi-block topology.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VertexSpec {
    pub name: String,
    /// `[x, y]` or `[x, y, z]`.
    pub at: Vec<f64>,
    /// Move the vertex to the closest point of this edge's curve (a point near the curve
    /// is enough in `at`).
    pub on: Option<String>,
}

/// `[[edge]]`: a named edge from one vertex to another, shared by the blocks that name it.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TopoEdgeSpec {
    pub name: String,
    /// Vertex names; the edge's first node is at `from`.
    pub from: String,
    pub to: String,
    /// Nodes on the edge, end vertices included.
    pub n: usize,
    /// The curve (default: the straight line between the vertices). Its ends lie on the
    /// vertices, or the vertices lie on the curve and the edge is the piece between them.
    pub curve: Option<CurveSpec>,
    #[serde(default)]
    pub distribution: DistributionSpec,
    /// Run along the curve from its end to its start.
    #[serde(default)]
    pub reverse: bool,
    /// The grid is orthogonal at the edge on every block side it lies on (Section 2.4).
    #[serde(default)]
    pub orthogonal: bool,
    /// The first spacing off the edge is held along it on every block side it lies on: the
    /// spacings of the edges leaving it, interpolated by arclength ([`crate::elliptic::wall2d`]).
    #[serde(default)]
    pub wall: bool,
    /// "fixed" (default: the nodes are where the distribution puts them) or "floating" (an
    /// interior edge whose interior nodes move with the grid of the blocks it joins).
    pub interface: Option<String>,
    /// Boundary-patch family written to the connectivity file (default: the edge's name).
    pub family: Option<String>,
    /// Boundary condition of the edge's family in solver meshes: "wall", "symmetry",
    /// "farfield", "inflow", "outflow" or "general" (default: suggested by the family's
    /// name). Boundary edges only; every edge of a family gives the same.
    pub bc: Option<String>,
}

/// `[[face]]`: a named face of a volume topology, bounded by four sides of named edges (as
/// the blocks of a 2D topology), shared by the volumes that name it.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaceSpec {
    pub name: String,
    /// How the face is gridded: "tfi" (default: the Coons patch of its sides), "minimal"
    /// (the Section 3 system: a soap film spanned by the sides; a plane if they are planar)
    /// or "surface" (Section 4 on the named `surface`).
    #[serde(default)]
    pub kind: FaceKind,
    /// The `[[surface]]` a `kind = "surface"` face lies on.
    pub surface: Option<String>,
    /// Sides at which the face's grid is orthogonal to its edges (Section 2.4), e.g.
    /// `["E3"]` (minimal and surface faces).
    #[serde(default)]
    pub orthogonal: Vec<String>,
    /// Boundary-patch family in the connectivity file (default: the face's name).
    pub family: Option<String>,
    /// The family's boundary condition in solver meshes ("wall", "symmetry", "farfield",
    /// "inflow", "outflow", "general"; default: guessed from the family name). Boundary
    /// faces only.
    pub bc: Option<String>,
    /// "fixed" (default: the face is gridded once, alone, and held) or "floating" (a face
    /// between two volumes whose interior nodes move with the volumes until the grid crosses
    /// it as smoothly as inside a block; README, "Floating interior faces").
    pub interface: Option<String>,
    #[serde(rename = "E1")]
    pub e1: Option<SideSpec>,
    #[serde(rename = "E2")]
    pub e2: Option<SideSpec>,
    #[serde(rename = "E3")]
    pub e3: Option<SideSpec>,
    #[serde(rename = "E4")]
    pub e4: Option<SideSpec>,
}

impl FaceSpec {
    /// The four sides E1..E4.
    pub fn sides(&self) -> [&Option<SideSpec>; 4] {
        [&self.e1, &self.e2, &self.e3, &self.e4]
    }

    /// True for `interface = "floating"` (checked by the topology: "fixed" or "floating").
    pub fn floating(&self) -> bool {
        self.interface.as_deref() == Some("floating")
    }
}

/// How a face of a volume topology is gridded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FaceKind {
    /// The Coons patch (transfinite interpolation) of the four sides, blended with their
    /// straight-line parameters [39, 40].
    #[default]
    Tfi,
    /// The Poisson system [24] with x ∈ R³ (Section 3): a minimal surface, planar when the
    /// sides are.
    Minimal,
    /// Section 4 on a named surface.
    Surface,
}

/// The kind of a block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BlockKind {
    /// A planar domain: edges in the xy-plane, the Poisson system of Section 2.
    #[default]
    Planar,
    /// A minimal surface spanned by four 3D edges: the same system with x ∈ R³ (Section 3).
    Minimal,
    /// A parametrized surface gridded by Laplace–Beltrami and inversion (Section 4).
    Surface,
}

/// One edge: a curve, the distribution of nodes along it, and its direction.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeSpec {
    /// The edge's curve (planar and minimal blocks; surface blocks use the surface's edges).
    pub curve: Option<CurveSpec>,
    #[serde(default)]
    pub distribution: DistributionSpec,
    /// Run along the curve from its end to its start.
    #[serde(default)]
    pub reverse: bool,
}

/// Edge curves. Points are `[x, y]` (or `[x, y, z]` with z = 0 for planar blocks).
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum CurveSpec {
    /// Straight segment.
    Line { from: Vec<f64>, to: Vec<f64> },
    /// Circular arc about `center` from `start_deg` to `end_deg` (counter-clockwise if
    /// end > start).
    Arc {
        center: Vec<f64>,
        radius: f64,
        start_deg: f64,
        end_deg: f64,
    },
    /// Circular arc through three points.
    ArcThrough {
        from: Vec<f64>,
        mid: Vec<f64>,
        to: Vec<f64>,
    },
    /// Piecewise-linear curve through points.
    Polyline { points: Vec<Vec<f64>> },
    /// C² cubic spline through points (chord-length parametrized).
    Spline { points: Vec<Vec<f64>> },
    /// NACA 4-digit airfoil: `side` "both" (TE → upper → LE → lower → TE), "upper" or "lower"
    /// (LE → TE), scaled by `chord` and moved to `origin` (leading edge).
    Naca4 {
        code: String,
        #[serde(default = "one")]
        chord: f64,
        #[serde(default = "yes")]
        sharp_te: bool,
        #[serde(default = "both")]
        side: String,
        #[serde(default)]
        origin: Option<Vec<f64>>,
    },
    /// Airfoil table (Selig or Lednicer .dat), splined; scaled by `chord`, moved to `origin`.
    Airfoil {
        file: PathBuf,
        #[serde(default = "one")]
        chord: f64,
        #[serde(default)]
        origin: Option<Vec<f64>>,
    },
    /// The edge's nodes themselves; their count must match the block and `distribution` is
    /// not used.
    Nodes { points: Vec<Vec<f64>> },
    /// A curve on a `[[surface]]`: the polyline through parameter points `uv` ([u, v] each,
    /// at least two) mapped onto the surface (e.g. `[[0, 0], [1, 0]]`: the side v = 0).
    OnSurface { surface: String, uv: Vec<Vec<f64>> },
    /// On a `type = "step"` block's model only: the junction where the model meets face
    /// `face` of the same STEP file (a pylon on a wing), from its point nearest `from` to the
    /// one nearest `to`, both first put on the model as projected edges are (traced by
    /// [`ellipgrid_geometry::trace_intersection`]).
    Intersection {
        face: usize,
        from: Vec<f64>,
        to: Vec<f64>,
    },
    /// On a `type = "step"` block's model only: the line of face `face` of the STEP file
    /// where `u` (or `v`) is fixed, the other parameter running `from` → `to` (default 0 → 1:
    /// an untrimmed patch's normalized parameters; a trimmed face's are its surface's own).
    Iso {
        face: usize,
        u: Option<f64>,
        v: Option<f64>,
        from: Option<f64>,
        to: Option<f64>,
    },
    /// On a `type = "step"` block's model only: edges `edges` of face `face`'s outer loop
    /// (1-based, in loop order, as `step list --edges` numbers them) run one after the other.
    Edges { face: usize, edges: Vec<usize> },
}

fn one() -> f64 {
    1.0
}
fn yes() -> bool {
    true
}
fn both() -> String {
    "both".into()
}

/// Node distribution along an edge. Spacings are lengths along the curve, at the edge's
/// first node (`first`) and last node (`last`) in index order.
///
/// Every variant is a struct variant (`Uniform {}`): serde lets a unit variant of an
/// internally tagged enum accept any keys, and unknown keys must be errors
/// (`{ type = "uniform", first = 1e-4 }` would silently ignore the spacing).
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum DistributionSpec {
    /// Equal arclength spacing.
    Uniform {},
    /// Geometric growth from the first spacing.
    Geometric { first: f64 },
    /// Vinokur's one- or two-sided stretching hitting the given spacings exactly.
    Vinokur {
        first: Option<f64>,
        last: Option<f64>,
    },
    /// `base` as fitted for `n` nodes, sampled `level` times finer in its own parameter
    /// ([`ellipgrid_geometry::Distribution::sample_refined`]): the grid families of `ellipgrid
    /// verify` ([`crate::case::LoadedCase::refined`]). Not a case-file key.
    #[serde(skip)]
    Refined {
        base: Box<DistributionSpec>,
        n: usize,
        level: u32,
    },
}

impl Default for DistributionSpec {
    fn default() -> Self {
        DistributionSpec::Uniform {}
    }
}

impl DistributionSpec {
    /// Normalized arclengths of `n` nodes on an edge of length `len` (spacings in the spec are
    /// lengths; the distribution hits them exactly).
    pub fn sample(&self, n: usize, len: f64, at: &str) -> Result<Vec<f64>> {
        let geo_err = |source| Error::Geometry {
            place: at.to_string(),
            source,
        };
        if let DistributionSpec::Refined { base, n: nb, level } = self {
            let sigma = base
                .geometric(len, at)?
                .sample_refined(*nb, *level)
                .map_err(geo_err)?;
            if sigma.len() != n {
                return Err(Error::input(
                    at,
                    format!(
                        "{n} nodes asked of a distribution of {nb} nodes refined {level} times \
                         ({} nodes)",
                        sigma.len()
                    ),
                ));
            }
            return Ok(sigma);
        }
        self.geometric(len, at)?.sample(n).map_err(geo_err)
    }

    /// The geometry crate's distribution for an edge of length `len` (spacings as fractions).
    fn geometric(&self, len: f64, at: &str) -> Result<geo::Distribution> {
        if !(len.is_finite() && len > 0.0) {
            return Err(Error::input(at, "the edge has zero length"));
        }
        let rel = |v: f64, name: &str| -> Result<f64> {
            if v.is_finite() && v > 0.0 {
                Ok(v / len)
            } else {
                Err(Error::input(
                    at,
                    format!("{name} spacing must be positive, got {v}"),
                ))
            }
        };
        Ok(match self {
            DistributionSpec::Uniform {} => geo::Distribution::Uniform,
            DistributionSpec::Geometric { first } => geo::Distribution::Geometric {
                first: rel(*first, "first")?,
            },
            DistributionSpec::Vinokur { first, last } => geo::Distribution::Vinokur {
                first: first.map(|v| rel(v, "first")).transpose()?,
                last: last.map(|v| rel(v, "last")).transpose()?,
            },
            DistributionSpec::Refined { base, .. } => base.geometric(len, at)?,
        })
    }
}

/// `[[volume]]`: one volume block.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumeSpec {
    /// Name used in messages and outputs (default `volume<k>`).
    pub name: Option<String>,
    /// Nodes along i (on E1–E4), j (E5–E8), k (E9–E12); in a volume topology optional (the
    /// faces give them; checked if given).
    pub ni: Option<usize>,
    pub nj: Option<usize>,
    pub nk: Option<usize>,
    /// Linear solver of each Picard step: "auto" (default: the 3D multigrid from
    /// [`crate::solve::select::AUTO_MULTIGRID_NODES`] nodes, else Bi-CGSTAB/ILU(0)), "multigrid",
    /// "bicgstab" or "direct" (small blocks).
    #[serde(default = "auto")]
    pub linear: String,
    /// Faces from edges: "tfi" (default; Coons patches) or "elliptic" (planar faces
    /// regridded by the Section 2 system).
    #[serde(default)]
    pub face_grids: Option<String>,
    /// Faces from a Plot3D file instead of edges.
    pub faces: Option<FacesFile>,
    /// A wall face ("F1" … "F6") whose first-cell heights are held to the bilinear
    /// interpolation of the first spacings of the four edges leaving it ([`crate::elliptic::wall`]).
    pub wall: Option<String>,
    /// With `wall`: also make the grid lines leave the wall along its normal
    /// ([`crate::elliptic::wall_normal`]; default true).
    pub wall_orthogonal: Option<bool>,
    /// With `wall`: where the interior columns' goal distances from the wall come from:
    /// "edges" (default; the four edges leaving the wall) or "faces" (the four side faces'
    /// columns, for side faces gridded before the volume: [`crate::elliptic::wall_profile`]).
    pub wall_profiles: Option<String>,
    /// Faces ("F1" … "F6") that the grid lines leave along the face's normal
    /// ([`crate::elliptic::orthogonal3d`]): on both sides of an interior face of a volume
    /// topology, the lines cross it without a kink.
    #[serde(default)]
    pub orthogonal: Vec<String>,
    /// Faces ("F1" … "F6") that are symmetry planes ([`crate::elliptic::symmetry3d`]): each
    /// lies on a plane, its nodes slide in it and the grid lines meet it at right angles, as
    /// in the whole domain's grid of which the block is the half.
    #[serde(default)]
    pub symmetry: Vec<String>,
    /// In a volume topology: faces ("F1" … "F6") shared with another volume whose grid lines
    /// leave the face in the direction that volume's lines arrive in; that volume is gridded
    /// first ([`crate::elliptic::continuation`]).
    #[serde(rename = "continue", default)]
    pub continue_faces: Vec<String>,
    /// In a volume topology: this volume is the mirror image of the named one in the plane of
    /// the symmetry faces they share (`symmetry` of that volume): not solved, but mirrored
    /// ([`crate::job`]'s `mirror`), so that the grid lines cross those faces without a kink.
    pub mirror: Option<String>,
    #[serde(rename = "E1")]
    pub e1: Option<EdgeSpec>,
    #[serde(rename = "E2")]
    pub e2: Option<EdgeSpec>,
    #[serde(rename = "E3")]
    pub e3: Option<EdgeSpec>,
    #[serde(rename = "E4")]
    pub e4: Option<EdgeSpec>,
    #[serde(rename = "E5")]
    pub e5: Option<EdgeSpec>,
    #[serde(rename = "E6")]
    pub e6: Option<EdgeSpec>,
    #[serde(rename = "E7")]
    pub e7: Option<EdgeSpec>,
    #[serde(rename = "E8")]
    pub e8: Option<EdgeSpec>,
    #[serde(rename = "E9")]
    pub e9: Option<EdgeSpec>,
    #[serde(rename = "E10")]
    pub e10: Option<EdgeSpec>,
    #[serde(rename = "E11")]
    pub e11: Option<EdgeSpec>,
    #[serde(rename = "E12")]
    pub e12: Option<EdgeSpec>,
    /// In a volume topology: the names of the faces F1 … F6 (`[[face]]` tables).
    #[serde(rename = "F1")]
    pub f1: Option<String>,
    #[serde(rename = "F2")]
    pub f2: Option<String>,
    #[serde(rename = "F3")]
    pub f3: Option<String>,
    #[serde(rename = "F4")]
    pub f4: Option<String>,
    #[serde(rename = "F5")]
    pub f5: Option<String>,
    #[serde(rename = "F6")]
    pub f6: Option<String>,
}

fn auto() -> String {
    "auto".into()
}

/// `faces = { file = "faces.x", orient = ["ab", …] }`: six surface blocks F1 … F6.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FacesFile {
    /// Plot3D file (any flavour), relative to the case file.
    pub file: PathBuf,
    /// Per face, how the stored block's indices (p, q) run along the face's (a, b) of
    /// [`crate::grid::faces`]: "ab" (default: p = a, q = b), "ba" (transposed), with "-" before a
    /// letter for a reversed direction ("-ab", "a-b", "b-a", …).
    pub orient: Option<Vec<String>>,
}

impl VolumeSpec {
    /// The names of faces F1 … F6 (a volume of a volume topology).
    pub fn face_names(&self) -> [&Option<String>; 6] {
        [&self.f1, &self.f2, &self.f3, &self.f4, &self.f5, &self.f6]
    }

    /// (ni, nj, nk) of a volume given by its edges or a faces file: all three are needed.
    pub fn dims(&self, place: &str) -> Result<[usize; 3]> {
        match (self.ni, self.nj, self.nk) {
            (Some(a), Some(b), Some(c)) => Ok([a, b, c]),
            _ => Err(Error::input(
                place,
                "a volume given by edges or a faces file needs ni, nj and nk",
            )),
        }
    }

    pub(crate) fn edge_specs(&self) -> [&Option<EdgeSpec>; 12] {
        [
            &self.e1, &self.e2, &self.e3, &self.e4, &self.e5, &self.e6, &self.e7, &self.e8,
            &self.e9, &self.e10, &self.e11, &self.e12,
        ]
    }
}
