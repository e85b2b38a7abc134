//! ellipgrid: elliptic structured grid generation after Spekreijse & Boerstoel (NLR TP 96338).
// Doc comments cite the paper's equations as [24], [86]–[88]: not links.
#![allow(rustdoc::broken_intra_doc_links)]
pub mod arclength;
pub mod blend;
pub mod boundary;
pub mod cad;
pub mod case;
pub mod control;
pub mod domain;
pub mod error;
pub mod grid;
pub mod harmonic;
pub mod inversion;
pub mod io;
pub mod job;
pub mod linsolve;
pub mod multigrid;
pub mod nested;
pub mod orthogonal;
pub(crate) mod picard;
pub mod plot;
pub mod poisson2d;
pub mod quality;
pub mod smooth;
pub mod stencil;
pub mod surfgrid;
pub mod transform;
pub mod volume;

pub use error::{Error, Result};
pub use grid::{Edge, Grid2, Grid3};
