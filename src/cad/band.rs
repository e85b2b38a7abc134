//! A closed band without a seam edge split into four blocks (issue #14): a face bounded by
//! two loops that both wind once around a periodic surface in its periodic direction (a
//! cylinder, cone or torus band as several CAD systems write them, e.g. a bolt hole's wall).
//!
//! Four straight (u, v) cuts across the band at a quarter period from each other (scaled as
//! in [`super::holes`]), the first an eighth of a period past the first loop's start, join the
//! two loops; block k lies between cuts k and k + 1, its E3 on the loop of lower
//! cross-coordinate (j = 0 there), E4 on the other, E1 and E2 on the cuts. Blocks are made
//! counterclockwise for a face whose normal is the surface's by [`super::split`].

use super::hole_cuts::crossings;
use super::holes::{locate, polygon, Cut, Layout, Node, Side};
use super::trim::{FaceLoop, LoopPoint};

/// The layout of a band bounded by `loops` (two, both winding), in (u, v) scaled by `scale`.
///
/// # Errors
/// Why the band cannot be split: the loops wind in different directions or not once around,
/// a cut crosses a loop more than once.
pub(super) fn band(loops: &mut [FaceLoop], scale: [f64; 2]) -> Result<Layout, String> {
    let w: Vec<[f64; 2]> = loops
        .iter()
        .map(|l| l.winding.unwrap_or([0.0; 2]))
        .collect();
    let d = if (w[0][0] * scale[0]).abs() >= (w[0][1] * scale[1]).abs() {
        0
    } else {
        1
    };
    let e = 1 - d;
    let t = loops[0].periods[d]
        .filter(|t| *t > 0.0)
        .ok_or("a loop winds around the surface in a direction that is not periodic")?;
    for (l, wl) in w.iter().enumerate() {
        if ((wl[d].abs() - t) / t).abs() > 1e-3 || (wl[e] * scale[e]).abs() > 1e-3 * t * scale[d] {
            return Err(format!(
                "loop {} does not wind exactly once around the surface",
                l + 1
            ));
        }
    }
    let polys: Vec<_> = loops.iter().map(|l| polygon(l, scale)).collect();
    let mean = |p: &[(LoopPoint, [f64; 2])]| p.iter().map(|q| q.1[e]).sum::<f64>() / p.len() as f64;
    let (a, b) = if mean(&polys[0]) <= mean(&polys[1]) {
        (0, 1)
    } else {
        (1, 0)
    };
    let ts = t * scale[d];
    let start = polys[a][0].1[d];
    let wrap = move |x: f64| x - ts * (x / ts).round();
    let mut ends = [[LoopPoint {
        edge: 0,
        sigma: 0.0,
    }; 2]; 4];
    for (k, end) in ends.iter_mut().enumerate() {
        let u = start + (k as f64 + 0.5) * 0.25 * ts;
        let f = move |q: [f64; 2]| wrap(q[d] - u);
        for (m, l) in [a, b].into_iter().enumerate() {
            let poly = &polys[l];
            // Sign changes of the wrapped coordinate, not its jumps half a period away.
            let x: Vec<usize> = crossings(poly, f)
                .into_iter()
                .map(|c| c.0)
                .filter(|&i| (f(poly[i].1) - f(poly[(i + 1) % poly.len()].1)).abs() < 0.5 * ts)
                .collect();
            if x.len() != 1 {
                return Err(format!(
                    "a cut across the band crosses loop {} {} times, not once",
                    l + 1,
                    x.len()
                ));
            }
            end[m] = locate(&mut loops[l], poly, x[0], scale, f)?;
        }
    }
    let cuts = ends
        .iter()
        .map(|[pa, pb]| Cut {
            from: Node { l: a, p: *pa },
            to: Node { l: b, p: *pb },
            radial: true,
        })
        .collect();
    let blocks = (0..4)
        .map(|k| {
            let k1 = (k + 1) % 4;
            // Along loop a in the direction the cuts follow each other, back along loop b.
            let s0 = Side::Loop {
                l: a,
                a: ends[k][0],
                b: ends[k1][0],
                forward: w[a][d] > 0.0,
            };
            let s2 = Side::Loop {
                l: b,
                a: ends[k1][1],
                b: ends[k][1],
                forward: w[b][d] < 0.0,
            };
            [
                Side::Cut { c: k, rev: false },
                Side::Cut { c: k1, rev: false },
                s0,
                s2.rev(),
            ]
        })
        .collect();
    Ok(Layout { cuts, blocks })
}
