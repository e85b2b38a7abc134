//! The algebraic stage: edge functions → parameter grids and control functions.
//!
//! | what | equations | module |
//! |---|---|---|
//! | straight-line transformation (2D), Lagrange transfinite start | [5, 6] [39, 40] | [`transform`] |
//! | bilinear transformation (3D) | [70–72] [90–92] | [`bilinear3d`] |
//! | Hermite-blended transformation (orthogonality) | [47–49] | [`blend`] |
//! | control functions P11, P12, P22 | [19, 20] | [`control2d`] |
//! | the 18 control functions of a volume | [83, 84] | [`control3d`] |
//! | Coons patches of volume faces from their edges | — | [`coons`] |
pub mod bilinear3d;
pub mod blend;
pub mod control2d;
pub mod control3d;
pub mod coons;
pub mod transform;

/// Which control functions drive the grid system.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ControlKind {
    /// From the straight-line algebraic transformation [19]: the paper's method (default).
    #[default]
    Algebraic,
    /// All zero: a Laplace (Winslow) grid, which loses boundary clustering. For comparison.
    Laplace,
}
