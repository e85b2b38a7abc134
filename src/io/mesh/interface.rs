//! 1-to-1 interfaces between block sides: which node of one side is which node of the other.
//! A `.conn` range pair fixes the corners; for a face (3D) the pairing of the two in-face
//! directions is the one whose nodes coincide. Also CGNS's form of an interface: point range,
//! donor range and transform.

use super::{corners, View};
use crate::io::connectivity::Range;
use crate::io::Block;
use crate::{Error, Result};

/// A node of a block: (block, local node index).
pub(super) type NodeRef = (usize, usize);

/// How side a's nodes map to side b's: 0-based corners and, per varying axis of a, b's axis.
pub(super) struct Correspondence {
    ba: usize,
    bb: usize,
    fa: [usize; 3],
    la: [usize; 3],
    fb: [usize; 3],
    lb: [usize; 3],
    /// a's varying axes and the b axis each runs along.
    axes: Vec<(usize, usize)>,
}

/// The index `s` steps from `f` towards `l`.
fn step(f: usize, l: usize, s: usize) -> usize {
    if l >= f {
        f + s
    } else {
        f - s
    }
}

impl Correspondence {
    /// b's node for a's node `x`.
    fn map(&self, x: [usize; 3]) -> [usize; 3] {
        let mut y = self.fb;
        for &(ca, cb) in &self.axes {
            y[cb] = step(self.fb[cb], self.lb[cb], x[ca].abs_diff(self.fa[ca]));
        }
        y
    }
}

/// Pairs side a's nodes with side b's (the node pairs: (block, local node) each), checks
/// they coincide (to 1e-6 of `scale`).
pub(super) fn correspond(
    place: &str,
    blocks: &[(String, Block)],
    views: &[View],
    n: usize,
    a: &Range,
    b: &Range,
    scale: f64,
) -> Result<(Correspondence, Vec<[NodeRef; 2]>)> {
    let what = format!("interface {}", n + 1);
    let (ba, fa, la) = corners(place, blocks, views, a, &what)?;
    let (bb, fb, lb) = corners(place, blocks, views, b, &what)?;
    let varying =
        |f: [usize; 3], l: [usize; 3]| -> Vec<usize> { (0..3).filter(|&c| f[c] != l[c]).collect() };
    let (va, vb) = (varying(fa, la), varying(fb, lb));
    if va.len() != vb.len() || va.is_empty() {
        return Err(Error::input(
            place,
            format!("{what}: the two sides' ranges are not of the same shape"),
        ));
    }
    let perms: Vec<Vec<usize>> = if vb.len() == 2 {
        vec![vec![vb[0], vb[1]], vec![vb[1], vb[0]]]
    } else {
        vec![vb.clone()]
    };
    let len = |f: [usize; 3], l: [usize; 3], c: usize| f[c].abs_diff(l[c]) + 1;
    let counts: Vec<usize> = va.iter().map(|&c| len(fa, la, c)).collect();
    let mut best: Option<(f64, Correspondence, Vec<[NodeRef; 2]>)> = None;
    for p in perms {
        if va
            .iter()
            .zip(&p)
            .any(|(&x, &y)| len(fa, la, x) != len(fb, lb, y))
        {
            continue;
        }
        let c = Correspondence {
            ba,
            bb,
            fa,
            la,
            fb,
            lb,
            axes: va.iter().copied().zip(p.iter().copied()).collect(),
        };
        let mut pairs = Vec::new();
        let mut worst = 0.0f64;
        for t in 0..counts.get(1).copied().unwrap_or(1) {
            for s in 0..counts[0] {
                let st = [s, t];
                let mut na = fa;
                for (m, &x) in va.iter().enumerate() {
                    na[x] = step(fa[x], la[x], st[m]);
                }
                let nb = c.map(na);
                let (pa, pb) = (
                    views[ba].point(na[0], na[1], na[2]),
                    views[bb].point(nb[0], nb[1], nb[2]),
                );
                let d = (0..3).map(|k| (pa[k] - pb[k]).powi(2)).sum::<f64>().sqrt();
                worst = worst.max(if d.is_nan() { f64::INFINITY } else { d });
                let local = |v: &View, x: [usize; 3]| x[0] + v.dims[0] * (x[1] + v.dims[1] * x[2]);
                pairs.push([(ba, local(&views[ba], na)), (bb, local(&views[bb], nb))]);
            }
        }
        if best.as_ref().is_none_or(|(w, _, _)| worst < *w) {
            best = Some((worst, c, pairs));
        }
    }
    let Some((worst, c, pairs)) = best else {
        return Err(Error::input(
            place,
            format!(
                "{what}: blocks '{}' and '{}': the two sides have different node counts",
                blocks[ba].0, blocks[bb].0
            ),
        ));
    };
    if worst > 1e-6 * scale {
        return Err(Error::input(
            place,
            format!(
                "{what}: blocks '{}' and '{}' do not meet there: nodes {worst:.3e} apart \
                 (grid size {scale:.3e})",
                blocks[ba].0, blocks[bb].0
            ),
        ));
    }
    Ok((c, pairs))
}

/// One side of an interface as CGNS's `GridConnectivity1to1` holds it (1-based indices).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OneToOne {
    /// This block and the donor block (0-based).
    pub block: usize,
    pub donor: usize,
    /// This side's nodes, lowest corner first.
    pub range: [[usize; 3]; 2],
    /// The donor's nodes that match `range`'s two corners.
    pub donor_range: [[usize; 3]; 2],
    /// Per index direction of this block, the donor's direction (±1, ±2, ±3).
    pub transform: [i32; 3],
}

/// CGNS's form of interface `a`–`b` as seen from block a (swap the ranges for b's).
///
/// # Errors
/// Those of the node pairing: ranges outside their blocks, of different shapes or lengths,
/// nodes apart.
pub fn one_to_one(
    place: &str,
    blocks: &[(String, Block)],
    n: usize,
    a: &Range,
    b: &Range,
) -> Result<OneToOne> {
    let views: Vec<View> = blocks.iter().map(|(_, b)| View::new(b, None)).collect();
    let scale = super::diameter(&views);
    let (c, _) = correspond(place, blocks, &views, n, a, b, scale)?;
    let lo = [0, 1, 2].map(|k| c.fa[k].min(c.la[k]));
    let hi = [0, 1, 2].map(|k| c.fa[k].max(c.la[k]));
    let mut transform = [0i32; 3];
    let sign = |f: usize, l: usize| if l >= f { 1i32 } else { -1 };
    for &(ca, cb) in &c.axes {
        transform[ca] = sign(c.fa[ca], c.la[ca]) * sign(c.fb[cb], c.lb[cb]) * (cb as i32 + 1);
    }
    // The axis across the interface: going into block a is going out of block b.
    let (da, db) = (views[c.ba].dims, views[c.bb].dims);
    let fixed = |f: [usize; 3], l: [usize; 3], d: [usize; 3]| {
        (0..3).find(|&k| f[k] == l[k] && d[k] > 1 && (f[k] == 0 || f[k] == d[k] - 1))
    };
    if let (Some(na), Some(nb)) = (fixed(c.fa, c.la, da), fixed(c.fb, c.lb, db)) {
        let side = |f: usize| if f == 0 { -1i32 } else { 1 };
        transform[na] = -side(c.fa[na]) * side(c.fb[nb]) * (nb as i32 + 1);
    }
    let one = |x: [usize; 3]| x.map(|v| v + 1);
    Ok(OneToOne {
        block: c.ba,
        donor: c.bb,
        range: [one(lo), one(hi)],
        donor_range: [one(c.map(lo)), one(c.map(hi))],
        transform,
    })
}
