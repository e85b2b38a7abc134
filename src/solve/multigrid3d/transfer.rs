//! Operator-dependent prolongation and restriction in the manner of Dendy's 3D black box
//! multigrid (BoxMG), with de Zeeuw's upwind split on the lines.
//!
//! Coarse unknown `K = (I, J, L)` sits on fine unknown `F = (2I+1, 2J+1, 2L+1)`; its *star*
//! holds the weight of its value at each fine point `F + c`, `c ∈ {−1, 0, 1}³` (zero outside
//! the grid). By the number of nonzero components of `c`:
//! * 0 — injection, weight 1;
//! * 1, *edge* points (differ from coarse points along one direction `d`): the stencil is
//!   collapsed (summed) onto the line along `d`; total weight `σ = −(ã₋ + ã₊)/ã₀` clamped to
//!   `[0, 1]`, split between the two coarse neighbours as the 2D `interp.rs` does (de Zeeuw:
//!   symmetric magnitudes plus the convective part of the antisymmetric stencil);
//! * 2, *face* points: the stencil collapsed onto the plane of the two directions (summed
//!   over the third), `w = −(Σ_o ã_o P(c+o))/ã₀` with the already known edge weights of the
//!   same star;
//! * 3, *body* points: the same with the full 27-point stencil and the edge and face weights.
//!
//! A collapsed diagonal that is not positive falls back to the uncollapsed one.
//! Restriction (default): the transpose of the prolongation built by the same formulas from
//! the adjoint operator `A*`, `A*_p[m] = A_{p+o_m}[26 − m]`; optionally `R = Pᵀ`.

use crate::solve::multigrid::split_weights;
use crate::solve::multigrid3d::level::{off27, s27, Level, CTR};
use crate::solve::multigrid3d::{use_par, SharedPtr};
use crate::solve::SolveError;
use rayon::prelude::*;

/// Offsets of the 27 slots.
const OFF: [[isize; 3]; 27] = {
    let mut t = [[0; 3]; 27];
    let mut m = 0;
    while m < 27 {
        t[m] = off27(m);
        m += 1;
    }
    t
};

/// `COLLAPSE[mask][m]`: the slot that slot `m` is summed into when the directions not in the
/// bit mask `mask` are collapsed.
const COLLAPSE: [[usize; 27]; 8] = {
    let mut t = [[0; 27]; 8];
    let mut mask = 0;
    while mask < 8 {
        let mut m = 0;
        while m < 27 {
            let o = OFF[m];
            let k0 = if mask & 1 != 0 { o[0] } else { 0 };
            let k1 = if mask & 2 != 0 { o[1] } else { 0 };
            let k2 = if mask & 4 != 0 { o[2] } else { 0 };
            t[mask][m] = s27(k0, k1, k2);
            m += 1;
        }
        mask += 1;
    }
    t
};

/// Row `f` of the adjoint operator `A*_f[m] = A_{f+o_m}[26 − m]` of a level (zero outside
/// the grid), computed where needed: a stored adjoint would cost 216 bytes per unknown
/// during the setup.
fn adjoint_row(lev: &Level, f: [usize; 3]) -> [f64; 27] {
    let [nx, ny, nz] = lev.dims;
    let mut row = [0.0; 27];
    for (m, o) in OFF.iter().enumerate() {
        let g = [
            f[0] as isize + o[0],
            f[1] as isize + o[1],
            f[2] as isize + o[2],
        ];
        let inside = g[0] >= 0
            && g[1] >= 0
            && g[2] >= 0
            && (g[0] as usize) < nx
            && (g[1] as usize) < ny
            && (g[2] as usize) < nz;
        if inside {
            row[m] = lev.coef(
                g[0] as usize + nx * (g[1] as usize + ny * g[2] as usize),
                26 - m,
            );
        }
    }
    row
}

/// Edge weights `[(w₋, w₊) of m, (w₋, w₊) of ma]` of a point interpolated along `d`.
fn edge_weights(m: &[f64; 27], ma: &[f64; 27], d: usize) -> [(f64, f64); 2] {
    // symmetric part: sums and largest off-centre magnitudes of the six sides
    let (mut sum, mut big) = ([[0.0f64; 2]; 3], [[0.0f64; 2]; 3]);
    let mut c = 0.0;
    for k in 0..27 {
        let (s, t) = (0.5 * (m[k] + ma[k]), 0.5 * (m[k] - ma[k]));
        let o = OFF[k];
        let nnz = (o[0] != 0) as usize + (o[1] != 0) as usize + (o[2] != 0) as usize;
        for e in 0..3 {
            if o[e] != 0 {
                let side = (o[e] + 1) as usize / 2;
                sum[e][side] += s;
                if nnz > 1 {
                    big[e][side] = big[e][side].max(s.abs());
                }
            }
        }
        c += o[d] as f64 * t;
    }
    let mag = |e: usize, side: usize| sum[e][side].abs().max(big[e][side]);
    let (dm, dp) = (mag(d, 0), mag(d, 1));
    let dq: f64 = (0..3)
        .filter(|&e| e != d)
        .map(|e| mag(e, 0) + mag(e, 1))
        .sum();
    let weights = |g: &[f64; 27], c: f64| {
        let (mut am, mut ap, mut ac) = (0.0, 0.0, 0.0);
        for (k, v) in g.iter().enumerate() {
            match OFF[k][d] {
                -1 => am += v,
                1 => ap += v,
                _ => ac += v,
            }
        }
        split_weights(am, ap, ac, [dm, dp, dq], c)
    };
    [weights(m, c), weights(ma, -c)]
}

/// For a face or body slot `c` of a star: the collapse mask, the non-centre slots of the
/// collapsed stencil, and the pairs (collapsed slot `o`, star slot `c + o`) inside the star.
struct InnerPlan {
    mask: usize,
    sub: Vec<usize>,
    pairs: Vec<(usize, usize)>,
}

impl InnerPlan {
    fn new(c: [isize; 3]) -> Self {
        let mask = (c[0] != 0) as usize | ((c[1] != 0) as usize) << 1 | ((c[2] != 0) as usize) << 2;
        let mut sub: Vec<usize> = COLLAPSE[mask].to_vec();
        sub.sort_unstable();
        sub.dedup();
        sub.retain(|&m| m != CTR);
        let pairs = sub
            .iter()
            .filter_map(|&m| {
                let o = OFF[m];
                let t = [c[0] + o[0], c[1] + o[1], c[2] + o[2]];
                t.iter()
                    .all(|v| v.abs() <= 1)
                    .then(|| (m, s27(t[0], t[1], t[2])))
            })
            .collect();
        InnerPlan { mask, sub, pairs }
    }
}

/// Weight at the face or body point `F + c` (plan `plan`) of the star `star` (its edge, and
/// for a body point face, entries already set) from that point's stencil `g`.
fn inner_weight(g: &[f64; 27], plan: &InnerPlan, star: &[f64; 27]) -> Option<f64> {
    // collapse over the directions in which c is zero
    let mut col = [0.0; 27];
    for (m, v) in g.iter().enumerate() {
        col[COLLAPSE[plan.mask][m]] += v;
    }
    // sign split: positive (non-M) couplings of the collapsed stencil join its diagonal
    for &m in &plan.sub {
        if col[m] > 0.0 {
            col[CTR] += col[m];
            col[m] = 0.0;
        }
    }
    let den = if col[CTR] > 1e-12 * g[CTR].abs() && col[CTR].is_finite() {
        col[CTR]
    } else {
        g[CTR]
    };
    if !(den.is_finite() && den != 0.0) {
        return None;
    }
    let s: f64 = plan.pairs.iter().map(|&(m, t)| col[m] * star[t]).sum();
    Some(-s / den)
}

/// One coarse plane of prolongation and restriction stars, with its index.
type StarPlanes<'a> = (usize, (&'a mut [[f32; 27]], &'a mut [[f32; 27]]));

/// Builds the prolongation stars `lev.p` and restriction stars `lev.r` of level `lev`
/// (`transpose`: `R = Pᵀ`).
pub(super) fn build_transfer(lev: &mut Level, transpose: bool) -> Result<(), SolveError> {
    let dims = lev.dims;
    let nc = [dims[0] / 2, dims[1] / 2, dims[2] / 2];
    let ncn = nc[0] * nc[1] * nc[2];
    let mut p = std::mem::take(&mut lev.p);
    let mut r = std::mem::take(&mut lev.r);
    p.resize(ncn, [0.0; 27]);
    r.resize(ncn, [0.0; 27]);
    let lv: &Level = lev;
    let plans: Vec<InnerPlan> = (0..27).map(|m| InnerPlan::new(OFF[m])).collect();
    let [nx, ny, _] = dims;
    let fp = |f: [usize; 3]| f[0] + nx * (f[1] + ny * f[2]);
    // slots grouped by the number of nonzero offset components
    let by_kind = |nnz: usize| -> Vec<usize> {
        (0..27)
            .filter(|&m| off27(m).iter().filter(|v| **v != 0).count() == nnz)
            .collect()
    };
    let (edges, faces, bodies) = (by_kind(1), by_kind(2), by_kind(3));
    let plane = |(kc, (pp, rp)): StarPlanes| {
        for jc in 0..nc[1] {
            for ic in 0..nc[0] {
                let fc = [2 * ic + 1, 2 * jc + 1, 2 * kc + 1];
                let mut ps = [0.0; 27];
                let mut rs = [0.0; 27];
                ps[CTR] = 1.0;
                rs[CTR] = 1.0;
                let fine = |m: usize| -> Option<[usize; 3]> {
                    let o = off27(m);
                    let f: [isize; 3] = std::array::from_fn(|d| fc[d] as isize + o[d]);
                    (0..3)
                        .all(|d| f[d] >= 0 && f[d] < dims[d] as isize)
                        .then(|| [f[0] as usize, f[1] as usize, f[2] as usize])
                };
                for &m in &edges {
                    let Some(f) = fine(m) else { continue };
                    let o = off27(m);
                    let d = (0..3).find(|&d| o[d] != 0).expect("edge slot");
                    let p = fp(f);
                    let w = edge_weights(&lv.row(p), &adjoint_row(lv, f), d);
                    // this coarse point is the minus side of f if f lies on its plus side
                    let pick = |x: (f64, f64)| if o[d] > 0 { x.0 } else { x.1 };
                    ps[m] = pick(w[0]);
                    rs[m] = pick(w[1]);
                }
                if transpose {
                    rs = ps;
                }
                for group in [&faces, &bodies] {
                    for &m in group.iter() {
                        let Some(f) = fine(m) else { continue };
                        let err = || {
                            SolveError::Singular(format!(
                                "multigrid: zero or non-finite diagonal at unknown {f:?}"
                            ))
                        };
                        ps[m] = inner_weight(&lv.row(fp(f)), &plans[m], &ps).ok_or_else(err)?;
                        rs[m] = if transpose {
                            ps[m]
                        } else {
                            inner_weight(&adjoint_row(lv, f), &plans[m], &rs).ok_or_else(err)?
                        };
                    }
                }
                let id = ic + nc[0] * jc;
                // built in f64 (the face and body weights read the edge weights), stored
                // rounded (Level::p)
                pp[id] = ps.map(|w| w as f32);
                rp[id] = rs.map(|w| w as f32);
            }
        }
        Ok(())
    };
    let pl = nc[0] * nc[1];
    let res = if ncn == 0 {
        Ok(())
    } else if use_par(lv.n()) {
        p.par_chunks_mut(pl)
            .zip(r.par_chunks_mut(pl))
            .enumerate()
            .try_for_each(plane)
    } else {
        p.chunks_mut(pl)
            .zip(r.chunks_mut(pl))
            .enumerate()
            .try_for_each(plane)
    };
    lev.p = p;
    lev.r = r;
    res
}

/// `bc = R rf`: restricts the padded fine residual `rf` of level `lev` to the unpadded
/// coarse right-hand side `bc`.
pub(super) fn restrict(lev: &Level, rf: &[f64], bc: &mut [f64]) {
    let dims = lev.dims;
    let nc = [dims[0] / 2, dims[1] / 2, dims[2] / 2];
    let pl = nc[0] * nc[1];
    if pl * nc[2] == 0 {
        return;
    }
    let qo = lev.qoff();
    let plane = |(kc, bp): (usize, &mut [f64])| {
        for jc in 0..nc[1] {
            for ic in 0..nc[0] {
                let id = ic + nc[0] * jc;
                let st = &lev.r[id + pl * kc];
                let q = lev.q(2 * ic + 1, 2 * jc + 1, 2 * kc + 1) as isize;
                let mut s = 0.0;
                for m in 0..27 {
                    s += f64::from(st[m]) * rf[(q + qo[m]) as usize];
                }
                bp[id] = s;
            }
        }
    };
    if use_par(lev.n()) {
        bc.par_chunks_mut(pl).enumerate().for_each(plane);
    } else {
        bc.chunks_mut(pl).enumerate().for_each(plane);
    }
}

/// `xf += P xc`: adds the interpolated padded coarse correction `xc` to the padded fine `xf`
/// of level `lev`. Coarse planes of one parity write disjoint fine planes and run in
/// parallel; star entries outside the grid are zero, so the ghosts of `xf` stay zero.
pub(super) fn prolong_add(lev: &Level, coarse: &Level, xc: &[f64], xf: &mut [f64]) {
    let dims = lev.dims;
    let nc = coarse.dims;
    if nc.iter().product::<usize>() == 0 {
        return;
    }
    let qo = lev.qoff();
    let xp = SharedPtr(xf.as_mut_ptr());
    for parity in 0..2 {
        let plane = |kc: usize| {
            let x = xp.get();
            for jc in 0..nc[1] {
                for ic in 0..nc[0] {
                    let e = xc[coarse.q(ic, jc, kc)];
                    if e == 0.0 {
                        continue;
                    }
                    let st = &lev.p[ic + nc[0] * (jc + nc[1] * kc)];
                    let q = lev.q(2 * ic + 1, 2 * jc + 1, 2 * kc + 1) as isize;
                    for m in 0..27 {
                        // SAFETY: coarse plane kc writes fine planes 2kc … 2kc + 2 only;
                        // planes of one parity are two coarse planes apart.
                        unsafe { *x.offset(q + qo[m]) += f64::from(st[m]) * e };
                    }
                }
            }
        };
        let _ = dims;
        if use_par(lev.n()) {
            (parity..nc[2]).into_par_iter().step_by(2).for_each(plane);
        } else {
            (parity..nc[2]).step_by(2).for_each(plane);
        }
    }
}
