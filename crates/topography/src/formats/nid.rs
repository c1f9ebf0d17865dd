//! Nanosurf `.nid` (and `.ezd`) files (easyScan, FlexAFM, DriveAFM).
//!
//! Layout (as Gwyddion's `nanosurf` module and SurfaceTopography read it): an INI-style text
//! header starting `[DataSet]` (CR LF lines; `[Section]` and `Key=Value`), then `#!` and the
//! binary data. `[DataSet]` gives `GroupCount` and per group `Gr<i>-Count` and, for each stored
//! data set `j`, `Gr<i>-Ch<j>=<section>` (absent entries have no data); each data set's section
//! gives `Points` (x), `Lines` (y), `Frame` (e.g. `Scan forward`), the axes `Dim0Range`,
//! `Dim1Range` (scan size) with `Dim0Unit`, `Dim1Unit`, the values' `Dim2Name`, `Dim2Unit`,
//! `Dim2Range`, `Dim2Min`, and the samples' `SaveMode` (`Binary`), `SaveBits` (16 or 32),
//! `SaveSign` (`Signed`/`Unsigned`) and `SaveOrder` (`Intel` little-endian, else big-endian). The
//! data sets' samples follow `#!` in that order, x fastest, the last row first. A value is
//! `sample x Dim2Range / 2^SaveBits + Dim2Min` (+ `Dim2Range / 2` for signed samples) in
//! `Dim2Unit`. Channels are named `Frame (Dim2Name)`; those whose unit is a length are heights.
//!
//! Not read (refused): text data (`SaveMode` other than `Binary`), sample sizes other than 16 or 32
//! bits (8-bit sets are listed and refused).

use stiction_units::text::excerpt;

use super::{Channel, ChannelInfo, Raster, Sample, Values, clean, height_like, length_unit};
use crate::TopographyError;

/// Longest header searched for the `#!` data marker.
const MAX_HEADER: usize = 4 << 20;
/// Most data sets listed.
const MAX_SETS: u64 = 1024;

pub(crate) fn is_nid(bytes: &[u8]) -> bool {
    bytes.starts_with(b"[DataSet]\r\n") || bytes.starts_with(b"[DataSet]\n")
}

type Section = Vec<(String, String)>;

fn get<'a>(s: &'a Section, k: &str) -> Option<&'a str> {
    s.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str())
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if !is_nid(bytes) {
        return Err(bad("not a Nanosurf NID file: it does not start with `[DataSet]`".into()));
    }
    let head = &bytes[..bytes.len().min(MAX_HEADER)];
    // The data marker `#!` at the start of a line.
    let data_at = head
        .windows(3)
        .position(|w| w[0] == b'\n' && w[1] == b'#' && w[2] == b'!')
        .map(|k| k + 3)
        .ok_or_else(|| bad(format!("no `#!` data marker in the first {MAX_HEADER} bytes")))?;
    let text: String = head[..data_at - 2].iter().map(|&b| char::from(b)).collect();
    let mut sections: Vec<(String, Section)> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        if t.starts_with('[') && t.ends_with(']') {
            sections.push((t[1..t.len() - 1].to_string(), Vec::new()));
        } else if let (Some((key, value)), Some(s)) = (t.split_once('='), sections.last_mut()) {
            s.1.push((key.trim().to_string(), value.trim().to_string()));
        } else {
            return Err(TopographyError::format(origin, k as u64 + 1, format!("{}: not `Key=Value`", excerpt(t))));
        }
    }
    let section = |n: &str| sections.iter().find(|(m, _)| m == n).map(|(_, s)| s);
    let top = section("DataSet").ok_or_else(|| bad("no `[DataSet]` section".into()))?;
    let count = |s: &Section, k: &str| -> Result<u64, TopographyError> {
        let v = get(s, k).ok_or_else(|| bad(format!("no `{k}` in the header")))?;
        v.parse::<u64>()
            .ok()
            .filter(|&n| n <= MAX_SETS)
            .ok_or_else(|| bad(format!("`{k}` = {}: expected a whole number up to {MAX_SETS}", excerpt(v))))
    };
    let groups = count(top, "GroupCount")?;
    let mut list = Vec::new();
    let mut offset = data_at as u64;
    for i in 0..groups {
        for j in 0..count(top, &format!("Gr{i}-Count"))? {
            let Some(name) = get(top, &format!("Gr{i}-Ch{j}")) else { continue };
            let set =
                section(name).ok_or_else(|| bad(format!("data set {} has no section in the header", excerpt(name))))?;
            let field = |k: &str| get(set, k).unwrap_or("");
            let whole = |k: &str| -> Result<u64, TopographyError> {
                field(k).parse().map_err(|_| {
                    bad(format!("data set {}: `{k}` = {}: expected a whole number", excerpt(name), excerpt(field(k))))
                })
            };
            let (nx, ny) = (whole("Points")?, whole("Lines")?);
            crate::map::check_grid_size(origin, nx, ny)?;
            let signed = field("SaveSign") == "Signed";
            let bits = whole("SaveBits")?;
            let sample = match (bits, signed) {
                (16, true) => Some(Sample::I16),
                (16, false) => Some(Sample::U16),
                (32, true) => Some(Sample::I32),
                (32, false) => Some(Sample::U32),
                (8, true) => Some(Sample::I8),
                (8, false) => Some(Sample::U8),
                _ => None,
            };
            let sample = sample.ok_or_else(|| {
                bad(format!("data set {}: {bits} bits per sample: expected 8, 16 or 32", excerpt(name)))
            })?;
            if field("SaveMode") != "Binary" {
                return Err(bad(format!(
                    "data set {}: `SaveMode` {}: only binary data are read",
                    excerpt(name),
                    excerpt(field("SaveMode"))
                )));
            }
            let bytes_needed = nx * ny * sample.bytes() as u64;
            if offset + bytes_needed > bytes.len() as u64 {
                return Err(bad(format!(
                    "data set {}: {nx} x {ny} samples of {} bytes from byte {offset} run past the end ({} bytes)",
                    excerpt(name),
                    sample.bytes(),
                    bytes.len()
                )));
            }
            let number = |k: &str| field(k).parse::<f64>().ok().filter(|v| v.is_finite());
            let unit = clean(field("Dim2Unit"));
            let height_unit_m = length_unit(&unit);
            let size_m = match (number("Dim0Range"), number("Dim1Range")) {
                (Some(a), Some(b)) if a > 0.0 && b > 0.0 => {
                    let ux = length_unit(field("Dim0Unit"));
                    let uy = length_unit(field("Dim1Unit"));
                    match (ux, uy) {
                        (Some(ux), Some(uy)) => Some((a * ux, b * uy)),
                        _ => None,
                    }
                }
                _ => None,
            };
            let range = number("Dim2Range").filter(|r| *r != 0.0);
            let min = number("Dim2Min").unwrap_or(0.0);
            let full = 2f64.powi(bits as i32);
            let dim2 = clean(field("Dim2Name"));
            let channel_name = clean(&format!("{} ({dim2})", field("Frame")));
            list.push(Channel {
                info: ChannelInfo {
                    index: list.len(),
                    name: channel_name,
                    nx: nx as usize,
                    ny: ny as usize,
                    size_m,
                    is_height: height_unit_m.is_some() && height_like(&dim2),
                    unit,
                    height_unit_m,
                },
                values: Values::Raster(Raster {
                    offset: offset as usize,
                    sample,
                    big_endian: field("SaveOrder") != "Intel",
                    flip_x: false,
                    flip_y: true,
                    scale: range.unwrap_or(1.0) / full,
                    row_bytes: None,
                    shift: min + if signed { range.unwrap_or(0.0) / 2.0 } else { 0.0 },
                    invalid: None,
                }),
                unreadable: range.is_none().then(|| "no finite `Dim2Range`: the values have no scale".to_string()),
            });
            offset += bytes_needed;
        }
    }
    if list.is_empty() {
        return Err(bad("no data set: the file holds no map".into()));
    }
    Ok(list)
}
