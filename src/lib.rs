//! ellipgrid: elliptic structured grid generation after Spekreijse & Boerstoel (NLR TP 96338).
pub mod error;
pub mod grid;
pub mod io;
pub mod linsolve;
pub mod multigrid;
pub mod quality;
pub mod stencil;

pub use error::{Error, Result};
pub use grid::{Edge, Grid2, Grid3};
