//! Outputs for viewers and solvers, read back by independent readers: glTF with the `gltf`
//! crate, OBJ with `tobj`, and every Plot3D flavour `convert` writes with our reader (VTK's
//! readers check the same files in `.ci/independent_readers.py`).

mod common;
use common::*;
use ellipgrid::io::gltf::{write_glb, GltfOptions};
use ellipgrid::io::obj::write_obj;
use ellipgrid::io::patches::{block_patches, CellMetric};
use ellipgrid::io::plot3d::{read_plot3d, write_plot3d, ByteOrder, Encoding, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::{Grid2, Grid3};
use std::path::Path;

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn example(name: &str) -> String {
    root()
        .join(format!("examples/{name}.toml"))
        .display()
        .to_string()
}

/// A curved volume block (right-handed, or mirrored: left-handed).
fn volume(ni: usize, nj: usize, nk: usize, mirror: bool) -> Block {
    let mut g = Grid3::zeros(ni, nj, nk);
    for k in 0..nk {
        for j in 0..nj {
            for i in 0..ni {
                let (s, t, u) = (
                    i as f64 / (ni - 1) as f64,
                    j as f64 / (nj - 1) as f64,
                    k as f64 / (nk - 1) as f64,
                );
                let r = 1.0 + s;
                let x = r * (1.1 * t).cos();
                g.set(
                    i,
                    j,
                    k,
                    [
                        if mirror { -x } else { x },
                        r * (1.1 * t).sin(),
                        u + 0.2 * s * t,
                    ],
                );
            }
        }
    }
    Block::Volume(g)
}

/// Reads a .glb: per node (name, positions, normals, triangle indices, line indices, colours).
type GlbMesh = (
    String,
    Vec<[f32; 3]>,
    Vec<[f32; 3]>,
    Vec<u32>,
    Vec<u32>,
    Option<Vec<[f32; 3]>>,
);

fn read_glb(path: &Path) -> Vec<GlbMesh> {
    let g = gltf::Gltf::from_slice(&std::fs::read(path).unwrap()).expect("gltf reads the file");
    let blob = g.blob.clone();
    let mut out = Vec::new();
    for node in g.document.nodes() {
        let mesh = node.mesh().expect("every node has a mesh");
        assert_eq!(mesh.name(), node.name(), "mesh named after its block");
        let (mut pos, mut nrm, mut tri, mut lin, mut col) = (vec![], vec![], vec![], vec![], None);
        for p in mesh.primitives() {
            let r = p.reader(|_| blob.as_deref());
            let idx: Vec<u32> = r.read_indices().unwrap().into_u32().collect();
            match p.mode() {
                gltf::mesh::Mode::Triangles => {
                    pos = r.read_positions().unwrap().collect();
                    nrm = r.read_normals().unwrap().collect();
                    col = r.read_colors(0).map(|c| c.into_rgb_f32().collect());
                    tri = idx;
                }
                gltf::mesh::Mode::Lines => lin = idx,
                m => panic!("unexpected mode {m:?}"),
            }
        }
        out.push((node.name().unwrap().to_string(), pos, nrm, tri, lin, col));
    }
    out
}

#[test]
fn glb_of_an_example_reads_back_with_the_gltf_crate() {
    let d = tmp();
    let o = ellipgrid(
        d.path(),
        &["run", &example("curved"), "-o", "g.x", "-o", "g.glb", "-q"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let grid = read_plot3d(&d.path().join("g.x")).unwrap();
    let Block::Planar(g) = &grid.blocks[0] else {
        panic!("planar expected")
    };
    let meshes = read_glb(&d.path().join("g.glb"));
    assert_eq!(meshes.len(), 1);
    let (name, pos, nrm, tri, lin, col) = &meshes[0];
    assert_eq!(name, "curved");
    assert_eq!(pos.len(), g.len());
    // Same points to f32 rounding, z = 0 (the example is right-handed: no mirroring).
    for j in 0..g.nj() {
        for i in 0..g.ni() {
            let p = g.point(i, j);
            let q = pos[g.idx(i, j)];
            assert_eq!(
                [q[0], q[1], q[2]],
                [p[0] as f32, p[1] as f32, 0.0],
                "node ({i}, {j})"
            );
        }
    }
    let cells = (g.ni() - 1) * (g.nj() - 1);
    assert_eq!(tri.len(), 6 * cells);
    assert_eq!(
        lin.len(),
        2 * ((g.ni() - 1) * g.nj() + g.ni() * (g.nj() - 1))
    );
    // Every triangle is counter-clockwise seen from +z, and the normals are +z.
    for t in tri.chunks(3) {
        let [a, b, c] = [0, 1, 2].map(|k| pos[t[k] as usize]);
        let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        assert!(cross > 0.0, "clockwise triangle {t:?}");
    }
    assert!(nrm.iter().all(|n| *n == [0.0, 0.0, 1.0]));
    assert!(col.is_none(), "no vertex colours unless asked for");
}

#[test]
fn glb_of_volumes_has_outward_faces_and_quality_colours() {
    let d = tmp();
    let path = d.path().join("v.glb");
    let blocks = vec![
        ("right".to_string(), volume(5, 4, 3, false)),
        ("left".to_string(), volume(3, 6, 4, true)),
    ];
    let opts = GltfOptions {
        color: Some(CellMetric::Skewness),
    };
    write_glb(&path, &blocks, &opts).unwrap();
    let meshes = read_glb(&path);
    assert_eq!(meshes.len(), 2);
    for ((name, b), (rname, pos, nrm, tri, _, col)) in blocks.iter().zip(&meshes) {
        assert_eq!(name, rname);
        let expect: Vec<[f32; 3]> = block_patches(b)
            .iter()
            .flat_map(|p| p.points.iter().map(|q| q.map(|v| v as f32)))
            .collect();
        assert_eq!(pos, &expect, "{name}: the six faces' nodes in order");
        // Outward orientation: the divergence theorem gives the (positive) block volume.
        let vol: f64 = tri
            .chunks(3)
            .map(|t| {
                let [a, b, c] = [0, 1, 2].map(|k| pos[t[k] as usize].map(f64::from));
                a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0])
            })
            .sum::<f64>()
            / 6.0;
        assert!(vol > 0.5, "{name}: enclosed volume {vol}");
        for n in nrm {
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!((l - 1.0).abs() < 1e-6, "{name}: normal length {l}");
        }
        let col = col.as_ref().expect("vertex colours");
        assert_eq!(col.len(), pos.len());
        assert!(col.iter().flatten().all(|c| (0.0..=1.0).contains(c)));
    }
}

#[test]
fn gltf_with_bin_and_colours_through_the_cli() {
    let d = tmp();
    let o = ellipgrid(d.path(), &["run", &example("scherk"), "-o", "s.x", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let o = ellipgrid(
        d.path(),
        &["convert", "s.x", "s.gltf", "--color", "jacobian", "-q"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let g = gltf::Gltf::from_slice(&std::fs::read(d.path().join("s.gltf")).unwrap()).unwrap();
    let bin = std::fs::read(d.path().join("s.bin")).unwrap();
    let grid = read_plot3d(&d.path().join("s.x")).unwrap();
    let Block::Surface(s) = &grid.blocks[0] else {
        panic!("surface expected")
    };
    let mesh = g.document.meshes().next().unwrap();
    let prim = mesh.primitives().next().unwrap();
    let r = prim.reader(|_| Some(&bin[..]));
    let pos: Vec<[f32; 3]> = r.read_positions().unwrap().collect();
    assert_eq!(pos.len(), s.len());
    for (k, q) in pos.iter().enumerate() {
        let (i, j) = (k % s.ni(), k / s.ni());
        assert_eq!(*q, s.point(i, j).map(|v| v as f32));
    }
    assert!(r.read_colors(0).is_some());
    assert!(g
        .document
        .scenes()
        .next()
        .unwrap()
        .name()
        .unwrap()
        .contains("scaled jacobian"));
}

#[test]
fn obj_reads_back_with_tobj_to_the_same_points_and_faces() {
    let d = tmp();
    let path = d.path().join("m.obj");
    let planar = Block::Planar(Grid2::from_fn(6, 4, |i, j| {
        [i as f64 * 0.1 + 1e-9 * j as f64, j as f64 / 3.0]
    }));
    let blocks = vec![
        ("plane".to_string(), planar),
        ("box".to_string(), volume(4, 3, 3, false)),
    ];
    write_obj(&path, &blocks).unwrap();
    let opts = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, materials) = tobj::load_obj(&path, &opts).unwrap();
    let materials = materials.unwrap();
    assert_eq!(materials.len(), 2);
    assert_eq!(models.len(), 2);
    for ((name, b), m) in blocks.iter().zip(&models) {
        assert_eq!(&m.name, name);
        assert_eq!(materials[m.mesh.material_id.unwrap()].name, *name);
        let patches = block_patches(b);
        let quads: Vec<[[f64; 3]; 4]> = patches
            .iter()
            .flat_map(|p| {
                p.quads()
                    .map(|q| q.map(|k| p.points[k]))
                    .collect::<Vec<_>>()
            })
            .collect();
        let arities = &m.mesh.face_arities;
        assert!(
            arities.is_empty() || arities.iter().all(|&a| a == 4),
            "quads as faces"
        );
        assert_eq!(m.mesh.indices.len(), 4 * quads.len(), "{name}");
        let p = &m.mesh.positions;
        for (f, q) in quads.iter().enumerate() {
            for (c, x) in q.iter().enumerate() {
                let v = m.mesh.indices[4 * f + c] as usize;
                assert_eq!(
                    [p[3 * v], p[3 * v + 1], p[3 * v + 2]],
                    *x,
                    "{name} face {f}"
                );
            }
        }
        assert_eq!(
            m.mesh.normal_indices.len(),
            m.mesh.indices.len(),
            "vertex normals"
        );
    }
}

#[test]
fn run_writes_viewer_outputs_and_rejects_unknown_extensions() {
    let d = tmp();
    let outs = ["g.glb", "g.gltf", "g.obj", "g.png", "g.svg"];
    let mut args = vec!["run", "-q"];
    let case = example("boundary_layer");
    args.push(&case);
    for o in &outs {
        args.extend(["-o", o]);
    }
    let o = ellipgrid(d.path(), &args);
    assert!(o.status.success(), "{}", text(&o));
    for f in outs.iter().chain(&["g.bin", "g.mtl"]) {
        assert!(d.path().join(f).exists(), "{f} missing");
    }
    let o = ellipgrid(d.path(), &["run", &case, "-o", "g.stl"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o).contains(".glb") && text(&o).contains("g.stl"),
        "{}",
        text(&o)
    );
}

/// `convert` into a Plot3D flavour, read back with our reader.
fn convert_flavour(
    dir: &Path,
    input: &str,
    out: &str,
    opts: &[&str],
) -> ellipgrid::io::plot3d::Plot3dFile {
    let mut args = vec!["convert", "-q", input, out];
    args.extend(opts);
    let o = ellipgrid(dir, &args);
    assert!(o.status.success(), "{args:?}: {}", text(&o));
    read_plot3d(&dir.join(out)).unwrap()
}

#[test]
fn convert_covers_every_plot3d_flavour_and_keeps_iblank() {
    let d = tmp();
    // Two planar blocks with IBLANK values of their own.
    let b1 = Block::Planar(Grid2::from_fn(5, 4, |i, j| {
        [i as f64 / 3.0, j as f64 * 0.7 + 0.1]
    }));
    let b2 = Block::Planar(Grid2::from_fn(3, 6, |i, j| {
        [2.0 + i as f64, j as f64 / 7.0]
    }));
    let ib = vec![
        (0..20).map(|k| k % 3 - 1).collect::<Vec<i32>>(),
        vec![2; 18],
    ];
    let fmt = Plot3dFormat {
        two_d: true,
        iblank: true,
        ..Plot3dFormat::default()
    };
    write_plot3d(
        &d.path().join("in.x"),
        &[b1.clone(), b2.clone()],
        &fmt,
        Some(&ib),
    )
    .unwrap();
    let blocks = [b1, b2];
    for enc in ["unformatted", "stream", "formatted"] {
        for prec in ["single", "double"] {
            for endian in ["--little-endian", "--big-endian"] {
                for dim in ["--two-d", "--three-d"] {
                    let out = format!("o_{enc}_{prec}{endian}{dim}.x");
                    let opts = ["--encoding", enc, "--precision", prec, endian, dim];
                    let f = convert_flavour(d.path(), "in.x", &out, &opts);
                    assert_eq!(f.format.two_d, dim == "--two-d", "{out}");
                    assert!(f.format.iblank && f.format.multi_block, "{out}");
                    assert_eq!(f.iblank.as_ref(), Some(&ib), "{out}: IBLANK kept");
                    if enc != "formatted" {
                        let big = endian == "--big-endian";
                        assert_eq!(f.format.byte_order == ByteOrder::Big, big, "{out}");
                        assert_eq!(
                            f.format.precision.bytes(),
                            if prec == "single" { 4 } else { 8 }
                        );
                    }
                    let tol = if prec == "single" { 1e-7 } else { 0.0 };
                    for (a, b) in f.blocks.iter().zip(&blocks) {
                        assert_eq!(a.dims(), b.dims());
                        for c in 0..2 {
                            for (x, y) in a.coord(c).iter().zip(b.coord(c)) {
                                assert!(
                                    (x - y).abs() <= tol * y.abs().max(1.0),
                                    "{out}: {x} vs {y}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }
    // Dropping IBLANK, and single-block files of one block.
    let f = convert_flavour(d.path(), "in.x", "noib.x", &["--no-iblank"]);
    assert!(!f.format.iblank && f.iblank.is_none());
    let o = ellipgrid(d.path(), &["convert", "in.x", "one.x", "--single-block"]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "two blocks do not fit a single-block file"
    );
    assert!(text(&o).contains("one.x"), "{}", text(&o));
    let o = ellipgrid(d.path(), &["run", "-q", &example("curved"), "-o", "c.x"]);
    assert!(o.status.success());
    let f = convert_flavour(
        d.path(),
        "c.x",
        "c1.x",
        &["--single-block", "--encoding", "stream"],
    );
    assert!(!f.format.multi_block && f.format.encoding == Encoding::Stream);
    // With no option the input's flavour is kept.
    let f = convert_flavour(
        d.path(),
        "o_formatted_single--big-endian--two-d.x",
        "same.x",
        &[],
    );
    assert_eq!(f.format.encoding, Encoding::Formatted);
}

#[test]
fn convert_rejects_bad_requests_without_writing() {
    let d = tmp();
    let o = ellipgrid(d.path(), &["run", "-q", &example("curved"), "-o", "c.x"]);
    assert!(o.status.success());
    for (args, needle) in [
        (
            vec!["convert", "c.x", "c.obj", "--color", "skewness"],
            "--color",
        ),
        (
            vec!["convert", "c.x", "c.glb", "--precision", "single"],
            "Plot3D options",
        ),
        (
            vec!["convert", "c.x", "c.glb", "--color", "beauty"],
            "beauty",
        ),
        (vec!["convert", "c.x", "c2.x", "--encoding", "hex"], "hex"),
        (vec!["convert", "c.obj", "c3.x"], "cannot read"),
        (vec!["convert", "missing.x", "c4.x"], "missing.x"),
    ] {
        let o = ellipgrid(d.path(), &args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        assert!(text(&o).contains(needle), "{args:?}: {}", text(&o));
        assert!(!d.path().join(args[2]).exists(), "{args:?} wrote a file");
    }
    // A case file converts directly (it is gridded first), and VTK files convert back exactly.
    let o = ellipgrid(d.path(), &["convert", "-q", &example("curved"), "c.vtm"]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(d.path().join("c_1_curved.vts").exists());
    let o = ellipgrid(d.path(), &["convert", "-q", "c.vtm", "back.x"]);
    assert!(o.status.success(), "{}", text(&o));
    let a = read_plot3d(&d.path().join("c.x")).unwrap();
    let b = read_plot3d(&d.path().join("back.x")).unwrap();
    assert_eq!(a.blocks, b.blocks, "Plot3D → .vtm → Plot3D is exact");
    let o = ellipgrid(d.path(), &["plot", "-q", "c_1_curved.vts", "-o", "c.svg"]);
    assert!(o.status.success(), "{}", text(&o));
}
