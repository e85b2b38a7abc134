//! Shared helpers of the integration tests: running the binary, temporary case files.
#![allow(dead_code)]

pub mod foam;

use ellipgrid::grid::Grid2;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Largest |a − b| over the coordinate arrays of two grids of the same size
/// (`Grid2::coords`, `Grid3::coords`).
pub fn max_diff(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(u, v)| u.iter().zip(v).map(|(p, q)| (p - q).abs()))
        .fold(0.0, f64::max)
}

/// Runs the `ellipgrid` binary with `args` in `dir`.
pub fn ellipgrid(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ellipgrid"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the ellipgrid binary runs")
}

/// stdout + stderr of a run, for messages in assertions.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// The repository root (for the shipped examples).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A case file with one block of four edges given as TOML tables.
pub fn one_block_case(ni: usize, nj: usize, e1: &str, e2: &str, e3: &str, e4: &str) -> String {
    format!(
        "[[block]]\nname = \"b\"\nni = {ni}\nnj = {nj}\n[block.E1]\n{e1}\n[block.E2]\n{e2}\n\
         [block.E3]\n{e3}\n[block.E4]\n{e4}\n"
    )
}

/// A unit-square case with uniform edges.
pub fn square_case(ni: usize, nj: usize) -> String {
    one_block_case(
        ni,
        nj,
        "curve = { type = \"line\", from = [0, 0], to = [0, 1] }",
        "curve = { type = \"line\", from = [1, 0], to = [1, 1] }",
        "curve = { type = \"line\", from = [0, 0], to = [1, 0] }",
        "curve = { type = \"line\", from = [0, 1], to = [1, 1] }",
    )
}

/// Runs `case` (written as `bad.toml`) and checks what every bad input must give: exit 2, the
/// `needles` in the message, no panic, and no file written (not even a partial one).
pub fn rejects(case: &str, needles: &[&str]) {
    let d = tempfile::tempdir().unwrap();
    std::fs::write(d.path().join("bad.toml"), case).unwrap();
    let o = ellipgrid(
        d.path(),
        &["run", "bad.toml", "-o", "out.x", "--report", "r.json"],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    for n in needles {
        assert!(t.contains(n), "message lacks '{n}': {t}");
    }
    assert!(!t.contains("panicked"), "{t}");
    let left: Vec<_> = std::fs::read_dir(d.path()).unwrap().collect();
    assert_eq!(left.len(), 1, "files written: {left:?}");
}

/// Node `p` of a surface grid.
pub fn grid_node(g: &Grid2<3>, p: usize) -> [f64; 3] {
    [g.coord(0)[p], g.coord(1)[p], g.coord(2)[p]]
}

/// Σ ½ |d₁ × d₂| over the cells of a surface grid (exact for planar quads and for the
/// triangles at a pole).
pub fn grid_area(g: &Grid2<3>) -> f64 {
    let (ni, nj) = (g.ni(), g.nj());
    let mut a = 0.0;
    for j in 0..nj - 1 {
        for i in 0..ni - 1 {
            let p = |ii: usize, jj: usize| grid_node(g, ii + ni * jj);
            let (x0, x1, x2, x3) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            let d1 = [x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]];
            let d2 = [x3[0] - x1[0], x3[1] - x1[1], x3[2] - x1[2]];
            let c = [
                d1[1] * d2[2] - d1[2] * d2[1],
                d1[2] * d2[0] - d1[0] * d2[2],
                d1[0] * d2[1] - d1[1] * d2[0],
            ];
            a += 0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        }
    }
    a
}

/// OpenFOAM's aspect ratio of a planar grid's cells, as `checkMesh` computes it on the extruded
/// mesh: per cell the larger over the smaller of the summed magnitudes of its faces' area
/// components in x and y, i.e. of Σ|Δy| and Σ|Δx| over the cell's four sides (the ratio of its
/// Cartesian extents: a thin cell counts in full only where it lies along x or y). The largest
/// over the grid, and its cell (i, j).
pub fn foam_aspect_ratio_max(g: &ellipgrid::Grid2<2>) -> (f64, usize, usize) {
    let mut worst = (0.0, 0, 0);
    for j in 0..g.nj() - 1 {
        for i in 0..g.ni() - 1 {
            let c = [
                g.point(i, j),
                g.point(i + 1, j),
                g.point(i + 1, j + 1),
                g.point(i, j + 1),
            ];
            let (mut sx, mut sy) = (0.0, 0.0);
            for (k, p) in c.iter().enumerate() {
                let q = c[(k + 1) % 4];
                sx += (q[1] - p[1]).abs();
                sy += (q[0] - p[0]).abs();
            }
            let r = sx.max(sy) / sx.min(sy);
            if r > worst.0 {
                worst = (r, i, j);
            }
        }
    }
    worst
}

/// Errors of a grid family at n, 2n − 1, 4n − 3, … nodes fall at second order: every ratio of
/// successive errors within 3.3 … 5 (4 per halving).
pub fn assert_second_order(name: &str, errs: &[f64]) {
    for w in errs.windows(2) {
        let r = w[0] / w[1];
        assert!(
            (3.3..5.0).contains(&r),
            "{name}: errors {errs:?}, ratio {r}"
        );
    }
}

/// `ellipgrid step grid STEP --all --ni NI --nj NJ -o OUT` run in `dir`.
pub fn step_grid_all(dir: &Path, step: &str, (ni, nj): (&str, &str), out: &str) -> Output {
    ellipgrid(
        dir,
        &[
            "step", "grid", step, "--all", "--ni", ni, "--nj", nj, "-o", out,
        ],
    )
}
