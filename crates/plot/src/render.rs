//! Layout and drawing of a [`Chart`]: every size comes from the font size and the canvas, so the
//! same chart fits a journal column at 8 pt and a 400 x 280 px preview.
//!
//! Order of decisions: the title is wrapped to the canvas width (shrunk from 1.15 to 1 font size
//! when it would take more than two lines); the note goes below as a wrapped caption; the axis
//! labels wrap to the plot's sides; tick counts fall until the labels of an axis do not touch;
//! the margins follow the widest tick label; the legend goes into the corner of the plot with no
//! data point under it (the chart's preferred corner first), or below the axes when no corner is
//! free or it would cover more than two thirds of the plot.

use crate::axes::{Axis, INK, draw_axes, draw_caption, draw_title, frame};
use crate::canvas::{Anchor, Prim, Rgb};
use crate::layout::{FONT_FLOOR, Layout, Place, Rect, TextBox, default_font_px, hbox};
use crate::style::{self, Marker, PALETTE};
use crate::text::{text_extent, text_width, wrap};
use crate::{Chart, LegendPosition, PlotError, SeriesStyle};

/// A marker polygon or circle.
fn marker_prim(shape: Marker, c: (f64, f64), r: f64, color: Rgb) -> Prim {
    let poly = |pts: &[(f64, f64)]| Prim::Fill {
        pts: pts.iter().map(|p| (c.0 + p.0 * r, c.1 + p.1 * r)).collect(),
        color,
        opacity: 1.0,
    };
    match shape {
        Marker::Circle => Prim::Circle { c, r, color },
        Marker::Square => poly(&[(-0.85, -0.85), (0.85, -0.85), (0.85, 0.85), (-0.85, 0.85)]),
        Marker::Diamond => poly(&[(0.0, -1.2), (1.2, 0.0), (0.0, 1.2), (-1.2, 0.0)]),
        Marker::Triangle => poly(&[(0.0, -1.2), (1.1, 0.75), (-1.1, 0.75)]),
        Marker::TriangleDown => poly(&[(0.0, 1.2), (1.1, -0.75), (-1.1, -0.75)]),
    }
}

/// Points every `step` px along a polyline (vertices included).
fn samples(pts: &[(f64, f64)], step: f64, out: &mut Vec<(f64, f64)>) {
    if let Some(&p) = pts.first() {
        out.push(p);
    }
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let k = (len / step).ceil().min(10_000.0) as usize;
        for i in 1..=k {
            let t = i as f64 / k as f64;
            out.push((a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t));
        }
    }
}

/// What a series looks like once resolved.
struct Resolved {
    color: Rgb,
    marker: Marker,
    on_top: bool,
    /// Marker radius as a fraction of the font size: 0.3, smaller for series of many points
    /// (0.3 sqrt(30 / n), at least 0.17), so a scatter of hundreds stays readable.
    marker_r: f64,
}

struct Entry {
    lines: Vec<String>,
    style: SeriesStyle,
    color: Rgb,
    marker: Marker,
    marker_r: f64,
}

impl Chart {
    /// The canvas size in px (1/96 in): from `size_mm`, else `size_px`, else 800 x 560.
    pub fn canvas_px(&self) -> (f64, f64) {
        match (self.size_mm, self.size_px) {
            (Some((w, h)), _) => (w / 25.4 * 96.0, h / 25.4 * 96.0),
            (None, Some((w, h))) => (w as f64, h as f64),
            _ => (800.0, 560.0),
        }
    }

    /// Tick-label font size in px: `font_px`, else 8 pt at a physical size, else
    /// [`default_font_px`] of the pixel size.
    pub fn font_size_px(&self) -> f64 {
        self.font_px.unwrap_or(default_font_px(self.size_mm.is_some(), self.size_px))
    }

    /// PNG device pixels per canvas px: `dpi` / 96; by default 300 dpi at a physical size, 1 at a
    /// pixel size, 1.5 without either.
    pub fn png_scale(&self) -> f64 {
        match (self.dpi, self.size_mm, self.size_px) {
            (Some(d), ..) => d / 96.0,
            (None, Some(_), _) => 300.0 / 96.0,
            (None, None, Some(_)) => 1.0,
            _ => 1.5,
        }
    }

    /// Colour, marker and drawing order of each series. Two marker series that would look the
    /// same (two `measured` sets) get different marker shapes, in the order of [`Marker`].
    fn resolve(&self) -> Vec<Resolved> {
        let mut free = 0usize;
        let registry: Vec<Rgb> = style::STYLES.iter().map(|s| s.1).collect();
        let mut looks: Vec<Resolved> = self
            .series
            .iter()
            .map(|s| {
                let look = style::look(s.key.as_deref().unwrap_or(&s.name));
                let color = match (look, s.color) {
                    (Some(l), _) => l.color,
                    (None, Some(i)) => PALETTE[i % PALETTE.len()],
                    (None, None) => {
                        // The palette's colours not taken by the registry first.
                        let open: Vec<Rgb> = PALETTE.iter().copied().filter(|c| !registry.contains(c)).collect();
                        let c = open[free % open.len()];
                        free += 1;
                        c
                    }
                };
                Resolved {
                    color,
                    marker: s.marker.or(look.map(|l| l.marker)).unwrap_or_default(),
                    on_top: s.on_top || look.is_some_and(|l| l.on_top && s.style == SeriesStyle::Markers),
                    marker_r: 0.3 * (30.0 / s.points.len().max(1) as f64).sqrt().clamp(0.57, 1.0),
                }
            })
            .collect();
        const SHAPES: [Marker; 5] =
            [Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond, Marker::TriangleDown];
        for k in 0..looks.len() {
            if self.series[k].style != SeriesStyle::Markers || self.series[k].marker.is_some() {
                continue;
            }
            let taken = |m: Marker, looks: &[Resolved]| {
                (0..k).any(|j| {
                    self.series[j].style == SeriesStyle::Markers
                        && looks[j].color == looks[k].color
                        && looks[j].marker == m
                })
            };
            if taken(looks[k].marker, &looks) {
                let start = SHAPES.iter().position(|m| *m == looks[k].marker).unwrap_or(0);
                if let Some(m) =
                    (1..SHAPES.len()).map(|i| SHAPES[(start + i) % SHAPES.len()]).find(|m| !taken(*m, &looks))
                {
                    looks[k].marker = m;
                }
            }
        }
        looks
    }

    /// Where every element of the chart is drawn (see [`Layout`]), on the canvas of
    /// [`Chart::canvas_px`].
    pub fn layout(&self) -> Result<Layout, PlotError> {
        Ok(self.render()?.1)
    }

    /// The display list and the layout. Crowding is solved by other means before the font
    /// shrinks: first the chart's font size with the legend in a free corner, then with the legend
    /// below the axes; only then 0.925 and [`FONT_FLOOR`] (0.85) times the font, in the same two
    /// ways. The first that keeps at least 40 % of the canvas height and 45 % of its width for the
    /// plot with nothing out of place wins; else the first with nothing out of place; else the
    /// one with the fewest problems. (Tick labels thin out and named ones turn upright within
    /// each try; titles and captions wrap.)
    pub(crate) fn render(&self) -> Result<(Vec<Prim>, Layout), PlotError> {
        let (w, h) = self.canvas_px();
        let f0 = self.font_size_px();
        let mut tries = Vec::new();
        for k in [1.0, 0.925, FONT_FLOOR] {
            for place in [Place::Auto, Place::Below, Place::Right] {
                let r = self.render_with(f0 * k, place)?;
                let problems = r.1.problems().len();
                if problems == 0 && r.1.plot.height() >= 0.4 * h && r.1.plot.width() >= 0.45 * w {
                    return Ok(r);
                }
                tries.push((problems, r));
            }
        }
        // Nothing out of place with a readable plot (a third of the canvas each way), at the
        // largest font; else nothing out of place with the largest plot; else the fewest problems.
        let area = |l: &Layout| l.plot.width() * l.plot.height();
        let readable = |l: &Layout| l.plot.height() >= h / 3.0 && l.plot.width() >= w / 3.0;
        let best = tries
            .iter()
            .position(|t| t.0 == 0 && readable(&t.1.1))
            .or_else(|| {
                (0..tries.len())
                    .filter(|&i| tries[i].0 == 0)
                    .max_by(|&a, &b| area(&tries[a].1.1).total_cmp(&area(&tries[b].1.1)))
            })
            .unwrap_or_else(|| {
                let fewest = tries.iter().map(|t| t.0).min().unwrap_or(0);
                tries.iter().position(|t| t.0 == fewest).unwrap_or(0)
            });
        Ok(tries.swap_remove(best).1)
    }

    fn render_with(&self, f: f64, place: Place) -> Result<(Vec<Prim>, Layout), PlotError> {
        let ((x0, x1), (y0, y1)) = self.ranges().ok_or_else(|| PlotError::Empty { title: self.title.clone() })?;
        let (w, h) = self.canvas_px();
        let pad = 0.5 * f;
        let looks = self.resolve();
        let min_font = FONT_FLOOR * self.font_size_px();
        let xa = Axis { scale: self.x_scale(), lo: x0, hi: x1, named: self.x_ticks.clone(), min_font };
        let ya = Axis { scale: self.y_scale(), lo: y0, hi: y1, named: None, min_font };
        let mut top_prims = Vec::new();
        let (title, title_bottom) = draw_title(&mut top_prims, &self.title, w, f);
        let (caption, caption_top) = draw_caption(&mut top_prims, self.note.as_deref(), w, h, f);
        let area = Rect { x0: pad, y0: title_bottom + 0.3 * f, x1: w - pad, y1: caption_top };

        // Legend entries, in series order.
        let ls = 0.9 * f;
        let sw = 2.0 * f;
        // One entry per name: a series named like an earlier one (the interval segments of a
        // marker series) shares its entry.
        let entries_for = |max_w: f64| -> Vec<Entry> {
            self.series
                .iter()
                .zip(&looks)
                .enumerate()
                .filter(|(k, (s, _))| !s.name.is_empty() && !self.series[..*k].iter().any(|e| e.name == s.name))
                .map(|(_, sl)| sl)
                .map(|(s, l)| Entry {
                    lines: wrap(&s.name, max_w, ls),
                    style: s.style,
                    color: l.color,
                    marker: l.marker,
                    marker_r: l.marker_r,
                })
                .collect()
        };
        let entry_h = |e: &Entry| e.lines.len() as f64 * 1.15 * ls + 0.25 * ls;
        let entry_w = |e: &Entry| sw + 0.5 * f + e.lines.iter().map(|l| text_width(l, ls)).fold(0.0, f64::max);

        // First pass: legend inside.
        let fr = frame(area, f, &xa, &ya, &self.x_label, &self.y_label, None);
        let inside_entries = entries_for(0.55 * fr.plot.width() - sw - 1.5 * f);
        let mut legend_box = None;
        let mut fr = fr;
        let mut below: Option<(f64, usize, f64)> = None; // (height, columns, label width)
        let mut right: Option<(f64, f64)> = None; // (left edge, label width)
        if !inside_entries.is_empty() {
            let bw = 0.4 * f + inside_entries.iter().map(entry_w).fold(0.0, f64::max) + 0.4 * f;
            let bh = 0.3 * f + inside_entries.iter().map(entry_h).sum::<f64>() + 0.2 * f;
            let p = fr.plot;
            let pts = self.data_samples(&p, &xa, &ya, 0.5 * f);
            let inset = 0.3 * f;
            let corner = |pos: LegendPosition| -> Rect {
                let (left, upper) = match pos {
                    LegendPosition::UpperLeft => (true, true),
                    LegendPosition::UpperRight => (false, true),
                    LegendPosition::LowerLeft => (true, false),
                    LegendPosition::LowerRight => (false, false),
                };
                let x = if left { p.x0 + inset } else { p.x1 - inset - bw };
                let y = if upper { p.y0 + inset } else { p.y1 - inset - bh };
                Rect { x0: x, y0: y, x1: x + bw, y1: y + bh }
            };
            let mut order = vec![self.legend];
            order.extend(
                [
                    LegendPosition::UpperRight,
                    LegendPosition::UpperLeft,
                    LegendPosition::LowerRight,
                    LegendPosition::LowerLeft,
                ]
                .into_iter()
                .filter(|c| *c != self.legend),
            );
            let fits = bw <= 0.65 * p.width() && bh <= 0.65 * p.height();
            let r = 0.3 * f + 1.0;
            legend_box = (fits && place == Place::Auto)
                .then(|| order.into_iter().map(corner).find(|b| !pts.iter().any(|q| b.grow(r).contains(*q))))
                .flatten();
            if legend_box.is_none() && place == Place::Right {
                // Right of the axes, one column a third of the canvas wide at most.
                let label_w = 0.36 * (w - 2.0 * pad) - sw - 0.5 * f;
                let entries = entries_for(label_w);
                let used = entries.iter().map(entry_w).fold(0.0, f64::max);
                let x0 = area.x1 - used;
                right = Some((x0, label_w));
                let area2 = Rect { x1: x0 - 0.8 * f, ..area };
                fr = frame(area2, f, &xa, &ya, &self.x_label, &self.y_label, None);
            } else if legend_box.is_none() {
                // Below the axes, in the number of columns (1 to 4, labels wrapped to the column)
                // that takes the least height.
                for cols in 1..=4usize {
                    let col_w = (w - 2.0 * pad - (cols - 1) as f64 * 1.2 * f) / cols as f64;
                    let label_w = col_w - sw - 0.5 * f;
                    if label_w < 6.0 * f && cols > 1 {
                        break;
                    }
                    let entries = entries_for(label_w);
                    let used = entries.iter().map(entry_w).fold(0.0, f64::max);
                    if cols > 1 && used > col_w + 1e-9 {
                        continue;
                    }
                    let height: f64 =
                        entries.chunks(cols).map(|row| row.iter().map(entry_h).fold(0.0, f64::max)).sum::<f64>()
                            + 0.4 * f;
                    if below.is_none_or(|b| height < b.0 - 1e-9) {
                        below = Some((height, cols, label_w));
                    }
                }
                let height = below.map_or(0.0, |b| b.0);
                let area2 = Rect { y1: area.y1 - height, ..area };
                fr = frame(area2, f, &xa, &ya, &self.x_label, &self.y_label, None);
            }
        }

        let mut prims = Vec::new();
        let (xt, yt, xl, yl) = draw_axes(&mut prims, &fr, &xa, &ya, f, true, pad);
        let p = fr.plot;
        prims.push(Prim::ClipBegin { x0: p.x0, y0: p.y0, x1: p.x1, y1: p.y1 });
        let points = self.draw_series(&mut prims, &p, &xa, &ya, f, &looks);
        prims.push(Prim::ClipEnd);
        prims.extend(top_prims);

        // The legend.
        let mut legend_entries = Vec::new();
        let mut legend = None;
        let draw_entry = |prims: &mut Vec<Prim>, e: &Entry, x: f64, y: f64, out: &mut Vec<TextBox>| {
            let (u, _) = text_extent("Ag", ls);
            let mid = y + 0.6 * ls;
            let stroke = 0.14 * f;
            match e.style {
                SeriesStyle::Line | SeriesStyle::Step => prims.push(Prim::Path {
                    pts: vec![(x, mid), (x + sw, mid)],
                    color: e.color,
                    width: stroke,
                    dash: None,
                }),
                SeriesStyle::Dashed => prims.push(Prim::Path {
                    pts: vec![(x, mid), (x + sw, mid)],
                    color: e.color,
                    width: stroke,
                    dash: Some((0.5 * f, 0.3 * f)),
                }),
                SeriesStyle::Markers => prims.push(marker_prim(e.marker, (x + sw / 2.0, mid), e.marker_r * f, e.color)),
                _ => prims.push(Prim::Fill {
                    pts: vec![
                        (x, mid - 0.35 * f),
                        (x + sw, mid - 0.35 * f),
                        (x + sw, mid + 0.35 * f),
                        (x, mid + 0.35 * f),
                    ],
                    color: e.color,
                    opacity: 0.3,
                }),
            }
            for (i, l) in e.lines.iter().enumerate() {
                let at = (x + sw + 0.5 * f, y + u + i as f64 * 1.15 * ls);
                prims.push(Prim::Text {
                    at,
                    text: l.clone(),
                    size: ls,
                    color: INK,
                    anchor: Anchor::Start,
                    vertical: false,
                });
                out.push(TextBox { text: l.clone(), rect: hbox(l, at, ls, Anchor::Start) });
            }
        };
        if let Some(b) = legend_box {
            prims.push(Prim::Outlined {
                pts: vec![(b.x0, b.y0), (b.x1, b.y0), (b.x1, b.y1), (b.x0, b.y1)],
                fill: Rgb(255, 255, 255),
                opacity: 0.9,
                stroke: Rgb(0x99, 0x99, 0x99),
                width: (0.05 * f).max(0.5),
            });
            let mut y = b.y0 + 0.3 * f;
            for e in &inside_entries {
                draw_entry(&mut prims, e, b.x0 + 0.4 * f, y, &mut legend_entries);
                y += entry_h(e);
            }
            legend = Some(b);
        } else if let Some((height, cols, label_w)) = below {
            let entries = entries_for(label_w);
            let col_w = (w - 2.0 * pad - (cols - 1) as f64 * 1.2 * f) / cols as f64 + 1.2 * f;
            let top = fr.below_axis + 0.4 * f;
            let mut y = top;
            for row in entries.chunks(cols) {
                for (c, e) in row.iter().enumerate() {
                    draw_entry(&mut prims, e, pad + c as f64 * col_w, y, &mut legend_entries);
                }
                y += row.iter().map(entry_h).fold(0.0, f64::max);
            }
            let used = (cols.min(entries.len()) as f64 * col_w - 1.2 * f).max(0.0);
            legend = Some(Rect { x0: pad, y0: top, x1: pad + used, y1: top + height - 0.4 * f });
        } else if let Some((x0, label_w)) = right {
            let entries = entries_for(label_w);
            let top = fr.plot.y0;
            let mut y = top;
            for e in &entries {
                draw_entry(&mut prims, e, x0, y, &mut legend_entries);
                y += entry_h(e);
            }
            let used = entries.iter().map(entry_w).fold(0.0, f64::max);
            legend = Some(Rect { x0, y0: top, x1: x0 + used, y1: y });
        }
        let layout = Layout {
            width: w,
            height: h,
            font_px: f,
            requested_font_px: self.font_size_px(),
            plot: p,
            title,
            caption,
            x_label: xl,
            y_label: yl,
            x_ticks: xt,
            y_ticks: yt,
            legend,
            legend_inside: legend_box.is_some(),
            legend_entries,
            points,
        };
        Ok((prims, layout))
    }

    /// Pixel positions of the drawn data for placing the legend: points along lines and error
    /// bars every `step` px, markers, band edges.
    fn data_samples(&self, p: &Rect, xa: &Axis, ya: &Axis, step: f64) -> Vec<(f64, f64)> {
        let mut out = Vec::new();
        for geom in self.geometry(p, xa, ya) {
            for line in geom {
                samples(&line, step, &mut out);
            }
        }
        out.retain(|q| p.contains(*q));
        out
    }

    /// The drawn polylines of each series (markers as one-point lines), in px.
    fn geometry(&self, p: &Rect, xa: &Axis, ya: &Axis) -> Vec<Vec<Vec<(f64, f64)>>> {
        let px = |v: f64| p.x0 + (v - xa.lo) / (xa.hi - xa.lo) * p.width();
        let py = |v: f64| p.y1 - (v - ya.lo) / (ya.hi - ya.lo) * p.height();
        let to = |x: f64, y: f64| -> Option<(f64, f64)> {
            let (a, b) = (px(self.tx(x)), py(self.ty(y)));
            (a.is_finite() && b.is_finite()).then_some((a, b))
        };
        self.series
            .iter()
            .map(|s| {
                let pts: Vec<(f64, f64)> = s.points.iter().filter_map(|&(x, y)| to(x, y)).collect();
                match s.style {
                    SeriesStyle::XSpan | SeriesStyle::YSpan => Vec::new(),
                    SeriesStyle::Band => {
                        let upper = s.upper.clone().unwrap_or_default();
                        let top: Vec<(f64, f64)> =
                            s.points.iter().zip(&upper).filter_map(|(&(x, _), &u)| to(x, u)).collect();
                        vec![pts, top]
                    }
                    SeriesStyle::Step => {
                        let mut stairs = Vec::with_capacity(2 * pts.len());
                        for (i, &q) in pts.iter().enumerate() {
                            if i > 0 {
                                stairs.push((q.0, pts[i - 1].1));
                            }
                            stairs.push(q);
                        }
                        vec![stairs]
                    }
                    SeriesStyle::Markers => {
                        let shift = if s.dodge.is_finite() { s.dodge * p.width() } else { 0.0 };
                        let to = |x: f64, y: f64| to(x, y).map(|(a, b)| (a + shift, b));
                        let pts: Vec<(f64, f64)> = s.points.iter().filter_map(|&(x, y)| to(x, y)).collect();
                        let mut v: Vec<Vec<(f64, f64)>> = pts.iter().map(|q| vec![*q]).collect();
                        for (i, &(x, y)) in s.points.iter().enumerate() {
                            if let Some(e) =
                                s.y_err.as_ref().and_then(|e| e.get(i)).filter(|e| e.is_finite() && **e > 0.0)
                            {
                                let lo = to(x, y - e).map(|q| q.1).unwrap_or(p.y1);
                                if let (Some(a), Some(_)) = (to(x, y + e), to(x, y)) {
                                    v.push(vec![(a.0, lo), a]);
                                }
                            }
                            if let Some(e) =
                                s.x_err.as_ref().and_then(|e| e.get(i)).filter(|e| e.is_finite() && **e > 0.0)
                            {
                                let lo = to(x - e, y).map(|q| q.0).unwrap_or(p.x0);
                                if let (Some(a), Some(_)) = (to(x + e, y), to(x, y)) {
                                    v.push(vec![(lo, a.1), a]);
                                }
                            }
                        }
                        v
                    }
                    SeriesStyle::Line | SeriesStyle::Dashed => vec![pts],
                }
            })
            .collect()
    }

    /// Draws the series (spans and bands first, then lines, then markers, then the series drawn
    /// on top); returns the drawn data positions inside the plot.
    fn draw_series(
        &self,
        prims: &mut Vec<Prim>,
        p: &Rect,
        xa: &Axis,
        ya: &Axis,
        f: f64,
        looks: &[Resolved],
    ) -> Vec<(f64, f64)> {
        let geom = self.geometry(p, xa, ya);
        let px = |v: f64| p.x0 + (v - xa.lo) / (xa.hi - xa.lo) * p.width();
        let py = |v: f64| p.y1 - (v - ya.lo) / (ya.hi - ya.lo) * p.height();
        let mut order: Vec<usize> = (0..self.series.len()).collect();
        order.sort_by_key(|&k| {
            let s = &self.series[k];
            let base = match s.style {
                SeriesStyle::XSpan | SeriesStyle::YSpan | SeriesStyle::Band => 0,
                SeriesStyle::Markers => 2,
                _ => 1,
            };
            if looks[k].on_top { 3 } else { base }
        });
        let stroke = 0.14 * f;
        let mut points = Vec::new();
        for k in order {
            let s = &self.series[k];
            let color = looks[k].color;
            match s.style {
                SeriesStyle::XSpan => {
                    for &(a, b) in &s.points {
                        let (a, b) = (px(self.tx(a)).max(p.x0), px(self.tx(b)).min(p.x1));
                        if a.is_finite() && b.is_finite() {
                            prims.push(Prim::Fill {
                                pts: vec![(a, p.y0), (b, p.y0), (b, p.y1), (a, p.y1)],
                                color,
                                opacity: 0.22,
                            });
                        }
                    }
                }
                SeriesStyle::YSpan => {
                    for &(a, b) in &s.points {
                        let (a, b) = (py(self.ty(a)).min(p.y1), py(self.ty(b)).max(p.y0));
                        if a.is_finite() && b.is_finite() {
                            prims.push(Prim::Fill {
                                pts: vec![(p.x0, a), (p.x1, a), (p.x1, b), (p.x0, b)],
                                color,
                                opacity: 0.22,
                            });
                        }
                    }
                }
                SeriesStyle::Band => {
                    if let [lower, upper] = geom[k].as_slice() {
                        let mut poly = lower.clone();
                        poly.extend(upper.iter().rev());
                        if poly.len() >= 3 {
                            prims.push(Prim::Fill { pts: poly, color, opacity: 0.22 });
                        }
                    }
                }
                SeriesStyle::Line | SeriesStyle::Step | SeriesStyle::Dashed => {
                    for line in &geom[k] {
                        if line.len() >= 2 {
                            let dash = (s.style == SeriesStyle::Dashed).then_some((0.55 * f, 0.35 * f));
                            prims.push(Prim::Path { pts: line.clone(), color, width: stroke, dash });
                        }
                        let mut s = Vec::new();
                        samples(line, 0.5 * f, &mut s);
                        points.extend(s.into_iter().filter(|q| p.contains(*q)));
                    }
                }
                SeriesStyle::Markers => {
                    let cap = 0.25 * f;
                    let bar_w = (0.07 * f).max(0.75);
                    for line in &geom[k] {
                        match line.as_slice() {
                            [c] => {
                                prims.push(marker_prim(looks[k].marker, *c, looks[k].marker_r * f, color));
                                if p.contains(*c) {
                                    points.push(*c);
                                }
                            }
                            [a, b] => {
                                prims.push(Prim::Path { pts: vec![*a, *b], color, width: bar_w, dash: None });
                                let vertical = (a.0 - b.0).abs() < 1e-9;
                                for e in [a, b] {
                                    let cap_pts = if vertical {
                                        vec![(e.0 - cap, e.1), (e.0 + cap, e.1)]
                                    } else {
                                        vec![(e.0, e.1 - cap), (e.0, e.1 + cap)]
                                    };
                                    prims.push(Prim::Path { pts: cap_pts, color, width: bar_w, dash: None });
                                }
                                let mut s = Vec::new();
                                samples(line, 0.5 * f, &mut s);
                                points.extend(s.into_iter().filter(|q| p.contains(*q)));
                            }
                            _ => {}
                        }
                    }
                }
            }
        }
        points
    }
}
