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

/// One table line: the metric name in `width` columns, then (label, value) columns with
/// right-aligned values.
pub(super) fn table_line(width: usize, name: &str, cols: &[(&str, String)]) -> String {
    let mut l = format!("  {name:<width$}");
    for (label, v) in cols {
        l += &format!(" {label:>4} {v:>10}");
    }
    l
}

/// "   first: (i,j) (i,j) …" of the first listed cells out of `count` ("" if none is listed).
pub(super) fn first_cells<const N: usize>(first: &[[usize; N]], count: usize) -> String {
    if first.is_empty() {
        return String::new();
    }
    let mut l = "   first:".to_string();
    for c in first {
        let idx: Vec<String> = c.iter().map(|v| v.to_string()).collect();
        l += &format!(" ({})", idx.join(","));
    }
    if count > first.len() {
        l += " …";
    }
    l
}

/// Width of the metric names in the planar report.
const NAME_WIDTH: usize = 20;

impl fmt::Display for QualityReport {
    /// A compact table, one metric a line, one line per edge for orthogonality.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let status = if self.is_folded() { "FOLDED" } else { "ok" };
        writeln!(
            f,
            "grid quality  {} x {} nodes, {} cells, {}: {}",
            self.ni, self.nj, self.cells, self.orientation, status
        )?;
        let table_line = |name: &str, cols: &[(&str, String)]| table_line(NAME_WIDTH, name, cols);
        let min_max = |a: f64, b: f64| [("min", num(a)), ("max", num(b))];
        let mut folded = table_line("folded cells", &[("", self.folded_cells.to_string())]);
        folded += &first_cells(&self.first_folded, self.folded_cells);
        let mut lines = vec![
            table_line("jacobian", &min_max(self.jacobian_min, self.jacobian_max)),
            table_line("scaled jacobian", &[("min", num(self.scaled_jacobian_min))]),
            folded,
        ];
        if self.collapsed_cells > 0 {
            // a pole or a CAD face's cusp: its cells apart, as the volume report's flat edges
            let n = self.collapsed_cells.to_string();
            lines.push(format!(
                "{}   (triangles at a side collapsed to a point; scaled jacobian min {} off them)",
                table_line("collapsed-side cells", &[("", n)]),
                num(self.scaled_jacobian_min_regular)
            ));
        }
        lines.extend([
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
        ]);
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

/// "cell (i, j), …" or "cell (i, j, k), …" for messages about folded cells.
pub(crate) fn cell_list<const N: usize>(c: &[[usize; N]]) -> String {
    c.iter()
        .map(|c| {
            let idx: Vec<String> = c.iter().map(|v| v.to_string()).collect();
            format!("cell ({})", idx.join(", "))
        })
        .collect::<Vec<_>>()
        .join(", ")
}
