//! SU2 native mesh output (`.su2`): the merged multi-block mesh ([`crate::io::mesh`]) as one
//! zone of quadrilaterals (2D) or hexahedra (3D), 0-based node numbers, and one `MARKER_TAG`
//! per family with its boundary lines or quadrilaterals.

use crate::io::mesh::{Cells, Mesh};
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
        writeln!(w, "NDIME= {ndime}")?;
        writeln!(w, "NELEM= {}", mesh.ncells())?;
        let mut e = 0usize;
        for b in &mesh.blocks {
            let [ci, cj, ck] = b.cell_dims();
            for k in 0..ck {
                for j in 0..cj {
                    for i in 0..ci {
                        let n = b.cell_nodes(i, j, k);
                        write!(w, "{cell_type}")?;
                        for v in &n[..nc] {
                            write!(w, " {v}")?;
                        }
                        writeln!(w, " {e}")?;
                        e += 1;
                    }
                }
            }
        }
        writeln!(w, "NPOIN= {}", mesh.points.len())?;
        for (k, p) in mesh.points.iter().enumerate() {
            if volume {
                writeln!(w, "{} {} {} {k}", p[0], p[1], p[2])?;
            } else {
                writeln!(w, "{} {} {k}", p[0], p[1])?;
            }
        }
        writeln!(w, "NMARK= {}", mesh.families.len())?;
        let nf = mesh.face_nodes();
        for (fam, faces) in mesh.families.iter().zip(&mesh.boundary) {
            writeln!(w, "MARKER_TAG= {}", marker(fam))?;
            writeln!(w, "MARKER_ELEMS= {}", faces.len())?;
            for f in faces {
                write!(w, "{face_type}")?;
                for v in &f.nodes[..nf] {
                    write!(w, " {v}")?;
                }
                writeln!(w)?;
            }
        }
        Ok(())
    })
}
