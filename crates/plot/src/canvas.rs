//! A display list in floating-point pixels and its two writers: SVG (coordinates kept to 0.01 px,
//! text as text in the embedded font's family) and PNG (anti-aliased, glyphs rasterised from the
//! embedded font, any scale).
//!
//! Why not plotters: its SVG backend places every point on a whole pixel (curves became
//! staircases, thin slopes bumpy), its bitmap backend draws steep wide lines thinner than flat
//! ones, and its text goes through the system's fontconfig and freetype. Drawing a handful of
//! primitives ourselves keeps sub-pixel geometry in both formats and needs no system library.

use ab_glyph::{Font, ScaleFont, point};
use ab_glyph_rasterizer::Rasterizer;

use crate::text::{self, FONT, Shift, run_metrics, typeset};

/// An RGB colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl Rgb {
    fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }
}

/// Horizontal anchor of a text line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// The position is the text's left end.
    Start,
    /// The position is the text's middle.
    Middle,
    /// The position is the text's right end.
    End,
}

/// One drawing primitive, coordinates in pixels (y down).
#[derive(Clone, Debug)]
pub enum Prim {
    /// A stroked polyline, optionally dashed (`on`, `off` lengths in px).
    Path { pts: Vec<(f64, f64)>, color: Rgb, width: f64, dash: Option<(f64, f64)> },
    /// A filled polygon.
    Fill { pts: Vec<(f64, f64)>, color: Rgb, opacity: f64 },
    /// A filled polygon with an outline.
    Outlined { pts: Vec<(f64, f64)>, fill: Rgb, opacity: f64, stroke: Rgb, width: f64 },
    /// A filled circle.
    Circle { c: (f64, f64), r: f64, color: Rgb },
    /// One line of marked-up text; `at` is on the baseline; `vertical`: rotated a quarter turn
    /// counter-clockwise (reading upwards).
    Text { at: (f64, f64), text: String, size: f64, color: Rgb, anchor: Anchor, vertical: bool },
    /// An RGB image of `nx` x `ny` cells (row 0 at the top) stretched over a rectangle.
    Image { x0: f64, y0: f64, x1: f64, y1: f64, nx: usize, ny: usize, rgb: Vec<u8> },
    /// What follows, up to [`Prim::ClipEnd`], is drawn only inside this rectangle.
    ClipBegin { x0: f64, y0: f64, x1: f64, y1: f64 },
    /// Ends the clipping of [`Prim::ClipBegin`].
    ClipEnd,
}

/// Formats a coordinate to 0.01 px, without trailing zeros.
fn n(v: f64) -> String {
    let r = (v * 100.0).round() / 100.0;
    let r = if r == 0.0 { 0.0 } else { r };
    format!("{r}")
}

fn pts_attr(pts: &[(f64, f64)]) -> String {
    pts.iter().map(|p| format!("{},{}", n(p.0), n(p.1))).collect::<Vec<_>>().join(" ")
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// SVG of the display list on a `w` x `h` px canvas; `physical`: the width and height to declare
/// (e.g. `85mm`), the drawing keeping its px coordinates through the viewBox.
pub fn svg(prims: &[Prim], w: f64, h: f64, physical: Option<(String, String)>) -> String {
    let (sw, sh) = physical.unwrap_or_else(|| (n(w), n(h)));
    let mut s = format!(
        "<svg width=\"{sw}\" height=\"{sh}\" viewBox=\"0 0 {} {}\" xmlns=\"http://www.w3.org/2000/svg\">\n",
        n(w),
        n(h)
    );
    s.push_str(&format!("<rect x=\"0\" y=\"0\" width=\"{}\" height=\"{}\" fill=\"#ffffff\"/>\n", n(w), n(h)));
    let mut clips = 0;
    for p in prims {
        match p {
            Prim::ClipBegin { x0, y0, x1, y1 } => {
                clips += 1;
                s.push_str(&format!(
                    "<clipPath id=\"clip{clips}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>\n<g clip-path=\"url(#clip{clips})\">\n",
                    n(*x0),
                    n(*y0),
                    n(x1 - x0),
                    n(y1 - y0)
                ));
            }
            Prim::ClipEnd => s.push_str("</g>\n"),
            Prim::Path { pts, color, width, dash } => {
                let dash = dash.map_or(String::new(), |(a, b)| format!(" stroke-dasharray=\"{} {}\"", n(a), n(b)));
                s.push_str(&format!(
                    "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"{dash} points=\"{}\"/>\n",
                    color.hex(),
                    n(*width),
                    pts_attr(pts)
                ));
            }
            Prim::Fill { pts, color, opacity } => s.push_str(&format!(
                "<polygon fill=\"{}\" fill-opacity=\"{}\" stroke=\"none\" points=\"{}\"/>\n",
                color.hex(),
                n(*opacity),
                pts_attr(pts)
            )),
            Prim::Outlined { pts, fill, opacity, stroke, width } => s.push_str(&format!(
                "<polygon fill=\"{}\" fill-opacity=\"{}\" stroke=\"{}\" stroke-width=\"{}\" points=\"{}\"/>\n",
                fill.hex(),
                n(*opacity),
                stroke.hex(),
                n(*width),
                pts_attr(pts)
            )),
            Prim::Circle { c, r, color } => s.push_str(&format!(
                "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"{}\" stroke=\"none\"/>\n",
                n(c.0),
                n(c.1),
                n(*r),
                color.hex()
            )),
            Prim::Text { at, text, size, color, anchor, vertical } => {
                let anchor = match anchor {
                    Anchor::Start => "start",
                    Anchor::Middle => "middle",
                    Anchor::End => "end",
                };
                let rot = if *vertical {
                    format!(" transform=\"rotate(-90 {} {})\"", n(at.0), n(at.1))
                } else {
                    String::new()
                };
                s.push_str(&format!(
                    "<text x=\"{}\" y=\"{}\" font-family=\"{}\" font-size=\"{}\" fill=\"{}\" text-anchor=\"{anchor}\"{rot}>",
                    n(at.0),
                    n(at.1),
                    text::FONT_FAMILY,
                    n(*size),
                    color.hex()
                ));
                // Runs as tspans shifted relative to the baseline (and back), so the line flows as
                // one text chunk whatever font a viewer substitutes.
                let mut dy = 0.0;
                for r in typeset(text) {
                    let (rs, off) = run_metrics(r.shift, *size);
                    let shift = off - dy;
                    dy = off;
                    if r.shift == Shift::Normal && shift == 0.0 {
                        s.push_str(&escape(&r.text));
                    } else {
                        s.push_str(&format!(
                            "<tspan dy=\"{}\" font-size=\"{}\">{}</tspan>",
                            n(shift),
                            n(rs),
                            escape(&r.text)
                        ));
                    }
                }
                s.push_str("</text>\n");
            }
            Prim::Image { x0, y0, x1, y1, nx, ny, rgb } => {
                let mut png = Vec::new();
                if crate::png::encode_png(rgb, *nx as u32, *ny as u32, &mut png).is_ok() {
                    s.push_str(&format!(
                        "<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"none\" \
                         style=\"image-rendering:pixelated\" href=\"data:image/png;base64,{}\"/>\n",
                        n(*x0),
                        n(*y0),
                        n(x1 - x0),
                        n(y1 - y0),
                        base64(&png)
                    ));
                }
            }
        }
    }
    s.push_str("</svg>\n");
    s
}

fn base64(bytes: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let v = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(T[(v >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Splits a polyline into its dashes (`on` drawn, `off` skipped, along the arc length).
pub(crate) fn dashes(pts: &[(f64, f64)], on: f64, off: f64) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    if on <= 0.0 || pts.len() < 2 {
        return vec![pts.to_vec()];
    }
    let period = on + off;
    // Distance into the current period: a dash while under `on`, a gap after.
    let mut phase = 0.0;
    let mut cur: Vec<(f64, f64)> = vec![pts[0]];
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let mut t = 0.0;
        while t < len {
            let drawing = phase < on;
            let boundary = if drawing { on } else { period };
            let step = (boundary - phase).min(len - t);
            t += step;
            phase += step;
            let f = if len > 0.0 { t / len } else { 1.0 };
            let p = (a.0 + (b.0 - a.0) * f, a.1 + (b.1 - a.1) * f);
            if drawing {
                cur.push(p);
            }
            if phase >= boundary - 1e-9 {
                if drawing {
                    if cur.len() > 1 {
                        out.push(std::mem::take(&mut cur));
                    }
                    cur.clear();
                } else {
                    phase = 0.0;
                    cur = vec![p];
                }
            }
        }
    }
    if phase < on && cur.len() > 1 {
        out.push(cur);
    }
    out
}

/// An RGB raster.
pub(crate) struct Raster {
    w: usize,
    h: usize,
    rgb: Vec<f32>,
    scale: f64,
    /// Drawing is limited to these device pixels (x0, y0, x1, y1).
    clip: (usize, usize, usize, usize),
}

fn signed_area(p: &[(f64, f64)]) -> f64 {
    let mut a = 0.0;
    for i in 0..p.len() {
        let (x0, y0) = p[i];
        let (x1, y1) = p[(i + 1) % p.len()];
        a += x0 * y1 - x1 * y0;
    }
    a / 2.0
}

fn circle_pts(c: (f64, f64), r: f64, k: usize) -> Vec<(f64, f64)> {
    (0..k)
        .map(|i| {
            let t = i as f64 / k as f64 * std::f64::consts::TAU;
            (c.0 + r * t.cos(), c.1 + r * t.sin())
        })
        .collect()
}

impl Raster {
    /// A white raster of `w` x `h` px drawing a display list at `scale` device px per px.
    pub fn new(w: usize, h: usize, scale: f64) -> Raster {
        Raster { w, h, rgb: vec![1.0; w * h * 3], scale, clip: (0, 0, w, h) }
    }

    /// Fills the union of polygons (device coordinates), each oriented the same way, so
    /// overlaps count once.
    fn fill_union(&mut self, polys: &[Vec<(f64, f64)>], color: Rgb, opacity: f64) {
        let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        for p in polys.iter().flatten() {
            x0 = x0.min(p.0);
            y0 = y0.min(p.1);
            x1 = x1.max(p.0);
            y1 = y1.max(p.1);
        }
        if !(x0.is_finite() && y1.is_finite()) {
            return;
        }
        let (cx0, cy0, cx1, cy1) = self.clip;
        let bx0 = (x0.floor().max(cx0 as f64)) as usize;
        let by0 = (y0.floor().max(cy0 as f64)) as usize;
        let bx1 = (x1.ceil().min(cx1 as f64)).max(0.0) as usize;
        let by1 = (y1.ceil().min(cy1 as f64)).max(0.0) as usize;
        if bx1 <= bx0 || by1 <= by0 {
            return;
        }
        let (rw, rh) = (bx1 - bx0, by1 - by0);
        let mut r = Rasterizer::new(rw, rh);
        for poly in polys {
            let flip = signed_area(poly) < 0.0;
            let m = poly.len();
            for i in 0..m {
                let (a, b) = if flip { (poly[(i + 1) % m], poly[i]) } else { (poly[i], poly[(i + 1) % m]) };
                // Clamped into the box: parts outside the canvas are cut.
                let c = |p: (f64, f64)| {
                    point(
                        (p.0 - bx0 as f64).clamp(0.0, rw as f64) as f32,
                        (p.1 - by0 as f64).clamp(0.0, rh as f64) as f32,
                    )
                };
                r.draw_line(c(a), c(b));
            }
        }
        let col = [color.0 as f32 / 255.0, color.1 as f32 / 255.0, color.2 as f32 / 255.0];
        let op = opacity as f32;
        r.for_each_pixel_2d(|x, y, a| {
            let a = a.min(1.0) * op;
            if a > 0.0 {
                let i = ((by0 + y as usize) * self.w + bx0 + x as usize) * 3;
                for (d, c) in self.rgb[i..i + 3].iter_mut().zip(col) {
                    *d += (c - *d) * a;
                }
            }
        });
    }

    fn stroke(&mut self, pts: &[(f64, f64)], color: Rgb, width: f64) {
        let hw = width / 2.0;
        let mut polys = Vec::new();
        for w in pts.windows(2) {
            let (a, b) = (w[0], w[1]);
            let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
            if len == 0.0 {
                continue;
            }
            let (nx, ny) = (-(b.1 - a.1) / len * hw, (b.0 - a.0) / len * hw);
            polys.push(vec![(a.0 + nx, a.1 + ny), (b.0 + nx, b.1 + ny), (b.0 - nx, b.1 - ny), (a.0 - nx, a.1 - ny)]);
        }
        // Round joins.
        if pts.len() > 2 && hw > 0.6 {
            for &p in &pts[1..pts.len() - 1] {
                polys.push(circle_pts(p, hw, 12));
            }
        }
        self.fill_union(&polys, color, 1.0);
    }

    fn text(&mut self, at: (f64, f64), markup: &str, size: f64, color: Rgb, anchor: Anchor, vertical: bool) {
        let width = text::text_width(markup, size);
        // Room for accents and parentheses above the layout's text box.
        let (up, down) = text::text_extent(markup, size);
        let (up, down) = (up + 0.3 * size, down + 0.15 * size);
        let start = match anchor {
            Anchor::Start => 0.0,
            Anchor::Middle => -width / 2.0,
            Anchor::End => -width,
        };
        // Coverage of the line drawn horizontally, in a buffer with the baseline at `up`.
        let (bw, bh) = ((width.ceil() + 2.0) as usize, (up + down).ceil() as usize + 2);
        let mut cov = vec![0f32; bw * bh];
        let mut x = 1.0;
        for r in typeset(markup) {
            let (rs, dy) = run_metrics(r.shift, size);
            let font = FONT.as_scaled(text::px_scale(rs));
            let mut prev = None;
            for c in r.text.chars() {
                let id = font.glyph_id(c);
                if let Some(p) = prev {
                    x += font.kern(p, id) as f64;
                }
                let glyph = id.with_scale_and_position(text::px_scale(rs), point(x as f32, (up + 1.0 + dy) as f32));
                if let Some(o) = FONT.outline_glyph(glyph) {
                    let b = o.px_bounds();
                    o.draw(|gx, gy, c| {
                        let (px, py) = (b.min.x as i64 + gx as i64, b.min.y as i64 + gy as i64);
                        if px >= 0 && py >= 0 && (px as usize) < bw && (py as usize) < bh {
                            let v = &mut cov[py as usize * bw + px as usize];
                            *v = (*v + c).min(1.0);
                        }
                    });
                }
                x += font.h_advance(id) as f64;
                prev = Some(id);
            }
        }
        // Place the buffer: its point (1 - start, up + 1) goes to `at`.
        let col = [color.0 as f32 / 255.0, color.1 as f32 / 255.0, color.2 as f32 / 255.0];
        let (ax, ay) = (at.0.round() as i64, at.1.round() as i64);
        let (ox, oy) = ((1.0 - start).round() as i64, (up + 1.0).round() as i64);
        for by in 0..bh {
            for bx in 0..bw {
                let a = cov[by * bw + bx];
                if a <= 0.0 {
                    continue;
                }
                let (u, v) = (bx as i64 - ox, by as i64 - oy);
                let (px, py) = if vertical { (ax + v, ay - u) } else { (ax + u, ay + v) };
                if px < 0 || py < 0 || px as usize >= self.w || py as usize >= self.h {
                    continue;
                }
                let i = (py as usize * self.w + px as usize) * 3;
                for (d, c) in self.rgb[i..i + 3].iter_mut().zip(col) {
                    *d += (c - *d) * a;
                }
            }
        }
    }

    /// Draws a display list.
    pub fn draw(&mut self, prims: &[Prim]) {
        let s = self.scale;
        let sc = |pts: &[(f64, f64)]| pts.iter().map(|p| (p.0 * s, p.1 * s)).collect::<Vec<_>>();
        for p in prims {
            match p {
                Prim::ClipBegin { x0, y0, x1, y1 } => {
                    let c = |v: f64, max: usize| ((v * s).round().max(0.0) as usize).min(max);
                    self.clip = (c(*x0, self.w), c(*y0, self.h), c(*x1, self.w), c(*y1, self.h));
                }
                Prim::ClipEnd => self.clip = (0, 0, self.w, self.h),
                Prim::Path { pts, color, width, dash } => {
                    let pts = sc(pts);
                    match dash {
                        Some((on, off)) => {
                            for d in dashes(&pts, on * s, off * s) {
                                self.stroke(&d, *color, width * s);
                            }
                        }
                        None => self.stroke(&pts, *color, width * s),
                    }
                }
                Prim::Fill { pts, color, opacity } => self.fill_union(&[sc(pts)], *color, *opacity),
                Prim::Outlined { pts, fill, opacity, stroke, width } => {
                    let pts = sc(pts);
                    self.fill_union(std::slice::from_ref(&pts), *fill, *opacity);
                    let mut closed = pts.clone();
                    closed.push(pts[0]);
                    self.stroke(&closed, *stroke, width * s);
                }
                Prim::Circle { c, r, color } => {
                    let k = ((r * s * 2.0) as usize).clamp(12, 64);
                    self.fill_union(&[circle_pts((c.0 * s, c.1 * s), r * s, k)], *color, 1.0)
                }
                Prim::Text { at, text, size, color, anchor, vertical } => {
                    self.text((at.0 * s, at.1 * s), text, size * s, *color, *anchor, *vertical)
                }
                Prim::Image { x0, y0, x1, y1, nx, ny, rgb } => {
                    let (dx0, dy0, dx1, dy1) = (x0 * s, y0 * s, x1 * s, y1 * s);
                    let (px0, px1) = (dx0.round().max(0.0) as usize, (dx1.round() as usize).min(self.w));
                    let (py0, py1) = (dy0.round().max(0.0) as usize, (dy1.round() as usize).min(self.h));
                    for py in py0..py1 {
                        let cy = (((py as f64 + 0.5 - dy0) / (dy1 - dy0) * *ny as f64) as usize).min(ny - 1);
                        for px in px0..px1 {
                            let cx = (((px as f64 + 0.5 - dx0) / (dx1 - dx0) * *nx as f64) as usize).min(nx - 1);
                            let (i, j) = ((py * self.w + px) * 3, (cy * nx + cx) * 3);
                            for k in 0..3 {
                                self.rgb[i + k] = rgb[j + k] as f32 / 255.0;
                            }
                        }
                    }
                }
            }
        }
    }

    /// The raster as RGB bytes.
    pub fn into_rgb(self) -> Vec<u8> {
        self.rgb.iter().map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dashes on a vertical line: each dash `on` long, gaps `off`, all on the line.
    #[test]
    fn dashes_are_measured_along_the_path_at_any_slope() {
        let d = dashes(&[(5.0, 0.0), (5.0, 23.0)], 4.0, 2.0);
        assert_eq!(d.len(), 4, "{d:?}");
        for seg in &d {
            assert!(seg.iter().all(|p| p.0 == 5.0));
            let len = seg.last().unwrap().1 - seg[0].1;
            assert!((len - 4.0).abs() < 1e-9 || seg[0].1 == 18.0, "{seg:?}");
        }
        assert_eq!(d[1][0], (5.0, 6.0));
    }

    /// A line drawn at 45 degrees is as thick (ink per unit length) as a horizontal one.
    #[test]
    fn wide_lines_keep_their_width_at_any_slope() {
        let ink = |pts: &[(f64, f64)]| {
            let mut r = Raster::new(100, 100, 1.0);
            r.stroke(pts, Rgb(0, 0, 0), 3.0);
            r.rgb.iter().map(|v| 1.0 - *v as f64).sum::<f64>() / 3.0
        };
        let flat = ink(&[(20.0, 50.0), (80.0, 50.0)]) / 60.0;
        let d = 60.0 / 2f64.sqrt();
        let steep = ink(&[(50.0 - d / 2.0, 50.0 - d / 2.0), (50.0 + d / 2.0, 50.0 + d / 2.0)]) / 60.0;
        assert!((flat - 3.0).abs() < 0.05, "{flat}");
        assert!((steep - 3.0).abs() < 0.05, "{steep}");
    }

    #[test]
    fn svg_keeps_sub_pixel_coordinates() {
        let s = svg(
            &[Prim::Path { pts: vec![(1.234, 5.0), (7.5, 9.876)], color: Rgb(0, 0, 0), width: 1.5, dash: None }],
            10.0,
            10.0,
            None,
        );
        assert!(s.contains("points=\"1.23,5 7.5,9.88\""), "{s}");
        assert_eq!(base64(b"Man"), "TWFu");
        assert_eq!(base64(b"Ma"), "TWE=");
    }
}
