//! Pictures: `ellipgrid plot` on every shipped example (PNG decoded with the `png` crate, SVG
//! header parsed), close-ups, colours, planes, and the bad-input paths.

mod common;
use common::*;
use ellipgrid::io::Block;
use ellipgrid::plot::{write_picture, Marks, Plane, PlotOptions, View};
use ellipgrid::Grid2;
use std::path::Path;

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

/// Decodes a PNG: (width, height, RGBA pixels).
fn decode_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let dec = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut r = dec.read_info().expect("a valid PNG header");
    let mut buf = vec![0; r.output_buffer_size()];
    let info = r.next_frame(&mut buf).expect("valid PNG data");
    assert_eq!(info.color_type, png::ColorType::Rgba);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Width and height from the root element of an SVG file.
fn svg_size(text: &str) -> (u32, u32) {
    assert!(text.starts_with("<?xml"), "XML declaration");
    let root = &text[text.find("<svg ").expect("an <svg> element")..];
    let root = &root[..root.find('>').unwrap()];
    assert!(root.contains("xmlns=\"http://www.w3.org/2000/svg\""));
    let attr = |n: &str| -> u32 {
        let s = &root[root.find(&format!(" {n}=\"")).unwrap() + n.len() + 3..];
        s[..s.find('"').unwrap()].parse().unwrap()
    };
    assert!(text.trim_end().ends_with("</svg>"));
    (attr("width"), attr("height"))
}

/// Counts of drawn (darker than light grey: grid lines) and non-grey (coloured) pixels.
fn pixel_stats(px: &[u8]) -> (usize, usize) {
    let mut dark = 0;
    let mut coloured = 0;
    for p in px.chunks(4) {
        let (r, g, b) = (p[0] as i32, p[1] as i32, p[2] as i32);
        if r + g + b < 600 {
            dark += 1;
        }
        if (r - g).abs() > 40 || (g - b).abs() > 40 {
            coloured += 1;
        }
    }
    (dark, coloured)
}

/// The distinct fill colours of an SVG picture's cell polygons.
fn fill_colours(svg: &str) -> std::collections::BTreeSet<&str> {
    svg.lines()
        .filter(|l| l.starts_with("<polygon"))
        .filter_map(|l| l.split("fill=\"").nth(1)?.get(..7))
        .collect()
}

/// Runs shipped example `name` into `out` in directory `d`.
fn run_example(d: &Path, name: &str, out: &str) {
    let case = root().join("examples").join(name);
    let o = ellipgrid(d, &["run", "-q", case.to_str().unwrap(), "-o", out]);
    assert!(o.status.success(), "{}", text(&o));
}

#[test]
fn every_example_gives_a_png_and_an_svg_of_the_requested_size() {
    let d = tmp();
    let mut n = 0;
    for e in std::fs::read_dir(root().join("examples")).unwrap() {
        let case = e.unwrap().path();
        if case.extension().and_then(|x| x.to_str()) != Some("toml") {
            continue;
        }
        n += 1;
        let name = case.file_stem().unwrap().to_str().unwrap().to_string();
        let c = case.to_str().unwrap();
        let png = format!("{name}.png");
        let o = ellipgrid(
            d.path(),
            &["plot", c, "-o", &png, "--size", "640x480", "-q"],
        );
        assert!(o.status.success(), "{name}: {}", text(&o));
        let (w, h, px) = decode_png(&d.path().join(&png));
        assert_eq!((w, h), (640, 480), "{name}");
        let (dark, coloured) = pixel_stats(&px);
        assert!(dark > 5000, "{name}: only {dark} drawn pixels: no grid?");
        assert_eq!(coloured, 0, "{name}: colours without --color");
        // Corners are background.
        assert_eq!(&px[0..4], &[255, 255, 255, 255]);

        let svg = format!("{name}.svg");
        let o = ellipgrid(
            d.path(),
            &[
                "plot", c, "-o", &svg, "--size", "300x200", "--color", "skewness", "-q",
            ],
        );
        assert!(o.status.success(), "{name}: {}", text(&o));
        let t = std::fs::read_to_string(d.path().join(&svg)).unwrap();
        assert_eq!(svg_size(&t), (300, 200), "{name}");
        assert!(
            t.contains("<polygon") && t.contains(">skewness</text>"),
            "{name}"
        );
    }
    assert!(n >= 3, "the examples were not found");
}

#[test]
fn close_up_colours_and_legend() {
    let d = tmp();
    run_example(d.path(), "boundary_layer.toml", "bl.x");
    let whole = ellipgrid(
        d.path(),
        &["plot", "bl.x", "-o", "whole.png", "--size", "400x300", "-q"],
    );
    assert!(whole.status.success(), "{}", text(&whole));
    let o = ellipgrid(
        d.path(),
        &[
            "plot",
            "bl.x",
            "-o",
            "zoom.png",
            "--size",
            "400x300",
            "--window",
            "1.0,-0.01,1.1,0.05",
            "-q",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    // The close-up x ∈ [1, 1.1], y ∈ [−0.01, 0.05] puts the wall (y ≈ 0) at about 70 % of the
    // height: rows below it are background.
    let (w, h, a) = decode_png(&d.path().join("whole.png"));
    let (_, _, b) = decode_png(&d.path().join("zoom.png"));
    let rows = |px: &[u8], from: f64, to: f64| {
        let r = (from * h as f64) as usize..(to * h as f64) as usize;
        pixel_stats(&px[4 * w as usize * r.start..4 * w as usize * r.end]).0
    };
    assert_eq!(rows(&b, 0.8, 0.95), 0, "close-up: nothing below the wall");
    assert!(
        rows(&a, 0.4, 0.6) > 1000,
        "whole grid: lines across the middle"
    );
    assert_ne!(a, b);
    assert!(rows(&b, 0.1, 0.6) > 1000, "close-up: lines above the wall");
    let o = ellipgrid(
        d.path(),
        &[
            "plot", "bl.x", "-o", "col.png", "--size", "500x300", "--color", "aspect", "-q",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let (w, h, px) = decode_png(&d.path().join("col.png"));
    assert_eq!((w, h), (500, 300));
    let (_, coloured) = pixel_stats(&px);
    assert!(
        coloured > 5000,
        "cells and colour bar are coloured: {coloured}"
    );
    // The colour bar: a column of the legend runs from yellow (top) to purple (bottom).
    let col: Vec<&[u8]> = (0..h as usize)
        .map(|y| &px[4 * (y * w as usize + 383)..][..4])
        .filter(|p| p[..3] != [255, 255, 255] && p[0] as u32 + p[1] as u32 + p[2] as u32 >= 100)
        .collect();
    assert!(col.len() > 100, "colour bar not at x = 383");
    let (top, bottom) = (col[2], col[col.len() - 3]);
    assert!(
        top[1] > 200 && bottom[1] < 50,
        "top {top:?}, bottom {bottom:?}"
    );
}

#[test]
fn volume_planes_views_and_library_entry() {
    let d = tmp();
    let case = root().join("examples/volume_warped_cube.toml");
    let c = case.to_str().unwrap();
    for (args, ok) in [
        (vec!["--plane", "k=0", "--view", "xy"], true),
        (
            vec!["--plane", "j=3", "--view", "xz", "--color", "jacobian"],
            true,
        ),
        (vec!["--view", "yz"], true),
        (vec!["--plane", "k=100000"], false),
        (vec!["--plane", "q=1"], false),
        (vec!["--view", "top"], false),
        (vec!["--size", "10x10"], false),
        (vec!["--size", "big"], false),
        (vec!["--window", "1,1,0,0"], false),
    ] {
        let mut a = vec!["plot", c, "-o", "v.png", "-q"];
        a.extend(&args);
        let _ = std::fs::remove_file(d.path().join("v.png"));
        let o = ellipgrid(d.path(), &a);
        assert_eq!(o.status.success(), ok, "{args:?}: {}", text(&o));
        assert_eq!(d.path().join("v.png").exists(), ok, "{args:?}");
        if !ok {
            assert_eq!(o.status.code(), Some(2), "{args:?}");
        }
    }
    let o = ellipgrid(d.path(), &["plot", c, "-o", "v.jpg"]);
    assert_eq!(o.status.code(), Some(2));

    // The library entry point: a sheared planar grid seen from iso still draws.
    let g = Grid2::<2>::from_fn(9, 5, |i, j| [i as f64 + 0.3 * j as f64, j as f64]);
    let opts = PlotOptions {
        size: (200, 100),
        view: Some(View::Iso),
        ..PlotOptions::default()
    };
    let p = d.path().join("lib.svg");
    write_picture(&p, &[("g".into(), Block::Planar(g.clone()))], &opts).unwrap();
    let t = std::fs::read_to_string(&p).unwrap();
    assert_eq!(svg_size(&t), (200, 100));
    assert_eq!(t.matches("<polygon").count(), 8 * 4, "one polygon per cell");
    let bad = PlotOptions {
        plane: Some(Plane::I(0)),
        ..PlotOptions::default()
    };
    assert!(write_picture(&p, &[("g".into(), Block::Planar(g))], &bad).is_err());
}

#[test]
fn blocks_in_colours_and_the_topology_of_a_multi_block_case() {
    let d = tmp();
    let case = root().join("examples/naca0012_ogrid.toml");
    let c = case.to_str().unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "plot",
            c,
            "-o",
            "t.svg",
            "--blocks",
            "--topology",
            "--size",
            "800x600",
            "-q",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let t = std::fs::read_to_string(d.path().join("t.svg")).unwrap();
    // Every vertex and edge is named (8 vertices, 12 edges), and the legend names the blocks.
    for name in [
        "te",
        "le",
        "up",
        "lo",
        "far_te",
        "far_up",
        "cut_te",
        "cut_lo",
        "upper_fore",
        "far_4",
        "lower_aft",
    ] {
        assert!(t.contains(&format!(">{name}</text>")), "{name} not drawn");
    }
    assert_eq!(t.matches("</text>").count(), 8 + 12 + 4);
    // The cells of the four blocks are filled with four colours.
    let fills = fill_colours(&t);
    assert_eq!(fills.len(), 4, "{fills:?}");
    let o = ellipgrid(
        d.path(),
        &["plot", c, "-o", "t.png", "--blocks", "--topology", "-q"],
    );
    assert!(o.status.success(), "{}", text(&o));

    // The library: vertices where the case puts them, edges from vertex to vertex.
    let loaded = ellipgrid::case::LoadedCase::read(&case).unwrap();
    let g = ellipgrid::job::generate(&loaded, |_| {}).unwrap();
    let m = Marks::topology(g.topology.as_ref().unwrap(), &g.blocks);
    let at = |n: &str| m.points.iter().find(|(v, _)| v == n).unwrap().1;
    for (n, p) in [
        ("te", [1.0, 0.0]),
        ("le", [0.0, 0.0]),
        ("far_up", [0.5, 10.0]),
    ] {
        let q = at(n);
        assert!(
            (q[0] - p[0]).abs() < 1e-9 && (q[1] - p[1]).abs() < 1e-9,
            "{n}: {q:?}"
        );
    }
    let (_, cut) = m.lines.iter().find(|(e, _)| e == "cut_te").unwrap();
    assert_eq!(cut.len(), 49);
    assert_eq!((cut[0], cut[48]), (at("te"), at("far_te")));

    // Bad requests exit 2 and write nothing: --topology of a Plot3D file, --blocks with --color.
    let o = ellipgrid(d.path(), &["run", "-q", c, "-o", "g.x"]);
    assert!(o.status.success(), "{}", text(&o));
    let o = ellipgrid(d.path(), &["plot", "g.x", "-o", "x.png", "--topology"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("g.x") && text(&o).contains("--topology"));
    let o = ellipgrid(
        d.path(),
        &[
            "plot", "g.x", "-o", "x.png", "--blocks", "--color", "aspect",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(!d.path().join("x.png").exists());
    // Block colours of a plain Plot3D file (blocks named by the file).
    let o = ellipgrid(d.path(), &["plot", "g.x", "-o", "b.png", "--blocks", "-q"]);
    assert!(o.status.success(), "{}", text(&o));
}

#[test]
fn selected_blocks_only_are_drawn() {
    let d = tmp();
    run_example(d.path(), "naca0012_ogrid.toml", "g.x");
    let polygons = |args: &[&str]| {
        let mut a = vec!["plot", "g.x", "-o", "s.svg", "-q", "--blocks"];
        a.extend(args);
        let o = ellipgrid(d.path(), &a);
        assert!(o.status.success(), "{args:?}: {}", text(&o));
        let t = std::fs::read_to_string(d.path().join("s.svg")).unwrap();
        let colours = fill_colours(&t).len();
        (t.matches("<polygon").count(), colours, t)
    };
    let (all, colours, _) = polygons(&[]);
    assert_eq!(colours, 4);
    // By number and by name: two of the four equal blocks, two colours, two legend entries.
    let (two, colours, t) = polygons(&["--select", "1, block3"]);
    assert_eq!((2 * two, colours), (all, 2));
    assert!(t.contains(">block1</text>") && t.contains(">block3</text>"));
    assert!(!t.contains(">block2</text>") && !t.contains(">block4</text>"));
    // An unknown block: exit 2 naming it and the blocks there are, no picture.
    let _ = std::fs::remove_file(d.path().join("s.svg"));
    for bad in ["5", "0", "wing"] {
        let o = ellipgrid(d.path(), &["plot", "g.x", "-o", "s.svg", "--select", bad]);
        assert_eq!(o.status.code(), Some(2), "{bad}: {}", text(&o));
        assert!(text(&o).contains(&format!("'{bad}'")) && text(&o).contains("block4"));
        assert!(!d.path().join("s.svg").exists());
    }
}

/// `--slice`: two 5 × 5 × 5 boxes side by side (x in [0, 1] and [1, 2]) cut at z = 0.6 give
/// each box's tensor grid: 2 × 40 segments (i and j surfaces, 4 segments each), 2 × 16 of them on
/// the boxes' faces (drawn heavy); the bad-input paths exit 2 without a picture.
#[test]
fn a_slice_through_two_boxes_draws_their_cut_grids() {
    use ellipgrid::io::plot3d::{write_plot3d, Plot3dFormat};
    use ellipgrid::plot::{cut, Slice};
    use ellipgrid::Grid3;
    let d = tmp();
    let boxes: Vec<Block> = (0..2)
        .map(|b| {
            Block::Volume(Grid3::from_fn(5, 5, 5, |i, j, k| {
                [b as f64 + i as f64 / 4.0, j as f64 / 4.0, k as f64 / 4.0]
            }))
        })
        .collect();
    let path = d.path().join("boxes.x");
    write_plot3d(&path, &boxes, &Plot3dFormat::default(), None).unwrap();
    let o = ellipgrid(
        d.path(),
        &["plot", "boxes.x", "--slice", "z=0.6", "-o", "s.svg", "-q"],
    );
    assert!(o.status.success(), "{}", text(&o));
    let svg = std::fs::read_to_string(d.path().join("s.svg")).unwrap();
    let lines: Vec<&str> = svg.lines().filter(|l| l.starts_with("<polyline")).collect();
    assert_eq!(lines.len(), 80, "one polyline per segment");
    let width = |l: &str| -> f64 {
        let s = &l[l.find("stroke-width=\"").unwrap() + 14..];
        s[..s.find('"').unwrap()].parse().unwrap()
    };
    let thick = width(lines.last().unwrap());
    assert_eq!(lines.iter().filter(|l| width(l) == thick).count(), 32);
    // The library gives the same cut.
    let Block::Volume(g) = &boxes[0] else {
        unreachable!()
    };
    assert_eq!(cut(g, Slice::parse("z=0.6").unwrap()).len(), 40);
    let o = ellipgrid(
        d.path(),
        &[
            "plot", "boxes.x", "--slice", "y=0.5", "--view", "iso", "-o", "iso.png", "-q",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    for args in [
        vec!["--slice", "z=2"],
        vec!["--slice", "w=0.5"],
        vec!["--slice", "z=0.5", "--plane", "k=1"],
        vec!["--slice", "z=0.5", "--color", "skewness"],
    ] {
        let mut a = vec!["plot", "boxes.x", "-o", "bad.png", "-q"];
        a.extend(&args);
        let o = ellipgrid(d.path(), &a);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        assert!(!d.path().join("bad.png").exists(), "{args:?}");
    }
    // A planar grid has nothing to cut.
    let g = Grid2::<2>::from_fn(3, 3, |i, j| [i as f64, j as f64]);
    let opts = PlotOptions {
        slice: Slice::parse("x=0.5"),
        ..PlotOptions::default()
    };
    let p = d.path().join("planar.png");
    assert!(write_picture(&p, &[("g".into(), Block::Planar(g))], &opts).is_err());
    assert!(!p.exists());
}
