//! A one-loop CAD face pointed at both ends by tips sharper than 45° but not cusps (30°),
//! gridded in the last try as a block whose sides E1 and E2 are both collapsed, one to each
//! tip (issue #14, `src/cad/trim/cusp.rs`, `Corners::Tips`): a thin curved band with a notch
//! in its outer rim (`data/step/make_tips.py`, as the CATIA engine block's 17-edge bands)
//! whose corner sets by turning angle, balanced sets and cut at the notch all fold.

mod common;
use common::{grid_area, grid_node as node, root, step_grid_all, text};
use ellipgrid::cad::{grid_face_blocks, grid_face_by, grid_face_split, read_step_faces, Corners};
use ellipgrid::case::DistributionSpec;
use ellipgrid::grid::Edge;
use ellipgrid::solve::select::by_name;
use ellipgrid::Error;

/// The generator's geometry (make_tips.py): centre, inner radius, width, tips at 90° ± THETA,
/// tip arcs' chords at CHORD to the inner rim, notch half width and depth.
const O: [f64; 2] = [5.0, -14.0];
const R: f64 = 14.0;
const W: f64 = 0.3;
const THETA: f64 = 60.0;
const CHORD: f64 = 18.0;
const NOTCH: [f64; 2] = [0.3, 0.2];

fn at(r: f64, deg: f64) -> [f64; 2] {
    let t = deg.to_radians();
    [O[0] + r * t.cos(), O[1] + r * t.sin()]
}

/// The face's area: its polygon A B K1 N1 N2 N3 N4 K2 (shoelace) plus the circular segments of
/// its convex arcs (tip arcs, outer rim, the notch's bottom) less that of the concave inner rim.
fn exact_area() -> f64 {
    let delta = (W / CHORD.to_radians().tan() / R).to_degrees();
    let w = (NOTCH[0] / (R + W)).to_degrees();
    let (a, b) = (at(R, 90.0 + THETA), at(R, 90.0 - THETA));
    let (k1, k2) = (
        at(R + W, 90.0 - THETA + delta),
        at(R + W, 90.0 + THETA - delta),
    );
    let (n1, n2) = (at(R + W, 90.0 - w), at(R + W - NOTCH[1], 90.0 - w));
    let (n3, n4) = (at(R + W - NOTCH[1], 90.0 + w), at(R + W, 90.0 + w));
    let pts = [a, b, k1, n1, n2, n3, n4, k2];
    let poly: f64 = (0..8)
        .map(|k| {
            let (p, q) = (pts[k], pts[(k + 1) % 8]);
            0.5 * (p[0] * q[1] - q[0] * p[1])
        })
        .sum();
    let d = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let seg = |p: [f64; 2], q: [f64; 2], r: f64| {
        let t = 2.0 * (d(p, q) / (2.0 * r)).asin();
        0.5 * r * r * (t - t.sin())
    };
    // the tip arc through a tangent to the outer rim at k
    let tangent = |a: [f64; 2], k: [f64; 2]| {
        let u = [(k[0] - O[0]) / (R + W), (k[1] - O[1]) / (R + W)];
        let e = [a[0] - k[0], a[1] - k[1]];
        -(e[0] * e[0] + e[1] * e[1]) / (2.0 * (e[0] * u[0] + e[1] * u[1]))
    };
    poly - seg(a, b, R)
        + seg(b, k1, tangent(b, k1))
        + seg(k1, n1, R + W)
        + seg(n2, n3, R + W - NOTCH[1])
        + seg(n4, k2, R + W)
        + seg(k2, a, tangent(a, k2))
}

fn tips() -> ellipgrid::cad::StepFace {
    let path = root().join("data/step/plane_tips.step");
    read_step_faces(&path).unwrap().remove(0)
}

#[test]
fn a_band_whose_corner_sets_and_cuts_fold_grids_fold_free_with_both_tips_collapsed() {
    let face = tips();
    let d = DistributionSpec::Uniform {};
    let uv_folds = |r: &ellipgrid::Result<ellipgrid::cad::FaceGrid>| matches!(r, Err(Error::Folded { place, .. }) if place.ends_with("(u, v) grid"));
    let (tip_a, tip_b) = (at(R, 90.0 + THETA), at(R, 90.0 - THETA));
    let mut errs = Vec::new();
    for n in [17, 33, 65] {
        let mut solver = by_name("multigrid").unwrap();
        // Both tips collapsed (the last try): one block, fold-free, E1 and E2 one point
        // each, at the tips.
        let tips = grid_face_by(&face, (n, n), &d, &d, solver.as_mut(), "t", Corners::Tips);
        let g = tips.unwrap_or_else(|e| panic!("{n}: {e}"));
        assert!(!g.quality.is_folded(), "{n}: {:?}", g.quality.first_folded);
        // Up to 33 × 33 every earlier way folds, and the face's grid is that last try's (at
        // 65 × 65 the cut at the notch is fold-free and is the face's grid).
        if n <= 33 {
            // The old sets (measured at 33 × 33: 542 and 343 folded cells in (u, v)):
            // corners by turning angle (the tips and the notch's convex vertices) and
            // balanced ones fold; no vertex turns by more than 150° (no cusp).
            for c in [Corners::Turning, Corners::Balanced] {
                let r = grid_face_by(&face, (n, n), &d, &d, solver.as_mut(), "t", c);
                assert!(uv_folds(&r), "{n}, {c:?}: {:?}", r.map(|g| g.corner_angles));
            }
            let e = grid_face_by(
                &face,
                (n, n),
                &d,
                &d,
                solver.as_mut(),
                "t",
                Corners::Collapsed,
            )
            .expect_err("no cusp")
            .to_string();
            assert!(e.contains("no cusp"), "{n}: {e}");
            // so does the cut at the notch's reentrant vertices (one of its blocks)
            let cut = grid_face_split(&face, (n, n), &d, &d, solver.as_mut(), "t");
            assert!(
                match &cut {
                    Ok(gs) => gs.iter().any(|g| g.quality.is_folded()),
                    Err(e) => matches!(e, Error::Folded { .. }),
                },
                "{n}: the cut does not fold"
            );
            let gs = grid_face_blocks(&face, (n, n), &d, &d, solver.as_mut(), "t")
                .unwrap_or_else(|e| panic!("{n}: {e}"));
            assert_eq!(gs.len(), 1, "{n}");
            assert_eq!(gs[0].result.grid, g.result.grid, "{n}");
        }
        let deg: Vec<i64> = g.corner_angles.iter().map(|a| a.round() as i64).collect();
        assert_eq!(deg, vec![144; 4], "{n}");
        let grid = &g.result.grid;
        let mut ends = Vec::new();
        for e in [Edge::E1, Edge::E2] {
            let s = grid.edge(e);
            assert!(s.iter().all(|p| *p == s[0]), "{n}: {e} not one point");
            ends.push([s[0][0], s[0][1]]);
        }
        let near = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]) < 1e-9;
        assert!(
            (near(ends[0], tip_a) && near(ends[1], tip_b))
                || (near(ends[0], tip_b) && near(ends[1], tip_a)),
            "{n}: {ends:?}"
        );
        // one (u, v) per collapsed side too
        let (ni, uv) = (grid.ni(), &g.result.uv);
        assert!(
            (0..n).all(|j| uv[ni * j] == uv[0]),
            "{n}: E1 not one (u, v)"
        );
        assert!(
            (0..n).all(|j| uv[ni * j + ni - 1] == uv[ni - 1]),
            "{n}: E2 not one (u, v)"
        );
        // every node on the plane, in the ring between the rims
        for p in 0..ni * grid.nj() {
            let x = node(grid, p);
            let r = (x[0] - O[0]).hypot(x[1] - O[1]);
            assert!(x[2].abs() < 1e-12, "{n}: node {p} off the plane: {x:?}");
            assert!(r > R - 1e-9 && r < R + W + 1e-9, "{n}: node {p} at r = {r}");
        }
        // the quality report counts the triangles apart: the n − 1 cells along each tip
        assert_eq!(g.quality.collapsed_cells, 2 * (n - 1), "{n}");
        assert!(
            g.quality.scaled_jacobian_min_regular > g.quality.scaled_jacobian_min,
            "{n}: {}",
            g.quality
        );
        errs.push((grid_area(grid) - exact_area()).abs());
    }
    // the area converges (the chords of the arcs: second order)
    for w in errs.windows(2) {
        assert!(w[1] < w[0] / 3.0, "{errs:?}");
    }
}

#[test]
fn step_grid_writes_the_band_with_both_tips_collapsed() {
    let dir = tempfile::tempdir().unwrap();
    let path = root().join("data/step/plane_tips.step");
    let o = step_grid_all(dir.path(), path.to_str().unwrap(), ("33", "9"), "t.vts");
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("corners turning 144°, 144°, 144°, 144°"), "{t}");
    assert!(t.contains("sides E1 and E2 collapsed to the tips"), "{t}");
    assert!(t.contains("folded cells                       0"), "{t}");
    // the 2 × 8 triangles along the tips, apart
    assert!(t.contains("collapsed-side cells              16"), "{t}");
    assert!(dir.path().join("t.vts").exists(), "{t}");
    // the old binary's way (the corners by turning angle only, as before this face's last
    // try) is refused: its (u, v) grid folds
    let mut solver = by_name("multigrid").unwrap();
    let d = DistributionSpec::Uniform {};
    let old = grid_face_by(
        &tips(),
        (33, 9),
        &d,
        &d,
        solver.as_mut(),
        "t",
        Corners::Turning,
    );
    assert!(
        matches!(old, Err(Error::Folded { .. })),
        "{:?}",
        old.is_ok()
    );
}
