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
    // A surface face without a surface.
    rejects(
        &good.replacen("kind = \"tfi\"", "kind = \"surface\"", 1),
        &["face 'fx000'", "needs surface"],
    );
}
