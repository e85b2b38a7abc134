//! Binary Plot3D reading with autodetection, as VTK/ParaView's reader does it.
//!
//! Fortran-unformatted is recognised by its first record: marker 4, 8 or 12 (the byte order is
//! the one that gives such a value) repeated after the payload. Then: first record 4 bytes →
//! multi-block; the dimension record is 12·nblocks (3D) or 8·nblocks (2D) bytes long; precision
//! and IBLANK follow from the length of block 1's record (N nodes, d coordinates: d·8·N, d·8·N +
//! 4·N, d·4·N or d·4·N + 4·N bytes), and every later block must have the same.
//!
//! C-stream files carry no lengths, so the flavour is the first of little/big endian ×
//! (multi 3D, multi 2D, single 3D, single 2D) × (double, double + IBLANK, single, single +
//! IBLANK) whose header is valid (counts ≥ 1) and whose total size equals the file size.
//! If a file looks Fortran-unformatted but fails, the stream rules are tried before giving up.

use crate::io::plot3d::{ByteOrder, Encoding, Parsed, Plot3dFormat, Precision, RawBlock};

type Res<T> = std::result::Result<T, String>;

/// Block layouts in order of preference: (multi-block, 2D).
const LAYOUTS: [(bool, bool); 4] = [(true, false), (true, true), (false, false), (false, true)];

/// Per-node data kinds in order of preference: (precision, IBLANK).
const KINDS: [(Precision, bool); 4] = [
    (Precision::Double, false),
    (Precision::Double, true),
    (Precision::Single, false),
    (Precision::Single, true),
];

/// Decodes a binary Plot3D file.
pub(super) fn parse(data: &[u8]) -> Res<Parsed> {
    let Some(bo) = fortran_byte_order(data) else {
        return parse_stream(data).map_err(|e| {
            format!("not a Fortran-unformatted Plot3D file (no record marker 4, 8 or 12 framing the first record) and {e}")
        });
    };
    match parse_fortran(data, bo) {
        Ok(p) => Ok(p),
        Err(e) if fortran_confident(data, bo) => Err(e),
        Err(e) => parse_stream(data).map_err(|_| e),
    }
}

/// True if the start of record 2 also fits Fortran framing: its marker is 12·nblocks or
/// 8·nblocks after a block count, or a valid block-record length after single-block dimensions.
/// A broken file that passes this is reported as Fortran, without trying stream layouts (a
/// truncated Fortran file could otherwise match a stream layout by size).
fn fortran_confident(data: &[u8], bo: ByteOrder) -> bool {
    let m1 = i32_at(data, 0, bo) as usize; // 4, 8 or 12, framed (fortran_byte_order)
    let p = 8 + m1;
    if data.len() < p + 4 {
        return false;
    }
    let m2 = i32_at(data, p, bo);
    let Ok(m2) = usize::try_from(m2) else {
        return false;
    };
    if m1 == 4 {
        let nb = i32_at(data, 4, bo);
        return nb >= 1 && (m2 == 12 * nb as usize || m2 == 8 * nb as usize);
    }
    let v: Vec<i32> = ints(&data[4..4 + m1], bo).collect();
    let nd = m1 / 4;
    dims_from(&v, nd).is_ok_and(|d| {
        KINDS
            .iter()
            .any(|&(pr, ib)| block_bytes(d[0], nd, pr, ib) == Some(m2))
    })
}

fn i32_at(data: &[u8], pos: usize, bo: ByteOrder) -> i32 {
    let b = [data[pos], data[pos + 1], data[pos + 2], data[pos + 3]];
    match bo {
        ByteOrder::Little => i32::from_le_bytes(b),
        ByteOrder::Big => i32::from_be_bytes(b),
    }
}

/// The byte order in which the first record is framed by equal markers of 4, 8 or 12.
fn fortran_byte_order(data: &[u8]) -> Option<ByteOrder> {
    [ByteOrder::Little, ByteOrder::Big].into_iter().find(|&bo| {
        data.len() >= 4 && {
            let m = i32_at(data, 0, bo);
            matches!(m, 4 | 8 | 12)
                && data.len() >= 8 + m as usize
                && i32_at(data, 4 + m as usize, bo) == m
        }
    })
}

/// Sequential reader of Fortran records.
struct Records<'a> {
    data: &'a [u8],
    pos: usize,
    bo: ByteOrder,
    count: usize,
}

impl<'a> Records<'a> {
    /// The payload of the next record; `what` names it in errors.
    fn next(&mut self, what: &str) -> Res<&'a [u8]> {
        self.count += 1;
        let (start, len, r) = (self.pos, self.data.len(), self.count);
        let at = format!("{what} (record {r}, byte {start})");
        if len - start < 4 {
            return Err(format!("{at}: the file ends at byte {len}, expected a 4-byte record marker (truncated file)"));
        }
        let m = i32_at(self.data, start, self.bo);
        if m < 0 {
            return Err(format!("{at}: negative record marker {m} (corrupt file, or gfortran sub-records, which are not supported)"));
        }
        let m = m as usize;
        let avail = len - start - 4;
        if avail < m + 4 {
            return Err(format!(
                "{at}: the record marker announces {m} bytes plus a 4-byte end marker, but only {avail} bytes follow (truncated file)"
            ));
        }
        let end = i32_at(self.data, start + 4 + m, self.bo);
        if end != m as i32 {
            return Err(format!(
                "{at}: end marker {end} at byte {} does not match the start marker {m}",
                start + 4 + m
            ));
        }
        self.pos = start + 8 + m;
        Ok(&self.data[start + 4..start + 4 + m])
    }
}

fn ints(bytes: &[u8], bo: ByteOrder) -> impl Iterator<Item = i32> + '_ {
    bytes.chunks_exact(4).map(move |c| i32_at(c, 0, bo))
}

/// Dimensions of `nb` blocks from `nd` ints each; every count must be at least 1.
fn dims_from(v: &[i32], nd: usize) -> Res<Vec<[usize; 3]>> {
    let nb = v.len() / nd;
    v.chunks_exact(nd)
        .enumerate()
        .map(|(b, d)| {
            let mut out = [1usize; 3];
            for (c, &n) in d.iter().enumerate() {
                if n < 1 {
                    let name = ["ni", "nj", "nk"][c];
                    return Err(format!(
                        "block {} of {nb}: dimension {name} = {n}, must be at least 1",
                        b + 1
                    ));
                }
                out[c] = n as usize;
            }
            Ok(out)
        })
        .collect()
}

/// Bytes of a block's data: N·(nd·P + 4·iblank), None on overflow.
fn block_bytes(d: [usize; 3], nd: usize, prec: Precision, iblank: bool) -> Option<usize> {
    let per_node = nd * prec.bytes() + if iblank { 4 } else { 0 };
    d[0].checked_mul(d[1])?
        .checked_mul(d[2])?
        .checked_mul(per_node)
}

fn parse_fortran(data: &[u8], bo: ByteOrder) -> Res<Parsed> {
    let mut rec = Records {
        data,
        pos: 0,
        bo,
        count: 0,
    };
    let first = rec.next("first record")?;
    let (multi, nd, dims) = match first.len() {
        4 => {
            let nb = i32_at(first, 0, bo);
            if nb < 1 {
                return Err(format!("record 1: block count {nb}, must be at least 1"));
            }
            let drec = rec.next("block-dimension record")?;
            let (nb, len) = (nb as usize, drec.len());
            let nd = if len == 12 * nb {
                3
            } else if len == 8 * nb {
                2
            } else {
                return Err(format!(
                    "record 2 (block dimensions) holds {len} bytes; expected {} (3D) or {} (2D) for {nb} blocks",
                    12 * nb,
                    8 * nb
                ));
            };
            (
                true,
                nd,
                dims_from(&ints(drec, bo).collect::<Vec<_>>(), nd)?,
            )
        }
        n @ (8 | 12) => (
            false,
            n / 4,
            dims_from(&ints(first, bo).collect::<Vec<_>>(), n / 4)?,
        ),
        n => {
            return Err(format!(
                "record 1 holds {n} bytes; expected 4 (block count), 8 or 12 (dimensions)"
            ))
        }
    };
    let nb = dims.len();
    let mut kind = None;
    let mut blocks = Vec::with_capacity(nb);
    for (b, &d) in dims.iter().enumerate() {
        let at = format!("block {} of {nb} ({}×{}×{} nodes)", b + 1, d[0], d[1], d[2]);
        let payload = rec.next(&format!("{at}: coordinate record"))?;
        let r = rec.count;
        let len = payload.len();
        let (prec, ib) = match kind {
            None => {
                let k = KINDS
                    .into_iter()
                    .find(|&(p, i)| block_bytes(d, nd, p, i) == Some(len));
                let Some(k) = k else {
                    let expect: Vec<String> = KINDS
                        .iter()
                        .filter_map(|&(p, i)| {
                            let n = block_bytes(d, nd, p, i)?;
                            Some(format!("{n} ({})", kind_name(p, i)))
                        })
                        .collect();
                    if expect.is_empty() {
                        return Err(format!(
                            "{at}: absurd dimensions: the block would need more than 2^64 bytes \
                             (its coordinate record holds {len} bytes)"
                        ));
                    }
                    return Err(format!(
                        "{at}: coordinate record (record {r}) holds {len} bytes; expected one of {}",
                        expect.join(", ")
                    ));
                };
                kind = Some(k);
                k
            }
            Some((p, i)) => {
                if block_bytes(d, nd, p, i) != Some(len) {
                    let want = block_bytes(d, nd, p, i)
                        .map_or("more than usize::MAX".into(), |n| n.to_string());
                    return Err(format!(
                        "{at}: coordinate record (record {r}) holds {len} bytes; expected {want} ({} as block 1)",
                        kind_name(p, i)
                    ));
                }
                (p, i)
            }
        };
        blocks.push(decode_block(payload, d, nd, prec, ib, bo));
    }
    if rec.pos != data.len() {
        return Err(format!(
            "{} bytes of trailing garbage after the last block (from byte {})",
            data.len() - rec.pos,
            rec.pos
        ));
    }
    let (precision, iblank) = kind.unwrap_or((Precision::Double, false));
    let format = Plot3dFormat {
        encoding: Encoding::Unformatted,
        precision,
        byte_order: bo,
        multi_block: multi,
        two_d: nd == 2,
        iblank,
    };
    Ok(Parsed { format, blocks })
}

fn kind_name(p: Precision, iblank: bool) -> &'static str {
    match (p, iblank) {
        (Precision::Double, false) => "double precision",
        (Precision::Double, true) => "double precision with IBLANK",
        (Precision::Single, false) => "single precision",
        (Precision::Single, true) => "single precision with IBLANK",
    }
}

/// Block dimensions and header length of a stream file read as `(multi, nd)`, if plausible.
fn stream_header(
    data: &[u8],
    bo: ByteOrder,
    multi: bool,
    nd: usize,
) -> Option<(Vec<[usize; 3]>, usize)> {
    let (nb, start) = if multi {
        if data.len() < 4 {
            return None;
        }
        (
            usize::try_from(i32_at(data, 0, bo))
                .ok()
                .filter(|&n| n >= 1)?,
            4,
        )
    } else {
        (1, 0)
    };
    let hdr = start + 4 * nd * nb;
    if hdr > data.len() {
        return None;
    }
    let v: Vec<i32> = ints(&data[start..hdr], bo).collect();
    Some((dims_from(&v, nd).ok()?, hdr))
}

fn parse_stream(data: &[u8]) -> Res<Parsed> {
    for bo in [ByteOrder::Little, ByteOrder::Big] {
        for (multi, two_d) in LAYOUTS {
            let nd = if two_d { 2 } else { 3 };
            let Some((dims, hdr)) = stream_header(data, bo, multi, nd) else {
                continue;
            };
            for (prec, ib) in KINDS {
                let total = dims.iter().try_fold(hdr, |acc, &d| {
                    acc.checked_add(block_bytes(d, nd, prec, ib)?)
                });
                if total != Some(data.len()) {
                    continue;
                }
                let mut pos = hdr;
                let blocks = dims
                    .iter()
                    .map(|&d| {
                        let n = block_bytes(d, nd, prec, ib).unwrap_or(0);
                        pos += n;
                        decode_block(&data[pos - n..pos], d, nd, prec, ib, bo)
                    })
                    .collect();
                let format = Plot3dFormat {
                    encoding: Encoding::Stream,
                    precision: prec,
                    byte_order: bo,
                    multi_block: multi,
                    two_d,
                    iblank: ib,
                };
                return Ok(Parsed { format, blocks });
            }
        }
    }
    Err(format!(
        "no C-stream layout (multi/single block, 2D/3D, single/double precision, with/without IBLANK, \
         either byte order) matches the file size of {} bytes",
        data.len()
    ))
}

/// Decodes a block's data; `bytes` holds exactly N·(nd·P + 4·iblank) bytes.
fn decode_block(
    bytes: &[u8],
    dims: [usize; 3],
    nd: usize,
    prec: Precision,
    ib: bool,
    bo: ByteOrder,
) -> RawBlock {
    let n = dims.iter().product::<usize>();
    let p = prec.bytes();
    let coords = (0..nd)
        .map(|c| {
            let chunk = &bytes[c * n * p..(c + 1) * n * p];
            match (prec, bo) {
                (Precision::Double, ByteOrder::Little) => chunk
                    .chunks_exact(8)
                    .map(|b| f64::from_le_bytes(b.try_into().unwrap_or_default()))
                    .collect(),
                (Precision::Double, ByteOrder::Big) => chunk
                    .chunks_exact(8)
                    .map(|b| f64::from_be_bytes(b.try_into().unwrap_or_default()))
                    .collect(),
                (Precision::Single, ByteOrder::Little) => chunk
                    .chunks_exact(4)
                    .map(|b| f32::from_le_bytes(b.try_into().unwrap_or_default()) as f64)
                    .collect(),
                (Precision::Single, ByteOrder::Big) => chunk
                    .chunks_exact(4)
                    .map(|b| f32::from_be_bytes(b.try_into().unwrap_or_default()) as f64)
                    .collect(),
            }
        })
        .collect();
    let iblank = ib.then(|| ints(&bytes[nd * n * p..], bo).collect());
    RawBlock {
        dims,
        coords,
        iblank,
    }
}
