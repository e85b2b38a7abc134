//! glTF 2.0 output for 3D viewers: binary `.glb`, or `.gltf` JSON with its `.bin` beside it.
//!
//! Every block becomes one node with its own named mesh and material (a distinct colour per
//! block). The mesh has two primitives over the same vertices: TRIANGLES (two per quad of every
//! patch, counter-clockwise about the outward normal, see [`crate::io::patches`]; one for a cell
//! along a block side collapsed to a point) with unit vertex NORMALs, and LINES along every
//! grid line of the patches (none of zero length). A planar block lies at z = 0, a
//! volume block shows its six faces (each face has its own vertices so that normals stay sharp
//! at the block's edges). Optionally the vertices carry COLOR_0 from a cell quality metric
//! averaged to the nodes, mapped over the range of all blocks ([`GltfOptions::color`]).
//!
//! Coordinates are written as given, as f32; glTF's unit is the metre and its up axis +y, so a
//! viewer shows the grid in metres with its z axis towards the viewer. The files pass the Khronos
//! glTF validator with no errors (`.ci/gltf_validate.js`).

use std::collections::BTreeMap;
use std::path::Path;

use gltf_json as json;
use json::validation::{Checked::Valid, USize64};

use crate::io::patches::{block_color, block_patches, colormap, value_range, CellMetric, Patch};
use crate::io::{write_atomic, Block};
use crate::{Error, Result};

/// Options of the glTF writer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GltfOptions {
    /// Colour the vertices by this metric (cell values averaged to the nodes); `None` (the
    /// default): material colours only.
    pub color: Option<CellMetric>,
}

/// Writes `blocks` as a binary glTF (`.glb`), atomically.
pub fn write_glb(path: &Path, blocks: &[(String, Block)], opts: &GltfOptions) -> Result<()> {
    let (root, bin) = build(path, blocks, opts, None)?;
    let json = root
        .to_vec()
        .map_err(|e| Error::format(path, format!("glTF JSON: {e}")))?;
    let json_len = json.len().next_multiple_of(4);
    let bin_len = bin.len().next_multiple_of(4);
    let total = 12 + 8 + json_len + 8 + bin_len;
    let total = u32::try_from(total)
        .map_err(|_| Error::input(path.display().to_string(), "grid too large for a .glb"))?;
    write_atomic(path, |w| {
        w.write_all(b"glTF")?;
        w.write_all(&2u32.to_le_bytes())?;
        w.write_all(&total.to_le_bytes())?;
        w.write_all(&(json_len as u32).to_le_bytes())?;
        w.write_all(b"JSON")?;
        w.write_all(&json)?;
        w.write_all(&b"   "[..json_len - json.len()])?;
        w.write_all(&(bin_len as u32).to_le_bytes())?;
        w.write_all(b"BIN\0")?;
        w.write_all(&bin)?;
        w.write_all(&[0u8; 3][..bin_len - bin.len()])
    })
}

/// Writes `blocks` as `.gltf` JSON at `path` and its buffer as `path` with extension `.bin`
/// (referenced by its file name), both atomically; the buffer is written first.
pub fn write_gltf(path: &Path, blocks: &[(String, Block)], opts: &GltfOptions) -> Result<()> {
    let bin_path = path.with_extension("bin");
    let Some(uri) = bin_path.file_name().and_then(|n| n.to_str()) else {
        return Err(Error::input(
            path.display().to_string(),
            "file name is not valid UTF-8",
        ));
    };
    // The uri is a relative URI reference: escape what would not survive as one.
    let uri: String = uri
        .bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'_' | b'.' | b'~' => {
                (b as char).to_string()
            }
            _ => format!("%{b:02X}"),
        })
        .collect();
    let (root, bin) = build(path, blocks, opts, Some(uri))?;
    let json = root
        .to_vec_pretty()
        .map_err(|e| Error::format(path, format!("glTF JSON: {e}")))?;
    write_atomic(&bin_path, |w| w.write_all(&bin))?;
    write_atomic(path, |w| w.write_all(&json))
}

/// Vertex and index data of one block, before it goes into the buffer.
#[derive(Default)]
struct MeshData {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    colors: Vec<[f32; 3]>,
    triangles: Vec<u32>,
    lines: Vec<u32>,
}

/// Node values of every patch of a block, and the colour range.
type Colouring<'a> = Option<(&'a [Vec<f64>], (f64, f64))>;

fn mesh_data(patches: &[Patch], values: Colouring) -> std::result::Result<MeshData, String> {
    let mut m = MeshData::default();
    for (k, p) in patches.iter().enumerate() {
        let base = u32::try_from(m.positions.len())
            .ok()
            .filter(|b| b.checked_add(p.points.len() as u32).is_some())
            .ok_or("more than 2³² vertices")?;
        m.positions
            .extend(p.points.iter().map(|q| q.map(|v| v as f32)));
        m.normals
            .extend(p.normals().iter().map(|q| unit_f32(q.map(|v| v as f32))));
        if let Some((vals, (lo, hi))) = values {
            m.colors.extend(
                vals[k]
                    .iter()
                    .map(|&v| colormap((v - lo) / (hi - lo)).map(|c| c as f32)),
            );
        }
        // (a cell along a side collapsed to a point is one triangle, no degenerate one)
        for (q, n) in p.polygons() {
            let q = q.map(|i| base + i as u32);
            m.triangles.extend([q[0], q[1], q[2]]);
            if n == 4 {
                m.triangles.extend([q[0], q[2], q[3]]);
            }
        }
        // (no lines of zero length along such a side)
        for s in p.segments() {
            if p.points[s[0]] != p.points[s[1]] {
                m.lines.extend(s.map(|i| base + i as u32));
            }
        }
    }
    Ok(m)
}

/// Renormalises in f32 so that the validator's unit-length check (|n| = 1 ± 5e-4) holds.
fn unit_f32(n: [f32; 3]) -> [f32; 3] {
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if l > 0.0 && l.is_finite() {
        n.map(|v| v / l)
    } else {
        [0.0, 0.0, 1.0]
    }
}

/// Builds the glTF document and its buffer (`uri`: `None` for the GLB-stored buffer).
fn build(
    path: &Path,
    blocks: &[(String, Block)],
    opts: &GltfOptions,
    uri: Option<String>,
) -> Result<(json::Root, Vec<u8>)> {
    let bad = |msg: String| Error::input(path.display().to_string(), msg);
    if blocks.is_empty() {
        return Err(bad("no blocks to write".into()));
    }
    let patches: Vec<Vec<Patch>> = blocks.iter().map(|(_, b)| block_patches(b)).collect();
    for ((name, _), ps) in blocks.iter().zip(&patches) {
        if !ps.iter().all(Patch::all_finite) {
            return Err(bad(format!("block '{name}': non-finite coordinates")));
        }
    }
    let values: Option<Vec<Vec<Vec<f64>>>> = opts.color.map(|m| {
        patches
            .iter()
            .map(|ps| ps.iter().map(|p| p.node_values(m)).collect())
            .collect()
    });
    let range = values
        .as_ref()
        .map(|v| value_range(v.iter().flatten().flatten()));

    let mut root = json::Root {
        asset: json::Asset {
            generator: Some(format!("ellipgrid {}", env!("CARGO_PKG_VERSION"))),
            ..Default::default()
        },
        ..Default::default()
    };
    let mut bin: Vec<u8> = Vec::new();
    let buffer = root.push(json::Buffer {
        byte_length: USize64(0),
        name: None,
        uri,
        extensions: None,
        extras: Default::default(),
    });
    let lines_material = root.push(material("grid lines", [0.1, 0.1, 0.1]));
    let mut nodes = Vec::new();
    for (k, ((name, _), ps)) in blocks.iter().zip(&patches).enumerate() {
        let vals = values.as_ref().map(|v| (v[k].as_slice(), range.unwrap()));
        let m = mesh_data(ps, vals).map_err(|e| bad(format!("block '{name}': {e}")))?;
        let mut b = Builder {
            root: &mut root,
            bin: &mut bin,
            buffer,
        };
        let pos = b.vec3(&m.positions, true, format!("{name} positions"));
        let nrm = b.vec3(&m.normals, false, format!("{name} normals"));
        let mut attributes = BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), pos);
        attributes.insert(Valid(json::mesh::Semantic::Normals), nrm);
        if values.is_some() {
            let col = b.vec3(&m.colors, false, format!("{name} colours"));
            attributes.insert(Valid(json::mesh::Semantic::Colors(0)), col);
        }
        let mut primitives = Vec::new();
        let mat = if values.is_some() {
            // White base colour: the vertex colours show as they are.
            material(name, [1.0, 1.0, 1.0])
        } else {
            material(name, block_color(k))
        };
        let mat = b.root.push(mat);
        if !m.triangles.is_empty() {
            let tri = b.indices(&m.triangles, format!("{name} triangles"));
            primitives.push(primitive(
                attributes.clone(),
                tri,
                mat,
                json::mesh::Mode::Triangles,
            ));
        }
        if !m.lines.is_empty() {
            let lin = b.indices(&m.lines, format!("{name} grid lines"));
            let mut a = BTreeMap::new();
            a.insert(Valid(json::mesh::Semantic::Positions), pos);
            primitives.push(primitive(a, lin, lines_material, json::mesh::Mode::Lines));
        }
        if primitives.is_empty() {
            return Err(bad(format!("block '{name}': no cells and no grid lines")));
        }
        let mesh = root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name.clone()),
            primitives,
            weights: None,
        });
        nodes.push(root.push(json::Node {
            mesh: Some(mesh),
            name: Some(name.clone()),
            ..Default::default()
        }));
    }
    root.buffers[0].byte_length = USize64(bin.len() as u64);
    let scene_name = match (opts.color, range) {
        (Some(m), Some((lo, hi))) => {
            format!(
                "ellipgrid grid; vertex colours: {} {lo:.6e} to {hi:.6e}",
                m.label()
            )
        }
        _ => "ellipgrid grid".to_string(),
    };
    let scene = root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: Some(scene_name),
        nodes,
    });
    root.scene = Some(scene);
    Ok((root, bin))
}

fn material(name: &str, c: [f64; 3]) -> json::Material {
    json::Material {
        name: Some(name.to_string()),
        double_sided: true,
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor([
                c[0] as f32,
                c[1] as f32,
                c[2] as f32,
                1.0,
            ]),
            metallic_factor: json::material::StrengthFactor(0.0),
            roughness_factor: json::material::StrengthFactor(0.9),
            ..Default::default()
        },
        ..Default::default()
    }
}

fn primitive(
    attributes: BTreeMap<
        json::validation::Checked<json::mesh::Semantic>,
        json::Index<json::Accessor>,
    >,
    indices: json::Index<json::Accessor>,
    material: json::Index<json::Material>,
    mode: json::mesh::Mode,
) -> json::mesh::Primitive {
    json::mesh::Primitive {
        attributes,
        extensions: None,
        extras: Default::default(),
        indices: Some(indices),
        material: Some(material),
        mode: Valid(mode),
        targets: None,
    }
}

/// Appends arrays to the buffer, one buffer view and accessor each.
struct Builder<'a> {
    root: &'a mut json::Root,
    bin: &'a mut Vec<u8>,
    buffer: json::Index<json::Buffer>,
}

impl Builder<'_> {
    fn view(
        &mut self,
        bytes: &[u8],
        target: json::buffer::Target,
    ) -> json::Index<json::buffer::View> {
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.root.push(json::buffer::View {
            buffer: self.buffer,
            byte_length: USize64(bytes.len() as u64),
            byte_offset: Some(USize64(offset as u64)),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        })
    }

    /// A float VEC3 accessor (with min/max when `bounds`: required for POSITION).
    fn vec3(&mut self, v: &[[f32; 3]], bounds: bool, name: String) -> json::Index<json::Accessor> {
        let bytes: Vec<u8> = v.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, json::buffer::Target::ArrayBuffer);
        let (min, max) = if bounds {
            let mut lo = [f32::INFINITY; 3];
            let mut hi = [f32::NEG_INFINITY; 3];
            for p in v {
                for c in 0..3 {
                    lo[c] = lo[c].min(p[c]);
                    hi[c] = hi[c].max(p[c]);
                }
            }
            (Some(serde_json::json!(lo)), Some(serde_json::json!(hi)))
        } else {
            (None, None)
        };
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64(v.len() as u64),
            component_type: Valid(json::accessor::GenericComponentType(
                json::accessor::ComponentType::F32,
            )),
            extensions: None,
            extras: Default::default(),
            type_: Valid(json::accessor::Type::Vec3),
            min,
            max,
            name: Some(name),
            normalized: false,
            sparse: None,
        })
    }

    /// An unsigned-int index accessor.
    fn indices(&mut self, v: &[u32], name: String) -> json::Index<json::Accessor> {
        let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, json::buffer::Target::ElementArrayBuffer);
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64(v.len() as u64),
            component_type: Valid(json::accessor::GenericComponentType(
                json::accessor::ComponentType::U32,
            )),
            extensions: None,
            extras: Default::default(),
            type_: Valid(json::accessor::Type::Scalar),
            min: None,
            max: None,
            name: Some(name),
            normalized: false,
            sparse: None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Grid2, Grid3};

    fn blocks() -> Vec<(String, Block)> {
        let p = Grid2::<2>::from_fn(4, 3, |i, j| [i as f64 * 0.5, j as f64 + 0.1 * i as f64]);
        let mut v = Grid3::zeros(3, 2, 2);
        for k in 0..2 {
            for j in 0..2 {
                for i in 0..3 {
                    v.set(i, j, k, [i as f64, j as f64, k as f64 + 5.0]);
                }
            }
        }
        vec![
            ("plane".into(), Block::Planar(p)),
            ("box".into(), Block::Volume(v)),
        ]
    }

    #[test]
    fn glb_layout_and_counts() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("g.glb");
        let opts = GltfOptions {
            color: Some(CellMetric::Skewness),
        };
        write_glb(&path, &blocks(), &opts).unwrap();
        let b = std::fs::read(&path).unwrap();
        assert_eq!(&b[0..4], b"glTF");
        assert_eq!(
            u32::from_le_bytes(b[8..12].try_into().unwrap()) as usize,
            b.len()
        );
        assert_eq!(b.len() % 4, 0);
        let jl = u32::from_le_bytes(b[12..16].try_into().unwrap()) as usize;
        let root = json::Root::from_slice(&b[20..20 + jl]).unwrap();
        assert_eq!(root.meshes.len(), 2);
        assert_eq!(root.nodes[1].name.as_deref(), Some("box"));
        // Volume 3 × 2 × 2: faces of 2×2, 2×2, 3×2, 3×2, 3×2, 3×2 nodes = 32 vertices.
        let pos = &root.accessors[root.meshes[1].primitives[0].attributes
            [&Valid(json::mesh::Semantic::Positions)]
            .value()];
        assert_eq!(pos.count.0, 32);
        assert_eq!(pos.min, Some(serde_json::json!([0.0, 0.0, 5.0])));
        // Triangles: 2 per quad, 1 + 1 + 2 + 2 + 2 + 2 quads.
        let tri = root.meshes[1].primitives[0].indices.unwrap();
        assert_eq!(root.accessors[tri.value()].count.0, 60);
        assert!(root.meshes[0].primitives[0]
            .attributes
            .contains_key(&Valid(json::mesh::Semantic::Colors(0))));
    }

    #[test]
    fn gltf_writes_bin_beside_and_rejects_nan() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("my grid.gltf");
        write_gltf(&path, &blocks(), &GltfOptions::default()).unwrap();
        let root = json::Root::from_slice(&std::fs::read(&path).unwrap()).unwrap();
        assert_eq!(root.buffers[0].uri.as_deref(), Some("my%20grid.bin"));
        let bin = std::fs::read(d.path().join("my grid.bin")).unwrap();
        assert_eq!(root.buffers[0].byte_length.0 as usize, bin.len());

        let g = Grid2::<2>::from_fn(2, 2, |i, _| [f64::NAN * i as f64, 0.0]);
        let p = d.path().join("nan.glb");
        let e = write_glb(
            &p,
            &[("b".into(), Block::Planar(g))],
            &GltfOptions::default(),
        );
        let e = e.unwrap_err().to_string();
        assert!(e.contains("nan.glb") && e.contains("non-finite"), "{e}");
        assert!(!p.exists());
    }
}
