//! A one-loop CAD face with a cusp gridded as a block whose side E1 is collapsed to the cusp,
//! one point in (u, v) and in 3D (issue #14, `src/cad/trim/cusp.rs`): a three-edge sliver
//! (`data/step/make_cusp.py`, as the CATIA ventilator's) whose every corner set by turning
//! angle folds, and which has no balanced corner set, is gridded fold-free, its cells at the
//! cusp triangles.

mod common;
use common::{ellipgrid, grid_area, grid_node as node, root, text};
use ellipgrid::cad::{grid_face, grid_face_blocks, grid_face_by, read_step_faces, Corners};
use ellipgrid::case::DistributionSpec;
use ellipgrid::grid::Edge;
use ellipgrid::solve::select::by_name;
use ellipgrid::Error;

fn cusp() -> ellipgrid::cad::StepFace {
    let path = root().join("data/step/plane_cusp.step");
    read_step_faces(&path).unwrap().remove(0)
}

/// The face's area: the triangle (0,0), (10,0), (10,2) less the three circular segments cut
/// off by its concave arcs (chords 10, 2, √104 on radii 100, 20, 60).
fn exact_area() -> f64 {
    let seg = |d: f64, r: f64| {
        let t = 2.0 * (d / (2.0 * r)).asin();
        0.5 * r * r * (t - t.sin())
    };
    10.0 - seg(10.0, 100.0) - seg(2.0, 20.0) - seg(104f64.sqrt(), 60.0)
}

#[test]
fn a_sliver_whose_corner_sets_fold_grids_fold_free_with_its_cusp_collapsed() {
    let face = cusp();
    let d = DistributionSpec::Uniform {};
    let mut errs = Vec::new();
    for n in [17, 33, 65] {
        let mut solver = by_name("multigrid").unwrap();
        // Every corner set by turning angle folds the (u, v) grid (measured: 1 cell next to
        // the cusp); there is no balanced set (no point inside an edge that does not bend
        // outwards, three vertices).
        let old = grid_face_by(
            &face,
            (n, n),
            &d,
            &d,
            solver.as_mut(),
            "c",
            Corners::Turning,
        );
        match &old {
            Err(Error::Folded { place, .. }) => assert!(place.ends_with("(u, v) grid"), "{place}"),
            Err(e) => panic!("{n}: {e}"),
            Ok(g) => panic!(
                "{n}: corners by turning angle do not fold: {:?}",
                g.corner_angles
            ),
        }
        let balanced = grid_face_by(
            &face,
            (n, n),
            &d,
            &d,
            solver.as_mut(),
            "c",
            Corners::Balanced,
        );
        let e = balanced.expect_err("no balanced corner set").to_string();
        assert!(e.contains("no other corner set"), "{n}: {e}");
        // The collapsed cusp: one block, fold-free.
        let gs = grid_face_blocks(&face, (n, n), &d, &d, solver.as_mut(), "c")
            .unwrap_or_else(|e| panic!("{n}: {e}"));
        assert_eq!(gs.len(), 1, "{n}");
        let g = &gs[0];
        assert!(!g.quality.is_folded(), "{n}: {:?}", g.quality.first_folded);
        // the cusp (176°) is the first and last corner, then B (96°) and C (109°)
        let deg: Vec<i64> = g.corner_angles.iter().map(|a| a.round() as i64).collect();
        assert_eq!(deg, vec![176, 96, 109, 176], "{n}");
        // side E1 is the cusp exactly; every node on the plane, inside the triangle ABC
        let grid = &g.result.grid;
        let e1 = grid.edge(Edge::E1);
        assert!(e1.iter().all(|p| *p == e1[0]), "{n}: E1 not one point");
        assert!(e1[0].iter().all(|c| c.abs() < 1e-12), "{n}: {:?}", e1[0]);
        let uv = &g.result.uv;
        let ni = grid.ni();
        assert!(
            (0..n).all(|j| uv[ni * j] == uv[0]),
            "{n}: E1 not one (u, v)"
        );
        for p in 0..ni * grid.nj() {
            let x = node(grid, p);
            assert!(x[2].abs() < 1e-12, "{n}: node {p} off the plane: {x:?}");
            let inside = x[0] >= -1e-12 && x[0] <= 10.0 + 1e-12 && x[1] >= -1e-12;
            assert!(
                inside && x[1] <= 0.2 * x[0] + 1e-12,
                "{n}: node {p} outside: {x:?}"
            );
        }
        // the triangles at the cusp split its 4° into n − 1 angles: their scaled Jacobian
        // (the sine of that angle) is the smallest, ~sin(4°/(n − 1))
        let want = (4.0f64.to_radians() / (n - 1) as f64).sin();
        let s = g.quality.scaled_jacobian_min;
        assert!(s > 0.5 * want && s < 2.0 * want, "{n}: {s} vs {want}");
        // grid_face (one block, every corner set) gives the same grid
        let one = grid_face(&face, (n, n), &d, &d, solver.as_mut(), "c").unwrap();
        assert_eq!(one.result.grid, *grid, "{n}");
        errs.push((grid_area(grid) - exact_area()).abs());
    }
    // the area converges at second order (the chords of the concave arcs)
    for w in errs.windows(2) {
        assert!(w[1] < w[0] / 3.0, "{errs:?}");
    }
}

#[test]
fn step_grid_writes_the_cusp_face_and_its_triangles() {
    let dir = tempfile::tempdir().unwrap();
    let path = root().join("data/step/plane_cusp.step");
    let o = ellipgrid(
        dir.path(),
        &[
            "step",
            "grid",
            path.to_str().unwrap(),
            "--all",
            "--ni",
            "17",
            "--nj",
            "9",
            "-o",
            "c.x",
            "-o",
            "c.obj",
            "-o",
            "c.glb",
            "-o",
            "c.vts",
        ],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("corners turning 176°, 96°, 109°, 176°"), "{t}");
    assert!(t.contains("side E1 collapsed to the cusp"), "{t}");
    assert!(t.contains("folded cells                       0"), "{t}");
    let written = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("c.x")).unwrap();
    assert_eq!(written.blocks.len(), 1);
    // OBJ: the 8 cells along the cusp are triangles, the other 16 × 8 − 8 quads; no NaN
    let obj = std::fs::read_to_string(dir.path().join("c.obj")).unwrap();
    let faces: Vec<usize> = obj
        .lines()
        .filter(|l| l.starts_with("f "))
        .map(|l| l.split_whitespace().count() - 1)
        .collect();
    assert_eq!(faces.iter().filter(|&&k| k == 3).count(), 8, "{obj}");
    assert_eq!(faces.iter().filter(|&&k| k == 4).count(), 16 * 8 - 8);
    assert!(!obj.to_lowercase().contains("nan"));
    for l in obj.lines().filter(|l| l.starts_with("vn ")) {
        let v: Vec<f64> = l[3..].split(' ').map(|x| x.parse().unwrap()).collect();
        assert!((v[2].abs() - 1.0).abs() < 1e-12, "{l}");
    }
    // glTF: one triangle per cell along the cusp, two per quad
    let glb = gltf::Gltf::from_slice(&std::fs::read(dir.path().join("c.glb")).unwrap()).unwrap();
    let blob = glb.blob.clone();
    let mesh = glb.document.meshes().next().unwrap();
    let tri = mesh.primitives().next().unwrap();
    assert_eq!(tri.mode(), gltf::mesh::Mode::Triangles);
    let reader = tri.reader(|_| blob.as_deref());
    let idx: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    assert_eq!(idx.len(), 3 * (8 + 2 * (16 * 8 - 8)));
    let pos: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    for t in idx.chunks(3) {
        let [a, b, c] = [0, 1, 2].map(|k| pos[t[k] as usize]);
        assert!(a != b && b != c && a != c, "a degenerate triangle {t:?}");
    }
    assert!(reader
        .read_normals()
        .unwrap()
        .all(|n| n.iter().all(|v| v.is_finite())));
}
