//! A face's boundary loop on its surface (METHOD.md §5 step 1 for a trimmed face): every edge's
//! (u, v) found by closest-point projection and continued across seams, four corners picked on
//! the loop, and the loop's four sides (chains of edges, or parts of one) sampled at given
//! fractions of their 3D arclength.

use super::edge::knots;
use super::LoopEdge;
pub(super) use cusp::{CORNER_LIKE, CUSP, TIP};
use ellipgrid_geometry::{
    project_within, ArclengthMap, Curve, Surface, TruckCurve, TruckSurface, Vec3,
};
pub use heal::HEAL;
use pole::singular;
use truck_geometry::prelude::{ParametricSurface, Point3, SearchNearestParameter, D2};
use truck_stepio::r#in::alias::{Curve3D, Surface as StepSurface};

mod balance;
mod corners;
mod cusp;
mod heal;
mod pole;
mod sample;

/// A CAD surface in its own parameters.
pub(super) type CadSurface = TruckSurface<StepSurface>;

/// Samples per edge of the loop polygon in (u, v) (hints, orientation, closure).
pub(super) const NS: usize = 32;
/// An edge shorter than this fraction of the loop is degenerate (a point: left out of the
/// loop; where it sits on a pole, the pole is found as at any vertex).
const DEGENERATE: f64 = 1e-9;

/// One oriented edge of the loop with its arclength table and its (u, v) samples.
#[derive(Clone)]
pub(super) struct LoopCurve {
    /// The edge's number in the loop as the file gives it (1-based, zero-length edges
    /// counted), for messages.
    number: usize,
    curve: TruckCurve<Curve3D>,
    map: ArclengthMap,
    /// (u, v) at the normalized arclengths k / NS, k = 0..=NS.
    pub uv: Vec<[f64; 2]>,
    /// Moves of its start and end where the file's edges do not meet ([`heal`]).
    shift: [Vec3; 2],
}

impl LoopCurve {
    /// The point at normalized arclength `sigma`, healed ([`heal`]).
    fn point(&self, sigma: f64) -> Vec3 {
        let x = self.curve.point(self.map.param_at(sigma));
        if self.shift == [Vec3::zeros(); 2] {
            x // bit for bit as read (no -0.0 turned into 0.0)
        } else {
            x + heal::blend(&self.shift, sigma)
        }
    }
}

/// A point of the loop: edge `edge` at normalized arclength `sigma` of that edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LoopPoint {
    pub edge: usize,
    pub sigma: f64,
}

/// A face's boundary loop on its surface (a clone of a loop not yet sampled is the loop
/// [`FaceLoop::new`] would build again: one per try of a face).
#[derive(Clone)]
pub(super) struct FaceLoop<'a> {
    surface: &'a CadSurface,
    bounds: [[f64; 2]; 2],
    pub periods: [Option<f64>; 2],
    pub edges: Vec<LoopCurve>,
    /// Largest distance between a sampled boundary point and the surface.
    pub gap: f64,
    /// Distance beyond which a boundary point is "not on the surface".
    tol: f64,
    /// Distance beyond which the file's defects are not healed ([`HEAL`] of the loop's size).
    heal: f64,
    /// Largest defect beyond `tol` healed: a gap between edges or a distance from the
    /// surface (0: none).
    pub healed: f64,
    /// Mean |x_u|, |x_v| over the samples ([`FaceLoop::metric_scale`]).
    scale: [f64; 2],
    /// (u, v) at the loop's end less at its start, if the loop winds around the surface.
    pub winding: Option<[f64; 2]>,
    /// The vertex (the start of this edge) where the loop runs through a pole of the
    /// surface's parametrization: there the loop's (u, v) jumps along the pole, which is a
    /// side of the face of zero length (a cone's apex, a sphere's pole).
    pub pole: Option<usize>,
    /// The vertex (the start of this edge) gridded as a side of zero length that is one point
    /// in (u, v) as well: a cusp, or the sharpest of three corner-like vertices
    /// ([`FaceLoop::collapsed_at`]); set only for that try of a face.
    pub cusp: Option<usize>,
}

/// Shifts periodic parameters of `uv` by whole periods to lie nearest `near`.
fn unwrap(mut uv: [f64; 2], near: [f64; 2], periods: [Option<f64>; 2]) -> [f64; 2] {
    for d in 0..2 {
        if let Some(t) = periods[d].filter(|t| *t > 0.0) {
            uv[d] += t * ((near[d] - uv[d]) / t).round();
        }
    }
    uv
}

impl<'a> FaceLoop<'a> {
    /// Samples the loop's edges and finds their (u, v) on `surface`; `bounds` is the box
    /// the projection may move in. A boundary point farther than `tol_rel` times the loop's
    /// size (or `tol_abs`, if larger: from the file's uncertainty) from the surface is an
    /// error; so is a loop that winds around the surface unless
    /// `winding` (then [`FaceLoop::winding`] says by how much).
    ///
    /// # Errors
    /// The reason, naming the edge (1-based in loop order): unbounded or degenerate edges,
    /// edges off the surface, edges that do not meet, a loop that winds around the surface.
    pub fn new(
        surface: &'a CadSurface,
        edges: &[LoopEdge],
        bounds: [[f64; 2]; 2],
        (tol_rel, tol_abs, heal_rel): (f64, f64, f64),
        winding: bool,
    ) -> Result<FaceLoop<'a>, String> {
        if edges.is_empty() {
            return Err("the boundary loop has no edges".into());
        }
        let mut curves = Vec::with_capacity(edges.len());
        for (n, e) in edges.iter().enumerate() {
            let curve = TruckCurve::on(e.curve.clone(), e.range, e.forward, &knots(&e.curve))
                .ok_or_else(|| format!("boundary edge {} is unbounded", n + 1))?;
            let map = ArclengthMap::new(&curve);
            if !map.length().is_finite() {
                return Err(format!("boundary edge {} has no finite length", n + 1));
            }
            curves.push((curve, map));
        }
        let total: f64 = curves.iter().map(|c| c.1.length()).sum();
        let (numbers, curves): (Vec<usize>, Vec<_>) = curves
            .into_iter()
            .enumerate()
            .filter(|(_, c)| c.1.length() > DEGENERATE * total)
            .map(|(k, c)| (k + 1, c))
            .unzip();
        if curves.is_empty() {
            return Err("the boundary loop has no length".into());
        }
        let mut pts: Vec<Vec<Vec3>> = curves
            .iter()
            .map(|(c, m)| {
                (0..=NS)
                    .map(|k| c.point(m.param_at(k as f64 / NS as f64)))
                    .collect()
            })
            .collect();
        let (lo, hi) = pts.iter().flatten().fold(
            (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.inf(p), hi.sup(p)),
        );
        let size = (hi - lo).norm();
        let mut lp = FaceLoop {
            surface,
            bounds,
            periods: surface.periods(),
            edges: Vec::new(),
            gap: 0.0,
            tol: (tol_rel * size).max(tol_abs),
            heal: (heal_rel * size).max(tol_rel * size).max(tol_abs),
            healed: 0.0,
            scale: [1.0; 2],
            winding: None,
            pole: None,
            cusp: None,
        };
        let n = curves.len();
        let ends: Vec<(Vec3, Vec3)> = pts.iter().map(|p| (p[0], p[NS])).collect();
        let mut shifts = match heal::end_shifts(&ends, lp.heal) {
            Ok((shifts, gap)) if gap > lp.tol => {
                lp.healed = gap;
                shifts
            }
            Ok(_) => vec![[Vec3::zeros(); 2]; n],
            Err((k, miss)) => {
                return Err(format!(
                    "boundary edges {} and {} do not meet (gap {miss:.3e}, {:.2} % of the loop's \
                     size; healed up to {:.2} %)",
                    numbers[k],
                    numbers[(k + 1) % n],
                    100.0 * miss / size,
                    100.0 * heal_rel
                ))
            }
        };
        for (p, shift) in pts
            .iter_mut()
            .zip(&shifts)
            .filter(|(_, s)| lp.healed > 0.0 && **s != [Vec3::zeros(); 2])
        {
            for (i, x) in p.iter_mut().enumerate() {
                *x += heal::blend(shift, i as f64 / NS as f64);
            }
        }
        let mut uv = lp.project_loop(&pts, &numbers, 0)?;
        // A pole at a vertex: the loop's (u, v) is continuous everywhere else, so it is
        // projected again starting there (a period in a periodic parameter is then taken up by
        // the pole), and the (u, v) of its two ends are the limits along their edges.
        if !winding {
            let poles: Vec<usize> = (0..n).filter(|&k| lp.is_pole(&uv, k)).collect();
            if poles.len() > 1 {
                let at: Vec<String> = poles.iter().map(|&k| numbers[k].to_string()).collect();
                return Err(format!(
                    "the boundary loop runs through {} poles of the surface (at the starts of \
                     edges {}): not one block face",
                    poles.len(),
                    at.join(", ")
                ));
            }
            if let Some(&k) = poles.first() {
                uv = lp.project_loop(&pts, &numbers, k)?;
                lp.pole = lp
                    .pole_ends(&mut uv, k, pts[k][0], size)
                    .map_err(|e| format!("boundary edge {}: {e}", numbers[k]))?;
            }
        }
        let (first, prev) = match lp.pole {
            Some(k) => (uv[k][0], uv[(k + n - 1) % n][NS]),
            None => (uv[0][0], uv[n - 1][NS]),
        };
        for (((curve, map), uv), number) in curves.into_iter().zip(uv).zip(numbers) {
            lp.edges.push(LoopCurve {
                number,
                curve,
                map,
                uv,
                shift: std::mem::take(&mut shifts[lp.edges.len()]),
            });
        }
        lp.scale = lp.mean_speeds();
        // Closure: back at the start in (u, v), not a period away (unless `winding`).
        let scale = lp.scale;
        let miss = (0..2)
            .map(|c| ((prev[c] - first[c]) * scale[c]).abs())
            .fold(0.0, f64::max);
        if miss > 1e-3 * size.max(f64::MIN_POSITIVE) && lp.pole.is_none() {
            lp.winding = Some([0, 1].map(|c| prev[c] - first[c]));
        }
        if lp.winding.is_some() && !winding {
            return Err(
                "the boundary loop winds around the surface (a closed band without a seam edge, \
                 or a cap around a pole): not one block face"
                    .into(),
            );
        }
        Ok(lp)
    }

    /// (u, v) of the samples `pts` of every edge, each from the one before, going round the
    /// loop from the start of edge `start`.
    fn project_loop(
        &mut self,
        pts: &[Vec<Vec3>],
        numbers: &[usize],
        start: usize,
    ) -> Result<Vec<Vec<[f64; 2]>>, String> {
        let n = pts.len();
        let mut out = vec![Vec::new(); n];
        let mut prev = self.initial_uv(pts[start][0])?;
        for k in (start..n).chain(0..start) {
            out[k] = Vec::with_capacity(NS + 1);
            for x in &pts[k] {
                let q = self.project(*x, prev, numbers[k])?;
                out[k].push(q);
                prev = q;
            }
        }
        Ok(out)
    }

    /// (u, v) of a first boundary point without a nearby start: truck's search, else a
    /// coarse search over the surface's bounded parameter box; then Newton.
    fn initial_uv(&self, x: Vec3) -> Result<[f64; 2], String> {
        let p = Point3::new(x.x, x.y, x.z);
        let found = super::quietly(|| {
            SearchNearestParameter::<D2>::search_nearest_parameter(
                self.surface.inner(),
                p,
                None,
                100,
            )
        })
        .ok()
        .flatten();
        let start = found.or_else(|| {
            let [[u0, u1], [v0, v1]] = self.search_box()?;
            let mut best = (f64::INFINITY, (u0, v0));
            for i in 0..=32 {
                for j in 0..=32 {
                    let (u, v) = (
                        u0 + (u1 - u0) * i as f64 / 32.0,
                        v0 + (v1 - v0) * j as f64 / 32.0,
                    );
                    let d = (self.surface.point(u, v) - x).norm();
                    if d < best.0 {
                        best = (d, (u, v));
                    }
                }
            }
            Some(best.1)
        });
        let start = start.ok_or("no start for the projection onto the surface")?;
        let (u, v) = project_within(self.surface, x, start, self.bounds)
            .ok_or("the projection of the boundary onto the surface did not converge")?;
        Ok([u, v])
    }

    /// The parameter box for a coarse search: bounded directions, one period of periodic ones.
    fn search_box(&self) -> Option<[[f64; 2]; 2]> {
        let (ru, rv) = self.surface.inner().try_range_tuple();
        let r = [ru, rv];
        let mut b = [[0.0; 2]; 2];
        for d in 0..2 {
            b[d] = match (self.periods[d], r[d]) {
                (Some(t), _) => [0.0, t],
                (None, Some((lo, hi))) if lo.is_finite() && hi.is_finite() => [lo, hi],
                _ => return None,
            };
        }
        Some(b)
    }

    /// (u, v) of boundary point `x` of edge `number` (1-based, for messages) by Newton from
    /// `near`, continued across seams. From a pole Newton cannot turn towards `x` (a
    /// parameter there moves no point): if it misses from one, it starts afresh.
    fn project(&mut self, x: Vec3, near: [f64; 2], number: usize) -> Result<[f64; 2], String> {
        let newton = |from: [f64; 2]| {
            project_within(self.surface, x, (from[0], from[1]), self.bounds)
                .map(|(u, v)| unwrap([u, v], near, self.periods))
        };
        let off = |q: [f64; 2]| (self.surface.point(q[0], q[1]) - x).norm();
        let pole = singular(self.surface, near).is_some();
        // at a pole already (Newton there may move along the pole, a parameter it cannot see)
        let mut found = if pole && off(near) <= 1e-9 * self.tol {
            Some(near)
        } else {
            newton(near)
        };
        // from a pole, or wherever Newton from the neighbour fails (a sphere's point next to
        // its pole, where the step from the neighbour turns about the pole): a fresh start
        if !found.is_some_and(|q| off(q) <= self.tol) {
            found = self
                .initial_uv(x)
                .ok()
                .and_then(|q| newton(unwrap(q, near, self.periods)));
        }
        let uv = found.ok_or_else(|| {
            format!("boundary edge {number}: the projection onto the surface did not converge")
        })?;
        let gap = off(uv);
        if gap.is_nan() || gap > self.heal {
            return Err(format!(
                "boundary edge {number} lies {gap:.3e} from the face's surface (tolerance {:.3e}, \
                 healed up to {:.3e})",
                self.tol, self.heal
            ));
        }
        if gap > self.tol {
            self.healed = self.healed.max(gap);
        }
        self.gap = self.gap.max(gap);
        Ok(uv)
    }

    /// Distance beyond which a boundary point is not on the surface.
    pub fn tol(&self) -> f64 {
        self.tol
    }

    /// Number of edges.
    pub fn len(&self) -> usize {
        self.edges.len()
    }

    /// Length of edge `k`.
    pub fn length(&self, k: usize) -> f64 {
        self.edges[k].map.length()
    }

    /// Mean |x_u| and |x_v| over the samples: scales that make (u, v) lengths ≈ 3D lengths.
    pub fn metric_scale(&self) -> [f64; 2] {
        self.scale
    }

    fn mean_speeds(&self) -> [f64; 2] {
        let uv: Vec<&[[f64; 2]]> = self.edges.iter().map(|e| &e.uv[..]).collect();
        self.mean_scale(&uv)
    }

    /// Mean |x_u| and |x_v| over the (u, v) samples `uv` (1 where not positive).
    fn mean_scale<V: AsRef<[[f64; 2]]>>(&self, uv: &[V]) -> [f64; 2] {
        let mut sum = [0.0; 2];
        let mut count = 0.0f64;
        for e in uv {
            for q in e.as_ref() {
                let s = self.surface.eval(q[0], q[1]);
                sum[0] += s.xu.norm();
                sum[1] += s.xv.norm();
                count += 1.0;
            }
        }
        sum.map(|v| {
            let m = v / count.max(1.0);
            if m.is_finite() && m > 0.0 {
                m
            } else {
                1.0
            }
        })
    }

    /// Signed area of the loop's polygon in (u, v) scaled by `scale`: positive if the loop
    /// runs counterclockwise.
    pub fn signed_area(&self, scale: [f64; 2]) -> f64 {
        let pts: Vec<[f64; 2]> = self
            .edges
            .iter()
            .flat_map(|e| e.uv[..NS].iter())
            .map(|q| [q[0] * scale[0], q[1] * scale[1]])
            .collect();
        let n = pts.len();
        0.5 * (0..n)
            .map(|i| {
                let (a, b) = (pts[i], pts[(i + 1) % n]);
                a[0] * b[1] - a[1] * b[0]
            })
            .sum::<f64>()
    }

    /// Turning angle (radians, 0 = straight on) of the loop at the start of edge `k`.
    pub fn turning(&self, k: usize) -> f64 {
        let n = self.len();
        let a = &self.edges[(k + n - 1) % n].curve;
        let b = &self.edges[k].curve;
        let (ta, tb) = (a.derivative(1.0), b.derivative(0.0));
        let c = ta.dot(&tb) / (ta.norm() * tb.norm());
        if c.is_finite() {
            c.clamp(-1.0, 1.0).acos()
        } else {
            0.0
        }
    }

    /// Whether the loop turns outwards (a reentrant, concave vertex) at the start of edge
    /// `k`: the turn in (u, v) against the loop's sense of rotation, from the chords of the
    /// (u, v) samples next to the vertex (`ccw`: the loop runs counterclockwise in (u, v)).
    pub fn reentrant(&self, k: usize, ccw: bool) -> bool {
        let n = self.len();
        let (a, b) = (&self.edges[(k + n - 1) % n].uv, &self.edges[k].uv);
        let s = self.scale;
        let da = [0, 1].map(|c| (a[NS][c] - a[NS - 1][c]) * s[c]);
        let db = [0, 1].map(|c| (b[1][c] - b[0][c]) * s[c]);
        let cross = da[0] * db[1] - da[1] * db[0];
        if ccw {
            cross < 0.0
        } else {
            cross > 0.0
        }
    }

    /// Whether the loop bends outwards (is concave) at a point inside an edge: the turn of
    /// its (u, v) at the point itself and at arclength ±1/(8 NS) of the edge (projected from
    /// the samples' (u, v)), else from the (u, v) samples next to it.
    pub(in crate::cad) fn bends_out(&self, p: LoopPoint, ccw: bool) -> bool {
        let e = &self.edges[p.edge];
        let s = self.scale;
        let h = 1.0 / (8 * NS) as f64;
        let near = |sigma: f64| {
            let x = e.point(sigma);
            let pos = sigma * NS as f64;
            let i = (pos.floor() as usize).min(NS - 1);
            let w = pos - i as f64;
            let hint = [0, 1].map(|c| (1.0 - w) * e.uv[i][c] + w * e.uv[i + 1][c]);
            project_within(self.surface, x, (hint[0], hint[1]), self.bounds)
                .map(|(u, v)| unwrap([u, v], hint, self.periods))
        };
        let local = if p.sigma > h && p.sigma < 1.0 - h {
            match (near(p.sigma - h), near(p.sigma), near(p.sigma + h)) {
                (Some(a), Some(b), Some(c)) => Some((a, b, c)),
                _ => None,
            }
        } else {
            None
        };
        let uv = &e.uv;
        let i = ((p.sigma * NS as f64).round() as usize).clamp(1, NS - 1);
        let (a, b, c) = local.unwrap_or((uv[i - 1], uv[i], uv[i + 1]));
        let da = [0, 1].map(|k| (b[k] - a[k]) * s[k]);
        let db = [0, 1].map(|k| (c[k] - b[k]) * s[k]);
        let cross = da[0] * db[1] - da[1] * db[0];
        let tiny = 1e-9 * (da[0].hypot(da[1]) * db[0].hypot(db[1]));
        if ccw {
            cross < -tiny
        } else {
            cross > tiny
        }
    }
}
