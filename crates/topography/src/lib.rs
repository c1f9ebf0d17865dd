//! stiction-topography: measured and generated height maps, their summits and statistics.
//!
//! A researcher's measured topography (an AFM scan of a sidewall, an optical profiler map) enters
//! stiction here:
//!
//! * [`HeightMap`]: a regular grid of heights in metres (NaN = missing pixel), the hand-over type;
//! * readers ([`read_file`]): NumPy `.npy`, text/CSV grids with Gwyddion's ASCII export header,
//!   Gwyddion `.gsf`, x-y-z point lists, and instrument files (Bruker NanoScope, Igor binary wave,
//!   ISO 25178-71 SDF, ISO 25178-72 X3P, Digital Surf, Wyko OPD) by content, channel by channel; metadata from the file, else from
//!   [`MapMetadata`];
//! * preparation ([`prepare`]): levelling, Gaussian short- and long-wavelength cut-offs;
//! * summits ([`find_summits`]): 8-neighbour maxima with their curvature;
//! * statistics ([`statistics`], [`radial_psd`], [`autocorrelation`]) and Nayak's predictions;
//! * scenario sources ([`HeightMapSpec`]): a map's patch under the shoe, stated or random per seed;
//! * a generator of Gaussian random maps ([`generate`]): Gaussian ACF or self-affine PSD, seeded.
//!
//! All quantities are SI (metres) inside.

mod error;
mod fft;
mod formats;
mod generate;
mod length_unit;
mod map;
mod map_format;
mod prep;
mod read;
mod spec;
mod stats;
mod summits;
mod with_metadata;

pub use error::TopographyError;
pub use formats::nanoscope::NANOSCOPE_MAX_HEADER_BYTES;
pub use formats::x3p::X3P_MAX_XML_BYTES;
pub use formats::{ChannelChoice, ChannelInfo, ChannelSelector, MAX_NAME_CHARS, detect};
pub use generate::{GeneratorSpec, Spectrum, generate};
pub use map::{HeightMap, MAX_PIXELS, check_grid_size};
pub use prep::{Levelling, Preparation, PreparationReport, prepare};
pub use read::{
    ArrayLayout, BINARY_INPUT_LIMIT_BYTES, BorrowedHeights, GSF_MAX_HEADER_BYTES, MAX_HEIGHT_M, MAX_PIXEL_SIZE_M,
    MAX_UNIT_M, MIN_PIXEL_SIZE_M, MIN_UNIT_M, MapFormat, MapInfo, MapMetadata, MetaSource, NPY_MAX_HEADER_BYTES,
    NpyDtype, TEXT_INPUT_LIMIT_BYTES, list_channels, parse_length_unit, read_array, read_file, read_file_channel,
    read_gsf, read_instrument, read_instrument_in_parts, read_npy, read_text_grid, read_xyz, resolve_format,
};
pub use spec::{GeneratedMapSpec, HeightMapSpec, Patch, PatchSummits, choose_patch, patch_summits};
pub use stats::{
    Autocorrelation, Nayak, Psd, PsdWindow, Statistics, SummitStats, autocorrelation, radial_psd, statistics,
    summit_stats,
};
pub use summits::{Summits, find_summits, find_summits_in};
pub use with_metadata::{MapMetadataRead, read_map_with_metadata};
