use crate::quality::display::num;
use crate::quality::*;

/// Tolerance for quantities computed exactly up to rounding.
const TOL: f64 = 1e-12;

#[track_caller]
fn near(a: f64, b: f64, tol: f64) {
    assert!(
        (a - b).abs() <= tol * (1.0 + b.abs()),
        "{a} differs from {b} by more than {tol}"
    );
}

fn field<'a>(f: &'a [(&'static str, Vec<f64>)], name: &str) -> &'a [f64] {
    &f.iter().find(|(n, _)| *n == name).expect("field").1
}

fn cartesian(ni: usize, nj: usize, hx: f64, hy: f64) -> Grid2<2> {
    Grid2::from_fn(ni, nj, |i, j| [i as f64 * hx, j as f64 * hy])
}

/// Parallelogram cells with angles 60° and 120°, unit edges.
fn sheared(ni: usize, nj: usize) -> Grid2<2> {
    let a = 60f64.to_radians();
    Grid2::from_fn(ni, nj, |i, j| {
        [i as f64 + j as f64 * a.cos(), j as f64 * a.sin()]
    })
}

fn mirrored(g: &Grid2<2>) -> Grid2<2> {
    let mut m = g.clone();
    m.coord_mut(0).iter_mut().for_each(|x| *x = -*x);
    m
}

/// 6 × 6 unit grid with node (2, 2) moved across its neighbour (3, 2).
fn moved_node() -> Grid2<2> {
    let mut g = cartesian(6, 6, 1.0, 1.0);
    g.set(2, 2, [3.5, 2.0]);
    g
}

/// 5 × 5 unit grid with nodes (2, 2) ↔ (3, 2) and (2, 3) ↔ (3, 3) swapped: cell (2, 2) is turned
/// over as a whole, cells (2, 1) and (2, 3) become bow-ties.
fn swapped_column() -> Grid2<2> {
    let mut g = cartesian(5, 5, 1.0, 1.0);
    for j in [2, 3] {
        let (a, b) = (g.point(2, j), g.point(3, j));
        g.set(2, j, b);
        g.set(3, j, a);
    }
    g
}

/// A planar grid placed in a tilted plane of R³.
fn tilted(g: &Grid2<2>) -> Grid2<3> {
    let (c, s) = (0.7f64.cos(), 0.7f64.sin());
    Grid2::from_fn(g.ni(), g.nj(), |i, j| {
        let [x, y] = g.point(i, j);
        [x, y * c, y * s + 1.0]
    })
}

#[test]
fn uniform_cartesian_grid() {
    let (hx, hy) = (0.5, 0.25);
    let g = cartesian(7, 5, hx, hy);
    let r = quality2d(&g);
    assert_eq!((r.ni, r.nj, r.cells), (7, 5, 24));
    assert_eq!(r.orientation, Orientation::RightHanded);
    near(r.jacobian_min, hx * hy, TOL);
    near(r.jacobian_max, hx * hy, TOL);
    near(r.scaled_jacobian_min, 1.0, TOL);
    assert_eq!(r.folded_cells, 0);
    assert!(!r.is_folded() && r.first_folded.is_empty());
    near(r.skewness_max, 0.0, TOL);
    near(r.skewness_mean, 0.0, TOL);
    let names: Vec<&str> = r.orthogonality.iter().map(|o| o.edge.as_str()).collect();
    assert_eq!(names, ["E1", "E2", "E3", "E4"]);
    for o in &r.orthogonality {
        near(o.max_deg, 0.0, TOL);
        near(o.mean_deg, 0.0, TOL);
    }
    let nodes: Vec<usize> = r.orthogonality.iter().map(|o| o.nodes).collect();
    assert_eq!(nodes, [3, 3, 5, 5]);
    near(r.aspect_ratio_max, hx / hy, TOL);
    near(r.growth_i_max, 1.0, TOL);
    near(r.growth_j_max, 1.0, TOL);
    near(r.min_spacing, hy, TOL);
    near(r.max_spacing, hx, TOL);

    let f = cell_fields2d(&g);
    let names: Vec<&str> = f.iter().map(|(n, _)| *n).collect();
    assert_eq!(names, CELL_FIELDS);
    for (_, v) in &f {
        assert_eq!(v.len(), 24);
    }
    field(&f, "jacobian_min")
        .iter()
        .for_each(|&v| near(v, hx * hy, TOL));
    field(&f, "aspect_ratio")
        .iter()
        .for_each(|&v| near(v, 2.0, TOL));
    field(&f, "skewness")
        .iter()
        .for_each(|&v| near(v, 0.0, TOL));
}

#[test]
fn sheared_parallelogram_60_degrees() {
    let g = sheared(6, 5);
    let r = quality2d(&g);
    let s60 = 60f64.to_radians().sin();
    assert_eq!(r.orientation, Orientation::RightHanded);
    assert_eq!(r.folded_cells, 0);
    near(r.jacobian_min, s60, TOL);
    near(r.jacobian_max, s60, TOL);
    near(r.scaled_jacobian_min, s60, TOL);
    near(r.skewness_max, 1.0 / 3.0, TOL);
    near(r.skewness_mean, 1.0 / 3.0, TOL);
    for o in &r.orthogonality {
        near(o.max_deg, 30.0, 1e-10);
        near(o.mean_deg, 30.0, 1e-10);
    }
    near(r.aspect_ratio_max, 1.0, TOL);
    field(&cell_fields2d(&g), "skewness")
        .iter()
        .for_each(|&v| near(v, 1.0 / 3.0, TOL));
}

#[test]
fn geometric_stretching_along_j() {
    // Spacing 1.2^j along j: y_j = (1.2^j − 1) / 0.2.
    let g = Grid2::from_fn(4, 9, |i, j| [i as f64, (1.2f64.powi(j as i32) - 1.0) / 0.2]);
    let r = quality2d(&g);
    near(r.growth_j_max, 1.2, TOL);
    near(r.growth_i_max, 1.0, TOL);
    near(r.min_spacing, 1.0, TOL);
    near(r.max_spacing, 1.2f64.powi(7), TOL);
    near(r.aspect_ratio_max, 1.2f64.powi(7), TOL);
    assert_eq!(r.folded_cells, 0);
    // Shrinking spacings (ratio 1/1.2) are inverted to the same growth.
    let g = Grid2::from_fn(4, 9, |i, j| {
        [i as f64, (1.0 - (1.0 / 1.2f64).powi(j as i32)) * 6.0]
    });
    near(quality2d(&g).growth_j_max, 1.2, TOL);
    // Along i, with a sharper jump in one place: the maximum is found.
    let g = Grid2::from_fn(5, 3, |i, j| {
        let x = [0.0, 1.0, 2.1, 3.0, 4.5][i];
        [x, j as f64]
    });
    let r = quality2d(&g);
    near(r.growth_i_max, 1.5 / 0.9, TOL);
    near(r.growth_j_max, 1.0, TOL);
}

#[test]
fn moved_node_folds_the_right_cells() {
    let g = moved_node();
    let r = quality2d(&g);
    assert_eq!(r.orientation, Orientation::RightHanded);
    assert_eq!(r.folded_cells, 2);
    assert!(r.is_folded());
    assert_eq!(r.first_folded, vec![[2, 1], [2, 2]]);
    near(r.jacobian_min, -0.5, TOL);
    assert!(r.scaled_jacobian_min < 0.0);
    assert!(r.skewness_max > 1.0, "reflex corner: skewness > 1");
    let f = cell_fields2d(&g);
    let negative: Vec<usize> = field(&f, "jacobian_min")
        .iter()
        .enumerate()
        .filter(|(_, &v)| v <= 0.0)
        .map(|(c, _)| c)
        .collect();
    assert_eq!(negative, [2 + 5, 2 + 5 * 2]);
    assert!(format!("{r}").contains("FOLDED"));
}

#[test]
fn left_handed_grid_is_valid_and_folds_are_relative_to_it() {
    let m = mirrored(&sheared(6, 5));
    let r = quality2d(&m);
    assert_eq!(r.orientation, Orientation::LeftHanded);
    assert_eq!(r.folded_cells, 0);
    assert!(!r.is_folded());
    let s60 = 60f64.to_radians().sin();
    near(r.jacobian_min, s60, TOL);
    near(r.scaled_jacobian_min, s60, TOL);
    near(r.skewness_max, 1.0 / 3.0, TOL);
    for o in &r.orthogonality {
        near(o.max_deg, 30.0, 1e-10);
    }
    assert!(field(&cell_fields2d(&m), "jacobian_min")
        .iter()
        .all(|&v| v > 0.0));
    // A fold in a left-handed grid is found at the same cells.
    let r = quality2d(&mirrored(&moved_node()));
    assert_eq!(r.orientation, Orientation::LeftHanded);
    assert_eq!(r.first_folded, vec![[2, 1], [2, 2]]);
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains(r#""orientation":"left-handed""#), "{json}");
}

#[test]
fn first_folded_is_capped_and_in_index_order() {
    // Column i = 3 moved past column 4: cell (3, j) is mirrored in every row.
    let mut g = cartesian(10, 21, 1.0, 1.0);
    for j in 0..21 {
        g.set(3, j, [4.5, j as f64]);
    }
    let r = quality2d(&g);
    assert_eq!(r.orientation, Orientation::RightHanded);
    assert_eq!(r.folded_cells, 20);
    let want: Vec<[usize; 2]> = (0..MAX_FIRST_FOLDED).map(|j| [3, j]).collect();
    assert_eq!(r.first_folded, want);
}

#[test]
fn swapped_column_folds_in_plane_and_on_surface() {
    let g = swapped_column();
    let want = vec![[2, 1], [2, 2], [2, 3]];
    assert_eq!(quality2d(&g).first_folded, want);
    // On a surface cell (2, 2) is positive against its own normal: only the neighbour-flip test
    // finds it.
    let r = quality_surface(&tilted(&g));
    assert_eq!(r.orientation, Orientation::Surface);
    assert_eq!(r.folded_cells, 3);
    assert_eq!(r.first_folded, want);
}

#[test]
fn surface_fold_by_moved_node() {
    let r = quality_surface(&tilted(&moved_node()));
    assert_eq!(r.first_folded, vec![[2, 1], [2, 2]]);
    near(r.jacobian_min, -0.5, TOL);
    // The same plane without the fold: as the planar grid.
    let r = quality_surface(&tilted(&sheared(6, 5)));
    assert_eq!(r.folded_cells, 0);
    near(r.skewness_max, 1.0 / 3.0, TOL);
    near(r.orthogonality[2].max_deg, 30.0, 1e-10);
}

#[test]
fn cylinder_patch_surface_grid() {
    let (rad, n) = (2.0, 9);
    let dth = std::f64::consts::FRAC_PI_2 / (n - 1) as f64;
    let z = |j: usize| (1.3f64.powi(j as i32) - 1.0) / 0.3 * 0.1;
    let g = Grid2::<3>::from_fn(n, 6, |i, j| {
        let th = i as f64 * dth;
        [rad * th.cos(), rad * th.sin(), z(j)]
    });
    let r = quality_surface(&g);
    assert_eq!(r.orientation, Orientation::Surface);
    assert_eq!(r.folded_cells, 0);
    for o in &r.orthogonality {
        assert_eq!(
            o.nodes,
            if o.edge == "E1" || o.edge == "E2" {
                4
            } else {
                7
            }
        );
        assert!(o.max_deg < 1e-10, "{}: {}", o.edge, o.max_deg);
    }
    near(r.skewness_max, 0.0, 1e-10);
    near(r.scaled_jacobian_min, 1.0, 1e-12);
    let chord = 2.0 * rad * (dth / 2.0).sin();
    near(r.jacobian_min, chord * 0.1, TOL);
    near(r.jacobian_max, chord * (z(5) - z(4)), TOL);
    near(r.growth_j_max, 1.3, TOL);
    near(r.growth_i_max, 1.0, TOL);
    // Reversing i turns every normal over: still no fold (surfaces have no handedness).
    let rev = Grid2::<3>::from_fn(n, 6, |i, j| g.point(n - 1 - i, j));
    assert_eq!(quality_surface(&rev).folded_cells, 0);
    let f = cell_fields_surface(&g);
    assert_eq!(field(&f, "jacobian_min").len(), 8 * 5);
    assert!(field(&f, "scaled_jacobian_min")
        .iter()
        .all(|&v| (v - 1.0).abs() < 1e-12));
}

#[test]
fn surface_orthogonality_is_measured_in_3d() {
    // Cylinder patch with the axial lines sheared along the circumference by 30° in the tangent
    // plane: at E3/E4 the off-wall line leaves the wall at 60° (to first order in the spacing).
    let (rad, n) = (50.0, 9);
    let dth = 0.001;
    let g = Grid2::<3>::from_fn(n, 5, |i, j| {
        let s = i as f64 * rad * dth + j as f64 * 0.05 * 30f64.to_radians().sin();
        let th = s / rad;
        [
            rad * th.cos(),
            rad * th.sin(),
            j as f64 * 0.05 * 30f64.to_radians().cos(),
        ]
    });
    let r = quality_surface(&g);
    assert_eq!(r.folded_cells, 0);
    near(r.orthogonality[2].max_deg, 30.0, 1e-4);
    near(r.orthogonality[3].mean_deg, 30.0, 1e-4);
}

#[test]
fn polar_grid_wall_tangent_is_a_central_difference() {
    // θ along i, r along j: x_ξ × x_η < 0, a left-handed grid. At the arcs E3, E4 the chord
    // x_{i+1} − x_{i−1} is exactly normal to the radial off-wall line; at the rays E1, E2 the
    // off-wall chord leaves the wall at 90° − dθ/2.
    let dth = 0.1f64;
    let g = Grid2::from_fn(12, 6, |i, j| {
        let (r, th) = (1.0 + 0.2 * j as f64, i as f64 * dth);
        [r * th.cos(), r * th.sin()]
    });
    let r = quality2d(&g);
    assert_eq!(r.orientation, Orientation::LeftHanded);
    assert_eq!(r.folded_cells, 0);
    for o in &r.orthogonality[2..] {
        assert!(o.max_deg < 1e-10, "{}: {}", o.edge, o.max_deg);
    }
    for o in &r.orthogonality[..2] {
        near(o.max_deg, (dth / 2.0).to_degrees(), 1e-10);
    }
}

#[test]
fn warped_surface_cell_angles_are_taken_in_its_plane() {
    // Saddle cell: the diagonals span the xy-plane, the edges leave it. Projected, the corners are
    // right angles; the 3D angle between the edges at x₀ is acos(h²/(1 + h²)).
    let h = 0.5;
    let g = Grid2::<3>::from_coords(
        2,
        2,
        [
            vec![0.0, 1.0, 0.0, 1.0],
            vec![0.0, 0.0, 1.0, 1.0],
            vec![0.0, h, h, 0.0],
        ],
    );
    let r = quality_surface(&g);
    assert_eq!(r.folded_cells, 0);
    near(r.skewness_max, 0.0, TOL);
    near(r.jacobian_min, 1.0, TOL);
    near(r.scaled_jacobian_min, 1.0 / (1.0 + h * h), TOL);
}

#[test]
fn json_round_trip() {
    let g = Grid2::from_fn(5, 7, |i, j| {
        [
            i as f64 * 0.3 + 0.01 * (j * j) as f64,
            1.1f64.powi(j as i32) + 0.02 * i as f64,
        ]
    });
    let r = quality2d(&g);
    let json = serde_json::to_string(&r).unwrap();
    let back: QualityReport = serde_json::from_str(&json).unwrap();
    // serde_json parses floats to within an ulp by default.
    let same = |a: f64, b: f64| near(a, b, 1e-15);
    assert_eq!((back.ni, back.nj, back.cells), (r.ni, r.nj, r.cells));
    assert_eq!(back.orientation, r.orientation);
    assert_eq!(back.folded_cells, r.folded_cells);
    assert_eq!(back.first_folded, r.first_folded);
    for (a, b) in [
        (back.jacobian_min, r.jacobian_min),
        (back.jacobian_max, r.jacobian_max),
        (back.scaled_jacobian_min, r.scaled_jacobian_min),
        (back.skewness_max, r.skewness_max),
        (back.skewness_mean, r.skewness_mean),
        (back.aspect_ratio_max, r.aspect_ratio_max),
        (back.growth_i_max, r.growth_i_max),
        (back.growth_j_max, r.growth_j_max),
        (back.min_spacing, r.min_spacing),
        (back.max_spacing, r.max_spacing),
    ] {
        same(a, b);
    }
    for (a, b) in back.orthogonality.iter().zip(&r.orthogonality) {
        assert_eq!((&a.edge, a.nodes), (&b.edge, b.nodes));
        same(a.max_deg, b.max_deg);
        same(a.mean_deg, b.mean_deg);
    }

    // Non-finite values: written as strings, read back as the same values.
    let deg = quality2d(&Grid2::zeros(3, 3));
    let json = serde_json::to_string(&deg).unwrap();
    assert!(json.contains(r#""aspect_ratio_max":"inf""#), "{json}");
    let back: QualityReport = serde_json::from_str(&json).unwrap();
    assert_eq!(back.aspect_ratio_max, f64::INFINITY);
    assert_eq!(back.folded_cells, 4);
    let empty = quality2d(&Grid2::zeros(1, 4));
    let json = serde_json::to_string_pretty(&empty).unwrap();
    let back: QualityReport = serde_json::from_str(&json).unwrap();
    assert!(back.jacobian_min.is_nan() && back.orthogonality[0].max_deg.is_nan());
    assert_eq!(
        serde_json::to_string(&back).unwrap(),
        serde_json::to_string(&empty).unwrap()
    );
    // serde_json's own `null` for NaN is accepted too.
    let nulled = json.replace(r#""nan""#, "null");
    assert!(serde_json::from_str::<QualityReport>(&nulled)
        .unwrap()
        .skewness_max
        .is_nan());
}

#[test]
fn degenerate_input_does_not_panic() {
    for (ni, nj) in [(0, 0), (1, 1), (1, 5), (5, 1), (0, 3)] {
        let r = quality2d(&Grid2::zeros(ni, nj));
        assert_eq!(r.cells, 0);
        assert!(!r.is_folded());
        assert_eq!(r.orthogonality.len(), 4);
        let _ = format!("{r}");
        serde_json::to_string(&r).unwrap();
        assert!(cell_fields2d(&Grid2::zeros(ni, nj))
            .iter()
            .all(|(_, v)| v.is_empty()));
        let s = quality_surface(&Grid2::zeros(ni, nj));
        assert_eq!((s.cells, s.folded_cells), (0, 0));
    }
    // All nodes coincident: every cell degenerate, finite skewness, infinite aspect ratio.
    let r = quality2d(&Grid2::zeros(2, 2));
    assert_eq!((r.cells, r.folded_cells), (1, 1));
    assert_eq!((r.jacobian_min, r.scaled_jacobian_min), (0.0, 0.0));
    assert_eq!(r.skewness_max, 1.0);
    assert_eq!(r.aspect_ratio_max, f64::INFINITY);
    assert_eq!(r.orthogonality[0].nodes, 0);
    let s = quality_surface(&Grid2::zeros(3, 3));
    assert_eq!(s.folded_cells, 4);
    // A block side collapsed to a point (a pole): the cells along it are triangles, valid
    // here; its zero spacings are not counted. Collapsed only in part: those cells fold.
    let mut g = cartesian(4, 4, 1.0, 1.0);
    for i in 0..4 {
        g.set(i, 0, [1.5, 0.0]);
    }
    let r = quality2d(&g);
    assert_eq!(r.first_folded, Vec::<[usize; 2]>::new());
    assert_eq!(r.min_spacing, 1.0);
    assert_eq!(r.growth_i_max, 1.0);
    near(r.growth_j_max, 3.25f64.sqrt(), TOL);
    assert!(r.skewness_max.is_finite());
    assert!(r.scaled_jacobian_min > 0.3, "{r}");
    assert_eq!(r.orthogonality[2].nodes, 0, "a pole has no tangent");
    // its 3 triangles counted apart, the unit squares above them regular
    assert_eq!(r.collapsed_cells, 3, "{r}");
    assert_eq!(r.scaled_jacobian_min_regular, 1.0, "{r}");
    assert!(
        format!("{r}").contains("collapsed-side cells               3"),
        "{r}"
    );
    // a report without the fields (written before them) reads as no collapsed side
    let mut v = serde_json::to_value(&r).unwrap();
    let o = v.as_object_mut().unwrap();
    o.remove("collapsed_cells");
    o.remove("scaled_jacobian_min_regular");
    let back: QualityReport = serde_json::from_value(v).unwrap();
    assert_eq!(back.collapsed_cells, 0);
    assert!(back.scaled_jacobian_min_regular.is_nan());
    let plain = quality2d(&cartesian(4, 4, 1.0, 1.0));
    assert_eq!(plain.collapsed_cells, 0);
    assert_eq!(plain.scaled_jacobian_min_regular, plain.scaled_jacobian_min);
    assert!(!format!("{plain}").contains("collapsed-side"), "{plain}");
    g.set(3, 0, [3.0, 0.0]);
    let r = quality2d(&g);
    assert_eq!(r.first_folded, vec![[0, 0], [1, 0]]);
    assert_eq!(r.min_spacing, 0.0);
    assert_eq!(r.growth_i_max, f64::INFINITY, "a zero spacing next to 1.5");
    // A duplicated node inside a line: growth ∞.
    let mut g = cartesian(3, 2, 1.0, 1.0);
    g.set(1, 0, [0.0, 0.0]);
    let r = quality2d(&g);
    assert_eq!(r.growth_i_max, f64::INFINITY);
    assert_eq!(r.first_folded, vec![[0, 0]]);
    // NaN coordinates: the cells touching them are folded, the metrics report NaN.
    let mut g = cartesian(4, 4, 1.0, 1.0);
    g.set(1, 1, [f64::NAN, 1.0]);
    let r = quality2d(&g);
    assert_eq!(r.folded_cells, 4);
    assert!(r.jacobian_min.is_nan());
    serde_json::to_string(&r).unwrap();
    let mut g = tilted(&cartesian(4, 4, 1.0, 1.0));
    g.set(1, 1, [f64::NAN, 1.0, 0.0]);
    assert_eq!(quality_surface(&g).folded_cells, 4);
}

#[test]
fn display_is_a_table() {
    let r = quality2d(&moved_node());
    let text = r.to_string();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 12, "{text}");
    assert!(
        lines[0].contains("6 x 6 nodes, 25 cells, right-handed: FOLDED"),
        "{text}"
    );
    assert!(text.contains("(2,1) (2,2)"), "{text}");
    assert!(lines[8].ends_with("(4 nodes)"), "{text}");
    for e in ["E1", "E2", "E3", "E4"] {
        assert!(text.contains(&format!("orthogonality {e}")), "{text}");
    }
    // Values start in the same column on every metric line.
    // Column where the first label ends.
    let col = |l: &str| {
        let b = [" min ", " max ", " i "]
            .iter()
            .filter_map(|k| l.find(k).map(|b| b + k.len() - 1))
            .min()?;
        Some(l[..b].chars().count())
    };
    assert!(lines.iter().all(|l| !l.ends_with(' ')), "{text}");
    let c = col(lines[1]).unwrap();
    let cols: Vec<usize> = lines[2..].iter().filter_map(|l| col(l)).collect();
    assert_eq!(cols.len(), 9, "{text}");
    assert!(cols.iter().all(|&k| k == c), "{text}");
    assert_eq!(num(1.0 / 3.0), "0.3333");
    assert_eq!(num(1.5e-7), "1.500e-7");
    assert_eq!(num(f64::NAN), "-");
}

#[test]
fn large_grid_matches_small_grid_metrics() {
    // 10⁶ nodes through the parallel path: the metrics of a uniform sheared grid do not depend on
    // the size, and the first folds stay in index order across row chunks.
    let mut g = Grid2::from_fn(1000, 1000, |i, j| {
        [i as f64 + 0.5 * j as f64, j as f64 * 0.75f64.sqrt()]
    });
    g.set(500, 700, [500.0 + 350.0 + 1.6, 700.0 * 0.75f64.sqrt()]);
    let t = std::time::Instant::now();
    let r = quality2d(&g);
    eprintln!("quality2d of 10^6 nodes: {:?}", t.elapsed());
    assert_eq!(r.first_folded, vec![[500, 699], [500, 700]]);
    near(r.skewness_max.min(1.0 / 3.0), 1.0 / 3.0, TOL);
    let t = std::time::Instant::now();
    let f = cell_fields2d(&g);
    eprintln!("cell_fields2d of 10^6 nodes: {:?}", t.elapsed());
    let jac = field(&f, "jacobian_min");
    assert!(jac[500 + 999 * 699] < 0.0 && jac[500 + 999 * 700] < 0.0 && jac[499 + 999 * 700] > 0.0);
    let s = tilted(&g);
    let t = std::time::Instant::now();
    let r = quality_surface(&s);
    eprintln!("quality_surface of 10^6 nodes: {:?}", t.elapsed());
    assert_eq!(r.first_folded, vec![[500, 699], [500, 700]]);
}

#[test]
fn a_flat_corner_is_degenerate_not_folded_but_a_collapsed_one_folds() {
    // One cell whose corner (0, 0) lies inside the straight edge from (−1, 0) to (1, 0): the
    // corner angle is 180° (a block corner placed inside a CAD edge).
    let flat = Grid2::<2>::from_fn(2, 2, |i, j| {
        [[0.0, 0.0], [1.0, 0.0], [-1.0, 0.0], [1.0, 1.0]][i + 2 * j]
    });
    let q = quality2d(&flat);
    assert_eq!(q.folded_cells, 0, "{q}");
    assert!(q.jacobian_min.abs() < 1e-15);
    // The same corner with its edges pointing the same way (angle 0°): folded.
    let collapsed = Grid2::<2>::from_fn(2, 2, |i, j| {
        [[0.0, 0.0], [1.0, 0.0], [0.5, 0.0], [1.0, 1.0]][i + 2 * j]
    });
    assert_eq!(quality2d(&collapsed).folded_cells, 1);
    // A zero-length edge folds, unless it is a whole block side collapsed to a pole (then
    // the cell is the triangle it is).
    let short = Grid2::<2>::from_fn(3, 2, |i, j| {
        [
            [0.0, 0.0],
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [0.5, 1.0],
            [1.0, 1.0],
        ][i + 3 * j]
    });
    assert_eq!(quality2d(&short).first_folded, vec![[0, 0]]);
    let pole = Grid2::<2>::from_fn(2, 2, |i, j| {
        [[0.0, 0.0], [0.0, 0.0], [1.0, 1.0], [0.0, 1.0]][i + 2 * j]
    });
    let q = quality2d(&pole);
    assert_eq!(q.folded_cells, 0, "{q}");
    near(q.scaled_jacobian_min, 0.5f64.sqrt(), 1e-12);
}

/// The pseudo-angle that picks a cell's extreme corners orders directions exactly as their
/// angles do, all the way round (the skewness takes the arctangent of those two corners only).
#[test]
fn the_pseudo_angle_orders_directions_as_their_angles() {
    use crate::quality::geom::{corner_angle, pseudo_angle};
    let mut dirs: Vec<(f64, f64)> = (0..720i32)
        .map(|k| {
            let t = (k as f64 * 0.5 + 0.123).to_radians();
            let r = 10f64.powi(k % 7 - 3);
            (r * t.sin(), r * t.cos())
        })
        .collect();
    // the axes, signed zeros and the zero vector
    dirs.extend([
        (0.0, 1.0),
        (1.0, 0.0),
        (0.0, -1.0),
        (-1.0, 0.0),
        (-0.0, 2.0),
        (-0.0, -2.0),
        (0.0, 0.0),
    ]);
    for &(s1, c1) in &dirs {
        for &(s2, c2) in &dirs {
            let (a1, a2) = (corner_angle(s1, c1), corner_angle(s2, c2));
            let (p1, p2) = (pseudo_angle(s1, c1), pseudo_angle(s2, c2));
            if (a1 - a2).abs() > 1e-9 {
                assert_eq!(a1 < a2, p1 < p2, "({s1}, {c1}) {a1}° vs ({s2}, {c2}) {a2}°");
            }
        }
    }
    assert_eq!(corner_angle(0.0, 0.0), 0.0);
    assert!(pseudo_angle(f64::NAN, 1.0).is_nan() && pseudo_angle(1.0, f64::NAN).is_nan());
}

/// Spacings and growth ratios line by line: a grid whose i-spacings grow by 1.1 along every
/// row and whose j-spacings are 0.5, 1.0, 0.25 (growth 2 and 4), the extremes over both.
#[test]
fn spacings_and_growth_ratios_along_the_lines() {
    let ys = [0.0, 0.5, 1.5, 1.75];
    let g = Grid2::<2>::from_fn(6, 4, |i, j| [(1.1f64.powi(i as i32) - 1.0) / 0.1, ys[j]]);
    let r = quality2d(&g);
    near(r.growth_i_max, 1.1, TOL);
    near(r.growth_j_max, 4.0, TOL);
    near(r.min_spacing, 0.25, TOL);
    near(r.max_spacing, 1.1f64.powi(4), TOL);
}
