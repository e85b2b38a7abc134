//! One-loop CAD faces cut at their reentrant vertices into blocks (issue #14,
//! `src/cad/reentrant.rs`): known layouts on the polygons of `data/step/make_lshape.py` and
//! `make_slot.py`, every node on the plane and inside the face, the face's area, cut nodes
//! shared bit for bit, the blocks' normals the face's; the cut is a fallback only for faces
//! whose one block folds, and `step grid` writes the blocks.

mod common;
use common::{ellipgrid, grid_area, grid_node as node, root, step_grid_all, text};
use ellipgrid::cad::{
    grid_face, grid_face_blocks, grid_face_by, grid_face_split, read_step_faces, Corners::Turning,
    FaceGrid,
};
use ellipgrid::case::DistributionSpec;
use ellipgrid::grid::Grid2;
use ellipgrid::quality;
use ellipgrid::quality::quality3d::AnyQuality;
use ellipgrid::solve::direct::DirectLu;

fn file(name: &str) -> std::path::PathBuf {
    root().join("data/step").join(name)
}

fn unfolded(g: &Grid2<3>) -> bool {
    !AnyQuality::from(quality::quality_surface(g)).is_folded()
}

/// The boundary nodes of a block.
fn boundary(g: &Grid2<3>) -> Vec<[f64; 3]> {
    let (ni, nj) = (g.ni(), g.nj());
    (0..ni * nj)
        .filter(|p| {
            let (i, j) = (p % ni, p / ni);
            i == 0 || j == 0 || i == ni - 1 || j == nj - 1
        })
        .map(|p| node(g, p))
        .collect()
}

/// The four corner nodes of a block, (x, y) rounded to 1e-6.
fn corners(g: &Grid2<3>) -> Vec<[i64; 2]> {
    let (ni, nj) = (g.ni(), g.nj());
    [0, ni - 1, ni * nj - 1, ni * (nj - 1)]
        .iter()
        .map(|&p| {
            let x = node(g, p);
            [(x[0] * 1e6).round() as i64, (x[1] * 1e6).round() as i64]
        })
        .collect()
}

/// Σ (d₁ × d₂)_z / 2 over the cells: the signed area seen from +z.
fn signed_area(g: &Grid2<3>) -> f64 {
    let (ni, nj) = (g.ni(), g.nj());
    let mut a = 0.0;
    for j in 0..nj - 1 {
        for i in 0..ni - 1 {
            let p = |ii: usize, jj: usize| node(g, ii + ni * jj);
            let (x0, x1, x2, x3) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            let d1 = [x2[0] - x0[0], x2[1] - x0[1]];
            let d2 = [x3[0] - x1[0], x3[1] - x1[1]];
            a += 0.5 * (d1[0] * d2[1] - d1[1] * d2[0]);
        }
    }
    a
}

/// Checks a face cut into blocks: fold-free, every node on z = 0 and `inside`, the blocks'
/// normals +z (the face's), the area within `tol` of `area`, every boundary node that
/// another block also has is that node bit for bit, and at least `cut_nodes` are shared.
fn check(
    gs: &[FaceGrid],
    inside: impl Fn(f64, f64) -> bool,
    area: f64,
    tol: f64,
    cut_nodes: usize,
) {
    let mut total = 0.0;
    for (b, g) in gs.iter().enumerate() {
        let g = &g.result.grid;
        assert!(unfolded(g), "block {b}: folded");
        for p in 0..g.len() {
            let [x, y, z] = node(g, p);
            assert!(z.abs() < 1e-11, "block {b}: node {p} {z:e} off the plane");
            assert!(
                inside(x, y),
                "block {b}: node {p} ({x}, {y}) outside the face"
            );
        }
        let (a, s) = (grid_area(g), signed_area(g));
        assert!(
            (s - a).abs() < 1e-9 * a,
            "block {b}: normal not +z ({s}, {a})"
        );
        total += a;
    }
    assert!((total - area).abs() <= tol, "area {total}, exact {area}");
    let mut shared = 0;
    for (a, ga) in gs.iter().enumerate() {
        for gb in gs.iter().skip(a + 1) {
            for x in boundary(&ga.result.grid) {
                for y in boundary(&gb.result.grid) {
                    let d = (0..3).map(|c| (x[c] - y[c]).abs()).fold(0.0, f64::max);
                    if d < 1e-9 {
                        assert_eq!(x.map(f64::to_bits), y.map(f64::to_bits));
                        shared += 1;
                    }
                }
            }
        }
    }
    assert!(
        shared >= cut_nodes,
        "{shared} shared nodes, {cut_nodes} cut nodes"
    );
}

#[test]
fn an_l_shaped_face_is_cut_at_its_reentrant_vertex_into_two_fold_free_blocks() {
    // plane_lshape.step: the reentrant vertex (43, 80) turns 90°; the bisector of its 270°
    // interior angle runs at 45° up and right and meets the top side at (68, 105). The cut
    // splits the L into the quadrilateral (68,105) (0,105) (0,80) (43,80) and the pentagon
    // (43,80) (43,0) (225,0) (225,105) (68,105), both with 135° at (43, 80).
    let faces = read_step_faces(&file("plane_lshape.step")).unwrap();
    let d = DistributionSpec::Uniform {};
    let inside = |x: f64, y: f64| {
        let eps = 1e-9;
        (-eps..=225.0 + eps).contains(&x)
            && (-eps..=105.0 + eps).contains(&y)
            && !(x < 43.0 - eps && y < 80.0 - eps)
    };
    for n in [17, 33, 65] {
        let gs = grid_face_split(&faces[0], (n, n), &d, &d, &mut DirectLu::new(), "l")
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(gs.len(), 2, "{n}");
        let c: Vec<Vec<[i64; 2]>> = gs.iter().map(|g| corners(&g.result.grid)).collect();
        for (x, y) in [(43, 80), (68, 105)] {
            let p = [x * 1_000_000, y * 1_000_000];
            assert!(
                c.iter().all(|b| b.contains(&p)),
                "{n}: corner {p:?} in {c:?}"
            );
        }
        // Every node of the straight boundary is on it, and all the L's vertices but
        // (43, 0), inside a side of the pentagon's block, are nodes: the summed quad areas
        // miss at most a triangle h² / 8 there (h ≤ 262 / (n − 1)).
        let h = 262.0 / (n - 1) as f64;
        check(&gs, inside, 20185.0, h * h / 8.0, n);
    }
}

#[test]
fn a_one_block_grid_with_a_zero_area_cell_is_cut_like_one_that_folds() {
    // At 257 × 129 the L's one block meets a cell of zero area in its harmonic step (the
    // untangled (u, v) grid next to the reentrant vertex): reported as a fold
    // (`Error::Folded`), so `grid_face_blocks` cuts the face at its reentrant vertex, as it
    // does where the one block folds. Through the command line as well: exit 0.
    let faces = read_step_faces(&file("plane_lshape.step")).unwrap();
    let d = DistributionSpec::Uniform {};
    let one = grid_face(&faces[0], (257, 129), &d, &d, &mut DirectLu::new(), "l");
    match &one {
        Err(ellipgrid::Error::Folded { first, .. }) => {
            assert!(first.contains("zero area"), "{first}")
        }
        other => panic!(
            "the one block at 257 × 129: {:?}",
            other.as_ref().map(|_| ())
        ),
    }
    let gs = grid_face_blocks(&faces[0], (257, 129), &d, &d, &mut DirectLu::new(), "l")
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(gs.len(), 2);
    assert!(gs.iter().all(|g| !g.quality.is_folded()));
    let dir = tempfile::tempdir().unwrap();
    let step = file("plane_lshape.step");
    let o = step_grid_all(dir.path(), step.to_str().unwrap(), ("257", "129"), "l.x");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
}

#[test]
fn the_cut_blocks_of_the_l_are_less_skewed_than_its_untangled_block() {
    // As one block the L is fold-free only after untangling (its cells next to the reentrant
    // vertex skewed); it is not cut by `grid_face_blocks` (a fold-free face is never cut),
    // but its cut blocks have right angles where the untangled block does not.
    let faces = read_step_faces(&file("plane_lshape.step")).unwrap();
    let d = DistributionSpec::Uniform {};
    let one = grid_face(&faces[0], (33, 33), &d, &d, &mut DirectLu::new(), "l").unwrap();
    let blocks = grid_face_blocks(&faces[0], (33, 33), &d, &d, &mut DirectLu::new(), "l").unwrap();
    assert_eq!(blocks.len(), 1);
    assert_eq!(
        blocks[0].result.grid.coord(0),
        one.result.grid.coord(0),
        "a fold-free face changed"
    );
    let cut = grid_face_split(&faces[0], (33, 33), &d, &d, &mut DirectLu::new(), "l").unwrap();
    let worst = |gs: &[&FaceGrid]| {
        gs.iter()
            .map(|g| g.quality.scaled_jacobian_min)
            .fold(f64::INFINITY, f64::min)
    };
    let (a, b) = (worst(&[&one]), worst(&cut.iter().collect::<Vec<_>>()));
    eprintln!("smallest scaled Jacobian: one block {a:.3}, cut {b:.3}");
    assert!(b > a + 0.1, "one block {a}, cut {b}");
}

#[test]
fn a_slotted_plate_whose_one_block_folds_is_gridded_as_three_blocks() {
    // plane_slot.step: as one block the (u, v) grid folds next to the slot (not untangled);
    // `grid_face_blocks` cuts it at the slot's two reentrant vertices (45, 10) and (55, 10),
    // down to the bottom side at (35, 0) and (65, 0): three blocks.
    let faces = read_step_faces(&file("plane_slot.step")).unwrap();
    let d = DistributionSpec::Uniform {};
    let inside = |x: f64, y: f64| {
        let eps = 1e-9;
        (-eps..=100.0 + eps).contains(&x)
            && (-eps..=60.0 + eps).contains(&y)
            && !(x > 45.0 + eps && x < 55.0 - eps && y > 10.0 + eps)
    };
    for n in [17, 33] {
        // One block on corners by turning angle folds (grid_face_blocks then cuts first; a
        // block on balanced corners, which grid_face also tries, is its last resort).
        let one = grid_face_by(
            &faces[0],
            (n, n),
            &d,
            &d,
            &mut DirectLu::new(),
            "s",
            Turning,
        );
        let folds = match &one {
            Ok(g) => g.quality.is_folded(),
            Err(e) => matches!(e, ellipgrid::Error::Folded { .. }),
        };
        assert!(folds, "{n}: one block does not fold");
        let gs = grid_face_blocks(&faces[0], (n, n), &d, &d, &mut DirectLu::new(), "s")
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(gs.len(), 3, "{n}");
        let c: Vec<Vec<[i64; 2]>> = gs.iter().map(|g| corners(&g.result.grid)).collect();
        for (x, y) in [(45, 10), (55, 10), (35, 0), (65, 0)] {
            let p = [x * 1_000_000, y * 1_000_000];
            assert!(
                c.iter().any(|b| b.contains(&p)),
                "{n}: no corner {p:?} in {c:?}"
            );
        }
        // Vertices inside a side (the slot's top corners, the plate's) cut at most a
        // triangle of h² / 8 each off the polygon.
        let h = 170.0 / (n - 1) as f64;
        check(&gs, inside, 5500.0, 6.0 * h * h / 8.0, 2 * n);
    }
}

#[test]
fn a_face_without_a_reentrant_vertex_is_not_cut() {
    let faces = read_step_faces(&file("plane_pentagon.step")).unwrap();
    let d = DistributionSpec::Uniform {};
    let e = grid_face_split(&faces[0], (9, 9), &d, &d, &mut DirectLu::new(), "p").unwrap_err();
    assert!(
        e.to_string()
            .contains("p: the loop has no reentrant vertex"),
        "{e}"
    );
}

#[test]
fn step_grid_writes_the_cut_blocks_with_exit_0() {
    let dir = tempfile::tempdir().unwrap();
    // A face whose one block folds: cut by default.
    let slot = file("plane_slot.step");
    let o = step_grid_all(dir.path(), slot.to_str().unwrap(), ("17", "17"), "s.x");
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("face1.b2 (plane, 17 × 17 nodes)"), "{t}");
    let written = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("s.x")).unwrap();
    assert_eq!(written.blocks.len(), 3);
    // The L (fold-free as one block) with --cut-reentrant.
    let l = file("plane_lshape.step");
    let o = ellipgrid(
        dir.path(),
        &[
            "step",
            "grid",
            l.to_str().unwrap(),
            "--face",
            "1",
            "--ni",
            "33",
            "--nj",
            "33",
            "--cut-reentrant",
            "-o",
            "l.x",
        ],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("face1.b1 (plane, 33 × 33 nodes)"), "{t}");
    let written = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("l.x")).unwrap();
    assert_eq!(written.blocks.len(), 2);
    for b in &written.blocks {
        let ellipgrid::io::Block::Surface(g) = b else {
            panic!("not a surface block")
        };
        assert!(unfolded(g));
    }
}
