//! Writes the ONERA M6 four-block C–O example (paper Section 5.3, Figs 37–42): the surface
//! control nets and the case file (paths below).
//!
//! The wing: ONERA D sections (`data/oneraD.dat`) with the trailing edge closed (the thickness
//! x · z_TE taken off each side, as the usual sharp-trailing-edge M6 of CFD validation), on the
//! M6 planform (root chord 0.8059, semi-span 1.1963, sweeps 30° and 15.8°), with a rounded tip
//! cap over the last 3 % of the span (thickness × cos φ, y = y₀ + Δ sin φ; shape constants from
//! `examples/common/wing_co_shape.rs`). Its upper and lower surfaces are bicubic Hermite nets
//! (blocks 1 and 2 of the nets file); the far field above and below (blocks 3 and 4) is, at each
//! span station, a quarter circle of 3.3 local chords about the 0.3-chord point from ahead of
//! the leading edge to overhead, then straight aft to the outflow plane x = 4, swung about the
//! span over the outer 40 % until it lies in the wing plane beyond the tip.
//!
//! Four volumes (C–O): above and below the wing, above and below the wake, each 64 × 64 × 48
//! cells (256 × 64 × 48 in all, the paper's count). The index i runs around the C from the
//! upper outflow over the trailing edge and the leading edge to the lower outflow, j from the
//! wall (or the wake sheet) to the far field, k from the root plane over the tip cap, where the
//! volumes wrap around the tip edge into the wing plane beyond it; every volume is
//! right-handed.
//!
//! `cargo run --release --example make_wing_m6 [NETS CASE [NI NJ NK [WALL]]]` (default
//! `wing_m6_nets.x` and `wing_m6_4block.toml` in the current directory, 65 × 65 × 49 nodes per
//! volume, first wall spacing WALL = 1e-5 local chord at the leading edge and twice that at the
//! trailing edge), then `ellipgrid run wing_m6_4block.toml`.
//!
//! Status (issue #18): shipped as `examples/m6/wing_m6_4block.toml` with its nets
//! `data/wing_m6_nets.x` (`make_wing_m6 data/wing_m6_nets.x examples/m6/wing_m6_4block.toml`).
//! Every face grids fold-free (the wing and far-field faces on their nets by Section 4, the
//! rest as minimal surfaces), and all four volumes are fold-free at the paper's size with the
//! wall spacing held at the wing: lines at most 0.065° (mean 0.002°) from the wall normal, the
//! first node at 0.9998–1.0004 of the prescribed spacing. What made that possible: the
//! square-root edge functions at the 180° edges (`ellipgrid::algebraic::flat_edge`; before
//! them the wing volumes folded over the tip cap and the wall correction's solves diverged),
//! Bi-CGSTAB for the volumes (the 3D multigrid's cycles diverge on them; "auto" would pick
//! it at this size), and no orthogonality goals on the faces between the volumes (with them
//! the lines left the tip's leading edge 6.3° off the normal and the flat-edge cells there
//! had wrongly oriented face pyramids). The far wake's streamwise nodes are the wake sheet's,
//! scaled (each far node above its sheet node): the mean kink across the wake sheet fell from
//! 77° to 18°, and with the wake sheet a symmetry face of the upper wake volume (its nodes
//! sliding in the wing plane; the lower volumes are the upper ones' mirror images) to about
//! 3°. The spanwise steps at the tip match the steps beyond the 180° edges of the wing
//! plane (below, "Along the span"): checkMesh finds no highly skewed face (it found 64, max
//! skewness 5.35, with 1.2e-3 everywhere). The upper wing volume's lines cross `ahead` and
//! `tipplane` at right angles (`CROSSINGS` below): mean kinks 23.4° and 40.5° at full size
//! (53.9° and 54.4° before). Left: the kinks across the other faces between the volumes
//! (`te_up`/`te_lo` 41.8°, `waketip` 61.6° at full size: those faces are gridded on their own
//! before the volumes; docs/ONERA_M6.md).

/// The volumes that are the mirror images of others in the wing plane z = 0 (the ONERA D
/// section is symmetric): the lower wing volume of the upper one, the lower wake volume of the
/// upper one. Only the upper volumes are solved.
const MIRRORS: [(&str, &str); 2] = [("wing_lo", "wing_up"), ("wake_lo", "wake_up")];

/// The faces of a volume that are symmetry planes (their nodes slide in the plane, the lines
/// meet it as the whole grid's cross it): the wake sheet, F3 of the upper wake volume (mean
/// kink 18.4° fixed, 3.6° sliding at 33 × 33 × 25; 3.2° at full size, as the floating sheet
/// before it at a third of the run time). `ahead` and `tipplane` share edges with the wall,
/// whose passes hold their side faces (they are crossed at right angles instead, `CROSSINGS`);
/// `waketip` as a symmetry face folds the cells next to
/// the 180° edge at the tip (its nodes are asked to lie under inner nodes that are inboard
/// of the edge; docs/ONERA_M6.md).
const SYMMETRY: [(&str, &str); 1] = [("wake_up", "F3")];

/// The side faces of a wall that the grid lines cross at right angles, held by the wall's own
/// passes (`ellipgrid::elliptic::crossing`): `ahead` (F2) and `tipplane` (F6) of the upper
/// wing volume, whose mirror image the lower one is, so that a right angle there is a smooth
/// crossing. Mean kinks at full size 53.9 → 23.4° (`ahead`) and 54.4 → 40.5° (`tipplane`),
/// part of the turn moving to the lines' first node off the face, the wall held, ~10 % more
/// run time (docs/ONERA_M6.md, "Crossing faces"). Not
/// `te_up`: the wake volume beyond it is not a mirror image, and made orthogonal on the wing
/// side only the lines left the wall 4° off its normal (33 × 33 × 25).
const CROSSINGS: [(&str, &str); 1] = [("wing_up", "\"F2\", \"F6\"")];

/// Faces of a volume without a wall that its grid lines leave at right angles
/// (`ellipgrid::elliptic::orthogonal3d`'s passes): `waketip` (F6) of the upper wake volume,
/// whose mirror image the lower one is, so that a right angle there is a smooth crossing. The
/// goals fade next to `te_up` (shared with the wing
/// volume) and the wake sheet (a symmetry face). Mean kink across `waketip` 61.6° → 15.1° at
/// full size, the lines turning 6.3° → 15.8° at their first node off it (docs/ONERA_M6.md).
const ORTHOGONAL: [(&str, &str); 1] = [("wake_up", "\"F6\"")];

/// Faces of a volume whose grid lines continue those of the volume beyond them, gridded first
/// (`ellipgrid::elliptic::continuation`): `te_up` (F2) of the upper wake volume, crossed
/// 30–40° off its normal by the wing volume's lines on both sides, so that orthogonality is
/// not the smooth crossing there. Mean kink across `te_up` 41.9° → 23.9° at full size, the
/// largest mean turn of the lines near it 41.3° → 23.5°, `waketip` 15.1° → 19.1°, checkMesh
/// 1512 faces above 70° instead of 1594 (docs/ONERA_M6.md).
const CONTINUE: [(&str, &str); 1] = [("wake_up", "\"F2\"")];

#[path = "common/wing_co_shape.rs"]
mod shape;

use ellipgrid::io::plot3d::{write_plot3d, Plot3dFormat};
use ellipgrid::io::Block;
use ellipgrid::Grid2;
use ellipgrid_geometry::{
    airfoil_curve, read_airfoil_dat, vinokur, ArclengthMap, Curve, Spline, Vec3,
};
use shape::{chord, station, x_le, CAP, SEMI_SPAN};
use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt::Write;

/// The outflow plane x = X_OUT.
const X_OUT: f64 = 4.0;
/// Far field: radius (local chords) about the point FAR_CENTER local chord behind the
/// leading edge; the far point above the trailing edge lies FAR_TE_AFT local chord behind it.
const FAR_RADIUS: f64 = 3.3;
const FAR_CENTER: f64 = 0.3;
const FAR_TE_AFT: f64 = 0.5;
/// The far field swings about the span from WRAP_FROM · b to the tip.
const WRAP_FROM: f64 = 0.8;
/// Far-field net intervals: arc, overhead to above the trailing edge, then to the outflow.
const FAR_ARC: usize = 24;
const FAR_MID: usize = 6;
const FAR_AFT: usize = 18;
/// Node counts of the volumes: around the C per volume, off the wall, along the span (the
/// paper's; the command line may give others for tests and studies).
const NODES: [usize; 3] = [65, 65, 49];

/// The upper surface of the closed-trailing-edge unit-chord section, LE (s = 0) → TE (s = 1).
struct Upper {
    spline: Spline,
    u_le: f64,
}

impl Curve for Upper {
    fn point(&self, s: f64) -> Vec3 {
        self.spline.point(self.u_le * (1.0 - s))
    }
    fn derivative(&self, s: f64) -> Vec3 {
        -self.u_le * self.spline.derivative(self.u_le * (1.0 - s))
    }
}

/// `n` points (x/c, z/c) of the upper surface, LE to TE, clustered at both ends with finite
/// end spacings (Vinokur in arclength): the net's parametrization must not be singular at the
/// leading edge (cosine clustering, arclength ∝ u² there, makes the bilinear inversion of
/// Section 4 misplace the first nodes off the leading edge by tens of percent).
fn section(n: usize) -> Vec<[f64; 2]> {
    let mut pts = read_airfoil_dat(include_str!("../data/oneraD.dat")).expect("oneraD.dat");
    let le = (0..pts.len())
        .min_by(|&a, &b| pts[a].x.total_cmp(&pts[b].x))
        .expect("points");
    // Close the trailing edge: z − x z_TE on each side.
    let (zu, zl) = (pts[0].y, pts[pts.len() - 1].y);
    for (k, p) in pts.iter_mut().enumerate() {
        let zte = if k <= le { zu } else { zl };
        p.y -= p.x * zte;
    }
    let spline = airfoil_curve(pts).expect("section spline");
    let upper = Upper {
        u_le: spline.knots()[le],
        spline,
    };
    let map = ArclengthMap::new(&upper);
    let sigma = vinokur(n, Some(1e-3), Some(3e-3)).expect("chordwise net distribution");
    let mut out: Vec<[f64; 2]> = map
        .params(&sigma)
        .iter()
        .map(|&s| {
            let p = upper.point(s);
            [p.x, p.y]
        })
        .collect();
    out[0] = [0.0, 0.0];
    out[n - 1] = [1.0, 0.0];
    out
}

/// Span stations of the wing net: inboard up to y₀ graded so that the last step matches the
/// cap's first, then the cap uniform in φ.
fn wing_stations(n_in: usize, n_cap: usize) -> Vec<shape::Station> {
    let y0 = (1.0 - CAP) * SEMI_SPAN;
    let first_cap = CAP * SEMI_SPAN * (FRAC_PI_2 / n_cap as f64).sin();
    let sig = vinokur(n_in + 1, None, Some(first_cap / y0)).expect("span stations");
    let mut out: Vec<shape::Station> = sig.iter().map(|&s| station(s)).collect();
    out.extend((1..=n_cap).map(|m| station(1.0 + m as f64 / n_cap as f64)));
    out
}

/// The wing net (upper if `side` = 1, lower if −1): sections × stations.
fn wing_net(sec: &[[f64; 2]], st: &[shape::Station], side: f64) -> Grid2<3> {
    Grid2::<3>::from_fn(sec.len(), st.len(), |i, k| {
        let (s, [x, z]) = (&st[k], sec[i]);
        let c = chord(s.y);
        let zz = if k + 1 == st.len() {
            0.0
        } else {
            side * c * s.tau * z
        };
        [x_le(s.y) + c * x, s.y, zz]
    })
}

/// Far-field point at path parameter m (0 … FAR_ARC + FAR_MID + FAR_AFT) of the section at axis
/// station y, swung by ψ about the span; `side` 1 above the wing plane, −1 below.
fn far_point(m: usize, y: f64, psi: f64, side: f64) -> [f64; 3] {
    let c = chord(y);
    let (xc, r) = (x_le(y) + FAR_CENTER * c, FAR_RADIUS * c);
    let x_te_far = x_le(y) + c * (1.0 + FAR_TE_AFT);
    let (x, h) = if m <= FAR_ARC {
        let th = PI - FRAC_PI_2 * m as f64 / FAR_ARC as f64;
        if m == 0 {
            (xc - r, 0.0)
        } else {
            (xc + r * th.cos(), r * th.sin())
        }
    } else if m <= FAR_ARC + FAR_MID {
        let t = (m - FAR_ARC) as f64 / FAR_MID as f64;
        (xc + (x_te_far - xc) * t, r)
    } else {
        let t = (m - FAR_ARC - FAR_MID) as f64 / FAR_AFT as f64;
        (x_te_far + (X_OUT - x_te_far) * t, r)
    };
    if psi == FRAC_PI_2 {
        [x, y + h, 0.0]
    } else {
        [x, y + h * psi.sin(), side * h * psi.cos()]
    }
}

/// Axis stations (y, ψ) of the far net: inboard up to WRAP_FROM · b, then the swing.
fn far_stations(n_in: usize, n_wrap: usize) -> Vec<(f64, f64)> {
    let b = SEMI_SPAN;
    let mut out: Vec<(f64, f64)> = (0..=n_in)
        .map(|m| (WRAP_FROM * b * m as f64 / n_in as f64, 0.0))
        .collect();
    out.extend((1..=n_wrap).map(|m| {
        let s = m as f64 / n_wrap as f64;
        let psi = if m == n_wrap {
            FRAC_PI_2
        } else {
            FRAC_PI_2 * s * s * (3.0 - 2.0 * s)
        };
        let y = if m == n_wrap {
            b
        } else {
            b * (WRAP_FROM + (1.0 - WRAP_FROM) * s)
        };
        (y, psi)
    }));
    out
}

fn far_net(st: &[(f64, f64)], side: f64) -> Grid2<3> {
    Grid2::<3>::from_fn(FAR_ARC + FAR_MID + FAR_AFT + 1, st.len(), |m, k| {
        far_point(m, st[k].0, st[k].1, side)
    })
}

fn main() -> ellipgrid::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let nets = args
        .first()
        .cloned()
        .unwrap_or_else(|| "wing_m6_nets.x".into());
    let case = args
        .get(1)
        .cloned()
        .unwrap_or_else(|| "wing_m6_4block.toml".into());
    let n: Vec<usize> = args[2.min(args.len())..5.min(args.len())]
        .iter()
        .map(|a| {
            a.parse()
                .map_err(|e| ellipgrid::Error::input("make_wing_m6", format!("{a}: {e}")))
        })
        .collect::<ellipgrid::Result<_>>()?;
    let n = match n[..] {
        [] => NODES,
        [a, b, c] if a >= 5 && b >= 5 && c >= 5 => [a, b, c],
        _ => {
            return Err(ellipgrid::Error::input(
                "make_wing_m6",
                "expected [NETS CASE [NI NJ NK [WALL]]], each count at least 5",
            ))
        }
    };
    // First wall spacing at the leading edge (local chords); twice that at the trailing edge.
    let wall: f64 = match args.get(5) {
        None => 1e-5,
        Some(a) => match a.parse::<f64>() {
            Ok(w) if w > 0.0 && w < 0.1 => w,
            _ => {
                return Err(ellipgrid::Error::input(
                    "make_wing_m6",
                    format!("WALL {a}: a first spacing in local chords, in (0, 0.1)"),
                ))
            }
        },
    };
    let sec = section(97);
    let wst = wing_stations(40, 16);
    let fst = far_stations(16, 16);
    let blocks = vec![
        Block::Surface(wing_net(&sec, &wst, 1.0)),
        Block::Surface(wing_net(&sec, &wst, -1.0)),
        Block::Surface(far_net(&fst, 1.0)),
        Block::Surface(far_net(&fst, -1.0)),
    ];
    write_plot3d(
        std::path::Path::new(&nets),
        &blocks,
        &Plot3dFormat::default(),
        None,
    )?;
    println!("wrote {nets} (wing and far-field nets, upper and lower)");
    // How many folders deep the case file lies below the current directory.
    let depth = std::path::Path::new(&case)
        .parent()
        .map(|p| p.components().count())
        .unwrap_or(0);
    std::fs::write(&case, case_text(&nets, depth, n, wall))
        .map_err(|e| ellipgrid::Error::input(&case, e.to_string()))?;
    println!("wrote {case}");
    Ok(())
}

/// An edge of the case: name, from, to, nodes, curve (None: the line), distribution.
type EdgeRow = (
    String,
    &'static str,
    &'static str,
    usize,
    Option<String>,
    String,
);
/// A face of the case: name, kind, surface, sides E1 … E4, orthogonal sides, family.
type FaceRow = (
    &'static str,
    &'static str,
    &'static str,
    [&'static str; 4],
    &'static str,
    &'static str,
);

/// A point as TOML.
fn p3(p: [f64; 3]) -> String {
    format!("[{:?}, {:?}, {:?}]", p[0], p[1], p[2])
}

/// The case file.
fn case_text(nets: &str, case_dir_depth: usize, [ni, nj, nk]: [usize; 3], wall: f64) -> String {
    let b = SEMI_SPAN;
    let (c0, cb) = (chord(0.0), chord(b));
    let u_te = (FAR_ARC + FAR_MID) as f64 / (FAR_ARC + FAR_MID + FAR_AFT) as f64;
    let far = |m: usize, tip: bool, side: f64| {
        if tip {
            far_point(m, b, FRAC_PI_2, side)
        } else {
            far_point(m, 0.0, 0.0, side)
        }
    };
    let mte = FAR_ARC + FAR_MID;
    let mout = mte + FAR_AFT;
    let mut t = String::new();
    t.push_str(
        "# ONERA M6 wing, four-block C–O Navier–Stokes grid (paper Section 5.3, Figs 37–42):\n\
         # 256 × 64 × 48 cells, first wall spacing 1e-5 local chord at the leading edge and\n\
         # 2e-5 at the trailing edge. Written by `cargo run --release --example make_wing_m6`\n\
         # (geometry and topology: examples/make_wing_m6.rs).\n\
         #\n\
         # Faces on the wing and the far field are gridded on their surfaces (Section 4), the\n\
         # planes and the surfaces rising from the trailing edge as minimal surfaces of their\n\
         # edges (Section 3), orthogonal at the wing's leading edge and in the root plane; the\n\
         # faces between the volumes (ahead, tipplane, te_up/lo, waketip) have no\n\
         # orthogonality goals: with them the grid lines kinked more across those faces\n\
         # and left the tip's leading edge 7.5° off the wall normal. Then the four volumes\n\
         # (Section 5) with the wall spacing held at the wing (wall = \"F3\"), by Bi-CGSTAB\n\
         # (the 3D multigrid diverges on these volumes), the wall columns following the\n\
         # side faces' profiles (wall_profiles = \"faces\"). The upper wing volume's lines\n\
         # cross ahead and tipplane at right angles (orthogonal = [\"F2\", \"F6\"], held by\n\
         # the wall's passes; its mirror image below makes that a smooth crossing), and the\n\
         # upper wake volume's lines leave waketip at right angles (orthogonal = [\"F6\"])\n\
         # and continue the upper wing volume's across te_up (continue = [\"F2\"]: the wing\n\
         # volume is gridded first).\n\
         # The lower volumes are the mirror images of the upper ones in the wing plane\n\
         # (mirror = ...: not solved), and the wake sheet is a symmetry face of the upper\n\
         # wake volume (symmetry = [\"F3\"]): its nodes slide in z = 0 and the grid lines\n\
         # cross it as the whole grid's (mean kink 18° fixed, 3° sliding).\n\
         # The spanwise steps at the tip (le_line, te_line, out_line) match the steps beyond\n\
         # the 180° edges of the wing plane there, so that checkMesh finds no highly skewed\n\
         # face at the tip's leading and trailing edges (examples/make_wing_m6.rs).\n\
         #\n\
         #   cargo run --release -- run examples/m6/wing_m6_4block.toml -o m6.x -o m6.conn\n\n",
    );
    // The nets file relative to the case file's folder.
    let rel = match (std::path::Path::new(nets).is_absolute(), case_dir_depth) {
        (true, _) => nets.to_string(),
        (false, d) => format!("{}{nets}", "../".repeat(d)),
    };
    // Anderson acceleration: with plain Picard steps the wake volumes stop at the 200-step
    // limit at full size (node updates 6e-10, just above the tolerance); with it every
    // volume converges.
    writeln!(
        t,
        "# Anderson acceleration of the Picard steps: without it the wake volumes stop at\n\
         # the 200-step limit at full size, just short of the tolerance.\n\
         [solver]\nanderson = 5\n"
    )
    .unwrap();
    writeln!(t, "[output]\nfiles = [\"wing_m6.x\", \"wing_m6.conn\"]\n").unwrap();
    for (name, block) in [("wing_up", 1), ("wing_lo", 2), ("far_up", 3), ("far_lo", 4)] {
        writeln!(
            t,
            "[[surface]]\nname = \"{name}\"\ntype = \"hermite_net\"\nfile = \"{rel}\"\nblock = {block}\n"
        )
        .unwrap();
    }
    let vertices: Vec<(&str, [f64; 3])> = vec![
        ("le_root", [0.0, 0.0, 0.0]),
        ("le_tip", [x_le(b), b, 0.0]),
        ("te_root", [c0, 0.0, 0.0]),
        ("te_tip", [x_le(b) + cb, b, 0.0]),
        ("fa_root", far(0, false, 1.0)),
        ("fa_tip", far(0, true, 1.0)),
        ("ft_root_up", far(mte, false, 1.0)),
        ("ft_root_lo", far(mte, false, -1.0)),
        ("ft_tip", far(mte, true, 1.0)),
        ("out_root", [X_OUT, 0.0, 0.0]),
        ("out_tip", [X_OUT, b, 0.0]),
        ("of_root_up", far(mout, false, 1.0)),
        ("of_root_lo", far(mout, false, -1.0)),
        ("of_tip", far(mout, true, 1.0)),
    ];
    for (n, p) in &vertices {
        writeln!(t, "[[vertex]]\nname = \"{n}\"\nat = {}\n", p3(*p)).unwrap();
    }
    let vin = |first: Option<f64>, last: Option<f64>| match (first, last) {
        (Some(f), Some(l)) => format!("{{ type = \"vinokur\", first = {f:e}, last = {l:e} }}"),
        (Some(f), None) => format!("{{ type = \"vinokur\", first = {f:e} }}"),
        (None, Some(l)) => format!("{{ type = \"vinokur\", last = {l:e} }}"),
        (None, None) => "{ type = \"uniform\" }".to_string(),
    };
    let on = |s: &str, a: [f64; 2], z: [f64; 2]| {
        format!(
            "{{ type = \"on_surface\", surface = \"{s}\", uv = [[{:?}, {:?}], [{:?}, {:?}]] }}",
            a[0], a[1], z[0], z[1]
        )
    };
    // (name, from, to, n, curve (None: the straight line), distribution)
    let mut edges: Vec<EdgeRow> = Vec::new();
    let mut e =
        |n: &str, f: &'static str, to: &'static str, count: usize, c: Option<String>, d: String| {
            edges.push((n.to_string(), f, to, count, c, d))
        };
    // Around the C (i): the wall sections, the far arcs, the wake lines.
    let chordwise = |c: f64| vin(Some(1e-3 * c), Some(4e-3 * c));
    // The far wake's nodes are the wake sheet's scaled to its length (the same Vinokur
    // distribution: each far node above its sheet node, so the wake volumes' j-lines rise
    // straight from the sheet), and the far arc ends with the far wake's first spacing, so
    // the spacing is the same on both sides of the cut above the trailing edge.
    let cut = |y: f64| {
        let x_te = x_le(y) + chord(y);
        4e-3 * chord(y) * (X_OUT - x_te - FAR_TE_AFT * chord(y)) / (X_OUT - x_te)
    };
    let (cut_root, cut_tip) = (cut(0.0), cut(b));
    e(
        "root_up",
        "le_root",
        "te_root",
        ni,
        Some(on("wing_up", [0.0, 0.0], [1.0, 0.0])),
        chordwise(c0),
    );
    e(
        "root_lo",
        "le_root",
        "te_root",
        ni,
        Some(on("wing_lo", [0.0, 0.0], [1.0, 0.0])),
        chordwise(c0),
    );
    e("tip", "le_tip", "te_tip", ni, None, chordwise(cb));
    e(
        "far_root_up",
        "fa_root",
        "ft_root_up",
        ni,
        Some(on("far_up", [0.0, 0.0], [u_te, 0.0])),
        vin(None, Some(cut_root)),
    );
    e(
        "far_root_lo",
        "fa_root",
        "ft_root_lo",
        ni,
        Some(on("far_lo", [0.0, 0.0], [u_te, 0.0])),
        vin(None, Some(cut_root)),
    );
    e(
        "far_tip",
        "fa_tip",
        "ft_tip",
        ni,
        Some(on("far_up", [0.0, 1.0], [u_te, 1.0])),
        vin(None, Some(cut_tip)),
    );
    e(
        "wake_root",
        "te_root",
        "out_root",
        ni,
        None,
        vin(Some(4e-3 * c0), None),
    );
    e(
        "wake_tip",
        "te_tip",
        "out_tip",
        ni,
        None,
        vin(Some(4e-3 * cb), None),
    );
    e(
        "farwake_root_up",
        "ft_root_up",
        "of_root_up",
        ni,
        Some(on("far_up", [u_te, 0.0], [1.0, 0.0])),
        vin(Some(cut_root), None),
    );
    e(
        "farwake_root_lo",
        "ft_root_lo",
        "of_root_lo",
        ni,
        Some(on("far_lo", [u_te, 0.0], [1.0, 0.0])),
        vin(Some(cut_root), None),
    );
    e(
        "farwake_tip",
        "ft_tip",
        "of_tip",
        ni,
        Some(on("far_up", [u_te, 1.0], [1.0, 1.0])),
        vin(Some(cut_tip), None),
    );
    // Off the wall (j): wall spacing 1e-5 local chord at the leading edge, 2e-5 at the trailing edge.
    e(
        "ahead_root",
        "le_root",
        "fa_root",
        nj,
        None,
        vin(Some(wall * c0), None),
    );
    e(
        "ahead_tip",
        "le_tip",
        "fa_tip",
        nj,
        None,
        vin(Some(wall * cb), None),
    );
    e(
        "rise_root_up",
        "te_root",
        "ft_root_up",
        nj,
        None,
        vin(Some(2.0 * wall * c0), None),
    );
    e(
        "rise_root_lo",
        "te_root",
        "ft_root_lo",
        nj,
        None,
        vin(Some(2.0 * wall * c0), None),
    );
    e(
        "rise_tip",
        "te_tip",
        "ft_tip",
        nj,
        None,
        vin(Some(2.0 * wall * cb), None),
    );
    e(
        "out_root_up",
        "out_root",
        "of_root_up",
        nj,
        None,
        vin(Some(1e-3), None),
    );
    e(
        "out_root_lo",
        "out_root",
        "of_root_lo",
        nj,
        None,
        vin(Some(1e-3), None),
    );
    e(
        "out_tip",
        "out_tip",
        "of_tip",
        nj,
        None,
        vin(Some(1e-3), None),
    );
    // Along the span (k), clustered towards the tip. Each of these edges ends on a 180° block
    // edge in the wing plane (ahead_tip, wake_tip), where the face beyond the tip (tipplane,
    // waketip) continues its face (ahead, wake sheet) in the same plane; the cells there are
    // wedges spanning both sides of the edge (`algebraic::flat_edge` maps them as w ↦ w²,
    // which wants the same spacing on both sides). With a spanwise last step much longer than
    // the step beyond the edge, the cell centres of the tip layer lie far inboard of their
    // faces in the wing plane: checkMesh found "highly skewed faces" (skewness up to 7.3 > 4)
    // at the tip's leading and trailing edges with 1.2e-3 everywhere. So the last spanwise
    // step is the tip edge's chordwise step at the leading edge (1e-3 tip chord), out_tip's
    // first step (1e-3) at the outflow, and at the trailing edge, where waketip starts with
    // the wall spacing (2e-5 tip chord), 1.5e-4, a compromise measured at 33, 49 and 65 nodes
    // (docs/ONERA_M6.md, "No highly skewed faces"): 1.2e-3 left skewness 7.3; 1.8e-4 passed at 33
    // and 65 nodes but not at 49 (4.1); 1e-4 passed but wing_up and wing_lo converged 3e-3 apart
    // (no longer mirror images) at 33 nodes; 9.1e-5 and 7e-5 left wall lines next to the tip's
    // trailing edge 5.7° (65 nodes) and 30° (49) off the normal.
    let spanwise = |last: f64| vin(Some(0.04), Some(last));
    e(
        "le_line",
        "le_root",
        "le_tip",
        nk,
        None,
        spanwise(1e-3 * cb),
    );
    e("te_line", "te_root", "te_tip", nk, None, spanwise(1.5e-4));
    e("out_line", "out_root", "out_tip", nk, None, spanwise(1e-3));
    e("far_ahead", "fa_root", "fa_tip", nk, None, vin(None, None));
    e(
        "far_te_up",
        "ft_root_up",
        "ft_tip",
        nk,
        Some(on("far_up", [u_te, 0.0], [u_te, 1.0])),
        vin(None, None),
    );
    e(
        "far_te_lo",
        "ft_root_lo",
        "ft_tip",
        nk,
        Some(on("far_lo", [u_te, 0.0], [u_te, 1.0])),
        vin(None, None),
    );
    e(
        "far_out_up",
        "of_root_up",
        "of_tip",
        nk,
        Some(on("far_up", [1.0, 0.0], [1.0, 1.0])),
        vin(None, None),
    );
    e(
        "far_out_lo",
        "of_root_lo",
        "of_tip",
        nk,
        Some(on("far_lo", [1.0, 0.0], [1.0, 1.0])),
        vin(None, None),
    );
    for (name, from, to, n, curve, dist) in &edges {
        writeln!(
            t,
            "[[edge]]\nname = \"{name}\"\nfrom = \"{from}\"\nto = \"{to}\"\nn = {n}"
        )
        .unwrap();
        if let Some(c) = curve {
            writeln!(t, "curve = {c}").unwrap();
        }
        writeln!(t, "distribution = {dist}\n").unwrap();
    }
    // (name, kind, surface, [E1, E2, E3, E4], orthogonal sides, family). The wing faces are
    // orthogonal at the leading edge only: orthogonal to the swept trailing edge too, their
    // chordwise lines left it 16-18° inboard of the streamwise wake lines (mean kink across
    // te_up/lo 59.3° without against 69.2° with, 33 × 33 × 25; docs/ONERA_M6.md, "Wall columns
    // from the side faces").
    let faces: Vec<FaceRow> = vec![
        (
            "wall_up",
            "surface",
            "wing_up",
            ["le_line", "te_line", "root_up", "tip"],
            "\"E1\"",
            "wall",
        ),
        (
            "wall_lo",
            "surface",
            "wing_lo",
            ["le_line", "te_line", "root_lo", "tip"],
            "\"E1\"",
            "wall",
        ),
        (
            "far_up",
            "surface",
            "far_up",
            ["far_ahead", "far_te_up", "far_root_up", "far_tip"],
            "",
            "farfield",
        ),
        (
            "far_lo",
            "surface",
            "far_lo",
            ["far_ahead", "far_te_lo", "far_root_lo", "far_tip"],
            "",
            "farfield",
        ),
        (
            "farwake_up",
            "surface",
            "far_up",
            ["far_te_up", "far_out_up", "farwake_root_up", "farwake_tip"],
            "",
            "farfield",
        ),
        (
            "farwake_lo",
            "surface",
            "far_lo",
            ["far_te_lo", "far_out_lo", "farwake_root_lo", "farwake_tip"],
            "",
            "farfield",
        ),
        (
            "root_up",
            "minimal",
            "",
            ["ahead_root", "rise_root_up", "root_up", "far_root_up"],
            "\"E1\", \"E2\", \"E3\"",
            "symmetry",
        ),
        (
            "root_lo",
            "minimal",
            "",
            ["ahead_root", "rise_root_lo", "root_lo", "far_root_lo"],
            "\"E1\", \"E2\", \"E3\"",
            "symmetry",
        ),
        (
            "rootwake_up",
            "minimal",
            "",
            [
                "rise_root_up",
                "out_root_up",
                "wake_root",
                "farwake_root_up",
            ],
            "\"E1\", \"E3\"",
            "symmetry",
        ),
        (
            "rootwake_lo",
            "minimal",
            "",
            [
                "rise_root_lo",
                "out_root_lo",
                "wake_root",
                "farwake_root_lo",
            ],
            "\"E1\", \"E3\"",
            "symmetry",
        ),
        (
            "ahead",
            "minimal",
            "",
            ["ahead_root", "ahead_tip", "le_line", "far_ahead"],
            "",
            "ahead",
        ),
        (
            "tipplane",
            "minimal",
            "",
            ["ahead_tip", "rise_tip", "tip", "far_tip"],
            "",
            "tipplane",
        ),
        (
            "te_up",
            "minimal",
            "",
            ["rise_root_up", "rise_tip", "te_line", "far_te_up"],
            "",
            "te_up",
        ),
        (
            "te_lo",
            "minimal",
            "",
            ["rise_root_lo", "rise_tip", "te_line", "far_te_lo"],
            "",
            "te_lo",
        ),
        (
            "wakesheet",
            "minimal",
            "",
            ["te_line", "out_line", "wake_root", "wake_tip"],
            "\"E4\"",
            "wakesheet",
        ),
        (
            "waketip",
            "minimal",
            "",
            ["rise_tip", "out_tip", "wake_tip", "farwake_tip"],
            "",
            "waketip",
        ),
        (
            "outflow_up",
            "minimal",
            "",
            ["out_root_up", "out_tip", "out_line", "far_out_up"],
            "",
            "outflow",
        ),
        (
            "outflow_lo",
            "minimal",
            "",
            ["out_root_lo", "out_tip", "out_line", "far_out_lo"],
            "",
            "outflow",
        ),
    ];
    for (name, kind, surf, [e1, e2, e3, e4], orth, fam) in &faces {
        writeln!(t, "[[face]]\nname = \"{name}\"\nkind = \"{kind}\"").unwrap();
        if !surf.is_empty() {
            writeln!(t, "surface = \"{surf}\"").unwrap();
        }
        writeln!(
            t,
            "E1 = \"{e1}\"\nE2 = \"{e2}\"\nE3 = \"{e3}\"\nE4 = \"{e4}\""
        )
        .unwrap();
        if !orth.is_empty() {
            writeln!(t, "orthogonal = [{orth}]").unwrap();
        }
        writeln!(t, "family = \"{fam}\"\n").unwrap();
    }
    // (name, F1 … F6, wall)
    let volumes: Vec<(&str, [&str; 6], bool)> = vec![
        (
            "wing_up",
            ["te_up", "ahead", "wall_up", "far_up", "root_up", "tipplane"],
            true,
        ),
        (
            "wing_lo",
            ["ahead", "te_lo", "wall_lo", "far_lo", "root_lo", "tipplane"],
            true,
        ),
        (
            "wake_up",
            [
                "outflow_up",
                "te_up",
                "wakesheet",
                "farwake_up",
                "rootwake_up",
                "waketip",
            ],
            false,
        ),
        (
            "wake_lo",
            [
                "te_lo",
                "outflow_lo",
                "wakesheet",
                "farwake_lo",
                "rootwake_lo",
                "waketip",
            ],
            false,
        ),
    ];
    for (name, f, wall) in &volumes {
        writeln!(t, "[[volume]]\nname = \"{name}\"").unwrap();
        for (k, face) in f.iter().enumerate() {
            writeln!(t, "F{} = \"{face}\"", k + 1).unwrap();
        }
        if *wall {
            writeln!(t, "wall = \"F3\"").unwrap();
            // The interior columns follow the side faces' profiles (te_up/lo, ahead, tipplane
            // are gridded before the volumes), not the edges' interpolation: the columns next
            // to te_up were 6 % higher than the face at mid-height, the lines crossing it
            // kinked up to 129°.
            writeln!(t, "wall_profiles = \"faces\"").unwrap();
        }
        // The 3D multigrid's cycles diverge on these flattened, strongly stretched volumes.
        writeln!(t, "linear = \"bicgstab\"").unwrap();
        for (v, f) in SYMMETRY {
            if v == *name {
                writeln!(t, "symmetry = [\"{f}\"]").unwrap();
            }
        }
        for (v, f) in CROSSINGS.iter().chain(&ORTHOGONAL) {
            if v == name {
                writeln!(t, "orthogonal = [{f}]").unwrap();
            }
        }
        for (v, f) in CONTINUE {
            if v == *name {
                writeln!(t, "continue = [{f}]").unwrap();
            }
        }
        for (v, a) in MIRRORS {
            if v == *name {
                writeln!(t, "mirror = \"{a}\"").unwrap();
            }
        }
        t.push('\n');
    }
    t
}
