//! stiction-plot: plain-data charts and maps written as SVG or PNG by a small renderer of its own
//! (`canvas`: SVG to 0.01 px, anti-aliased PNG; text from the embedded DejaVu Sans, `text`), laid
//! out from the font and canvas size (`render`, [`Chart::layout`]), with their data beside them.
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
//! a marker, or a shaded patch for bands and reference ranges. A series keeps its colour and marker
//! by name in every figure ([`style`]); symbols in text are typeset ([`text`]: `F_a0`, `μ_e,a`).
//!
//! Data CSV ([`Chart::data_csv`]): columns `series` (the legend name), `style`, x and y with their
//! units in the names, x and y error half-lengths, a band's upper edge and a range's upper end; one
//! row per point, values in the axes' units written as the shortest decimal that reads back to the
//! same f64; an empty cell means no value (the column does not apply, or the value is not finite
//! and is not drawn).

use std::path::{Path, PathBuf};

mod canvas;
mod map;
mod render;
pub mod style;
pub mod text;
pub use canvas::Rgb;
pub use map::{ImageMap, block_means};
pub use render::{FONT_FLOOR, Layout, Rect, TextBox, default_font_px};
pub use style::Marker;

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
    /// Colour index into the palette, for a series the style registry does not know (a series
    /// whose key or name the registry knows always takes the registry's colour, see [`style`]);
    /// default: the next palette colour.
    pub color: Option<usize>,
    /// Style key in the registry ([`style::STYLES`], e.g. `measured`, `explicit`, `gw-dmt`);
    /// default: looked up from the name.
    pub key: Option<String>,
    /// Marker shape (default: from the registry, else a circle).
    pub marker: Option<Marker>,
    /// Drawn after every other series (the measured or best series).
    pub on_top: bool,
    /// What each point is (one per point, e.g. the input a Sobol index belongs to): the data CSV's
    /// `label` column, present when any series of the chart has labels.
    pub labels: Option<Vec<String>>,
    /// Markers only: drawn shifted sideways by this fraction of the plot's width (a "dodge", so
    /// that series of nearly equal values at the same x stay apart); the data and its CSV keep the
    /// true x.
    pub dodge: f64,
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
    /// Names each point (one label per point; the data CSV's `label` column).
    pub fn with_labels(mut self, labels: Vec<String>) -> Self {
        self.labels = Some(labels);
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
    /// Styles the series as registry entry `key` (colour, marker, drawn on top for `measured`).
    pub fn keyed(mut self, key: impl Into<String>) -> Self {
        self.key = Some(key.into());
        self
    }
    /// Draws the series after every other one (the measured or best series).
    pub fn on_top(mut self) -> Self {
        self.on_top = true;
        self
    }
    /// Draws the markers in this shape.
    pub fn with_marker(mut self, marker: Marker) -> Self {
        self.marker = Some(marker);
        self
    }
    /// Draws the markers (and their error bars) shifted sideways by `fraction` of the plot's
    /// width; the data keep their x (see [`Series::dodge`]).
    pub fn with_dodge(mut self, fraction: f64) -> Self {
        self.dodge = fraction;
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
    /// Title above the plot: what the data are (wrapped to the canvas width).
    pub title: String,
    /// Caption below the figure (what a reader must know to read it), wrapped to the canvas
    /// width; `\n` starts a new line.
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
    /// Figure size in px of 1/96 in (default 800 x 560; a PNG has 1.5 times as many pixels
    /// unless `dpi` is set).
    pub size_px: Option<(u32, u32)>,
    /// Figure size in millimetres on the page (overrides `size_px`): the SVG declares it, the PNG
    /// has it at `dpi` (default 300).
    pub size_mm: Option<(f64, f64)>,
    /// PNG resolution, pixels per inch of the figure's size (1 px of `size_px` is 1/96 in).
    pub dpi: Option<f64>,
    /// Tick label font size in px of 1/96 in (0.75 pt; default [`default_font_px`]: 15 px at
    /// 800 x 560 px, less on a smaller canvas down to 8 pt, and 8 pt at a physical size);
    /// titles, labels, legend and caption scale with it.
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

    /// Sets the caption below the figure (builder style).
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.note = Some(note.into());
        self
    }

    /// Sets the caption below the figure (builder style; the same as [`Chart::with_note`]).
    pub fn with_caption(mut self, caption: impl Into<String>) -> Self {
        self.note = Some(caption.into());
        self
    }

    /// Sets a size on the page in millimetres and the PNG resolution, checked: sides 20-1000 mm,
    /// 50-2400 dpi.
    pub fn physical(mut self, size_mm: (f64, f64), dpi: Option<f64>) -> Result<Self, PlotError> {
        for (what, v) in [("width", size_mm.0), ("height", size_mm.1)] {
            if !(20.0..=1000.0).contains(&v) {
                return Err(PlotError::Option { what, value: v, expected: "20 to 1000 mm" });
            }
        }
        if let Some(d) = dpi
            && !(50.0..=2400.0).contains(&d)
        {
            return Err(PlotError::Option { what: "dpi", value: d, expected: "50 to 2400" });
        }
        self.size_mm = Some(size_mm);
        self.dpi = dpi.or(self.dpi);
        Ok(self)
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

    /// The chart as SVG text: coordinates to 0.01 px, text in the embedded font's family, the
    /// physical size declared when `size_mm` is set.
    pub fn svg_text(&self) -> Result<String, PlotError> {
        let (prims, layout) = self.render()?;
        let physical = self.size_mm.map(|(w, h)| (format!("{}mm", mm(w)), format!("{}mm", mm(h))));
        Ok(canvas::svg(&prims, layout.width, layout.height, physical))
    }

    /// Writes the chart as SVG, atomically.
    pub fn write_svg(&self, path: &Path) -> Result<(), PlotError> {
        let text = self.svg_text()?;
        stiction_units::io::write_atomic(path, text.as_bytes())?;
        Ok(())
    }

    /// The PNG size in pixels: the canvas times [`Chart::png_scale`].
    pub fn png_size(&self) -> (u32, u32) {
        let (w, h) = self.canvas_px();
        let s = self.png_scale();
        ((w * s).round().max(1.0) as u32, (h * s).round().max(1.0) as u32)
    }

    /// Writes the chart as PNG (default 1200 x 840 px), atomically.
    pub fn write_png(&self, path: &Path) -> Result<(), PlotError> {
        let (prims, _) = self.render()?;
        let (w, h) = self.png_size();
        let dpi = self.png_scale() * 96.0;
        write_raster(path, &prims, w, h, self.png_scale(), dpi)
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

    /// The plotted numbers as CSV: one row per point, columns `series`, `style`, (`label` when a
    /// series names its points), x and y with their
    /// units, the error bars, band edges and span ends where a series has them
    /// ([`Chart::data_columns`]).
    pub fn data_csv(&self) -> String {
        let mut w = csv::Writer::from_writer(Vec::new());
        let mut header = vec!["series".to_string(), "style".into()];
        let labelled = self.series.iter().any(|s| s.labels.is_some());
        if labelled {
            header.push("label".into());
        }
        header.extend(self.data_columns());
        // Writing to a Vec cannot fail.
        w.write_record(&header).ok();
        let num = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
        for s in &self.series {
            for (i, row) in Self::rows(s).into_iter().enumerate() {
                let mut rec = vec![s.name.clone(), s.style.name().to_string()];
                if labelled {
                    rec.push(s.labels.as_ref().and_then(|l| l.get(i)).cloned().unwrap_or_default());
                }
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

    pub(crate) fn tx(&self, x: f64) -> f64 {
        self.x_scale().to_axis(x)
    }
    pub(crate) fn ty(&self, y: f64) -> f64 {
        self.y_scale().to_axis(y)
    }
    pub(crate) fn x_scale(&self) -> Scale {
        Scale::of(self.x_log, self.x_symlog)
    }
    pub(crate) fn y_scale(&self) -> Scale {
        Scale::of(self.y_log, self.y_symlog)
    }

    /// The data range after the log transform, padded by 4 %.
    pub(crate) fn ranges(&self) -> Option<((f64, f64), (f64, f64))> {
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
}

/// A millimetre value as written in an SVG size (to 0.01 mm).
fn mm(v: f64) -> String {
    format!("{}", (v * 100.0).round() / 100.0)
}

/// Rasterises a display list and writes it as PNG, atomically.
fn write_raster(path: &Path, prims: &[canvas::Prim], w: u32, h: u32, scale: f64, dpi: f64) -> Result<(), PlotError> {
    if (w as u64) * (h as u64) > 80_000_000 {
        return Err(PlotError::Option {
            what: "PNG pixel count",
            value: (w as f64) * (h as f64),
            expected: "at most 80 million",
        });
    }
    let mut r = canvas::Raster::new(w as usize, h as usize, scale);
    r.draw(prims);
    let rgb = r.into_rgb();
    let mut png = Vec::new();
    encode_png_dpi(&rgb, w, h, Some(dpi), &mut png).map_err(|e| PlotError::Backend {
        path: path.display().to_string(),
        message: format!("PNG encoding failed: {e}"),
    })?;
    stiction_units::io::write_atomic(path, &png)?;
    Ok(())
}

/// Encodes an RGB8 buffer as PNG.
pub(crate) fn encode_png(rgb: &[u8], w: u32, h: u32, out: &mut Vec<u8>) -> Result<(), String> {
    encode_png_dpi(rgb, w, h, None, out)
}

/// Encodes an RGB8 buffer as PNG, with a `pHYs` chunk stating `dpi` when given (so a word
/// processor places the figure at its physical size).
fn encode_png_dpi(rgb: &[u8], w: u32, h: u32, dpi: Option<f64>, out: &mut Vec<u8>) -> Result<(), String> {
    use image::ImageEncoder;
    let mut plain = Vec::new();
    image::codecs::png::PngEncoder::new(&mut plain)
        .write_image(rgb, w, h, image::ColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    let Some(dpi) = dpi else {
        *out = plain;
        return Ok(());
    };
    // Insert pHYs (pixels per metre) after IHDR: signature 8 bytes, IHDR chunk 25 bytes.
    let ppm = (dpi / 0.0254).round() as u32;
    let mut chunk = Vec::with_capacity(21);
    chunk.extend_from_slice(&9u32.to_be_bytes());
    let mut body = b"pHYs".to_vec();
    body.extend_from_slice(&ppm.to_be_bytes());
    body.extend_from_slice(&ppm.to_be_bytes());
    body.push(1);
    chunk.extend_from_slice(&body);
    chunk.extend_from_slice(&crc32(&body).to_be_bytes());
    out.clear();
    out.extend_from_slice(&plain[..33]);
    out.extend_from_slice(&chunk);
    out.extend_from_slice(&plain[33..]);
    Ok(())
}

/// CRC-32 (ISO 3309) of a PNG chunk's type and data.
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = 0xffff_ffffu32;
    for &b in bytes {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 { 0xedb8_8320 ^ (c >> 1) } else { c >> 1 };
        }
    }
    !c
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
pub(crate) enum Scale {
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
    pub(crate) fn to_axis(self, v: f64) -> f64 {
        match self {
            Scale::Linear => v,
            Scale::Log => v.log10(),
            Scale::SymLog(c) => v.signum() * (v.abs() / c).ln_1p() / std::f64::consts::LN_10,
        }
    }
    pub(crate) fn to_data(self, t: f64) -> f64 {
        match self {
            Scale::Linear => t,
            Scale::Log => 10f64.powf(t),
            Scale::SymLog(c) => t.signum() * c * (10f64.powf(t.abs()) - 1.0),
        }
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

/// The labelled (bold) and light tick positions of an axis over `[lo, hi]` in axis coordinates,
/// about `n` labelled intervals. Linear: multiples of a nice step, light lines at a fifth of it. Log: every decade (every
/// second or more on long axes), 2 and 5 times a power of ten on axes shorter than about two
/// decades, light lines at 2..9 times each power. Symmetric log: 0 and plus and minus powers of
/// ten, every one or every few decades counted from the largest.
pub(crate) fn ticks(scale: Scale, lo: f64, hi: f64, n: f64) -> (Vec<f64>, Vec<f64>) {
    let span = (hi - lo).abs().max(1e-300);
    let within = |v: &f64| *v >= lo - 1e-9 * span && *v <= hi + 1e-9 * span;
    match scale {
        Scale::Linear => {
            let step = nice_step(span, n);
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
            let every = nice_step(hi - lo, n).max(1.0) as i64;
            let mut bold: Vec<f64> = (a..=b).filter(|k| k.rem_euclid(every) == 0).map(|k| k as f64).collect();
            if hi - lo < 2.2 && n >= 4.0 {
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
            let every = (decades as f64 / (n * 0.8).max(1.0)).ceil().max(1.0) as i64;
            // Every `every`-th decade counted down from the largest on the axis, none closer to 0
            // than three quarters of the spacing (its label would touch the 0).
            let kt = top.log10().floor() as i64;
            for k in k0..=k0 + decades {
                let p = 10f64.powi(k as i32);
                if (kt - k).rem_euclid(every) == 0 && scale.to_axis(p) >= 0.75 * every as f64 {
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
pub(crate) fn tick_label(v: f64, scale: Scale, lo: f64, hi: f64) -> String {
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

    /// A dodge draws the markers (and their error bars) shifted by its fraction of the plot's
    /// width, and the data CSV keeps the true x: two series at the same point stay apart.
    #[test]
    fn a_dodge_shifts_the_drawn_markers_not_the_data() {
        let chart = |dodge: f64| {
            let mut c = Chart::new("dodge", "x", "y")
                .with(Series::markers("a", vec![(1.0, 1.0), (2.0, 2.0)]).with_y_err(vec![0.1, 0.1]).with_dodge(dodge));
            // (Room on both sides, so that no shifted position leaves the axes.)
            c.x_range = Some((0.0, 3.0));
            c.y_range = Some((0.0, 3.0));
            c
        };
        let (plain, moved) = (chart(0.0), chart(0.05));
        let (lp, lm) = (plain.layout().unwrap(), moved.layout().unwrap());
        assert_eq!(lp.plot, lm.plot);
        let shift = 0.05 * lp.plot.width();
        // Markers and the sampled error bars: every drawn position moves by the shift, none stays.
        assert_eq!(lp.points.len(), lm.points.len());
        for (a, b) in lp.points.iter().zip(&lm.points) {
            assert!((b.0 - a.0 - shift).abs() < 1e-9 && (b.1 - a.1).abs() < 1e-9, "{a:?} -> {b:?}");
        }
        assert_eq!(plain.data_csv(), moved.data_csv());
    }

    #[test]
    fn writes_an_svg_with_the_labels_and_refuses_an_empty_chart() {
        let dir = tmp("svg");
        let path = dir.join("c.svg");
        sample().write(&path).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("Test chart") && svg.contains("friction F<tspan") && svg.contains("data"));
        assert!(!svg.contains("F_f"), "no literal underscore: {svg}");
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
        let (bold, light) = ticks(log, -1.35, 0.2, 10.0);
        let labels: Vec<String> = bold.iter().map(|v| tick_label(*v, log, -1.35, 0.2)).collect();
        assert_eq!(labels, ["0.05", "0.1", "0.2", "0.5", "1"]);
        let labels: Vec<String> = bold.iter().map(|v| tick_label(*v - 5.0, log, -6.35, -4.8)).collect();
        assert_eq!(labels, ["5·10⁻⁷", "10⁻⁶", "2·10⁻⁶", "5·10⁻⁶", "10⁻⁵"]);
        assert!(light.len() > bold.len());
        let (bold, _) = ticks(log, -6.2, 0.3, 10.0);
        assert_eq!(bold, [-6.0, -5.0, -4.0, -3.0, -2.0, -1.0, 0.0]);
        // symmetric log: 0 and signed powers of ten, both sides visible
        let sym = Scale::SymLog(1e-5);
        let (lo, hi) = (sym.to_axis(-0.03), sym.to_axis(1.0));
        let (bold, _) = ticks(sym, lo, hi, 10.0);
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
