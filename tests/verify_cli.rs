//! `ellipgrid verify` through the command line (issue #20): the table, the JSON report and the
//! family files of a passing case (exit 0; the coarsest grid is `run`'s, bit for bit); exit 5
//! and the failing property named when the parametrization-dependent initial grid is
//! verified; exit 2 and no file on bad input; the same report on 1 and 2 threads.

mod common;
use common::*;
use ellipgrid::io::plot3d::read_plot3d;
use std::fs;
use std::path::Path;
use std::process::Command;

/// The shipped curved quadrilateral at 17 × 13 nodes, written to `dir`.
fn small_curved(dir: &Path) {
    let text = fs::read_to_string(root().join("examples/curved.toml"))
        .unwrap()
        .replace("ni = 65", "ni = 17")
        .replace("nj = 49", "nj = 13");
    fs::write(dir.join("curved.toml"), text).unwrap();
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn a_passing_case_prints_its_table_writes_its_report_and_its_family() {
    let d = tempfile::tempdir().unwrap();
    small_curved(d.path());
    let o = ellipgrid(
        d.path(),
        &[
            "verify",
            "curved.toml",
            "--report",
            "v.json",
            "--write-family",
            "fam",
            "--family-format",
            "x,vts",
        ],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    for needle in [
        "block 'curved' (planar, 17 × 13): pass",
        "17 × 13 → 33 × 25",
        "33 × 25 → 65 × 49",
        "p = ",
        "start grid: scrambled (seed 20",
        "pass: 1 of 1 blocks pass",
        "wrote fam/curved_L2.vts",
    ] {
        assert!(t.contains(needle), "no '{needle}' in:\n{t}");
    }
    let r = json(&d.path().join("v.json"));
    assert_eq!(r["pass"], true);
    assert_eq!(r["seed"], 20);
    assert_eq!(r["levels"].as_array().unwrap().len(), 3);
    let b = &r["blocks"][0];
    assert_eq!(b["kind"], "planar");
    let p = b["family"]["order_rms"][0].as_f64().unwrap();
    assert!(p > 1.8, "{p}");
    assert!(b["start"]["difference"]["max"].as_f64().unwrap() < 1e-9);
    assert_eq!(r["family"].as_array().unwrap().len(), 6);
    // the family: three levels, nested sizes; level 0 is what `run` writes, bit for bit
    for (l, n) in [(0, [17, 13]), (1, [33, 25]), (2, [65, 49])] {
        let f = read_plot3d(&d.path().join(format!("fam/curved_L{l}.x"))).unwrap();
        assert_eq!(f.blocks[0].dims(), [n[0], n[1], 1]);
        assert!(d.path().join(format!("fam/curved_L{l}.vts")).exists());
    }
    let o = ellipgrid(d.path(), &["run", "curved.toml", "-o", "run.x", "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert_eq!(
        fs::read(d.path().join("run.x")).unwrap(),
        fs::read(d.path().join("fam/curved_L0.x")).unwrap()
    );
}

#[test]
fn the_initial_surface_grid_fails_with_exit_5_naming_the_property() {
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/wing_pylon.toml");
    let case = case.to_str().unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "verify",
            case,
            "--surface-grid",
            "initial",
            "--report",
            "bad.json",
            "--write-family",
            "fam",
        ],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(5), "{t}");
    assert!(
        t.contains("block 'wing_pylon' (surface, 129 × 65): FAIL"),
        "{t}"
    );
    assert!(
        t.contains("error:") && t.contains("block 'wing_pylon': parametrization: observed order"),
        "{t}"
    );
    let r = json(&d.path().join("bad.json"));
    assert_eq!(r["pass"], false);
    assert_eq!(r["surface_grid"], "initial");
    assert_eq!(r["blocks"][0]["parametrization"]["pass"], false);
    // the family is written all the same (the grids are fine; the property is not)
    assert!(d.path().join("fam/wing_pylon_L2.x").exists());
    // the Section 4 grid of the same case passes, quietly
    let o = ellipgrid(d.path(), &["verify", case, "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(o.stdout.is_empty());
}

#[test]
fn bad_input_exits_2_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    small_curved(d.path());
    let nodes = one_block_case(
        5,
        3,
        "curve = { type = \"line\", from = [0, 0], to = [0, 2] }",
        "curve = { type = \"line\", from = [4, 0], to = [4, 2] }",
        "curve = { type = \"line\", from = [0, 0], to = [4, 0] }",
        "curve = { type = \"nodes\", points = [[0, 2], [1, 2], [2, 2], [3, 2], [4, 2]] }",
    );
    fs::write(d.path().join("nodes.toml"), nodes).unwrap();
    for (args, needle) in [
        (
            vec!["verify", "curved.toml", "--levels", "2"],
            "needs 3 grids",
        ),
        (vec!["verify", "nodes.toml"], "block 'b', edge E4"),
        (vec!["verify", "missing.toml"], "missing.toml"),
        (
            vec![
                "verify",
                "curved.toml",
                "--write-family",
                "fam",
                "--family-format",
                "xyz,png,bad",
            ],
            "unknown output extension",
        ),
    ] {
        let mut a = args.clone();
        a.extend(["--report", "r.json"]);
        let o = ellipgrid(d.path(), &a);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {t}");
        assert!(
            t.contains(needle) && !t.contains("panicked"),
            "{args:?}: {t}"
        );
        assert!(!d.path().join("r.json").exists(), "{args:?}");
        let fam = d.path().join("fam");
        assert!(
            !fam.exists() || fs::read_dir(&fam).unwrap().next().is_none(),
            "{args:?}"
        );
    }
}

#[test]
fn the_report_is_the_same_on_one_and_two_threads() {
    let d = tempfile::tempdir().unwrap();
    small_curved(d.path());
    let mut blocks = Vec::new();
    for (threads, name) in [("1", "a.json"), ("2", "b.json")] {
        let o = Command::new(env!("CARGO_BIN_EXE_ellipgrid"))
            .args(["verify", "curved.toml", "--quiet", "--report", name])
            .env("RAYON_NUM_THREADS", threads)
            .current_dir(d.path())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{}", text(&o));
        blocks.push(json(&d.path().join(name))["blocks"].clone());
    }
    assert_eq!(blocks[0], blocks[1]);
}
