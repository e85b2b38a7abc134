//! The NACA0012 four-domain O-grid (paper Figs 7–10) under refinement: the smoothness across
//! its interior edges improves with the grid, as the issue asks: the kink of the grid lines
//! crossing the orthogonal cuts shrinks, and with floating cuts the kink and the spacing
//! ratio shrink at least as fast as the same measures inside a block.

mod common;
use common::root;
use ellipgrid::case::LoadedCase;
use ellipgrid::io::Block;
use ellipgrid::job;
use std::path::Path;

/// The shipped example with every edge refined once: n → 2n − 1, and the Vinokur end
/// spacings (fractions of the edge length) halved, so that the nodes of the coarse grid
/// keep their places along the edges (up to the distribution's own convergence).
fn refined(text: &str, times: u32) -> String {
    let f = 1usize << times;
    let mut out = String::new();
    for line in text.lines() {
        let line = if let Some(n) = line.strip_prefix("n = ") {
            let n: usize = n.trim().parse().unwrap();
            format!("n = {}", (n - 1) * f + 1)
        } else if line.starts_with("distribution = { type = \"vinokur\"") {
            halve_spacings(line, f as f64)
        } else {
            line.to_string()
        };
        out.push_str(&line);
        out.push('\n');
    }
    out
}

/// `first = a, last = b` of an inline distribution table divided by `f`.
fn halve_spacings(line: &str, f: f64) -> String {
    let body = line
        .trim_start_matches("distribution = {")
        .trim_end_matches('}');
    let parts: Vec<String> = body
        .split(',')
        .map(|kv| {
            let (k, v) = kv.split_once('=').unwrap();
            let k = k.trim();
            if k == "first" || k == "last" {
                let v: f64 = v.trim().parse().unwrap();
                format!("{k} = {:?}", v / f)
            } else {
                format!("{k} = {}", v.trim())
            }
        })
        .collect();
    format!("distribution = {{ {} }}", parts.join(", "))
}

/// The cuts at mid-chord float (the two rows upper_fore + upper_aft and lower_fore +
/// lower_aft are gridded as one block each).
fn floating_mid_cuts(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        out.push_str(line);
        out.push('\n');
        if line == "name = \"cut_up\"" || line == "name = \"cut_lo\"" {
            out.push_str("interface = \"floating\"\n");
        }
    }
    out
}

fn generate(text: &str) -> job::Generated {
    let path = root().join("examples/naca0012_ogrid.toml");
    let case = LoadedCase::parse(text, Path::new(&path)).unwrap();
    job::generate(&case, |_| {}).unwrap()
}

/// (kink max °, kink mean °, spacing ratio max − 1, spacing ratio mean − 1) of an interface.
fn across(g: &job::Generated, edge: &str) -> [f64; 4] {
    let f = g.report.interfaces.iter().find(|f| f.edge == edge).unwrap();
    let s = &f.smoothness;
    [
        s.kink_max_deg,
        s.kink_mean_deg,
        s.spacing_ratio_max - 1.0,
        s.spacing_ratio_mean - 1.0,
    ]
}

/// The same measures inside block `name` at i-line `i` (from the end if negative): the kink
/// of the j = const lines crossing it and the ratio of their spacings on the two sides.
fn inside(g: &job::Generated, name: &str, i: isize) -> [f64; 4] {
    let (_, b) = g.blocks.iter().find(|(n, _)| n == name).unwrap();
    let Block::Planar(x) = b else {
        panic!("planar")
    };
    let i = if i < 0 { x.ni() as isize + i } else { i } as usize;
    let mut m = [0.0f64; 4];
    let n = x.nj() - 2;
    for j in 1..x.nj() - 1 {
        let p = x.point(i, j);
        let a = x.point(i - 1, j);
        let b = x.point(i + 1, j);
        let (u, v) = ([a[0] - p[0], a[1] - p[1]], [b[0] - p[0], b[1] - p[1]]);
        let (lu, lv) = (u[0].hypot(u[1]), v[0].hypot(v[1]));
        let cos = -(u[0] * v[0] + u[1] * v[1]) / (lu * lv);
        let kink = cos.clamp(-1.0, 1.0).acos().to_degrees();
        let ratio = lu.max(lv) / lu.min(lv) - 1.0;
        m[0] = m[0].max(kink);
        m[1] += kink / n as f64;
        m[2] = m[2].max(ratio);
        m[3] += ratio / n as f64;
    }
    m
}

fn shipped() -> String {
    std::fs::read_to_string(root().join("examples/naca0012_ogrid.toml")).unwrap()
}

/// The example as shipped and refined once, gridded.
fn coarse_and_fine(text: &str) -> [job::Generated; 2] {
    [0, 1].map(|t| generate(&refined(text, t)))
}

#[test]
fn the_kink_across_the_orthogonal_cuts_shrinks_under_refinement() {
    let [coarse, fine] = coarse_and_fine(&shipped());
    for g in [&coarse, &fine] {
        for r in &g.report.blocks {
            assert_eq!(r.quality.folded_cells, 0, "{}", r.name);
        }
    }
    // Orthogonality on both sides gives slope continuity: the kink is a first-order
    // quantity, halving with h (measured 2.0–2.4 at the leading-edge and mid-chord cuts).
    for cut in ["cut_le", "cut_up", "cut_lo"] {
        let (c, f) = (across(&coarse, cut), across(&fine, cut));
        assert!(
            c[0] / f[0] > 1.8 && c[1] / f[1] > 1.8,
            "{cut}: {c:?} → {f:?}"
        );
    }
    // At the trailing-edge cut the lines next to the sharp trailing edge turn round it (the
    // largest kink stays ~94°, at the corner); the mean still shrinks (measured 1.6).
    let (c, f) = (across(&coarse, "cut_te"), across(&fine, "cut_te"));
    assert!(c[1] / f[1] > 1.4, "cut_te: {c:?} → {f:?}");
}

#[test]
fn floating_cuts_are_as_smooth_as_the_inside_of_a_block_under_refinement() {
    let [coarse, fine] = coarse_and_fine(&floating_mid_cuts(&shipped()));
    let [pc, pf] = coarse_and_fine(&shipped());
    for cut in ["cut_up", "cut_lo"] {
        let blk = if cut == "cut_up" {
            "upper_fore"
        } else {
            "lower_fore"
        };
        let (c, f) = (across(&coarse, cut), across(&fine, cut));
        let (ic, if_) = (inside(&coarse, blk, -2), inside(&fine, blk, -2));
        for m in 0..4 {
            // As smooth as inside a block next to the cut (the line one cell before it in
            // the fore block; the kink varies along the chord: +1.2 % at the cut), and
            // shrinking as fast (within 10 %; measured 1.93–2.0 across, ~2.0 inside).
            assert!(
                c[m] <= 1.05 * ic[m] && f[m] <= 1.05 * if_[m],
                "{cut} measure {m}: {c:?} {f:?} inside {ic:?} {if_:?}"
            );
            assert!(
                c[m] / f[m] >= 0.9 * ic[m] / if_[m],
                "{cut} measure {m}: {c:?} → {f:?}, inside {ic:?} → {if_:?}"
            );
        }
        // A prescribed cut keeps a spacing jump of ~30 % that does not shrink; the floating
        // cut's is a hundred times smaller.
        let (prescribed_c, prescribed_f) = (across(&pc, cut), across(&pf, cut));
        assert!(
            prescribed_f[2] >= 0.8 * prescribed_c[2],
            "{prescribed_c:?} {prescribed_f:?}"
        );
        assert!(
            f[2] < 0.01 * prescribed_f[2],
            "{f:?} vs prescribed {prescribed_f:?}"
        );
    }
}
