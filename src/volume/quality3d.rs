//! Quality of a volume grid: corner Jacobians (the eight corner tetrahedra of every cell),
//! scaled Jacobian, folded cells, skewness, orthogonality at the six faces, aspect and growth
//! ratios, spacings ([`quality3d`], [`QualityReport3`]); per-cell arrays for VTK from
//! [`cell_fields3d`]. Definitions after notes/FORMATS.md, "Quality metrics".
//!
//! - Cell (i, j, k) has lower corner node (i, j, k). The corner Jacobian at a corner is the
//!   triple product e_ξ · (e_η × e_ζ) of the three cell edges leaving it, each pointing in its
//!   index direction (edges that leave towards lower indices are negated), i.e. six times the
//!   volume of the corner tetrahedron; the scaled Jacobian divides it by the three edge lengths
//!   (1: orthogonal corner).
//! - Orientation: the sign held by the majority of corner Jacobians; Jacobians are reported
//!   relative to it (a left-handed grid is valid). A cell is folded iff a corner Jacobian is
//!   ≤ 0 or NaN.
//! - Skewness: the largest equiangular skewness max[(θmax − 90°)/90°, (90° − θmin)/90°] of the
//!   six quadrilateral faces of a cell (corner angles between the face's edges in R³).
//! - Orthogonality at a face: at every face node that is not on the face's rim, the angle
//!   between the first grid line off the face (first interior node − face node) and the face
//!   normal (cross product of the central differences along the face): its deviation from
//!   90° to the face. With it, the first-cell heights (lengths of those lines).
//! - Aspect ratio: longest / shortest of a cell's twelve edges; growth ratio: adjacent
//!   spacings along i-, j-, k-lines, inverted to be ≥ 1.

use std::fmt;

use rayon::prelude::*;
use serde::Serialize;

use crate::quality::QualityReport;
use crate::Grid3;

/// At most this many folded cells are listed.
pub const MAX_FIRST_FOLDED: usize = 10;

/// Non-finite f64 as "nan"/"inf"/"-inf" strings (JSON has no NaN).
fn jf64<S: serde::Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if v.is_finite() {
        s.serialize_f64(*v)
    } else if v.is_nan() {
        s.serialize_str("nan")
    } else {
        s.serialize_str(if *v > 0.0 { "inf" } else { "-inf" })
    }
}

/// Orthogonality and first-cell heights at one face.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FaceQuality {
    /// "F1" … "F6".
    pub face: String,
    /// Face nodes measured (those off the face's rim).
    pub nodes: usize,
    /// Largest deviation from 90° of the first grid line off the face, degrees.
    #[serde(serialize_with = "jf64")]
    pub orthogonality_max_deg: f64,
    /// Mean deviation, degrees.
    #[serde(serialize_with = "jf64")]
    pub orthogonality_mean_deg: f64,
    /// Shortest first-cell height (length of the first grid line off the face).
    #[serde(serialize_with = "jf64")]
    pub first_height_min: f64,
    /// Longest first-cell height.
    #[serde(serialize_with = "jf64")]
    pub first_height_max: f64,
}

/// Quality summary of a volume grid (module docs give the definitions).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct QualityReport3 {
    pub ni: usize,
    pub nj: usize,
    pub nk: usize,
    /// (ni − 1)(nj − 1)(nk − 1).
    pub cells: usize,
    /// "right-handed" or "left-handed".
    pub orientation: String,
    #[serde(serialize_with = "jf64")]
    pub jacobian_min: f64,
    #[serde(serialize_with = "jf64")]
    pub jacobian_max: f64,
    #[serde(serialize_with = "jf64")]
    pub scaled_jacobian_min: f64,
    pub folded_cells: usize,
    /// Lower corner nodes (i, j, k) of the first folded cells, in index order.
    pub first_folded: Vec<[usize; 3]>,
    #[serde(serialize_with = "jf64")]
    pub skewness_max: f64,
    #[serde(serialize_with = "jf64")]
    pub skewness_mean: f64,
    /// One entry per face F1 … F6.
    pub faces: Vec<FaceQuality>,
    #[serde(serialize_with = "jf64")]
    pub aspect_ratio_max: f64,
    #[serde(serialize_with = "jf64")]
    pub growth_i_max: f64,
    #[serde(serialize_with = "jf64")]
    pub growth_j_max: f64,
    #[serde(serialize_with = "jf64")]
    pub growth_k_max: f64,
    #[serde(serialize_with = "jf64")]
    pub min_spacing: f64,
    #[serde(serialize_with = "jf64")]
    pub max_spacing: f64,
}

impl QualityReport3 {
    /// True if any cell is folded (or degenerate).
    pub fn is_folded(&self) -> bool {
        self.folded_cells > 0
    }

    /// "cell (i, j, k), …" of the first folded cells.
    pub fn folded_list(&self) -> String {
        self.first_folded
            .iter()
            .map(|c| format!("cell ({}, {}, {})", c[0], c[1], c[2]))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

type V = [f64; 3];
#[inline]
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline]
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline]
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
#[inline]
fn norm(a: V) -> f64 {
    dot(a, a).sqrt()
}
#[inline]
fn angle(a: V, b: V) -> f64 {
    norm(cross(a, b)).atan2(dot(a, b)).to_degrees()
}
fn nmin(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.min(b)
    }
}
fn nmax(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}
fn growth(a: f64, b: f64) -> f64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    if hi == 0.0 {
        1.0
    } else {
        hi / lo
    }
}

/// Per-cell measures: (min corner Jacobian, min scaled Jacobian, skewness, aspect ratio), with
/// the Jacobians multiplied by `sign`.
fn eval_cell(g: &Grid3, i: usize, j: usize, k: usize, sign: f64) -> [f64; 4] {
    let x: [V; 8] = std::array::from_fn(|c| g.point(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)));
    let (mut jmin, mut smin) = (f64::INFINITY, f64::INFINITY);
    for (c, &xc) in x.iter().enumerate() {
        let e: [V; 3] = std::array::from_fn(|a| {
            let d = sub(x[c ^ (1 << a)], xc);
            if (c >> a) & 1 == 1 {
                [-d[0], -d[1], -d[2]]
            } else {
                d
            }
        });
        let jac = sign * dot(e[0], cross(e[1], e[2]));
        let l = norm(e[0]) * norm(e[1]) * norm(e[2]);
        jmin = nmin(jmin, jac);
        smin = nmin(smin, if l > 0.0 { jac / l } else { 0.0 });
    }
    // The six faces as corner cycles of cell-corner numbers (bit 0 = i, 1 = j, 2 = k).
    const FACES: [[usize; 4]; 6] = [
        [0, 2, 6, 4],
        [1, 3, 7, 5],
        [0, 1, 5, 4],
        [2, 3, 7, 6],
        [0, 1, 3, 2],
        [4, 5, 7, 6],
    ];
    let mut skew = 0.0f64;
    for f in FACES {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for q in 0..4 {
            let p = x[f[q]];
            let th = angle(sub(x[f[(q + 1) % 4]], p), sub(x[f[(q + 3) % 4]], p));
            lo = nmin(lo, th);
            hi = nmax(hi, th);
        }
        skew = nmax(skew, nmax((hi - 90.0) / 90.0, (90.0 - lo) / 90.0));
    }
    let (mut emin, mut emax) = (f64::INFINITY, 0.0f64);
    for c in 0..8 {
        for a in 0..3 {
            if (c >> a) & 1 == 0 {
                let l = norm(sub(x[c | (1 << a)], x[c]));
                emin = nmin(emin, l);
                emax = nmax(emax, l);
            }
        }
    }
    [jmin, smin, skew, emax / emin]
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
                    let jac = eval_cell(g, i, j, k, 1.0)[0];
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

struct Acc {
    jmin: f64,
    jmax: f64,
    smin: f64,
    skew_max: f64,
    skew_sum: f64,
    aspect: f64,
    folded: usize,
    first: Vec<[usize; 3]>,
}

impl Acc {
    fn new() -> Self {
        Acc {
            jmin: f64::INFINITY,
            jmax: f64::NEG_INFINITY,
            smin: f64::INFINITY,
            skew_max: f64::NEG_INFINITY,
            skew_sum: 0.0,
            aspect: f64::NEG_INFINITY,
            folded: 0,
            first: vec![],
        }
    }
    fn merge(mut self, b: Acc) -> Acc {
        self.jmin = nmin(self.jmin, b.jmin);
        self.jmax = nmax(self.jmax, b.jmax);
        self.smin = nmin(self.smin, b.smin);
        self.skew_max = nmax(self.skew_max, b.skew_max);
        self.skew_sum += b.skew_sum;
        self.aspect = nmax(self.aspect, b.aspect);
        self.folded += b.folded;
        let room = MAX_FIRST_FOLDED - self.first.len();
        self.first.extend(b.first.into_iter().take(room));
        self
    }
}

/// Growth ratios and spacing extremes along lines of direction `a` (0 = i, 1 = j, 2 = k).
fn lines(g: &Grid3, a: usize) -> (f64, f64, f64) {
    let d = g.dims();
    let st = [1, d[0], d[0] * d[1]][a];
    let x = g.coords();
    let h = |p: usize| {
        let v: V = std::array::from_fn(|c| x[c][p + st] - x[c][p]);
        norm(v)
    };
    (0..d.iter().product::<usize>())
        .into_par_iter()
        .filter(|&p| [p % d[0], (p / d[0]) % d[1], p / (d[0] * d[1])][a] + 1 < d[a])
        .map(|p| {
            let hp = h(p);
            let idx = [p % d[0], (p / d[0]) % d[1], p / (d[0] * d[1])][a];
            let gr = if idx + 2 < d[a] {
                growth(hp, h(p + st))
            } else {
                1.0
            };
            (gr, hp, hp)
        })
        .reduce(
            || (1.0, f64::INFINITY, 0.0),
            |u, v| (nmax(u.0, v.0), nmin(u.1, v.1), nmax(u.2, v.2)),
        )
}

/// Orthogonality and first heights at face f (0 = F1 … 5 = F6).
fn face_quality(g: &Grid3, f: usize) -> FaceQuality {
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
                    a.jmin = nmin(a.jmin, jac);
                    a.jmax = nmax(a.jmax, jac);
                    a.smin = nmin(a.smin, s);
                    a.skew_max = nmax(a.skew_max, sk);
                    a.skew_sum += sk;
                    a.aspect = nmax(a.aspect, ar);
                    if jac <= 0.0 || jac.is_nan() {
                        a.folded += 1;
                        if a.first.len() < MAX_FIRST_FOLDED {
                            a.first.push([i, j, k]);
                        }
                    }
                }
            }
            a
        })
        .collect::<Vec<_>>()
        .into_iter()
        .fold(Acc::new(), Acc::merge);
    let (gi, gj, gk) = (lines(g, 0), lines(g, 1), lines(g, 2));
    rep.jacobian_min = acc.jmin;
    rep.jacobian_max = acc.jmax;
    rep.scaled_jacobian_min = acc.smin;
    rep.folded_cells = acc.folded;
    rep.first_folded = acc.first;
    rep.skewness_max = acc.skew_max;
    rep.skewness_mean = acc.skew_sum / cells as f64;
    rep.aspect_ratio_max = acc.aspect;
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

fn num(v: f64) -> String {
    if v.is_nan() {
        "-".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else if v == 0.0 {
        "0".into()
    } else if (1e-3..1e5).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

impl fmt::Display for QualityReport3 {
    /// A compact table like the 2D report's, one line per face for orthogonality.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let status = if self.is_folded() { "FOLDED" } else { "ok" };
        writeln!(
            f,
            "grid quality  {} x {} x {} nodes, {} cells, {}: {}",
            self.ni, self.nj, self.nk, self.cells, self.orientation, status
        )?;
        let line = |name: &str, cols: &[(&str, f64)]| {
            let mut l = format!("  {name:<22}");
            for (label, v) in cols {
                l += &format!(" {label:>4} {:>10}", num(*v));
            }
            l
        };
        writeln!(
            f,
            "{}",
            line(
                "jacobian",
                &[("min", self.jacobian_min), ("max", self.jacobian_max)]
            )
        )?;
        writeln!(
            f,
            "{}",
            line("scaled jacobian", &[("min", self.scaled_jacobian_min)])
        )?;
        let mut folded = format!("  {:<22} {:>15}", "folded cells", self.folded_cells);
        if !self.first_folded.is_empty() {
            folded += "   first:";
            for [i, j, k] in &self.first_folded {
                folded += &format!(" ({i},{j},{k})");
            }
            if self.folded_cells > self.first_folded.len() {
                folded += " …";
            }
        }
        writeln!(f, "{folded}")?;
        writeln!(
            f,
            "{}",
            line(
                "skewness",
                &[("max", self.skewness_max), ("mean", self.skewness_mean)]
            )
        )?;
        writeln!(
            f,
            "{}",
            line("aspect ratio", &[("max", self.aspect_ratio_max)])
        )?;
        writeln!(
            f,
            "{}",
            line(
                "growth ratio",
                &[
                    ("i", self.growth_i_max),
                    ("j", self.growth_j_max),
                    ("k", self.growth_k_max)
                ]
            )
        )?;
        writeln!(
            f,
            "{}",
            line(
                "spacing",
                &[("min", self.min_spacing), ("max", self.max_spacing)]
            )
        )?;
        for q in &self.faces {
            let l = line(
                &format!("orthogonality {} (°)", q.face),
                &[
                    ("max", q.orthogonality_max_deg),
                    ("mean", q.orthogonality_mean_deg),
                ],
            );
            writeln!(
                f,
                "{l}   first height {} .. {}",
                num(q.first_height_min),
                num(q.first_height_max)
            )?;
        }
        Ok(())
    }
}

/// The quality report of a 2D (planar or surface) or a volume block, for reports that hold
/// either (smoothing). Serialized as the inner report.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum AnyQuality {
    Surface(QualityReport),
    Volume(QualityReport3),
}

impl AnyQuality {
    /// True if any cell is folded.
    pub fn is_folded(&self) -> bool {
        match self {
            AnyQuality::Surface(q) => q.is_folded(),
            AnyQuality::Volume(q) => q.is_folded(),
        }
    }

    /// Number of folded cells.
    pub fn folded_cells(&self) -> usize {
        match self {
            AnyQuality::Surface(q) => q.folded_cells,
            AnyQuality::Volume(q) => q.folded_cells,
        }
    }

    /// "cell (i, j[, k]), …" of the first folded cells.
    pub fn folded_list(&self) -> String {
        match self {
            AnyQuality::Surface(q) => crate::job::cell_list(&q.first_folded),
            AnyQuality::Volume(q) => q.folded_list(),
        }
    }
}

impl From<QualityReport> for AnyQuality {
    fn from(q: QualityReport) -> Self {
        AnyQuality::Surface(q)
    }
}

impl fmt::Display for AnyQuality {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AnyQuality::Surface(q) => q.fmt(f),
            AnyQuality::Volume(q) => q.fmt(f),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn box_grid(xs: &[f64], ys: &[f64], zs: &[f64]) -> Grid3 {
        let mut g = Grid3::zeros(xs.len(), ys.len(), zs.len());
        for (k, z) in zs.iter().enumerate() {
            for (j, y) in ys.iter().enumerate() {
                for (i, x) in xs.iter().enumerate() {
                    g.set(i, j, k, [*x, *y, *z]);
                }
            }
        }
        g
    }

    #[test]
    fn box_metrics_are_exact() {
        let g = box_grid(&[0.0, 1.0, 3.0], &[0.0, 0.5], &[0.0, 2.0, 4.0, 8.0]);
        let q = quality3d(&g);
        assert_eq!(q.cells, 2 * 3);
        assert_eq!(q.folded_cells, 0);
        assert_eq!(q.orientation, "right-handed");
        assert!((q.jacobian_min - 1.0).abs() < 1e-14); // 1 × 0.5 × 2
        assert!((q.jacobian_max - 2.0 * 0.5 * 4.0).abs() < 1e-14);
        assert!((q.scaled_jacobian_min - 1.0).abs() < 1e-14);
        assert!(q.skewness_max.abs() < 1e-14);
        assert!((q.aspect_ratio_max - 8.0).abs() < 1e-14); // 4 / 0.5
        assert!((q.growth_i_max - 2.0).abs() < 1e-14 && (q.growth_k_max - 2.0).abs() < 1e-14);
        assert_eq!(q.growth_j_max, 1.0);
        assert!((q.min_spacing - 0.5).abs() < 1e-14 && (q.max_spacing - 4.0).abs() < 1e-14);
        // F5 (k = 0) has one inner node (i = 1, j: none since nj = 2) → no nodes.
        assert_eq!(q.faces[4].nodes, 0);
        assert_eq!(q.faces[0].nodes, 0);
        let s = q.to_string();
        assert!(s.contains("folded cells") && s.contains("F6"), "{s}");
    }

    #[test]
    fn a_folded_cell_is_found_and_mirrors_are_valid() {
        let r: Vec<f64> = (0..4).map(|v| v as f64).collect();
        let mut g = box_grid(&r, &r, &r);
        let mirrored = {
            let mut m = g.clone();
            m.coords_mut()[0].iter_mut().for_each(|v| *v = -*v);
            m
        };
        let qm = quality3d(&mirrored);
        assert_eq!(
            (qm.orientation.as_str(), qm.folded_cells),
            ("left-handed", 0)
        );
        g.set(1, 1, 1, [0.2, 0.2, 0.2]); // the (+,+,+) corner of cell (0,0,0) turned inside out
        let q = quality3d(&g);
        assert!(q.is_folded());
        assert_eq!(q.first_folded[0], [0, 0, 0]);
        let f = cell_fields3d(&g);
        assert_eq!(f[0].1.len(), 27);
        assert!(f[0].1[0] < 0.0);
        let face = q.faces[0].clone();
        assert_eq!(face.nodes, 4);
        assert!((face.first_height_min - 1.0).abs() < 1e-14);
    }
}
