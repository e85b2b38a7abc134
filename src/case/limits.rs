//! Size limits, checked before anything is allocated: node counts with overflow-safe
//! arithmetic, an absolute cap, and the memory a job will need against the memory the
//! machine has ("this grid needs ~N GB, the machine has M GB available").
//!
//! The memory estimate uses the measured peak of a generation per node, rounded up
//! (issue #16, `examples/bench_memory.rs`): in 2D 296 bytes on a smooth block (curved 2049²,
//! Picard steps only) but ~980 where Newton steps run (dented square 1025²: the block
//! preconditioner's second hierarchy and the Krylov basis; ~1100 before the line factors went
//! to f32), kept at 1200; in 3D 748 (warped box 129³; 880 before), kept at 2 KB as the bound
//! for the blocks not measured (corrected volumes, other configurations). The available memory is `MemAvailable` of
//! `/proc/meminfo`, or the environment variable `ELLIPGRID_MEMORY_GB` when set (to allow
//! more, or less, than the machine reports); without either only the absolute cap applies.

use crate::solve::direct::lu_bytes;
use crate::{Error, Result};

/// At most this many nodes in one job (all blocks together): 2³¹.
pub const MAX_NODES: u64 = 1 << 31;

/// Peak bytes per node of a 2D block's generation (planar or surface), rounded up.
pub const BYTES_PER_NODE_2D: u64 = 1_200;

/// Peak bytes per node of a volume block's generation, rounded up.
pub const BYTES_PER_NODE_3D: u64 = 2_000;

pub use crate::io::MEMORY_VAR;

/// Bytes per node of a finished grid kept until it is written (three f64 coordinates).
pub const KEPT_BYTES_PER_NODE: u64 = 24;

/// What the blocks of a job add up to. Blocks are generated up to one per thread at a time
/// and kept until written, so the memory estimate is (threads × the largest block's peak) +
/// (every node × [`KEPT_BYTES_PER_NODE`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Budget {
    /// Nodes of all blocks.
    pub nodes: u64,
    /// Blocks added.
    pub blocks: u64,
    /// Peak bytes of the largest block's generation.
    pub largest: u64,
    /// Of `largest`, the bytes of a direct solver's LU (0 without one).
    pub largest_lu: u64,
}

impl Budget {
    /// Adds a block of `dims` nodes at `bytes_per_node`.
    ///
    /// # Errors
    /// [`Error::Input`] at `place` if a dimension is zero-sized in a product that overflows,
    /// or the job passes [`MAX_NODES`].
    pub fn add(&mut self, place: &str, dims: &[usize], bytes_per_node: u64) -> Result<()> {
        self.add_solved(place, dims, bytes_per_node, "")
    }

    /// [`Budget::add`] for a block solved by the linear solver called `linear`: "direct"
    /// adds the LU's memory ([`lu_bytes`] of every node of the block) to the block's peak.
    ///
    /// # Errors
    /// As [`Budget::add`].
    pub fn add_solved(
        &mut self,
        place: &str,
        dims: &[usize],
        bytes_per_node: u64,
        linear: &str,
    ) -> Result<()> {
        let shown: Vec<String> = dims.iter().map(usize::to_string).collect();
        let too_many = || {
            Error::input(
                place,
                format!(
                    "{} nodes: more than the {MAX_NODES} nodes a job may have",
                    shown.join(" × ")
                ),
            )
        };
        let n = dims
            .iter()
            .try_fold(1u64, |acc, &d| acc.checked_mul(d as u64))
            .filter(|&n| n <= MAX_NODES)
            .ok_or_else(too_many)?;
        self.nodes = self
            .nodes
            .checked_add(n)
            .filter(|&t| t <= MAX_NODES)
            .ok_or_else(too_many)?;
        self.blocks += 1;
        let lu = if linear == "direct" {
            lu_bytes(n as usize, dims.len().clamp(2, 3))
        } else {
            0
        };
        let peak = n.saturating_mul(bytes_per_node).saturating_add(lu);
        if peak > self.largest {
            (self.largest, self.largest_lu) = (peak, lu);
        }
        Ok(())
    }

    /// The estimated peak memory of the job (see [`Budget`]), in bytes.
    pub fn bytes(&self) -> u64 {
        let threads = rayon::current_num_threads() as u64;
        self.largest
            .saturating_mul(threads.min(self.blocks).max(1))
            .saturating_add(self.nodes.saturating_mul(KEPT_BYTES_PER_NODE))
    }

    /// Checks the estimated memory against the memory available.
    ///
    /// # Errors
    /// [`Error::Input`] at `place`, with both figures, if the job would not fit.
    pub fn check_memory(&self, place: &str) -> Result<()> {
        let Some(avail) = available_memory() else {
            return Ok(());
        };
        let bytes = self.bytes();
        if bytes > avail {
            let lu = if self.largest_lu > 0 {
                format!(
                    ", of which ~{:.3} GB for the LU of linear = \"direct\" (use linear = \
                     \"multigrid\", or \"bicgstab\" for a volume block)",
                    gb(self.largest_lu)
                )
            } else {
                String::new()
            };
            return Err(Error::input(
                place,
                format!(
                    "this grid ({} nodes) needs ~{:.3} GB{lu}, the machine has {:.3} GB \
                     available (set {MEMORY_VAR} to override)",
                    self.nodes,
                    gb(bytes),
                    gb(avail)
                ),
            ));
        }
        Ok(())
    }
}

fn gb(bytes: u64) -> f64 {
    bytes as f64 / 1e9
}

pub use crate::io::available_memory;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overflowing_and_huge_counts_are_errors_not_panics() {
        let mut b = Budget::default();
        assert!(b.add("x", &[usize::MAX, usize::MAX], 700).is_err());
        assert!(b.add("x", &[1 << 32, 1 << 32], 700).is_err());
        assert!(b.add("x", &[1 << 20, 1 << 10], 700).is_ok());
        assert!(b.add("x", &[1 << 20, 1 << 10], 700).is_ok());
        let e = b.add("x", &[2, 2], 700).unwrap_err().to_string();
        assert!(e.contains("2 × 2 nodes: more than the 2147483648"), "{e}");
        assert_eq!((b.nodes, b.blocks), (MAX_NODES, 2));
        assert_eq!(b.largest, (MAX_NODES / 2) * 700);
        let threads = rayon::current_num_threads().min(2) as u64;
        assert_eq!(b.bytes(), threads * (MAX_NODES / 2) * 700 + MAX_NODES * 24);
    }
}
