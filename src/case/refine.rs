//! Grid families: a case refined `level` times, every direction from N to (N − 1)·2^level + 1
//! nodes, every boundary distribution refined in its own parameter
//! ([`ellipgrid_geometry::Distribution::sample_refined`]), so that the nodes of the coarse
//! case are every 2^level-th node of the fine one, boundary nodes included, and the finer
//! grids discretize the same continuous map (ξ, η) → x (`ellipgrid verify`).
//!
//! Vinokur distributions keep their fitted stretching function (the end spacings then shrink
//! by ~2^level, not exactly); geometric ones keep their growth law (ratio r^(1/2^level));
//! uniform ones stay uniform. Edges given by their nodes (`curve = { type = "nodes" }`) and
//! volume faces read from a file cannot be refined: they are refused, naming the edge.

use super::spec::{Case, CurveSpec, DistributionSpec, EdgeSpec, SideSpec};
use super::LoadedCase;
use crate::grid::Edge;
use crate::{Error, Result};

/// Nodes of a direction of `n` nodes refined `level` times: (n − 1)·2^level + 1.
///
/// # Errors
/// [`Error::Input`] at `place` if the count overflows.
pub fn refined_count(n: usize, level: u32, place: &str) -> Result<usize> {
    n.checked_sub(1)
        .and_then(|m| 1usize.checked_shl(level).and_then(|f| m.checked_mul(f)))
        .and_then(|m| m.checked_add(1))
        .filter(|_| level < usize::BITS)
        .ok_or_else(|| {
            Error::input(
                place,
                format!("{n} nodes refined {level} times do not fit a node count"),
            )
        })
}

/// The distribution `d` of an edge of `n` nodes refined `level` times.
fn refine_distribution(d: &DistributionSpec, n: usize, level: u32) -> DistributionSpec {
    match d {
        // already a family member: refine its base further
        DistributionSpec::Refined { base, n, level: l } => DistributionSpec::Refined {
            base: base.clone(),
            n: *n,
            level: l + level,
        },
        _ => DistributionSpec::Refined {
            base: Box::new(d.clone()),
            n,
            level,
        },
    }
}

/// An inline edge of `n` nodes refined `level` times; an edge given by its nodes is refused.
fn refine_edge(spec: &mut EdgeSpec, n: usize, level: u32, place: &str) -> Result<()> {
    if let Some(CurveSpec::Nodes { .. }) = spec.curve {
        return Err(Error::input(
            place,
            "the edge is given by its nodes (curve = { type = \"nodes\" }), which cannot be \
             refined for a grid family: give its curve and distribution instead",
        ));
    }
    spec.distribution = refine_distribution(&spec.distribution, n, level);
    Ok(())
}

impl LoadedCase {
    /// The case refined `level` times (module docs); level 0 is the case itself.
    ///
    /// # Errors
    /// [`Error::Input`] naming the block and edge for edges given by their nodes and volumes
    /// with faces from a file, and the checks of [`LoadedCase::from_case`] (sizes and memory
    /// of the refined case).
    pub fn refined(&self, level: u32) -> Result<LoadedCase> {
        if level == 0 {
            return Ok(self.clone());
        }
        let file = self.path.display().to_string();
        let mut case: Case = self.case.clone();
        let count = |n: usize, at: &str| refined_count(n, level, at);
        for e in case.edges.iter_mut() {
            let at = format!("{file}: edge '{}'", e.name);
            if let Some(CurveSpec::Nodes { .. }) = e.curve {
                return Err(Error::input(
                    at,
                    "the edge is given by its nodes, which cannot be refined for a grid \
                     family: give its curve and distribution instead",
                ));
            }
            e.distribution = refine_distribution(&e.distribution, e.n, level);
            e.n = count(e.n, &at)?;
        }
        for (k, b) in case.blocks.iter_mut().enumerate() {
            let at = self.block_place(k);
            let (ni, nj) = (b.ni, b.nj);
            if self.topology.is_none() {
                let (Some(ni), Some(nj)) = (ni, nj) else {
                    return Err(Error::input(at, "the block needs ni and nj"));
                };
                for (e, side) in Edge::ALL
                    .into_iter()
                    .zip([&mut b.e1, &mut b.e2, &mut b.e3, &mut b.e4])
                {
                    let n = if e.runs_along_i() { ni } else { nj };
                    if let Some(SideSpec::Edge(spec)) = side {
                        refine_edge(spec, n, level, &format!("{at}, edge {e}"))?;
                    }
                }
            }
            b.ni = ni.map(|n| count(n, &at)).transpose()?;
            b.nj = nj.map(|n| count(n, &at)).transpose()?;
        }
        for (k, v) in case.volumes.iter_mut().enumerate() {
            let at = crate::case::volume::volume_place(self, k);
            if v.faces.is_some() {
                return Err(Error::input(
                    at,
                    "faces read from a file cannot be refined for a grid family: give the \
                     volume's twelve edges instead",
                ));
            }
            let given = [v.ni, v.nj, v.nk];
            let edges = [
                &mut v.e1, &mut v.e2, &mut v.e3, &mut v.e4, &mut v.e5, &mut v.e6, &mut v.e7,
                &mut v.e8, &mut v.e9, &mut v.e10, &mut v.e11, &mut v.e12,
            ];
            for (e, spec) in edges.into_iter().enumerate() {
                if let (Some(spec), Some(n)) = (spec, given[e / 4]) {
                    refine_edge(spec, n, level, &format!("{at}, edge E{}", e + 1))?;
                }
            }
            // (a volume of a volume topology takes its counts from its faces' edges, refined
            // above; given counts are checked against them)
            v.ni = v.ni.map(|n| count(n, &at)).transpose()?;
            v.nj = v.nj.map(|n| count(n, &at)).transpose()?;
            v.nk = v.nk.map(|n| count(n, &at)).transpose()?;
        }
        LoadedCase::from_case(case, &self.path)
    }
}
