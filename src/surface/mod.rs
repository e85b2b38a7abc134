//! Parametrized surfaces (paper Section 4): the pipeline (boundary (u, v) from arclength,
//! Laplace–Beltrami on the initial grid [50–53], straight-line target grid) in [`pipeline`],
//! and the point location + bilinear inversion of its last step in [`inversion`]; faces bounded
//! by any curves on a surface (CAD faces, faces of volume topologies) in [`face`]; the Hermite
//! net of a block face on a CAD model (several faces) in [`net`]. Minimal
//! surfaces (Section 3) are 2D blocks in R³: [`crate::elliptic::domain`].
pub mod face;
pub mod inversion;
pub mod net;
pub mod pipeline;
pub mod untangle;
