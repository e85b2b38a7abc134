//! The top edge of the square with a square-capped mushroom dent (`bench_memory`'s `dented:N`
//! case, #16; `tests/folding.rs` checks how it grids): a stem 0.1 wide from y = 1 down to
//! 0.55, a cap 0.5 wide from 0.55 down to 0.3, corners rounded by three moving averages over
//! ~0.03 of arclength, nodes equally spaced in arclength.

/// `m` points along the polyline `p`, equally spaced in arclength.
pub fn resample(p: &[[f64; 2]], m: usize) -> Vec<[f64; 2]> {
    let mut s = vec![0.0];
    for w in p.windows(2) {
        let d = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
        s.push(s.last().unwrap() + d);
    }
    let total = *s.last().unwrap();
    let mut k = 0;
    (0..m)
        .map(|q| {
            let t = total * q as f64 / (m - 1) as f64;
            while k + 2 < s.len() && s[k + 1] < t {
                k += 1;
            }
            let f = ((t - s[k]) / (s[k + 1] - s[k])).clamp(0.0, 1.0);
            [0, 1].map(|c| p[k][c] + f * (p[k + 1][c] - p[k][c]))
        })
        .collect()
}

/// The dented top edge with `n` nodes, from (0, 1) to (1, 1).
pub fn square_cap_top(n: usize) -> Vec<[f64; 2]> {
    let outline = [
        [0.0, 1.0],
        [0.45, 1.0],
        [0.45, 0.55],
        [0.25, 0.55],
        [0.25, 0.3],
        [0.75, 0.3],
        [0.75, 0.55],
        [0.55, 0.55],
        [0.55, 1.0],
        [1.0, 1.0],
    ];
    let fine = 16 * n;
    let mut top = resample(&outline, fine);
    let w = fine / 200;
    for _ in 0..3 {
        let prev = top.clone();
        for q in 1..fine - 1 {
            let h = w.min(q).min(fine - 1 - q);
            let c = (2 * h + 1) as f64;
            top[q] = [0, 1].map(|k| prev[q - h..=q + h].iter().map(|p| p[k]).sum::<f64>() / c);
        }
    }
    resample(&top, n)
}
