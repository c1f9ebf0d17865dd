//! Park Systems AFM TIFF files (`.tiff`, `.tif`).
//!
//! Container: a TIFF (Adobe TIFF 6.0): `II*\0` or `MM\0*`, the offset of the first image file
//! directory (IFD), whose 12-byte entries give a tag, a type, a count and the value or its
//! offset. Read by hand: only four private tags of the first IFD are needed, and the data tag's
//! offset is used to decode the samples in place (the `tiff` crate hands tag values over as
//! copied vectors, under a 1 MiB default limit that a 4096 x 4096 map exceeds).
//!
//! Park's tags (as Gwyddion's `psia` module and SurfaceTopography read them): 50432 the magic
//! `0x0E031301`, 50433 the version (`0x1000001` or `0x1000002`), 50434 the data, 50435 the
//! little-endian header: at 0 the image type (uint32: 0 a 2-D map), 4 the source name (32 UTF-16
//! characters), 100, 104 the grid `nx`, `ny` (uint32), 140, 148 the scan size in µm (float64),
//! 220 the data gain, 228 the scale factor (0 read as 1), 236 the offset (float64), 244 the data
//! unit (8 UTF-16 characters, empty read as µm) and, in version 2, 348 the data type (uint32:
//! 0 int16, 1 int32, 2 float32; version 1 is int16). A height is
//! `(sample x scale + offset) x gain` in the data unit; the samples run x fastest, the last row
//! first (row 0 of the map is the file's last row).
//!
//! Not read (refused): line profiles and spectroscopy (image type other than 0), several images.

use stiction_units::text::excerpt;

use super::fields::Fields;
use super::{Channel, ChannelInfo, Raster, Sample, Values, clean, length_unit};
use crate::TopographyError;

const TAG_MAGIC: u16 = 50432;
const TAG_VERSION: u16 = 50433;
const TAG_DATA: u16 = 50434;
const TAG_HEADER: u16 = 50435;
const PARK_MAGIC: u32 = 0x0E03_1301;
const HEADER_V1: u64 = 284;
const HEADER_V2: u64 = 352;

fn tiff_order(bytes: &[u8]) -> Option<bool> {
    if bytes.starts_with(b"II*\0") {
        Some(false)
    } else if bytes.starts_with(b"MM\0*") {
        Some(true)
    } else {
        None
    }
}

/// The first IFD's entries: (tag, type, count, value-or-offset field position).
fn ifd(bytes: &[u8]) -> Option<Vec<(u16, u16, u32, usize)>> {
    let big = tiff_order(bytes)?;
    let f = Fields { b: bytes, big };
    let at = f.u32(4)? as usize;
    let n = usize::from(f.u16(at)?);
    if at + 2 + 12 * n > bytes.len() {
        return None;
    }
    Some(
        (0..n)
            .filter_map(|k| {
                let e = at + 2 + 12 * k;
                Some((f.u16(e)?, f.u16(e + 2)?, f.u32(e + 4)?, e + 8))
            })
            .collect(),
    )
}

pub(crate) fn is_park(bytes: &[u8]) -> bool {
    let Some(big) = tiff_order(bytes) else { return false };
    let f = Fields { b: bytes, big };
    ifd(bytes).is_some_and(|e| e.iter().any(|&(t, _, _, at)| t == TAG_MAGIC && f.u32(at) == Some(PARK_MAGIC)))
}

/// UTF-16LE text of `chars` characters at `at`, up to the first NUL.
fn utf16(b: &[u8], at: usize, chars: usize) -> String {
    let units: Vec<u16> = (0..chars)
        .filter_map(|k| b.get(at + 2 * k..at + 2 * k + 2))
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    let end = units.iter().position(|&u| u == 0).unwrap_or(units.len());
    clean(&String::from_utf16_lossy(&units[..end]))
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    let big = tiff_order(bytes).ok_or_else(|| bad("not a TIFF file: it does not start with `II*` or `MM*`".into()))?;
    let entries =
        ifd(bytes).ok_or_else(|| bad("the TIFF's first image directory lies past the end of the file".into()))?;
    if !is_park(bytes) {
        return Err(bad(
            "a TIFF without the Park Systems tags (50432 = 0x0E031301): not a Park Systems AFM file".into()
        ));
    }
    let f = Fields { b: bytes, big };
    let find = |tag: u16| entries.iter().find(|e| e.0 == tag).copied();
    let version = find(TAG_VERSION).and_then(|e| f.u32(e.3)).unwrap_or(0);
    let header_len = match version {
        0x0100_0001 => HEADER_V1,
        0x0100_0002 => HEADER_V2,
        v => return Err(bad(format!("Park version {v:#x}: expected 0x1000001 or 0x1000002"))),
    };
    // A tag's bytes: in place when they fit in the 4-byte field, else at the offset it holds.
    let block = |tag: u16| -> Result<(usize, usize), TopographyError> {
        let (_, kind, count, at) = find(tag).ok_or_else(|| bad(format!("no TIFF tag {tag}")))?;
        let size: u64 = match kind {
            1 | 2 | 6 | 7 => 1,
            3 | 8 => 2,
            4 | 9 | 11 => 4,
            _ => 8,
        };
        let len = u64::from(count) * size;
        let start = if len <= 4 { at as u64 } else { u64::from(f.u32(at).unwrap_or(u32::MAX)) };
        if start + len > bytes.len() as u64 {
            return Err(bad(format!(
                "TIFF tag {tag}: {len} bytes from byte {start} run past the end ({} bytes)",
                bytes.len()
            )));
        }
        Ok((start as usize, len as usize))
    };
    let (h_at, h_len) = block(TAG_HEADER)?;
    if (h_len as u64) < header_len {
        return Err(bad(format!("a Park header of {h_len} bytes: version {version:#x} has {header_len}")));
    }
    let h = Fields::le(&bytes[h_at..h_at + h_len]);
    let image_type = h.u32(0).unwrap_or(u32::MAX);
    if image_type != 0 {
        return Err(bad(format!(
            "image type {image_type}: only a 2-D map (0) is read, not a line profile or spectroscopy"
        )));
    }
    let (nx, ny) = (u64::from(h.u32(100).unwrap_or(0)), u64::from(h.u32(104).unwrap_or(0)));
    crate::map::check_grid_size(origin, nx, ny)?;
    let sample = match if header_len == HEADER_V2 { h.u32(348).unwrap_or(u32::MAX) } else { 0 } {
        0 => Sample::I16,
        1 => Sample::I32,
        2 => Sample::F32,
        t => return Err(bad(format!("data type {t}: expected 0 (int16), 1 (int32) or 2 (float32)"))),
    };
    let (d_at, d_len) = block(TAG_DATA)?;
    if (d_len as u64) < nx * ny * sample.bytes() as u64 {
        return Err(bad(format!(
            "the data tag holds {d_len} bytes, a {nx} x {ny} map of {} bytes per sample needs {}",
            sample.bytes(),
            nx * ny * sample.bytes() as u64
        )));
    }
    let get = |at| h.f64(at).unwrap_or(f64::NAN);
    let (sx_um, sy_um) = (get(140), get(148));
    let size_m =
        (sx_um.is_finite() && sy_um.is_finite() && sx_um > 0.0 && sy_um > 0.0).then_some((sx_um * 1e-6, sy_um * 1e-6));
    let (gain, scale, offset) = (get(220), get(228), get(236));
    let scale = if scale == 0.0 { 1.0 } else { scale };
    if !(gain.is_finite() && scale.is_finite() && offset.is_finite() && gain != 0.0) {
        return Err(bad(format!(
            "data gain {gain:e}, scale {scale:e}, offset {offset:e}: expected finite values, the gain other than 0"
        )));
    }
    let unit = match utf16(&bytes[h_at..h_at + h_len], 244, 8) {
        u if u.is_empty() => "µm".to_string(),
        u => u,
    };
    let height_unit_m = length_unit(&unit);
    let name = utf16(&bytes[h_at..h_at + h_len], 4, 32);
    Ok(vec![Channel {
        info: ChannelInfo {
            index: 0,
            is_height: height_unit_m.is_some(),
            name: if name.is_empty() { "Default".into() } else { name },
            nx: nx as usize,
            ny: ny as usize,
            size_m,
            unit: if height_unit_m.is_none() { excerpt(&unit).trim_matches('`').to_string() } else { unit },
            height_unit_m,
        },
        values: Values::Raster(Raster {
            offset: d_at,
            sample,
            big_endian: false,
            flip_x: false,
            flip_y: true,
            scale: scale * gain,
            shift: offset * gain,
            row_bytes: None,
            invalid: None,
        }),
        unreadable: None,
    }])
}
