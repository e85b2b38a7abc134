//! Regressions from fuzzing (issue #17; `bench/fuzz.sh`, targets in `fuzz/src/lib.rs`). Every
//! input that made a fuzz target panic or abort is kept in `tests/data/fuzz/` and run here,
//! through the library (the path the fuzz target took) and through the command line: each
//! must give a clear error (exit 2 naming the file and the place), no panic, and no output
//! file. The file's name says which reader takes it (by extension) and the class of bug.

mod common;
use common::*;
use ellipgrid::io::connectivity;
use ellipgrid::io::mesh::Mesh;
use ellipgrid::io::plot3d::{self, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::{Grid2, Grid3};
use std::path::{Path, PathBuf};

fn corpus() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join("tests/data/fuzz"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

/// Named blocks, as the mesh builder takes them.
type Named = Vec<(String, Block)>;

/// The fixed blocks of the fuzz target `conn` (fuzz/src/lib.rs): two planar blocks of 4 × 3
/// nodes meeting at x = 1, and two volume blocks of 4 × 3 × 2 likewise.
fn conn_blocks() -> (Named, Named) {
    let planar = |x0: f64| {
        Block::Planar(Grid2::<2>::from_fn(4, 3, |i, j| {
            [x0 + i as f64 / 3.0, j as f64 / 2.0]
        }))
    };
    let volume = |x0: f64| {
        Block::Volume(Grid3::from_fn(4, 3, 2, |i, j, k| {
            [x0 + i as f64 / 3.0, j as f64 / 2.0, k as f64]
        }))
    };
    (
        vec![("a".into(), planar(0.0)), ("b".into(), planar(1.0))],
        vec![("a".into(), volume(0.0)), ("b".into(), volume(1.0))],
    )
}

/// Runs the library path of the fuzz target that found `file`; returns the error messages
/// (every step of the path that did not fail is fine too).
fn library_errors(file: &Path) -> Vec<String> {
    let bytes = std::fs::read(file).unwrap();
    let text = String::from_utf8_lossy(&bytes);
    let ext = file.extension().and_then(|e| e.to_str()).unwrap_or("");
    let err = |r: Result<_, ellipgrid::Error>| r.err().map(|e: ellipgrid::Error| e.to_string());
    match ext {
        "conn" => match connectivity::parse(&text, file) {
            Err(e) => vec![e.to_string()],
            Ok(c) => {
                let (planar, volume) = conn_blocks();
                [
                    err(Mesh::build("p", &planar, &c, None).map(|_| ())),
                    err(Mesh::build("p", &planar, &c, Some(0.1)).map(|_| ())),
                    err(Mesh::build("p", &volume, &c, None).map(|_| ())),
                ]
                .into_iter()
                .flatten()
                .collect()
            }
        },
        "x" => err(plot3d::parse_plot3d(&bytes, file).map(|_| ()))
            .into_iter()
            .collect(),
        "vts" => err(ellipgrid::io::vtk_read::vts_from_bytes(&bytes, file).map(|_| ()))
            .into_iter()
            .collect(),
        "step" => err(ellipgrid::cad::step_faces_from_text(&text, file).map(|_| ()))
            .into_iter()
            .collect(),
        "toml" => err(ellipgrid::case::LoadedCase::parse(&text, file)
            .and_then(|c| ellipgrid::job::start_grids(&c).map(|_| ())))
        .into_iter()
        .collect(),
        _ => panic!("{}: no reader for this extension", file.display()),
    }
}

#[test]
fn every_fuzz_regression_is_a_clear_library_error() {
    let files = corpus();
    assert!(!files.is_empty());
    for f in files {
        let errors = library_errors(&f);
        assert!(!errors.is_empty(), "{}: accepted", f.display());
        for e in errors {
            assert!(!e.is_empty() && !e.contains("panicked"), "{e}");
        }
    }
}

/// Writes the conn target's planar blocks as `blocks.x` in `dir`.
fn write_planar_blocks(dir: &Path) {
    let (planar, _) = conn_blocks();
    let only: Vec<Block> = planar.into_iter().map(|(_, b)| b).collect();
    let fmt = Plot3dFormat {
        two_d: true,
        ..Plot3dFormat::default()
    };
    plot3d::write_plot3d(&dir.join("blocks.x"), &only, &fmt, None).unwrap();
}

/// `convert blocks.x OUT --conn FILE`: exit 2, the message holds `needles`, no panic, and
/// nothing but the inputs in the directory afterwards.
fn convert_rejects(conn: &str, out: &str, needles: &[&str]) {
    let d = tempfile::tempdir().unwrap();
    write_planar_blocks(d.path());
    std::fs::copy(
        root().join("tests/data/fuzz").join(conn),
        d.path().join(conn),
    )
    .unwrap();
    let o = ellipgrid(d.path(), &["convert", "blocks.x", out, "--conn", conn]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{conn} → {out}: {t}");
    for n in needles {
        assert!(t.contains(n), "{conn} → {out}: message lacks '{n}': {t}");
    }
    assert!(!t.contains("panicked"), "{t}");
    let mut left: Vec<String> = std::fs::read_dir(d.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["blocks.x", conn], "{conn} → {out}: files written");
}

#[test]
fn connectivity_numbers_out_of_range_are_refused_when_read() {
    // A family id of 2⁶⁴ − 1 overflowed `max id + 1` when the front-and-back family of an
    // extruded (OpenFOAM) mesh was added. Every count, index and id is now 0/1 to 2³¹.
    convert_rejects(
        "conn_family_id_max.conn",
        "case/constant/polyMesh",
        &[
            "conn_family_id_max.conn",
            "line 8",
            "family line starts with its id",
        ],
    );
    let d = tempfile::tempdir().unwrap();
    for (body, needle) in [
        (
            "1\n 0 4 1 1 4 3 1\n",
            "line 2: an interface: '0' is not an index",
        ),
        (
            "0\n1\n 1 1 1 1 4 1 99999999999 1\n",
            "'99999999999' is not an index",
        ),
        ("0\n0\n", "line 3: ends before the family count"),
        (
            "0\n0\n1\n18446744073709551615 wall\n",
            "line 4: a family line starts with its id (1 to 2147483648)",
        ),
    ] {
        let e = connectivity::parse(body, &d.path().join("c.conn"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("c.conn") && e.contains(needle), "{e}");
    }
}

#[test]
fn connectivity_ranges_off_the_block_sides_are_refused() {
    // The whole planar block (1,1,1)…(4,3,1) as an interface side: extruded through k for
    // OpenFOAM it varied in three directions and the node pairing indexed past its two
    // in-face steps (index out of bounds). A range must lie on a block side.
    for out in ["case/constant/polyMesh", "m.su2", "m.msh"] {
        convert_rejects(
            "conn_range_not_a_side.conn",
            out,
            &[
                "interface 1",
                "is not on a side of block 'block1'",
                "one index must stay at 1 or at its last value",
            ],
        );
    }
}

#[test]
fn step_reference_cycles_are_refused_before_the_reader_recurses_into_them() {
    // Found by the `step` target: a SURFACE_CURVE whose 3D curve is the SURFACE_CURVE itself.
    // truck-stepio resolves references by recursion and overflowed the stack (an abort that
    // no panic handler sees). The pre-scan now refuses reference cycles and chains deeper
    // than 256.
    let d = tempfile::tempdir().unwrap();
    let name = "step_surface_curve_cycle.step";
    std::fs::copy(
        root().join("tests/data/fuzz").join(name),
        d.path().join(name),
    )
    .unwrap();
    for args in [
        &["step", "list", name][..],
        &["step", "grid", name, "--all", "-o", "g.x"],
    ] {
        let o = ellipgrid(d.path(), args);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {t}");
        assert!(
            t.contains(name) && t.contains("entity references form a cycle: #26 → #26"),
            "{t}"
        );
        assert!(!t.contains("overflow") && !t.contains("panicked"), "{t}");
    }
    assert_eq!(std::fs::read_dir(d.path()).unwrap().count(), 1);
}
