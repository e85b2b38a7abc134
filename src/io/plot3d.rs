//! Plot3D "whole" grid files in every flavour: Fortran-unformatted, formatted (ASCII) or C
//! stream; single or double precision; either byte order; single- or multi-block; 2D or 3D;
//! with or without IBLANK. Layout (FORMATS.md), multi-block 3D unformatted:
//! `[nblocks]`, `[ni nj nk for each block]`, then one record per block holding x(all) y(all)
//! z(all) (iblank(all)), i fastest. 2D files drop nk and z; single-block files drop `[nblocks]`.
//!
//! [`read_plot3d`] autodetects the flavour the way VTK/ParaView do (see `binary` and `ascii` for
//! the exact rules) and rejects malformed files with a message naming block, record and bytes.

use std::borrow::{Borrow, Cow};
use std::fmt;
use std::io::Write;
use std::path::Path;

use crate::io::{write_atomic, Block};
use crate::{Error, Grid2, Grid3, Result};

mod ascii;
mod binary;
#[cfg(test)]
mod tests;

/// How the values are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Encoding {
    /// Fortran sequential unformatted: records framed by 4-byte byte counts.
    Unformatted,
    /// ASCII, whitespace-separated values.
    Formatted,
    /// C binary stream: the same values without record markers.
    Stream,
}

/// Floating-point width of the coordinates (binary files).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Precision {
    Single,
    Double,
}

impl Encoding {
    /// Parses "unformatted", "formatted" or "stream" (the names case files and the CLI use).
    pub fn parse(name: &str) -> Option<Encoding> {
        match name {
            "unformatted" => Some(Encoding::Unformatted),
            "formatted" => Some(Encoding::Formatted),
            "stream" => Some(Encoding::Stream),
            _ => None,
        }
    }
}

impl Precision {
    /// Parses "single" or "double".
    pub fn parse(name: &str) -> Option<Precision> {
        match name {
            "single" => Some(Precision::Single),
            "double" => Some(Precision::Double),
            _ => None,
        }
    }

    /// Bytes per coordinate value.
    pub fn bytes(self) -> usize {
        match self {
            Precision::Single => 4,
            Precision::Double => 8,
        }
    }
}

/// Byte order of binary files.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ByteOrder {
    Little,
    Big,
}

/// A Plot3D grid-file flavour. For formatted files `byte_order` is irrelevant and `precision`
/// only sets the digits written (single: 9 significant digits of the f32 value, double: 17).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Plot3dFormat {
    pub encoding: Encoding,
    pub precision: Precision,
    pub byte_order: ByteOrder,
    /// Block count record present (`false`: exactly one block, no count).
    pub multi_block: bool,
    /// 2D file: two dimensions and x, y per block (planar blocks only).
    pub two_d: bool,
    /// An int32 IBLANK value per node follows the coordinates of each block.
    pub iblank: bool,
}

impl Default for Plot3dFormat {
    /// Unformatted, double, little-endian, multi-block, 3D, no IBLANK.
    fn default() -> Self {
        Plot3dFormat {
            encoding: Encoding::Unformatted,
            precision: Precision::Double,
            byte_order: ByteOrder::Little,
            multi_block: true,
            two_d: false,
            iblank: false,
        }
    }
}

impl fmt::Display for Plot3dFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let enc = match self.encoding {
            Encoding::Unformatted => "Fortran-unformatted",
            Encoding::Formatted => "formatted (ASCII)",
            Encoding::Stream => "C-stream",
        };
        write!(f, "{enc}")?;
        if self.encoding != Encoding::Formatted {
            let prec = match self.precision {
                Precision::Single => "single",
                Precision::Double => "double",
            };
            let bo = match self.byte_order {
                ByteOrder::Little => "little-endian",
                ByteOrder::Big => "big-endian",
            };
            write!(f, " {prec} precision {bo}")?;
        }
        let mb = if self.multi_block { "multi" } else { "single" };
        let dim = if self.two_d { "2D" } else { "3D" };
        let ib = if self.iblank { "with" } else { "without" };
        write!(f, " {mb}-block {dim} {ib} IBLANK")
    }
}

/// The contents of a Plot3D grid file.
#[derive(Clone, Debug, PartialEq)]
pub struct Plot3dFile {
    /// Planar blocks for 2D files; for 3D files surfaces (nk = 1) and volumes (nk > 1).
    pub blocks: Vec<Block>,
    /// The detected flavour. Formatted files report `Double` and `Little` (not stored in them).
    pub format: Plot3dFormat,
    /// One IBLANK array per block (i fastest) if the file has them.
    pub iblank: Option<Vec<Vec<i32>>>,
}

/// One value array of a record.
enum Item<'a> {
    /// Integers, and how many per line in formatted output.
    Ints(Cow<'a, [i32]>, usize),
    Reals(Cow<'a, [f64]>),
}

/// Writes `blocks` as a Plot3D grid file, atomically.
///
/// With `fmt.two_d` every block must be planar; otherwise planar blocks are written as 3D with
/// z = 0, nk = 1. `iblank` (one array of ni·nj·nk values per block) requires `fmt.iblank`; with
/// `fmt.iblank` and `None` every node gets IBLANK = 1. Non-finite coordinates are refused.
/// `blocks` may be blocks or references to them (nothing is copied).
pub fn write_plot3d<B: Borrow<Block>>(
    path: &Path,
    blocks: &[B],
    fmt: &Plot3dFormat,
    iblank: Option<&[Vec<i32>]>,
) -> Result<()> {
    let records = build_records(blocks, fmt, iblank)
        .map_err(|msg| Error::input(path.display().to_string(), msg))?;
    write_atomic(path, |w| {
        for rec in &records {
            write_record(w, rec, fmt)?;
        }
        Ok(())
    })
}

/// Reads a Plot3D grid file of any flavour, detected from its contents.
pub fn read_plot3d(path: &Path) -> Result<Plot3dFile> {
    parse_plot3d(&crate::io::read_input(path)?, path)
}

/// Parses the contents of a Plot3D grid file of any flavour; `path` names it in messages.
///
/// # Errors
/// [`Error::Format`] naming `path`, the block and the record if the contents are malformed.
pub fn parse_plot3d(data: &[u8], path: &Path) -> Result<Plot3dFile> {
    let parsed = if data.is_empty() {
        Err("empty file".to_string())
    } else if let Some(text) = as_text(data) {
        ascii::parse(text)
    } else {
        binary::parse(data)
    };
    parsed
        .and_then(into_file)
        .map_err(|msg| Error::format(path, msg))
}

/// Validates the blocks and lays out the records of the file.
fn build_records<'a, B: Borrow<Block>>(
    blocks: &'a [B],
    fmt: &Plot3dFormat,
    iblank: Option<&'a [Vec<i32>]>,
) -> std::result::Result<Vec<Vec<Item<'a>>>, String> {
    let nb = blocks.len();
    if nb == 0 {
        return Err("no blocks to write".into());
    }
    if !fmt.multi_block && nb != 1 {
        return Err(format!(
            "the single-block Plot3D format holds one block, got {nb}"
        ));
    }
    match (fmt.iblank, iblank) {
        (false, Some(_)) => return Err("IBLANK values given but the format has no IBLANK".into()),
        (true, Some(ib)) if ib.len() != nb => {
            return Err(format!("{} IBLANK arrays for {nb} blocks", ib.len()))
        }
        _ => {}
    }
    let nd = if fmt.two_d { 2 } else { 3 };
    let mut dims = Vec::with_capacity(nb * nd);
    let mut records = Vec::with_capacity(nb + 2);
    let mut block_recs = Vec::with_capacity(nb);
    for (b, blk) in blocks.iter().map(Borrow::borrow).enumerate() {
        let at = format!("block {} of {nb}", b + 1);
        if fmt.two_d && !matches!(blk, Block::Planar(_)) {
            return Err(format!(
                "{at}: a 2D Plot3D file holds planar blocks, got a {} block",
                blk.kind()
            ));
        }
        let d = blk.dims();
        if d.iter().any(|&n| n == 0 || n > i32::MAX as usize) {
            return Err(format!(
                "{at}: dimensions {}×{}×{} out of range",
                d[0], d[1], d[2]
            ));
        }
        dims.extend(d[..nd].iter().map(|&n| n as i32));
        let n = blk.nnodes();
        let mut items = Vec::with_capacity(nd + 1);
        for (c, axis) in AXES.iter().enumerate().take(nd) {
            let x = if c < blk.ncoords() {
                blk.coord(c)
            } else {
                &[][..]
            };
            if let Some(p) = x.iter().position(|v| !v.is_finite()) {
                let what = format!("coordinate {axis} = {}", x[p]);
                return Err(format!("{at}: {what} at node {} is not finite", node(d, p)));
            }
            if fmt.precision == Precision::Single {
                if let Some(p) = x.iter().position(|&v| !(v as f32).is_finite()) {
                    let what = format!("coordinate {axis} = {:e}", x[p]);
                    return Err(format!(
                        "{at}: {what} at node {} overflows single precision",
                        node(d, p)
                    ));
                }
            }
            items.push(Item::Reals(if x.is_empty() {
                Cow::Owned(vec![0.0; n])
            } else {
                Cow::Borrowed(x)
            }));
        }
        if fmt.iblank {
            let ib = match iblank {
                Some(ib) if ib[b].len() != n => {
                    return Err(format!("{at}: {} IBLANK values for {n} nodes", ib[b].len()))
                }
                Some(ib) => Cow::Borrowed(&ib[b][..]),
                None => Cow::Owned(vec![1; n]),
            };
            items.push(Item::Ints(ib, 10));
        }
        if fmt.encoding == Encoding::Unformatted {
            let len = record_bytes(&items, fmt.precision);
            if len > i32::MAX as u64 {
                return Err(format!(
                    "{at}: coordinate record of {len} bytes exceeds the 2^31−1 bytes a Fortran \
                     record marker can count; use the stream or formatted encoding"
                ));
            }
        }
        block_recs.push(items);
    }
    if fmt.multi_block {
        records.push(vec![Item::Ints(Cow::Owned(vec![nb as i32]), 1)]);
    }
    records.push(vec![Item::Ints(Cow::Owned(dims), nd)]);
    records.extend(block_recs);
    Ok(records)
}

/// Coordinate names for messages.
const AXES: [&str; 3] = ["x", "y", "z"];

/// "(i, j, k)" of linear node index `p` in a block of dimensions `d`, for messages.
fn node(d: [usize; 3], p: usize) -> String {
    let (i, j, k) = (p % d[0], (p / d[0]) % d[1], p / (d[0] * d[1]));
    format!("(i, j, k) = ({i}, {j}, {k}) (0-based)")
}

/// Payload bytes of a binary record.
fn record_bytes(items: &[Item], prec: Precision) -> u64 {
    items
        .iter()
        .map(|it| match it {
            Item::Ints(v, _) => 4 * v.len() as u64,
            Item::Reals(v) => (prec.bytes() * v.len()) as u64,
        })
        .sum()
}

/// Writes one record in the encoding of `fmt`.
fn write_record(w: &mut dyn Write, items: &[Item], fmt: &Plot3dFormat) -> std::io::Result<()> {
    let bo = fmt.byte_order;
    let marker = i32_bytes(record_bytes(items, fmt.precision) as i32, bo);
    if fmt.encoding == Encoding::Unformatted {
        w.write_all(&marker)?;
    }
    for it in items {
        match (fmt.encoding, it) {
            (Encoding::Formatted, Item::Ints(v, per_line)) => {
                for line in v.chunks(*per_line) {
                    let s: Vec<String> = line.iter().map(|n| n.to_string()).collect();
                    writeln!(w, "{}", s.join(" "))?;
                }
            }
            (Encoding::Formatted, Item::Reals(v)) => write_reals_text(w, v, fmt.precision)?,
            (_, Item::Ints(v, _)) => {
                let mut buf = Vec::with_capacity(4 * v.len().min(8192));
                for chunk in v.chunks(8192) {
                    buf.clear();
                    chunk
                        .iter()
                        .for_each(|&n| buf.extend_from_slice(&i32_bytes(n, bo)));
                    w.write_all(&buf)?;
                }
            }
            (_, Item::Reals(v)) => {
                let mut buf = Vec::with_capacity(8 * v.len().min(8192));
                for chunk in v.chunks(8192) {
                    buf.clear();
                    for &x in chunk {
                        match (fmt.precision, bo) {
                            (Precision::Double, ByteOrder::Little) => {
                                buf.extend_from_slice(&x.to_le_bytes())
                            }
                            (Precision::Double, ByteOrder::Big) => {
                                buf.extend_from_slice(&x.to_be_bytes())
                            }
                            (Precision::Single, ByteOrder::Little) => {
                                buf.extend_from_slice(&(x as f32).to_le_bytes())
                            }
                            (Precision::Single, ByteOrder::Big) => {
                                buf.extend_from_slice(&(x as f32).to_be_bytes())
                            }
                        }
                    }
                    w.write_all(&buf)?;
                }
            }
        }
    }
    if fmt.encoding == Encoding::Unformatted {
        w.write_all(&marker)?;
    }
    Ok(())
}

/// ASCII reals, four per line, with enough digits to round-trip exactly (17 significant digits
/// for doubles, 9 for the f32 value in single precision).
fn write_reals_text(w: &mut dyn Write, v: &[f64], prec: Precision) -> std::io::Result<()> {
    for line in v.chunks(4) {
        for &x in line {
            match prec {
                Precision::Double => write!(w, " {x:>24.16e}")?,
                Precision::Single => write!(w, " {:>15.8e}", x as f32)?,
            }
        }
        writeln!(w)?;
    }
    Ok(())
}

fn i32_bytes(n: i32, bo: ByteOrder) -> [u8; 4] {
    match bo {
        ByteOrder::Little => n.to_le_bytes(),
        ByteOrder::Big => n.to_be_bytes(),
    }
}

/// The file as text if every byte is printable ASCII or white space (binary Plot3D files
/// always contain NUL bytes in their small integers).
fn as_text(data: &[u8]) -> Option<&str> {
    let text = data
        .iter()
        .all(|&b| (0x20..0x7f).contains(&b) || matches!(b, b'\t' | b'\n' | b'\r' | 0x0b | 0x0c));
    if text {
        std::str::from_utf8(data).ok()
    } else {
        None
    }
}

/// A block as decoded from a file, before validation.
struct RawBlock {
    /// (ni, nj, nk), nk = 1 for 2D files; all ≥ 1.
    dims: [usize; 3],
    /// 2 or 3 arrays of ni·nj·nk values.
    coords: Vec<Vec<f64>>,
    iblank: Option<Vec<i32>>,
}

/// A decoded file: its flavour and blocks.
struct Parsed {
    format: Plot3dFormat,
    blocks: Vec<RawBlock>,
}

/// Checks coordinates and builds the blocks.
fn into_file(p: Parsed) -> std::result::Result<Plot3dFile, String> {
    let nb = p.blocks.len();
    let mut blocks = Vec::with_capacity(nb);
    let mut iblank = Vec::with_capacity(if p.format.iblank { nb } else { 0 });
    for (b, raw) in p.blocks.into_iter().enumerate() {
        let d = raw.dims;
        for (c, x) in raw.coords.iter().enumerate() {
            if let Some(q) = x.iter().position(|v| !v.is_finite()) {
                return Err(format!(
                    "block {} of {nb}: coordinate {} = {} at node {} is not finite",
                    b + 1,
                    AXES[c],
                    x[q],
                    node(d, q)
                ));
            }
        }
        let mut c = raw.coords.into_iter();
        let mut next = || c.next().unwrap_or_default();
        blocks.push(if p.format.two_d {
            Block::Planar(Grid2::from_coords(d[0], d[1], [next(), next()]))
        } else if d[2] == 1 {
            Block::Surface(Grid2::from_coords(d[0], d[1], [next(), next(), next()]))
        } else {
            Block::Volume(Grid3::from_coords(
                d[0],
                d[1],
                d[2],
                [next(), next(), next()],
            ))
        });
        iblank.extend(raw.iblank);
    }
    Ok(Plot3dFile {
        blocks,
        format: p.format,
        iblank: p.format.iblank.then_some(iblank),
    })
}
