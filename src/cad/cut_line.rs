//! The lines an untrimmed patch is cut along when its one block folds ([`super::crease`],
//! `boundary_cuts`): where, and why.

use std::fmt;

/// One line an untrimmed patch is cut along (a crease, or one of the other kinds).
#[derive(Clone, Debug, PartialEq)]
pub struct Crease {
    /// The iso-line's direction: 0 for u = `at`, 1 for v = `at`.
    pub dir: usize,
    /// Its normalized parameter (the patch's domain is [0, 1]²).
    pub at: f64,
    /// Smallest and largest turn of the normal across it over the samples, degrees (NaN
    /// where no sample has both normals).
    pub turn: [f64; 2],
    /// What the line is.
    pub kind: CutKind,
}

/// Why a patch is cut along an iso-line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CutKind {
    /// A crease: the normal turns by more than [`super::CREASE_TURN`] across it.
    Crease,
    /// Not a crease but a C0 iso-line along which a sub-patch between creases collapses to
    /// one point (the leading edge of a wing's cap: the cap, a lens between the airfoil and
    /// its camber line traversed twice, is cut there into two halves with cusps at both
    /// ends); the whole patch is cut along it.
    Pole,
    /// A C0 iso-line at which a side of a patch without creases turns by more than
    /// [`super::KINK_TURN`] (a cranked wing's leading edge in a flat patch):
    /// the block's corner goes there (`cad::boundary_cuts`).
    Kink,
    /// The patch folds back over itself beyond this line: the piece between it and the
    /// patch's side at parameter `end` (0 or 1) covers part of the rest a second time and is
    /// left out (`cad::boundary_cuts`).
    FoldBack { end: u8 },
}

impl fmt::Display for Crease {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let line = format!("{} = {:.4}", ["u", "v"][self.dir], self.at);
        let [a, b] = self.turn;
        match self.kind {
            CutKind::Pole => write!(f, "{line} (a cap collapses to a point along it)"),
            CutKind::Crease => write!(f, "{line} (normal turning {a:.0}°–{b:.0}°)"),
            CutKind::Kink => write!(f, "{line} (a side turns by {b:.0}° there)"),
            CutKind::FoldBack { end } => write!(
                f,
                "{line} (the patch folds back over itself between it and {} = {end}: left out)",
                ["u", "v"][self.dir]
            ),
        }
    }
}
