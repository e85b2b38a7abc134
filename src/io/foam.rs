//! OpenFOAM mesh output: a `constant/polyMesh` directory (points, faces, owner, neighbour,
//! boundary) of the merged multi-block mesh ([`crate::io::mesh`]), every cell a hexahedron;
//! planar grids extruded one cell thick with an `empty` `frontAndBack` patch. Faces in
//! OpenFOAM's order: internal faces upper-triangular (by owner, then neighbour; normals
//! from owner to neighbour), then the boundary faces patch by patch (normals outward).
//! Numbers are written in ASCII with the shortest representation that reads back to the same
//! f64, formatted in parallel pieces written in order ([`crate::io::text`]), or in OpenFOAM's
//! binary format (raw little-endian f64 and 32-bit labels, faces as a `faceCompactList`).

use crate::io::mesh::{BcKind, Face, Mesh};
use crate::io::text::{push_f64, push_int, write_ranges, CHUNK};
use crate::io::{staged, write_atomic};
use crate::{Error, Result};
use std::io::Write;
use std::path::Path;

/// The OpenFOAM file header (`binary`: raw little-endian lists, 32-bit labels).
fn header(
    w: &mut dyn Write,
    class: &str,
    object: &str,
    note: Option<&str>,
    binary: bool,
) -> std::io::Result<()> {
    writeln!(
        w,
        "/*--------------------------------*- C++ -*----------------------------------*\\\n\
         | written by ellipgrid                                                      |\n\
         \\*---------------------------------------------------------------------------*/"
    )?;
    let format = if binary { "binary" } else { "ascii" };
    writeln!(
        w,
        "FoamFile\n{{\n    version     2.0;\n    format      {format};"
    )?;
    if binary {
        writeln!(w, "    arch        \"LSB;label=32;scalar=64\";")?;
    }
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

/// OpenFOAM's patch type for a family's boundary condition.
fn patch_type(bc: BcKind) -> &'static str {
    match bc {
        BcKind::Wall => "wall",
        BcKind::Empty => "empty",
        BcKind::Symmetry => "symmetry",
        _ => "patch",
    }
}

/// Writes `mesh` (hexahedral: volume blocks, or planar blocks built with an extrusion) as
/// the polyMesh directory `dir` in ASCII (created if missing; every file replaced
/// atomically, all or none).
///
/// # Errors
/// [`Error::Input`] for a mesh of quadrilaterals, or two families with the same patch name;
/// [`Error::Io`] naming the file that could not be written.
pub fn write_polymesh(dir: &Path, mesh: &Mesh) -> Result<()> {
    write_polymesh_as(dir, mesh, false)
}

/// [`write_polymesh`] in OpenFOAM's ASCII or `binary` format (points as raw f64, labels as
/// 32-bit integers, faces as a `faceCompactList`; the `boundary` dictionary stays text).
///
/// # Errors
/// Those of [`write_polymesh`], and [`Error::Input`] in binary for more points, cells or
/// face nodes than 32-bit labels count.
pub fn write_polymesh_as(dir: &Path, mesh: &Mesh, binary: bool) -> Result<()> {
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
    if binary && (4 * (nint + nbound)).max(mesh.npoints()) > i32::MAX as usize {
        return Err(Error::input(
            place,
            "too large for OpenFOAM's 32-bit labels in binary: write it in ASCII",
        ));
    }
    let chunks = mesh.cell_chunks(CHUNK);
    let nchunks = chunks.len();
    // boundary faces after the internal ones, in pieces of CHUNK
    let bfaces: Vec<&Face> = mesh.boundary.iter().flatten().collect();
    let nbchunks = bfaces.len().div_ceil(CHUNK);
    let bpiece = |c: usize| &bfaces[c * CHUNK..((c + 1) * CHUNK).min(bfaces.len())];
    // A list: its length, then its items between parentheses; in binary the items are raw
    // little-endian numbers between the parentheses, and an empty list is its length alone.
    let open = |w: &mut dyn Write, n: usize| -> std::io::Result<()> {
        match (binary, n) {
            (true, 0) => writeln!(w, "0"),
            (true, _) => write!(w, "{n}\n("),
            (false, _) => writeln!(w, "{n}\n("),
        }
    };
    let close = |w: &mut dyn Write, n: usize| -> std::io::Result<()> {
        match (binary, n) {
            (true, 0) => Ok(()),
            _ => writeln!(w, ")"),
        }
    };
    let label = |b: &mut Vec<u8>, v: usize| {
        if binary {
            b.extend_from_slice(&(v as i32).to_le_bytes());
        } else {
            push_int(b, v);
            b.push(b'\n');
        }
    };
    // Pieces of faces: internal ones by cell chunks, then the boundary ones.
    let faces_of = |c: usize, f: &mut dyn FnMut(&[u32; 4], usize, usize)| {
        if c < nchunks {
            let (blk, ref cells) = chunks[c];
            mesh.internal_faces_in(blk, cells.clone(), f);
        } else {
            bpiece(c - nchunks)
                .iter()
                .for_each(|x| f(&x.nodes, x.cell, usize::MAX));
        }
    };
    let nfaces = nint + nbound;
    staged(|| {
        write_atomic(&dir.join("points"), |w| {
            header(w, "vectorField", "points", None, binary)?;
            open(w, mesh.npoints())?;
            write_ranges(w, mesh.npoints().div_ceil(CHUNK), |c, b| {
                mesh.points_in(c * CHUNK..(c + 1) * CHUNK, |_, p| {
                    if binary {
                        p.iter().for_each(|x| b.extend_from_slice(&x.to_le_bytes()));
                        return;
                    }
                    b.push(b'(');
                    push_f64(b, p[0]);
                    b.push(b' ');
                    push_f64(b, p[1]);
                    b.push(b' ');
                    push_f64(b, p[2]);
                    b.extend_from_slice(b")\n");
                })
            })?;
            close(w, mesh.npoints())
        })?;
        write_atomic(&dir.join("faces"), |w| {
            if binary {
                // faceCompactList: the offsets of the faces' nodes, then all the nodes
                header(w, "faceCompactList", "faces", None, binary)?;
                open(w, nfaces + 1)?;
                write_ranges(w, (nfaces + 1).div_ceil(CHUNK), |c, b| {
                    for k in c * CHUNK..((c + 1) * CHUNK).min(nfaces + 1) {
                        label(b, 4 * k);
                    }
                })?;
                close(w, nfaces + 1)?;
                open(w, 4 * nfaces)?;
                write_ranges(w, nchunks + nbchunks, |c, b| {
                    faces_of(c, &mut |f, _, _| {
                        f.iter().for_each(|&v| label(b, v as usize))
                    })
                })?;
                return close(w, 4 * nfaces);
            }
            header(w, "faceList", "faces", None, binary)?;
            open(w, nfaces)?;
            write_ranges(w, nchunks + nbchunks, |c, b| {
                faces_of(c, &mut |f, _, _| {
                    b.extend_from_slice(b"4(");
                    for (k, v) in f.iter().enumerate() {
                        push_int(b, *v);
                        b.push(if k < 3 { b' ' } else { b')' });
                    }
                    b.push(b'\n');
                })
            })?;
            close(w, nfaces)
        })?;
        write_atomic(&dir.join("owner"), |w| {
            header(w, "labelList", "owner", Some(&note), binary)?;
            open(w, nfaces)?;
            write_ranges(w, nchunks + nbchunks, |c, b| {
                faces_of(c, &mut |_, o, _| label(b, o))
            })?;
            close(w, nfaces)
        })?;
        write_atomic(&dir.join("neighbour"), |w| {
            header(w, "labelList", "neighbour", Some(&note), binary)?;
            open(w, nint)?;
            write_ranges(w, nchunks, |c, b| faces_of(c, &mut |_, _, n| label(b, n)))?;
            close(w, nint)
        })?;
        write_atomic(&dir.join("boundary"), |w| {
            header(w, "polyBoundaryMesh", "boundary", None, false)?;
            writeln!(w, "{}\n(", names.len())?;
            let mut start = nint;
            for ((name, bc), faces) in names.iter().zip(&mesh.bcs).zip(&mesh.boundary) {
                let t = patch_type(*bc);
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
