//! Airfoil coordinate files (`.dat`) in Selig and Lednicer format.
//!
//! Selig: an optional name line, then "x y" rows from the trailing edge over the upper surface
//! to the leading edge and back along the lower surface. Lednicer: a name line, a line with the
//! two point counts ("65. 65."), the upper surface LE → TE, a blank line, the lower surface
//! LE → TE. Both are returned in Selig order with the leading edge once. Lines starting with
//! '#' are comments; columns after the second are ignored; ',' also separates columns and
//! Fortran 'D' exponents are accepted. Errors carry the 1-based line number.

use crate::curve::Spline;
use crate::{GeometryError, Vec3};

/// Parses a Selig or Lednicer airfoil file into points (z = 0) in Selig order.
///
/// # Errors
/// [`GeometryError::Parse`] naming the line of a malformed row or of a Lednicer count that does
/// not match the rows; [`GeometryError::Invalid`] if fewer than 3 points.
pub fn read_airfoil_dat(text: &str) -> Result<Vec<Vec3>, GeometryError> {
    // Non-blank, non-comment lines with their 1-based numbers.
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
        .peekable();
    // Optional name line: anything whose first two columns are not numbers.
    if let Some(&(_, l)) = lines.peek() {
        if numbers(l).len() < 2 {
            lines.next();
        }
    }
    let Some(&(count_line, l)) = lines.peek() else {
        return Err(GeometryError::Invalid(
            "airfoil file: no coordinates".into(),
        ));
    };
    let points = if let Some((nu, nl)) = lednicer_counts(l) {
        lines.next();
        let rows: Vec<(usize, &str)> = lines.collect();
        read_lednicer(&rows, nu, nl, count_line)?
    } else {
        lines
            .map(|(n, l)| parse_xy(n, l))
            .collect::<Result<Vec<_>, _>>()?
    };
    if points.len() < 3 {
        return Err(GeometryError::Invalid(format!(
            "airfoil file: only {} point(s)",
            points.len()
        )));
    }
    Ok(points)
}

/// A C² cubic spline through airfoil points (chord-length parametrization, natural ends).
///
/// Consecutive duplicate points (a leading edge listed twice, as some files do) are dropped.
///
/// # Errors
/// Fewer than 3 distinct points, or non-finite ones.
pub fn airfoil_curve(mut points: Vec<Vec3>) -> Result<Spline, GeometryError> {
    points.dedup();
    if points.len() < 3 {
        return Err(GeometryError::Invalid(format!(
            "airfoil curve: needs at least 3 distinct points, got {}",
            points.len()
        )));
    }
    Spline::new(points)
}

/// The leading numeric columns of a line (stops at the first non-number).
fn numbers(line: &str) -> Vec<f64> {
    line.split(|c: char| c.is_whitespace() || c == ',')
        .filter(|t| !t.is_empty())
        .map_while(|t| t.replace(['D', 'd'], "e").parse::<f64>().ok())
        .collect()
}

/// "x y [ignored …]" → point, or a parse error for that line.
fn parse_xy(line_no: usize, line: &str) -> Result<Vec3, GeometryError> {
    let v = numbers(line);
    if v.len() < 2 {
        return Err(GeometryError::Parse {
            line: line_no,
            message: format!("expected two numbers 'x y', found '{line}'"),
        });
    }
    if !(v[0].is_finite() && v[1].is_finite()) {
        return Err(GeometryError::Parse {
            line: line_no,
            message: format!("coordinates are not finite: '{line}'"),
        });
    }
    Ok(Vec3::new(v[0], v[1], 0.0))
}

/// A Lednicer count line: exactly two whole numbers ≥ 2 ("65. 65."). A Selig coordinate line
/// never looks like that (its y is not a whole number ≥ 2).
fn lednicer_counts(line: &str) -> Option<(usize, usize)> {
    let tokens = line
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter(|t| !t.is_empty())
        .count();
    let v = numbers(line);
    let whole = |x: f64| x.fract() == 0.0 && (2.0..1e7).contains(&x);
    (tokens == 2 && v.len() == 2 && whole(v[0]) && whole(v[1]))
        .then(|| (v[0] as usize, v[1] as usize))
}

/// Upper (LE → TE) and lower (LE → TE) rows → Selig order, leading edge once.
fn read_lednicer(
    rows: &[(usize, &str)],
    nu: usize,
    nl: usize,
    count_line: usize,
) -> Result<Vec<Vec3>, GeometryError> {
    if rows.len() != nu + nl {
        let (line, message) = if rows.len() < nu + nl {
            (
                rows.last().map_or(count_line, |r| r.0),
                format!(
                    "Lednicer counts on line {count_line} announce {nu} + {nl} points, the file has {}",
                    rows.len()
                ),
            )
        } else {
            (
                rows[nu + nl].0,
                format!("more points than the Lednicer counts ({nu} + {nl}) on line {count_line}"),
            )
        };
        return Err(GeometryError::Parse { line, message });
    }
    let pts = rows
        .iter()
        .map(|&(n, l)| parse_xy(n, l))
        .collect::<Result<Vec<_>, _>>()?;
    let (upper, lower) = pts.split_at(nu);
    let mut out: Vec<Vec3> = upper.iter().rev().copied().collect();
    let skip = usize::from(lower[0] == upper[0]);
    out.extend_from_slice(&lower[skip..]);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::{ArclengthMap, Curve};

    const SELIG: &str = "NACA 0012-ish test section
# comment line
1.0 0.00126
0.5 0.0529  extra-column ignored
0.0 0.0

0.5, -0.0529
1.0 -0.00126
";

    const LEDNICER: &str = "TEST LEDNICER
3.  3.

0.0 0.0
0.5 0.05
1.0 0.0

0.0 0.0
0.5 -0.04
1.0 0.0
";

    #[test]
    fn selig_with_name_and_comments() {
        let p = read_airfoil_dat(SELIG).unwrap();
        assert_eq!(p.len(), 5);
        assert_eq!(p[0], Vec3::new(1.0, 0.00126, 0.0));
        assert_eq!(p[1], Vec3::new(0.5, 0.0529, 0.0));
        assert_eq!(p[3], Vec3::new(0.5, -0.0529, 0.0));
        // Without the name line, and with a Fortran exponent.
        let p2 = read_airfoil_dat("1 0\n0.5 5.0D-02\n0 0\n0.5 -0.05\n1 0\n").unwrap();
        assert_eq!(p2.len(), 5);
        assert_eq!(p2[1].y, 0.05);
    }

    #[test]
    fn lednicer_to_selig_order() {
        let p = read_airfoil_dat(LEDNICER).unwrap();
        let want = [
            (1.0, 0.0),
            (0.5, 0.05),
            (0.0, 0.0),
            (0.5, -0.04),
            (1.0, 0.0),
        ];
        assert_eq!(p.len(), want.len());
        for (a, (x, y)) in p.iter().zip(want) {
            assert_eq!(*a, Vec3::new(x, y, 0.0));
        }
    }

    #[test]
    fn errors_carry_line_numbers() {
        let bad = "name\n1.0 0.0\n0.5 abc\n0.0 0.0\n";
        assert_eq!(
            read_airfoil_dat(bad).unwrap_err(),
            GeometryError::Parse {
                line: 3,
                message: "expected two numbers 'x y', found '0.5 abc'".into()
            }
        );
        let short = "L\n3. 3.\n0 0\n0.5 0.05\n1 0\n\n0 0\n0.5 -0.04\n";
        match read_airfoil_dat(short).unwrap_err() {
            GeometryError::Parse { line, .. } => assert_eq!(line, 8),
            e => panic!("{e}"),
        }
        let bad_row = "L\n2. 2.\n0 0\n1 x\n\n0 0\n1 0\n";
        assert!(read_airfoil_dat(bad_row)
            .unwrap_err()
            .to_string()
            .starts_with("line 4:"));
        assert!(read_airfoil_dat("# only a comment\n").is_err());
        assert!(read_airfoil_dat("1 0\n0 0\n").is_err());
    }

    #[test]
    fn curve_through_points_drops_duplicates() {
        let mut p = read_airfoil_dat(SELIG).unwrap();
        p.insert(2, p[2]);
        let c = airfoil_curve(p).unwrap();
        assert_eq!(c.points().len(), 5);
        assert_eq!(c.point(0.0), Vec3::new(1.0, 0.00126, 0.0));
    }

    /// The real RAE 2822 / ONERA D files, if present in the repository (or the shared data).
    #[test]
    fn real_files_if_present() {
        let dirs = [
            concat!(env!("CARGO_MANIFEST_DIR"), "/../data/"),
            concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data/"),
        ];
        for (name, count, te_y) in [("rae2822.dat", 129, 0.0), ("oneraD.dat", 143, 0.0007052)] {
            let Some(text) = dirs
                .iter()
                .find_map(|d| std::fs::read_to_string(format!("{d}{name}")).ok())
            else {
                eprintln!("skipping: {name} not found");
                continue;
            };
            let p = read_airfoil_dat(&text).unwrap();
            assert_eq!(p.len(), count, "{name}");
            assert_eq!(p[0], Vec3::new(1.0, te_y, 0.0));
            assert_eq!(p[count - 1], Vec3::new(1.0, -te_y, 0.0));
            let le = p.iter().fold(f64::INFINITY, |m, q| m.min(q.x));
            assert_eq!(le, 0.0);
            let curve = airfoil_curve(p.clone()).unwrap();
            for (q, &t) in p.iter().zip(curve.knots()) {
                assert!((curve.point(t) - q).norm() < 1e-14);
            }
            // Perimeter of a ~10–12 % thick section of unit chord: a little above 2.
            let len = ArclengthMap::new(&curve).length();
            assert!(len > 2.0 && len < 2.1, "{name}: {len}");
        }
    }
}
