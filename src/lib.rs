//! ellipgrid: elliptic structured grid generation after Spekreijse & Boerstoel (NLR TP 96338).
//!
//! One folder per concern (`docs/ARCHITECTURE.md` maps them to METHOD.md): the numerics
//! ([`grid`], [`algebraic`], [`elliptic`], [`solve`], [`surface`], [`quality`]) never read
//! files, case tables or the command line; [`case`], [`job`], [`io`], [`cad`] and [`plot`] do.
// Doc comments cite the paper's equations as [24], [86]–[88]: not links.
#![allow(rustdoc::broken_intra_doc_links)]
pub mod algebraic;
pub mod cad;
pub mod case;
pub mod elliptic;
pub mod error;
pub mod grid;
pub mod io;
pub mod job;
pub mod plot;
pub mod quality;
pub mod solve;
pub mod surface;

pub use error::{Error, Result};
pub use grid::{Edge, Grid2, Grid3};
