//! The fuzz targets of ellipgrid's input paths (issue #17), one function per target, each
//! taking the raw bytes libFuzzer hands it. What a target checks: no panic, no abort, no
//! allocation above libFuzzer's `-rss_limit_mb`/`-malloc_limit_mb`, no run past `-timeout`.
//! Errors are the expected outcome of most inputs; a panic aborts the process (libfuzzer-sys
//! installs an aborting panic hook), except inside `cad::quietly`, where the STEP reader's and
//! truck's panics are caught by design and reported as errors.
//!
//! Every target runs with the memory the job may use capped ([`MEMORY_GB`]), so that an
//! input asking for a huge grid is refused by `case::limits` as the CLI would refuse it on a
//! small machine, instead of being gridded slowly.
//!
//! | target | input | what runs |
//! |---|---|---|
//! | `case` | a case file (TOML) | `LoadedCase::parse`, then every block's boundary or surface and edge (u, v), the start grids of blocks and volumes, the output settings: everything up to the elliptic solve |
//! | `plot3d` | a Plot3D grid file | `read_plot3d` (flavour detection, every flavour) |
//! | `vtk` | a `.vts` file | `read_vts` |
//! | `step` | a STEP file | the pre-scan, truck-stepio behind `cad::quietly`, every face's route; the first gridable face gridded at 5 × 5 |
//! | `conn` | a `.conn` file | `connectivity::parse`, then the solver mesh of two fixed planar blocks, the same extruded, and two fixed volume blocks |
//! | `smooth` | a Plot3D grid file | `smooth`'s path: `read_plot3d`, then `smooth_blocks` for files of at most [`SMOOTH_MAX_NODES`] nodes |

use ellipgrid::case::LoadedCase;
use ellipgrid::io::connectivity;
use ellipgrid::io::mesh::Mesh;
use ellipgrid::io::plot3d;
use ellipgrid::io::Block;
use ellipgrid::{cad, job, Grid2, Grid3};
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::Once;

/// The memory the jobs of the `case` target may use, gigabytes (`ELLIPGRID_MEMORY_GB`):
/// about 14 000 nodes of a 2D block, 5 000 of a volume.
pub const MEMORY_GB: &str = "0.01";

/// Largest file (all blocks' nodes) the `smooth` target regrids; larger ones are only read.
pub const SMOOTH_MAX_NODES: usize = 400;

/// Largest single allocation a target may make: 512 MiB, from inputs of a few kilobytes (the
/// `case` target's grids are capped far below by [`MEMORY_GB`]). Without a sanitizer
/// libFuzzer's `-malloc_limit_mb` sees no allocation, and an untouched one never shows in
/// the resident size, so the targets' allocator checks each request itself.
pub const MAX_ALLOC: usize = 512 << 20;

/// The system allocator, aborting (a crash libFuzzer records) on a request above
/// [`MAX_ALLOC`]: a runaway allocation driven by the input.
pub struct Capped;

// SAFETY: every call is passed on to the system allocator unchanged, or aborts.
unsafe impl GlobalAlloc for Capped {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        check(layout.size());
        System.alloc(layout)
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        check(layout.size());
        System.alloc_zeroed(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        check(new_size);
        System.realloc(ptr, layout, new_size)
    }
}

fn check(size: usize) {
    if size > MAX_ALLOC {
        use std::io::Write;
        // no allocation here: stderr is unbuffered, the number formats on the stack
        let _ = writeln!(
            std::io::stderr(),
            "==ellipgrid-fuzz== allocation of {size} bytes (more than {MAX_ALLOC})"
        );
        std::process::abort();
    }
}

#[global_allocator]
static ALLOC: Capped = Capped;

/// Most Picard steps of a fuzzed solve (the case file's `max_steps` is lowered to this).
const MAX_STEPS: usize = 20;

fn init() {
    static INIT: Once = Once::new();
    INIT.call_once(|| {
        // SAFETY (edition 2021: safe call): set once, before the library reads it and before
        // any thread of ours starts.
        std::env::set_var(ellipgrid::io::MEMORY_VAR, MEMORY_GB);
    });
}

/// The repository root: case files are placed in `examples/` so that their relative input
/// paths (`../data/…`) resolve as the shipped examples' do.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Target `case`: a case file up to (not including) the elliptic solve.
pub fn case(data: &[u8]) {
    init();
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = root().join("examples").join("fuzz.toml");
    let Ok(mut case) = LoadedCase::parse(text, &path) else {
        return;
    };
    case.case.solver.picard.max_steps = case.case.solver.picard.max_steps.min(MAX_STEPS);
    load_case(&case);
}

/// Everything `run` does with a loaded case before the elliptic solve; errors are fine.
fn load_case(case: &LoadedCase) {
    let _ = job::plot3d_format(case);
    for p in &case.case.output.files {
        let _ = job::output_kind(p);
    }
    let _ = ellipgrid::solve::select::by_name(&case.case.solver.linear);
    for k in 0..case.case.blocks.len() {
        let _ = case.block_orthogonal(k);
        match case.case.blocks[k].kind {
            ellipgrid::case::BlockKind::Planar => {
                let _ = case.planar_boundary(k);
            }
            ellipgrid::case::BlockKind::Minimal => {
                let _ = case.minimal_boundary(k);
                let _ = case.reference_surface(k);
            }
            ellipgrid::case::BlockKind::Surface => {
                let _ = case.surface_block(k);
            }
        }
    }
    let _ = job::start_grids(case);
}

/// Target `plot3d`: any Plot3D flavour.
pub fn plot3d(data: &[u8]) {
    init();
    let _ = plot3d::parse_plot3d(data, Path::new("fuzz.x"));
}

/// Target `vtk`: one `.vts` file.
pub fn vtk(data: &[u8]) {
    init();
    let _ = ellipgrid::io::vtk_read::vts_from_bytes(data, Path::new("fuzz.vts"));
}

/// Target `step`: a STEP file listed, and its first gridable face gridded at 5 × 5 (a face
/// with holes or a seamless band as its blocks).
pub fn step(data: &[u8]) {
    init();
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(faces) = cad::step_faces_from_text(text, Path::new("fuzz.step")) else {
        return;
    };
    let mut gridded = false;
    for f in &faces {
        let route = f.route();
        let _ = f.patch(Path::new("fuzz.step"));
        if gridded || matches!(route, cad::Route::Refused(_)) {
            continue;
        }
        gridded = true;
        let uniform = ellipgrid::case::DistributionSpec::Uniform {};
        let Ok(mut solver) = ellipgrid::solve::select::by_name("direct") else {
            continue;
        };
        let _ = cad::grid_face_blocks(f, (5, 5), &uniform, &uniform, solver.as_mut(), "fuzz");
    }
}

/// Named blocks, as the mesh builder takes them.
pub type Named = Vec<(String, Block)>;

/// The fixed blocks of the `conn` target: two planar blocks side by side (4 × 3 nodes each,
/// sharing the side x = 1) and two volume blocks likewise (4 × 3 × 2).
pub fn conn_blocks() -> (Named, Named) {
    let planar = |x0: f64| {
        Block::Planar(Grid2::<2>::from_fn(4, 3, |i, j| {
            [x0 + i as f64 / 3.0, j as f64 / 2.0]
        }))
    };
    let volume = |x0: f64| {
        Block::Volume(Grid3::from_fn(4, 3, 2, |i, j, k| {
            [x0 + i as f64 / 3.0, j as f64 / 2.0, k as f64]
        }))
    };
    (
        vec![("a".into(), planar(0.0)), ("b".into(), planar(1.0))],
        vec![("a".into(), volume(0.0)), ("b".into(), volume(1.0))],
    )
}

/// Target `conn`: a connectivity file, then the solver meshes it describes for the fixed
/// blocks of [`conn_blocks`] (planar, planar extruded as for OpenFOAM, volume).
pub fn conn(data: &[u8]) {
    init();
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(c) = connectivity::parse(text, Path::new("fuzz.conn")) else {
        return;
    };
    let (planar, volume) = conn_blocks();
    let _ = Mesh::build("fuzz", &planar, &c, None);
    let _ = Mesh::build("fuzz", &planar, &c, Some(0.1));
    let _ = Mesh::build("fuzz", &volume, &c, None);
}

/// Target `smooth`: `ellipgrid smooth`'s input path. The file is read; if it has at most
/// [`SMOOTH_MAX_NODES`] nodes, its blocks are regridded, with the solver and surface method
/// chosen by the input's length (direct or multigrid, Poisson or surface) so that every
/// path is reached from one corpus.
pub fn smooth(data: &[u8]) {
    use ellipgrid::job::smooth::{smooth_blocks, SmoothOptions, SurfaceMethod};
    init();
    let Ok(file) = plot3d::parse_plot3d(data, Path::new("fuzz.x")) else {
        return;
    };
    let nodes: usize = file.blocks.iter().map(Block::nnodes).sum();
    if nodes > SMOOTH_MAX_NODES {
        return;
    }
    let mut opts = SmoothOptions {
        linear: if data.len() % 2 == 0 {
            "direct".into()
        } else {
            "multigrid".into()
        },
        method: if data.len() % 4 < 2 {
            SurfaceMethod::Poisson
        } else {
            SurfaceMethod::Surface
        },
        ..SmoothOptions::default()
    };
    opts.picard.max_steps = MAX_STEPS;
    let _ = smooth_blocks(&file.blocks, "fuzz.x", &opts);
}
