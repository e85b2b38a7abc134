//! CAD faces with holes (issue #14) gridded as several blocks: an O-type ring of four blocks
//! around each hole, the face cut into one-hole strips between holes. Known answers from the
//! OpenCascade-written files in `data/step/` (`data/step/README.md`): every node on the plane,
//! hole boundary nodes on the circles, the face's area summed over its blocks converging at
//! second order to the plate's area minus the holes', cut nodes shared bit for bit, the
//! blocks' normals the face's.

mod common;
use common::{ellipgrid, root, text};
use ellipgrid::cad::{grid_face_blocks, read_step_faces, FaceGrid, Route};
use ellipgrid::case::DistributionSpec;
use ellipgrid::grid::Grid2;
use ellipgrid::quality;
use ellipgrid::quality::quality3d::AnyQuality;
use ellipgrid::solve::direct::DirectLu;
use std::f64::consts::PI;

fn file(name: &str) -> std::path::PathBuf {
    root().join("data/step").join(name)
}

/// Face `k` (1-based) of a test file gridded with `ni` × `nj` uniform nodes per block.
fn blocks(name: &str, k: usize, (ni, nj): (usize, usize)) -> Vec<FaceGrid> {
    let faces = read_step_faces(&file(name)).unwrap();
    let d = DistributionSpec::Uniform {};
    grid_face_blocks(&faces[k - 1], (ni, nj), &d, &d, &mut DirectLu::new(), name)
        .unwrap_or_else(|e| panic!("{e}"))
}

fn node(g: &Grid2<3>, p: usize) -> [f64; 3] {
    [g.coord(0)[p], g.coord(1)[p], g.coord(2)[p]]
}

/// Σ ½ (d₁ × d₂) over the cells: the grid's vector area (exact for planar quads; its length
/// is the area of a planar grid, its sign says which way the grid's normal points).
fn vector_area(g: &Grid2<3>) -> [f64; 3] {
    let (ni, nj) = (g.ni(), g.nj());
    let mut a = [0.0; 3];
    for j in 0..nj - 1 {
        for i in 0..ni - 1 {
            let p = |ii: usize, jj: usize| node(g, ii + ni * jj);
            let (x0, x1, x2, x3) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            let d1 = [x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]];
            let d2 = [x3[0] - x1[0], x3[1] - x1[1], x3[2] - x1[2]];
            a[0] += 0.5 * (d1[1] * d2[2] - d1[2] * d2[1]);
            a[1] += 0.5 * (d1[2] * d2[0] - d1[0] * d2[2]);
            a[2] += 0.5 * (d1[0] * d2[1] - d1[1] * d2[0]);
        }
    }
    a
}

fn unfolded(g: &Grid2<3>) -> bool {
    !AnyQuality::from(quality::quality_surface(g)).is_folded()
}

/// The boundary nodes of a block (index p of its grid).
fn boundary(g: &Grid2<3>) -> Vec<usize> {
    let (ni, nj) = (g.ni(), g.nj());
    (0..ni * nj)
        .filter(|p| {
            let (i, j) = (p % ni, p / ni);
            i == 0 || j == 0 || i == ni - 1 || j == nj - 1
        })
        .collect()
}

/// Checks a face with holes on the plane z = `z` with outward normal `sign`·z at three
/// resolutions: `4 · holes.len()` blocks, fold-free; every node on the plane (1e-11); the
/// first grid line (j = 0) of every block on its hole's circle (1e-11); cut nodes shared
/// bit for bit (every boundary node that another block also has is the same f64s there);
/// the summed area converging to `exact` at second order. Returns the area errors.
fn check_face(
    name: &str,
    k: usize,
    (z, sign): (f64, f64),
    holes: &[([f64; 2], f64)],
    exact: f64,
) -> Vec<f64> {
    let mut errs = Vec::new();
    for n in [9, 17, 33] {
        let gs = blocks(name, k, (2 * n - 1, n));
        assert_eq!(gs.len(), 4 * holes.len(), "{name} face {k}");
        let mut total = 0.0;
        for (b, g) in gs.iter().enumerate() {
            let g = &g.result.grid;
            assert!(unfolded(g), "{name} face {k} block {b} ({n}): folded");
            let a = vector_area(g);
            assert!(a[2] * sign > 0.0, "{name} face {k} block {b}: normal {a:?}");
            total += a[2].abs();
            for p in 0..g.len() {
                let x = node(g, p);
                assert!(
                    (x[2] - z).abs() < 1e-11,
                    "{name} block {b}: node {x:?} off the plane"
                );
            }
            let ni = g.ni();
            let on_hole = holes.iter().any(|(c, r)| {
                (0..ni).all(|i| {
                    let x = node(g, i);
                    ((x[0] - c[0]).hypot(x[1] - c[1]) - r).abs() < 1e-11
                })
            });
            assert!(
                on_hole,
                "{name} face {k} block {b}: j = 0 is not on a hole's circle"
            );
        }
        // Shared nodes: every boundary node of a block that lies at another block's boundary
        // node is that node bit for bit; 4 cuts of n nodes per hole (+ a strip cut of 2n − 1
        // between holes) are shared.
        let mut shared = 0;
        for (a, ga) in gs.iter().enumerate() {
            for gb in gs.iter().skip(a + 1) {
                let (ga, gb) = (&ga.result.grid, &gb.result.grid);
                for p in boundary(ga) {
                    for q in boundary(gb) {
                        let (x, y) = (node(ga, p), node(gb, q));
                        let d = (0..3).map(|c| (x[c] - y[c]).abs()).fold(0.0, f64::max);
                        if d < 1e-9 {
                            assert_eq!(x.map(f64::to_bits), y.map(f64::to_bits), "{name}");
                            shared += 1;
                        }
                    }
                }
            }
        }
        // Cut nodes are shared by 2 blocks, except the cut ends where 3 blocks meet (counted
        // 3 times as pairs): at least every cut node once.
        let cuts = 4 * holes.len() * n + (holes.len() - 1) * (2 * n - 1);
        assert!(
            shared >= cuts,
            "{name}: {shared} shared nodes, {cuts} cut nodes"
        );
        errs.push((total - exact).abs() / exact);
        eprintln!("{name} face {k}: {n} nodes, area error {:.3e}", errs[errs.len() - 1]);
    }
    for w in errs.windows(2) {
        let r = w[0] / w[1];
        assert!(
            (3.3..5.0).contains(&r),
            "{name} face {k}: area errors {errs:?}, ratio {r}"
        );
    }
    errs
}

#[test]
fn a_plane_face_with_one_hole_is_a_ring_of_four_fold_free_blocks() {
    let exact = 12.0 - 0.5625 * PI;
    let errs = check_face(
        "box_with_hole_face.step",
        1,
        (0.0, 1.0),
        &[([2.0, 1.5], 0.75)],
        exact,
    );
    assert!(errs[2] < 1e-3, "{errs:?}");
}

#[test]
fn the_plates_faces_with_two_holes_are_two_rings_and_converge_in_area() {
    let faces = read_step_faces(&file("plate_with_holes.step")).unwrap();
    let holes: Vec<usize> = faces
        .iter()
        .filter(|f| f.route() == Route::Holes(2))
        .map(|f| f.index)
        .collect();
    assert_eq!(holes, [2, 5]);
    // 40 × 30 less the fillet's corner (9 − 9π/4) and two holes of radius 3.
    let exact = 1200.0 - (9.0 - 2.25 * PI) - 18.0 * PI;
    let circles = [([10.0, 15.0], 3.0), ([25.0, 15.0], 3.0)];
    // Face 2 is the top (z = 5, normal +z), face 5 the bottom (z = 0, normal −z).
    check_face("plate_with_holes.step", 2, (5.0, 1.0), &circles, exact);
    check_face("plate_with_holes.step", 5, (0.0, -1.0), &circles, exact);
}

#[test]
fn step_grid_all_writes_every_face_of_the_plate_with_its_hole_blocks() {
    let dir = tempfile::tempdir().unwrap();
    let step = file("plate_with_holes.step");
    let o = ellipgrid(
        dir.path(),
        &[
            "step",
            "grid",
            step.to_str().unwrap(),
            "--all",
            "--ni",
            "9",
            "--nj",
            "9",
            "-o",
            "plate.x",
            "-o",
            "plate.vtm",
        ],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    for b in 0..8 {
        assert!(
            t.contains(&format!("face2.b{b} (plane, 9 × 9 nodes)")),
            "{t}"
        );
        assert!(t.contains(&format!("face5.b{b} (plane")), "{t}");
    }
    // 7 one-block faces and 2 × 8 hole blocks.
    let written = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("plate.x")).unwrap();
    assert_eq!(written.blocks.len(), 23);
    let vtm = std::fs::read_to_string(dir.path().join("plate.vtm")).unwrap();
    assert!(vtm.contains("face2.b7") && vtm.contains("face9"), "{vtm}");
    // `step list` says how the faces with holes are gridded.
    let o = ellipgrid(dir.path(), &["step", "list", step.to_str().unwrap()]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(
        t.contains(
            "face 5: plane, 8 block faces: an O-type ring of 4 blocks around each of 2 holes"
        ),
        "{t}"
    );
}

#[test]
fn step_grid_face_with_a_hole_writes_its_four_blocks() {
    let dir = tempfile::tempdir().unwrap();
    let step = file("box_with_hole_face.step");
    let o = ellipgrid(
        dir.path(),
        &[
            "step",
            "grid",
            step.to_str().unwrap(),
            "--face",
            "1",
            "--ni",
            "17",
            "--nj",
            "9",
            "--first-j",
            "0.01",
            "-o",
            "h.x",
        ],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    let written = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("h.x")).unwrap();
    assert_eq!(written.blocks.len(), 4);
    // --first-j is the first spacing off the hole, along the cuts.
    for b in &written.blocks {
        let ellipgrid::io::Block::Surface(g) = b else {
            panic!("not a surface block")
        };
        assert_eq!((g.ni(), g.nj()), (17, 9));
        let (x0, x1) = (node(g, 0), node(g, g.ni()));
        let d = (x1[0] - x0[0]).hypot(x1[1] - x0[1]);
        assert!((d - 0.01).abs() < 1e-6, "first spacing at the hole {d}");
    }
}
