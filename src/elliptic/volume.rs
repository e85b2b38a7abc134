//! Volume grids (paper Section 5, METHOD.md §6): six face grids → twelve arclength edge
//! functions → algebraic bilinear transformation [70–72, 90–92] → 18 control functions
//! [83, 84] → Picard iteration of the grid system [86–88] on a 19-point stencil.
//!
//! | stage | module |
//! |---|---|
//! | faces, edges; transfinite start | [`crate::grid::faces`]; [`crate::algebraic::transfinite3d`] |
//! | edge functions, bilinear transformation [70–72] | [`crate::algebraic::bilinear3d`] |
//! | control functions [83, 84] | [`crate::algebraic::control3d`] |
//! | 19-point operator | [`crate::solve::stencil19`] |
//! | grid system [86–88], (inexact) Picard | [`crate::elliptic::poisson3d`] |
//! | nested iteration, work units | [`crate::elliptic::nested3d`] |
//! | linear solvers (Bi-CGSTAB/ILU(0), faer LU, multigrid) | [`crate::solve::ilu`], [`crate::solve::direct`], [`crate::solve::multigrid3d`] |
//! | quality report | [`crate::quality::quality3d`] |
//! | prescribed first-cell heights at a wall face | [`crate::elliptic::wall`] |
//!
//! The entry point is [`grid_volume`].

use crate::solve::stencil19::Stencil19;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::algebraic::control3d::control_for;
use crate::algebraic::transfinite3d::transfinite;
use crate::algebraic::ControlKind;
use crate::elliptic::picard::{PicardParams, PicardStep, VolumeResult};
use crate::elliptic::{nested3d, poisson3d};
use crate::grid::faces::Faces;
use crate::solve::LinearSolver;
use crate::{Grid3, Result};

static PROGRESS: AtomicBool = AtomicBool::new(false);

/// Enables (or disables) the terminal progress bars: of long volume solves (Picard step and
/// residual) and over the blocks of a multi-block case, on stderr, drawn only when stderr is
/// a terminal. Off by default; the CLI turns it on unless `--quiet`.
pub fn set_progress(on: bool) {
    PROGRESS.store(on, Ordering::Relaxed);
}

/// True if progress bars are enabled (see [`set_progress`]).
pub fn progress_enabled() -> bool {
    PROGRESS.load(Ordering::Relaxed)
}

/// Grids one volume block: transfinite start (or `start`, whose boundary nodes are replaced
/// by the faces'), control functions of `kind`, Picard iteration of [86]. `progress` sees
/// every Picard step (of the finest level).
///
/// Without `start`, and with nested iteration on ([`nested3d::nested_for3`]: by default with
/// the multigrid and the Bi-CGSTAB solvers), the block is solved by [`nested3d`] instead,
/// which also reports the work units.
pub fn grid_volume(
    faces: &Faces,
    start: Option<Grid3>,
    kind: ControlKind,
    solver: &mut dyn LinearSolver<Stencil19>,
    params: &PicardParams,
    place: &str,
    progress: &mut dyn FnMut(usize, &PicardStep),
) -> Result<VolumeResult> {
    if start.is_none() && nested3d::nested_for3(params, solver.name()) {
        return nested3d::grid_volume_nested(faces, kind, solver, params, place, progress)
            .map(|r| r.0);
    }
    let mut x = match start {
        Some(g) if g.dims() == faces.dims() => g,
        Some(g) => {
            return Err(crate::Error::input(
                place,
                format!(
                    "start grid has {:?} nodes but the faces need {:?}",
                    g.dims(),
                    faces.dims()
                ),
            ))
        }
        None => transfinite(faces),
    };
    faces.apply_to(&mut x);
    let ctrl = control_for(faces, kind, place)?;
    let picard = poisson3d::solve(&mut x, &ctrl, solver, params, place, progress)?;
    Ok(VolumeResult { grid: x, picard })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::{direct::DirectLu3, ilu::BiCgStabIlu};

    #[test]
    fn tensor_product_box_is_an_exact_discrete_solution() {
        let xs: Vec<f64> = (0..9).map(|k| 2.0 * (k as f64 / 8.0).powf(1.5)).collect();
        let ys: Vec<f64> = (0..7)
            .map(|k| ((k as f64 / 6.0) * 1.2).sinh() / 1.2f64.sinh())
            .collect();
        let zs: Vec<f64> = (0..8)
            .map(|k| 0.5 * (k as f64 / 7.0).powi(2) + 0.3 * k as f64 / 7.0)
            .collect();
        let exact = Grid3::rectilinear(&xs, &ys, &zs);
        let faces = Faces::from_grid(&exact);
        for solver in [
            &mut DirectLu3::new() as &mut dyn LinearSolver<Stencil19>,
            &mut BiCgStabIlu::new(),
        ] {
            let r = grid_volume(
                &faces,
                None,
                ControlKind::Algebraic,
                solver,
                &PicardParams::default(),
                "box",
                &mut |_, _| {},
            )
            .unwrap();
            assert!(r.picard.converged, "{:?}", r.picard);
            for c in 0..3 {
                for (u, v) in r.grid.coord(c).iter().zip(exact.coord(c)) {
                    assert!((u - v).abs() < 1e-12, "{u} vs {v}");
                }
            }
        }
    }
}
