//! Reading VTK XML structured grids back: `.vts` (as [`crate::io::vtk`] writes them, and other
//! uncompressed ones: raw appended or ASCII inline points, Float32 or Float64, either byte order,
//! UInt32 or UInt64 headers) and `.vtm` indexes of such files. Used by `ellipgrid convert` and
//! `ellipgrid plot`, so that every grid format ellipgrid writes with structure can be read again.
//!
//! A block with nk = 1 whose z are all 0 comes back planar (that is how planar blocks are
//! written), other nk = 1 blocks as surfaces, nk > 1 as volumes. Compressed or base64-encoded
//! data are refused with a message.

use std::path::Path;

use crate::io::Block;
use crate::{Error, Grid2, Grid3, Result};

/// Reads one `.vts` file.
pub fn read_vts(path: &Path) -> Result<Block> {
    vts_from_bytes(&crate::io::read_input(path)?, path)
}

/// Parses the contents of a `.vts` file; `path` names it in messages.
///
/// # Errors
/// [`Error::Format`] naming `path` if the contents are malformed.
pub fn vts_from_bytes(bytes: &[u8], path: &Path) -> Result<Block> {
    parse_vts(bytes).map_err(|m| Error::format(path, m))
}

/// Reads a `.vtm` index and every `.vts` it lists (paths relative to the index): (name, block).
pub fn read_vtm(path: &Path) -> Result<Vec<(String, Block)>> {
    let text = crate::io::read_input_string(path)?;
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut out = Vec::new();
    for (k, el) in text.split("<DataSet").skip(1).enumerate() {
        let el = &el[..el.find('>').unwrap_or(el.len())];
        let file = attr(el, "file")
            .ok_or_else(|| Error::format(path, format!("DataSet {} has no file", k + 1)))?;
        let name = attr(el, "name").unwrap_or_else(|| format!("block{}", k + 1));
        // a listed file's error names the index too
        let block = read_vts(&dir.join(file))
            .map_err(|e| Error::format(path, format!("DataSet {} ('{name}'): {e}", k + 1)))?;
        out.push((name, block));
    }
    if out.is_empty() {
        return Err(Error::format(path, "no DataSet with a file in this .vtm"));
    }
    Ok(out)
}

/// The unescaped value of attribute `name` in the tag text `el`.
fn attr(el: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let start = el.find(&key)? + key.len();
    let v = &el[start..start + el[start..].find('"')?];
    Some(
        v.replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&apos;", "'")
            .replace("&amp;", "&"),
    )
}

fn parse_vts(bytes: &[u8]) -> std::result::Result<Block, String> {
    // The XML part ends where raw appended data begin.
    let tag = b"<AppendedData";
    let app = bytes.windows(tag.len()).position(|w| w == tag);
    let xml_end = app.unwrap_or(bytes.len());
    let xml = std::str::from_utf8(&bytes[..xml_end]).map_err(|_| "not UTF-8 XML")?;
    let root = xml
        .find("<VTKFile")
        .ok_or("not a VTK XML file (no <VTKFile>)")?;
    let root_tag = &xml[root..root + xml[root..].find('>').ok_or("truncated <VTKFile>")?];
    if attr(root_tag, "type").as_deref() != Some("StructuredGrid") {
        return Err("not a StructuredGrid (.vts) file".into());
    }
    if attr(root_tag, "compressor").is_some() {
        return Err("compressed VTK data are not supported: write it uncompressed".into());
    }
    let big = attr(root_tag, "byte_order").as_deref() == Some("BigEndian");
    let header64 = attr(root_tag, "header_type").as_deref() == Some("UInt64");
    // The extent of the grid element, after the root (an attribute before it is not ours).
    let ext = root + xml[root..].find(" WholeExtent=").ok_or("no WholeExtent")?;
    let ext: Vec<i64> = attr(&xml[ext..], "WholeExtent")
        .ok_or("bad WholeExtent")?
        .split_whitespace()
        .map(|t| {
            t.parse::<i64>()
                .map_err(|_| format!("bad WholeExtent value '{t}'"))
        })
        .collect::<std::result::Result<_, _>>()?;
    // Each extent's node count, overflow-safe (i64::MIN..i64::MAX must not wrap).
    let count = |a: usize| {
        ext[2 * a + 1]
            .checked_sub(ext[2 * a])
            .filter(|&v| v >= 0)
            .and_then(|v| v.checked_add(1))
            .and_then(|v| usize::try_from(v).ok())
    };
    let d = match (ext.len() == 6).then(|| [0, 1, 2].map(count)) {
        Some([Some(a), Some(b), Some(c)]) => [a, b, c],
        _ => return Err(format!("bad WholeExtent {ext:?}")),
    };
    let n = d[0]
        .checked_mul(d[1])
        .and_then(|v| v.checked_mul(d[2]))
        .filter(|&n| n <= bytes.len())
        .ok_or("WholeExtent larger than the file")?;
    let pts = xml.find("<Points>").ok_or("no <Points>")?;
    let da = pts + xml[pts..].find("<DataArray").ok_or("no Points DataArray")?;
    let da_end = da + xml[da..].find('>').ok_or("truncated DataArray")?;
    let el = &xml[da..da_end];
    let ty = attr(el, "type").ok_or("Points DataArray without type")?;
    let width = match ty.as_str() {
        "Float64" => 8,
        "Float32" => 4,
        t => return Err(format!("Points of type {t}: Float32 or Float64 expected")),
    };
    if attr(el, "NumberOfComponents").as_deref() != Some("3") {
        return Err("Points need NumberOfComponents=\"3\"".into());
    }
    let vals: Vec<f64> = match attr(el, "format").as_deref() {
        Some("ascii") => {
            let body = &xml[da_end + 1..];
            let body = &body[..body.find("</DataArray>").ok_or("unterminated DataArray")?];
            body.split_whitespace()
                .take(3 * n)
                .map(|t| t.parse::<f64>().map_err(|_| format!("bad number '{t}'")))
                .collect::<std::result::Result<_, _>>()?
        }
        Some("appended") => {
            let app = app.ok_or("appended format but no <AppendedData>")?;
            let gt = bytes[app..]
                .iter()
                .position(|&b| b == b'>')
                .ok_or("bad <AppendedData>")?;
            let head = std::str::from_utf8(&bytes[app..app + gt]).unwrap_or("");
            if !head.contains("encoding=\"raw\"") {
                return Err("appended data must be raw (base64 is not supported)".into());
            }
            let us = app
                + bytes[app..]
                    .iter()
                    .position(|&b| b == b'_')
                    .ok_or("no '_' marker")?;
            let off: usize = attr(el, "offset")
                .and_then(|o| o.trim().parse().ok())
                .ok_or("appended DataArray without offset")?;
            let hl = if header64 { 8 } else { 4 };
            let range = (us + 1 + hl)
                .checked_add(off)
                .and_then(|start| Some(start..start.checked_add(3 * n * width)?));
            let data = range
                .and_then(|r| bytes.get(r))
                .ok_or("appended data shorter than the points")?;
            data.chunks_exact(width)
                .map(|c| match (width, big) {
                    (8, false) => f64::from_le_bytes(c.try_into().unwrap()),
                    (8, true) => f64::from_be_bytes(c.try_into().unwrap()),
                    (_, false) => f32::from_le_bytes(c.try_into().unwrap()) as f64,
                    (_, true) => f32::from_be_bytes(c.try_into().unwrap()) as f64,
                })
                .collect()
        }
        f => {
            return Err(format!(
                "Points format {f:?}: ascii or appended (raw) expected"
            ))
        }
    };
    if vals.len() != 3 * n {
        return Err(format!("{} point values for {n} points", vals.len()));
    }
    if let Some(k) = vals.iter().position(|v| !v.is_finite()) {
        return Err(format!(
            "point {} has a non-finite coordinate ({})",
            k / 3,
            vals[k]
        ));
    }
    let c = |k: usize| {
        vals.iter()
            .skip(k)
            .step_by(3)
            .copied()
            .collect::<Vec<f64>>()
    };
    let (x, y, z) = (c(0), c(1), c(2));
    Ok(if d[2] > 1 {
        Block::Volume(Grid3::from_coords(d[0], d[1], d[2], [x, y, z]))
    } else if z.iter().all(|&v| v == 0.0) {
        Block::Planar(Grid2::from_coords(d[0], d[1], [x, y]))
    } else {
        Block::Surface(Grid2::from_coords(d[0], d[1], [x, y, z]))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::vtk::{write_vtm, write_vts};
    use std::path::PathBuf;

    #[test]
    fn vts_and_vtm_round_trip_every_block_kind() {
        let d = tempfile::tempdir().unwrap();
        let p = Block::Planar(Grid2::from_fn(4, 3, |i, j| {
            [i as f64 * 0.3, 1.0 / (j + 1) as f64]
        }));
        let s = Block::Surface(Grid2::from_fn(3, 2, |i, j| {
            [i as f64, j as f64, 0.1 * i as f64]
        }));
        let mut v = Grid3::zeros(2, 3, 4);
        v.set(1, 2, 3, [1.5, -2.0, 1e-300]);
        let v = Block::Volume(v);
        let mut pieces = Vec::new();
        for (k, b) in [&p, &s, &v].into_iter().enumerate() {
            let f = PathBuf::from(format!("b{k}.vts"));
            let cells = vec![0.5; b.dims().iter().map(|&n| (n - 1).max(1)).product()];
            write_vts(&d.path().join(&f), b, &[("q", &cells)], &[]).unwrap();
            assert_eq!(&read_vts(&d.path().join(&f)).unwrap(), b);
            pieces.push((format!("n & {k}"), f));
        }
        write_vtm(&d.path().join("all.vtm"), &pieces).unwrap();
        let all = read_vtm(&d.path().join("all.vtm")).unwrap();
        assert_eq!(all.len(), 3);
        assert_eq!(all[1].0, "n & 1");
        assert_eq!(all[2].1, v);
    }

    #[test]
    fn ascii_float32_and_bad_files() {
        let x = "<?xml version=\"1.0\"?>\n<VTKFile type=\"StructuredGrid\" version=\"0.1\">\
                 <StructuredGrid WholeExtent=\"0 1 0 0 0 0\"><Piece Extent=\"0 1 0 0 0 0\">\
                 <Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\
                 0 0 0 2.5 1 0</DataArray></Points></Piece></StructuredGrid></VTKFile>";
        let b = parse_vts(x.as_bytes()).unwrap();
        assert_eq!(b.coord(0), &[0.0, 2.5]);
        assert!(parse_vts(x.replace("0 1 0 0", "0 5 0 0").as_bytes()).is_err());
        let e = parse_vts(x.replace("version=\"0.1\"", "compressor=\"z\"").as_bytes());
        assert!(e.unwrap_err().contains("compressed"));
        assert!(parse_vts(b"garbage").is_err());
        // Hostile headers: an extent before the root, extents that overflow, an offset that
        // overflows, NaN points; errors, not panics.
        let early = format!("WholeExtent=\"0 1 0 0 0 0\"{x}");
        assert_eq!(parse_vts(early.as_bytes()).unwrap().coord(0), &[0.0, 2.5]);
        assert!(parse_vts(b"WholeExtent=\"0 1\"<VTKFile type=\"StructuredGrid\">").is_err());
        let wide = x.replace(
            "WholeExtent=\"0 1 0 0 0 0\"",
            "WholeExtent=\"-9223372036854775808 9223372036854775807 0 0 0 0\"",
        );
        assert!(parse_vts(wide.as_bytes())
            .unwrap_err()
            .contains("WholeExtent"));
        let nan = x.replace("2.5 1 0<", "nan 1 0<");
        assert!(parse_vts(nan.as_bytes()).unwrap_err().contains("point 1"));
        let d = tempfile::tempdir().unwrap();
        let e = read_vts(&d.path().join("none.vts")).unwrap_err();
        assert!(e.to_string().contains("none.vts"));
    }
}
