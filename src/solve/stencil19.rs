//! The 19-point operator of one Picard step of the volume grid system [86–88].
//!
//! A [`Stencil19`] acts on the `nx × ny × nz` interior nodes of a volume block (unknowns i
//! fastest, then j, then k). Central differences of [86] couple a node to its 6 face
//! neighbours and its 12 edge neighbours (the mixed derivatives); the 8 cube corners never
//! appear, hence 27 − 8 = 19 coefficients a row. Couplings to boundary nodes are moved to the
//! right-hand side by the assembler, so coefficients that would reach outside the grid are zero.

use rayon::prelude::*;

/// Offsets (di, dj, dk) of the 19 coefficients, in the order of a row: centre, the six face
/// neighbours W E S N B T, then the ξη, ξζ and ηζ edge neighbours.
pub const OFFSETS: [[i8; 3]; 19] = [
    [0, 0, 0],
    [-1, 0, 0],
    [1, 0, 0],
    [0, -1, 0],
    [0, 1, 0],
    [0, 0, -1],
    [0, 0, 1],
    [-1, -1, 0],
    [1, -1, 0],
    [-1, 1, 0],
    [1, 1, 0],
    [-1, 0, -1],
    [1, 0, -1],
    [-1, 0, 1],
    [1, 0, 1],
    [0, -1, -1],
    [0, 1, -1],
    [0, -1, 1],
    [0, 1, 1],
];

/// Index of the centre coefficient.
pub const C: usize = 0;

/// The position in [`OFFSETS`] of an offset, if it is one of the 19.
pub fn slot(d: [i8; 3]) -> Option<usize> {
    OFFSETS.iter().position(|&o| o == d)
}

/// Nineteen-point operator on `nx × ny × nz` unknowns.
///
/// Row `p = i + nx (j + ny k)` reads `Σ_m coef[p][m] · u[p + offset_m]` with the offsets of
/// [`OFFSETS`]. Coefficients that would reach outside the grid are zero (and never read).
#[derive(Clone, Debug, PartialEq)]
pub struct Stencil19 {
    dims: [usize; 3],
    coef: Vec<[f64; 19]>,
}

impl Stencil19 {
    /// The zero operator on `nx × ny × nz` unknowns.
    pub fn zeros(nx: usize, ny: usize, nz: usize) -> Self {
        Stencil19 {
            dims: [nx, ny, nz],
            coef: vec![[0.0; 19]; nx * ny * nz],
        }
    }

    /// The operator on `nx × ny × nz` unknowns with the rows `coef` (taken over, not copied).
    ///
    /// # Panics
    /// If `coef` does not hold `nx · ny · nz` rows.
    pub fn from_coefs(dims: [usize; 3], coef: Vec<[f64; 19]>) -> Self {
        assert_eq!(
            coef.len(),
            dims.iter().product::<usize>(),
            "Stencil19::from_coefs: row count"
        );
        Stencil19 { dims, coef }
    }

    /// The rows, giving the operator up (no copy).
    pub fn into_coefs(self) -> Vec<[f64; 19]> {
        self.coef
    }

    /// Unknowns along i, j, k.
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// Number of unknowns.
    pub fn len(&self) -> usize {
        self.coef.len()
    }

    /// True for an operator without unknowns.
    pub fn is_empty(&self) -> bool {
        self.coef.is_empty()
    }

    /// Coefficients of all rows.
    pub fn coefs(&self) -> &[[f64; 19]] {
        &self.coef
    }

    /// Coefficients of all rows, mutable.
    pub fn coefs_mut(&mut self) -> &mut [[f64; 19]] {
        &mut self.coef
    }

    /// Linear offset of each of the 19 neighbours.
    pub fn linear_offsets(&self) -> [isize; 19] {
        let [nx, ny, _] = self.dims;
        let (sx, sy) = (nx as isize, (nx * ny) as isize);
        std::array::from_fn(|m| {
            let [a, b, c] = OFFSETS[m];
            a as isize + sx * b as isize + sy * c as isize
        })
    }

    /// Which of the 19 neighbours of row (i, j, k) lie inside the grid.
    #[inline]
    pub fn inside(&self, i: usize, j: usize, k: usize) -> [bool; 19] {
        Self::inside_of(self.dims, i, j, k)
    }

    /// Which of the 19 neighbours of row (i, j, k) lie inside a grid of `dims` unknowns.
    #[inline]
    pub fn inside_of(dims: [usize; 3], i: usize, j: usize, k: usize) -> [bool; 19] {
        let [nx, ny, nz] = dims;
        std::array::from_fn(|m| {
            let [a, b, c] = OFFSETS[m];
            let ok = |v: usize, d: i8, n: usize| match d {
                -1 => v > 0,
                1 => v + 1 < n,
                _ => true,
            };
            ok(i, a, nx) && ok(j, b, ny) && ok(k, c, nz)
        })
    }

    /// Zeroes every coefficient that points outside the grid.
    pub fn clip_to_grid(&mut self) {
        let [nx, ny, _] = self.dims;
        let inside: Vec<[bool; 19]> = (0..self.len())
            .map(|p| self.inside(p % nx, (p / nx) % ny, p / (nx * ny)))
            .collect();
        for (row, ins) in self.coef.iter_mut().zip(inside) {
            for (c, ok) in row.iter_mut().zip(ins) {
                if !ok {
                    *c = 0.0;
                }
            }
        }
    }

    /// y = A x (rayon over k-planes).
    pub fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.residual_into(None, x, y);
        y.par_iter_mut().for_each(|v| *v = -*v);
    }

    /// r = b − A x (rayon over k-planes).
    pub fn residual(&self, b: &[f64], x: &[f64], r: &mut [f64]) {
        self.residual_into(Some(b), x, r);
    }

    fn residual_into(&self, b: Option<&[f64]>, x: &[f64], r: &mut [f64]) {
        let [nx, ny, _] = self.dims;
        assert_eq!(x.len(), self.len());
        assert_eq!(r.len(), self.len());
        let plane = nx * ny;
        let off = self.linear_offsets();
        r.par_chunks_mut(plane).enumerate().for_each(|(k, rp)| {
            for j in 0..ny {
                for i in 0..nx {
                    let p = i + nx * (j + ny * k);
                    let a = &self.coef[p];
                    let interior =
                        i > 0 && i + 1 < nx && j > 0 && j + 1 < ny && k > 0 && k + 1 < self.dims[2];
                    let mut s = 0.0;
                    if interior {
                        for m in 0..19 {
                            s += a[m] * x[(p as isize + off[m]) as usize];
                        }
                    } else {
                        let ins = self.inside(i, j, k);
                        for m in 0..19 {
                            if ins[m] {
                                s += a[m] * x[(p as isize + off[m]) as usize];
                            }
                        }
                    }
                    rp[i + nx * j] = b.map_or(0.0, |b| b[p]) - s;
                }
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seven_point_laplacian_and_slots() {
        assert_eq!(slot([0, 0, 0]), Some(C));
        assert_eq!(slot([1, 1, 1]), None);
        let mut a = Stencil19::zeros(4, 3, 3);
        for row in a.coefs_mut() {
            row[C] = 6.0;
            for r in row.iter_mut().take(7).skip(1) {
                *r = -1.0;
            }
        }
        a.clip_to_grid();
        let x: Vec<f64> = (0..a.len()).map(|p| p as f64).collect();
        let mut y = vec![0.0; a.len()];
        a.apply(&x, &mut y);
        // Interior node (1,1,1): p = 1 + 4 (1 + 3) = 17; a linear function is harmonic.
        assert_eq!(y[17], 0.0);
        // Corner (0,0,0): 6·0 − (1 + 4 + 12) = −17.
        assert_eq!(y[0], -17.0);
    }
}
