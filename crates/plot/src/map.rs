//! A field drawn as a colour image with markers (summits) and a colour bar, as SVG or PNG, at full
//! resolution (one image pixel per grid cell; [`block_means`] downsamples when the caller asks),
//! with the same text sizes and layout rules as the line charts.

use std::path::Path;

use crate::axes::{Axis, draw_axes, draw_caption, draw_title, frame};
use crate::canvas::{Anchor, Prim, Rgb};
use crate::layout::Rect;
use crate::scales::{Scale, tick_label, ticks};
use crate::text::{text_extent, text_width};
use crate::{Format, PlotError};

/// A grid of values drawn as an image, with optional markers.
#[derive(Clone, Debug, Default)]
pub struct ImageMap {
    /// Title above the image (wrapped to the width): what the field is and the state or load.
    pub title: String,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// Label of the colour bar: with its unit when `value_unit` is None (`height (nm)`), else the
    /// quantity alone (`pressure`), the unit chosen from `value_unit`.
    pub value_label: String,
    /// SI unit of `values` (`Pa`, `m`): the colour bar then shows them with the SI prefix that
    /// puts the largest magnitude between 1 and 1000 (`MPa`, `GPa`, `nm`).
    pub value_unit: Option<String>,
    /// Columns.
    pub nx: usize,
    /// Rows (row 0 at the bottom, y = 0).
    pub ny: usize,
    /// Values row-major (`iy * nx + ix`); NaN is drawn grey.
    pub values: Vec<f64>,
    /// The image covers `[0, x_max] x [0, y_max]` in axis units.
    pub x_max: f64,
    /// See `x_max`.
    pub y_max: f64,
    /// Marker positions in axis units.
    pub markers: Vec<(f64, f64)>,
    /// Legend text of the markers (default `summits`).
    pub marker_label: Option<String>,
    /// Caption below the figure.
    pub note: Option<String>,
    /// Image size in px of 1/96 in (default 800 wide, the height from the map's aspect ratio; a
    /// PNG has 1.5 times as many pixels unless `dpi` is set).
    pub size_px: Option<(u32, u32)>,
    /// Size on the page in millimetres (overrides `size_px`).
    pub size_mm: Option<(f64, f64)>,
    /// PNG resolution (default 300 at a physical size).
    pub dpi: Option<f64>,
    /// Tick label font size in px (default: as a chart's, `Chart::font_size_px`).
    pub font_px: Option<f64>,
}

/// The SI prefix (factor to multiply SI values by, prefix) that puts `max_abs` in [1, 1000).
pub fn si_prefix(max_abs: f64) -> (f64, &'static str) {
    const P: [(i32, &str); 10] =
        [(-15, "f"), (-12, "p"), (-9, "n"), (-6, "µ"), (-3, "m"), (0, ""), (3, "k"), (6, "M"), (9, "G"), (12, "T")];
    if !(max_abs.is_finite() && max_abs > 0.0) {
        return (1.0, "");
    }
    let e = ((max_abs.log10() / 3.0).floor() as i32 * 3).clamp(-15, 12);
    let (e, p) = P.iter().find(|(k, _)| *k == e).copied().unwrap_or((0, ""));
    (10f64.powi(-e), p)
}

/// A perceptually ordered colour map (viridis, 5 anchors, linear between them), `t` in [0, 1].
fn viridis(t: f64) -> Rgb {
    const A: [(f64, f64, f64); 5] =
        [(68., 1., 84.), (59., 82., 139.), (33., 145., 140.), (94., 201., 98.), (253., 231., 37.)];
    let t = t.clamp(0.0, 1.0) * 4.0;
    let i = (t.floor() as usize).min(3);
    let f = t - i as f64;
    let c = |a: f64, b: f64| (a + (b - a) * f).round() as u8;
    Rgb(c(A[i].0, A[i + 1].0), c(A[i].1, A[i + 1].1), c(A[i].2, A[i + 1].2))
}

/// Block means of a row-major `nx x ny` grid (`values[iy * nx + ix]`) for drawing: the smallest
/// whole block side `b` that brings the longer side to at most `max_cells` cells, and the mean of
/// each `b x b` block (the last row and column of blocks may be partial). NaN values are left out
/// of a mean; a block without any is NaN (drawn grey). Returns `(b, cells_x, cells_y, means)`.
pub fn block_means(values: &[f64], nx: usize, ny: usize, max_cells: usize) -> (usize, usize, usize, Vec<f64>) {
    let block = nx.max(ny).div_ceil(max_cells.max(1)).max(1);
    let (cx, cy) = (nx.div_ceil(block), ny.div_ceil(block));
    let mut cells = vec![f64::NAN; cx * cy];
    for by in 0..cy {
        for bx in 0..cx {
            let (mut sum, mut n) = (0.0, 0usize);
            for iy in by * block..((by + 1) * block).min(ny) {
                for ix in bx * block..((bx + 1) * block).min(nx) {
                    let v = values[iy * nx + ix];
                    if !v.is_nan() {
                        sum += v;
                        n += 1;
                    }
                }
            }
            if n > 0 {
                cells[by * cx + bx] = sum / n as f64;
            }
        }
    }
    (block, cx, cy, cells)
}

impl ImageMap {
    /// The factor applied to the values for display, and the colour bar label with its unit.
    pub fn display_scale(&self) -> (f64, String) {
        match &self.value_unit {
            None => (1.0, self.value_label.clone()),
            Some(unit) => {
                let max = self.values.iter().filter(|v| v.is_finite()).fold(0.0f64, |m, v| m.max(v.abs()));
                let (k, p) = si_prefix(max);
                (k, format!("{} ({p}{unit})", self.value_label))
            }
        }
    }

    /// The drawn cells as CSV: one row per cell with its centre and value, columns named from the
    /// axis and colour-bar labels with their units (`x_um,y_um,height_nm`), values in the units the
    /// colour bar shows; an empty value where the cell has none (drawn grey).
    pub fn data_csv(&self) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        let (k, label) = self.display_scale();
        let keys = [crate::column_key(&self.x_label), crate::column_key(&self.y_label), crate::column_key(&label)];
        // Writing to a Vec cannot fail.
        w.write_record(&keys).ok();
        if self.nx > 0 && self.ny > 0 && self.values.len() == self.nx * self.ny {
            let (cx, cy) = (self.x_max / self.nx as f64, self.y_max / self.ny as f64);
            for iy in 0..self.ny {
                for ix in 0..self.nx {
                    let v = self.values[iy * self.nx + ix] * k;
                    w.write_record([
                        format!("{}", (ix as f64 + 0.5) * cx),
                        format!("{}", (iy as f64 + 0.5) * cy),
                        if v.is_finite() { format!("{v}") } else { String::new() },
                    ])
                    .ok();
                }
            }
        }
        String::from_utf8(w.into_inner().unwrap_or_default()).unwrap_or_default()
    }

    /// The canvas in px of 1/96 in.
    pub fn canvas_px(&self) -> (f64, f64) {
        let aspect = (self.y_max / self.x_max).clamp(0.05, 20.0);
        match (self.size_mm, self.size_px) {
            (Some((w, h)), _) => (w / 25.4 * 96.0, h / 25.4 * 96.0),
            (None, Some((w, h))) => (w as f64, h as f64),
            _ => (800.0, (620.0 * aspect + 130.0).clamp(260.0, 1000.0)),
        }
    }

    fn font(&self) -> f64 {
        self.font_px.unwrap_or(crate::layout::default_font_px(self.size_mm.is_some(), self.size_px))
    }

    fn png_scale(&self) -> f64 {
        match (self.dpi, self.size_mm, self.size_px) {
            (Some(d), ..) => d / 96.0,
            (None, Some(_), _) => 300.0 / 96.0,
            (None, None, Some(_)) => 1.0,
            _ => 1.5,
        }
    }

    /// The display list and the layout (plot = the image, legend = the colour bar).
    pub(crate) fn render(&self) -> Result<(Vec<Prim>, crate::Layout), PlotError> {
        let finite: Vec<f64> = self.values.iter().copied().filter(|v| v.is_finite()).collect();
        if finite.is_empty()
            || self.nx == 0
            || self.ny == 0
            || self.values.len() != self.nx * self.ny
            || !(self.x_max > 0.0 && self.y_max > 0.0)
        {
            return Err(PlotError::Empty { title: self.title.clone() });
        }
        let (k, bar_label) = self.display_scale();
        let lo = finite.iter().copied().fold(f64::INFINITY, f64::min) * k;
        let hi = finite.iter().copied().fold(f64::NEG_INFINITY, f64::max) * k;
        let span = if hi > lo { hi - lo } else { lo.abs().max(1e-300) };
        let (w, h) = self.canvas_px();
        let f = self.font();
        let pad = 0.5 * f;
        let mut prims = Vec::new();
        let (title, title_bottom) = draw_title(&mut prims, &self.title, w, f);
        let (caption, caption_top) = draw_caption(&mut prims, self.note.as_deref(), w, h, f);
        let marker_h = if self.markers.is_empty() { 0.0 } else { 1.4 * f };
        // The colour bar's axis, its labels and its upright label take the right margin.
        let bar = Axis { scale: Scale::Linear, lo, hi: lo + span, named: None, min_font: f };
        let (tl, g) = (0.35 * f, 0.3 * f);
        let bar_ticks_guess = ticks(Scale::Linear, lo, lo + span, 6.0).0;
        let bar_label_w = bar_ticks_guess
            .iter()
            .map(|v| text_width(&tick_label(*v, Scale::Linear, lo, lo + span), f))
            .fold(0.0, f64::max);
        let bar_lines = crate::text::wrap(&bar_label, h * 0.6, f);
        let reserve = 0.8 * f + 1.0 * f + tl + g + bar_label_w + g + bar_lines.len() as f64 * 1.2 * f;
        let area = Rect { x0: pad, y0: title_bottom + 0.3 * f, x1: w - pad - reserve, y1: caption_top - marker_h };
        let xa = Axis { scale: Scale::Linear, lo: 0.0, hi: self.x_max, named: None, min_font: f };
        let ya = Axis { scale: Scale::Linear, lo: 0.0, hi: self.y_max, named: None, min_font: f };
        let fr = frame(area, f, &xa, &ya, &self.x_label, &self.y_label, Some((self.x_max, self.y_max)));
        let p = fr.plot;
        // The image, row 0 of the grid at the bottom.
        let mut rgb = Vec::with_capacity(self.nx * self.ny * 3);
        for iy in (0..self.ny).rev() {
            for ix in 0..self.nx {
                let v = self.values[iy * self.nx + ix] * k;
                let c = if v.is_finite() { viridis((v - lo) / span) } else { Rgb(160, 160, 160) };
                rgb.extend([c.0, c.1, c.2]);
            }
        }
        prims.push(Prim::Image { x0: p.x0, y0: p.y0, x1: p.x1, y1: p.y1, nx: self.nx, ny: self.ny, rgb });
        let (xt, yt, xl, yl) = draw_axes(&mut prims, &fr, &xa, &ya, f, false, pad);
        let red = Rgb(0xd6, 0x27, 0x28);
        // Marker rings no wider than about a third of the mean spacing of the markers on the
        // drawn image (sqrt(area / n)), so that dense summits do not hide the map; 0.22 font
        // sizes at most, 0.8 px at least.
        let spacing = (p.width() * p.height() / self.markers.len().max(1) as f64).sqrt();
        let r = (0.22 * f).min(0.3 * spacing).max(0.8);
        let ring_w = (0.07 * f).max(0.75).min(0.4 * r);
        let ring = |c: (f64, f64)| -> Vec<(f64, f64)> {
            (0..=16)
                .map(|i| i as f64 / 16.0 * std::f64::consts::TAU)
                .map(|t| (c.0 + r * t.cos(), c.1 + r * t.sin()))
                .collect()
        };
        let mut points = Vec::new();
        prims.push(Prim::ClipBegin { x0: p.x0, y0: p.y0, x1: p.x1, y1: p.y1 });
        for &(x, y) in &self.markers {
            let c = (p.x0 + x / self.x_max * p.width(), p.y1 - y / self.y_max * p.height());
            if c.0.is_finite() && c.1.is_finite() {
                prims.push(Prim::Path { pts: ring(c), color: red, width: ring_w, dash: None });
                points.push(c);
            }
        }
        prims.push(Prim::ClipEnd);
        let mut legend_entries = Vec::new();
        if !self.markers.is_empty() {
            let label = self.marker_label.clone().unwrap_or_else(|| "summits".into());
            let (u, _) = text_extent("Ag", 0.9 * f);
            let y = fr.below_axis + 0.3 * f + u;
            let r_key = 0.22 * f;
            let key_ring: Vec<(f64, f64)> = (0..=16)
                .map(|i| i as f64 / 16.0 * std::f64::consts::TAU)
                .map(|t| (p.x0 + r_key + r_key * t.cos(), y - 0.3 * f + r_key * t.sin()))
                .collect();
            prims.push(Prim::Path { pts: key_ring, color: red, width: (0.07 * f).max(0.75), dash: None });
            let at = (p.x0 + 2.0 * r_key + 0.4 * f, y);
            prims.push(Prim::Text {
                at,
                text: label.clone(),
                size: 0.9 * f,
                color: Rgb(0x22, 0x22, 0x22),
                anchor: Anchor::Start,
                vertical: false,
            });
            let wl = text_width(&label, 0.9 * f);
            let (u2, d2) = text_extent(&label, 0.9 * f);
            legend_entries.push(crate::TextBox {
                text: label,
                rect: Rect { x0: at.0, y0: at.1 - u2, x1: at.0 + wl, y1: at.1 + d2 },
            });
        }
        // Colour bar beside the image, as tall as it.
        let bx0 = p.x1 + 0.8 * f;
        let bar_rect = Rect { x0: bx0, y0: p.y0, x1: bx0 + f, y1: p.y1 };
        let steps = 256usize;
        let mut bar_rgb = Vec::with_capacity(steps * 3);
        for i in (0..steps).rev() {
            let c = viridis(i as f64 / (steps - 1) as f64);
            bar_rgb.extend([c.0, c.1, c.2]);
        }
        prims.push(Prim::Image {
            x0: bar_rect.x0,
            y0: bar_rect.y0,
            x1: bar_rect.x1,
            y1: bar_rect.y1,
            nx: 1,
            ny: steps,
            rgb: bar_rgb,
        });
        let bar_fr = crate::axes::Frame {
            plot: bar_rect,
            xt: crate::axes::Ticks { bold: Vec::new(), light: Vec::new(), vertical: false, size: f },
            yt: bar.ticks_public(bar_rect.height(), f),
            x_lines: Vec::new(),
            y_lines: Vec::new(),
            below_axis: bar_rect.y1,
        };
        // Ticks and labels on the bar's right side: draw as a y axis mirrored.
        let mut bar_ticks = Vec::new();
        let axis_w = (0.07 * f).max(0.75);
        for (v, l) in &bar_fr.yt.bold {
            let yp = bar_rect.y1 - (v - bar.lo) / (bar.hi - bar.lo) * bar_rect.height();
            prims.push(Prim::Path {
                pts: vec![(bar_rect.x1, yp), (bar_rect.x1 + tl, yp)],
                color: Rgb(0x22, 0x22, 0x22),
                width: axis_w,
                dash: None,
            });
            let (u, d) = text_extent(l, f);
            let at = (bar_rect.x1 + tl + g, yp + (u - d) / 2.0);
            prims.push(Prim::Text {
                at,
                text: l.clone(),
                size: f,
                color: Rgb(0x22, 0x22, 0x22),
                anchor: Anchor::Start,
                vertical: false,
            });
            bar_ticks.push(crate::TextBox {
                text: l.clone(),
                rect: Rect { x0: at.0, y0: at.1 - u, x1: at.0 + text_width(l, f), y1: at.1 + d },
            });
        }
        prims.push(Prim::Path {
            pts: vec![
                (bar_rect.x0, bar_rect.y0),
                (bar_rect.x1, bar_rect.y0),
                (bar_rect.x1, bar_rect.y1),
                (bar_rect.x0, bar_rect.y1),
                (bar_rect.x0, bar_rect.y0),
            ],
            color: Rgb(0x22, 0x22, 0x22),
            width: axis_w,
            dash: None,
        });
        let label_x = bar_rect.x1 + tl + g + bar_ticks.iter().map(|t| t.rect.width()).fold(0.0, f64::max) + g;
        for (i, l) in bar_lines.iter().enumerate() {
            let (u, _) = text_extent("Ag", f);
            let at = (label_x + u + i as f64 * 1.2 * f, (bar_rect.y0 + bar_rect.y1) / 2.0);
            prims.push(Prim::Text {
                at,
                text: l.clone(),
                size: f,
                color: Rgb(0x22, 0x22, 0x22),
                anchor: Anchor::Middle,
                vertical: true,
            });
            let (u2, d2) = text_extent(l, f);
            let tw = text_width(l, f);
            legend_entries.push(crate::TextBox {
                text: l.clone(),
                rect: Rect { x0: at.0 - u2, x1: at.0 + d2, y0: at.1 - tw / 2.0, y1: at.1 + tw / 2.0 },
            });
        }
        let mut y_ticks = yt;
        y_ticks.extend(bar_ticks);
        let layout = crate::Layout {
            width: w,
            height: h,
            font_px: f,
            requested_font_px: f,
            plot: p,
            title,
            caption,
            x_label: xl,
            y_label: yl,
            x_ticks: xt,
            y_ticks,
            legend: Some(bar_rect),
            legend_inside: false,
            legend_entries,
            points,
        };
        Ok((prims, layout))
    }

    /// Where the title, axes, image (`plot`), colour bar (`legend`) and markers are drawn.
    pub fn layout(&self) -> Result<crate::Layout, PlotError> {
        Ok(self.render()?.1)
    }

    /// Writes the map in the format its extension names (`.svg` or `.png`), atomically.
    pub fn write(&self, path: &Path) -> Result<(), PlotError> {
        match Format::of(path)? {
            Format::Svg => self.write_svg(path),
            Format::Png => self.write_png(path),
        }
    }

    /// Writes the map as SVG (the image embedded as PNG data, one pixel per cell), atomically.
    pub fn write_svg(&self, path: &Path) -> Result<(), PlotError> {
        let (prims, l) = self.render()?;
        let physical =
            self.size_mm.map(|(w, h)| (format!("{}mm", crate::output::mm(w)), format!("{}mm", crate::output::mm(h))));
        stiction_units::io::write_atomic(path, crate::canvas::svg(&prims, l.width, l.height, physical).as_bytes())?;
        Ok(())
    }

    /// Writes the map as PNG (default 1200 px wide), atomically.
    pub fn write_png(&self, path: &Path) -> Result<(), PlotError> {
        let (prims, l) = self.render()?;
        let s = self.png_scale();
        let (w, h) = ((l.width * s).round().max(1.0) as u32, (l.height * s).round().max(1.0) as u32);
        crate::output::write_raster(path, &prims, w, h, s, s * 96.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Block means: a 5 x 3 grid in blocks of 2 (max 3 cells a side), partial blocks and a NaN
    /// left out of its block's mean; values chosen so every mean is exact in binary.
    #[test]
    fn block_means_average_whole_and_partial_blocks() {
        let v = [1.0, 3.0, 5.0, 7.0, 9.0, 2.0, f64::NAN, 6.0, 8.0, 10.0, 0.5, 0.5, 0.5, 0.5, 0.5];
        let (b, cx, cy, m) = block_means(&v, 5, 3, 3);
        assert_eq!((b, cx, cy), (2, 3, 2));
        assert_eq!(m, vec![2.0, 6.5, 9.5, 0.5, 0.5, 0.5]);
    }

    /// The CSV holds the cell centres and the values drawn, keyed by the labels' units.
    #[test]
    fn data_csv_holds_the_cells() {
        let m = ImageMap {
            x_label: "x (µm)".into(),
            y_label: "y (µm)".into(),
            value_label: "height (nm)".into(),
            nx: 2,
            ny: 1,
            values: vec![1.5, f64::NAN],
            x_max: 4.0,
            y_max: 1.0,
            ..ImageMap::default()
        };
        assert_eq!(m.data_csv(), "x_um,y_um,height_nm\n1,0.5,1.5\n3,0.5,\n");
    }

    /// Pressures in Pa up to 2.8e10 are shown in GPa (0.028 GPa = 28 MPa would need the
    /// smaller prefix only if the largest were under 1 GPa).
    #[test]
    fn the_colour_bar_picks_its_si_prefix() {
        assert_eq!(si_prefix(2.8e10), (1e-9, "G"));
        assert_eq!(si_prefix(9.99e8).1, "M");
        assert_eq!(si_prefix(3.0e-9).1, "n");
        let m = ImageMap {
            value_label: "pressure".into(),
            value_unit: Some("Pa".into()),
            values: vec![1.0e9, 2.8e10],
            ..ImageMap::default()
        };
        assert_eq!(m.display_scale().1, "pressure (GPa)");
    }
}
