//! [`BoxTree`] against brute force: random boxes (thin, flat, tiny, far from the origin) and
//! points inside, outside, exactly on faces and at corners.

use super::*;
use crate::surface::testutil::Rng;

/// Exact f64 containment.
fn inside(b: &[f64; 6], p: [f64; 3]) -> bool {
    (0..3).all(|d| b[d] <= p[d] && p[d] <= b[d + 3])
}

/// Exact f64 distance from p to box b.
fn dist(b: &[f64; 6], p: [f64; 3]) -> f64 {
    (0..3)
        .map(|d| (b[d] - p[d]).max(p[d] - b[d + 3]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Random boxes around `centre` with sizes down to `tiny` (below f32 resolution there).
fn random_boxes(
    rng: &mut Rng,
    n: usize,
    centre: f64,
    spread: f64,
    tiny: f64,
    flat: bool,
) -> Vec<[f64; 6]> {
    (0..n)
        .map(|_| {
            let mut b = [0.0; 6];
            for d in 0..3 {
                let lo = centre + rng.range(-spread, spread);
                let size = if rng.f64() < 0.3 {
                    tiny * rng.f64()
                } else {
                    rng.range(0.0, 0.1 * spread)
                };
                b[d] = lo;
                b[d + 3] = lo + size;
            }
            if flat {
                b[2] = 0.0;
                b[5] = 0.0;
            }
            b
        })
        .collect()
}

/// Query points: random, and exactly on faces, edges and corners of random boxes.
fn query_points(
    rng: &mut Rng,
    boxes: &[[f64; 6]],
    centre: f64,
    spread: f64,
    n: usize,
) -> Vec<[f64; 3]> {
    (0..n)
        .map(|k| {
            let b = &boxes[rng.next_u64() as usize % boxes.len()];
            let mut p = [0.0; 3];
            for d in 0..3 {
                p[d] = match (k % 4, rng.next_u64() % 3) {
                    (0, _) => centre + rng.range(-1.2 * spread, 1.2 * spread),
                    (1, 0) | (2, _) => b[d],
                    (1, 1) | (3, _) => b[d + 3],
                    _ => rng.range(b[d], b[d + 3]),
                };
            }
            p
        })
        .collect()
}

fn check(boxes: &[[f64; 6]], points: &[[f64; 3]]) {
    let tree = BoxTree::new(boxes).unwrap();
    assert_eq!(tree.len(), boxes.len());
    let mut got = Vec::new();
    let mut found = 0;
    for &p in points {
        tree.candidates(p, &mut got);
        got.sort_unstable();
        let want: Vec<usize> = (0..boxes.len()).filter(|&k| inside(&boxes[k], p)).collect();
        found += want.len();
        // Every containing box is reported; extras only within the padding (~1e-6 relative).
        for k in &want {
            assert!(
                got.binary_search(k).is_ok(),
                "box {k} {:?} misses {p:?}",
                boxes[*k]
            );
        }
        let scale = 1.0 + p.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for &k in &got {
            assert!(
                dist(&boxes[k], p) < 1e-6 * scale,
                "candidate {k} far from {p:?}"
            );
        }
        // nearest with the exact box distance equals the brute-force minimum.
        let mut calls = 0;
        let (k, d) = tree
            .nearest(p, |k| {
                calls += 1;
                dist(&boxes[k], p)
            })
            .unwrap();
        let dmin = boxes
            .iter()
            .map(|b| dist(b, p))
            .fold(f64::INFINITY, f64::min);
        assert_eq!(d, dmin, "nearest at {p:?}");
        assert_eq!(dist(&boxes[k], p), d);
        assert!(calls <= boxes.len());
    }
    assert!(
        found > points.len() / 2,
        "too few hits ({found}) to test anything"
    );
}

#[test]
fn candidates_and_nearest_match_brute_force() {
    let mut rng = Rng::new(42);
    for &(n, centre, spread, tiny, flat) in &[
        (1, 0.0, 1.0, 0.0, false),
        (7, 0.0, 1.0, 1e-12, false),
        (500, 0.0, 1.0, 1e-9, false),
        (500, 0.0, 1.0, 1e-9, true),       // 2D: z = 0
        (400, 1.0e5, 10.0, 1e-9, false),   // far from the origin: widths below f32 resolution
        (300, -3.0e-7, 1e-6, 1e-20, true), // tiny coordinates
    ] {
        let boxes = random_boxes(&mut rng, n, centre, spread, tiny, flat);
        let pts = query_points(&mut rng, &boxes, centre, spread, 2000);
        check(&boxes, &pts);
    }
}

#[test]
fn edge_cases() {
    let empty = BoxTree::new(&[]).unwrap();
    let mut out = vec![7];
    empty.candidates([0.0; 3], &mut out);
    assert!(out.is_empty() && empty.is_empty());
    assert!(empty.nearest([0.0; 3], |_| 0.0).is_none());
    let tree = BoxTree::new(&[[0.0, 0.0, 0.0, 1.0, 1.0, 0.0]]).unwrap();
    tree.candidates([f64::NAN, 0.5, 0.0], &mut out);
    assert!(out.is_empty());
    tree.candidates([1.0, 1.0, 0.0], &mut out);
    assert_eq!(out, [0]);
    assert!(tree.nearest([f64::NAN, 0.0, 0.0], |_| 0.0).is_none());
    assert!(tree.nearest([0.0; 3], |_| f64::NAN).is_none());
    assert!(BoxTree::new(&[[0.0, 0.0, 0.0, -1.0, 1.0, 1.0]]).is_err());
    assert!(BoxTree::new(&[[0.0, f64::INFINITY, 0.0, 1.0, 1.0, 1.0]]).is_err());
    // Outward rounding to f32.
    for x in [0.1f64, -0.1, 1e-40, -1e-40, 0.0, 3.0e5 + 1e-9] {
        assert!((f32_down(x) as f64) <= x && (f32_up(x) as f64) >= x, "{x}");
    }
}

/// Prints build and query cost (no timing assert) for the boxes of a 316 × 316 cell grid.
#[test]
fn speed() {
    let n = 316;
    let h = 1.0 / n as f64;
    let boxes: Vec<[f64; 6]> = (0..n * n)
        .map(|c| {
            let (x, y) = ((c % n) as f64 * h, (c / n) as f64 * h);
            [x, y, 0.0, x + h, y + h, 0.0]
        })
        .collect();
    let t = std::time::Instant::now();
    let tree = BoxTree::new(&boxes).unwrap();
    let build = t.elapsed();
    let mut rng = Rng::new(1);
    let pts: Vec<[f64; 3]> = (0..100_000).map(|_| [rng.f64(), rng.f64(), 0.0]).collect();
    let mut out = Vec::new();
    let t = std::time::Instant::now();
    let mut hits = 0;
    for &p in &pts {
        tree.candidates(p, &mut out);
        hits += out.len();
    }
    let cand_ns = t.elapsed().as_nanos() as f64 / pts.len() as f64;
    let t = std::time::Instant::now();
    let mut s = 0.0;
    for &p in &pts {
        let q = [p[0], p[1], 0.01];
        s += tree.nearest(q, |k| dist(&boxes[k], q)).unwrap().1;
    }
    let near_ns = t.elapsed().as_nanos() as f64 / pts.len() as f64;
    println!(
        "BoxTree {} boxes: build {build:?}, candidates {cand_ns:.0} ns ({:.2} hits a query), \
         nearest {near_ns:.0} ns ({s:.1})",
        boxes.len(),
        hits as f64 / pts.len() as f64
    );
    assert!(hits >= pts.len());
}
