//! The measures of a volume grid's quality report (definitions in [`super`]): corner
//! Jacobians and skewness per cell, orientation, growth ratios along grid lines, orthogonality
//! and first heights at the faces, and per-cell arrays for VTK.

use rayon::prelude::*;

use crate::quality::geom::{angle_deg as angle, cross, dot, nmax, nmin, norm, sub, V3 as V};
use crate::quality::quality3d::{FaceQuality, QualityReport3};
use crate::quality::stats::{lines, CellStats, Listed};
use crate::Grid3;

/// The eight corners of cell (i, j, k), corner c at (i + bit 0, j + bit 1, k + bit 2).
fn cell_corners(g: &Grid3, i: usize, j: usize, k: usize) -> [V; 8] {
    std::array::from_fn(|c| g.point(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)))
}

/// The three cell edges leaving corner c, oriented along +i, +j, +k.
#[inline]
fn corner_edges(x: &[V; 8], c: usize) -> [V; 3] {
    std::array::from_fn(|a| {
        let d = sub(x[c ^ (1 << a)], x[c]);
        if (c >> a) & 1 == 1 {
            [-d[0], -d[1], -d[2]]
        } else {
            d
        }
    })
}

/// The smallest of the eight corner Jacobians of cell (i, j, k), times `sign`.
fn corner_jacobian_min(g: &Grid3, i: usize, j: usize, k: usize, sign: f64) -> f64 {
    let x = cell_corners(g, i, j, k);
    (0..8)
        .map(|c| {
            let e = corner_edges(&x, c);
            sign * dot(e[0], cross(e[1], e[2]))
        })
        .fold(f64::INFINITY, nmin)
}

/// The six faces of a cell as corner cycles of cell-corner numbers (bit 0 = i, 1 = j, 2 = k).
const FACES: [[usize; 4]; 6] = [
    [0, 2, 6, 4],
    [1, 3, 7, 5],
    [0, 1, 5, 4],
    [2, 3, 7, 6],
    [0, 1, 3, 2],
    [4, 5, 7, 6],
];

/// Per-cell measures: (min corner Jacobian, min scaled Jacobian, skewness, aspect ratio), with
/// the Jacobians multiplied by `sign`.
///
/// The twelve cell edges are formed and measured once. The skewness needs only the smallest
/// and the largest of the 24 face-corner angles, and only the one of them that sets it
/// (θmax − 90° ≥ 90° − θmin exactly when cos θmax ≤ −cos θmin): the corners are compared by
/// their cosines and one arctangent is taken, where each corner used to take one.
fn eval_cell(g: &Grid3, i: usize, j: usize, k: usize, sign: f64) -> [f64; 4] {
    let x = cell_corners(g, i, j, k);
    // edge (c, a): from corner c (bit a clear) along +a, and its length
    let mut ev = [[[0.0; 3]; 3]; 8];
    let mut el = [[0.0; 3]; 8];
    let (mut emin, mut emax) = (f64::INFINITY, 0.0f64);
    for c in 0..8 {
        for a in 0..3 {
            if (c >> a) & 1 == 0 {
                ev[c][a] = sub(x[c | (1 << a)], x[c]);
                el[c][a] = norm(ev[c][a]);
                emin = nmin(emin, el[c][a]);
                emax = nmax(emax, el[c][a]);
            }
        }
    }
    let (mut jmin, mut smin) = (f64::INFINITY, f64::INFINITY);
    for c in 0..8 {
        // the corner's edges along +i, +j, +k (as `corner_edges`)
        let e: [V; 3] = std::array::from_fn(|a| ev[c & !(1 << a)][a]);
        let jac = sign * dot(e[0], cross(e[1], e[2]));
        let l = (0..3).map(|a| el[c & !(1 << a)][a]).product::<f64>();
        jmin = nmin(jmin, jac);
        smin = nmin(smin, if l > 0.0 { jac / l } else { 0.0 });
    }
    // the edge from corner p to its neighbour q on a face, and its length
    let edge = |p: usize, q: usize| -> (V, f64) {
        let a = (p ^ q).trailing_zeros() as usize;
        let (d, l) = (ev[p.min(q)][a], el[p.min(q)][a]);
        if q > p {
            (d, l)
        } else {
            ([-d[0], -d[1], -d[2]], l)
        }
    };
    // the corners of largest and smallest cosine (smallest and largest angle)
    let (mut cmax, mut cmin) = (
        (f64::NEG_INFINITY, [0.0; 3], [0.0; 3]),
        (f64::INFINITY, [0.0; 3], [0.0; 3]),
    );
    let mut nan = false;
    for f in FACES {
        for q in 0..4 {
            let (u, lu) = edge(f[q], f[(q + 1) % 4]);
            let (w, lw) = edge(f[q], f[(q + 3) % 4]);
            let d = dot(u, w);
            // a zero-length edge: angle 0° (`angle_deg` of a zero vector)
            let cos = if lu * lw > 0.0 { d / (lu * lw) } else { 1.0 };
            nan |= cos.is_nan();
            if cos > cmax.0 {
                cmax = (cos, u, w);
            }
            if cos < cmin.0 {
                cmin = (cos, u, w);
            }
        }
    }
    let skew = if nan {
        f64::NAN
    } else if cmin.0 <= -cmax.0 {
        (angle(cmin.1, cmin.2) - 90.0) / 90.0
    } else {
        (90.0 - angle(cmax.1, cmax.2)) / 90.0
    };
    [jmin, smin, skew, emax / emin]
}

/// Smallest block-edge dihedral (degrees) counted as flat: [`flat_edge_cell`].
pub const FLAT_EDGE_DEG: f64 = 179.0;

/// True if every non-positive corner Jacobian of cell (i, j, k) (relative to `sign`) sits at a
/// node on a block edge where the two block faces meeting there are flat: dihedral ≥
/// [`FLAT_EDGE_DEG`], measured at that node between the cell edges leaving it in the two faces,
/// projected normal to the block edge. Such a corner has three (nearly) coplanar edges by the
/// block's topology (the 180° edge where two faces of a C–O block share one plane), not by a
/// fold; its scaled Jacobian is at most sin 1° in size. False if no corner is non-positive, or
/// a NaN, a zero-length edge or any other non-positive corner is present.
pub fn flat_edge_cell(g: &Grid3, i: usize, j: usize, k: usize, sign: f64) -> bool {
    let dims = g.dims();
    let x = cell_corners(g, i, j, k);
    let mut any = false;
    for (c, &xc) in x.iter().enumerate() {
        let raw: [V; 3] = std::array::from_fn(|a| sub(x[c ^ (1 << a)], xc));
        let e: [V; 3] = std::array::from_fn(|a| {
            if (c >> a) & 1 == 1 {
                [-raw[a][0], -raw[a][1], -raw[a][2]]
            } else {
                raw[a]
            }
        });
        let jac = sign * dot(e[0], cross(e[1], e[2]));
        if jac > 0.0 {
            continue;
        }
        if jac.is_nan() {
            return false;
        }
        any = true;
        let n = [i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)];
        let ext: [bool; 3] = std::array::from_fn(|a| n[a] == 0 || n[a] + 1 == dims[a]);
        // Along a block edge of axis d the two other axes are at their ends; the cell edges
        // along them lie in the two faces that meet at the block edge.
        let flat = (0..3).any(|d| {
            let (a, b) = ((d + 1) % 3, (d + 2) % 3);
            if !(ext[a] && ext[b]) {
                return false;
            }
            let t = raw[d];
            let tt = dot(t, t);
            if tt <= 0.0 {
                return false;
            }
            let perp = |v: V| {
                let s = dot(v, t) / tt;
                [v[0] - s * t[0], v[1] - s * t[1], v[2] - s * t[2]]
            };
            let (u, w) = (perp(raw[a]), perp(raw[b]));
            if norm(u) <= 0.0 || norm(w) <= 0.0 {
                return false;
            }
            angle(u, w) >= FLAT_EDGE_DEG
        });
        if !flat {
            return false;
        }
    }
    any
}

/// Majority sign of the corner Jacobians (+1 right-handed, −1 left-handed).
fn orientation(g: &Grid3) -> f64 {
    let [ni, nj, nk] = g.dims();
    let (pos, neg) = (0..nk - 1)
        .into_par_iter()
        .map(|k| {
            let (mut p, mut n) = (0usize, 0usize);
            for j in 0..nj - 1 {
                for i in 0..ni - 1 {
                    let jac = corner_jacobian_min(g, i, j, k, 1.0);
                    p += usize::from(jac > 0.0);
                    n += usize::from(jac < 0.0);
                }
            }
            (p, n)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    if neg > pos {
        -1.0
    } else {
        1.0
    }
}

/// The cells of one layer: [`CellStats`], and the flat-edge cells apart.
struct Acc {
    cells: CellStats<3>,
    flat: Listed<3>,
    /// Smallest scaled Jacobian over the cells that are not flat-edge cells.
    smin_regular: f64,
}

impl Acc {
    fn new() -> Self {
        Acc {
            cells: CellStats::new(),
            flat: Listed::new(),
            smin_regular: f64::INFINITY,
        }
    }

    fn merge(mut self, b: Acc) -> Acc {
        self.cells.merge(b.cells);
        self.flat.merge(b.flat);
        self.smin_regular = nmin(self.smin_regular, b.smin_regular);
        self
    }
}

/// Orthogonality and first heights at face f (0 = F1 … 5 = F6).
pub fn face_quality(g: &Grid3, f: usize) -> FaceQuality {
    let d = g.dims();
    let axis = f / 2;
    let (ta, tb) = match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    let wall = if f % 2 == 0 { 0 } else { d[axis] - 1 };
    let inward: isize = if f % 2 == 0 { 1 } else { -1 };
    let at = |n: [usize; 3]| g.point(n[0], n[1], n[2]);
    let r = (1..d[tb].saturating_sub(1))
        .into_par_iter()
        .map(|b| {
            let (mut mx, mut sum, mut cnt, mut hmin, mut hmax) = (
                f64::NEG_INFINITY,
                0.0,
                0usize,
                f64::INFINITY,
                f64::NEG_INFINITY,
            );
            for a in 1..d[ta] - 1 {
                let mut n = [0; 3];
                n[axis] = wall;
                n[ta] = a;
                n[tb] = b;
                let mut q = n;
                q[axis] = (wall as isize + inward) as usize;
                let (mut ap, mut am, mut bp, mut bm) = (n, n, n, n);
                ap[ta] += 1;
                am[ta] -= 1;
                bp[tb] += 1;
                bm[tb] -= 1;
                let nrm = cross(sub(at(ap), at(am)), sub(at(bp), at(bm)));
                let off = sub(at(q), at(n));
                let c = dot(off, nrm).abs() / (norm(off) * norm(nrm));
                let dev = if c.is_finite() {
                    c.min(1.0).acos().to_degrees()
                } else {
                    90.0
                };
                mx = nmax(mx, dev);
                sum += dev;
                cnt += 1;
                hmin = nmin(hmin, norm(off));
                hmax = nmax(hmax, norm(off));
            }
            (mx, sum, cnt, hmin, hmax)
        })
        .reduce(
            || (f64::NEG_INFINITY, 0.0, 0, f64::INFINITY, f64::NEG_INFINITY),
            |u, v| {
                (
                    nmax(u.0, v.0),
                    u.1 + v.1,
                    u.2 + v.2,
                    nmin(u.3, v.3),
                    nmax(u.4, v.4),
                )
            },
        );
    let nan = f64::NAN;
    let ok = r.2 > 0;
    FaceQuality {
        face: format!("F{}", f + 1),
        nodes: r.2,
        orthogonality_max_deg: if ok { r.0 } else { nan },
        orthogonality_mean_deg: if ok { r.1 / r.2 as f64 } else { nan },
        first_height_min: if ok { r.3 } else { nan },
        first_height_max: if ok { r.4 } else { nan },
    }
}

/// The number of folded cells of [`quality3d`] alone (a non-positive corner Jacobian that is
/// not a flat-edge corner), without the other measures: for solvers that only need to know
/// whether a grid folds.
pub fn folded_cells3d(g: &Grid3) -> usize {
    let [ni, nj, nk] = g.dims();
    if ni < 2 || nj < 2 || nk < 2 {
        return 0;
    }
    let sign = orientation(g);
    (0..nk - 1)
        .into_par_iter()
        .map(|k| {
            let mut n = 0;
            for j in 0..nj - 1 {
                for i in 0..ni - 1 {
                    let jac = corner_jacobian_min(g, i, j, k, sign);
                    if (jac.is_nan() || jac <= 0.0) && !flat_edge_cell(g, i, j, k, sign) {
                        n += 1;
                    }
                }
            }
            n
        })
        .sum()
}

/// The quality report of a volume grid (module docs). Never panics; grids smaller than
/// 2 × 2 × 2 give `cells = 0` and NaN metrics.
pub fn quality3d(g: &Grid3) -> QualityReport3 {
    let [ni, nj, nk] = g.dims();
    let nan = f64::NAN;
    let cells = if ni < 2 || nj < 2 || nk < 2 {
        0
    } else {
        (ni - 1) * (nj - 1) * (nk - 1)
    };
    let mut rep = QualityReport3 {
        ni,
        nj,
        nk,
        cells,
        orientation: "right-handed".into(),
        jacobian_min: nan,
        jacobian_max: nan,
        scaled_jacobian_min: nan,
        folded_cells: 0,
        first_folded: vec![],
        flat_edge_cells: 0,
        first_flat_edge: vec![],
        scaled_jacobian_min_regular: nan,
        skewness_max: nan,
        skewness_mean: nan,
        faces: vec![],
        aspect_ratio_max: nan,
        growth_i_max: nan,
        growth_j_max: nan,
        growth_k_max: nan,
        min_spacing: nan,
        max_spacing: nan,
    };
    if cells == 0 {
        return rep;
    }
    let sign = orientation(g);
    if sign < 0.0 {
        rep.orientation = "left-handed".into();
    }
    let acc = (0..nk - 1)
        .into_par_iter()
        .map(|k| {
            let mut a = Acc::new();
            for j in 0..nj - 1 {
                for i in 0..ni - 1 {
                    let [jac, s, sk, ar] = eval_cell(g, i, j, k, sign);
                    // The largest Jacobian is taken over the cells' smallest corner ones.
                    a.cells.add(jac, jac, s, sk, ar);
                    if jac > 0.0 {
                        a.smin_regular = nmin(a.smin_regular, s);
                    } else if flat_edge_cell(g, i, j, k, sign) {
                        a.flat.push([i, j, k]);
                    } else {
                        a.smin_regular = nmin(a.smin_regular, s);
                        a.cells.folded.push([i, j, k]);
                    }
                }
            }
            a
        })
        .collect::<Vec<_>>()
        .into_iter()
        .fold(Acc::new(), Acc::merge);
    let point = |[i, j, k]: [usize; 3]| g.point(i, j, k);
    let [gi, gj, gk] = [0, 1, 2].map(|a| lines([ni, nj, nk], a, point, |_| false));
    let c = acc.cells;
    rep.jacobian_min = c.jmin;
    rep.jacobian_max = c.jmax;
    rep.scaled_jacobian_min = c.smin;
    rep.folded_cells = c.folded.count;
    rep.first_folded = c.folded.first;
    rep.flat_edge_cells = acc.flat.count;
    rep.first_flat_edge = acc.flat.first;
    rep.scaled_jacobian_min_regular = acc.smin_regular;
    rep.skewness_max = c.skew_max;
    rep.skewness_mean = c.skew_sum / cells as f64;
    rep.aspect_ratio_max = c.aspect_max;
    rep.growth_i_max = gi.0;
    rep.growth_j_max = gj.0;
    rep.growth_k_max = gk.0;
    rep.min_spacing = nmin(gi.1, nmin(gj.1, gk.1));
    rep.max_spacing = nmax(gi.2, nmax(gj.2, gk.2));
    rep.faces = (0..6).map(|f| face_quality(g, f)).collect();
    rep
}

/// Per-cell arrays for VTK cell data, cell (i, j, k) at i + (ni−1)(j + (nj−1) k):
/// "jacobian_min", "scaled_jacobian_min", "skewness", "aspect_ratio".
pub fn cell_fields3d(g: &Grid3) -> Vec<(&'static str, Vec<f64>)> {
    let [ni, nj, nk] = g.dims();
    let names = [
        "jacobian_min",
        "scaled_jacobian_min",
        "skewness",
        "aspect_ratio",
    ];
    if ni < 2 || nj < 2 || nk < 2 {
        return names.into_iter().map(|n| (n, vec![])).collect();
    }
    let sign = orientation(g);
    let (ci, cj) = (ni - 1, nj - 1);
    let vals: Vec<[f64; 4]> = (0..ci * cj * (nk - 1))
        .into_par_iter()
        .map(|p| eval_cell(g, p % ci, (p / ci) % cj, p / (ci * cj), sign))
        .collect();
    names
        .into_iter()
        .enumerate()
        .map(|(m, n)| (n, vals.iter().map(|v| v[m]).collect()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The skewness from one arctangent is the definition's: the largest deviation from 90°
    /// over all 24 face-corner angles, each by `angle_deg`, on distorted cells where the
    /// smallest angle sets it and where the largest does; the Jacobians and the aspect ratio
    /// as `corner_edges` gives them.
    #[test]
    fn a_cells_skewness_is_that_of_its_extreme_face_angles() {
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let (mut by_min, mut by_max) = (0, 0);
        for _ in 0..400 {
            let d: Vec<f64> = (0..24).map(|_| 0.5 * rnd()).collect();
            let g = Grid3::from_fn(2, 2, 2, |i, j, k| {
                let c = i + 2 * j + 4 * k;
                [
                    i as f64 + d[3 * c],
                    j as f64 + d[3 * c + 1],
                    k as f64 + d[3 * c + 2],
                ]
            });
            let x = cell_corners(&g, 0, 0, 0);
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for f in FACES {
                for q in 0..4 {
                    let p = x[f[q]];
                    let th = angle(sub(x[f[(q + 1) % 4]], p), sub(x[f[(q + 3) % 4]], p));
                    lo = lo.min(th);
                    hi = hi.max(th);
                }
            }
            let want = ((hi - 90.0) / 90.0).max((90.0 - lo) / 90.0);
            if hi - 90.0 >= 90.0 - lo {
                by_max += 1;
            } else {
                by_min += 1;
            }
            let [jmin, _, skew, aspect] = eval_cell(&g, 0, 0, 0, 1.0);
            assert!((skew - want).abs() < 1e-14, "{skew} vs {want}");
            assert_eq!(jmin, corner_jacobian_min(&g, 0, 0, 0, 1.0));
            let (mut emin, mut emax) = (f64::INFINITY, 0.0f64);
            for c in 0..8 {
                for e in corner_edges(&x, c) {
                    emin = emin.min(norm(e));
                    emax = emax.max(norm(e));
                }
            }
            assert_eq!(aspect, emax / emin);
        }
        assert!(by_min > 50 && by_max > 50, "{by_min} {by_max}");
    }
}
