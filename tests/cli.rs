//! The command line: runs of the shipped examples, the exact rectangle through a case file,
//! and every bad-input path (exit code, message, no output file).

mod common;
use common::*;
use ellipgrid::io::plot3d::read_plot3d;
use ellipgrid::io::Block;
use std::fs;

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

#[test]
fn examples_run_fold_free_and_converge() {
    for ex in [
        "curved",
        "boundary_layer",
        "folding_start",
        "wing_pylon",
        "scherk",
    ] {
        let d = tmp();
        let case = root().join(format!("examples/{ex}.toml"));
        let o = ellipgrid(
            d.path(),
            &[
                "run",
                case.to_str().unwrap(),
                "-o",
                "g.x",
                "-o",
                "g.vts",
                "--report",
                "r.json",
            ],
        );
        assert!(o.status.success(), "{ex}: {}", text(&o));
        assert!(d.path().join("g.x").exists() && d.path().join("g.vts").exists());
        let r: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
        for b in r["blocks"].as_array().unwrap() {
            if b["picard"].is_null() {
                // a surface block (Section 4): no Picard iteration, its steps are timed
                assert!(b["surface_steps"]["inversion"].as_f64().is_some(), "{ex}");
            } else {
                assert_eq!(b["picard"]["converged"], true, "{ex}");
                assert!(!b["picard"]["history"].as_array().unwrap().is_empty());
            }
            assert_eq!(b["quality"]["folded_cells"], 0, "{ex}");
        }
        // The Plot3D file reads back and `check` agrees that it is fold-free.
        let c = ellipgrid(d.path(), &["check", "g.x"]);
        assert!(c.status.success(), "{ex}: {}", text(&c));
        assert!(text(&c).contains("folded cells"));
    }
}

#[test]
fn rectangle_case_is_exact_through_the_cli() {
    let d = tmp();
    // Equal stretched distributions on opposite edges of a 2 × 1 rectangle.
    let case = one_block_case(
        33,
        17,
        "curve = { type = \"line\", from = [0, 0], to = [0, 1] }\ndistribution = { type = \"vinokur\", first = 0.002 }",
        "curve = { type = \"line\", from = [2, 0], to = [2, 1] }\ndistribution = { type = \"vinokur\", first = 0.002 }",
        "curve = { type = \"line\", from = [0, 0], to = [2, 0] }\ndistribution = { type = \"geometric\", first = 0.01 }",
        "curve = { type = \"line\", from = [0, 1], to = [2, 1] }\ndistribution = { type = \"geometric\", first = 0.01 }",
    );
    fs::write(d.path().join("rect.toml"), case).unwrap();
    let o = ellipgrid(d.path(), &["run", "rect.toml", "-o", "rect.x"]);
    assert!(o.status.success(), "{}", text(&o));
    let f = read_plot3d(&d.path().join("rect.x")).unwrap();
    let Block::Planar(g) = &f.blocks[0] else {
        panic!("expected a planar block")
    };
    for j in 0..g.nj() {
        for i in 0..g.ni() {
            let p = g.point(i, j);
            assert!((p[0] - g.point(i, 0)[0]).abs() < 1e-12, "x at ({i},{j})");
            assert!((p[1] - g.point(0, j)[1]).abs() < 1e-12, "y at ({i},{j})");
        }
    }
}

const E1: &str = "curve = { type = \"line\", from = [0, 0], to = [0, 1] }";
const E2: &str = "curve = { type = \"line\", from = [1, 0], to = [1, 1] }";
const E3: &str = "curve = { type = \"line\", from = [0, 0], to = [1, 0] }";
const E4: &str = "curve = { type = \"line\", from = [0, 1], to = [1, 1] }";

#[test]
fn bad_inputs_exit_2_with_a_message_and_no_output() {
    // unreadable case file
    let d = tmp();
    let o = ellipgrid(d.path(), &["run", "missing.toml", "-o", "out.x"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("missing.toml"));
    // malformed TOML
    rejects("[[block]\nni = 3", &["bad.toml"]);
    // unknown key
    rejects(
        &square_case(5, 5).replace("ni = 5", "ni = 5\nnj_typo = 3"),
        &["bad.toml", "nj_typo"],
    );
    // too few points
    rejects(&square_case(2, 5), &["block 'b'", "at least 3"]);
    // edges that do not meet
    rejects(
        &one_block_case(
            5,
            5,
            E1,
            "curve = { type = \"line\", from = [1, 0], to = [1.5, 1] }",
            E3,
            E4,
        ),
        &["block 'b'", "do not meet"],
    );
    // mismatched point count on a `nodes` edge
    rejects(
        &one_block_case(
            5,
            5,
            "curve = { type = \"nodes\", points = [[0, 0], [0, 0.5], [0, 1]] }",
            E2,
            E3,
            E4,
        ),
        &["block 'b', edge E1", "3 nodes given", "needs 5"],
    );
    // NaN coordinate
    rejects(
        &one_block_case(
            5,
            5,
            E1,
            E2,
            "curve = { type = \"line\", from = [0, 0], to = [nan, 0] }",
            E4,
        ),
        &["edge E3", "not finite"],
    );
    // zero-length edge
    rejects(
        &one_block_case(
            5,
            5,
            E1,
            E2,
            "curve = { type = \"line\", from = [0, 0], to = [0, 0] }",
            E4,
        ),
        &["edge E3", "zero length"],
    );
    // self-intersecting boundary: E4 dips below E3
    rejects(
        &one_block_case(
            5,
            5,
            E1,
            E2,
            E3,
            "curve = { type = \"polyline\", points = [[0, 1], [0.5, -0.5], [1, 1]] }",
        ),
        &["block 'b'", "intersects itself"],
    );
    // impossible distribution
    rejects(
        &one_block_case(
            5,
            5,
            E1,
            E2,
            &format!("{E3}\ndistribution = {{ type = \"vinokur\", first = 2.0 }}"),
            E4,
        ),
        &["edge E3"],
    );
    // unknown output extension
    let d = tmp();
    fs::write(d.path().join("ok.toml"), square_case(5, 5)).unwrap();
    let o = ellipgrid(d.path(), &["run", "ok.toml", "-o", "out.xyzzy"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("out.xyzzy"));
    // no output named at all
    let o = ellipgrid(d.path(), &["run", "ok.toml"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    // a grid file that is not Plot3D
    fs::write(d.path().join("junk.x"), b"this is not a grid").unwrap();
    let o = ellipgrid(d.path(), &["check", "junk.x"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("junk.x"));
}

#[test]
fn help_on_every_subcommand() {
    let d = tmp();
    for args in [
        vec!["--help"],
        vec!["run", "--help"],
        vec!["check", "--help"],
    ] {
        let o = ellipgrid(d.path(), &args);
        assert!(o.status.success());
        assert!(text(&o).contains("Usage"));
    }
}
