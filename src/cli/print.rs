//! Human-readable output of a run: the Picard history and the quality table per block.

use ellipgrid::elliptic::picard::{Nonlinear, PicardInfo};
use ellipgrid::job::smooth::SmoothReport;
use ellipgrid::job::{BlockReport, RunReport};

/// Prints what `smooth` did to a block.
pub fn smoothed(r: &SmoothReport) {
    println!(
        "block {}: {} system, start from the {}",
        r.block, r.method, r.start
    );
    if let Some(p) = &r.picard {
        history(p);
    }
    println!("{}", r.quality);
}

/// Prints a block's Picard history and quality report.
pub fn block(b: &BlockReport) {
    println!(
        "block '{}' ({} × {} nodes), {:.3} s{}",
        b.name,
        b.ni,
        b.nj,
        b.seconds,
        b.group
            .as_ref()
            .map(|g| format!(" (gridded as one with {g})"))
            .unwrap_or_default()
    );
    if let Some(p) = &b.picard {
        history(p);
    }
    if let Some(d) = &b.surface_distance {
        println!(
            "  distance from the reference surface: max {:.3e}, rms {:.3e}",
            d.max, d.rms
        );
    }
    if let Some(d) = &b.model_distance {
        println!(
            "  nodes moved onto the STEP model: max {:.3e}, rms {:.3e}",
            d.max, d.rms
        );
    }
    if let Some(t) = &b.surface_steps {
        println!(
            "  Section 4 pipeline: initial grid {:.3} s, Laplace–Beltrami {:.3} s, target {:.3} s, \
             inversion {:.3} s",
            t.initial_grid, t.laplace_beltrami, t.target, t.inversion
        );
    }
    for w in &b.wall {
        println!(
            "  wall {}: first spacing {:.3e} … {:.3e}, {:.3} … {:.3} of the target (the side \
             edges' spacing interpolated along the wall; a periodic block's: its cut's) ({} nodes)",
            w.edge, w.first_min, w.first_max, w.ratio_min, w.ratio_max, w.nodes
        );
    }
    println!("{}", b.quality);
}

/// Prints the smoothness of the grid across every interior edge.
pub fn interfaces(list: &[ellipgrid::job::multiblock::InterfaceReport]) {
    smoothness_table(
        "edge",
        "blocks",
        list.iter().map(|f| {
            (
                f.edge.as_str(),
                format!("{} | {}", f.blocks[0], f.blocks[1]),
                &f.smoothness,
                if f.floating { "  (floating)" } else { "" },
            )
        }),
    );
}

/// Prints the smoothness of the grid across every interior face of a volume topology.
pub fn face_interfaces(list: &[ellipgrid::job::multivolume::FaceInterfaceReport]) {
    let notes: Vec<String> = list
        .iter()
        .map(|f| {
            let next = match (
                f.smoothness.turn_next_max_deg,
                f.smoothness.turn_next_mean_deg,
            ) {
                (Some(m), Some(a)) => format!("  next node turns {m:.1} / {a:.1}"),
                _ => String::new(),
            };
            next + &match &f.floating {
                Some(h) => format!(
                    "  (floating{}: {} rounds, last move {:.1e}{})",
                    if h.planar { ", planar" } else { "" },
                    h.rounds,
                    h.updates.last().copied().unwrap_or(0.0),
                    if h.converged { "" } else { ", not converged" }
                ),
                None => String::new(),
            }
        })
        .collect();
    smoothness_table(
        "face",
        "volumes",
        list.iter().zip(&notes).map(|(f, note)| {
            (
                f.face.as_str(),
                format!("{} | {}", f.volumes[0], f.volumes[1]),
                &f.smoothness,
                note.as_str(),
            )
        }),
    );
}

/// One line per interface: its name, the two blocks, kink and spacing ratio, a note.
fn smoothness_table<'a>(
    what: &str,
    between: &str,
    rows: impl ExactSizeIterator<
        Item = (
            &'a str,
            String,
            &'a ellipgrid::quality::interface::InterfaceSmoothness,
            &'a str,
        ),
    >,
) {
    if rows.len() == 0 {
        return;
    }
    println!("interfaces: kink of the crossing grid lines (deg) and first-spacing ratio");
    println!(
        "  {:<16} {:<24} {:>9} {:>9} {:>9} {:>9}",
        what, between, "kink max", "mean", "ratio max", "mean"
    );
    for (name, pair, s, note) in rows {
        println!(
            "  {:<16} {:<24} {:>9.3} {:>9.3} {:>9.4} {:>9.4}{note}",
            name, pair, s.kink_max_deg, s.kink_mean_deg, s.spacing_ratio_max, s.spacing_ratio_mean,
        );
    }
}

/// Prints one line per face of a volume topology: kind, size, time, solve, folding.
pub fn faces(list: &[ellipgrid::job::multivolume::FaceReport]) {
    if list.is_empty() {
        return;
    }
    println!("faces:");
    for f in list {
        let solve = match &f.picard {
            Some(p) => format!(
                ", {} Picard steps{}",
                p.steps,
                if p.converged { "" } else { " NOT converged" }
            ),
            None => String::new(),
        };
        println!(
            "  {:<16} {:<8} {:>4} × {:<4} {:.3} s{solve}, min scaled Jacobian {:.3}, folded cells {}",
            f.name,
            format!("{:?}", f.kind).to_lowercase(),
            f.ni,
            f.nj,
            f.seconds,
            f.quality.scaled_jacobian_min,
            f.quality.folded_cells
        );
    }
}

/// Prints a volume block's Picard history and 3D quality report.
pub fn volume(v: &ellipgrid::job::volume::VolumeReport) {
    println!(
        "volume '{}' ({} × {} × {} nodes), {:.3} s",
        v.name, v.ni, v.nj, v.nk, v.seconds
    );
    match &v.mirror_of {
        // not solved: its history is its original's
        Some(a) => println!(
            "  the mirror image of '{a}' (not solved; its own boundary within {:.1e} of the \
             mirror image of '{a}''s)",
            v.mirror_deviation.unwrap_or(0.0)
        ),
        None => history(&v.picard),
    }
    println!("{}", v.quality);
    if let Some(w) = &v.wall {
        println!(
            "  wall {}: first grid lines {:.3}° (mean {:.3}°) from the normal; first node at \
             {:.3} … {:.3} of the prescribed wall-normal spacing ({} nodes off the rim)",
            w.face, w.angle_max_deg, w.angle_mean_deg, w.ratio_min, w.ratio_max, w.nodes
        );
    }
    if !v.picard.converged && v.mirror_of.is_none() {
        eprintln!(
            "warning: volume '{}': Picard iteration stopped after {} steps (tolerance {:.1e})",
            v.name, v.picard.steps, v.picard.tolerance
        );
    }
    if let (Some(p), None) = (&v.picard.passes, &v.mirror_of) {
        println!(
            "  correction passes: {} run, the grid keeps pass {}",
            p.run, p.kept
        );
        if let Some(why) = &p.fell_back {
            eprintln!(
                "warning: volume '{}': {why}; the grid is pass {}'s, the best fold-free one: \
                 its wall and orthogonal faces are as the quality lines above say, not as asked",
                v.name, p.kept
            );
        }
    }
}

/// The name of the nonlinear iteration a report ran, with its Anderson depth.
fn iteration(p: &PicardInfo) -> String {
    match (p.nonlinear, p.anderson) {
        (Nonlinear::Newton, _) => "Newton–Krylov".into(),
        (Nonlinear::Picard, 0) => "Picard".into(),
        (Nonlinear::Picard, k) => format!("Picard, Anderson depth {k}"),
    }
}

/// Prints a Picard (or Newton–Krylov) history, after the one it started from (step 1 of
/// the orthogonality), if any.
pub fn history(p: &PicardInfo) {
    if let Some(f) = &p.first {
        println!("  orthogonality, step 1 (straight-line control functions):");
        history(f);
        println!("  orthogonality, step 3 (Hermite-blended control functions) from its grid:");
    }
    println!(
        "  {} steps ({}; {}), {}",
        p.steps,
        iteration(p),
        p.linear_solver,
        if p.converged {
            "converged".to_string()
        } else {
            format!("NOT converged to {:.1e}", p.tolerance)
        }
    );
    println!("  step   max update   residual[24]   linear its   linear res");
    for (k, s) in p.history.iter().enumerate() {
        let its = s
            .linear_iterations
            .iter()
            .map(|v| v.to_string())
            .collect::<Vec<_>>()
            .join("/");
        let lres = s.linear_residual.iter().cloned().fold(0.0f64, f64::max);
        println!(
            "  {:>4}   {:>10.3e}   {:>12.3e}   {:>10}   {:>10.2e}",
            k + 1,
            s.update,
            s.residual,
            its,
            lres
        );
    }
    println!("  final residual[24] {:.3e}", p.final_residual);
    if let Some(wu) = p.work_units {
        println!(
            "  nested iteration: coarse-level steps {:?}; whole grid {:.1} work units",
            p.coarse_steps, wu
        );
    }
}

/// Warns about blocks whose Picard iteration did not converge.
pub fn not_converged(r: &RunReport) {
    for b in &r.blocks {
        let Some(p) = &b.picard else { continue };
        if !p.converged {
            eprintln!(
                "warning: block '{}': {} iteration stopped after {} steps at update {:.3e} \
                 (tolerance {:.1e})",
                b.name,
                iteration(p),
                p.steps,
                p.history.last().map_or(f64::NAN, |s| s.update),
                p.tolerance
            );
        }
    }
}
