//! ellipgrid: elliptic structured grid generation after Spekreijse & Boerstoel (NLR TP 96338).
pub mod grid;
pub mod linsolve;
pub mod stencil;
