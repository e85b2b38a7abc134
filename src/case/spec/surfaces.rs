//! The surface tables of a case file: a surface block's `surface` (inline or the name of a
//! `[[surface]]`) and the surface types.

use serde::Deserialize;
use std::path::PathBuf;

/// A block's surface: given inline, or the name of a `[[surface]]`.
#[derive(Clone, Debug)]
pub enum SurfaceRef {
    Inline(SurfaceSpec),
    Named(String),
}

impl<'de> Deserialize<'de> for SurfaceRef {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        use serde::de::value::MapAccessDeserializer;
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = SurfaceRef;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a surface table or the name of a [[surface]]")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> std::result::Result<SurfaceRef, E> {
                Ok(SurfaceRef::Named(v.to_string()))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> std::result::Result<SurfaceRef, A::Error> {
                SurfaceSpec::deserialize(MapAccessDeserializer::new(map)).map(SurfaceRef::Inline)
            }
        }
        d.deserialize_any(V)
    }
}

/// `[[surface]]`: a named surface, `name` beside the keys of a [`SurfaceSpec`]
/// (`type = "hermite_net"`, …).
#[derive(Clone, Debug)]
pub struct NamedSurface {
    pub name: String,
    pub surface: SurfaceSpec,
}

impl<'de> Deserialize<'de> for NamedSurface {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        use serde::de::Error as _;
        let mut t = toml::Table::deserialize(d)?;
        let name = match t.remove("name") {
            Some(toml::Value::String(s)) => s,
            Some(_) => return Err(D::Error::custom("[[surface]]: name must be a string")),
            None => return Err(D::Error::custom("[[surface]] needs a name")),
        };
        let surface = SurfaceSpec::deserialize(toml::Value::Table(t))
            .map_err(|e| D::Error::custom(format!("[[surface]] '{name}': {e}")))?;
        Ok(NamedSurface { name, surface })
    }
}

/// The surface of a `kind = "surface"` block. Its parameter square's sides are the block's
/// edges: E1 ↔ u = 0, E2 ↔ u = 1, E3 ↔ v = 0, E4 ↔ v = 1.
#[derive(Clone, Debug, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum SurfaceSpec {
    /// A bicubic Hermite surface through a control net: read from a Plot3D file (a surface
    /// block, ni × nj × 1; `block` is 1-based, default 1), or given inline as `ni`, `nj` and
    /// `points` (i fastest). Control points sit at uniform parameter values.
    HermiteNet {
        file: Option<PathBuf>,
        #[serde(default)]
        block: Option<usize>,
        ni: Option<usize>,
        nj: Option<usize>,
        points: Option<Vec<Vec<f64>>>,
    },
    /// The plane x = origin + u du + v dv.
    Plane {
        origin: Vec<f64>,
        du: Vec<f64>,
        dv: Vec<f64>,
    },
    /// The paper's z = (1/8) tanh(15 (1/4 − (x−1)² − (y−1)²)) over (x, y) ∈ [0, 2]² (a struct
    /// variant so that unknown keys are errors, see [`super::DistributionSpec`]).
    TanhBump {},
    /// Scherk's minimal surface z = ln(cos y / cos x) over [−a, a]².
    Scherk { half_width: f64 },
    /// A block face on a STEP model that need not be a CAD face (issue #14): the model is
    /// faces `faces` of `file` (1-based, as `step list` numbers them), the block's four edges
    /// are curves on it (`line`, `polyline`, `spline` projected onto it, `iso` lines of its
    /// faces, `intersection`s with another face), and the surface is the bicubic Hermite net
    /// of `net` = [m, n] points (default the block's ni × nj) spanned by those edges and
    /// projected onto the model (the paper's wing–pylon way, §5); the grid's nodes are moved
    /// onto the model at the end. `along` = [x, y, z]: lines, polylines and splines are
    /// projected along this direction (a planform line onto a wing: [0, 0, 1]) instead of to
    /// their closest points.
    Step {
        file: PathBuf,
        faces: Vec<usize>,
        net: Option<[usize; 2]>,
        along: Option<Vec<f64>>,
    },
}
