//! Floating interior faces of a volume topology: the face between two volumes is moved with
//! them until the grid crosses it as it would the inside of one block.
//!
//! The volumes on either side of the face, seen from the face, form one structured block: the
//! **strip** of node (p, q, l), p and q the face's own indices, l running from the far side of
//! volume A (l = 0) through the face (l = `la`) to the far side of volume B. Its nodes are the
//! volumes' nodes (the orientation from the topology, as the connectivity file maps them); its
//! control functions are the volumes' own (the 18 P^c_ij carried over to the strip's axes, a
//! tensor under the permutation and reflection of the axes), at the face the mean of the two
//! sides' one layer in. The strip is solved by the volume grid system [86] with its boundary
//! (the volumes' other faces) held: the face nodes then satisfy the grid equations of the
//! merged block, with the union stencil of side A's layer, the face and side B's layer. A
//! planar face (its edges in one plane to 1e-12 of its diameter) keeps its nodes in the plane:
//! the solved face nodes are projected onto it (a sliding face).
//!
//! Between two volumes with their walls on one side of the strip, the strip can be solved
//! with the volume wall correction instead ([`crate::elliptic::orthogonal3d`]): its wall the
//! union of the two ([`Strip::wall_face`]), its goal columns the volumes' own
//! ([`Strip::wall_targets`]), its algebraic map glued from theirs ([`Strip::glued_param`]);
//! its control functions, carried back ([`Strip::volume_controls`]), make the volumes' grid
//! systems the strip's.
//!
//! The job layer alternates these face solves with the volume solves (warm-started) until the
//! largest move of a face node falls below the solve tolerance: an alternating Schwarz
//! iteration whose overlap is the whole of both volumes, so that two volumes meeting at one
//! floating face and nowhere else converge in one or two rounds.

use crate::algebraic::bilinear3d::ParamGrid3;
use crate::algebraic::control3d::{Control3, PAIRS};
use crate::elliptic::picard::{PicardInfo, PicardParams};
use crate::elliptic::poisson3d;
use crate::elliptic::wall::WallTargets;
use crate::grid::faces::{block_node, face_dims, normal};
use crate::grid::topology::volume::{FaceInterface, Topology3, VolumeSide};
use crate::grid::Grid2;
use crate::solve::stencil19::Stencil19;
use crate::solve::LinearSolver;
use crate::{Error, Grid3, Result};

/// Relative distance of a face's edge nodes from their plane below which the face is planar.
pub const PLANAR: f64 = 1e-12;

/// One side of a strip: the volume side, how deep the strip reaches into it, and for each strip
/// axis (p, q, l) the volume axis and its sign.
#[derive(Clone, Copy, Debug)]
struct Side {
    side: VolumeSide,
    layers: usize,
    axes: [(usize, f64); 3],
}

/// The strip across one interior face (module docs).
#[derive(Clone, Debug)]
pub struct Strip {
    face: usize,
    dims: [usize; 3],
    sides: [Side; 2],
}

impl Strip {
    /// The strip across interior face `f`. Two different volumes are taken whole; a face
    /// between two sides of one volume (which must be opposite) takes just under half of it
    /// from each side, so that no node appears twice.
    pub fn new(topo: &Topology3, f: &FaceInterface, place: &str) -> Result<Self> {
        let [np, nq] = topo.face_dims(f.face);
        let depth = |s: VolumeSide| {
            let (d, _) = normal(s.side);
            topo.volumes[s.volume].dims[d] - 1
        };
        let (la, lb) = if f.a.volume != f.b.volume {
            (depth(f.a), depth(f.b))
        } else if f.a.side / 2 == f.b.side / 2 {
            let n = depth(f.a);
            (n / 2, n.saturating_sub(1) - n / 2)
        } else {
            (0, 0)
        };
        if la == 0 || lb == 0 || np < 3 || nq < 3 {
            return Err(Error::input(
                place,
                "a floating face needs at least 3 × 3 nodes and, between two sides of one \
                 volume, opposite sides with at least 4 nodes between them",
            ));
        }
        let side = |s: VolumeSide, layers: usize, toward: bool| {
            let at = |p, q| topo.volume_node(s.volume, s.side, p, q);
            let axis = |m: [usize; 3], n: [usize; 3]| {
                let d = (0..3).find(|&d| m[d] != n[d]).unwrap_or(0);
                (d, if n[d] > m[d] { 1.0 } else { -1.0 })
            };
            let (d, lo) = normal(s.side);
            // l grows toward the face on side A, away from it on side B.
            let inward = if lo { 1.0 } else { -1.0 };
            let sign = if toward { -inward } else { inward };
            Side {
                side: s,
                layers,
                axes: [
                    axis(at(0, 0), at(1, 0)),
                    axis(at(0, 0), at(0, 1)),
                    (d, sign),
                ],
            }
        };
        Ok(Strip {
            face: f.face,
            dims: [np, nq, la + lb + 1],
            sides: [side(f.a, la, true), side(f.b, lb, false)],
        })
    }

    /// Node counts (np, nq, layers).
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The layer of the face.
    pub fn face_layer(&self) -> usize {
        self.sides[0].layers
    }

    /// The side (0 = A, 1 = B) and its volume node of strip node (p, q, l); the face layer
    /// belongs to side A.
    fn node(&self, topo: &Topology3, p: usize, q: usize, l: usize) -> (usize, [usize; 3]) {
        let la = self.sides[0].layers;
        let (k, depth) = if l <= la { (0, la - l) } else { (1, l - la) };
        let s = self.sides[k].side;
        let mut n = topo.volume_node(s.volume, s.side, p, q);
        let (d, lo) = normal(s.side);
        if lo {
            n[d] += depth;
        } else {
            n[d] -= depth;
        }
        (k, n)
    }

    /// The strip's grid from the volume grids.
    pub fn gather(&self, topo: &Topology3, volumes: &[&Grid3]) -> Grid3 {
        let [np, nq, nl] = self.dims;
        Grid3::from_fn(np, nq, nl, |p, q, l| {
            let (k, [i, j, kk]) = self.node(topo, p, q, l);
            volumes[self.sides[k].side.volume].point(i, j, kk)
        })
    }

    /// The strip's control functions from the volumes' (module docs): zero on its boundary,
    /// at the face the mean of the two sides' one layer in.
    pub fn controls(&self, topo: &Topology3, ctrl: &[&Control3]) -> Control3 {
        let [np, nq, nl] = self.dims;
        let la = self.face_layer();
        let at = |p: usize, q: usize, l: usize| {
            let (k, [i, j, kk]) = self.node(topo, p, q, l);
            let s = &self.sides[k];
            let [ni, nj, _] = topo.volumes[s.side.volume].dims;
            carry(ctrl[s.side.volume].at(i + ni * (j + nj * kk)), s.axes)
        };
        let mut out = vec![[0.0; 18]; np * nq * nl];
        for l in 1..nl - 1 {
            for q in 1..nq - 1 {
                for p in 1..np - 1 {
                    out[p + np * (q + nq * l)] = if l == la {
                        let (a, b) = (at(p, q, l - 1), at(p, q, l + 1));
                        std::array::from_fn(|m| 0.5 * (a[m] + b[m]))
                    } else {
                        at(p, q, l)
                    };
                }
            }
        }
        Control3::stored(self.dims, out)
    }

    /// Solves the strip from the volume grids (warm start) with control functions `ctrl`:
    /// the grid system [86] with the strip's boundary held. Returns the solved strip and the
    /// Picard history.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &self,
        topo: &Topology3,
        volumes: &[&Grid3],
        ctrl: &Control3,
        solver: &mut dyn LinearSolver<Stencil19>,
        params: &PicardParams,
        place: &str,
    ) -> Result<(Grid3, PicardInfo)> {
        let mut x = self.gather(topo, volumes);
        let info = poisson3d::solve(&mut x, ctrl, solver, params, place, &mut |_, _| {})?;
        Ok((x, info))
    }

    /// Takes the solved strip over: the face's interior nodes into `face` (projected onto
    /// `plane` if given), the strip's other interior nodes into the volumes (the next volume
    /// solves' start). Returns the largest move of a face node.
    pub fn scatter(
        &self,
        topo: &Topology3,
        strip: &Grid3,
        face: &mut Grid2<3>,
        plane: Option<&Plane>,
        volumes: &mut [Grid3],
    ) -> f64 {
        let [np, nq, nl] = self.dims;
        let la = self.face_layer();
        let mut moved = 0.0f64;
        for l in 1..nl - 1 {
            for q in 1..nq - 1 {
                for p in 1..np - 1 {
                    let mut x = strip.point(p, q, l);
                    if l == la {
                        if let Some(pl) = plane {
                            x = pl.project(x);
                        }
                        let old = face.point(p, q);
                        let d = (0..3).map(|c| (x[c] - old[c]).powi(2)).sum::<f64>();
                        moved = moved.max(d.sqrt());
                        face.set(p, q, x);
                        continue;
                    }
                    let (k, [i, j, kk]) = self.node(topo, p, q, l);
                    volumes[self.sides[k].side.volume].set(i, j, kk, x);
                }
            }
        }
        moved
    }

    /// The strip's face (0 … 5, F1 … F6 of the strip) that is wall face `walls[k]` of the
    /// volume of side k on both sides (the union of two walls, e.g. the two wing volumes'
    /// across the plane ahead of the leading edge), if the two volumes differ and both have
    /// their wall on the same face of the strip.
    pub fn wall_face(&self, walls: [Option<usize>; 2]) -> Option<usize> {
        if self.sides[0].side.volume == self.sides[1].side.volume {
            return None;
        }
        let mut out = None;
        for (s, w) in self.sides.iter().zip(walls) {
            let (d, lo) = normal(w?);
            let a = (0..2).find(|&a| s.axes[a].0 == d)?;
            // Strip index = volume index along d if the sign is positive (from the low end).
            let f = 2 * a + usize::from(lo != (s.axes[a].1 > 0.0));
            if out.is_some_and(|o| o != f) {
                return None;
            }
            out = Some(f);
        }
        out
    }

    /// The goal columns of the strip's wall face `w` ([`Strip::wall_face`]) from its
    /// volumes' wall targets `targets` (side A's, side B's): each column the goal of the
    /// volume column it is.
    pub fn wall_targets(
        &self,
        topo: &Topology3,
        w: usize,
        targets: [&WallTargets; 2],
    ) -> WallTargets {
        let m = self.dims[normal(w).0];
        let [na, nb] = face_dims(w, self.dims);
        let mut cols = Vec::with_capacity(na * nb * m);
        for b in 0..nb {
            for a in 0..na {
                let [p, q, l] = block_node(w, a, b, self.dims);
                let (k, n) = self.node(topo, p, q, l);
                cols.extend((0..m).map(|j| targets[k].at(n, j)));
            }
        }
        WallTargets::from_columns(w, self.dims, cols)
    }

    /// The strip's algebraic parameters glued from its volumes' `params` (side A's, side
    /// B's): along p and q the volumes' parameters of those axes (reflected where the axis
    /// runs against the volume's), along l side A's on [0, 1/2] and side B's on [1/2, 1]
    /// (the face at 1/2); on the face p and q are the mean of the two sides' one layer in.
    pub fn glued_param(&self, topo: &Topology3, params: [&ParamGrid3; 2]) -> ParamGrid3 {
        let [np, nq, nl] = self.dims;
        let mut out: [Vec<f64>; 3] = std::array::from_fn(|_| Vec::with_capacity(np * nq * nl));
        for l in 0..nl {
            for q in 0..nq {
                for p in 0..np {
                    let (k, [i, j, kk]) = self.node(topo, p, q, l);
                    let s = &self.sides[k];
                    let [ni, nj, _] = topo.volumes[s.side.volume].dims;
                    let v = params[k].at(i + ni * (j + nj * kk));
                    for (a, o) in out.iter_mut().enumerate() {
                        let (d, sign) = s.axes[a];
                        let x = if sign > 0.0 { v[d] } else { 1.0 - v[d] };
                        o.push(if a < 2 { x } else { 0.5 * (k as f64 + x) });
                    }
                }
            }
        }
        // At the face, p and q as the mean of the two sides' one layer in: each volume's
        // corrections shifted its parameters next to the face but not on it.
        let la = self.face_layer();
        for o in out.iter_mut().take(2) {
            for q in 1..nq - 1 {
                for p in 1..np - 1 {
                    let n = p + np * (q + nq * la);
                    o[n] = 0.5 * (o[n - np * nq] + o[n + np * nq]);
                }
            }
        }
        let [s, t, u] = out;
        ParamGrid3::from_parts(self.dims, s, t, u)
    }

    /// The strip's control functions `ctrl` carried back to the volumes of sides A and B
    /// (stored; each volume's interior nodes are interior nodes of the strip off the face
    /// layer, and with these controls the volume's grid system is the strip's there). For two
    /// different volumes ([`Strip::wall_face`]).
    pub fn volume_controls(&self, topo: &Topology3, ctrl: &Control3) -> [Control3; 2] {
        let [np, nq, nl] = self.dims;
        let la = self.face_layer();
        let vdims = self.sides.map(|s| topo.volumes[s.side.volume].dims);
        let mut out = vdims.map(|d| vec![[0.0; 18]; d.iter().product()]);
        let back = self.sides.map(|s| inverse(s.axes));
        for l in (1..nl - 1).filter(|&l| l != la) {
            for q in 1..nq - 1 {
                for p in 1..np - 1 {
                    let (k, [i, j, kk]) = self.node(topo, p, q, l);
                    let [ni, nj, _] = vdims[k];
                    out[k][i + ni * (j + nj * kk)] = carry(ctrl.at(p + np * (q + nq * l)), back[k]);
                }
            }
        }
        let [a, b] = out;
        [Control3::stored(vdims[0], a), Control3::stored(vdims[1], b)]
    }

    /// The face this strip crosses.
    pub fn face(&self) -> usize {
        self.face
    }

    /// The volumes of sides A and B.
    pub fn volumes(&self) -> [usize; 2] {
        self.sides.map(|s| s.side.volume)
    }
}

/// The control functions `p` of a volume node carried over to the strip's axes: strip axis a
/// is volume axis π(a) with sign s_a, so P'^c_ab = s_a s_b s_c P^π(c)_π(a)π(b).
fn carry(p: [f64; 18], axes: [(usize, f64); 3]) -> [f64; 18] {
    let pair = |a: usize, b: usize| {
        let (lo, hi) = (a.min(b), a.max(b));
        PAIRS
            .iter()
            .position(|&[x, y]| x == lo && y == hi)
            .unwrap_or(0)
    };
    let mut out = [0.0; 18];
    for (m, &[a, b]) in PAIRS.iter().enumerate() {
        let ((va, sa), (vb, sb)) = (axes[a], axes[b]);
        let mv = pair(va, vb);
        for (c, &(vc, sc)) in axes.iter().enumerate() {
            out[3 * m + c] = sa * sb * sc * p[3 * mv + vc];
        }
    }
    out
}

/// The inverse of a signed axis permutation (strip axis a is volume axis π(a) with sign s_a):
/// volume axis v is strip axis π⁻¹(v) with the same sign, so that [`carry`] with it undoes
/// [`carry`] with `axes`.
fn inverse(axes: [(usize, f64); 3]) -> [(usize, f64); 3] {
    let mut out = [(0, 1.0); 3];
    for (a, &(v, s)) in axes.iter().enumerate() {
        out[v] = (a, s);
    }
    out
}

/// The plane of a planar face: a point on it and the unit normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub point: [f64; 3],
    pub normal: [f64; 3],
}

impl Plane {
    /// The plane of the face's edge nodes if they all lie within [`PLANAR`] of its
    /// diameter from it (Newell's normal of the boundary polygon through its centroid).
    pub fn of_face(face: &Grid2<3>) -> Option<Plane> {
        let (ni, nj) = (face.ni(), face.nj());
        let ring: Vec<[f64; 3]> = (0..ni - 1)
            .map(|i| face.point(i, 0))
            .chain((0..nj - 1).map(|j| face.point(ni - 1, j)))
            .chain((1..ni).rev().map(|i| face.point(i, nj - 1)))
            .chain((1..nj).rev().map(|j| face.point(0, j)))
            .collect();
        let m = ring.len() as f64;
        let c: [f64; 3] = std::array::from_fn(|k| ring.iter().map(|x| x[k]).sum::<f64>() / m);
        let mut n = [0.0; 3];
        for (a, b) in ring.iter().zip(ring.iter().cycle().skip(1)) {
            let (a, b) = (
                [a[0] - c[0], a[1] - c[1], a[2] - c[2]],
                [b[0] - c[0], b[1] - c[1], b[2] - c[2]],
            );
            n[0] += a[1] * b[2] - a[2] * b[1];
            n[1] += a[2] * b[0] - a[0] * b[2];
            n[2] += a[0] * b[1] - a[1] * b[0];
        }
        let len = n.iter().map(|v| v * v).sum::<f64>().sqrt();
        let diam = face.diameter();
        if len == 0.0 || !len.is_finite() || diam == 0.0 {
            return None;
        }
        let plane = Plane {
            point: c,
            normal: n.map(|v| v / len),
        };
        ring.iter()
            .all(|&x| plane.distance(x).abs() <= PLANAR * diam)
            .then_some(plane)
    }

    /// Signed distance of `x` from the plane.
    pub fn distance(&self, x: [f64; 3]) -> f64 {
        (0..3)
            .map(|k| (x[k] - self.point[k]) * self.normal[k])
            .sum()
    }

    /// The foot of `x` on the plane.
    pub fn project(&self, x: [f64; 3]) -> [f64; 3] {
        let d = self.distance(x);
        std::array::from_fn(|k| x[k] - d * self.normal[k])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn carried_controls_follow_a_reflection_and_a_swap() {
        // Strip axes (p, q, l) = (−k, i, j): P'^c_ab = s_a s_b s_c P^π(c)_π(a)π(b).
        let mut p = [0.0; 18];
        for (m, v) in p.iter_mut().enumerate() {
            *v = m as f64 + 1.0;
        }
        let axes = [(2, -1.0), (0, 1.0), (1, 1.0)];
        let q = carry(p, axes);
        // P'^p_pp = (−1)³ P^k_kk = −P[3·5 + 2]
        assert_eq!(q[0], -p[17]);
        // P'^l_pq = (−1)(1)(1) P^j_ki = −P[3·2 + 1] (pair ik = 13)
        assert_eq!(q[3 + 2], -p[7]);
        // P'^q_ll = P^i_jj = P[3·3 + 0]
        assert_eq!(q[15 + 1], p[9]);
    }

    #[test]
    fn carrying_back_undoes_carrying() {
        let p: [f64; 18] = std::array::from_fn(|m| (m * m) as f64 - 3.5);
        for axes in [
            [(2, -1.0), (0, 1.0), (1, 1.0)],
            [(1, 1.0), (2, -1.0), (0, -1.0)],
            [(0, -1.0), (1, 1.0), (2, 1.0)],
        ] {
            assert_eq!(carry(carry(p, axes), inverse(axes)), p);
        }
    }

    #[test]
    fn a_planar_face_is_found_and_a_bent_one_is_not() {
        let flat = Grid2::<3>::from_fn(5, 4, |i, j| [i as f64, 0.3 * j as f64, 2.0]);
        let pl = Plane::of_face(&flat).expect("planar");
        assert!((pl.normal[2].abs() - 1.0).abs() < 1e-15);
        assert_eq!(pl.project([0.5, 0.5, 7.0])[2], 2.0);
        let bent = Grid2::<3>::from_fn(5, 4, |i, j| [i as f64, j as f64, 1e-6 * (i * j) as f64]);
        assert!(Plane::of_face(&bent).is_none());
    }
}
