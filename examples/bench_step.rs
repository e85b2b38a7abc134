//! Real-CAD benchmark (issue #14): every face of every STEP file of a corpus directory gridded
//! as `ellipgrid step grid --all` does, each file with a time limit; prints per file, per CAD
//! system and per surface type how many faces were gridded fold-free, and the commonest
//! reasons for the others.
//!
//! The corpus is not in the repository (licences vary): see `bench/step_corpus.md` for its
//! files, their sources (repository, commit, path, SHA-256) and how to fetch them.
//!
//! ```text
//! cargo run --release --example bench_step -- /work/corpus/step [--n 33] [--timeout 60] \
//!     [--only NAME] [--show REASON] [--linear direct|multigrid]
//! ```
//!
//! `--only NAME` runs the files whose name contains NAME; `--show REASON` prints the file and
//! face number of every face whose outcome contains REASON (e.g. `--show "(u, v)"`);
//! `--linear` the linear solver of the faces' elliptic steps (`step grid --linear`; default
//! multigrid, as there).

use ellipgrid::cad::{grid_face_blocks, read_step_faces, Route};
use ellipgrid::case::DistributionSpec;
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::mpsc;
use std::time::{Duration, Instant};

#[derive(Clone, Debug)]
enum Outcome {
    /// Gridded fold-free; the largest defect of the file's boundary healed (0: none).
    Ok(f64),
    Folded(f64),
    Refused(String),
    Failed(String),
}

/// A reason with numbers blanked, so that like reasons group.
fn class(m: &str) -> String {
    let tail = m.rsplit(": face ").next().unwrap_or(m);
    let tail = tail.split_once(": ").map_or(tail, |x| x.1);
    let mut out = String::new();
    let mut digit = false;
    for c in tail.chars() {
        if c.is_ascii_digit() || (digit && (c == '.' || c == 'e' || c == '-')) {
            if !digit {
                out.push('#');
            }
            digit = true;
        } else {
            digit = false;
            out.push(c);
        }
    }
    out.chars().take(110).collect()
}

/// (face number, surface type, outcome, whether the face has holes).
type Faces = Vec<(usize, &'static str, Outcome, bool)>;

fn grid_file(path: PathBuf, n: usize, linear: &str) -> Result<Faces, String> {
    let faces = read_step_faces(&path).map_err(|e| e.to_string())?;
    let d = DistributionSpec::Uniform {};
    Ok(faces
        .par_iter()
        .map(|f| {
            let o = match f.route() {
                Route::Refused(why) => Outcome::Refused(why),
                _ => {
                    let mut solver = ellipgrid::solve::select::by_name(linear).unwrap();
                    match grid_face_blocks(f, (n, n), &d, &d, solver.as_mut(), "") {
                        Ok(gs) => {
                            let folded = gs.iter().any(|g| g.quality.is_folded());
                            let healed = gs.iter().map(|g| g.healed).fold(0.0, f64::max);
                            if folded {
                                Outcome::Folded(healed)
                            } else {
                                Outcome::Ok(healed)
                            }
                        }
                        Err(e) => Outcome::Failed(e.to_string()),
                    }
                }
            };
            (
                f.index,
                f.surface_type,
                o,
                matches!(f.route(), Route::Holes(_)),
            )
        })
        .collect())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dir = PathBuf::from(args.first().map_or("/work/corpus/step", |s| s.as_str()));
    let opt = |name: &str, default: u64| {
        args.iter()
            .position(|a| a == name)
            .and_then(|k| args.get(k + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let (n, timeout) = (opt("--n", 33) as usize, opt("--timeout", 60));
    let text = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|k| args.get(k + 1))
            .cloned()
    };
    let (only, show) = (text("--only"), text("--show"));
    let linear = text("--linear").unwrap_or_else(|| "multigrid".into());
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("corpus directory")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("step") || e.eq_ignore_ascii_case("stp"))
        })
        .filter(|p| {
            only.as_ref()
                .is_none_or(|o| p.to_string_lossy().contains(o.as_str()))
        })
        .collect();
    files.sort();
    let mut by_system: BTreeMap<String, [usize; 3]> = BTreeMap::new();
    let mut by_type: BTreeMap<&str, [usize; 3]> = BTreeMap::new();
    let mut reasons: BTreeMap<String, usize> = BTreeMap::new();
    // Faces with holes (several loops): how many, how many gridded fold-free.
    let mut with_holes = [0usize; 2];
    // Faces whose boundary was healed beyond the file's tolerance: gridded, fold-free.
    let mut healed = [0usize; 2];
    let (mut all, mut ok_all, mut slowest) = (0, 0, (0.0, String::new()));
    println!("{n} × {n} nodes per face, time limit {timeout} s per file\n");
    println!(
        "{:<42} {:>6} {:>6} {:>6} {:>7} {:>6} {:>8}",
        "file", "faces", "ok", "folded", "refused", "failed", "seconds"
    );
    for path in files {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let system = name.split('_').nth(1).unwrap_or("?").to_string();
        let (tx, rx) = mpsc::channel();
        let t0 = Instant::now();
        let (p, l) = (path.clone(), linear.clone());
        std::thread::spawn(move || {
            let _ = tx.send(grid_file(p, n, &l));
        });
        let r = rx.recv_timeout(Duration::from_secs(timeout));
        let secs = t0.elapsed().as_secs_f64();
        if secs > slowest.0 {
            slowest = (secs, name.clone());
        }
        let faces = match r {
            Err(_) => {
                println!("{name:<42} TIMEOUT after {secs:.0} s");
                *reasons.entry("file: time limit".into()).or_default() += 1;
                continue;
            }
            Ok(Err(e)) => {
                println!("{name:<42} not read: {}", class(&e));
                *reasons.entry(format!("file: {}", class(&e))).or_default() += 1;
                continue;
            }
            Ok(Ok(f)) => f,
        };
        let count = |f: fn(&Outcome) -> bool| faces.iter().filter(|x| f(&x.2)).count();
        let ok = count(|o| matches!(o, Outcome::Ok(_)));
        let folded = count(|o| matches!(o, Outcome::Folded(_)));
        let refused = count(|o| matches!(o, Outcome::Refused(_)));
        let failed = count(|o| matches!(o, Outcome::Failed(_)));
        println!(
            "{name:<42} {:>6} {ok:>6} {folded:>6} {refused:>7} {failed:>6} {secs:>8.2}",
            faces.len()
        );
        all += faces.len();
        ok_all += ok;
        let s = by_system.entry(system).or_default();
        s[0] += faces.len();
        s[1] += ok;
        for (index, ty, o, holes) in &faces {
            if *holes {
                with_holes[0] += 1;
                with_holes[1] += usize::from(matches!(o, Outcome::Ok(_)));
            }
            let t = by_type.entry(ty).or_default();
            t[0] += 1;
            if matches!(o, Outcome::Ok(_)) {
                t[1] += 1;
            }
            if let Outcome::Ok(h) | Outcome::Folded(h) = o {
                if *h > 0.0 {
                    healed[0] += 1;
                    healed[1] += usize::from(matches!(o, Outcome::Ok(_)));
                    if show.as_deref() == Some("healed") {
                        println!("    {name} face {index}: healed {h:.3e}");
                    }
                }
            }
            let key = match o {
                Outcome::Ok(_) => continue,
                Outcome::Folded(_) => "folded".to_string(),
                Outcome::Refused(m) => format!("refused: {}", class(m)),
                Outcome::Failed(m) => format!("failed: {}", class(m)),
            };
            if show
                .as_ref()
                .is_some_and(|w| format!("{o:?}").contains(w.as_str()))
            {
                println!("    {name} face {index}: {o:?}");
            }
            *reasons.entry(key).or_default() += 1;
        }
    }
    let pct = |a: usize, b: usize| 100.0 * a as f64 / b.max(1) as f64;
    println!(
        "\nall: {ok_all} of {all} faces gridded fold-free ({:.1} %); slowest file {:.2} s ({})",
        pct(ok_all, all),
        slowest.0,
        slowest.1
    );
    println!(
        "faces with holes (several loops): {} of {} gridded fold-free",
        with_holes[1], with_holes[0]
    );
    println!(
        "faces healed (edges missing each other or the surface beyond the file's tolerance): \
         {} gridded, {} fold-free",
        healed[0], healed[1]
    );
    println!("\nby CAD system:");
    for (s, c) in &by_system {
        println!(
            "  {s:<16} {:>5} of {:>5} ({:>5.1} %)",
            c[1],
            c[0],
            pct(c[1], c[0])
        );
    }
    println!("\nby surface type:");
    for (s, c) in &by_type {
        println!(
            "  {s:<16} {:>5} of {:>5} ({:>5.1} %)",
            c[1],
            c[0],
            pct(c[1], c[0])
        );
    }
    let mut r: Vec<_> = reasons.into_iter().collect();
    r.sort_by_key(|x| std::cmp::Reverse(x.1));
    println!("\nreasons (faces):");
    for (m, c) in r.iter().take(25) {
        println!("  {c:>5}  {m}");
    }
}
