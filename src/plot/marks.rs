//! What `ellipgrid plot` draws over a grid on request: every block in its own colour with a
//! legend of block names (`--blocks`), and the topology of a multi-block case
//! (`--topology`): every edge as a coloured line with its name, every vertex as a square with
//! its name.

use super::canvas::{Canvas, Rgb};
use crate::grid::topology::{SideRange, Topology};
use crate::io::Block;

/// Named lines (edges) and points (vertices) in model space, drawn over a grid.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Marks {
    /// Every edge: its name and nodes.
    pub lines: Vec<(String, Vec<[f64; 3]>)>,
    /// Every vertex: its name and position.
    pub points: Vec<(String, [f64; 3])>,
}

impl Marks {
    /// The edges and vertices of `topo`, at the nodes of its gridded `blocks` (in the
    /// topology's block order, as `job::generate` returns them).
    pub fn topology(topo: &Topology, blocks: &[(String, Block)]) -> Marks {
        let conn = topo.connectivity();
        let mut ranges: Vec<Option<SideRange>> = vec![None; topo.edges.len()];
        let found = conn
            .interfaces
            .iter()
            .map(|f| (f.edge, &f.a))
            .chain(conn.patches.iter().map(|p| (p.edge, &p.range)));
        for (e, r) in found {
            ranges[e].get_or_insert(*r);
        }
        let mut marks = Marks::default();
        let mut seen = vec![false; topo.vertices.len()];
        for (e, r) in ranges.iter().enumerate() {
            let Some(r) = r else { continue };
            let Some((_, block)) = blocks.get(r.block) else {
                continue;
            };
            let pts: Vec<[f64; 3]> = (0..r.len())
                .filter_map(|k| node(block, r.node(k)))
                .collect();
            let (Some(&first), Some(&last)) = (pts.first(), pts.last()) else {
                continue;
            };
            let edge = &topo.edges[e];
            for (v, p) in [(edge.from, first), (edge.to, last)] {
                if !seen[v] {
                    seen[v] = true;
                    marks.points.push((topo.vertices[v].clone(), p));
                }
            }
            marks.lines.push((edge.name.clone(), pts));
        }
        marks
    }
}

/// Node (i, j) of a 2D block in R³.
fn node(b: &Block, [i, j]: [usize; 2]) -> Option<[f64; 3]> {
    match b {
        Block::Planar(g) => {
            let p = g.point(i, j);
            Some([p[0], p[1], 0.0])
        }
        Block::Surface(g) => Some(g.point(i, j)),
        _ => None,
    }
}

/// Projected marks: edges as screen-ready polylines, vertices as points (model units of the
/// view).
pub(super) type Projected2 = (Vec<(String, Vec<(f64, f64)>)>, Vec<(String, (f64, f64))>);

/// A light colour per block (Tableau 10, blended halfway to white), cycling.
pub(super) fn block_colour(k: usize) -> Rgb {
    const T10: [(u8, u8, u8); 10] = [
        (31, 119, 180),
        (255, 127, 14),
        (44, 160, 44),
        (214, 39, 40),
        (148, 103, 189),
        (140, 86, 75),
        (227, 119, 194),
        (127, 127, 127),
        (188, 189, 34),
        (23, 190, 207),
    ];
    let (r, g, b) = T10[k % T10.len()];
    let light = |v: u8| ((u16::from(v) + 255) / 2) as u8;
    Rgb(light(r), light(g), light(b))
}

/// Edge lines in this colour.
const EDGE: Rgb = Rgb(200, 30, 30);
/// Vertex squares in this colour.
const VERTEX: Rgb = Rgb(20, 20, 160);

/// Draws projected marks through the screen transform `tf`; `s` is the picture's smaller
/// side (line widths and text sizes follow it).
pub(super) fn draw(
    c: &mut dyn Canvas,
    marks: &Projected2,
    tf: &dyn Fn((f64, f64)) -> (f64, f64),
    s: f64,
) {
    let width = (s / 300.0).max(2.0);
    let size = (s / 70.0).clamp(8.0, 24.0);
    for (_, pts) in &marks.0 {
        let l: Vec<_> = pts.iter().map(|&p| tf(p)).collect();
        c.polyline(&l, EDGE, width);
    }
    for (name, pts) in &marks.0 {
        if let Some(&mid) = pts.get(pts.len() / 2) {
            let (x, y) = tf(mid);
            c.text(x + 0.4 * size, y - 0.4 * size, size, name);
        }
    }
    let r = 1.5 * width;
    for (name, p) in &marks.1 {
        let (x, y) = tf(*p);
        c.rect([x - r, y - r, x + r, y + r], VERTEX);
        c.text(x + r + 2.0, y + size + r, size, name);
    }
}

/// The legend of `--blocks` in `r` = (x0, y0, x1, y1): a swatch and the name of every block.
pub(super) fn block_legend(c: &mut dyn Canvas, names: &[String], r: [f64; 4]) {
    let longest = names.iter().map(|n| n.len()).max().unwrap_or(1).max(1) as f64;
    let rows = names.len().max(1) as f64;
    let size = ((r[3] - r[1]) / (1.5 * rows))
        .min((r[2] - r[0] - 24.0) / longest)
        .clamp(8.0, 20.0);
    for (k, name) in names.iter().enumerate() {
        let y = r[1] + 1.5 * size * (k as f64 + 1.0);
        c.polygon(
            &[
                (r[0] + 4.0, y - size),
                (r[0] + 4.0 + size, y - size),
                (r[0] + 4.0 + size, y),
                (r[0] + 4.0, y),
            ],
            block_colour(k),
            Rgb(0, 0, 0),
            1.0,
        );
        c.text(r[0] + 8.0 + size, y, size, name);
    }
}
