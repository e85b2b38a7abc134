//! Rewrites of a STEP file's text before truck-stepio reads it, each for an entity form that
//! real CAD systems write and truck-stepio 0.3 loses (the edge or face then disappears, or
//! its curve evaluates to NaN). Each keeps the geometry the file describes:
//! - [`prefer_3d_curves`]: `SURFACE_CURVE`s read through their 3D curve;
//! - [`unnamed_labels`]: a geometric or topological entity whose name is `$` gets `''`
//!   (Rhino 8 writes `AXIS2_PLACEMENT_3D($, …)`; the name is a mandatory label, and the
//!   reader drops the entity and everything built on it);
//! - [`untrim_curves`]: an edge or a swept surface on a `TRIMMED_CURVE` refers to the basis
//!   curve (truck-stepio reads no `TRIMMED_CURVE`: Rhino 8 bounds its circular edges so,
//!   ANSA and Creo the profiles of extrusions; the edge or face was lost);
//! - [`default_ref_directions`]: an `AXIS2_PLACEMENT_3D` without a reference direction gets
//!   ISO 10303-42's default (truck takes (1, 0, 0) always, which is NaN for an axis along x:
//!   CATIA writes such circles);
//! - [`super::units::radian_cone_angles`] (in `units`): a cone's semi-angle in the file's
//!   plane angle unit (Creo, Inventor, Pro/E, UG write degrees) written in radians.
//! - [`empty_lists`]: an empty list given as an attribute becomes `$` (zoo.dev writes
//!   `PRODUCT(…, ())`, at which truck-stepio's tokenizer refuses the whole file);
//! - [`super::complex::complex_order`] (in `complex`): the partial entities of a complex
//!   instance in the byte order of their names (Spatial writes `B_SPLINE_SURFACE(…)` before
//!   `BOUNDED_SURFACE()`, and the reader lost every rational surface so written).

use super::prescan::{code_bytes, references, statements, top_level_args};
use std::borrow::Cow;
use std::collections::HashMap;

/// Makes truck-stepio read every `SURFACE_CURVE` / `SEAM_CURVE` through its 3D curve: with
/// `.PCURVE_S1.` / `.PCURVE_S2.` as the master representation it builds the edge from the
/// pcurve, and fails on surfaces whose point search needs a hint (spheres: "the point is not
/// on surface", the edge is lost) or leaves B-spline pcurves untrimmed. The 3D curve is the
/// same edge within the file's tolerance.
pub(super) fn prefer_3d_curves(text: &str) -> Cow<'_, str> {
    if text.contains(".PCURVE_S1.") || text.contains(".PCURVE_S2.") {
        Cow::Owned(
            text.replace(".PCURVE_S1.", ".CURVE_3D.")
                .replace(".PCURVE_S2.", ".CURVE_3D."),
        )
    } else {
        Cow::Borrowed(text)
    }
}

/// The geometric and topological entity types truck-stepio reads, whose first attribute is
/// the item's mandatory `name` label.
const LABELLED: &[&str] = &[
    "CARTESIAN_POINT",
    "DIRECTION",
    "VECTOR",
    "AXIS1_PLACEMENT",
    "AXIS2_PLACEMENT_2D",
    "AXIS2_PLACEMENT_3D",
    "LINE",
    "POLYLINE",
    "CIRCLE",
    "ELLIPSE",
    "HYPERBOLA",
    "PARABOLA",
    "TRIMMED_CURVE",
    "B_SPLINE_CURVE_WITH_KNOTS",
    "BEZIER_CURVE",
    "QUASI_UNIFORM_CURVE",
    "UNIFORM_CURVE",
    "PCURVE",
    "SURFACE_CURVE",
    "SEAM_CURVE",
    "PLANE",
    "SPHERICAL_SURFACE",
    "CYLINDRICAL_SURFACE",
    "TOROIDAL_SURFACE",
    "CONICAL_SURFACE",
    "B_SPLINE_SURFACE_WITH_KNOTS",
    "UNIFORM_SURFACE",
    "QUASI_UNIFORM_SURFACE",
    "BEZIER_SURFACE",
    "SURFACE_OF_LINEAR_EXTRUSION",
    "SURFACE_OF_REVOLUTION",
    "VERTEX_POINT",
    "EDGE_CURVE",
    "EDGE_LOOP",
    "FACE_BOUND",
    "FACE_OUTER_BOUND",
    "ADVANCED_FACE",
    "FACE_SURFACE",
    "ORIENTED_FACE",
    "CLOSED_SHELL",
    "OPEN_SHELL",
    "ORIENTED_CLOSED_SHELL",
    "MANIFOLD_SOLID_BREP",
];

/// Every entity of [`LABELLED`] type whose name is `$` (unset) gets the empty name `''`;
/// `REPRESENTATION_ITEM($)` in complex instances likewise.
pub(super) fn unnamed_labels(text: &str) -> Cow<'_, str> {
    if !text.contains("($") {
        return Cow::Borrowed(text);
    }
    let mut edits = Vec::new();
    for e in instances(text, LABELLED) {
        let a = top_level_args(&text[e.open..]);
        if let Some(name) = a.first().filter(|n| **n == "$") {
            let at = offset(text, name);
            edits.push((at, at + 1, "''".to_string()));
        }
    }
    let out = apply(text, edits);
    if out.contains("REPRESENTATION_ITEM($)") {
        Cow::Owned(out.replace("REPRESENTATION_ITEM($)", "REPRESENTATION_ITEM('')"))
    } else {
        out
    }
}

/// A simple entity instance `#id = NAME(…)`: its id, type name and the byte where its
/// argument list opens.
pub(super) struct Instance<'a> {
    pub id: u64,
    pub name: &'a str,
    /// where `#id` starts
    start: usize,
    pub open: usize,
    /// the byte after the `;` that closes the instance
    end: usize,
}

/// The simple entity instances of a STEP text whose type is one of `names` (complex
/// instances `#id = (A(…) B(…))` are left out).
pub(super) fn instances<'a>(text: &'a str, names: &[&str]) -> Vec<Instance<'a>> {
    statements(text)
        .filter_map(|st| {
            let rest = text[st.body..st.end].trim_start();
            let len = rest
                .bytes()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == b'_')
                .count();
            let name = &rest[..len];
            let after = rest[len..].trim_start();
            (len > 0 && after.starts_with('(') && names.contains(&name)).then(|| Instance {
                id: st.id,
                name,
                start: st.start,
                open: offset(text, after),
                end: st.end,
            })
        })
        .collect()
}

/// How often each id of `ids` is referred to (`#n` outside strings and not defining `#n`).
fn reference_counts<V>(text: &str, ids: &HashMap<u64, V>) -> HashMap<u64, usize> {
    let mut out: HashMap<u64, usize> = ids.keys().map(|&k| (k, 0)).collect();
    for r in references(text) {
        if !text[r.end..].trim_start().starts_with('=') {
            if let Some(k) = out.get_mut(&r.id) {
                *k += 1;
            }
        }
    }
    out
}

/// Byte offset of `arg` (a slice of `text`) in `text`.
pub(super) fn offset(text: &str, arg: &str) -> usize {
    arg.as_ptr() as usize - text.as_ptr() as usize
}

/// `#n` as n.
pub(super) fn reference(arg: &str) -> Option<u64> {
    arg.strip_prefix('#')?.parse().ok()
}

/// `.T.` / `.F.` as a bool.
fn logical(arg: &str) -> Option<bool> {
    match arg {
        ".T." => Some(true),
        ".F." => Some(false),
        _ => None,
    }
}

/// Applies replacements (byte range, new text), which must not overlap.
pub(super) fn apply<'a>(text: &'a str, mut edits: Vec<(usize, usize, String)>) -> Cow<'a, str> {
    if edits.is_empty() {
        return Cow::Borrowed(text);
    }
    edits.sort_by_key(|e| e.0);
    let mut out = String::with_capacity(text.len() + 64 * edits.len());
    let mut at = 0;
    for (from, to, new) in edits {
        out.push_str(&text[at..from]);
        out.push_str(&new);
        at = to;
    }
    out.push_str(&text[at..]);
    Cow::Owned(out)
}

/// Every reference to a `TRIMMED_CURVE` (through a chain of them) from an `EDGE_CURVE` or a
/// swept surface is made a reference to the basis curve, which truck-stepio reads:
/// - an edge's `same_sense` is flipped where the trimmed curve runs against its basis
///   (`sense_agreement = .F.`); the edge's vertices bound its curve, so the trims add
///   nothing an edge needs;
/// - a `SURFACE_OF_LINEAR_EXTRUSION` or `SURFACE_OF_REVOLUTION` sweeps the whole basis curve,
///   a surface the face's edges trim as before; where the trimmed curve ran against its
///   basis the surface's normal turns over, so the `same_sense` of the `ADVANCED_FACE`s on it
///   is flipped.
pub(super) fn untrim_curves(text: &str) -> Cow<'_, str> {
    if !text.contains("TRIMMED_CURVE") {
        return Cow::Borrowed(text);
    }
    const SWEPT: [&str; 2] = ["SURFACE_OF_LINEAR_EXTRUSION", "SURFACE_OF_REVOLUTION"];
    let all = instances(
        text,
        &[
            "TRIMMED_CURVE",
            "EDGE_CURVE",
            SWEPT[0],
            SWEPT[1],
            "ADVANCED_FACE",
        ],
    );
    let mut basis: HashMap<u64, (u64, bool)> = HashMap::new();
    for e in all.iter().filter(|e| e.name == "TRIMMED_CURVE") {
        let a = top_level_args(&text[e.open..]);
        if let (Some(b), Some(sense)) = (
            a.get(1).and_then(|s| reference(s)),
            a.get(4).and_then(|s| logical(s)),
        ) {
            basis.insert(e.id, (b, sense));
        }
    }
    // The basis at the end of the chain from `c`, and whether it runs the same way.
    let resolve = |mut c: u64| {
        let (mut agree, mut hops) = (true, 0);
        while let Some(&(b, a)) = basis.get(&c) {
            (c, agree, hops) = (b, agree == a, hops + 1);
            if hops > basis.len() {
                return None; // a cycle: the reader reports it
            }
        }
        (hops > 0).then_some((c, agree))
    };
    let flag = |b: bool| if b { ".T." } else { ".F." }.to_string();
    let mut edits = Vec::new();
    let mut replace = |arg: &str, new: String| {
        let at = offset(text, arg);
        edits.push((at, at + arg.len(), new));
    };
    let mut reversed = std::collections::HashSet::new();
    for e in &all {
        let a = top_level_args(&text[e.open..]);
        match e.name {
            "EDGE_CURVE" => {
                let (Some(curve), Some(same)) = (a.get(3), a.get(4)) else {
                    continue;
                };
                let (Some(c), Some(s)) = (reference(curve), logical(same)) else {
                    continue;
                };
                if let Some((b, agree)) = resolve(c) {
                    replace(curve, format!("#{b}"));
                    replace(same, flag(s == agree));
                }
            }
            n if SWEPT.contains(&n) => {
                let Some(curve) = a.get(1) else { continue };
                if let Some((b, agree)) = reference(curve).and_then(resolve) {
                    replace(curve, format!("#{b}"));
                    if !agree {
                        reversed.insert(e.id);
                    }
                }
            }
            _ => {}
        }
    }
    for e in all.iter().filter(|e| e.name == "ADVANCED_FACE") {
        let a = top_level_args(&text[e.open..]);
        let (Some(surface), Some(same)) = (a.get(2), a.get(3)) else {
            continue;
        };
        if let (Some(s), Some(true)) = (
            logical(same),
            reference(surface).map(|k| reversed.contains(&k)),
        ) {
            replace(same, flag(!s));
        }
    }
    // The trimmed curves nothing refers to any more go: the reader cannot convert them and
    // would print an error for each.
    let mut left = reference_counts(text, &basis);
    for (from, to, _) in &edits {
        if let Some(n) = reference(&text[*from..*to]).and_then(|k| left.get_mut(&k)) {
            *n = n.saturating_sub(1);
        }
    }
    let trimmed: HashMap<u64, &Instance> = all
        .iter()
        .filter(|e| e.name == "TRIMMED_CURVE")
        .map(|e| (e.id, e))
        .collect();
    let mut gone: Vec<u64> = left
        .iter()
        .filter(|(_, &n)| n == 0)
        .map(|(&k, _)| k)
        .collect();
    while let Some(id) = gone.pop() {
        let Some(e) = trimmed.get(&id) else { continue };
        edits.push((e.start, e.end, String::new()));
        // a trimmed curve of a trimmed curve: its basis loses a reference
        if let Some(n) = basis.get(&id).and_then(|(b, _)| left.get_mut(b)) {
            *n = n.saturating_sub(1);
            if *n == 0 {
                gone.push(basis[&id].0);
            }
        }
    }
    apply(text, edits)
}

/// The three numbers of a `DIRECTION('', (x, y, z))`.
fn direction(text: &str, open: usize) -> Option<[f64; 3]> {
    let a = top_level_args(&text[open..]);
    let list = a.get(1)?.strip_prefix('(')?.strip_suffix(')')?;
    let v: Vec<f64> = list
        .split(',')
        .map(|t| t.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .ok()?;
    (v.len() == 3).then(|| [v[0], v[1], v[2]])
}

/// Every `AXIS2_PLACEMENT_3D` with an axis along ±x and no reference direction gets
/// (0, 0, 1) as its reference direction, a new `DIRECTION` instance: ISO 10303-42's
/// `first_proj_axis` takes (1, 0, 0) unless the axis is (1, 0, 0), then (0, 0, 1); truck
/// takes (1, 0, 0) always, and its projection onto the plane normal to the axis is then zero
/// (NaN after normalising: the circle's edge has no range). An axis along −x is degenerate
/// in the standard's formula too; (0, 0, 1) is the choice there.
pub(super) fn default_ref_directions(text: &str) -> Cow<'_, str> {
    if !text.contains("AXIS2_PLACEMENT_3D") {
        return Cow::Borrowed(text);
    }
    let all = instances(text, &["AXIS2_PLACEMENT_3D", "DIRECTION"]);
    let dirs: HashMap<u64, [f64; 3]> = all
        .iter()
        .filter(|e| e.name == "DIRECTION")
        .filter_map(|e| Some((e.id, direction(text, e.open)?)))
        .collect();
    let along_x = |d: [f64; 3]| {
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        n > 0.0 && (d[1] * d[1] + d[2] * d[2]).sqrt() <= 1e-12 * n
    };
    let mut edits = Vec::new();
    let mut new_id = None;
    for e in all.iter().filter(|e| e.name == "AXIS2_PLACEMENT_3D") {
        let a = top_level_args(&text[e.open..]);
        let (Some(axis), Some(refd)) = (a.get(2), a.get(3)) else {
            continue;
        };
        if *refd != "$"
            || !reference(axis)
                .and_then(|k| dirs.get(&k))
                .is_some_and(|&d| along_x(d))
        {
            continue;
        }
        let id = *new_id.get_or_insert_with(|| max_id(text) + 1);
        let r = offset(text, refd);
        edits.push((r, r + 1, format!("#{id}")));
    }
    let Some(id) = new_id else {
        return Cow::Borrowed(text);
    };
    // The new DIRECTION goes before the DATA section's ENDSEC.
    let Some(data) = text.find("DATA;") else {
        return Cow::Borrowed(text);
    };
    let Some(end) = text[data..].find("ENDSEC;").map(|k| data + k) else {
        return Cow::Borrowed(text);
    };
    edits.push((end, end, format!("#{id}=DIRECTION('',(0.,0.,1.));\n")));
    apply(text, edits)
}

/// Every empty list given as an attribute (`PRODUCT('p', 'p', $, ())`: zoo.dev writes its
/// products' empty context sets so) becomes `$`: truck-stepio's tokenizer stops at `()` after a
/// `,` or `(` and refuses the whole file. An entity without attributes (`LENGTH_UNIT()` in a
/// complex instance) keeps its `()`. None of these attributes is read for the geometry.
pub(super) fn empty_lists(text: &str) -> Cow<'_, str> {
    let mut edits = Vec::new();
    for st in statements(text) {
        let body = &text[st.body..st.end];
        let b = body.as_bytes();
        // The last byte outside strings and whitespace before the current one, `'` after a
        // string (code_bytes skips strings: a gap in the positions is one).
        let (mut last, mut next) = (0u8, 0usize);
        for (i, c) in code_bytes(body) {
            if i != next {
                last = b'\'';
            }
            next = i + 1;
            if c == b'(' && matches!(last, b',' | b'(') {
                let close = i
                    + 1
                    + b[i + 1..]
                        .iter()
                        .take_while(|d| d.is_ascii_whitespace())
                        .count();
                if b.get(close) == Some(&b')') {
                    edits.push((st.body + i, st.body + close + 1, "$".to_string()));
                }
            }
            if !c.is_ascii_whitespace() {
                last = c;
            }
        }
    }
    apply(text, edits)
}

/// The largest entity id of the text.
fn max_id(text: &str) -> u64 {
    let b = text.as_bytes();
    let mut best = 0;
    let mut i = 0;
    while let Some(k) = text[i..].find('#') {
        let at = i + k + 1;
        let end = at + b[at..].iter().take_while(|d| d.is_ascii_digit()).count();
        if let Ok(n) = text[at..end].parse::<u64>() {
            best = best.max(n);
        }
        i = end.max(at);
    }
    best
}

#[cfg(test)]
mod tests;
