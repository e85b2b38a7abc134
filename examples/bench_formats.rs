//! Benchmark of the grid writers (#19, item 5): one warped volume block of n³ nodes (default
//! 216³ ≈ 10 M) written as Plot3D (unformatted double), OpenFOAM polyMesh (ASCII and binary),
//! SU2, Gmsh MSH 4.1 and, with the `cgns` feature, CGNS; wall seconds, CPU seconds of the
//! process (all threads: the work, whatever else runs on the machine) and MB/s per format, and
//! the peak resident memory (VmHWM) after each against the grid's own size.
//!
//! `cargo run --release --example bench_formats [--features cgns] -- [n] [--dir DIR]`

use ellipgrid::io::mesh::{sides_as_patches, Mesh};
use ellipgrid::io::plot3d::{write_plot3d, Plot3dFormat};
use ellipgrid::io::{foam, gmsh, su2, Block};
use ellipgrid::Grid3;
use std::path::{Path, PathBuf};
use std::time::Instant;

fn peak_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|v| v.parse::<f64>().ok())
            })
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// User + system CPU seconds of this process so far (all threads).
fn cpu_s() -> f64 {
    // SAFETY: getrusage writes into the zeroed struct it is given.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) } != 0 {
        return f64::NAN;
    }
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}

fn size_mb(p: &Path) -> f64 {
    if p.is_dir() {
        std::fs::read_dir(p)
            .map(|d| d.flatten().map(|e| size_mb(&e.path())).sum())
            .unwrap_or(0.0)
    } else {
        std::fs::metadata(p).map_or(0.0, |m| m.len() as f64 / 1e6)
    }
}

fn main() -> ellipgrid::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = args.first().and_then(|s| s.parse().ok()).unwrap_or(216);
    let dir = args
        .iter()
        .position(|a| a == "--dir")
        .and_then(|k| args.get(k + 1))
        .map(PathBuf::from)
        .unwrap_or_else(std::env::temp_dir)
        .join("ellipgrid_bench_formats");
    std::fs::create_dir_all(&dir).map_err(|e| ellipgrid::Error::io(&dir, e))?;
    let h = (n - 1) as f64;
    let g = Grid3::from_fn(n, n, n, |i, j, k| {
        let (x, y, z) = (i as f64 / h, j as f64 / h, k as f64 / h);
        [
            x + 0.05 * (3.0 * y).sin(),
            y * y + 0.1 * y,
            z + 0.05 * (2.0 * x).cos(),
        ]
    });
    let blocks = vec![("box".to_string(), Block::Volume(g))];
    let grid_mb = (n * n * n * 24) as f64 / 1e6;
    println!(
        "grid {n}³ = {:.2} M nodes, {grid_mb:.0} MB of coordinates; peak so far {:.0} MB",
        (n * n * n) as f64 / 1e6,
        peak_mb()
    );
    let conn = sides_as_patches(&blocks);
    let time = |name: &str, path: &Path, f: &dyn Fn() -> ellipgrid::Result<()>| {
        let (t, c) = (Instant::now(), cpu_s());
        let r = f();
        let (s, cpu) = (t.elapsed().as_secs_f64(), cpu_s() - c);
        let mb = size_mb(path);
        println!(
            "{name:<15} {s:6.2} s  cpu {cpu:6.2} s  {mb:6.0} MB  {:5.0} MB/s  peak {:.0} MB",
            mb / s,
            peak_mb()
        );
        r
    };
    let p = dir.join("grid.x");
    time("plot3d", &p, &|| {
        write_plot3d(&p, &[&blocks[0].1], &Plot3dFormat::default(), None)
    })?;
    let (t, c) = (Instant::now(), cpu_s());
    let mesh = Mesh::build("bench", &blocks, &conn, None)?;
    println!(
        "{:<15} {:6.2} s  cpu {:6.2} s  (io::mesh::Mesh::build)  peak {:.0} MB",
        "merge",
        t.elapsed().as_secs_f64(),
        cpu_s() - c,
        peak_mb()
    );
    let p = dir.join("constant/polyMesh");
    time("openfoam", &p, &|| foam::write_polymesh(&p, &mesh))?;
    let p = dir.join("binary/polyMesh");
    time("openfoam binary", &p, &|| {
        foam::write_polymesh_as(&p, &mesh, true)
    })?;
    let p = dir.join("grid.su2");
    time("su2", &p, &|| su2::write_su2(&p, &mesh))?;
    let p = dir.join("grid.msh");
    time("gmsh", &p, &|| gmsh::write_msh(&p, &mesh))?;
    #[cfg(feature = "cgns")]
    {
        let p = dir.join("grid.cgns");
        time("cgns", &p, &|| {
            ellipgrid::io::cgns::write_cgns(&p, &blocks, &conn)
        })?;
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}
