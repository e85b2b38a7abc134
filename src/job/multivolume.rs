//! Runs a volume topology (`[[face]]` tables, volumes naming six faces): every face is gridded
//! once, by its kind (Coons patch, minimal surface, or Section 4 on its surface), the faces in
//! parallel; then every volume from its six faces (Section 5), the volumes in parallel. A face
//! that two volumes share is one grid seen in two orientations, so their nodes on it are
//! bit-identical; the report gives the smoothness of the grid across every interior face.

use super::floating::FloatingHistory;
use super::volume::{solve_volume, VolumeReport};
use crate::algebraic::coons::coons_sides;
use crate::algebraic::transfinite3d::transfinite;
use crate::case::volume::volume_name;
use crate::case::{FaceKind, LoadedCase};
use crate::elliptic::orthogonal::grid_block_with;
use crate::elliptic::picard::PicardInfo;
use crate::grid::boundary::Boundary2;
use crate::grid::faces::{normal, step_in, Faces};
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
    let (mut grids, faces) = grid_faces(case, topo)?;
    let (done, mut floating) = if case.case.faces.iter().any(|f| f.floating()) {
        if let Some(b) = mirrors.iter().position(Option::is_some) {
            return Err(Error::input(
                topo.volume_place(&case.path.display().to_string(), b),
                "mirror volumes and floating faces in one topology are not supported yet",
            ));
        }
        super::floating::float(case, topo, &mut grids)?
    } else {
        let solved: Vec<Option<(String, Block, VolumeReport)>> = (0..topo.volumes.len())
            .into_par_iter()
            .map(|v| {
                if mirrors[v].is_some() {
                    return Ok(None);
                }
                let t0 = Instant::now();
                let place = topo.volume_place(&case.path.display().to_string(), v);
                let f = Faces::new(topo.volume_faces(v, &grids), &place)?;
                solve_volume(case, v, &f, &place, t0).map(Some)
            })
            .collect::<Result<_>>()?;
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
