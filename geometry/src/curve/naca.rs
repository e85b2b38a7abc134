//! NACA 4-digit airfoil \[Abbott & von Doenhoff\], thickness applied normal to the camber line.
//!
//! Half thickness y_t = 5 t c [0.2969 √ξ − 0.1260 ξ − 0.3516 ξ² + 0.2843 ξ³ + a₄ ξ⁴], ξ = x/c,
//! a₄ = −0.1036 (closed trailing edge) or −0.1015 (the original, blunt one). Camber line
//! y_c = m/p² (2pξ − ξ²) for ξ < p, m/(1−p)² (1 − 2p + 2pξ − ξ²) for ξ ≥ p.
//!
//! Parametrization: ξ = q² with q the signed square root of the chord position (q > 0 upper,
//! q < 0 lower surface). Then √ξ = |q| and the contour is a smooth function of q through the
//! leading edge (finite, non-zero derivative everywhere, unlike x(ξ)). The full contour uses
//! q = 1 − 2u (u = 0 upper TE, ½ LE, 1 lower TE); [`Naca4::upper`] uses q = u and
//! [`Naca4::lower`] q = −u. Derivatives are analytic. Breakpoints: the leading edge (the
//! thickness polynomial contains q|q|) and, when cambered, ξ = p (the camber curvature jumps).

use super::Curve;
use crate::{GeometryError, Vec3};

/// A NACA 4-digit section "MPTT" with chord c, leading edge at the origin, chord along +x.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Naca4 {
    /// Maximum camber / c.
    m: f64,
    /// Chordwise position of maximum camber / c.
    p: f64,
    /// Thickness / c.
    t: f64,
    chord: f64,
    /// Coefficient of ξ⁴ in the thickness polynomial.
    a4: f64,
}

/// One surface of a [`Naca4`], from the leading edge (u = 0) to the trailing edge (u = 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Naca4Side {
    airfoil: Naca4,
    /// +1 upper, −1 lower.
    sign: f64,
}

impl Naca4 {
    /// The section with 4-digit `code` ("0012", "2412"; a "NACA" prefix is accepted).
    ///
    /// `sharp_te` selects a₄ = −0.1036 (closed trailing edge) instead of −0.1015.
    ///
    /// # Errors
    /// A code that is not 4 digits, zero thickness, camber without a camber position, or a
    /// chord that is not positive and finite.
    pub fn new(code: &str, chord: f64, sharp_te: bool) -> Result<Naca4, GeometryError> {
        let trimmed = code.trim();
        let digits = trimmed
            .strip_prefix("NACA")
            .or_else(|| trimmed.strip_prefix("naca"))
            .unwrap_or(trimmed)
            .trim();
        let bad = |why: &str| GeometryError::Invalid(format!("NACA 4-digit code '{code}': {why}"));
        if digits.len() != 4 || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(bad("expected exactly 4 digits like 0012 or 2412"));
        }
        let d: Vec<f64> = digits.bytes().map(|b| f64::from(b - b'0')).collect();
        let (m, p, t) = (d[0] / 100.0, d[1] / 10.0, (10.0 * d[2] + d[3]) / 100.0);
        if t == 0.0 {
            return Err(bad("zero thickness"));
        }
        if m > 0.0 && p == 0.0 {
            return Err(bad("camber given but its position digit is 0"));
        }
        if !(chord.is_finite() && chord > 0.0) {
            return Err(GeometryError::Invalid(format!(
                "NACA airfoil: chord must be positive, got {chord}"
            )));
        }
        Ok(Naca4 {
            m,
            p: if m > 0.0 { p } else { 0.0 },
            t,
            chord,
            a4: if sharp_te { -0.1036 } else { -0.1015 },
        })
    }

    /// Chord length.
    pub fn chord(&self) -> f64 {
        self.chord
    }

    /// Maximum thickness / chord.
    pub fn thickness_ratio(&self) -> f64 {
        self.t
    }

    /// Upper surface, leading edge (u = 0) to trailing edge (u = 1).
    pub fn upper(&self) -> Naca4Side {
        Naca4Side {
            airfoil: *self,
            sign: 1.0,
        }
    }

    /// Lower surface, leading edge (u = 0) to trailing edge (u = 1).
    pub fn lower(&self) -> Naca4Side {
        Naca4Side {
            airfoil: *self,
            sign: -1.0,
        }
    }

    /// Camber line height y_c at chordwise position x (in length units, 0 ≤ x ≤ c).
    pub fn camber(&self, x: f64) -> f64 {
        self.chord * self.camber_line(x / self.chord).0
    }

    /// Half thickness y_t at chordwise position x (in length units, 0 ≤ x ≤ c).
    pub fn half_thickness(&self, x: f64) -> f64 {
        let xi = x / self.chord;
        self.chord * self.thickness(xi.max(0.0).sqrt()).0
    }

    /// (y_c, y_c', y_c'') at ξ, derivatives with respect to ξ.
    fn camber_line(&self, xi: f64) -> (f64, f64, f64) {
        let (m, p) = (self.m, self.p);
        if m == 0.0 {
            (0.0, 0.0, 0.0)
        } else if xi < p {
            let k = m / (p * p);
            (k * (2.0 * p * xi - xi * xi), 2.0 * k * (p - xi), -2.0 * k)
        } else {
            let k = m / ((1.0 - p) * (1.0 - p));
            (
                k * (1.0 - 2.0 * p + 2.0 * p * xi - xi * xi),
                2.0 * k * (p - xi),
                -2.0 * k,
            )
        }
    }

    /// Signed half thickness T(q) = sign(q) y_t(q²) and dT/dq (unit chord).
    fn thickness(&self, q: f64) -> (f64, f64) {
        let xi = q * q;
        let poly = xi * (-0.1260 + xi * (-0.3516 + xi * (0.2843 + xi * self.a4)));
        let dpoly = -0.1260 + xi * (-0.7032 + xi * (0.8529 + xi * 4.0 * self.a4));
        let t5 = 5.0 * self.t;
        (
            t5 * (0.2969 * q + q.signum() * poly),
            t5 * (0.2969 + 2.0 * q.abs() * dpoly),
        )
    }

    /// Point and d/dq at signed root chord position q (scaled by the chord).
    fn eval(&self, q: f64) -> (Vec3, Vec3) {
        let xi = q * q;
        let (tq, dtq) = self.thickness(q);
        let (yc, yc1, yc2) = self.camber_line(xi);
        let w = 1.0 + yc1 * yc1;
        let cos = 1.0 / w.sqrt();
        let sin = yc1 * cos;
        let dtheta = yc2 / w; // dθ/dξ with θ = atan(y_c').
        let x = xi - tq * sin;
        let y = yc + tq * cos;
        let dx = 2.0 * q - dtq * sin - tq * cos * dtheta * 2.0 * q;
        let dy = yc1 * 2.0 * q + dtq * cos - tq * sin * dtheta * 2.0 * q;
        let c = self.chord;
        (Vec3::new(c * x, c * y, 0.0), Vec3::new(c * dx, c * dy, 0.0))
    }
}

impl Curve for Naca4 {
    /// Full contour: upper TE (u = 0) → LE (u = ½) → lower TE (u = 1).
    fn point(&self, u: f64) -> Vec3 {
        self.eval(1.0 - 2.0 * u).0
    }

    fn derivative(&self, u: f64) -> Vec3 {
        -2.0 * self.eval(1.0 - 2.0 * u).1
    }

    fn breakpoints(&self) -> Vec<f64> {
        if self.m > 0.0 {
            let r = self.p.sqrt();
            vec![0.5 * (1.0 - r), 0.5, 0.5 * (1.0 + r)]
        } else {
            vec![0.5]
        }
    }
}

impl Curve for Naca4Side {
    fn point(&self, u: f64) -> Vec3 {
        self.airfoil.eval(self.sign * u).0
    }

    fn derivative(&self, u: f64) -> Vec3 {
        self.sign * self.airfoil.eval(self.sign * u).1
    }

    fn breakpoints(&self) -> Vec<f64> {
        if self.airfoil.m > 0.0 {
            vec![self.airfoil.p.sqrt()]
        } else {
            vec![]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn naca0012_thickness_and_symmetry() {
        let a = Naca4::new("0012", 1.0, false).unwrap();
        let up = a.upper();
        let (mut ymax, mut xmax) = (0.0, 0.0);
        for i in 0..=20000 {
            let p = up.point(i as f64 / 20000.0);
            if p.y > ymax {
                (ymax, xmax) = (p.y, p.x);
            }
        }
        assert!((ymax - 0.06).abs() < 1e-3, "{ymax}");
        assert!((xmax - 0.3).abs() < 1e-2, "{xmax}");
        // Tabulated y_t(0.3) = 0.06002 for the 0012.
        assert!((a.half_thickness(0.3) - 0.060_02).abs() < 1e-5);
        for &u in &[0.0, 0.013, 0.2, 0.49, 0.5] {
            let (p, q) = (a.point(u), a.point(1.0 - u));
            assert!(
                (p.x - q.x).abs() < 1e-15 && (p.y + q.y).abs() < 1e-15,
                "{u}"
            );
        }
        assert_eq!(a.point(0.5), Vec3::zeros());
        // Blunt trailing edge: gap 2·5·0.12·0.0021 = 0.00252.
        assert!(((a.point(0.0) - a.point(1.0)).norm() - 0.00252).abs() < 1e-9);
    }

    #[test]
    fn naca2412_camber() {
        let a = Naca4::new("NACA 2412", 2.0, true).unwrap();
        assert!((a.camber(0.8) - 0.04).abs() < 1e-15);
        // Thickness is applied normal to the camber line: the midpoint of the upper and lower
        // points at the same ξ lies on the camber line at that ξ.
        let q = 0.4f64.sqrt();
        let mid = 0.5 * (a.upper().point(q) + a.lower().point(q));
        assert!((mid - Vec3::new(0.8, 0.04, 0.0)).norm() < 1e-14, "{mid}");
        // Elsewhere the camber line is inclined, so the normal offset moves x: at ξ = 0.1 the
        // midpoint is still on the camber line but the upper point lies ahead of ξ c.
        let q = 0.1f64.sqrt();
        let (up, lo) = (a.upper().point(q), a.lower().point(q));
        assert!(((up + lo) / 2.0 - Vec3::new(0.2, a.camber(0.2), 0.0)).norm() < 1e-14);
        assert!(up.x < 0.2 - 1e-3 && lo.x > 0.2 + 1e-3);
        let unit = Naca4::new("2412", 1.0, false).unwrap();
        assert!((unit.camber(0.4) - 0.02).abs() < 1e-16);
        // Aft of p: y_c(0.7) = 0.02/0.36 (1 − 0.8 + 0.56 − 0.49) = 0.015.
        assert!((a.camber(1.4) - 2.0 * 0.015).abs() < 1e-15);
    }

    #[test]
    fn sharp_te_closes() {
        for code in ["0012", "2412", "4415"] {
            let a = Naca4::new(code, 1.0, true).unwrap();
            assert!((a.point(0.0) - a.point(1.0)).norm() < 1e-12, "{code}");
            assert!((a.upper().point(1.0) - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-12);
        }
    }

    #[test]
    fn derivative_matches_central_difference() {
        let h = 1e-6;
        for code in ["0012", "2412"] {
            let a = Naca4::new(code, 1.5, false).unwrap();
            let sides: [&dyn Curve; 3] = [&a, &a.upper(), &a.lower()];
            for c in sides {
                for &u in &[0.0, 0.05, 0.21, 0.5, 0.57, 0.93, 1.0] {
                    if c.breakpoints()
                        .iter()
                        .any(|b| (b - u).abs() < 1e-3 && u != 0.5)
                    {
                        continue;
                    }
                    let fd = (c.point(u + h) - c.point(u - h)) / (2.0 * h);
                    let d = c.derivative(u);
                    assert!(
                        (fd - d).norm() < 1e-6 * d.norm(),
                        "{code} u={u}: {fd} vs {d}"
                    );
                    assert!(d.norm() > 0.1, "speed must not vanish");
                }
            }
        }
    }

    #[test]
    fn bad_codes() {
        for code in ["012", "00120", "00a2", "2012", "0000", ""] {
            assert!(Naca4::new(code, 1.0, true).is_err(), "{code}");
        }
        assert!(Naca4::new("0012", 0.0, true).is_err());
    }
}
