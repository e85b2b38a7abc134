//! The elliptic stage: the grid systems [24] (2D, minimal surfaces) and [86]–[88] (volumes),
//! solved by inexact Picard iteration with nested iteration; the harmonic (Neumann) problems
//! of Section 2.4 and the wall corrections of volume blocks.
//!
//! | what | equations | module |
//! |---|---|---|
//! | one inexact Picard iteration (2D and 3D) | [41–44] | [`picard`] |
//! | Anderson acceleration of the Picard steps | [43, 44] | [`anderson`] |
//! | Newton–Krylov steps (Jacobian of [24], GMRES preconditioned by the Picard solver) | [24] | [`newton`] |
//! | the 2D / minimal-surface system, nine-point assembly | [24] [43, 44] | [`poisson2d`] |
//! | the 2D system on a block periodic in ξ (an O-grid's floating cut) | [24] [43, 44] | [`periodic`] |
//! | the volume system, 19-point assembly | [86]–[88] | [`poisson3d`] |
//! | nested iteration, work units | — | [`nested`], [`nested3d`] |
//! | one 2D block (Section 2, minimal surfaces Section 3) | [19–44] | [`domain`] |
//! | one volume block (Section 5) | [70–92] | [`volume`] |
//! | harmonic s, t with Neumann edges | [50–53] | [`harmonic`] |
//! | orthogonality at chosen edges (Section 2.4) | [46–49] | [`orthogonal`] |
//! | wall spacing and wall-normal lines of volume blocks | — | [`mod@wall`], [`wall_normal`] |
//! | wall spacing along edges of 2D blocks | — | [`wall2d`] |
//! | floating interior faces of a volume topology (the strip across a face) | [86]–[88] | [`floating3d`] |
//! | grid lines continued across an interior face from the volume beyond it | — | [`continuation`] |
pub mod anderson;
pub mod continuation;
pub mod crossing;
pub mod domain;
pub mod floating3d;
pub mod harmonic;
pub(crate) mod jacobian2d;
pub mod metric3d;
pub mod nested;
pub mod nested3d;
pub mod newton;
pub mod orthogonal;
pub mod orthogonal3d;
pub mod periodic;
pub mod periodic_orthogonal;
pub mod picard;
pub mod poisson2d;
pub mod poisson3d;
pub mod symmetry3d;
pub mod volume;
pub mod wall;
pub mod wall2d;
pub mod wall_normal;
pub mod wall_profile;
