//! A map with its metadata in one value, for callers that hand the heights on as an array
//! (the Python `read_map`): the heights in metres, row-major, and what the file said of them.

use std::path::Path;

use serde::Serialize;

use crate::TopographyError;
use crate::formats::{ChannelChoice, ChannelInfo, ChannelSelector};
use crate::map_format::MapFormat;
use crate::read::{MapInfo, MapMetadata, list_channels, read_file_channel};

/// What a file's map is, beside its heights: sizes in metres, the unit, the channel.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapMetadataRead {
    /// The format read (by the file's content).
    pub format: MapFormat,
    /// Columns (x) and rows (y) of the heights.
    pub nx: usize,
    /// Rows (y).
    pub ny: usize,
    /// Pixel size along x \[m\].
    pub pixel_size_x_m: f64,
    /// Pixel size along y \[m\].
    pub pixel_size_y_m: f64,
    /// The unit of the heights handed over: always `m` (the file's unit is `file_height_unit_m`).
    pub unit: &'static str,
    /// Metres per height unit of the file.
    pub file_height_unit_m: f64,
    /// Pixels without a height (NaN in the heights).
    pub missing_pixels: usize,
    /// The channel read (instrument files) and whether by default or as asked.
    pub channel: Option<ChannelChoice>,
    /// Every channel of the file (one for npy, gsf, text, xyz).
    pub channels: Vec<ChannelInfo>,
    /// How the metadata were had (`pixel_size_from`, `height_unit_from`).
    pub read: MapInfo,
}

/// Reads `path` (format by content, `channel` or the first height channel, metadata the file
/// lacks from `meta`) and returns its heights in metres, row-major (`iy * nx + ix`, NaN where
/// missing), moved out of the map without a copy, with the metadata.
pub fn read_map_with_metadata(
    path: &Path,
    format: Option<MapFormat>,
    channel: Option<&ChannelSelector>,
    meta: &MapMetadata,
) -> Result<(Vec<f64>, MapMetadataRead), TopographyError> {
    let (map, info) = read_file_channel(path, format, channel, meta)?;
    let (_, channels) = list_channels(path, Some(info.format), meta)?;
    let m = MapMetadataRead {
        format: info.format,
        nx: map.nx(),
        ny: map.ny(),
        pixel_size_x_m: map.dx_m(),
        pixel_size_y_m: map.dy_m(),
        unit: "m",
        file_height_unit_m: info.height_unit_m,
        missing_pixels: info.missing_pixels,
        channel: info.channel.clone(),
        channels,
        read: info,
    };
    Ok((map.into_heights_m(), m))
}
