//! Writes the shipped STEP model `data/step/wing_pylon.step` of the wing–pylon example: four
//! bicubic B-spline faces in one open shell, interpolating the analytic shape of
//! `common/wing_pylon_shape.rs`, in this order:
//!
//! 1. the wing's lower surface inboard, y ∈ [−0.2, 0.5], normal down (−z);
//! 2. the wing's lower surface outboard, y ∈ [0.5, 1.2], normal down; its side v = 1 is face
//!    1's side v = 0 (y = 0.5) exactly, one shared edge of the shell;
//! 3. the wing's upper surface, y ∈ [−0.2, 1.2], normal up (+z);
//! 4. the pylon's outboard side wall y = +pylon_half_width(x), z ∈ [−0.45, 0.05], normal
//!    outboard (+y); it pierces the wing's lower surface along the junction curve.
//!
//! Every face has x ∈ [0.1, 1.9] and u = (x − 0.1)/1.8 (x is linear in u, so the stations
//! are where the interpolation points are); v runs across (y or z, linear in v). Each face is
//! the tensor-product cubic spline interpolating the shape at the chordwise stations (spacing
//! growing from 1 mm at the pylon nose X_P and 1.5 mm at the pylon's taper kink X_B, 2 cm at
//! the leading edge, to at most 6 cm: 109 stations) and at four v stations (the shape is linear across, so that
//! is exact): not-a-knot end conditions, rows first, then columns. It prints each face's fit
//! error: the largest deviation from the shape (in z for the wing, in y for the pylon: an
//! upper bound of the distance) at the midpoints between the interpolation points.
//!
//! `cargo run --release --example make_wing_pylon_step [OUT]`

#[path = "common/wing_pylon_shape.rs"]
pub mod shape;

use ellipgrid::cad::write_step_surfaces;
use nalgebra::{DMatrix, Dyn, LU};
use std::path::Path;
use truck_geometry::prelude::{BSplineSurface, KnotVec, ParametricSurface, Point3};

/// The faces' chordwise extent (m).
const X0: f64 = 0.1;
const X1: f64 = 1.9;
/// The wing's inboard end, the joint of faces 1 and 2, its outboard end (m).
const Y_IN: f64 = -0.2;
const Y_JOINT: f64 = 0.5;
const Y_OUT: f64 = 1.2;
/// The pylon wall's top and bottom (m).
const Z_TOP: f64 = 0.05;
const Z_BOTTOM: f64 = -0.45;

/// Chordwise station spacing (m): least at the leading edge, the pylon nose, the pylon's
/// taper kink; growth per metre away from them; largest.
const H_LEADING_EDGE: f64 = 0.02;
const H_NOSE: f64 = 0.001;
const H_KINK: f64 = 0.0015;
const GROWTH: f64 = 0.15;
const H_MAX: f64 = 0.06;

/// Stations across each face (v = 0, 1/3, 2/3, 1).
const NV: usize = 4;

fn main() -> ellipgrid::Result<()> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "data/step/wing_pylon.step".into());
    let faces = model();
    for (k, f) in faces.iter().enumerate() {
        let n = f.surface.control_points().len();
        println!(
            "face {}: {}: {n} × {NV} control points, fit error {:.2e} m",
            k + 1,
            f.name,
            f.fit_error
        );
    }
    let path = Path::new(&out);
    let surfaces: Vec<_> = faces.into_iter().map(|f| f.surface).collect();
    write_step_surfaces(path, &surfaces)?;
    let size = std::fs::metadata(path).map_or(String::new(), |m| format!(", {} bytes", m.len()));
    println!("wrote {out} ({} faces{size})", surfaces.len());
    Ok(())
}

/// One face of the model.
pub struct Face {
    pub name: &'static str,
    pub surface: BSplineSurface<Point3>,
    /// The largest deviation from the shape at the midpoints (m), see the module doc.
    pub fit_error: f64,
}

/// The model's four faces, in the file's order (the module doc).
pub fn model() -> Vec<Face> {
    let xs = stations();
    let us: Vec<f64> = xs.iter().map(|x| (x - X0) / (X1 - X0)).collect();
    let vs: Vec<f64> = (0..NV).map(|l| l as f64 / (NV - 1) as f64).collect();
    let (iu, iv) = (Interpolation::new(&us), Interpolation::new(&vs));
    // exact at both ends, so that faces 1 and 2 get the same points at y = 0.5
    let lerp = |a: f64, b: f64, t: f64| a * (1.0 - t) + b * t;
    let wing = |y0: f64, y1: f64, z: fn(f64, f64) -> f64| {
        move |x: f64, v: f64| {
            let y = lerp(y0, y1, v);
            Point3::new(x, y, z(x, y))
        }
    };
    let lower = shape::lower_surface as fn(f64, f64) -> f64;
    let upper = shape::upper_surface as fn(f64, f64) -> f64;
    let pylon =
        |x: f64, v: f64| Point3::new(x, shape::pylon_half_width(x), lerp(Z_TOP, Z_BOTTOM, v));
    let wing_off = |z: fn(f64, f64) -> f64| move |p: Point3| (p.z - z(p.x, p.y)).abs();
    let pylon_off = |p: Point3| (p.y - shape::pylon_half_width(p.x)).abs();
    type Shape<'a> = &'a dyn Fn(f64, f64) -> Point3;
    type Off<'a> = &'a dyn Fn(Point3) -> f64;
    let faces: [(&str, Shape, Off); 4] = [
        (
            "wing lower surface, inboard",
            &wing(Y_JOINT, Y_IN, lower),
            &wing_off(lower),
        ),
        (
            "wing lower surface, outboard",
            &wing(Y_OUT, Y_JOINT, lower),
            &wing_off(lower),
        ),
        (
            "wing upper surface",
            &wing(Y_IN, Y_OUT, upper),
            &wing_off(upper),
        ),
        ("pylon outboard side wall", &pylon, &pylon_off),
    ];
    faces
        .into_iter()
        .map(|(name, point, off)| {
            let surface = fit(&iu, &iv, &xs, &vs, point);
            let fit_error = fit_error(&surface, &us, &vs, off);
            Face {
                name,
                surface,
                fit_error,
            }
        })
        .collect()
}

/// The chordwise stations from X0 to X1, X_P and X_B among them: the spacing grows by
/// [`GROWTH`] per metre from its least values at the leading edge, X_P and X_B, up to
/// [`H_MAX`]; each of the three intervals is marched and then scaled to end on its end.
fn stations() -> Vec<f64> {
    let h = |x: f64| {
        (H_LEADING_EDGE + GROWTH * (x - X0))
            .min(H_NOSE + GROWTH * (x - shape::X_P).abs())
            .min(H_KINK + GROWTH * (x - shape::X_B).abs())
            .min(H_MAX)
    };
    let mut xs = vec![X0];
    for (a, b) in [(X0, shape::X_P), (shape::X_P, shape::X_B), (shape::X_B, X1)] {
        let mut march = vec![a];
        while *march.last().unwrap() < b {
            let x = *march.last().unwrap();
            march.push(x + h(x));
        }
        let scale = (b - a) / (march.last().unwrap() - a);
        let n = march.len() - 1;
        xs.extend(march[1..n].iter().map(|x| a + (x - a) * scale));
        xs.push(b);
    }
    xs
}

/// Cubic spline interpolation at given parameters, not-a-knot: the knots are the interior
/// parameters but the second and the last but one (Bézier for four points), and the
/// collocation matrix N_j(t_k) is factored once for every row or column to fit.
struct Interpolation {
    knots: KnotVec,
    lu: LU<f64, Dyn, Dyn>,
}

impl Interpolation {
    fn new(t: &[f64]) -> Self {
        let n = t.len();
        assert!(n >= 4, "cubic interpolation needs four points or more");
        let mut k = vec![t[0]; 4];
        k.extend_from_slice(&t[2..n - 2]);
        k.extend([t[n - 1]; 4]);
        let knots = KnotVec::from(k);
        let mut a = DMatrix::zeros(n, n);
        // the ends by the clamped knots (truck's basis is 0 at the last knot)
        a[(0, 0)] = 1.0;
        a[(n - 1, n - 1)] = 1.0;
        for (r, &tr) in t.iter().enumerate().take(n - 1).skip(1) {
            for (c, b) in knots.bspline_basis_functions(3, tr).into_iter().enumerate() {
                a[(r, c)] = b;
            }
        }
        Interpolation { knots, lu: a.lu() }
    }

    /// The control points of the curve through `points` at the parameters.
    fn control_points(&self, points: &[Point3]) -> Vec<Point3> {
        let n = points.len();
        let rhs = DMatrix::from_fn(n, 3, |r, c| points[r][c]);
        let x = self
            .lu
            .solve(&rhs)
            .expect("the collocation matrix is regular");
        let mut cp: Vec<Point3> = (0..n)
            .map(|r| Point3::new(x[(r, 0)], x[(r, 1)], x[(r, 2)]))
            .collect();
        // the clamped ends are the end points exactly, so that faces built from the same
        // boundary points have the same boundary curves
        cp[0] = points[0];
        cp[n - 1] = points[n - 1];
        cp
    }
}

/// The bicubic B-spline surface interpolating `point(x, v)` at the chordwise stations `xs`
/// (through `iu`) and the stations `vs` across (through `iv`): rows along u first, then
/// columns along v, so that a face's boundary row depends on that row's points alone.
fn fit(
    iu: &Interpolation,
    iv: &Interpolation,
    xs: &[f64],
    vs: &[f64],
    point: &dyn Fn(f64, f64) -> Point3,
) -> BSplineSurface<Point3> {
    let rows: Vec<Vec<Point3>> = vs
        .iter()
        .map(|&v| iu.control_points(&xs.iter().map(|&x| point(x, v)).collect::<Vec<_>>()))
        .collect();
    let cp: Vec<Vec<Point3>> = (0..xs.len())
        .map(|i| iv.control_points(&rows.iter().map(|r| r[i]).collect::<Vec<_>>()))
        .collect();
    BSplineSurface::new((iu.knots.clone(), iv.knots.clone()), cp)
}

/// The largest `deviation` of the surface's points at the midpoints between consecutive
/// parameters `us`, on the v stations and between them.
fn fit_error(
    s: &BSplineSurface<Point3>,
    us: &[f64],
    vs: &[f64],
    deviation: &dyn Fn(Point3) -> f64,
) -> f64 {
    let mids = |t: &[f64]| {
        t.windows(2)
            .map(|w| 0.5 * (w[0] + w[1]))
            .collect::<Vec<_>>()
    };
    let v_all: Vec<f64> = vs.iter().copied().chain(mids(vs)).collect();
    mids(us)
        .iter()
        .flat_map(|&u| v_all.iter().map(move |&v| (u, v)))
        .map(|(u, v)| deviation(s.subs(u, v)))
        .fold(0.0, f64::max)
}
