//! The two drawing back ends: a tiny-skia pixmap encoded as PNG, and SVG text. Coordinates are
//! pixels with y down. PNG text uses the public-domain 8×8 bitmap font of `font8x8` (scaled by
//! whole pixels), so no font file or system library is needed; SVG text is left to the viewer.

use std::fmt::Write as _;

use tiny_skia::{FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

/// An sRGB colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

/// What the scene needs from a back end.
pub trait Canvas {
    /// Restricts drawing to the rectangle (x0, y0, x1, y1) until [`Canvas::unclip`].
    fn clip(&mut self, r: [f64; 4]);
    /// Ends the clipping.
    fn unclip(&mut self);
    /// A filled polygon with a stroked outline.
    fn polygon(&mut self, pts: &[(f64, f64)], fill: Rgb, stroke: Rgb, width: f64);
    /// An open polyline.
    fn polyline(&mut self, pts: &[(f64, f64)], color: Rgb, width: f64);
    /// A filled axis-aligned rectangle (x0, y0, x1, y1).
    fn rect(&mut self, r: [f64; 4], fill: Rgb);
    /// Text of height `size` with its baseline's left end at (x, y).
    fn text(&mut self, x: f64, y: f64, size: f64, s: &str);
}

/// PNG back end.
pub struct PngCanvas {
    pixmap: Pixmap,
    clip: Option<tiny_skia::Mask>,
}

impl PngCanvas {
    /// A white picture, or `None` if it cannot be allocated.
    pub fn new(w: u32, h: u32) -> Option<PngCanvas> {
        let mut pixmap = Pixmap::new(w, h)?;
        pixmap.fill(tiny_skia::Color::WHITE);
        Some(PngCanvas { pixmap, clip: None })
    }

    /// The encoded PNG.
    pub fn finish(self) -> Result<Vec<u8>, String> {
        self.pixmap.encode_png().map_err(|e| e.to_string())
    }

    fn paint(c: Rgb) -> Paint<'static> {
        let mut p = Paint::default();
        p.set_color_rgba8(c.0, c.1, c.2, 255);
        p.anti_alias = true;
        p
    }

    fn path(pts: &[(f64, f64)], close: bool) -> Option<tiny_skia::Path> {
        let mut b = PathBuilder::new();
        let (first, rest) = pts.split_first()?;
        b.move_to(first.0 as f32, first.1 as f32);
        for p in rest {
            b.line_to(p.0 as f32, p.1 as f32);
        }
        if close {
            b.close();
        }
        b.finish()
    }

    fn stroke(width: f64) -> Stroke {
        Stroke {
            width: width as f32,
            line_cap: LineCap::Round,
            line_join: LineJoin::Round,
            ..Stroke::default()
        }
    }
}

impl Canvas for PngCanvas {
    fn clip(&mut self, r: [f64; 4]) {
        let (w, h) = (self.pixmap.width(), self.pixmap.height());
        let mut mask = tiny_skia::Mask::new(w, h);
        let rect = Rect::from_ltrb(r[0] as f32, r[1] as f32, r[2] as f32, r[3] as f32);
        if let (Some(m), Some(rect)) = (mask.as_mut(), rect) {
            let path = PathBuilder::from_rect(rect);
            m.fill_path(&path, FillRule::Winding, false, Transform::identity());
        }
        self.clip = mask;
    }

    fn unclip(&mut self) {
        self.clip = None;
    }

    fn polygon(&mut self, pts: &[(f64, f64)], fill: Rgb, stroke: Rgb, width: f64) {
        if let Some(path) = Self::path(pts, true) {
            let m = self.clip.as_ref();
            let t = Transform::identity();
            let pf = Self::paint(fill);
            self.pixmap.fill_path(&path, &pf, FillRule::Winding, t, m);
            let ps = Self::paint(stroke);
            self.pixmap
                .stroke_path(&path, &ps, &Self::stroke(width), t, m);
        }
    }

    fn polyline(&mut self, pts: &[(f64, f64)], color: Rgb, width: f64) {
        if let Some(path) = Self::path(pts, false) {
            let p = Self::paint(color);
            let m = self.clip.as_ref();
            self.pixmap
                .stroke_path(&path, &p, &Self::stroke(width), Transform::identity(), m);
        }
    }

    fn rect(&mut self, r: [f64; 4], fill: Rgb) {
        if let Some(rect) = Rect::from_ltrb(r[0] as f32, r[1] as f32, r[2] as f32, r[3] as f32) {
            let p = Self::paint(fill);
            self.pixmap.fill_rect(rect, &p, Transform::identity(), None);
        }
    }

    fn text(&mut self, x: f64, y: f64, size: f64, s: &str) {
        let scale = (size / 8.0).floor().max(1.0) as f32;
        let mut p = Self::paint(Rgb(0, 0, 0));
        p.anti_alias = false;
        let top = y as f32 - 7.0 * scale;
        for (n, ch) in s.chars().enumerate() {
            let glyph = font8x8::legacy::BASIC_LEGACY
                .get(ch as usize)
                .copied()
                .unwrap_or([0; 8]);
            let left = x as f32 + n as f32 * 8.0 * scale;
            for (row, bits) in glyph.iter().enumerate() {
                for col in 0..8 {
                    // Bit 0 is the leftmost pixel of a row.
                    if bits & (1 << col) != 0 {
                        let (px, py) = (left + col as f32 * scale, top + row as f32 * scale);
                        if let Some(r) = Rect::from_xywh(px, py, scale, scale) {
                            self.pixmap.fill_rect(r, &p, Transform::identity(), None);
                        }
                    }
                }
            }
        }
    }
}

/// SVG back end.
pub struct SvgCanvas {
    out: String,
    clips: usize,
    clipped: bool,
}

impl SvgCanvas {
    /// An empty picture of `w × h` user units with a white background.
    pub fn new(w: u32, h: u32) -> SvgCanvas {
        let mut out = String::new();
        out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
        let _ = writeln!(
            out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">"
        );
        let _ = writeln!(out, "<rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>");
        SvgCanvas {
            out,
            clips: 0,
            clipped: false,
        }
    }

    /// The SVG document.
    pub fn finish(mut self) -> String {
        self.unclip();
        self.out.push_str("</svg>\n");
        self.out
    }

    fn points(&mut self, pts: &[(f64, f64)]) {
        for (k, p) in pts.iter().enumerate() {
            let sep = if k == 0 { "" } else { " " };
            let _ = write!(self.out, "{sep}{:.2},{:.2}", p.0, p.1);
        }
    }
}

fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

impl Canvas for SvgCanvas {
    fn clip(&mut self, r: [f64; 4]) {
        self.unclip();
        self.clips += 1;
        let id = self.clips;
        let _ = writeln!(
            self.out,
            "<clipPath id=\"c{id}\"><rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\"/></clipPath>",
            r[0],
            r[1],
            r[2] - r[0],
            r[3] - r[1]
        );
        let _ = writeln!(
            self.out,
            "<g clip-path=\"url(#c{id})\" stroke-linecap=\"round\" stroke-linejoin=\"round\">"
        );
        self.clipped = true;
    }

    fn unclip(&mut self) {
        if self.clipped {
            self.out.push_str("</g>\n");
            self.clipped = false;
        }
    }

    fn polygon(&mut self, pts: &[(f64, f64)], fill: Rgb, stroke: Rgb, width: f64) {
        self.out.push_str("<polygon points=\"");
        self.points(pts);
        let _ = writeln!(
            self.out,
            "\" fill=\"{}\" stroke=\"{}\" stroke-width=\"{width:.2}\"/>",
            hex(fill),
            hex(stroke)
        );
    }

    fn polyline(&mut self, pts: &[(f64, f64)], color: Rgb, width: f64) {
        self.out.push_str("<polyline points=\"");
        self.points(pts);
        let _ = writeln!(
            self.out,
            "\" fill=\"none\" stroke=\"{}\" stroke-width=\"{width:.2}\"/>",
            hex(color)
        );
    }

    fn rect(&mut self, r: [f64; 4], fill: Rgb) {
        let _ = writeln!(
            self.out,
            "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{}\"/>",
            r[0],
            r[1],
            r[2] - r[0],
            r[3] - r[1],
            hex(fill)
        );
    }

    fn text(&mut self, x: f64, y: f64, size: f64, s: &str) {
        let esc = s
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        let _ = writeln!(
            self.out,
            "<text x=\"{x:.2}\" y=\"{y:.2}\" font-family=\"sans-serif\" font-size=\"{size:.1}\">{esc}</text>"
        );
    }
}
