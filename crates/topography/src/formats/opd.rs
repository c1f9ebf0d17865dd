//! Wyko / Bruker Vision `.opd` files (white-light interferometers).
//!
//! Layout (the Vision OPD block format, as Gwyddion's `wyko` module and SurfaceTopography read
//! it): two bytes, then a directory of 24-byte block headers (a 16-byte name, an int16 type, an
//! int32 length, a uint16 attribute), the first being `Directory` itself, whose length is the
//! directory's size; the blocks' contents follow the directory in its order, each of its length.
//! A block of type 3 is an array: `nx`, `ny` and the bytes per sample (1: uint8, 2: int16,
//! 4: float32), then the samples with y fastest, the last y first (row 0 of the map is the
//! file's last value of each column). Scalars: `Wavelength` (nm, float), `Mult` (int16),
//! `Pixel_size` (mm, float), `Aspect` (the y/x pixel ratio). A height is
//! `sample x Wavelength / Mult` nm; an int16 sample of 32766 or more, and a float32 sample that
//! is not finite or is 1e38 or more, is undefined (missing).
//!
//! Not read: files without `Wavelength` (no height scale; refused), arrays whose names are not
//! height arrays (`RAW DATA`, `RAW_DATA`, `OPD`, `Raw`, `SAMPLE_DATA`) are listed but not heights.

use stiction_units::text::excerpt;

use super::{Channel, ChannelInfo, Values, clean, latin1};
use crate::TopographyError;

const ENTRY: usize = 24;
const HEIGHT_ARRAYS: [&str; 5] = ["RAW DATA", "RAW_DATA", "OPD", "Raw", "SAMPLE_DATA"];

pub(crate) fn is_opd(bytes: &[u8]) -> bool {
    bytes.len() > 11 && &bytes[2..11] == b"Directory"
}

struct Block<'a> {
    name: String,
    kind: i16,
    data: &'a [u8],
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if !is_opd(bytes) || bytes.len() < 2 + ENTRY {
        return Err(bad("not a Wyko OPD file: no `Directory` block at byte 2".into()));
    }
    let head = |at: usize| -> (String, i16, i64) {
        let b = &bytes[at..at + ENTRY];
        (
            latin1(&b[..16]),
            i16::from_le_bytes([b[16], b[17]]),
            i64::from(i32::from_le_bytes([b[18], b[19], b[20], b[21]])),
        )
    };
    let (_, _, dir_len) = head(2);
    if dir_len < ENTRY as i64 || dir_len % ENTRY as i64 != 0 || 2 + dir_len as u64 > bytes.len() as u64 {
        return Err(bad(format!(
            "the directory's length {dir_len} is not a multiple of {ENTRY} within the file's {} bytes",
            bytes.len()
        )));
    }
    let mut at = 2 + dir_len as usize;
    let mut blocks = Vec::new();
    for k in 1..dir_len as usize / ENTRY {
        let (name, kind, len) = head(2 + k * ENTRY);
        if len < 0 {
            return Err(bad(format!("block {}: length {len}", excerpt(&name))));
        }
        if len == 0 {
            continue;
        }
        let end = at.checked_add(len as usize).filter(|&e| e <= bytes.len()).ok_or_else(|| {
            bad(format!(
                "block {} of {len} bytes from byte {at} runs past the end ({} bytes)",
                excerpt(&name),
                bytes.len()
            ))
        })?;
        blocks.push(Block { name: clean(&name), kind, data: &bytes[at..end] });
        at = end;
    }
    let scalar = |name: &str| -> Option<f64> {
        let b = blocks.iter().find(|b| b.name == name && b.kind != 3)?;
        let d = b.data;
        match (b.kind, d.len()) {
            (6, 2) | (7, 2) => Some(f64::from(i16::from_le_bytes([d[0], d[1]]))),
            (6, 4) | (12, 4..) => Some(f64::from(i32::from_le_bytes([d[0], d[1], d[2], d[3]]))),
            (7, 4..) => Some(f64::from(f32::from_le_bytes([d[0], d[1], d[2], d[3]]))),
            (8, 8..) => Some(f64::from_le_bytes(d[..8].try_into().ok()?)),
            _ => None,
        }
    };
    let wavelength = scalar("Wavelength")
        .filter(|w| w.is_finite() && *w > 0.0)
        .ok_or_else(|| bad("no usable `Wavelength` block: the heights have no scale".into()))?;
    let mult = scalar("Mult").unwrap_or(1.0);
    if !(mult.is_finite() && mult != 0.0) {
        return Err(bad(format!("`Mult` = {mult}: expected a finite value other than 0")));
    }
    let aspect = scalar("Aspect").unwrap_or(1.0);
    let pixel_mm = scalar("Pixel_size").filter(|p| p.is_finite() && *p > 0.0);
    if !(aspect.is_finite() && aspect > 0.0) {
        return Err(bad(format!("`Aspect` = {aspect}: expected a finite value > 0")));
    }
    let mut list = Vec::new();
    for b in blocks.iter().filter(|b| b.kind == 3) {
        let d = b.data;
        if d.len() < 6 {
            return Err(bad(format!("array {}: {} bytes, less than its 6-byte header", excerpt(&b.name), d.len())));
        }
        let nx = u64::from(u16::from_le_bytes([d[0], d[1]]));
        let ny = u64::from(u16::from_le_bytes([d[2], d[3]]));
        let size = u16::from_le_bytes([d[4], d[5]]);
        crate::map::check_grid_size(origin, nx, ny)?;
        if ![1, 2, 4].contains(&size) {
            return Err(bad(format!("array {}: {size} bytes per sample: expected 1, 2 or 4", excerpt(&b.name))));
        }
        let need = (nx * ny * u64::from(size)) as usize;
        if d.len() - 6 < need {
            return Err(bad(format!(
                "array {}: {nx} x {ny} x {size} bytes, but the block holds {}",
                excerpt(&b.name),
                d.len() - 6
            )));
        }
        let (nx, ny, s) = (nx as usize, ny as usize, size as usize);
        let data = &d[6..6 + need];
        let scale = wavelength / mult;
        let value = |k: usize| -> f64 {
            let c = &data[k * s..(k + 1) * s];
            match s {
                1 => f64::from(c[0]) * scale,
                2 => {
                    let v = i16::from_le_bytes([c[0], c[1]]);
                    if v >= 32766 { f64::NAN } else { f64::from(v) * scale }
                }
                _ => {
                    let v = f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
                    if !v.is_finite() || v >= 1e38 { f64::NAN } else { f64::from(v) * scale }
                }
            }
        };
        // Sample (ix, jy) is at ix * ny + jy; row iy of the map is jy = ny - 1 - iy.
        let mut values = Vec::with_capacity(nx * ny);
        for iy in 0..ny {
            values.extend((0..nx).map(|ix| value(ix * ny + (ny - 1 - iy))));
        }
        let is_height = HEIGHT_ARRAYS.contains(&b.name.as_str());
        list.push(Channel {
            info: ChannelInfo {
                index: list.len(),
                name: b.name.clone(),
                nx,
                ny,
                size_m: pixel_mm.map(|p| (p * 1e-3 * nx as f64, p * 1e-3 * aspect * ny as f64)),
                unit: if is_height { "nm".into() } else { String::new() },
                height_unit_m: is_height.then_some(1e-9),
                is_height,
            },
            values: Values::Parsed(values),
            unreadable: None,
        });
    }
    if list.is_empty() {
        return Err(bad("no array block: the file holds no map".into()));
    }
    Ok(list)
}
