//! Periodic (floating) cuts (#15): a block whose cut E1 = E2 is one floating edge, and a ring
//! of blocks joined by floating edges, are gridded as one block periodic in ξ — the cut's
//! nodes are unknowns and the stencils wrap around the seam (`src/elliptic/periodic.rs`).
//! Known answers on an annulus (every ξ-line a ray at uniform angles, the seam no different),
//! independence of the cut's given nodes, the NACA0012 O-grid as one block and as a ring of
//! four (orthogonal at the airfoil, with and without a held wall spacing), the shipped example
//! through the command line, a minimal ring (the catenoid at second order), and bad input.

mod common;
use common::*;
use ellipgrid::algebraic::periodic::periodic_start;
use ellipgrid::algebraic::transform::transfinite;
use ellipgrid::algebraic::ControlKind;
use ellipgrid::case::LoadedCase;
use ellipgrid::elliptic::periodic;
use ellipgrid::elliptic::picard::PicardParams;
use ellipgrid::io::Block;
use ellipgrid::job;
use ellipgrid::Grid2;
use std::f64::consts::TAU;
use std::path::Path;

/// Rays and uniform angles are asserted to this (radians, and relative to the radius).
const RAY_TOL: f64 = 1e-10;

fn generate(text: &str) -> job::Generated {
    let case = LoadedCase::parse(text, Path::new("periodic.toml")).unwrap();
    job::generate(&case, |_| {}).unwrap()
}

fn planar(b: &Block) -> &Grid2<2> {
    match b {
        Block::Planar(g) => g,
        _ => panic!("a planar block"),
    }
}

/// An annulus 1 < r < 5 as one block: E3 the inner circle, E4 the outer one (both closed,
/// uniform, `n` nodes), E1 = E2 the cut along y = 0 (`m` nodes, `cut` its extra lines).
fn annulus(n: usize, m: usize, cut: &str) -> String {
    format!(
        r#"
[[vertex]]
name = "in"
at = [1, 0]
[[vertex]]
name = "out"
at = [5, 0]
[[edge]]
name = "inner"
from = "in"
to = "in"
n = {n}
curve = {{ type = "arc", center = [0, 0], radius = 1, start_deg = 0, end_deg = 360 }}
[[edge]]
name = "outer"
from = "out"
to = "out"
n = {n}
curve = {{ type = "arc", center = [0, 0], radius = 5, start_deg = 0, end_deg = 360 }}
[[edge]]
name = "cut"
from = "in"
to = "out"
n = {m}
{cut}
[[block]]
name = "ring"
E1 = "cut"
E2 = "cut"
E3 = "inner"
E4 = "outer"
"#
    )
}

/// Every ξ-line of `g` is a ray at angle 2π i / (ni − 1), every η-line a circle.
fn assert_polar(g: &Grid2<2>) {
    let (ni, nj) = (g.ni(), g.nj());
    for j in 0..nj {
        let r0 = g.point(0, j)[0].hypot(g.point(0, j)[1]);
        for i in 0..ni {
            let [x, y] = g.point(i, j);
            let want = TAU * (i % (ni - 1)) as f64 / (ni - 1) as f64;
            let d = (y.atan2(x) - want).rem_euclid(TAU);
            let d = d.min(TAU - d);
            assert!(d < RAY_TOL, "node ({i}, {j}) is {d:e} rad off its ray");
            let r = x.hypot(y);
            assert!(
                (r - r0).abs() < RAY_TOL * r0,
                "row {j}: r {r} at i = {i}, {r0} at the seam"
            );
        }
    }
}

#[test]
fn an_annulus_with_a_floating_cut_has_straight_rays_at_uniform_angles() {
    let r = generate(&annulus(33, 13, "interface = \"floating\""));
    let g = planar(&r.blocks[0].1);
    assert_eq!((g.ni(), g.nj()), (33, 13));
    let picard = r.report.blocks[0].picard.as_ref().unwrap();
    assert!(picard.converged, "{picard:?}");
    assert_polar(g);
    // The seam's two copies are bit-identical, and the rows are circles whose radii grow
    // (the discrete log-spacing of a Laplace grid between the η boundaries).
    for j in 0..g.nj() {
        assert_eq!(g.point(0, j), g.point(g.ni() - 1, j));
    }
    let radii: Vec<f64> = (0..g.nj())
        .map(|j| g.point(5, j)[0].hypot(g.point(5, j)[1]))
        .collect();
    let steps: Vec<f64> = radii.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(steps.windows(2).all(|w| w[1] > w[0]), "{radii:?}");
    // The connectivity lists the seam as a 1-to-1 interface of the block with itself.
    let conn = r.connectivity.unwrap();
    assert_eq!(conn.interfaces.len(), 1);
}

#[test]
fn the_cut_s_distribution_acts_through_the_control_functions_only() {
    // A clustered cut: its nodes are unknowns, its distribution sets t along every ξ-line
    // (P22 = −t_ηη / t_η), the same on every ray, so the grid is still polar with the seam
    // like any other ray, and clustered at the inner circle.
    let clustered_cut =
        "interface = \"floating\"\ndistribution = { type = \"geometric\", first = 0.01 }";
    let uniform = generate(&annulus(33, 13, "interface = \"floating\""));
    let clustered = generate(&annulus(33, 13, clustered_cut));
    let (a, b) = (planar(&uniform.blocks[0].1), planar(&clustered.blocks[0].1));
    assert_polar(b);
    let first = |g: &Grid2<2>| g.point(9, 1)[0].hypot(g.point(9, 1)[1]) - 1.0;
    assert!(first(b) < 0.5 * first(a), "{} vs {}", first(b), first(a));
    // The same grid from two different starts: the fixed-cut transfinite grid (the cut's
    // given nodes in column 0) and the periodic start (straight rays).
    let case = LoadedCase::parse(&annulus(33, 13, clustered_cut), Path::new("p.toml")).unwrap();
    let topo = case.topology.as_ref().unwrap();
    let g = &topo.groups("p").unwrap()[0];
    assert!(g.periodic);
    let bnd = case
        .planar_from(case.group_points(g).unwrap(), "p")
        .unwrap();
    // both to 1e-13, against the run's default 1e-10 (of the diameter 10)
    let p = PicardParams {
        tolerance: 1e-13,
        ..PicardParams::default()
    };
    let alg = ControlKind::Algebraic;
    let none = [false; 4];
    let from_tf = periodic::grid_block(&bnd, Some(transfinite(&bnd)), none, alg, &p, "p").unwrap();
    let from_ps =
        periodic::grid_block(&bnd, Some(periodic_start(&bnd)), none, alg, &p, "p").unwrap();
    for c in 0..2 {
        let (u, v, w) = (from_tf.grid.coord(c), from_ps.grid.coord(c), b.coord(c));
        for k in 0..u.len() {
            assert!((u[k] - v[k]).abs() < RAY_TOL, "{} vs {}", u[k], v[k]);
            assert!((v[k] - w[k]).abs() < 1e-8, "{} vs {}", v[k], w[k]);
        }
    }
}

#[test]
fn a_fixed_cut_keeps_its_nodes() {
    // Without `interface = "floating"` the cut is Dirichlet data, as before.
    let r = generate(&annulus(
        33,
        13,
        "distribution = { type = \"geometric\", first = 0.01 }",
    ));
    let g = planar(&r.blocks[0].1);
    let first = g.point(0, 1)[0] - g.point(0, 0)[0];
    assert!((first - 0.01).abs() < 1e-9, "{first}");
}

/// The shipped one-block NACA0012 O-grid.
fn oneblock_text() -> String {
    std::fs::read_to_string(root().join("examples/naca0012_oneblock.toml")).unwrap()
}

/// The one-block example's vertices and edges with 62 cells on every far-field quarter and
/// 58 on the aft airfoil edges (+ 4 on the base halves): every quarter of the ring below has
/// 62 cells along i.
fn ring_edges() -> String {
    let one = oneblock_text();
    let mut t = one[..one.find("[[block]]").unwrap()].to_string();
    t = t.replace(
        "n = 65\ncurve = { type = \"arc\"",
        "n = 63\ncurve = { type = \"arc\"",
    );
    for to in ["to = \"te_up\"\nn = 63", "to = \"te_lo\"\nn = 63"] {
        assert!(t.contains(to), "{to}");
        t = t.replace(to, &to.replace("63", "59"));
    }
    t
}

/// The same airfoil and far field as a ring of four blocks (the four domains of
/// `examples/naca0012_ogrid.toml`) whose four cuts all float.
fn ring_text() -> String {
    let mut t = ring_edges();
    for (cut, from, far) in [
        ("cut_le", "le", "far_le"),
        ("cut_up", "up", "far_up"),
        ("cut_lo", "lo", "far_lo"),
    ] {
        t.push_str(&format!(
            "[[edge]]\nname = \"{cut}\"\nfrom = \"{from}\"\nto = \"{far}\"\nn = 49\n\
             distribution = {{ type = \"vinokur\", first = 0.003, last = 1.5 }}\n\
             interface = \"floating\"\n"
        ));
    }
    for (name, e1, e2, e3, e4) in [
        ("upper_fore", "cut_le", "cut_up", "\"upper_fore\"", "far_2"),
        (
            "upper_aft",
            "cut_up",
            "cut_te",
            "[\"upper_aft\", \"base_up\"]",
            "far_1",
        ),
        (
            "lower_aft",
            "cut_te",
            "cut_lo",
            "[\"base_lo\", \"lower_aft\"]",
            "far_4",
        ),
        ("lower_fore", "cut_lo", "cut_le", "\"lower_fore\"", "far_3"),
    ] {
        t.push_str(&format!(
            "[[block]]\nname = \"{name}\"\nE1 = \"{e1}\"\nE2 = \"{e2}\"\nE3 = {e3}\nE4 = \"{e4}\"\n"
        ));
    }
    t
}

#[test]
fn the_one_block_naca0012_o_grid_converges_fold_free() {
    let r = generate(&oneblock_text());
    let rep = &r.report.blocks[0];
    let picard = rep.picard.as_ref().unwrap();
    assert!(picard.converged, "{} steps", picard.steps);
    assert_eq!(rep.quality.folded_cells, 0);
    let g = planar(&r.blocks[0].1);
    assert_eq!((g.ni(), g.nj()), (257, 49));
    for j in 0..g.nj() {
        assert_eq!(g.point(0, j), g.point(256, j), "seam row {j}");
    }
    // The wall is clustered through the control functions (the cut's first spacing 0.003,
    // and the O-grid's own growth away from the wall): mid-chord, upper surface,
    // i = 4 + 3 × 62; measured 5.2e-4.
    let (w, p) = (g.point(190, 0), g.point(190, 1));
    let first = (p[0] - w[0]).hypot(p[1] - w[1]);
    eprintln!("first spacing at mid-chord {first}");
    assert!((1e-4..3e-3).contains(&first), "first spacing {first}");
    // The lines leave the airfoil at right angles (`orthogonal = true`): 0.38° off the normal
    // on average, 12.9° at worst at the base's corners (23.6° / 66.9° without, measured).
    let o = &rep.quality.orthogonality[2];
    assert!(o.mean_deg < 1.0 && o.max_deg < 15.0, "{o:?}");
    // The report carries both solves: step 1 (straight-line control functions, 16 Newton
    // steps) as the `first` of step 3's history (8 steps, measured).
    let first = picard.first.as_ref().expect("step 1's history");
    assert!(first.converged && first.steps > 0 && first.history.len() == first.steps);
    // The seam is an interface of the block with itself, and it is smooth.
    let seam = r
        .report
        .interfaces
        .iter()
        .find(|f| f.edge == "cut_te")
        .unwrap();
    assert!(seam.floating);
    let sm = &seam.smoothness;
    eprintln!("seam {sm:?}");
    assert!(
        sm.kink_max_deg < 10.0 && sm.spacing_ratio_max < 1.3,
        "{sm:?}"
    );
}

#[test]
fn newton_steps_reach_the_picard_reference_in_a_tenth_of_the_steps() {
    // The shipped example takes Newton steps; the reference is the damped Picard iteration
    // run to 1e-13 (its own stop at 1e-10 is checked against it below).
    let text = oneblock_text();
    assert!(text.contains("nonlinear = \"newton\""));
    let newton = generate(&text);
    let steps = newton.report.blocks[0].picard.as_ref().unwrap().steps;
    let reference = generate(&text.replace(
        "nonlinear = \"newton\"",
        "nonlinear = \"picard\"\ntolerance = 1e-13\nmax_steps = 400",
    ));
    let rp = reference.report.blocks[0].picard.as_ref().unwrap();
    assert!(rp.converged);
    eprintln!("Newton {steps} steps, Picard to 1e-13 {} steps", rp.steps);
    assert!(
        steps * 8 < rp.steps,
        "{steps} Newton steps against {}",
        rp.steps
    );
    let (a, b) = (planar(&newton.blocks[0].1), planar(&reference.blocks[0].1));
    let diff = (0..a.nj())
        .flat_map(|j| (0..a.ni()).map(move |i| (i, j)))
        .map(|(i, j)| {
            let (p, q) = (a.point(i, j), b.point(i, j));
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .fold(0.0f64, f64::max);
    let diam = a.diameter();
    eprintln!("Newton vs reference {:.2e} of the diameter", diff / diam);
    assert!(diff < 1e-10 * diam, "{diff} against the diameter {diam}");
    // The damped Picard iteration's own stop at the default 1e-10 is honest: its a-posteriori
    // bound counts the slow contraction (~0.85) of the damped steps (it stopped on the last
    // update alone before, 7.7e-10 of the diameter off).
    let picard = generate(&text.replace("nonlinear = \"newton\"", "nonlinear = \"picard\""));
    let pp = planar(&picard.blocks[0].1);
    let off = (0..pp.nj())
        .flat_map(|j| (0..pp.ni()).map(move |i| (i, j)))
        .map(|(i, j)| {
            let (p, q) = (pp.point(i, j), b.point(i, j));
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .fold(0.0f64, f64::max);
    eprintln!(
        "Picard to 1e-10: {} steps, {:.2e} of the diameter off",
        picard.report.blocks[0].picard.as_ref().unwrap().steps,
        off / diam
    );
    assert!(off < 2e-10 * diam, "{off} against the diameter {diam}");
    assert_eq!(newton.report.blocks[0].quality.folded_cells, 0);
}

#[test]
fn a_ring_of_four_floating_blocks_is_the_one_block_grid() {
    let ring = generate(&ring_text());
    let blocks: Vec<&Grid2<2>> = ring.blocks.iter().map(|(_, b)| planar(b)).collect();
    for (rep, g) in ring.report.blocks.iter().zip(&blocks) {
        assert!(rep.picard.as_ref().unwrap().converged, "{}", rep.name);
        assert_eq!(rep.quality.folded_cells, 0, "{}", rep.name);
        assert_eq!((g.ni(), g.nj()), (63, 49));
        assert_eq!(
            rep.group.as_deref(),
            Some("upper_fore+upper_aft+lower_aft+lower_fore")
        );
    }
    // Interface nodes bit-identical: each block's E2 is the next block's E1, round the ring.
    for k in 0..4 {
        let (a, b) = (blocks[k], blocks[(k + 1) % 4]);
        for j in 0..49 {
            assert_eq!(
                a.point(62, j),
                b.point(0, j),
                "blocks {k}, {}: row {j}",
                (k + 1) % 4
            );
        }
    }
    // The same grid as the one block (its seam at the trailing edge, the ring's at the
    // leading edge): the periodic system does not know where its seam is (the control
    // functions are invariant under the affine change of s between the two), so the grids
    // agree to the Picard tolerance (1e-10 of the diameter 20).
    let one_text = oneblock_text();
    let one = generate(&(ring_edges() + &one_text[one_text.find("[[block]]").unwrap()..]));
    let g1 = planar(&one.blocks[0].1);
    // column c of the ring's block k is column (le + 62 k + c) of the one block, whose E3
    // reaches the leading edge after base_lo, lower_aft and lower_fore
    let le = 4 + 58 + 62;
    let mut worst = 0.0f64;
    for (k, g) in blocks.iter().enumerate() {
        for j in 0..49 {
            for c in 0..63 {
                let i1 = (le + 62 * k + c) % 248;
                let (p, q) = (g.point(c, j), g1.point(i1, j));
                worst = worst.max((p[0] - q[0]).hypot(p[1] - q[1]));
            }
        }
    }
    assert!(worst < 1e-8, "ring and one block differ by {worst:e}");
}

#[test]
fn the_shipped_example_runs_through_the_command_line() {
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/naca0012_oneblock.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            case.to_str().unwrap(),
            "-o",
            "one.x",
            "-o",
            "one.conn",
            "--report",
            "r.json",
            "-q",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    let b = &r["blocks"][0];
    assert_eq!(b["quality"]["folded_cells"], 0);
    assert_eq!(b["picard"]["converged"], true);
    assert_eq!(b["picard"]["linear_solver"], "direct-lu");
    // Step 1 of the orthogonality in the JSON report, with its history.
    assert_eq!(b["picard"]["first"]["converged"], true);
    assert!(b["picard"]["first"]["history"].as_array().unwrap().len() > 1);
    // and printed before step 3's
    let o = ellipgrid(d.path(), &["run", case.to_str().unwrap(), "-o", "two.x"]);
    let out = text(&o);
    let (s1, s3) = (
        out.find("orthogonality, step 1").unwrap(),
        out.find("orthogonality, step 3").unwrap(),
    );
    assert!(s1 < s3, "{out}");
    // The written grid has its seam duplicated bit for bit, and the connectivity file lists
    // the seam as the block's 1-to-1 interface with itself.
    let f = ellipgrid::io::plot3d::read_plot3d(&d.path().join("one.x")).unwrap();
    let g = planar(&f.blocks[0]);
    for j in 0..g.nj() {
        assert_eq!(g.point(0, j), g.point(g.ni() - 1, j));
    }
    let conn = std::fs::read_to_string(d.path().join("one.conn")).unwrap();
    assert!(conn.starts_with("1\n"), "{conn}");
}

#[test]
fn bad_periodic_blocks_are_refused_naming_the_block_and_edge() {
    // E3 and E4 of the periodic block with different node counts.
    let t = annulus(33, 13, "interface = \"floating\"");
    let i = t.rfind("n = 33").unwrap();
    let bad = format!("{}n = 29{}", &t[..i], &t[i + 6..]);
    rejects(&bad, &["block 'ring'", "inner", "outer"]);
    // A floating cut on adjacent sides of one block cannot be periodic.
    let adjacent = t.replace(
        "E2 = \"cut\"\nE3 = \"inner\"",
        "E3 = \"cut\"\nE2 = \"inner\"",
    );
    assert_ne!(adjacent, t);
    let o = {
        let d = tempfile::tempdir().unwrap();
        std::fs::write(d.path().join("bad.toml"), &adjacent).unwrap();
        ellipgrid(d.path(), &["run", "bad.toml", "-o", "out.x"])
    };
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
}

#[test]
fn verify_finds_second_order_and_the_same_grid_from_a_folded_start() {
    // An eccentric annulus (far field centred at x = 0.5) with a clustered floating cut:
    // `ellipgrid verify` grids it at 3 levels (order of the family) and from a scrambled,
    // folded start (the same grid to the limit); exit 0 = every property holds.
    let t = annulus(
        33,
        13,
        "interface = \"floating\"\ndistribution = { type = \"geometric\", first = 0.05 }",
    )
    .replace(
        "center = [0, 0], radius = 5",
        "center = [0.5, 0], radius = 5",
    )
    .replace("at = [5, 0]", "at = [5.5, 0]");
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("ann.toml"), t).unwrap();
    let o = ellipgrid(d.path(), &["verify", "ann.toml", "--levels", "3"]);
    let msg = text(&o);
    assert!(o.status.success(), "{msg}");
    assert!(
        msg.contains("pass: 1 of 1 blocks pass") && msg.contains("folded"),
        "{msg}"
    );
}

#[test]
fn the_periodic_grid_is_bit_identical_on_one_and_two_threads() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(
        d.path().join("ann.toml"),
        annulus(
            33,
            13,
            "interface = \"floating\"\ndistribution = { type = \"geometric\", first = 0.05 }",
        ),
    )
    .unwrap();
    // and the one-block O-grid by Newton steps (finite-difference Jacobian, GMRES)
    std::fs::write(d.path().join("one.toml"), oneblock_text()).unwrap();
    for case in ["ann", "one"] {
        let mut files = Vec::new();
        for threads in ["1", "2"] {
            let out = format!("{case}{threads}.x");
            let o = std::process::Command::new(env!("CARGO_BIN_EXE_ellipgrid"))
                .args(["run", &format!("{case}.toml"), "-o", &out, "-q"])
                .env("RAYON_NUM_THREADS", threads)
                .current_dir(d.path())
                .output()
                .unwrap();
            assert!(o.status.success(), "{}", text(&o));
            files.push(std::fs::read(d.path().join(out)).unwrap());
        }
        assert!(
            files[0] == files[1],
            "{case}: the grids differ between 1 and 2 threads"
        );
    }
}

#[test]
fn a_wall_on_a_periodic_ring_holds_the_cuts_first_spacing_through_the_command_line() {
    // The eccentric annulus (far field centred at x = 0.5) with the cut's first spacing 1e-3:
    // without `wall` the first spacing is 0.23 … 0.28 of the cut's (measured: the control
    // functions carry the cut's relative distribution, not its lengths); with `wall = true` on
    // the inner circle every node of the ring is within 1 % of it (1.00008 … 1.00012,
    // measured), as the report's "wall" entry says, and fold-free.
    let t = annulus(
        65,
        25,
        "interface = \"floating\"\ndistribution = { type = \"geometric\", first = 1e-3 }",
    )
    .replace(
        "center = [0, 0], radius = 5",
        "center = [1.5, 0], radius = 5",
    )
    .replace("at = [5, 0]", "at = [6.5, 0]");
    let wall = t.replace("name = \"inner\"\n", "name = \"inner\"\nwall = true\n");
    let d = tempfile::tempdir().unwrap();
    let mut ratios = Vec::new();
    for (name, case) in [("plain", &t), ("wall", &wall)] {
        std::fs::write(d.path().join(format!("{name}.toml")), case).unwrap();
        let (x, rep) = (format!("{name}.x"), format!("{name}.json"));
        let o = ellipgrid(
            d.path(),
            &[
                "run",
                &format!("{name}.toml"),
                "-o",
                &x,
                "--report",
                &rep,
                "-q",
            ],
        );
        assert!(o.status.success(), "{}", text(&o));
        let r: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(d.path().join(&rep)).unwrap()).unwrap();
        let b = &r["blocks"][0];
        assert_eq!(b["quality"]["folded_cells"], 0);
        assert_eq!(b["picard"]["converged"], true);
        let f = ellipgrid::io::plot3d::read_plot3d(&d.path().join(&x)).unwrap();
        let g = planar(&f.blocks[0]);
        let first: Vec<f64> = (0..g.ni() - 1)
            .map(|i| {
                let (p, q) = (g.point(i, 0), g.point(i, 1));
                (p[0] - q[0]).hypot(p[1] - q[1]) / 1e-3
            })
            .collect();
        let lo = first.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = first.iter().copied().fold(0.0, f64::max);
        ratios.push((lo, hi));
        if name == "wall" {
            let w = &b["wall"][0];
            assert_eq!(w["edge"], "E3");
            assert_eq!(w["nodes"], 64);
            let (rlo, rhi) = (
                w["ratio_min"].as_f64().unwrap(),
                w["ratio_max"].as_f64().unwrap(),
            );
            assert!((rlo - lo).abs() < 1e-9 && (rhi - hi).abs() < 1e-9);
        }
    }
    assert!(ratios[0].1 < 0.5, "{ratios:?}");
    assert!(ratios[1].0 > 0.99 && ratios[1].1 < 1.01, "{ratios:?}");
}

#[test]
fn the_naca0012_one_block_holds_a_navier_stokes_wall_spacing_at_right_angles() {
    // The shipped one-block O-grid (orthogonal at the airfoil) with the cut's first spacing
    // 1e-5 (97 nodes) and `wall` on the airfoil: 2.2e-7 … 1.7e-6 without the wall passes; with
    // them within 1 % all round, the lines leaving the airfoil 0.38° off its normal on average
    // (measured; 11° at worst, at the base's corners), 36 steps. Without orthogonality the
    // lines leave 27° off the normal, and the passes oscillate at the trailing-edge base after
    // the fifth (1.1e-2 → 6.1e-2): that pass is undone and the passes stop (49 steps; 1367
    // steps and 147 s when they ran on).
    let ns = oneblock_text()
        .replace("family = \"airfoil\"", "wall = true\nfamily = \"airfoil\"")
        .replace(
            "n = 49\ndistribution = { type = \"vinokur\", first = 0.003, last = 1.5 }",
            "n = 97\ndistribution = { type = \"vinokur\", first = 1e-5, last = 1.5 }",
        )
        .replace("../data/", &format!("{}/data/", root().display()));
    assert!(ns.contains("first = 1e-5") && ns.contains("orthogonal = true"));
    let skew = ns.replace("orthogonal = true\n", "");
    for (case, orthogonal) in [(&ns, true), (&skew, false)] {
        let r = generate(case);
        let b = &r.report.blocks[0];
        let picard = b.picard.as_ref().unwrap();
        assert!(
            picard.converged && picard.steps < 100,
            "{} steps",
            picard.steps
        );
        let w = &b.wall[0];
        assert_eq!((w.edge.as_str(), w.nodes), ("E3", 256));
        assert!(w.ratio_min > 0.99 && w.ratio_max < 1.01, "{w:?}");
        assert_eq!(b.quality.folded_cells, 0);
        let o = &b.quality.orthogonality[2];
        if orthogonal {
            assert!(o.mean_deg < 1.0 && o.max_deg < 15.0, "{o:?}");
        } else {
            assert!(o.mean_deg > 20.0, "{o:?}");
        }
    }
}

/// A minimal-surface ring between the circles of radius 1 at z = ±0.5 (`n` nodes round
/// each), its cut (`m` nodes) floating: the block is periodic in i; `extra` goes into both
/// circles' edges.
fn catenoid_text(n: usize, m: usize, extra: &str) -> String {
    let circle = |name: &str, v: &str, z: f64| {
        format!(
            "[[edge]]\nname = \"{name}\"\nfrom = \"{v}\"\nto = \"{v}\"\nn = {n}\n{extra}\
             curve = {{ type = \"arc\", center = [0, 0, {z}], radius = 1, start_deg = 0, \
             end_deg = 360 }}\n"
        )
    };
    format!(
        "[[vertex]]\nname = \"in\"\nat = [1, 0, -0.5]\n[[vertex]]\nname = \"out\"\nat = [1, 0, 0.5]\n\
         {}{}[[edge]]\nname = \"cut\"\nfrom = \"in\"\nto = \"out\"\nn = {m}\ninterface = \"floating\"\n\
         [[block]]\nname = \"catenoid\"\nkind = \"minimal\"\nE1 = \"cut\"\nE2 = \"cut\"\n\
         E3 = \"bottom\"\nE4 = \"top\"\n",
        circle("bottom", "in", -0.5),
        circle("top", "out", 0.5)
    )
}

fn surface(b: &Block) -> &Grid2<3> {
    match b {
        Block::Surface(g) => g,
        _ => panic!("a surface block"),
    }
}

#[test]
fn a_minimal_ring_between_coaxial_circles_is_the_catenoid_at_second_order() {
    // The soap film spanning the circles r = 1 at z = ±0.5 is the catenoid r = c cosh(z/c),
    // c cosh(0.5/c) = 1 (c = 0.84834, the stable branch). The periodic minimal block (Section 3
    // with the seam wrapped) lies on it to 1.9e-3, 4.7e-4, 1.2e-4 at 33 × 17, 65 × 33,
    // 129 × 65 (ratios 4.03, 4.01, measured). With orthogonality at both circles (Section 2.4
    // on the surface, the harmonic s by Laplace–Beltrami) the grid is the same: on uniform
    // circles the harmonic s is the angle itself and the blend the straight-line map.
    let f = |c: f64| c * (0.5 / c).cosh() - 1.0;
    let (mut lo, mut hi) = (0.6, 1.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let c = 0.5 * (lo + hi);
    let off = |g: &Grid2<3>| {
        (0..g.nj())
            .flat_map(|j| (0..g.ni()).map(move |i| (i, j)))
            .map(|(i, j)| {
                let [x, y, z] = g.point(i, j);
                (x.hypot(y) - c * (z / c).cosh()).abs()
            })
            .fold(0.0f64, f64::max)
    };
    let mut errors = Vec::new();
    for m in [17, 33, 65] {
        let r = generate(&catenoid_text(2 * m - 1, m, ""));
        assert!(r.report.blocks[0].picard.as_ref().unwrap().converged);
        let g = surface(&r.blocks[0].1);
        for j in 0..g.nj() {
            assert_eq!(g.point(0, j), g.point(g.ni() - 1, j), "seam row {j}");
        }
        errors.push(off(g));
    }
    assert!(errors[0] < 2.5e-3, "{errors:?}");
    for e in errors.windows(2) {
        assert!(e[0] / e[1] > 3.5, "{errors:?}");
    }
    let plain = generate(&catenoid_text(65, 33, ""));
    let orth = generate(&catenoid_text(65, 33, "orthogonal = true\n"));
    let first = orth.report.blocks[0]
        .picard
        .as_ref()
        .unwrap()
        .first
        .as_ref();
    assert!(first.is_some_and(|f| f.converged), "step 1 reported");
    let (a, b) = (surface(&plain.blocks[0].1), surface(&orth.blocks[0].1));
    let worst = (0..a.coords()[0].len())
        .map(|p| {
            (0..3)
                .map(|k| (a.coords()[k][p] - b.coords()[k][p]).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0f64, f64::max);
    assert!(
        worst < 1e-8,
        "orthogonality changed the catenoid's grid by {worst:e}"
    );
}
