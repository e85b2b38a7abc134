//! `ellipgrid verify` through the library (issue #20): grid families whose boundary nodes
//! nest bit for bit, a rectangle reproduced exactly at every level, second-order families on
//! shipped cases of every kind (planar, minimal, surface, volume, multi-block with floating
//! interfaces), grids that forget their scrambled, folded start, surface grids that do not
//! depend on the parametrization — and the initial grid x^I of Section 4, which does, caught.

mod common;
use common::root;
use ellipgrid::case::LoadedCase;
use ellipgrid::job::verify::{verify, SurfaceGrid, VerifyOptions, VerifyReport, ORDER_MIN};
use std::fmt::Write;
use std::path::Path;

/// A shipped example with some lines replaced (smaller sizes), parsed at its own path so that
/// its relative input paths still resolve.
fn example(name: &str, replace: &[(&str, &str)]) -> LoadedCase {
    let path = root().join("examples").join(name);
    let mut text = std::fs::read_to_string(&path).unwrap();
    for (a, b) in replace {
        assert!(text.contains(a), "{name} has no '{a}'");
        text = text.replace(a, b);
    }
    LoadedCase::parse(&text, &path).unwrap()
}

fn run(case: &LoadedCase, opts: &VerifyOptions) -> VerifyReport {
    verify(case, opts, None).unwrap()
}

fn levels(n: usize) -> VerifyOptions {
    VerifyOptions {
        levels: n,
        ..VerifyOptions::default()
    }
}

/// The last observed order (rms and max) of the family of block b.
fn family_order(r: &VerifyReport, b: usize) -> (f64, f64) {
    let f = &r.blocks[b].family;
    (
        f.order_rms.last().copied().flatten().unwrap(),
        f.order_max.last().copied().flatten().unwrap(),
    )
}

#[test]
fn refined_cases_nest_their_boundary_nodes_bit_for_bit() {
    // planar curves (an arc, a spline, lines)
    let c = example("curved.toml", &[]);
    let (b0, b2) = (
        c.planar_boundary(0).unwrap(),
        c.refined(2).unwrap().planar_boundary(0).unwrap(),
    );
    assert_eq!(c.refined(2).unwrap().block_dims(0), [257, 193]);
    for e in ellipgrid::grid::Edge::ALL {
        let (coarse, fine) = (b0.edge(e), b2.edge(e));
        assert_eq!(fine.len(), 4 * (coarse.len() - 1) + 1);
        for (k, p) in coarse.iter().enumerate() {
            assert_eq!(*p, fine[4 * k], "edge {e} node {k}");
        }
    }
    // a surface block: (u, v) of the boundary nodes by Vinokur distributions along the net
    let w = example("wing_pylon.toml", &[]);
    let (s, uv0) = w.surface_block(0).unwrap();
    let uv1 = w.refined(1).unwrap().surface_uv(0, s.as_ref()).unwrap();
    for e in 0..4 {
        for (k, p) in uv0[e].iter().enumerate() {
            assert_eq!(*p, uv1[e][2 * k], "edge {e} node {k}");
        }
    }
    // topology edges n → 2n − 1, the vertices on the airfoil kept
    let o = example("naca0012_ogrid.toml", &[]);
    let (n0, n1) = (
        o.topology_nodes().unwrap(),
        o.refined(1).unwrap().topology_nodes().unwrap(),
    );
    for (a, b) in n0.iter().zip(&n1) {
        assert_eq!(b.len(), 2 * a.len() - 1);
        for (k, p) in a.iter().enumerate() {
            assert_eq!(*p, b[2 * k], "node {k}");
        }
    }
    // volumes: every direction
    let v = example("volume_shell_sector.toml", &[]);
    let r = v.refined(1).unwrap().case.volumes[0].clone();
    assert_eq!([r.ni, r.nj, r.nk], [Some(65), Some(49), Some(33)]);
}

#[test]
fn edges_given_by_their_nodes_cannot_be_refined() {
    let text = common::one_block_case(
        5,
        3,
        "curve = { type = \"line\", from = [0, 0], to = [0, 2] }",
        "curve = { type = \"line\", from = [4, 0], to = [4, 2] }",
        "curve = { type = \"line\", from = [0, 0], to = [4, 0] }",
        "curve = { type = \"nodes\", points = [[0, 2], [1, 2], [2, 2], [3, 2], [4, 2]] }",
    );
    let c = LoadedCase::parse(&text, Path::new("n.toml")).unwrap();
    let e = verify(&c, &VerifyOptions::default(), None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("block 'b', edge E4") && e.contains("nodes"),
        "{e}"
    );
    let e = verify(&c, &levels(2), None).unwrap_err().to_string();
    assert!(e.contains("--levels") && e.contains("3 grids"), "{e}");
}

#[test]
fn a_rectangle_with_equal_opposite_distributions_is_reproduced_exactly_at_every_level() {
    // The tensor-product grid is an exact discrete solution (METHOD.md §8) at every level: the
    // differences are rounding, the family passes "at tolerance" with no order to observe.
    let line = |a: [f64; 2], b: [f64; 2], d: &str| {
        format!("curve = {{ type = \"line\", from = {a:?}, to = {b:?} }}\ndistribution = {d}")
    };
    let (g, v) = (
        "{ type = \"geometric\", first = 0.02 }",
        "{ type = \"vinokur\", first = 0.01, last = 0.2 }",
    );
    let text = common::one_block_case(
        17,
        13,
        &line([0.0, 0.0], [0.0, 1.0], v),
        &line([2.0, 0.0], [2.0, 1.0], v),
        &line([0.0, 0.0], [2.0, 0.0], g),
        &line([0.0, 1.0], [2.0, 1.0], g),
    );
    let c = LoadedCase::parse(&text, Path::new("rect.toml")).unwrap();
    let r = run(&c, &VerifyOptions::default());
    let b = &r.blocks[0];
    assert!(b.pass && b.family.at_tolerance, "{b:?}");
    for d in &b.family.differences {
        assert!(d.max < 1e-13, "{d:?}");
    }
}

#[test]
fn a_planar_family_converges_at_second_order_and_forgets_its_folded_start() {
    let c = example(
        "curved.toml",
        &[("ni = 65", "ni = 17"), ("nj = 49", "nj = 13")],
    );
    let r = run(&c, &VerifyOptions::default());
    assert!(r.pass, "{:?}", r.blocks[0].reasons);
    assert_eq!(r.levels[2].dims, vec![[65, 49, 1]]);
    let (p, pmax) = family_order(&r, 0);
    assert!(
        (1.85..2.15).contains(&p) && (1.85..2.15).contains(&pmax),
        "{p} {pmax}"
    );
    let s = r.blocks[0].start.as_ref().unwrap();
    // the start folds through and through, yet Picard ends at the same grid
    assert!(s.start_folded * 2 > s.start_cells, "{s:?}");
    assert!(s.converged && s.difference.unwrap().max <= s.limit, "{s:?}");
    assert_eq!(s.limit, 10.0 * c.case.solver.picard.tolerance);
    // the coarsest grid is what `run` writes
    let g = ellipgrid::job::generate(&c, |_| {}).unwrap();
    let family = r.blocks[0].family.differences[0];
    let d = ellipgrid::job::generate(&c.refined(1).unwrap(), |_| {}).unwrap();
    let (a, b) = match (&g.blocks[0].1, &d.blocks[0].1) {
        (ellipgrid::io::Block::Planar(a), ellipgrid::io::Block::Planar(b)) => (a, b),
        _ => unreachable!(),
    };
    let e = (0..a.nj())
        .flat_map(|j| (0..a.ni()).map(move |i| (i, j)))
        .map(|(i, j)| {
            let (p, q) = (a.point(i, j), b.point(2 * i, 2 * j));
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
        })
        .fold(0.0f64, f64::max);
    assert_eq!(e / a.diameter(), family.max);
}

#[test]
fn a_minimal_surface_converges_at_second_order_in_rms_and_first_at_its_corners() {
    // Scherk's surface spanned by four edges, corners of ~150°: METHOD.md §8 says max-norm
    // differences converge like O(h) near such corners while the rms stays O(h²).
    let r = run(&example("scherk.toml", &[]), &levels(4));
    assert!(r.pass, "{:?}", r.blocks[0].reasons);
    let (p, pmax) = family_order(&r, 0);
    assert!((ORDER_MIN..2.2).contains(&p), "{p}");
    assert!(pmax < 1.5, "{pmax}");
    assert!(r.blocks[0].start.as_ref().unwrap().pass);
}

#[test]
fn a_surface_grid_does_not_depend_on_the_parametrization_but_its_initial_grid_does() {
    let c = example("wing_pylon.toml", &[]);
    let r = run(&c, &VerifyOptions::default());
    let b = &r.blocks[0];
    assert!(b.pass, "{:?}", b.reasons);
    assert!(b.start.is_none());
    let w = b.parametrization.as_ref().unwrap();
    assert_eq!(w.differences.len(), 3);
    for p in w.order_rms.iter().map(|p| p.unwrap()) {
        assert!((ORDER_MIN..2.3).contains(&p), "{w:?}");
    }
    // the warp really changes the parametrization: x^I moves by ~1 % of the diameter
    let opts = VerifyOptions {
        surface_grid: SurfaceGrid::Initial,
        ..VerifyOptions::default()
    };
    let bad = run(&c, &opts);
    let b = &bad.blocks[0];
    assert!(!b.pass && !bad.pass);
    let w = b.parametrization.as_ref().unwrap();
    assert!(w.differences.iter().all(|d| d.rms > 1e-3), "{w:?}");
    assert!(w.order_rms.iter().all(|p| p.unwrap().abs() < 0.2), "{w:?}");
    assert!(
        b.reasons[0].starts_with("parametrization"),
        "{:?}",
        b.reasons
    );
    let e = bad.failure().unwrap();
    assert_eq!(e.exit_code(), 5);
    assert!(e.to_string().contains("block 'wing_pylon'"), "{e}");
    // another seed, another warp, the same verdicts
    let other = VerifyOptions {
        seed: 7,
        ..VerifyOptions::default()
    };
    let r7 = run(&c, &other);
    assert!(r7.pass);
    assert_ne!(
        r7.blocks[0].parametrization.as_ref().unwrap().differences[0],
        r.blocks[0].parametrization.as_ref().unwrap().differences[0]
    );
}

#[test]
fn a_volume_family_converges_at_second_order_with_and_without_a_wall_spacing() {
    let small = [
        ("ni = 33", "ni = 17"),
        ("nj = 25", "nj = 13"),
        ("nk = 17", "nk = 9"),
    ];
    let r = run(&example("volume_shell_sector.toml", &small), &levels(3));
    assert!(r.pass, "{:?}", r.blocks[0].reasons);
    assert!(family_order(&r, 0).0 >= 1.9);
    // with the wall spacing held at F3: the start is forgotten to the tolerance of the
    // intermediate solves of the wall passes
    let tiny = [
        ("ni = 33", "ni = 9"),
        ("nj = 25", "nj = 7"),
        ("nk = 17", "nk = 5"),
        (
            "\nface_grids = \"elliptic\"\n",
            "\nface_grids = \"elliptic\"\nwall = \"F3\"\n",
        ),
    ];
    let r = run(&example("volume_shell_sector.toml", &tiny), &levels(3));
    assert!(r.pass, "{:?}", r.blocks[0].reasons);
    let s = r.blocks[0].start.as_ref().unwrap();
    assert_eq!(s.limit, 10.0 * ellipgrid::elliptic::wall::LOOSE_TOLERANCE);
    assert!(
        s.start_folded > 0 && s.difference.unwrap().max > 1e-12,
        "{s:?}"
    );
}

/// The annulus 1 < r < 2 in four quarter blocks, rays 1 and 3 floating (two half rings).
fn annulus(n: usize, m: usize) -> String {
    let mut t = String::new();
    for q in 0..4 {
        let a = q as f64 * std::f64::consts::FRAC_PI_2;
        for (c, r) in [("i", 1.0), ("o", 2.0)] {
            let (x, y) = (r * a.cos(), r * a.sin());
            writeln!(t, "[[vertex]]\nname = \"{c}{q}\"\nat = [{x:?}, {y:?}]").unwrap();
        }
    }
    for q in 0..4 {
        let ray = if q % 2 == 1 {
            "interface = \"floating\""
        } else {
            "distribution = { type = \"vinokur\", first = 0.02 }"
        };
        writeln!(
            t,
            "[[edge]]\nname = \"ray{q}\"\nfrom = \"i{q}\"\nto = \"o{q}\"\nn = {m}\n{ray}"
        )
        .unwrap();
        for (c, rad) in [("i", 1.0), ("o", 2.0)] {
            writeln!(
                t,
                "[[edge]]\nname = \"{c}arc{q}\"\nfrom = \"{c}{q}\"\nto = \"{c}{}\"\nn = {n}\n\
                 curve = {{ type = \"arc\", center = [0, 0], radius = {rad:?}, start_deg = {}, \
                 end_deg = {} }}",
                (q + 1) % 4,
                90 * q,
                90 * (q + 1)
            )
            .unwrap();
        }
    }
    for q in 0..4 {
        writeln!(
            t,
            "[[block]]\nname = \"q{q}\"\nE1 = \"ray{q}\"\nE2 = \"ray{}\"\nE3 = \"iarc{q}\"\n\
             E4 = \"oarc{q}\"",
            (q + 1) % 4
        )
        .unwrap();
    }
    t
}

#[test]
fn a_multiblock_family_with_floating_interfaces_converges_at_second_order() {
    let c = LoadedCase::parse(&annulus(17, 9), Path::new("annulus.toml")).unwrap();
    let r = run(&c, &VerifyOptions::default());
    assert_eq!(r.blocks.len(), 4);
    for (b, v) in r.blocks.iter().enumerate() {
        assert!(v.pass, "{}: {:?}", v.name, v.reasons);
        assert_eq!(v.dims[2], [65, 33, 1]);
        assert!(family_order(&r, b).0 >= ORDER_MIN);
        // each half ring is gridded as one from its scrambled start
        let s = v.start.as_ref().unwrap();
        assert_eq!(s.group.len(), 2, "{s:?}");
    }
}

#[test]
fn the_verdicts_are_the_same_in_parallel_and_one_level_after_the_other() {
    let c = example(
        "curved.toml",
        &[("ni = 65", "ni = 17"), ("nj = 49", "nj = 13")],
    );
    let a = run(&c, &VerifyOptions::default());
    let b = run(
        &c,
        &VerifyOptions {
            parallel: false,
            ..VerifyOptions::default()
        },
    );
    assert!(!b.parallel);
    assert_eq!(
        serde_json::to_string(&a.blocks).unwrap(),
        serde_json::to_string(&b.blocks).unwrap()
    );
}

#[allow(clippy::needless_range_loop)]
/// Two boxes in a row along x as a volume topology ([[face]] tables): vertices (i, j, k) with
/// i ≤ 2, j, k ≤ 1; x edges stretched alike (so the union is a tensor grid), `n` nodes each way.
fn two_boxes(n: usize) -> String {
    let (xs, ys, zs) = ([0.0, 1.0, 2.5], [0.0, 0.7], [0.0, 1.3]);
    let v = |i: usize, j: usize, k: usize| format!("v{i}{j}{k}");
    let mut t = String::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..3 {
                let (x, y, z) = (xs[i], ys[j], zs[k]);
                writeln!(
                    t,
                    "[[vertex]]\nname = \"{}\"\nat = [{x:?}, {y:?}, {z:?}]",
                    v(i, j, k)
                )
                .unwrap();
            }
        }
    }
    // edge names: a{axis}{i}{j}{k} from vertex (i, j, k) one step along the axis
    let e = |d: usize, c: [usize; 3]| format!("a{d}{}{}{}", c[0], c[1], c[2]);
    for d in 0..3 {
        for k in 0..2 {
            for j in 0..2 {
                for i in 0..3 {
                    let c = [i, j, k];
                    let top = [2, 1, 1];
                    if c[d] == top[d] {
                        continue;
                    }
                    let mut u = c;
                    u[d] += 1;
                    let dist = if d == 0 {
                        "distribution = { type = \"geometric\", first = 0.05 }"
                    } else {
                        ""
                    };
                    writeln!(
                        t,
                        "[[edge]]\nname = \"{}\"\nfrom = \"{}\"\nto = \"{}\"\nn = {n}\n{dist}",
                        e(d, c),
                        v(c[0], c[1], c[2]),
                        v(u[0], u[1], u[2])
                    )
                    .unwrap();
                }
            }
        }
    }
    // faces normal to axis d at corner c, p along the lower other axis, q along the higher
    let f = |d: usize, c: [usize; 3]| format!("f{d}{}{}{}", c[0], c[1], c[2]);
    for d in 0..3 {
        let (a, b) = [(1, 2), (0, 2), (0, 1)][d];
        for k in 0..2 {
            for j in 0..2 {
                for i in 0..3 {
                    let c = [i, j, k];
                    let top = [3, 2, 2];
                    if c[d] >= top[d] || c[a] + 1 >= top[a] || c[b] + 1 >= top[b] {
                        continue;
                    }
                    let (mut ua, mut ub) = (c, c);
                    ua[a] += 1;
                    ub[b] += 1;
                    writeln!(
                        t,
                        "[[face]]\nname = \"{}\"\nE1 = \"{}\"\nE2 = \"{}\"\nE3 = \"{}\"\nE4 = \"{}\"",
                        f(d, c),
                        e(b, c),
                        e(b, ua),
                        e(a, c),
                        e(a, ub)
                    )
                    .unwrap();
                }
            }
        }
    }
    for i in 0..2 {
        let c = [i, 0, 0];
        writeln!(
            t,
            "[[volume]]\nname = \"box{i}\"\nlinear = \"direct\"\nF1 = \"{}\"\nF2 = \"{}\"\n\
             F3 = \"{}\"\nF4 = \"{}\"\nF5 = \"{}\"\nF6 = \"{}\"",
            f(0, c),
            f(0, [i + 1, 0, 0]),
            f(1, c),
            f(1, [i, 1, 0]),
            f(2, c),
            f(2, [i, 0, 1])
        )
        .unwrap();
    }
    t
}

#[test]
fn a_volume_topology_is_refined_through_its_edges_and_reproduced_exactly() {
    let c = LoadedCase::parse(&two_boxes(5), Path::new("boxes.toml")).unwrap();
    let r = run(&c, &VerifyOptions::default());
    assert_eq!(r.blocks.len(), 2);
    for b in &r.blocks {
        assert!(b.pass && b.family.at_tolerance, "{b:?}");
        assert_eq!(b.kind, "volume");
        assert_eq!(b.dims, vec![[5, 5, 5], [9, 9, 9], [17, 17, 17]]);
        assert!(b.family.differences.iter().all(|d| d.max < 1e-12), "{b:?}");
        // from a scrambled start within the faces of its grid
        let s = b.start.as_ref().unwrap();
        assert!(s.start_folded > 0 && s.pass, "{s:?}");
    }
}
