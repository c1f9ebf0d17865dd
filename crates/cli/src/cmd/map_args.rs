//! The height-map flags shared by `stiction topography` and `stiction bem`: the file's metadata
//! (when the file does not state it) and the preparation (levelling and cut-offs). The reading
//! and the preparation themselves are the engine's (`stiction_engine::topography::read`,
//! `compose`).

use stiction_engine::topography::{Levelling, MapFormat, MapMetadata, Preparation, parse_length_unit};
use stiction_units::{Constraint, Dimension};

use crate::output::quantity;

/// Metadata and preparation of a height-map file.
#[derive(clap::Args, Debug, Clone)]
pub struct MapArgs {
    /// File format: npy, text, gsf, xyz, nanoscope, ibw, sdf, x3p, sur or opd (default: from the
    /// content, else the extension).
    #[arg(long, value_parser = |s: &str| s.parse::<MapFormat>())]
    pub format: Option<MapFormat>,
    /// Pixel size, when the file does not state it: "10 nm".
    #[arg(long, value_name = "L", value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub pixel_size: Option<f64>,
    /// Pixel size along y, if it differs from --pixel-size.
    #[arg(long, value_name = "L", value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub pixel_size_y: Option<f64>,
    /// Unit of the file's heights, when the file does not state it: "nm", "um", "m".
    #[arg(long, value_name = "U", value_parser = |s: &str| parse_length_unit(s))]
    pub height_unit: Option<f64>,
    /// Unit of the x and y coordinates of an xyz point list: "um".
    #[arg(long, value_name = "U", value_parser = |s: &str| parse_length_unit(s))]
    pub xy_unit: Option<f64>,
    /// Levelling: none, mean, plane, poly2, poly3.
    #[arg(long, default_value = "plane", value_parser = |s: &str| s.parse::<Levelling>())]
    pub level: Levelling,
    /// Short-wavelength cut-off (Gaussian low-pass, 50 % at this wavelength): "40 nm".
    #[arg(long, value_name = "L", value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub cutoff: Option<f64>,
    /// Long-wavelength cut-off (Gaussian high-pass, 50 % at this wavelength): "5 um".
    #[arg(long, value_name = "L", value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub long_cutoff: Option<f64>,
    /// Draw the maps (height, pressure, gap) in square blocks, each the mean of its grid cells,
    /// with at most N blocks along the longer side (16 to 100000); default: every grid cell,
    /// one image pixel each. Their data CSVs hold what is drawn.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(16..=100_000))]
    pub map_cells: Option<u32>,
}

impl MapArgs {
    /// The metadata given on the command line.
    pub fn metadata(&self) -> MapMetadata {
        MapMetadata {
            pixel_size_x_m: self.pixel_size,
            pixel_size_y_m: self.pixel_size_y,
            height_unit_m: self.height_unit,
            xy_unit_m: self.xy_unit,
        }
    }

    /// A row-major `nx x ny` field as drawn: `(block side, columns, rows, values)`, every cell
    /// (block side 1) unless --map-cells asks for block means ([`stiction_plot::block_means`]).
    pub fn drawn_cells(&self, values: &[f64], nx: usize, ny: usize) -> (usize, usize, usize, Vec<f64>) {
        let max = self.map_cells.map_or(nx.max(ny), |n| n as usize);
        stiction_plot::block_means(values, nx, ny, max)
    }

    /// The preparation asked for.
    pub fn preparation(&self) -> Preparation {
        Preparation { levelling: self.level, short_cutoff_m: self.cutoff, long_cutoff_m: self.long_cutoff }
    }
}
