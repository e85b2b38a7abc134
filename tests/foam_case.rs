//! Runnable OpenFOAM cases (#19 "Beyond"): `DIR/NAME.foam` as an output writes the polyMesh
//! and the `system/`, `constant/` and `0/` files of a steady incompressible case, with the
//! boundary conditions of each family's kind. Known answers: the patches of `0/U` and `0/p`
//! are the polyMesh's, each with the condition of its kind; the polyMesh is byte for byte the
//! one a `polyMesh` output writes; a family without a kind is refused with nothing written;
//! the flow of `[flow]` and of `convert`'s flags is the one written into `0/U` and `nu`, and
//! bad flow values exit 2 naming the key, with nothing written. (`.ci/check_meshes.py` runs OpenFOAM's checkMesh and 200 simpleFoam iterations on the
//! shipped airfoil C-grid's case.)

mod common;

use common::{ellipgrid, root, text};
use ellipgrid::io::connectivity::ConnFile;
use ellipgrid::io::foam_case::CASE_FILES;
use ellipgrid::io::plot3d::Plot3dFormat;
use ellipgrid::io::Block;
use ellipgrid::job::{write_outputs_with, MeshOptions};
use ellipgrid::Grid2;
use std::path::Path;

fn rect(x0: f64, ni: usize, nj: usize) -> Block {
    Block::Planar(Grid2::from_fn(ni, nj, |i, j| {
        [x0 + i as f64 / (ni - 1) as f64, j as f64 / (nj - 1) as f64]
    }))
}

/// Two unit squares side by side sharing x = 1: a channel with an inflow at x = 0, an
/// outflow at x = 2, walls below, a symmetry plane above.
fn channel() -> (Vec<(String, Block)>, ConnFile) {
    let blocks = vec![
        ("a".to_string(), rect(0.0, 3, 3)),
        ("b".to_string(), rect(1.0, 3, 3)),
    ];
    let conn = ConnFile {
        interfaces: vec![[(1, [3, 1, 1], [3, 3, 1]), (2, [1, 1, 1], [1, 3, 1])]],
        patches: vec![
            ((1, [1, 1, 1], [1, 3, 1]), 1),
            ((1, [1, 1, 1], [3, 1, 1]), 2),
            ((1, [1, 3, 1], [3, 3, 1]), 4),
            ((2, [3, 1, 1], [3, 3, 1]), 3),
            ((2, [1, 1, 1], [3, 1, 1]), 2),
            ((2, [1, 3, 1], [3, 3, 1]), 4),
        ],
        families: vec![
            (1, "inlet".into()),
            (2, "floor wall".into()),
            (3, "outlet".into()),
            (4, "top".into()),
        ],
        // "top" would be general by its name: the .conn's kinds section makes it a symmetry
        bcs: vec![(4, ellipgrid::io::mesh::BcKind::Symmetry)],
    };
    (blocks, conn)
}

/// The entries of `boundaryField` in an OpenFOAM field file: (patch, its dictionary's text).
fn boundary_field(path: &Path) -> Vec<(String, String)> {
    let t = std::fs::read_to_string(path).unwrap();
    let body = &t[t.find("boundaryField").expect("a boundaryField")..];
    let mut out = Vec::new();
    let mut rest = &body[body.find('{').unwrap() + 1..];
    while let Some(open) = rest.find('{') {
        let name = rest[..open].trim().to_string();
        let close = open + rest[open..].find('}').unwrap();
        out.push((name, rest[open + 1..close].trim().to_string()));
        rest = &rest[close + 1..];
    }
    out
}

/// The patch names and types of a polyMesh `boundary` file.
fn patches(boundary: &Path) -> Vec<(String, String)> {
    let t = std::fs::read_to_string(boundary).unwrap();
    let lines: Vec<&str> = t.lines().map(str::trim).collect();
    let mut out = Vec::new();
    for (k, l) in lines.iter().enumerate() {
        if let Some(ty) = l.strip_prefix("type") {
            let name = lines[k - 2].to_string();
            out.push((name, ty.trim().trim_end_matches(';').to_string()));
        }
    }
    out
}

#[test]
fn a_case_has_every_file_and_the_condition_of_every_family_kind() {
    let d = tempfile::tempdir().unwrap();
    let (blocks, conn) = channel();
    let case = d.path().join("channel").join("channel.foam");
    let mesh = MeshOptions::with_span(0.25, "test").unwrap();
    let fmt = Plot3dFormat::default();
    let written = write_outputs_with(
        &blocks,
        Some(&conn),
        std::slice::from_ref(&case),
        &fmt,
        &mesh,
    )
    .unwrap();
    let dir = d.path().join("channel");
    for f in CASE_FILES {
        assert!(
            written.contains(&dir.join(f)),
            "{f} not listed: {written:?}"
        );
    }
    assert!(written.contains(&case));
    assert_eq!(
        std::fs::read(&case).unwrap(),
        b"",
        "the .foam file is empty"
    );
    // The polyMesh is the one a polyMesh output writes, byte for byte.
    let pm = d.path().join("direct").join("polyMesh");
    write_outputs_with(&blocks, Some(&conn), std::slice::from_ref(&pm), &fmt, &mesh).unwrap();
    for f in ["points", "faces", "owner", "neighbour", "boundary"] {
        let a = std::fs::read(dir.join("constant/polyMesh").join(f)).unwrap();
        assert_eq!(a, std::fs::read(pm.join(f)).unwrap(), "{f}");
    }
    // Patch types and both fields' conditions, patch for patch.
    let types = patches(&dir.join("constant/polyMesh/boundary"));
    let names: Vec<&str> = types.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        ["inlet", "floor_wall", "outlet", "top", "frontAndBack"]
    );
    let u = boundary_field(&dir.join("0/U"));
    let p = boundary_field(&dir.join("0/p"));
    let un: Vec<&str> = u.iter().map(|(n, _)| n.as_str()).collect();
    let pn: Vec<&str> = p.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(un, names);
    assert_eq!(pn, names);
    let want = [
        (
            "patch",
            "type fixedValue; value uniform (1 0 0);",
            "type zeroGradient;",
        ),
        ("wall", "type noSlip;", "type zeroGradient;"),
        (
            "patch",
            "type inletOutlet; inletValue uniform (0 0 0); value uniform (1 0 0);",
            "type fixedValue; value uniform 0;",
        ),
        ("symmetry", "type symmetry;", "type symmetry;"),
        ("empty", "type empty;", "type empty;"),
    ];
    for (k, (ty, uc, pc)) in want.iter().enumerate() {
        assert_eq!(types[k].1, *ty, "{}", names[k]);
        assert_eq!(u[k].1, *uc, "U on {}", names[k]);
        assert_eq!(p[k].1, *pc, "p on {}", names[k]);
    }
    let control = std::fs::read_to_string(dir.join("system/controlDict")).unwrap();
    assert!(control.contains("application     simpleFoam;"));
    let turb = std::fs::read_to_string(dir.join("constant/turbulenceProperties")).unwrap();
    assert!(turb.contains("simulationType  laminar;"));
    let tp = std::fs::read_to_string(dir.join("constant/transportProperties")).unwrap();
    assert!(tp.contains("nu              1e-3;"), "{tp}");
    // The extrusion span: z of the points from 0 to 0.25.
    let pts = std::fs::read_to_string(dir.join("constant/polyMesh/points")).unwrap();
    assert!(pts.contains("(0 0 0.25)") && pts.contains("(2 1 0)"));
}

#[test]
fn the_airfoil_c_grid_case_through_the_cli() {
    let d = tempfile::tempdir().unwrap();
    let ex = root().join("examples/rae2822_cgrid.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "-q",
            ex.to_str().unwrap(),
            "-o",
            "rae/rae.foam",
            "-o",
            "rae.x",
            "-o",
            "rae.conn",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let u = boundary_field(&d.path().join("rae/0/U"));
    let kinds: Vec<(&str, &str)> = u
        .iter()
        .map(|(n, c)| (n.as_str(), c.split(';').next().unwrap()))
        .collect();
    assert_eq!(
        kinds,
        [
            ("airfoil", "type noSlip"),
            ("farfield", "type freestreamVelocity"),
            ("outflow", "type inletOutlet"),
            ("frontAndBack", "type empty"),
        ]
    );
    let p = boundary_field(&d.path().join("rae/0/p"));
    assert_eq!(
        p[1].1,
        "type freestreamPressure; freestreamValue uniform 0;"
    );
    // convert writes the same case from the grid and its .conn (found beside it), binary and
    // with a span.
    let o = ellipgrid(
        d.path(),
        &[
            "convert",
            "-q",
            "rae.x",
            "thin/rae.foam",
            "--span",
            "0.01",
            "--foam-format",
            "binary",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    for f in CASE_FILES {
        let a = std::fs::read(d.path().join("rae").join(f)).unwrap();
        assert_eq!(
            a,
            std::fs::read(d.path().join("thin").join(f)).unwrap(),
            "{f}"
        );
    }
    let pts = std::fs::read(d.path().join("thin/constant/polyMesh/points")).unwrap();
    assert!(String::from_utf8_lossy(&pts[..600]).contains("format      binary;"));
    // A bad span is refused, naming the option.
    let o = ellipgrid(
        d.path(),
        &["convert", "rae.x", "bad/rae.foam", "--span", "0"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--span"), "{}", text(&o));
    assert!(!d.path().join("bad").exists());
}

#[test]
fn a_family_without_a_kind_is_refused_and_nothing_is_written() {
    let d = tempfile::tempdir().unwrap();
    // Without a topology every block side is a family of its own, of kind general.
    std::fs::write(d.path().join("sq.toml"), common::square_case(5, 4)).unwrap();
    let o = ellipgrid(
        d.path(),
        &["run", "sq.toml", "-o", "out.x", "-o", "sq/sq.foam"],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(
        t.contains("sq/sq.foam")
            && t.contains("'b_E1', 'b_E2', 'b_E3', 'b_E4' are of kind general")
            && t.contains("bc = \"wall\""),
        "{t}"
    );
    assert!(!d.path().join("out.x").exists(), "a partial output");
    let left: Vec<_> = walk(&d.path().join("sq"));
    assert!(left.is_empty(), "files left: {left:?}");
}

/// Every file under `dir` (none if it does not exist).
fn walk(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    if let Ok(rd) = std::fs::read_dir(dir) {
        for e in rd {
            let p = e.unwrap().path();
            if p.is_dir() {
                out.extend(walk(&p));
            } else {
                out.push(p);
            }
        }
    }
    out
}

/// The text of a case file in `dir`.
fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap()
}

#[test]
fn the_flow_options_are_written_into_u_the_far_field_and_nu() {
    let d = tempfile::tempdir().unwrap();
    // The C-grid with a [flow] table: 4 degrees, speed 2, Reynolds number 500 on a length
    // of 0.5: nu = 2 * 0.5 / 500 = 2e-3.
    let toml = std::fs::read_to_string(root().join("examples/rae2822_cgrid.toml"))
        .unwrap()
        .replace(
            "../data/rae2822.dat",
            root().join("data/rae2822.dat").to_str().unwrap(),
        )
        + "\n[flow]\nspeed = 2\nalpha = 4\nreynolds = 500\nlength = 0.5\n";
    std::fs::write(d.path().join("c.toml"), &toml).unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "run", "-q", "c.toml", "-o", "a/c.foam", "-o", "c.x", "-o", "c.conn",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let a = 4f64.to_radians();
    let u = format!("uniform ({} {} 0)", 2.0 * a.cos(), 2.0 * a.sin());
    let dir = d.path().join("a");
    assert!(read(&dir, "0/U").contains(&format!("internalField   {u};")));
    let bcs = boundary_field(&dir.join("0/U"));
    assert_eq!(
        bcs[1],
        (
            "farfield".to_string(),
            format!("type freestreamVelocity; freestreamValue {u};")
        )
    );
    assert!(bcs[2].1.ends_with(&format!("value {u};")), "{}", bcs[2].1);
    assert!(read(&dir, "constant/transportProperties").contains("nu              2e-3;"));
    // The same flow by convert's flags, with nu given directly: the same files.
    let o = ellipgrid(
        d.path(),
        &[
            "convert", "-q", "c.x", "b/c.foam", "--speed", "2", "--alpha", "4", "--nu", "2e-3",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    for f in CASE_FILES {
        assert_eq!(read(&dir, f), read(&d.path().join("b"), f), "{f}");
    }
    // convert of the case file itself takes its [flow]: the same files as run wrote.
    let o = ellipgrid(d.path(), &["convert", "-q", "c.toml", "t/c.foam"]);
    assert!(o.status.success(), "{}", text(&o));
    for f in CASE_FILES {
        assert_eq!(read(&dir, f), read(&d.path().join("t"), f), "{f}");
    }
    // Flags win key by key: --alpha replaces 4 degrees, the speed and the Reynolds number
    // stay the case's; --nu replaces the case's reynolds and length as one group.
    let o = ellipgrid(
        d.path(),
        &[
            "convert", "-q", "c.toml", "f/c.foam", "--alpha", "1", "--nu", "5e-3",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let a = 1f64.to_radians();
    let f = d.path().join("f");
    assert!(read(&f, "0/U").contains(&format!(
        "internalField   uniform ({} {} 0);",
        2.0 * a.cos(),
        2.0 * a.sin()
    )));
    assert!(read(&f, "constant/transportProperties").contains("nu              5e-3;"));
    // A negative angle (the flag takes negative numbers) and the default viscosity.
    let o = ellipgrid(
        d.path(),
        &["convert", "-q", "c.x", "n/c.foam", "--alpha", "-2.5"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let a = (-2.5f64).to_radians();
    assert!(read(&d.path().join("n"), "0/U").contains(&format!(
        "internalField   uniform ({} {} 0);",
        a.cos(),
        a.sin()
    )));
    assert!(read(&d.path().join("n"), "constant/transportProperties").contains("1e-3;"));
}

#[test]
fn bad_flow_values_exit_2_naming_the_key_and_write_nothing() {
    let d = tempfile::tempdir().unwrap();
    let ex = root().join("examples/rae2822_cgrid.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "-q",
            ex.to_str().unwrap(),
            "-o",
            "c.x",
            "-o",
            "c.conn",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    for (args, key) in [
        (&["--alpha", "95"][..], "--alpha = 95"),
        (&["--alpha", "NaN"][..], "--alpha = NaN"),
        (&["--speed", "-1"][..], "--speed = -1"),
        (&["--nu", "0"][..], "--nu = 0"),
        (&["--reynolds", "inf"][..], "--reynolds = inf"),
        (&["--length", "2"][..], "--length = 2"),
        (
            &["--nu", "1e-3", "--reynolds", "100"][..],
            "--nu and --reynolds",
        ),
        // a planar grid's flow lies in its plane
        (&["--sideslip", "3"][..], "sideslip = 3"),
    ] {
        let mut a = vec!["convert", "c.x", "bad/c.foam"];
        a.extend_from_slice(args);
        let o = ellipgrid(d.path(), &a);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        assert!(text(&o).contains(key), "{args:?}: {}", text(&o));
        assert!(!d.path().join("bad").exists(), "{args:?}: files written");
    }
    // Flow flags on another output are refused.
    let o = ellipgrid(d.path(), &["convert", "c.x", "c.su2", "--alpha", "2"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--alpha"), "{}", text(&o));
    // In a case file: the table and the key are named; unknown keys are refused.
    let toml = std::fs::read_to_string(&ex).unwrap().replace(
        "../data/rae2822.dat",
        root().join("data/rae2822.dat").to_str().unwrap(),
    );
    for (flow, key) in [
        ("alpha = -120", "alpha = -120"),
        ("nu = -1e-3", "nu = -0.001"),
        ("mach = 0.5", "mach"),
    ] {
        std::fs::write(d.path().join("f.toml"), format!("{toml}\n[flow]\n{flow}\n")).unwrap();
        let o = ellipgrid(
            d.path(),
            &["run", "f.toml", "-o", "out/c.foam", "-o", "f.x"],
        );
        assert_eq!(o.status.code(), Some(2), "{flow}: {}", text(&o));
        assert!(
            text(&o).contains(key) && text(&o).contains("f.toml"),
            "{flow}: {}",
            text(&o)
        );
        assert!(!d.path().join("out").exists() && !d.path().join("f.x").exists());
    }
}
