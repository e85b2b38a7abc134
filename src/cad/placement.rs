//! Assembly placements: where each shell of a STEP file sits in the assembly, once per
//! instance of its part.
//!
//! A part's shell lies in its shape representation's coordinates (an
//! `ADVANCED_BREP_SHAPE_REPRESENTATION` holding a `MANIFOLD_SOLID_BREP` of the shell, say).
//! Representations of one part are tied without a transformation (a plain
//! `SHAPE_REPRESENTATION_RELATIONSHIP`, or two `SHAPE_DEFINITION_REPRESENTATION`s of one
//! product shape); an assembly places a component's representation `rep_1` in its parent's
//! `rep_2` by a `REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION` whose
//! `ITEM_DEFINED_TRANSFORMATION` maps the placement `transform_item_1` (in `rep_1`) onto
//! `transform_item_2` (in `rep_2`): x₂ = M(item₂) M(item₁)⁻¹ x₁, M the placement's frame. A
//! component used several times has one such relationship per use, at every level, so a shell
//! has one placement per path from its representation to a root.

use super::complex::partials;
use super::prescan::{statements, top_level_args};
use super::rewrite::reference;
use std::collections::HashMap;
use truck_geometry::prelude::{
    InnerSpace, Matrix4, Point3, SquareMatrix, Transform, Transformed, Vector3,
};

/// The most instances of one shell (a bound on the work of a pathological assembly tree).
pub(super) const MAX_INSTANCES: usize = 10_000;

/// The most faces an assembly may place in all (each a copy of its shell's face: a bound on
/// the memory of a file that uses a large part very many times).
pub(super) const MAX_FACES: usize = 200_000;

/// Entity bodies by id: each simple instance as one `(NAME, args)` part, a complex one as its
/// partial entities.
type Bodies<'a> = HashMap<u64, Vec<(&'a str, Vec<&'a str>)>>;

/// The placements of shell `#id` for every shell id of `shells`: the frames (child to root)
/// of each instance, in a fixed order; one identity for a shell outside any assembly.
///
/// # Errors
/// A message if a shell has more than [`MAX_INSTANCES`] instances or the assembly's
/// relationships form a cycle.
pub(super) fn shell_placements(
    text: &str,
    shells: &[u64],
) -> Result<HashMap<u64, Vec<Matrix4>>, String> {
    if !text.contains("ITEM_DEFINED_TRANSFORMATION") && !text.contains("MAPPED_ITEM") {
        return Ok(shells
            .iter()
            .map(|s| (*s, vec![Matrix4::identity()]))
            .collect());
    }
    let bodies = parse(text);
    let mut space = Spaces::default();
    // representations and the shells in their items (ids in order: deterministic)
    let mut ids: Vec<u64> = bodies.keys().copied().collect();
    ids.sort_unstable();
    let mut shell_rep: HashMap<u64, u64> = HashMap::new();
    let mut rep_items: HashMap<u64, Vec<u64>> = HashMap::new();
    // (representation, mapped item) of every mapped item of a shape representation
    let mut mapped: Vec<(u64, u64)> = Vec::new();
    for &id in &ids {
        let [(name, args)] = bodies[&id].as_slice() else {
            continue;
        };
        if !name.ends_with("REPRESENTATION") || args.len() < 3 {
            continue;
        }
        let items = list(args[1]);
        for &item in &items {
            if matches!(
                bodies.get(&item).map(Vec::as_slice),
                Some([("MAPPED_ITEM", _)])
            ) {
                mapped.push((id, item));
            }
            for s in item_shells(&bodies, item) {
                // a shell in two representations: both are the part's coordinates
                match shell_rep.get(&s) {
                    Some(&other) => space.union(other, id),
                    None => {
                        shell_rep.insert(s, id);
                    }
                }
            }
        }
        rep_items.insert(id, items);
    }
    // representations of one part: one space
    let mut by_shape: HashMap<u64, u64> = HashMap::new();
    for parts in bodies.values() {
        let [(name, args)] = parts.as_slice() else {
            continue;
        };
        let refs = |k: usize| args.get(k).and_then(|a| reference(a));
        match *name {
            "SHAPE_REPRESENTATION_RELATIONSHIP" => {
                if let (Some(a), Some(b)) = (refs(2), refs(3)) {
                    space.union(a, b);
                }
            }
            "SHAPE_DEFINITION_REPRESENTATION" => {
                if let (Some(pds), Some(rep)) = (refs(0), refs(1)) {
                    if let Some(&other) = by_shape.get(&pds) {
                        space.union(other, rep);
                    } else {
                        by_shape.insert(pds, rep);
                    }
                }
            }
            _ => {}
        }
    }
    // placements of a component's space in its parent's
    let mut up: HashMap<u64, Vec<(u64, u64, Matrix4)>> = HashMap::new();
    for &id in &ids {
        let parts = &bodies[&id];
        let find = |n: &str| parts.iter().find(|(p, _)| *p == n).map(|(_, a)| a);
        let (Some(rr), Some(rrwt)) = (
            find("REPRESENTATION_RELATIONSHIP"),
            find("REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION"),
        ) else {
            continue;
        };
        let (Some(r1), Some(r2)) = (
            rr.get(2).and_then(|a| reference(a)),
            rr.get(3).and_then(|a| reference(a)),
        ) else {
            continue;
        };
        let Some(idt) = rrwt
            .first()
            .and_then(|a| reference(a))
            .and_then(|k| bodies.get(&k))
        else {
            continue;
        };
        let [("ITEM_DEFINED_TRANSFORMATION", t)] = idt.as_slice() else {
            continue;
        };
        let (Some(i1), Some(i2)) = (
            t.get(2).and_then(|a| reference(a)),
            t.get(3).and_then(|a| reference(a)),
        ) else {
            continue;
        };
        let (Some(m1), Some(m2)) = (frame(&bodies, i1), frame(&bodies, i2)) else {
            continue;
        };
        let (c1, c2) = (space.find(r1), space.find(r2));
        let scale = unit_scale(&bodies, r1, r2);
        // the standard: item₁ in rep_1 (the component); some writers swap the items
        let in_space = |item: u64, s: u64| {
            rep_items
                .iter()
                .any(|(r, items)| items.contains(&item) && space.root(*r) == s)
        };
        let swapped = in_space(i1, c2) && in_space(i2, c1) && !in_space(i1, c1);
        let (from, to) = if swapped { (m2, m1) } else { (m1, m2) };
        let Some(inv) = from.invert() else {
            continue;
        };
        up.entry(c1).or_default().push((c2, id, to * scale * inv));
    }
    // a mapped item places its map's representation, x₂ = M(target) M(origin)⁻¹ x₁
    for (rep, item) in mapped {
        let Some(m) = mapped_item(&bodies, item) else {
            continue;
        };
        let (c1, c2) = (space.find(m.source), space.find(rep));
        let scale = unit_scale(&bodies, m.source, rep);
        up.entry(c1)
            .or_default()
            .push((c2, item, m.target * scale * m.origin_inverse));
    }
    let mut memo: HashMap<u64, Vec<Matrix4>> = HashMap::new();
    let mut out = HashMap::new();
    for &s in shells {
        let placed = match shell_rep.get(&s) {
            Some(&rep) => instances(space.root(rep), &up, &mut memo, 0)?,
            None => vec![Matrix4::identity()],
        };
        out.insert(s, placed);
    }
    Ok(out)
}

/// A `MAPPED_ITEM`'s representation map: the mapped representation, the inverse frame of
/// the map's origin and the frame of the item's target (an `AXIS2_PLACEMENT_3D` or a
/// `CARTESIAN_TRANSFORMATION_OPERATOR_3D`).
struct Mapped {
    source: u64,
    origin_inverse: Matrix4,
    target: Matrix4,
}

fn mapped_item(bodies: &Bodies, item: u64) -> Option<Mapped> {
    let [("MAPPED_ITEM", a)] = bodies.get(&item)?.as_slice() else {
        return None;
    };
    let [("REPRESENTATION_MAP", map)] = bodies.get(&reference(a.get(1)?)?)?.as_slice() else {
        return None;
    };
    let origin = frame(bodies, reference(map.first()?)?)?;
    let source = reference(map.get(1)?)?;
    let t = reference(a.get(2)?)?;
    let target = frame(bodies, t).or_else(|| operator(bodies, t))?;
    Some(Mapped {
        source,
        origin_inverse: origin.invert()?,
        target,
    })
}

/// The matrix of a `CARTESIAN_TRANSFORMATION_OPERATOR_3D` (axes 1, 2, 3 as given or made up
/// as for a placement, the local origin, a uniform scale; default axes x, y, z, scale 1).
fn operator(bodies: &Bodies, id: u64) -> Option<Matrix4> {
    let parts = bodies.get(&id)?;
    let (_, a) = parts
        .iter()
        .find(|(n, _)| *n == "CARTESIAN_TRANSFORMATION_OPERATOR_3D")
        .or_else(|| {
            parts
                .iter()
                .find(|(n, _)| *n == "CARTESIAN_TRANSFORMATION_OPERATOR")
        })?;
    let dir = |k: usize| {
        a.get(k)
            .and_then(|x| reference(x))
            .and_then(|r| numbers(bodies, r, "DIRECTION"))
    };
    let o = numbers(bodies, reference(a.get(4)?)?, "CARTESIAN_POINT")?;
    let scale = match a.get(5).map(|x| x.trim()) {
        None | Some("$") => 1.0,
        Some(x) => x
            .parse::<f64>()
            .ok()
            .filter(|s| s.is_finite() && *s > 0.0)?,
    };
    let z = dir(6).unwrap_or(Vector3::new(0.0, 0.0, 1.0));
    if z.magnitude() == 0.0 {
        return None;
    }
    let z = z.normalize();
    let x = dir(2).unwrap_or(Vector3::new(1.0, 0.0, 0.0));
    let x = x - z * x.dot(z);
    if x.magnitude() < 1e-12 {
        return None;
    }
    let x = x.normalize();
    let y = z.cross(x);
    Some(Matrix4::from_cols(
        (x * scale).extend(0.0),
        (y * scale).extend(0.0),
        (z * scale).extend(0.0),
        o.extend(1.0),
    ))
}

/// A component measured in another length unit than its parent: the scale to the parent's.
fn unit_scale(bodies: &Bodies, component: u64, parent: u64) -> Matrix4 {
    let unit = |r: u64| {
        bodies
            .get(&r)
            .and_then(|p| p.first())
            .and_then(|(_, a)| a.get(2).and_then(|c| reference(c)))
            .and_then(|c| metres_per_unit(bodies, c))
    };
    match (unit(component), unit(parent)) {
        (Some(a), Some(b)) if a != b => Matrix4::from_scale(a / b),
        _ => Matrix4::identity(),
    }
}

/// The frames (to the root) of every instance of space `s`.
fn instances(
    s: u64,
    up: &HashMap<u64, Vec<(u64, u64, Matrix4)>>,
    memo: &mut HashMap<u64, Vec<Matrix4>>,
    depth: usize,
) -> Result<Vec<Matrix4>, String> {
    if let Some(m) = memo.get(&s) {
        return Ok(m.clone());
    }
    if depth > 64 {
        return Err("the assembly's placements form a cycle (or nest deeper than 64)".into());
    }
    let out = match up.get(&s) {
        None => vec![Matrix4::identity()],
        Some(parents) => {
            let mut out = Vec::new();
            for (p, _, t) in parents {
                for m in instances(*p, up, memo, depth + 1)? {
                    out.push(m * t);
                    if out.len() > MAX_INSTANCES {
                        return Err(format!(
                            "a part is placed more than {MAX_INSTANCES} times in the assembly"
                        ));
                    }
                }
            }
            out
        }
    };
    memo.insert(s, out.clone());
    Ok(out)
}

/// Union–find over representation ids.
#[derive(Default)]
struct Spaces {
    parent: HashMap<u64, u64>,
}

impl Spaces {
    fn find(&mut self, a: u64) -> u64 {
        let p = *self.parent.get(&a).unwrap_or(&a);
        if p == a {
            return a;
        }
        let r = self.find(p);
        self.parent.insert(a, r);
        r
    }

    /// The root without path compression (for shared borrows).
    fn root(&self, mut a: u64) -> u64 {
        while let Some(&p) = self.parent.get(&a).filter(|p| **p != a) {
            a = p;
        }
        a
    }

    fn union(&mut self, a: u64, b: u64) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent.insert(ra.max(rb), ra.min(rb));
        }
    }
}

/// The shells an item of a representation holds: a shell itself, a solid's outer shell and
/// voids, a shell-based surface model's shells.
fn item_shells(bodies: &Bodies, item: u64) -> Vec<u64> {
    let Some([(name, args)]) = bodies.get(&item).map(Vec::as_slice) else {
        return Vec::new();
    };
    match *name {
        "CLOSED_SHELL" | "OPEN_SHELL" => vec![item],
        "MANIFOLD_SOLID_BREP" | "FACETED_BREP" => {
            args.get(1).and_then(|a| reference(a)).into_iter().collect()
        }
        "BREP_WITH_VOIDS" => {
            let mut v: Vec<u64> = args.get(1).and_then(|a| reference(a)).into_iter().collect();
            v.extend(args.get(2).map_or(Vec::new(), |a| list(a)));
            v
        }
        "SHELL_BASED_SURFACE_MODEL" => args.get(1).map_or(Vec::new(), |a| list(a)),
        _ => Vec::new(),
    }
}

/// The frame of an `AXIS2_PLACEMENT_3D` (its local coordinates to its representation's):
/// z its axis (default z), x its reference direction made normal to z (default x, or the
/// axis least aligned with z), y = z × x, the origin its location.
fn frame(bodies: &Bodies, id: u64) -> Option<Matrix4> {
    let [("AXIS2_PLACEMENT_3D", a)] = bodies.get(&id)?.as_slice() else {
        return None;
    };
    let loc = numbers(bodies, reference(a.get(1)?)?, "CARTESIAN_POINT")?;
    let dir = |k: usize| {
        a.get(k)
            .and_then(|x| reference(x))
            .and_then(|r| numbers(bodies, r, "DIRECTION"))
    };
    let z = dir(2).unwrap_or(Vector3::new(0.0, 0.0, 1.0));
    if z.magnitude() == 0.0 {
        return None;
    }
    let z = z.normalize();
    let fallback = if z.x.abs() < 0.9 {
        Vector3::new(1.0, 0.0, 0.0)
    } else {
        Vector3::new(0.0, 1.0, 0.0)
    };
    let r = dir(3).unwrap_or(fallback);
    let x = r - z * r.dot(z);
    let x = if x.magnitude() > 1e-12 {
        x
    } else {
        fallback - z * fallback.dot(z)
    }
    .normalize();
    let y = z.cross(x);
    let o = Point3::new(loc.x, loc.y, loc.z);
    Some(Matrix4::from_cols(
        x.extend(0.0),
        y.extend(0.0),
        z.extend(0.0),
        o.to_homogeneous(),
    ))
}

/// The three numbers of a `CARTESIAN_POINT` or `DIRECTION` (`name`) with id `id`.
fn numbers(bodies: &Bodies, id: u64, name: &str) -> Option<Vector3> {
    let [(n, a)] = bodies.get(&id)?.as_slice() else {
        return None;
    };
    if *n != name {
        return None;
    }
    let inner = a.get(1)?.strip_prefix('(')?.strip_suffix(')')?;
    let v: Vec<f64> = inner
        .split(',')
        .map(|t| t.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .ok()?;
    (v.len() == 3 && v.iter().all(|c| c.is_finite())).then(|| Vector3::new(v[0], v[1], v[2]))
}

/// Metres per length unit of the representation context `context` (its
/// `GLOBAL_UNIT_ASSIGNED_CONTEXT`'s `LENGTH_UNIT`: an SI metre with its prefix, or a
/// conversion-based unit such as the inch by its `LENGTH_MEASURE_WITH_UNIT`).
fn metres_per_unit(bodies: &Bodies, context: u64) -> Option<f64> {
    let parts = bodies.get(&context)?;
    let (_, units) = parts
        .iter()
        .find(|(n, _)| *n == "GLOBAL_UNIT_ASSIGNED_CONTEXT")?;
    list(units.first()?)
        .into_iter()
        .find_map(|u| length_unit(bodies, u, 0))
}

/// Metres per unit of the length unit `id` (`None` if it is not a length unit).
fn length_unit(bodies: &Bodies, id: u64, depth: usize) -> Option<f64> {
    let parts = bodies.get(&id)?;
    if depth > 8 || !parts.iter().any(|(n, _)| *n == "LENGTH_UNIT") {
        return None;
    }
    let arg = |name: &str, k: usize| {
        parts
            .iter()
            .find(|(n, _)| *n == name)
            .and_then(|(_, a)| a.get(k).copied())
    };
    if let Some(unit) = arg("SI_UNIT", 1) {
        if unit != ".METRE." {
            return None;
        }
        let prefix = match arg("SI_UNIT", 0)? {
            "$" => 1.0,
            ".KILO." => 1e3,
            ".DECI." => 1e-1,
            ".CENTI." => 1e-2,
            ".MILLI." => 1e-3,
            ".MICRO." => 1e-6,
            ".NANO." => 1e-9,
            _ => return None,
        };
        return Some(prefix);
    }
    let measure = bodies.get(&reference(arg("CONVERSION_BASED_UNIT", 1)?)?)?;
    let [(_, m)] = measure.as_slice() else {
        return None;
    };
    let value: f64 = m
        .first()?
        .trim()
        .strip_prefix("LENGTH_MEASURE")?
        .trim()
        .strip_prefix('(')?
        .strip_suffix(')')?
        .trim()
        .parse()
        .ok()?;
    let base = length_unit(bodies, reference(m.get(1)?)?, depth + 1)?;
    (value.is_finite() && value > 0.0).then_some(value * base)
}

/// `(#1, #2, …)` as ids.
fn list(arg: &str) -> Vec<u64> {
    arg.strip_prefix('(')
        .and_then(|a| a.strip_suffix(')'))
        .map_or(Vec::new(), |a| {
            a.split(',').filter_map(|x| reference(x.trim())).collect()
        })
}

/// Every instance of the assembly structure's types and the geometry they refer to.
fn parse(text: &str) -> Bodies<'_> {
    let mut out = Bodies::new();
    for st in statements(text) {
        let body = text[st.body..st.end].trim_start();
        let parts = if let Some(inner) = body.strip_prefix('(') {
            match partials(inner) {
                Some(p) => p
                    .into_iter()
                    .map(|(name, _, t)| (name, top_level_args(t[name.len()..].trim_start())))
                    .collect(),
                None => continue,
            }
        } else {
            let len = body
                .bytes()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == b'_')
                .count();
            let rest = body[len..].trim_start();
            if len == 0 || !rest.starts_with('(') {
                continue;
            }
            vec![(&body[..len], top_level_args(rest))]
        };
        out.insert(st.id, parts);
    }
    out
}

/// The shell moved by the frame `m` (a rigid placement): its vertices, edge curves and
/// surfaces.
pub(super) fn place(shell: &super::Shell, m: Matrix4) -> super::Shell {
    let mut s = shell.clone();
    for v in &mut s.vertices {
        *v = m.transform_point(*v);
    }
    for e in &mut s.edges {
        e.curve.transform_by(m);
    }
    for f in &mut s.faces {
        f.surface.transform_by(m);
    }
    s
}
