//! `--write DIR` of the benchmarks: each computed grid (or linear solution) as raw
//! little-endian f64, one file per case, so that `scripts/same-grids.sh` can compare two
//! builds byte for byte.

use std::path::PathBuf;

/// The folder given by `--write DIR`, if any (created).
pub fn target() -> Option<PathBuf> {
    let args: Vec<String> = std::env::args().collect();
    let dir = args
        .iter()
        .position(|a| a == "--write")
        .and_then(|k| args.get(k + 1))
        .map(PathBuf::from)?;
    std::fs::create_dir_all(&dir).expect("--write: cannot create the folder");
    Some(dir)
}

/// Writes `parts` one after the other to `DIR/name.f64` when `--write DIR` was given.
pub fn dump(name: &str, parts: &[&[f64]]) {
    let Some(dir) = target() else { return };
    let mut bytes = Vec::new();
    for p in parts {
        for v in p.iter() {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
    }
    let name: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let path = dir.join(format!("{name}.f64"));
    std::fs::write(&path, bytes).expect("--write: cannot write");
}
