//! Instrument file formats: Bruker/Veeco NanoScope (`.spm`, `.di`, `.001`), Igor binary wave
//! (`.ibw`, Asylum Research AFMs), ISO 25178-71 SDF (`.sdf`, ASCII and binary) and ISO 25178-72
//! X3P (`.x3p`), Digital Surf (`.sur`) and Wyko (`.opd`), detected by
//! their content ([`detect`]), read channel by channel.
//!
//! A reader parses the file's header into [`Channel`]s: the listing ([`ChannelInfo`]) and where and
//! how its values lie ([`Raster`]); only the chosen channel's values are decoded. Units, pixel sizes
//! and the height scale come from the file; what a file lacks is asked for by name (the crate's
//! `MapMetadata`), never guessed.

pub(crate) mod al3d;
mod fields;
pub(crate) mod ibw;
pub(crate) mod metropro;
pub(crate) mod mi;
pub mod nanoscope;
pub(crate) mod nc;
pub(crate) mod nid;
pub(crate) mod opd;
pub(crate) mod park;
pub(crate) mod parts;
pub(crate) mod plu;
pub(crate) mod sdf;
pub(crate) mod sur;
pub(crate) mod wsxm;
pub mod x3p;

use serde::Serialize;
use stiction_units::text::excerpt;

use crate::TopographyError;
use crate::map_format::MapFormat;

/// One channel of a file as listed by `stiction topography FILE --channels`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelInfo {
    /// Position in the file, from 0.
    pub index: usize,
    /// The channel's name as the file gives it.
    pub name: String,
    /// Columns (pixels along x).
    pub nx: usize,
    /// Rows (pixels along y).
    pub ny: usize,
    /// Physical size along x and y \[m\]; `None` when the file states no length unit.
    pub size_m: Option<(f64, f64)>,
    /// The unit of the values as the file writes it (`nm`, `deg`, `V`; empty if none).
    pub unit: String,
    /// Metres per value (after the file's scale) when the unit is a length, else `None`.
    pub height_unit_m: Option<f64>,
    /// Whether the channel holds heights (a length unit, or no unit at all, and a height-like name
    /// where the file names its channels).
    pub is_height: bool,
}

/// Type of the stored samples of a raster.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Sample {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Sample {
    pub(crate) fn bytes(self) -> usize {
        match self {
            Sample::I8 | Sample::U8 => 1,
            Sample::I16 | Sample::U16 => 2,
            Sample::I32 | Sample::U32 | Sample::F32 => 4,
            Sample::F64 => 8,
        }
    }
}

/// Which stored samples mark a missing pixel (besides NaN in float types, always missing).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Missing {
    /// A sample equal to this value (e.g. Digital Surf's `zmin - 2`, Sensofar's 1000001).
    Equal(f64),
    /// A sample at or above this value (e.g. Zygo MetroPro's 2147483640).
    AtLeast(f64),
}

/// Where a channel's `nx x ny` samples lie in the file: from `offset`, x fastest, rows in file
/// order (row 0 of the map is the file's last row when `flip_y`; column 0 the row's last sample
/// when `flip_x`); value = sample x `scale` + `shift`, in the channel's unit; a sample `invalid` marks, or NaN
/// (float types), is missing.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Raster {
    pub offset: usize,
    pub sample: Sample,
    pub big_endian: bool,
    pub flip_x: bool,
    pub flip_y: bool,
    pub scale: f64,
    pub shift: f64,
    /// Bytes from one row's start to the next's, if rows are padded (else `nx` samples).
    pub row_bytes: Option<usize>,
    pub invalid: Option<Missing>,
}

/// How a channel's values are had.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Values {
    /// Binary samples in the file.
    Raster(Raster),
    /// Values parsed with the header (text formats), row 0 first, NaN for missing.
    Parsed(Vec<f64>),
}

/// A channel: its listing and its values.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Channel {
    pub info: ChannelInfo,
    pub values: Values,
    /// Why the channel cannot be read as heights, if it cannot (e.g. no scale in the header).
    pub unreadable: Option<String>,
}

/// The format whose magic bytes the content starts with, if any (NumPy, Gwyddion simple field,
/// NanoScope, Igor binary wave version 5 with a valid header checksum, SDF). Text grids and x-y-z
/// lists have no magic.
pub fn detect(bytes: &[u8]) -> Option<MapFormat> {
    if bytes.starts_with(b"\x93NUMPY") {
        Some(MapFormat::Npy)
    } else if bytes.starts_with(b"Gwyddion Simple Field") {
        Some(MapFormat::Gsf)
    } else if nanoscope::is_nanoscope(bytes) {
        Some(MapFormat::Nanoscope)
    } else if sdf::is_sdf(bytes) {
        Some(MapFormat::Sdf)
    } else if ibw::is_ibw(bytes) {
        Some(MapFormat::Ibw)
    } else if opd::is_opd(bytes) {
        Some(MapFormat::Opd)
    } else if sur::is_sur(bytes) {
        Some(MapFormat::Sur)
    } else if x3p::is_zip(bytes) {
        Some(MapFormat::X3p)
    } else if plu::is_plu(bytes) {
        Some(MapFormat::Plu)
    } else if metropro::is_metropro(bytes) {
        Some(MapFormat::Metropro)
    } else if nc::is_nc(bytes) {
        Some(MapFormat::Netcdf)
    } else if wsxm::is_wsxm(bytes) {
        Some(MapFormat::Wsxm)
    } else if mi::is_mi(bytes) {
        Some(MapFormat::Mi)
    } else if nid::is_nid(bytes) {
        Some(MapFormat::Nid)
    } else if al3d::is_al3d(bytes) {
        Some(MapFormat::Al3d)
    } else if park::is_park(bytes) {
        Some(MapFormat::Park)
    } else {
        None
    }
}

/// The channels of an instrument file.
pub(crate) fn channels(format: MapFormat, bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    match format {
        MapFormat::Nanoscope => nanoscope::channels(bytes, origin),
        MapFormat::Ibw => ibw::channels(bytes, origin),
        MapFormat::Sdf => sdf::channels(bytes, origin),
        MapFormat::X3p => x3p::channels(bytes, origin),
        MapFormat::Sur => sur::channels(bytes, origin),
        MapFormat::Opd => opd::channels(bytes, origin),
        MapFormat::Plu => plu::channels(bytes, origin),
        MapFormat::Metropro => metropro::channels(bytes, origin),
        MapFormat::Netcdf => nc::channels(bytes, origin),
        MapFormat::Wsxm => wsxm::channels(bytes, origin),
        MapFormat::Mi => mi::channels(bytes, origin),
        MapFormat::Nid => nid::channels(bytes, origin),
        MapFormat::Al3d => al3d::channels(bytes, origin),
        MapFormat::Park => park::channels(bytes, origin),
        other => Err(TopographyError::format(origin, 0, format!("{other} files have no channel list"))),
    }
}

/// Which channel to read: by index or by name. In a scenario (`surface.height_map.channel`) an
/// integer (the index) or a string (a name, or an index written as digits).
#[derive(Debug, Clone, PartialEq, Eq, schemars::JsonSchema)]
#[schemars(with = "ChannelSelectorInput")]
pub enum ChannelSelector {
    /// The channel at this index (from 0).
    Index(usize),
    /// The first channel with this name (case-insensitive).
    Name(String),
}

/// The JSON form of a [`ChannelSelector`]: a channel index or a channel name.
#[derive(schemars::JsonSchema)]
#[serde(untagged)]
#[allow(dead_code)]
enum ChannelSelectorInput {
    /// The channel's index in the file, from 0.
    Index(u32),
    /// The channel's name (case-insensitive), or its index as digits.
    Name(String),
}

impl Serialize for ChannelSelector {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            ChannelSelector::Index(k) => s.serialize_u64(*k as u64),
            ChannelSelector::Name(n) => s.serialize_str(n),
        }
    }
}

impl<'de> serde::Deserialize<'de> for ChannelSelector {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Index(u64),
            Name(String),
        }
        match Raw::deserialize(d)? {
            Raw::Index(k) => usize::try_from(k)
                .map(ChannelSelector::Index)
                .map_err(|_| serde::de::Error::custom(format!("channel index {k} is too large"))),
            Raw::Name(n) => n.parse().map_err(serde::de::Error::custom),
        }
    }
}

impl std::str::FromStr for ChannelSelector {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let t = s.trim();
        if t.is_empty() {
            return Err("a channel name or index is needed".into());
        }
        Ok(match t.parse::<usize>() {
            Ok(k) => ChannelSelector::Index(k),
            Err(_) => ChannelSelector::Name(t.to_string()),
        })
    }
}

/// The channel read and why it was chosen.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelChoice {
    /// Its index.
    pub index: usize,
    /// Its name.
    pub name: String,
    /// Channels in the file.
    pub of: usize,
    /// `default`: the first height channel; `given`: `--channel` (or the scenario field).
    pub chosen: &'static str,
}

/// Picks the channel: `selector`, else the first height channel, else an error naming the channels.
pub(crate) fn choose<'a>(
    list: &'a [Channel],
    selector: Option<&ChannelSelector>,
    origin: &str,
) -> Result<(&'a Channel, ChannelChoice), TopographyError> {
    let names = || {
        let mut s: Vec<String> =
            list.iter().take(12).map(|c| format!("{} {}", c.info.index, excerpt(&c.info.name))).collect();
        if list.len() > 12 {
            s.push(format!("... ({} in all)", list.len()));
        }
        s.join(", ")
    };
    let (ch, chosen) = match selector {
        Some(ChannelSelector::Index(k)) => (
            list.get(*k).ok_or_else(|| {
                TopographyError::format(origin, 0, format!("no channel {k}: the file has {} ({})", list.len(), names()))
            })?,
            "given",
        ),
        Some(ChannelSelector::Name(n)) => (
            list.iter().find(|c| c.info.name.eq_ignore_ascii_case(n)).ok_or_else(|| {
                TopographyError::format(origin, 0, format!("no channel named {}: the file has {}", excerpt(n), names()))
            })?,
            "given",
        ),
        None => (
            list.iter().find(|c| c.info.is_height).ok_or_else(|| {
                TopographyError::format(
                    origin,
                    0,
                    format!("no height channel; choose one with --channel NAME|INDEX ({})", names()),
                )
            })?,
            "default",
        ),
    };
    if let Some(why) = &ch.unreadable {
        return Err(TopographyError::format(
            origin,
            0,
            format!("channel {} {}: {why}", ch.info.index, excerpt(&ch.info.name)),
        ));
    }
    if !ch.info.is_height && ch.info.height_unit_m.is_none() && !ch.info.unit.is_empty() {
        return Err(TopographyError::format(
            origin,
            0,
            format!(
                "channel {} {} holds {}, not heights (a length): choose a height channel (--channels lists them)",
                ch.info.index,
                excerpt(&ch.info.name),
                excerpt(&ch.info.unit)
            ),
        ));
    }
    let choice = ChannelChoice { index: ch.info.index, name: ch.info.name.clone(), of: list.len(), chosen };
    Ok((ch, choice))
}

/// Whether the channels of a `format` file are listed from bytes other than their samples, so
/// that the route in parts ([`parts`]) may read them. Not WSxM: its samples start after the line
/// end that follows `[Header end]`, whatever bytes come there, and an int16 image's scale is the
/// Z amplitude over the samples' range; a WSxM file is read whole.
pub(crate) fn listed_without_samples(format: MapFormat) -> bool {
    format != MapFormat::Wsxm
}

/// Whether a channel name reads as a height channel.
pub(crate) fn height_like(name: &str) -> bool {
    let n = name.to_ascii_lowercase();
    n.contains("height") || n.contains("topograph") || n == "z" || n.starts_with("z ") || n.contains("z-axis")
}

/// Text of a latin-1 byte string (every byte one char), up to the first NUL.
pub(crate) fn latin1(bytes: &[u8]) -> String {
    bytes.iter().take_while(|&&b| b != 0).map(|&b| char::from(b)).collect()
}

/// A length unit's metres, if `unit` is a length unit (`nm`, `um`, `µm`, `m`, ...).
pub(crate) fn length_unit(unit: &str) -> Option<f64> {
    let u = unit.trim();
    if u.is_empty() || !u.starts_with(|c: char| c.is_alphabetic()) {
        return None;
    }
    crate::length_unit::parse_length_unit(u).ok()
}

/// Longest channel name or unit kept from a file, characters.
pub const MAX_NAME_CHARS: usize = 64;

/// A name or unit from a file as listed: control and format characters dropped, at most
/// [`MAX_NAME_CHARS`] characters.
pub(crate) fn clean(s: &str) -> String {
    s.trim()
        .chars()
        .filter(|c| {
            !c.is_control() && !matches!(c, '\u{200b}'..='\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
        })
        .take(MAX_NAME_CHARS)
        .collect()
}
