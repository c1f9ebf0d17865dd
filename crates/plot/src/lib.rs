//! stiction-plot: plain-data charts and maps written as SVG or PNG by a small renderer of its own
//! (`canvas`: SVG to 0.01 px, anti-aliased PNG; text from the embedded DejaVu Sans, `text`), laid
//! out from the font and canvas size (`render`, `layout`, `axes`, [`Chart::layout`]), with their data beside them.
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

mod axes;
mod canvas;
mod chart;
mod data;
mod error;
mod layout;
mod map;
mod output;
mod png;
mod render;
mod scales;
pub mod style;
pub mod text;

pub use canvas::Rgb;
pub use chart::{Chart, LegendPosition, Series, SeriesStyle};
pub use data::column_key;
pub use error::PlotError;
pub use layout::{FONT_FLOOR, Layout, Rect, TextBox, default_font_px};
pub use map::{ImageMap, block_means};
pub use output::{Format, data_path};
pub use scales::superscript;
pub use style::Marker;

#[cfg(test)]
mod tests;
