//! Floating interior faces of volume topologies (`interface = "floating"` on a `[[face]]`):
//! a box split in two whose shared face starts displaced (sheared in its plane and bent out of
//! it) floats back to the single block's tensor grid, with uniform and with stretched
//! distributions; through the CLI the shared face is bit-identical in both blocks, the
//! connectivity file matches, across a sheared pair the kink of the fixed face drops to a
//! third, and the grid is the same bit for bit on one and on four threads.

mod common;
use common::*;
use ellipgrid::case::LoadedCase;
use ellipgrid::io::plot3d::read_plot3d;
use ellipgrid::io::Block;
use ellipgrid::job::floating::float;
use ellipgrid::job::multivolume::grid_faces;
use ellipgrid::{job, Grid3};
use std::fmt::Write;
use std::path::Path;

/// The box [0, 2] × [0, 1] × [0, 1] cut at x = 1 into volumes "left" and "right", `n` nodes
/// per edge along x (each half), y and z; with `stretch` the y and z edges cluster (Vinokur).
/// The shared face `fx1` runs z before y (transposed against the other x faces) and is
/// `interface` ("fixed" or "floating").
fn split_box(n: [usize; 3], stretch: bool, interface: &str) -> String {
    let mut t = String::new();
    for i in 0..3 {
        for j in 0..2 {
            for k in 0..2 {
                writeln!(
                    t,
                    "[[vertex]]\nname = \"v{i}{j}{k}\"\nat = [{:?}, {:?}, {:?}]",
                    i as f64, j as f64, k as f64
                )
                .unwrap();
            }
        }
    }
    let dist = |first: f64, last: f64| {
        if stretch {
            format!("\ndistribution = {{ type = \"vinokur\", first = {first}, last = {last} }}")
        } else {
            String::new()
        }
    };
    for i in 0..2 {
        for j in 0..2 {
            for k in 0..2 {
                writeln!(
                    t,
                    "[[edge]]\nname = \"ex{i}{j}{k}\"\nfrom = \"v{i}{j}{k}\"\nto = \"v{}{j}{k}\"\nn = {}",
                    i + 1,
                    n[0]
                )
                .unwrap();
            }
        }
    }
    for i in 0..3 {
        for k in 0..2 {
            writeln!(
                t,
                "[[edge]]\nname = \"ey{i}{k}\"\nfrom = \"v{i}0{k}\"\nto = \"v{i}1{k}\"\nn = {}{}",
                n[1],
                dist(0.02, 0.1)
            )
            .unwrap();
        }
        for j in 0..2 {
            writeln!(
                t,
                "[[edge]]\nname = \"ez{i}{j}\"\nfrom = \"v{i}{j}0\"\nto = \"v{i}{j}1\"\nn = {}{}",
                n[2],
                dist(0.1, 0.03)
            )
            .unwrap();
        }
    }
    let face = |t: &mut String, name: &str, e: [String; 4], extra: &str| {
        writeln!(
            t,
            "[[face]]\nname = \"{name}\"\nkind = \"minimal\"\nE1 = \"{}\"\nE2 = \"{}\"\nE3 = \"{}\"\nE4 = \"{}\"{extra}",
            e[0], e[1], e[2], e[3]
        )
        .unwrap();
    };
    for i in [0, 2] {
        face(
            &mut t,
            &format!("fx{i}"),
            [
                format!("ez{i}0"),
                format!("ez{i}1"),
                format!("ey{i}0"),
                format!("ey{i}1"),
            ],
            "",
        );
    }
    face(
        &mut t,
        "fx1",
        ["ey10".into(), "ey11".into(), "ez10".into(), "ez11".into()],
        &format!("\ninterface = \"{interface}\""),
    );
    for h in 0..2 {
        for j in 0..2 {
            face(
                &mut t,
                &format!("fy{j}{h}"),
                [
                    format!("ez{h}{j}"),
                    format!("ez{}{j}", h + 1),
                    format!("ex{h}{j}0"),
                    format!("ex{h}{j}1"),
                ],
                "",
            );
        }
        for k in 0..2 {
            face(
                &mut t,
                &format!("fz{k}{h}"),
                [
                    format!("ey{h}{k}"),
                    format!("ey{}{k}", h + 1),
                    format!("ex{h}0{k}"),
                    format!("ex{h}1{k}"),
                ],
                "",
            );
        }
    }
    for (h, name) in ["left", "right"].iter().enumerate() {
        writeln!(
            t,
            "[[volume]]\nname = \"{name}\"\nlinear = \"direct\"\nF1 = \"fx{h}\"\nF2 = \"fx{}\"\n\
             F3 = \"fy0{h}\"\nF4 = \"fy1{h}\"\nF5 = \"fz0{h}\"\nF6 = \"fz1{h}\"",
            h + 1
        )
        .unwrap();
    }
    t
}

fn volume(b: &Block) -> &Grid3 {
    match b {
        Block::Volume(g) => g,
        _ => panic!("a volume block"),
    }
}

/// Volume `g`'s node coordinates along its i, j, k edges through node (0, 0, 0).
fn axes(g: &Grid3) -> [Vec<f64>; 3] {
    let [ni, nj, nk] = g.dims();
    [
        (0..ni).map(|i| g.point(i, 0, 0)[0]).collect(),
        (0..nj).map(|j| g.point(0, j, 0)[1]).collect(),
        (0..nk).map(|k| g.point(0, 0, k)[2]).collect(),
    ]
}

#[test]
fn a_displaced_floating_face_floats_back_to_the_tensor_grid() {
    for stretch in [false, true] {
        let text = split_box([7, 9, 8], stretch, "floating");
        let case = LoadedCase::parse(&text, Path::new("split.toml")).unwrap();
        let topo = case.topology3.as_ref().unwrap();
        let (mut grids, _) = grid_faces(&case, topo).unwrap();
        let f = case
            .case
            .faces
            .iter()
            .position(|f| f.name == "fx1")
            .unwrap();
        // Its own indices: p along z, q along y. Shear it in its plane, bend it out of it.
        let face = &mut grids[f];
        let (np, nq) = (face.ni(), face.nj());
        let mut displaced = 0.0f64;
        for q in 1..nq - 1 {
            for p in 1..np - 1 {
                let [x, y, z] = face.point(p, q);
                let s = (std::f64::consts::PI * y).sin() * (std::f64::consts::PI * z).sin();
                face.set(p, q, [x + 0.2 * s, y + 0.15 * s * z, z - 0.1 * s * y]);
                displaced = displaced.max(0.2 * s);
            }
        }
        assert!(displaced > 0.15);
        let (done, hist) = float(&case, topo, &mut grids).unwrap();
        let h = hist[f].as_ref().expect("fx1 floats");
        assert!(h.converged && h.planar, "{h:?}");
        assert!(h.updates[0] > 0.01, "{h:?}");
        assert!(hist.iter().filter(|h| h.is_some()).count() == 1);
        let (left, right) = (volume(&done[0].1), volume(&done[1].1));
        let [xl, ys, zs] = axes(left);
        let xr = axes(right)[0].clone();
        for (g, xs, name) in [(left, &xl, "left"), (right, &xr, "right")] {
            let want = Grid3::rectilinear(xs, &ys, &zs);
            let d = max_diff(g.coords(), want.coords());
            assert!(d < 1e-9, "stretch {stretch}, {name}: {d:e} ({h:?})");
        }
        // The face's interior nodes are the tensor grid's too.
        for (q, &y) in ys.iter().enumerate().take(nq) {
            for (p, &z) in zs.iter().enumerate().take(np) {
                let want = [1.0, y, z];
                let got = grids[f].point(p, q);
                for c in 0..3 {
                    assert!((got[c] - want[c]).abs() < 1e-9, "{got:?} vs {want:?}");
                }
            }
        }
    }
}

#[test]
fn the_cli_writes_a_floating_face_bit_identical_in_both_blocks_with_a_matching_connectivity_file() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(
        d.path().join("split.toml"),
        split_box([5, 6, 7], true, "floating"),
    )
    .unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "split.toml",
            "-o",
            "split.x",
            "-o",
            "split.conn",
            "--report",
            "r.json",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("(floating, planar: "), "{}", text(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    let fl = &report["face_interfaces"][0]["floating"];
    assert_eq!(fl["converged"], true, "{report}");
    assert!(fl["rounds"].as_u64().unwrap() >= 1);
    let blocks = read_plot3d(&d.path().join("split.x")).unwrap().blocks;
    let (l, r) = (volume(&blocks[0]), volume(&blocks[1]));
    let [ni, nj, nk] = l.dims();
    for k in 0..nk {
        for j in 0..nj {
            assert_eq!(
                l.point(ni - 1, j, k).map(f64::to_bits),
                r.point(0, j, k).map(f64::to_bits)
            );
        }
    }
    let conn = std::fs::read_to_string(d.path().join("split.conn")).unwrap();
    let c = ellipgrid::io::connectivity::read(&d.path().join("split.conn")).unwrap();
    assert_eq!(c.interfaces.len(), 1, "{conn}");
    assert_eq!(c.patches.len(), 10, "{conn}");
}

/// Two volumes stacked along z: below the box [0, 1]² × [−1, 0], above the box [0, 1]² ×
/// [0, 1] sheared by `shear` along x at its top, sharing the face z = 0 (`interface`).
fn sheared_pair(shear: f64, n: usize, interface: &str) -> String {
    let mut t = String::new();
    for (k, z) in [-1.0f64, 0.0, 1.0].iter().enumerate() {
        let dx = if k == 2 { shear } else { 0.0 };
        for j in 0..2 {
            for i in 0..2 {
                writeln!(
                    t,
                    "[[vertex]]\nname = \"v{i}{j}{k}\"\nat = [{:?}, {:?}, {z:?}]",
                    i as f64 + dx,
                    j as f64
                )
                .unwrap();
            }
        }
    }
    let mut edge = |name: String, a: String, b: String| {
        writeln!(
            t,
            "[[edge]]\nname = \"{name}\"\nfrom = \"{a}\"\nto = \"{b}\"\nn = {n}"
        )
        .unwrap();
    };
    for k in 0..3 {
        for j in 0..2 {
            edge(format!("x{j}{k}"), format!("v0{j}{k}"), format!("v1{j}{k}"));
        }
        for i in 0..2 {
            edge(format!("y{i}{k}"), format!("v{i}0{k}"), format!("v{i}1{k}"));
        }
    }
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
                edge(
                    format!("z{i}{j}{k}"),
                    format!("v{i}{j}{k}"),
                    format!("v{i}{j}{}", k + 1),
                );
            }
        }
    }
    let face = |t: &mut String, name: String, e: [String; 4], extra: &str| {
        writeln!(
            t,
            "[[face]]\nname = \"{name}\"\nkind = \"minimal\"\nE1 = \"{}\"\nE2 = \"{}\"\nE3 = \"{}\"\nE4 = \"{}\"{extra}",
            e[0], e[1], e[2], e[3]
        )
        .unwrap();
    };
    for k in 0..3 {
        let extra = if k == 1 {
            format!("\ninterface = \"{interface}\"")
        } else {
            String::new()
        };
        face(
            &mut t,
            format!("fz{k}"),
            [
                format!("y0{k}"),
                format!("y1{k}"),
                format!("x0{k}"),
                format!("x1{k}"),
            ],
            &extra,
        );
    }
    for k in 0..2 {
        let up = k + 1;
        for i in 0..2 {
            face(
                &mut t,
                format!("fx{i}{k}"),
                [
                    format!("z{i}0{k}"),
                    format!("z{i}1{k}"),
                    format!("y{i}{k}"),
                    format!("y{i}{up}"),
                ],
                "",
            );
        }
        for j in 0..2 {
            face(
                &mut t,
                format!("fy{j}{k}"),
                [
                    format!("z0{j}{k}"),
                    format!("z1{j}{k}"),
                    format!("x{j}{k}"),
                    format!("x{j}{up}"),
                ],
                "",
            );
        }
    }
    for k in 0..2 {
        writeln!(
            t,
            "[[volume]]\nname = \"b{k}\"\nlinear = \"direct\"\nF1 = \"fx0{k}\"\nF2 = \"fx1{k}\"\n\
             F3 = \"fy0{k}\"\nF4 = \"fy1{k}\"\nF5 = \"fz{k}\"\nF6 = \"fz{}\"",
            k + 1
        )
        .unwrap();
    }
    t
}

fn generate(text: &str) -> job::Generated {
    let case = LoadedCase::parse(text, Path::new("pair.toml")).unwrap();
    job::generate(&case, |_| {}).unwrap()
}

#[test]
fn a_floating_face_removes_the_kink_of_a_sheared_pair() {
    let fixed = generate(&sheared_pair(0.6, 9, "fixed"));
    let floating = generate(&sheared_pair(0.6, 9, "floating"));
    let (a, b) = (
        fixed.report.face_interfaces[0].smoothness,
        floating.report.face_interfaces[0].smoothness,
    );
    // The fixed face is the box's: the sheared volume's lines lean by atan(0.6) = 31° there.
    assert!(
        (a.kink_mean_deg - 0.6f64.atan().to_degrees()).abs() < 1e-6,
        "{a:?}"
    );
    // Floating, the lines bend smoothly through the face except near its edges, where the
    // side walls themselves kink by 31° (measured 10.1° mean, 16.9° max at 9 nodes).
    assert!(
        b.kink_mean_deg < 0.4 * a.kink_mean_deg,
        "{b:?} (fixed {a:?})"
    );
    assert!(b.spacing_ratio_max < 1.1, "{b:?}");
    let h = floating.report.face_interfaces[0]
        .floating
        .as_ref()
        .unwrap();
    assert!(h.converged && h.planar, "{h:?}");
    for v in &floating.report.volumes {
        assert_eq!(v.quality.folded_cells, 0);
        assert!(v.picard.converged);
    }
    // The face stays in its plane z = 0.
    let below = volume(&floating.blocks[0].1);
    let [ni, nj, nk] = below.dims();
    for j in 0..nj {
        for i in 0..ni {
            assert_eq!(below.point(i, j, nk - 1)[2], 0.0);
        }
    }
}

#[test]
fn floating_face_errors_exit_2_naming_the_face() {
    let good = split_box([3, 3, 3], false, "floating");
    rejects(
        &good.replace("interface = \"floating\"", "interface = \"sliding\""),
        &["face 'fx1'", "interface = 'sliding'"],
    );
    rejects(
        &good.replacen(
            "name = \"fx0\"\nkind = \"minimal\"",
            "name = \"fx0\"\nkind = \"minimal\"\ninterface = \"floating\"",
            1,
        ),
        &["face 'fx0'", "between two volumes"],
    );
}

#[test]
fn a_floating_face_gives_the_same_bits_on_one_and_on_four_threads() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("pair.toml"), sheared_pair(0.6, 7, "floating")).unwrap();
    let run = |threads: &str, out: &str| {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_ellipgrid"))
            .current_dir(d.path())
            .env("RAYON_NUM_THREADS", threads)
            .args(["run", "pair.toml", "-q", "-o", out])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", text(&o));
        std::fs::read(d.path().join(out)).unwrap()
    };
    assert!(run("1", "one.x") == run("4", "four.x"));
}

/// [`split_box`] with stretched y edges, both volumes with their wall at y = 0 (`wall =
/// "F3"`) and the first wall spacing 0.02 at x = 0 and x = 1 (the shared face's edges) but
/// 0.004 at x = 2: the prescription is 0.02 over the left volume and falls linearly over the
/// right one, not linearly over the whole strip from 0.02 to 0.004 as the strip's own corner
/// edges would give it.
fn split_box_with_walls(interface: &str) -> String {
    let text = split_box([9, 11, 7], true, interface);
    let mut out = String::new();
    for (n, part) in text.split("[[edge]]\n").enumerate() {
        if n > 0 {
            out.push_str("[[edge]]\n");
        }
        if part.starts_with("name = \"ey2") {
            out.push_str(&part.replace("first = 0.02", "first = 0.004"));
        } else {
            out.push_str(part);
        }
    }
    assert_eq!(out.matches("first = 0.004").count(), 2);
    out.replace(
        "linear = \"direct\"\n",
        "linear = \"direct\"\nwall = \"F3\"\n",
    )
}

/// A floating face between two volumes with their walls on one side of the strip: the strip
/// is solved with the wall correction at the union of the two walls, its goal columns the
/// volumes' own (`Strip::wall_targets`), so the first nodes stay within 1 % of each volume's
/// prescription and the lines within 1° of the wall normal, while the face floats (the face
/// moves, the kink vanishes). Measured: the fixed face's kink 4.08° mean (7.98° max), the
/// floating face's 3e-7° (the box's straight lines), first node 1.000 of the prescription in
/// both; before (the strip solved with its volumes' control functions carried over, no wall
/// passes) the floating face's kink was 1.35° mean (5.37° max) and the first nodes 0.958 …
/// 1.000 of the prescription.
#[test]
fn a_floating_face_between_two_wall_volumes_holds_the_wall_spacing() {
    let fixed = generate(&split_box_with_walls("fixed"));
    let floating = generate(&split_box_with_walls("floating"));
    let (a, b) = (
        fixed.report.face_interfaces[0].smoothness,
        floating.report.face_interfaces[0].smoothness,
    );
    let h = floating.report.face_interfaces[0]
        .floating
        .as_ref()
        .unwrap();
    assert!(h.converged && h.planar, "{h:?}");
    assert!(h.updates[0] > 1e-4, "{h:?}");
    for (name, g) in [("fixed", &fixed), ("floating", &floating)] {
        for v in &g.report.volumes {
            assert_eq!(v.quality.folded_cells, 0, "{name} {}", v.name);
            let w = v.wall.as_ref().expect("a wall");
            assert!(
                w.ratio_min > 0.99 && w.ratio_max < 1.01,
                "{name} {}: {w:?}",
                v.name
            );
            assert!(w.angle_max_deg < 1.0, "{name} {}: {w:?}", v.name);
        }
    }
    assert!(a.kink_mean_deg > 3.0, "fixed {a:?}");
    assert!(b.kink_mean_deg < 0.01, "floating {b:?}, fixed {a:?}");
}
