//! Gmsh MSH 4.1 output (ASCII): the merged multi-block mesh ([`crate::io::mesh`]) with one
//! entity per block (a surface, or a volume) and one per family (curves, or surfaces), and a
//! physical group named after each block and each family, so that a solver reading Gmsh
//! meshes (or Gmsh itself) finds the boundary patches by name. Node tags are the merged node
//! numbers + 1; every node is listed once, classified on the entity it lies on: a family's
//! (the first family's where two meet), else the block's where it is first met.

use crate::io::mesh::{Cells, Mesh};
use crate::io::text::{push_f64, push_int, write_par, write_ranges, CHUNK};
use crate::io::write_atomic;
use crate::Result;
use std::io::Write;
use std::path::Path;

/// Gmsh element types.
const LINE: u8 = 1;
const QUAD: u8 = 3;
const HEX: u8 = 5;

/// Bounding box of a set of nodes, as Gmsh's six numbers.
fn bbox(mesh: &Mesh, nodes: impl Iterator<Item = u32>) -> [f64; 6] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for n in nodes {
        grow(&mut b, mesh.point(n));
    }
    b
}

/// Widens bounding box `b` to hold `p`.
fn grow(b: &mut [f64; 6], p: [f64; 3]) {
    for c in 0..3 {
        b[c] = b[c].min(p[c]);
        b[c + 3] = b[c + 3].max(p[c]);
    }
}

/// A name inside Gmsh's double quotes.
fn quoted(s: &str) -> String {
    s.replace('"', "'")
}

/// Writes `mesh` as a Gmsh MSH 4.1 file (atomically).
///
/// # Errors
/// [`crate::Error::Io`] if the file cannot be written.
pub fn write_msh(path: &Path, mesh: &Mesh) -> Result<()> {
    let volume = mesh.cells == Cells::Volume;
    let (dim, nc, cell_type, face_type) = if volume {
        (3, 8, HEX, QUAD)
    } else {
        (2, 4, QUAD, LINE)
    };
    let nf = mesh.face_nodes();
    let nb = mesh.blocks.len();
    let nfam = mesh.families.len();
    // Physical tags: blocks 1..=nb, families nb+1..
    write_atomic(path, |w| {
        writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?;
        writeln!(w, "$PhysicalNames\n{}", nb + nfam)?;
        for (k, b) in mesh.blocks.iter().enumerate() {
            writeln!(w, "{dim} {} \"{}\"", k + 1, quoted(&b.name))?;
        }
        for (k, f) in mesh.families.iter().enumerate() {
            writeln!(w, "{} {} \"{}\"", dim - 1, nb + k + 1, quoted(f))?;
        }
        writeln!(w, "$EndPhysicalNames\n$Entities")?;
        let fmt = |b: [f64; 6]| format!("{} {} {} {} {} {}", b[0], b[1], b[2], b[3], b[4], b[5]);
        let (ncurves, nsurf, nvol) = if volume { (0, nfam, nb) } else { (nfam, nb, 0) };
        writeln!(w, "0 {ncurves} {nsurf} {nvol}")?;
        let families = |w: &mut dyn Write| -> std::io::Result<()> {
            for (k, faces) in mesh.boundary.iter().enumerate() {
                let b = bbox(
                    mesh,
                    faces.iter().flat_map(|f| f.nodes[..nf].iter().copied()),
                );
                writeln!(w, "{} {} 1 {} 0", k + 1, fmt(b), nb + k + 1)?;
            }
            Ok(())
        };
        let blocks = |w: &mut dyn Write| -> std::io::Result<()> {
            for k in 0..mesh.blocks.len() {
                let mut bb = bbox(mesh, std::iter::empty());
                mesh.block_points(k, |p| grow(&mut bb, p));
                writeln!(w, "{} {} 1 {} 0", k + 1, fmt(bb), k + 1)?;
            }
            Ok(())
        };
        // entities by dimension: the families' (one lower) before the blocks'
        families(w)?;
        blocks(w)?;
        writeln!(w, "$EndEntities")?;
        let np = mesh.npoints();
        // Nodes by entity: each family's (those of its faces not on an earlier family),
        // then each block's (those first met in it, not on a family).
        let mut claimed = vec![0u64; np.div_ceil(64)];
        let is_claimed = |c: &[u64], k: usize| c[k / 64] >> (k % 64) & 1 == 1;
        let mut fam_nodes: Vec<Vec<u32>> = Vec::with_capacity(nfam);
        for faces in &mesh.boundary {
            let mut v: Vec<u32> = faces.iter().flat_map(|f| f.nodes[..nf].to_vec()).collect();
            v.sort_unstable();
            v.dedup();
            v.retain(|&k| !is_claimed(&claimed, k as usize));
            v.iter()
                .for_each(|&k| claimed[k as usize / 64] |= 1 << (k % 64));
            fam_nodes.push(v);
        }
        let range = |k: usize| {
            let end = mesh
                .blocks
                .get(k + 1)
                .map_or(np, |b| b.first_point as usize);
            mesh.blocks[k].first_point as usize..end
        };
        let block_count: Vec<usize> = (0..nb)
            .map(|k| range(k).filter(|&n| !is_claimed(&claimed, n)).count())
            .collect();
        let nentities = fam_nodes.iter().filter(|v| !v.is_empty()).count()
            + block_count.iter().filter(|&&n| n > 0).count();
        writeln!(w, "$Nodes\n{nentities} {np} 1 {np}")?;
        let point = |buf: &mut Vec<u8>, p: [f64; 3]| {
            push_f64(buf, p[0]);
            buf.push(b' ');
            push_f64(buf, p[1]);
            buf.push(b' ');
            push_f64(buf, p[2]);
            buf.push(b'\n');
        };
        for (k, v) in fam_nodes.iter().enumerate().filter(|(_, v)| !v.is_empty()) {
            writeln!(w, "{} {} 0 {}", dim - 1, k + 1, v.len())?;
            write_par(w, v.len(), |m, buf| {
                push_int(buf, v[m] + 1);
                buf.push(b'\n');
            })?;
            write_par(w, v.len(), |m, buf| point(buf, mesh.point(v[m])))?;
        }
        for k in (0..nb).filter(|&k| block_count[k] > 0) {
            writeln!(w, "{dim} {} 0 {}", k + 1, block_count[k])?;
            let r = range(k);
            let pieces = r.len().div_ceil(CHUNK);
            let piece = |c: usize| r.start + c * CHUNK..(r.start + (c + 1) * CHUNK).min(r.end);
            write_ranges(w, pieces, |c, buf| {
                for n in piece(c).filter(|&n| !is_claimed(&claimed, n)) {
                    push_int(buf, n + 1);
                    buf.push(b'\n');
                }
            })?;
            write_ranges(w, pieces, |c, buf| {
                mesh.points_in(piece(c), |n, p| {
                    if !is_claimed(&claimed, n) {
                        point(buf, p);
                    }
                })
            })?;
        }
        writeln!(w, "$EndNodes")?;
        let ncells = mesh.ncells();
        let nfaces: usize = mesh.boundary.iter().map(Vec::len).sum();
        let nblocks = nb + mesh.boundary.iter().filter(|f| !f.is_empty()).count();
        writeln!(
            w,
            "$Elements\n{nblocks} {} 1 {}",
            ncells + nfaces,
            ncells + nfaces
        )?;
        let chunks = mesh.cell_chunks(CHUNK);
        for (k, b) in mesh.blocks.iter().enumerate() {
            writeln!(w, "{dim} {} {cell_type} {}", k + 1, b.ncells())?;
            let mine: Vec<&(usize, std::ops::Range<usize>)> =
                chunks.iter().filter(|c| c.0 == k).collect();
            let [ci, cj, _] = b.cell_dims();
            write_ranges(w, mine.len(), |c, buf| {
                for local in mine[c].1.clone() {
                    push_int(buf, b.first_cell + local + 1);
                    let n = b.cell_nodes(local % ci, (local / ci) % cj, local / (ci * cj));
                    for v in &n[..nc] {
                        buf.push(b' ');
                        push_int(buf, v + 1);
                    }
                    buf.push(b'\n');
                }
            })?;
        }
        let mut tag = ncells + 1;
        for (k, faces) in mesh.boundary.iter().enumerate() {
            if faces.is_empty() {
                continue;
            }
            writeln!(w, "{} {} {face_type} {}", dim - 1, k + 1, faces.len())?;
            write_par(w, faces.len(), |m, buf| {
                push_int(buf, tag + m);
                for v in &faces[m].nodes[..nf] {
                    buf.push(b' ');
                    push_int(buf, v + 1);
                }
                buf.push(b'\n');
            })?;
            tag += faces.len();
        }
        writeln!(w, "$EndElements")
    })
}
