//! Grid file output and input: Plot3D (every "whole" flavour, read with autodetection) and VTK
//! XML (`.vts` per block, `.vtm` for a multi-block set); for viewers glTF 2.0 ([`gltf`]) and OBJ
//! ([`obj`]) of the blocks' surfaces ([`patches`]). All writers are atomic: a file at the
//! target path is either the complete new output or untouched.

use std::io::{BufWriter, Write};
use std::path::Path;

use crate::{Error, Grid2, Grid3, Result};

#[cfg(feature = "cgns")]
pub mod cgns;
pub mod connectivity;
pub mod foam;
pub mod foam_case;
pub mod gltf;
pub mod gmsh;
pub mod mesh;
pub mod obj;
pub mod patches;
pub mod plot3d;
pub mod su2;
pub mod text;
pub mod vtk;
pub mod vtk_read;

/// One structured block as stored in a grid file.
#[derive(Clone, Debug, PartialEq)]
pub enum Block {
    /// A planar 2D grid (x, y).
    Planar(Grid2<2>),
    /// A surface grid in R³ (one layer of nodes, nk = 1).
    Surface(Grid2<3>),
    /// A volume grid.
    Volume(Grid3),
}

impl Block {
    /// Node counts (ni, nj, nk); nk = 1 for planar and surface grids.
    pub fn dims(&self) -> [usize; 3] {
        match self {
            Block::Planar(g) => [g.ni(), g.nj(), 1],
            Block::Surface(g) => [g.ni(), g.nj(), 1],
            Block::Volume(g) => g.dims(),
        }
    }

    /// Number of coordinate components stored: 2 for planar grids, 3 otherwise.
    pub fn ncoords(&self) -> usize {
        match self {
            Block::Planar(_) => 2,
            Block::Surface(_) | Block::Volume(_) => 3,
        }
    }

    /// Number of nodes, ni·nj·nk.
    pub fn nnodes(&self) -> usize {
        self.dims().iter().product()
    }

    /// Coordinate array of component `c` (0 = x, 1 = y, 2 = z), i fastest.
    ///
    /// # Panics
    /// If `c >= self.ncoords()`.
    pub fn coord(&self, c: usize) -> &[f64] {
        match self {
            Block::Planar(g) => g.coord(c),
            Block::Surface(g) => g.coord(c),
            Block::Volume(g) => g.coord(c),
        }
    }

    /// Short name of the block kind, for messages.
    pub fn kind(&self) -> &'static str {
        match self {
            Block::Planar(_) => "planar",
            Block::Surface(_) => "surface",
            Block::Volume(_) => "volume",
        }
    }
}

impl From<Grid2<2>> for Block {
    fn from(g: Grid2<2>) -> Self {
        Block::Planar(g)
    }
}

impl From<Grid2<3>> for Block {
    fn from(g: Grid2<3>) -> Self {
        Block::Surface(g)
    }
}

impl From<Grid3> for Block {
    fn from(g: Grid3) -> Self {
        Block::Volume(g)
    }
}

/// The environment variable that overrides the available memory (gigabytes).
pub const MEMORY_VAR: &str = "ELLIPGRID_MEMORY_GB";

/// The memory available to a job, in bytes: [`MEMORY_VAR`] if set (gigabytes), else
/// `MemAvailable` of `/proc/meminfo`, else unknown.
pub fn available_memory() -> Option<u64> {
    if let Ok(v) = std::env::var(MEMORY_VAR) {
        if let Ok(g) = v.trim().parse::<f64>() {
            if g.is_finite() && g > 0.0 {
                return Some((g * 1e9) as u64);
            }
        }
    }
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kb.checked_mul(1024)
}

/// Largest special file (device, pipe: no size known in advance) read as an input.
pub const MAX_SPECIAL_INPUT_BYTES: u64 = 256 << 20;

/// Reads a whole input file, refusing before the memory runs out: a regular file larger than
/// the memory available ([`available_memory`]), or a special file (a
/// device or a pipe, e.g. `/dev/zero`) longer than [`MAX_SPECIAL_INPUT_BYTES`].
///
/// # Errors
/// [`Error::Io`] if the file cannot be read, [`Error::Input`] naming it if it is a directory
/// or too large.
pub fn read_input(path: &Path) -> Result<Vec<u8>> {
    use std::io::Read;
    let f = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let meta = f.metadata().map_err(|e| Error::io(path, e))?;
    if meta.is_dir() {
        return Err(Error::input(path.display().to_string(), "is a directory"));
    }
    let avail = available_memory().unwrap_or(u64::MAX);
    let limit = if meta.is_file() {
        avail
    } else {
        MAX_SPECIAL_INPUT_BYTES.min(avail)
    };
    if meta.is_file() && meta.len() > limit {
        return Err(Error::input(
            path.display().to_string(),
            format!(
                "{} bytes: larger than the {limit} bytes of memory available",
                meta.len()
            ),
        ));
    }
    let cap = if meta.is_file() { meta.len() } else { 0 };
    let mut buf = Vec::with_capacity(usize::try_from(cap).unwrap_or(0));
    f.take(limit.saturating_add(1))
        .read_to_end(&mut buf)
        .map_err(|e| Error::io(path, e))?;
    if buf.len() as u64 > limit {
        return Err(Error::input(
            path.display().to_string(),
            format!("more than {limit} bytes (a device or a pipe that does not end?)"),
        ));
    }
    Ok(buf)
}

/// [`read_input`] of a text file (UTF-8).
///
/// # Errors
/// Those of [`read_input`], and [`Error::Io`] if the file is not UTF-8.
pub fn read_input_string(path: &Path) -> Result<String> {
    String::from_utf8(read_input(path)?).map_err(|_| {
        Error::io(
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidData, "not UTF-8 text"),
        )
    })
}

thread_local! {
    /// Files written inside [`staged`] on this thread: (temporary file, final path).
    static STAGE: std::cell::RefCell<Option<Vec<(tempfile::TempPath, std::path::PathBuf)>>> =
        const { std::cell::RefCell::new(None) };
}

/// Runs `f` with every [`write_atomic`] of this thread held back: the files are renamed onto
/// their paths, in the order written, only if `f` succeeds; if it fails, none is, and the
/// temporary files are removed. A run that fails after its first output thus leaves no
/// output at all. Stages do not nest: an inner `staged` joins the outer one.
///
/// # Errors
/// The error of `f`, or of a rename.
pub fn staged<T>(f: impl FnOnce() -> Result<T>) -> Result<T> {
    if STAGE.with(|s| s.borrow().is_some()) {
        // inside a stage already: the outer one renames or drops
        return f();
    }
    STAGE.with(|s| *s.borrow_mut() = Some(Vec::new()));
    let r = f();
    let files = STAGE.with(|s| s.borrow_mut().take()).unwrap_or_default();
    let value = r?;
    for (tmp, path) in files {
        tmp.persist(&path).map_err(|e| Error::io(&path, e.error))?;
    }
    Ok(value)
}

/// Writes a file atomically: `f` writes (buffered) into a temporary file in the directory of
/// `path`, which is renamed onto `path` only after `f` and the flush succeeded. On any error the
/// temporary file is removed and `path` is left untouched, so readers never see partial output.
/// Inside [`staged`] the rename waits for the end of the stage.
pub fn write_atomic(
    path: &Path,
    f: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let err = |e| Error::io(path, e);
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".ellipgrid-").suffix(".tmp");
    // NamedTempFile defaults to mode 0600; output files should get the usual 0666 & !umask.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let tmp = builder.tempfile_in(dir).map_err(err)?;
    let mut w = BufWriter::new(tmp);
    f(&mut w).map_err(err)?;
    let tmp = w.into_inner().map_err(|e| err(e.into_error()))?;
    tmp.as_file().sync_all().map_err(err)?;
    let tmp = STAGE.with(|s| match s.borrow_mut().as_mut() {
        Some(stage) => {
            stage.push((tmp.into_temp_path(), path.to_path_buf()));
            None
        }
        None => Some(tmp),
    });
    if let Some(tmp) = tmp {
        tmp.persist(path).map_err(|e| err(e.error))?;
    }
    Ok(())
}

/// [`write_atomic`] for writers that need a file name (a C library writing the file itself):
/// `f` writes the temporary file at the path it is given, which is renamed onto `path` only
/// if `f` succeeds (inside [`staged`], at the end of the stage).
pub fn write_atomic_path(path: &Path, f: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let tmp = tempfile::Builder::new()
        .prefix(".ellipgrid-")
        .suffix(".tmp")
        .tempfile_in(dir)
        .map_err(|e| Error::io(path, e))?
        .into_temp_path();
    f(&tmp)?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::Permissions::from_mode(0o644);
        std::fs::set_permissions(&tmp, mode).map_err(|e| Error::io(path, e))?;
    }
    let tmp = STAGE.with(|s| match s.borrow_mut().as_mut() {
        Some(stage) => {
            stage.push((tmp, path.to_path_buf()));
            None
        }
        None => Some(tmp),
    });
    if let Some(tmp) = tmp {
        tmp.persist(path).map_err(|e| Error::io(path, e.error))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_dims_and_coords() {
        let p = Block::from(Grid2::<2>::from_fn(3, 2, |i, j| [i as f64, j as f64]));
        assert_eq!(p.dims(), [3, 2, 1]);
        assert_eq!(p.ncoords(), 2);
        assert_eq!(p.nnodes(), 6);
        assert_eq!(p.coord(1), &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
        let v = Block::from(Grid3::zeros(2, 3, 4));
        assert_eq!(v.dims(), [2, 3, 4]);
        assert_eq!(v.ncoords(), 3);
        assert_eq!(v.kind(), "volume");
    }

    #[test]
    fn write_atomic_writes_and_replaces() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        write_atomic(&path, |w| w.write_all(b"first")).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"first");
        write_atomic(&path, |w| w.write_all(b"second")).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&path).unwrap().permissions().mode();
            assert_ne!(
                mode & 0o044,
                0,
                "output should be readable by others: {mode:o}"
            );
        }
    }

    #[test]
    fn write_atomic_failure_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        let r = write_atomic(&path, |w| {
            w.write_all(&[7u8; 100_000])?;
            Err(std::io::Error::other("boom"))
        });
        let e = r.unwrap_err().to_string();
        assert!(e.contains("out.txt") && e.contains("boom"), "{e}");
        assert!(!path.exists());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "temp file left behind"
        );

        // An existing file is left untouched by a failed rewrite.
        std::fs::write(&path, b"old").unwrap();
        assert!(write_atomic(&path, |_| Err(std::io::Error::other("boom"))).is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn write_atomic_bad_directory_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("missing").join("out.txt");
        let e = write_atomic(&path, |w| w.write_all(b"x")).unwrap_err();
        assert!(e.to_string().contains("out.txt"), "{e}");
    }
}
