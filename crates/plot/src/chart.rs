//! The chart as plain data: its series ([`Series`], drawn as a [`SeriesStyle`]), axes, legend and
//! size ([`Chart`]), built in builder style, and the axis scales it maps data with.

use crate::error::PlotError;
use crate::scales::Scale;
use crate::style::Marker;

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
