//! The linear solvers by the names of case files and the command line: 2D ([`by_name`]) and
//! volume blocks ([`by_name3`], [`for_block`] with "auto").

use crate::solve::direct::{DirectLu, DirectLu3};
use crate::solve::ilu::BiCgStabIlu;
use crate::solve::multigrid::{MgParams, MultigridSafe};
use crate::solve::multigrid3d::Multigrid3;
use crate::solve::stencil19::Stencil19;
use crate::solve::LinearSolver;

/// The linear solver called `name` in case files: "direct" (sparse LU, the reference),
/// "multigrid" ([`MultigridSafe`] with the default [`MgParams`]: F(1,1) cycles with
/// alternating zebra line Gauss–Seidel, Bi-CGSTAB as the fallback; the default of case files)
/// or "multigrid-lean" (the same with [`MgParams::lean_y_lines`]: ~85 bytes per node less,
/// ~17 % more CPU time).
pub fn by_name(name: &str) -> Result<Box<dyn LinearSolver>, String> {
    match name {
        "direct" => Ok(Box::new(DirectLu::new())),
        "multigrid" => Ok(Box::new(MultigridSafe::new(MgParams::default()))),
        "multigrid-lean" => Ok(Box::new(MultigridSafe::new(MgParams {
            lean_y_lines: true,
            ..MgParams::default()
        }))),
        _ => Err(format!(
            "linear solver '{name}': expected \"direct\", \"multigrid\" or \"multigrid-lean\""
        )),
    }
}

/// The volume solver called `name` in case files and on the command line: "bicgstab"
/// (default), "multigrid" ([`crate::solve::multigrid3d::Multigrid3`], V(1,1) cycles) or "direct".
pub fn by_name3(name: &str) -> Result<Box<dyn LinearSolver<Stencil19>>, String> {
    match name {
        "bicgstab" | "iterative" => Ok(Box::new(BiCgStabIlu::new())),
        "direct" => Ok(Box::new(DirectLu3::new())),
        "multigrid" => Ok(Box::new(Multigrid3::default())),
        _ => Err(format!(
            "volume linear solver '{name}': expected \"auto\", \"bicgstab\", \"multigrid\" or \"direct\""
        )),
    }
}

/// Blocks of at least this many nodes use the 3D multigrid under "auto" (the default of
/// case files), smaller ones Bi-CGSTAB/ILU(0). Measured on the warped box of
/// `examples/bench_volume.rs` (whole nested solve, idle 2-core machine): 33³ Bi-CGSTAB 0.21 s
/// against multigrid 0.44 s; 65³ multigrid 2.44 s against 3.04 s; 129³ multigrid 21.2 s
/// against 47.8 s.
pub const AUTO_MULTIGRID_NODES: usize = 200_000;

/// The solver called `name` for a block of `dims` nodes: as [`by_name3`], plus "auto" —
/// "multigrid" from [`AUTO_MULTIGRID_NODES`] nodes, else "bicgstab".
pub fn for_block(name: &str, dims: [usize; 3]) -> Result<Box<dyn LinearSolver<Stencil19>>, String> {
    match name {
        "auto" if dims.iter().product::<usize>() >= AUTO_MULTIGRID_NODES => by_name3("multigrid"),
        "auto" => by_name3("bicgstab"),
        _ => by_name3(name),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_picks_multigrid_for_large_blocks_and_names_are_checked() {
        assert_eq!(
            for_block("auto", [33, 33, 33]).unwrap().name(),
            "bicgstab-ilu0"
        );
        assert_eq!(for_block("auto", [65, 65, 65]).unwrap().name(), "multigrid");
        assert_eq!(
            for_block("direct", [65, 65, 65]).unwrap().name(),
            "direct-lu"
        );
        let e = for_block("gmres", [9, 9, 9]).err().unwrap();
        assert!(e.contains("'gmres'") && e.contains("auto"), "{e}");
    }

    #[test]
    fn unknown_names_are_rejected() {
        assert!(by_name3("bicgstab").is_ok());
        assert!(by_name3("direct").is_ok());
        assert!(matches!(by_name3("cg"), Err(e) if e.contains("bicgstab")));
    }
}
