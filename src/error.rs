//! The crate's one error type. Every variant names where the problem is (file, block, edge)
//! so that the command line can print it as is.

use std::path::PathBuf;

/// Result with [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Errors of ellipgrid.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad user input: a malformed case file, edges that do not meet, NaN, … `place` names the
    /// file, block and edge ("case.toml: block 'duct', edge E3").
    #[error("{place}: {msg}")]
    Input { place: String, msg: String },

    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },

    /// A grid file is not in the expected format.
    #[error("{}: {msg}", path.display())]
    Format { path: PathBuf, msg: String },

    /// A geometric construction failed (curve, distribution, surface).
    #[error("{place}: {source}")]
    Geometry {
        place: String,
        source: ellipgrid_geometry::GeometryError,
    },

    /// A linear solve failed.
    #[error("{place}: {source}")]
    Solve {
        place: String,
        source: crate::solve::SolveError,
    },

    /// A property `ellipgrid verify` checks fails (the observed order of a grid family, the
    /// independence of the start grid or of the parametrization); `place` names the block.
    #[error("{place}: {msg}")]
    Property { place: String, msg: String },

    /// The generated grid folds (non-positive Jacobian at a cell corner).
    #[error("{place}: the grid folds: {count} folded cell(s), first at {first}")]
    Folded {
        place: String,
        count: usize,
        first: String,
    },
}

impl Error {
    /// A bad-input error at `place`.
    pub fn input(place: impl Into<String>, msg: impl Into<String>) -> Self {
        Error::Input {
            place: place.into(),
            msg: msg.into(),
        }
    }

    /// An I/O error on `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }

    /// A format error in file `path`.
    pub fn format(path: impl Into<PathBuf>, msg: impl Into<String>) -> Self {
        Error::Format {
            path: path.into(),
            msg: msg.into(),
        }
    }

    /// Process exit code: 2 for bad input (a direct solve too large for the memory counts as a
    /// grid too large), 3 for a folded grid, 4 for a solver failure, 5 for a property that
    /// `verify` finds broken.
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Solve {
                source: crate::solve::SolveError::OutOfMemory { .. },
                ..
            } => 2,
            Error::Input { .. }
            | Error::Io { .. }
            | Error::Format { .. }
            | Error::Geometry { .. } => 2,
            Error::Folded { .. } => 3,
            Error::Solve { .. } => 4,
            Error::Property { .. } => 5,
        }
    }
}
