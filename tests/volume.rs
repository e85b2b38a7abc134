//! Volume grids (issue #6, METHOD.md §6): exactness on a box, independence of the start grid,
//! convergence under refinement, and the command line (run, check, smooth, bad faces).

mod common;
use common::*;
use ellipgrid::case::LoadedCase;
use ellipgrid::domain::ControlKind;
use ellipgrid::io::plot3d::{read_plot3d, write_plot3d, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::poisson2d::PicardParams;
use ellipgrid::volume::case3d::volume_faces;
use ellipgrid::volume::{grid_volume, transfinite, BiCgStabIlu, Faces};
use ellipgrid::Grid3;
use std::fs;
use std::path::Path;

/// The warped cube of examples/volume_warped_cube.toml with n nodes each way and, if
/// `uniform`, no clustering.
fn warped_cube(n: usize, uniform: bool) -> Faces {
    let mut text = fs::read_to_string(root().join("examples/volume_warped_cube.toml")).unwrap();
    for key in ["ni", "nj", "nk"] {
        text = text.replace(&format!("{key} = 25"), &format!("{key} = {n}"));
    }
    if uniform {
        text = text.replace("distribution = { type = \"vinokur\", first = 0.01 }", "");
    }
    let case = LoadedCase::parse(&text, Path::new("cube.toml")).unwrap();
    volume_faces(&case, 0, &PicardParams::default()).unwrap()
}

fn solve(faces: &Faces, start: Option<Grid3>) -> Grid3 {
    let r = grid_volume(
        faces,
        start,
        ControlKind::Algebraic,
        &mut BiCgStabIlu::new(),
        &PicardParams {
            tolerance: 1e-12,
            ..PicardParams::default()
        },
        "cube",
        &mut |_, _| {},
    )
    .unwrap();
    assert!(r.picard.converged, "{:?}", r.picard);
    r.grid
}

#[test]
fn the_grid_does_not_depend_on_the_start_grid() {
    let faces = warped_cube(13, false);
    let a = solve(&faces, None);
    // A scrambled, badly folded interior: every interior node moved by up to the block size.
    let mut s = transfinite(&faces);
    let d = s.dims();
    let mut seed = 12345u64;
    for c in 0..3 {
        for (p, v) in s.coords_mut()[c].iter_mut().enumerate() {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let r = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            let (i, j, k) = (p % d[0], (p / d[0]) % d[1], p / (d[0] * d[1]));
            if i > 0 && j > 0 && k > 0 && i + 1 < d[0] && j + 1 < d[1] && k + 1 < d[2] {
                *v += 0.8 * r;
            }
        }
    }
    assert!(ellipgrid::volume::quality3d(&s).is_folded());
    let b = solve(&faces, Some(s));
    for c in 0..3 {
        for (u, v) in a.coord(c).iter().zip(b.coord(c)) {
            assert!((u - v).abs() < 1e-9, "{u} vs {v}");
        }
    }
    assert!(!ellipgrid::volume::quality3d(&a).is_folded());
}

/// rms difference of two grids at the nodes of the coarser (every second node of the finer).
fn rms_common(coarse: &Grid3, fine: &Grid3) -> f64 {
    let [n, m, l] = coarse.dims();
    let mut sum = 0.0;
    for k in 0..l {
        for j in 0..m {
            for i in 0..n {
                let (p, q) = (coarse.point(i, j, k), fine.point(2 * i, 2 * j, 2 * k));
                sum += (0..3).map(|c| (p[c] - q[c]).powi(2)).sum::<f64>();
            }
        }
    }
    (sum / (n * m * l) as f64).sqrt()
}

#[test]
fn second_order_convergence_under_refinement() {
    let g: Vec<Grid3> = [9, 17, 33]
        .iter()
        .map(|&n| solve(&warped_cube(n, true), None))
        .collect();
    let (d1, d2) = (rms_common(&g[0], &g[1]), rms_common(&g[1], &g[2]));
    let ratio = d1 / d2;
    eprintln!("rms differences {d1:.3e} {d2:.3e}, ratio {ratio:.2}");
    assert!(ratio > 3.0 && ratio < 5.0, "ratio {ratio}");
}

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

#[test]
fn cli_runs_a_volume_case_and_checks_it() {
    let d = tmp();
    let case = root().join("examples/volume_warped_cube.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            case.to_str().unwrap(),
            "-o",
            "c.x",
            "-o",
            "c.vts",
            "--report",
            "r.json",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("volume 'cube' (25 × 25 × 25 nodes)"),
        "{}",
        text(&o)
    );
    let vts = fs::read_to_string(d.path().join("c.vts")).unwrap_or_default();
    assert!(vts.is_empty() || vts.contains("WholeExtent=\"0 24 0 24 0 24\""));
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    let v = &r["volumes"][0];
    assert_eq!(v["picard"]["converged"], true);
    assert_eq!(v["quality"]["folded_cells"], 0);
    assert_eq!(v["quality"]["faces"].as_array().unwrap().len(), 6);
    let f = read_plot3d(&d.path().join("c.x")).unwrap();
    assert!(matches!(&f.blocks[0], Block::Volume(g) if g.dims() == [25, 25, 25]));
    let c = ellipgrid(d.path(), &["check", "c.x", "--report", "q.json"]);
    assert!(c.status.success(), "{}", text(&c));
    let t = text(&c);
    assert!(
        t.contains("25 x 25 x 25 nodes") && t.contains("orthogonality F6"),
        "{t}"
    );
    // Smoothing the volume block keeps every boundary node bit for bit.
    let s = ellipgrid(
        d.path(),
        &["smooth", "c.x", "-o", "s.x", "--tolerance", "1e-9"],
    );
    assert!(s.status.success(), "{}", text(&s));
    let (Block::Volume(a), Block::Volume(b)) = (
        &f.blocks[0],
        &read_plot3d(&d.path().join("s.x")).unwrap().blocks[0],
    ) else {
        panic!("volume blocks expected")
    };
    let fa = Faces::from_grid(a);
    assert_eq!(fa, Faces::from_grid(b));
    let diff = (0..3)
        .flat_map(|c| {
            a.coord(c)
                .iter()
                .zip(b.coord(c))
                .map(|(u, v)| (u - v).abs())
        })
        .fold(0.0, f64::max);
    assert!(diff < 1e-7, "an already converged grid moves by {diff}");
}

#[test]
fn faces_that_do_not_meet_exit_2_naming_them() {
    let d = tmp();
    let mut g = Grid3::zeros(5, 4, 3);
    for k in 0..3 {
        for j in 0..4 {
            for i in 0..5 {
                g.set(i, j, k, [i as f64, j as f64, k as f64]);
            }
        }
    }
    let faces = Faces::from_grid(&g);
    let mut blocks: Vec<Block> = (0..6)
        .map(|f| Block::Surface(faces.face(f).clone()))
        .collect();
    if let Block::Surface(f2) = &mut blocks[1] {
        f2.coord_mut(0).iter_mut().for_each(|x| *x += 0.5); // F2 moved off the block
    }
    write_plot3d(
        &d.path().join("faces.x"),
        &blocks,
        &Plot3dFormat::default(),
        None,
    )
    .unwrap();
    let case = "[[volume]]\nname = \"v\"\nni = 5\nnj = 4\nnk = 3\nfaces = { file = \"faces.x\" }\n";
    fs::write(d.path().join("v.toml"), case).unwrap();
    let o = ellipgrid(d.path(), &["run", "v.toml", "-o", "v.x"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let t = text(&o);
    assert!(
        t.contains("volume 'v'") && t.contains("faces F2 and F5 do not meet on edge E6"),
        "{t}"
    );
    assert!(!d.path().join("v.x").exists());
    // With the faces intact the same case runs.
    blocks[1] = Block::Surface(faces.face(1).clone());
    write_plot3d(
        &d.path().join("faces.x"),
        &blocks,
        &Plot3dFormat::default(),
        None,
    )
    .unwrap();
    let o = ellipgrid(d.path(), &["run", "v.toml", "-o", "v.x"]);
    assert!(o.status.success(), "{}", text(&o));
}

/// The M6 wing block of examples/wing_m6_upper.toml (ONERA D sections on the M6 planform,
/// wall face F3, `wall = "F3"`) at 41 × 33 × 13 nodes: fold-free, and the first-cell height at
/// every wall node within 20 % of 1e-5 local chord at the leading edge, 2e-5 at the trailing
/// edge, linear in x/c in between (paper Section 5.3, Fig. 37–42). Without the wall correction
/// the heights next to the leading edge were 42 % of the target.
#[test]
fn wing_block_holds_the_prescribed_wall_spacing_fold_free() {
    use ellipgrid::volume::case3d::generate_volume;
    let path = root().join("examples/wing_m6_upper.toml");
    let mut text = fs::read_to_string(&path).unwrap();
    for (key, from, to) in [("ni", 65, 41), ("nj", 49, 33), ("nk", 25, 13)] {
        text = text.replace(&format!("{key} = {from}"), &format!("{key} = {to}"));
    }
    let case = LoadedCase::parse(&text, &path).unwrap();
    let (_, block, rep) = generate_volume(&case, 0).unwrap();
    assert!(rep.picard.converged, "{:?}", rep.picard);
    assert!(!rep.quality.is_folded(), "{}", rep.quality);
    let Block::Volume(g) = block else {
        panic!("not a volume block")
    };
    let [ni, _, nk] = g.dims();
    assert_eq!(g.dims(), [41, 33, 13]);
    let mut worst: f64 = 0.0;
    for k in 0..nk {
        let (le, te) = (g.point(0, 0, k), g.point(ni - 1, 0, k));
        let chord = te[0] - le[0];
        for i in 0..ni {
            let (p0, p1) = (g.point(i, 0, k), g.point(i, 1, k));
            let h = (0..3).map(|c| (p1[c] - p0[c]).powi(2)).sum::<f64>().sqrt();
            let target = chord * (1e-5 + 1e-5 * (p0[0] - le[0]) / chord);
            let r = h / target;
            assert!(
                (0.8..=1.2).contains(&r),
                "node ({i}, 0, {k}): h {h:.3e}, want {target:.3e}"
            );
            worst = worst.max((r - 1.0).abs());
        }
    }
    // The correction reaches ~1 % (the rest is arclength vs x/c interpolation).
    assert!(worst < 0.03, "worst relative error {worst}");
}
