//! Block faces on a STEP model that are not CAD faces (issue #14, item 4): `kind = "surface"`
//! blocks with `surface = { type = "step", file, faces }`, their edges projected lines, iso
//! lines or junctions with another face, gridded through a Hermite net projected onto the
//! model (Section 4), the nodes moved onto the model at the end.

mod common;

use common::{ellipgrid, root, text};
use ellipgrid::io::{plot3d::read_plot3d, Block};
use ellipgrid::Grid2;
use std::path::Path;

/// Runs `case` (written as `case.toml` in `dir`) through the CLI and reads its one grid.
fn run(dir: &Path, case: &str) -> Grid2<3> {
    std::fs::write(dir.join("case.toml"), case).unwrap();
    let o = ellipgrid(
        dir,
        &["run", "case.toml", "-o", "g.x", "--report", "r.json"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let f = read_plot3d(&dir.join("g.x")).unwrap();
    let Block::Surface(g) = &f.blocks[0] else {
        panic!("a surface block")
    };
    g.clone()
}

/// A block on the twisted wing patch (z = 0.1 sin(1.3x) cos(0.9y) + 0.05xy): its edges
/// lines, a spline and a polyline in the plane z = 0, projected onto the model.
fn twisted_case(file: &str) -> String {
    let step = root().join("data/step").join(file);
    format!(
        r#"[[block]]
name = "inner"
kind = "surface"
ni = 49
nj = 33
surface = {{ type = "step", file = "{}", faces = [1] }}
[block.E1]
curve = {{ type = "line", from = [0.3, 0.2, 0.0], to = [0.2, 1.3, 0.0] }}
[block.E2]
curve = {{ type = "line", from = [1.7, 0.3, 0.0], to = [1.8, 1.2, 0.0] }}
distribution = {{ type = "vinokur", first = 0.005 }}
[block.E3]
curve = {{ type = "spline", points = [[0.3, 0.2, 0.0], [1.0, 0.1, 0.0], [1.7, 0.3, 0.0]] }}
distribution = {{ type = "vinokur", first = 0.005 }}
[block.E4]
curve = {{ type = "polyline", points = [[0.2, 1.3, 0.0], [1.0, 1.35, 0.0], [1.8, 1.2, 0.0]] }}
"#,
        step.display()
    )
}

fn twisted(x: f64, y: f64) -> f64 {
    0.1 * (1.3 * x).sin() * (0.9 * y).cos() + 0.05 * x * y
}

/// The same shape in two CAD parametrizations (uniform, and nearly singular at two edges):
/// the grids agree to the files' fit error (the net is built in space, not in (u, v)), and
/// every node lies on the shape.
#[test]
fn model_grid_does_not_depend_on_the_cad_parametrization() {
    let d = tempfile::tempdir().unwrap();
    let a = run(d.path(), &twisted_case("wing_patch_twisted.step"));
    let b = run(d.path(), &twisted_case("wing_patch_twisted_reparam.step"));
    let diff = common::max_diff(a.coords(), b.coords());
    eprintln!("twisted patch, two parametrizations: grids differ by {diff:.3e}");
    assert!(diff < 1e-7, "{diff}");
    for g in [&a, &b] {
        for k in 0..g.len() {
            let (x, y, z) = (g.coord(0)[k], g.coord(1)[k], g.coord(2)[k]);
            assert!((z - twisted(x, y)).abs() < 1e-7, "node {k} off the shape");
        }
    }
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    let b0 = &r["blocks"][0];
    assert_eq!(b0["quality"]["folded_cells"], 0);
    // the net's Hermite surface lies within 1e-6 of the model at the nodes
    assert!(b0["model_distance"]["max"].as_f64().unwrap() < 1e-6, "{b0}");
}

/// Edges that are iso lines of the face: the block is the patch's sub-rectangle
/// [0, 0.8] × [0.1, 0.9] in (u, v) = (x/2, y/1.5); the E3 nodes lie on y = 0.15, the E1
/// nodes on x = 0, to the Hermite net's accuracy (nodes are moved onto the model, not onto
/// an iso line: 1e-9 here).
#[test]
fn iso_line_edges_bound_the_sub_patch() {
    let d = tempfile::tempdir().unwrap();
    let step = root().join("data/step/wing_patch_twisted.step");
    let case = format!(
        r#"[[block]]
kind = "surface"
ni = 33
nj = 25
surface = {{ type = "step", file = "{}", faces = [1], net = [41, 31] }}
[block.E1]
curve = {{ type = "iso", face = 1, u = 0.0, from = 0.1, to = 0.9 }}
[block.E2]
curve = {{ type = "iso", face = 1, u = 0.8, from = 0.1, to = 0.9 }}
[block.E3]
curve = {{ type = "iso", face = 1, v = 0.1, to = 0.8 }}
[block.E4]
curve = {{ type = "iso", face = 1, v = 0.9, to = 0.8 }}
"#,
        step.display()
    );
    let g = run(d.path(), &case);
    let (ni, nj) = (g.ni(), g.nj());
    for i in 0..ni {
        let p = g.point(i, 0);
        assert!((p[1] - 0.15).abs() < 1e-8, "E3 node {i}: {p:?}");
    }
    for j in 0..nj {
        let p = g.point(0, j);
        assert!(p[0].abs() < 1e-8, "E1 node {j}: {p:?}");
        let q = g.point(ni - 1, j);
        assert!((q[0] - 1.6).abs() < 1e-8, "E2 node {j}: {q:?}");
    }
    assert!((g.point(ni - 1, nj - 1)[1] - 1.35).abs() < 1e-8);
}

/// Bad model blocks: exit 2, the block and edge named, nothing written.
#[test]
fn bad_model_blocks_are_refused_by_name() {
    let step = root().join("data/step/wing_patch_twisted.step");
    let block = |faces: &str, e1: &str, e4: &str| {
        format!(
            r#"[[block]]
name = "m"
kind = "surface"
ni = 9
nj = 9
surface = {{ type = "step", file = "{}", faces = [{faces}] }}
[block.E1]
curve = {e1}
[block.E2]
curve = {{ type = "line", from = [1.5, 0.2, 0], to = [1.5, 1.2, 0] }}
[block.E3]
curve = {{ type = "line", from = [0.5, 0.2, 0], to = [1.5, 0.2, 0] }}
[block.E4]
curve = {e4}
"#,
            step.display()
        )
    };
    let e1 = r#"{ type = "line", from = [0.5, 0.2, 0], to = [0.5, 1.2, 0] }"#;
    let e4 = r#"{ type = "line", from = [0.5, 1.2, 0], to = [1.5, 1.2, 0] }"#;
    // E4 starting 0.1 away from E1's end: more than 2 % of the edges
    let far = r#"{ type = "line", from = [0.6, 1.2, 0], to = [1.5, 1.2, 0] }"#;
    common::rejects(
        &block("1", e1, far),
        &["block 'm'", "edges E1 and E4 do not meet"],
    );
    common::rejects(&block("3", e1, e4), &["face 3 is not in the file"]);
    let off = r#"{ type = "line", from = [0.5, 0.2, 9], to = [0.5, 1.2, 9] }"#;
    common::rejects(
        &block("1", off, e4),
        &["edge E1", "from the model, more than its length"],
    );
    let arc = r#"{ type = "arc", center = [1, 1, 0], radius = 0.5, start_deg = 0, end_deg = 90 }"#;
    common::rejects(
        &block("1", arc, e4),
        &["block 'm', edge E1", "a line, polyline or spline"],
    );
    let both = r#"{ type = "iso", face = 1, u = 0.2, v = 0.3 }"#;
    common::rejects(&block("1", both, e4), &["edge E1", "fixes one of u and v"]);
    let miss = r#"{ type = "intersection", face = 1, from = [0.5, 0.2, 0], to = [0.5, 1.2, 0] }"#;
    common::rejects(&block("1", miss, e4), &["edge E1", "junction with face 1"]);
    // a STEP model is not a named or reference surface
    let named = format!(
        "[[surface]]\nname = \"s\"\ntype = \"step\"\nfile = \"{}\"\nfaces = [1]\n{}",
        step.display(),
        block("1", e1, e4).replace(
            &format!(
                "{{ type = \"step\", file = \"{}\", faces = [1] }}",
                step.display()
            ),
            "\"s\""
        )
    );
    common::rejects(&named, &["block whose four edges lie on it"]);
}

/// Edges that are the face's own CAD edges (`step list --edges` numbers them): the block is
/// the whole face, the same grid as with iso lines of its sides; a chain of edges that do not
/// follow each other is refused.
#[test]
fn cad_edges_make_the_same_block_as_iso_lines() {
    let d = tempfile::tempdir().unwrap();
    let step = root().join("data/step/wing_patch_twisted.step");
    let case = |e: [&str; 4]| {
        format!(
            "[[block]]\nname = \"w\"\nkind = \"surface\"\nni = 33\nnj = 25\n\
             surface = {{ type = \"step\", file = \"{}\", faces = [1] }}\n\
             [block.E1]\n{}\n[block.E2]\n{}\n[block.E3]\n{}\n[block.E4]\n{}\n",
            step.display(),
            e[0],
            e[1],
            e[2],
            e[3]
        )
    };
    // loop: edge 1 (0, 1.5) → (0, 0), 2 along y = 0, 3 along x = 2, 4 (2, 1.5) → (0, 1.5)
    let by_edges = run(
        d.path(),
        &case([
            "curve = { type = \"edges\", face = 1, edges = [1] }\nreverse = true",
            "curve = { type = \"edges\", face = 1, edges = [3] }",
            "curve = { type = \"edges\", face = 1, edges = [2] }",
            "curve = { type = \"edges\", face = 1, edges = [4] }\nreverse = true",
        ]),
    );
    let by_iso = run(
        d.path(),
        &case([
            "curve = { type = \"iso\", face = 1, u = 0.0 }",
            "curve = { type = \"iso\", face = 1, u = 1.0 }",
            "curve = { type = \"iso\", face = 1, v = 0.0 }",
            "curve = { type = \"iso\", face = 1, v = 1.0 }",
        ]),
    );
    let diff = common::max_diff(by_edges.coords(), by_iso.coords());
    eprintln!("whole twisted face by CAD edges and by iso lines: grids differ by {diff:.3e}");
    assert!(diff < 1e-8, "{diff}");
    assert!((by_edges.point(32, 24)[0] - 2.0).abs() < 1e-12);
    let apart = case([
        "curve = { type = \"edges\", face = 1, edges = [1, 3] }",
        "curve = { type = \"edges\", face = 1, edges = [3] }",
        "curve = { type = \"edges\", face = 1, edges = [2] }",
        "curve = { type = \"edges\", face = 1, edges = [4] }",
    ]);
    common::rejects(&apart, &["edge E1", "edges 1 and 3 of face 1 do not meet"]);
    let o = ellipgrid(
        d.path(),
        &["step", "list", "--edges", step.to_str().unwrap()],
    );
    assert!(
        text(&o)
            .contains("edge 3: (2.000000, 0.000000, 0.051550) → (2.000000, 1.500000, 0.161290)"),
        "{}",
        text(&o)
    );
}

#[path = "../examples/common/wing_pylon_shape.rs"]
mod shape;

/// Runs a shipped example through the CLI (from a temporary directory) and reads its grid and
/// the block's report.
fn run_example(dir: &Path, case: &Path, out: &str) -> (Grid2<3>, serde_json::Value) {
    let rep = format!("{out}.json");
    let o = ellipgrid(
        dir,
        &["run", case.to_str().unwrap(), "-o", out, "--report", &rep],
    );
    assert!(o.status.success(), "{}", text(&o));
    let f = read_plot3d(&dir.join(out)).unwrap();
    let Block::Surface(g) = &f.blocks[0] else {
        panic!("a surface block")
    };
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(rep)).unwrap()).unwrap();
    (g.clone(), r["blocks"][0].clone())
}

/// Largest turn (degrees) of the j-lines at the interior nodes where `pick` holds.
fn j_turn(g: &Grid2<3>, pick: impl Fn([f64; 3]) -> bool) -> f64 {
    let mut worst = 0.0f64;
    for j in 1..g.nj() - 1 {
        for i in 0..g.ni() {
            let [a, b, c] = [g.point(i, j - 1), g.point(i, j), g.point(i, j + 1)];
            if !pick(b) {
                continue;
            }
            let s: [f64; 3] = std::array::from_fn(|d| b[d] - a[d]);
            let t: [f64; 3] = std::array::from_fn(|d| c[d] - b[d]);
            let dot: f64 = (0..3).map(|d| s[d] * t[d]).sum();
            let n = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
            worst = worst.max((dot / (n(s) * n(t))).clamp(-1.0, 1.0).acos().to_degrees());
        }
    }
    worst
}

/// The wing–pylon example on its STEP model (examples/wing_pylon_step.toml, the paper's Figs
/// 33–36): a block face spanning two CAD faces, E3 the computed junction with the pylon.
/// Fold-free; every node on the analytic wing, the E3 nodes on the analytic pylon (to the
/// model's 2e-6 fit); the planform edges where they were asked; no kink where the block crosses
/// from face 1 to face 2 (y = 0.5); the same grid as the `hermite_net` route on the analytic
/// net (examples/wing_pylon.toml) to a small fraction of the spacing; and the net's surface
/// converging to the model as the net is refined (ratio ≈ 10 per halving).
#[test]
fn wing_pylon_block_face_on_the_step_model() {
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/wing_pylon_step.toml");
    let (g, rep) = run_example(d.path(), &case, "step.x");
    assert_eq!(rep["quality"]["folded_cells"], 0, "{rep}");
    let (ni, nj) = (g.ni(), g.nj());
    for k in 0..g.len() {
        let (x, y, z) = (g.coord(0)[k], g.coord(1)[k], g.coord(2)[k]);
        assert!(
            (z - shape::lower_surface(x, y)).abs() < 5e-6,
            "node {k} off the wing"
        );
    }
    for i in 0..ni {
        let p = g.point(i, 0);
        assert!(
            (p[1] - shape::pylon_half_width(p[0])).abs() < 5e-6,
            "E3 node {i} off the pylon: {p:?}"
        );
        assert!((g.point(i, nj - 1)[1] - 1.0).abs() < 1e-7, "E4 node {i}");
    }
    for j in 0..nj {
        assert!((g.point(0, j)[0] - 0.2).abs() < 1e-12, "E1 node {j}");
        assert!((g.point(ni - 1, j)[0] - 1.8).abs() < 1e-12, "E2 node {j}");
    }
    // smooth across the two CAD faces: the j-lines turn no more at the seam than the
    // analytic route's (which has none) do there
    let (h, hrep) = run_example(d.path(), &root().join("examples/wing_pylon.toml"), "net.x");
    let seam = |p: [f64; 3]| (p[1] - 0.5).abs() < 0.03;
    let (ts, th) = (j_turn(&g, seam), j_turn(&h, seam));
    eprintln!("j-lines turn at the seam y = 0.5: {ts:.4}° (hermite_net route {th:.4}°)");
    assert!(ts < 0.05 && ts < 1.5 * th, "{ts} {th}");
    let diff = common::max_diff(g.coords(), h.coords());
    let spacing = hrep["quality"]["min_spacing"].as_f64().unwrap();
    eprintln!("wing–pylon: STEP model and hermite_net routes differ by {diff:.3e} (min spacing {spacing:.3e})");
    assert!(diff < 0.25 * spacing, "{diff} {spacing}");
    // the net's Hermite surface converges to the model
    let text = std::fs::read_to_string(&case)
        .unwrap()
        .replace("along = [0, 0, 1] }", "along = [0, 0, 1], net = [NET] }")
        .replace("../data", root().join("data").to_str().unwrap());
    let moved: Vec<f64> = ["65, 33", "129, 65", "257, 129"]
        .iter()
        .map(|n| {
            std::fs::write(d.path().join("n.toml"), text.replace("NET", n)).unwrap();
            let (_, r) = run_example(d.path(), &d.path().join("n.toml"), "n.x");
            r["model_distance"]["max"].as_f64().unwrap()
        })
        .collect();
    eprintln!("nodes moved onto the model, nets 65 × 33, 129 × 65, 257 × 129: {moved:?}");
    assert!(
        moved[0] / moved[1] > 6.0 && moved[1] / moved[2] > 6.0,
        "{moved:?}"
    );
    assert!(moved[2] < 1e-5);
}

/// A block inside a trimmed face (the notched plate, one loop of five edges; the model samples
/// the face by its own block grid): a rectangle below the notch, uniform edges, gives the
/// uniform grid exactly (a rectangle with equal opposite distributions).
#[test]
fn block_inside_a_trimmed_face_is_the_exact_rectangle_grid() {
    let d = tempfile::tempdir().unwrap();
    let step = root().join("data/step/plane_notch.step");
    let case = format!(
        r#"[[block]]
kind = "surface"
ni = 31
nj = 7
surface = {{ type = "step", file = "{}", faces = [1], along = [0, 0, 1] }}
[block.E1]
curve = {{ type = "line", from = [0.5, 0.1, 0.1], to = [0.5, 0.4, 0.1] }}
[block.E2]
curve = {{ type = "line", from = [3.5, 0.1, 0.1], to = [3.5, 0.4, 0.1] }}
[block.E3]
curve = {{ type = "line", from = [0.5, 0.1, 0.1], to = [3.5, 0.1, 0.1] }}
[block.E4]
curve = {{ type = "line", from = [0.5, 0.4, 0.1], to = [3.5, 0.4, 0.1] }}
"#,
        step.display()
    );
    let g = run(d.path(), &case);
    for j in 0..7 {
        for i in 0..31 {
            let p = g.point(i, j);
            let want = [0.5 + 0.1 * i as f64, 0.1 + 0.05 * j as f64, 0.0];
            for c in 0..3 {
                assert!((p[c] - want[c]).abs() < 1e-10, "node ({i}, {j}): {p:?}");
            }
        }
    }
}

/// A band around the filleted vertical edge of the OpenCascade plate: three trimmed CAD faces
/// (the side x = 40, the fillet cylinder r = 3 about (37, 27), the side y = 30), the block's
/// long edges polylines cutting the corner, projected onto the model. The band is developable:
/// unrolled it is a 33.71 × 5 rectangle, and with uniform edges its grid is the uniform grid
/// there. Every node on the model to rounding; the error against the unrolled uniform grid
/// falls about 12 times per halving of the net spacing (the net's surface converging to the
/// model across the faces' curvature jumps).
#[test]
fn band_around_a_fillet_spans_three_cad_faces() {
    let d = tempfile::tempdir().unwrap();
    let step = root().join("data/step/plate_with_holes.step");
    let (ni, nj) = (49, 9);
    let long = 17.0 + 1.5 * std::f64::consts::PI + 12.0;
    // unrolled arclength from (40, 10) along the band
    let s_of = |x: f64, y: f64| {
        if y <= 27.0 && (x - 40.0).abs() < 1e-9 {
            y - 10.0
        } else if x <= 37.0 && (y - 30.0).abs() < 1e-9 {
            17.0 + 1.5 * std::f64::consts::PI + (37.0 - x)
        } else {
            17.0 + 3.0 * (y - 27.0).atan2(x - 37.0)
        }
    };
    let mut errs = Vec::new();
    for net in ["49, 9", "97, 17", "193, 33"] {
        let case = format!(
            r#"[[block]]
name = "band"
kind = "surface"
ni = {ni}
nj = {nj}
surface = {{ type = "step", file = "{}", faces = [1, 3, 6], net = [{net}] }}
[block.E1]
curve = {{ type = "line", from = [40, 10, 0], to = [40, 10, 5] }}
[block.E2]
curve = {{ type = "line", from = [25, 30, 0], to = [25, 30, 5] }}
[block.E3]
curve = {{ type = "polyline", points = [[40, 10, 0], [40, 27, 0], [37, 30, 0], [25, 30, 0]] }}
[block.E4]
curve = {{ type = "polyline", points = [[40, 10, 5], [40, 27, 5], [37, 30, 5], [25, 30, 5]] }}
"#,
            step.display()
        );
        let g = run(d.path(), &case);
        let mut err = 0.0f64;
        for j in 0..nj {
            for i in 0..ni {
                let [x, y, z] = g.point(i, j);
                let on_side = ((x - 40.0).abs() < 1e-12 && y <= 27.0)
                    || ((y - 30.0).abs() < 1e-12 && x <= 37.0)
                    || (((x - 37.0).hypot(y - 27.0) - 3.0).abs() < 1e-12 && x >= 37.0 && y >= 27.0);
                assert!(on_side, "node ({i}, {j}) off the model: {:?}", [x, y, z]);
                let want = [
                    long * i as f64 / (ni - 1) as f64,
                    5.0 * j as f64 / (nj - 1) as f64,
                ];
                err = err
                    .max((s_of(x, y) - want[0]).abs())
                    .max((z - want[1]).abs());
            }
        }
        errs.push(err);
    }
    eprintln!("fillet band against its unrolled uniform grid, nets 49, 97, 193: {errs:?}");
    assert!(
        errs[0] < 1e-3 && errs[0] / errs[1] > 8.0 && errs[1] / errs[2] > 8.0,
        "{errs:?}"
    );
}

/// `ellipgrid verify` on the wing–pylon block on its STEP model: the grid family converges at
/// second order and the grid does not depend on the net's parametrization (warped).
#[test]
fn verify_passes_on_the_step_model_block() {
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/wing_pylon_step.toml");
    let o = ellipgrid(
        d.path(),
        &["verify", case.to_str().unwrap(), "--report", "v.json"],
    );
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("pass: 1 of 1 blocks pass"),
        "{}",
        text(&o)
    );
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.path().join("v.json")).unwrap()).unwrap();
    let b = &r["blocks"][0];
    let p = b["family"]["order_rms"][0].as_f64().unwrap();
    assert!(p > 1.8, "observed order {p}: {b}");
    assert_eq!(b["parametrization"]["pass"], true, "{b}");
}

/// Two blocks on the wing–pylon model side by side (fore and aft of x = 1), given the same
/// edge x = 1 between them: its nodes are the same in both (to rounding) and the `.conn` file
/// lists that 1-to-1 interface, every other side a patch of its block.
#[test]
fn blocks_on_a_model_sharing_an_edge_are_joined() {
    let d = tempfile::tempdir().unwrap();
    let step = root().join("data/step/wing_pylon.step");
    let w1 = shape::pylon_half_width(1.0);
    let block = |name: &str, x0: f64, y0: f64, x1: f64, y1: f64| {
        format!(
            r#"[[block]]
name = "{name}"
kind = "surface"
ni = 41
nj = 33
surface = {{ type = "step", file = "{step}", faces = [1, 2], along = [0, 0, 1] }}
[block.E1]
curve = {{ type = "line", from = [{x0}, {y0}, 0], to = [{x0}, 1.0, 0] }}
distribution = {{ type = "vinokur", first = 2e-3 }}
[block.E2]
curve = {{ type = "line", from = [{x1}, {y1}, 0], to = [{x1}, 1.0, 0] }}
distribution = {{ type = "vinokur", first = 2e-3 }}
[block.E3]
curve = {{ type = "intersection", face = 4, from = [{x0}, {y0}, -0.09], to = [{x1}, {y1}, -0.05] }}
[block.E4]
curve = {{ type = "line", from = [{x0}, 1.0, 0], to = [{x1}, 1.0, 0] }}
"#,
            step = step.display()
        )
    };
    let case = format!(
        "{}\n{}",
        block("fore", 0.2, 0.0, 1.0, w1),
        block("aft", 1.0, w1, 1.8, shape::pylon_half_width(1.8))
    );
    std::fs::write(d.path().join("two.toml"), case).unwrap();
    let o = ellipgrid(
        d.path(),
        &["run", "two.toml", "-o", "two.x", "-o", "two.conn"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let f = read_plot3d(&d.path().join("two.x")).unwrap();
    let [Block::Surface(a), Block::Surface(b)] = &f.blocks[..] else {
        panic!("two surface blocks")
    };
    for j in 0..33 {
        let (p, q) = (a.point(40, j), b.point(0, j));
        let gap = (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0, f64::max);
        assert!(gap < 1e-12, "node {j} of the shared edge: {p:?} {q:?}");
    }
    let conn = std::fs::read_to_string(d.path().join("two.conn")).unwrap();
    let lines: Vec<&str> = conn.lines().collect();
    assert_eq!(lines[0].trim(), "1", "{conn}");
    let words = |l: &str| l.split_whitespace().map(String::from).collect::<Vec<_>>();
    assert_eq!(
        words(lines[1]),
        ["1", "41", "1", "1", "41", "33", "1"],
        "{conn}"
    );
    assert_eq!(
        words(lines[2]),
        ["2", "1", "1", "1", "1", "33", "1"],
        "{conn}"
    );
    assert_eq!(lines[3].trim(), "6", "{conn}");
}
