//! OpenFOAM mesh output: a `constant/polyMesh` directory (points, faces, owner, neighbour,
//! boundary) of the merged multi-block mesh ([`crate::io::mesh`]), every cell a hexahedron;
//! planar grids extruded one cell thick with an `empty` `frontAndBack` patch. Faces in
//! OpenFOAM's order: internal faces upper-triangular (by owner, then neighbour; normals
//! from owner to neighbour), then the boundary faces patch by patch (normals outward).
//! Numbers are written in ASCII with the shortest representation that reads back to the same
//! f64, formatted in parallel pieces written in order ([`crate::io::text`]).

use crate::io::mesh::{BcKind, Face, Mesh};
use crate::io::text::{push_f64, push_int, write_ranges, CHUNK};
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
        mesh.npoints(),
        mesh.ncells(),
        nint + nbound
    );
    let chunks = mesh.cell_chunks(CHUNK);
    let nchunks = chunks.len();
    // boundary faces after the internal ones, in pieces of CHUNK
    let bfaces: Vec<&Face> = mesh.boundary.iter().flatten().collect();
    let nbchunks = bfaces.len().div_ceil(CHUNK);
    let bpiece = |c: usize| &bfaces[c * CHUNK..((c + 1) * CHUNK).min(bfaces.len())];
    staged(|| {
        write_atomic(&dir.join("points"), |w| {
            header(w, "vectorField", "points", None)?;
            writeln!(w, "{}\n(", mesh.npoints())?;
            write_ranges(w, mesh.npoints().div_ceil(CHUNK), |c, b| {
                mesh.points_in(c * CHUNK..(c + 1) * CHUNK, |_, p| {
                    b.push(b'(');
                    push_f64(b, p[0]);
                    b.push(b' ');
                    push_f64(b, p[1]);
                    b.push(b' ');
                    push_f64(b, p[2]);
                    b.extend_from_slice(b")\n");
                })
            })?;
            writeln!(w, ")")
        })?;
        let face = |b: &mut Vec<u8>, f: &[u32; 4]| {
            b.extend_from_slice(b"4(");
            for (k, v) in f.iter().enumerate() {
                push_int(b, *v);
                b.push(if k < 3 { b' ' } else { b')' });
            }
            b.push(b'\n');
        };
        write_atomic(&dir.join("faces"), |w| {
            header(w, "faceList", "faces", None)?;
            writeln!(w, "{}\n(", nint + nbound)?;
            write_ranges(w, nchunks + nbchunks, |c, b| {
                if c < nchunks {
                    let (blk, ref cells) = chunks[c];
                    mesh.internal_faces_in(blk, cells.clone(), |f, _, _| face(b, f));
                } else {
                    bpiece(c - nchunks).iter().for_each(|f| face(b, &f.nodes));
                }
            })?;
            writeln!(w, ")")
        })?;
        let label = |b: &mut Vec<u8>, v: usize| {
            push_int(b, v);
            b.push(b'\n');
        };
        write_atomic(&dir.join("owner"), |w| {
            header(w, "labelList", "owner", Some(&note))?;
            writeln!(w, "{}\n(", nint + nbound)?;
            write_ranges(w, nchunks + nbchunks, |c, b| {
                if c < nchunks {
                    let (blk, ref cells) = chunks[c];
                    mesh.internal_faces_in(blk, cells.clone(), |_, o, _| label(b, o));
                } else {
                    bpiece(c - nchunks).iter().for_each(|f| label(b, f.cell));
                }
            })?;
            writeln!(w, ")")
        })?;
        write_atomic(&dir.join("neighbour"), |w| {
            header(w, "labelList", "neighbour", Some(&note))?;
            writeln!(w, "{nint}\n(")?;
            write_ranges(w, nchunks, |c, b| {
                let (blk, ref cells) = chunks[c];
                mesh.internal_faces_in(blk, cells.clone(), |_, _, n| label(b, n));
            })?;
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
