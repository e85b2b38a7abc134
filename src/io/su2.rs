//! SU2 native mesh output (`.su2`): the merged multi-block mesh ([`crate::io::mesh`]) as one
//! zone of quadrilaterals (2D) or hexahedra (3D), 0-based node numbers, and one `MARKER_TAG`
//! per family with its boundary lines or quadrilaterals. SU2 takes boundary conditions from
//! its configuration file, so each marker's kind (given or by its name) is a comment line
//! `% marker NAME: KIND` after the first.

use crate::io::mesh::{Cells, Mesh};
use crate::io::text::{push_f64, push_int, write_par, write_ranges, CHUNK};
use crate::io::write_atomic;
use crate::{Error, Result};
use std::path::Path;

/// SU2 (VTK) element types.
const LINE: u8 = 3;
const QUAD: u8 = 9;
const HEX: u8 = 12;

/// A family name as a marker tag (no blanks or `=`).
fn marker(family: &str) -> String {
    family
        .chars()
        .map(|c| {
            if c.is_whitespace() || c == '=' {
                '_'
            } else {
                c
            }
        })
        .collect()
}

/// Writes `mesh` (planar quadrilaterals, or hexahedra) as an SU2 mesh file (atomically).
///
/// # Errors
/// [`Error::Input`] for surface blocks (SU2 grids are planar or volumes); [`Error::Io`].
pub fn write_su2(path: &Path, mesh: &Mesh) -> Result<()> {
    if mesh.cells == Cells::Surface {
        return Err(Error::input(
            path.display().to_string(),
            "SU2 meshes are planar or volume grids, not surface grids",
        ));
    }
    let volume = mesh.cells == Cells::Volume;
    let (ndime, nc, cell_type, face_type) = if volume {
        (3, 8, HEX, QUAD)
    } else {
        (2, 4, QUAD, LINE)
    };
    write_atomic(path, |w| {
        writeln!(w, "% written by ellipgrid: {} blocks", mesh.blocks.len())?;
        // SU2 sets boundary conditions in its configuration file: each marker's kind here
        for (fam, bc) in mesh.families.iter().zip(&mesh.bcs) {
            writeln!(w, "% marker {}: {}", marker(fam), bc.name())?;
        }
        writeln!(w, "NDIME= {ndime}")?;
        writeln!(w, "NELEM= {}", mesh.ncells())?;
        let chunks = mesh.cell_chunks(CHUNK);
        write_ranges(w, chunks.len(), |c, buf| {
            let (b, ref cells) = chunks[c];
            let mb = &mesh.blocks[b];
            let [ci, cj, _] = mb.cell_dims();
            for local in cells.clone() {
                let n = mb.cell_nodes(local % ci, (local / ci) % cj, local / (ci * cj));
                push_int(buf, cell_type);
                for v in &n[..nc] {
                    buf.push(b' ');
                    push_int(buf, *v);
                }
                buf.push(b' ');
                push_int(buf, mb.first_cell + local);
                buf.push(b'\n');
            }
        })?;
        writeln!(w, "NPOIN= {}", mesh.npoints())?;
        let ndim = if volume { 3 } else { 2 };
        write_ranges(w, mesh.npoints().div_ceil(CHUNK), |c, buf| {
            mesh.points_in(c * CHUNK..(c + 1) * CHUNK, |k, p| {
                for x in &p[..ndim] {
                    push_f64(buf, *x);
                    buf.push(b' ');
                }
                push_int(buf, k);
                buf.push(b'\n');
            })
        })?;
        writeln!(w, "NMARK= {}", mesh.families.len())?;
        let nf = mesh.face_nodes();
        for (fam, faces) in mesh.families.iter().zip(&mesh.boundary) {
            writeln!(w, "MARKER_TAG= {}", marker(fam))?;
            writeln!(w, "MARKER_ELEMS= {}", faces.len())?;
            write_par(w, faces.len(), |k, buf| {
                push_int(buf, face_type);
                for v in &faces[k].nodes[..nf] {
                    buf.push(b' ');
                    push_int(buf, *v);
                }
                buf.push(b'\n');
            })?;
        }
        Ok(())
    })
}
