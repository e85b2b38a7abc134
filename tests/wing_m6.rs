//! The ONERA M6 four-block C–O grid (issue #18, paper §5.3): the shipped case
//! `examples/m6/wing_m6_4block.toml` at reduced size (33 × 33 × 25 nodes per volume instead of
//! 65 × 65 × 49), through the command line.

mod common;
use common::foam::{
    cell_faces, face_pair_aspect_ratio, foam_aspect_ratio, foam_cell_centre, foam_skewness, V3,
};
use common::*;
use ellipgrid::io::plot3d::read_plot3d;
use ellipgrid::io::Block;
use std::fs;

/// The shipped case with every 65-node edge at 33 nodes and every 49-node edge at 25, the
/// nets read from the repository.
fn small_case() -> String {
    let text = fs::read_to_string(root().join("examples/m6/wing_m6_4block.toml")).unwrap();
    let nets = root().join("data/wing_m6_nets.x");
    assert!(text.contains("n = 65\n") && text.contains("n = 49\n"));
    text.replace("n = 65\n", "n = 33\n")
        .replace("n = 49\n", "n = 25\n")
        .replace("../../data/wing_m6_nets.x", &nets.display().to_string())
}

/// All four volumes fold-free (only the cells along the 180° edges have a zero corner, by
/// topology); at the wing the first node within 1 % of the prescribed 1e-5 … 2e-5 local chord
/// (measured 0.999 … 1.001) and the grid lines within 1° of the wall normal (measured 0.08°
/// at most; 7.5° and 0.911 before the interior faces lost their
/// orthogonality goals); the grid lines cross the interior faces with the mean kinks measured
/// (degrees) ahead 29.0, tipplane 46.2 (crossed at right angles by the upper wing volume's
/// lines, `elliptic::crossing`; 56.8 and 59.8 before), te_up 39.1, wakesheet 3.6 (sliding; 18.4 fixed),
/// waketip 66.6 since the wall columns' first-height scaling fades in the node index (ahead
/// 60.6, tipplane 64.3, te_up 46.2 before; `elliptic::wall_profile::SCALE_REACH`); since the
/// spanwise steps at the tip match those beyond the 180° edges (ahead
/// 55.5, tipplane 68.3, te_up 52.0, wakesheet 2.2, waketip 75.4 before; 57.8, 62.6, 69.2
/// across the first three before the wing volumes' wall columns
/// followed the side faces' profiles, `wall_profiles = "faces"`, and the wing faces lost their
/// orthogonality at the trailing edge; 84.6, 92.1, 57.5, 77.1 and 105.3 before the far wake
/// took the wake sheet's streamwise distribution and those faces their orthogonality goals
/// were dropped) and the first-spacing ratio across te_up at most 2.05 (1.95 before the
/// crossing faces, 4.1 with the distance
/// weight of the first-height scaling, 9.5 with the wall correction's former blend, 6.7 then
/// with the spanwise
/// step 1.2e-3 at the tip, 14.8 before the wall columns followed the faces); the lower
/// volumes are the mirror images of the upper ones, bit for bit (the ONERA D section is
/// symmetric: they are mirrored, not solved); the connectivity lists the interfaces. Since
/// the upper wake volume's lines leave `waketip` at right angles (`orthogonal = ["F6"]`) its
/// kink is 26.6 (66.6 before), the lines turning 14.9 at their first node off it.
#[test]
fn four_block_c_o_grid_is_fold_free_and_holds_the_wall_spacing() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("m6.toml"), small_case()).unwrap();
    let o = ellipgrid(
        d.path(),
        &[
            "run", "m6.toml", "-q", "-o", "m6.x", "-o", "m6.conn", "--report", "r.json",
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.path().join("r.json")).unwrap()).unwrap();
    let vols = r["volumes"].as_array().unwrap();
    assert_eq!(vols.len(), 4);
    for v in vols {
        let q = &v["quality"];
        assert_eq!(q["folded_cells"], 0, "{}: {q}", v["name"]);
        assert!(q["flat_edge_cells"].as_u64().unwrap() <= 33, "{q}");
        assert!(
            q["scaled_jacobian_min_regular"].as_f64().unwrap() > 0.0,
            "{q}"
        );
    }
    for v in &vols[..2] {
        // The wall correction's goals blend into the elliptic grid by v ≈ 0.1 of the column
        // (`elliptic::wall::BLEND_POWER`) and the first-height scaling of the side faces'
        // profiles fades in the node index (`elliptic::wall_profile::SCALE_REACH`): largest
        // growth ratios along i and k 2.30 and 5.75 (2.23 before the crossing faces; 3.55 and
        // 5.97 with the scaling's former
        // distance weight, 7.27 and 7.38 with the former blend (1 − v)³, which held the edges'
        // profile far out).
        let q = &v["quality"];
        assert!(q["growth_i_max"].as_f64().unwrap() < 2.5, "{q}");
        assert!(q["growth_k_max"].as_f64().unwrap() < 6.3, "{q}");
        let w = &v["wall"];
        let (lo, hi) = (
            w["ratio_min"].as_f64().unwrap(),
            w["ratio_max"].as_f64().unwrap(),
        );
        assert!(lo >= 0.99 && hi <= 1.01, "{}: {w}", v["name"]);
        assert!(w["angle_mean_deg"].as_f64().unwrap() < 0.05, "{w}");
        assert!(w["angle_max_deg"].as_f64().unwrap() < 1.0, "{w}");
        // the wall's passes (and the crossings they hold) kept their last pass
        let p = &v["picard"]["passes"];
        assert!(p["kept"] == p["run"] && p.get("fell_back").is_none(), "{p}");
    }
    // Mean kink (degrees) of the grid lines crossing each interior face: the measured value
    // with about 10 % margin. The wake sheet is a symmetry face of the upper wake volume,
    // mirrored below: 3.60° (as when it floated; 2.16° floating with the spanwise step
    // 1.2e-3 at the tip, 18.4° fixed); the wake tip 26.6° since the upper wake volume's lines
    // leave it at right angles (`orthogonal = ["F6"]`, faded next to te_up and the sheet:
    // `wall_normal::SIDE_FADE`; 66.6° before, 75.4° with 1.2e-3, 70.7° with the sheet fixed). ahead 29.0°, tipplane 46.2° since the upper wing volume's lines cross
    // them at right angles (`orthogonal = ["F2", "F6"]`, `elliptic::crossing`; 56.8°, 59.8°
    // before), te_up/lo 39.1° (60.6°, 64.3°, 46.2° with the
    // first-height scaling's distance weight; 59.8°, 67.4°, 52.2° with the
    // wall correction's former blend (1 − v)³; 55.5°, 68.3°, 52.0° with
    // 1.2e-3; 57.8°, 62.6°, 69.2° with the wall columns from the edges and the wing faces
    // orthogonal at the trailing edge). Since the wake volume continues the wing volume's
    // lines across te_up (`continue = ["F2"]`, `elliptic::continuation`): te_up/lo 26.6°
    // (39.1° before), waketip 33.6° (26.6°: its goals now hold 6 columns next to te_up,
    // `continuation::CORNER_HOLD`; 19.1° against 15.1° at full size).
    let kinks = r["face_interfaces"].as_array().unwrap();
    for (face, bound) in [
        ("ahead", 32.0),
        ("tipplane", 51.0),
        ("te_up", 30.0),
        ("te_lo", 30.0),
        ("wakesheet", 4.0),
        ("waketip", 37.0),
    ] {
        let f = kinks.iter().find(|f| f["face"] == face).unwrap();
        let mean = f["kink_mean_deg"].as_f64().unwrap();
        assert!(mean < bound, "{face}: mean kink {mean}° (bound {bound}°)");
    }
    // The crossing moves part of the turn to the lines' first node off `ahead` and `tipplane`
    // (`turn_next_mean_deg`): 31.8° and 31.3° (19.7° and 22.8° without it), so the largest mean
    // turn near those faces is 31.8° and 46.2° (56.8° and 59.8° at the faces without it).
    // `waketip`: 14.9° (8.6° without its orthogonality), the largest mean turn near it 26.6°
    // against 66.6°.
    for (face, bound) in [("ahead", 35.0), ("tipplane", 35.0), ("waketip", 16.0)] {
        let f = kinks.iter().find(|f| f["face"] == face).unwrap();
        let turn = f["turn_next_mean_deg"].as_f64().unwrap();
        assert!(
            turn < bound,
            "{face}: next node turns {turn}° (bound {bound}°)"
        );
    }
    // First-spacing ratio across the trailing-edge face: 2.05 at most (1.95 before the
    // crossing faces, 4.07 with the
    // first-height scaling's distance weight, 9.45 with the former blend (1 − v)³, 6.67 then
    // with the spanwise step 1.2e-3 at the tip, 14.8 before the wall columns followed the
    // faces).
    let te = kinks.iter().find(|f| f["face"] == "te_up").unwrap();
    // The wake volume's passes at waketip keep their last pass and the wake's spacings
    // smooth: largest growth ratio along i 2.23 (1.40 without; 10.9 with the goals faded next
    // to every side face over 2 columns, 4.58 with one column held over 4).
    let wake = &vols[2];
    let p = &wake["picard"]["passes"];
    assert!(p["kept"] == p["run"] && p.get("fell_back").is_none(), "{p}");
    // Without a wall they stop once the mean angle at waketip settles (`SETTLED`): 3 passes
    // (6, the limit, before).
    assert!(p["run"].as_u64().unwrap() <= 4, "{p}");
    let g = wake["quality"]["growth_i_max"].as_f64().unwrap();
    assert!(g < 2.5, "wake_up: growth ratio along i {g}");
    let ratio = te["spacing_ratio_max"].as_f64().unwrap();
    assert!(ratio < 2.2, "te_up: first-spacing ratio {ratio}");
    // The lower volumes are mirrored, not solved; their own boundaries (the lower wing and
    // far-field faces, gridded on their nets) are the mirror images of the upper ones' exactly.
    for (v, a) in [(1, "wing_up"), (3, "wake_up")] {
        assert_eq!(vols[v]["mirror_of"], a, "{}", vols[v]);
        assert_eq!(vols[v]["mirror_deviation"], 0.0, "{}", vols[v]);
    }
    let file = read_plot3d(&d.path().join("m6.x")).unwrap();
    let g: Vec<_> = file
        .blocks
        .iter()
        .map(|b| match b {
            Block::Volume(g) => g.clone(),
            _ => panic!("not a volume"),
        })
        .collect();
    assert_eq!(g.len(), 4);
    // wing_lo (i from the leading edge) and wake_lo (i from the trailing edge) mirror
    // wing_up and wake_up in z = 0, with i reversed.
    for (up, lo) in [(0, 1), (2, 3)] {
        let [ni, nj, nk] = g[up].dims();
        assert_eq!(g[lo].dims(), [ni, nj, nk]);
        let mut worst: f64 = 0.0;
        for k in 0..nk {
            for j in 0..nj {
                for i in 0..ni {
                    let (p, q) = (g[up].point(i, j, k), g[lo].point(ni - 1 - i, j, k));
                    worst = worst
                        .max((p[0] - q[0]).abs())
                        .max((p[1] - q[1]).abs())
                        .max((p[2] + q[2]).abs());
                }
            }
        }
        // Bit for bit: the lower volumes are the upper ones mirrored.
        assert_eq!(
            worst, 0.0,
            "volumes {up} and {lo}: mirror differs by {worst}"
        );
    }
    let conn = fs::read_to_string(d.path().join("m6.conn")).unwrap();
    assert!(conn.contains("wall") && conn.contains("farfield"), "{conn}");
}

/// checkMesh's "highly skewed faces" (skewness > 4, issue #18/#19) were the faces in the wing
/// plane between the upper and lower volumes next to the 180° block edges at the tip's leading
/// and trailing edges (tipplane beside ahead, waketip beside the wake sheet): the cells there
/// are wedges whose centres lay far inboard of their faces (spanwise last step 1.2e-3 against
/// the wall spacing beyond the edge). Computed here as checkMesh does over every face in
/// z = 0 shared by an upper volume and its mirror image: at most 2.75 now (small size; 2.97 before
/// the wake volume's orthogonality at `waketip`, 4.28 with it and one column held next to
/// `te_up`, `wall_normal::SIDE_HOLD`; 3.54 at
/// 49 × 49 × 37, 3.01 at 65 × 65 × 49), 7.31 (checkMesh's value, the same face) before the
/// spanwise last steps at the tip matched the steps beyond the flat edges (make_wing_m6.rs).
#[test]
fn four_block_c_o_grid_has_no_highly_skewed_faces_at_the_tip() {
    let d = tempfile::tempdir().unwrap();
    fs::write(d.path().join("m6.toml"), small_case()).unwrap();
    let o = ellipgrid(d.path(), &["run", "m6.toml", "-q", "-o", "m6.x"]);
    assert!(o.status.success(), "{}", text(&o));
    let file = read_plot3d(&d.path().join("m6.x")).unwrap();
    let (mut worst, mut at, mut faces) = (0.0_f64, String::new(), 0);
    // wing_up and wake_up; wing_lo and wake_lo are their mirror images (checked above).
    for (b, name) in [(0, "wing_up"), (2, "wake_up")] {
        let Block::Volume(g) = &file.blocks[b] else {
            panic!("not a volume")
        };
        let [ni, nj, nk] = g.dims();
        let flat = 1e-9 * g.diameter();
        for k in 0..nk - 1 {
            for j in 0..nj - 1 {
                for i in 0..ni - 1 {
                    let side = [
                        i == 0,
                        i == ni - 2,
                        j == 0,
                        j == nj - 2,
                        k == 0,
                        k == nk - 2,
                    ];
                    if !side.iter().any(|&s| s) {
                        continue;
                    }
                    let cf = cell_faces(g, i, j, k);
                    let c = foam_cell_centre(&cf);
                    for (f, face) in cf.iter().enumerate() {
                        if !side[f] || face.iter().any(|p| p[2].abs() > flat) {
                            continue;
                        }
                        faces += 1;
                        let s = foam_skewness(face, c, V3::new(c[0], c[1], -c[2]));
                        if s > worst {
                            worst = s;
                            at = format!("{name} cell ({i}, {j}, {k}) face {f}");
                        }
                    }
                }
            }
        }
    }
    assert!(faces > 2000, "{faces} faces in the wing plane");
    eprintln!("largest checkMesh skewness in the wing plane {worst:.3} at {at}");
    assert!(
        worst < 4.0,
        "checkMesh skewness {worst} at {at} (highly skewed above 4)"
    );
    // checkMesh's "High aspect ratio cells" (issue #19, allowed in .ci/check_meshes.py): only
    // wall cells of the wing volumes, which checkMesh sees with their true ratio (chordwise
    // step over first height) where their faces are normal to the axes (the cap next to the
    // tip edge, the section's maximum thickness); in the wing volumes' own frames the wall
    // cells are thinner still (the face-pair ratio), the wake volumes stay below 1000.
    // Measured: wing_up 72 cells above 1000 (j <= 4), max 4093, face-pair max 27 774 on the
    // wall layer; wake_up max 683 (checkMesh at 33 x 33 x 25: 4093, 144 cells in all).
    let ar = |g: &ellipgrid::Grid3| {
        let [ni, nj, nk] = g.dims();
        let (mut max, mut above, mut max_j, mut pair) = (0.0_f64, 0, 0, 0.0_f64);
        for k in 0..nk - 1 {
            for j in 0..nj - 1 {
                for i in 0..ni - 1 {
                    let cf = cell_faces(g, i, j, k);
                    let a = foam_aspect_ratio(&cf);
                    max = max.max(a);
                    if a > 1000.0 {
                        above += 1;
                        max_j = max_j.max(j);
                    }
                    if j == 0 {
                        pair = pair.max(face_pair_aspect_ratio(&cf));
                    }
                }
            }
        }
        (max, above, max_j, pair)
    };
    let [Block::Volume(wing), _, Block::Volume(wake), ..] = &file.blocks[..] else {
        panic!("not volumes")
    };
    let (w, wa) = (ar(wing), ar(wake));
    eprintln!("aspect ratio: wing_up {w:?}, wake_up {wa:?}");
    assert!(w.0 > 1000.0 && w.2 < 6, "{w:?}");
    assert!(w.3 > 2.0 * w.0, "{w:?}");
    assert!(wa.0 < 1000.0, "{wa:?}");
}
