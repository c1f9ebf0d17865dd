//! stiction-plot: plain-data charts written as SVG or PNG with plotters, with their data beside them.
//!
//! Physics crates produce numbers; the command line builds a [`Chart`] from them and writes it with
//! [`Chart::write`] (the format from the extension; an unknown extension is an error) or
//! [`Chart::write_with_data`], which also writes the plotted numbers as CSV beside the figure
//! (`fig7.svg` -> `fig7.csv`), one row per point, with the axis units in the column names, so every
//! figure can be re-plotted in another tool. Files are written atomically (temporary file, then
//! rename) and never through a symbolic link.
//!
//! Logarithmic axes are drawn by plotting log10 of the data on a linear axis; their ticks are
//! labelled as powers of ten (`10⁻³`) and, between decades, only at 2 and 5 times a power of ten,
//! so that one axis never mixes formats. Legend swatches match their series: a line, a dashed line,
//! a marker, or a shaded patch for bands and reference ranges.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::prelude::*;

mod map;
pub use map::{ImageMap, block_means};

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SeriesStyle {
    /// A solid line through the points.
    #[default]
    Line,
    /// A dashed line through the points.
    Dashed,
    /// Markers only (measured data), with optional error bars.
    Markers,
    /// A staircase through the points (an empirical CDF): horizontal from each point to the next x.
    Step,
    /// A shaded band between the points' y (lower edge) and `upper` (upper edge).
    Band,
    /// A shaded vertical strip over the whole plot between two x values (a reference range of x).
    XSpan,
    /// A shaded horizontal strip over the whole plot between two y values (a reference range of y).
    YSpan,
}

impl SeriesStyle {
    /// The name written in the data CSV.
    pub fn name(self) -> &'static str {
        match self {
            SeriesStyle::Line => "line",
            SeriesStyle::Dashed => "dashed",
            SeriesStyle::Markers => "markers",
            SeriesStyle::Step => "step",
            SeriesStyle::Band => "band",
            SeriesStyle::XSpan => "x-range",
            SeriesStyle::YSpan => "y-range",
        }
    }
}

/// One named series of (x, y) points.
#[derive(Clone, Debug, Default)]
pub struct Series {
    /// Legend entry (empty: not in the legend).
    pub name: String,
    /// The points, in the chart's units. For a span, one point (low, high).
    pub points: Vec<(f64, f64)>,
    /// Half-lengths of vertical error bars, one per point.
    pub y_err: Option<Vec<f64>>,
    /// Half-lengths of horizontal error bars, one per point.
    pub x_err: Option<Vec<f64>>,
    /// Upper edge of a band, one per point (the points hold the lower edge).
    pub upper: Option<Vec<f64>>,
    /// How the series is drawn.
    pub style: SeriesStyle,
    /// Colour index into the palette (default: the series' position).
    pub color: Option<usize>,
}

impl Series {
    fn of(name: impl Into<String>, points: Vec<(f64, f64)>, style: SeriesStyle) -> Self {
        Series { name: name.into(), points, style, ..Default::default() }
    }
    /// A solid line.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::of(name, points, SeriesStyle::Line)
    }
    /// A dashed line.
    pub fn dashed(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::of(name, points, SeriesStyle::Dashed)
    }
    /// Markers (measured points).
    pub fn markers(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::of(name, points, SeriesStyle::Markers)
    }
    /// A staircase (empirical CDF).
    pub fn step(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::of(name, points, SeriesStyle::Step)
    }
    /// A shaded band from (x, lower, upper) triples.
    pub fn band(name: impl Into<String>, points: Vec<(f64, f64, f64)>) -> Self {
        let upper = points.iter().map(|p| p.2).collect();
        Series { upper: Some(upper), ..Self::of(name, points.iter().map(|p| (p.0, p.1)).collect(), SeriesStyle::Band) }
    }
    /// A shaded reference range of x, from `low` to `high`, over the whole height of the plot.
    pub fn x_range(name: impl Into<String>, low: f64, high: f64) -> Self {
        Self::of(name, vec![(low, high)], SeriesStyle::XSpan)
    }
    /// A shaded reference range of y, from `low` to `high`, over the whole width of the plot.
    pub fn y_range(name: impl Into<String>, low: f64, high: f64) -> Self {
        Self::of(name, vec![(low, high)], SeriesStyle::YSpan)
    }
    /// Adds vertical error bars (half-lengths).
    pub fn with_y_err(mut self, y_err: Vec<f64>) -> Self {
        self.y_err = Some(y_err);
        self
    }
    /// Adds horizontal error bars (half-lengths).
    pub fn with_x_err(mut self, x_err: Vec<f64>) -> Self {
        self.x_err = Some(x_err);
        self
    }
    /// Draws the series in palette colour `index` (to pair a band with its line).
    pub fn with_color(mut self, index: usize) -> Self {
        self.color = Some(index);
        self
    }
}

/// Where the legend sits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LegendPosition {
    /// Upper left corner (default).
    #[default]
    UpperLeft,
    /// Upper right corner.
    UpperRight,
    /// Lower left corner.
    LowerLeft,
    /// Lower right corner.
    LowerRight,
}

/// A single-panel x-y chart.
#[derive(Clone, Debug, Default)]
pub struct Chart {
    /// Title above the plot: what the data are.
    pub title: String,
    /// An optional second line under the title (what a reader must know to read the figure).
    pub note: Option<String>,
    /// x-axis label with its unit, e.g. `load L (µN)`.
    pub x_label: String,
    /// y-axis label with its unit.
    pub y_label: String,
    /// Column name of x in the data CSV (with the unit, e.g. `load_un`); default: from the label.
    pub x_key: Option<String>,
    /// Column name of y in the data CSV; default: from the label.
    pub y_key: Option<String>,
    /// Logarithmic x axis (all x must be positive).
    pub x_log: bool,
    /// Logarithmic y axis (all y must be positive).
    pub y_log: bool,
    /// Symmetric-logarithmic x axis with this linear threshold c (data units): drawn at
    /// sign(x) log10(1 + |x|/c), so that negative and positive values over many decades, and zero,
    /// are all visible (ticks at 0 and at plus and minus powers of ten).
    pub x_symlog: Option<f64>,
    /// Symmetric-logarithmic y axis with this linear threshold (see `x_symlog`).
    pub y_symlog: Option<f64>,
    /// Named x ticks (position in data units, label) instead of numbers: a categorical axis.
    pub x_ticks: Option<Vec<(f64, String)>>,
    /// The data.
    pub series: Vec<Series>,
    /// Optional fixed x range (in data units).
    pub x_range: Option<(f64, f64)>,
    /// Optional fixed y range (in data units).
    pub y_range: Option<(f64, f64)>,
    /// Where the legend sits.
    pub legend: LegendPosition,
    /// Figure size in pixels (default 800 x 560 for SVG, 1.5 times that for PNG).
    pub size_px: Option<(u32, u32)>,
    /// Tick label font size in pixels (default 15; titles and axis labels scale with it).
    pub font_px: Option<f64>,
}

/// Why a chart could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// No finite point to draw.
    #[error("chart {title:?} has no finite point to draw (on a log axis, values must be positive)")]
    Empty {
        /// The chart title.
        title: String,
    },
    /// The output file's extension names no format.
    #[error("cannot write {path}: unknown figure format {extension:?}, expected .svg or .png")]
    UnknownFormat {
        /// Output path.
        path: String,
        /// The extension given.
        extension: String,
    },
    /// A size or font option is out of range.
    #[error("figure {what} {value} is out of range: expected {expected}")]
    Option {
        /// Which option.
        what: &'static str,
        /// The value given.
        value: f64,
        /// What is accepted.
        expected: &'static str,
    },
    /// The drawing backend failed (font missing).
    #[error("could not draw {path}: {message}")]
    Backend {
        /// Output path.
        path: String,
        /// Backend message.
        message: String,
    },
    /// The file could not be written.
    #[error(transparent)]
    File(#[from] stiction_units::io::FileError),
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x17, 0xbe, 0xcf),
];

/// The figure formats [`Chart::write`] knows, from a path's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Scalable vector graphics.
    Svg,
    /// Portable network graphics (raster, 1.5 times the SVG size).
    Png,
}

impl Format {
    /// The format of `path` from its extension (case-insensitive), or an error naming it.
    pub fn of(path: &Path) -> Result<Format, PlotError> {
        let ext = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
        match ext.as_str() {
            "svg" => Ok(Format::Svg),
            "png" => Ok(Format::Png),
            _ => Err(PlotError::UnknownFormat { path: path.display().to_string(), extension: ext }),
        }
    }
}

/// The data CSV written beside a figure: same folder and stem, extension `.csv`.
pub fn data_path(figure: &Path) -> PathBuf {
    figure.with_extension("csv")
}

impl Chart {
    /// A chart with a title and axis labels and no data yet.
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Chart { title: title.into(), x_label: x_label.into(), y_label: y_label.into(), ..Default::default() }
    }

    /// Adds a series (builder style).
    pub fn with(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// Sets the CSV column names of x and y (builder style), with their units: `("load_un", "friction_un")`.
    pub fn keys(mut self, x_key: impl Into<String>, y_key: impl Into<String>) -> Self {
        self.x_key = Some(x_key.into());
        self.y_key = Some(y_key.into());
        self
    }

    /// Sets the note under the title (builder style).
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.note = Some(note.into());
        self
    }

    /// Sets the size and font options, checked: width and height 200-8000 px, font 6-72 px.
    pub fn sized(mut self, size_px: Option<(u32, u32)>, font_px: Option<f64>) -> Result<Self, PlotError> {
        if let Some((w, h)) = size_px {
            for (what, v) in [("width", w), ("height", h)] {
                if !(200..=8000).contains(&v) {
                    return Err(PlotError::Option { what, value: v as f64, expected: "200 to 8000 px" });
                }
            }
        }
        if let Some(f) = font_px
            && !(6.0..=72.0).contains(&f)
        {
            return Err(PlotError::Option { what: "font size", value: f, expected: "6 to 72 px" });
        }
        self.size_px = size_px.or(self.size_px);
        self.font_px = font_px.or(self.font_px);
        Ok(self)
    }

    /// Writes the chart in the format its extension names (`.svg` or `.png`), atomically.
    pub fn write(&self, path: &Path) -> Result<(), PlotError> {
        match Format::of(path)? {
            Format::Svg => self.write_svg(path),
            Format::Png => self.write_png(path),
        }
    }

    /// Writes the chart ([`Chart::write`]) and its data as CSV beside it ([`data_path`]).
    /// Returns the path of the CSV.
    pub fn write_with_data(&self, path: &Path) -> Result<PathBuf, PlotError> {
        Format::of(path)?;
        let csv_path = data_path(path);
        stiction_units::io::write_atomic(&csv_path, self.data_csv().as_bytes())?;
        self.write(path)?;
        Ok(csv_path)
    }

    fn svg_size(&self) -> (u32, u32) {
        self.size_px.unwrap_or((800, 560))
    }

    /// Writes the chart as SVG (default 800 x 560 px), atomically.
    pub fn write_svg(&self, path: &Path) -> Result<(), PlotError> {
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, self.svg_size()).into_drawing_area();
            self.draw(root, path, 1.0)?;
        }
        stiction_units::io::write_atomic(path, text.as_bytes())?;
        Ok(())
    }

    /// Writes the chart as PNG (default 1200 x 840 px), atomically.
    pub fn write_png(&self, path: &Path) -> Result<(), PlotError> {
        let (w, h) = self.svg_size();
        let (w, h) = if self.size_px.is_some() { (w, h) } else { (w * 3 / 2, h * 3 / 2) };
        let scale = if self.size_px.is_some() { 1.0 } else { 1.5 };
        let mut rgb = vec![0u8; w as usize * h as usize * 3];
        {
            let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
            self.draw(root, path, scale)?;
        }
        let mut png = Vec::new();
        encode_png(&rgb, w, h, &mut png).map_err(|e| PlotError::Backend {
            path: path.display().to_string(),
            message: format!("PNG encoding failed: {e}"),
        })?;
        stiction_units::io::write_atomic(path, &png)?;
        Ok(())
    }

    /// The CSV column names of x and y (with their units).
    pub fn column_keys(&self) -> (String, String) {
        (
            self.x_key.clone().unwrap_or_else(|| column_key(&self.x_label)),
            self.y_key.clone().unwrap_or_else(|| column_key(&self.y_label)),
        )
    }

    /// The data columns after `series` and `style`: x, y, x error, y error, upper y edge, upper x edge.
    pub fn data_columns(&self) -> [String; 6] {
        let (xk, yk) = self.column_keys();
        [xk.clone(), yk.clone(), format!("{xk}_err"), format!("{yk}_err"), format!("{yk}_upper"), format!("{xk}_upper")]
    }

    /// The plotted numbers of series `s`, one row per point, in the order of [`Chart::data_columns`]
    /// (None: empty). A span is one row: an x range has x = low and `x_upper` = high, a y range y = low
    /// and `y_upper` = high.
    fn rows(s: &Series) -> Vec<[Option<f64>; 6]> {
        let fin = |v: f64| v.is_finite().then_some(v);
        s.points
            .iter()
            .enumerate()
            .map(|(i, &(x, y))| {
                let pick = |v: &Option<Vec<f64>>| v.as_ref().and_then(|v| v.get(i)).copied().and_then(fin);
                match s.style {
                    SeriesStyle::XSpan => [fin(x), None, None, None, None, fin(y)],
                    SeriesStyle::YSpan => [None, fin(x), None, None, fin(y), None],
                    _ => [fin(x), fin(y), pick(&s.x_err), pick(&s.y_err), pick(&s.upper), None],
                }
            })
            .collect()
    }

    /// The plotted numbers as CSV: one row per point, columns `series`, `style`, x and y with their
    /// units, the error bars, band edges and span ends where a series has them
    /// ([`Chart::data_columns`]).
    pub fn data_csv(&self) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        let mut header = vec!["series".to_string(), "style".into()];
        header.extend(self.data_columns());
        // Writing to a Vec cannot fail.
        w.write_record(&header).ok();
        let num = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
        for s in &self.series {
            for row in Self::rows(s) {
                let mut rec = vec![s.name.clone(), s.style.name().to_string()];
                rec.extend(row.iter().map(|v| num(*v)));
                w.write_record(&rec).ok();
            }
        }
        String::from_utf8(w.into_inner().unwrap_or_default()).unwrap_or_default()
    }

    /// The same numbers as [`Chart::data_csv`] as JSON, for results files: `title`, `x_label`,
    /// `y_label`, and `series`, each with `name`, `style` and one array per column that has a value
    /// (keys as the CSV columns, with units: `load_un`, `friction_un`, `friction_un_err`, ...;
    /// null where a point has none).
    pub fn data_json(&self) -> serde_json::Value {
        use serde_json::{Value, json};
        let cols = self.data_columns();
        let series: Vec<Value> = self
            .series
            .iter()
            .map(|s| {
                let rows = Self::rows(s);
                let mut obj = serde_json::Map::new();
                obj.insert("name".into(), json!(s.name));
                obj.insert("style".into(), json!(s.style.name()));
                for (c, key) in cols.iter().enumerate() {
                    if rows.iter().any(|r| r[c].is_some()) {
                        obj.insert(key.clone(), Value::Array(rows.iter().map(|r| json!(r[c])).collect()));
                    }
                }
                Value::Object(obj)
            })
            .collect();
        json!({"title": self.title, "x_label": self.x_label, "y_label": self.y_label, "series": series})
    }

    fn tx(&self, x: f64) -> f64 {
        self.x_scale().to_axis(x)
    }
    fn ty(&self, y: f64) -> f64 {
        self.y_scale().to_axis(y)
    }
    fn x_scale(&self) -> Scale {
        Scale::of(self.x_log, self.x_symlog)
    }
    fn y_scale(&self) -> Scale {
        Scale::of(self.y_log, self.y_symlog)
    }

    /// The data range after the log transform, padded by 4 %.
    fn ranges(&self) -> Option<((f64, f64), (f64, f64))> {
        let mut xs = (f64::INFINITY, f64::NEG_INFINITY);
        let mut ys = (f64::INFINITY, f64::NEG_INFINITY);
        let grow = |r: &mut (f64, f64), v: f64| {
            if v.is_finite() {
                *r = (r.0.min(v), r.1.max(v));
            }
        };
        for s in &self.series {
            match s.style {
                SeriesStyle::XSpan => {
                    for &(a, b) in &s.points {
                        grow(&mut xs, self.tx(a));
                        grow(&mut xs, self.tx(b));
                    }
                    continue;
                }
                SeriesStyle::YSpan => {
                    for &(a, b) in &s.points {
                        grow(&mut ys, self.ty(a));
                        grow(&mut ys, self.ty(b));
                    }
                    continue;
                }
                _ => {}
            }
            for (i, &(x, y)) in s.points.iter().enumerate() {
                let (tx, ty) = (self.tx(x), self.ty(y));
                if !(tx.is_finite() && ty.is_finite()) {
                    continue;
                }
                let ye = s.y_err.as_ref().and_then(|e| e.get(i)).copied().unwrap_or(0.0);
                let xe = s.x_err.as_ref().and_then(|e| e.get(i)).copied().unwrap_or(0.0);
                grow(&mut xs, self.tx(x - xe));
                grow(&mut xs, self.tx(x + xe));
                grow(&mut ys, self.ty(y - ye));
                grow(&mut ys, self.ty(y + ye));
                if let Some(u) = s.upper.as_ref().and_then(|u| u.get(i)) {
                    grow(&mut ys, self.ty(*u));
                }
            }
        }
        if let Some((a, b)) = self.x_range {
            xs = (self.tx(a), self.tx(b));
        }
        if let Some((a, b)) = self.y_range {
            ys = (self.ty(a), self.ty(b));
        }
        if !(xs.0.is_finite() && ys.0.is_finite() && xs.1.is_finite() && ys.1.is_finite()) {
            return None;
        }
        let pad = |(lo, hi): (f64, f64)| {
            let span = if hi > lo { hi - lo } else { lo.abs().max(1e-300) };
            (lo - 0.04 * span, hi + 0.04 * span)
        };
        Some((if self.x_range.is_some() { xs } else { pad(xs) }, if self.y_range.is_some() { ys } else { pad(ys) }))
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>, path: &Path, scale: f64) -> Result<(), PlotError> {
        let backend_err =
            |e: &dyn std::fmt::Display| PlotError::Backend { path: path.display().to_string(), message: e.to_string() };
        let ((x0, x1), (y0, y1)) = self.ranges().ok_or_else(|| PlotError::Empty { title: self.title.clone() })?;
        let font = self.font_px.unwrap_or(15.0) * scale;
        let px = |v: f64| (v * scale).round() as u32;
        root.fill(&WHITE).map_err(|e| backend_err(&e))?;
        let title_font = TextStyle::from(("sans-serif", font * 1.45).into_font());
        let (_, title_h) = root.estimate_text_size("Ag", &title_font).unwrap_or((0, 20));
        let note_font = ("sans-serif", font).into_font().color(&RGBColor(0x44, 0x44, 0x44));
        let mut top = px(10.0) as i32;
        root.draw(&Text::new(self.title.clone(), (px(14.0) as i32, top), title_font.clone()))
            .map_err(|e| backend_err(&e))?;
        top += title_h as i32 + px(4.0) as i32;
        if let Some(note) = &self.note {
            // One text line per `\n`.
            for line in note.lines() {
                root.draw(&Text::new(line.to_string(), (px(14.0) as i32, top), note_font.clone()))
                    .map_err(|e| backend_err(&e))?;
                top += (font * 1.3) as i32;
            }
        }
        let area = root.split_vertically(top + px(4.0) as i32).1;
        let (xs, ys) = (self.x_scale(), self.y_scale());
        let (x_bold, x_light) = match &self.x_ticks {
            Some(t) => (t.iter().map(|p| self.tx(p.0)).collect(), Vec::new()),
            None => ticks(xs, x0, x1),
        };
        let named = self.x_ticks.clone();
        let (y_bold, y_light) = ticks(ys, y0, y1);
        let mut chart = ChartBuilder::on(&area)
            .margin(px(14.0))
            .x_label_area_size(px(52.0))
            .y_label_area_size(px(80.0))
            .build_cartesian_2d(
                TickedAxis { lo: x0, hi: x1, bold: x_bold, light: x_light },
                TickedAxis { lo: y0, hi: y1, bold: y_bold, light: y_light },
            )
            .map_err(|e| backend_err(&e))?;
        let x_fmt = move |v: &f64| match &named {
            Some(t) => t
                .iter()
                .find(|p| (xs.to_axis(p.0) - v).abs() <= 1e-9 * (x1 - x0).abs())
                .map_or(String::new(), |p| p.1.clone()),
            None => tick_label(*v, xs, x0, x1),
        };
        let y_fmt = move |v: &f64| tick_label(*v, ys, y0, y1);
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .label_style(("sans-serif", font))
            .axis_desc_style(("sans-serif", font * 1.13))
            .light_line_style(RGBColor(0xee, 0xee, 0xee))
            .draw()
            .map_err(|e| backend_err(&e))?;
        let stroke = px(2.0);
        let marker = px(4.0);
        // Spans and bands first, so that lines and markers lie on top.
        let mut order: Vec<usize> = (0..self.series.len()).collect();
        order.sort_by_key(|&k| match self.series[k].style {
            SeriesStyle::XSpan | SeriesStyle::YSpan | SeriesStyle::Band => 0,
            _ => 1,
        });
        let mut legend_entries: Vec<(usize, usize)> = Vec::new();
        for &k in &order {
            let s = &self.series[k];
            let color = PALETTE[s.color.unwrap_or(k) % PALETTE.len()];
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .map(|&(x, y)| (self.tx(x), self.ty(y)))
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .collect();
            let shade = color.mix(0.22).filled();
            let anno = match s.style {
                SeriesStyle::Line => {
                    chart.draw_series(LineSeries::new(pts, color.stroke_width(stroke))).map_err(|e| backend_err(&e))?
                }
                SeriesStyle::Dashed => chart
                    .draw_series(DashedLineSeries::new(pts, px(8.0), px(5.0), color.stroke_width(stroke)))
                    .map_err(|e| backend_err(&e))?,
                SeriesStyle::Step => {
                    let mut stairs = Vec::with_capacity(2 * pts.len());
                    for (i, &(x, y)) in pts.iter().enumerate() {
                        if i > 0 {
                            stairs.push((x, pts[i - 1].1));
                        }
                        stairs.push((x, y));
                    }
                    chart
                        .draw_series(LineSeries::new(stairs, color.stroke_width(stroke)))
                        .map_err(|e| backend_err(&e))?
                }
                SeriesStyle::Band => {
                    let upper = s.upper.clone().unwrap_or_default();
                    let mut poly: Vec<(f64, f64)> = s
                        .points
                        .iter()
                        .map(|&(x, y)| (self.tx(x), self.ty(y)))
                        .filter(|(x, y)| x.is_finite() && y.is_finite())
                        .collect();
                    let top: Vec<(f64, f64)> = s
                        .points
                        .iter()
                        .zip(&upper)
                        .map(|(&(x, _), &u)| (self.tx(x), self.ty(u)))
                        .filter(|(x, y)| x.is_finite() && y.is_finite())
                        .collect();
                    poly.extend(top.into_iter().rev());
                    chart.draw_series(std::iter::once(Polygon::new(poly, shade))).map_err(|e| backend_err(&e))?
                }
                SeriesStyle::XSpan => {
                    let rects: Vec<_> = s
                        .points
                        .iter()
                        .map(|&(a, b)| Rectangle::new([(self.tx(a).max(x0), y0), (self.tx(b).min(x1), y1)], shade))
                        .collect();
                    chart.draw_series(rects).map_err(|e| backend_err(&e))?
                }
                SeriesStyle::YSpan => {
                    let rects: Vec<_> = s
                        .points
                        .iter()
                        .map(|&(a, b)| Rectangle::new([(x0, self.ty(a).max(y0)), (x1, self.ty(b).min(y1))], shade))
                        .collect();
                    chart.draw_series(rects).map_err(|e| backend_err(&e))?
                }
                SeriesStyle::Markers => {
                    let bar_style = color.stroke_width(px(1.0).max(1));
                    if let Some(err) = &s.y_err {
                        let bars: Vec<_> = s
                            .points
                            .iter()
                            .zip(err)
                            .filter(|((x, y), e)| x.is_finite() && y.is_finite() && e.is_finite() && **e > 0.0)
                            .map(|(&(x, y), &e)| {
                                let (lo, hi) = (self.ty(y - e), self.ty(y + e));
                                let lo = if lo.is_finite() { lo } else { y0 };
                                ErrorBar::new_vertical(self.tx(x), lo, self.ty(y), hi, bar_style, px(8.0))
                            })
                            .collect();
                        chart.draw_series(bars).map_err(|e| backend_err(&e))?;
                    }
                    if let Some(err) = &s.x_err {
                        let bars: Vec<_> = s
                            .points
                            .iter()
                            .zip(err)
                            .filter(|((x, y), e)| x.is_finite() && y.is_finite() && e.is_finite() && **e > 0.0)
                            .map(|(&(x, y), &e)| {
                                let (lo, hi) = (self.tx(x - e), self.tx(x + e));
                                let lo = if lo.is_finite() { lo } else { x0 };
                                ErrorBar::new_horizontal(self.ty(y), lo, self.tx(x), hi, bar_style, px(8.0))
                            })
                            .collect();
                        chart.draw_series(bars).map_err(|e| backend_err(&e))?;
                    }
                    chart
                        .draw_series(pts.into_iter().map(|p| Circle::new(p, marker, color.filled())))
                        .map_err(|e| backend_err(&e))?
                }
            };
            if !s.name.is_empty() {
                legend_entries.push((k, 0));
                let style = s.style;
                let w = px(22.0) as i32;
                let h = px(6.0) as i32;
                let st = stroke;
                let r = marker;
                let dash = px(6.0) as i32;
                anno.label(legend_label(&s.name)).legend(move |(x, y)| {
                    // One element type for every swatch (a backend borrowed for the SVG string
                    // cannot box elements): unused parts are empty or transparent.
                    let none = TRANSPARENT.stroke_width(0);
                    let (seg1, seg2): (Vec<Pixel>, Vec<Pixel>) = match style {
                        SeriesStyle::Line | SeriesStyle::Step => (vec![(0, 0), (w, 0)], vec![]),
                        SeriesStyle::Dashed => (vec![(0, 0), (dash, 0)], vec![(w - dash, 0), (w, 0)]),
                        _ => (vec![], vec![]),
                    };
                    let dot = if style == SeriesStyle::Markers { color.filled() } else { none };
                    let patch = match style {
                        SeriesStyle::Band | SeriesStyle::XSpan | SeriesStyle::YSpan => color.mix(0.3).filled(),
                        _ => none,
                    };
                    EmptyElement::at((x, y))
                        + Rectangle::new([(0, -h), (w, h)], patch)
                        + PathElement::new(seg1, color.stroke_width(st))
                        + PathElement::new(seg2, color.stroke_width(st))
                        + Circle::new((w / 2, 0), if style == SeriesStyle::Markers { r } else { 0 }, dot)
                });
            }
        }
        if !legend_entries.is_empty() {
            let pos = match self.legend {
                LegendPosition::UpperLeft => SeriesLabelPosition::UpperLeft,
                LegendPosition::UpperRight => SeriesLabelPosition::UpperRight,
                LegendPosition::LowerLeft => SeriesLabelPosition::LowerLeft,
                LegendPosition::LowerRight => SeriesLabelPosition::LowerRight,
            };
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.9))
                .border_style(BLACK.mix(0.4))
                .label_font(("sans-serif", font))
                .legend_area_size(px(30.0))
                .position(pos)
                .draw()
                .map_err(|e| backend_err(&e))?;
        }
        root.present().map_err(|e| backend_err(&e))?;
        Ok(())
    }
}

/// A point in backend pixels.
type Pixel = (i32, i32);

fn legend_label(name: &str) -> String {
    name.to_string()
}

/// Encodes an RGB8 buffer as PNG with the `image` crate that plotters' bitmap backend already uses.
fn encode_png(rgb: &[u8], w: u32, h: u32, out: &mut Vec<u8>) -> Result<(), String> {
    use image::ImageEncoder;
    image::codecs::png::PngEncoder::new(out).write_image(rgb, w, h, image::ColorType::Rgb8).map_err(|e| e.to_string())
}

/// A CSV column name from an axis label: the quantity's words and its unit, lower case, ASCII,
/// e.g. `load L (µN)` -> `load_l_un`, `V_pull² (V²)` -> `v_pull2_v2`; the micro sign µ becomes `u`,
/// the Greek letter μ `mu`.
pub fn column_key(label: &str) -> String {
    let mut out = String::new();
    for c in label.chars() {
        let mapped: String = match c {
            'µ' => "u".into(),
            'μ' => "mu".into(),
            '²' => "2".into(),
            '³' => "3".into(),
            '⁻' => "-".into(),
            'θ' => "theta".into(),
            'σ' => "sigma".into(),
            'α' => "alpha".into(),
            'κ' => "kappa".into(),
            '*' => "star".into(),
            '%' => "percent".into(),
            c if c.is_ascii_alphanumeric() => c.to_ascii_lowercase().to_string(),
            _ => "_".into(),
        };
        out.push_str(&mapped);
    }
    let mut key = String::new();
    for part in out.split('_').filter(|p| !p.is_empty()) {
        if !key.is_empty() {
            key.push('_');
        }
        key.push_str(part);
    }
    if key.is_empty() { "value".into() } else { key }
}

/// Superscript digits for a power of ten: `-3` -> `⁻³`.
pub fn superscript(n: i64) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            '9' => '⁹',
            c => c,
        })
        .collect()
}

/// How an axis maps data to drawing coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Scale {
    Linear,
    Log,
    /// Symmetric log with linear threshold c: sign(v) log10(1 + |v|/c).
    SymLog(f64),
}

impl Scale {
    fn of(log: bool, symlog: Option<f64>) -> Scale {
        match (log, symlog) {
            (true, _) => Scale::Log,
            (false, Some(c)) if c > 0.0 && c.is_finite() => Scale::SymLog(c),
            _ => Scale::Linear,
        }
    }
    fn to_axis(self, v: f64) -> f64 {
        match self {
            Scale::Linear => v,
            Scale::Log => v.log10(),
            Scale::SymLog(c) => v.signum() * (v.abs() / c).ln_1p() / std::f64::consts::LN_10,
        }
    }
    fn to_data(self, t: f64) -> f64 {
        match self {
            Scale::Linear => t,
            Scale::Log => 10f64.powf(t),
            Scale::SymLog(c) => t.signum() * c * (10f64.powf(t.abs()) - 1.0),
        }
    }
}

/// A linear axis in drawing coordinates with the tick positions chosen by [`ticks`] (plotters'
/// own key points know nothing of log or symmetric-log labels).
struct TickedAxis {
    lo: f64,
    hi: f64,
    bold: Vec<f64>,
    light: Vec<f64>,
}

impl Ranged for TickedAxis {
    type ValueType = f64;
    type FormatOption = DefaultFormatting;
    /// As plotters' own f64 axis: linear from `lo` to `hi`.
    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        if self.hi == self.lo {
            return (limit.1 - limit.0) / 2;
        }
        let logic = (v - self.lo) / (self.hi - self.lo);
        let length = limit.1 - limit.0;
        if length == 0 {
            return limit.1;
        }
        if logic.is_infinite() {
            return if logic > 0.0 { limit.1 } else { limit.0 };
        }
        if length > 0 {
            limit.0 + (length as f64 * logic + 1e-3).floor() as i32
        } else {
            limit.0 + (length as f64 * logic - 1e-3).ceil() as i32
        }
    }
    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() { self.light.clone() } else { self.bold.clone() }
    }
    fn range(&self) -> std::ops::Range<f64> {
        self.lo..self.hi
    }
}

/// A "nice" tick step (1, 2 or 5 times a power of ten) for about `n` intervals over `span`.
fn nice_step(span: f64, n: f64) -> f64 {
    let raw = (span / n).max(f64::MIN_POSITIVE);
    let e = raw.log10().floor();
    let base = 10f64.powf(e);
    let m = raw / base;
    let k = if m <= 1.0 {
        1.0
    } else if m <= 2.0 {
        2.0
    } else if m <= 5.0 {
        5.0
    } else {
        10.0
    };
    k * base
}

/// The labelled (bold) and light tick positions of an axis over `[lo, hi]` in axis coordinates.
/// Linear: multiples of a nice step, light lines at a fifth of it. Log: every decade (every
/// second or more on long axes), 2 and 5 times a power of ten on axes shorter than about two
/// decades, light lines at 2..9 times each power. Symmetric log: 0 and plus and minus powers of ten.
fn ticks(scale: Scale, lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>) {
    let span = (hi - lo).abs().max(1e-300);
    let within = |v: &f64| *v >= lo - 1e-9 * span && *v <= hi + 1e-9 * span;
    match scale {
        Scale::Linear => {
            let step = nice_step(span, 10.0);
            let multiples = |step: f64| -> Vec<f64> {
                let (a, b) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
                if b < a || b - a > 10_000 {
                    return Vec::new();
                }
                (a..=b).map(|k| k as f64 * step).collect()
            };
            (multiples(step), multiples(step / 5.0))
        }
        Scale::Log => {
            let (a, b) = (lo.floor() as i64, hi.ceil() as i64);
            if b - a > 400 {
                return (Vec::new(), Vec::new());
            }
            let every = nice_step(hi - lo, 10.0).max(1.0) as i64;
            let mut bold: Vec<f64> = (a..=b).filter(|k| k.rem_euclid(every) == 0).map(|k| k as f64).collect();
            if hi - lo < 2.2 {
                for k in a..=b {
                    bold.extend([2.0f64, 5.0].map(|m| k as f64 + m.log10()));
                }
            }
            let mut light = Vec::new();
            if hi - lo <= 12.0 {
                for k in a..=b {
                    light.extend((1..10).map(|m| k as f64 + (m as f64).log10()));
                }
            }
            bold.retain(within);
            bold.sort_by(f64::total_cmp);
            light.retain(within);
            (bold, light)
        }
        Scale::SymLog(c) => {
            let top = scale.to_data(lo.abs().max(hi.abs()));
            // Labels from 10 c outwards: c itself sits too close to 0 to be labelled.
            let (k0, k1) = (c.log10().ceil() as i64 + 1, top.log10().ceil() as i64);
            let mut bold = vec![0.0];
            let mut light = Vec::new();
            let decades = (k1 - k0).clamp(0, 400);
            let every = (decades as f64 / 8.0).ceil().max(1.0) as i64;
            for k in k0..=k0 + decades {
                let p = 10f64.powi(k as i32);
                if (k - k0) % every == 0 {
                    bold.extend([scale.to_axis(p), scale.to_axis(-p)]);
                }
                for m in 2..10 {
                    light.extend([scale.to_axis(m as f64 * p), scale.to_axis(-(m as f64) * p)]);
                }
            }
            bold.retain(within);
            bold.sort_by(f64::total_cmp);
            light.retain(within);
            (bold, light)
        }
    }
}

/// `10ⁿ` (or `−10ⁿ`) when `v` is a power of ten within rounding, else `a·10ⁿ` with one decimal.
fn power_label(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let sign = if v < 0.0 { "−" } else { "" };
    let l = v.abs().log10();
    let e = l.round();
    if (l - e).abs() < 1e-6 {
        return format!("{sign}10{}", superscript(e as i64));
    }
    let e = l.floor();
    let m = v.abs() / 10f64.powf(e);
    format!("{sign}{}·10{}", (m * 10.0).round() / 10.0, superscript(e as i64))
}

/// A tick label, one format per axis (`lo`, `hi`: the axis range in drawing coordinates). Log
/// axis (`v` is log10 of the value): `10ⁿ` at decades; on a short axis (under about two decades)
/// 2 and 5 times a power of ten too, all as plain numbers when the whole axis lies within
/// 0.001-100000 (`20, 50, 100, 200`), else as `a·10ⁿ`. Symmetric-log axis: `0`, `10ⁿ`, `−10ⁿ`.
/// Linear axis: plain numbers, or `a·10ⁿ` for very large or small values.
fn tick_label(v: f64, scale: Scale, lo: f64, hi: f64) -> String {
    let span = (hi - lo).abs();
    match scale {
        Scale::Log => {
            let short = span <= 2.2;
            let plain = short && lo.min(hi) >= -3.0 && lo.max(hi) < 5.0;
            let r = v.round();
            let at_decade = (v - r).abs() < 1e-6;
            if plain {
                if !at_decade && !is_2_or_5(v) {
                    return String::new();
                }
                let x = 10f64.powf(v);
                // Rounded to 4 significant digits: 0.002, 50, 200.
                let decimals = (3.0 - x.log10().floor()).clamp(0.0, 8.0) as usize;
                let t = format!("{x:.decimals$}");
                return if t.contains('.') { t.trim_end_matches('0').trim_end_matches('.').to_string() } else { t };
            }
            if at_decade {
                return format!("10{}", superscript(r as i64));
            }
            if !short || !is_2_or_5(v) {
                return String::new();
            }
            power_label(10f64.powf(v))
        }
        Scale::SymLog(_) => {
            if v.abs() < 1e-9 {
                "0".into()
            } else {
                power_label(scale.to_data(v))
            }
        }
        Scale::Linear => {
            let a = v.abs();
            if a != 0.0 && !(1e-3..1e5).contains(&a) {
                power_label(v)
            } else {
                let r = (v * 1e6).round() / 1e6;
                // No "-0".
                format!("{}", if r == 0.0 { 0.0 } else { r }).replace('-', "−")
            }
        }
    }
}

/// Whether log10 value `v` is at 2 or 5 times a power of ten.
fn is_2_or_5(v: f64) -> bool {
    let m = 10f64.powf(v - v.floor());
    [2.0f64, 5.0].iter().any(|k| (m - k).abs() < 0.02 * k)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("stiction-plot-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn sample() -> Chart {
        Chart::new("Test chart", "load L (µN)", "friction F_f (µN)")
            .with(Series::line("model", (0..10).map(|i| (i as f64, (i * i) as f64)).collect()))
            .with(Series::markers("data", vec![(1.0, 1.2), (2.0, 3.9)]).with_y_err(vec![0.3, 0.4]))
            .with(Series::y_range("measured range", 2.0, 5.0))
    }

    #[test]
    fn writes_an_svg_with_the_labels_and_refuses_an_empty_chart() {
        let dir = tmp("svg");
        let path = dir.join("c.svg");
        sample().write(&path).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("Test chart") && svg.contains("friction F_f (µN)") && svg.contains("data"));
        // Legend swatch of the markers series is a marker: 2 data circles + 1 in the legend.
        // (the error bars draw open circles of their own; markers are filled)
        let filled = svg.split("<circle").skip(1).filter(|c| c.contains(r#"stroke="none""#)).count();
        assert_eq!(filled, 3, "{svg}");
        let empty = Chart { y_log: true, ..Chart::new("e", "x", "y") }.with(Series::line("neg", vec![(1.0, -1.0)]));
        assert!(matches!(empty.write_svg(&dir.join("e.svg")), Err(PlotError::Empty { .. })));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn unknown_extensions_are_errors_and_png_is_png() {
        let dir = tmp("fmt");
        let err = sample().write(&dir.join("p.txt")).unwrap_err();
        assert!(err.to_string().contains("\"txt\"") && err.to_string().contains(".svg or .png"), "{err}");
        assert!(!dir.join("p.txt").exists());
        sample().write(&dir.join("p.png")).unwrap();
        let bytes = std::fs::read(dir.join("p.png")).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        assert!(sample().sized(Some((100, 100)), None).is_err());
        assert!(sample().sized(None, Some(100.0)).is_err());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn the_data_csv_holds_every_plotted_number_with_units_in_the_header() {
        let dir = tmp("csv");
        let path = dir.join("fig.svg");
        let csv_path = sample().write_with_data(&path).unwrap();
        assert_eq!(csv_path, dir.join("fig.csv"));
        let text = std::fs::read_to_string(&csv_path).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next().unwrap(),
            "series,style,load_l_un,friction_f_f_un,load_l_un_err,friction_f_f_un_err,friction_f_f_un_upper,load_l_un_upper"
        );
        let rows: Vec<&str> = lines.collect();
        assert_eq!(rows.len(), 10 + 2 + 1);
        assert_eq!(rows[3], "model,line,3,9,,,,");
        assert_eq!(rows[11], "data,markers,2,3.9,,0.4,,");
        assert_eq!(rows[12], "measured range,y-range,,2,,,5,");
        // the JSON holds the same numbers under the same keys
        let json = sample().data_json();
        let data = &json["series"][1];
        assert_eq!(data["name"], "data");
        assert_eq!(data["friction_f_f_un_err"], serde_json::json!([0.3, 0.4]));
        assert_eq!(json["series"][2]["friction_f_f_un_upper"], serde_json::json!([5.0]));
        assert!(json["series"][0].get("load_l_un_err").is_none());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn log_ticks_use_one_format() {
        let log = Scale::Log;
        assert_eq!(tick_label(-3.0, log, -4.0, 0.0), "10⁻³");
        assert_eq!(tick_label(2.0, log, -1.0, 3.0), "10²");
        // between decades only on short axes: as a·10ⁿ far from 1, else plain numbers
        assert_eq!(tick_label(-4.0 + 2f64.log10(), log, -5.0, -3.0), "2·10⁻⁴");
        assert_eq!(tick_label(-4.0 + 2f64.log10(), log, -8.0, -3.0), "");
        assert_eq!(tick_label(1.0 + 2f64.log10(), log, 1.0, 2.5), "20");
        assert_eq!(tick_label(2.0, log, 1.0, 2.5), "100");
        assert_eq!(tick_label(-2.0 + 5f64.log10(), log, -2.1, -0.5), "0.05");
        assert_eq!(tick_label(2.5, Scale::Linear, 0.0, 10.0), "2.5");
        assert_eq!(tick_label(-2.5, Scale::Linear, -5.0, 5.0), "−2.5");
        assert_eq!(tick_label(3.2e-6, Scale::Linear, 0.0, 1e-5), "3.2·10⁻⁶");
        // the chosen ticks of a log axis: decades, and 2, 5 between them on short axes
        let (bold, light) = ticks(log, -1.35, 0.2);
        let labels: Vec<String> = bold.iter().map(|v| tick_label(*v, log, -1.35, 0.2)).collect();
        assert_eq!(labels, ["0.05", "0.1", "0.2", "0.5", "1"]);
        let labels: Vec<String> = bold.iter().map(|v| tick_label(*v - 5.0, log, -6.35, -4.8)).collect();
        assert_eq!(labels, ["5·10⁻⁷", "10⁻⁶", "2·10⁻⁶", "5·10⁻⁶", "10⁻⁵"]);
        assert!(light.len() > bold.len());
        let (bold, _) = ticks(log, -6.2, 0.3);
        assert_eq!(bold, [-6.0, -5.0, -4.0, -3.0, -2.0, -1.0, 0.0]);
        // symmetric log: 0 and signed powers of ten, both sides visible
        let sym = Scale::SymLog(1e-5);
        let (lo, hi) = (sym.to_axis(-0.03), sym.to_axis(1.0));
        let (bold, _) = ticks(sym, lo, hi);
        let labels: Vec<String> = bold.iter().map(|v| tick_label(*v, sym, lo, hi)).collect();
        assert_eq!(labels, ["−10⁻²", "−10⁻³", "−10⁻⁴", "0", "10⁻⁴", "10⁻³", "10⁻²", "10⁻¹", "10⁰"]);
        assert!((sym.to_data(sym.to_axis(-2e-5)) + 2e-5).abs() < 1e-18);
    }

    #[test]
    fn column_keys_are_ascii_with_units() {
        assert_eq!(column_key("V_pull² (V²)"), "v_pull2_v2");
        assert_eq!(column_key("apparent friction coefficient μ_e,a"), "apparent_friction_coefficient_mu_e_a");
        assert_eq!(column_key("load L (µN)"), "load_l_un");
    }
}
