//! Assembly placements of STEP files (issue #14): a part used several times in an assembly
//! gives its faces once per use, each moved by the composed placements of its path to the
//! root, in the root's length unit (`data/step/plane_triangle_assembly.step` and its `_inch`
//! variant, made by `make_assembly.py`).

mod common;
use common::{ellipgrid, grid_node as node, root, step_grid_all, text};
use ellipgrid::cad::{grid_face, read_step_faces, FaceGrid};
use ellipgrid::case::DistributionSpec;
use ellipgrid::solve::direct::DirectLu;

fn file(name: &str) -> std::path::PathBuf {
    root().join("data/step").join(name)
}

/// Every face of a file gridded with n × n uniform nodes.
fn grids(name: &str, n: usize) -> Vec<FaceGrid> {
    let d = DistributionSpec::Uniform {};
    read_step_faces(&file(name))
        .unwrap()
        .iter()
        .map(|f| grid_face(f, (n, n), &d, &d, &mut DirectLu::new(), name).unwrap())
        .collect()
}

#[test]
fn a_part_used_twice_in_a_sub_assembly_is_gridded_at_both_places() {
    // The triangle of plane_triangle.step in `pair` at (10, 0, 0) turned 90° about z and at
    // (0, 0, 5) with its axes x, y, z along y, z, x (that transformation's items written the
    // other way round), `pair` in `frame` at (0, 100, 0).
    let moves: [fn([f64; 3]) -> [f64; 3]; 2] = [
        |p| [10.0 - p[1], 100.0 + p[0], p[2]],
        |p| [p[2], 100.0 + p[0], 5.0 + p[1]],
    ];
    for n in [5, 9] {
        let base = grids("plane_triangle.step", n);
        let placed = grids("plane_triangle_assembly.step", n);
        assert_eq!((base.len(), placed.len()), (1, 2));
        let b = &base[0].result.grid;
        for (k, g) in placed.iter().enumerate() {
            let g = &g.result.grid;
            assert_eq!(g.len(), b.len());
            let worst = (0..g.len())
                .map(|p| {
                    let want = moves[k](node(b, p));
                    let got = node(g, p);
                    (0..3).map(|c| (got[c] - want[c]).abs()).fold(0.0, f64::max)
                })
                .fold(0.0, f64::max);
            assert!(worst < 1e-11, "{n} × {n}: instance {k} is {worst:e} off");
        }
    }
    // The assemblies in inches, the part in millimetres: the faces in inches.
    let inch: [fn([f64; 3]) -> [f64; 3]; 2] = [
        |p| [10.0 - p[1] / 25.4, 100.0 + p[0] / 25.4, p[2] / 25.4],
        |p| [p[2] / 25.4, 100.0 + p[0] / 25.4, 5.0 + p[1] / 25.4],
    ];
    let base = grids("plane_triangle.step", 9);
    let placed = grids("plane_triangle_assembly_inch.step", 9);
    assert_eq!(placed.len(), 2);
    let b = &base[0].result.grid;
    for (k, g) in placed.iter().enumerate() {
        let g = &g.result.grid;
        let worst = (0..g.len())
            .map(|p| {
                let (want, got) = (inch[k](node(b, p)), node(g, p));
                (0..3).map(|c| (got[c] - want[c]).abs()).fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        assert!(worst < 1e-11, "inches: instance {k} is {worst:e} off");
    }
    // Through the CLI: two faces listed, two blocks written.
    let dir = tempfile::tempdir().unwrap();
    let path = file("plane_triangle_assembly.step");
    let o = ellipgrid(dir.path(), &["step", "list", path.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        out.lines().filter(|l| l.starts_with("face ")).count(),
        2,
        "{out}"
    );
    let o = step_grid_all(dir.path(), path.to_str().unwrap(), ("5", "5"), "a.x");
    assert!(o.status.success(), "{}", text(&o));
    let p = ellipgrid::io::plot3d::read_plot3d(&dir.path().join("a.x")).unwrap();
    assert_eq!(p.blocks.len(), 2);
}

#[test]
fn mapped_items_place_a_part_like_the_assembly_relationships() {
    // plane_triangle_mapped.step: the same two instances as plane_triangle_assembly.step,
    // written as mapped items (one targeted at a placement, one at a transformation
    // operator, `pair` mapped into `frame`), and a draughting model's identity mapped item
    // that places nothing.
    for n in [5, 9] {
        let nested = grids("plane_triangle_assembly.step", n);
        let mapped = grids("plane_triangle_mapped.step", n);
        assert_eq!(mapped.len(), 2, "{n} × {n}");
        for (k, (a, b)) in nested.iter().zip(&mapped).enumerate() {
            let (a, b) = (&a.result.grid, &b.result.grid);
            assert_eq!(a.len(), b.len());
            let worst = (0..a.len())
                .map(|p| {
                    let (x, y) = (node(a, p), node(b, p));
                    (0..3).map(|c| (x[c] - y[c]).abs()).fold(0.0, f64::max)
                })
                .fold(0.0, f64::max);
            assert!(worst < 1e-11, "{n} × {n}: instance {k} is {worst:e} off");
        }
    }
    // Through the CLI: the same file written.
    let dir = tempfile::tempdir().unwrap();
    for (name, out) in [
        ("plane_triangle_assembly.step", "a.x"),
        ("plane_triangle_mapped.step", "m.x"),
    ] {
        let path = file(name);
        let o = step_grid_all(dir.path(), path.to_str().unwrap(), ("5", "5"), out);
        assert!(o.status.success(), "{}", text(&o));
    }
    let (a, m) = (
        ellipgrid::io::plot3d::read_plot3d(&dir.path().join("a.x")).unwrap(),
        ellipgrid::io::plot3d::read_plot3d(&dir.path().join("m.x")).unwrap(),
    );
    assert_eq!(m.blocks.len(), 2);
    for (x, y) in a.blocks.iter().zip(&m.blocks) {
        use ellipgrid::io::Block::Surface;
        let (Surface(x), Surface(y)) = (x, y) else {
            panic!("surface blocks expected");
        };
        assert_eq!(x.len(), y.len());
        let d = (0..x.len())
            .map(|p| {
                let (p, q) = (node(x, p), node(y, p));
                (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        assert!(d < 1e-11, "the CLI's blocks differ by {d:e}");
    }
}
