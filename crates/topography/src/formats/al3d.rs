//! Alicona (Bruker Alicona) `.al3d` files (InfiniteFocus focus-variation microscopes).
//!
//! Layout (as Gwyddion's `alicona` module and SurfaceTopography read it): the magic
//! `AliconaImaging\0\r\n` (17 bytes), then 52-byte tags (a 20-byte key, a 30-byte value, both
//! NUL-padded text, and CR LF): `Version`, `TagCount` (the number of tags that follow), then tags
//! such as `Cols`, `Rows`, `PixelSizeXMeter`, `PixelSizeYMeter`, `InvalidPixelValue` and
//! `DepthImageOffset`; a 256-byte comment. The depth image at `DepthImageOffset` is little-endian
//! float32 heights in metres, `Cols` per row padded to a multiple of 8 bytes, row 0 first. A
//! point that is NaN or equal to `InvalidPixelValue` (as float32) is missing.

use stiction_units::text::excerpt;

use super::{Channel, ChannelInfo, Missing, Raster, Sample, Values, latin1};
use crate::TopographyError;

const MAGIC: &[u8] = b"AliconaImaging\x00\r\n";
const TAG: usize = 52;
/// Most tags read.
const MAX_TAGS: u64 = 10_000;

pub(crate) fn is_al3d(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if !is_al3d(bytes) {
        return Err(bad("not an Alicona AL3D file: no `AliconaImaging` magic at byte 0".into()));
    }
    let tag = |k: usize| -> Result<(String, String), TopographyError> {
        let at = MAGIC.len() + k * TAG;
        let b =
            bytes.get(at..at + TAG).ok_or_else(|| bad(format!("tag {k} at byte {at} is past the end of the file")))?;
        if &b[50..52] != b"\r\n" {
            return Err(bad(format!("tag {k} at byte {at} does not end in CR LF")));
        }
        Ok((latin1(&b[..20]).trim().to_string(), latin1(&b[20..50]).trim().to_string()))
    };
    let (k0, version) = tag(0)?;
    let (k1, count) = tag(1)?;
    if k0 != "Version" || k1 != "TagCount" {
        return Err(bad("the first two tags are not `Version` and `TagCount`".into()));
    }
    if version != "1" {
        return Err(bad(format!("version {}: only version 1 is read", excerpt(&version))));
    }
    let count: u64 = count
        .parse()
        .ok()
        .filter(|&n| n <= MAX_TAGS && MAGIC.len() as u64 + (n + 2) * TAG as u64 <= bytes.len() as u64)
        .ok_or_else(|| bad(format!("`TagCount` {}: more tags than the file holds", excerpt(&count))))?;
    let tags = (2..2 + count as usize).map(tag).collect::<Result<Vec<_>, _>>()?;
    let get = |k: &str| tags.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str());
    let whole = |k: &str| -> Result<u64, TopographyError> {
        let v = get(k).ok_or_else(|| bad(format!("no `{k}` tag")))?;
        v.parse().map_err(|_| bad(format!("`{k}` = {}: expected a whole number", excerpt(v))))
    };
    let (nx, ny) = (whole("Cols")?, whole("Rows")?);
    crate::map::check_grid_size(origin, nx, ny)?;
    let offset = whole("DepthImageOffset")?;
    let row_bytes = (nx * 4).div_ceil(8) * 8;
    let need = if ny == 0 { 0 } else { row_bytes * (ny - 1) + nx * 4 };
    if offset.checked_add(need).is_none_or(|e| e > bytes.len() as u64) {
        return Err(bad(format!(
            "a {nx} x {ny} depth image from byte {offset} runs past the end ({} bytes)",
            bytes.len()
        )));
    }
    let pixel = |k: &str| get(k).and_then(|v| v.parse::<f64>().ok()).filter(|p| p.is_finite() && *p > 0.0);
    let size_m = match (pixel("PixelSizeXMeter"), pixel("PixelSizeYMeter")) {
        (Some(px), Some(py)) => Some((px * nx as f64, py * ny as f64)),
        _ => None,
    };
    let invalid = get("InvalidPixelValue")
        .and_then(|v| v.parse::<f64>().ok())
        .filter(|v| v.is_finite())
        .map(|v| Missing::Equal(f64::from(v as f32)));
    Ok(vec![Channel {
        info: ChannelInfo {
            index: 0,
            name: "Depth".into(),
            nx: nx as usize,
            ny: ny as usize,
            size_m,
            unit: "m".into(),
            height_unit_m: Some(1.0),
            is_height: true,
        },
        values: Values::Raster(Raster {
            offset: offset as usize,
            sample: Sample::F32,
            big_endian: false,
            flip_x: false,
            flip_y: false,
            scale: 1.0,
            shift: 0.0,
            row_bytes: Some(row_bytes as usize),
            invalid,
        }),
        unreadable: None,
    }])
}
