//! WSxM image files (`.stp`, `.top`, and the other image extensions WSxM writes).
//!
//! Layout (as Gwyddion's `wsxmfile` module, which reads and writes the format, and
//! SurfaceTopography read it): a text header of lines `WSxM file copyright ...`, `SxM Image file`,
//! `Image header size: N`, then `[Section]` lines and `Key: value` lines up to `[Header end]`; then
//! `Number of columns x Number of rows` little-endian samples (`Image Data Type`: `double`,
//! `float`, or `short`/`integer` for int16; int16 when not given), x fastest. The header size is
//! not used for the data offset (Gwyddion notes that writers miscalculate it): the samples follow
//! the `[Header end]` line. `Control::X Amplitude`, `Y Amplitude` give the scan size with its
//! unit; `General Info::Z Amplitude` the range of the heights with their unit.
//!
//! Height scale: float and double samples are heights in the Z unit (the header's amplitude is
//! their range, printed to six digits); int16 samples are scaled by `Z Amplitude / (max - min)`
//! with the range of the samples themselves (Gwyddion's rule; SurfaceTopography takes the range
//! from the header's `Miscellaneous::Maximum`/`Minimum`, printed to six digits). Orientation: the
//! image is stored turned by 180 degrees: the file's last row is row 0 and each row runs from
//! the right (both readers).
//!
//! Not read (refused): a Z unit that is not a length is listed (e.g. `V`) but not read as heights.

use stiction_units::text::excerpt;

use super::{Channel, ChannelInfo, Raster, Sample, Values, clean, length_unit};
use crate::TopographyError;

/// Longest header searched for `[Header end]`.
const MAX_HEADER: usize = 1 << 20;

pub(crate) fn is_wsxm(bytes: &[u8]) -> bool {
    bytes.starts_with(b"WSxM file copyright")
}

/// `value unit` of a header entry: the number and the unit text.
fn amplitude(v: &str) -> Option<(f64, String)> {
    let t = v.trim();
    let end = t.find(|c: char| c.is_whitespace()).unwrap_or(t.len());
    let x: f64 = t[..end].parse().ok()?;
    Some((x, clean(&t[end..])))
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if !is_wsxm(bytes) {
        return Err(bad("not a WSxM file: it does not start with `WSxM file copyright`".into()));
    }
    let head = &bytes[..bytes.len().min(MAX_HEADER)];
    let marker = b"[Header end]";
    let end = head
        .windows(marker.len())
        .position(|w| w == marker)
        .ok_or_else(|| bad(format!("no `[Header end]` in the first {MAX_HEADER} bytes")))?;
    let mut data_at = end + marker.len();
    for &c in [b'\r', b'\n'].iter() {
        if bytes.get(data_at) == Some(&c) {
            data_at += 1;
        }
    }
    let text: String = head[..end].iter().map(|&b| char::from(b)).collect();
    let mut lines = text.lines();
    if lines.nth(1).map(str::trim) != Some("SxM Image file") {
        return Err(bad("the second line is not `SxM Image file`: not a WSxM image".into()));
    }
    let mut section = String::new();
    let mut entries: Vec<(String, String)> = Vec::new();
    for (k, line) in text.lines().enumerate().skip(3) {
        let t = line.trim();
        if t.starts_with('[') && t.ends_with(']') {
            section = t[1..t.len() - 1].to_string();
        } else if let Some((key, value)) = t.split_once(':') {
            entries.push((format!("{section}::{}", key.trim()), value.trim().to_string()));
        } else if !t.is_empty() {
            return Err(TopographyError::format(origin, k as u64 + 1, format!("{}: not `Key: value`", excerpt(t))));
        }
    }
    let get = |k: &str| entries.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str());
    let int = |k: &str| -> Result<u64, TopographyError> {
        let v = get(k).ok_or_else(|| bad(format!("no `{k}` in the header")))?;
        v.parse::<u64>().map_err(|_| bad(format!("`{k}` = {}: expected a whole number", excerpt(v))))
    };
    let (nx, ny) = (int("General Info::Number of columns")?, int("General Info::Number of rows")?);
    crate::map::check_grid_size(origin, nx, ny)?;
    let sample = match get("General Info::Image Data Type").unwrap_or("short") {
        "double" => Sample::F64,
        "float" => Sample::F32,
        "short" | "integer" => Sample::I16,
        t => return Err(bad(format!("`Image Data Type` = {}: expected double, float, short or integer", excerpt(t)))),
    };
    let need = nx * ny * sample.bytes() as u64;
    if data_at as u64 + need > bytes.len() as u64 {
        return Err(bad(format!(
            "{nx} x {ny} samples of {} bytes from byte {data_at} need {} bytes, the file has {}",
            sample.bytes(),
            data_at as u64 + need,
            bytes.len()
        )));
    }
    let size = |k: &str| -> Result<Option<f64>, TopographyError> {
        let Some(v) = get(k) else { return Ok(None) };
        let (x, unit) =
            amplitude(v).ok_or_else(|| bad(format!("`{k}` = {}: expected a number and a unit", excerpt(v))))?;
        match length_unit(&unit) {
            Some(u) if x.is_finite() && x > 0.0 => Ok(Some(x * u)),
            Some(_) => Err(bad(format!("`{k}` = {x:e}: expected a finite value > 0"))),
            None => Ok(None),
        }
    };
    let (sx, sy) = (size("Control::X Amplitude")?, size("Control::Y Amplitude")?);
    let size_m = match (sx, sy) {
        (Some(a), Some(b)) => Some((a, b)),
        (Some(a), None) if get("Control::Y Amplitude").is_none() => Some((a, a)),
        _ => None,
    };
    let (z_amp, z_unit) = match get("General Info::Z Amplitude") {
        Some(v) => {
            amplitude(v).ok_or_else(|| bad(format!("`Z Amplitude` = {}: expected a number and a unit", excerpt(v))))?
        }
        None => return Err(bad("no `General Info::Z Amplitude`: the heights have no scale".into())),
    };
    if !(z_amp.is_finite() && z_amp > 0.0) {
        return Err(bad(format!("`Z Amplitude` = {z_amp:e}: expected a finite value > 0")));
    }
    let height_unit_m = length_unit(&z_unit);
    let name = get("General Info::Acquisition channel").map(clean).filter(|n| !n.is_empty());
    let offset = data_at;
    let raster = Raster {
        offset,
        sample,
        big_endian: false,
        flip_x: true,
        flip_y: true,
        scale: 1.0,
        shift: 0.0,
        row_bytes: None,
        invalid: None,
    };
    let mut ch = Channel {
        info: ChannelInfo {
            index: 0,
            name: name.unwrap_or_else(|| "Default".into()),
            nx: nx as usize,
            ny: ny as usize,
            size_m,
            is_height: height_unit_m.is_some(),
            unit: z_unit,
            height_unit_m,
        },
        values: Values::Raster(raster),
        unreadable: None,
    };
    if sample == Sample::I16 {
        // Z Amplitude over the range of the samples.
        let s = &bytes[offset..offset + need as usize];
        let (lo, hi) = s
            .chunks_exact(2)
            .map(|c| i16::from_le_bytes([c[0], c[1]]))
            .fold((i16::MAX, i16::MIN), |(a, b), v| (a.min(v), b.max(v)));
        if hi > lo {
            if let Values::Raster(r) = &mut ch.values {
                r.scale = z_amp / (f64::from(hi) - f64::from(lo));
            }
        } else {
            ch.unreadable = Some("every sample is equal: the Z amplitude gives no scale".into());
        }
    }
    Ok(vec![ch])
}
