//! Volumes of a topology that are mirror images of others (`mirror = "A"` in a `[[volume]]`
//! table): B is A's mirror image in the plane of the faces they share (a plane x, y or z =
//! constant), so B costs no solve. If those faces are symmetry faces of A (`symmetry`: their
//! nodes slide in the plane, [`crate::elliptic::symmetry3d`]) the whole is the grid of the
//! whole symmetric domain, and the grid lines cross the shared faces without a kink; if they
//! are fixed, B is the grid its own solve would give (to the iteration's tolerance).
//!
//! B's own boundary must be the mirror image of A's (within 1e-6 of A's diameter, e.g. the
//! faces of a symmetric wing gridded on mirror-image surfaces): B keeps its own boundary nodes
//! (bit-identical with the volumes it shares faces with), takes A's nodes on the shared faces,
//! and the mirror images of A's interior nodes.

use crate::case::volume::volume_name;
use crate::case::LoadedCase;
use crate::elliptic::symmetry3d::SymmetryFace;
use crate::grid::faces::{parse_face, Faces, FACE_NAMES};
use crate::grid::topology::volume::Topology3;
use crate::grid::Grid2;
use crate::{Error, Grid3, Result};

/// For every volume, the volume it mirrors (`mirror = "A"`), checked: A exists, is not a
/// mirror itself and is not B.
pub(super) fn mirrors(case: &LoadedCase, topo: &Topology3) -> Result<Vec<Option<usize>>> {
    let path = case.path.display().to_string();
    let names: Vec<String> = (0..topo.volumes.len())
        .map(|v| volume_name(case, v))
        .collect();
    let out: Vec<Option<usize>> = case
        .case
        .volumes
        .iter()
        .enumerate()
        .map(|(b, v)| {
            let Some(a) = &v.mirror else { return Ok(None) };
            let place = topo.volume_place(&path, b);
            let k = names.iter().position(|n| n == a).ok_or_else(|| {
                Error::input(&place, format!("mirror = \"{a}\": no volume of that name"))
            })?;
            if k == b {
                return Err(Error::input(
                    &place,
                    "mirror: a volume cannot mirror itself",
                ));
            }
            if !v.symmetry.is_empty() {
                return Err(Error::input(
                    &place,
                    "a mirrored volume has no symmetry faces of its own (they are its \
                     original's)",
                ));
            }
            Ok(Some(k))
        })
        .collect::<Result<_>>()?;
    for (b, m) in out.iter().enumerate() {
        if let Some(a) = m {
            if out[*a].is_some() {
                return Err(Error::input(
                    topo.volume_place(&path, b),
                    format!(
                        "mirror = \"{}\": that volume is a mirror image itself",
                        names[*a]
                    ),
                ));
            }
        }
    }
    // A symmetry face shared with another volume: that volume must be the mirror image
    // (the face's nodes slide; any other volume would keep the face's gridded nodes).
    for (a, v) in case.case.volumes.iter().enumerate() {
        for n in &v.symmetry {
            let Some(sa) = parse_face(n) else { continue };
            let f = topo.volumes[a].faces[sa].face;
            for (c, _) in topo.uses_of(f) {
                if c != a && out[c] != Some(a) {
                    return Err(Error::input(
                        topo.volume_place(&path, a),
                        format!(
                            "symmetry = [\"{n}\"]: the face ('{}') is shared with volume '{}', \
                             which is not this volume's mirror image (mirror = \"{}\")",
                            topo.faces.blocks[f].name, names[c], names[a]
                        ),
                    ));
                }
            }
        }
    }
    Ok(out)
}

/// Volume `b` as the mirror image of volume `a`'s grid `ga` (module documentation), and the
/// largest distance of b's own boundary nodes from the mirror images of a's; `grids` are the
/// gridded faces of the topology.
pub(super) fn mirror_volume(
    case: &LoadedCase,
    topo: &Topology3,
    b: usize,
    a: usize,
    ga: &Grid3,
    grids: &[Grid2<3>],
) -> Result<(Grid3, f64)> {
    let path = case.path.display().to_string();
    let place = topo.volume_place(&path, b);
    let name_a = volume_name(case, a);
    // The faces A shares with B (as (side in A, side in B)), all on one coordinate plane.
    let shared: Vec<(usize, usize)> = (0..6)
        .filter_map(|sa| {
            let f = topo.volumes[a].faces[sa].face;
            (0..6)
                .find(|&sb| topo.volumes[b].faces[sb].face == f)
                .map(|sb| (sa, sb))
        })
        .collect();
    let Some(&(first, _)) = shared.first() else {
        return Err(Error::input(
            &place,
            format!("mirror = \"{name_a}\": the two volumes share no face"),
        ));
    };
    let plane = SymmetryFace::of_grid(ga, first + 1, &place).map_err(|e| {
        Error::input(
            &place,
            format!("mirror = \"{name_a}\": the shared faces must lie on a plane x, y or z = constant: {e}"),
        )
    })?;
    for &(sa, _) in &shared[1..] {
        let p = SymmetryFace::of_grid(ga, sa + 1, &place)?;
        let m = (0..3).position(|d| plane.normal[d] != 0.0).unwrap_or(0);
        if p.normal[m] == 0.0 || (p.point[m] - plane.point[m]).abs() > 1e-9 * ga.diameter() {
            return Err(Error::input(
                &place,
                format!(
                    "mirror = \"{name_a}\": the shared faces {} and {} of '{name_a}' are not on \
                     one plane",
                    FACE_NAMES[first], FACE_NAMES[sa]
                ),
            ));
        }
    }
    let dims_b = topo.volumes[b].dims;
    let mut own = Grid3::zeros(dims_b[0], dims_b[1], dims_b[2]);
    Faces::new(topo.volume_faces(b, grids), &place)?.apply_to(&mut own);
    let corners: Vec<[usize; 3]> = (0..8)
        .map(|c: usize| std::array::from_fn(|d| if c >> d & 1 == 1 { dims_b[d] - 1 } else { 0 }))
        .collect();
    let candidates = orderings(ga, &own, &plane, &corners);
    let boundary: Vec<[usize; 3]> = (0..dims_b[2])
        .flat_map(|k| (0..dims_b[1]).flat_map(move |j| (0..dims_b[0]).map(move |i| [i, j, k])))
        .filter(|ijk| (0..3).any(|d| ijk[d] == 0 || ijk[d] + 1 == dims_b[d]))
        .collect();
    // The ordering whose whole boundary fits, else the first whose corners do (for the
    // error below, which names the face that does not fit).
    let order = candidates
        .iter()
        .find(|o| !misfits(ga, &own, &plane, &boundary, o))
        .or(candidates.first())
        .copied()
        .ok_or_else(|| {
            Error::input(
                &place,
                format!(
                    "mirror = \"{name_a}\": no ordering of this volume's nodes makes its \
                     corners the mirror images of '{name_a}''s in the plane of its face {}",
                    FACE_NAMES[first]
                ),
            )
        })?;
    let map = |ijk: [usize; 3]| order.map(ijk);
    // Every boundary node within 1e-6 of the diameter of its mirror image.
    let tol = 1e-6 * ga.diameter();
    let [ni, nj, nk] = dims_b;
    let on_side = |ijk: [usize; 3], s: usize| {
        let ax = s / 2;
        ijk[ax] == if s % 2 == 1 { dims_b[ax] - 1 } else { 0 }
    };
    // B's sides on the shared faces that are symmetry faces of A (their nodes slid in A).
    let sym_a: Vec<usize> = case.case.volumes[a]
        .symmetry
        .iter()
        .filter_map(|n| parse_face(n))
        .collect();
    let sliding: Vec<usize> = shared
        .iter()
        .filter(|(sa, _)| sym_a.contains(sa))
        .map(|&(_, sb)| sb)
        .collect();
    let mut worst = 0.0f64;
    let mut out = Grid3::zeros(ni, nj, nk);
    for k in 0..nk {
        for j in 0..nj {
            for i in 0..ni {
                let ijk = [i, j, k];
                let ia = map(ijk);
                let pa = ga.point(ia[0], ia[1], ia[2]);
                let boundary = (0..6).find(|&s| on_side(ijk, s));
                let p = match boundary {
                    None => plane.mirror(pa),
                    Some(_) if sliding.iter().any(|&sb| on_side(ijk, sb)) => pa,
                    Some(_) if shared.iter().any(|&(_, sb)| on_side(ijk, sb)) => own.point(i, j, k),
                    Some(s) => {
                        let q = own.point(i, j, k);
                        let m = plane.mirror(pa);
                        let d = (0..3).map(|c| (q[c] - m[c]).abs()).fold(0.0, f64::max);
                        if d > tol || d.is_nan() {
                            return Err(Error::input(
                                &place,
                                format!(
                                    "mirror = \"{name_a}\": face {} ('{}') is not the mirror \
                                     image of '{name_a}''s: node ({i}, {j}, {k}) lies {d:.3e} \
                                     from it (more than 1e-6 of the diameter)",
                                    FACE_NAMES[s],
                                    topo.faces.blocks[topo.volumes[b].faces[s].face].name
                                ),
                            ));
                        }
                        worst = worst.max(d);
                        q
                    }
                };
                out.set(i, j, k, p);
            }
        }
    }
    Ok((out, worst))
}

/// True if some node of `nodes` does not fit ordering `o` (see [`orderings`]).
fn misfits(a: &Grid3, b: &Grid3, plane: &SymmetryFace, nodes: &[[usize; 3]], o: &Ordering) -> bool {
    let tol = 1e-6 * a.diameter();
    nodes.iter().any(|&ib| {
        let ia = o.map(ib);
        let p = plane.mirror(a.point(ia[0], ia[1], ia[2]));
        let q = b.point(ib[0], ib[1], ib[2]);
        !(0..3).all(|c| (p[c] - q[c]).abs() <= tol)
    })
}

/// An ordering of a block's nodes: node `ib` of `b` is node `map(ib)` of `a` (an axis
/// permutation with reversals).
#[derive(Clone, Copy)]
struct Ordering {
    perm: [usize; 3],
    flips: u8,
    dims: [usize; 3],
}

impl Ordering {
    fn map(&self, ib: [usize; 3]) -> [usize; 3] {
        let mut ia = [0; 3];
        for d in 0..3 {
            ia[self.perm[d]] = if self.flips >> d & 1 == 1 {
                self.dims[d] - 1 - ib[d]
            } else {
                ib[d]
            };
        }
        ia
    }
}

/// The orderings of `b`'s nodes (of the 48) under which `b`'s boundary nodes `nodes` are the
/// mirror images of `a`'s in `plane` within 1e-6 of the diameter.
fn orderings(a: &Grid3, b: &Grid3, plane: &SymmetryFace, nodes: &[[usize; 3]]) -> Vec<Ordering> {
    let (da, db) = (a.dims(), b.dims());
    let tol = 1e-6 * a.diameter();
    const PERMS: [[usize; 3]; 6] = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let mut out = Vec::new();
    for perm in PERMS {
        if (0..3).any(|d| db[d] != da[perm[d]]) {
            continue;
        }
        for flips in 0..8u8 {
            let o = Ordering {
                perm,
                flips,
                dims: db,
            };
            let fits = nodes.iter().all(|&ib| {
                let ia = o.map(ib);
                let p = plane.mirror(a.point(ia[0], ia[1], ia[2]));
                let q = b.point(ib[0], ib[1], ib[2]);
                (0..3).all(|c| (p[c] - q[c]).abs() <= tol)
            });
            if fits {
                out.push(o);
            }
        }
    }
    out
}
