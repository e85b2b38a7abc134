//! CGNS output and input (#19; the `cgns` feature): Plot3D → CGNS → Plot3D bit-identical,
//! the connectivity (interfaces and family patches) back as written, solver meshes from a
//! CGNS input, and CGNS through the CLI.
#![cfg(feature = "cgns")]

mod common;

use common::{ellipgrid, root, text};
use ellipgrid::io::cgns::{read_cgns, write_cgns};
use ellipgrid::io::connectivity::ConnFile;
use ellipgrid::io::mesh::{one_to_one, sides_as_patches};
use ellipgrid::io::Block;
use ellipgrid::{Grid2, Grid3};

/// One test at a time: HDF5 locks a file through its open file description, and a CLI
/// subprocess spawned by another test thread while this process has a CGNS file open
/// inherits that descriptor (HDF5 does not mark it close-on-exec) and with it the lock, so
/// reopening the file here fails ("cgio_open_file: File-open error") until the child exits.
static SERIAL: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn serial() -> std::sync::MutexGuard<'static, ()> {
    SERIAL.lock().unwrap_or_else(|p| p.into_inner())
}

/// A connectivity in a canonical form: each interface from its lower (block, range) side,
/// that side's range ascending (the other's following it), everything sorted.
fn sorted(mut c: ConnFile) -> ConnFile {
    for f in c.interfaces.iter_mut() {
        let key = |r: &ellipgrid::io::connectivity::Range| (r.0, r.1.min(r.2));
        if key(&f[1]) < key(&f[0]) {
            f.swap(0, 1);
        }
        if f[0].1 > f[0].2 {
            for r in f.iter_mut() {
                std::mem::swap(&mut r.1, &mut r.2);
            }
        }
    }
    c.interfaces.sort();
    c.patches.sort();
    c
}

#[test]
fn c_grid_round_trip_through_cgns_keeps_nodes_and_connectivity() {
    let _serial = serial();
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/rae2822_cgrid.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "-q",
            case.to_str().unwrap(),
            "-o",
            "c.x",
            "-o",
            "c.conn",
            "-o",
            "named.cgns",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    for (from, to) in [
        ("c.x", "c.cgns"),
        ("c.cgns", "back.x"),
        ("c.cgns", "back.conn"),
    ] {
        let o = ellipgrid(d.path(), &["convert", from, to]);
        assert!(o.status.success(), "{}", text(&o));
    }
    let a = std::fs::read(d.path().join("c.x")).unwrap();
    assert_eq!(
        a,
        std::fs::read(d.path().join("back.x")).unwrap(),
        "Plot3D → CGNS → Plot3D"
    );
    let conn = ellipgrid::io::connectivity::read(&d.path().join("c.conn")).unwrap();
    let back = ellipgrid::io::connectivity::read(&d.path().join("back.conn")).unwrap();
    assert_eq!(sorted(conn.clone()), sorted(back));
    // Solver meshes from the CGNS input equal those from the Plot3D + .conn.
    for (from, to) in [("c.cgns", "a.su2"), ("c.x", "b.su2")] {
        let o = ellipgrid(d.path(), &["convert", from, to]);
        assert!(o.status.success(), "{}", text(&o));
    }
    assert_eq!(
        std::fs::read(d.path().join("a.su2")).unwrap(),
        std::fs::read(d.path().join("b.su2")).unwrap()
    );
    // check and plot read CGNS too.
    for args in [
        &["check", "c.cgns"][..],
        &["plot", "-q", "c.cgns", "-o", "c.png"],
    ] {
        let o = ellipgrid(d.path(), args);
        assert!(o.status.success(), "{}", text(&o));
    }
    assert!(text(&ellipgrid(d.path(), &["check", "c.cgns"])).contains("block 4 (97 × 81)"));
    // A case written to CGNS directly: the block and family names of the case file.
    let (blocks, c) = read_cgns(&d.path().join("named.cgns")).unwrap();
    let names: Vec<&str> = blocks.iter().map(|b| b.0.as_str()).collect();
    assert_eq!(names, ["upper", "lower", "wake_upper", "wake_lower"]);
    let fams: Vec<&str> = c.families.iter().map(|f| f.1.as_str()).collect();
    assert_eq!(fams, ["airfoil", "farfield", "outflow"]);
    assert_eq!(sorted(c), sorted(conn));
}

#[test]
fn transforms_of_turned_blocks_and_volumes() {
    let _serial = serial();
    // Block b is block a's neighbour across x = 1, turned by 90° (its i runs along y down).
    let a = Block::Planar(Grid2::from_fn(3, 4, |i, j| {
        [i as f64 * 0.5, j as f64 / 3.0]
    }));
    let b = Block::Planar(Grid2::from_fn(4, 3, |i, j| {
        [1.0 + j as f64 * 0.5, 1.0 - i as f64 / 3.0]
    }));
    let blocks = vec![("a".to_string(), a), ("b".to_string(), b)];
    let r = one_to_one(
        "t",
        &blocks,
        0,
        &(1, [3, 1, 1], [3, 4, 1]),
        &(2, [4, 1, 1], [1, 1, 1]),
    )
    .unwrap();
    assert_eq!(r.range, [[3, 1, 1], [3, 4, 1]]);
    assert_eq!(r.donor_range, [[4, 1, 1], [1, 1, 1]]);
    // a's i (across, into a = out of b's j = 1 side ... ) and a's j along b's -i.
    assert_eq!(&r.transform[..2], &[2, -1]);
    // Volumes: two unit cubes sharing x = 1, the second with its j and k swapped.
    let v1 = Block::Volume(Grid3::from_fn(3, 3, 3, |i, j, k| {
        [i as f64 * 0.5, j as f64 * 0.5, k as f64 * 0.5]
    }));
    let v2 = Block::Volume(Grid3::from_fn(3, 3, 3, |i, j, k| {
        [1.0 + i as f64 * 0.5, k as f64 * 0.5, j as f64 * 0.5]
    }));
    let blocks = vec![("v1".to_string(), v1), ("v2".to_string(), v2)];
    let r = one_to_one(
        "t",
        &blocks,
        0,
        &(1, [3, 1, 1], [3, 3, 3]),
        &(2, [1, 1, 1], [1, 3, 3]),
    )
    .unwrap();
    assert_eq!(r.transform, [1, 3, 2]);
    let d = tempfile::tempdir().unwrap();
    let mut conn = sides_as_patches(&blocks);
    conn.patches.retain(|(r, _)| {
        let joined = (r.0 == 1 && r.1[0] == 3 && r.2[0] == 3) || (r.0 == 2 && r.2[0] == 1);
        !joined
    });
    conn.interfaces
        .push([(1, [3, 1, 1], [3, 3, 3]), (2, [1, 1, 1], [1, 3, 3])]);
    let path = d.path().join("v.cgns");
    write_cgns(&path, &blocks, &conn).unwrap();
    let (back, c2) = read_cgns(&path).unwrap();
    assert_eq!(back, blocks);
    assert_eq!(c2.interfaces.len(), 1);
    assert_eq!(c2.patches.len(), 10);
    // A broken interface is refused before anything is written.
    let bad = d.path().join("bad.cgns");
    conn.interfaces[0][1] = (2, [3, 1, 1], [3, 3, 3]);
    let e = write_cgns(&bad, &blocks, &conn).unwrap_err().to_string();
    assert!(e.contains("'v1' and 'v2' do not meet"), "{e}");
    assert!(!bad.exists());
}

#[test]
fn unreadable_cgns_is_a_clear_error() {
    let _serial = serial();
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("junk.cgns"), b"not a cgns file").unwrap();
    let o = ellipgrid(d.path(), &["convert", "junk.cgns", "out.x"]);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(t.contains("junk.cgns") && !t.contains("panicked"), "{t}");
    assert!(!d.path().join("out.x").exists());
}

#[test]
fn smooth_reads_cgns_and_keeps_names_connectivity_and_boundary_nodes() {
    let _serial = serial();
    // The NACA 0012 O-grid's four blocks as CGNS; smooth regrids their interiors from the
    // transfinite start the Plot3D would give: boundary nodes bit for bit, the connectivity
    // and the block names carried to the CGNS output, the solver mesh from it merges.
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/naca0012_ogrid.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "-q",
            case.to_str().unwrap(),
            "-o",
            "o.conn",
            "--write-start",
            "s.x",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let o = ellipgrid(
        d.path(),
        &["convert", "-q", "s.x", "s.cgns", "--conn", "o.conn"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let o = ellipgrid(
        d.path(),
        &[
            "smooth", "-q", "s.cgns", "-o", "out.cgns", "-o", "out.x", "-o", "out.su2",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let (start, conn) = read_cgns(&d.path().join("s.cgns")).unwrap();
    let (out, conn_out) = read_cgns(&d.path().join("out.cgns")).unwrap();
    assert_eq!(sorted(conn_out), sorted(conn));
    let names = |b: &[(String, Block)]| b.iter().map(|x| x.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(&out), names(&start));
    for ((_, a), (_, b)) in start.iter().zip(&out) {
        let (Block::Planar(a), Block::Planar(b)) = (a, b) else {
            panic!("planar blocks")
        };
        let (ni, nj) = (a.ni(), a.nj());
        for j in 0..nj {
            for i in 0..ni {
                if i == 0 || j == 0 || i == ni - 1 || j == nj - 1 {
                    assert_eq!(a.point(i, j), b.point(i, j), "boundary node ({i}, {j})");
                }
            }
        }
        assert_ne!(a, b, "the interior was regridded");
    }
    let plot3d = ellipgrid::io::plot3d::read_plot3d(&d.path().join("out.x")).unwrap();
    assert_eq!(plot3d.blocks.len(), 4);
    let su2 = std::fs::read_to_string(d.path().join("out.su2")).unwrap();
    assert!(su2.contains("MARKER_TAG= airfoil\n"), "families kept");
}
