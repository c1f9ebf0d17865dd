//! stiction-plot: plain-data charts written as SVG (and PNG) with plotters.
//!
//! Physics crates produce numbers; the command line builds a [`Chart`] from them and writes it.
//! Logarithmic axes are drawn by plotting log10 of the data on a linear axis and labelling the
//! ticks as powers of ten, so every chart uses one code path.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

mod map;
pub use map::ImageMap;

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SeriesStyle {
    /// A solid line through the points.
    #[default]
    Line,
    /// A dashed line through the points.
    Dashed,
    /// Markers only (measured data), with optional vertical error bars.
    Markers,
}

/// One named series of (x, y) points.
#[derive(Clone, Debug, Default)]
pub struct Series {
    /// Legend entry.
    pub name: String,
    /// The points, in the chart's units.
    pub points: Vec<(f64, f64)>,
    /// Half-lengths of vertical error bars, one per point.
    pub y_err: Option<Vec<f64>>,
    /// Line, dashed line or markers.
    pub style: SeriesStyle,
}

impl Series {
    /// A solid line.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series { name: name.into(), points, y_err: None, style: SeriesStyle::Line }
    }
    /// A dashed line.
    pub fn dashed(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series { name: name.into(), points, y_err: None, style: SeriesStyle::Dashed }
    }
    /// Markers (measured points).
    pub fn markers(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series { name: name.into(), points, y_err: None, style: SeriesStyle::Markers }
    }
    /// Adds vertical error bars (half-lengths).
    pub fn with_y_err(mut self, y_err: Vec<f64>) -> Self {
        self.y_err = Some(y_err);
        self
    }
}

/// A single-panel x-y chart.
#[derive(Clone, Debug, Default)]
pub struct Chart {
    /// Title above the plot.
    pub title: String,
    /// x-axis label with its unit.
    pub x_label: String,
    /// y-axis label with its unit.
    pub y_label: String,
    /// Logarithmic x axis (all x must be positive).
    pub x_log: bool,
    /// Logarithmic y axis (all y must be positive).
    pub y_log: bool,
    /// The data.
    pub series: Vec<Series>,
    /// Optional fixed x range (in data units).
    pub x_range: Option<(f64, f64)>,
    /// Optional fixed y range (in data units).
    pub y_range: Option<(f64, f64)>,
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
    /// The drawing backend failed (file not writable, font missing).
    #[error("could not draw {path}: {message}")]
    Backend {
        /// Output path.
        path: String,
        /// Backend message.
        message: String,
    },
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

    /// Writes the chart as SVG (800 x 560 px).
    pub fn write_svg(&self, path: &Path) -> Result<(), PlotError> {
        let root = SVGBackend::new(path, (800, 560)).into_drawing_area();
        self.draw(root, path)
    }

    /// Writes the chart as PNG (1200 x 840 px).
    pub fn write_png(&self, path: &Path) -> Result<(), PlotError> {
        let root = BitMapBackend::new(path, (1200, 840)).into_drawing_area();
        self.draw(root, path)
    }

    fn tx(&self, x: f64) -> f64 {
        if self.x_log { x.log10() } else { x }
    }
    fn ty(&self, y: f64) -> f64 {
        if self.y_log { y.log10() } else { y }
    }

    /// The data range after the log transform, padded by 4 %.
    fn ranges(&self) -> Option<((f64, f64), (f64, f64))> {
        let mut xs = (f64::INFINITY, f64::NEG_INFINITY);
        let mut ys = (f64::INFINITY, f64::NEG_INFINITY);
        for s in &self.series {
            for (i, &(x, y)) in s.points.iter().enumerate() {
                let (x, y) = (self.tx(x), self.ty(y));
                if !(x.is_finite() && y.is_finite()) {
                    continue;
                }
                let e = s.y_err.as_ref().and_then(|e| e.get(i)).copied().unwrap_or(0.0);
                xs = (xs.0.min(x), xs.1.max(x));
                let (lo, hi) = if self.y_log { (y, y) } else { (y - e, y + e) };
                ys = (ys.0.min(lo), ys.1.max(hi));
            }
        }
        if let Some((a, b)) = self.x_range {
            xs = (self.tx(a), self.tx(b));
        }
        if let Some((a, b)) = self.y_range {
            ys = (self.ty(a), self.ty(b));
        }
        if !(xs.0.is_finite() && ys.0.is_finite()) {
            return None;
        }
        let pad = |(lo, hi): (f64, f64)| {
            let span = if hi > lo { hi - lo } else { lo.abs().max(1e-300) };
            (lo - 0.04 * span, hi + 0.04 * span)
        };
        Some((if self.x_range.is_some() { xs } else { pad(xs) }, if self.y_range.is_some() { ys } else { pad(ys) }))
    }

    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>, path: &Path) -> Result<(), PlotError> {
        let backend_err =
            |e: &dyn std::fmt::Display| PlotError::Backend { path: path.display().to_string(), message: e.to_string() };
        let ((x0, x1), (y0, y1)) = self.ranges().ok_or_else(|| PlotError::Empty { title: self.title.clone() })?;
        root.fill(&WHITE).map_err(|e| backend_err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, ("sans-serif", 22))
            .margin(14)
            .x_label_area_size(52)
            .y_label_area_size(78)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| backend_err(&e))?;
        let (x_log, y_log) = (self.x_log, self.y_log);
        let x_fmt = move |v: &f64| tick_label(*v, x_log);
        let y_fmt = move |v: &f64| tick_label(*v, y_log);
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .label_style(("sans-serif", 15))
            .axis_desc_style(("sans-serif", 17))
            .light_line_style(RGBColor(0xee, 0xee, 0xee))
            .draw()
            .map_err(|e| backend_err(&e))?;
        for (k, s) in self.series.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .map(|&(x, y)| (self.tx(x), self.ty(y)))
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .collect();
            let anno = match s.style {
                SeriesStyle::Line => {
                    chart.draw_series(LineSeries::new(pts, color.stroke_width(2))).map_err(|e| backend_err(&e))?
                }
                SeriesStyle::Dashed => chart
                    .draw_series(DashedLineSeries::new(pts, 8, 5, color.stroke_width(2)))
                    .map_err(|e| backend_err(&e))?,
                SeriesStyle::Markers => {
                    if let Some(err) = &s.y_err {
                        let bars: Vec<_> = s
                            .points
                            .iter()
                            .zip(err)
                            .filter(|((x, y), e)| x.is_finite() && y.is_finite() && e.is_finite())
                            .map(|(&(x, y), &e)| {
                                let (lo, hi) = (self.ty(y - e), self.ty(y + e));
                                let lo = if lo.is_finite() { lo } else { y0 };
                                ErrorBar::new_vertical(self.tx(x), lo, self.ty(y), hi, color.stroke_width(1), 8)
                            })
                            .collect();
                        chart.draw_series(bars).map_err(|e| backend_err(&e))?;
                    }
                    chart
                        .draw_series(pts.into_iter().map(|p| Circle::new(p, 4, color.filled())))
                        .map_err(|e| backend_err(&e))?
                }
            };
            if !s.name.is_empty() {
                anno.label(s.name.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(3)));
            }
        }
        if self.series.iter().any(|s| !s.name.is_empty()) {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.4))
                .label_font(("sans-serif", 15))
                .position(SeriesLabelPosition::UpperLeft)
                .draw()
                .map_err(|e| backend_err(&e))?;
        }
        root.present().map_err(|e| backend_err(&e))?;
        Ok(())
    }
}

/// A tick label: a plain number, or 10^v on a log axis.
fn tick_label(v: f64, log: bool) -> String {
    if log {
        let r = v.round();
        let x = 10f64.powf(v);
        if (v - r).abs() < 1e-9 {
            format!("1e{}", r as i64)
        } else if (0.01..1e4).contains(&x) {
            format!("{x:.2}")
        } else {
            format!("{x:.1e}")
        }
    } else {
        let a = v.abs();
        if a != 0.0 && !(1e-3..1e5).contains(&a) { format!("{v:.1e}") } else { format!("{}", (v * 1e6).round() / 1e6) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_an_svg_with_the_labels_and_refuses_an_empty_chart() {
        let dir = std::env::temp_dir().join(format!("stiction-plot-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("c.svg");
        let chart = Chart::new("Test chart", "load L (uN)", "friction F_f (uN)")
            .with(Series::line("model", (0..10).map(|i| (i as f64, (i * i) as f64)).collect()))
            .with(Series::markers("data", vec![(1.0, 1.2), (2.0, 3.9)]).with_y_err(vec![0.3, 0.4]));
        chart.write_svg(&path).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("Test chart") && svg.contains("friction F_f (uN)") && svg.contains("data"));
        let empty = Chart { y_log: true, ..Chart::new("e", "x", "y") }.with(Series::line("neg", vec![(1.0, -1.0)]));
        assert!(matches!(empty.write_svg(&dir.join("e.svg")), Err(PlotError::Empty { .. })));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn log_tick_labels_are_powers_of_ten() {
        assert_eq!(tick_label(-3.0, true), "1e-3");
        assert_eq!(tick_label(-3.5, true), "3.2e-4");
        assert_eq!(tick_label(-0.5, true), "0.32");
        assert_eq!(tick_label(2.5, false), "2.5");
    }
}
