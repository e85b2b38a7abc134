//! Smoothness of a multi-block grid across an interior edge: the kink of the grid lines that
//! cross it (the angle between the line directions on the two sides; 0 when a line goes
//! straight through) and the ratio of the first spacings on the two sides (1 when they match).
//! The edge's end nodes (vertices, where blocks meet at corners) are not counted; across an
//! interior face of a volume topology, the face's boundary nodes are not counted.

use crate::grid::topology::SideRange;
use crate::{Grid2, Grid3};
use serde::Serialize;

/// Kink and spacing ratio along one interface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct InterfaceSmoothness {
    /// Nodes measured (the edge's interior nodes).
    pub nodes: usize,
    /// Largest and mean kink angle of the crossing grid lines, degrees.
    pub kink_max_deg: f64,
    pub kink_mean_deg: f64,
    /// Largest and mean ratio of the larger to the smaller first spacing (≥ 1).
    pub spacing_ratio_max: f64,
    pub spacing_ratio_mean: f64,
    /// Across a volume face: the largest and mean turn of the crossing lines at their first
    /// node off the face (the larger of the two sides'), degrees. A correction that makes the
    /// lines meet the face at right angles can move their turn there, where the kink does not
    /// see it (`elliptic::crossing`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turn_next_max_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turn_next_mean_deg: Option<f64>,
}

/// The smoothness across an interface: node k of `ra` in `ga` is node k of `rb` in `gb`.
pub fn interface_smoothness<const D: usize>(
    ga: &Grid2<D>,
    ra: &SideRange,
    gb: &Grid2<D>,
    rb: &SideRange,
) -> InterfaceSmoothness {
    let n = ra.len();
    smoothness(
        (1..n.saturating_sub(1))
            .map(|k| (at(ga, ra.node(k)), at(ga, ra.inner(k)), at(gb, rb.inner(k)))),
    )
}

/// The smoothness across an interior face of a volume topology: for every node of the face
/// (its boundary nodes left out), its block node and the nodes one and two steps in, in `ga`
/// and in `gb`.
pub fn face_smoothness(
    ga: &Grid3,
    gb: &Grid3,
    nodes: impl Iterator<Item = [[usize; 3]; 6]> + Clone,
) -> InterfaceSmoothness {
    let at3 = |g: &Grid3, [i, j, k]: [usize; 3]| g.point(i, j, k);
    let mut s = smoothness(
        nodes
            .clone()
            .map(|[p, a, _, _, b, _]| (at3(ga, p), at3(ga, a), at3(gb, b))),
    );
    let (mut max, mut sum, mut n) = (0.0f64, 0.0, 0usize);
    for [p, a, a2, q, b, b2] in nodes {
        let turn = |g: &Grid3, p: [usize; 3], a: [usize; 3], a2: [usize; 3]| {
            let (p, a, a2) = (at3(g, p), at3(g, a), at3(g, a2));
            turn_deg(&sub(&a, &p), &sub(&a2, &a))
        };
        let t = turn(ga, p, a, a2).max(turn(gb, q, b, b2));
        max = max.max(t);
        sum += t;
        n += 1;
    }
    if n > 0 {
        s.turn_next_max_deg = Some(max);
        s.turn_next_mean_deg = Some(sum / n as f64);
    }
    s
}

/// The angle between two successive segments of a line (0 when it goes straight on), degrees.
fn turn_deg<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    let cos = a.iter().zip(b).map(|(u, v)| u * v).sum::<f64>() / (norm(a) * norm(b));
    cos.clamp(-1.0, 1.0).acos().to_degrees()
}

/// Kink and spacing ratio over (node, neighbour on side a, neighbour on side b) triples.
fn smoothness<const D: usize>(
    triples: impl Iterator<Item = ([f64; D], [f64; D], [f64; D])>,
) -> InterfaceSmoothness {
    let mut s = InterfaceSmoothness::default();
    for (p, pa, pb) in triples {
        let a = sub(&pa, &p);
        let b = sub(&pb, &p);
        let (la, lb) = (norm(&a), norm(&b));
        // Straight through: a and b point in opposite directions, the line turns by 0.
        let kink = turn_deg(&a.map(|c| -c), &b);
        let ratio = la.max(lb) / la.min(lb);
        s.nodes += 1;
        s.kink_max_deg = s.kink_max_deg.max(kink);
        s.kink_mean_deg += kink;
        s.spacing_ratio_max = s.spacing_ratio_max.max(ratio);
        s.spacing_ratio_mean += ratio;
    }
    if s.nodes > 0 {
        s.kink_mean_deg /= s.nodes as f64;
        s.spacing_ratio_mean /= s.nodes as f64;
    }
    s
}

fn at<const D: usize>(g: &Grid2<D>, [i, j]: [usize; 2]) -> [f64; D] {
    g.point(i, j)
}

fn sub<const D: usize>(a: &[f64; D], b: &[f64; D]) -> [f64; D] {
    std::array::from_fn(|c| a[c] - b[c])
}

fn norm<const D: usize>(a: &[f64; D]) -> f64 {
    a.iter().map(|v| v * v).sum::<f64>().sqrt()
}
