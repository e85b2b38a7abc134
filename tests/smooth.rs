//! `ellipgrid smooth`: regridding existing blocks read from Plot3D.

mod common;
use common::*;
use ellipgrid::algebraic::transform::transfinite;
use ellipgrid::grid::boundary::Boundary2;
use ellipgrid::io::plot3d::{read_plot3d, write_plot3d, Encoding, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::{Grid2, Grid3};
use std::fs;
use std::path::Path;

fn bits(c: &[f64]) -> Vec<u64> {
    c.iter().map(|v| v.to_bits()).collect()
}

/// A curved planar block from the shipped example, with its converged grid.
fn run_curved(dir: &Path) -> Grid2<2> {
    let case = root().join("examples/curved.toml");
    let o = ellipgrid(dir, &["run", case.to_str().unwrap(), "-o", "run.x", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
    match read_plot3d(&dir.join("run.x")).unwrap().blocks.remove(0) {
        Block::Planar(g) => g,
        b => panic!("unexpected {}", b.kind()),
    }
}

/// Deterministic pseudo-random numbers in [0, 1).
fn rng(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn scrambled(g: &Grid2<2>) -> Grid2<2> {
    let mut r = rng(7);
    Grid2::from_fn(g.ni(), g.nj(), |i, j| {
        if g.is_boundary(i, j) {
            g.point(i, j)
        } else {
            [-0.5 + 3.0 * r(), 2.0 * r()]
        }
    })
}

#[test]
fn smooth_reproduces_run_and_ignores_the_interior_it_is_given() {
    let d = tempfile::tempdir().unwrap();
    let run = run_curved(d.path());
    let b = Boundary2::from_grid(&run, "b").unwrap();
    let tfi = transfinite(&b);
    let scr = scrambled(&run);
    let volume = Grid3::from_coords(
        3,
        3,
        2,
        std::array::from_fn(|c| (0..18).map(|p| ((p >> c) & 1) as f64 + c as f64).collect()),
    );
    // A multi-block 3D file: the run grid's boundary with a scrambled interior, the same
    // with a transfinite interior, and an untouched surface block at z = 0.5.
    let lift = |g: &Grid2<2>, z: f64| {
        Block::Surface(Grid2::<3>::from_coords(
            g.ni(),
            g.nj(),
            [g.coord(0).to_vec(), g.coord(1).to_vec(), vec![z; g.len()]],
        ))
    };
    let input = vec![
        lift(&scr, 0.5),
        lift(&tfi, 0.5),
        Block::Volume(volume.clone()),
    ];
    let fmt = Plot3dFormat::default();
    write_plot3d(&d.path().join("in.x"), &input, &fmt, None).unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "smooth", "in.x", "-o", "out.x", "--blocks", "1,2", "--report", "s.json",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let out = read_plot3d(&d.path().join("out.x")).unwrap();
    assert_eq!(out.format, fmt);
    assert_eq!(out.blocks.len(), 3);
    // The unselected volume block is identical to the bit.
    assert_eq!(out.blocks[2], Block::Volume(volume));
    let flat = |b: &Block| match b {
        Block::Surface(g) => {
            assert!(g.coord(2).iter().all(|&z| z == 0.5));
            Grid2::<2>::from_coords(g.ni(), g.nj(), [g.coord(0).to_vec(), g.coord(1).to_vec()])
        }
        b => panic!("unexpected {}", b.kind()),
    };
    let (s1, s2) = (flat(&out.blocks[0]), flat(&out.blocks[1]));
    // Boundary nodes bit for bit.
    for g in [&s1, &s2] {
        for j in 0..g.nj() {
            for i in 0..g.ni() {
                if g.is_boundary(i, j) {
                    assert_eq!(bits(&g.point(i, j)), bits(&run.point(i, j)));
                }
            }
        }
    }
    // Independent of the interior it was given, and equal to the `run` grid.
    let diam = run.diameter();
    assert!(
        max_diff(s1.coords(), s2.coords()) / diam < 1e-9,
        "{:e}",
        max_diff(s1.coords(), s2.coords())
    );
    assert!(
        max_diff(s1.coords(), run.coords()) / diam < 1e-9,
        "{:e}",
        max_diff(s1.coords(), run.coords())
    );
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(r["blocks"][0]["start"], "transfinite");
    assert_eq!(r["blocks"][1]["start"], "existing interior");
    assert_eq!(r["blocks"][0]["method"], "planar (z = const)");
}

#[test]
fn smooth_keeps_the_input_flavour_and_unselected_blocks_byte_identical() {
    let d = tempfile::tempdir().unwrap();
    let run = run_curved(d.path());
    let other = Grid2::<2>::from_fn(9, 5, |i, j| [i as f64 * 0.37, (j * j) as f64 * 0.11]);
    let fmt = Plot3dFormat {
        encoding: Encoding::Stream,
        two_d: true,
        ..Plot3dFormat::default()
    };
    write_plot3d(
        &d.path().join("in.x"),
        &[Block::Planar(other.clone()), Block::Planar(scrambled(&run))],
        &fmt,
        None,
    )
    .unwrap();
    let o = ellipgrid(
        d.path(),
        &["smooth", "in.x", "-o", "out.x", "--blocks", "2", "-q"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let (a, b) = (
        fs::read(d.path().join("in.x")).unwrap(),
        fs::read(d.path().join("out.x")).unwrap(),
    );
    assert_eq!(a.len(), b.len());
    // header (block count, dims) and the whole first block are the same bytes
    let head = 4 + 2 * 2 * 4 + 2 * other.len() * 8;
    assert_eq!(a[..head], b[..head]);
    let out = read_plot3d(&d.path().join("out.x")).unwrap();
    assert_eq!(out.format, fmt);
    let Block::Planar(s) = &out.blocks[1] else {
        panic!()
    };
    assert!(max_diff(s.coords(), run.coords()) / run.diameter() < 1e-9);
}

#[test]
fn smooth_errors_exit_2_and_folds_exit_3_without_output() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("junk.x"), [7u8; 13]).unwrap();
    let o = ellipgrid(d.path(), &["smooth", "junk.x", "-o", "out.x"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("junk.x"));
    let g = Grid2::<2>::from_fn(5, 4, |i, j| [i as f64, j as f64]);
    write_plot3d(
        &d.path().join("g.x"),
        &[Block::Planar(g)],
        &Plot3dFormat::default(),
        None,
    )
    .unwrap();
    let o = ellipgrid(d.path(), &["smooth", "g.x", "-o", "out.x", "--blocks", "3"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("block 3"));
    // A boundary whose grid must fold (a notch almost through the block).
    let e4 = [
        [0.0, 2.0],
        [2.0, 0.02],
        [2.02, 1.99],
        [3.0, 1.99],
        [4.0, 2.0],
    ];
    let f = Grid2::<2>::from_fn(5, 3, |i, j| match j {
        0 => [i as f64, 0.0],
        2 => e4[i],
        _ => [i as f64, if i == 0 || i == 4 { 1.0 } else { 0.5 }],
    });
    write_plot3d(
        &d.path().join("f.x"),
        &[Block::Planar(f)],
        &Plot3dFormat::default(),
        None,
    )
    .unwrap();
    let o = ellipgrid(d.path(), &["smooth", "f.x", "-o", "out.x"]);
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(!d.path().join("out.x").exists());
    let o = ellipgrid(
        d.path(),
        &["smooth", "f.x", "-o", "out.x", "--allow-folded", "-q"],
    );
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(d.path().join("out.x").exists());
}

#[test]
fn smooth_method_surface_keeps_nodes_on_the_surface() {
    use ellipgrid_geometry::{Surface, TanhBump};
    let d = tempfile::tempdir().unwrap();
    let bump = TanhBump::default();
    let n = 65;
    // An existing grid on the bump with a distorted interior distribution.
    let g = Grid2::<3>::from_fn(n, n, |i, j| {
        let (u, v) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
        let (uu, vv) = (
            u + 0.1 * (std::f64::consts::PI * u).sin() * v * (1.0 - v),
            v,
        );
        let p = bump.point(uu, vv);
        [p.x, p.y, p.z]
    });
    write_plot3d(
        &d.path().join("in.x"),
        &[Block::Surface(g.clone())],
        &Plot3dFormat::default(),
        None,
    )
    .unwrap();
    let o = ellipgrid(
        d.path(),
        &["smooth", "in.x", "-o", "out.x", "--method", "surface", "-q"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let out = read_plot3d(&d.path().join("out.x")).unwrap();
    let Block::Surface(s) = &out.blocks[0] else {
        panic!()
    };
    let mut off = 0.0f64;
    let mut moved = 0.0f64;
    for p in 0..s.len() {
        let (i, j) = (p % n, p / n);
        let x = [s.coord(0)[p], s.coord(1)[p], s.coord(2)[p]];
        if s.is_boundary(i, j) {
            assert_eq!(bits(&x), bits(&g.point(i, j)), "boundary node ({i}, {j})");
        }
        // distance from the bump z(x, y)
        let z = bump.point(x[0] / 2.0, x[1] / 2.0).z;
        off = off.max((x[2] - z).abs());
        moved = moved.max((x[0] - g.coord(0)[p]).abs());
    }
    assert!(moved > 1e-2, "the interior was not regridded ({moved})");
    assert!(off < 2e-3, "nodes left the surface by {off}");
    // --method poisson regrids it as a minimal surface instead: off the bump
    let o = ellipgrid(d.path(), &["smooth", "in.x", "-o", "min.x", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
}
