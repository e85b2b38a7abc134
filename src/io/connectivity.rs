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
//! 1                          optional: boundary conditions given explicitly (`bc =`)
//!   1 wall                     family id and kind (wall, symmetry, farfield, inflow,
//!                              outflow, general); other families: by their names
//! ```
//! Indices are 1-based and k is 1 for 2D blocks. Side a runs with growing indices; side b's
//! range runs from the node that matches a's first node to the one that matches its last, so a
//! reversed interface has b's first index above its last. Interfaces and patches together
//! cover every block side.

use crate::grid::faces::{block_node, face_dims};
use crate::grid::matching::{Side, SideMatch};
use crate::grid::topology::volume::{Topology3, VolumeSide};
use crate::grid::topology::{SideRange, Topology};
use crate::grid::Edge;
use crate::io::write_atomic;
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
    /// Boundary conditions given explicitly, by family id; other families get the one
    /// their name suggests ([`BcKind::of`]).
    pub bcs: Vec<(usize, BcKind)>,
}

impl ConnFile {
    /// The boundary condition of family `id` (named `name`): explicit, else by its name.
    pub fn bc(&self, id: usize, name: &str) -> BcKind {
        self.bcs
            .iter()
            .find(|b| b.0 == id)
            .map_or_else(|| BcKind::of(name), |b| b.1)
    }
}

/// One side range: 1-based block, first node, last node.
pub type Range = (usize, [usize; 3], [usize; 3]);

/// Largest count, index or family id a connectivity file may hold: 2³¹ (the most nodes a job
/// may have, [`crate::case::limits::MAX_NODES`]).
pub const MAX_INDEX: usize = 1 << 31;

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
    // explicit boundary conditions (one per family: the case checked it)
    for (id, fam) in &out.families {
        let given = c
            .patches
            .iter()
            .filter(|p| &p.family == fam)
            .find_map(|p| topo.edges[p.edge].bc.as_deref().and_then(BcKind::parse));
        if let Some(kind) = given {
            out.bcs.push((*id, kind));
        }
    }
    out
}

/// The connectivity of a volume topology as a file holds it: per interface face, side a the
/// face in its first volume with growing indices, side b the same face in the second volume
/// from the node matching a's first node to the one matching its last; per boundary face, its
/// range and family (numbered in order of first use).
pub fn from_topology3(topo: &Topology3) -> ConnFile {
    let c = topo.connectivity();
    let mut families: Vec<String> = Vec::new();
    for p in &c.patches {
        if !families.contains(&p.family) {
            families.push(p.family.clone());
        }
    }
    let one = |v: usize, from: [usize; 3], to: [usize; 3]| -> Range {
        (v + 1, from.map(|x| x + 1), to.map(|x| x + 1))
    };
    // The block nodes of the volume-face corners (0, 0) and (end, end) of side s.
    let span = |s: VolumeSide| {
        let dims = topo.volumes[s.volume].dims;
        let [na, nb] = face_dims(s.side, dims);
        (
            block_node(s.side, 0, 0, dims),
            block_node(s.side, na - 1, nb - 1, dims),
        )
    };
    let mut out = ConnFile::default();
    for f in &c.interfaces {
        let (a0, a1) = span(f.a);
        // The face nodes (p, q) at a's corners, then where b has them.
        let ua = topo.volumes[f.a.volume].faces[f.a.side];
        let fd = topo.face_dims(f.face);
        let [na, nb] = face_dims(f.a.side, topo.volumes[f.a.volume].dims);
        let [p0, q0] = ua.orient.face_node(0, 0, fd);
        let [p1, q1] = ua.orient.face_node(na - 1, nb - 1, fd);
        let b0 = topo.volume_node(f.b.volume, f.b.side, p0, q0);
        let b1 = topo.volume_node(f.b.volume, f.b.side, p1, q1);
        out.interfaces
            .push([one(f.a.volume, a0, a1), one(f.b.volume, b0, b1)]);
    }
    for p in &c.patches {
        let (lo, hi) = span(p.side);
        let id = 1 + families.iter().position(|f| f == &p.family).unwrap_or(0);
        out.patches.push((one(p.side.volume, lo, hi), id));
    }
    out.families = families
        .into_iter()
        .enumerate()
        .map(|(k, f)| (k + 1, f))
        .collect();
    // explicit boundary conditions (one per family: the case checked it)
    for (id, fam) in &out.families {
        let given = c
            .patches
            .iter()
            .filter(|p| &p.family == fam)
            .find_map(|p| topo.bcs[p.face].as_deref().and_then(BcKind::parse));
        if let Some(kind) = given {
            out.bcs.push((*id, kind));
        }
    }
    out
}

/// Relative tolerance (of the blocks' box diagonal) within which block sides gridded apart
/// count as the same nodes ([`of_surface_blocks`]).
pub const MATCH_TOLERANCE: f64 = 1e-9;

/// The connectivity of surface blocks gridded apart (a STEP file's face blocks, blocks on a
/// STEP model): interfaces where sides coincide node for node within [`MATCH_TOLERANCE`] of
/// the blocks' diagonal, every other side a patch of the family `family(name)` of its block.
/// Other blocks are left out.
pub fn of_surface_blocks(
    blocks: &[(String, crate::io::Block)],
    family: impl Fn(&str) -> String,
) -> ConnFile {
    let (grids, families): (Vec<&crate::grid::Grid2<3>>, Vec<String>) = blocks
        .iter()
        .filter_map(|(name, b)| match b {
            crate::io::Block::Surface(g) => Some((g, family(name))),
            _ => None,
        })
        .unzip();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for g in &grids {
        for (c, x) in g.coords().iter().enumerate() {
            for v in x {
                lo[c] = lo[c].min(*v);
                hi[c] = hi[c].max(*v);
            }
        }
    }
    let diag = (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
    let matches = crate::grid::matching::matching_sides(&grids, MATCH_TOLERANCE * diag);
    let dims: Vec<[usize; 2]> = grids.iter().map(|g| [g.ni(), g.nj()]).collect();
    from_matches(&dims, &matches, &families)
}

/// The connectivity of 2D blocks gridded apart, from the pairs of their sides that coincide
/// ([`crate::grid::matching::matching_sides`]): those are the interfaces, every other side a
/// patch of its block's family `family[block]` (families numbered in order of first use).
/// `dims[block]` = (ni, nj).
pub fn from_matches(dims: &[[usize; 2]], matches: &[SideMatch], family: &[String]) -> ConnFile {
    // The 1-based range of side e of block b, from its first node to its last.
    let range = |(b, e): Side| -> Range {
        let [ni, nj] = dims[b];
        let (from, to) = match e {
            Edge::E1 => ([1, 1, 1], [1, nj, 1]),
            Edge::E2 => ([ni, 1, 1], [ni, nj, 1]),
            Edge::E3 => ([1, 1, 1], [ni, 1, 1]),
            Edge::E4 => ([1, nj, 1], [ni, nj, 1]),
        };
        (b + 1, from, to)
    };
    let mut out = ConnFile::default();
    let mut paired = std::collections::HashSet::new();
    for m in matches {
        let b = range(m.b);
        let b = if m.reversed { (b.0, b.2, b.1) } else { b };
        out.interfaces.push([range(m.a), b]);
        paired.insert(m.a);
        paired.insert(m.b);
    }
    let mut families: Vec<String> = Vec::new();
    for (b, _) in dims.iter().enumerate() {
        for e in Edge::ALL {
            if paired.contains(&(b, e)) {
                continue;
            }
            let name = &family[b];
            let id = match families.iter().position(|f| f == name) {
                Some(k) => k + 1,
                None => {
                    families.push(name.clone());
                    families.len()
                }
            };
            out.patches.push((range((b, e)), id));
        }
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
        if !c.bcs.is_empty() {
            writeln!(w, "{}", c.bcs.len())?;
            for (k, bc) in &c.bcs {
                writeln!(w, "{k:4} {}", bc.name())?;
            }
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
    // optional: boundary conditions given explicitly, "family-id kind" per line
    if let Some((k, l)) = lines.next() {
        let n: usize = l
            .trim()
            .parse()
            .map_err(|_| bad(k, "after the families: the count of boundary conditions"))?;
        for _ in 0..n {
            let (k, l) = lines
                .next()
                .ok_or_else(|| bad(usize::MAX - 1, "ends before a boundary condition"))?;
            let v: Vec<&str> = l.split_whitespace().collect();
            let id = v.first().and_then(|s| s.parse::<usize>().ok());
            let kind = v.get(1).and_then(|s| BcKind::parse(s));
            match (id, kind, v.len()) {
                (Some(id), Some(kind), 2) if c.families.iter().any(|f| f.0 == id) => {
                    c.bcs.push((id, kind))
                }
                (Some(id), Some(_), 2) => {
                    return Err(bad(
                        k,
                        &format!("boundary condition of family {id}, which is not listed"),
                    ))
                }
                _ => {
                    return Err(bad(
                        k,
                        &format!(
                            "a boundary condition line is a family id and one of {}",
                            BC_NAMES.join(", ")
                        ),
                    ))
                }
            }
        }
    }
    Ok(c)
}

/// Family of the two sides of an extruded planar grid.
pub const FRONT_AND_BACK: &str = "frontAndBack";

/// The kind of boundary condition of a family, for formats that type their patches
/// (OpenFOAM's `wall`, CGNS's `BCWall`, …): given in the case file (`bc = "wall"` on an
/// edge) or suggested by the family's name ([`BcKind::of`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BcKind {
    /// A solid surface: the name holds `wall`, `airfoil`, `wing`, `body`, `fuselage`, `flap`,
    /// `slat`, `main`, `blade`, `hull`, `pylon` or `nacelle`.
    Wall,
    /// The name holds `sym`.
    Symmetry,
    /// The name holds `far`.
    Farfield,
    /// The name holds `inflow` or `inlet`.
    Inflow,
    /// The name holds `outflow` or `outlet`.
    Outflow,
    /// The two sides of an extruded planar grid ([`FRONT_AND_BACK`]).
    Empty,
    /// Anything else (`bc = "general"`).
    Other,
}

/// The names `bc =` takes, in the order of [`BcKind::NAMED`].
pub const BC_NAMES: [&str; 6] = [
    "wall", "symmetry", "farfield", "inflow", "outflow", "general",
];

impl BcKind {
    /// The kinds a case file or `.conn` file can name.
    pub const NAMED: [BcKind; 6] = [
        BcKind::Wall,
        BcKind::Symmetry,
        BcKind::Farfield,
        BcKind::Inflow,
        BcKind::Outflow,
        BcKind::Other,
    ];

    /// The kind named `s` (one of [`BC_NAMES`]).
    pub fn parse(s: &str) -> Option<BcKind> {
        BC_NAMES
            .iter()
            .position(|n| *n == s)
            .map(|k| BcKind::NAMED[k])
    }

    /// The name [`BcKind::parse`] reads (`empty` for the extrusion's sides).
    pub fn name(self) -> &'static str {
        match BcKind::NAMED.iter().position(|k| *k == self) {
            Some(k) => BC_NAMES[k],
            None => "empty",
        }
    }

    /// The kind a family name suggests (case-insensitive).
    pub fn of(family: &str) -> BcKind {
        if family == FRONT_AND_BACK {
            return BcKind::Empty;
        }
        let f = family.to_ascii_lowercase();
        let has = |words: &[&str]| words.iter().any(|w| f.contains(w));
        if has(&[
            "wall", "airfoil", "wing", "body", "fuselage", "flap", "slat", "main", "blade", "hull",
            "pylon", "nacelle",
        ]) {
            BcKind::Wall
        } else if has(&["sym"]) {
            BcKind::Symmetry
        } else if has(&["far"]) {
            BcKind::Farfield
        } else if has(&["inflow", "inlet"]) {
            BcKind::Inflow
        } else if has(&["outflow", "outlet"]) {
            BcKind::Outflow
        } else {
            BcKind::Other
        }
    }
}
