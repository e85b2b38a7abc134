//! A bounding-volume hierarchy over f64 boxes: a thin, conservative wrapper over obvhs.
//!
//! obvhs builds its BVH (PLOC, [`obvhs::bvh2::Bvh2`]) in f32. Every box is therefore padded
//! outward before it is handed over: each bound moves by a relative 4 f32-epsilons and is then
//! rounded outward to the next f32, so the padded f32 box contains the f64 box exactly.
//! Containment of a query point is decided against these padded boxes, which makes the queries
//! conservative: no f64 point inside a box can be missed, and a few near misses may be
//! reported; the caller decides exactly in f64.
//!
//! - [`BoxTree::candidates`]: all boxes whose padded box contains a point (point location:
//!   the caller then inverts the cell, e.g. a bilinear Newton).
//! - [`BoxTree::nearest`]: best-first search with box-distance lower bounds and an exact
//!   distance callback (closest-patch search for the surface projection).
//!
//! 2D users pass z = 0 for both bounds.

use crate::GeometryError;
use obvhs::aabb::Aabb;
use obvhs::bvh2::{builder::build_bvh2, Bvh2};
use obvhs::BvhBuildParams;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Boxes beyond this magnitude are rejected (f32 range, with room for the padding).
const MAX_COORD: f64 = 1e30;

/// BVH over axis-aligned boxes [min x, min y, min z, max x, max y, max z]; see the module doc.
#[derive(Clone)]
pub struct BoxTree {
    bvh: Bvh2,
    /// Padded f32 box of each input box, in input order.
    boxes: Vec<Aabb>,
}

impl std::fmt::Debug for BoxTree {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BoxTree")
            .field("boxes", &self.boxes.len())
            .finish()
    }
}

/// The largest f32 not above x (x finite, |x| < f32::MAX).
fn f32_down(x: f64) -> f32 {
    let y = x as f32;
    if (y as f64) <= x {
        y
    } else {
        next_toward(y, f32::NEG_INFINITY)
    }
}

/// The smallest f32 not below x.
fn f32_up(x: f64) -> f32 {
    let y = x as f32;
    if (y as f64) >= x {
        y
    } else {
        next_toward(y, f32::INFINITY)
    }
}

/// Next f32 after y towards `dir` (y finite).
fn next_toward(y: f32, dir: f32) -> f32 {
    if y == 0.0 {
        return if dir > 0.0 {
            f32::from_bits(1)
        } else {
            -f32::from_bits(1)
        };
    }
    let b = y.to_bits();
    // Away from zero: bits + 1; towards zero: bits − 1.
    if (y > 0.0) == (dir > y) {
        f32::from_bits(b + 1)
    } else {
        f32::from_bits(b - 1)
    }
}

impl BoxTree {
    /// Builds the tree over `boxes` ([min x, min y, min z, max x, max y, max z] each).
    ///
    /// # Errors
    /// A bound that is not finite or exceeds 1e30 in magnitude, or min > max (names the box).
    pub fn new(boxes: &[[f64; 6]]) -> Result<BoxTree, GeometryError> {
        let mut padded = Vec::with_capacity(boxes.len());
        for (k, b) in boxes.iter().enumerate() {
            if b.iter().any(|x| !x.is_finite() || x.abs() > MAX_COORD)
                || (0..3).any(|d| b[d] > b[d + 3])
            {
                return Err(GeometryError::Invalid(format!(
                    "bounding box {k}: {b:?} is not finite or has min > max"
                )));
            }
            let pad = |x: f64| 4.0 * f32::EPSILON as f64 * x.abs();
            let lo = [0, 1, 2].map(|d| f32_down(b[d] - pad(b[d])));
            let hi = [3, 4, 5].map(|d| f32_up(b[d] + pad(b[d])));
            padded.push(Aabb::new(lo.into(), hi.into()));
        }
        let bvh = if padded.is_empty() {
            Bvh2::default()
        } else {
            build_bvh2(
                &padded,
                BvhBuildParams::medium_build(),
                &mut Default::default(),
            )
        };
        Ok(BoxTree { bvh, boxes: padded })
    }

    /// Number of boxes.
    pub fn len(&self) -> usize {
        self.boxes.len()
    }

    /// True if there are no boxes.
    pub fn is_empty(&self) -> bool {
        self.boxes.is_empty()
    }

    /// Replaces `out` by the indices of all boxes whose padded box contains p (every box that
    /// contains p, plus possibly boxes within the padding).
    pub fn candidates(&self, p: [f64; 3], out: &mut Vec<usize>) {
        out.clear();
        if self.boxes.is_empty() {
            return;
        }
        // Rounding is monotone and the padded bounds are f32 values, so lo ≤ p implies
        // lo ≤ f32(p): the f32 traversal cannot lose a box containing p.
        let q = [p[0] as f32, p[1] as f32, p[2] as f32];
        self.bvh.point_traverse(q.into(), |bvh, node| {
            let n = &bvh.nodes[node as usize];
            let first = n.first_index as usize;
            for &k in &bvh.primitive_indices[first..first + n.prim_count as usize] {
                if contains(&self.boxes[k as usize], p) {
                    out.push(k as usize);
                }
            }
            true
        });
    }

    /// The box index minimizing `dist` and that distance, by best-first search.
    ///
    /// `dist(k)` is the exact distance from p to the object in box k; it must not be less than
    /// the Euclidean distance from p to box k (true for any object inside its box). Boxes
    /// whose lower bound is not below the best distance so far are skipped, so `dist` is
    /// called for few boxes. `None` if there are no boxes or every distance is NaN.
    pub fn nearest(&self, p: [f64; 3], mut dist: impl FnMut(usize) -> f64) -> Option<(usize, f64)> {
        if self.boxes.is_empty() || p.iter().any(|x| x.is_nan()) {
            return None;
        }
        let nodes = &self.bvh.nodes;
        let mut best: Option<(usize, f64)> = None;
        let mut heap = BinaryHeap::with_capacity(64);
        heap.push(Entry(box_distance(nodes[0].aabb(), p), 0));
        while let Some(Entry(bound, node)) = heap.pop() {
            if best.is_some_and(|(_, d)| bound >= d) {
                break;
            }
            let n = &nodes[node as usize];
            if n.prim_count == 0 {
                for c in [n.first_index, n.first_index + 1] {
                    heap.push(Entry(box_distance(nodes[c as usize].aabb(), p), c));
                }
                continue;
            }
            let first = n.first_index as usize;
            for &k in &self.bvh.primitive_indices[first..first + n.prim_count as usize] {
                let k = k as usize;
                if best.is_some_and(|(_, d)| box_distance(&self.boxes[k], p) >= d) {
                    continue;
                }
                let d = dist(k);
                if !d.is_nan() && best.is_none_or(|(_, b)| d < b) {
                    best = Some((k, d));
                }
            }
        }
        best
    }
}

/// p inside the (closed) f32 box, compared in f64.
fn contains(b: &Aabb, p: [f64; 3]) -> bool {
    (0..3).all(|d| b.min[d] as f64 <= p[d] && p[d] <= b.max[d] as f64)
}

/// Euclidean distance from p to the f32 box, in f64 (0 inside).
fn box_distance(b: &Aabb, p: [f64; 3]) -> f64 {
    let mut s = 0.0;
    for (d, &x) in p.iter().enumerate() {
        let e = (b.min[d] as f64 - x).max(x - b.max[d] as f64).max(0.0);
        s += e * e;
    }
    s.sqrt()
}

/// Heap entry ordered by smallest bound first (NaN bounds last).
struct Entry(f64, u32);

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0)
    }
}

#[cfg(test)]
#[path = "bvh_tests.rs"]
mod tests;
