//! The layout's rules (docs/ARCHITECTURE.md), checked on the source text:
//! - the numerical folders (grid, algebraic, elliptic, solve, surface, quality) never read
//!   files and never reach case tables, jobs, I/O, CAD, plots or the command line;
//! - no circle of imports between modules (files), nor between the top-level folders;
//! - source files stay under ~500 lines of code (tests and comments not counted);
//! - docs/ARCHITECTURE.md names every module of a top-level folder (its files and subfolders).
//!
//! An import is a `crate::…` (or `super::…`) path in a module's non-test code, resolved to the
//! longest module path that exists; `mod` and `pub use` re-export lines, and a module's use of
//! its own submodules (how a folder's `mod.rs` assembles its files), are not counted.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const NUMERICS: [&str; 6] = [
    "grid",
    "algebraic",
    "elliptic",
    "solve",
    "surface",
    "quality",
];
const PLUMBING: [&str; 6] = ["case", "job", "io", "cad", "cli", "plot"];

/// Every `.rs` file under `dir`.
fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Module path of a source file: `src/solve/multigrid/mod.rs` → `solve::multigrid`.
fn module_of(src: &Path, f: &Path) -> Vec<String> {
    let rel = f.strip_prefix(src).unwrap().with_extension("");
    let mut m: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().into_owned())
        .collect();
    if m.last()
        .is_some_and(|s| s == "mod" || s == "lib" || s == "main")
    {
        m.pop();
    }
    m
}

/// The library code of a file: comments, `mod` and `pub use` lines dropped, and everything
/// from an inline `#[cfg(test)] mod … {` on (a test module is the last item of our files);
/// also the names of the file's `#[cfg(test)] mod name;` children (test-only modules).
fn code(text: &str) -> (Vec<String>, Vec<String>) {
    let (mut out, mut test_mods) = (Vec::new(), Vec::new());
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        let t = line.trim_start();
        if t.starts_with("#[cfg(test)]") {
            let next = lines.peek().map_or("", |l| l.trim());
            let decl = next.strip_prefix("pub(crate) ").unwrap_or(next);
            if let Some(name) = decl.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
                test_mods.push(name.trim().to_string());
                lines.next();
                continue;
            }
            if decl.starts_with("mod ") {
                break;
            }
            continue;
        }
        if t.starts_with("//") || t.starts_with("pub use") || t.starts_with("pub(crate) use") {
            continue;
        }
        let t = t.split("//").next().unwrap_or("");
        out.push(t.to_string());
    }
    (out, test_mods)
}

/// Paths (as segment lists) that follow `crate::` or `super::` in `s`, brace groups expanded.
fn paths(s: &str, module: &[String]) -> Vec<Vec<String>> {
    let b = s.as_bytes();
    let mut out = Vec::new();
    let mut k = 0;
    while k < b.len() {
        let rest = &b[k..];
        let (base, skip): (Vec<String>, usize) = if rest.starts_with(b"crate::") {
            (Vec::new(), 7)
        } else if rest.starts_with(b"super::")
            && (k == 0 || !is_ident(b[k - 1]) && b[k - 1] != b':')
        {
            let mut n = 0;
            let mut r = rest;
            while r.starts_with(b"super::") {
                n += 1;
                r = &r[7..];
            }
            let keep = module.len().saturating_sub(n);
            (module[..keep].to_vec(), 7 * n)
        } else {
            k += 1;
            continue;
        };
        if k > 0 && (is_ident(b[k - 1]) || b[k - 1] == b':') && skip == 7 && base.is_empty() {
            k += 1;
            continue;
        }
        let end = expand(&s[k + skip..], base, &mut out);
        k += skip + end.max(1);
    }
    out
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// Reads `a::b::{c, d::e}` at the start of `s` onto `prefix`; returns the bytes read.
fn expand(s: &str, prefix: Vec<String>, out: &mut Vec<Vec<String>>) -> usize {
    let b = s.as_bytes();
    let mut k = 0;
    let mut path = prefix;
    loop {
        if k < b.len() && b[k] == b'{' {
            // a brace group: items separated by top-level commas
            let mut depth = 0;
            let mut start = k + 1;
            let mut j = k;
            while j < b.len() {
                match b[j] {
                    b'{' => depth += 1,
                    b'}' => {
                        depth -= 1;
                        if depth == 0 {
                            expand_item(&s[start..j], &path, out);
                            return j + 1;
                        }
                    }
                    b',' if depth == 1 => {
                        expand_item(&s[start..j], &path, out);
                        start = j + 1;
                    }
                    _ => {}
                }
                j += 1;
            }
            return j;
        }
        let st = k;
        while k < b.len() && is_ident(b[k]) {
            k += 1;
        }
        if k == st {
            break;
        }
        path.push(s[st..k].to_string());
        if s[k..].starts_with("::") {
            k += 2;
        } else {
            break;
        }
    }
    out.push(path);
    k
}

fn expand_item(item: &str, prefix: &[String], out: &mut Vec<Vec<String>>) {
    let t = item.trim();
    if t.is_empty() || t == "self" || t.starts_with("self ") {
        out.push(prefix.to_vec());
        return;
    }
    expand(t, prefix.to_vec(), out);
}

struct Tree {
    /// module path → its library code lines
    modules: BTreeMap<Vec<String>, Vec<String>>,
    /// module path → source file
    file: BTreeMap<Vec<String>, PathBuf>,
}

fn tree() -> Tree {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut fs = Vec::new();
    files(&src, &mut fs);
    let mut t = Tree {
        modules: BTreeMap::new(),
        file: BTreeMap::new(),
    };
    let mut test_only = BTreeSet::new();
    for f in fs {
        let m = module_of(&src, &f);
        let text = std::fs::read_to_string(&f).unwrap();
        let (lines, tests) = code(&text);
        for name in tests {
            let mut c = m.clone();
            c.push(name);
            test_only.insert(c);
        }
        t.modules.insert(m.clone(), lines);
        t.file.insert(m, f);
    }
    t.modules.retain(|m, _| !test_only.contains(m));
    t
}

/// Module-level import graph: module → modules it uses (other than itself and its ancestors'
/// re-exports).
fn graph(t: &Tree) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let mut g = BTreeMap::new();
    for (m, lines) in &t.modules {
        let mut uses = BTreeSet::new();
        for line in lines {
            if line.starts_with("mod ") || line.starts_with("pub mod ") {
                continue;
            }
            for p in paths(line, m) {
                // the longest existing module prefix
                let target = (1..=p.len())
                    .rev()
                    .map(|n| p[..n].to_vec())
                    .find(|q| t.modules.contains_key(q));
                // a module's use of its own submodules is how a folder assembles them
                if let Some(q) = target {
                    if !q.starts_with(m) && !q.is_empty() {
                        uses.insert(q);
                    }
                }
            }
        }
        g.insert(m.clone(), uses);
    }
    g
}

/// A cycle in `g`, if any (depth-first search).
fn cycle<N: Ord + Clone>(g: &BTreeMap<N, BTreeSet<N>>) -> Option<Vec<N>> {
    fn visit<N: Ord + Clone>(
        n: &N,
        g: &BTreeMap<N, BTreeSet<N>>,
        state: &mut BTreeMap<N, u8>,
        stack: &mut Vec<N>,
    ) -> Option<Vec<N>> {
        match state.get(n) {
            Some(1) => {
                let at = stack.iter().position(|x| x == n).unwrap();
                let mut c = stack[at..].to_vec();
                c.push(n.clone());
                return Some(c);
            }
            Some(2) => return None,
            _ => {}
        }
        state.insert(n.clone(), 1);
        stack.push(n.clone());
        for m in g.get(n).into_iter().flatten() {
            if let Some(c) = visit(m, g, state, stack) {
                return Some(c);
            }
        }
        stack.pop();
        state.insert(n.clone(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in g.keys() {
        if let Some(c) = visit(n, g, &mut state, &mut Vec::new()) {
            return Some(c);
        }
    }
    None
}

#[test]
fn no_circle_of_imports_between_modules() {
    let mut g = graph(&tree());
    // every circle, each reported once (its closing edge removed before the next search)
    let mut circles = Vec::new();
    while let Some(c) = cycle(&g) {
        let names: Vec<String> = c.iter().map(|m| m.join("::")).collect();
        circles.push(names.join(" → "));
        let (a, b) = (&c[c.len() - 2], &c[c.len() - 1]);
        g.get_mut(a).unwrap().remove(b);
    }
    assert!(
        circles.is_empty(),
        "import circles:\n{}",
        circles.join("\n")
    );
}

#[test]
fn no_circle_of_imports_between_folders() {
    let g = graph(&tree());
    let mut top: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (m, uses) in &g {
        let Some(a) = m.first() else { continue };
        let e = top.entry(a.clone()).or_default();
        for u in uses {
            if u[0] != *a {
                e.insert(u[0].clone());
            }
        }
    }
    if let Some(c) = cycle(&top) {
        panic!("folder import circle: {}", c.join(" → "));
    }
}

#[test]
fn numerics_never_reach_files_cases_or_the_command_line() {
    let t = tree();
    let g = graph(&t);
    let mut bad = Vec::new();
    for (m, lines) in &t.modules {
        if !m.first().is_some_and(|a| NUMERICS.contains(&a.as_str())) {
            continue;
        }
        for u in &g[m] {
            if PLUMBING.contains(&u[0].as_str()) {
                bad.push(format!("{} uses {}", m.join("::"), u.join("::")));
            }
        }
        for l in lines {
            if l.contains("std::fs") || l.contains("File::open") || l.contains("File::create") {
                bad.push(format!("{} reads or writes files: {l}", m.join("::")));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn modules_stay_small() {
    let t = tree();
    let mut big = Vec::new();
    for (m, lines) in &t.modules {
        let n = lines.iter().filter(|l| !l.trim().is_empty()).count();
        if n > 520 {
            big.push(format!(
                "{} ({}): {n} lines",
                m.join("::"),
                t.file[m].display()
            ));
        }
    }
    assert!(big.is_empty(), "{}", big.join("\n"));
}

/// Every file and subfolder directly under a top-level folder of `src/` (but `mod.rs` and
/// test modules) is named in docs/ARCHITECTURE.md as `` `name` `` (or `` `name/` ``, `` `name: ``), so that
/// the map stays true as modules are added.
#[test]
fn the_architecture_map_names_every_module() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(root.join("docs/ARCHITECTURE.md")).unwrap();
    let mut missing = Vec::new();
    for folder in NUMERICS.iter().chain(PLUMBING.iter()) {
        let dir = root.join("src").join(folder);
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            let name = if p.is_dir() {
                p.file_name().unwrap().to_string_lossy().into_owned()
            } else if p.extension().is_some_and(|x| x == "rs") {
                p.file_stem().unwrap().to_string_lossy().into_owned()
            } else {
                continue;
            };
            if name == "mod" || name == "tests" {
                continue;
            }
            let named = [
                format!("`{name}`"),
                format!("`{name}/`"),
                format!("`{name}:"),
            ]
            .iter()
            .any(|k| doc.contains(k.as_str()));
            if !named {
                missing.push(format!("src/{folder}/{name}"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "docs/ARCHITECTURE.md does not name: {}",
        missing.join(", ")
    );
}

#[test]
fn the_path_parser_expands_brace_groups() {
    let m = vec!["a".to_string(), "b".to_string()];
    let p = paths(
        "use crate::{x::y, z::{w, v::u}}; let q = super::c::d(crate::e);",
        &m,
    );
    let s: Vec<String> = p.iter().map(|v| v.join("::")).collect();
    assert_eq!(s, ["x::y", "z::w", "z::v::u", "a::c::d", "e"]);
}
