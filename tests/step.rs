//! STEP in and out (issue 7, CAD part): a B-spline surface written, read back and gridded
//! equals the grid of the original surface to 1e-12; faces that are not untrimmed four-sided
//! B-spline patches and unreadable files give exit 2 with a message naming the file and face.

use ellipgrid::cad::{
    self, grid_patch, read_step_faces, write_step_surface, write_step_surfaces, Route,
};
use ellipgrid::case::DistributionSpec;
use ellipgrid::solve::direct::DirectLu;
use ellipgrid::Grid2;
use ellipgrid_geometry::{BSplineSurf, HermiteSurface, Surface, Vec3};
use std::path::Path;
use std::process::Command;
use truck_geometry::prelude::{
    BSplineCurve, BSplineSurface, KnotVec, NurbsCurve, NurbsSurface, Point3, Vector4,
};
use truck_stepio::out::{CompleteStepDisplay, StepHeaderDescriptor, StepModel};
use truck_stepio::r#in::alias::{Curve3D, Surface as StepSurface};
use truck_topology::compress::{CompressedEdge, CompressedFace, CompressedShell};

/// Round-trip tolerance of the issue.
const ROUND_TRIP_TOL: f64 = 1e-12;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_ellipgrid"))
}

/// A wavy 7 × 5 control net over [0, 2] × [0, 1.5] with coordinates of every magnitude
/// (including |x| < 10⁻², which truck's writer prints with fewer digits).
fn net() -> HermiteSurface {
    let (ni, nj) = (7, 5);
    let pts = (0..ni * nj)
        .map(|k| {
            let (i, j) = ((k % ni) as f64, (k / ni) as f64);
            let (x, y) = (2.0 * i / 6.0 + 0.003 * j, 1.5 * j / 4.0 + 0.002 * i * i);
            Vec3::new(x, y, 0.2 * (2.0 * x).sin() * (1.0 + y) + 0.004 * y * y)
        })
        .collect();
    HermiteSurface::new(ni, nj, pts).unwrap()
}

fn grid(s: &dyn Surface, di: &DistributionSpec) -> Grid2<3> {
    grid_patch(
        s,
        (33, 25),
        di,
        &DistributionSpec::Uniform {},
        &mut DirectLu::new(),
        "test",
    )
    .unwrap()
    .grid
}

fn max_diff(a: &Grid2<3>, b: &Grid2<3>) -> f64 {
    (0..3)
        .flat_map(|c| {
            a.coord(c)
                .iter()
                .zip(b.coord(c))
                .map(|(x, y)| (x - y).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn bspline_written_read_and_gridded_equals_the_original_grid() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("net.step");
    let h = net();
    let b = h.to_bspline();
    write_step_surface(&path, &b).unwrap();
    let faces = read_step_faces(&path).unwrap();
    assert_eq!(faces.len(), 1);
    let f = &faces[0];
    assert_eq!((f.index, f.surface_type), (1, "B-spline"));
    assert!(f.is_four_sided_patch(), "{:?}", f.trimmed);
    let read = f.patch(&path).unwrap();
    assert_eq!(read.degrees(), (3, 3));
    let original = BSplineSurf::from_truck_bspline(&b).unwrap();
    for di in [
        DistributionSpec::Uniform {},
        DistributionSpec::Vinokur {
            first: Some(0.01),
            last: Some(0.05),
        },
    ] {
        let g_read = grid(read, &di);
        let g_bspline = grid(&original, &di);
        let g_hermite = grid(&h, &di);
        let (d1, d2) = (max_diff(&g_read, &g_bspline), max_diff(&g_read, &g_hermite));
        eprintln!("{di:?}: |read − B-spline| = {d1:e}, |read − Hermite| = {d2:e}");
        assert!(d1 <= ROUND_TRIP_TOL, "{d1:e}");
        assert!(d2 <= ROUND_TRIP_TOL, "{d2:e}");
    }
    // The library entry point for case files gives the same surface.
    assert_eq!(&cad::step_surface(&path, 1).unwrap(), read);
}

/// Three B-spline faces written in one shell come back numbered in the order given, each an
/// untrimmed four-sided patch evaluating to its surface's points (to the writer's print
/// precision); a side two surfaces share is one edge of the shell, and bad input writes no file.
#[test]
fn several_surfaces_written_in_order_read_back_as_the_same_patches() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("three.step");
    let a = net().to_bspline();
    // b: a bicubic strip below a in y whose last column is a's first exactly (u knots shared)
    let (acp, uk) = (a.control_points(), a.uknot_vec().clone());
    let b_cp: Vec<Vec<Point3>> = acp
        .iter()
        .map(|col| {
            let p = col[0];
            vec![
                Point3::new(p.x, p.y - 0.9, p.z + 0.1),
                Point3::new(p.x, p.y - 0.6, p.z - 0.05),
                Point3::new(p.x, p.y - 0.3, p.z + 0.02),
                p,
            ]
        })
        .collect();
    let b = BSplineSurface::new((uk, KnotVec::bezier_knot(3)), b_cp);
    // c: a biquadratic bump far away, so that a reordering cannot go unseen
    let c_cp: Vec<Vec<Point3>> = (0..3)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let (x, y) = (5.0 + i as f64, 3.0 + 0.5 * j as f64);
                    Point3::new(x, y, 0.3 * (i * j) as f64)
                })
                .collect()
        })
        .collect();
    let c = BSplineSurface::new(
        (
            KnotVec::bezier_knot(2),
            KnotVec::from(vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0]),
        ),
        c_cp,
    );
    let surfaces = [a, b, c];
    write_step_surfaces(&path, &surfaces).unwrap();
    let read = cad::read_step(&path).unwrap();
    assert!(read.unread.is_empty(), "{:?}", read.unread);
    assert_eq!(read.faces.len(), 3);
    for (k, (f, s)) in read.faces.iter().zip(&surfaces).enumerate() {
        assert_eq!(f.index, k + 1);
        assert_eq!(f.route(), Route::Patch, "face {}: {:?}", k + 1, f.trimmed);
        assert!(f.orientation, "face {}", k + 1);
        let original = BSplineSurf::from_truck_bspline(s).unwrap();
        let got = f.patch(&path).unwrap();
        assert_eq!(got.degrees(), original.degrees());
        let mut off = 0.0_f64;
        for n in 0..=20 * 20 {
            let (u, v) = ((n % 21) as f64 / 20.0, (n / 21) as f64 / 20.0);
            off = off.max((got.point(u, v) - original.point(u, v)).norm());
        }
        assert!(off < 1e-12, "face {}: {off:e}", k + 1);
    }
    // a and b share one edge (and its two vertices): 4 + 3 + 4 edges, 4 + 2 + 4 vertices
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.matches("= EDGE_CURVE(").count(), 11);
    assert_eq!(text.matches("= VERTEX_POINT(").count(), 10);
    // one surface: the same file as write_step_surface writes
    let (one, many) = (dir.path().join("one.step"), dir.path().join("many.step"));
    write_step_surface(&one, &surfaces[1]).unwrap();
    write_step_surfaces(&many, &surfaces[1..2]).unwrap();
    let data = |p: &Path| {
        let t = std::fs::read_to_string(p).unwrap();
        t[t.find("DATA;").unwrap()..].to_string()
    };
    assert_eq!(data(&one), data(&many));
    // no surface, or a bad one among good ones: an input error naming it, no file
    let bad_path = dir.path().join("bad.step");
    let e = write_step_surfaces(&bad_path, &[]).unwrap_err();
    assert!(e.to_string().contains("no surface"), "{e}");
    let mut bad = surfaces[2].clone();
    *bad.control_point_mut(1, 1) = Point3::new(f64::NAN, 0.0, 0.0);
    let e = write_step_surfaces(&bad_path, &[surfaces[0].clone(), bad]).unwrap_err();
    assert!(e.to_string().contains("surface 2"), "{e}");
    assert!(!bad_path.exists());
}

/// Writes a STEP shell with one B-spline face of the plane z = 0 over [0, 1]², bounded by
/// the given closed polygon (straight B-spline edges).
fn write_plane_face(path: &Path, corners: &[[f64; 2]]) {
    let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    let surface = BSplineSurface::new(
        (KnotVec::bezier_knot(1), KnotVec::bezier_knot(1)),
        vec![vec![p(0., 0.), p(0., 1.)], vec![p(1., 0.), p(1., 1.)]],
    );
    let n = corners.len();
    let vertices: Vec<Point3> = corners.iter().map(|c| p(c[0], c[1])).collect();
    let edges = (0..n)
        .map(|k| CompressedEdge {
            vertices: (k, (k + 1) % n),
            curve: Curve3D::BSplineCurve(BSplineCurve::new(
                KnotVec::bezier_knot(1),
                vec![vertices[k], vertices[(k + 1) % n]],
            )),
        })
        .collect();
    let shell = CompressedShell {
        vertices,
        edges,
        faces: vec![CompressedFace {
            boundaries: vec![(0..n).map(|k| (k, true).into()).collect()],
            orientation: true,
            surface: StepSurface::BSplineSurface(Box::new(surface)),
        }],
    };
    let text = CompleteStepDisplay::new(StepModel::from(&shell), StepHeaderDescriptor::default())
        .to_string();
    std::fs::write(path, text).unwrap();
}

#[test]
fn four_sided_check_accepts_the_sides_and_rejects_trimmed_faces() {
    let dir = tempfile::tempdir().unwrap();
    // (name, boundary polygon in (u, v), why it is not four-sided)
    type Case<'a> = (&'a str, &'a [[f64; 2]], Option<&'a str>);
    let cases: [Case; 4] = [
        ("square", &[[0., 0.], [1., 0.], [1., 1.], [0., 1.]], None),
        // Five edges: a side split in two is still four-sided.
        (
            "split",
            &[[0., 0.], [0.4, 0.], [1., 0.], [1., 1.], [0., 1.]],
            None,
        ),
        (
            "triangle",
            &[[0., 0.], [1., 0.], [0., 1.]],
            Some("boundary edge 2 is not on a side"),
        ),
        (
            "inner",
            &[[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]],
            Some("boundary edge 1 is not on a side"),
        ),
    ];
    for (name, corners, why) in cases {
        let path = dir.path().join(format!("{name}.step"));
        write_plane_face(&path, corners);
        let faces = read_step_faces(&path).unwrap();
        assert_eq!(faces.len(), 1, "{name}");
        match why {
            None => assert!(
                faces[0].is_four_sided_patch(),
                "{name}: {:?}",
                faces[0].trimmed
            ),
            Some(w) => {
                let got = faces[0].trimmed.as_deref().unwrap_or("");
                assert!(got.contains(w), "{name}: {got}");
                let e = faces[0].patch(&path).unwrap_err().to_string();
                assert!(e.contains("face 1") && e.contains(name), "{e}");
            }
        }
    }
}

/// A NURBS face (a quarter of the unit cylinder, exact: rational quadratic arcs) read back
/// and gridded equals the grid of the original surface, and the grid lies on the cylinder.
#[test]
fn nurbs_face_round_trip_on_a_cylinder() {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = |z: f64| {
        vec![
            Vector4::new(1.0, 0.0, z, 1.0),
            Vector4::new(w, w, w * z, w),
            Vector4::new(0.0, 1.0, z, 1.0),
        ]
    };
    let (a0, a1) = (arc(0.0), arc(2.0));
    // control_points()[i_u][i_v]: u around the arc, v along the axis.
    let cp: Vec<Vec<Vector4>> = (0..3).map(|i| vec![a0[i], a1[i]]).collect();
    let (ku, kv) = (KnotVec::bezier_knot(2), KnotVec::bezier_knot(1));
    let surface = NurbsSurface::new(BSplineSurface::new((ku.clone(), kv.clone()), cp.clone()));
    let curve = |k: &KnotVec, pts: Vec<Vector4>| {
        Curve3D::NurbsCurve(NurbsCurve::new(BSplineCurve::new(k.clone(), pts)))
    };
    let p = |v: Vector4| Point3::new(v.x / v.w, v.y / v.w, v.z / v.w);
    let shell = CompressedShell {
        vertices: vec![p(cp[0][0]), p(cp[2][0]), p(cp[2][1]), p(cp[0][1])],
        edges: vec![
            CompressedEdge {
                vertices: (0, 1),
                curve: curve(&ku, a0.clone()),
            },
            CompressedEdge {
                vertices: (1, 2),
                curve: curve(&kv, cp[2].clone()),
            },
            CompressedEdge {
                vertices: (3, 2),
                curve: curve(&ku, a1.clone()),
            },
            CompressedEdge {
                vertices: (0, 3),
                curve: curve(&kv, cp[0].clone()),
            },
        ],
        faces: vec![CompressedFace {
            boundaries: vec![vec![
                (0, true).into(),
                (1, true).into(),
                (2, false).into(),
                (3, false).into(),
            ]],
            orientation: true,
            surface: StepSurface::NurbsSurface(Box::new(surface.clone())),
        }],
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cylinder.step");
    let text = CompleteStepDisplay::new(StepModel::from(&shell), StepHeaderDescriptor::default())
        .to_string();
    std::fs::write(&path, text).unwrap();
    let faces = read_step_faces(&path).unwrap();
    assert_eq!(faces[0].surface_type, "NURBS");
    let read = faces[0].patch(&path).unwrap();
    let original = BSplineSurf::from_truck_nurbs(&surface).unwrap();
    let di = DistributionSpec::Vinokur {
        first: Some(0.01),
        last: None,
    };
    let (g, g0) = (grid(read, &di), grid(&original, &di));
    let d = max_diff(&g, &g0);
    assert!(d <= ROUND_TRIP_TOL, "{d:e}");
    let off = (0..g.len())
        .map(|k| (g.coord(0)[k].hypot(g.coord(1)[k]) - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(off < 1e-12, "distance from the cylinder {off:e}");
}

#[test]
fn cli_export_then_grid_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let h = net();
    // The control net as a Plot3D surface block.
    let (ni, nj) = (7, 5);
    let mut g = Grid2::<3>::zeros(ni, nj);
    let b = h.to_bspline();
    for j in 0..nj {
        for i in 0..ni {
            // Hermite nodes are the B-spline control points (3i, 3j).
            let p = b.control_points()[3 * i][3 * j];
            for (c, v) in [p.x, p.y, p.z].into_iter().enumerate() {
                g.coord_mut(c)[i + ni * j] = v;
            }
        }
    }
    let netx = dir.path().join("net.x");
    ellipgrid::io::plot3d::write_plot3d(
        &netx,
        &[ellipgrid::io::Block::from(g)],
        &ellipgrid::io::plot3d::Plot3dFormat::default(),
        None,
    )
    .unwrap();
    let step = dir.path().join("net.step");
    let out = bin()
        .args(["step", "export"])
        .arg(&netx)
        .arg("-o")
        .arg(&step)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let grid_x = dir.path().join("grid.x");
    let out = bin()
        .args(["step", "grid"])
        .arg(&step)
        .args([
            "--face",
            "1",
            "--ni",
            "33",
            "--nj",
            "25",
            "--first-i",
            "0.01",
            "--last-i",
            "0.05",
            // The library grid below is solved by the direct LU: the same solver, so that
            // the round trip is compared to the 1e-12 (the multigrid's grid differs
            // from it by its solve tolerance, 4.5e-12).
            "--linear",
            "direct",
            "-q",
            "-o",
        ])
        .arg(&grid_x)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let file = ellipgrid::io::plot3d::read_plot3d(&grid_x).unwrap();
    let ellipgrid::io::Block::Surface(got) = &file.blocks[0] else {
        panic!("not a surface block");
    };
    let di = DistributionSpec::Vinokur {
        first: Some(0.01),
        last: Some(0.05),
    };
    let d = max_diff(got, &grid(&h, &di));
    assert!(d <= ROUND_TRIP_TOL, "{d:e}");
    // `list` names the face.
    let out = bin().args(["step", "list"]).arg(&step).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("face 1: B-spline, four-sided patch, degrees 3 × 3"),
        "{text}"
    );
}

/// `step export --all` writes every block of a control-net file as faces 1, 2, … of one
/// shell, in block order, each the block's bicubic B-spline; `--all` with `--block` is refused.
#[test]
fn cli_export_all_blocks_as_faces_in_order() {
    let dir = tempfile::tempdir().unwrap();
    let h = net();
    let (ni, nj) = (7, 5);
    let b = h.to_bspline();
    // block k: the net's Hermite nodes moved up by k
    let blocks: Vec<ellipgrid::io::Block> = (0..3)
        .map(|k| {
            Grid2::<3>::from_fn(ni, nj, |i, j| {
                let p = b.control_points()[3 * i][3 * j];
                [p.x, p.y, p.z + k as f64]
            })
            .into()
        })
        .collect();
    let netx = dir.path().join("nets.x");
    let fmt = ellipgrid::io::plot3d::Plot3dFormat::default();
    ellipgrid::io::plot3d::write_plot3d(&netx, &blocks, &fmt, None).unwrap();
    let step = dir.path().join("nets.step");
    let out = bin()
        .args(["step", "export", "--all"])
        .arg(&netx)
        .arg("-o")
        .arg(&step)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(
        text.contains("3 control nets (7 × 5, 7 × 5, 7 × 5)"),
        "{text}"
    );
    let faces = read_step_faces(&step).unwrap();
    assert_eq!(faces.len(), 3);
    let original = BSplineSurf::from_truck_bspline(&b).unwrap();
    for (k, f) in faces.iter().enumerate() {
        assert_eq!(f.route(), Route::Patch);
        let s = f.patch(&step).unwrap();
        for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.5), (0.5, 1.0)] {
            let d = s.point(u, v) - original.point(u, v) - Vec3::new(0.0, 0.0, k as f64);
            assert!(d.norm() < 1e-12, "face {}: {d:?}", k + 1);
        }
    }
    let out = bin()
        .args(["step", "export", "--all", "--block", "2"])
        .arg(&netx)
        .arg("-o")
        .arg(dir.path().join("no.step"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(!dir.path().join("no.step").exists());
}

#[test]
fn cli_trimmed_face_and_unreadable_files_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let tri = dir.path().join("tri.step");
    write_plane_face(&tri, &[[0., 0.], [1., 0.], [0., 1.]]);
    let out_x = dir.path().join("out.x");
    let run = |file: &Path, face: &str| {
        bin()
            .args(["step", "grid"])
            .arg(file)
            .args(["--face", face, "-o"])
            .arg(&out_x)
            .output()
            .unwrap()
    };
    // A three-sided face is gridded as a block face (tests/step_faces.rs).
    let out = run(&tri, "1");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    std::fs::remove_file(&out_x).unwrap();
    let out = run(&tri, "2");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("face 2") && err.contains("no such face"),
        "{err}"
    );
    // --all with a face that cannot be gridded (ni < 3): exit 2.
    let out = bin()
        .args(["step", "grid"])
        .arg(&tri)
        .args(["--all", "--ni", "2", "-o"])
        .arg(&out_x)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    // Missing file, garbage, a STEP file without shells.
    let garbage = dir.path().join("garbage.step");
    std::fs::write(&garbage, "ISO-10303-21;\nthis is not STEP\n").unwrap();
    let empty = dir.path().join("empty.step");
    std::fs::write(
        &empty,
        "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1 = CARTESIAN_POINT('', (0.0, 0.0, 0.0));\nENDSEC;\nEND-ISO-10303-21;\n",
    )
    .unwrap();
    for (f, want) in [
        (dir.path().join("missing.step"), "missing.step"),
        (garbage, "garbage.step"),
        (empty, "empty.step"),
    ] {
        let out = run(&f, "1");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{want}: {err}");
        assert!(err.contains(want), "{err}");
    }
    assert!(!out_x.exists(), "no output on errors");
}
