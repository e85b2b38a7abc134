//! Malformed input for every reader (issue #17): Plot3D of every encoding (through `check`,
//! `convert` and `smooth`), VTK `.vts`/`.vtm`, STEP, connectivity files, and the files a case
//! refers to (airfoil tables, Hermite control nets, volume faces). Each case must exit 2 with
//! a message naming the file (and the referring case, block or edge), print no panic, and
//! leave nothing but its inputs in the directory. Sizes, settings and hostile headers are in
//! `malformed_settings.rs`, the fuzzers' finds in `fuzz_regressions.rs`.

mod common;
use common::*;
use ellipgrid::io::plot3d::{self, Encoding, Plot3dFormat};
use ellipgrid::Grid2;
use std::fs;

/// Writes `files` into a fresh directory, runs `args` there and checks: exit 2, every needle
/// in the message, no panic, no file written.
fn refuses(files: &[(&str, Vec<u8>)], args: &[&str], needles: &[&str]) {
    let d = tempfile::tempdir().unwrap();
    for (name, body) in files {
        fs::write(d.path().join(name), body).unwrap();
    }
    let o = ellipgrid(d.path(), args);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {t}");
    for n in needles {
        assert!(t.contains(n), "{args:?}: message lacks '{n}': {t}");
    }
    assert!(!t.contains("panicked"), "{args:?}: {t}");
    let left = fs::read_dir(d.path()).unwrap().count();
    assert_eq!(left, files.len(), "{args:?}: files written");
}

/// A 5 × 4 planar block (2D, multi-block, double) in `encoding`.
fn grid_file(encoding: Encoding) -> Vec<u8> {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("g.x");
    let g = Grid2::<2>::from_fn(5, 4, |i, j| [i as f64 / 4.0, j as f64 / 3.0]);
    let fmt = Plot3dFormat {
        encoding,
        two_d: true,
        ..Plot3dFormat::default()
    };
    plot3d::write_plot3d(&p, &[ellipgrid::io::Block::from(g)], &fmt, None).unwrap();
    fs::read(p).unwrap()
}

#[test]
fn malformed_plot3d_files_in_every_encoding() {
    let unf = grid_file(Encoding::Unformatted);
    let fmtd = String::from_utf8(grid_file(Encoding::Formatted)).unwrap();
    let stream = grid_file(Encoding::Stream);
    let patch = |at: usize, bytes: &[u8]| {
        let mut v = unf.clone();
        v[at..at + bytes.len()].copy_from_slice(bytes);
        v
    };
    // layout: [4] 1 [4] [8] ni nj [8] [320] x(20) y(20) [320]
    let huge = [i32::MAX.to_le_bytes(), i32::MAX.to_le_bytes()].concat();
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (unf[..unf.len() / 2].to_vec(), "(truncated file)"),
        (patch(16, &huge), "absurd dimensions"),
        (patch(24, &999i32.to_le_bytes()), "end marker 999"),
        (patch(48, &f64::NAN.to_le_bytes()), "is not finite"),
        (patch(16, &0i32.to_le_bytes()), "g.x"),
        (
            fmtd.replacen("2.5000000000000000e-1", "2.5e-1x", 1)
                .into_bytes(),
            "'2.5e-1x' is not a number",
        ),
        (
            fmtd.replacen("5 4", "5 -4", 1).into_bytes(),
            "fits no Plot3D layout",
        ),
        (stream[..stream.len() - 7].to_vec(), "no C-stream layout"),
        (Vec::new(), "empty file"),
    ];
    for (body, needle) in cases {
        let files = [("g.x", body)];
        refuses(&files, &["check", "g.x"], &["g.x", needle]);
        refuses(&files, &["convert", "g.x", "o.vts"], &["g.x", needle]);
        refuses(&files, &["smooth", "g.x", "-o", "o.x"], &["g.x", needle]);
    }
}

#[test]
fn malformed_vtk_files_and_indexes() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("g.x"), grid_file(Encoding::Unformatted)).unwrap();
    let o = ellipgrid(d.path(), &["convert", "g.x", "g.vts", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    let vts = fs::read(d.path().join("g.vts")).unwrap();
    let index = |file: &str| {
        format!(
            "<VTKFile type=\"vtkMultiBlockDataSet\"><vtkMultiBlockDataSet>\
             <DataSet index=\"0\" name=\"a\" file=\"{file}\"/></vtkMultiBlockDataSet></VTKFile>"
        )
        .into_bytes()
    };
    let bad_vts = [
        &b"<VTKFile compressor=\"vtkZLibDataCompressor\" "[..],
        &vts["<VTKFile ".len() + vts.windows(9).position(|w| w == b"<VTKFile ").unwrap()..],
    ]
    .concat();
    let cut = vts[..vts.len() / 2].to_vec();
    for (files, needles) in [
        (
            vec![("m.vtm", index("missing.vts"))],
            vec!["m.vtm", "DataSet 1 ('a')", "missing.vts"],
        ),
        (
            vec![(
                "m.vtm",
                b"<VTKFile type=\"vtkMultiBlockDataSet\"></VTKFile>".to_vec(),
            )],
            vec!["m.vtm", "no DataSet"],
        ),
        (
            vec![("m.vtm", index("z.vts")), ("z.vts", bad_vts.clone())],
            vec!["m.vtm", "z.vts", "compressed"],
        ),
        (
            vec![("m.vtm", index("c.vts")), ("c.vts", cut)],
            vec!["m.vtm", "c.vts"],
        ),
    ] {
        refuses(&files, &["convert", "m.vtm", "o.x"], &needles);
    }
    refuses(
        &[("z.vts", bad_vts)],
        &["plot", "z.vts", "-o", "p.png"],
        &["z.vts", "compressed"],
    );
}

#[test]
fn malformed_step_and_connectivity_files() {
    for (body, needle) in [
        (&b"this is not STEP"[..], "not a STEP file"),
        (
            b"ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n\
              FILE_NAME('','',(''),(''),'','','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\n\
              ENDSEC;\nDATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n",
            "no faces found",
        ),
        (&[0xff, 0xfe, 0x00][..], "not UTF-8"),
    ] {
        refuses(
            &[("f.step", body.to_vec())],
            &["step", "list", "f.step"],
            &["f.step", needle],
        );
    }
    let g = grid_file(Encoding::Unformatted);
    for (conn, needle) in [
        ("1\n", "line 2: ends before an interface"),
        ("0\n1\n 1 1 1 1 5\n", "line 3: a patch: expected 8 values"),
        (
            "0\n1\n 1 1 1 1 5 1 1 1\n0\n",
            "family 1 is not in the family list",
        ),
        (
            "0\n1\n 2 1 1 1 5 1 1 1\n1\n1 wall\n",
            "block 2 does not exist",
        ),
        ("0\n1\n 1 1 1 1 9 1 1 1\n1\n1 wall\n", "lies outside block"),
        ("x\n", "line 1: the interface count: 'x' is not an index"),
    ] {
        refuses(
            &[("g.x", g.clone()), ("g.conn", conn.as_bytes().to_vec())],
            &["convert", "g.x", "g.su2", "--conn", "g.conn"],
            &["g.conn", needle],
        );
    }
}

/// A case whose edge E3 is the airfoil table `file`.
fn airfoil_case(file: &str) -> Vec<u8> {
    format!(
        "[[block]]\nname = \"w\"\nni = 9\nnj = 5\n\
         [block.E1]\ncurve = {{ type = \"line\", from = [0, 0], to = [0, 1] }}\n\
         [block.E2]\ncurve = {{ type = \"line\", from = [1, 0], to = [1, 1] }}\n\
         [block.E3]\ncurve = {{ type = \"airfoil\", file = \"{file}\" }}\n\
         [block.E4]\ncurve = {{ type = \"line\", from = [0, 1], to = [1, 1] }}\n"
    )
    .into_bytes()
}

#[test]
fn files_a_case_refers_to_are_named_with_the_case() {
    // airfoil tables: missing, malformed
    refuses(
        &[("c.toml", airfoil_case("nothere.dat"))],
        &["run", "c.toml", "-o", "o.x"],
        &["c.toml: block 'w', edge E3", "nothere.dat"],
    );
    refuses(
        &[
            ("c.toml", airfoil_case("bad.dat")),
            ("bad.dat", b"NACA\n1.0 0.0\n0.5 abc\n".to_vec()),
        ],
        &["run", "c.toml", "-o", "o.x"],
        &["c.toml: block 'w', edge E3", "bad.dat: line 3", "'0.5 abc'"],
    );
    // Hermite control nets: truncated, a block that is not there
    let net = |extra: &str| {
        format!(
            "[[block]]\nname = \"s\"\nkind = \"surface\"\nni = 5\nnj = 5\n\
             surface = {{ type = \"hermite_net\", file = \"net.x\"{extra} }}\n\
             [block.E1]\n[block.E2]\n[block.E3]\n[block.E4]\n"
        )
        .into_bytes()
    };
    let g = grid_file(Encoding::Unformatted);
    refuses(
        &[("c.toml", net("")), ("net.x", g[..g.len() / 2].to_vec())],
        &["run", "c.toml", "-o", "o.x"],
        &["c.toml: block 's'", "net.x", "truncated"],
    );
    refuses(
        &[("c.toml", net(", block = 3")), ("net.x", g.clone())],
        &["run", "c.toml", "-o", "o.x"],
        &[
            "c.toml: block 's'",
            "net.x: block 3",
            "the file has 1 block(s)",
        ],
    );
    // volume faces from a Plot3D file: not six faces, truncated
    let vol = "[[volume]]\nname = \"v\"\nni = 5\nnj = 4\nnk = 3\nfaces = { file = \"f.x\" }\n";
    refuses(
        &[("c.toml", vol.as_bytes().to_vec()), ("f.x", g.clone())],
        &["run", "c.toml", "-o", "o.x"],
        &["c.toml: volume 'v'", "needs 6 face blocks"],
    );
    refuses(
        &[
            ("c.toml", vol.as_bytes().to_vec()),
            ("f.x", g[..40].to_vec()),
        ],
        &["run", "c.toml", "-o", "o.x"],
        &["c.toml: volume 'v'", "f.x"],
    );
}
