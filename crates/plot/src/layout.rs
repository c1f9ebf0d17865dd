//! The layout of a chart in pixels: rectangles ([`Rect`]), the text boxes of every label
//! ([`TextBox`]), the plot area and legend placement ([`Layout`]), and the default font size from
//! the canvas ([`default_font_px`]).

use crate::canvas::Anchor;
use crate::text::{text_extent, text_width};

/// A rectangle in pixels, y down.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Rect {
    /// Left.
    pub x0: f64,
    /// Top.
    pub y0: f64,
    /// Right.
    pub x1: f64,
    /// Bottom.
    pub y1: f64,
}

impl Rect {
    /// Whether the two rectangles share area (touching edges do not count).
    pub fn overlaps(&self, o: &Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }
    /// Whether `o` lies inside this rectangle, with `tol` px of tolerance.
    pub fn contains_rect(&self, o: &Rect, tol: f64) -> bool {
        o.x0 >= self.x0 - tol && o.x1 <= self.x1 + tol && o.y0 >= self.y0 - tol && o.y1 <= self.y1 + tol
    }
    /// Whether point `p` lies inside.
    pub fn contains(&self, p: (f64, f64)) -> bool {
        p.0 >= self.x0 && p.0 <= self.x1 && p.1 >= self.y0 && p.1 <= self.y1
    }
    /// Width.
    pub fn width(&self) -> f64 {
        self.x1 - self.x0
    }
    /// Height.
    pub fn height(&self) -> f64 {
        self.y1 - self.y0
    }
    pub(crate) fn grow(&self, d: f64) -> Rect {
        Rect { x0: self.x0 - d, y0: self.y0 - d, x1: self.x1 + d, y1: self.y1 + d }
    }
}

/// The smallest fraction of the requested font size a crowded layout may fall back to: at the
/// journal preset's 8 pt, tick labels stay at 6.8 pt or more and the legend and caption (0.9 of
/// it) at 6.1 pt, above the 6 pt that journals state as their smallest lettering (e.g. Elsevier's
/// artwork guidelines: 7 pt, 6 pt for sub- and superscripts; Nature: 5 to 7 pt).
pub const FONT_FLOOR: f64 = 0.85;

/// The font size in px when none is asked for: 8 pt at a size on the page; at a pixel size 15 px
/// (about 11 pt) on an 800 x 560 canvas or larger, scaled down with a smaller canvas (the smaller
/// of width / 800 and height / 560) to no less than 8 pt, so that a 400 x 280 preview (106 mm x
/// 74 mm at 96 px per inch, a journal column's size) has a journal's 8 pt rather than a font
/// meant for twice its size.
pub fn default_font_px(physical: bool, size_px: Option<(u32, u32)>) -> f64 {
    let pt8 = 8.0 * 4.0 / 3.0;
    match (physical, size_px) {
        (true, _) => pt8,
        (false, Some((w, h))) => (15.0 * (w as f64 / 800.0).min(h as f64 / 560.0)).clamp(pt8, 15.0),
        (false, None) => 15.0,
    }
}

/// Where a layout try puts the legend.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Place {
    /// In a free corner of the plot, else below the axes.
    Auto,
    /// Below the axes.
    Below,
    /// Right of the axes, in one column.
    Right,
}

/// A line of text and the box it covers.
#[derive(Clone, Debug, PartialEq)]
pub struct TextBox {
    /// The text (with its markup).
    pub text: String,
    /// Where it is drawn.
    pub rect: Rect,
}

/// Where every element of a drawn chart sits, in pixels of the canvas (SVG user units; a PNG is
/// the same picture scaled by its dpi / 96). For tests and for callers placing annotations.
#[derive(Clone, Debug, Default)]
pub struct Layout {
    /// Canvas width.
    pub width: f64,
    /// Canvas height.
    pub height: f64,
    /// Font size of tick labels, px.
    pub font_px: f64,
    /// The font size the chart asked for, px: `font_px` is smaller only when the layout had to
    /// fall back (never below [`FONT_FLOOR`] times it).
    pub requested_font_px: f64,
    /// The axes' frame.
    pub plot: Rect,
    /// Title lines.
    pub title: Vec<TextBox>,
    /// Caption lines below the figure (the chart's note).
    pub caption: Vec<TextBox>,
    /// x axis label lines.
    pub x_label: Vec<TextBox>,
    /// y axis label lines (drawn upright, reading upwards).
    pub y_label: Vec<TextBox>,
    /// x tick labels.
    pub x_ticks: Vec<TextBox>,
    /// y tick labels.
    pub y_ticks: Vec<TextBox>,
    /// The legend's box (None: no legend).
    pub legend: Option<Rect>,
    /// Whether the legend sits inside the axes (else below them).
    pub legend_inside: bool,
    /// Legend entry texts.
    pub legend_entries: Vec<TextBox>,
    /// Drawn data positions inside the plot: markers and line vertices, and points along lines
    /// and error bars every half font size.
    pub points: Vec<(f64, f64)>,
}

impl Layout {
    /// Every text box.
    pub fn texts(&self) -> impl Iterator<Item = &TextBox> {
        self.title
            .iter()
            .chain(&self.caption)
            .chain(&self.x_label)
            .chain(&self.y_label)
            .chain(&self.x_ticks)
            .chain(&self.y_ticks)
            .chain(&self.legend_entries)
    }

    /// The layout as JSON (every box as `[x0, y0, x1, y1]` in px, y down), with its
    /// [`Layout::problems`]: for tests that check a program's figures from outside.
    pub fn to_json(&self) -> serde_json::Value {
        use serde_json::json;
        let r = |r: &Rect| json!([r.x0, r.y0, r.x1, r.y1]);
        let t = |v: &[TextBox]| -> Vec<serde_json::Value> {
            v.iter().map(|b| json!({"text": b.text, "box": r(&b.rect)})).collect()
        };
        json!({
            "width_px": self.width,
            "height_px": self.height,
            "font_px": self.font_px,
            "requested_font_px": self.requested_font_px,
            "plot": r(&self.plot),
            "title": t(&self.title),
            "caption": t(&self.caption),
            "x_label": t(&self.x_label),
            "y_label": t(&self.y_label),
            "x_ticks": t(&self.x_ticks),
            "y_ticks": t(&self.y_ticks),
            "legend": self.legend.as_ref().map(r),
            "legend_inside": self.legend_inside,
            "legend_entries": t(&self.legend_entries),
            "points": self.points.iter().map(|p| json!([p.0, p.1])).collect::<Vec<_>>(),
            "problems": self.problems(),
        })
    }

    /// What is wrong with the layout, one sentence each (empty: nothing): text outside the canvas,
    /// tick labels touching, the legend over data, text over the plot or over other text.
    pub fn problems(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.font_px < FONT_FLOOR * self.requested_font_px - 1e-9 {
            out.push(format!(
                "font fell back to {:.2} of the requested size (floor {FONT_FLOOR})",
                self.font_px / self.requested_font_px
            ));
        }
        let canvas = Rect { x0: 0.0, y0: 0.0, x1: self.width, y1: self.height };
        for t in self.texts() {
            if !canvas.contains_rect(&t.rect, 0.5) {
                out.push(format!("text {:?} at {:?} leaves the {}x{} canvas", t.text, t.rect, self.width, self.height));
            }
        }
        for ticks in [&self.x_ticks, &self.y_ticks] {
            for (i, a) in ticks.iter().enumerate() {
                for b in &ticks[i + 1..] {
                    if a.rect.overlaps(&b.rect) {
                        out.push(format!("tick labels {:?} and {:?} overlap", a.text, b.text));
                    }
                }
            }
        }
        if let Some(l) = self.legend {
            if let Some(p) = self.points.iter().find(|p| l.contains(**p)) {
                out.push(format!("legend {l:?} covers the data point at {p:?}"));
            }
            if !self.legend_inside && l.overlaps(&self.plot) {
                out.push("legend outside the axes overlaps them".into());
            }
        }
        let outer: Vec<&TextBox> = self
            .title
            .iter()
            .chain(&self.caption)
            .chain(&self.x_label)
            .chain(&self.y_label)
            .chain(&self.x_ticks)
            .chain(&self.y_ticks)
            .collect();
        for (i, a) in outer.iter().enumerate() {
            if let Some(l) = self.legend.filter(|_| !self.legend_inside)
                && a.rect.overlaps(&l)
            {
                out.push(format!("text {:?} lies under the legend", a.text));
            }
            if a.rect.overlaps(&self.plot.grow(-0.5)) {
                out.push(format!("text {:?} lies over the plot", a.text));
            }
            for b in &outer[i + 1..] {
                if a.rect.overlaps(&b.rect) && !std::ptr::eq(*a, *b) {
                    out.push(format!("texts {:?} and {:?} overlap", a.text, b.text));
                }
            }
        }
        out
    }
}

/// The text box of a horizontal line at baseline `at`.
pub(super) fn hbox(text: &str, at: (f64, f64), size: f64, anchor: Anchor) -> Rect {
    let w = text_width(text, size);
    let (up, down) = text_extent(text, size);
    let x0 = match anchor {
        Anchor::Start => at.0,
        Anchor::Middle => at.0 - w / 2.0,
        Anchor::End => at.0 - w,
    };
    Rect { x0, y0: at.1 - up, x1: x0 + w, y1: at.1 + down }
}

/// The box of a line rotated to read upwards, baseline point `at`.
pub(super) fn vbox(text: &str, at: (f64, f64), size: f64, anchor: Anchor) -> Rect {
    let w = text_width(text, size);
    let (up, down) = text_extent(text, size);
    let s = match anchor {
        Anchor::Start => 0.0,
        Anchor::Middle => -w / 2.0,
        Anchor::End => -w,
    };
    Rect { x0: at.0 - up, x1: at.0 + down, y0: at.1 - s - w, y1: at.1 - s }
}
