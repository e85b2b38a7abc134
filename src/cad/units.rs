//! The file's units and tolerances, read from its text: plane angles in degrees converted
//! for truck-stepio (which assumes radians), and the distance uncertainty that sets how far
//! an edge may lie from its face.

use super::prescan::{statements, top_level_args};
use super::rewrite::{apply, instances, offset, reference};
use std::borrow::Cow;
use std::collections::HashMap;

/// Every entity instance (`#id = …;`, simple or complex) as its id and its text after `=`
/// up to the closing `;`, for the instances whose text contains one of `needles`.
fn bodies<'a>(text: &'a str, needles: &[&str]) -> HashMap<u64, &'a str> {
    statements(text)
        .map(|st| (st.id, &text[st.body..st.end - 1]))
        .filter(|(_, body)| needles.iter().any(|n| body.contains(n)))
        .collect()
}

/// The radians per unit of the plane angle unit `body` (an SI radian: 1; a conversion-based
/// unit: its `PLANE_ANGLE_MEASURE` in radians), or `None` for a unit not understood.
fn radians_per_unit(bodies: &HashMap<u64, &str>, body: &str) -> Option<f64> {
    if body.contains("SI_UNIT") && body.contains(".RADIAN.") {
        let milli = body.contains(".MILLI.");
        return Some(if milli { 1e-3 } else { 1.0 });
    }
    let k = body.find("CONVERSION_BASED_UNIT")?;
    let args = top_level_args(&body[k + "CONVERSION_BASED_UNIT".len()..]);
    let measure = bodies.get(&reference(args.get(1)?)?)?;
    let k = measure.find("PLANE_ANGLE_MEASURE(")? + "PLANE_ANGLE_MEASURE(".len();
    let value: f64 = measure[k..].split(')').next()?.trim().parse().ok()?;
    let base = top_level_args(&measure[measure.find('(')?..]);
    let base = bodies.get(&reference(base.get(1)?)?)?;
    (base.contains(".RADIAN.") && !base.contains(".MILLI.") && value > 0.0).then_some(value)
}

/// The cone semi-angles (`CONICAL_SURFACE`'s fourth attribute) are written in radians when
/// every unit context of the file (`GLOBAL_UNIT_ASSIGNED_CONTEXT`) measures plane angles in
/// one unit other than the radian (files of several parts with different angle units are
/// left as they are).
pub(super) fn radian_cone_angles(text: &str) -> Cow<'_, str> {
    if !text.contains("CONICAL_SURFACE") || !text.contains("CONVERSION_BASED_UNIT") {
        return Cow::Borrowed(text);
    }
    let units = bodies(text, &["PLANE_ANGLE", "GLOBAL_UNIT_ASSIGNED_CONTEXT"]);
    let mut factors: Vec<f64> = Vec::new();
    for body in units.values() {
        let Some(k) = body.find("GLOBAL_UNIT_ASSIGNED_CONTEXT") else {
            continue;
        };
        let args = top_level_args(&body[k + "GLOBAL_UNIT_ASSIGNED_CONTEXT".len()..]);
        let Some(list) = args.first() else { continue };
        for unit in top_level_args(list) {
            let Some(u) = reference(unit).and_then(|r| units.get(&r)) else {
                continue;
            };
            if u.contains("PLANE_ANGLE_UNIT") {
                match radians_per_unit(&units, u) {
                    Some(f) => factors.push(f),
                    None => return Cow::Borrowed(text),
                }
            }
        }
    }
    let f = match factors.first() {
        Some(&f) if factors.iter().all(|&g| (g - f).abs() <= 1e-12 * f) => f,
        _ => return Cow::Borrowed(text),
    };
    if (f - 1.0).abs() <= 1e-12 {
        return Cow::Borrowed(text);
    }
    let mut edits = Vec::new();
    for e in instances(text, &["CONICAL_SURFACE"]) {
        let a = top_level_args(&text[e.open..]);
        if let Some(angle) = a.get(3) {
            if let Ok(v) = angle.parse::<f64>() {
                let at = offset(text, angle);
                edits.push((at, at + angle.len(), format!("{:.17E}", v * f)));
            }
        }
    }
    apply(text, edits)
}

/// The file's distance uncertainty: the largest `LENGTH_MEASURE` of its
/// `UNCERTAINTY_MEASURE_WITH_UNIT`s named `'distance_accuracy_value'` (0 if there is none).
pub(super) fn distance_uncertainty(text: &str) -> f64 {
    let key = "UNCERTAINTY_MEASURE_WITH_UNIT";
    let mut best: f64 = 0.0;
    let mut from = 0;
    while let Some(k) = text[from..].find(key) {
        let at = from + k + key.len();
        from = at;
        let args = top_level_args(&text[at..]);
        let named = args.get(2).is_some_and(|n| {
            n.trim_matches('\'')
                .eq_ignore_ascii_case("distance_accuracy_value")
        });
        let value = args.first().and_then(|a| {
            let a = a.trim();
            let inner = a.strip_prefix("LENGTH_MEASURE")?.trim().strip_prefix('(')?;
            inner.strip_suffix(')')?.trim().parse::<f64>().ok()
        });
        if let (true, Some(v)) = (named, value) {
            if v.is_finite() && v > 0.0 {
                best = best.max(v);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cone_angles_in_degrees_become_radians() {
        let t = "DATA;\n#1=CONICAL_SURFACE('',#2,1.5,3.E1);\n\
            #5=(CONVERSION_BASED_UNIT('DEGREE',#6)NAMED_UNIT(*)PLANE_ANGLE_UNIT());\n\
            #6=PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(1.745329251994E-2),\n#7);\n\
            #7=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n\
            #8=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n\
            #9=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#8,#5))\n\
            REPRESENTATION_CONTEXT('ID1','3'));\nENDSEC;\n";
        let r = radian_cone_angles(t);
        let head = "#1=CONICAL_SURFACE('',#2,1.5,";
        let k = r.find(head).unwrap() + head.len();
        let v: f64 = r[k..].split(')').next().unwrap().parse().unwrap();
        assert!((v - std::f64::consts::PI / 6.0).abs() < 1e-11, "{r}");
        // radians already, or two contexts in different units: unchanged
        assert!(matches!(
            radian_cone_angles(&t.replace(
                "GLOBAL_UNIT_ASSIGNED_CONTEXT((#8,#5))",
                "GLOBAL_UNIT_ASSIGNED_CONTEXT((#8,#7))"
            )),
            Cow::Borrowed(_)
        ));
        let two = t.replace(
            "ENDSEC;",
            "#10=(GLOBAL_UNIT_ASSIGNED_CONTEXT((#7)));\nENDSEC;",
        );
        assert!(matches!(radian_cone_angles(&two), Cow::Borrowed(_)));
    }

    #[test]
    fn the_distance_uncertainty_is_read() {
        let t = "#95 = UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#92,\n\
            'distance_accuracy_value','confusion accuracy');\n\
            #96=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE( 5.0E-03 ),#41,'DISTANCE_ACCURACY_VALUE','');\n\
            #97=UNCERTAINTY_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(0.1),#42,'angle_accuracy_value','');\n";
        assert_eq!(distance_uncertainty(t), 5e-3);
        assert_eq!(distance_uncertainty("#1=LINE();"), 0.0);
    }
}
