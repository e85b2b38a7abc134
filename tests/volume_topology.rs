//! Volume topologies (`[[face]]` tables, volumes naming six faces): a box in 2 × 2 × 2 volumes
//! is the tensor grid exactly whatever the faces' own orientations; shared faces are
//! bit-identical in both volumes; the connectivity file matches the written grid; topology
//! errors exit 2 naming the volume, face and edge.

mod common;
use common::*;
use ellipgrid::case::LoadedCase;
use ellipgrid::io::connectivity::{self, ConnFile, Range};
use ellipgrid::io::plot3d::read_plot3d;
use ellipgrid::io::Block;
use ellipgrid::{job, Grid3};
use std::fmt::Write;
use std::path::Path;

const XS: [f64; 3] = [0.0, 0.8, 2.0];
const YS: [f64; 3] = [0.0, 0.5, 1.0];
const ZS: [f64; 3] = [0.0, 1.2, 3.0];

fn vname(i: usize, j: usize, k: usize) -> String {
    format!("v{i}{j}{k}")
}

/// A box cut at the middle entries of XS, YS, ZS into 2 × 2 × 2 volumes, `n[d][h]` nodes on the
/// edges along axis d in half h; faces of `kind`. The faces are given in all eight
/// orientations of their own indices (by their position), so that every volume has to work
/// them out.
#[allow(clippy::needless_range_loop)]
fn box_case(n: [[usize; 2]; 3], kind: &str) -> String {
    let mut t = String::new();
    for k in 0..3 {
        for j in 0..3 {
            for i in 0..3 {
                writeln!(
                    t,
                    "[[vertex]]\nname = \"{}\"\nat = [{:?}, {:?}, {:?}]",
                    vname(i, j, k),
                    XS[i],
                    YS[j],
                    ZS[k]
                )
                .unwrap();
            }
        }
    }
    // Edges along axis d from node (i, j, k) one step up.
    let up = |d: usize, c: [usize; 3]| {
        let mut u = c;
        u[d] += 1;
        u
    };
    let ename =
        |d: usize, c: [usize; 3]| format!("e{}{}{}{}", ["x", "y", "z"][d], c[0], c[1], c[2]);
    for d in 0..3 {
        for k in 0..3 {
            for j in 0..3 {
                for i in 0..3 {
                    let c = [i, j, k];
                    if c[d] == 2 {
                        continue;
                    }
                    let u = up(d, c);
                    writeln!(
                        t,
                        "[[edge]]\nname = \"{}\"\nfrom = \"{}\"\nto = \"{}\"\nn = {}",
                        ename(d, c),
                        vname(c[0], c[1], c[2]),
                        vname(u[0], u[1], u[2]),
                        n[d][c[d]]
                    )
                    .unwrap();
                }
            }
        }
    }
    // Faces normal to axis d at c[d], spanning one step along the two other axes (a, b).
    let fname =
        |d: usize, c: [usize; 3]| format!("f{}{}{}{}", ["x", "y", "z"][d], c[0], c[1], c[2]);
    let mut variant = 0usize;
    for d in 0..3 {
        let (a, b) = match d {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        for k in 0..3 {
            for j in 0..3 {
                for i in 0..3 {
                    let c = [i, j, k];
                    if c[a] == 2 || c[b] == 2 {
                        continue;
                    }
                    // Own index p along a or b (transposed), forwards or backwards.
                    variant += 1;
                    let (pa, qa) = if variant % 2 == 0 { (a, b) } else { (b, a) };
                    let back = variant % 4 >= 2;
                    let low_p = ename(pa, c); // along p at q = 0
                    let high_p = ename(pa, up(qa, c)); // along p at q = end
                    let low_q = ename(qa, c); // along q at p = 0
                    let high_q = ename(qa, up(pa, c));
                    let (e1, e2) = if back {
                        (high_q, low_q)
                    } else {
                        (low_q, high_q)
                    };
                    writeln!(
                        t,
                        "[[face]]\nname = \"{}\"\nkind = \"{kind}\"\nE1 = \"{e1}\"\nE2 = \"{e2}\"\n\
                         E3 = \"{low_p}\"\nE4 = \"{high_p}\"",
                        fname(d, c)
                    )
                    .unwrap();
                }
            }
        }
    }
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
                let c = [i, j, k];
                writeln!(
                    t,
                    "[[volume]]\nname = \"b{i}{j}{k}\"\nlinear = \"direct\"\nF1 = \"{}\"\nF2 = \"{}\"\n\
                     F3 = \"{}\"\nF4 = \"{}\"\nF5 = \"{}\"\nF6 = \"{}\"",
                    fname(0, c),
                    fname(0, up(0, c)),
                    fname(1, c),
                    fname(1, up(1, c)),
                    fname(2, c),
                    fname(2, up(2, c))
                )
                .unwrap();
            }
        }
    }
    t
}

fn generate(text: &str) -> job::Generated {
    let case = LoadedCase::parse(text, Path::new("vt.toml")).unwrap();
    job::generate(&case, |_| {}).unwrap()
}

fn volume(b: &Block) -> &Grid3 {
    match b {
        Block::Volume(g) => g,
        _ => panic!("a volume block"),
    }
}

fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
        .collect()
}

#[test]
fn a_box_in_2x2x2_volumes_is_the_tensor_grid_exactly() {
    // Equal spacings on either side of each cut: the union is one uniform tensor grid.
    let n = [[5, 7], [3, 3], [5, 8]];
    for kind in ["tfi", "minimal"] {
        let g = generate(&box_case(n, kind));
        assert_eq!(g.blocks.len(), 8);
        assert_eq!(g.report.face_interfaces.len(), 12);
        for (v, (name, b)) in g.blocks.iter().enumerate() {
            let (i, j, k) = (v % 2, (v / 2) % 2, v / 4);
            assert_eq!(name, &format!("b{i}{j}{k}"));
            let want = Grid3::rectilinear(
                &linspace(XS[i], XS[i + 1], n[0][i]),
                &linspace(YS[j], YS[j + 1], n[1][j]),
                &linspace(ZS[k], ZS[k + 1], n[2][k]),
            );
            let got = volume(b);
            assert_eq!(got.dims(), want.dims(), "{kind} {name}");
            for c in 0..3 {
                for (a, w) in got.coord(c).iter().zip(want.coord(c)) {
                    assert!((a - w).abs() < 1e-12, "{kind} {name}: {a} vs {w}");
                }
            }
            assert!(g.report.volumes[v].picard.converged);
        }
        for f in &g.report.face_interfaces {
            assert!(
                f.smoothness.kink_max_deg < 1e-6,
                "{kind} {}: {:?}",
                f.face,
                f.smoothness
            );
        }
    }
}

/// Node (i, j, k) (0-based) of a 1-based range of a connectivity file: the first node plus
/// `s` and `t` steps along its two varying directions (in the order i, j, k).
fn range_nodes(r: &Range) -> Vec<[usize; 3]> {
    let (_, lo, hi) = r;
    let axes: Vec<usize> = (0..3).filter(|&d| lo[d] != hi[d]).collect();
    assert_eq!(axes.len(), 2, "a face range varies along two axes: {r:?}");
    let mut out = Vec::new();
    let steps = |d: usize| lo[d].abs_diff(hi[d]);
    for t in 0..=steps(axes[1]) {
        for s in 0..=steps(axes[0]) {
            let mut n = [lo[0] - 1, lo[1] - 1, lo[2] - 1];
            for (d, m) in [(axes[0], s), (axes[1], t)] {
                n[d] = if hi[d] > lo[d] { n[d] + m } else { n[d] - m };
            }
            out.push(n);
        }
    }
    out
}

/// Checks a written volume grid against its connectivity file: every interface's two ranges
/// hold the same points bit for bit (first to first, last to last), and interfaces and patches
/// cover every boundary node of every volume.
fn check_connectivity3(grid: &Path, conn: &Path) -> ConnFile {
    let blocks = read_plot3d(grid).unwrap().blocks;
    let c = connectivity::read(conn).unwrap();
    let point = |b: usize, [i, j, k]: [usize; 3]| volume(&blocks[b - 1]).point(i, j, k);
    let mut covered: Vec<Vec<u8>> = blocks
        .iter()
        .map(|b| vec![0; volume(b).dims().iter().product()])
        .collect();
    let mut cover = |r: &Range| {
        let [ni, nj, _] = volume(&blocks[r.0 - 1]).dims();
        for [i, j, k] in range_nodes(r) {
            covered[r.0 - 1][i + ni * (j + nj * k)] = 1;
        }
    };
    for [a, b] in &c.interfaces {
        let (na, nb) = (range_nodes(a), range_nodes(b));
        assert_eq!(na.len(), nb.len());
        assert_eq!(point(a.0, na[0]), point(b.0, nb[0]), "{a:?} {b:?}: first");
        assert_eq!(
            point(a.0, *na.last().unwrap()),
            point(b.0, *nb.last().unwrap()),
            "{a:?} {b:?}: last"
        );
        let pb: Vec<[u64; 3]> = nb
            .iter()
            .map(|&n| point(b.0, n).map(f64::to_bits))
            .collect();
        for &n in &na {
            let p = point(a.0, n).map(f64::to_bits);
            assert!(
                pb.contains(&p),
                "{a:?}: node {n:?} has no bit-identical twin in {b:?}"
            );
        }
        cover(a);
        cover(b);
    }
    for (r, fam) in &c.patches {
        assert!(c.families.iter().any(|(id, _)| id == fam));
        cover(r);
    }
    for (b, cov) in covered.iter().enumerate() {
        let [ni, nj, nk] = volume(&blocks[b]).dims();
        for k in 0..nk {
            for j in 0..nj {
                for i in 0..ni {
                    let boundary =
                        i == 0 || j == 0 || k == 0 || i == ni - 1 || j == nj - 1 || k == nk - 1;
                    assert_eq!(
                        cov[i + ni * (j + nj * k)] == 1,
                        boundary,
                        "volume {} node ({i}, {j}, {k})",
                        b + 1
                    );
                }
            }
        }
    }
    c
}

#[test]
fn shared_faces_are_bit_identical_and_the_connectivity_file_matches_the_grid() {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(
        d.path().join("box.toml"),
        box_case([[4, 5], [3, 4], [5, 3]], "minimal"),
    )
    .unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "run", "box.toml", "-o", "box.x", "-o", "box.conn", "--report", "r.json",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let c = check_connectivity3(&d.path().join("box.x"), &d.path().join("box.conn"));
    assert_eq!((c.interfaces.len(), c.patches.len()), (12, 24));
    let report = std::fs::read_to_string(d.path().join("r.json")).unwrap();
    assert!(report.contains("\"face_interfaces\"") && report.contains("\"faces\""));
}

#[test]
fn volume_topology_errors_exit_2_naming_volume_face_and_edge() {
    let good = box_case([[3, 3], [3, 3], [3, 3]], "tfi");
    // A face name no face has.
    rejects(
        &good.replacen("F6 = \"fz002\"", "F6 = \"nope\"", 1),
        &["volume 'b001'", "F6", "no face named 'nope'"],
    );
    // A face used by three volume sides.
    rejects(
        &good.replacen("F2 = \"fx200\"", "F2 = \"fx100\"", 1),
        &["face 'fx100'"],
    );
    // Node counts that do not fit: one edge of a face with more nodes.
    rejects(
        &good.replacen(
            "name = \"ex000\"\nfrom = \"v000\"\nto = \"v100\"\nn = 3",
            "name = \"ex000\"\nfrom = \"v000\"\nto = \"v100\"\nn = 4",
            1,
        ),
        &["opposite sides"],
    );
    // A volume whose six faces do not close: F6 replaced by a face elsewhere.
    rejects(
        &good.replacen("F6 = \"fz002\"", "F6 = \"fz011\"", 1),
        &["volume 'b001'", "share no corner vertex"],
    );
    // Edge-level keys that belong to faces in 3D.
    rejects(
        &good.replacen("n = 3\n", "n = 3\northogonal = true\n", 1),
        &["edge 'ex000'", "orthogonal"],
    );
    // A boundary condition on a face between two volumes, and an unknown one.
    rejects(
        &good.replacen("name = \"fx100\"\n", "name = \"fx100\"\nbc = \"wall\"\n", 1),
        &["face 'fx100'", "between two volumes"],
    );
    rejects(
        &good.replacen("name = \"fx000\"\n", "name = \"fx000\"\nbc = \"slip\"\n", 1),
        &["face 'fx000'", "bc = 'slip'"],
    );
    // A surface face without a surface.
    rejects(
        &good.replacen("kind = \"tfi\"", "kind = \"surface\"", 1),
        &["face 'fx000'", "needs surface"],
    );
}

/// Two volumes stacked along z: below a box, above a box sheared by `shear` along x, sharing
/// the face z = 0; `orthogonal` adds orthogonality at the shared face on both sides.
fn sheared_pair(shear: f64, orthogonal: bool, n: usize) -> String {
    let mut t = String::new();
    let z = [-1.0, 0.0, 1.0];
    let mut vs = Vec::new();
    for (k, zk) in z.iter().enumerate() {
        let dx = if k == 2 { shear } else { 0.0 };
        for (j, y) in [0.0, 1.0].iter().enumerate() {
            for (i, x) in [0.0, 1.0].iter().enumerate() {
                let name = format!("v{i}{j}{k}");
                writeln!(
                    t,
                    "[[vertex]]\nname = \"{name}\"\nat = [{:?}, {y:?}, {zk:?}]",
                    x + dx
                )
                .unwrap();
                vs.push(name);
            }
        }
    }
    let e = |t: &mut String, name: &str, a: &str, b: &str| {
        writeln!(
            t,
            "[[edge]]\nname = \"{name}\"\nfrom = \"{a}\"\nto = \"{b}\"\nn = {n}"
        )
        .unwrap();
    };
    for k in 0..3 {
        e(
            &mut t,
            &format!("x0{k}"),
            &format!("v00{k}"),
            &format!("v10{k}"),
        );
        e(
            &mut t,
            &format!("x1{k}"),
            &format!("v01{k}"),
            &format!("v11{k}"),
        );
        e(
            &mut t,
            &format!("y0{k}"),
            &format!("v00{k}"),
            &format!("v01{k}"),
        );
        e(
            &mut t,
            &format!("y1{k}"),
            &format!("v10{k}"),
            &format!("v11{k}"),
        );
    }
    for k in 0..2 {
        for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            e(
                &mut t,
                &format!("z{i}{j}{k}"),
                &format!("v{i}{j}{k}"),
                &format!("v{i}{j}{}", k + 1),
            );
        }
    }
    let face = |t: &mut String, name: &str, kind: &str, s: [String; 4]| {
        writeln!(
            t,
            "[[face]]\nname = \"{name}\"\nkind = \"{kind}\"\nE1 = \"{}\"\nE2 = \"{}\"\nE3 = \"{}\"\nE4 = \"{}\"",
            s[0], s[1], s[2], s[3]
        )
        .unwrap();
    };
    for k in 0..3 {
        // z = const: E1/E2 along y at x = 0, 1; E3/E4 along x at y = 0, 1.
        face(
            &mut t,
            &format!("fz{k}"),
            "minimal",
            [
                format!("y0{k}"),
                format!("y1{k}"),
                format!("x0{k}"),
                format!("x1{k}"),
            ],
        );
    }
    for k in 0..2 {
        let up = k + 1;
        face(
            &mut t,
            &format!("fx0{k}"),
            "minimal",
            [
                format!("z00{k}"),
                format!("z01{k}"),
                format!("y0{k}"),
                format!("y0{up}"),
            ],
        );
        face(
            &mut t,
            &format!("fx1{k}"),
            "minimal",
            [
                format!("z10{k}"),
                format!("z11{k}"),
                format!("y1{k}"),
                format!("y1{up}"),
            ],
        );
        face(
            &mut t,
            &format!("fy0{k}"),
            "minimal",
            [
                format!("z00{k}"),
                format!("z10{k}"),
                format!("x0{k}"),
                format!("x0{up}"),
            ],
        );
        face(
            &mut t,
            &format!("fy1{k}"),
            "minimal",
            [
                format!("z01{k}"),
                format!("z11{k}"),
                format!("x1{k}"),
                format!("x1{up}"),
            ],
        );
    }
    for (k, side) in [(0, "F6"), (1, "F5")] {
        writeln!(
            t,
            "[[volume]]\nname = \"b{k}\"\nlinear = \"direct\"\nF1 = \"fx0{k}\"\nF2 = \"fx1{k}\"\nF3 = \"fy0{k}\"\nF4 = \"fy1{k}\"\nF5 = \"fz{k}\"\nF6 = \"fz{}\"{}",
            k + 1,
            if orthogonal { format!("\northogonal = [\"{side}\"]") } else { String::new() }
        )
        .unwrap();
    }
    t
}

#[test]
fn orthogonality_at_an_interior_face_removes_the_kink_across_it() {
    let kink = |g: &job::Generated| g.report.face_interfaces[0].smoothness;
    let plain = generate(&sheared_pair(0.6, false, 9));
    let ortho = generate(&sheared_pair(0.6, true, 9));
    let fine = generate(&sheared_pair(0.6, true, 17));
    let (p, o, f) = (kink(&plain), kink(&ortho), kink(&fine));
    // The sheared volume's lines lean by atan(0.6) = 31° at the face; made orthogonal on both
    // sides, the kink is a third of that and halves under refinement (first order, as in 2D;
    // measured 11.2°, 6.0°, 3.2° mean at 9, 17, 33 nodes).
    assert!(
        (p.kink_mean_deg - 0.6f64.atan().to_degrees()).abs() < 1e-6,
        "{p:?}"
    );
    assert!(o.kink_mean_deg < 0.4 * p.kink_mean_deg, "{o:?} vs {p:?}");
    assert!(f.kink_mean_deg < 0.6 * o.kink_mean_deg, "{f:?} vs {o:?}");
    assert!(o.spacing_ratio_max < p.spacing_ratio_max);
    for v in ortho.report.volumes.iter().chain(&fine.report.volumes) {
        assert_eq!(v.quality.folded_cells, 0);
        assert!(v.picard.converged);
    }
    // The volume below is a box: its lines were orthogonal already and stay the box's grid.
    let below = volume(&ortho.blocks[0].1);
    let want = Grid3::rectilinear(
        &linspace(0.0, 1.0, 9),
        &linspace(0.0, 1.0, 9),
        &linspace(-1.0, 0.0, 9),
    );
    for c in 0..3 {
        for (a, w) in below.coord(c).iter().zip(want.coord(c)) {
            assert!((a - w).abs() < 1e-9, "{a} vs {w}");
        }
    }
}

#[test]
fn the_lid_example_runs_fold_free_with_a_smooth_interface_and_a_matching_connectivity_file() {
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/volume_topology_lid.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            case.to_str().unwrap(),
            "-o",
            "lid.x",
            "-o",
            "lid.conn",
            "--report",
            "r.json",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let c = check_connectivity3(&d.path().join("lid.x"), &d.path().join("lid.conn"));
    assert_eq!((c.interfaces.len(), c.patches.len()), (1, 10));
    assert!(c.families.iter().any(|(_, f)| f == "lid"));
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    for v in r["volumes"].as_array().unwrap() {
        assert_eq!(v["quality"]["folded_cells"], 0);
        assert_eq!(v["picard"]["converged"], true);
    }
    // Both volumes orthogonal at the shared face: the lines cross it nearly straight.
    let f = &r["face_interfaces"][0];
    assert_eq!(f["face"], "middle");
    assert!(f["kink_max_deg"].as_f64().unwrap() < 1.0, "{f}");
    // The lid: a surface face on Scherk's surface, the wall spacing held within 2 %.
    let w = &r["volumes"][1]["wall"];
    assert!(w["ratio_min"].as_f64().unwrap() > 0.98 && w["ratio_max"].as_f64().unwrap() < 1.02);
    assert!(w["angle_max_deg"].as_f64().unwrap() < 5.0, "{w}");
    let lid = volume(&read_plot3d(&d.path().join("lid.x")).unwrap().blocks[1]).clone();
    let [ni, nj, nk] = lid.dims();
    for j in 0..nj {
        for i in 0..ni {
            let p = lid.point(i, j, nk - 1);
            let z = (p[1].cos() / p[0].cos()).ln();
            assert!(
                (p[2] - z).abs() < 1e-9,
                "lid node ({i}, {j}) off Scherk's surface"
            );
        }
    }
}
