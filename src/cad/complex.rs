//! Complex entity instances `#id = (A(…) B(…) …);` with their partial entities in the order
//! the STEP reader looks them up.
//!
//! ISO 10303-21 writes a complex instance as its partial entity instances in alphabetical
//! order of their names; ruststep finds a partial entity (a `RATIONAL_B_SPLINE_SURFACE`'s
//! `B_SPLINE_SURFACE_WITH_KNOTS` part, say) only in the byte order of the names, where `O` comes
//! before `_` (`BOUNDED_SURFACE` < `B_SPLINE_SURFACE`). Spatial's writer (TraceParts) sorts
//! with `_` first, and the reader then drops each such surface with "Lookup failed" and the
//! face on it; sorting the partial entities by their names' bytes is the same instance.

use super::prescan::{code_bytes, statements};
use super::rewrite::apply;
use std::borrow::Cow;

/// Every complex instance whose partial entities are not in the byte order of their names
/// rewritten with them in that order (each partial entity's text kept as written).
pub(super) fn complex_order(text: &str) -> Cow<'_, str> {
    let mut edits = Vec::new();
    for st in statements(text) {
        let body = &text[st.body..st.end];
        let Some(inner) = body.trim_start().strip_prefix('(') else {
            continue;
        };
        let inner_at = st.body + (body.len() - inner.len());
        let Some(parts) = partials(inner) else {
            continue;
        };
        if parts.windows(2).all(|w| w[0].0 <= w[1].0) {
            continue;
        }
        let mut sorted = parts.clone();
        sorted.sort_by_key(|p| p.0);
        let (first, last) = (&parts[0], &parts[parts.len() - 1]);
        let new: Vec<&str> = sorted.iter().map(|p| p.2).collect();
        edits.push((
            inner_at + first.1,
            inner_at + last.1 + last.2.len(),
            new.join(" "),
        ));
    }
    apply(text, edits)
}

/// The partial entity instances `NAME(…)` at the start of `inner` (the text after a complex
/// instance's opening parenthesis) up to its closing one: each name, its byte offset in
/// `inner` and its text; `None` if `inner` is not such a list.
pub(super) fn partials(inner: &str) -> Option<Vec<(&str, usize, &str)>> {
    let mut out = Vec::new();
    let mut at = 0;
    loop {
        let rest = &inner[at..];
        let skip = rest.len() - rest.trim_start().len();
        at += skip;
        let rest = &inner[at..];
        if rest.starts_with(')') {
            return (!out.is_empty()).then_some(out);
        }
        let len = rest
            .bytes()
            .take_while(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || *c == b'_')
            .count();
        if !rest.starts_with(|c: char| c.is_ascii_uppercase()) {
            return None;
        }
        let open = len + (rest[len..].len() - rest[len..].trim_start().len());
        if !rest[open..].starts_with('(') {
            return None;
        }
        let close = matching(&rest[open..])? + open;
        out.push((&rest[..len], at, &rest[..=close]));
        at += close + 1;
    }
}

/// The byte of the `)` that closes the list opening at the start of `s`, strings skipped.
fn matching(s: &str) -> Option<usize> {
    let mut depth = 0usize;
    for (i, c) in code_bytes(s) {
        match c {
            b'(' => depth += 1,
            b')' => {
                depth = depth.checked_sub(1)?;
                if depth == 0 {
                    return Some(i);
                }
            }
            b';' => return None,
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partial_entities_are_sorted_by_the_bytes_of_their_names() {
        let t = "DATA;\n#1=(B_SPLINE_SURFACE(1,1,((#2,#3),(#4,#5)),.UNSPECIFIED.,.F.,.F.,.F.)\
            B_SPLINE_SURFACE_WITH_KNOTS((2),(2),(0.,1.),(0.,1.),.UNSPECIFIED.)\
            RATIONAL_B_SPLINE_SURFACE(((1.,2.),(1.,1.)))BOUNDED_SURFACE()\
            REPRESENTATION_ITEM('a);b')GEOMETRIC_REPRESENTATION_ITEM()SURFACE());\n\
            #6=( BOUNDED_CURVE() REPRESENTATION_ITEM('') );\n#7=LINE('',#8,#9);\nENDSEC;\n";
        let r = complex_order(t);
        let want = "#1=(BOUNDED_SURFACE() B_SPLINE_SURFACE(1,1,((#2,#3),(#4,#5)),\
            .UNSPECIFIED.,.F.,.F.,.F.) B_SPLINE_SURFACE_WITH_KNOTS((2),(2),(0.,1.),(0.,1.),\
            .UNSPECIFIED.) GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE(((1.,2.),\
            (1.,1.))) REPRESENTATION_ITEM('a);b') SURFACE());";
        assert!(r.contains(want), "{r}");
        // already in order, and simple instances: untouched
        assert!(
            r.contains("#6=( BOUNDED_CURVE() REPRESENTATION_ITEM('') );"),
            "{r}"
        );
        assert!(r.contains("#7=LINE('',#8,#9);"), "{r}");
        let ordered = "#6=( BOUNDED_CURVE() REPRESENTATION_ITEM('') );\n#7=LINE('',#8,#9);\n";
        assert!(matches!(complex_order(ordered), Cow::Borrowed(_)));
    }

    #[test]
    fn malformed_complex_instances_are_left_as_they_are() {
        for t in [
            "#1=(B() A(;\n",
            "#1=(B() 3A());\n",
            "#1=(B() A);\n",
            "#1=();\n",
            "#1=('x');\n",
        ] {
            assert_eq!(complex_order(t), t);
        }
    }
}
