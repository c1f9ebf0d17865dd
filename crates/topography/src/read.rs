//! Readers (and writers) of height-map files: NumPy `.npy`, text/CSV grids (with Gwyddion's ASCII
//! export header), Gwyddion simple field `.gsf`, and x-y-z point lists on a regular grid.
//!
//! Metadata (pixel size, height unit) comes from the file where the format has it, else from
//! [`MapMetadata`] (command-line flags or scenario fields); where both give a value they must agree
//! (relative difference <= 1e-6), and where neither does, the error says what is missing and how
//! to give it. Sizes are checked against [`crate::MAX_PIXELS`] before a grid is allocated.
//!
//! The `.npy` header is parsed by hand (about 60 lines): the format is a fixed magic, a length and
//! a Python dict literal with three keys (NumPy's NEP 1), and the maintained crates that read it
//! (`npyz`, `ndarray-npy`) bring an array library or a generic reader framework for that.

use std::path::Path;
use std::str::FromStr;

use serde::Serialize;
use stiction_units::text::{MAX_LINE_BYTES, check_line_bytes, check_lines, excerpt};
use stiction_units::{Dimension, parse_quantity};

use crate::formats::parts::{ByteSource, HEADER_PREFIX_BYTES, HeightTally, check_channel, decode_channel, raster_span};
use crate::formats::{Channel, ChannelChoice, ChannelInfo, ChannelSelector};
use crate::map::check_grid_size;
use crate::{HeightMap, MAX_PIXELS, TopographyError};

/// Size limit of a text input file (grid or point list): 1 GiB.
pub const TEXT_INPUT_LIMIT_BYTES: u64 = 1 << 30;
/// Size limit of a binary input file: [`MAX_PIXELS`] float64 values and 1 MiB of header.
pub const BINARY_INPUT_LIMIT_BYTES: u64 = MAX_PIXELS * 8 + (1 << 20);

pub use crate::map_format::MapFormat;

impl std::fmt::Display for MapFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for MapFormat {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "npy" => Ok(MapFormat::Npy),
            "text" | "csv" => Ok(MapFormat::Text),
            "gsf" => Ok(MapFormat::Gsf),
            "xyz" => Ok(MapFormat::Xyz),
            "nanoscope" => Ok(MapFormat::Nanoscope),
            "ibw" => Ok(MapFormat::Ibw),
            "sdf" => Ok(MapFormat::Sdf),
            "x3p" => Ok(MapFormat::X3p),
            "sur" => Ok(MapFormat::Sur),
            "opd" => Ok(MapFormat::Opd),
            "plu" => Ok(MapFormat::Plu),
            "metropro" => Ok(MapFormat::Metropro),
            "netcdf" => Ok(MapFormat::Netcdf),
            "wsxm" => Ok(MapFormat::Wsxm),
            "mi" => Ok(MapFormat::Mi),
            "nid" => Ok(MapFormat::Nid),
            "al3d" => Ok(MapFormat::Al3d),
            "park" => Ok(MapFormat::Park),
            _ => Err(format!(
                "unknown height-map format `{s}`: expected npy, text, gsf, xyz, nanoscope, ibw, sdf, x3p, sur, opd, plu, metropro, netcdf, wsxm, mi, nid, al3d or park"
            )),
        }
    }
}

/// Metadata given outside the file (flags, scenario fields), SI.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MapMetadata {
    /// Pixel size along x \[m\].
    pub pixel_size_x_m: Option<f64>,
    /// Pixel size along y \[m\] (default: the x pixel size).
    pub pixel_size_y_m: Option<f64>,
    /// Metres per height unit of the file's numbers (1e-9 for heights in nm).
    pub height_unit_m: Option<f64>,
    /// Metres per unit of the x and y coordinates of a point list (xyz only).
    pub xy_unit_m: Option<f64>,
}

/// Where a piece of metadata came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MetaSource {
    /// The file's header.
    File,
    /// A flag or scenario field.
    Given,
    /// Both, and they agree.
    FileAndGiven,
}

/// What a reader found besides the heights.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapInfo {
    /// The format read.
    pub format: MapFormat,
    /// Where the pixel size came from.
    pub pixel_size_from: MetaSource,
    /// Where the height unit came from.
    pub height_unit_from: MetaSource,
    /// Metres per height unit of the file.
    pub height_unit_m: f64,
    /// Pixels without a height (NaN in the file, masked in an instrument file, or absent from a
    /// point list).
    pub missing_pixels: usize,
    /// The channel read from a multi-channel instrument file, and whether by default or as asked.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub channel: Option<ChannelChoice>,
}

pub use crate::length_unit::parse_length_unit;

fn resolve(
    origin: &str,
    from_file: Option<f64>,
    given: Option<f64>,
    what: &str,
    how: &str,
) -> Result<(f64, MetaSource), TopographyError> {
    match (from_file, given) {
        (Some(f), Some(g)) => {
            if (f - g).abs() <= 1e-6 * f.abs().max(g.abs()) {
                Ok((f, MetaSource::FileAndGiven))
            } else {
                Err(TopographyError::invalid(
                    what,
                    format!("{g:e} m (given)"),
                    format!("the value in {origin}, {f:e} m (remove the flag or field, or fix the file)"),
                ))
            }
        }
        (Some(f), None) => Ok((f, MetaSource::File)),
        (None, Some(g)) => Ok((g, MetaSource::Given)),
        (None, None) => Err(TopographyError::MissingMetadata {
            origin: origin.to_string(),
            missing: format!("the {what} (the file does not state it): {how}"),
        }),
    }
}

const PIXEL_HOW: &str = "give it with --pixel-size (e.g. \"10 nm\") or the scenario field `pixel_size`";
const UNIT_HOW: &str = "give it with --height-unit (e.g. \"nm\") or the scenario field `height_unit`";

/// Resolves the pixel sizes (x, y) and height unit and builds the map.
#[allow(clippy::too_many_arguments)] // one private helper shared by the four readers
fn finish(
    origin: &str,
    format: MapFormat,
    nx: usize,
    ny: usize,
    file_dx: Option<f64>,
    file_dy: Option<f64>,
    file_unit: Option<f64>,
    meta: &MapMetadata,
    heights: Vec<f64>,
) -> Result<(HeightMap, MapInfo), TopographyError> {
    finish_scaled(origin, format, nx, ny, file_dx, file_dy, file_unit, meta, heights, false)
}

/// [`finish`], for heights already in metres when `in_metres` (scaled while decoded).
#[allow(clippy::too_many_arguments)]
fn finish_scaled(
    origin: &str,
    format: MapFormat,
    nx: usize,
    ny: usize,
    file_dx: Option<f64>,
    file_dy: Option<f64>,
    file_unit: Option<f64>,
    meta: &MapMetadata,
    mut heights: Vec<f64>,
    in_metres: bool,
) -> Result<(HeightMap, MapInfo), TopographyError> {
    let resolved = resolve_meta(origin, file_dx, file_dy, file_unit, meta)?;
    if resolved.unit != 1.0 && !in_metres {
        for h in &mut heights {
            *h *= resolved.unit;
        }
    }
    let mut tally = HeightTally::default();
    tally.add(&heights);
    build(origin, format, nx, ny, &resolved, heights, tally)
}

/// The pixel sizes and the height unit, from the file or `meta`, checked.
struct Resolved {
    dx: f64,
    dy: f64,
    pixel_from: MetaSource,
    unit: f64,
    unit_from: MetaSource,
}

fn resolve_meta(
    origin: &str,
    file_dx: Option<f64>,
    file_dy: Option<f64>,
    file_unit: Option<f64>,
    meta: &MapMetadata,
) -> Result<Resolved, TopographyError> {
    let (dx, src_x) = resolve(origin, file_dx, meta.pixel_size_x_m, "pixel size", PIXEL_HOW)?;
    let given_dy = meta.pixel_size_y_m.or(meta.pixel_size_x_m);
    let (dy, _) = resolve(origin, file_dy.or(file_dx), given_dy, "pixel size along y", PIXEL_HOW)?;
    let (unit, src_u) = resolve(origin, file_unit, meta.height_unit_m, "height unit", UNIT_HOW)?;
    for (what, d) in [("pixel size", dx), ("pixel size along y", dy)] {
        if !(MIN_PIXEL_SIZE_M..=MAX_PIXEL_SIZE_M).contains(&d) {
            return Err(TopographyError::invalid(
                what,
                format!("{d:e} m"),
                format!("a pixel size in [{MIN_PIXEL_SIZE_M:e}, {MAX_PIXEL_SIZE_M:e}] m (from {origin})"),
            ));
        }
    }
    if !(MIN_UNIT_M..=MAX_UNIT_M).contains(&unit) {
        return Err(TopographyError::invalid(
            "height unit",
            format!("{unit:e} m"),
            format!("a unit in [{MIN_UNIT_M:e}, {MAX_UNIT_M:e}] m (from {origin})"),
        ));
    }
    Ok(Resolved { dx, dy, pixel_from: src_x, unit, unit_from: src_u })
}

/// The map of heights in metres whose tally (NaN count, largest |h|) is `tally`: refused when a
/// height is beyond [`MAX_HEIGHT_M`] or every pixel is missing.
fn build(
    origin: &str,
    format: MapFormat,
    nx: usize,
    ny: usize,
    resolved: &Resolved,
    heights: Vec<f64>,
    tally: HeightTally,
) -> Result<(HeightMap, MapInfo), TopographyError> {
    if tally.largest > MAX_HEIGHT_M {
        let h = heights.iter().find(|h| h.abs() > MAX_HEIGHT_M).copied().unwrap_or(tally.largest);
        return Err(TopographyError::format(
            origin,
            0,
            format!("a height of {h:e} m (in SI units) is beyond the limit of {MAX_HEIGHT_M} m for a height map"),
        ));
    }
    if tally.nan == heights.len() {
        return Err(TopographyError::format(origin, 0, "every pixel is missing (NaN)"));
    }
    // Every height was tallied (finite and within MAX_HEIGHT_M, or NaN).
    let map = HeightMap::from_checked_heights(nx, ny, resolved.dx, resolved.dy, heights)
        .map_err(|e| TopographyError::format(origin, 0, e.to_string()))?;
    Ok((
        map,
        MapInfo {
            format,
            pixel_size_from: resolved.pixel_from,
            height_unit_from: resolved.unit_from,
            height_unit_m: resolved.unit,
            missing_pixels: tally.nan,
            channel: None,
        },
    ))
}

/// Reads a height-map file: its first channel that holds heights. See [`read_file_channel`].
pub fn read_file(
    path: &Path,
    format: Option<MapFormat>,
    meta: &MapMetadata,
) -> Result<(HeightMap, MapInfo), TopographyError> {
    read_file_channel(path, format, None, meta)
}

/// The format of `bytes`: their content decides ([`crate::detect`]); the claim (`format` given,
/// else the extension of `path`) only where the content has no magic (text grids, x-y-z lists).
/// A claim the content contradicts is an error naming both.
pub fn resolve_format(path: &Path, format: Option<MapFormat>, bytes: &[u8]) -> Result<MapFormat, TopographyError> {
    let origin = path.display().to_string();
    let (claim, by) = match format {
        Some(f) => (Some(f), "--format"),
        None => (MapFormat::from_extension(path), "its extension"),
    };
    match (claim, crate::formats::detect(bytes)) {
        (Some(c), Some(d)) if c != d => Err(TopographyError::format(
            &origin,
            0,
            format!(
                "{by} says {c}, but the content is a {d} file (by its first bytes): rename the file or give --format {d}"
            ),
        )),
        (_, Some(d)) => Ok(d),
        (Some(c), None) => Ok(c),
        (None, None) => Ok(MapFormat::Text),
    }
}

/// Reads a height-map file through [`stiction_units::io::read_input`] (regular files only, size
/// limit checked before reading): the format by content ([`resolve_format`]); for a file with
/// channels, the channel `channel` selects, else its first height channel (the choice is in
/// [`MapInfo::channel`]).
pub fn read_file_channel(
    path: &Path,
    format: Option<MapFormat>,
    channel: Option<&ChannelSelector>,
    meta: &MapMetadata,
) -> Result<(HeightMap, MapInfo), TopographyError> {
    let origin = path.display().to_string();
    let claim = format.or_else(|| MapFormat::from_extension(path)).unwrap_or(MapFormat::Text);
    let limit = if claim.has_magic() { BINARY_INPUT_LIMIT_BYTES } else { TEXT_INPUT_LIMIT_BYTES };
    let file = stiction_units::io::open_input(path, limit)?;
    let size = file.size_bytes();
    // A large file is read in parts (an instrument file's header, then its channel's samples
    // straight into the map); what that route does not read, the whole-file route below reads.
    let bytes = if size > 2 * HEADER_PREFIX_BYTES as u64 && size <= BINARY_INPUT_LIMIT_BYTES {
        match read_in_parts(&file, HEADER_PREFIX_BYTES, |b| resolve_format(path, format, b), channel, meta, &origin)? {
            Parts::Read(result) => return result,
            Parts::Whole(bytes) => bytes,
        }
    } else {
        file.read_all()?
    };
    let format = resolve_format(path, format, &bytes)?;
    if format.has_magic() && bytes.len() as u64 > BINARY_INPUT_LIMIT_BYTES {
        return Err(stiction_units::io::FileError::TooLarge {
            path: path.to_path_buf(),
            size_bytes: bytes.len() as u64,
            limit_bytes: BINARY_INPUT_LIMIT_BYTES,
        }
        .into());
    }
    let single = |format: MapFormat| -> Result<(), TopographyError> {
        match channel {
            None | Some(ChannelSelector::Index(0)) => Ok(()),
            Some(_) => Err(TopographyError::format(
                &origin,
                0,
                format!("a {format} file has one channel (0): --channel selects among an instrument file's channels"),
            )),
        }
    };
    match format {
        MapFormat::Npy => {
            single(format)?;
            read_npy(&bytes, &origin, meta)
        }
        MapFormat::Gsf => {
            single(format)?;
            read_gsf(&bytes, &origin, meta)
        }
        MapFormat::Text | MapFormat::Xyz => {
            single(format)?;
            let text = text_of(path, bytes)?;
            if format == MapFormat::Text {
                read_text_grid(&text, &origin, meta)
            } else {
                read_xyz(&text, &origin, meta)
            }
        }
        _ => read_instrument(&bytes, format, &origin, channel, meta),
    }
}

fn text_of(path: &Path, bytes: Vec<u8>) -> Result<String, TopographyError> {
    let mut text = String::from_utf8(bytes).map_err(|e| stiction_units::io::FileError::Io {
        path: path.to_path_buf(),
        action: "read (not UTF-8 text)",
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error()),
    })?;
    if text.starts_with('\u{feff}') {
        text.drain(..'\u{feff}'.len_utf8());
    }
    Ok(text)
}

/// Reads one channel of an instrument file's bytes (NanoScope, Igor binary wave, SDF): `channel`,
/// else the first height channel. Units, pixel sizes and the height scale come from the file; a
/// value it lacks comes from `meta` (else an error asks for it); a value in both must agree.
pub fn read_instrument(
    bytes: &[u8],
    format: MapFormat,
    origin: &str,
    channel: Option<&ChannelSelector>,
    meta: &MapMetadata,
) -> Result<(HeightMap, MapInfo), TopographyError> {
    let list = crate::formats::channels(format, bytes, origin)?;
    let (ch, choice) = crate::formats::choose(&list, channel, origin)?;
    read_channel(ch, choice, bytes, format, origin, meta)
}

/// Reads a channel's values from `src` (the file's bytes, or the file) into the map.
fn read_channel<S: ByteSource + ?Sized>(
    ch: &Channel,
    choice: ChannelChoice,
    src: &S,
    format: MapFormat,
    origin: &str,
    meta: &MapMetadata,
) -> Result<(HeightMap, MapInfo), TopographyError> {
    let i = &ch.info;
    // A unit the file states is the unit (a given one must agree): the values are scaled to metres
    // while they are decoded, in one pass; so is a unit given for a file that states none.
    let file_unit = i.height_unit_m;
    if let (Some(f), Some(_)) = (file_unit, meta.height_unit_m) {
        resolve(origin, Some(f), meta.height_unit_m, "height unit", UNIT_HOW)?;
    }
    check_channel(ch, src.size_bytes(), origin)?;
    let (dx, dy) = match i.size_m {
        Some((a, b)) => (Some(a / i.nx as f64), Some(b / i.ny as f64)),
        None => (None, None),
    };
    let resolved = resolve_meta(origin, dx, dy, file_unit, meta)?;
    let post = if file_unit.is_some() { 1.0 } else { resolved.unit };
    let (values, tally) = decode_channel(ch, src, origin, file_unit.unwrap_or(1.0), post)?;
    let (map, mut info) = build(origin, format, i.nx, i.ny, &resolved, values, tally)?;
    info.channel = Some(choice);
    Ok((map, info))
}

/// What [`read_in_parts`] did: read the channel (the map, or the error reading it gave), or read
/// the whole file for the whole-file route.
enum Parts {
    Read(Result<(HeightMap, MapInfo), TopographyError>),
    Whole(Vec<u8>),
}

/// Reads an instrument file's channel in parts (see the module `formats::parts`): the first
/// `prefix` bytes into a buffer of the file's size (the rest of it untouched, zero), the format
/// (`detect`) and the channel's samples `R` found there; then every byte outside `R` and the
/// channel found again, which must give the same `R`; then `R` decoded from `src` into the map.
/// Whenever a step does not give a raster channel, the rest of the file is read
/// ([`Parts::Whole`]) for the whole-file route, which decides (and words any error).
fn read_in_parts<S: ByteSource + ?Sized>(
    src: &S,
    prefix: usize,
    detect: impl Fn(&[u8]) -> Result<MapFormat, TopographyError>,
    channel: Option<&ChannelSelector>,
    meta: &MapMetadata,
    origin: &str,
) -> Result<Parts, TopographyError> {
    let size = src.size_bytes();
    // Zeroed on demand: the pages of this buffer that no read below fills are never touched.
    let mut bytes = vec![0u8; size];
    let prefix = prefix.min(size);
    src.read_at(0, &mut bytes[..prefix])?;
    let find = |bytes: &[u8]| -> Option<(MapFormat, Channel, ChannelChoice, (usize, usize))> {
        let format = detect(bytes).ok().filter(|&f| crate::formats::listed_without_samples(f))?;
        let list = crate::formats::channels(format, bytes, origin).ok()?;
        let (ch, choice) = crate::formats::choose(&list, channel, origin).ok()?;
        Some((format, ch.clone(), choice, raster_span(ch, size)?))
    };
    let fill = |bytes: &mut Vec<u8>, a: usize, b: usize| -> Result<(), TopographyError> {
        let a = a.max(prefix);
        if b > a { src.read_at(a, &mut bytes[a..b]) } else { Ok(()) }
    };
    let Some((_, _, _, (a, b))) = find(&bytes) else {
        fill(&mut bytes, prefix, size)?;
        return Ok(Parts::Whole(bytes));
    };
    fill(&mut bytes, prefix, a)?;
    fill(&mut bytes, b, size)?;
    match find(&bytes) {
        Some((format, ch, choice, span)) if span == (a, b) => {
            drop(bytes);
            Ok(Parts::Read(read_channel(&ch, choice, src, format, origin, meta)))
        }
        _ => {
            fill(&mut bytes, a, b)?;
            Ok(Parts::Whole(bytes))
        }
    }
}

/// [`read_instrument`] by the route [`read_file_channel`] takes for a large file (the header
/// from the first `prefix` bytes, then the channel's samples decoded in parts); the same result,
/// bit for bit; with whether the samples were read in parts (else the whole bytes were read and
/// [`read_instrument`] read them). For the tests that hold the two routes equal.
#[doc(hidden)]
pub fn read_instrument_in_parts(
    bytes: &[u8],
    prefix: usize,
    format: MapFormat,
    origin: &str,
    channel: Option<&ChannelSelector>,
    meta: &MapMetadata,
) -> (Result<(HeightMap, MapInfo), TopographyError>, bool) {
    match read_in_parts(bytes, prefix, |_| Ok(format), channel, meta, origin) {
        Err(e) => (Err(e), false),
        Ok(Parts::Read(result)) => (result, true),
        Ok(Parts::Whole(all)) => (read_instrument(&all, format, origin, channel, meta), false),
    }
}

/// The channels of a height-map file (format as [`read_file_channel`] finds it). A file without
/// channels (npy, gsf, text, xyz) lists its one map, read with `meta`.
pub fn list_channels(
    path: &Path,
    format: Option<MapFormat>,
    meta: &MapMetadata,
) -> Result<(MapFormat, Vec<ChannelInfo>), TopographyError> {
    let claim = format.or_else(|| MapFormat::from_extension(path)).unwrap_or(MapFormat::Text);
    if !claim.has_magic() || matches!(claim, MapFormat::Npy | MapFormat::Gsf) {
        let (map, info) = read_file(path, format, meta)?;
        let one = ChannelInfo {
            index: 0,
            name: "height".into(),
            nx: map.nx(),
            ny: map.ny(),
            size_m: Some((map.length_x_m(), map.length_y_m())),
            unit: "m".into(),
            height_unit_m: Some(info.height_unit_m),
            is_height: true,
        };
        return Ok((info.format, vec![one]));
    }
    let origin = path.display().to_string();
    let bytes = stiction_units::io::read_input(path, BINARY_INPUT_LIMIT_BYTES)?;
    let format = resolve_format(path, format, &bytes)?;
    if !format.has_magic() || matches!(format, MapFormat::Npy | MapFormat::Gsf) {
        return list_channels(path, Some(format), meta);
    }
    let list = crate::formats::channels(format, &bytes, &origin)?;
    Ok((format, list.into_iter().map(|c| c.info).collect()))
}

// ---------------------------------------------------------------------------------------------
// .npy

/// Largest |height| a map file may hold, in metres after its unit: 1 m (heights beyond it are
/// not a surface's, and their squares in the statistics would overflow).
pub const MAX_HEIGHT_M: f64 = 1.0;

/// Smallest height or coordinate unit of a map file: 1 fm (1e-15 m).
pub const MIN_UNIT_M: f64 = 1e-15;

/// Largest height or coordinate unit of a map file: 1 km.
pub const MAX_UNIT_M: f64 = 1e3;

/// Smallest pixel size: 1 pm (the differences of the statistics divide by its square).
pub const MIN_PIXEL_SIZE_M: f64 = 1e-12;

/// Largest pixel size: 1 m.
pub const MAX_PIXEL_SIZE_M: f64 = 1.0;

/// Largest `.npy` header accepted, bytes (NumPy writes about 120 for a 2-D float array).
pub const NPY_MAX_HEADER_BYTES: usize = 1 << 16;

/// Largest `.gsf` text header accepted, bytes (Gwyddion writes a few hundred).
pub const GSF_MAX_HEADER_BYTES: usize = 1 << 20;

/// Element type of a `.npy` file this crate reads or writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NpyDtype {
    /// IEEE float32 (`<f4`).
    F32,
    /// IEEE float64 (`<f8`).
    F64,
}

/// The value of `key` in a `.npy` header dict: the text after `'key':` up to the next `,` or `}`
/// at nesting depth 0 (a tuple's commas are inside parentheses).
fn npy_field<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    let start = header.find(&format!("'{key}'")).or_else(|| header.find(&format!("\"{key}\"")))?;
    let rest = &header[start + key.len() + 2..];
    let rest = rest.trim_start().strip_prefix(':')?.trim_start();
    let mut depth = 0i32;
    for (i, c) in rest.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' | '}' if depth == 0 => return Some(rest[..i].trim()),
            _ => {}
        }
    }
    Some(rest.trim())
}

/// Reads a `.npy` file's bytes: a 2-D array (rows = y) of float32 or float64, little or big
/// endian, C or Fortran order. `.npy` has no pixel size or unit: both come from `meta`.
pub fn read_npy(bytes: &[u8], origin: &str, meta: &MapMetadata) -> Result<(HeightMap, MapInfo), TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err(bad("not a NumPy .npy file (no \\x93NUMPY magic at the start)".into()));
    }
    let (header_len, header_start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10usize),
        2 | 3 if bytes.len() >= 12 => (u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize, 12),
        v => return Err(bad(format!(".npy format version {v} is not supported (expected 1, 2 or 3)"))),
    };
    let data_start = header_start
        .checked_add(header_len)
        .filter(|&e| e <= bytes.len())
        .ok_or_else(|| bad(format!("the header length {header_len} runs past the end of the file")))?;
    if header_len > NPY_MAX_HEADER_BYTES {
        return Err(bad(format!(
            "the header is {header_len} bytes, more than the limit of {NPY_MAX_HEADER_BYTES} bytes (a 2-D float array's \
             header is about 120)"
        )));
    }
    let header =
        std::str::from_utf8(&bytes[header_start..data_start]).map_err(|_| bad("the .npy header is not text".into()))?;
    let descr = npy_field(header, "descr").ok_or_else(|| bad("no 'descr' in the header".into()))?;
    let descr = descr.trim_matches(|c| c == '\'' || c == '"');
    let (little, size) = match descr {
        "<f8" | "=f8" => (true, 8),
        ">f8" => (false, 8),
        "<f4" | "=f4" => (true, 4),
        ">f4" => (false, 4),
        other => {
            return Err(bad(format!(
                "dtype {} is not supported: expected float32 or float64 ('<f4', '<f8', '>f4', '>f8')",
                excerpt(other)
            )));
        }
    };
    let fortran = match npy_field(header, "fortran_order") {
        Some("False") => false,
        Some("True") => true,
        Some(other) => return Err(bad(format!("'fortran_order' is {}: expected True or False", excerpt(other)))),
        None => return Err(bad("no 'fortran_order' in the header: expected True or False".into())),
    };
    let shape_text = npy_field(header, "shape").ok_or_else(|| bad("no 'shape' in the header".into()))?;
    let dims: Vec<u64> = shape_text
        .trim_matches(|c| c == '(' || c == ')')
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<u64>().map_err(|_| bad(format!("shape {} is not a tuple of integers", excerpt(shape_text)))))
        .collect::<Result<_, _>>()?;
    let [ny, nx] = dims[..] else {
        return Err(bad(format!("shape {}: expected a 2-D array (rows, columns)", excerpt(shape_text))));
    };
    check_grid_size(origin, nx, ny)?;
    let (nx, ny) = (nx as usize, ny as usize);
    let data = &bytes[data_start..];
    if data.len() != nx * ny * size {
        return Err(bad(format!(
            "{} data bytes after the header, expected {nx} x {ny} x {size} = {}",
            data.len(),
            nx * ny * size
        )));
    }
    let value = |k: usize| -> f64 {
        let b = &data[k * size..(k + 1) * size];
        if size == 8 {
            let a: [u8; 8] = b.try_into().unwrap_or_default();
            if little { f64::from_le_bytes(a) } else { f64::from_be_bytes(a) }
        } else {
            let a: [u8; 4] = b.try_into().unwrap_or_default();
            f64::from(if little { f32::from_le_bytes(a) } else { f32::from_be_bytes(a) })
        }
    };
    let mut heights = Vec::with_capacity(nx * ny);
    if fortran {
        for iy in 0..ny {
            heights.extend((0..nx).map(|ix| value(ix * ny + iy)));
        }
    } else {
        heights.extend((0..nx * ny).map(value));
    }
    finish(origin, MapFormat::Npy, nx, ny, None, None, None, meta, heights)
}

/// Heights of a 2-D array in memory (NumPy's float32 or float64), borrowed: the reader takes
/// them as they lie, without a copy of the array; [`read_array`] makes the one map in metres.
#[derive(Debug, Clone, Copy)]
pub enum BorrowedHeights<'a> {
    /// float32 values.
    F32(&'a [f32]),
    /// float64 values.
    F64(&'a [f64]),
}

impl BorrowedHeights<'_> {
    fn len(&self) -> usize {
        match self {
            BorrowedHeights::F32(d) => d.len(),
            BorrowedHeights::F64(d) => d.len(),
        }
    }
}

/// Where the elements of a 2-D array (rows = y) lie in a slice: element (row `iy`, column `ix`) is
/// `data[offset + iy * row_stride + ix * col_stride]`, strides counted in elements (not bytes).
/// C order is `(nx, 1)`, Fortran order `(1, ny)`; a NumPy view (`a[::2]`, `a.T`, `a[::-1]`) has
/// any strides, negative ones included, with `offset` the index of element (0, 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArrayLayout {
    /// Rows (pixels along y).
    pub ny: usize,
    /// Columns (pixels along x).
    pub nx: usize,
    /// Elements from one row to the next.
    pub row_stride: isize,
    /// Elements from one column to the next.
    pub col_stride: isize,
    /// Index of element (0, 0) in the slice.
    pub offset: usize,
}

impl ArrayLayout {
    /// A C-ordered (row-major) `ny x nx` array from the start of the slice.
    pub fn c_order(ny: usize, nx: usize) -> ArrayLayout {
        ArrayLayout { ny, nx, row_stride: nx as isize, col_stride: 1, offset: 0 }
    }

    /// A Fortran-ordered (column-major) `ny x nx` array from the start of the slice.
    pub fn fortran_order(ny: usize, nx: usize) -> ArrayLayout {
        ArrayLayout { ny, nx, row_stride: 1, col_stride: ny as isize, offset: 0 }
    }
}

/// Reads a height map from a 2-D array in memory (rows = y), float32 or float64, in any layout
/// ([`ArrayLayout`]): the heights are read once, in place, into the map (metres, row-major), with
/// the same checks and the same arithmetic as [`read_npy`] (float32 widened to float64, then times
/// the height unit), so an array and the `.npy` file of it give bit-identical maps. The pixel size
/// and the height unit come from `meta`; `origin` names the array in errors. The format reported
/// is [`MapFormat::Npy`] (NumPy's memory layout).
pub fn read_array(
    heights: BorrowedHeights<'_>,
    layout: ArrayLayout,
    origin: &str,
    meta: &MapMetadata,
) -> Result<(HeightMap, MapInfo), TopographyError> {
    let ArrayLayout { ny, nx, row_stride, col_stride, offset } = layout;
    check_grid_size(origin, nx as u64, ny as u64)?;
    // Every element in bounds: the extreme indices are at the corners.
    let last_row = (ny as i128 - 1) * row_stride as i128;
    let last_col = (nx as i128 - 1) * col_stride as i128;
    let lo = offset as i128 + last_row.min(0) + last_col.min(0);
    let hi = offset as i128 + last_row.max(0) + last_col.max(0);
    if lo < 0 || hi >= heights.len() as i128 {
        return Err(TopographyError::format(
            origin,
            0,
            format!(
                "a {ny} x {nx} array with strides ({row_stride}, {col_stride}) from element {offset} reaches elements \
                 {lo}..={hi} of {}",
                heights.len()
            ),
        ));
    }
    let index = |iy: usize, ix: usize| (offset as isize + iy as isize * row_stride + ix as isize * col_stride) as usize;
    let contiguous_rows = col_stride == 1 && row_stride == nx as isize;
    let mut out = Vec::with_capacity(nx * ny);
    match heights {
        BorrowedHeights::F64(d) if contiguous_rows => out.extend_from_slice(&d[offset..offset + nx * ny]),
        BorrowedHeights::F32(d) if contiguous_rows => {
            out.extend(d[offset..offset + nx * ny].iter().map(|&v| f64::from(v)))
        }
        BorrowedHeights::F64(d) => {
            for iy in 0..ny {
                out.extend((0..nx).map(|ix| d[index(iy, ix)]));
            }
        }
        BorrowedHeights::F32(d) => {
            for iy in 0..ny {
                out.extend((0..nx).map(|ix| f64::from(d[index(iy, ix)])));
            }
        }
    }
    finish(origin, MapFormat::Npy, nx, ny, None, None, None, meta, out)
}

impl HeightMap {
    /// The map as `.npy` bytes (heights in metres, version 1.0 header), float32 or float64, C or
    /// Fortran order.
    pub fn to_npy_bytes(&self, dtype: NpyDtype, fortran_order: bool) -> Vec<u8> {
        let descr = match dtype {
            NpyDtype::F32 => "<f4",
            NpyDtype::F64 => "<f8",
        };
        let mut header = format!(
            "{{'descr': '{descr}', 'fortran_order': {}, 'shape': ({}, {}), }}",
            if fortran_order { "True" } else { "False" },
            self.ny(),
            self.nx()
        );
        while !(10 + header.len() + 1).is_multiple_of(64) {
            header.push(' ');
        }
        header.push('\n');
        let mut out = b"\x93NUMPY\x01\x00".to_vec();
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        let (nx, ny) = (self.nx(), self.ny());
        let order: Box<dyn Iterator<Item = f64>> = if fortran_order {
            Box::new((0..nx).flat_map(move |ix| (0..ny).map(move |iy| self.at(ix, iy))))
        } else {
            Box::new(self.heights_m().iter().copied())
        };
        for h in order {
            match dtype {
                NpyDtype::F32 => out.extend_from_slice(&(h as f32).to_le_bytes()),
                NpyDtype::F64 => out.extend_from_slice(&h.to_le_bytes()),
            }
        }
        out
    }
}

// ---------------------------------------------------------------------------------------------
// Text grid

/// The line bound of every text format ([`stiction_units::text::check_lines`]), as a format error.
fn check_text(text: &str, origin: &str) -> Result<(), TopographyError> {
    check_lines(text, MAX_LINE_BYTES).map_err(|e| TopographyError::format(origin, e.line, e.to_string()))
}

fn parse_cell(text: &str) -> Option<f64> {
    let t = text.trim();
    if t.is_empty() || t.eq_ignore_ascii_case("nan") {
        return Some(f64::NAN);
    }
    t.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// Reads a text grid: one row of heights per line (the first line is row 0, y = 0), separated by
/// commas, semicolons, tabs or runs of spaces; empty cells and `NaN` are missing pixels. Lines
/// starting with `#` are comments; Gwyddion's ASCII export header lines `# Width: 5.000 µm`,
/// `# Height: 5.000 µm` (the map's physical size along x and y) and `# Value units: m` give the
/// pixel size and height unit.
pub fn read_text_grid(text: &str, origin: &str, meta: &MapMetadata) -> Result<(HeightMap, MapInfo), TopographyError> {
    check_text(text, origin)?;
    let (mut width, mut height, mut unit) = (None, None, None);
    let mut first_data: Option<&str> = None;
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(c) = t.strip_prefix('#') {
            if let Some((key, value)) = c.split_once(':') {
                let parse_len = |v: &str| {
                    let v = v.trim();
                    stiction_units::text::check_cell(v).map_err(|e| {
                        TopographyError::format(origin, k as u64 + 1, format!("header {}: {e}", excerpt(key.trim())))
                    })?;
                    parse_quantity(v, Dimension::Length).map_err(|e| {
                        TopographyError::format(
                            origin,
                            k as u64 + 1,
                            format!("header {}: {}", excerpt(key.trim()), e.brief()),
                        )
                    })
                };
                match key.trim().to_ascii_lowercase().as_str() {
                    "width" => width = Some(parse_len(value)?),
                    "height" => height = Some(parse_len(value)?),
                    "value units" => {
                        unit = Some(parse_length_unit(value).map_err(|e| {
                            TopographyError::format(
                                origin,
                                k as u64 + 1,
                                format!("header `Value units`: {e} (heights must be lengths)"),
                            )
                        })?)
                    }
                    _ => {}
                }
            }
        } else if !t.is_empty() && first_data.is_none() {
            first_data = Some(t);
        }
    }
    let first = first_data.ok_or_else(|| TopographyError::format(origin, 0, "no data line"))?;
    let delimiter = [b',', b';', b'\t'].into_iter().find(|d| first.as_bytes().contains(d));
    let mut heights: Vec<f64> = Vec::new();
    let mut nx = 0usize;
    let mut ny = 0usize;
    let mut push_row = |line: u64, cells: &mut dyn Iterator<Item = &str>| -> Result<(), TopographyError> {
        let before = heights.len();
        for (c, cell) in cells.enumerate() {
            stiction_units::text::check_cell(cell)
                .map_err(|e| TopographyError::format(origin, line, format!("column {}: {e}", c + 1)))?;
            let v = parse_cell(cell).ok_or_else(|| {
                TopographyError::format(
                    origin,
                    line,
                    format!(
                        "column {}: {} is not a finite number (or NaN / empty for a missing pixel)",
                        c + 1,
                        excerpt(cell)
                    ),
                )
            })?;
            if heights.len() as u64 >= MAX_PIXELS {
                return Err(TopographyError::TooLarge {
                    origin: origin.into(),
                    nx: nx.max(c + 1) as u64,
                    ny: ny as u64 + 1,
                    limit: MAX_PIXELS,
                });
            }
            heights.push(v);
        }
        let n = heights.len() - before;
        if ny == 0 {
            nx = n;
        } else if n != nx {
            return Err(TopographyError::format(
                origin,
                line,
                format!("{n} values, but the first data row has {nx}: every row of a grid must have the same length"),
            ));
        }
        ny += 1;
        Ok(())
    };
    match delimiter {
        Some(d) => {
            let mut r = csv::ReaderBuilder::new()
                .has_headers(false)
                .delimiter(d)
                .trim(csv::Trim::All)
                .flexible(true)
                .comment(Some(b'#'))
                .from_reader(text.as_bytes());
            let mut rec = csv::StringRecord::new();
            loop {
                match r.read_record(&mut rec) {
                    Ok(false) => break,
                    Ok(true) => {}
                    Err(e) => {
                        let line = e.position().map_or(0, |p| p.line());
                        return Err(TopographyError::format(origin, line, e.to_string()));
                    }
                }
                let line = rec.position().map_or(0, |p| p.line());
                if rec.iter().all(|c| c.is_empty()) {
                    continue;
                }
                // A trailing delimiter makes an empty last cell; drop it.
                let mut cells: Vec<&str> = rec.iter().collect();
                if cells.len() > 1 && cells.last() == Some(&"") {
                    cells.pop();
                }
                push_row(line, &mut cells.into_iter())?;
            }
        }
        None => {
            for (k, line) in text.lines().enumerate() {
                let t = line.trim();
                if t.is_empty() || t.starts_with('#') {
                    continue;
                }
                push_row(k as u64 + 1, &mut t.split_whitespace())?;
            }
        }
    }
    check_grid_size(origin, nx as u64, ny as u64)?;
    let dx = width.map(|w| w / nx as f64);
    let dy = height.map(|h| h / ny as f64);
    finish(origin, MapFormat::Text, nx, ny, dx, dy, unit, meta, heights)
}

impl HeightMap {
    /// The map as a tab-separated text grid in metres with Gwyddion's ASCII export header
    /// (`# Width`, `# Height` in m, `# Value units: m`); NaN for missing pixels. Numbers use the
    /// shortest text that reads back to the same value.
    pub fn to_text_grid(&self) -> String {
        let mut s = String::with_capacity(self.nx() * self.ny() * 24 + 128);
        s.push_str("# Channel: Height\n");
        s.push_str(&format!("# Width: {} m\n# Height: {} m\n# Value units: m\n", self.length_x_m(), self.length_y_m()));
        for iy in 0..self.ny() {
            for (ix, h) in self.row(iy).iter().enumerate() {
                if ix > 0 {
                    s.push('\t');
                }
                s.push_str(&h.to_string());
            }
            s.push('\n');
        }
        s
    }
}

// ---------------------------------------------------------------------------------------------
// Gwyddion simple field

/// Reads a Gwyddion simple field (`.gsf`): the line `Gwyddion Simple Field 1.0`, `Key = Value`
/// lines (`XRes`, `YRes` required; `XReal`, `YReal` the physical size in `XYUnits`, `ZUnits` the
/// height unit), NUL padding to a multiple of 4 bytes, then `XRes * YRes` little-endian float32.
/// A missing `XReal` or `ZUnits` must come from `meta`.
pub fn read_gsf(bytes: &[u8], origin: &str, meta: &MapMetadata) -> Result<(HeightMap, MapInfo), TopographyError> {
    let bad = |line: u64, m: String| TopographyError::format(origin, line, m);
    const MAGIC: &[u8] = b"Gwyddion Simple Field 1.0";
    if !bytes.starts_with(MAGIC) {
        return Err(bad(1, "not a Gwyddion simple field (expected `Gwyddion Simple Field 1.0`)".into()));
    }
    let nul = bytes
        .iter()
        .position(|&b| b == 0)
        .ok_or_else(|| bad(0, "no NUL padding after the header: the file is truncated".into()))?;
    if nul > GSF_MAX_HEADER_BYTES {
        return Err(bad(
            0,
            format!("the text header is {nul} bytes, more than the limit of {GSF_MAX_HEADER_BYTES} bytes"),
        ));
    }
    check_line_bytes(&bytes[..nul], MAX_LINE_BYTES).map_err(|e| bad(e.line, e.to_string()))?;
    let header = std::str::from_utf8(&bytes[..nul]).map_err(|_| bad(0, "the header is not UTF-8 text".into()))?;
    let data_start = nul + (4 - nul % 4);
    if data_start > bytes.len() || bytes[nul..data_start].iter().any(|&b| b != 0) {
        return Err(bad(0, "the header must be followed by 1 to 4 NUL bytes up to a multiple of 4".into()));
    }
    let mut keys = std::collections::HashMap::new();
    for (k, line) in header.lines().enumerate().skip(1) {
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        let (key, value) = t
            .split_once('=')
            .ok_or_else(|| bad(k as u64 + 1, format!("{} is not a `Key = Value` line", excerpt(t))))?;
        stiction_units::text::check_cell(value.trim())
            .map_err(|e| bad(k as u64 + 1, format!("{}: {e}", excerpt(key.trim()))))?;
        if let Some((first, _)) = keys.insert(key.trim().to_string(), (k as u64 + 1, value.trim().to_string())) {
            return Err(bad(k as u64 + 1, format!("{} appears twice (first on line {first})", excerpt(key.trim()))));
        }
    }
    let res = |name: &str| -> Result<u64, TopographyError> {
        let (line, v) = keys.get(name).ok_or_else(|| bad(0, format!("`{name}` is missing from the header")))?;
        v.parse::<u64>().map_err(|_| bad(*line, format!("`{name}` = {}: expected a positive integer", excerpt(v))))
    };
    let (nx, ny) = (res("XRes")?, res("YRes")?);
    check_grid_size(origin, nx, ny)?;
    let (nx, ny) = (nx as usize, ny as usize);
    let xy_unit = match keys.get("XYUnits") {
        Some((line, u)) => parse_length_unit(u).map_err(|e| bad(*line, format!("`XYUnits`: {e}")))?,
        None => 1.0,
    };
    let real = |name: &str, n: usize| -> Result<Option<f64>, TopographyError> {
        match keys.get(name) {
            None => Ok(None),
            Some((line, v)) => {
                let x: f64 =
                    v.parse().map_err(|_| bad(*line, format!("`{name}` = {}: expected a number", excerpt(v))))?;
                if x.is_finite() && x > 0.0 {
                    Ok(Some(x * xy_unit / n as f64))
                } else {
                    Err(bad(*line, format!("`{name}` = {}: expected a finite size > 0", excerpt(v))))
                }
            }
        }
    };
    let (dx, dy) = (real("XReal", nx)?, real("YReal", ny)?);
    let unit = match keys.get("ZUnits") {
        Some((line, u)) => Some(parse_length_unit(u).map_err(|e| bad(*line, format!("`ZUnits`: {e}")))?),
        None => None,
    };
    let data = &bytes[data_start..];
    if data.len() != nx * ny * 4 {
        return Err(bad(0, format!("{} data bytes, expected XRes x YRes x 4 = {}", data.len(), nx * ny * 4)));
    }
    let heights = data.chunks_exact(4).map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]]))).collect();
    finish(origin, MapFormat::Gsf, nx, ny, dx, dy, unit, meta, heights)
}

impl HeightMap {
    /// The map as a Gwyddion simple field (float32 heights in metres, sizes in metres).
    pub fn to_gsf_bytes(&self) -> Vec<u8> {
        let header = format!(
            "Gwyddion Simple Field 1.0\nXRes = {}\nYRes = {}\nXReal = {}\nYReal = {}\nXYUnits = m\nZUnits = m\nTitle = stiction\n",
            self.nx(),
            self.ny(),
            self.length_x_m(),
            self.length_y_m()
        );
        let mut out = header.into_bytes();
        let pad = 4 - out.len() % 4;
        out.extend(std::iter::repeat_n(0u8, pad));
        for h in self.heights_m() {
            out.extend_from_slice(&(*h as f32).to_le_bytes());
        }
        out
    }
}

// ---------------------------------------------------------------------------------------------
// x-y-z point lists

/// Sorted distinct values and the grid step; errors if they are not evenly spaced (relative
/// tolerance 1e-6 of the step).
fn grid_axis(origin: &str, name: &str, values: &[f64]) -> Result<(f64, f64, usize), TopographyError> {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    v.dedup();
    if v.len() < 2 {
        return Err(TopographyError::format(origin, 0, format!("only {} distinct {name} value(s)", v.len())));
    }
    let step = (v[v.len() - 1] - v[0]) / (v.len() - 1) as f64;
    for (k, w) in v.windows(2).enumerate() {
        if ((w[1] - w[0]) - step).abs() > 1e-6 * step {
            return Err(TopographyError::format(
                origin,
                0,
                format!(
                    "the {name} coordinates are not on a regular grid: {:e} follows {:e} (step {:e}), expected the step {step:e} (value {} of {})",
                    w[1],
                    w[0],
                    w[1] - w[0],
                    k + 2,
                    v.len()
                ),
            ));
        }
    }
    Ok((v[0], step, v.len()))
}

/// Reads an x-y-z point list: one point per line (`x y z`, separated by spaces, tabs, commas or
/// semicolons; `#` lines are comments; a first line that is not numeric is taken as a header), on a
/// regular grid in any order; grid points absent from the file are missing pixels. The unit of x
/// and y comes from `meta.xy_unit_m` (the pixel size is the grid step), the height unit from
/// `meta.height_unit_m`.
pub fn read_xyz(text: &str, origin: &str, meta: &MapMetadata) -> Result<(HeightMap, MapInfo), TopographyError> {
    let xy_unit = meta.xy_unit_m.ok_or_else(|| TopographyError::MissingMetadata {
        origin: origin.into(),
        missing:
            "the unit of the x and y coordinates: give it with --xy-unit (e.g. \"um\") or the scenario field `xy_unit`"
                .into(),
    })?;
    if !(MIN_UNIT_M..=MAX_UNIT_M).contains(&xy_unit) {
        return Err(TopographyError::invalid(
            "xy_unit",
            format!("{xy_unit:e} m"),
            format!("a unit in [{MIN_UNIT_M:e}, {MAX_UNIT_M:e}] m"),
        ));
    }
    if meta.pixel_size_x_m.is_some() || meta.pixel_size_y_m.is_some() {
        return Err(TopographyError::invalid(
            "pixel_size",
            "given",
            "no pixel size for an x-y-z list: the grid step of its coordinates is the pixel size (give `xy_unit`)",
        ));
    }
    check_text(text, origin)?;
    let mut pts: Vec<[f64; 3]> = Vec::new();
    let mut first = true;
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> =
            t.split(|c: char| c == ',' || c == ';' || c.is_whitespace()).filter(|s| !s.is_empty()).take(4).collect();
        for c in &cells {
            stiction_units::text::check_cell(c).map_err(|e| TopographyError::format(origin, k as u64 + 1, e))?;
        }
        let nums: Option<Vec<f64>> = cells.iter().map(|c| c.parse::<f64>().ok()).collect();
        let Some(nums) = nums else {
            if first {
                first = false;
                continue; // a header line such as `x,y,z`
            }
            return Err(TopographyError::format(
                origin,
                k as u64 + 1,
                format!("{} is not three numbers x y z", excerpt(t)),
            ));
        };
        first = false;
        if nums.len() != 3 || !nums[0].is_finite() || !nums[1].is_finite() || nums[2].is_infinite() {
            return Err(TopographyError::format(
                origin,
                k as u64 + 1,
                format!("{}: expected three numbers x y z (finite x, y; z finite or NaN)", excerpt(t)),
            ));
        }
        if pts.len() as u64 >= MAX_PIXELS {
            return Err(TopographyError::format(origin, k as u64 + 1, format!("more than {MAX_PIXELS} points")));
        }
        pts.push([nums[0], nums[1], nums[2]]);
    }
    let xs: Vec<f64> = pts.iter().map(|p| p[0]).collect();
    let (x0, sx, nx) = grid_axis(origin, "x", &xs)?;
    drop(xs);
    let ys: Vec<f64> = pts.iter().map(|p| p[1]).collect();
    let (y0, sy, ny) = grid_axis(origin, "y", &ys)?;
    drop(ys);
    check_grid_size(origin, nx as u64, ny as u64)?;
    let mut heights = vec![f64::NAN; nx * ny];
    let mut seen = vec![false; nx * ny];
    for p in &pts {
        let ix = ((p[0] - x0) / sx).round() as usize;
        let iy = ((p[1] - y0) / sy).round() as usize;
        let k = iy * nx + ix;
        if seen[k] {
            return Err(TopographyError::format(
                origin,
                0,
                format!("the point ({:e}, {:e}) appears twice", p[0], p[1]),
            ));
        }
        seen[k] = true;
        heights[k] = p[2];
    }
    let meta2 = MapMetadata { pixel_size_x_m: None, pixel_size_y_m: None, ..*meta };
    finish(origin, MapFormat::Xyz, nx, ny, Some(sx * xy_unit), Some(sy * xy_unit), None, &meta2, heights)
}

impl HeightMap {
    /// The map as an x-y-z list (`x y z` per line, all in metres; x = ix dx, y = iy dy), missing
    /// pixels left out.
    pub fn to_xyz_text(&self) -> String {
        let mut s = String::from("x_m y_m z_m\n");
        for iy in 0..self.ny() {
            for (ix, h) in self.row(iy).iter().enumerate() {
                if !h.is_nan() {
                    s.push_str(&format!("{} {} {}\n", ix as f64 * self.dx_m(), iy as f64 * self.dy_m(), h));
                }
            }
        }
        s
    }
}
