//! ISO 25178-71 surface data files (`.sdf`), ASCII (`aISO-1.0`) and binary (`bISO-1.0`).
//!
//! Layout (ISO 25178-71, the format of the SDF of ISO 5436-2 for areal data): ASCII files have the
//! magic line, `Key = Value` lines (`NumPoints` columns along x, `NumProfiles` rows along y,
//! `Xscale`, `Yscale` the pixel steps in metres, `Zscale` the metres per stored value,
//! `DataType` 5 int16, 6 int32 or 7 double, `Compression` 0), a line `*`, the values (profile after
//! profile, `BAD` for a missing point), a line `*`, then an optional trailer. Binary files have an
//! 81-byte little-endian header (magic 8, ManufacID 10, CreateDate 12, ModDate 12, NumPoints u16,
//! NumProfiles u16, Xscale, Yscale, Zscale, Zresolution f64, Compression, DataType, CheckType u8)
//! and the samples after it; the type's smallest integer marks a missing point (NaN for doubles).
//! Profile 0 is row 0 (y = 0). Not read: compressed data (`Compression` other than 0).

use std::collections::HashMap;

use stiction_units::text::{MAX_LINE_BYTES, check_cell, check_line_bytes, excerpt};

use super::{Channel, ChannelInfo, Missing, Raster, Sample, Values};
use crate::{MAX_PIXELS, TopographyError};

const BINARY_HEADER: usize = 81;

pub(crate) fn is_sdf(bytes: &[u8]) -> bool {
    bytes.starts_with(b"aISO-1.0") || bytes.starts_with(b"bISO-1.0")
}

struct Header {
    nx: u64,
    ny: u64,
    xs: f64,
    ys: f64,
    zs: f64,
    compression: u64,
    data_type: u64,
}

fn channel(h: &Header, origin: &str, values: Values) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    crate::map::check_grid_size(origin, h.nx, h.ny)?;
    for (name, v) in [("Xscale", h.xs), ("Yscale", h.ys), ("Zscale", h.zs)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(bad(format!("`{name}` = {v:e}: expected a finite value > 0 (metres)")));
        }
    }
    if h.compression != 0 {
        return Err(bad(format!("`Compression` = {}: compressed data are not read (expected 0)", h.compression)));
    }
    Ok(vec![Channel {
        info: ChannelInfo {
            index: 0,
            name: "Default".into(),
            nx: h.nx as usize,
            ny: h.ny as usize,
            size_m: Some((h.xs * h.nx as f64, h.ys * h.ny as f64)),
            unit: "m".into(),
            height_unit_m: Some(1.0),
            is_height: true,
        },
        values,
        unreadable: None,
    }])
}

fn sample_of(data_type: u64, origin: &str) -> Result<(Sample, Option<Missing>), TopographyError> {
    match data_type {
        5 => Ok((Sample::I16, Some(Missing::Equal(f64::from(i16::MIN))))),
        6 => Ok((Sample::I32, Some(Missing::Equal(f64::from(i32::MIN))))),
        7 => Ok((Sample::F64, None)),
        t => Err(TopographyError::format(
            origin,
            0,
            format!("`DataType` = {t}: expected 5 (int16), 6 (int32) or 7 (double)"),
        )),
    }
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    if bytes.starts_with(b"bISO-1.0") {
        return binary(bytes, origin);
    }
    if !bytes.starts_with(b"aISO-1.0") {
        return Err(TopographyError::format(
            origin,
            0,
            "not an SDF file: it does not start with `aISO-1.0` or `bISO-1.0`",
        ));
    }
    check_line_bytes(bytes, MAX_LINE_BYTES).map_err(|e| TopographyError::format(origin, e.line, e.to_string()))?;
    let text = std::str::from_utf8(bytes).map_err(|e| {
        TopographyError::format(origin, 0, format!("an ASCII SDF file is not text (byte {})", e.valid_up_to()))
    })?;
    let mut lines = text.lines().enumerate().skip(1);
    let mut keys: HashMap<String, (u64, String)> = HashMap::new();
    let mut ended = false;
    for (k, line) in lines.by_ref() {
        let t = line.trim();
        if t == "*" {
            ended = true;
            break;
        }
        if t.is_empty() {
            continue;
        }
        let (key, value) = t.split_once('=').ok_or_else(|| {
            TopographyError::format(origin, k as u64 + 1, format!("{} is not a `Key = Value` line", excerpt(t)))
        })?;
        check_cell(value.trim()).map_err(|e| TopographyError::format(origin, k as u64 + 1, e))?;
        keys.insert(key.trim().to_string(), (k as u64 + 1, value.trim().to_string()));
    }
    if !ended {
        return Err(TopographyError::format(origin, 0, "no `*` line after the header"));
    }
    let get = |name: &str| -> Result<&(u64, String), TopographyError> {
        keys.get(name).ok_or_else(|| TopographyError::format(origin, 0, format!("`{name}` is missing from the header")))
    };
    let int = |name: &str| -> Result<u64, TopographyError> {
        let (line, v) = get(name)?;
        v.parse().map_err(|_| {
            TopographyError::format(origin, *line, format!("`{name}` = {}: expected an integer >= 0", excerpt(v)))
        })
    };
    let real = |name: &str| -> Result<f64, TopographyError> {
        let (line, v) = get(name)?;
        v.parse().map_err(|_| {
            TopographyError::format(origin, *line, format!("`{name}` = {}: expected a number", excerpt(v)))
        })
    };
    let h = Header {
        nx: int("NumPoints")?,
        ny: int("NumProfiles")?,
        xs: real("Xscale")?,
        ys: real("Yscale")?,
        zs: real("Zscale")?,
        compression: if keys.contains_key("Compression") { int("Compression")? } else { 0 },
        data_type: int("DataType")?,
    };
    sample_of(h.data_type, origin)?;
    crate::map::check_grid_size(origin, h.nx, h.ny)?;
    let n = (h.nx * h.ny) as usize;
    let mut values = Vec::with_capacity(n.min(bytes.len() / 2 + 1));
    let mut closed = false;
    'lines: for (k, line) in lines {
        let t = line.trim();
        if t == "*" {
            closed = true;
            break;
        }
        for cell in t.split_whitespace() {
            if values.len() as u64 >= MAX_PIXELS || values.len() >= n {
                return Err(TopographyError::format(
                    origin,
                    k as u64 + 1,
                    format!("more than NumPoints x NumProfiles = {n} values"),
                ));
            }
            let v = if cell.eq_ignore_ascii_case("bad") {
                f64::NAN
            } else {
                match cell.parse::<f64>() {
                    Ok(v) if v.is_finite() => v * h.zs,
                    _ => {
                        return Err(TopographyError::format(
                            origin,
                            k as u64 + 1,
                            format!("{} is not a finite number (or BAD for a missing point)", excerpt(cell)),
                        ));
                    }
                }
            };
            values.push(v);
            if values.len() > n {
                break 'lines;
            }
        }
    }
    if !closed {
        return Err(TopographyError::format(origin, 0, "no `*` line after the data: the file is truncated"));
    }
    if values.len() != n {
        return Err(TopographyError::format(
            origin,
            0,
            format!("{} values, expected NumPoints x NumProfiles = {} x {} = {n}", values.len(), h.nx, h.ny),
        ));
    }
    channel(&h, origin, Values::Parsed(values))
}

fn binary(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    if bytes.len() < BINARY_HEADER {
        return Err(TopographyError::format(
            origin,
            0,
            format!("{} bytes: a binary SDF header has {BINARY_HEADER}", bytes.len()),
        ));
    }
    let u16_at = |at: usize| u64::from(u16::from_le_bytes([bytes[at], bytes[at + 1]]));
    let f64_at = |at: usize| {
        let mut a = [0u8; 8];
        a.copy_from_slice(&bytes[at..at + 8]);
        f64::from_le_bytes(a)
    };
    let h = Header {
        nx: u16_at(42),
        ny: u16_at(44),
        xs: f64_at(46),
        ys: f64_at(54),
        zs: f64_at(62),
        compression: u64::from(bytes[78]),
        data_type: u64::from(bytes[79]),
    };
    let (sample, invalid) = sample_of(h.data_type, origin)?;
    crate::map::check_grid_size(origin, h.nx, h.ny)?;
    let need = h.nx * h.ny * sample.bytes() as u64;
    // A trailer (after the data) may follow: it is not read.
    if ((bytes.len() - BINARY_HEADER) as u64) < need {
        return Err(TopographyError::format(
            origin,
            0,
            format!(
                "{} data bytes after the header, expected at least {} x {} x {} = {need}",
                bytes.len() - BINARY_HEADER,
                h.nx,
                h.ny,
                sample.bytes()
            ),
        ));
    }
    let raster = Raster {
        offset: BINARY_HEADER,
        sample,
        big_endian: false,
        flip_x: false,
        flip_y: false,
        scale: h.zs,
        shift: 0.0,
        row_bytes: None,
        invalid,
    };
    channel(&h, origin, Values::Raster(raster))
}
