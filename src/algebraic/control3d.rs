//! The 18 control functions of the volume grid system, eqs. [83, 84] (METHOD.md §6).

use crate::algebraic::bilinear3d::{bilinear, det3, ParamGrid3};
use crate::algebraic::flat_edge::edge_functions;
use crate::algebraic::{ControlKind, Controls, COMPUTED_FROM};
use crate::grid::faces::Faces;
use crate::Result;
use rayon::prelude::*;

/// Index pairs ij of the six second derivatives, in storage order: 11, 12, 13, 22, 23, 33.
pub const PAIRS: [[usize; 2]; 6] = [[0, 0], [0, 1], [0, 2], [1, 1], [1, 2], [2, 2]];

/// The control functions per node, fixed during the whole elliptic solve:
/// `p[n][3 m + c] = P^c_{ij}` with ij = `PAIRS[m]` and c = 0, 1, 2 (s, t, u component);
/// zero on the boundary.
pub type Control3 = Controls<18, 3>;

/// Central differences of `f` at node n of a grid with strides (1, sj, sk), unit spacing:
/// the first derivatives (ξ, η, ζ) and the six second derivatives in [`PAIRS`] order. The
/// mixed derivatives use the 4-corner formula of the Picard operator (METHOD.md §8).
#[inline]
pub fn central(f: &[f64], n: usize, st: [usize; 3]) -> ([f64; 3], [f64; 6]) {
    let d1 = |a: usize| 0.5 * (f[n + st[a]] - f[n - st[a]]);
    let d2 = |a: usize| f[n + st[a]] - 2.0 * f[n] + f[n - st[a]];
    let dm = |a: usize, b: usize| {
        0.25 * (f[n + st[a] + st[b]] - f[n - st[a] + st[b]] - f[n + st[a] - st[b]]
            + f[n - st[a] - st[b]])
    };
    (
        [d1(0), d1(1), d1(2)],
        [d2(0), dm(0, 1), dm(0, 2), d2(1), dm(1, 2), d2(2)],
    )
}

impl Control3 {
    /// Control functions at interior nodes, eqs. [83, 84]: P_ij = −T⁻¹ (s_{ξiξj}, t_{ξiξj},
    /// u_{ξiξj})ᵀ with T = ∂(s, t, u)/∂(ξ, η, ζ), by central differences of the bilinear
    /// (s, t, u) grid in index space (the grid system is homogeneous in the spacings, so the
    /// factors 1/N, 1/M, 1/L cancel). With the operator's own mixed-derivative formula, the
    /// tensor-product box is an exact discrete solution.
    pub fn from_algebraic(pg: &ParamGrid3) -> Self {
        let dims = pg.dims();
        let [ni, nj, nk] = dims;
        let plane = ni * nj;
        if plane * nk >= COMPUTED_FROM {
            let param = [pg.s.clone(), pg.t.clone(), pg.u.clone()];
            return Controls::computed(dims, param, node);
        }
        let mut p = vec![[0.0; 18]; plane * nk];
        p.par_chunks_mut(plane).enumerate().for_each(|(k, row)| {
            if k == 0 || k + 1 == nk {
                return;
            }
            for j in 1..nj - 1 {
                for i in 1..ni - 1 {
                    let n = i + ni * j + plane * k;
                    row[i + ni * j] = interior([&pg.s, &pg.t, &pg.u], n, [1, ni, plane]);
                }
            }
        });
        Controls::stored(dims, p)
    }
}

/// The control functions at the interior node `n` of the (s, t, u) grid `f` with strides
/// `st` (see [`Control3::from_algebraic`]).
#[inline]
fn interior(f: [&[f64]; 3], n: usize, st: [usize; 3]) -> [f64; 18] {
    let (ds, dds) = central(f[0], n, st);
    let (dt, ddt) = central(f[1], n, st);
    let (du, ddu) = central(f[2], n, st);
    let tm = [ds, dt, du];
    let d = det3(tm);
    let mut q = [0.0; 18];
    for m in 0..6 {
        let r = [dds[m], ddt[m], ddu[m]];
        // Cramer: x = T⁻¹ r, P = −x.
        for c in 0..3 {
            let mut mc = tm;
            for (rr, mrow) in r.iter().zip(mc.iter_mut()) {
                mrow[c] = *rr;
            }
            q[3 * m + c] = -det3(mc) / d;
        }
    }
    q
}

/// The control functions at node `ijk` of a face (normal to `axis`) of the (s, t, u) grid
/// `pg`, as at the plane of symmetry of the whole domain that the block is the half of: the
/// parameter along `axis` continued oddly beyond the face (its mirror image), the other two
/// evenly ([`crate::elliptic::symmetry3d`]), without the components P^c_aa (c ≠ a, a =
/// `axis`) that would make the lines cross the plane obliquely. Only the face's inside (not
/// its rim).
pub fn at_symmetry_face(pg: &ParamGrid3, axis: usize, ijk: [usize; 3]) -> [f64; 18] {
    let [ni, nj, _] = pg.dims();
    let layer = ijk[axis];
    let high = layer > 0;
    let param = [&pg.s, &pg.t, &pg.u];
    let index = |p: [isize; 3]| p[0] as usize + ni * p[1] as usize + ni * nj * p[2] as usize;
    // The 3 × 3 × 3 neighbourhood of every parameter, ghosts beyond the face: a ghost's
    // partner is its mirror image in the face; the parameter along `axis` continues as
    // 2 s(face) − s(partner) on the partner's line, the others as their partner's values.
    let mut loc = [[0.0; 27]; 3];
    for m in 0..27usize {
        let o = [m % 3, (m / 3) % 3, m / 9];
        let mut p: [isize; 3] = std::array::from_fn(|d| ijk[d] as isize + o[d] as isize - 1);
        let beyond = if high {
            p[axis] > layer as isize
        } else {
            p[axis] < 0
        };
        if beyond {
            p[axis] = 2 * layer as isize - p[axis];
        }
        let mut on_face = p;
        on_face[axis] = layer as isize;
        for (c, (pc, lc)) in param.iter().zip(loc.iter_mut()).enumerate() {
            lc[m] = if beyond && c == axis {
                2.0 * pc[index(on_face)] - pc[index(p)]
            } else {
                pc[index(p)]
            };
        }
    }
    let mut q = interior([&loc[0], &loc[1], &loc[2]], 13, [1, 3, 9]);
    // The lines are to cross the plane at right angles: drop the components P^c_aa (c ≠ a)
    // that an algebraic map oblique to the face has there (they set the face nodes' offset
    // from their inner neighbours; ONERA M6 wake sheet: mean kink 18.3° with them, 3.2°
    // without).
    let maa = [0, 3, 5][axis];
    for c in (0..3).filter(|&c| c != axis) {
        q[3 * maa + c] = 0.0;
    }
    q
}

/// The control functions at node `n` of a grid of `dims` nodes from its (s, t, u) grid `f`:
/// [`interior`], zero on the boundary.
fn node(dims: &[usize; 3], f: &[Vec<f64>; 3], n: usize) -> [f64; 18] {
    let [ni, nj, nk] = *dims;
    let plane = ni * nj;
    let (i, j, k) = (n % ni, (n / ni) % nj, n / plane);
    if i == 0 || j == 0 || k == 0 || i + 1 >= ni || j + 1 >= nj || k + 1 >= nk {
        return [0.0; 18];
    }
    interior([&f[0], &f[1], &f[2]], n, [1, ni, plane])
}

/// The control functions of a block's faces for the chosen kind: from the bilinear
/// transformation of the arclength edge functions [83, 84], or all zero.
pub fn control_for(faces: &Faces, kind: ControlKind, place: &str) -> Result<Control3> {
    Ok(match kind {
        ControlKind::Algebraic => {
            Control3::from_algebraic(&bilinear(&edge_functions(faces), place)?)
        }
        ControlKind::Laplace => Control3::zeros(faces.dims()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebraic::bilinear3d::{bilinear, EdgeFunctions3};

    /// The control functions computed at each use (large grids, #16) are those stored, bit
    /// for bit, zero on the boundary.
    #[test]
    fn computed_controls_equal_stored_ones() {
        let dist = |n: usize, p: f64| -> Vec<f64> {
            (0..n)
                .map(|k| (k as f64 / (n - 1) as f64).powf(p))
                .collect()
        };
        let ef = EdgeFunctions3 {
            s: [0.8, 1.2, 1.5, 2.0].map(|p| dist(7, p)),
            t: [1.1, 0.7, 1.9, 1.4].map(|p| dist(6, p)),
            u: [1.3, 1.6, 0.9, 2.2].map(|p| dist(8, p)),
        };
        let pg = bilinear(&ef, "b").unwrap();
        let stored = Control3::from_algebraic(&pg);
        assert!(!stored.p.is_empty());
        let param = [pg.s.clone(), pg.t.clone(), pg.u.clone()];
        let computed = Controls::computed(pg.dims(), param, node);
        assert!(computed.p.is_empty());
        assert_eq!(computed, stored);
        assert!(computed.all_finite());
        let n = 3 + 7 * (2 + 6 * 4);
        assert!(stored.at(n).iter().filter(|v| **v != 0.0).count() > 9);
        assert_eq!(computed.at(7 * 6 * 4), [0.0; 18], "zero on the boundary");
    }

    #[test]
    fn thomas_middlecoff_in_3d() {
        // Equal distributions on parallel edges: P^1_11 = −s_ξξ/s_ξ, P^2_22 = −t_ηη/t_η,
        // P^3_33 = −u_ζζ/u_ζ, all others zero.
        let s: Vec<f64> = (0..6).map(|i| (i as f64 / 5.0).powi(2)).collect();
        let t: Vec<f64> = (0..5).map(|j| (j as f64 / 4.0).sqrt()).collect();
        let u: Vec<f64> = (0..5)
            .map(|k| ((k as f64 / 4.0) * 2.0).sinh() / 2f64.sinh())
            .collect();
        let ef = EdgeFunctions3 {
            s: std::array::from_fn(|_| s.clone()),
            t: std::array::from_fn(|_| t.clone()),
            u: std::array::from_fn(|_| u.clone()),
        };
        let c = Control3::from_algebraic(&bilinear(&ef, "b").unwrap());
        let (i, j, k) = (2, 2, 3);
        let q = c.at(i + 6 * (j + 5 * k));
        let tm = |f: &[f64], n: usize| {
            -(f[n + 1] - 2.0 * f[n] + f[n - 1]) / (0.5 * (f[n + 1] - f[n - 1]))
        };
        let mut want = [0.0; 18];
        want[0] = tm(&s, i);
        want[3 * 3 + 1] = tm(&t, j);
        want[3 * 5 + 2] = tm(&u, k);
        for (a, b) in q.iter().zip(want) {
            assert!((a - b).abs() < 1e-13, "{q:?}");
        }
    }
}
