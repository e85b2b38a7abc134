//! Untrimmed patches with creases (issue #14): `data/step/wing_crease.step` (written by
//! `data/step/make_crease.py`) is a swept wing wrapped round its airfoil as one bare
//! B-spline patch (degrees 1 × 3) whose last spanwise knot span is a flat tip cap in the plane
//! y = 3, as OpenVSP writes wings. Its one-block grid folds at the cap; cut along the crease
//! u = 2/3 (and the cap's leading-edge line v = 1/2, one point on the cap) it is four
//! fold-free blocks that meet node for node.

mod common;
use common::{ellipgrid, root, text};
use ellipgrid::cad::{
    creased_blocks, creases, grid_creased, grid_face, grid_face_blocks, read_step_faces,
};
use ellipgrid::cad::{CutKind, Route, StepFace};
use ellipgrid::case::DistributionSpec;
use ellipgrid::grid::Edge;
use ellipgrid::solve::direct::DirectLu;

fn face() -> StepFace {
    let faces = read_step_faces(&root().join("data/step/wing_crease.step")).unwrap();
    assert_eq!(faces.len(), 1);
    assert_eq!(faces[0].route(), Route::Patch);
    faces.into_iter().next().unwrap()
}

#[test]
fn the_crease_and_the_caps_leading_edge_are_found() {
    let c = creases(&face());
    assert_eq!(c.len(), 2, "{c:?}");
    // the skin meets the cap at 82°–90° (the skin's normal is within the airfoil's slopes of
    // the cap plane's normal's perpendicular); the spanwise kink at u = 1/3 is no crease; on
    // the skin the leading-edge line v = 1/2 is smooth (no turn), on the cap one point
    assert!(c[0].dir == 0 && (c[0].at - 2.0 / 3.0).abs() < 1e-15 && c[0].kind == CutKind::Crease);
    assert!(c[0].turn[0] > 75.0 && c[0].turn[1] < 95.0, "{c:?}");
    assert!(
        c[1].dir == 1 && c[1].at == 0.5 && c[1].kind == CutKind::Pole,
        "{c:?}"
    );
}

#[test]
fn unsplit_folds_split_is_fold_free_and_blocks_meet_node_for_node() {
    let f = face();
    let d = DistributionSpec::Uniform {};
    let mut lu = DirectLu::new();
    for n in [17, 33] {
        let one = grid_face(&f, (n, n), &d, &d, &mut lu, "w").unwrap();
        assert!(one.quality.is_folded(), "{n}: the one block should fold");
        let (blocks, skipped) = grid_creased(&f, (n, n), &d, &d, &mut lu, "w").unwrap();
        assert_eq!((blocks.len(), skipped), (4, 0));
        // the memory budget of `step grid` counts the blocks gridded
        assert_eq!(creased_blocks(&f), blocks.len());
        for (k, b) in blocks.iter().enumerate() {
            assert!(!b.quality.is_folded(), "{n}, block {k}: {}", b.quality);
            assert!(b.quality.min_spacing > 0.0, "{n}, block {k}");
        }
        // grid_face_blocks picks the split (its one block folds)
        let picked = grid_face_blocks(&f, (n, n), &d, &d, &mut lu, "w").unwrap();
        assert_eq!(picked.len(), 4);
        // blocks: (skin, lower), (skin, upper), (cap, lower), (cap, upper); the crease
        // u = 2/3 is E2 of the skin blocks and E1 of the cap blocks, the line v = 1/2 E4 of
        // the lower blocks and E3 of the upper ones
        let g = |k: usize| &blocks[k].result.grid;
        for (a, b, ea, eb) in [
            (0, 2, Edge::E2, Edge::E1),
            (1, 3, Edge::E2, Edge::E1),
            (0, 1, Edge::E4, Edge::E3),
            (2, 3, Edge::E4, Edge::E3),
        ] {
            assert_eq!(g(a).edge(ea), g(b).edge(eb), "{n}: blocks {a} and {b}");
        }
        // the crease on the cap plane y = 3, the cap flat, the skin off it
        for p in g(2).edge(Edge::E1).iter().chain(&g(3).edge(Edge::E2)) {
            assert!((p[1] - 3.0).abs() < 1e-12, "{p:?}");
        }
        let y = g(2).coord(1);
        assert!(y.iter().all(|v| (v - 3.0).abs() < 1e-12));
        // the cap's leading-edge side E4 (lower half) is one point: the cusp
        let le = g(2).edge(Edge::E4);
        assert!(le.iter().all(|p| *p == le[0]), "{le:?}");
    }
}

#[test]
fn step_grid_cuts_the_patch_and_writes_four_blocks() {
    let dir = tempfile::tempdir().unwrap();
    let path = root().join("data/step/wing_crease.step");
    let p = path.to_str().unwrap();
    let list = ellipgrid(dir.path(), &["step", "list", p]);
    let t = text(&list);
    assert!(list.status.success(), "{t}");
    assert!(
        t.contains("degrees 1 × 3; creases at u = 0.6667 (normal turning"),
        "{t}"
    );
    assert!(
        t.contains("v = 0.5000 (a cap collapses to a point along it)"),
        "{t}"
    );
    let args = ["step", "grid", p, "--face", "1", "--ni", "17", "--nj", "17"];
    let o = ellipgrid(dir.path(), &[&args[..], &["-o", "w.x"]].concat());
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("face1: cut along u = 0.6667"), "{t}");
    assert!(t.contains("into 4 blocks"), "{t}");
    for b in 0..4 {
        assert!(
            t.contains(&format!("face1.b{b} (B-spline, 17 × 17 nodes)")),
            "{t}"
        );
    }
    assert_eq!(
        t.matches("folded cells                       0").count(),
        4,
        "{t}"
    );
    let written = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("w.x")).unwrap();
    assert_eq!(written.blocks.len(), 4);
}
