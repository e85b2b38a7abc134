//! Geometry for ellipgrid: curves, boundary point distributions, airfoils (and, later, surfaces).

/// Errors of the geometry crate.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum GeometryError {
    #[error("{0}")]
    Invalid(String),
}
