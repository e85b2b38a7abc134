//! Solver meshes (#19): OpenFOAM polyMesh, SU2 and Gmsh from multi-block grids, the blocks
//! merged through their interfaces. Known answers: node and face counts of small grids, every
//! OpenFOAM cell closed (its outward face area vectors sum to zero) with a positive volume
//! (Gauss), upper-triangular face order, the grid's nodes bit-identical among the points.

mod common;

use common::{ellipgrid, root, text};
use ellipgrid::io::connectivity::ConnFile;
use ellipgrid::io::mesh::{sides_as_patches, BcKind, Mesh};
use ellipgrid::io::Block;
use ellipgrid::Grid2;
use std::path::Path;

fn rect(x0: f64, ni: usize, nj: usize) -> Block {
    Block::Planar(Grid2::from_fn(ni, nj, |i, j| {
        [x0 + i as f64 / (ni - 1) as f64, j as f64 / (nj - 1) as f64]
    }))
}

/// Two unit squares side by side, sharing the edge x = 1.
fn two_squares() -> (Vec<(String, Block)>, ConnFile) {
    let blocks = vec![
        ("a".to_string(), rect(0.0, 3, 3)),
        ("b".to_string(), rect(1.0, 3, 3)),
    ];
    let conn = ConnFile {
        interfaces: vec![[(1, [3, 1, 1], [3, 3, 1]), (2, [1, 1, 1], [1, 3, 1])]],
        patches: vec![
            ((1, [1, 1, 1], [1, 3, 1]), 1),
            ((1, [1, 1, 1], [3, 1, 1]), 2),
            ((1, [1, 3, 1], [3, 3, 1]), 2),
            ((2, [3, 1, 1], [3, 3, 1]), 3),
            ((2, [1, 1, 1], [3, 1, 1]), 2),
            ((2, [1, 3, 1], [3, 3, 1]), 2),
        ],
        families: vec![
            (1, "inflow".into()),
            (2, "wall".into()),
            (3, "outflow".into()),
        ],
        bcs: vec![],
    };
    (blocks, conn)
}

#[test]
fn two_blocks_sharing_an_edge_merge_into_one_mesh() {
    let (blocks, conn) = two_squares();
    let m = Mesh::build("t", &blocks, &conn, None).unwrap();
    assert_eq!(m.npoints(), 15, "3 × 5 distinct nodes");
    assert_eq!(m.ncells(), 8);
    assert_eq!(m.joins.len(), 2, "two cell faces on the shared edge");
    assert_eq!(m.ninternal_faces(), 2 * 4 + 2);
    let sizes: Vec<usize> = m.boundary.iter().map(Vec::len).collect();
    assert_eq!(sizes, vec![2, 8, 2]);
    assert_eq!(m.families, vec!["inflow", "wall", "outflow"]);
    // Each join's owner is in block a, its neighbour in block b, and its nodes are at x = 1.
    for j in &m.joins {
        assert!(j.owner < 4 && j.neighbour >= 4, "{j:?}");
        for n in &j.nodes[..2] {
            assert_eq!(m.point(*n)[0], 1.0);
        }
    }
    // Extruded one cell thick: twice the nodes, hexahedra, front and back as one family.
    let m = Mesh::build("t", &blocks, &conn, Some(0.5)).unwrap();
    assert_eq!(m.npoints(), 30);
    assert_eq!(m.ninternal_faces(), 10);
    assert_eq!(m.families.last().unwrap(), "frontAndBack");
    assert_eq!(m.boundary.last().unwrap().len(), 16);
    assert_eq!(BcKind::of("frontAndBack"), BcKind::Empty);
    assert_eq!(BcKind::of("wall"), BcKind::Wall);
}

/// A one-block O-grid about the unit circle, i counter-clockwise (left-handed), closed by a
/// periodic cut i = 1 ↔ i = ni.
fn o_grid(ni: usize, nj: usize) -> (Vec<(String, Block)>, ConnFile) {
    let g = Grid2::from_fn(ni, nj, |i, j| {
        let t = 2.0 * std::f64::consts::PI * i as f64 / (ni - 1) as f64;
        let r = 1.0 + j as f64 / (nj - 1) as f64;
        [r * t.cos(), r * t.sin()]
    });
    let conn = ConnFile {
        interfaces: vec![[(1, [1, 1, 1], [1, nj, 1]), (1, [ni, 1, 1], [ni, nj, 1])]],
        patches: vec![
            ((1, [1, 1, 1], [ni, 1, 1]), 1),
            ((1, [1, nj, 1], [ni, nj, 1]), 2),
        ],
        families: vec![(1, "wall".into()), (2, "farfield".into())],
        bcs: vec![],
    };
    (vec![("ring".to_string(), Block::Planar(g))], conn)
}

#[test]
fn a_periodic_cut_joins_a_block_to_itself_and_left_handed_cells_are_turned() {
    let (blocks, conn) = o_grid(17, 5);
    let m = Mesh::build("t", &blocks, &conn, None).unwrap();
    assert_eq!(m.npoints(), 16 * 5);
    assert_eq!(m.joins.len(), 4, "one face per cell row across the cut");
    assert!(
        m.blocks[0].flip,
        "i counter-clockwise, j outward: left-handed"
    );
    for b in &m.blocks {
        for j in 0..b.cell_dims()[1] {
            for i in 0..b.cell_dims()[0] {
                let n = b.cell_nodes(i, j, 0);
                let p: Vec<[f64; 3]> = n[..4].iter().map(|&k| m.point(k)).collect();
                let area: f64 = (0..4)
                    .map(|k| {
                        let (a, c) = (p[k], p[(k + 1) % 4]);
                        a[0] * c[1] - a[1] * c[0]
                    })
                    .sum();
                assert!(area > 0.0, "cell ({i}, {j}) clockwise");
            }
        }
    }
    // Boundary faces run with the domain on their left: the wall (inner circle) clockwise.
    let w = m.boundary[0][0].nodes;
    let (a, b) = (m.point(w[0]), m.point(w[1]));
    assert!(a[0] * b[1] - a[1] * b[0] < 0.0, "wall face runs clockwise");
}

#[test]
fn bad_connectivity_is_named() {
    let (blocks, mut conn) = two_squares();
    conn.patches.remove(3);
    let e = Mesh::build("g.x", &blocks, &conn, None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("block 'b'") && e.contains("i = max") && e.contains("neither"),
        "{e}"
    );

    let (blocks, mut conn) = two_squares();
    conn.interfaces[0][1] = (2, [3, 1, 1], [3, 3, 1]);
    conn.patches[3] = ((2, [1, 1, 1], [1, 3, 1]), 3);
    let e = Mesh::build("g.x", &blocks, &conn, None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("'a' and 'b' do not meet") && e.contains("apart"),
        "{e}"
    );

    let (blocks, mut conn) = two_squares();
    conn.patches[0].0 .2 = [1, 4, 1];
    let e = Mesh::build("g.x", &blocks, &conn, None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("outside block 'a'"), "{e}");

    let (mut blocks, conn) = two_squares();
    blocks[1].1 = Block::Surface(Grid2::from_fn(3, 3, |i, j| [i as f64, j as f64, 0.0]));
    let e = Mesh::build("g.x", &blocks, &conn, None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("one mesh holds blocks of one kind"), "{e}");

    let c = sides_as_patches(&blocks[..1]);
    assert_eq!(c.families[3].1, "a_E4");
}

/// Numbers of an OpenFOAM list file: the entries between the outermost parentheses after the
/// header, as flat numbers per line.
fn foam_list(path: &Path) -> Vec<Vec<f64>> {
    let s = std::fs::read_to_string(path).unwrap();
    let body = &s[s.find("}\n").unwrap() + 2..];
    let open = body.find("\n(").unwrap();
    body[open + 2..]
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && *l != ")")
        .map(|l| {
            let l = l.find('(').map_or(l, |k| &l[k + 1..]);
            l.trim_end_matches(')')
                .split_whitespace()
                .map(|v| v.parse::<f64>().unwrap())
                .collect()
        })
        .collect()
}

/// Checks an OpenFOAM mesh as a solver sees it; returns (points, cells, boundary text).
fn check_polymesh(dir: &Path) -> (Vec<[f64; 3]>, usize, String) {
    let pts: Vec<[f64; 3]> = foam_list(&dir.join("points"))
        .into_iter()
        .map(|v| [v[0], v[1], v[2]])
        .collect();
    let faces: Vec<Vec<usize>> = foam_list(&dir.join("faces"))
        .into_iter()
        .map(|v| v.into_iter().map(|x| x as usize).collect())
        .collect();
    let owner: Vec<usize> = foam_list(&dir.join("owner"))
        .iter()
        .map(|v| v[0] as usize)
        .collect();
    let nb: Vec<usize> = foam_list(&dir.join("neighbour"))
        .iter()
        .map(|v| v[0] as usize)
        .collect();
    assert_eq!(faces.len(), owner.len());
    let ncells = owner.iter().chain(&nb).max().unwrap() + 1;
    // upper-triangular: owner < neighbour, sorted by (owner, neighbour)
    for k in 0..nb.len() {
        assert!(owner[k] < nb[k], "face {k}");
        if k > 0 {
            assert!(
                (owner[k - 1], nb[k - 1]) < (owner[k], nb[k]),
                "face {k} out of order"
            );
        }
    }
    let mut sum = vec![[0.0f64; 3]; ncells];
    let mut vol = vec![0.0f64; ncells];
    let mut scale = 0.0f64;
    for (f, nodes) in faces.iter().enumerate() {
        assert_eq!(nodes.len(), 4);
        let p: Vec<[f64; 3]> = nodes.iter().map(|&n| pts[n]).collect();
        let mut s = [0.0; 3];
        let mut c = [0.0; 3];
        for k in 0..4 {
            let (a, b) = (p[k], p[(k + 1) % 4]);
            s[0] += 0.5 * (a[1] * b[2] - a[2] * b[1]);
            s[1] += 0.5 * (a[2] * b[0] - a[0] * b[2]);
            s[2] += 0.5 * (a[0] * b[1] - a[1] * b[0]);
            for d in 0..3 {
                c[d] += 0.25 * a[d];
            }
        }
        scale = scale.max(s.iter().map(|x| x.abs()).fold(0.0, f64::max));
        let flux = (c[0] * s[0] + c[1] * s[1] + c[2] * s[2]) / 3.0;
        for d in 0..3 {
            sum[owner[f]][d] += s[d];
        }
        vol[owner[f]] += flux;
        if f < nb.len() {
            for d in 0..3 {
                sum[nb[f]][d] -= s[d];
            }
            vol[nb[f]] -= flux;
        }
    }
    for c in 0..ncells {
        let open = sum[c].iter().map(|x| x.abs()).fold(0.0, f64::max);
        assert!(open <= 1e-10 * scale, "cell {c} not closed: {:?}", sum[c]);
        assert!(vol[c] > 0.0, "cell {c}: volume {} (faces inward?)", vol[c]);
    }
    let boundary = std::fs::read_to_string(dir.join("boundary")).unwrap();
    (pts, ncells, boundary)
}

#[test]
fn c_grid_to_openfoam_su2_and_gmsh_through_the_cli() {
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/rae2822_cgrid.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "-q",
            case.to_str().unwrap(),
            "-o",
            "c.x",
            "-o",
            "c.conn",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    for out in ["case/constant/polyMesh", "c.su2", "c.msh"] {
        let o = ellipgrid(d.path(), &["convert", "c.x", out]);
        assert!(o.status.success(), "{}", text(&o));
        assert!(
            text(&o).contains("connectivity from c.conn"),
            "{}",
            text(&o)
        );
    }
    let grid = ellipgrid::io::plot3d::read_plot3d(&d.path().join("c.x")).unwrap();
    let nodes: usize = grid.blocks.iter().map(|b| b.nnodes()).sum();
    // 4 blocks; merged: every interface node once (the wake cut, the three cuts).
    let (pts, ncells, boundary) = check_polymesh(&d.path().join("case/constant/polyMesh"));
    assert_eq!(ncells, 2 * 128 * 80 + 2 * 96 * 80);
    assert_eq!(pts.len(), 2 * 36272);
    assert!(nodes > 36272);
    for (name, t) in [
        ("airfoil", "wall"),
        ("farfield", "patch"),
        ("outflow", "patch"),
        ("frontAndBack", "empty"),
    ] {
        let k = boundary.find(&format!("    {name}\n")).expect(name);
        assert!(
            boundary[k..].contains(&format!("type            {t};")),
            "{name}"
        );
    }
    // Every grid node is a point of the mesh, bit for bit, at z = 0 and at z = 1.
    let mut set: std::collections::HashSet<[u64; 3]> =
        pts.iter().map(|p| p.map(f64::to_bits)).collect();
    for b in &grid.blocks {
        for n in 0..b.nnodes() {
            let p = [b.coord(0)[n], b.coord(1)[n], 0.0];
            assert!(set.contains(&p.map(f64::to_bits)), "{p:?}");
        }
    }
    set.clear();

    let su2 = std::fs::read_to_string(d.path().join("c.su2")).unwrap();
    assert!(su2.contains("NDIME= 2\nNELEM= 35840\n"));
    assert!(su2.contains("NPOIN= 36272\n"));
    assert!(su2.contains("MARKER_TAG= airfoil\nMARKER_ELEMS= 256\n"));
    assert!(su2.contains("MARKER_TAG= outflow\nMARKER_ELEMS= 160\n"));
    let msh = std::fs::read_to_string(d.path().join("c.msh")).unwrap();
    for n in [
        "2 1 \"block1\"",
        "2 4 \"block4\"",
        "1 5 \"airfoil\"",
        "1 7 \"outflow\"",
    ] {
        assert!(msh.contains(n), "{n}");
    }
    // nodes classified by entity: 3 families, then 4 blocks; the closed airfoil's 256 first
    assert!(msh.contains("$Nodes\n7 36272 1 36272\n1 1 0 256\n"));
    assert!(msh.contains("\n2 4 0 7505\n"), "block4's own nodes");
}

#[test]
fn volume_case_to_openfoam_directly_and_bad_requests_write_nothing() {
    let d = tempfile::tempdir().unwrap();
    let case = root().join("examples/volume_warped_cube.toml");
    let o = ellipgrid(
        d.path(),
        &[
            "run",
            "-q",
            case.to_str().unwrap(),
            "-o",
            "cube/constant/polyMesh",
            "-o",
            "cube.su2",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let (pts, ncells, boundary) = check_polymesh(&d.path().join("cube/constant/polyMesh"));
    assert_eq!(pts.len(), 25 * 25 * 25);
    assert_eq!(ncells, 24 * 24 * 24);
    for f in ["cube_F1", "cube_F6"] {
        assert!(boundary.contains(f), "{boundary}");
    }
    let su2 = std::fs::read_to_string(d.path().join("cube.su2")).unwrap();
    assert!(su2.contains("NDIME= 3\nNELEM= 13824\n"));
    assert!(su2.contains("MARKER_TAG= cube_F3\nMARKER_ELEMS= 576\n"));

    // A .conn whose interface joins sides that do not meet: exit 2, the blocks named, no file.
    let (blocks, mut conn) = two_squares();
    let only: Vec<Block> = blocks.iter().map(|b| b.1.clone()).collect();
    ellipgrid::io::plot3d::write_plot3d(
        &d.path().join("two.x"),
        &only,
        &ellipgrid::io::plot3d::Plot3dFormat {
            multi_block: true,
            two_d: true,
            ..Default::default()
        },
        None,
    )
    .unwrap();
    conn.interfaces[0][1] = (2, [3, 1, 1], [3, 3, 1]);
    conn.patches[3] = ((2, [1, 1, 1], [1, 3, 1]), 3);
    ellipgrid::io::connectivity::write_file(&d.path().join("bad.conn"), &conn).unwrap();
    for out in ["bad/polyMesh", "bad.su2", "bad.msh"] {
        let o = ellipgrid(d.path(), &["convert", "two.x", out, "--conn", "bad.conn"]);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{t}");
        assert!(
            t.contains("blocks 'block1' and 'block2' do not meet"),
            "{t}"
        );
        assert!(!d.path().join(out).exists(), "{out} written");
    }
    // Without a .conn every block side is a patch of its own, named after block and side.
    let o = ellipgrid(d.path(), &["convert", "two.x", "two.msh"]);
    assert!(o.status.success(), "{}", text(&o));
    let msh = std::fs::read_to_string(d.path().join("two.msh")).unwrap();
    assert!(msh.contains("\"block2_E1\""));
}
