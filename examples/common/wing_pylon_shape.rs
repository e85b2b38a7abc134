//! The shape of the wing–pylon example (paper Fig. 33–36): the lower surface of a wing of
//! NACA 0012 section (chord 2 m) next to a pylon, whose intersection with the wing is the wall
//! E3 (v = 0), and the wing's upper surface. Shared by `make_wing_pylon` (which writes the
//! shipped control net), `make_wing_pylon_step` (which writes the STEP model) and the tests
//! (which build other nets of the same shape, or check the model against it).
#![allow(dead_code)]

/// Chordwise extent of the patch (m), pylon leading edge, outboard edge (m).
pub const X_A: f64 = 0.2;
pub const X_B: f64 = 1.8;
pub const X_P: f64 = 0.6;
pub const Y_OUT: f64 = 1.0;

/// Half width of the pylon footprint at chordwise station x: a smooth nose of radius ~3 cm at
/// X_P, tapering aft.
pub fn pylon_half_width(x: f64) -> f64 {
    let xi = ((x - X_P) / (X_B - X_P)).clamp(0.0, 1.0);
    0.06 * 0.5 * (1.0 + ((x - X_P) / 0.03).tanh()) * (1.0 - 0.4 * xi)
}

/// The wing's lower surface z(x, y): NACA 0012 thickness on a 2 m chord, slight dihedral.
pub fn lower_surface(x: f64, y: f64) -> f64 {
    -half_thickness(x) + 0.02 * y
}

/// The wing's upper surface z(x, y): the mirror of [`lower_surface`]'s thickness, the same
/// dihedral.
pub fn upper_surface(x: f64, y: f64) -> f64 {
    half_thickness(x) + 0.02 * y
}

/// Half the NACA 0012 thickness (m) at chordwise station x on a 2 m chord.
fn half_thickness(x: f64) -> f64 {
    let c = 2.0;
    let t = x / c;
    let half = 0.6
        * (0.2969 * t.sqrt() - 0.1260 * t - 0.3516 * t * t + 0.2843 * t.powi(3)
            - 0.1015 * t.powi(4));
    c * half
}

/// The point of the patch at (a, b) ∈ [0, 1]²: a chordwise, b spanwise from the pylon.
pub fn patch_point(a: f64, b: f64) -> [f64; 3] {
    let x = X_A + (X_B - X_A) * a;
    let y0 = pylon_half_width(x);
    let y = y0 + (Y_OUT - y0) * b;
    [x, y, lower_surface(x, y)]
}

/// Chordwise net parameter with control points clustered strongly at the pylon nose:
/// a(s) = a0 + A sinh(k (s − s0)), densest where a = a0.
pub fn clustered_a(s: f64) -> f64 {
    let a0 = (X_P - X_A) / (X_B - X_A);
    let k: f64 = 5.0;
    // s0 from sinh(k (1 − s0)) / sinh(k s0) = (1 − a0) / a0, by bisection
    let (mut lo, mut hi): (f64, f64) = (1e-9, 1.0 - 1e-9);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if (k * (1.0 - m)).sinh() * a0 > (k * m).sinh() * (1.0 - a0) {
            lo = m;
        } else {
            hi = m;
        }
    }
    let s0 = 0.5 * (lo + hi);
    let amp = a0 / (k * s0).sinh();
    (a0 + amp * (k * (s - s0)).sinh()).clamp(0.0, 1.0)
}

/// Spanwise net parameter clustered at the pylon wall (spacing grows ~12× from the wall out).
pub fn clustered_b(s: f64) -> f64 {
    s * (0.15 + 0.85 * s)
}

/// A control net of `ni × nj` points (i fastest), clustered or uniform in (a, b).
pub fn net(ni: usize, nj: usize, clustered: bool) -> Vec<[f64; 3]> {
    (0..ni * nj)
        .map(|n| {
            let (i, j) = (n % ni, n / ni);
            let (s, t) = (i as f64 / (ni - 1) as f64, j as f64 / (nj - 1) as f64);
            if clustered {
                patch_point(clustered_a(s), clustered_b(t))
            } else {
                patch_point(s, t)
            }
        })
        .collect()
}
