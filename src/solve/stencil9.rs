//! Structured stencil operators: the linear systems of one Picard step.
//!
//! A [`Stencil9`] is the nine-point operator of [43–44] on the `nx × ny` interior nodes of a
//! block (unknowns i fastest). Couplings to boundary nodes are moved to the right-hand side
//! by the assembler, so a stencil never points outside its grid.

/// Position of a coefficient in a nine-point stencil: `k = (di + 1) + 3 (dj + 1)`.
pub mod dir {
    pub const SW: usize = 0;
    pub const S: usize = 1;
    pub const SE: usize = 2;
    pub const W: usize = 3;
    pub const C: usize = 4;
    pub const E: usize = 5;
    pub const NW: usize = 6;
    pub const N: usize = 7;
    pub const NE: usize = 8;
}

/// Nine-point operator on an `nx × ny` grid of unknowns.
///
/// Row `p = i + nx j` reads `Σ_{di,dj ∈ {−1,0,1}} coef[p][(di+1) + 3(dj+1)] · u[(i+di) + nx (j+dj)]`.
/// Coefficients that would reach outside the grid are zero.
#[derive(Clone, Debug, PartialEq)]
pub struct Stencil9 {
    nx: usize,
    ny: usize,
    coef: Vec<[f64; 9]>,
}

impl Stencil9 {
    /// The zero operator on `nx × ny` unknowns.
    pub fn zeros(nx: usize, ny: usize) -> Self {
        Stencil9 {
            nx,
            ny,
            coef: vec![[0.0; 9]; nx * ny],
        }
    }

    /// The operator on `nx × ny` unknowns with the rows `coef` (taken over, not copied).
    ///
    /// # Panics
    /// If `coef` does not hold `nx · ny` rows.
    pub fn from_coefs(nx: usize, ny: usize, coef: Vec<[f64; 9]>) -> Self {
        assert_eq!(coef.len(), nx * ny, "Stencil9::from_coefs: row count");
        Stencil9 { nx, ny, coef }
    }

    /// The rows, giving the operator up (no copy).
    pub fn into_coefs(self) -> Vec<[f64; 9]> {
        self.coef
    }

    /// Unknowns along i.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Unknowns along j.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Number of unknowns.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// True for an operator without unknowns.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Coefficients of all rows.
    pub fn coefs(&self) -> &[[f64; 9]] {
        &self.coef
    }

    /// Coefficients of all rows, mutable.
    pub fn coefs_mut(&mut self) -> &mut [[f64; 9]] {
        &mut self.coef
    }

    /// Coefficients of row (i, j).
    #[inline]
    pub fn row(&self, i: usize, j: usize) -> &[f64; 9] {
        &self.coef[i + self.nx * j]
    }

    /// Zeroes every coefficient that points outside the grid.
    pub fn clip_to_grid(&mut self) {
        let (nx, ny) = (self.nx, self.ny);
        for j in 0..ny {
            for i in 0..nx {
                let row = &mut self.coef[i + nx * j];
                for dj in 0..3 {
                    for di in 0..3 {
                        let ii = i as isize + di as isize - 1;
                        let jj = j as isize + dj as isize - 1;
                        if ii < 0 || jj < 0 || ii >= nx as isize || jj >= ny as isize {
                            row[di + 3 * dj] = 0.0;
                        }
                    }
                }
            }
        }
    }

    /// y = A x.
    pub fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.residual_into(None, x, y);
        for v in y.iter_mut() {
            *v = -*v;
        }
    }

    /// r = b − A x.
    pub fn residual(&self, b: &[f64], x: &[f64], r: &mut [f64]) {
        self.residual_into(Some(b), x, r);
    }

    fn residual_into(&self, b: Option<&[f64]>, x: &[f64], r: &mut [f64]) {
        let nx = self.nx;
        assert_eq!(x.len(), self.len());
        assert_eq!(r.len(), self.len());
        for j in 0..self.ny {
            for i in 0..nx {
                let p = i + nx * j;
                let a = &self.coef[p];
                let mut s = 0.0;
                for dj in 0..3usize {
                    if (j == 0 && dj == 0) || (j + 1 == self.ny && dj == 2) {
                        continue;
                    }
                    let q0 = p + dj * nx - nx;
                    for di in 0..3usize {
                        if (i == 0 && di == 0) || (i + 1 == nx && di == 2) {
                            continue;
                        }
                        s += a[di + 3 * dj] * x[q0 + di - 1];
                    }
                }
                r[p] = b.map_or(0.0, |b| b[p]) - s;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apply_five_point_laplacian() {
        let (nx, ny) = (4, 3);
        let mut a = Stencil9::zeros(nx, ny);
        for row in a.coefs_mut() {
            *row = [0.0, -1.0, 0.0, -1.0, 4.0, -1.0, 0.0, -1.0, 0.0];
        }
        a.clip_to_grid();
        let x: Vec<f64> = (0..nx * ny).map(|p| p as f64).collect();
        let mut y = vec![0.0; nx * ny];
        a.apply(&x, &mut y);
        // interior node (1,1) = p 5: 4*5 - 4 - 6 - 1 - 9 = 0
        assert_eq!(y[5], 0.0);
        // corner (0,0): 4*0 - 1 - 4 = -5
        assert_eq!(y[0], -5.0);
    }
}
