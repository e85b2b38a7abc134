use super::*;
use crate::grid::Grid2;

fn edge(name: &str, from: usize, to: usize, n: usize, floating: bool) -> TopoEdge {
    TopoEdge {
        name: name.into(),
        from,
        to,
        n,
        orthogonal: false,
        wall: false,
        floating,
        family: name.into(),
        bc: None,
    }
}

fn sides(names: [&[&str]; 4]) -> [Vec<(String, Option<bool>)>; 4] {
    names.map(|c| c.iter().map(|n| (n.to_string(), None)).collect())
}

/// Two unit squares side by side, vertices 0 1 2 (bottom) and 3 4 5 (top); the middle edge
/// `m` may float.
fn two_squares(floating: bool) -> Topology {
    let v = ["a", "b", "c", "d", "e", "f"].map(String::from).to_vec();
    let e = vec![
        edge("ab", 0, 1, 5, false),
        edge("cb", 2, 1, 5, false), // runs backwards along its side
        edge("de", 3, 4, 5, false),
        edge("ef", 4, 5, 5, false),
        edge("ad", 0, 3, 4, false),
        edge("m", 4, 1, 4, floating), // runs from top to bottom
        edge("cf", 2, 5, 4, false),
    ];
    let blocks = [
        BlockSides {
            name: "left".into(),
            sides: sides([&["ad"], &["m"], &["ab"], &["de"]]),
            orthogonal: [false; 4],
            wall: [false; 4],
        },
        // Transposed: its E3 is the shared edge.
        BlockSides {
            name: "right".into(),
            sides: sides([&["cb"], &["ef"], &["m"], &["cf"]]),
            orthogonal: [false; 4],
            wall: [false; 4],
        },
    ];
    Topology::new(v, e, &blocks, "t").unwrap()
}

#[test]
fn edge_directions_follow_from_the_shared_vertices() {
    let t = two_squares(false);
    let left = &t.blocks[0];
    assert!(!left.sides[2][0].reversed); // ab runs a → b like E3
    assert!(left.sides[1][0].reversed); // m runs e → b, E2 runs b → e
    let right = &t.blocks[1];
    // E3 of `right` is m from b to e (reversed); E1 is cb from b to c (reversed).
    assert!(right.sides[2][0].reversed && right.sides[0][0].reversed);
    assert_eq!(t.dims(0), [5, 4]);
    assert_eq!(t.dims(1), [4, 5]);
    let c = t.connectivity();
    assert_eq!(c.interfaces.len(), 1);
    let f = &c.interfaces[0];
    // m's first node (e) is left (4, 3) and right (3, 0).
    assert_eq!((f.a.start, f.a.end), ([4, 3], [4, 0]));
    assert_eq!((f.b.start, f.b.end), ([3, 0], [0, 0]));
    assert_eq!(c.patches.len(), 6);
}

#[test]
fn a_floating_edge_joins_its_blocks_into_one_row_and_the_cut_restores_each_block() {
    let t = two_squares(true);
    let g = t.groups("t").unwrap();
    assert_eq!(g.len(), 1);
    let row = &g[0];
    assert_eq!(row.name, "left+right");
    // The row is 5 + 5 − 1 nodes along i and 4 along j.
    let ni: usize = 1 + row.sides[2]
        .iter()
        .map(|u| t.edges[u.edge].n - 1)
        .sum::<usize>();
    assert_eq!(ni, 9);
    // A grid of the row labelled by (i, j): cutting it gives each block its own indexing,
    // and the shared edge's nodes agree.
    let grid = Grid2::<2>::from_fn(9, 4, |i, j| [i as f64, j as f64]);
    let left = row.pieces[0].cut(&grid);
    let right = row.pieces[1].cut(&grid);
    assert_eq!([left.ni(), left.nj()], [5, 4]);
    assert_eq!([right.ni(), right.nj()], [4, 5]);
    let f = &t.connectivity().interfaces[0];
    for k in 0..4 {
        assert_eq!(
            left.point(f.a.node(k)[0], f.a.node(k)[1]),
            right.point(f.b.node(k)[0], f.b.node(k)[1])
        );
    }
    // Without floating the blocks are two groups.
    assert_eq!(two_squares(false).groups("t").unwrap().len(), 2);
}

#[test]
fn structural_errors_name_the_block_and_the_edges() {
    let v = ["a", "b", "c", "d"].map(String::from).to_vec();
    let e = vec![
        edge("ab", 0, 1, 5, false),
        edge("cd", 2, 3, 6, false),
        edge("ac", 0, 2, 4, false),
        edge("bd", 1, 3, 4, false),
    ];
    let b = [BlockSides {
        name: "q".into(),
        sides: sides([&["ac"], &["bd"], &["ab"], &["cd"]]),
        orthogonal: [false; 4],
        wall: [false; 4],
    }];
    let m = Topology::new(v.clone(), e.clone(), &b, "t")
        .unwrap_err()
        .to_string();
    assert!(
        m.contains("block 'q'") && m.contains("'ab'") && m.contains("5 and 6"),
        "{m}"
    );
    let mut e2 = e.clone();
    e2[1].n = 5;
    e2.push(edge("spare", 0, 3, 3, false));
    let m = Topology::new(v.clone(), e2, &b, "t")
        .unwrap_err()
        .to_string();
    assert!(m.contains("edge 'spare'") && m.contains("no block"), "{m}");
}

/// An annulus: with `two`, two blocks joined by the floating cuts `c0` and `c1` (a ring;
/// inner vertices 0, 1, outer 2, 3), else one block whose cut `c0` is its E1 and E2.
fn ring(two: bool) -> Topology {
    if !two {
        let v = ["a0", "b0"].map(String::from).to_vec();
        let e = vec![
            edge("in", 0, 0, 9, false),
            edge("out", 1, 1, 9, false),
            edge("c0", 0, 1, 5, true),
        ];
        let b = [BlockSides {
            name: "one".into(),
            sides: sides([&["c0"], &["c0"], &["in"], &["out"]]),
            orthogonal: [false; 4],
            wall: [false; 4],
        }];
        return Topology::new(v, e, &b, "t").unwrap();
    }
    let v = ["a0", "a1", "b0", "b1"].map(String::from).to_vec();
    let e = vec![
        edge("i0", 0, 1, 5, false),
        edge("i1", 1, 0, 5, false),
        edge("o0", 2, 3, 5, false),
        edge("o1", 3, 2, 5, false),
        edge("c0", 0, 2, 4, true),
        edge("c1", 1, 3, 4, true),
    ];
    let b = [
        BlockSides {
            name: "top".into(),
            sides: sides([&["c0"], &["c1"], &["i0"], &["o0"]]),
            orthogonal: [false; 4],
            wall: [false; 4],
        },
        BlockSides {
            name: "bottom".into(),
            sides: sides([&["c1"], &["c0"], &["i1"], &["o1"]]),
            orthogonal: [false; 4],
            wall: [false; 4],
        },
    ];
    Topology::new(v, e, &b, "t").unwrap()
}

#[test]
fn a_floating_cut_and_a_ring_of_floating_edges_make_one_periodic_group() {
    let one = ring(false).groups("t").unwrap();
    assert_eq!(one.len(), 1);
    assert!(one[0].periodic);
    assert_eq!(one[0].pieces.len(), 1);
    assert!(one[0].pieces[0].ops.is_empty());
    assert_eq!(one[0].sides[0], one[0].sides[1]);
    let t = ring(true);
    let g = t.groups("t").unwrap();
    assert_eq!(g.len(), 1);
    let g = &g[0];
    assert!(g.periodic);
    assert_eq!(g.name, "top+bottom");
    // E1 and E2 of the group are the seam c0; the pieces follow each other round the ring.
    assert_eq!(g.sides[0], g.sides[1]);
    assert_eq!(t.edges[g.sides[0][0].edge].name, "c0");
    assert_eq!(
        g.pieces
            .iter()
            .map(|p| (p.block, p.offset))
            .collect::<Vec<_>>(),
        vec![(0, 0), (1, 4)]
    );
    assert_eq!(g.sides[2].len(), 2);
    // Without floating edges the two blocks are two groups, neither periodic.
    let mut fixed = t.clone();
    for e in &mut fixed.edges {
        e.floating = false;
    }
    let g = fixed.groups("t").unwrap();
    assert_eq!(g.len(), 2);
    assert!(g.iter().all(|g| !g.periodic));
}
