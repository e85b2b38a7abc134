//! Formatted (ASCII) Plot3D reading with autodetection from the counts of values.
//!
//! Values are separated by white space or commas; Fortran list-directed repeat counts (`3*0.0`),
//! `D` exponents and exponents without letter (`1.0-100`) are accepted. Header values (block
//! count, dimensions) must be plain integers ≥ 1. The layout is the first of multi-block 3D,
//! multi-block 2D, single-block 3D, single-block 2D — each without, then with IBLANK — whose
//! header is valid and whose value count equals the number of values in the file exactly (and
//! whose values then parse). Since no precision or byte order is stored, `Double` and `Little`
//! are reported.

use crate::io::plot3d::{node, ByteOrder, Encoding, Parsed, Plot3dFormat, Precision, RawBlock};

type Res<T> = std::result::Result<T, String>;

/// Reading the whole text as the first matching layout.
pub(super) fn parse(text: &str) -> Res<Parsed> {
    let total = count(text)?;
    let mut first_err = None;
    let mut tried = Vec::new();
    for (multi, two_d) in [(true, false), (true, true), (false, false), (false, true)] {
        let nd = if two_d { 2 } else { 3 };
        let Some((dims, hdr)) = header(text, total, multi, nd) else {
            continue;
        };
        for ib in [false, true] {
            let want = dims.iter().try_fold(hdr, |acc, d| {
                let n = d[0].checked_mul(d[1])?.checked_mul(d[2])?;
                acc.checked_add(n.checked_mul(nd + ib as usize)?)
            });
            if want == Some(total) {
                let format = Plot3dFormat {
                    encoding: Encoding::Formatted,
                    precision: Precision::Double,
                    byte_order: ByteOrder::Little,
                    multi_block: multi,
                    two_d,
                    iblank: ib,
                };
                match values(text, hdr, &dims, nd, ib) {
                    Ok(blocks) => return Ok(Parsed { format, blocks }),
                    Err(e) => {
                        first_err.get_or_insert(format!("read as {format}: {e}"));
                    }
                }
            }
            let want = want.map_or("more than usize::MAX".into(), |n| n.to_string());
            tried.push(format!(
                "{}-block {}D{}: {want}",
                if multi { "multi" } else { "single" },
                nd,
                if ib { " with IBLANK" } else { "" }
            ));
        }
    }
    Err(first_err.unwrap_or_else(|| {
        let hint = if tried.is_empty() {
            "no layout has a valid header (block count and dimensions must be integers ≥ 1)"
                .to_string()
        } else {
            format!("expected values by layout: {}", tried.join("; "))
        };
        format!("formatted file with {total} values fits no Plot3D layout; {hint}")
    }))
}

/// Whitespace/comma separated tokens.
struct Tokens<'a> {
    s: &'a str,
}

impl<'a> Iterator for Tokens<'a> {
    type Item = &'a str;
    fn next(&mut self) -> Option<&'a str> {
        let sep = |c: char| c.is_ascii_whitespace() || c == ',';
        let s = self.s.trim_start_matches(sep);
        let end = s.find(sep).unwrap_or(s.len());
        self.s = &s[end..];
        (end > 0).then(|| &s[..end])
    }
}

/// Logical values: tokens with repeat counts expanded; yields (value text, 0-based index).
struct Values<'a> {
    toks: Tokens<'a>,
    cur: &'a str,
    left: u64,
    index: usize,
}

impl<'a> Values<'a> {
    fn new(text: &'a str) -> Self {
        Values {
            toks: Tokens { s: text },
            cur: "",
            left: 0,
            index: 0,
        }
    }

    /// The next value; `Ok(None)` at the end of the text.
    fn next(&mut self) -> Res<Option<(&'a str, usize)>> {
        if self.left == 0 {
            let Some(t) = self.toks.next() else {
                return Ok(None);
            };
            (self.cur, self.left) = split_repeat(t)?;
        }
        self.left -= 1;
        self.index += 1;
        Ok(Some((self.cur, self.index - 1)))
    }

    /// The next value, which must exist.
    fn need(&mut self, what: impl FnOnce() -> String) -> Res<(&'a str, usize)> {
        self.next()?
            .ok_or_else(|| format!("{}: unexpected end of file", what()))
    }
}

/// Splits a Fortran repeat token `r*value` into (value, r); other tokens repeat once.
fn split_repeat(t: &str) -> Res<(&str, u64)> {
    match t.split_once('*') {
        None => Ok((t, 1)),
        Some((r, v)) => match r.parse::<u64>() {
            Ok(r) if r >= 1 && !v.is_empty() && !v.contains('*') => Ok((v, r)),
            _ => Err(format!("malformed value or repeat count '{t}'")),
        },
    }
}

/// Number of values in the text, checked against the file size so that repeat counts cannot
/// make the reader allocate without bound.
fn count(text: &str) -> Res<usize> {
    let mut total: u64 = 0;
    for t in (Tokens { s: text }) {
        total = total.saturating_add(split_repeat(t)?.1);
    }
    let limit = 64 * text.len() as u64 + (1 << 20);
    if total > limit {
        return Err(format!(
            "repeat counts expand to {total} values, implausibly many for a file of {} bytes",
            text.len()
        ));
    }
    if total == 0 {
        return Err("formatted file without values".into());
    }
    Ok(total as usize)
}

/// A plain integer ≥ 1 that fits an int32 (block counts and dimensions).
fn count_value(t: &str) -> Option<usize> {
    t.parse::<i32>()
        .ok()
        .filter(|&n| n >= 1)
        .map(|n| n as usize)
}

/// Block dimensions and the number of header values when the text is read as `(multi, nd)`.
fn header(text: &str, total: usize, multi: bool, nd: usize) -> Option<(Vec<[usize; 3]>, usize)> {
    let mut v = Values::new(text);
    let mut int = || v.next().ok().flatten().and_then(|(t, _)| count_value(t));
    let nb = if multi { int()? } else { 1 };
    let hdr = multi as usize + nd * nb;
    if hdr > total {
        return None;
    }
    let mut dims = Vec::with_capacity(nb);
    for _ in 0..nb {
        let mut d = [1; 3];
        for x in d.iter_mut().take(nd) {
            *x = int()?;
        }
        dims.push(d);
    }
    Some((dims, hdr))
}

/// Parses a real; accepts Fortran `D` exponents and exponents without letter (`1.0-100`).
fn real(t: &str) -> Option<f64> {
    if let Ok(x) = t.parse() {
        return Some(x);
    }
    let s = t.replace(['d', 'D'], "e");
    if let Ok(x) = s.parse() {
        return Some(x);
    }
    let p = s
        .rfind(['+', '-'])
        .filter(|&p| p > 0 && !s.contains(['e', 'E']))?;
    format!("{}e{}", &s[..p], &s[p..]).parse().ok()
}

/// The blocks' values after `hdr` header values (the count has been checked).
fn values(text: &str, hdr: usize, dims: &[[usize; 3]], nd: usize, ib: bool) -> Res<Vec<RawBlock>> {
    let mut v = Values::new(text);
    for _ in 0..hdr {
        v.next()?;
    }
    let nb = dims.len();
    let mut blocks = Vec::with_capacity(nb);
    for (b, &d) in dims.iter().enumerate() {
        let n = d[0] * d[1] * d[2];
        let at = |what: &str, p: usize| {
            format!("block {} of {nb}, {what} at node {}", b + 1, node(d, p))
        };
        let mut coords = Vec::with_capacity(nd);
        for name in ["x", "y", "z"].iter().take(nd) {
            let mut x = Vec::with_capacity(n);
            for p in 0..n {
                let (t, i) = v.need(|| at(name, p))?;
                let bad = || format!("{} (value {}): '{t}' is not a number", at(name, p), i + 1);
                x.push(real(t).ok_or_else(bad)?);
            }
            coords.push(x);
        }
        let iblank = if ib {
            let mut m = Vec::with_capacity(n);
            for p in 0..n {
                let (t, i) = v.need(|| at("IBLANK", p))?;
                let bad = |_| {
                    format!(
                        "{} (value {}): '{t}' is not an integer",
                        at("IBLANK", p),
                        i + 1
                    )
                };
                m.push(t.parse::<i32>().map_err(bad)?);
            }
            Some(m)
        } else {
            None
        };
        blocks.push(RawBlock {
            dims: d,
            coords,
            iblank,
        });
    }
    Ok(blocks)
}
