//! A one-loop CAD face with many ±90° vertices cut by chords between its reentrant vertices
//! into rectangles (issue #14, `src/cad/chords.rs`): a comb, a spine with three fingers on
//! each side (`data/step/make_comb.py`, as the CATIA engine block's cylinder faces 364–371),
//! whose every corner set of one block and whose bisector cuts fold.

mod common;
use common::{grid_area, grid_node as node, root, step_grid_all, text};
use ellipgrid::cad::{
    grid_face_blocks, grid_face_by, grid_face_chords, grid_face_split, read_step_faces, Corners,
    FaceGrid, CLEARLY_VALID,
};
use ellipgrid::case::DistributionSpec;
use ellipgrid::grid::Edge;
use ellipgrid::solve::select::by_name;

/// The generator's geometry (make_comb.py): finger tips, spine, levels of the fingers, top.
const X: [f64; 4] = [0.0, 30.0, 45.0, 95.0];
const AREA: f64 = 15.0 * 68.0 + 3.0 * 12.0 * (30.0 + 50.0);

fn comb() -> ellipgrid::cad::StepFace {
    let path = root().join("data/step/plane_comb.step");
    read_step_faces(&path).unwrap().remove(0)
}

fn folds(r: &ellipgrid::Result<FaceGrid>) -> bool {
    r.as_ref().map_or(true, |g| g.quality.is_folded())
}

/// The block sides (E1–E4 node lists) shared bit for bit by two blocks, either way round.
fn shared_sides(gs: &[FaceGrid]) -> usize {
    let sides: Vec<Vec<Vec<[f64; 3]>>> = gs
        .iter()
        .map(|g| {
            [Edge::E1, Edge::E2, Edge::E3, Edge::E4]
                .iter()
                .map(|e| g.result.grid.edge(*e).to_vec())
                .collect()
        })
        .collect();
    let mut n = 0;
    for a in 0..gs.len() {
        for b in a + 1..gs.len() {
            for s in &sides[a] {
                for t in &sides[b] {
                    let r: Vec<[f64; 3]> = t.iter().rev().copied().collect();
                    if s == t || *s == r {
                        n += 1;
                    }
                }
            }
        }
    }
    n
}

#[test]
fn a_comb_whose_corner_sets_and_bisector_cuts_fold_is_cut_by_chords_into_rectangles() {
    let face = comb();
    let d = DistributionSpec::Uniform {};
    for n in [17, 33, 65] {
        let mut solver = by_name("multigrid").unwrap();
        let gs = grid_face_chords(&face, (n, n), &d, &d, solver.as_mut(), "c")
            .unwrap_or_else(|e| panic!("{n}: {e}"));
        // 12 chords, 13 rectangles: 7 pieces of the spine and 6 fingers
        assert_eq!(gs.len(), 13, "{n}");
        for (b, g) in gs.iter().enumerate() {
            assert!(!g.quality.is_folded(), "{n}, block {b}: {}", g.quality);
            // each a rectangle: its grid is uniform and orthogonal
            assert!(g.quality.scaled_jacobian_min > 1.0 - 1e-9, "{n}, block {b}");
            let grid = &g.result.grid;
            for p in 0..grid.ni() * grid.nj() {
                let x = node(grid, p);
                assert!(x[2].abs() < 1e-12, "{n}: node {p} off the plane");
                assert!(x[0] > X[0] - 1e-9 && x[0] < X[3] + 1e-9, "{n}: node {p}");
            }
        }
        // every chord one side of two blocks, node for node
        assert_eq!(shared_sides(&gs), 12, "{n}");
        // the blocks cover the face: straight edges, so the area is exact
        let area: f64 = gs.iter().map(|g| grid_area(&g.result.grid)).sum();
        assert!((area - AREA).abs() < 1e-9 * AREA, "{n}: {area}");
        if n >= 33 {
            // Every earlier way folds or is not clearly valid: one block with corners by
            // turning angle (folds), balanced ones (fold at 33²; at 65² the (u, v) grid's 22
            // folded cells are untangled, and the grid, fold-free, has a smallest scaled
            // Jacobian of ~6e-4 or fails its harmonic step on a degenerate cell, depending on
            // the last bits of the (u, v) solve), (no cusp, no tip), and the cut along the
            // bisectors (folds).
            for c in [
                Corners::Turning,
                Corners::Balanced,
                Corners::Collapsed,
                Corners::Tips,
            ] {
                let r = grid_face_by(&face, (n, n), &d, &d, solver.as_mut(), "c", c);
                let clearly_valid = r.as_ref().is_ok_and(|g| {
                    !g.quality.is_folded() && g.quality.scaled_jacobian_min_regular >= CLEARLY_VALID
                });
                assert!(!clearly_valid, "{n}, {c:?} is clearly valid");
                if c == Corners::Turning || n == 33 {
                    assert!(folds(&r), "{n}, {c:?} does not fold");
                }
            }
            let cut = grid_face_split(&face, (n, n), &d, &d, solver.as_mut(), "c");
            assert!(
                cut.as_ref()
                    .map_or(true, |gs| gs.iter().any(|g| g.quality.is_folded())),
                "{n}: the bisector cut does not fold"
            );
            // so the face's grid is the chords' blocks (the better: every block a rectangle)
            let all = grid_face_blocks(&face, (n, n), &d, &d, solver.as_mut(), "c")
                .unwrap_or_else(|e| panic!("{n}: {e}"));
            assert_eq!(all.len(), 13, "{n}");
            for (a, b) in all.iter().zip(&gs) {
                assert_eq!(a.result.grid, b.result.grid, "{n}");
            }
        }
    }
}

#[test]
fn step_grid_writes_the_comb_as_thirteen_blocks() {
    for name in ["plane_comb.step", "cylinder_comb.step"] {
        step_grid_writes_thirteen_blocks(name);
    }
}

fn step_grid_writes_thirteen_blocks(name: &str) {
    let dir = tempfile::tempdir().unwrap();
    let path = root().join("data/step").join(name);
    let o = step_grid_all(dir.path(), path.to_str().unwrap(), ("33", "33"), "c.vtm");
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("face1.b12 "), "{t}");
    assert!(!t.contains("face1.b13"), "{t}");
    assert_eq!(
        t.matches("folded cells                       0").count(),
        13,
        "{t}"
    );
    assert!(!t.contains("FOLDED"), "{t}");
    assert!(dir.path().join("c.vtm").exists(), "{t}");
}

#[test]
fn the_comb_wrapped_on_a_cylinder_is_cut_the_same_way_and_its_area_converges_at_second_order() {
    // cylinder_comb.step: the comb on the cylinder of radius 40 about z (make_comb.py), its
    // scaled (u, v) plane the plane comb's; the exact area is the plane comb's (developable),
    // which the grids' flat cells reach at second order.
    const R: f64 = 40.0;
    let path = root().join("data/step/cylinder_comb.step");
    let face = read_step_faces(&path).unwrap().remove(0);
    let d = DistributionSpec::Uniform {};
    let mut errors = Vec::new();
    for n in [17, 33, 65] {
        let mut solver = by_name("multigrid").unwrap();
        let gs = grid_face_chords(&face, (n, n), &d, &d, solver.as_mut(), "c")
            .unwrap_or_else(|e| panic!("{n}: {e}"));
        assert_eq!(gs.len(), 13, "{n}");
        assert_eq!(shared_sides(&gs), 12, "{n}");
        for (b, g) in gs.iter().enumerate() {
            assert!(!g.quality.is_folded(), "{n}, block {b}: {}", g.quality);
            let grid = &g.result.grid;
            for p in 0..grid.ni() * grid.nj() {
                let x = node(grid, p);
                let r = x[0].hypot(x[1]);
                assert!(
                    (r - R).abs() < 1e-9 * R,
                    "{n}, block {b}: node {p} at r = {r}"
                );
                assert!(x[2] > -1e-9 && x[2] < 68.0 + 1e-9, "{n}: node {p}");
            }
        }
        let area: f64 = gs.iter().map(|g| grid_area(&g.result.grid)).sum();
        assert!(area < AREA, "{n}: flat cells inside the cylinder: {area}");
        errors.push(AREA - area);
    }
    // error ratio ≈ 4 per halving of the spacing (the chord's sag, 1 − sin θ / θ ≈ θ² / 6)
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        assert!(
            (3.6..4.4).contains(&ratio),
            "errors {errors:?}: ratio {ratio}"
        );
    }
}
