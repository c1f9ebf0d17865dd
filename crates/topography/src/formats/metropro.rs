//! Zygo MetroPro `.dat` files (white-light and laser interferometers).
//!
//! Layout (Zygo's "MetroPro Reference Guide", section "Data file format", as Gwyddion's
//! `metropro` module and SurfaceTopography read it): big-endian; the magic number `88 1b 03 6f`
//! (header format 1), `88 1b 03 70` (2) or `88 1b 03 71` (3); at 4 the header format (uint16),
//! 6 the header size (uint32: 834 for formats 1 and 2, 4096 for 3); the intensity matrix at 48
//! (int16 x, y, uint16 width, height, buckets; int16 range; uint32 bytes at 60) and the phase
//! matrix at 64 (int16 x, y, uint16 width 68, height 70; uint32 bytes 72); at 164 the
//! interferometric scale factor S, 168 the wavelength W \[m\], 176 the obliquity factor O, 184 the
//! lateral resolution \[m per pixel\] (all float32), 218 the phase resolution (int16: 0, 1, 2 for
//! R = 4096, 32768, 131072) and 232 the sign (int16, 1: inverted). After the header come the
//! intensity bytes, then the phase as int32, `width` per row, the first row first. A height is
//! `phase x S x O x W / R` metres (negated when the sign is 1); a phase of 2147483640 or more is
//! invalid (missing).
//!
//! Not read (refused): a phase resolution outside 0 to 2, a file without lateral resolution has no
//! pixel size (asked for by `--pixel-size`).

use super::fields::Fields;
use super::{Channel, ChannelInfo, Missing, Raster, Sample, Values};
use crate::TopographyError;

const MAGIC: [[u8; 4]; 3] = [[0x88, 0x1b, 0x03, 0x6f], [0x88, 0x1b, 0x03, 0x70], [0x88, 0x1b, 0x03, 0x71]];
/// The first invalid phase value.
const INVALID_PHASE: f64 = 2_147_483_640.0;

pub(crate) fn is_metropro(bytes: &[u8]) -> bool {
    bytes.len() >= 4 && MAGIC.iter().any(|m| bytes[..4] == m[..])
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if !is_metropro(bytes) {
        return Err(bad("not a Zygo MetroPro file: no MetroPro magic number at byte 0".into()));
    }
    let f = Fields::be(bytes);
    let short = || bad(format!("{} bytes: shorter than a MetroPro header (834)", bytes.len()));
    let format = f.u16(4).ok_or_else(short)?;
    let header = f.u32(6).ok_or_else(short)?;
    let expected = if bytes[3] == 0x71 { 4096 } else { 834 };
    if header != expected || u32::from(format) != u32::from(bytes[3] - 0x6e) {
        return Err(bad(format!(
            "header format {format} of {header} bytes: expected format {} of {expected} bytes for its magic number",
            bytes[3] - 0x6e
        )));
    }
    if bytes.len() < header as usize {
        return Err(short());
    }
    let u16_at = |at| u64::from(f.u16(at).unwrap_or(0));
    let intensity_bytes = u64::from(f.u32(60).unwrap_or(0));
    let (nx, ny) = (u16_at(68), u16_at(70));
    let phase_bytes = u64::from(f.u32(72).unwrap_or(0));
    if nx == 0 || ny == 0 {
        return Err(bad("no phase data (a 0-pixel phase matrix): the file holds no heights".into()));
    }
    crate::map::check_grid_size(origin, nx, ny)?;
    if phase_bytes != nx * ny * 4 {
        return Err(bad(format!(
            "{phase_bytes} phase bytes for a {nx} x {ny} matrix of int32: expected {}",
            nx * ny * 4
        )));
    }
    let offset = u64::from(header) + intensity_bytes;
    if offset + phase_bytes > bytes.len() as u64 {
        return Err(bad(format!(
            "the header ({header} bytes), {intensity_bytes} intensity bytes and {phase_bytes} phase bytes need {} bytes, the file has {}",
            offset + phase_bytes,
            bytes.len()
        )));
    }
    let get = |at| f.f32(at).unwrap_or(f64::NAN);
    let (s, w, o, lateral) = (get(164), get(168), get(176), get(184));
    let r = match f.i16(218).unwrap_or(-1) {
        0 => 4096.0,
        1 => 32768.0,
        2 => 131072.0,
        p => return Err(bad(format!("phase resolution {p}: expected 0, 1 or 2"))),
    };
    let mut scale = s * o * w / r;
    if !(scale.is_finite() && scale != 0.0) {
        return Err(bad(format!(
            "height scale S x O x W / R = {s:e} x {o:e} x {w:e} / {r}: expected a finite value other than 0"
        )));
    }
    if f.i16(232) == Some(1) {
        scale = -scale;
    }
    let size_m = (lateral.is_finite() && lateral > 0.0).then_some((lateral * nx as f64, lateral * ny as f64));
    Ok(vec![Channel {
        info: ChannelInfo {
            index: 0,
            name: "Height".into(),
            nx: nx as usize,
            ny: ny as usize,
            size_m,
            unit: "m".into(),
            height_unit_m: Some(1.0),
            is_height: true,
        },
        values: Values::Raster(Raster {
            offset: offset as usize,
            sample: Sample::I32,
            big_endian: true,
            flip_x: false,
            flip_y: false,
            scale,
            shift: 0.0,
            row_bytes: None,
            invalid: Some(Missing::AtLeast(INVALID_PHASE)),
        }),
        unreadable: None,
    }])
}
