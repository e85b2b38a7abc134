//! Pictures of grids, like the paper's figures: PNG (rasterised by tiny-skia, anti-aliased, no
//! system libraries) or SVG (written as text).
//!
//! A planar block is drawn in the (x, y) plane; surfaces and volumes are projected
//! ([`View`]: onto xy, xz, yz or isometric), a volume either as its six faces, as one grid
//! plane ([`Plane`]) or as its cut by a coordinate plane ([`Slice`]). Grid lines are thin and
//! dark, block boundaries heavier. With a metric ([`PlotOptions::color`]) the cells are filled
//! on a viridis-like scale over the range of the cells in view, and a colour bar with the range
//! and the metric's name stands at the right.
//! Pictures of surfaces and volumes, and coloured pictures, are drawn cell by cell from back to
//! front (painter's algorithm), so nearer faces hide farther ones. A window
//! ([`PlotOptions::window`]) gives a close-up of part of the projected picture; the scale is the
//! same in both directions and the window is widened to the picture's aspect ratio.
//!
//! The entry point is [`write_picture`]; the format follows the file extension.

mod canvas;
mod marks;
mod slice;
pub use marks::Marks;
pub use slice::{cut, Segment, Slice};

use std::path::Path;

use crate::io::patches::{block_patches, colormap, value_range, CellMetric, Patch};
use crate::io::{write_atomic, Block};
use crate::{Error, Result};
use canvas::{Canvas, PngCanvas, Rgb, SvgCanvas};

/// Direction of projection.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// Looking down −z: x right, y up.
    Xy,
    /// Looking along +y: x right, z up.
    Xz,
    /// Looking along −x: y right, z up.
    Yz,
    /// Isometric from (1, 1, 1): z up.
    Iso,
}

impl View {
    /// Parses "xy", "xz", "yz" or "iso".
    pub fn parse(s: &str) -> Option<View> {
        match s.to_ascii_lowercase().as_str() {
            "xy" => Some(View::Xy),
            "xz" => Some(View::Xz),
            "yz" => Some(View::Yz),
            "iso" => Some(View::Iso),
            _ => None,
        }
    }

    /// Screen coordinates (right, up) and distance from the viewer (larger: farther).
    fn project(self, p: [f64; 3]) -> (f64, f64, f64) {
        let [x, y, z] = p;
        match self {
            View::Xy => (x, y, -z),
            View::Xz => (x, z, y),
            View::Yz => (y, z, -x),
            View::Iso => (
                (y - x) / 2f64.sqrt(),
                (2.0 * z - x - y) / 6f64.sqrt(),
                -(x + y + z) / 3f64.sqrt(),
            ),
        }
    }
}

/// A grid plane of volume blocks, by 0-based index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plane {
    I(usize),
    J(usize),
    K(usize),
}

impl Plane {
    /// Parses "i=3", "j=0", "k=10".
    pub fn parse(s: &str) -> Option<Plane> {
        let (a, n) = s.split_once('=')?;
        let n: usize = n.trim().parse().ok()?;
        match a.trim().to_ascii_lowercase().as_str() {
            "i" => Some(Plane::I(n)),
            "j" => Some(Plane::J(n)),
            "k" => Some(Plane::K(n)),
            _ => None,
        }
    }
}

/// What to draw and how.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlotOptions {
    /// Picture size in pixels (PNG) or user units (SVG); default 1200 × 900.
    pub size: (u32, u32),
    /// Close-up window (x0, y0, x1, y1) in projected coordinates (model x, y for the xy view).
    pub window: Option<[f64; 4]>,
    /// Fill cells by this metric, with a colour bar.
    pub color: Option<CellMetric>,
    /// Projection; default xy if every block is planar, else iso.
    pub view: Option<View>,
    /// Draw this grid plane of volume blocks instead of their faces.
    pub plane: Option<Plane>,
    /// Draw the cut of the volume blocks by this coordinate plane instead of their faces.
    pub slice: Option<Slice>,
    /// Fill every block with its own colour, with a legend of block names.
    pub blocks: bool,
}

impl Default for PlotOptions {
    fn default() -> Self {
        PlotOptions {
            size: (1200, 900),
            window: None,
            color: None,
            view: None,
            plane: None,
            slice: None,
            blocks: false,
        }
    }
}

/// Largest picture side accepted (pixels).
pub const MAX_SIDE: u32 = 16384;

/// Draws `blocks` into `path` (`.png` or `.svg`), atomically.
pub fn write_picture(path: &Path, blocks: &[(String, Block)], opts: &PlotOptions) -> Result<()> {
    write_picture_marked(path, blocks, opts, &Marks::default())
}

/// [`write_picture`] with `marks` (a multi-block topology, [`Marks::topology`]) drawn over the
/// grid.
pub fn write_picture_marked(
    path: &Path,
    blocks: &[(String, Block)],
    opts: &PlotOptions,
    marks: &Marks,
) -> Result<()> {
    let bad = |msg: String| Error::input(path.display().to_string(), msg);
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default();
    let (w, h) = opts.size;
    if !(16..=MAX_SIDE).contains(&w) || !(16..=MAX_SIDE).contains(&h) {
        return Err(bad(format!(
            "picture size {w}x{h}: each side must be 16 to {MAX_SIDE}"
        )));
    }
    if opts.blocks && opts.color.is_some() {
        return Err(bad(
            "block colours and a quality metric's colours cannot be drawn together".into(),
        ));
    }
    if opts.slice.is_some() && (opts.plane.is_some() || opts.color.is_some() || opts.blocks) {
        return Err(bad(
            "a slice is drawn as grid lines: not with a grid plane, a metric or block colours"
                .into(),
        ));
    }
    let scene = Scene::new(blocks, opts, marks).map_err(bad)?;
    match ext.as_str() {
        "png" => {
            let mut c =
                PngCanvas::new(w, h).ok_or_else(|| bad("cannot allocate picture".into()))?;
            scene.draw(&mut c, opts);
            let bytes = c.finish().map_err(|e| bad(format!("PNG encoding: {e}")))?;
            write_atomic(path, |f| f.write_all(&bytes))
        }
        "svg" => {
            let mut c = SvgCanvas::new(w, h);
            scene.draw(&mut c, opts);
            let text = c.finish();
            write_atomic(path, |f| f.write_all(text.as_bytes()))
        }
        _ => Err(bad("unknown picture extension: use .png or .svg".into())),
    }
}

/// One quad to draw: projected corners, distance, value, which edges are block boundaries.
struct Cell {
    pts: [(f64, f64); 4],
    depth: f64,
    value: f64,
    boundary: [bool; 4],
    block: usize,
}

/// A patch's size (ni, nj) and projected nodes.
type Projected = (usize, usize, Vec<(f64, f64)>);

/// A projected segment of a slice: its ends, true on a block face.
type Segment2 = ((f64, f64), (f64, f64), bool);

/// Projected patches and their cells.
struct Scene {
    /// Projected nodes of each patch with its size (ni, nj).
    patches: Vec<Projected>,
    /// Projected segments of a slice ([`Slice`]), true on a block face.
    segments: Vec<Segment2>,
    cells: Vec<Cell>,
    /// Fill cells and sort them (else: grid lines only).
    painter: bool,
    bbox: [f64; 4],
    /// Block names (for the legend of block colours).
    names: Vec<String>,
    marks: marks::Projected2,
}

impl Scene {
    fn new(
        blocks: &[(String, Block)],
        opts: &PlotOptions,
        marks: &Marks,
    ) -> std::result::Result<Scene, String> {
        if blocks.is_empty() {
            return Err("no blocks to draw".into());
        }
        let all_planar = blocks.iter().all(|(_, b)| matches!(b, Block::Planar(_)));
        let default = match opts.slice {
            Some(s) => s.view(),
            None if all_planar => View::Xy,
            None => View::Iso,
        };
        let view = opts.view.unwrap_or(default);
        if opts.slice.is_some() && !blocks.iter().any(|(_, b)| matches!(b, Block::Volume(_))) {
            return Err("--slice needs a volume block (this grid has none)".into());
        }
        let flat = |q: &[f64; 3]| {
            let (x, y, _) = view.project(*q);
            (x, y)
        };
        let mut segments = Vec::new();
        if let Some(s) = opts.slice {
            for (name, b) in blocks {
                if let Block::Volume(g) = b {
                    if !g.coords().iter().flatten().all(|c| c.is_finite()) {
                        return Err(format!("block '{name}': non-finite coordinates"));
                    }
                    segments.extend(cut(g, s).iter().map(|(p, q, f)| (flat(p), flat(q), *f)));
                }
            }
            if segments.is_empty() {
                return Err(format!("the plane {} does not cut the grid", s.label()));
            }
        }
        if opts.plane.is_some() && !blocks.iter().any(|(_, b)| matches!(b, Block::Volume(_))) {
            return Err("--plane needs a volume block (this grid has none)".into());
        }
        let mut patches = Vec::new();
        let mut owner = Vec::new();
        for (k, (name, b)) in blocks.iter().enumerate() {
            if opts.slice.is_some() {
                break;
            }
            let ps = match (b, opts.plane) {
                (Block::Volume(g), Some(pl)) => {
                    let [ni, nj, nk] = g.dims();
                    let (n, max) = match pl {
                        Plane::I(n) => (n, ni),
                        Plane::J(n) => (n, nj),
                        Plane::K(n) => (n, nk),
                    };
                    if n >= max {
                        return Err(format!(
                            "block '{name}': plane {pl:?} outside 0..{} ({ni}×{nj}×{nk} nodes)",
                            max - 1
                        ));
                    }
                    vec![match pl {
                        Plane::I(i) => Patch::from_fn(nj, nk, |j, k| g.point(i, j, k)),
                        Plane::J(j) => Patch::from_fn(ni, nk, |i, k| g.point(i, j, k)),
                        Plane::K(k) => Patch::from_fn(ni, nj, |i, j| g.point(i, j, k)),
                    }]
                }
                _ => block_patches(b),
            };
            if !ps.iter().all(Patch::all_finite) {
                return Err(format!("block '{name}': non-finite coordinates"));
            }
            owner.extend(std::iter::repeat_n(k, ps.len()));
            patches.extend(ps);
        }
        let painter = opts.color.is_some() || opts.blocks || !(all_planar && view == View::Xy);
        let mut cells = Vec::new();
        let mut projected: Vec<Projected> = Vec::new();
        for (p, &block) in patches.iter().zip(&owner) {
            let proj: Vec<(f64, f64, f64)> = p.points.iter().map(|&q| view.project(q)).collect();
            if painter {
                let values = match opts.color {
                    Some(m) => p.cell_values(m),
                    None => vec![],
                };
                let (ci, cj) = (p.ni - 1, p.nj - 1);
                for (c, q) in p.quads().enumerate() {
                    let (i, j) = (c % ci.max(1), c / ci.max(1));
                    let pts = q.map(|k| (proj[k].0, proj[k].1));
                    let depth = q.iter().map(|&k| proj[k].2).sum::<f64>() / 4.0;
                    cells.push(Cell {
                        pts,
                        depth,
                        value: values.get(c).copied().unwrap_or(f64::NAN),
                        boundary: [j == 0, i + 1 == ci, j + 1 == cj, i == 0],
                        block,
                    });
                }
            }
            projected.push((p.ni, p.nj, proj.iter().map(|q| (q.0, q.1)).collect()));
        }
        // Far cells first; the sort is stable so that equal depths keep the grid order.
        cells.sort_by(|a, b| b.depth.total_cmp(&a.depth));
        let mut bbox = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        let ends = segments.iter().flat_map(|(p, q, _)| [*p, *q]);
        for (x, y) in projected
            .iter()
            .flat_map(|p| p.2.iter().copied())
            .chain(ends)
        {
            bbox = [
                bbox[0].min(x),
                bbox[1].min(y),
                bbox[2].max(x),
                bbox[3].max(y),
            ];
        }
        if !bbox.iter().all(|v| v.is_finite()) {
            return Err("the grid has no nodes".into());
        }
        let marks = (
            marks
                .lines
                .iter()
                .map(|(n, l)| (n.clone(), l.iter().map(flat).collect()))
                .collect(),
            marks
                .points
                .iter()
                .map(|(n, p)| (n.clone(), flat(p)))
                .collect(),
        );
        Ok(Scene {
            patches: projected,
            segments,
            cells,
            painter,
            bbox,
            names: blocks.iter().map(|(n, _)| n.clone()).collect(),
            marks,
        })
    }

    fn draw(&self, c: &mut dyn Canvas, opts: &PlotOptions) {
        let (w, h) = (opts.size.0 as f64, opts.size.1 as f64);
        let s = w.min(h);
        let margin = (0.04 * s).max(8.0);
        let legend_w = if opts.color.is_some() || opts.blocks {
            (0.2 * w).max(130.0)
        } else {
            0.0
        };
        let area = [margin, margin, w - margin - legend_w, h - margin];
        let win = match opts.window {
            Some(win) => win,
            None => {
                let b = self.bbox;
                let pad = 0.01 * (b[2] - b[0]).max(b[3] - b[1]).max(1e-300);
                [b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad]
            }
        };
        let (ww, wh) = ((win[2] - win[0]).max(1e-300), (win[3] - win[1]).max(1e-300));
        let (aw, ah) = (area[2] - area[0], area[3] - area[1]);
        let scale = (aw / ww).min(ah / wh);
        let (cx, cy) = (0.5 * (win[0] + win[2]), 0.5 * (win[1] + win[3]));
        let (ax, ay) = (0.5 * (area[0] + area[2]), 0.5 * (area[1] + area[3]));
        let tf = |(x, y): (f64, f64)| (ax + (x - cx) * scale, ay - (y - cy) * scale);
        // What is visible of the model, for culling cells of a close-up.
        let vis = [
            cx - (ax - area[0]) / scale,
            cy - (area[3] - ay) / scale,
            cx + (area[2] - ax) / scale,
            cy + (ay - area[1]) / scale,
        ];
        let thin = (s / 1400.0).max(0.5);
        let thick = (s / 450.0).max(1.5);
        let line = Rgb(40, 40, 40);
        let bound = Rgb(0, 0, 0);

        let visible = |cell: &&Cell| {
            let xs = cell.pts.map(|p| p.0);
            let ys = cell.pts.map(|p| p.1);
            let fold = |v: [f64; 4], f: fn(f64, f64) -> f64| v.into_iter().reduce(f).unwrap();
            !(fold(xs, f64::max) < vis[0]
                || fold(xs, f64::min) > vis[2]
                || fold(ys, f64::max) < vis[1]
                || fold(ys, f64::min) > vis[3])
        };
        let cells: Vec<&Cell> = self.cells.iter().filter(visible).collect();
        // The colour scale spans the cells in view (a close-up gets its own range).
        let (lo, hi) = value_range(cells.iter().map(|c| &c.value));

        c.clip(area);
        if self.painter {
            for cell in cells {
                let fill = match opts.color {
                    Some(_) => rgb(colormap((cell.value - lo) / (hi - lo))),
                    None if opts.blocks => marks::block_colour(cell.block),
                    None => Rgb(255, 255, 255),
                };
                let pts = cell.pts.map(tf);
                c.polygon(&pts, fill, line, thin);
                for e in 0..4 {
                    if cell.boundary[e] {
                        c.polyline(&[pts[e], pts[(e + 1) % 4]], bound, thick);
                    }
                }
            }
        } else {
            for (ni, nj, pts) in &self.patches {
                let (ni, nj) = (*ni, *nj);
                for j in 0..nj {
                    let l: Vec<_> = (0..ni).map(|i| tf(pts[i + ni * j])).collect();
                    c.polyline(&l, line, thin);
                }
                for i in 0..ni {
                    let l: Vec<_> = (0..nj).map(|j| tf(pts[i + ni * j])).collect();
                    c.polyline(&l, line, thin);
                }
                // The boundary loop E3, E2, E4 reversed, E1 reversed.
                let mut b: Vec<_> = (0..ni).map(|i| pts[i]).collect();
                b.extend((1..nj).map(|j| pts[ni - 1 + ni * j]));
                b.extend(
                    (0..ni.saturating_sub(1))
                        .rev()
                        .map(|i| pts[i + ni * (nj - 1)]),
                );
                b.extend((0..nj.saturating_sub(1)).rev().map(|j| pts[ni * j]));
                let b: Vec<_> = b.into_iter().map(tf).collect();
                c.polyline(&b, bound, thick);
            }
        }
        for heavy in [false, true] {
            for (p, q, _) in self.segments.iter().filter(|g| g.2 == heavy) {
                let (colour, width) = if heavy { (bound, thick) } else { (line, thin) };
                c.polyline(&[tf(*p), tf(*q)], colour, width);
            }
        }
        marks::draw(c, &self.marks, &tf, s);
        c.unclip();
        if opts.blocks {
            let r = [w - legend_w, margin, w - margin, h - margin];
            marks::block_legend(c, &self.names, r);
        }
        if let Some(m) = opts.color {
            self.legend(
                c,
                m,
                (lo, hi),
                [w - legend_w, margin, w - margin, h - margin],
            );
        }
    }

    /// Colour bar with the range and the metric's name in `r` = (x0, y0, x1, y1).
    fn legend(&self, c: &mut dyn Canvas, m: CellMetric, (lo, hi): (f64, f64), r: [f64; 4]) {
        let text = (0.018 * (r[3] - r[1]) / 0.9).clamp(8.0, 32.0);
        let bar_x = r[0] + 4.0;
        let bar_w = (0.15 * (r[2] - r[0])).clamp(10.0, 30.0);
        // Glyphs are at most `size` wide (PNG: 8 px × whole scale ≤ size): fit the labels.
        let labels = [lo, 0.5 * (lo + hi), hi].map(number);
        let longest = labels.iter().map(|l| l.len()).max().unwrap_or(1) as f64;
        let lsize = text.min((r[2] - bar_x - bar_w - 6.0) / longest).max(8.0);
        let (y0, y1) = (r[1] + 2.5 * text, r[3] - text);
        const N: usize = 64;
        let dy = (y1 - y0) / N as f64;
        for k in 0..N {
            let t = (k as f64 + 0.5) / N as f64;
            let y = y1 - (k + 1) as f64 * dy;
            c.rect([bar_x, y, bar_x + bar_w, y + dy + 0.5], rgb(colormap(t)));
        }
        let frame = [
            (bar_x, y0),
            (bar_x + bar_w, y0),
            (bar_x + bar_w, y1),
            (bar_x, y1),
            (bar_x, y0),
        ];
        c.polyline(&frame, Rgb(0, 0, 0), 1.0);
        // The title may be wider than the legend: shrink it to fit (8 units per glyph in PNG).
        let title = m.label();
        let tsize = text.min((r[2] - r[0]) / title.len() as f64).max(8.0);
        c.text(r[0], r[1] + tsize, tsize, title);
        for (t, label) in [0.0, 0.5, 1.0].into_iter().zip(&labels) {
            let y = y1 - t * (y1 - y0);
            c.polyline(
                &[(bar_x + bar_w, y), (bar_x + bar_w + 4.0, y)],
                Rgb(0, 0, 0),
                1.0,
            );
            c.text(bar_x + bar_w + 6.0, y + 0.35 * lsize, lsize, label);
        }
    }
}

fn rgb(c: [f64; 3]) -> Rgb {
    let b = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    Rgb(b(c[0]), b(c[1]), b(c[2]))
}

/// A legend number: 4 significant digits, scientific outside [1e-3, 1e5).
fn number(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        format!("{v:.3e}")
    } else {
        let decimals = if a == 0.0 {
            0
        } else {
            (3 - a.log10().floor() as i32).max(0) as usize
        };
        let s = format!("{v:.decimals$}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s == "-0" {
            "0".into()
        } else {
            s.into()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Grid2;

    #[test]
    fn iso_projection_axes() {
        // Looking from (1, 1, 1): z is up on screen, that point is nearest.
        let (_, up, _) = View::Iso.project([0.0, 0.0, 1.0]);
        assert!(up > 0.0);
        let (_, _, near) = View::Iso.project([1.0, 1.0, 1.0]);
        let (_, _, far) = View::Iso.project([-1.0, -1.0, -1.0]);
        assert!(near < far);
        assert_eq!(View::Xz.project([1.0, 2.0, 3.0]), (1.0, 3.0, 2.0));
    }

    #[test]
    fn parse_options() {
        assert_eq!(Plane::parse("k=3"), Some(Plane::K(3)));
        assert_eq!(Plane::parse("x=3"), None);
        assert_eq!(View::parse("ISO"), Some(View::Iso));
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(1.0), "1");
        assert_eq!(number(2.5e-6), "2.500e-6");
    }

    #[test]
    fn plane_on_planar_grid_is_an_error() {
        let g = Grid2::<2>::from_fn(3, 3, |i, j| [i as f64, j as f64]);
        let opts = PlotOptions {
            plane: Some(Plane::K(0)),
            ..PlotOptions::default()
        };
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("a.png");
        let e = write_picture(&p, &[("b".into(), Block::Planar(g))], &opts).unwrap_err();
        assert!(e.to_string().contains("a.png") && e.to_string().contains("volume"));
        assert!(!p.exists());
    }
}
