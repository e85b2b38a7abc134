//! Limits checked on a STEP file's text before the STEP reader sees it (issue #17): the
//! reader expands knot vectors from their multiplicities and parses nested lists
//! recursively, so a 15 KB file with a multiplicity of 2³¹ − 1 asks for gigabytes, and
//! 10 000 nested parentheses overflow the stack; and it holds the whole file as a syntax tree
//! (measured: ~17 bytes per byte of a file of tiny entities, ~27 per byte of one long list,
//! 10 s per million entities). Refused here, with the entity or line named: nesting, knot
//! multiplicities, the number of entity instances, the length of one list, and the memory
//! the reader would need against the memory available.

/// Deepest parenthesis nesting accepted (real files stay below 10).
pub const MAX_DEPTH: usize = 64;

/// Largest knot multiplicity accepted (a multiplicity is at most degree + 1; real degrees
/// stay below 30).
pub const MAX_MULTIPLICITY: i64 = 64;

/// Longest chain of entity references accepted (real files stay below 30): the reader
/// resolves a reference by recursion, so a cycle (`#26 = SURFACE_CURVE('', #26, …)`, found
/// by fuzzing) overflowed the stack, and so would a chain of some thousand entities.
pub const MAX_REF_DEPTH: usize = 256;

/// Most entity instances accepted (the 40 files of the #14 corpus have at most a few
/// 10⁵; the reader takes ~10 s per million).
pub const MAX_ENTITIES: usize = 5_000_000;

/// Most items in one list (a B-spline's control-point rows and knot vectors stay far below).
pub const MAX_LIST_ITEMS: usize = 1_000_000;

/// Memory the STEP reader needs per byte of the file, rounded up from the measured 17–27
/// (a million tiny `CARTESIAN_POINT`s: 40 MB file, 696 MB peak; one list of 3 million
/// numbers: 9 MB file, 248 MB peak).
pub const READER_BYTES_PER_BYTE: u64 = 30;

/// Checks the memory the reader needs, nesting depth, the number of entities, the length of
/// every list, that entity references form no cycle and no chain deeper than
/// [`MAX_REF_DEPTH`], and every knot multiplicity of B-spline curves and surfaces.
///
/// # Errors
/// A message naming the entity (`#id`) or the line.
pub fn check(text: &str) -> Result<(), String> {
    check_memory(text.len())?;
    check_structure(text)?;
    check_references(text)?;
    for kind in ["B_SPLINE_SURFACE_WITH_KNOTS", "B_SPLINE_CURVE_WITH_KNOTS"] {
        let mut from = 0;
        while let Some(k) = text[from..].find(kind) {
            let at = from + k;
            from = at + kind.len();
            let rest = text[from..].trim_start();
            if !rest.starts_with('(') {
                continue;
            }
            let open = text.len() - rest.len();
            let args = top_level_args(&text[open..]);
            let entity = entity_id(text, at);
            // Multiplicities: the lists of integers among the arguments (a simple instance has
            // them after the control points and flags, a complex instance's WITH_KNOTS part
            // starts with them; both are the only lists of plain integers).
            for a in &args {
                for m in integer_list(a) {
                    if !(1..=MAX_MULTIPLICITY).contains(&m) {
                        return Err(format!(
                            "{entity} ({kind}): knot multiplicity {m} outside 1..{MAX_MULTIPLICITY}"
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

/// The reader's memory for a file of `len` bytes against the memory available.
fn check_memory(len: usize) -> Result<(), String> {
    let Some(avail) = crate::io::available_memory() else {
        return Ok(());
    };
    let need = (len as u64).saturating_mul(READER_BYTES_PER_BYTE);
    if need > avail {
        return Err(format!(
            "reading this {len}-byte STEP file needs ~{:.3} GB, the machine has {:.3} GB \
             available (set {} to override)",
            need as f64 / 1e9,
            avail as f64 / 1e9,
            crate::io::MEMORY_VAR
        ));
    }
    Ok(())
}

/// Outside strings: parenthesis depth at most [`MAX_DEPTH`], at most [`MAX_ENTITIES`]
/// statements (entity instances end with `;` outside parentheses) and at most
/// [`MAX_LIST_ITEMS`] items in any one list.
fn check_structure(text: &str) -> Result<(), String> {
    let mut depth = 0usize;
    let mut statements = 0usize;
    // items so far of the list open at each depth
    let mut items = [0usize; MAX_DEPTH + 1];
    // the line of byte `i`, for the messages
    let line = |i: usize| 1 + text[..i].bytes().filter(|&c| c == b'\n').count();
    for (i, c) in code_bytes(text) {
        match c {
            b'(' => {
                depth += 1;
                if depth > MAX_DEPTH {
                    return Err(format!(
                        "line {}: parentheses nested deeper than {MAX_DEPTH}",
                        line(i)
                    ));
                }
                items[depth] = 1;
            }
            b')' => depth = depth.saturating_sub(1),
            b',' if depth > 0 => {
                items[depth] += 1;
                if items[depth] > MAX_LIST_ITEMS {
                    return Err(format!(
                        "line {}: a list of more than {MAX_LIST_ITEMS} items",
                        line(i)
                    ));
                }
            }
            b';' if depth == 0 => {
                statements += 1;
                if statements > MAX_ENTITIES {
                    return Err(format!(
                        "line {}: more than {MAX_ENTITIES} entity instances",
                        line(i)
                    ));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// The entity instances (`#id = …;`) and the references (`#n`) in each, outside strings,
/// as ids and a flat list of references per instance; an instance the text ends inside
/// (no closing `;`) counts too, up to the end of the text.
fn instances(text: &str) -> (Vec<u64>, Vec<usize>, Vec<u64>) {
    let (mut ids, mut starts, mut refs) = (Vec::new(), Vec::new(), Vec::new());
    for (st, _) in scan(text) {
        ids.push(st.id);
        starts.push(refs.len());
        refs.extend(references(&text[st.body..st.end]).map(|r| r.id));
    }
    starts.push(refs.len());
    (ids, starts, refs)
}

/// No cycle of references and no chain longer than [`MAX_REF_DEPTH`] (an iterative
/// depth-first search: the check itself must not recurse).
fn check_references(text: &str) -> Result<(), String> {
    let (ids, starts, refs) = instances(text);
    let index: std::collections::HashMap<u64, usize> =
        ids.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    let succ = |v: usize| {
        refs[starts[v]..starts[v + 1]]
            .iter()
            .filter_map(|r| index.get(r).copied())
    };
    // 0: not seen, 1: on the path, 2: done; depth of the longest chain from each instance
    let mut state = vec![0u8; ids.len()];
    let mut depth = vec![0usize; ids.len()];
    for root in 0..ids.len() {
        if state[root] != 0 {
            continue;
        }
        let mut path: Vec<(usize, usize)> = vec![(root, 0)];
        state[root] = 1;
        while let Some(&mut (v, ref mut next)) = path.last_mut() {
            if let Some(w) = succ(v).nth(*next) {
                *next += 1;
                match state[w] {
                    1 => {
                        let from = path.iter().position(|&(u, _)| u == w).unwrap_or(0);
                        let cycle: Vec<String> = path[from..]
                            .iter()
                            .map(|&(u, _)| format!("#{}", ids[u]))
                            .chain([format!("#{}", ids[w])])
                            .collect();
                        return Err(format!(
                            "entity references form a cycle: {}",
                            cycle.join(" → ")
                        ));
                    }
                    0 => {
                        state[w] = 1;
                        path.push((w, 0));
                        if path.len() > MAX_REF_DEPTH {
                            return Err(format!(
                                "#{}: entity references nested deeper than {MAX_REF_DEPTH}",
                                ids[root]
                            ));
                        }
                    }
                    _ => {}
                }
            } else {
                depth[v] = 1 + succ(v).map(|w| depth[w]).max().unwrap_or(0);
                if depth[v] > MAX_REF_DEPTH {
                    return Err(format!(
                        "#{}: entity references nested deeper than {MAX_REF_DEPTH}",
                        ids[v]
                    ));
                }
                state[v] = 2;
                path.pop();
            }
        }
    }
    Ok(())
}

/// One entity instance `#id = body;` of a STEP text, as byte positions: `start` at its `#`,
/// `body` just after its `=`, `end` just after its closing `;`.
pub(super) struct Statement {
    pub id: u64,
    pub start: usize,
    pub body: usize,
    pub end: usize,
}

/// The entity instances of a STEP text in order (an `#id =` outside strings at nesting depth
/// 0 opens one, the next `;` at depth 0 closes it); the one scanner of the rewrites, the
/// unit reader and the reference check.
pub(super) fn statements(text: &str) -> impl Iterator<Item = Statement> + '_ {
    scan(text).filter_map(|(st, closed)| closed.then_some(st))
}

/// [`statements`], and last an instance the text ends inside (no closing `;` at depth 0,
/// `end` at the end of the text), each with whether it was closed.
fn scan(text: &str) -> impl Iterator<Item = (Statement, bool)> + '_ {
    let mut depth = 0usize;
    let mut open: Option<(u64, usize, usize)> = None;
    code_bytes(text)
        .map(Some)
        .chain([None])
        .filter_map(move |token| {
            let Some((i, c)) = token else {
                return close(&mut open, text.len(), false);
            };
            match c {
                b'(' => depth += 1,
                b')' => depth = depth.saturating_sub(1),
                b';' if depth == 0 => return close(&mut open, i + 1, true),
                b'#' if depth == 0 && open.is_none() => {
                    let (id, end) = number_after_hash(text, i)?;
                    let rest = text[end..].trim_start().strip_prefix('=')?;
                    open = Some((id, i, text.len() - rest.len()));
                }
                _ => {}
            }
            None
        })
}

/// The statement `open` (id, start, body) ended at `end`, if one is open, and whether a `;`
/// closed it.
fn close(
    open: &mut Option<(u64, usize, usize)>,
    end: usize,
    closed: bool,
) -> Option<(Statement, bool)> {
    let (id, start, body) = open.take()?;
    Some((
        Statement {
            id,
            start,
            body,
            end,
        },
        closed,
    ))
}

/// A reference `#n` in a STEP text: its number and the byte after its digits.
pub(super) struct Reference {
    pub id: u64,
    pub end: usize,
}

/// Every `#n` of a STEP text outside strings, in order. Over a statement's body these are its
/// references; over a whole file the `#id` that open the statements are among them.
pub(super) fn references(text: &str) -> impl Iterator<Item = Reference> + '_ {
    code_bytes(text)
        .filter(|&(_, c)| c == b'#')
        .filter_map(|(at, _)| {
            let (id, end) = number_after_hash(text, at)?;
            Some(Reference { id, end })
        })
}

/// The number written after the `#` at byte `at`, and the byte after its digits.
fn number_after_hash(text: &str, at: usize) -> Option<(u64, usize)> {
    let digits = &text[at + 1..];
    let end = at + 1 + digits.bytes().take_while(u8::is_ascii_digit).count();
    Some((text[at + 1..end].parse().ok()?, end))
}

/// The bytes of a STEP text outside its strings, with their positions: the one place that
/// says what a string is. A `'` opens a string and the next `'` closes it; ISO 10303-21
/// writes a quote inside a string as `''`, which closes the string and at once opens it
/// again, so it needs no rule of its own. The quotes themselves are not yielded.
pub(super) fn code_bytes(text: &str) -> impl Iterator<Item = (usize, u8)> + '_ {
    let mut in_str = false;
    text.bytes().enumerate().filter(move |&(_, c)| {
        if c == b'\'' {
            in_str = !in_str;
            false
        } else {
            !in_str
        }
    })
}

/// The top-level arguments of the list that starts at `s` (with its `(`), as text.
pub(super) fn top_level_args(s: &str) -> Vec<&str> {
    let (mut depth, mut start) = (0usize, 1usize);
    let mut out = Vec::new();
    for (i, c) in code_bytes(s) {
        match c {
            b'(' => depth += 1,
            b')' => {
                depth -= 1;
                if depth == 0 {
                    out.push(s[start..i].trim());
                    return out;
                }
            }
            b',' if depth == 1 => {
                out.push(s[start..i].trim());
                start = i + 1;
            }
            b';' => break,
            _ => {}
        }
    }
    out
}

/// The integers of an argument that is a flat list of integers, e.g. `(4, 3, 3, 4)`;
/// nothing for any other argument.
fn integer_list(arg: &str) -> Vec<i64> {
    let Some(inner) = arg.strip_prefix('(').and_then(|a| a.strip_suffix(')')) else {
        return Vec::new();
    };
    let items: Vec<&str> = inner.split(',').map(str::trim).collect();
    let ints: Vec<i64> = items.iter().filter_map(|t| t.parse().ok()).collect();
    if ints.len() == items.len() {
        ints
    } else {
        // a list of reals (knots), references or nested lists: not multiplicities; an
        // integer too large for i64 still counts as a (bad) multiplicity
        if items
            .iter()
            .all(|t| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit() || b == b'-'))
        {
            vec![i64::MAX]
        } else {
            Vec::new()
        }
    }
}

/// `#id` of the entity instance around byte `at` (the last `#` starting a line before it).
fn entity_id(text: &str, at: usize) -> String {
    let head = &text[..at];
    let line_start = head.rfind('\n').map_or(0, |k| k + 1);
    let line = &text[line_start..at];
    match line.trim_start().split_once('=') {
        Some((id, _)) if id.trim().starts_with('#') => id.trim().to_string(),
        _ => format!("entity at byte {at}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings_hide_references_semicolons_and_parentheses_and_doubled_quotes_stay_inside() {
        // `''` is a quote inside a string: `'it''s #13; ('` is one string, `'''#14'''` the
        // string `'#14'`, `''''` the string `'`
        let t = "#1 = A('#12', #2, 'it''s #13; (', (#3, '''#14'''));\n\
            #2 = B('', #1, '''');\n#3=C(';');\n";
        let st: Vec<(u64, &str)> = statements(t).map(|s| (s.id, &t[s.start..s.end])).collect();
        assert_eq!(
            st,
            [
                (1, "#1 = A('#12', #2, 'it''s #13; (', (#3, '''#14'''));"),
                (2, "#2 = B('', #1, '''');"),
                (3, "#3=C(';');"),
            ]
        );
        assert_eq!(t[statements(t).next().unwrap().body..].find('A'), Some(1));
        let refs: Vec<u64> = references(t).map(|r| r.id).collect();
        assert_eq!(refs, [1, 2, 3, 2, 1, 3]);
        assert_eq!(
            top_level_args(&t[t.find('(').unwrap()..]),
            ["'#12'", "#2", "'it''s #13; ('", "(#3, '''#14''')"]
        );
        let (ids, starts, flat) = instances(t);
        assert_eq!(
            (ids, starts, flat),
            (vec![1, 2, 3], vec![0, 2, 3, 3], vec![2, 3, 1])
        );
        let e = check(t).unwrap_err();
        assert!(e.contains("cycle: #1 → #2 → #1"), "{e}");
        // a statement the text ends inside still counts for the cycle check
        let e = check("#5 = A((#5);").unwrap_err();
        assert!(e.contains("cycle: #5 → #5"), "{e}");
        assert_eq!(statements("#5 = A((#5);").count(), 0);
        // a line number counts the lines inside strings too
        let deep = format!("#1 = A('\n\n', {}{});", "(".repeat(100), ")".repeat(100));
        assert!(check(&deep).unwrap_err().starts_with("line 3:"));
    }

    const SURF: &str = "#33 = B_SPLINE_SURFACE_WITH_KNOTS('', 3, 3, ((#34, #35), (#36, #37)), \
        .UNSPECIFIED., .U., .U., .U., (4, 4), (4, 4), (0.0, 1.0), (0.0, 1.0), .UNSPECIFIED.);\n";

    #[test]
    fn sane_files_pass_and_hostile_multiplicities_and_nesting_are_named() {
        assert!(check(SURF).is_ok());
        for bad in [
            "1000000000",
            "2147483647",
            "-4",
            "0",
            "99999999999999999999",
        ] {
            let t = SURF.replacen("(4, 4)", &format!("(4, {bad})"), 1);
            let e = check(&t).unwrap_err();
            assert!(
                e.contains("#33") && e.contains("multiplicity"),
                "{bad}: {e}"
            );
        }
        let deep = format!("#1 = X({}{});", "(".repeat(10_000), ")".repeat(10_000));
        assert!(check(&deep).unwrap_err().contains("line 1"));
        // strings may hold anything
        assert!(check("#1 = PRODUCT('((((((((', '');").is_ok());
    }

    #[test]
    fn reference_cycles_and_deep_chains_are_named() {
        let ok = "#1 = A(#2, #3);\n#2 = B(#3, '#1');\n#3 = C((#4));\n#4 = D();\n";
        assert!(check(ok).is_ok());
        let e = check(&ok.replace("#4 = D()", "#4 = D(#2)")).unwrap_err();
        assert!(e.contains("cycle: #2 → #3 → #4 → #2"), "{e}");
        let e = check("#7 = SURFACE_CURVE('', #7, (#8), .CURVE_3D.);").unwrap_err();
        assert!(e.contains("cycle: #7 → #7"), "{e}");
        let chain = |n: usize| -> String {
            (1..=n)
                .map(|k| format!("#{k} = A(#{});\n", k + 1))
                .collect()
        };
        assert!(check(&chain(MAX_REF_DEPTH - 1)).is_ok());
        let e = check(&chain(MAX_REF_DEPTH + 5)).unwrap_err();
        assert!(e.contains("nested deeper than 256"), "{e}");
        // the same chain listed backwards is found from its far end first
        let back: String = (1..=MAX_REF_DEPTH + 5)
            .rev()
            .map(|k| format!("#{k} = A(#{});\n", k + 1))
            .collect();
        assert!(check(&back).unwrap_err().contains("nested deeper"));
    }
}
