//! OpenFOAM mesh output: a `constant/polyMesh` directory (points, faces, owner, neighbour,
//! boundary) of the merged multi-block mesh ([`crate::io::mesh`]), every cell a hexahedron;
//! planar grids extruded one cell thick with an `empty` `frontAndBack` patch. Faces in
//! OpenFOAM's order: internal faces upper-triangular (by owner, then neighbour; normals
//! from owner to neighbour), then the boundary faces patch by patch (normals outward).
//! Numbers are written in ASCII with the shortest representation that reads back to the same
//! f64.

use crate::io::mesh::{BcKind, Mesh};
use crate::io::{staged, write_atomic};
use crate::{Error, Result};
use std::io::Write;
use std::path::Path;

/// The OpenFOAM file header.
fn header(w: &mut dyn Write, class: &str, object: &str, note: Option<&str>) -> std::io::Result<()> {
    writeln!(
        w,
        "/*--------------------------------*- C++ -*----------------------------------*\\\n\
         | written by ellipgrid                                                      |\n\
         \\*---------------------------------------------------------------------------*/"
    )?;
    writeln!(
        w,
        "FoamFile\n{{\n    version     2.0;\n    format      ascii;"
    )?;
    writeln!(w, "    class       {class};")?;
    if let Some(n) = note {
        writeln!(w, "    note        \"{n}\";")?;
    }
    writeln!(
        w,
        "    location    \"constant/polyMesh\";\n    object      {object};\n}}\n"
    )
}

/// A family name as an OpenFOAM patch name (a `word`: no blanks, quotes, braces, …).
pub fn patch_name(family: &str) -> String {
    let s: String = family
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "_-.:+".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() {
        "patch".into()
    } else {
        s
    }
}

/// OpenFOAM's patch type for a family.
fn patch_type(family: &str) -> &'static str {
    match BcKind::of(family) {
        BcKind::Wall => "wall",
        BcKind::Empty => "empty",
        BcKind::Symmetry => "symmetry",
        _ => "patch",
    }
}

/// Writes `mesh` (hexahedral: volume blocks, or planar blocks built with an extrusion) as
/// the polyMesh directory `dir` (created if missing; every file replaced atomically, all or
/// none).
///
/// # Errors
/// [`Error::Input`] for a mesh of quadrilaterals, or two families with the same patch name;
/// [`Error::Io`] naming the file that could not be written.
pub fn write_polymesh(dir: &Path, mesh: &Mesh) -> Result<()> {
    let place = dir.display().to_string();
    if mesh.face_nodes() != 4 {
        return Err(Error::input(
            place,
            "an OpenFOAM mesh is made of volumes: planar grids are extruded, surface grids \
             cannot be written",
        ));
    }
    let names: Vec<String> = mesh.families.iter().map(|f| patch_name(f)).collect();
    for (k, n) in names.iter().enumerate() {
        if names[..k].contains(n) {
            return Err(Error::input(
                place,
                format!("two families are both the OpenFOAM patch '{n}'"),
            ));
        }
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let nint = mesh.ninternal_faces();
    let nbound: usize = mesh.boundary.iter().map(Vec::len).sum();
    let note = format!(
        "nPoints:{} nCells:{} nFaces:{} nInternalFaces:{nint}",
        mesh.points.len(),
        mesh.ncells(),
        nint + nbound
    );
    staged(|| {
        write_atomic(&dir.join("points"), |w| {
            header(w, "vectorField", "points", None)?;
            writeln!(w, "{}\n(", mesh.points.len())?;
            for p in &mesh.points {
                writeln!(w, "({} {} {})", p[0], p[1], p[2])?;
            }
            writeln!(w, ")")
        })?;
        write_atomic(&dir.join("faces"), |w| {
            header(w, "faceList", "faces", None)?;
            writeln!(w, "{}\n(", nint + nbound)?;
            let mut r = Ok(());
            mesh.for_each_internal_face(|f, _, _| {
                if r.is_ok() {
                    r = writeln!(w, "4({} {} {} {})", f[0], f[1], f[2], f[3]);
                }
            });
            r?;
            for f in mesh.boundary.iter().flatten() {
                let n = f.nodes;
                writeln!(w, "4({} {} {} {})", n[0], n[1], n[2], n[3])?;
            }
            writeln!(w, ")")
        })?;
        write_atomic(&dir.join("owner"), |w| {
            header(w, "labelList", "owner", Some(&note))?;
            writeln!(w, "{}\n(", nint + nbound)?;
            let mut r = Ok(());
            mesh.for_each_internal_face(|_, o, _| {
                if r.is_ok() {
                    r = writeln!(w, "{o}");
                }
            });
            r?;
            for f in mesh.boundary.iter().flatten() {
                writeln!(w, "{}", f.cell)?;
            }
            writeln!(w, ")")
        })?;
        write_atomic(&dir.join("neighbour"), |w| {
            header(w, "labelList", "neighbour", Some(&note))?;
            writeln!(w, "{nint}\n(")?;
            let mut r = Ok(());
            mesh.for_each_internal_face(|_, _, n| {
                if r.is_ok() {
                    r = writeln!(w, "{n}");
                }
            });
            r?;
            writeln!(w, ")")
        })?;
        write_atomic(&dir.join("boundary"), |w| {
            header(w, "polyBoundaryMesh", "boundary", None)?;
            writeln!(w, "{}\n(", names.len())?;
            let mut start = nint;
            for ((name, fam), faces) in names.iter().zip(&mesh.families).zip(&mesh.boundary) {
                let t = patch_type(fam);
                writeln!(w, "    {name}\n    {{")?;
                writeln!(w, "        type            {t};")?;
                if t != "patch" {
                    writeln!(w, "        inGroups        List<word> 1({t});")?;
                }
                writeln!(w, "        nFaces          {};", faces.len())?;
                writeln!(w, "        startFace       {start};\n    }}")?;
                start += faces.len();
            }
            writeln!(w, ")")
        })
    })
}
