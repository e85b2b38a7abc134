//! Benchmark of `ellipgrid verify` (issue #20): the whole verification of a case (every level
//! of the family, the warped surfaces, the scrambled start), with the runs in parallel and one
//! after the other, alternately in one process so that both see the same machine state; best
//! and median of the repeats (wall clock, and the CPU seconds of the process), and the seconds
//! of each level's generation in the best run.
//!
//! `cargo run --release --example bench_verify [-- CASE.toml] [--levels K] [--repeat R]`
//! (default: examples/wing_pylon.toml, 3 levels, 5 repeats)

use ellipgrid::case::LoadedCase;
use ellipgrid::job::verify::{verify, VerifyOptions, VerifyReport};
use std::path::PathBuf;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|k| args.get(k + 1))
            .map(|v| v.parse::<usize>().expect("a number"))
    };
    let levels = value("--levels").unwrap_or(3);
    let repeat = value("--repeat").unwrap_or(5);
    let case = args
        .iter()
        .enumerate()
        .find(|(k, a)| !a.starts_with("--") && (*k == 0 || !args[k - 1].starts_with("--")))
        .map(|(_, a)| PathBuf::from(a))
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/wing_pylon.toml")
        });
    let case = LoadedCase::read(&case).expect("the case reads");
    let mut runs: [Vec<VerifyReport>; 2] = [Vec::new(), Vec::new()];
    let mut cpu: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
    for _ in 0..repeat {
        for (k, parallel) in [true, false].into_iter().enumerate() {
            let opts = VerifyOptions {
                levels,
                parallel,
                ..VerifyOptions::default()
            };
            let c0 = cpu_seconds();
            runs[k].push(verify(&case, &opts, None).expect("verify runs"));
            cpu[k].push(cpu_seconds() - c0);
        }
    }
    println!(
        "verify {} ({} levels, {} threads, {repeat} runs each, alternating)",
        case.path.display(),
        levels,
        rayon::current_num_threads()
    );
    for (k, what) in ["parallel levels", "sequential levels"].iter().enumerate() {
        let mut secs: Vec<f64> = runs[k].iter().map(|r| r.seconds).collect();
        secs.sort_by(f64::total_cmp);
        let best = runs[k]
            .iter()
            .min_by(|a, b| a.seconds.total_cmp(&b.seconds))
            .expect("a run");
        let levels: Vec<String> = best
            .levels
            .iter()
            .map(|l| {
                let d = l.dims.first().copied().unwrap_or_default();
                format!(
                    "{}×{}{} {:.3} s",
                    d[0],
                    d[1],
                    if d[2] > 1 {
                        format!("×{}", d[2])
                    } else {
                        String::new()
                    },
                    l.seconds
                )
            })
            .collect();
        let mut c = cpu[k].clone();
        c.sort_by(f64::total_cmp);
        println!(
            "{what:<18} best {:.3} s  median {:.3} s  cpu median {:.3} s  (parallel: {}, pass: \
             {}; levels: {})",
            secs[0],
            secs[secs.len() / 2],
            c[c.len() / 2],
            best.parallel,
            best.pass,
            levels.join(", ")
        );
    }
}

/// User + system CPU seconds of this process so far.
fn cpu_seconds() -> f64 {
    // SAFETY: getrusage writes into the zeroed struct we pass.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) } != 0 {
        return f64::NAN;
    }
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}
