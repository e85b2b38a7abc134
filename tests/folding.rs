//! Grids that fold: exit code 3, a report naming the folded cells, and no grid file unless
//! `--allow-folded`; `check` flags folded grids read from Plot3D.

mod common;
#[path = "../examples/common/square_cap.rs"]
mod square_cap;
use common::*;
use ellipgrid::io::plot3d::{write_plot3d, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::Grid2;
use std::fs;

/// A coarse block whose roof has a narrow notch reaching almost to the floor: with 5 × 3 nodes
/// the interior nodes cannot be placed without folding cells next to the notch.
fn folding_case() -> String {
    one_block_case(
        5,
        3,
        "curve = { type = \"line\", from = [0, 0], to = [0, 2] }",
        "curve = { type = \"line\", from = [4, 0], to = [4, 2] }",
        "curve = { type = \"line\", from = [0, 0], to = [4, 0] }",
        "curve = { type = \"nodes\", points = [[0, 2], [2.0, 0.02], [2.02, 1.99], [3, 1.99], [4, 2]] }",
    )
}

#[test]
fn a_folded_result_exits_3_and_writes_no_grid() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("fold.toml"), folding_case()).unwrap();
    let o = ellipgrid(
        d.path(),
        &["run", "fold.toml", "-o", "g.x", "--report", "r.json"],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(3), "{t}");
    assert!(t.contains("folds") && t.contains("cell ("), "{t}");
    assert!(!d.path().join("g.x").exists());
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    assert!(r["blocks"][0]["quality"]["folded_cells"].as_u64().unwrap() > 0);
    assert!(r["outputs"].as_array().unwrap().is_empty());
    // --allow-folded writes it, still with exit code 3
    let o = ellipgrid(
        d.path(),
        &["run", "fold.toml", "-o", "g.x", "--allow-folded"],
    );
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(d.path().join("g.x").exists());
}

#[test]
fn check_flags_a_folded_plot3d_grid() {
    let d = tempfile::tempdir().unwrap();
    let mut g = Grid2::<2>::from_fn(5, 4, |i, j| [i as f64, j as f64]);
    g.set(2, 1, [2.0, 2.5]); // pushed across its upper neighbour
    let path = d.path().join("f.x");
    write_plot3d(&path, &[Block::Planar(g)], &Plot3dFormat::default(), None).unwrap();
    let o = ellipgrid(d.path(), &["check", "f.x", "--report", "q.json"]);
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(text(&o).contains("cell ("));
    assert!(d.path().join("q.json").exists());
}

#[test]
fn a_failed_run_leaves_no_output_at_all() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("fold.toml"), folding_case()).unwrap();
    // The start grid waits for the run: a fold (exit 3) writes neither it nor the grid.
    let o = ellipgrid(
        d.path(),
        &["run", "fold.toml", "-o", "g.x", "--write-start", "start.x"],
    );
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(!d.path().join("start.x").exists() && !d.path().join("g.x").exists());
    // ... nor says it did.
    assert!(!text(&o).contains("wrote"), "{}", text(&o));
    // With --allow-folded both are written (exit code still 3).
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "fold.toml",
            "-o",
            "g.x",
            "--write-start",
            "start.x",
            "--allow-folded",
        ],
    );
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(d.path().join("start.x").exists() && d.path().join("g.x").exists());
    // An output that fails after an earlier one was written (two blocks do not fit one .vts)
    // leaves neither, and no temporary file.
    let e = tempfile::tempdir().unwrap();
    let two = format!(
        "{}{}",
        square_case(5, 5),
        square_case(5, 5).replace("\"b\"", "\"c\"")
    );
    fs::write(e.path().join("two.toml"), two).unwrap();
    let o = ellipgrid(e.path(), &["run", "two.toml", "-o", "g.x", "-o", "g.vts"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(t.contains("g.vts") && t.contains(".vtm"), "{t}");
    let left: Vec<_> = fs::read_dir(e.path())
        .unwrap()
        .map(|f| f.unwrap().file_name())
        .collect();
    assert_eq!(left, vec![std::ffi::OsString::from("two.toml")], "{left:?}");
}

/// The shipped dented square (the Gmsh benchmark's hard domain, #16): its transfinite start
/// grid folds (9266 of 65536 cells, the count Gmsh's transfinite mesher gives too), the
/// elliptic grid does not.
#[test]
fn the_dented_square_folds_at_the_start_and_not_at_the_end() {
    let d = tempfile::tempdir().unwrap();
    let ex = root().join("examples/dented_square.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            ex.to_str().unwrap(),
            "-o",
            "g.x",
            "--write-start",
            "s.x",
            "--report",
            "r.json",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    assert_eq!(r["blocks"][0]["quality"]["folded_cells"].as_u64(), Some(0));
    let o = ellipgrid(d.path(), &["check", "s.x", "--report", "s.json"]);
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    let s: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(
        s["blocks"][0]["quality"]["folded_cells"].as_u64(),
        Some(9266)
    );
}

/// The dented top edge of `bench_memory`'s `dented:N` case as a case-file curve.
fn square_cap_edge(n: usize) -> String {
    let pts: Vec<String> = square_cap::square_cap_top(n)
        .iter()
        .map(|p| format!("[{:.12}, {:.12}]", p[0], p[1]))
        .collect();
    format!(
        "curve = {{ type = \"polyline\", points = [{}] }}",
        pts.join(", ")
    )
}

/// The bench's square-cap dent (#16): with the algebraic control functions the converged grid folds
/// next to the cap's two reentrant corners (108 cells at 257², docs/PERFORMANCE.md "Memory"); with
/// orthogonality at the dented edge (Section 2.4) it is fold-free with a smallest scaled Jacobian
/// of 0.446.
#[test]
fn a_square_cap_dent_folds_at_its_reentrant_corners_unless_its_edge_is_orthogonal() {
    let n = 257;
    let case = one_block_case(
        n,
        n,
        "curve = { type = \"line\", from = [0, 0], to = [0, 1] }",
        "curve = { type = \"line\", from = [1, 0], to = [1, 1] }",
        "curve = { type = \"line\", from = [0, 0], to = [1, 0] }",
        &square_cap_edge(n),
    );
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("cap.toml"), &case).unwrap();
    let o = ellipgrid(
        d.path(),
        &["run", "cap.toml", "-o", "g.x", "--report", "r.json"],
    );
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    let folded = r["blocks"][0]["quality"]["folded_cells"].as_u64().unwrap();
    assert!((50..200).contains(&folded), "{folded} folded cells");
    let ortho = case.replace("nj = 257\n", "nj = 257\northogonal = [\"E4\"]\n");
    assert_ne!(ortho, case);
    fs::write(d.path().join("ortho.toml"), ortho).unwrap();
    let o = ellipgrid(
        d.path(),
        &["run", "ortho.toml", "-o", "g.x", "--report", "r.json"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    let q = &r["blocks"][0]["quality"];
    assert_eq!(q["folded_cells"].as_u64(), Some(0));
    let sj = q["scaled_jacobian_min"].as_f64().unwrap();
    assert!(sj > 0.4, "smallest scaled Jacobian {sj}");
}
