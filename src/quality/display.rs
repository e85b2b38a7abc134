//! The report as a table for the terminal.

use std::fmt;

use crate::quality::QualityReport;

/// A number in 4 significant digits, fixed or exponential by size; "-" for NaN.
pub(super) fn num(v: f64) -> String {
    if v.is_nan() {
        "-".to_string()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.to_string()
    } else if v == 0.0 {
        "0".to_string()
    } else if (1e-3..1e5).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

/// One table line: the metric name, then (label, value) columns with right-aligned values.
fn table_line(name: &str, cols: &[(&str, String)]) -> String {
    let mut l = format!("  {name:<20}");
    for (label, v) in cols {
        l += &format!(" {label:>4} {v:>10}");
    }
    l
}

impl fmt::Display for QualityReport {
    /// A compact table, one metric a line, one line per edge for orthogonality.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let status = if self.is_folded() { "FOLDED" } else { "ok" };
        writeln!(
            f,
            "grid quality  {} x {} nodes, {} cells, {}: {}",
            self.ni, self.nj, self.cells, self.orientation, status
        )?;
        let min_max = |a: f64, b: f64| [("min", num(a)), ("max", num(b))];
        let mut folded = table_line("folded cells", &[("", self.folded_cells.to_string())]);
        if !self.first_folded.is_empty() {
            folded += "   first:";
            for [i, j] in &self.first_folded {
                folded += &format!(" ({i},{j})");
            }
            if self.folded_cells > self.first_folded.len() {
                folded += " …";
            }
        }
        let lines = [
            table_line("jacobian", &min_max(self.jacobian_min, self.jacobian_max)),
            table_line("scaled jacobian", &[("min", num(self.scaled_jacobian_min))]),
            folded,
            table_line(
                "skewness",
                &[
                    ("max", num(self.skewness_max)),
                    ("mean", num(self.skewness_mean)),
                ],
            ),
            table_line("aspect ratio", &[("max", num(self.aspect_ratio_max))]),
            table_line(
                "growth ratio",
                &[("i", num(self.growth_i_max)), ("j", num(self.growth_j_max))],
            ),
            table_line("spacing", &min_max(self.min_spacing, self.max_spacing)),
        ];
        for l in lines {
            writeln!(f, "{}", l.trim_end())?;
        }
        for o in &self.orthogonality {
            let cols = [("max", num(o.max_deg)), ("mean", num(o.mean_deg))];
            let l = table_line(&format!("orthogonality {} (°)", o.edge), &cols);
            writeln!(f, "{l}  ({} nodes)", o.nodes)?;
        }
        Ok(())
    }
}

/// "cell (i, j), …" for messages about folded cells.
pub(crate) fn cell_list(c: &[[usize; 2]]) -> String {
    c.iter()
        .map(|c| format!("cell ({}, {})", c[0], c[1]))
        .collect::<Vec<_>>()
        .join(", ")
}
