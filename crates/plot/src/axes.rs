//! Axes of a chart or map: an axis's mapping and ticks ([`Axis`]), the frame of the plot area with
//! its tick labels and axis labels ([`frame`], [`draw_axes`]), the title and the caption.

use crate::canvas::{Anchor, Prim, Rgb};
use crate::layout::{Rect, TextBox, hbox, vbox};
use crate::scales::{Scale, tick_label, ticks};
use crate::text::{text_extent, text_width, wrap};

pub(super) const INK: Rgb = Rgb(0x22, 0x22, 0x22);
pub(super) const GREY: Rgb = Rgb(0x44, 0x44, 0x44);

/// An axis: how data map to it, its range in axis coordinates and its ticks.
pub(crate) struct Axis {
    pub scale: Scale,
    pub lo: f64,
    pub hi: f64,
    pub named: Option<Vec<(f64, String)>>,
    /// The smallest size named tick labels may take, px ([`FONT_FLOOR`] times the requested font).
    pub min_font: f64,
}

/// Tick positions (axis coordinates) with their labels, the light ones, and whether the labels are
/// set upright (vertical) and their size.
pub(crate) struct Ticks {
    pub bold: Vec<(f64, String)>,
    pub light: Vec<f64>,
    pub vertical: bool,
    pub size: f64,
}

impl Axis {
    /// Ticks of an upright axis of `length` px (a colour bar).
    pub(crate) fn ticks_public(&self, length: f64, f: f64) -> Ticks {
        self.ticks(length, f, false)
    }

    /// Ticks whose labels do not touch over `length` px along the axis.
    fn ticks(&self, length: f64, f: f64, horizontal: bool) -> Ticks {
        if let Some(named) = &self.named {
            let bold: Vec<(f64, String)> = named.iter().map(|(v, l)| (self.scale.to_axis(*v), l.clone())).collect();
            let spacing = length / (bold.len().max(1) as f64) * {
                // Named ticks are usually evenly spaced: the smallest gap between them.
                let mut pos: Vec<f64> = bold.iter().map(|b| b.0).collect();
                pos.sort_by(f64::total_cmp);
                let min_gap = pos.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
                if min_gap.is_finite() && self.hi > self.lo {
                    min_gap / (self.hi - self.lo) * bold.len() as f64
                } else {
                    1.0
                }
            };
            let names = bold.clone();
            let widest = |s: f64| names.iter().map(|b| text_width(&b.1, s)).fold(0.0, f64::max);
            if !horizontal {
                return Ticks { bold, light: Vec::new(), vertical: false, size: f };
            }
            // Named labels across at the font size, else across at the floor size, else upright
            // at the floor size (never below FONT_FLOOR of the requested font).
            let small = self.min_font.min(f);
            for s in [f, small] {
                if widest(s) + 0.4 * f <= spacing {
                    return Ticks { bold, light: Vec::new(), vertical: false, size: s };
                }
            }
            // Upright, a label of several words on two lines (split at the space nearest its
            // middle) when the spacing holds two lines: half the height below the axis.
            let two_lines = spacing >= 2.5 * small;
            let bold = bold
                .into_iter()
                .map(|(v, l)| {
                    let split = two_lines
                        .then(|| {
                            let mid = l.chars().count() / 2;
                            l.char_indices()
                                .filter(|(_, c)| *c == ' ')
                                .min_by_key(|(i, _)| l[..*i].chars().count().abs_diff(mid))
                                .map(|(i, _)| format!("{}\n{}", &l[..i], &l[i + 1..]))
                        })
                        .flatten();
                    (v, split.unwrap_or(l))
                })
                .collect();
            return Ticks { bold, light: Vec::new(), vertical: true, size: small };
        }
        let mut n = if horizontal { 10.0 } else { (length / (1.9 * f)).clamp(2.0, 10.0) };
        loop {
            let (bold, light) = ticks(self.scale, self.lo, self.hi, n);
            let labelled: Vec<(f64, String)> = bold
                .into_iter()
                .map(|v| (v, tick_label(v, self.scale, self.lo, self.hi)))
                .filter(|(_, l)| !l.is_empty())
                .collect();
            let px = |v: f64| (v - self.lo) / (self.hi - self.lo) * length;
            let fits = labelled.windows(2).all(|w| {
                let gap = (px(w[1].0) - px(w[0].0)).abs();
                if horizontal {
                    gap >= (text_width(&w[0].1, f) + text_width(&w[1].1, f)) / 2.0 + 0.6 * f
                } else {
                    gap >= 1.35 * f
                }
            });
            if fits && labelled.len() < 2 && self.scale == Scale::Linear && self.hi > self.lo && length >= 1.5 * f {
                // A short axis (a colour bar) with at most one nice tick: label both ends, to
                // three significant digits.
                let digits = (2.0 - (self.hi.abs().max(self.lo.abs())).log10().floor()).clamp(0.0, 12.0) as usize;
                let label = |v: f64| {
                    let t = format!("{v:.digits$}");
                    let t = if t.contains('.') { t.trim_end_matches('0').trim_end_matches('.').to_string() } else { t };
                    t.replace('-', "−")
                };
                return Ticks {
                    bold: vec![(self.lo, label(self.lo)), (self.hi, label(self.hi))],
                    light,
                    vertical: false,
                    size: f,
                };
            }
            if fits || n <= 1.0 {
                return Ticks { bold: labelled, light, vertical: false, size: f };
            }
            n = (n * 0.7).floor().max(1.0);
        }
    }
}

/// The frame of a plot: where the axes sit and what the margins hold.
pub(crate) struct Frame {
    pub plot: Rect,
    pub xt: Ticks,
    pub yt: Ticks,
    pub x_lines: Vec<String>,
    pub y_lines: Vec<String>,
    /// Bottom of the x axis' texts.
    pub below_axis: f64,
}

/// Geometry of the axes inside `area` (the canvas minus title, caption and what the caller
/// reserves), with font `f`; `aspect`: data units per px equal on both axes (maps).
pub(crate) fn frame(
    area: Rect,
    f: f64,
    x: &Axis,
    y: &Axis,
    x_label: &str,
    y_label: &str,
    aspect: Option<(f64, f64)>,
) -> Frame {
    let (tl, g) = (0.35 * f, 0.3 * f);
    let line = 1.2 * f;
    let mut plot = Rect { x0: area.x0 + 4.0 * f, y0: area.y0 + 0.6 * f, x1: area.x1 - f, y1: area.y1 - 4.0 * f };
    let mut out = None;
    for _ in 0..3 {
        let x_lines = wrap(x_label, plot.width().max(4.0 * f), f);
        let y_lines = wrap(y_label, plot.height().max(4.0 * f), f);
        let xt = x.ticks(plot.width(), f, true);
        let yt = y.ticks(plot.height(), f, false);
        let yw = yt.bold.iter().map(|b| text_width(&b.1, yt.size)).fold(0.0, f64::max);
        let xt_h = if xt.vertical {
            xt.bold.iter().flat_map(|b| b.1.split('\n')).map(|l| text_width(l, xt.size)).fold(0.0, f64::max)
        } else {
            let (u, d) = text_extent("0", xt.size);
            u + d
        };
        let last_half = xt.bold.last().map_or(0.0, |b| if xt.vertical { 0.0 } else { text_width(&b.1, xt.size) / 2.0 });
        let y_top_half = 0.5 * f;
        let x0 = area.x0 + y_lines.len() as f64 * line + g + yw + g + tl;
        let x1 = area.x1 - last_half.max(0.3 * f);
        let y0 = area.y0 + y_top_half;
        let y1 = area.y1 - (x_lines.len() as f64 * line + g + xt_h + g + tl);
        plot = Rect { x0, y0, x1: x1.max(x0 + 2.0 * f), y1: y1.max(y0 + 2.0 * f) };
        if let Some((xs, ys)) = aspect {
            let ppu = (plot.width() / xs).min(plot.height() / ys);
            let (w, h) = (ppu * xs, ppu * ys);
            plot.x1 = plot.x0 + w;
            let spare = plot.height() - h;
            plot.y0 += spare / 2.0;
            plot.y1 = plot.y0 + h;
        }
        let below_axis = plot.y1 + tl + g + xt_h + g + x_lines.len() as f64 * line;
        out = Some(Frame { plot, xt, yt, x_lines, y_lines, below_axis });
    }
    out.expect("three passes")
}

/// Draws the axes of `fr` (grid, frame, ticks, labels); returns their text boxes
/// (x ticks, y ticks, x label, y label).
#[allow(clippy::type_complexity)]
pub(crate) fn draw_axes(
    prims: &mut Vec<Prim>,
    fr: &Frame,
    x: &Axis,
    y: &Axis,
    f: f64,
    grid: bool,
    area_left: f64,
) -> (Vec<TextBox>, Vec<TextBox>, Vec<TextBox>, Vec<TextBox>) {
    let p = fr.plot;
    let (tl, g, line) = (0.35 * f, 0.3 * f, 1.2 * f);
    let px = |v: f64| p.x0 + (v - x.lo) / (x.hi - x.lo) * p.width();
    let py = |v: f64| p.y1 - (v - y.lo) / (y.hi - y.lo) * p.height();
    let thin = (0.05 * f).max(0.5);
    if grid {
        for &v in &fr.xt.light {
            prims.push(Prim::Path {
                pts: vec![(px(v), p.y0), (px(v), p.y1)],
                color: Rgb(0xf0, 0xf0, 0xf0),
                width: thin,
                dash: None,
            });
        }
        for &v in &fr.yt.light {
            prims.push(Prim::Path {
                pts: vec![(p.x0, py(v)), (p.x1, py(v))],
                color: Rgb(0xf0, 0xf0, 0xf0),
                width: thin,
                dash: None,
            });
        }
        for (v, _) in &fr.xt.bold {
            prims.push(Prim::Path {
                pts: vec![(px(*v), p.y0), (px(*v), p.y1)],
                color: Rgb(0xdd, 0xdd, 0xdd),
                width: thin,
                dash: None,
            });
        }
        for (v, _) in &fr.yt.bold {
            prims.push(Prim::Path {
                pts: vec![(p.x0, py(*v)), (p.x1, py(*v))],
                color: Rgb(0xdd, 0xdd, 0xdd),
                width: thin,
                dash: None,
            });
        }
    }
    let axis_w = (0.07 * f).max(0.75);
    let mut xb = Vec::new();
    for (v, l) in &fr.xt.bold {
        let xp = px(*v);
        prims.push(Prim::Path { pts: vec![(xp, p.y1), (xp, p.y1 + tl)], color: INK, width: axis_w, dash: None });
        if fr.xt.vertical {
            // Upright, one or two lines side by side, centred on the tick.
            let lines: Vec<&str> = l.split('\n').collect();
            let step = 1.15 * fr.xt.size;
            for (j, line) in lines.iter().enumerate() {
                let (u, d) = text_extent(line, fr.xt.size);
                let shift = (j as f64 - (lines.len() - 1) as f64 / 2.0) * step;
                let at = (xp + (u - d) / 2.0 + shift, p.y1 + tl + g);
                prims.push(Prim::Text {
                    at,
                    text: line.to_string(),
                    size: fr.xt.size,
                    color: INK,
                    anchor: Anchor::End,
                    vertical: true,
                });
                xb.push(TextBox { text: line.to_string(), rect: vbox(line, at, fr.xt.size, Anchor::End) });
            }
            continue;
        }
        let (at, rect, vertical, anchor) = {
            let (u, _) = text_extent("0", fr.xt.size);
            let at = (xp, p.y1 + tl + g + u);
            (at, hbox(l, at, fr.xt.size, Anchor::Middle), false, Anchor::Middle)
        };
        prims.push(Prim::Text { at, text: l.clone(), size: fr.xt.size, color: INK, anchor, vertical });
        xb.push(TextBox { text: l.clone(), rect });
    }
    let mut yb = Vec::new();
    for (v, l) in &fr.yt.bold {
        let yp = py(*v);
        prims.push(Prim::Path { pts: vec![(p.x0 - tl, yp), (p.x0, yp)], color: INK, width: axis_w, dash: None });
        let (u, d) = text_extent(l, fr.yt.size);
        let at = (p.x0 - tl - g, yp + (u - d) / 2.0);
        prims.push(Prim::Text {
            at,
            text: l.clone(),
            size: fr.yt.size,
            color: INK,
            anchor: Anchor::End,
            vertical: false,
        });
        yb.push(TextBox { text: l.clone(), rect: hbox(l, at, fr.yt.size, Anchor::End) });
    }
    prims.push(Prim::Path {
        pts: vec![(p.x0, p.y0), (p.x1, p.y0), (p.x1, p.y1), (p.x0, p.y1), (p.x0, p.y0)],
        color: INK,
        width: axis_w,
        dash: None,
    });
    let xt_h = fr.below_axis - p.y1 - tl - g - g - fr.x_lines.len() as f64 * line;
    let mut xl = Vec::new();
    for (i, l) in fr.x_lines.iter().enumerate() {
        let (u, _) = text_extent("Ag", f);
        let at = ((p.x0 + p.x1) / 2.0, p.y1 + tl + g + xt_h + g + i as f64 * line + u);
        prims.push(Prim::Text { at, text: l.clone(), size: f, color: INK, anchor: Anchor::Middle, vertical: false });
        xl.push(TextBox { text: l.clone(), rect: hbox(l, at, f, Anchor::Middle) });
    }
    let mut yl = Vec::new();
    for (i, l) in fr.y_lines.iter().enumerate() {
        let (u, _) = text_extent("Ag", f);
        let at = (area_left + u + i as f64 * line, (p.y0 + p.y1) / 2.0);
        prims.push(Prim::Text { at, text: l.clone(), size: f, color: INK, anchor: Anchor::Middle, vertical: true });
        yl.push(TextBox { text: l.clone(), rect: vbox(l, at, f, Anchor::Middle) });
    }
    (xb, yb, xl, yl)
}

/// Title lines from the top of the canvas; returns the boxes and the bottom of the last line.
pub(crate) fn draw_title(prims: &mut Vec<Prim>, title: &str, w: f64, f: f64) -> (Vec<TextBox>, f64) {
    let pad = 0.5 * f;
    let mut size = 1.15 * f;
    let mut lines = wrap(title, w - 2.0 * pad, size);
    if lines.len() > 2 {
        size = f;
        lines = wrap(title, w - 2.0 * pad, size);
    }
    let mut y = pad;
    let mut out = Vec::new();
    for l in lines {
        let (u, d) = text_extent(&l, size);
        let at = (pad, y + u);
        prims.push(Prim::Text { at, text: l.clone(), size, color: INK, anchor: Anchor::Start, vertical: false });
        out.push(TextBox { rect: hbox(&l, at, size, Anchor::Start), text: l });
        y += (u + d).max(1.2 * size);
    }
    let bottom = if out.is_empty() { pad } else { y };
    (out, bottom)
}

/// Caption lines at the bottom of the canvas; returns the boxes and the top of the first line.
pub(crate) fn draw_caption(prims: &mut Vec<Prim>, note: Option<&str>, w: f64, h: f64, f: f64) -> (Vec<TextBox>, f64) {
    let pad = 0.5 * f;
    let size = 0.9 * f;
    let lines = note.map(|n| wrap(n, w - 2.0 * pad, size)).unwrap_or_default();
    let step = 1.2 * size;
    let top = h - pad - lines.len() as f64 * step;
    let mut out = Vec::new();
    for (i, l) in lines.into_iter().enumerate() {
        let (u, _) = text_extent("Ag", size);
        let at = (pad, top + i as f64 * step + u);
        prims.push(Prim::Text { at, text: l.clone(), size, color: GREY, anchor: Anchor::Start, vertical: false });
        out.push(TextBox { rect: hbox(&l, at, size, Anchor::Start), text: l });
    }
    let top = if out.is_empty() { h - pad } else { top - 0.3 * f };
    (out, top)
}
