//! Faces of a shell that the STEP reader leaves out, each with its entity id and the reason.
//!
//! truck-stepio builds a shell from the faces whose surface it can read and drops the others
//! after printing the reader's message (`Lookup failed for #2146`) to stderr; the faces after
//! them then get lower numbers. The same checks are made here face by face, so that `step
//! list` and `step grid` can name every face that is not read, its surface and why.

use super::prescan::statements;
use truck_stepio::r#in::alias::Surface as StepSurface;
use truck_stepio::r#in::ruststep::ast::Name;
use truck_stepio::r#in::ruststep::tables::{IntoOwned, PlaceHolder};
use truck_stepio::r#in::{ShellHolder, Table};

/// A face of a shell that the reader did not read.
#[derive(Clone, Debug, PartialEq)]
pub struct Unread {
    /// The face's entity id (`#531 = ADVANCED_FACE(…)`).
    pub face: u64,
    /// The shell's entity id.
    pub shell: u64,
    /// Why: the surface entity and the reader's message.
    pub reason: String,
}

impl std::fmt::Display for Unread {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "face entity #{} of shell #{}: {}",
            self.face, self.shell, self.reason
        )
    }
}

/// The faces of shell `id` that the reader drops (its `to_compressed_shell` reads a face if
/// the face entity resolves and its surface converts), in the shell's order. `text` is the
/// STEP text, for the surface entities' type names.
pub(super) fn unread_faces(table: &Table, id: u64, shell: &ShellHolder, text: &str) -> Vec<Unread> {
    let mut out = Vec::new();
    for face in &shell.cfs_faces {
        let PlaceHolder::Ref(Name::Entity(fid)) = face else {
            continue;
        };
        let reason = if let Some(fs) = table.face_surface.get(fid) {
            let sid = match &fs.face_geometry {
                PlaceHolder::Ref(Name::Entity(s)) => Some(*s),
                _ => None,
            };
            let read = fs
                .face_geometry
                .clone()
                .into_owned(table)
                .map_err(|e| e.to_string())
                .and_then(|s| StepSurface::try_from(&s).map_err(|e| e.to_string()));
            match (read, sid) {
                (Ok(_), _) => continue,
                (Err(e), Some(s)) => format!("its surface #{s} ({}): {e}", kind(text, s)),
                (Err(e), None) => format!("its surface: {e}"),
            }
        } else if table.oriented_face.contains_key(fid) {
            continue;
        } else {
            "not a face entity the reader knows".to_string()
        };
        out.push(Unread {
            face: *fid,
            shell: id,
            reason,
        });
    }
    out
}

/// The type name(s) of entity `id` in `text`: `NAME` of a simple instance, `A B C` of a
/// complex one, "missing" if the file has no such entity.
fn kind(text: &str, id: u64) -> String {
    let Some(st) = statements(text).find(|st| st.id == id) else {
        return "missing".into();
    };
    let body = text[st.body..st.end].trim_start();
    if body.starts_with('(') {
        partial_names(body).join(" ")
    } else {
        let len = body
            .bytes()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == b'_')
            .count();
        body[..len].to_string()
    }
}

/// The names of the partial entities of a complex instance's body `(A(…) B (…) …)`: the
/// word before each parenthesis that opens at depth 1.
fn partial_names(body: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut depth = 0usize;
    for (i, c) in super::prescan::code_bytes(body) {
        match c {
            b'(' => {
                if depth == 1 {
                    let before = body[..i].trim_end();
                    let len = before
                        .bytes()
                        .rev()
                        .take_while(|c| c.is_ascii_alphanumeric() || *c == b'_')
                        .count();
                    out.push(&before[before.len() - len..]);
                }
                depth += 1;
            }
            b')' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entity_kinds_name_simple_and_complex_instances() {
        let t = "DATA;\n#1=PLANE('',#2);\n#3 =( BOUNDED_SURFACE ( ) B_SPLINE_SURFACE(1,1,(('a(',#4)))\n\
            SURFACE());\nENDSEC;\n";
        assert_eq!(kind(t, 1), "PLANE");
        assert_eq!(kind(t, 3), "BOUNDED_SURFACE B_SPLINE_SURFACE SURFACE");
        assert_eq!(kind(t, 9), "missing");
    }
}
