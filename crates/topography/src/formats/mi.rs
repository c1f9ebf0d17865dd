//! Agilent / Keysight (Molecular Imaging) PicoView `.mi` image files.
//!
//! Layout (as Gwyddion's `mifile` module and SurfaceTopography read it): text lines of a key in
//! the first 14 characters and its value after them (lines that start with a space continue the
//! previous one), from `fileType Image` to the line whose key is `data`, whose value is the sample
//! type: `BINARY` (int16) or `BINARY_32` (int32), little-endian. `xPixels`, `yPixels` give the
//! grid, `xLength`, `yLength` the scan size in metres. Each `bufferLabel` line opens a channel
//! (buffer) whose `bufferRange` and `bufferUnit` follow: a value is
//! `sample x bufferRange / 32768` (int16) or `/ 2147483648` (int32) in `bufferUnit`. The buffers'
//! samples follow the `data` line one after the other, x fastest, the last row first (row 0 of the
//! map is the file's last row).
//!
//! Not read (refused): spectroscopy files (`fileType Spectroscopy`) and text (ASCII) data.

use stiction_units::text::excerpt;

use super::{Channel, ChannelInfo, Raster, Sample, Values, clean, height_like, length_unit};
use crate::TopographyError;

const KEY_WIDTH: usize = 14;
/// Longest header searched for the `data` line.
const MAX_HEADER: usize = 1 << 20;

pub(crate) fn is_mi(bytes: &[u8]) -> bool {
    bytes.starts_with(b"fileType      Image") || bytes.starts_with(b"fileType      Spectroscopy")
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if !bytes.starts_with(b"fileType") {
        return Err(bad("not a PicoView MI file: it does not start with `fileType`".into()));
    }
    let mut at = 0usize;
    let mut global: Vec<(String, String)> = Vec::new();
    let mut buffers: Vec<Vec<(String, String)>> = Vec::new();
    let mut data_type = None;
    let mut line_no = 0u64;
    while at < bytes.len().min(MAX_HEADER) {
        let end = bytes[at..].iter().position(|&b| b == b'\n').map_or(bytes.len(), |k| at + k);
        let line: String = bytes[at..end].iter().map(|&b| char::from(b)).collect();
        let line = line.trim_end_matches('\r');
        at = end + 1;
        line_no += 1;
        if line.starts_with(' ') || line.is_empty() {
            continue;
        }
        let split = line.char_indices().nth(KEY_WIDTH).map_or(line.len(), |(k, _)| k);
        let (key, value) = (line[..split].trim().to_string(), line[split..].trim().to_string());
        if key == "data" {
            data_type = Some(value);
            break;
        }
        if key == "bufferLabel" {
            buffers.push(Vec::new());
        }
        match buffers.last_mut() {
            Some(b) => b.push((key, value)),
            None => global.push((key, value)),
        }
        if line_no > 100_000 {
            break;
        }
    }
    let get = |k: &str| global.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str());
    match get("fileType") {
        Some("Image") => {}
        Some("Spectroscopy") => return Err(bad("a spectroscopy MI file is not read: only images".into())),
        other => return Err(bad(format!("`fileType` {}: expected Image", excerpt(other.unwrap_or(""))))),
    }
    let sample = match data_type.as_deref() {
        Some("BINARY") | Some("") => Sample::I16,
        Some("BINARY_32") => Sample::I32,
        Some(t) => return Err(bad(format!("`data` {}: only BINARY and BINARY_32 are read, not text", excerpt(t)))),
        None => return Err(bad(format!("no `data` line in the first {MAX_HEADER} bytes"))),
    };
    let int = |k: &str| -> Result<u64, TopographyError> {
        let v = get(k).ok_or_else(|| bad(format!("no `{k}` in the header")))?;
        v.parse().map_err(|_| bad(format!("`{k}` = {}: expected a whole number", excerpt(v))))
    };
    let (nx, ny) = (int("xPixels")?, int("yPixels")?);
    crate::map::check_grid_size(origin, nx, ny)?;
    if buffers.is_empty() {
        return Err(bad("no `bufferLabel`: the file holds no channel".into()));
    }
    let per = nx * ny * sample.bytes() as u64;
    let need = at as u64 + per * buffers.len() as u64;
    if need > bytes.len() as u64 {
        return Err(bad(format!(
            "{} channels of {nx} x {ny} samples of {} bytes from byte {at} need {need} bytes, the file has {}",
            buffers.len(),
            sample.bytes(),
            bytes.len()
        )));
    }
    let length = |k: &str| get(k).and_then(|v| v.parse::<f64>().ok()).filter(|v| v.is_finite() && *v > 0.0);
    let size_m = match (length("xLength"), length("yLength")) {
        (Some(a), Some(b)) => Some((a, b)),
        _ => None,
    };
    let full = if sample == Sample::I32 { 2_147_483_648.0 } else { 32_768.0 };
    let mut list = Vec::with_capacity(buffers.len());
    for (k, b) in buffers.iter().enumerate() {
        let bget = |n: &str| b.iter().find(|(m, _)| m == n).map(|(_, v)| v.as_str());
        let name = clean(bget("bufferLabel").unwrap_or(""));
        let unit = clean(bget("bufferUnit").unwrap_or(""));
        let range = bget("bufferRange").and_then(|v| v.parse::<f64>().ok());
        let height_unit_m = length_unit(&unit);
        let unreadable = match range {
            Some(r) if r.is_finite() && r != 0.0 => None,
            _ => Some("no finite `bufferRange`: the values have no scale".to_string()),
        };
        list.push(Channel {
            info: ChannelInfo {
                index: k,
                is_height: height_unit_m.is_some() && (height_like(&name) || k == 0),
                name,
                nx: nx as usize,
                ny: ny as usize,
                size_m,
                unit,
                height_unit_m,
            },
            values: Values::Raster(Raster {
                offset: at + k * per as usize,
                sample,
                big_endian: false,
                flip_x: false,
                flip_y: true,
                scale: range.unwrap_or(1.0) / full,
                shift: 0.0,
                row_bytes: None,
                invalid: None,
            }),
            unreadable,
        });
    }
    Ok(list)
}
