//! The connectivity file of a multi-block grid (`.conn`): NASA Glenn-HT's `.ght_conn` layout
//! (what NASA's `plot3d` Python tools write and read), followed by the family names.
//!
//! ```text
//! 3                          interfaces (1-to-1), two lines each:
//!   1   17  1  1   17 33  1    block, (i, j, k) first node, (i, j, k) last node: side a
//!   2    1  1  1    1 33  1    the same for side b; its first node matches a's first node
//! 5                          boundary patches, one line each:
//!   1    1  1  1   17  1  1   1   block, first node, last node, family id
//! 2                          families, one line each:
//!   1 wall                     family id and name (from the case file)
//! ```
//! Indices are 1-based and k is 1 for 2D blocks. Side a runs with growing indices; side b's
//! range runs from the node that matches a's first node to the one that matches its last, so a
//! reversed interface has b's first index above its last. Interfaces and patches together
//! cover every block side.

use crate::grid::topology::{SideRange, Topology};
use crate::io::{write_atomic, Block};
use crate::{Error, Result};
use std::path::Path;

/// A connectivity file as read back: 1-based (block, i, j, k) ranges.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ConnFile {
    /// Per interface, the two sides as (block, first (i, j, k), last (i, j, k)).
    pub interfaces: Vec<[Range; 2]>,
    /// Per patch, its range and family id.
    pub patches: Vec<(Range, usize)>,
    /// Family ids and names.
    pub families: Vec<(usize, String)>,
}

/// One side range: 1-based block, first node, last node.
pub type Range = (usize, [usize; 3], [usize; 3]);

/// Largest count, index or family id a connectivity file may hold: 2³¹ (the most nodes a job
/// may have, [`crate::case::limits::MAX_NODES`]).
pub const MAX_INDEX: usize = 1 << 31;

/// Writes the connectivity of `topo` (atomically); `blocks` are the written grids, in order.
pub fn write(path: &Path, topo: &Topology, blocks: &[(String, Block)]) -> Result<()> {
    if blocks.len() < topo.blocks.len() {
        return Err(Error::input(
            path.display().to_string(),
            "the connectivity needs every block of the topology",
        ));
    }
    write_file(path, &from_topology(topo))
}

/// The connectivity of a topology as a file holds it: side a of each interface with growing
/// indices, b following a's node order; families numbered in order of first use.
pub fn from_topology(topo: &Topology) -> ConnFile {
    let c = topo.connectivity();
    let mut families: Vec<String> = Vec::new();
    for p in &c.patches {
        if !families.contains(&p.family) {
            families.push(p.family.clone());
        }
    }
    let one = |r: &SideRange, from: [usize; 2], to: [usize; 2]| -> Range {
        (
            r.block + 1,
            [from[0] + 1, from[1] + 1, 1],
            [to[0] + 1, to[1] + 1, 1],
        )
    };
    let mut out = ConnFile::default();
    for f in &c.interfaces {
        let (a, b) = (&f.a, &f.b);
        out.interfaces.push(if a.start <= a.end {
            [one(a, a.start, a.end), one(b, b.start, b.end)]
        } else {
            [one(a, a.end, a.start), one(b, b.end, b.start)]
        });
    }
    for p in &c.patches {
        let r = &p.range;
        let (lo, hi) = (r.start.min(r.end), r.start.max(r.end));
        let id = 1 + families.iter().position(|f| f == &p.family).unwrap_or(0);
        out.patches.push((one(r, lo, hi), id));
    }
    out.families = families
        .into_iter()
        .enumerate()
        .map(|(k, f)| (k + 1, f))
        .collect();
    out
}

/// Writes a connectivity file (atomically).
pub fn write_file(path: &Path, c: &ConnFile) -> Result<()> {
    let one = |r: &Range| {
        format!(
            "{:4} {:6} {:6} {:6} {:6} {:6} {:6}",
            r.0, r.1[0], r.1[1], r.1[2], r.2[0], r.2[1], r.2[2]
        )
    };
    write_atomic(path, |w| {
        writeln!(w, "{}", c.interfaces.len())?;
        for [a, b] in &c.interfaces {
            writeln!(w, "{}", one(a))?;
            writeln!(w, "{}", one(b))?;
        }
        writeln!(w, "{}", c.patches.len())?;
        for (r, id) in &c.patches {
            writeln!(w, "{} {id:4}", one(r))?;
        }
        writeln!(w, "{}", c.families.len())?;
        for (k, f) in &c.families {
            writeln!(w, "{k:4} {f}")?;
        }
        Ok(())
    })
}

/// Reads a connectivity file (as [`write`] writes it).
pub fn read(path: &Path) -> Result<ConnFile> {
    parse(&crate::io::read_input_string(path)?, path)
}

/// Parses the text of a connectivity file; `path` names it in messages.
///
/// # Errors
/// [`Error::Format`] naming `path` and the line if the text is malformed.
pub fn parse(text: &str, path: &Path) -> Result<ConnFile> {
    let bad = |line: usize, m: &str| Error::Format {
        path: path.to_path_buf(),
        msg: format!("line {}: {m}", line + 1),
    };
    // the line after the last, for "ends before …"
    let end = text.lines().count();
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    // Every number is a count, a 1-based index or a family id: 1 to MAX_INDEX (counts from
    // 0), so that no later sum or product of them overflows.
    let mut next = |what: &str, len: usize, from: usize| -> Result<Vec<usize>> {
        let (n, l) = lines
            .next()
            .ok_or_else(|| bad(end, &format!("ends before {what}")))?;
        let v: Vec<&str> = l.split_whitespace().collect();
        if v.len() < len {
            return Err(bad(n, &format!("{what}: expected {len} values")));
        }
        v[..len]
            .iter()
            .map(|s| {
                s.parse()
                    .ok()
                    .filter(|k| (from..=MAX_INDEX).contains(k))
                    .ok_or_else(|| {
                        bad(
                            n,
                            &format!("{what}: '{s}' is not an index ({from} to {MAX_INDEX})"),
                        )
                    })
            })
            .collect()
    };
    let range = |v: &[usize]| (v[0], [v[1], v[2], v[3]], [v[4], v[5], v[6]]);
    let mut c = ConnFile::default();
    let n = next("the interface count", 1, 0)?[0];
    for _ in 0..n {
        let a = next("an interface", 7, 1)?;
        let b = next("an interface", 7, 1)?;
        c.interfaces.push([range(&a), range(&b)]);
    }
    let n = next("the patch count", 1, 0)?[0];
    for _ in 0..n {
        let p = next("a patch", 8, 1)?;
        c.patches.push((range(&p), p[7]));
    }
    let n = next("the family count", 1, 0)?[0];
    for _ in 0..n {
        let (k, l) = lines
            .next()
            .ok_or_else(|| bad(end, "ends before a family"))?;
        let mut it = l.split_whitespace();
        let id = it
            .next()
            .and_then(|s| s.parse().ok())
            .filter(|k| (1..=MAX_INDEX).contains(k))
            .ok_or_else(|| {
                bad(
                    k,
                    &format!("a family line starts with its id (1 to {MAX_INDEX})"),
                )
            })?;
        c.families.push((id, it.collect::<Vec<_>>().join(" ")));
    }
    Ok(c)
}
