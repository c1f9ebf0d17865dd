//! Writing a chart: the format from the extension ([`Format`]), SVG text and PNG rasters, and the
//! data CSV beside the figure ([`data_path`]); files are written atomically.

use std::path::{Path, PathBuf};

use crate::canvas;
use crate::chart::Chart;
use crate::error::PlotError;
use crate::png::encode_png_dpi;

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
}

/// A millimetre value as written in an SVG size (to 0.01 mm).
pub(crate) fn mm(v: f64) -> String {
    format!("{}", (v * 100.0).round() / 100.0)
}

/// Rasterises a display list and writes it as PNG, atomically.
pub(crate) fn write_raster(
    path: &Path,
    prims: &[canvas::Prim],
    w: u32,
    h: u32,
    scale: f64,
    dpi: f64,
) -> Result<(), PlotError> {
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
