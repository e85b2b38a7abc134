//! Runs a volume topology (`[[face]]` tables, volumes naming six faces): every face is gridded
//! once, by its kind (Coons patch, minimal surface, or Section 4 on its surface), the faces in
//! parallel; then every volume from its six faces (Section 5), the volumes in parallel. A face
//! that two volumes share is one grid seen in two orientations, so their nodes on it are
//! bit-identical; the report gives the smoothness of the grid across every interior face.

use super::floating::FloatingHistory;
use super::volume::{continued_faces, solve_volume_continued, Continued, VolumeReport};
use crate::algebraic::coons::coons_sides;
use crate::algebraic::transfinite3d::transfinite;
use crate::case::volume::volume_name;
use crate::case::{FaceKind, LoadedCase};
use crate::elliptic::continuation::Lines;
use crate::elliptic::orthogonal::grid_block_with;
use crate::elliptic::picard::PicardInfo;
use crate::grid::boundary::Boundary2;
use crate::grid::faces::{face_dims, normal, step_in, tangents, Faces, FACE_NAMES};
use crate::grid::topology::volume::{FaceInterface, Topology3, VolumeSide};
use crate::grid::topology::{self as topology};
use crate::grid::Grid2;
use crate::io::Block;
use crate::quality::interface::{face_smoothness, InterfaceSmoothness};
use crate::quality::{self, QualityReport};
use crate::solve;
use crate::surface::face::{grid_face_on, project_boundary};
use crate::surface::pipeline::StepTimes;
use crate::{Error, Grid3, Result};
use ellipgrid_geometry::Vec3;
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;

/// Report of one face: how it was gridded and its quality as a surface grid.
#[derive(Clone, Debug, Serialize)]
pub struct FaceReport {
    pub name: String,
    pub kind: FaceKind,
    pub ni: usize,
    pub nj: usize,
    pub seconds: f64,
    /// The Picard history of a minimal face.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub picard: Option<PicardInfo>,
    /// Seconds per step of the Section 4 pipeline (surface faces).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface_steps: Option<StepTimes>,
    pub quality: QualityReport,
}

/// Smoothness of the grid across one interior face.
#[derive(Clone, Debug, Serialize)]
pub struct FaceInterfaceReport {
    pub face: String,
    pub volumes: [String; 2],
    #[serde(flatten)]
    pub smoothness: InterfaceSmoothness,
    /// The rounds of a floating face (`interface = "floating"`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub floating: Option<FloatingHistory>,
}

/// The grids and reports of a volume topology.
pub(super) struct Gridded3 {
    pub blocks: Vec<(String, Block)>,
    pub volumes: Vec<VolumeReport>,
    pub faces: Vec<FaceReport>,
    pub interfaces: Vec<FaceInterfaceReport>,
}

/// Grids every face, then every volume, of a volume topology.
pub(super) fn generate(case: &LoadedCase, topo: &Topology3) -> Result<Gridded3> {
    let mirrors = super::mirror::mirrors(case, topo)?;
    let conts = continuations(case, topo, &mirrors)?;
    let (mut grids, faces) = grid_faces(case, topo)?;
    let (done, mut floating) = if case.case.faces.iter().any(|f| f.floating()) {
        let other = mirrors
            .iter()
            .position(Option::is_some)
            .map(|b| (b, "mirror volumes"))
            .or_else(|| {
                conts
                    .iter()
                    .position(|c| !c.is_empty())
                    .map(|b| (b, "continue"))
            });
        if let Some((b, what)) = other {
            return Err(Error::input(
                topo.volume_place(&case.path.display().to_string(), b),
                format!("{what} and floating faces in one topology are not supported yet"),
            ));
        }
        super::floating::float(case, topo, &mut grids)?
    } else {
        let solve = |v: usize, lines: Continued| {
            let t0 = Instant::now();
            let place = topo.volume_place(&case.path.display().to_string(), v);
            let f = Faces::new(topo.volume_faces(v, &grids), &place)?;
            solve_volume_continued(case, v, &f, lines, &place, t0)
        };
        // The volumes that continue no face first, then those that do (from the first).
        let mut solved: Vec<Option<(String, Block, VolumeReport)>> = (0..topo.volumes.len())
            .into_par_iter()
            .map(|v| {
                if mirrors[v].is_some() || !conts[v].is_empty() {
                    return Ok(None);
                }
                solve(v, Default::default()).map(Some)
            })
            .collect::<Result<_>>()?;
        let second: Vec<(usize, (String, Block, VolumeReport))> = (0..topo.volumes.len())
            .into_par_iter()
            .filter(|&v| !conts[v].is_empty())
            .map(|v| {
                let mut lines = Continued::default();
                for &(s, beyond) in &conts[v] {
                    let Some((_, Block::Volume(g), _)) = &solved[beyond.volume] else {
                        unreachable!("the volume beyond a continued face is solved first")
                    };
                    lines[s] = Some(std::sync::Arc::new(arriving(topo, v, s, beyond, g)));
                }
                solve(v, lines).map(|r| (v, r))
            })
            .collect::<Result<_>>()?;
        for (v, r) in second {
            solved[v] = Some(r);
        }
        // The mirror images first (they read their originals), then every block in order.
        let mut mirrored: Vec<Option<(String, Block, VolumeReport)>> = Vec::new();
        for (b, m) in mirrors.iter().enumerate() {
            let Some(a) = *m else {
                mirrored.push(None);
                continue;
            };
            let t0 = Instant::now();
            let (_, block, rep_a) = solved[a].as_ref().expect("an original is solved");
            let Block::Volume(ga) = block else {
                unreachable!("volumes are volume blocks")
            };
            let (g, deviation) = super::mirror::mirror_volume(case, topo, b, a, ga, &grids)?;
            let [ni, nj, nk] = g.dims();
            let rep = VolumeReport {
                name: volume_name(case, b),
                ni,
                nj,
                nk,
                seconds: t0.elapsed().as_secs_f64(),
                picard: rep_a.picard.clone(),
                quality: crate::quality::quality3d::quality3d(&g),
                wall: rep_a.wall.clone(),
                mirror_of: Some(rep_a.name.clone()),
                mirror_deviation: Some(deviation),
            };
            mirrored.push(Some((rep.name.clone(), Block::Volume(g), rep)));
        }
        let done: Vec<(String, Block, VolumeReport)> = solved
            .into_iter()
            .zip(mirrored)
            .map(|(s, m)| s.or(m).expect("every volume is solved or mirrored"))
            .collect();
        (done, vec![None; topo.faces.blocks.len()])
    };
    let (blocks, volumes): (Vec<_>, Vec<_>) = done
        .into_iter()
        .map(|(name, block, rep)| ((name, block), rep))
        .unzip();
    let grids3: Vec<&Grid3> = blocks
        .iter()
        .map(|(_, b)| match b {
            Block::Volume(g) => g,
            _ => unreachable!("volumes are volume blocks"),
        })
        .collect();
    let interfaces = topo
        .connectivity()
        .interfaces
        .iter()
        .map(|f| FaceInterfaceReport {
            face: topo.faces.blocks[f.face].name.clone(),
            volumes: [f.a.volume, f.b.volume].map(|v| topo.volumes[v].name.clone()),
            smoothness: across(topo, f, &grids3),
            floating: floating[f.face].take(),
        })
        .collect();
    Ok(Gridded3 {
        blocks,
        volumes,
        faces,
        interfaces,
    })
}

/// For every volume, its continued faces (`continue`) and the volume side beyond each. The
/// volume beyond is solved in the first round: it must be neither mirrored nor continuing
/// a face itself (exit 2 naming the volume and the face).
fn continuations(
    case: &LoadedCase,
    topo: &Topology3,
    mirrors: &[Option<usize>],
) -> Result<Vec<Vec<(usize, VolumeSide)>>> {
    let file = case.path.display().to_string();
    let flags = (0..topo.volumes.len())
        .map(|v| continued_faces(&case.case.volumes[v], &topo.volume_place(&file, v)))
        .collect::<Result<Vec<_>>>()?;
    let interfaces = topo.connectivity().interfaces;
    (0..topo.volumes.len())
        .map(|v| {
            let place = topo.volume_place(&file, v);
            (0..6)
                .filter(|&s| flags[v][s])
                .map(|s| {
                    let here = VolumeSide { volume: v, side: s };
                    let beyond = interfaces.iter().find_map(|f| {
                        (f.a == here)
                            .then_some(f.b)
                            .or((f.b == here).then_some(f.a))
                    });
                    let why = match beyond {
                        None => Some("the face is not shared with another volume".to_string()),
                        Some(b) if b.volume == v => {
                            Some("the face is shared with this volume itself".into())
                        }
                        Some(b)
                            if mirrors[b.volume].is_some() || flags[b.volume].contains(&true) =>
                        {
                            Some(format!(
                                "the volume beyond, '{}', is mirrored or continues a face \
                                 itself (it must be gridded first; not supported yet)",
                                topo.volumes[b.volume].name
                            ))
                        }
                        _ => None,
                    };
                    match (why, beyond) {
                        (None, Some(b)) => Ok((s, b)),
                        (why, _) => Err(Error::input(
                            &place,
                            format!(
                                "continue = [\"{}\"]: {}",
                                FACE_NAMES[s],
                                why.unwrap_or_default()
                            ),
                        )),
                    }
                })
                .collect()
        })
        .collect()
}

/// The directions in which the grid lines of `beyond` (its grid `g`) arrive at the face on
/// side `s` of volume `v`, in `v`'s face indices: from its node one step in to the face node.
fn arriving(topo: &Topology3, v: usize, s: usize, beyond: VolumeSide, g: &Grid3) -> Lines {
    let [na, nb] = face_dims(s, topo.volumes[v].dims);
    let [np, nq] = topo.face_dims(topo.volumes[v].faces[s].face);
    let (ta, tb) = tangents(s);
    let mut dirs = vec![[0.0; 3]; na * nb];
    let (d, lo) = normal(beyond.side);
    for q in 0..nq {
        for p in 0..np {
            let n = topo.volume_node(v, s, p, q);
            let f = topo.volume_node(beyond.volume, beyond.side, p, q);
            let i = step_in(f, d, lo);
            let (xf, xi) = (g.point(f[0], f[1], f[2]), g.point(i[0], i[1], i[2]));
            dirs[n[ta] + na * n[tb]] = std::array::from_fn(|e| xf[e] - xi[e]);
        }
    }
    Lines::new(na, nb, |a, b| dirs[a + na * b])
}

/// The transfinite start grids of the volumes of a topology (from the gridded faces).
pub fn start_grids(case: &LoadedCase, topo: &Topology3) -> Result<Vec<(String, Block)>> {
    let (grids, _) = grid_faces(case, topo)?;
    let file = case.path.display().to_string();
    (0..topo.volumes.len())
        .map(|v| {
            let f = Faces::new(topo.volume_faces(v, &grids), &topo.volume_place(&file, v))?;
            Ok((volume_name(case, v), Block::Volume(transfinite(&f))))
        })
        .collect()
}

/// The grid of every face of a volume topology (in its own indices) with its report, in
/// parallel.
pub fn grid_faces(case: &LoadedCase, topo: &Topology3) -> Result<(Vec<Grid2<3>>, Vec<FaceReport>)> {
    let nodes = case.topology_nodes()?;
    let file = case.path.display().to_string();
    let done: Vec<(Grid2<3>, FaceReport)> = (0..topo.faces.blocks.len())
        .into_par_iter()
        .map(|f| {
            let sides = topology::chain_points(&topo.faces.blocks[f].sides, &nodes);
            grid_face(case, topo, f, sides, &topo.faces.block_place(&file, f))
        })
        .collect::<Result<_>>()?;
    Ok(done.into_iter().unzip())
}

/// Grids face `f` from the nodes of its four sides.
fn grid_face(
    case: &LoadedCase,
    topo: &Topology3,
    f: usize,
    sides: [Vec<Vec3>; 4],
    place: &str,
) -> Result<(Grid2<3>, FaceReport)> {
    let t0 = Instant::now();
    let spec = &case.case.faces[f];
    let solver_spec = &case.case.solver;
    let orth = topo.faces.blocks[f].orthogonal;
    let arrays = sides
        .clone()
        .map(|s| s.iter().map(|p| [p.x, p.y, p.z]).collect::<Vec<_>>());
    let solver = || {
        solve::select::by_name(&solver_spec.linear)
            .map_err(|m| Error::input(format!("{}: [solver]", case.path.display()), m))
    };
    let (grid, picard, surface_steps) = match spec.kind {
        FaceKind::Tfi => {
            let [a, b, c, d] = &arrays;
            (coons_sides([a, b, c, d]), None, None)
        }
        FaceKind::Minimal => {
            let b = Boundary2::<3>::new(arrays, place)?;
            let r = grid_block_with(
                &b,
                None,
                orth,
                solver_spec.control,
                solver()?.as_mut(),
                &solver_spec.picard,
                place,
            )?;
            (r.grid, Some(r.picard), None)
        }
        FaceKind::Surface => {
            let name = spec.surface.as_deref().unwrap_or_default();
            let surface = case.named_surface(name, place)?;
            let uv = project_boundary(surface.as_ref(), &sides, place)?;
            let r = grid_face_on(
                surface.as_ref(),
                &sides,
                &uv,
                orth,
                solver()?.as_mut(),
                place,
            )?;
            (r.result.grid, r.uv_picard, Some(r.result.times))
        }
    };
    let rep = FaceReport {
        name: spec.name.clone(),
        kind: spec.kind,
        ni: grid.ni(),
        nj: grid.nj(),
        seconds: t0.elapsed().as_secs_f64(),
        picard,
        surface_steps,
        quality: quality::quality_surface(&grid),
    };
    Ok((grid, rep))
}

/// The smoothness of the grid across interior face `f.face`: every node of the face off its
/// boundary, with its neighbours one and two steps into either volume.
fn across(topo: &Topology3, f: &FaceInterface, grids: &[&Grid3]) -> InterfaceSmoothness {
    let [np, nq] = topo.face_dims(f.face);
    let side = |s: VolumeSide, p: usize, q: usize| {
        let n = topo.volume_node(s.volume, s.side, p, q);
        let (d, lo) = normal(s.side);
        let i = step_in(n, d, lo);
        (n, i, step_in(i, d, lo))
    };
    let nodes = (1..nq.saturating_sub(1)).flat_map(move |q| {
        (1..np.saturating_sub(1)).map(move |p| {
            let (na, ia, ia2) = side(f.a, p, q);
            let (nb, ib, ib2) = side(f.b, p, q);
            [na, ia, ia2, nb, ib, ib2]
        })
    });
    face_smoothness(grids[f.a.volume], grids[f.b.volume], nodes)
}
