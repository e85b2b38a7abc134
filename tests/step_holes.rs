//! CAD faces with holes (issue #14) gridded as several blocks: an O-type ring of four blocks
//! around each hole, the face cut into one-hole strips between holes. Known answers from the
//! OpenCascade-written files in `data/step/` (`data/step/README.md`): every node on the plane,
//! hole boundary nodes on the circles, the face's area summed over its blocks converging at
//! second order to the plate's area minus the holes', cut nodes shared bit for bit, the
//! blocks' normals the face's.

mod common;
use common::{ellipgrid, grid_node as node, root, step_grid_all, text};
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

/// Σ ½ |d₁ × d₂| over the cells (exact for planar quads), and Σ ½ (d₁ × d₂) · n at the cell
/// centres (positive if the grid's normal is `n`'s; `n` need not be a unit vector).
fn area(g: &Grid2<3>, n: &dyn Fn([f64; 3]) -> [f64; 3]) -> (f64, f64) {
    let (ni, nj) = (g.ni(), g.nj());
    let (mut a, mut signed) = (0.0, 0.0);
    for j in 0..nj - 1 {
        for i in 0..ni - 1 {
            let p = |ii: usize, jj: usize| node(g, ii + ni * jj);
            let (x0, x1, x2, x3) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            let d1 = [x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]];
            let d2 = [x3[0] - x1[0], x3[1] - x1[1], x3[2] - x1[2]];
            let c = [
                0.5 * (d1[1] * d2[2] - d1[2] * d2[1]),
                0.5 * (d1[2] * d2[0] - d1[0] * d2[2]),
                0.5 * (d1[0] * d2[1] - d1[1] * d2[0]),
            ];
            let m = [0, 1, 2].map(|k| 0.25 * (x0[k] + x1[k] + x2[k] + x3[k]));
            let nm = n(m);
            let nm = nm.map(|v| v / (nm[0] * nm[0] + nm[1] * nm[1] + nm[2] * nm[2]).sqrt());
            a += (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
            signed += c[0] * nm[0] + c[1] * nm[1] + c[2] * nm[2];
        }
    }
    (a, signed)
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

/// A face with holes: its surface (distance of a point from it), its outward normal, its
/// holes (distance of a point from each hole's curve) and the tolerance on them (1e-11 for
/// analytic edges; B-spline edges are off their analytic curves by the file's fit).
struct Known<'a> {
    surface: &'a dyn Fn([f64; 3]) -> f64,
    normal: &'a dyn Fn([f64; 3]) -> [f64; 3],
    holes: &'a [&'a dyn Fn([f64; 3]) -> f64],
    hole_tol: f64,
    area: f64,
    /// Whether a point is on the surface's seam (nodes there on both sides of the face are
    /// sampled on the seam edge each way: equal to round-off, not bit for bit).
    seam: &'a dyn Fn([f64; 3]) -> bool,
}

/// Checks face `k` of a file at three resolutions: `4 · holes` blocks, fold-free, normals
/// outward; every node on the surface (1e-11; nodes on the holes' CAD edges within the
/// file's gap of it); the first grid line (j = 0) of every block on
/// a hole; cut nodes shared bit for bit (every boundary node that another block also has is
/// the same f64s there); the summed area converging to the exact one at second order.
/// Returns the area errors.
fn check_face(name: &str, k: usize, known: &Known) -> Vec<f64> {
    check_face_at(name, k, known, [9, 17, 33])
}

/// [`check_face`] with `levels` nodes along the cuts (twice as many less one along the holes).
fn check_face_at(name: &str, k: usize, known: &Known, levels: [usize; 3]) -> Vec<f64> {
    let mut errs = Vec::new();
    let nh = known.holes.len();
    for n in levels {
        let gs = blocks(name, k, (2 * n - 1, n));
        assert_eq!(gs.len(), 4 * nh, "{name} face {k}");
        let mut total = 0.0;
        for (b, g) in gs.iter().enumerate() {
            let g = &g.result.grid;
            assert!(unfolded(g), "{name} face {k} block {b} ({n}): folded");
            let (a, signed) = area(g, known.normal);
            assert!(
                signed > 0.999 * a,
                "{name} face {k} block {b}: normal inwards"
            );
            total += a;
            // Nodes on the hole's CAD edges (j = 0) lie where the edges lie: within the
            // file's gap of the surface; all others on the surface.
            let gap = gs[b].gap;
            for p in 0..g.len() {
                let x = node(g, p);
                let d = (known.surface)(x);
                let tol = if p < g.ni() {
                    1e-11_f64.max(2.0 * gap)
                } else {
                    1e-11
                };
                assert!(
                    d < tol,
                    "{name} block {b}: node {p} {x:?} {d:e} off the surface"
                );
            }
            let on_hole = known
                .holes
                .iter()
                .any(|h| (0..g.ni()).all(|i| h(node(g, i)) < known.hole_tol));
            assert!(on_hole, "{name} face {k} block {b}: j = 0 is not on a hole");
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
                        if d < 1e-9 && !(known.seam)(x) {
                            assert_eq!(x.map(f64::to_bits), y.map(f64::to_bits), "{name}");
                            shared += 1;
                        }
                    }
                }
            }
        }
        // Cut nodes are shared by 2 blocks (the cut ends by 3, counted as 3 pairs): at least
        // every cut node once.
        let cuts = 4 * nh * n + (nh - 1) * (2 * n - 1);
        assert!(
            shared >= cuts,
            "{name}: {shared} shared nodes, {cuts} cut nodes"
        );
        errs.push((total - known.area).abs() / known.area);
        eprintln!(
            "{name} face {k}: {n} nodes, area error {:.3e}",
            errs[errs.len() - 1]
        );
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

/// Distance from the circle of radius r about c in the plane z = const.
fn circle(c: [f64; 2], r: f64) -> impl Fn([f64; 3]) -> f64 {
    move |x| ((x[0] - c[0]).hypot(x[1] - c[1]) - r).abs()
}

#[test]
fn a_plane_face_with_one_hole_is_a_ring_of_four_fold_free_blocks() {
    let known = Known {
        surface: &|x| x[2].abs(),
        normal: &|_| [0.0, 0.0, 1.0],
        holes: &[&circle([2.0, 1.5], 0.75)],
        hole_tol: 1e-11,
        area: 12.0 - 0.5625 * PI,
        seam: &|_| false,
    };
    let errs = check_face("box_with_hole_face.step", 1, &known);
    assert!(errs[2] < 1e-3, "{errs:?}");
}

#[test]
fn a_hole_that_cannot_see_a_corner_gets_corners_it_sees() {
    // plane_lshape_hole.step (make_lshape_hole.py): the L-shaped plate's one-loop corners
    // include (10, 7), which the hole at (3, 8.5) does not see past the reentrant vertex
    // (7, 7): the straight cut to it crossed the plate's boundary ("the boundary intersects
    // itself"). The ring's four corners are picked among the outer loop's points the hole
    // sees instead (`cad::visible`): four fold-free blocks covering the plate.
    let name = "plane_lshape_hole.step";
    let in_plate = |x: [f64; 3]| {
        let e = 1e-9;
        let plate = x[0] > -e && x[1] > -e && x[0] < 10.0 + e && x[1] < 10.0 + e;
        let notch = x[0] > 7.0 + e && x[1] > 7.0 + e;
        let hole = (x[0] - 3.0).abs() < 0.5 - e && (x[1] - 8.5).abs() < 0.5 - e;
        plate && !notch && !hole
    };
    let mut errs = Vec::new();
    for n in [9, 17, 33] {
        let gs = blocks(name, 1, (2 * n - 1, n));
        assert_eq!(gs.len(), 4, "{name}");
        let mut total = 0.0;
        for (b, g) in gs.iter().enumerate() {
            let g = &g.result.grid;
            assert!(unfolded(g), "{name} block {b} ({n}): folded");
            for p in 0..g.len() {
                let x = node(g, p);
                assert!(
                    x[2].abs() < 1e-12,
                    "{name} block {b}: node {p} off the plane"
                );
                assert!(
                    in_plate(x),
                    "{name} block {b}: node {p} {x:?} outside the face"
                );
            }
            let (a, signed) = area(g, &|_| [0.0, 0.0, 1.0]);
            assert!(signed > 0.999 * a, "{name} block {b}: normal inwards");
            total += a;
        }
        errs.push((total - 90.0).abs() / 90.0);
    }
    // the plate's corners between nodes: the area converges (cut corners of O(h²) each)
    assert!(errs[2] < 2e-3 && errs[2] < errs[0], "area errors {errs:?}");
    // through the command line: the four blocks written, exit 0
    let dir = tempfile::tempdir().unwrap();
    let step = file(name);
    let o = step_grid_all(dir.path(), step.to_str().unwrap(), ("65", "49"), "l.x");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let written = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("l.x")).unwrap();
    assert_eq!(written.blocks.len(), 4);
}

#[test]
fn an_annulus_between_two_one_edge_circles_is_a_ring() {
    // washer.step: both loops are one closed circle edge; the rays from the hole's centre to
    // the outer loop's corners meet the hole where its polygon closes.
    let known = Known {
        surface: &|x| (x[2] - 1.0).abs(),
        normal: &|_| [0.0, 0.0, 1.0],
        holes: &[&circle([0.0, 0.0], 1.0)],
        hole_tol: 1e-11,
        area: 3.0 * PI,
        seam: &|_| false,
    };
    check_face("washer.step", 1, &known);
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
    // 40 × 30 less the fillet's corner (9 − 9π/4) and two holes of radius 3; face 2 is the
    // top (z = 5, normal +z), face 5 the bottom (z = 0, normal −z).
    for (k, z) in [(2, 5.0), (5, 0.0)] {
        let sign = if z > 0.0 { 1.0 } else { -1.0 };
        let known = Known {
            surface: &move |x: [f64; 3]| (x[2] - z).abs(),
            normal: &move |_| [0.0, 0.0, sign],
            holes: &[&circle([10.0, 15.0], 3.0), &circle([25.0, 15.0], 3.0)],
            hole_tol: 1e-11,
            area: 1200.0 - (9.0 - 2.25 * PI) - 18.0 * PI,
            seam: &|_| false,
        };
        check_face("plate_with_holes.step", k, &known);
    }
}

#[test]
fn a_cylinder_face_with_two_holes_across_its_seam_side_is_gridded_on_the_cylinder() {
    // tube_with_holes.step (make_step_holes.py): the lateral face of a cylinder r = 2,
    // 0 ≤ z ≤ 4, with its seam, drilled through along y by a cylinder r = 0.5 at z = 2.
    let faces = read_step_faces(&file("tube_with_holes.step")).unwrap();
    let k = faces
        .iter()
        .position(|f| f.route() == Route::Holes(2))
        .expect("the lateral face has two holes")
        + 1;
    let drill = |x: [f64; 3]| (x[0].hypot(x[2] - 2.0) - 0.5).abs();
    let known = Known {
        surface: &|x| (x[0].hypot(x[1]) - 2.0).abs(),
        normal: &|x| [x[0], x[1], 0.0],
        holes: &[&drill, &drill],
        // The holes' edges are OpenCascade's B-spline fits of the intersection curves.
        hole_tol: 1e-6,
        // 2π R H less twice ∫ 2R √(r² − R² sin²θ) dθ over |sin θ| ≤ r/R (R = 2, r = 0.5).
        area: 48.6821169260,
        seam: &|x| x[1].abs() < 1e-9 && x[0] > 0.0,
    };
    check_face("tube_with_holes.step", k, &known);
}

#[test]
fn a_closed_cylinder_band_without_a_seam_edge_is_four_blocks_across_it() {
    // cylinder_band_seamless.step (make_band.py): the band r = 1, 0 ≤ z ≤ 2 bounded by its
    // two circles alone, as two loops; its j = 0 lines on one of the circles.
    check_band("cylinder_band_seamless.step");
}

/// The seamless band r = 1, 0 ≤ z ≤ 2 of `name`: four blocks across it, on the cylinder,
/// area 4π at second order.
fn check_band(name: &str) {
    let faces = read_step_faces(&file(name)).unwrap();
    assert_eq!(faces[0].route(), Route::Holes(1));
    let on_circle =
        |x: [f64; 3]| x[2].abs().min((x[2] - 2.0).abs()) + (x[0].hypot(x[1]) - 1.0).abs();
    let known = Known {
        surface: &|x| (x[0].hypot(x[1]) - 1.0).abs(),
        normal: &|x| [x[0], x[1], 0.0],
        holes: &[&on_circle],
        hole_tol: 1e-11,
        area: 4.0 * PI,
        seam: &|_| false,
    };
    check_face(name, 1, &known);
}

#[test]
fn a_closed_nurbs_band_is_periodic_across_the_rows_where_it_closes() {
    // nurbs_band_seamless.step (make_band.py): the same band on the same cylinder as a
    // rational B-spline whose first and last rows of control points are equal (no seam
    // edge, no period in truck): its loops cross that seam, which is found and made periodic.
    check_band("nurbs_band_seamless.step");
    // Through the CLI: four blocks written.
    let dir = tempfile::tempdir().unwrap();
    let step = file("nurbs_band_seamless.step");
    let o = step_grid_all(dir.path(), step.to_str().unwrap(), ("17", "9"), "band.x");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let p = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("band.x")).unwrap();
    assert_eq!(p.blocks.len(), 4);
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
            "-o",
            "plate.conn",
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
    check_connectivity(&written, &dir.path().join("plate.conn"));

    // `step list` says how the faces with holes are gridded.
    let o = ellipgrid(dir.path(), &["step", "list", step.to_str().unwrap()]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(
        t.contains("face 5: plane, 3 boundary loops, gridded as several blocks: an O-type ring"),
        "{t}"
    );
}

/// The nodes of a 1-based side range of a `.conn` file, from its first node to its last.
fn range_nodes(
    blocks: &[ellipgrid::io::Block],
    (b, from, to): ellipgrid::io::connectivity::Range,
) -> Vec<[f64; 3]> {
    let ellipgrid::io::Block::Surface(g) = &blocks[b - 1] else {
        panic!("not a surface block")
    };
    let steps = from[0].abs_diff(to[0]).max(from[1].abs_diff(to[1]));
    let at = |f: usize, t: usize, k: usize| match t.cmp(&f) {
        std::cmp::Ordering::Equal => f,
        std::cmp::Ordering::Greater => f + k,
        std::cmp::Ordering::Less => f - k,
    };
    (0..=steps)
        .map(|k| {
            let (i, j) = (at(from[0], to[0], k), at(from[1], to[1], k));
            node(g, (i - 1) + g.ni() * (j - 1))
        })
        .collect()
}

/// The plate's `.conn` (`step grid --all`): every interface's two sides hold the same nodes,
/// interfaces and patches together cover every block side once, each face's cuts are its
/// interfaces (an O-ring of four per hole, and the two rings meet along one cut: 9 per face
/// with two holes), faces that share a CAD edge with the same nodes on it are joined, and
/// every patch is of its face's family.
fn check_connectivity(written: &ellipgrid::io::plot3d::Plot3dFile, conn: &std::path::Path) {
    let c = ellipgrid::io::connectivity::read(conn).unwrap();
    let blocks = &written.blocks;
    // Block names in the written order: face1, face2.b0 … b7, face3, face4, face5.b0 … b7,
    // face6 … face9.
    let face_of = |b: usize| match b {
        1 => 1,
        2..=9 => 2,
        10 => 3,
        11 => 4,
        12..=19 => 5,
        _ => b - 14,
    };
    let mut covered = std::collections::HashMap::new();
    let mut side_key = |(b, f, t): ellipgrid::io::connectivity::Range| {
        let key = (
            b,
            f[0].min(t[0]),
            f[1].min(t[1]),
            f[0].max(t[0]),
            f[1].max(t[1]),
        );
        *covered.entry(key).or_insert(0) += 1;
    };
    let (mut within, mut across) = ([0; 10], 0);
    for [a, b] in &c.interfaces {
        let (na, nb) = (range_nodes(blocks, *a), range_nodes(blocks, *b));
        assert_eq!(na.len(), nb.len());
        for (p, q) in na.iter().zip(&nb) {
            let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
            assert!(d < 1e-8, "interface {a:?} {b:?}: nodes {d} apart");
        }
        side_key(*a);
        side_key(*b);
        if face_of(a.0) == face_of(b.0) {
            within[face_of(a.0)] += 1;
        } else {
            across += 1;
        }
    }
    for (r, id) in &c.patches {
        side_key(*r);
        let family = &c.families.iter().find(|f| f.0 == *id).unwrap().1;
        assert_eq!(family, &format!("face{}", face_of(r.0)));
    }
    assert_eq!(covered.len(), 4 * blocks.len());
    assert!(covered.values().all(|&n| n == 1), "{covered:?}");
    assert_eq!((within[2], within[5]), (9, 9), "{within:?}");
    assert!(across >= 4, "{across} interfaces between faces");
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

#[test]
fn holes_that_no_u_or_v_cut_separates_are_cut_by_oblique_lines() {
    // plane_holes_overlapping.step: two holes whose u ranges and v ranges both overlap;
    // plane_bolt_circle.step: four holes on a bolt circle at 45°, 135°, 225°, 315° (make_bolt_circle.py).
    let overlapping = Known {
        surface: &|x| x[2].abs(),
        normal: &|_| [0.0, 0.0, 1.0],
        holes: &[&circle([1.2, 1.1], 0.8), &circle([2.6, 1.9], 0.8)],
        hole_tol: 1e-11,
        area: 12.0 - 1.28 * PI,
        seam: &|_| false,
    };
    check_face_at(
        "plane_holes_overlapping.step",
        1,
        &overlapping,
        [17, 33, 65],
    );
    let s = 2.6 * std::f64::consts::FRAC_1_SQRT_2;
    let bolt = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
        .map(|(a, b)| circle([5.0 + a * s, 4.0 + b * s], 0.5));
    let known = Known {
        surface: &|x| x[2].abs(),
        normal: &|_| [0.0, 0.0, 1.0],
        holes: &[&bolt[0], &bolt[1], &bolt[2], &bolt[3]],
        hole_tol: 1e-11,
        area: 80.0 - PI,
        seam: &|_| false,
    };
    let errs = check_face_at("plane_bolt_circle.step", 1, &known, [17, 33, 65]);
    assert!(errs[2] < 1e-3, "{errs:?}");
}

#[test]
fn a_flange_is_cut_by_a_fan_of_cuts_from_its_bore() {
    // plane_flange.step: a bore r = 2 and six holes r = 0.5 on a circle of 3.2 about it; the
    // six rings' j = 0 lie on the six holes, the bore is a side of the sectors.
    let six: Vec<_> = (0..6)
        .map(|k| {
            let a = (60.0 * k as f64).to_radians();
            circle([5.0 + 3.2 * a.cos(), 5.0 + 3.2 * a.sin()], 0.5)
        })
        .collect();
    let known = Known {
        surface: &|x| x[2].abs(),
        normal: &|_| [0.0, 0.0, 1.0],
        holes: &[&six[0], &six[1], &six[2], &six[3], &six[4], &six[5]],
        hole_tol: 1e-11,
        area: 19.5 * PI,
        seam: &|_| false,
    };
    let errs = check_face_at("plane_flange.step", 1, &known, [17, 33, 65]);
    assert!(errs[2] < 1e-3, "{errs:?}");
}

#[test]
fn step_grid_cuts_a_bolt_circle_and_a_flange_into_rings() {
    for (name, blocks) in [("plane_bolt_circle.step", 16), ("plane_flange.step", 24)] {
        let dir = tempfile::tempdir().unwrap();
        let step = file(name);
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
                "17",
                "-o",
                "h.x",
            ],
        );
        assert!(o.status.success(), "{}", text(&o));
        let written = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("h.x")).unwrap();
        assert_eq!(written.blocks.len(), blocks, "{name}");
    }
}

#[test]
fn holes_that_no_straight_cut_separates_are_refused_with_the_reason_and_no_output() {
    // plane_holes_2x2.step: four holes 0.2 apart in a 2 × 2 pattern: no parallel lines
    // separate them, and seen from any one two others overlap (no fan).
    let faces = read_step_faces(&file("plane_holes_2x2.step")).unwrap();
    let d = DistributionSpec::Uniform {};
    let e = grid_face_blocks(&faces[0], (9, 9), &d, &d, &mut DirectLu::new(), "f")
        .expect_err("refused");
    assert!(
        e.to_string()
            .contains("no straight (u, v) cuts separate them"),
        "{e}"
    );
    let dir = tempfile::tempdir().unwrap();
    let step = file("plane_holes_2x2.step");
    let o = ellipgrid(
        dir.path(),
        &[
            "step",
            "grid",
            step.to_str().unwrap(),
            "--face",
            "1",
            "-o",
            "h.x",
        ],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(
        t.contains("face 1: the holes overlap in every direction"),
        "{t}"
    );
    assert!(!dir.path().join("h.x").exists());
}
