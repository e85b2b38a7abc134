//! Multi-block grids (`[[vertex]]`, `[[edge]]`, blocks naming edges): exact and convergent
//! known answers, bit-identical interfaces, the connectivity file read back against the
//! written grid, floating interfaces, and topology errors through the command line.

mod common;
use common::*;
use ellipgrid::case::LoadedCase;
use ellipgrid::io::connectivity::{self, ConnFile};
use ellipgrid::io::plot3d::read_plot3d;
use ellipgrid::io::Block;
use ellipgrid::job;
use std::fmt::Write;
use std::fs;
use std::path::Path;

/// TOML of a vertex.
fn vertex(out: &mut String, name: &str, x: f64, y: f64) {
    writeln!(out, "[[vertex]]\nname = \"{name}\"\nat = [{x:?}, {y:?}]").unwrap();
}

/// TOML of an edge with extra lines.
fn edge(out: &mut String, name: &str, from: &str, to: &str, n: usize, extra: &str) {
    writeln!(
        out,
        "[[edge]]\nname = \"{name}\"\nfrom = \"{from}\"\nto = \"{to}\"\nn = {n}\n{extra}"
    )
    .unwrap();
}

/// TOML of a block by its four sides.
fn block(out: &mut String, name: &str, sides: [&str; 4]) {
    let [e1, e2, e3, e4] = sides;
    writeln!(
        out,
        "[[block]]\nname = \"{name}\"\nE1 = {e1}\nE2 = {e2}\nE3 = {e3}\nE4 = {e4}"
    )
    .unwrap();
}

fn generate(text: &str) -> job::Generated {
    let case = LoadedCase::parse(text, Path::new("mb.toml")).unwrap();
    job::generate(&case, |_| {}).unwrap()
}

fn planar(b: &Block) -> &ellipgrid::Grid2<2> {
    match b {
        Block::Planar(g) => g,
        _ => panic!("a planar block"),
    }
}

/// A 3 × 2 rectangle cut at x = 1.2 and y = 0.8 into four blocks, uniform edges.
#[allow(clippy::needless_range_loop)]
fn rectangle_2x2(n: [usize; 2], m: [usize; 2]) -> String {
    let (xs, ys) = ([0.0, 1.2, 3.0], [0.0, 0.8, 2.0]);
    let mut t = String::new();
    for (j, y) in ys.iter().enumerate() {
        for (i, x) in xs.iter().enumerate() {
            vertex(&mut t, &format!("v{i}{j}"), *x, *y);
        }
    }
    for j in 0..3 {
        for i in 0..2 {
            // Edge h{i}{j}: along x from v{i}{j}; some run backwards to test orientation.
            let (a, b) = (format!("v{i}{j}"), format!("v{}{j}", i + 1));
            let (from, to) = if (i + j) % 2 == 0 { (a, b) } else { (b, a) };
            edge(&mut t, &format!("h{i}{j}"), &from, &to, n[i], "");
        }
    }
    for j in 0..2 {
        for i in 0..3 {
            let (a, b) = (format!("v{i}{j}"), format!("v{i}{}", j + 1));
            let (from, to) = if i == 1 { (b, a) } else { (a, b) };
            edge(&mut t, &format!("w{i}{j}"), &from, &to, m[j], "");
        }
    }
    for j in 0..2 {
        for i in 0..2 {
            let s = |p: &str| format!("\"{p}\"");
            block(
                &mut t,
                &format!("b{i}{j}"),
                [
                    &s(&format!("w{i}{j}")),
                    &s(&format!("w{}{j}", i + 1)),
                    &s(&format!("h{i}{j}")),
                    &s(&format!("h{i}{}", j + 1)),
                ],
            );
        }
    }
    t
}

#[test]
fn a_rectangle_in_2x2_blocks_is_the_single_block_tensor_grid() {
    let (n, m) = ([9, 17], [7, 11]);
    let g = generate(&rectangle_2x2(n, m));
    let (xs, ys) = ([0.0, 1.2, 3.0], [0.0, 0.8, 2.0]);
    let mut worst = 0.0f64;
    for (k, (name, b)) in g.blocks.iter().enumerate() {
        let (i0, j0) = (k % 2, k / 2);
        assert_eq!(name, &format!("b{i0}{j0}"));
        let grid = planar(b);
        assert_eq!([grid.ni(), grid.nj()], [n[i0], m[j0]]);
        for j in 0..grid.nj() {
            for i in 0..grid.ni() {
                let x = xs[i0] + (xs[i0 + 1] - xs[i0]) * i as f64 / (n[i0] - 1) as f64;
                let y = ys[j0] + (ys[j0 + 1] - ys[j0]) * j as f64 / (m[j0] - 1) as f64;
                let p = grid.point(i, j);
                worst = worst.max((p[0] - x).abs()).max((p[1] - y).abs());
            }
        }
    }
    assert!(worst < 1e-12, "largest deviation {worst:e}");
    // Every interior edge is an interface with no kink and the spacing ratio of the cells.
    assert_eq!(g.report.interfaces.len(), 4);
    for f in &g.report.interfaces {
        assert!(f.smoothness.kink_max_deg < 1e-9, "{f:?}");
    }
}

/// The annulus 1 < r < 2 in four quarter blocks; rays orthogonal (both sides), uniform edges.
fn annulus(n: usize, m: usize, floating: bool) -> String {
    let mut t = String::new();
    for q in 0..4 {
        let a = q as f64 * std::f64::consts::FRAC_PI_2;
        vertex(&mut t, &format!("i{q}"), a.cos(), a.sin());
        vertex(&mut t, &format!("o{q}"), 2.0 * a.cos(), 2.0 * a.sin());
    }
    for q in 0..4 {
        let r = (q + 1) % 4;
        let ray = if floating && q % 2 == 1 {
            "interface = \"floating\""
        } else {
            "orthogonal = true"
        };
        edge(
            &mut t,
            &format!("ray{q}"),
            &format!("i{q}"),
            &format!("o{q}"),
            m,
            ray,
        );
        for (c, rad) in [("i", 1.0), ("o", 2.0)] {
            let arc = format!(
                "curve = {{ type = \"arc\", center = [0, 0], radius = {rad:?}, start_deg = {}, \
                 end_deg = {} }}",
                90 * q,
                90 * (q + 1)
            );
            edge(
                &mut t,
                &format!("{c}arc{q}"),
                &format!("{c}{q}"),
                &format!("{c}{r}"),
                n,
                &arc,
            );
        }
    }
    for q in 0..4 {
        let s = |p: String| format!("\"{p}\"");
        block(
            &mut t,
            &format!("q{q}"),
            [
                &s(format!("ray{q}")),
                &s(format!("ray{}", (q + 1) % 4)),
                &s(format!("iarc{q}")),
                &s(format!("oarc{q}")),
            ],
        );
    }
    t
}

/// Largest distance of the nodes of an annulus grid from the polar grid.
fn polar_error(g: &job::Generated, n: usize, m: usize) -> f64 {
    let mut worst = 0.0f64;
    for (q, (_, b)) in g.blocks.iter().enumerate() {
        let grid = planar(b);
        for j in 0..m {
            for i in 0..n {
                let th = std::f64::consts::FRAC_PI_2 * (q as f64 + i as f64 / (n - 1) as f64);
                let r = 1.0 + j as f64 / (m - 1) as f64;
                let p = grid.point(i, j);
                worst = worst
                    .max(((p[0] - r * th.cos()).powi(2) + (p[1] - r * th.sin()).powi(2)).sqrt());
            }
        }
    }
    worst
}

#[test]
fn an_annulus_in_four_blocks_converges_to_the_polar_grid_at_second_order() {
    let e: Vec<f64> = [(17, 9), (33, 17), (65, 33)]
        .iter()
        .map(|&(n, m)| polar_error(&generate(&annulus(n, m, false)), n, m))
        .collect();
    // Second order: the ratio per halving tends to 4 from above.
    let ratios = [e[0] / e[1], e[1] / e[2]];
    assert!(
        ratios[0] > 3.5 && (3.5..5.0).contains(&ratios[1]),
        "errors {e:?}"
    );
    assert!(e[2] < 1e-5, "{e:?}");
}

#[test]
fn floating_rays_give_the_polar_grid_too_and_a_smooth_crossing() {
    // Rays 1 and 3 float: the annulus is gridded as two half rings; the floating rays move
    // to where the grid is smooth, which here is the ray itself.
    let kinks: Vec<(f64, f64)> = [(17, 9), (33, 17)]
        .iter()
        .map(|&(n, m)| {
            let g = generate(&annulus(n, m, true));
            assert!(polar_error(&g, n, m) < 0.02);
            let f = g
                .report
                .interfaces
                .iter()
                .find(|f| f.edge == "ray1")
                .unwrap();
            assert!(f.floating);
            (
                f.smoothness.kink_max_deg,
                f.smoothness.spacing_ratio_max - 1.0,
            )
        })
        .collect();
    // The crossing circles turn by one cell's angle at every node, inside a block as across
    // the ray: 90°/(n − 1), halving with h; the spacings match.
    for ((kink, ratio), n) in kinks.iter().zip([17.0, 33.0]) {
        assert!((kink - 90.0 / (n - 1.0)).abs() < 0.01 * kink, "{kinks:?}");
        assert!(*ratio < 1e-6, "{kinks:?}");
    }
}

/// Checks a written grid and its connectivity file: interfaces match node for node, and
/// interfaces and patches cover every block side exactly once (twice for none).
fn check_connectivity(grid: &Path, conn: &Path) -> ConnFile {
    let blocks = read_plot3d(grid).unwrap().blocks;
    let c = connectivity::read(conn).unwrap();
    let node = |(b, lo, hi): &connectivity::Range, k: usize| -> [usize; 2] {
        let step = |a: usize, z: usize| match z.cmp(&a) {
            std::cmp::Ordering::Greater => a + k,
            std::cmp::Ordering::Less => a - k,
            std::cmp::Ordering::Equal => a,
        };
        let _ = b;
        [step(lo[0], hi[0]) - 1, step(lo[1], hi[1]) - 1]
    };
    let len = |(_, lo, hi): &connectivity::Range| 1 + lo[0].abs_diff(hi[0]) + lo[1].abs_diff(hi[1]);
    let point = |b: usize, [i, j]: [usize; 2]| -> [f64; 2] {
        let g = planar(&blocks[b - 1]);
        g.point(i, j)
    };
    let mut covered: Vec<Vec<Vec<u32>>> = blocks
        .iter()
        .map(|b| {
            let [ni, nj, _] = b.dims();
            vec![vec![0; ni.max(nj)]; 4]
        })
        .collect();
    let mut cover = |r: &connectivity::Range| {
        let [ni, nj, _] = blocks[r.0 - 1].dims();
        for k in 0..len(r) {
            let [i, j] = node(r, k);
            let (side, s) = if r.1[0] == r.2[0] && (i == 0 || i == ni - 1) && r.1[1] != r.2[1] {
                (usize::from(i != 0), j)
            } else {
                assert!(j == 0 || j == nj - 1, "range {r:?} is not on a side");
                (2 + usize::from(j != 0), i)
            };
            covered[r.0 - 1][side][s] += 1;
        }
    };
    for [a, b] in &c.interfaces {
        assert_eq!(len(a), len(b));
        for k in 0..len(a) {
            assert_eq!(
                point(a.0, node(a, k)),
                point(b.0, node(b, k)),
                "interface {a:?} / {b:?}, node {k}: not bit-identical"
            );
        }
        cover(a);
        cover(b);
    }
    for (r, fam) in &c.patches {
        assert!(c.families.iter().any(|(id, _)| id == fam));
        cover(r);
    }
    for (b, sides) in covered.iter().enumerate() {
        let [ni, nj, _] = blocks[b].dims();
        for (s, counts) in sides.iter().enumerate() {
            let n = if s < 2 { nj } else { ni };
            // Vertices between two edges of a chain are counted by both; none may be zero.
            assert!(
                counts[..n].iter().all(|&c| c >= 1),
                "block {} side E{} has nodes in no interface or patch: {:?}",
                b + 1,
                s + 1,
                &counts[..n]
            );
        }
    }
    c
}

/// Runs a shipped multi-block example through the CLI: every block converged, fold-free and
/// right-handed; the connectivity file matches the grid node for node and covers every side.
/// Returns the run report and the grid's blocks.
fn paper_example(
    name: &str,
    interfaces: usize,
    patches: usize,
    families: &[&str],
) -> (serde_json::Value, Vec<Block>) {
    let d = tempfile::tempdir().unwrap();
    let case = root().join(format!("examples/{name}.toml"));
    let o = ellipgrid(
        d.path(),
        &["run", case.to_str().unwrap(), "--report", "r.json"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    for b in r["blocks"].as_array().unwrap() {
        assert_eq!(b["quality"]["folded_cells"], 0, "{name}: {}", b["name"]);
        assert_eq!(
            b["quality"]["orientation"], "right-handed",
            "{name}: {}",
            b["name"]
        );
        assert_eq!(b["picard"]["converged"], true, "{name}: {}", b["name"]);
    }
    assert_eq!(
        r["interfaces"].as_array().unwrap().len(),
        interfaces,
        "{name}"
    );
    let c = check_connectivity(
        &d.path().join(format!("{name}.x")),
        &d.path().join(format!("{name}.conn")),
    );
    assert_eq!(c.interfaces.len(), interfaces, "{name}");
    assert_eq!(c.patches.len(), patches, "{name}");
    let names: Vec<&str> = c.families.iter().map(|(_, n)| n.as_str()).collect();
    assert_eq!(names, families, "{name}");
    let blocks = read_plot3d(&d.path().join(format!("{name}.x")))
        .unwrap()
        .blocks;
    (r, blocks)
}

#[test]
fn the_naca0012_o_grid_example_runs_fold_free_with_a_matching_connectivity_file() {
    paper_example("naca0012_ogrid", 4, 8, &["airfoil", "farfield"]);
}

#[test]
fn the_rae2822_c_grid_example_runs_fold_free_with_a_matching_connectivity_file() {
    paper_example("rae2822_cgrid", 4, 8, &["airfoil", "farfield", "outflow"]);
}

#[test]
fn the_nlr7301_flap_example_runs_fold_free_with_a_matching_connectivity_file() {
    // 13 interfaces: the cuts from the cove entry's walls are split at the off-wall
    // junctions p and q (cut_k1 | cut_k, cut_f1 | cut_f; 11 before, from k and f on the walls).
    let (r, blocks) = paper_example(
        "nlr7301_flap",
        13,
        19,
        &["main", "flap", "farfield", "outflow"],
    );
    // No sheared cells: the slot block's long sides have matching node distributions (the
    // main wake split across from the flap's trailing edge). With the main wake as one edge
    // the slot's grid lines crossed at 4 degrees (scaled Jacobian 0.07).
    for b in r["blocks"].as_array().unwrap() {
        let sj = b["quality"]["scaled_jacobian_min"].as_f64().unwrap();
        assert!(sj > 0.5, "{}: smallest scaled Jacobian {sj}", b["name"]);
    }
    // The four wake lines (the sides of the two base-wake strips, blocks 7 and 8) descend to
    // the outflow without sagging below it: with only the outflow point beyond x = 2.5 their
    // splines dipped to y = -0.10 (main) and -0.425 (flap) near x = 9 and came back up.
    for (b, block) in blocks.iter().enumerate().skip(6) {
        let g = planar(block);
        for j in [0, g.nj() - 1] {
            let line: Vec<[f64; 2]> = (0..g.ni())
                .map(|i| g.point(i, j))
                .filter(|p| p[0] > 2.5)
                .collect();
            assert!(line.len() > 10, "block {}: {} nodes", b + 1, line.len());
            for w in line.windows(2) {
                assert!(
                    w[1][0] > w[0][0] && w[1][1] < w[0][1],
                    "block {} j = {j}: the wake line rises or turns back at {:?} -> {:?}",
                    b + 1,
                    w[0],
                    w[1]
                );
            }
        }
    }
    // checkMesh's aspect ratio (OpenFOAM's measure) is under its limit of 1000 everywhere:
    // 1786 on 12 wake cells before, where the sagging splines ran level.
    for (b, block) in blocks.iter().enumerate() {
        let (ar, i, j) = foam_aspect_ratio_max(planar(block));
        assert!(
            ar < 1000.0,
            "block {}: aspect ratio {ar} at cell ({i}, {j})",
            b + 1
        );
    }
}

#[test]
fn the_foam_aspect_ratio_is_the_ratio_of_a_cells_cartesian_extents() {
    // A 1 x 0.001 cell along x: 1000; the same cell turned by 90 degrees: 1000; turned by
    // 45 degrees its extents are equal: 1. A 2 x 1 grid of 0.5 x 0.1 cells: 5.
    let cell = |angle: f64| {
        let (c, s) = (angle.cos(), angle.sin());
        ellipgrid::Grid2::from_fn(2, 2, |i, j| {
            let (x, y) = (i as f64, 1e-3 * j as f64);
            [c * x - s * y, s * x + c * y]
        })
    };
    let r = |g: &ellipgrid::Grid2<2>| foam_aspect_ratio_max(g).0;
    assert!((r(&cell(0.0)) - 1000.0).abs() < 1e-9, "{}", r(&cell(0.0)));
    let quarter = r(&cell(std::f64::consts::FRAC_PI_2));
    assert!((quarter - 1000.0).abs() < 1e-6, "{quarter}");
    let diagonal = r(&cell(std::f64::consts::FRAC_PI_4));
    assert!((diagonal - 1.0).abs() < 1e-9, "{diagonal}");
    let g = ellipgrid::Grid2::from_fn(3, 2, |i, j| [0.5 * i as f64, 0.1 * j as f64]);
    assert_eq!(foam_aspect_ratio_max(&g), (5.0, 0, 0));
}

#[test]
fn the_artificial_boundary_example_runs_fold_free_from_a_folded_start() {
    let (r, _) = paper_example("artificial_boundary", 3, 6, &["wall", "farfield"]);
    // The wall spacing is held along the whole body, valley bottoms included (5.2e-3 there
    // without `wall`), and fades out over 35 % of the lines (`wall_fade`): no cell sheared
    // halfway up the valleys (with the default fade 0.75: skewness 0.96, scaled Jacobian
    // 0.06; here 0.65, 0.52) and a bounded growth off the wall (1.32).
    for b in r["blocks"].as_array().unwrap() {
        let w = &b["wall"][0];
        assert_eq!(w["edge"], "E3", "{b}");
        for k in ["ratio_min", "ratio_max"] {
            let x = w[k].as_f64().unwrap();
            assert!((x - 1.0).abs() < 0.02, "{}: {k} {x}", b["name"]);
        }
        let q = &b["quality"];
        let f = |k: &str| q[k].as_f64().unwrap();
        assert!(f("skewness_max") < 0.7, "{}: {q}", b["name"]);
        assert!(f("scaled_jacobian_min") > 0.5, "{}: {q}", b["name"]);
        assert!(f("growth_j_max") < 1.35, "{}: {q}", b["name"]);
        assert!(
            q["orthogonality"][2]["mean_deg"].as_f64().unwrap() < 1.0,
            "{q}"
        );
    }
    for i in r["interfaces"].as_array().unwrap() {
        assert!(i["kink_max_deg"].as_f64().unwrap() < 4.0, "{i}");
    }
    // The transfinite start folds (the paper's Fig. 19); the elliptic grid above does not.
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/artificial_boundary.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            case.to_str().unwrap(),
            "--write-start",
            "start.x",
            "-q",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let o = ellipgrid(d.path(), &["check", "start.x"]);
    assert!(
        !o.status.success(),
        "the start grid should fold: {}",
        text(&o)
    );
    assert!(text(&o).contains("folded cell"), "{}", text(&o));
}

const CIRCLE: &str =
    "curve = { type = \"arc\", center = [0, 0], radius = 1, start_deg = 0, end_deg = 360 }";

#[test]
fn an_o_grid_cut_and_a_c_grid_wake_are_interfaces_of_one_block() {
    // One O-block about a cylinder: the wall and the far field are closed edges, the cut is
    // E1 and E2. (About the NACA0012 such single blocks do not converge yet: the four-block
    // O-grid above is the way.)
    let mut o = String::new();
    vertex(&mut o, "te", 1.0, 0.0);
    vertex(&mut o, "far", 6.0, 0.0);
    edge(&mut o, "foil", "te", "te", 49, CIRCLE);
    edge(
        &mut o,
        "farfield",
        "far",
        "far",
        49,
        "curve = { type = \"arc\", center = [1, 0], radius = 5, start_deg = 0, end_deg = 360 }",
    );
    edge(
        &mut o,
        "cut",
        "te",
        "far",
        17,
        "distribution = { type = \"geometric\", first = 0.02 }",
    );
    block(
        &mut o,
        "ring",
        ["\"cut\"", "\"cut\"", "\"foil\"", "\"farfield\""],
    );
    // One C-block about a cylinder: the wake is used twice by E3.
    let mut c = String::new();
    vertex(&mut c, "te", 1.0, 0.0);
    vertex(&mut c, "out", 4.0, 0.0);
    vertex(&mut c, "top", 4.0, 3.0);
    vertex(&mut c, "bottom", 4.0, -3.0);
    edge(
        &mut c,
        "wake",
        "te",
        "out",
        13,
        "distribution = { type = \"geometric\", first = 0.02 }",
    );
    edge(&mut c, "foil", "te", "te", 49, CIRCLE);
    edge(
        &mut c,
        "up",
        "out",
        "top",
        17,
        "distribution = { type = \"geometric\", first = 0.02 }",
    );
    edge(
        &mut c,
        "down",
        "out",
        "bottom",
        17,
        "distribution = { type = \"geometric\", first = 0.02 }",
    );
    edge(
        &mut c,
        "outer",
        "top",
        "bottom",
        73,
        "curve = { type = \"polyline\", points = [[4, 3], [-3, 3], [-3, -3], [4, -3]] }",
    );
    block(
        &mut c,
        "c",
        [
            "\"up\"",
            "\"down\"",
            "[\"wake\", \"foil\", \"wake\"]",
            "\"outer\"",
        ],
    );
    for (case, ni, nj, expect) in [
        (
            o,
            49,
            17,
            [(1, [1, 1, 1], [1, 17, 1]), (1, [49, 1, 1], [49, 17, 1])],
        ),
        (
            c,
            73,
            17,
            [(1, [1, 1, 1], [13, 1, 1]), (1, [73, 1, 1], [61, 1, 1])],
        ),
    ] {
        let d = tempfile::tempdir().unwrap();
        fs::write(d.path().join("c.toml"), &case).unwrap();
        let out = ellipgrid(d.path(), &["run", "c.toml", "-o", "g.x", "-o", "g.conn"]);
        assert!(out.status.success(), "{}", text(&out));
        let conn = check_connectivity(&d.path().join("g.x"), &d.path().join("g.conn"));
        assert_eq!(conn.interfaces.len(), 1, "{conn:?}");
        // Side a runs with growing indices; b from the node that matches a's first.
        assert_eq!(conn.interfaces[0], expect, "{ni} × {nj}");
    }
}

#[test]
fn topology_errors_exit_2_naming_the_block_and_the_edge() {
    let base = rectangle_2x2([5, 5], [5, 5]);
    let cases: Vec<(String, &[&str])> = vec![
        // A side with another node count than its opposite side.
        (
            base.replacen("from = \"v00\"\nto = \"v10\"\nn = 5", "from = \"v00\"\nto = \"v10\"\nn = 7", 1),
            &["block 'b00'", "E3", "'h00'", "E4", "'h01'", "7 and 5"],
        ),
        // A loop that does not close: b11's E4 names an edge of another block.
        (
            base.replacen("E4 = \"h11\"", "E4 = \"h10\"", 1),
            &["block 'b10'", "'h10'", "closed loop"],
        ),
        // An edge used by no block.
        (
            format!("{base}[[edge]]\nname = \"spare\"\nfrom = \"v00\"\nto = \"v22\"\nn = 5\n"),
            &["edge 'spare'", "no block"],
        ),
        // A block side on an edge of another block.
        (
            base.replacen("E3 = \"h01\"", "E3 = \"h00\"", 1),
            &["block 'b01'"],
        ),
        // Unknown edge name.
        (
            base.replacen("E2 = \"w11\"", "E2 = \"nope\"", 1),
            &["block 'b01'", "E2", "'nope'"],
        ),
        // A vertex off its edge's curve.
        (
            base.replacen(
                "from = \"v00\"\nto = \"v10\"\nn = 5",
                "from = \"v00\"\nto = \"v10\"\nn = 5\ncurve = { type = \"line\", from = [0, 0.5], to = [1.2, 0] }",
                1,
            ),
            &["edge 'h00'", "vertex 'v00'"],
        ),
        // Edges that cross.
        (
            base.replacen(
                "from = \"v00\"\nto = \"v10\"\nn = 5",
                "from = \"v00\"\nto = \"v10\"\nn = 5\ncurve = { type = \"polyline\", points = [[0, 0], [0.6, 1.5], [1.2, 0]] }",
                1,
            ),
            &["'h00'", "cross"],
        ),
    ];
    for (case, needles) in cases {
        let d = tempfile::tempdir().unwrap();
        fs::write(d.path().join("c.toml"), &case).unwrap();
        let o = ellipgrid(d.path(), &["run", "c.toml", "-o", "g.x", "-o", "g.conn"]);
        let msg = text(&o);
        assert_eq!(o.status.code(), Some(2), "{msg}");
        for n in needles {
            assert!(msg.contains(n), "'{n}' not in: {msg}");
        }
        assert!(!d.path().join("g.x").exists() && !d.path().join("g.conn").exists());
    }
}

/// The 2 × 2 rectangle on the tilted plane z = (x + y) / 2 as surface blocks on a named
/// `[[surface]]` (Section 4 for sides that lie on the surface): each block is the tensor grid
/// of its edges, lifted onto the plane.
#[test]
fn surface_blocks_in_a_topology_lie_on_their_surface_and_reproduce_the_tensor_grid() {
    let (n, m) = ([9, 17], [7, 11]);
    let planar_text = rectangle_2x2(n, m);
    let mut t = String::from(
        "[[surface]]\nname = \"tilt\"\ntype = \"plane\"\norigin = [0, 0, 0]\n\
         du = [3, 0, 1.5]\ndv = [0, 2, 1]\n\n",
    );
    for line in planar_text.lines() {
        if let Some(rest) = line.strip_prefix("at = [") {
            let v: Vec<f64> = rest
                .trim_end_matches(']')
                .split(',')
                .map(|s| s.trim().parse().unwrap())
                .collect();
            writeln!(
                t,
                "at = [{:?}, {:?}, {:?}]",
                v[0],
                v[1],
                0.5 * (v[0] + v[1])
            )
            .unwrap();
        } else if line.starts_with("[[block]]") {
            writeln!(t, "{line}\nkind = \"surface\"\nsurface = \"tilt\"").unwrap();
        } else {
            writeln!(t, "{line}").unwrap();
        }
    }
    let g = generate(&t);
    let (xs, ys) = ([0.0, 1.2, 3.0], [0.0, 0.8, 2.0]);
    let mut worst = 0.0f64;
    for (k, (_, b)) in g.blocks.iter().enumerate() {
        let (i0, j0) = (k % 2, k / 2);
        let Block::Surface(grid) = b else {
            panic!("a surface block")
        };
        for j in 0..grid.nj() {
            for i in 0..grid.ni() {
                let x = xs[i0] + (xs[i0 + 1] - xs[i0]) * i as f64 / (n[i0] - 1) as f64;
                let y = ys[j0] + (ys[j0 + 1] - ys[j0]) * j as f64 / (m[j0] - 1) as f64;
                let p = grid.point(i, j);
                worst = worst
                    .max((p[0] - x).abs())
                    .max((p[1] - y).abs())
                    .max((p[2] - 0.5 * (x + y)).abs());
            }
        }
        assert!(g.report.blocks[k].surface_steps.is_some());
    }
    // exact to rounding (projection, harmonic solve and inversion on a domain of size 3)
    assert!(worst < 1e-11, "largest deviation {worst:e}");
    assert_eq!(g.report.interfaces.len(), 4);
    // Without a surface the block is refused, naming it.
    rejects(
        &t.replacen("surface = \"tilt\"\n", "", 1),
        &["block 'b00'", "needs surface"],
    );
}
