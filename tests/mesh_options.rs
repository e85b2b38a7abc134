//! Options of the solver meshes (#19): boundary conditions given per family in the case file
//! (`bc = "wall"` on an edge, over the name-based guess) and the extrusion span of planar
//! grids (`[output] span`, `convert --span`), OpenFOAM's binary format (the ASCII files'
//! numbers, read back raw), through the command line and the library; and the merged mesh's
//! points read from the blocks.

mod common;
use common::*;
use ellipgrid::io::connectivity::{self, BcKind, ConnFile};
use ellipgrid::io::mesh::{sides_as_patches, Mesh};
use ellipgrid::io::Block;
use ellipgrid::Grid2;
use std::fs;

/// Two unit squares side by side (x from 0 to 2), 5 × 5 nodes each; the edges' families:
/// bottom "lower" (both bottom edges), top "upper", left "inlet", right "outlet". `extra`
/// adds lines to an edge: (edge name, lines).
fn two_squares_case(extra: &[(&str, &str)], output: &str) -> String {
    let mut t = format!("{output}\n");
    for (name, x, y) in [
        ("v00", 0, 0),
        ("v10", 1, 0),
        ("v20", 2, 0),
        ("v01", 0, 1),
        ("v11", 1, 1),
        ("v21", 2, 1),
    ] {
        t += &format!("[[vertex]]\nname = \"{name}\"\nat = [{x}, {y}]\n");
    }
    for (name, from, to, family) in [
        ("b0", "v00", "v10", "lower"),
        ("b1", "v10", "v20", "lower"),
        ("t0", "v01", "v11", "upper"),
        ("t1", "v11", "v21", "upper"),
        ("left", "v00", "v01", "inlet"),
        ("mid", "v10", "v11", "mid"),
        ("right", "v20", "v21", "outlet"),
    ] {
        t += &format!(
            "[[edge]]\nname = \"{name}\"\nfrom = \"{from}\"\nto = \"{to}\"\nn = 5\n\
             family = \"{family}\"\n"
        );
        for (e, lines) in extra {
            if *e == name {
                t += lines;
                t += "\n";
            }
        }
    }
    t += "[[block]]\nname = \"a\"\nE1 = \"left\"\nE2 = \"mid\"\nE3 = \"b0\"\nE4 = \"t0\"\n";
    t += "[[block]]\nname = \"b\"\nE1 = \"mid\"\nE2 = \"right\"\nE3 = \"b1\"\nE4 = \"t1\"\n";
    t
}

/// The `type` of each patch of an OpenFOAM boundary file, by name.
fn patch_types(boundary: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut name = String::new();
    for l in boundary.lines() {
        let t = l.trim();
        if l.starts_with("    ") && !l.starts_with("     ") && !t.is_empty() && t != "{" && t != "}"
        {
            name = t.to_string();
        }
        if let Some(v) = t.strip_prefix("type") {
            out.push((name.clone(), v.trim().trim_end_matches(';').to_string()));
        }
    }
    out
}

/// The z values of an OpenFOAM points file.
fn zs(points: &str) -> Vec<f64> {
    points
        .lines()
        .filter(|l| l.starts_with('(') && l.ends_with(')'))
        .map(|l| {
            l[1..l.len() - 1]
                .split_whitespace()
                .nth(2)
                .unwrap()
                .parse()
                .unwrap()
        })
        .collect()
}

#[test]
fn explicit_boundary_conditions_reach_openfoam_su2_cgns_and_the_conn_file() {
    let d = tempfile::tempdir().unwrap();
    // "lower" would be a plain patch by its name, "upper" too; "inlet" would be an inflow
    // (OpenFOAM: patch). Given: lower a wall, upper a symmetry plane, inlet a far field.
    let case = two_squares_case(
        &[
            ("b0", "bc = \"wall\""),
            ("t0", "bc = \"symmetry\""),
            ("t1", "bc = \"symmetry\""),
            ("left", "bc = \"farfield\""),
        ],
        "[output]\nspan = 0.25",
    );
    fs::write(d.path().join("c.toml"), case).unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "-q",
            "c.toml",
            "-o",
            "c.x",
            "-o",
            "c.conn",
            "-o",
            "run/constant/polyMesh",
            "-o",
            "c.su2",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let boundary = fs::read_to_string(d.path().join("run/constant/polyMesh/boundary")).unwrap();
    let want = [
        ("inlet", "patch"), // a far field is a plain patch in OpenFOAM
        ("lower", "wall"),
        ("upper", "symmetry"),
        ("outlet", "patch"),
        ("frontAndBack", "empty"),
    ];
    let mut got = patch_types(&boundary);
    got.sort();
    let mut want: Vec<(String, String)> = want
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    want.sort();
    assert_eq!(got, want, "{boundary}");
    // [output] span: the extrusion runs from z = 0 to z = 0.25
    let z = zs(&fs::read_to_string(d.path().join("run/constant/polyMesh/points")).unwrap());
    assert_eq!(z.len(), 2 * 45);
    assert!(z.iter().all(|&v| v == 0.0 || v == 0.25), "{z:?}");
    assert_eq!(z.iter().filter(|&&v| v == 0.25).count(), 45);

    // SU2: each marker's kind as a comment; the .conn file: the explicit ones only.
    let su2 = fs::read_to_string(d.path().join("c.su2")).unwrap();
    for l in [
        "% marker lower: wall\n",
        "% marker upper: symmetry\n",
        "% marker inlet: farfield\n",
        "% marker outlet: outflow\n",
    ] {
        assert!(su2.contains(l), "{l}: {su2}");
    }
    let conn = connectivity::read(&d.path().join("c.conn")).unwrap();
    let named = |id: usize| conn.families.iter().find(|f| f.0 == id).unwrap().1.clone();
    let mut given: Vec<(String, BcKind)> = conn.bcs.iter().map(|b| (named(b.0), b.1)).collect();
    given.sort_by(|a, b| a.0.cmp(&b.0));
    assert_eq!(
        given,
        vec![
            ("inlet".to_string(), BcKind::Farfield),
            ("lower".to_string(), BcKind::Wall),
            ("upper".to_string(), BcKind::Symmetry),
        ]
    );
    // convert from Plot3D + .conn: the same boundary file; --span sets the thickness
    let o = ellipgrid(
        d.path(),
        &["convert", "c.x", "conv/polyMesh", "--span", "0.5"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let again = fs::read_to_string(d.path().join("conv/polyMesh/boundary")).unwrap();
    assert_eq!(again, boundary);
    let z = zs(&fs::read_to_string(d.path().join("conv/polyMesh/points")).unwrap());
    assert_eq!(z.iter().cloned().fold(0.0, f64::max), 0.5);
    #[cfg(feature = "cgns")]
    {
        let o = ellipgrid(d.path(), &["convert", "c.x", "c.cgns"]);
        assert!(o.status.success(), "{}", text(&o));
        let (_, back) = ellipgrid::io::cgns::read_cgns(&d.path().join("c.cgns")).unwrap();
        let fam = |c: &ConnFile, n: &str| {
            let f = c.families.iter().find(|f| f.1 == n).unwrap();
            c.bc(f.0, &f.1)
        };
        for (n, k) in [
            ("lower", BcKind::Wall),
            ("upper", BcKind::Symmetry),
            ("inlet", BcKind::Farfield),
            ("outlet", BcKind::Outflow),
        ] {
            assert_eq!(fam(&back, n), k, "{n}");
        }
    }
}

#[test]
fn bad_boundary_conditions_and_spans_exit_2_naming_the_key() {
    let out = "[output]\nfiles = [\"g.su2\"]";
    rejects(
        &two_squares_case(&[("b0", "bc = \"wal\"")], out),
        &["edge 'b0'", "bc = 'wal'", "wall, symmetry, farfield"],
    );
    rejects(
        &two_squares_case(&[("mid", "bc = \"wall\"")], out),
        &["edge 'mid'", "between two blocks"],
    );
    rejects(
        &two_squares_case(&[("b0", "bc = \"wall\""), ("b1", "bc = \"inflow\"")], out),
        &["edge 'b0'", "edge 'b1'", "family 'lower'"],
    );
    rejects(
        &two_squares_case(&[], "[output]\nspan = -1"),
        &["[output]", "span = -1", "> 0"],
    );
    // convert: --span only with OpenFOAM output, and > 0
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("c.toml"), two_squares_case(&[], "")).unwrap();
    for (args, needle) in [
        (
            vec!["convert", "c.toml", "c.su2", "--span", "2"],
            "options of OpenFOAM",
        ),
        (
            vec!["convert", "c.toml", "x/polyMesh", "--foam-format", "bin"],
            "format 'bin'",
        ),
        (
            vec!["convert", "c.toml", "x/polyMesh", "--span", "0"],
            "span = 0",
        ),
        (
            vec!["convert", "c.toml", "x/polyMesh", "--span", "nan"],
            "span = NaN",
        ),
    ] {
        let o = ellipgrid(d.path(), &args);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{t}");
        assert!(t.contains(needle), "{needle}: {t}");
        assert!(!d.path().join("x").exists() && !d.path().join("c.su2").exists());
    }
    // a .conn file whose boundary conditions are unknown or name no family
    let c = ConnFile {
        families: vec![(1, "w".into())],
        ..Default::default()
    };
    for (tail, needle) in [("1\n 1 wal\n", "one of wall"), ("1\n 7 wall\n", "family 7")] {
        let p = d.path().join("bad.conn");
        connectivity::write_file(&p, &c).unwrap();
        let mut s = fs::read_to_string(&p).unwrap();
        s += tail;
        fs::write(&p, s).unwrap();
        let e = connectivity::read(&p).unwrap_err().to_string();
        assert!(e.contains("bad.conn") && e.contains(needle), "{e}");
    }
}

#[test]
fn conn_files_keep_explicit_boundary_conditions_and_old_files_still_read() {
    let d = tempfile::tempdir().unwrap();
    let mut c = ConnFile {
        patches: vec![
            ((1, [1, 1, 1], [3, 1, 1]), 1),
            ((1, [1, 3, 1], [3, 3, 1]), 2),
        ],
        families: vec![(1, "outer wall".into()), (2, "top".into())],
        bcs: vec![(2, BcKind::Outflow)],
        ..Default::default()
    };
    let p = d.path().join("c.conn");
    connectivity::write_file(&p, &c).unwrap();
    let back = connectivity::read(&p).unwrap();
    assert_eq!(back, c);
    assert_eq!(back.bc(1, "outer wall"), BcKind::Wall, "by the name");
    assert_eq!(back.bc(2, "top"), BcKind::Outflow, "given");
    // without explicit conditions the file is the old layout, and reads back the same
    c.bcs.clear();
    connectivity::write_file(&p, &c).unwrap();
    let s = fs::read_to_string(&p).unwrap();
    assert!(s.ends_with("   2 top\n"), "{s}");
    assert_eq!(connectivity::read(&p).unwrap(), c);
}

#[test]
fn merged_points_are_read_from_the_blocks_in_order() {
    // Two blocks sharing a side and a one-block ring closed on itself: the ids of duplicate
    // nodes point at their first occurrence, and reading the points in pieces gives the
    // same as one by one.
    let a = Grid2::from_fn(4, 3, |i, j| [i as f64, j as f64]);
    let b = Grid2::from_fn(4, 3, |i, j| [3.0 + i as f64, j as f64]);
    let blocks = vec![
        ("a".to_string(), Block::Planar(a)),
        ("b".to_string(), Block::Planar(b)),
    ];
    let mut conn = sides_as_patches(&blocks);
    // a's i = max joins b's i = 1: drop those two patches, add the interface
    conn.patches.retain(|p| p.1 != 2 && p.1 != 5);
    conn.families.retain(|f| f.0 != 2 && f.0 != 5);
    conn.interfaces
        .push([(1, [4, 1, 1], [4, 3, 1]), (2, [1, 1, 1], [1, 3, 1])]);
    for span in [None, Some(2.0)] {
        let m = Mesh::build("t", &blocks, &conn, span).unwrap();
        let layers = if span.is_some() { 2 } else { 1 };
        assert_eq!(m.npoints(), 7 * 3 * layers);
        assert_eq!(m.blocks[1].dups.len(), 3 * layers);
        // node id k is at x = k mod 7 in block order: a's 4 per row, then b's 3 new ones
        let mut all = Vec::new();
        m.points_in(0..m.npoints(), |k, p| all.push((k, p)));
        for (k, p) in &all {
            assert_eq!(*p, m.point(*k as u32));
        }
        let pieces: Vec<(usize, [f64; 3])> = (0..m.npoints())
            .step_by(5)
            .flat_map(|s| {
                let mut v = Vec::new();
                m.points_in(s..s + 5, |k, p| v.push((k, p)));
                v
            })
            .collect();
        assert_eq!(pieces, all);
        let xs: Vec<f64> = all[..12].iter().map(|(_, p)| p[0]).collect();
        assert_eq!(xs, [0., 1., 2., 3., 0., 1., 2., 3., 0., 1., 2., 3.]);
        assert_eq!(all[12 * layers].1, [4.0, 0.0, 0.0]);
        // b's first node is a's (3, 0)
        assert_eq!(m.blocks[1].ids[0], m.blocks[0].ids[3]);
        assert_eq!(m.blocks[1].first_point as usize, 12 * layers);
    }
}

/// The lists of an OpenFOAM file after its header: ASCII entries as numbers, or (binary)
/// raw little-endian numbers of `size` bytes (`per` in an item), each list as f64 values.
fn foam_lists(path: &std::path::Path, binary: Option<(usize, usize)>) -> Vec<Vec<f64>> {
    let s = fs::read(path).unwrap();
    let head = s.windows(3).position(|w| w == b"}\n\n").unwrap() + 3;
    let mut at = head;
    let mut lists = Vec::new();
    while at < s.len() {
        let line_end = at
            + s[at..]
                .iter()
                .position(|&c| c == b'\n' || c == b'(')
                .unwrap();
        let text = std::str::from_utf8(&s[at..line_end]).unwrap().trim();
        if text.is_empty() {
            at = line_end + 1;
            continue;
        }
        let n: usize = text.parse().unwrap();
        let Some((size, per)) = binary else {
            // ASCII: the numbers of the next n lines inside the parentheses
            let body = std::str::from_utf8(&s[line_end..]).unwrap();
            let close = body.find("\n)").unwrap();
            let v: Vec<f64> = body[1..close]
                .split(|c: char| c.is_whitespace() || c == '(' || c == ')')
                .filter(|t| !t.is_empty())
                .map(|t| t.parse().unwrap())
                .collect();
            lists.push(v);
            at = line_end + close + 3;
            continue;
        };
        if n == 0 {
            lists.push(Vec::new());
            at = line_end + 1;
            continue;
        }
        let len = n * per * size;
        assert_eq!(s[line_end + 1], b'(', "{}", path.display());
        let raw = &s[line_end + 2..line_end + 2 + len];
        assert_eq!(s[line_end + 2 + len], b')', "{}", path.display());
        lists.push(
            raw.chunks(size)
                .map(|c| match size {
                    4 => f64::from(i32::from_le_bytes(c.try_into().unwrap())),
                    _ => f64::from_le_bytes(c.try_into().unwrap()),
                })
                .collect(),
        );
        at = line_end + 3 + len;
    }
    lists
}

#[test]
fn binary_openfoam_meshes_hold_the_ascii_ones_numbers() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("c.toml"), two_squares_case(&[], "")).unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "-q",
            "c.toml",
            "-o",
            "c.x",
            "-o",
            "c.conn",
            "-o",
            "a/polyMesh",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let o = ellipgrid(
        d.path(),
        &[
            "convert",
            "-q",
            "c.x",
            "b/polyMesh",
            "--foam-format",
            "binary",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let (a, b) = (d.path().join("a/polyMesh"), d.path().join("b/polyMesh"));
    let head = fs::read_to_string(b.join("boundary")).unwrap();
    assert_eq!(
        head,
        fs::read_to_string(a.join("boundary")).unwrap(),
        "the boundary dictionary stays text"
    );
    let points = foam_lists(&b.join("points"), Some((8, 3)));
    assert_eq!(points.len(), 1);
    assert_eq!(points[0], foam_lists(&a.join("points"), None)[0]);
    for f in ["owner", "neighbour"] {
        assert_eq!(
            foam_lists(&b.join(f), Some((4, 1))),
            foam_lists(&a.join(f), None),
            "{f}"
        );
    }
    // faceCompactList: offsets 0, 4, 8, … then the faces' nodes as the ASCII faceList has them
    let faces = foam_lists(&b.join("faces"), Some((4, 1)));
    let ascii: Vec<f64> = foam_lists(&a.join("faces"), None)[0]
        .chunks(5)
        .flat_map(|f| {
            assert_eq!(f[0], 4.0);
            f[1..].to_vec()
        })
        .collect();
    let n = ascii.len() / 4;
    assert_eq!(
        faces[0],
        (0..=n).map(|k| (4 * k) as f64).collect::<Vec<_>>()
    );
    assert_eq!(faces[1], ascii);
    let owner = fs::read(b.join("owner")).unwrap();
    let head = String::from_utf8_lossy(&owner[..400]);
    assert!(
        head.contains("format      binary;")
            && head.contains("arch        \"LSB;label=32;scalar=64\";"),
        "{head}"
    );
    // --foam-format in a case file
    fs::write(
        d.path().join("c2.toml"),
        two_squares_case(&[], "[output]\nfoam_format = \"binary\""),
    )
    .unwrap();
    let o = ellipgrid(d.path(), &["run", "-q", "c2.toml", "-o", "c2/polyMesh"]);
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(
        fs::read(d.path().join("c2/polyMesh/points")).unwrap(),
        fs::read(b.join("points")).unwrap()
    );
    rejects(
        &two_squares_case(
            &[],
            "[output]\nfoam_format = \"bin\"\nfiles = [\"p/polyMesh\"]",
        ),
        &["[output]", "OpenFOAM format 'bin'"],
    );
}
