//! Wavefront OBJ output (`.obj` with its `.mtl` beside it) for viewers and CAD tools.
//!
//! One group (`g NAME`) and one material (`usemtl NAME`, a distinct diffuse colour per block) per
//! block. The quads of its patches ([`crate::io::patches`]: the block at z = 0, the surface, or the six
//! outward faces of a volume) are written as four-vertex faces `f v//vn …`, counter-clockwise
//! about the outward normal, with unit vertex normals; a cell along a block side collapsed to
//! a point (a pole, a CAD face's cusp) as the three-vertex face it is. Coordinates are written with Rust's
//! shortest round-trip formatting, so a reader with f64 gets the points back exactly.

use std::path::Path;

use crate::io::patches::{block_color, block_patches, Patch};
use crate::io::{write_atomic, Block};
use crate::{Error, Result};

/// Writes `blocks` as OBJ at `path` and their materials at `path` with extension `.mtl`, both
/// atomically (the `.mtl` first).
pub fn write_obj(path: &Path, blocks: &[(String, Block)]) -> Result<()> {
    let bad = |msg: String| Error::input(path.display().to_string(), msg);
    if blocks.is_empty() {
        return Err(bad("no blocks to write".into()));
    }
    let mtl_path = path.with_extension("mtl");
    let Some(mtl_name) = mtl_path.file_name().and_then(|n| n.to_str()) else {
        return Err(bad("file name is not valid UTF-8".into()));
    };
    if mtl_name.contains(char::is_whitespace) {
        // `mtllib` takes whitespace-separated names: such a file name would not be found.
        return Err(bad(
            "OBJ file name must not contain spaces (its .mtl is named after it)".into(),
        ));
    }
    let names: Vec<String> = blocks.iter().map(|(n, _)| obj_name(n)).collect();
    let patches: Vec<Vec<Patch>> = blocks.iter().map(|(_, b)| block_patches(b)).collect();
    for (name, ps) in names.iter().zip(&patches) {
        if !ps.iter().all(Patch::all_finite) {
            return Err(bad(format!("block '{name}': non-finite coordinates")));
        }
    }

    write_atomic(&mtl_path, |w| {
        writeln!(w, "# ellipgrid {} materials", env!("CARGO_PKG_VERSION"))?;
        for (k, name) in names.iter().enumerate() {
            let c = block_color(k);
            writeln!(w, "\nnewmtl {name}")?;
            writeln!(
                w,
                "Ka 0 0 0\nKd {:.4} {:.4} {:.4}\nKs 0 0 0\nd 1\nillum 1",
                c[0], c[1], c[2]
            )?;
        }
        Ok(())
    })?;
    write_atomic(path, |w| {
        writeln!(
            w,
            "# ellipgrid {}: {} block(s)",
            env!("CARGO_PKG_VERSION"),
            blocks.len()
        )?;
        writeln!(w, "mtllib {mtl_name}")?;
        // OBJ indices are 1-based and global over the file.
        let mut base = 1usize;
        for (name, ps) in names.iter().zip(&patches) {
            writeln!(w, "\ng {name}\nusemtl {name}")?;
            for p in ps {
                for q in &p.points {
                    writeln!(w, "v {} {} {}", q[0], q[1], q[2])?;
                }
                for n in p.normals() {
                    writeln!(w, "vn {} {} {}", n[0], n[1], n[2])?;
                }
                for (q, n) in p.polygons() {
                    let [a, b, c, d] = q.map(|i| i + base);
                    if n == 4 {
                        writeln!(w, "f {a}//{a} {b}//{b} {c}//{c} {d}//{d}")?;
                    } else {
                        // a cell along a side collapsed to a point: the triangle it is
                        writeln!(w, "f {a}//{a} {b}//{b} {c}//{c}")?;
                    }
                }
                base += p.points.len();
            }
        }
        Ok(())
    })
}

/// A block name usable as an OBJ group and material name (no whitespace, not empty).
fn obj_name(n: &str) -> String {
    let s: String = n
        .chars()
        .map(|c| {
            if c.is_whitespace() || c.is_control() {
                '_'
            } else {
                c
            }
        })
        .collect();
    if s.is_empty() {
        "block".into()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Grid2;

    #[test]
    fn obj_text_layout() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("g.obj");
        let g = Grid2::<2>::from_fn(3, 2, |i, j| [i as f64 * 0.1, j as f64]);
        write_obj(&path, &[("my block".into(), Block::Planar(g))]).unwrap();
        let t = std::fs::read_to_string(&path).unwrap();
        assert!(t.contains("mtllib g.mtl\n"));
        assert!(t.contains("\ng my_block\nusemtl my_block\n"));
        assert!(
            t.contains("v 0.2 1 0\n"),
            "shortest round-trip formatting: {t}"
        );
        assert_eq!(t.lines().filter(|l| l.starts_with("f ")).count(), 2);
        assert!(t.contains("f 1//1 2//2 5//5 4//4\n"));
        assert!(t.contains("vn 0 0 1\n"));
        let m = std::fs::read_to_string(d.path().join("g.mtl")).unwrap();
        assert!(m.contains("newmtl my_block\n"));
    }

    #[test]
    fn obj_rejects_spaces_and_nan() {
        let d = tempfile::tempdir().unwrap();
        let g = Grid2::<2>::from_fn(2, 2, |i, j| [i as f64, j as f64]);
        let b = [("b".to_string(), Block::Planar(g))];
        assert!(write_obj(&d.path().join("a b.obj"), &b).is_err());
        let g = Grid2::<2>::from_fn(2, 2, |_, j| [f64::INFINITY, j as f64]);
        let e = write_obj(&d.path().join("n.obj"), &[("b".into(), Block::Planar(g))]);
        assert!(e.unwrap_err().to_string().contains("non-finite"));
        assert!(!d.path().join("n.obj").exists());
    }
}
