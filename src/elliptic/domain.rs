//! The Section 2 pipeline for one 2D block: boundary → arclength edge functions [30–38] →
//! straight-line transformation [39, 40] → control functions [19] → Picard solve of [24].
//! The same pipeline grids a minimal surface (Section 3) when the boundary lies in R³.

use crate::algebraic::control2d::control_for;
use crate::algebraic::transform::transfinite;
use crate::algebraic::ControlKind;
use crate::elliptic::picard::BlockResult;
use crate::elliptic::picard::PicardParams;
use crate::elliptic::poisson2d;
use crate::grid::boundary::Boundary2;
use crate::grid::Grid2;
use crate::solve::LinearSolver;
use crate::Result;

/// Grids one block: transfinite start (or `start`, whose boundary nodes are replaced by
/// `b`'s), control functions of `kind`, Picard iteration of [24].
///
/// Without `start`, and with nested iteration on (`params.nested_for(solver.name())`: by
/// default with the multigrid solver), the block is solved by [`crate::elliptic::nested`] instead.
pub fn grid_block<const D: usize>(
    b: &Boundary2<D>,
    start: Option<Grid2<D>>,
    kind: ControlKind,
    solver: &mut dyn LinearSolver,
    params: &PicardParams,
    place: &str,
) -> Result<BlockResult<D>> {
    if start.is_none() && params.nested_for(solver.name()) {
        return crate::elliptic::nested::grid_block_nested(b, kind, solver, params, place)
            .map(|r| r.0);
    }
    let start = start.unwrap_or_else(|| transfinite(b));
    let ctrl = control_for(b, kind);
    let (grid, picard) = poisson2d::solve_from(b, start, &ctrl, solver, params, place)?;
    Ok(BlockResult { grid, picard })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::direct::DirectLu;

    #[test]
    fn rectangle_with_equal_opposite_distributions_is_exact() {
        let xs: Vec<f64> = (0..9).map(|k| 2.0 * (k as f64 / 8.0).powf(1.5)).collect();
        let ys: Vec<f64> = (0..7)
            .map(|k| ((k as f64 / 6.0) * 1.2).sinh() / 1.2f64.sinh())
            .collect();
        let exact = Grid2::<2>::from_fn(9, 7, |i, j| [xs[i], ys[j]]);
        let b = Boundary2::from_grid(&exact, "rect").unwrap();
        let r = grid_block(
            &b,
            None,
            ControlKind::Algebraic,
            &mut DirectLu::new(),
            &PicardParams::default(),
            "rect",
        )
        .unwrap();
        assert!(r.picard.converged);
        for c in 0..2 {
            for (u, v) in r.grid.coord(c).iter().zip(exact.coord(c)) {
                assert!((u - v).abs() < 1e-12, "{u} vs {v}");
            }
        }
    }
}
