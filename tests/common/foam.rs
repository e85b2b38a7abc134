//! OpenFOAM checkMesh's skewness of the faces of a structured volume block, computed as
//! checkMesh computes it (primitiveMesh face and cell geometry, primitiveMeshTools
//! faceSkewness and boundaryFaceSkewness): checkMesh calls a face "highly skewed" above 4.

use ellipgrid::Grid3;

pub type V3 = nalgebra::Vector3<f64>;

/// OpenFOAM's centre and area vector of a face (primitiveMesh: triangles about the mean of
/// its vertices, the centre weighted by their areas).
pub fn foam_face(p: &[V3; 4]) -> (V3, V3) {
    let mean = p.iter().sum::<V3>() / 4.0;
    let (mut sum_n, mut sum_a, mut sum_ac) = (V3::zeros(), 0.0, V3::zeros());
    for m in 0..4 {
        let (a, b) = (p[m], p[(m + 1) % 4]);
        let n = (b - a).cross(&(mean - a));
        let area = n.norm();
        sum_a += area;
        sum_n += n;
        sum_ac += area * (a + b + mean);
    }
    (sum_ac / (3.0 * sum_a), 0.5 * sum_n)
}

/// The six faces of cell (i, j, k), outward for a right-handed block, in the order
/// i−, i+, j−, j+, k−, k+.
pub fn cell_faces(g: &Grid3, i: usize, j: usize, k: usize) -> [[V3; 4]; 6] {
    let n = |a: usize, b: usize, c: usize| V3::from(g.point(i + a, j + b, k + c));
    [
        [n(0, 0, 0), n(0, 0, 1), n(0, 1, 1), n(0, 1, 0)],
        [n(1, 0, 0), n(1, 1, 0), n(1, 1, 1), n(1, 0, 1)],
        [n(0, 0, 0), n(1, 0, 0), n(1, 0, 1), n(0, 0, 1)],
        [n(0, 1, 0), n(0, 1, 1), n(1, 1, 1), n(1, 1, 0)],
        [n(0, 0, 0), n(0, 1, 0), n(1, 1, 0), n(1, 0, 0)],
        [n(0, 0, 1), n(1, 0, 1), n(1, 1, 1), n(0, 1, 1)],
    ]
}

/// OpenFOAM's cell centre: the volume-weighted centroids of the pyramids from the mean of
/// the face centres to the faces.
pub fn foam_cell_centre(faces: &[[V3; 4]; 6]) -> V3 {
    let geo: Vec<(V3, V3)> = faces.iter().map(foam_face).collect();
    let est = geo.iter().map(|(c, _)| c).sum::<V3>() / 6.0;
    let (mut vol, mut sum) = (0.0, V3::zeros());
    for (c, a) in &geo {
        let v = a.dot(&(c - est));
        vol += v;
        sum += v * (0.75 * c + 0.25 * est);
    }
    sum / vol
}

/// The skewness vector `sv` over the face's extent in its direction, at least `floor`
/// (checkMesh's normalisation).
fn normalised(face: &[V3; 4], fc: V3, sv: V3, floor: f64) -> f64 {
    let sv_hat = sv / (sv.norm() + 1e-300);
    let fd = face
        .iter()
        .map(|p| sv_hat.dot(&(p - fc)).abs())
        .fold(floor, f64::max);
    sv.norm() / fd
}

/// checkMesh's skewness of an internal face (primitiveMeshTools::faceSkewness): the distance
/// from the face centre to where the owner–neighbour centre line crosses the face, relative
/// to the face's extent in that direction (at least 0.2 of the centres' distance).
pub fn foam_skewness(face: &[V3; 4], own: V3, nei: V3) -> f64 {
    let (fc, fa) = foam_face(face);
    let cpf = fc - own;
    let d = nei - own;
    let t = fa.dot(&cpf) / (fa.dot(&d) + 1e-300);
    normalised(face, fc, cpf - t * d, 0.2 * d.norm())
}

/// checkMesh's skewness of a boundary face (primitiveMeshTools::boundaryFaceSkewness): the
/// distance from the face centre to the foot of the owner centre on the face's plane,
/// relative to the face's extent in that direction (at least 0.4 of the centre's height).
pub fn foam_boundary_skewness(face: &[V3; 4], own: V3) -> f64 {
    let (fc, fa) = foam_face(face);
    let cpf = fc - own;
    let n = fa / (fa.norm() + 1e-300);
    let d = n * n.dot(&cpf);
    normalised(face, fc, cpf - d, 0.4 * d.norm())
}

/// The largest checkMesh skewness over every face of a volume block converted on its own
/// (its six faces boundary patches), where it is (cell and face i−, i+, j−, j+, k−, k+), and
/// the number of faces above `limit`.
pub fn block_skewness(g: &Grid3, limit: f64) -> (f64, String, usize) {
    let [ni, nj, nk] = g.dims();
    let centre = |i: usize, j: usize, k: usize| foam_cell_centre(&cell_faces(g, i, j, k));
    let (mut worst, mut at, mut above) = (0.0_f64, String::new(), 0);
    for k in 0..nk - 1 {
        for j in 0..nj - 1 {
            for i in 0..ni - 1 {
                let faces = cell_faces(g, i, j, k);
                let c = foam_cell_centre(&faces);
                let ends = [(i, ni - 2), (j, nj - 2), (k, nk - 2)];
                for (f, face) in faces.iter().enumerate() {
                    let (m, last) = ends[f / 2];
                    let s = match (f % 2, m) {
                        (0, 0) => foam_boundary_skewness(face, c),
                        (1, m) if m == last => foam_boundary_skewness(face, c),
                        // each internal face once, from its owner (the lower cell)
                        (0, _) => continue,
                        _ => {
                            let mut n = [i, j, k];
                            n[f / 2] += 1;
                            foam_skewness(face, c, centre(n[0], n[1], n[2]))
                        }
                    };
                    above += usize::from(s > limit);
                    if s > worst {
                        worst = s;
                        at = format!("cell ({i}, {j}, {k}) face {f}");
                    }
                }
            }
        }
    }
    (worst, at, above)
}

/// checkMesh's aspect ratio of a cell (primitiveMeshTools::cellClosedness): with Σ|S| the sum
/// over its faces of the area vectors' Cartesian components taken positive, the larger of
/// max(Σ|S|) / min(Σ|S|) and (Σ|S|ₓ + Σ|S|ᵧ + Σ|S|_z) / (6 V^(2/3)); checkMesh reports
/// "High aspect ratio cells" above 1000. Not invariant under rotation: an axis-aligned box
/// a × b × c (a ≥ b ≥ c) gives a / c, the same box tilted gives less.
pub fn foam_aspect_ratio(faces: &[[V3; 4]; 6]) -> f64 {
    let geo: Vec<(V3, V3)> = faces.iter().map(foam_face).collect();
    let sum_mag = geo.iter().map(|(_, a)| a.abs()).sum::<V3>();
    let est = geo.iter().map(|(c, _)| c).sum::<V3>() / 6.0;
    // (its sign is the block's handedness)
    let vol = (geo.iter().map(|(c, a)| a.dot(&(c - est))).sum::<f64>() / 3.0).abs();
    let cmpt = sum_mag.max() / (sum_mag.min() + 1e-150);
    let hydraulic = sum_mag.sum() / (6.0 * vol.max(1e-150).powf(2.0 / 3.0));
    cmpt.max(hydraulic)
}

/// A rotation-invariant aspect ratio of a cell: the largest over the smallest of the sums of
/// the face areas |S| of its three pairs of opposite faces (a / c for a box a × b × c, a ≥ b
/// ≥ c, however it is turned).
pub fn face_pair_aspect_ratio(faces: &[[V3; 4]; 6]) -> f64 {
    let pair = |d: usize| foam_face(&faces[2 * d]).1.norm() + foam_face(&faces[2 * d + 1]).1.norm();
    let s = [pair(0), pair(1), pair(2)];
    s.iter().copied().fold(0.0, f64::max) / s.iter().copied().fold(f64::INFINITY, f64::min)
}
