//! The faces of a volume block from its twelve edges: each face the Coons patch (transfinite
//! interpolation) of its four edges, blended with the straight-line parameters [39, 40] of the
//! face's own edge distributions so that clustered edges give clustered faces.

use crate::algebraic::transform::{straight_line, ParamGrid};
use crate::grid::arclength::{normalized_arclength, EdgeFunctions};
use crate::grid::faces::{face_dims, face_edges};
use crate::Grid2;

/// The Coons patch of face f from the twelve edge point lists (module docs).
pub fn coons_face(f: usize, edges: &[Vec<[f64; 3]>; 12], dims: [usize; 3]) -> Grid2<3> {
    coons_eval(f, edges, dims, &coons_params(f, edges, dims))
}

/// The four edges of face f as the sides E1..E4 of a 2D block in the face's (a, b) indices.
fn face_sides(f: usize, edges: &[Vec<[f64; 3]>; 12]) -> [&[[f64; 3]]; 4] {
    let [ba, ta, lb, rb] = face_edges(f);
    [&edges[lb], &edges[rb], &edges[ba], &edges[ta]]
}

/// The straight-line parameters [39, 40] of face f from its four edges' arclength.
pub fn coons_params(f: usize, edges: &[Vec<[f64; 3]>; 12], dims: [usize; 3]) -> ParamGrid {
    debug_assert_eq!(edges[face_edges(f)[0]].len(), face_dims(f, dims)[0]);
    sides_params(face_sides(f, edges))
}

/// The Coons patch of face f with the blending weights `pg` (the edges are sampled at the
/// face's own node indices; the parameters only weight them).
pub fn coons_eval(
    f: usize,
    edges: &[Vec<[f64; 3]>; 12],
    dims: [usize; 3],
    pg: &ParamGrid,
) -> Grid2<3> {
    debug_assert_eq!(edges[face_edges(f)[0]].len(), face_dims(f, dims)[0]);
    sides_eval(face_sides(f, edges), pg)
}

/// The Coons patch of a four-sided face given by its sides E1..E4 (a 2D block's: E1 at i = 0
/// and E2 at i = N along j, E3 at j = 0 and E4 at j = M along i; corners shared), blended with
/// the straight-line parameters of the sides' arclength.
pub fn coons_sides(sides: [&[[f64; 3]]; 4]) -> Grid2<3> {
    sides_eval(sides, &sides_params(sides))
}

/// The straight-line parameters [39, 40] of four sides E1..E4 from their arclength.
pub fn sides_params(sides: [&[[f64; 3]]; 4]) -> ParamGrid {
    let [e1, e2, e3, e4] = sides;
    straight_line(&EdgeFunctions {
        s_e3: normalized_arclength(e3),
        s_e4: normalized_arclength(e4),
        t_e1: normalized_arclength(e1),
        t_e2: normalized_arclength(e2),
    })
}

/// The Coons patch of four sides E1..E4 with the blending weights `pg`.
pub fn sides_eval(sides: [&[[f64; 3]]; 4], pg: &ParamGrid) -> Grid2<3> {
    let [lb, rb, ba, ta] = sides;
    let (na, nb) = (ba.len(), lb.len());
    let (c00, c10, c01, c11) = (ba[0], ba[na - 1], ta[0], ta[na - 1]);
    Grid2::<3>::from_fn(na, nb, |a, b| {
        let (s, t) = pg.at(a, b);
        std::array::from_fn(|c| {
            (1.0 - s) * lb[b][c] + s * rb[b][c] + (1.0 - t) * ba[a][c] + t * ta[a][c]
                - ((1.0 - s) * (1.0 - t) * c00[c]
                    + s * (1.0 - t) * c10[c]
                    + (1.0 - s) * t * c01[c]
                    + s * t * c11[c])
        })
    })
}

/// True if every point of a face lies within 1e-9 of its size of the plane through its
/// corners' mean with the normal of its diagonals.
pub fn is_planar(g: &Grid2<3>) -> bool {
    let (ni, nj) = (g.ni(), g.nj());
    let (p00, p10, p01, p11) = (
        g.point(0, 0),
        g.point(ni - 1, 0),
        g.point(0, nj - 1),
        g.point(ni - 1, nj - 1),
    );
    let d1: [f64; 3] = std::array::from_fn(|c| p11[c] - p00[c]);
    let d2: [f64; 3] = std::array::from_fn(|c| p01[c] - p10[c]);
    let n = [
        d1[1] * d2[2] - d1[2] * d2[1],
        d1[2] * d2[0] - d1[0] * d2[2],
        d1[0] * d2[1] - d1[1] * d2[0],
    ];
    let nn = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if nn == 0.0 {
        return false;
    }
    let o: [f64; 3] = std::array::from_fn(|c| 0.25 * (p00[c] + p10[c] + p01[c] + p11[c]));
    let tol = 1e-9 * g.diameter();
    (0..nj).all(|j| {
        (0..ni).all(|i| {
            let p = g.point(i, j);
            ((0..3).map(|c| (p[c] - o[c]) * n[c]).sum::<f64>() / nn).abs() <= tol
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::faces::{edge_nodes, Faces};

    #[test]
    fn coons_faces_of_box_edges_meet() {
        let dims = [4, 3, 5];
        let edges: [Vec<[f64; 3]>; 12] = std::array::from_fn(|e| {
            edge_nodes(e, dims)
                .into_iter()
                .map(|n| [n[0] as f64, (n[1] as f64).powi(2), n[2] as f64 * 0.5])
                .collect()
        });
        let faces: [Grid2<3>; 6] = std::array::from_fn(|f| coons_face(f, &edges, dims));
        let f = Faces::new(faces, "b").unwrap();
        assert_eq!(f.dims(), dims);
        assert_eq!(f.face(3).point(2, 4), [2.0, 4.0, 2.0]);
    }
}
