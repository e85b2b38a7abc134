//! Symmetry planes of a volume block (#18 item 3, beyond the paper, which fixes every face):
//! a block face that lies on a plane and whose nodes slide in it, the grid lines meeting it at
//! right angles.
//!
//! The half of a domain that is symmetric about a plane is gridded as the whole would be:
//! at a node of the face the grid system [86] is discretized with the mirror images of the
//! inner layer as its outer neighbours (a ghost layer), so the node takes the place that the
//! whole domain's grid gives the node on its plane of symmetry. The face's nodes are unknowns
//! of the Picard operator ([`crate::elliptic::poisson3d`]) for their in-plane coordinates;
//! the coordinate normal to the plane stays on it. The plane must be a coordinate plane (x,
//! y or z = constant). A mirrored volume (`mirror`, `src/job/mirror.rs`) then continues the
//! grid on the other side as the whole domain's grid. Nodes on two symmetry faces (an edge
//! where two of them meet) and on the face's rim stay where the faces put them.
//!
//! The control functions at the face's nodes are those of the whole domain's algebraic map,
//! the block's continued by symmetry ([`Symmetry::with_controls`],
//! [`crate::algebraic::control3d::at_symmetry_face`]), without the components that would tilt
//! the lines crossing the plane; without the map (a solve with given control functions), the
//! inner neighbours'.
//!
//! Each coordinate is solved with its own unknowns: on a plane x = c the coordinate x is held
//! and y, z slide, so the coordinates fall into groups by the faces they slide along
//! ([`Symmetry::groups`]), each with its own operator and linear solver.

use crate::algebraic::bilinear3d::ParamGrid3;
use crate::algebraic::control3d::{at_symmetry_face, Control3};
use crate::elliptic::metric3d::{alphas, row_coefficients};
use crate::solve::stencil19::{slot, OFFSETS};
use crate::{Error, Grid3, Result};

/// A face of a block (axis `axis` at index 0, or the last index if `high`) on the plane
/// through `point` with unit normal `normal`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SymmetryFace {
    pub axis: usize,
    pub high: bool,
    pub point: [f64; 3],
    pub normal: [f64; 3],
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl SymmetryFace {
    /// The face `F1` … `F6` (axis = (F − 1) / 2, high for even F) of grid `x`, whose nodes must
    /// lie on one plane (within 1e-9 of the block's diameter): the plane through the face's
    /// first corner normal to its area vector (a corner, not the centroid, so that an axis
    /// plane holds its nodes exactly). Errors name `place` and the face.
    pub fn of_grid(x: &Grid3, face: usize, place: &str) -> Result<Self> {
        let (axis, high) = ((face - 1) / 2, face % 2 == 0);
        let dims = x.dims();
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        let at = |p: usize, q: usize| {
            let mut ijk = [0; 3];
            ijk[axis] = if high { dims[axis] - 1 } else { 0 };
            ijk[a] = p;
            ijk[b] = q;
            x.point(ijk[0], ijk[1], ijk[2])
        };
        let (na, nb) = (dims[a], dims[b]);
        let c = at(0, 0);
        let mut area = [0.0; 3];
        for q in 0..nb {
            for p in 0..na {
                let v = at(p, q);
                if p + 1 < na && q + 1 < nb {
                    let (d1, d2) = (at(p + 1, q + 1), at(p, q + 1));
                    let (u, w) = (
                        std::array::from_fn::<f64, 3, _>(|d| d1[d] - v[d]),
                        std::array::from_fn::<f64, 3, _>(|d| d2[d] - at(p + 1, q)[d]),
                    );
                    area[0] += u[1] * w[2] - u[2] * w[1];
                    area[1] += u[2] * w[0] - u[0] * w[2];
                    area[2] += u[0] * w[1] - u[1] * w[0];
                }
            }
        }
        let len = dot(area, area).sqrt();
        let name = format!("face F{face}");
        if !len.is_finite() || len <= 0.0 {
            return Err(Error::input(
                place,
                format!("symmetry {name}: the face has no area, so no plane"),
            ));
        }
        let normal = area.map(|v| v / len);
        // The plane must be a coordinate plane (each coordinate is then either held on the
        // face or slides along it: `groups`).
        let m = (0..3)
            .max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs()))
            .unwrap_or(0);
        if 1.0 - normal[m].abs() > 1e-9 {
            return Err(Error::input(
                place,
                format!(
                    "symmetry {name}: the face's plane (normal ({:.4}, {:.4}, {:.4})) is not a \
                     plane x, y or z = constant",
                    normal[0], normal[1], normal[2]
                ),
            ));
        }
        let normal: [f64; 3] =
            std::array::from_fn(|d| if d == m { normal[m].signum() } else { 0.0 });
        let tol = 1e-9 * x.diameter();
        let worst = (0..nb)
            .flat_map(|q| (0..na).map(move |p| (p, q)))
            .map(|(p, q)| {
                let v = at(p, q);
                dot(std::array::from_fn(|d| v[d] - c[d]), normal).abs()
            })
            .fold(0.0, f64::max);
        if worst > tol {
            return Err(Error::input(
                place,
                format!(
                    "symmetry {name}: the face is not planar (a node lies {worst:.3e} off the \
                     plane of the others, more than 1e-9 of the block's diameter)"
                ),
            ));
        }
        Ok(SymmetryFace {
            axis,
            high,
            point: c,
            normal,
        })
    }

    /// The mirror image of `p` in the plane.
    #[inline]
    pub fn mirror(&self, p: [f64; 3]) -> [f64; 3] {
        let h = 2.0 * dot(std::array::from_fn(|d| p[d] - self.point[d]), self.normal);
        std::array::from_fn(|d| p[d] - h * self.normal[d])
    }

    /// The index of the face's layer along its axis in a block of `dims` nodes.
    fn layer(&self, dims: [usize; 3]) -> usize {
        if self.high {
            dims[self.axis] - 1
        } else {
            0
        }
    }
}

/// The symmetry faces of a block of `dims` nodes, and the box of nodes they make unknowns:
/// the interior and the inside of every symmetry face.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Symmetry {
    faces: Vec<SymmetryFace>,
    /// Per face, the control functions at its nodes (the face's two other indices, i fastest)
    /// from the algebraic map ([`Symmetry::with_controls`]); empty: the inner neighbours'.
    controls: Vec<Vec<[f64; 18]>>,
}

impl Symmetry {
    /// No symmetry face: the unknowns are the interior nodes.
    pub fn none() -> Self {
        Symmetry::default()
    }

    /// The given faces (at most one per block face).
    pub fn new(faces: Vec<SymmetryFace>) -> Self {
        let controls = vec![Vec::new(); faces.len()];
        Symmetry { faces, controls }
    }

    /// The same faces with the control functions at their nodes from the algebraic map `pg`
    /// of the block ([`at_symmetry_face`]: those of the whole domain's map at its plane of
    /// symmetry) instead of the inner neighbours'.
    pub fn with_controls(&self, pg: &ParamGrid3) -> Self {
        let dims = pg.dims();
        let controls = self
            .faces
            .iter()
            .map(|f| {
                let (a, b) = ((f.axis + 1) % 3, (f.axis + 2) % 3);
                let mut out = vec![[0.0; 18]; dims[a] * dims[b]];
                for q in 1..dims[b] - 1 {
                    for p in 1..dims[a] - 1 {
                        let mut ijk = [0; 3];
                        ijk[f.axis] = f.layer(dims);
                        ijk[a] = p;
                        ijk[b] = q;
                        out[p + dims[a] * q] = at_symmetry_face(pg, f.axis, ijk);
                    }
                }
                out
            })
            .collect();
        Symmetry {
            faces: self.faces.clone(),
            controls,
        }
    }

    /// The control functions at node `ijk` of face m, if given ([`Self::with_controls`]).
    #[inline]
    pub(crate) fn control(&self, m: usize, dims: [usize; 3], ijk: [usize; 3]) -> Option<[f64; 18]> {
        let c = self.controls.get(m).filter(|c| !c.is_empty())?;
        let f = &self.faces[m];
        let (a, b) = ((f.axis + 1) % 3, (f.axis + 2) % 3);
        Some(c[ijk[a] + dims[a] * ijk[b]])
    }

    /// True if the block has no symmetry face.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }

    /// The faces.
    pub fn faces(&self) -> &[SymmetryFace] {
        &self.faces
    }

    /// The first node and the number of nodes of the unknowns' box along each axis.
    pub fn unknown_box(&self, dims: [usize; 3]) -> ([usize; 3], [usize; 3]) {
        let lo: [usize; 3] = std::array::from_fn(|a| {
            usize::from(!self.faces.iter().any(|f| f.axis == a && !f.high))
        });
        let hi: [usize; 3] = std::array::from_fn(|a| {
            dims[a] - 1 - usize::from(!self.faces.iter().any(|f| f.axis == a && f.high))
        });
        (lo, std::array::from_fn(|a| hi[a] + 1 - lo[a]))
    }

    /// The symmetry faces node `ijk` lies on: none, one (its index in [`Self::faces`]) or
    /// several (`Err`: the node is held).
    #[inline]
    pub(crate) fn on(
        &self,
        dims: [usize; 3],
        ijk: [usize; 3],
    ) -> std::result::Result<Option<usize>, ()> {
        let mut found = None;
        for (m, f) in self.faces.iter().enumerate() {
            if ijk[f.axis] == f.layer(dims) {
                if found.is_some() {
                    return Err(());
                }
                found = Some(m);
            }
        }
        Ok(found)
    }

    /// The coordinates grouped by the symmetry faces they slide along: a coordinate along a
    /// face's normal is held on that face (the face is a plane of constant coordinate), the
    /// others slide. Each group is solved with its own operator
    /// ([`crate::elliptic::poisson3d`]); without symmetry faces, one group of all three.
    pub fn groups(&self) -> Vec<(Symmetry, Vec<usize>)> {
        let mut out: Vec<(Symmetry, Vec<usize>)> = Vec::new();
        for c in 0..3 {
            let keep: Vec<usize> = (0..self.faces.len())
                .filter(|&m| self.faces[m].normal[c] == 0.0)
                .collect();
            let faces: Vec<SymmetryFace> = keep.iter().map(|&m| self.faces[m]).collect();
            match out.iter_mut().find(|(s, _)| s.faces == faces) {
                Some((_, cs)) => cs.push(c),
                None => {
                    let controls = keep.iter().map(|&m| self.controls[m].clone()).collect();
                    out.push((Symmetry { faces, controls }, vec![c]))
                }
            }
        }
        out
    }
}

/// The row (in the slot order of [`OFFSETS`], scaled as [`row_coefficients`]) and the
/// right-hand sides of the node `ijk` on symmetry face `f` of grid `x`, whose unknowns are the
/// nodes for which `unknown` is true: [86] with the mirror images of the inner neighbours as
/// the outer ones. A ghost's coefficient goes to its mirror partner when that is an unknown
/// (the correction of a ghost is that of its partner, in the plane), and the difference of
/// the ghost's value from its partner's to the right-hand side, so that b − A x is the
/// residual of [86] at the iterate; known neighbours go to the right-hand side.
#[allow(clippy::too_many_arguments)]
pub(crate) fn face_row(
    x: &Grid3,
    ctrl: &Control3,
    own: Option<[f64; 18]>,
    f: &SymmetryFace,
    ijk: [usize; 3],
    unknown: impl Fn([usize; 3]) -> bool,
    row: &mut [f64; 19],
    b: &mut [f64; 3],
) {
    let dims = x.dims();
    let [ni, nj, _] = dims;
    let index = |p: [usize; 3]| p[0] + ni * p[1] + ni * nj * p[2];
    let outside = |o: [i8; 3]| {
        let t = ijk[f.axis] as isize + o[f.axis] as isize;
        t < 0 || t >= dims[f.axis] as isize
    };
    let at = |o: [i8; 3]| -> [usize; 3] {
        std::array::from_fn(|d| (ijk[d] as isize + o[d] as isize) as usize)
    };
    let partner = |o: [i8; 3]| {
        let mut p = o;
        p[f.axis] = -p[f.axis];
        p
    };
    // Point at offset o, the mirror image of its partner beyond the face.
    let point = |o: [i8; 3]| {
        if outside(o) {
            let p = at(partner(o));
            f.mirror(x.point(p[0], p[1], p[2]))
        } else {
            let p = at(o);
            x.point(p[0], p[1], p[2])
        }
    };
    let mut d = [[0.0; 3]; 3];
    for ax in 0..3 {
        let (mut e, mut w) = ([0i8; 3], [0i8; 3]);
        e[ax] = 1;
        w[ax] = -1;
        let (pe, pw) = (point(e), point(w));
        for c in 0..3 {
            d[c][ax] = 0.5 * (pe[c] - pw[c]);
        }
    }
    let g: [[f64; 3]; 3] =
        std::array::from_fn(|p| std::array::from_fn(|r| (0..3).map(|c| d[c][p] * d[c][r]).sum()));
    let al = alphas(g);
    // The face's own control functions, else the inner neighbour's (module documentation).
    let mut inner = ijk;
    inner[f.axis] = if f.high {
        ijk[f.axis] - 1
    } else {
        ijk[f.axis] + 1
    };
    let pk = own.unwrap_or_else(|| ctrl.at(index(inner)));
    let w = [1.0, 2.0, 2.0, 1.0, 2.0, 1.0];
    let sk: [f64; 3] = std::array::from_fn(|c| (0..6).map(|m| w[m] * al[m] * pk[3 * m + c]).sum());
    row_coefficients(row, al, sk);
    *b = [0.0; 3];
    for m in 1..19 {
        let o = OFFSETS[m];
        let coef = row[m];
        if outside(o) {
            let po = partner(o);
            let p = at(po);
            let xp = x.point(p[0], p[1], p[2]);
            let ghost = f.mirror(xp);
            if unknown(p) {
                let s = slot(po).expect("a partner offset is a stencil offset");
                row[s] += coef;
                for c in 0..3 {
                    b[c] -= coef * (ghost[c] - xp[c]);
                }
            } else {
                for c in 0..3 {
                    b[c] -= coef * ghost[c];
                }
            }
            row[m] = 0.0;
        } else {
            let p = at(o);
            if !unknown(p) {
                let xp = x.point(p[0], p[1], p[2]);
                for c in 0..3 {
                    b[c] -= coef * xp[c];
                }
                row[m] = 0.0;
            }
        }
    }
}

#[cfg(test)]
mod tests;
