//! Untrimmed patches with boundary defects that fold a one-block grid (issue #14,
//! `src/cad/boundary_cuts.rs`), from `data/step/patch_defects.step` (written by
//! `data/step/make_patch_defects.py`, after OpenVSP's supersonic model):
//! - face 1, a planar quarter ring whose radial sides overshoot their end corners (the patch
//!   folds back over itself beyond u = 2^(-1/3)): gridded as the part before the fold, its
//!   last grid line on the patch's side u = 1;
//! - face 2, a flat wing planform in one bilinear patch whose leading edge is cranked by 25°
//!   at a C0 knot: cut there into two blocks.

mod common;
use common::{ellipgrid, grid_area, root, text};
use ellipgrid::cad::{creases, grid_face, grid_face_blocks, read_step_faces, CutKind, StepFace};
use ellipgrid::case::DistributionSpec;
use ellipgrid::grid::Edge;
use ellipgrid::solve::direct::DirectLu;
use ellipgrid_geometry::Surface;

fn faces() -> Vec<StepFace> {
    let f = read_step_faces(&root().join("data/step/patch_defects.step")).unwrap();
    assert_eq!(f.len(), 2);
    f
}

/// Radius about the ring's axis (the x axis) of a node.
fn radius(p: [f64; 3]) -> f64 {
    p[1].hypot(p[2])
}

/// The area of the ring face: the region between its sides u = 0 and u = 1 (in the plane
/// x = 0, the radial sides on the y and z axes), by the shoelace formula on 20 000 points of
/// each curved side.
fn ring_area(f: &StepFace) -> f64 {
    let s = f.surface.as_ref().unwrap();
    let m = 20_000;
    let mut pts: Vec<[f64; 2]> = (0..=m)
        .map(|k| s.point(0.0, k as f64 / m as f64))
        .map(|p| [p.y, p.z])
        .collect();
    pts.extend((0..=m).rev().map(|k| {
        let p = s.point(1.0, k as f64 / m as f64);
        [p.y, p.z]
    }));
    let n = pts.len();
    let twice: f64 = (0..n)
        .map(|k| {
            let (a, b) = (pts[k], pts[(k + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum();
    0.5 * twice.abs()
}

/// The distance from `p` to the side u = 1 of `s` (the nearest of 4000 samples, then a
/// golden-section search between its neighbours).
fn off_side(s: &dyn Surface, p: [f64; 3]) -> f64 {
    let dist = |v: f64| {
        let q = s.point(1.0, v);
        ((q.x - p[0]).powi(2) + (q.y - p[1]).powi(2) + (q.z - p[2]).powi(2)).sqrt()
    };
    let m: usize = 4000;
    let k = (0..=m)
        .min_by(|a, b| dist(*a as f64 / m as f64).total_cmp(&dist(*b as f64 / m as f64)))
        .unwrap();
    let (mut a, mut b) = (
        k.saturating_sub(1) as f64 / m as f64,
        (k + 1).min(m) as f64 / m as f64,
    );
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if dist(c) < dist(d) {
            b = d;
        } else {
            a = c;
        }
    }
    dist(0.5 * (a + b))
}

#[test]
fn the_fold_back_and_the_kink_are_found() {
    let f = faces();
    let c = creases(&f[0]);
    assert_eq!(c.len(), 1, "{c:?}");
    assert_eq!((c[0].dir, c[0].kind), (0, CutKind::FoldBack { end: 1 }));
    // the quartic r(u) comes back to r(1) at u = 2^(-1/3) (the generator's radii)
    assert!((c[0].at - 0.5f64.cbrt()).abs() < 1e-6, "{c:?}");
    let c = creases(&f[1]);
    assert_eq!(c.len(), 1, "{c:?}");
    assert_eq!(
        (c[0].dir, c[0].at, c[0].kind),
        (1, 2.0 / 3.0, CutKind::Kink)
    );
    assert!(c[0].turn[1] > 24.0 && c[0].turn[1] < 26.0, "{c:?}");
}

#[test]
fn the_ring_is_gridded_before_its_fold_on_its_own_end_side() {
    let f = &faces()[0];
    let d = DistributionSpec::Uniform {};
    let mut lu = DirectLu::new();
    let exact = ring_area(f);
    let mut errors = Vec::new();
    for n in [17, 33, 65] {
        // the one block's radial sides run past the inner corner (r = 3.25) and back
        let one = grid_face(f, (n, n), &d, &d, &mut lu, "ring").unwrap();
        let side = one.result.grid.edge(Edge::E3);
        let inner = side
            .iter()
            .map(|p| radius(*p))
            .fold(f64::INFINITY, f64::min);
        assert!(inner < 3.245, "{n}: {inner}");
        let blocks = grid_face_blocks(f, (n, n), &d, &d, &mut lu, "ring").unwrap();
        assert_eq!(blocks.len(), 1, "{n}");
        let g = &blocks[0];
        assert!(!g.quality.is_folded(), "{n}: {}", g.quality);
        assert_eq!(g.patch_cuts.len(), 1);
        // every node between the outer and the inner side (the cubic quarter circles are
        // 1.0e-3 off their radius at most), none in the flap (down to r = 3.2338)
        for c in 0..n * n {
            let p = [
                g.result.grid.coord(0)[c],
                g.result.grid.coord(1)[c],
                g.result.grid.coord(2)[c],
            ];
            let r = radius(p);
            assert!(
                r > 3.25 - 1.5e-3 && r < 3.6 + 1.5e-3,
                "{n}: node {c} at r = {r}"
            );
        }
        // the last line is the patch's side u = 1, not the iso-line at the fold (which is up
        // to 1.9e-3 off it): each of its nodes is a point of that side
        let s = f.surface.as_ref().unwrap();
        for p in g.result.grid.edge(Edge::E2) {
            let q = off_side(s, p);
            assert!(q < 1e-12, "{n}: {p:?} is {q:.2e} off the side u = 1");
        }
        errors.push((grid_area(&g.result.grid) - exact).abs() / exact);
    }
    // the polygonal cells' area converges at second order to the face's
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        assert!(ratio > 3.5 && ratio < 4.6, "{errors:?}");
    }
}

#[test]
fn the_cranked_wing_folds_as_one_block_and_not_as_two() {
    let f = &faces()[1];
    let d = DistributionSpec::Uniform {};
    let mut lu = DirectLu::new();
    let one = grid_face(f, (33, 33), &d, &d, &mut lu, "wing").unwrap();
    assert!(one.quality.is_folded(), "{}", one.quality);
    for n in [17, 33, 65] {
        let blocks = grid_face_blocks(f, (n, n), &d, &d, &mut lu, "wing").unwrap();
        assert_eq!(blocks.len(), 2, "{n}");
        for b in &blocks {
            assert!(!b.quality.is_folded(), "{n}: {}", b.quality);
        }
        // the two blocks meet node for node along the cut v = 2/3: E4 of the first, E3 of
        // the second, which starts at the crank of the leading edge (1.07025, 0.15, ..)
        let (a, b) = (&blocks[0].result.grid, &blocks[1].result.grid);
        assert_eq!(a.edge(Edge::E4), b.edge(Edge::E3), "{n}");
        let crank = b.edge(Edge::E3)[0];
        assert!((crank[0] - 1.07024817180472).abs() < 1e-12, "{crank:?}");
        assert!((crank[1] - 0.15).abs() < 1e-12, "{crank:?}");
    }
}

#[test]
fn step_grid_cuts_both_patches_and_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let path = root().join("data/step/patch_defects.step");
    let p = path.to_str().unwrap();
    let o = ellipgrid(dir.path(), &["step", "list", p]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(
        t.contains("a cut at u = 0.7937 (the patch folds back over itself"),
        "{t}"
    );
    assert!(
        t.contains("a cut at v = 0.6667 (a side turns by 25° there)"),
        "{t}"
    );
    let args = [
        "step", "grid", p, "--all", "--ni", "33", "--nj", "33", "-o", "d.vtm",
    ];
    let o = ellipgrid(dir.path(), &args);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(
        t.contains("face1: cut along u = 0.7937 (the patch folds back over itself between it and u = 1: left out) into 1 block (1 sub-patch(es) left out)"),
        "{t}"
    );
    assert!(
        t.contains("face2: cut along v = 0.6667 (a side turns by 25° there) into 2 blocks"),
        "{t}"
    );
    assert!(!t.contains("FOLDED"), "{t}");
    assert!(dir.path().join("d.vtm").exists(), "{t}");
}
