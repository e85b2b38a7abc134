use super::*;
use crate::algebraic::control3d::control_for;
use crate::algebraic::transfinite3d::transfinite;
use crate::algebraic::ControlKind;
use crate::elliptic::picard::PicardParams;
use crate::elliptic::poisson3d::{solve, solve_symmetric};
use crate::grid::faces::Faces;
use crate::solve::ilu::BiCgStabIlu;

fn params() -> PicardParams {
    PicardParams {
        max_steps: 400,
        ..PicardParams::default()
    }
}

/// A box [0, 2] × [0, 1] × [0, 0.8] of `n` nodes clustered differently along each axis (the
/// tensor grid: the exact discrete solution).
fn clustered_box(n: [usize; 3]) -> Grid3 {
    let at = |a: usize, f: &dyn Fn(f64) -> f64| -> Vec<f64> {
        (0..n[a]).map(|k| f(k as f64 / (n[a] - 1) as f64)).collect()
    };
    Grid3::rectilinear(
        &at(0, &|t| 2.0 * t.powf(1.5)),
        &at(1, &|t| (t * 2.0).sinh() / 2.0f64.sinh()),
        &at(2, &|t| 0.5 * t * t + 0.3 * t),
    )
}

/// Solves `x` with the symmetry faces `sym` (Bi-CGSTAB) to `p`, asserting convergence.
fn solved(x: &mut Grid3, ctrl: &Control3, sym: &Symmetry, p: &PicardParams) {
    let info = solve_symmetric(
        x,
        ctrl,
        sym,
        &mut BiCgStabIlu::new(),
        p,
        "block",
        &mut |_, _| {},
    )
    .unwrap();
    assert!(info.converged, "{info:?}");
}

/// Asserts that `x` is `exact` to 1e-9 in every coordinate (`what` names the case).
fn assert_same(x: &Grid3, exact: &Grid3, what: &str) {
    for c in 0..3 {
        for (u, v) in x.coord(c).iter().zip(exact.coord(c)) {
            assert!((u - v).abs() < 1e-9, "{what}: {u} vs {v}");
        }
    }
}

/// The largest coordinate difference between `half` and the nodes k ≥ m of `whole`.
fn off_half(half: &Grid3, whole: &Grid3, m: usize) -> f64 {
    let [ni, nj, nk] = half.dims();
    let mut worst = 0.0f64;
    for k in 0..nk {
        for j in 0..nj {
            for i in 0..ni {
                let (p, q) = (half.point(i, j, k), whole.point(i, j, k + m));
                for c in 0..3 {
                    worst = worst.max((p[c] - q[c]).abs());
                }
            }
        }
    }
    worst
}

/// A box clustered in all three directions with a symmetry face at x = 2 (F2): started
/// from the face's nodes moved in their plane and the interior moved too, the iteration
/// returns to the tensor-product grid (the exact discrete solution, also with the
/// algebraic control functions, which the face's nodes take from their inner neighbours).
/// With the face held instead, the moved face stays.
#[test]
fn a_clustered_box_slides_back_to_its_tensor_grid() {
    let exact = clustered_box([13, 11, 9]);
    let faces = Faces::from_grid(&exact);
    let ctrl = control_for(&faces, ControlKind::Algebraic, "box").unwrap();
    let face = SymmetryFace::of_grid(&exact, 2, "box").unwrap();
    assert_eq!(face.normal.map(f64::abs), [1.0, 0.0, 0.0]);
    assert_eq!(face.point[0], 2.0);
    let [ni, nj, nk] = exact.dims();
    let mut x = moved(&exact, &[face]);
    let moved = x.clone();
    let sym = Symmetry::new(vec![face]);
    solved(&mut x, &ctrl, &sym, &params());
    assert_same(&x, &exact, "F2");
    // The face's nodes never left the plane x = 2.
    for k in 0..nk {
        for j in 0..nj {
            assert_eq!(x.point(ni - 1, j, k)[0], 2.0);
        }
    }
    // Held, the moved face is a different grid.
    let mut held = moved;
    solve(
        &mut held,
        &ctrl,
        &mut BiCgStabIlu::new(),
        &params(),
        "box",
        &mut |_, _| {},
    )
    .unwrap();
    let off = (0..nk)
        .flat_map(|k| (0..nj).map(move |j| (j, k)))
        .map(|(j, k)| (held.point(ni - 1, j, k)[1] - exact.point(ni - 1, j, k)[1]).abs())
        .fold(0.0, f64::max);
    assert!(off > 5e-3, "{off}");
}

/// `exact` with its interior nodes and those of the symmetry faces `sym` moved by 0.01 in
/// every direction that keeps them in their planes.
fn moved(exact: &Grid3, sym: &[SymmetryFace]) -> Grid3 {
    let dims = exact.dims();
    let mut x = exact.clone();
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                let ijk = [i, j, k];
                let inner = (0..3)
                    .filter(|&a| ijk[a] > 0 && ijk[a] + 1 < dims[a])
                    .count();
                let on: Vec<&SymmetryFace> = sym
                    .iter()
                    .filter(|f| ijk[f.axis] == if f.high { dims[f.axis] - 1 } else { 0 })
                    .collect();
                if inner + on.len() < 3 || on.len() > 1 {
                    continue;
                }
                let p = exact.point(i, j, k);
                let s = (i * 7 + j * 3 + k * 5) as f64;
                let h = 0.01;
                let mut d = [h * s.sin(), h * s.cos(), h * (0.5 * s).sin()];
                for f in &on {
                    d[f.axis] = 0.0;
                }
                x.set(i, j, k, [p[0] + d[0], p[1] + d[1], p[2] + d[2]]);
            }
        }
    }
    x
}

/// The box of the test above with symmetry faces on every side in turn and on pairs of
/// sides that meet: it returns to its tensor grid from moved nodes.
#[test]
fn every_side_of_a_box_slides() {
    let exact = clustered_box([9, 8, 7]);
    let faces = Faces::from_grid(&exact);
    let ctrl = control_for(&faces, ControlKind::Algebraic, "box").unwrap();
    let sets: Vec<Vec<usize>> = (1..=6)
        .map(|f| vec![f])
        .chain([vec![2, 6], vec![1, 3], vec![4, 5, 2]])
        .collect();
    for set in sets {
        let sym: Vec<SymmetryFace> = set
            .iter()
            .map(|&f| SymmetryFace::of_grid(&exact, f, "box").unwrap())
            .collect();
        let mut x = moved(&exact, &sym);
        solved(&mut x, &ctrl, &Symmetry::new(sym), &params());
        assert_same(&x, &exact, &format!("{set:?}"));
    }
}

/// The curved domain X(s, t, u) = (s + 0.2 sin(πt) u², t + 0.1 s² + 0.1 u², u (1 + 0.3 s t)),
/// u ∈ [−1, 1], is symmetric about z = 0. Its half u ≥ 0 gridded with the plane as a
/// symmetry face is the upper half of the whole domain's grid (Laplace controls, the same
/// discrete system: the mirror images are the whole grid's lower nodes), to the
/// iteration's tolerance, though it starts from the half's own transfinite grid; the whole
/// grid's lines cross the plane at right angles.
#[test]
fn the_half_of_a_symmetric_domain_is_half_of_the_whole_grid() {
    let (ni, nj, m) = (13, 11, 6);
    let at = |i: usize, j: usize, k: usize, kmid: usize| {
        let (s, t) = (i as f64 / (ni - 1) as f64, j as f64 / (nj - 1) as f64);
        let u = (k as f64 - kmid as f64) / m as f64;
        [
            s + 0.2 * (std::f64::consts::PI * t).sin() * u * u,
            t + 0.1 * s * s + 0.1 * u * u,
            u * (1.0 + 0.3 * s * t),
        ]
    };
    let boundary = Grid3::from_fn(ni, nj, 2 * m + 1, |i, j, k| at(i, j, k, m));
    let faces = Faces::from_grid(&boundary);
    let ctrl = control_for(&faces, ControlKind::Laplace, "whole").unwrap();
    let mut whole = transfinite(&faces);
    let tight = PicardParams {
        tolerance: 1e-12,
        ..params()
    };
    let info = solve(
        &mut whole,
        &ctrl,
        &mut BiCgStabIlu::new(),
        &tight,
        "whole",
        &mut |_, _| {},
    )
    .unwrap();
    assert!(info.converged, "{info:?}");

    let hb = Grid3::from_fn(ni, nj, m + 1, |i, j, k| at(i, j, k, 0));
    let hfaces = Faces::from_grid(&hb);
    let hctrl = control_for(&hfaces, ControlKind::Laplace, "half").unwrap();
    let mut half = transfinite(&hfaces);
    let face = SymmetryFace::of_grid(&half, 5, "half").unwrap();
    solved(&mut half, &hctrl, &Symmetry::new(vec![face]), &tight);
    let worst = off_half(&half, &whole, m);
    let mut slid = 0.0f64;
    for j in 0..nj {
        for i in 0..ni {
            let p = half.point(i, j, 0);
            slid = slid.max((p[0] - hb.point(i, j, 0)[0]).abs());
            assert_eq!(p[2], 0.0);
        }
    }
    assert!(worst < 1e-10, "{worst}");
    // The face's nodes did move from where its own boundary put them.
    assert!(slid > 1e-3, "{slid}");
}

/// The same half with the algebraic control functions: the face's own control functions
/// ([`Symmetry::with_controls`]) are those of the whole domain's map continued by
/// symmetry (the half's map mirrored: s, t even, u odd; less the two components that
/// tilt the crossing lines), so the half gridded with them is the upper half of the whole
/// grid solved with the mirrored map's control functions, to the iteration's tolerance.
/// With the inner neighbours' control functions instead, it is not (the face's nodes then
/// take other places).
#[test]
fn the_half_with_algebraic_controls_is_half_of_the_whole_grid() {
    use crate::algebraic::bilinear3d::{bilinear, ParamGrid3};
    use crate::algebraic::flat_edge::edge_functions;
    let (ni, nj, m) = (13, 11, 6);
    let at = |i: usize, j: usize, k: usize| {
        let (s, t) = (i as f64 / (ni - 1) as f64, j as f64 / (nj - 1) as f64);
        let u = (k as f64 / m as f64).powf(1.3);
        [
            s + 0.2 * (std::f64::consts::PI * t).sin() * u * u,
            t + 0.1 * s * s + 0.1 * u * u,
            u * (1.0 + 0.3 * s * t),
        ]
    };
    let hb = Grid3::from_fn(ni, nj, m + 1, at);
    let hfaces = Faces::from_grid(&hb);
    let pg = bilinear(&edge_functions(&hfaces), "half").unwrap();
    let hctrl = Control3::from_algebraic(&pg);
    // The whole: the half and its mirror image; its map the half's continued.
    let nk = 2 * m + 1;
    let half_k = |k: usize| k.abs_diff(m);
    let whole0 = Grid3::from_fn(ni, nj, nk, |i, j, k| {
        let p = hb.point(i, j, half_k(k));
        [p[0], p[1], if k >= m { p[2] } else { -p[2] }]
    });
    let field = |f: &[f64], odd: bool| -> Vec<f64> {
        (0..ni * nj * nk)
            .map(|n| {
                let (i, j, k) = (n % ni, (n / ni) % nj, n / (ni * nj));
                let v = f[i + ni * j + ni * nj * half_k(k)];
                if odd && k < m {
                    -v
                } else {
                    v
                }
            })
            .collect()
    };
    let wpg = ParamGrid3::from_values(
        [ni, nj, nk],
        field(&pg.s, false),
        field(&pg.t, false),
        field(&pg.u, true),
    );
    // ... without, at the plane of symmetry, the components P^s_uu, P^t_uu that tilt the
    // crossing lines (as `at_symmetry_face`).
    let full = Control3::from_algebraic(&wpg);
    let wctrl = Control3::stored(
        [ni, nj, nk],
        (0..ni * nj * nk)
            .map(|n| {
                let mut q = full.at(n);
                if n / (ni * nj) == m {
                    q[15] = 0.0;
                    q[16] = 0.0;
                }
                q
            })
            .collect(),
    );
    let tight = PicardParams {
        tolerance: 1e-12,
        ..params()
    };
    let mut whole = transfinite(&Faces::from_grid(&whole0));
    let info = solve(
        &mut whole,
        &wctrl,
        &mut BiCgStabIlu::new(),
        &tight,
        "whole",
        &mut |_, _| {},
    )
    .unwrap();
    assert!(info.converged, "{info:?}");
    let face = SymmetryFace::of_grid(&hb, 5, "half").unwrap();
    let distance = |own: bool| {
        let sym = Symmetry::new(vec![face]);
        let sym = if own { sym.with_controls(&pg) } else { sym };
        let mut half = transfinite(&hfaces);
        solved(&mut half, &hctrl, &sym, &tight);
        off_half(&half, &whole, m)
    };
    let (own, inner) = (distance(true), distance(false));
    assert!(own < 1e-10, "{own}");
    assert!(inner > 1e-4, "{inner}");
}

/// A face whose nodes are not on one plane, or on a plane that is not a coordinate
/// plane, is refused, naming the face.
#[test]
fn curved_and_oblique_faces_are_refused() {
    let g = Grid3::from_fn(5, 5, 5, |i, j, k| {
        let (x, y) = (i as f64 / 4.0, j as f64 / 4.0);
        [x, y, k as f64 / 4.0 + 0.1 * x * (1.0 - x) * y * (1.0 - y)]
    });
    let e = SymmetryFace::of_grid(&g, 5, "blk").unwrap_err().to_string();
    assert!(
        e.contains("blk") && e.contains("F5") && e.contains("not planar"),
        "{e}"
    );
    assert!(SymmetryFace::of_grid(&g, 1, "blk").is_ok());
    let g = Grid3::from_fn(5, 5, 5, |i, j, k| {
        let (x, y) = (i as f64 / 4.0, j as f64 / 4.0);
        [x, y, k as f64 / 4.0 + 0.1 * x]
    });
    let e = SymmetryFace::of_grid(&g, 6, "blk").unwrap_err().to_string();
    assert!(
        e.contains("F6") && e.contains("not a plane x, y or z"),
        "{e}"
    );
}
