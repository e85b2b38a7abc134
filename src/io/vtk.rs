//! VTK XML output for ParaView: one `.vts` StructuredGrid per block (coordinates and quality
//! fields as raw little-endian appended Float64 arrays, UInt64 byte-count headers) and a `.vtm`
//! multi-block index listing them.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::io::{write_atomic, Block};
use crate::{Error, Result};

/// Writes `block` as a VTK XML StructuredGrid (`.vts`), atomically.
///
/// Points are one 3-component Float64 array (z = 0 for planar blocks), i fastest. Each
/// `point_data` array needs ni·nj·nk values, each `cell_data` array
/// max(ni−1,1)·max(nj−1,1)·max(nk−1,1) values (cell (i, j, k) at i + (ni−1)(j + (nj−1)k)).
/// Names must be non-empty and distinct within point and within cell data. Non-finite values
/// are written as they are, so that a failed grid can still be inspected.
pub fn write_vts(
    path: &Path,
    block: &Block,
    cell_data: &[(&str, &[f64])],
    point_data: &[(&str, &[f64])],
) -> Result<()> {
    let bad = |msg: String| Error::input(path.display().to_string(), msg);
    let d = block.dims();
    if d.contains(&0) {
        return Err(bad(format!(
            "empty block ({}×{}×{} nodes)",
            d[0], d[1], d[2]
        )));
    }
    let npoints = block.nnodes();
    let ncells: usize = d.iter().map(|&n| (n - 1).max(1)).product();
    check_arrays("point", point_data, npoints).map_err(bad)?;
    check_arrays("cell", cell_data, ncells).map_err(bad)?;

    // Appended layout: point data, cell data, points; each array = u64 byte count + data.
    let mut offset = 0u64;
    let mut next = |len: usize| {
        let o = offset;
        offset += 8 + 8 * len as u64;
        o
    };
    let extent = format!("0 {} 0 {} 0 {}", d[0] - 1, d[1] - 1, d[2] - 1);
    let mut xml = String::new();
    xml.push_str("<?xml version=\"1.0\"?>\n");
    xml.push_str(
        "<VTKFile type=\"StructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
    );
    xml.push_str(&format!("  <StructuredGrid WholeExtent=\"{extent}\">\n"));
    xml.push_str(&format!("    <Piece Extent=\"{extent}\">\n"));
    for (tag, arrays) in [("PointData", point_data), ("CellData", cell_data)] {
        xml.push_str(&format!("      <{tag}>\n"));
        for (name, v) in arrays {
            xml.push_str(&format!(
                "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"1\" format=\"appended\" offset=\"{}\"/>\n",
                escape(name),
                next(v.len())
            ));
        }
        xml.push_str(&format!("      </{tag}>\n"));
    }
    xml.push_str("      <Points>\n");
    xml.push_str(&format!(
        "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" offset=\"{}\"/>\n",
        next(3 * npoints)
    ));
    xml.push_str("      </Points>\n    </Piece>\n  </StructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _");

    write_atomic(path, |w| {
        w.write_all(xml.as_bytes())?;
        for (_, v) in point_data.iter().chain(cell_data) {
            write_f64s(w, v.iter().copied(), v.len())?;
        }
        let c = |k: usize| {
            if k < block.ncoords() {
                block.coord(k)
            } else {
                &[][..]
            }
        };
        let (x, y, z) = (c(0), c(1), c(2));
        let pts = (0..npoints).flat_map(|p| [x[p], y[p], z.get(p).copied().unwrap_or(0.0)]);
        write_f64s(w, pts, 3 * npoints)?;
        w.write_all(b"\n  </AppendedData>\n</VTKFile>\n")
    })
}

/// Writes a `.vtm` multi-block index, atomically: one DataSet per `(name, file)` piece.
///
/// Files are stored relative to the directory of `path` when they lie below it (relative paths
/// are taken as relative to that directory already); other absolute paths are kept as they are.
pub fn write_vtm(path: &Path, pieces: &[(String, PathBuf)]) -> Result<()> {
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut xml = String::new();
    xml.push_str("<?xml version=\"1.0\"?>\n");
    xml.push_str(
        "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
    );
    xml.push_str("  <vtkMultiBlockDataSet>\n");
    for (i, (name, file)) in pieces.iter().enumerate() {
        let rel = if dir.as_os_str().is_empty() {
            file.as_path()
        } else {
            file.strip_prefix(dir).unwrap_or(file)
        };
        let Some(rel) = rel.to_str() else {
            let msg = format!(
                "piece '{name}': file name {} is not valid UTF-8",
                file.display()
            );
            return Err(Error::input(path.display().to_string(), msg));
        };
        let rel = rel.replace('\\', "/");
        xml.push_str(&format!(
            "    <DataSet index=\"{i}\" name=\"{}\" file=\"{}\"/>\n",
            escape(name),
            escape(&rel)
        ));
    }
    xml.push_str("  </vtkMultiBlockDataSet>\n</VTKFile>\n");
    write_atomic(path, |w| w.write_all(xml.as_bytes()))
}

/// Checks names and lengths of data arrays.
fn check_arrays(
    kind: &str,
    arrays: &[(&str, &[f64])],
    want: usize,
) -> std::result::Result<(), String> {
    for (k, (name, v)) in arrays.iter().enumerate() {
        if name.is_empty() {
            return Err(format!("{kind} data array {} has an empty name", k + 1));
        }
        if arrays[..k].iter().any(|(n, _)| n == name) {
            return Err(format!("{kind} data array '{name}' appears twice"));
        }
        if v.len() != want {
            return Err(format!(
                "{kind} data array '{name}' has {} values, the block has {want} {kind}s",
                v.len()
            ));
        }
    }
    Ok(())
}

/// One appended array: u64 byte count, then the values, little endian.
fn write_f64s(w: &mut dyn Write, v: impl Iterator<Item = f64>, len: usize) -> std::io::Result<()> {
    w.write_all(&(8 * len as u64).to_le_bytes())?;
    let mut buf = Vec::with_capacity(8 * 4096);
    for x in v {
        buf.extend_from_slice(&x.to_le_bytes());
        if buf.len() >= 8 * 4096 {
            w.write_all(&buf)?;
            buf.clear();
        }
    }
    w.write_all(&buf)
}

/// Escapes text for an XML attribute value.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Grid2, Grid3};

    /// Header text and named appended arrays (name, values) of a `.vts` file, checking framing.
    fn parse_vts(bytes: &[u8]) -> (String, Vec<(String, Vec<f64>)>) {
        let tag = b"<AppendedData encoding=\"raw\">";
        let start = bytes.windows(tag.len()).position(|w| w == tag).unwrap();
        let us = start + bytes[start..].iter().position(|&b| b == b'_').unwrap();
        let header = String::from_utf8(bytes[..us].to_vec()).unwrap();
        let data = &bytes[us + 1..];
        let mut arrays = Vec::new();
        let mut end = 0;
        for el in header.split("<DataArray").skip(1) {
            let attr = |a: &str| {
                el.split(&format!("{a}=\""))
                    .nth(1)
                    .unwrap()
                    .split('"')
                    .next()
                    .unwrap()
                    .to_string()
            };
            let off: usize = attr("offset").parse().unwrap();
            assert_eq!(attr("type"), "Float64");
            let n = u64::from_le_bytes(data[off..off + 8].try_into().unwrap()) as usize;
            let v = data[off + 8..off + 8 + n]
                .chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap()));
            arrays.push((attr("Name"), v.collect()));
            end = end.max(off + 8 + n);
        }
        assert_eq!(&data[end..], b"\n  </AppendedData>\n</VTKFile>\n");
        (header, arrays)
    }

    #[test]
    fn volume_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("v.vts");
        let g = Grid3::from_coords(
            3,
            4,
            2,
            std::array::from_fn(|c| (0..24).map(|p| (p * (c + 2)) as f64 / 7.0).collect()),
        );
        let block = Block::Volume(g.clone());
        let dist: Vec<f64> = (0..24).map(|p| p as f64 * 0.1).collect();
        let skew: Vec<f64> = (0..6).map(|p| -(p as f64) / 3.0).collect();
        write_vts(
            &path,
            &block,
            &[("skew", &skew)],
            &[("wall <distance> & \"more\"", &dist)],
        )
        .unwrap();
        let (header, arrays) = parse_vts(&std::fs::read(&path).unwrap());
        assert!(header.contains(r#"<VTKFile type="StructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#));
        assert!(header.contains(r#"<StructuredGrid WholeExtent="0 2 0 3 0 1">"#));
        assert!(header.contains(r#"<Piece Extent="0 2 0 3 0 1">"#));
        let names: Vec<&str> = arrays.iter().map(|a| a.0.as_str()).collect();
        assert_eq!(
            names,
            [
                "wall &lt;distance&gt; &amp; &quot;more&quot;",
                "skew",
                "Points"
            ]
        );
        assert_eq!(arrays[0].1, dist);
        assert_eq!(arrays[1].1, skew);
        let pts: Vec<f64> = (0..24)
            .flat_map(|p| [g.coord(0)[p], g.coord(1)[p], g.coord(2)[p]])
            .collect();
        assert_eq!(arrays[2].1, pts);
    }

    #[test]
    fn planar_gets_zero_z_and_cell_count_rules() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p.vts");
        let block = Block::Planar(Grid2::from_fn(3, 2, |i, j| [i as f64, j as f64 + 0.5]));
        write_vts(&path, &block, &[("area", &[1.0, 2.0])], &[]).unwrap();
        let (header, arrays) = parse_vts(&std::fs::read(&path).unwrap());
        assert!(header.contains(r#"WholeExtent="0 2 0 1 0 0""#));
        assert_eq!(
            arrays[1].1,
            [
                0.0, 0.5, 0.0, 1.0, 0.5, 0.0, 2.0, 0.5, 0.0, 0.0, 1.5, 0.0, 1.0, 1.5, 0.0, 2.0,
                1.5, 0.0
            ]
        );

        // A line of nodes (nj = 1) still has max(nj−1, 1) = 1 cell row.
        let line = Block::Surface(Grid2::zeros(4, 1));
        write_vts(&path, &line, &[("q", &[0.0; 3])], &[]).unwrap();

        type Arrays<'a> = &'a [(&'a str, &'a [f64])];
        let bad: [(Arrays, Arrays, &str); 4] = [
            (
                &[("area", &[1.0])],
                &[],
                "'area' has 1 values, the block has 2 cells",
            ),
            (
                &[],
                &[("d", &[0.0; 5])],
                "'d' has 5 values, the block has 6 points",
            ),
            (&[("", &[1.0, 2.0])], &[], "empty name"),
            (
                &[("a", &[1.0, 2.0]), ("a", &[1.0, 2.0])],
                &[],
                "'a' appears twice",
            ),
        ];
        let path = dir.path().join("bad.vts");
        for (cells, points, want) in bad {
            let e = write_vts(&path, &block, cells, points)
                .unwrap_err()
                .to_string();
            assert!(
                e.contains(want) && e.contains("bad.vts"),
                "expected '{want}' in: {e}"
            );
            assert!(!path.exists());
        }
    }

    #[test]
    fn vtm_lists_relative_files() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("case.vtm");
        let pieces = vec![
            (
                "inner".to_string(),
                dir.path().join("case").join("inner.vts"),
            ),
            ("outer & far".to_string(), PathBuf::from("case/outer.vts")),
            ("elsewhere".to_string(), PathBuf::from("/data/x.vts")),
        ];
        write_vtm(&path, &pieces).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.contains(r#"<VTKFile type="vtkMultiBlockDataSet" version="1.0""#),
            "{text}"
        );
        assert!(
            text.contains(r#"<DataSet index="0" name="inner" file="case/inner.vts"/>"#),
            "{text}"
        );
        assert!(
            text.contains(r#"<DataSet index="1" name="outer &amp; far" file="case/outer.vts"/>"#),
            "{text}"
        );
        assert!(
            text.contains(r#"<DataSet index="2" name="elsewhere" file="/data/x.vts"/>"#),
            "{text}"
        );
        assert!(text.trim_end().ends_with("</VTKFile>"));
    }
}
