//! netCDF classic and 64-bit-offset files (`.nc`) as contact.engineering (SurfaceTopography)
//! writes a height map.
//!
//! Container (Unidata, "NetCDF Classic and 64-bit Offset Format", the header grammar): big-endian;
//! `CDF` and a version byte (1 classic, 2 64-bit offset), the record count, then the dimension list
//! (tag 10; per dimension a name and a length, 0 for the record dimension), the global attribute
//! list (tag 12) and the variable list (tag 11; per variable a name, its dimension ids, its
//! attributes, its type, its size and the byte offset of its values, 4 bytes in version 1, 8 in
//! version 2). An absent list is two zero words; names and attribute values are padded to 4 bytes.
//! Types: 1 byte, 2 char, 3 short, 4 int, 5 float, 6 double.
//!
//! The height map (SurfaceTopography's NetCDF layout): a variable `heights(x, y)`, x the first
//! (slowest) index; optional variables `x` and `y` whose attribute `length` is the physical size
//! and `unit` its unit (the heights' unit, which `heights:unit` repeats); an optional variable
//! `mask(x, y)` whose non-zero points are missing. The attributes of the netCDF conventions on
//! `heights` apply: `scale_factor`, `add_offset`, and points equal to `_FillValue` or
//! `missing_value` are missing.
//!
//! Written by hand: the classic format is a short, fully specified grammar (Unidata's), and what
//! is read of it is a few fixed-size variables; a pure-Rust netCDF crate would add more code than
//! this reader. Not read (refused): CDF-5 (version 5), netCDF-4 (an HDF5 file), line scans (a
//! `heights` of one dimension), heights along the record (unlimited) dimension.

use stiction_units::text::excerpt;

use super::fields::Fields;
use super::{Channel, ChannelInfo, Values, clean, length_unit};
use crate::TopographyError;

/// Most dimensions, attributes per list and variables a header may declare.
const MAX_ITEMS: u64 = 4096;

pub(crate) fn is_nc(bytes: &[u8]) -> bool {
    bytes.len() >= 4 && bytes.starts_with(b"CDF") && matches!(bytes[3], 1 | 2)
}

#[derive(Debug, Clone)]
enum Attr {
    Text(String),
    Numbers(Vec<f64>),
}

struct Var {
    name: String,
    dims: Vec<usize>,
    attrs: Vec<(String, Attr)>,
    kind: u32,
    begin: u64,
}

impl Var {
    fn attr(&self, name: &str) -> Option<&Attr> {
        self.attrs.iter().find(|(n, _)| n == name).map(|(_, a)| a)
    }
    fn number(&self, name: &str) -> Option<f64> {
        match self.attr(name)? {
            Attr::Numbers(v) => v.first().copied(),
            Attr::Text(t) => t.trim().parse().ok(),
        }
    }
    fn text(&self, name: &str) -> Option<String> {
        match self.attr(name)? {
            Attr::Text(t) => Some(clean(t)),
            Attr::Numbers(_) => None,
        }
    }
}

fn type_bytes(kind: u32) -> Option<u64> {
    match kind {
        1 | 2 => Some(1),
        3 => Some(2),
        4 | 5 => Some(4),
        6 => Some(8),
        _ => None,
    }
}

struct Parser<'a> {
    f: Fields<'a>,
    at: usize,
    origin: &'a str,
}

impl<'a> Parser<'a> {
    fn err(&self, m: String) -> TopographyError {
        TopographyError::format(self.origin, 0, format!("netCDF header at byte {}: {m}", self.at))
    }
    fn u32(&mut self) -> Result<u32, TopographyError> {
        let v = self.f.u32(self.at).ok_or_else(|| self.err("the header runs past the end of the file".into()))?;
        self.at += 4;
        Ok(v)
    }
    fn u64(&mut self) -> Result<u64, TopographyError> {
        let v = self.f.u64(self.at).ok_or_else(|| self.err("the header runs past the end of the file".into()))?;
        self.at += 8;
        Ok(v)
    }
    /// A count of items of at least `min_bytes` each: bounded by the bytes left.
    fn count(&mut self, min_bytes: u64) -> Result<u64, TopographyError> {
        let n = u64::from(self.u32()?);
        let left = (self.f.b.len() - self.at.min(self.f.b.len())) as u64;
        if n > MAX_ITEMS || n * min_bytes > left {
            return Err(self.err(format!("{n} items declared, more than the file can hold")));
        }
        Ok(n)
    }
    /// `n` bytes, then the padding to a multiple of 4.
    fn bytes(&mut self, n: u64) -> Result<&'a [u8], TopographyError> {
        let padded = n.div_ceil(4) * 4;
        let end = (self.at as u64).checked_add(padded).filter(|&e| e <= self.f.b.len() as u64);
        let end = end.ok_or_else(|| self.err(format!("{n} bytes declared, past the end of the file")))?;
        let s = &self.f.b[self.at..self.at + n as usize];
        self.at = end as usize;
        Ok(s)
    }
    fn name(&mut self) -> Result<String, TopographyError> {
        let n = self.count(1)?;
        let b = self.bytes(n)?;
        Ok(String::from_utf8_lossy(b).into_owned())
    }
    /// A list's tag and count: (0, 0) when absent.
    fn list(&mut self, tag: u32, min_bytes: u64) -> Result<u64, TopographyError> {
        let t = self.u32()?;
        let n = self.count(min_bytes)?;
        match (t, n) {
            (0, 0) => Ok(0),
            (t, _) if t == tag => Ok(n),
            _ => Err(self.err(format!("list tag {t}: expected {tag} or an absent list"))),
        }
    }
    fn attrs(&mut self) -> Result<Vec<(String, Attr)>, TopographyError> {
        let n = self.list(12, 12)?;
        let mut out = Vec::with_capacity(n as usize);
        for _ in 0..n {
            let name = self.name()?;
            let kind = self.u32()?;
            let size = type_bytes(kind).ok_or_else(|| self.err(format!("attribute type {kind}: expected 1 to 6")))?;
            let count = self.count(size)?;
            let b = self.bytes(count * size)?;
            let f = Fields::be(b);
            let value = match kind {
                2 => Attr::Text(String::from_utf8_lossy(b).trim_end_matches('\0').to_string()),
                _ => Attr::Numbers(
                    (0..count as usize)
                        .filter_map(|k| match kind {
                            1 => Some(f64::from(b[k] as i8)),
                            3 => f.i16(2 * k).map(f64::from),
                            4 => f.i32(4 * k).map(f64::from),
                            5 => f.f32(4 * k),
                            _ => f.f64(8 * k),
                        })
                        .collect(),
                ),
            };
            out.push((name, value));
        }
        Ok(out)
    }
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if bytes.starts_with(b"\x89HDF") {
        return Err(bad("a netCDF-4 (HDF5) file is not read: save it as netCDF classic or 64-bit offset".into()));
    }
    if bytes.len() >= 4 && bytes.starts_with(b"CDF") && bytes[3] == 5 {
        return Err(bad("a CDF-5 (64-bit data) netCDF file is not read: save it as netCDF classic".into()));
    }
    if !is_nc(bytes) {
        return Err(bad("not a netCDF classic file: it does not start with `CDF` and version 1 or 2".into()));
    }
    let wide = bytes[3] == 2;
    let mut p = Parser { f: Fields::be(bytes), at: 4, origin };
    let _records = p.u32()?;
    let ndims = p.list(10, 8)?;
    let mut dims = Vec::with_capacity(ndims as usize);
    for _ in 0..ndims {
        let name = p.name()?;
        let len = p.u32()?;
        dims.push((name, u64::from(len)));
    }
    p.attrs()?;
    let nvars = p.list(11, 16)?;
    let mut vars = Vec::with_capacity(nvars as usize);
    for _ in 0..nvars {
        let name = p.name()?;
        let nd = p.count(4)?;
        let mut ids = Vec::with_capacity(nd as usize);
        for _ in 0..nd {
            let id = p.u32()? as usize;
            if id >= dims.len() {
                return Err(p.err(format!("variable {}: dimension {id} of {}", excerpt(&name), dims.len())));
            }
            ids.push(id);
        }
        let attrs = p.attrs()?;
        let kind = p.u32()?;
        let _vsize = p.u32()?;
        let begin = if wide { p.u64()? } else { u64::from(p.u32()?) };
        vars.push(Var { name, dims: ids, attrs, kind, begin });
    }
    let find = |n: &str| vars.iter().find(|v| v.name == n);
    let heights = find("heights")
        .ok_or_else(|| bad("no variable `heights`: not a height map as contact.engineering writes it".into()))?;
    if heights.dims.len() != 2 {
        return Err(bad(format!(
            "`heights` has {} dimensions: only a map (x, y) is read, not a line scan",
            heights.dims.len()
        )));
    }
    let (nx, ny) = (dims[heights.dims[0]].1, dims[heights.dims[1]].1);
    if nx == 0 || ny == 0 {
        return Err(bad("`heights` runs along the record (unlimited) dimension: not read".into()));
    }
    crate::map::check_grid_size(origin, nx, ny)?;
    let (nx, ny) = (nx as usize, ny as usize);
    let read_var = |v: &Var| -> Result<Vec<f64>, TopographyError> {
        let size = type_bytes(v.kind)
            .filter(|_| v.kind != 2)
            .ok_or_else(|| bad(format!("variable {} of type {}: expected a number type", excerpt(&v.name), v.kind)))?;
        let n = (nx * ny) as u64;
        let end = v.begin.checked_add(n * size).filter(|&e| e <= bytes.len() as u64).ok_or_else(|| {
            bad(format!(
                "variable {}: {nx} x {ny} values of {size} bytes from byte {} run past the end ({} bytes)",
                excerpt(&v.name),
                v.begin,
                bytes.len()
            ))
        })?;
        let data = Fields::be(&bytes[v.begin as usize..end as usize]);
        Ok((0..n as usize)
            .map(|k| match v.kind {
                1 => f64::from(data.b[k] as i8),
                3 => data.i16(2 * k).map_or(f64::NAN, f64::from),
                4 => data.i32(4 * k).map_or(f64::NAN, f64::from),
                5 => data.f32(4 * k).unwrap_or(f64::NAN),
                _ => data.f64(8 * k).unwrap_or(f64::NAN),
            })
            .collect())
    };
    if let Some(m) = find("mask")
        && m.dims != heights.dims
    {
        return Err(bad("`mask` does not have the dimensions of `heights`".into()));
    }
    let unit = find("x").and_then(|x| x.text("unit")).or_else(|| heights.text("unit")).unwrap_or_default();
    if let Some(hu) = heights.text("unit")
        && !unit.is_empty()
        && length_unit(&hu) != length_unit(&unit)
    {
        return Err(bad(format!("`heights:unit` {} differs from `x:unit` {}", excerpt(&hu), excerpt(&unit))));
    }
    let unit_m = length_unit(&unit);
    if !unit.is_empty() && unit_m.is_none() {
        return Err(bad(format!("unit {}: not a length unit", excerpt(&unit))));
    }
    let length = |n: &str| find(n).and_then(|v| v.number("length"));
    let size_m = match (length("x"), length("y"), unit_m) {
        (Some(lx), Some(ly), Some(u)) if lx.is_finite() && ly.is_finite() && lx > 0.0 && ly > 0.0 => {
            Some((lx * u, ly * u))
        }
        (Some(lx), Some(ly), Some(_)) => {
            return Err(bad(format!("`x:length` {lx:e}, `y:length` {ly:e}: expected finite values > 0")));
        }
        _ => None,
    };
    let info = ChannelInfo {
        index: 0,
        name: "heights".into(),
        nx,
        ny,
        size_m,
        unit: unit.clone(),
        height_unit_m: unit_m,
        is_height: true,
    };
    // Values, checked and decoded now (a map is small next to the header checks).
    let raw = read_var(heights)?;
    let mask = match find("mask") {
        Some(m) => Some(read_var(m)?),
        None => None,
    };
    let scale = heights.number("scale_factor").unwrap_or(1.0);
    let offset = heights.number("add_offset").unwrap_or(0.0);
    let fill = [heights.number("_FillValue"), heights.number("missing_value")];
    // heights(x, y): x the slowest index; row iy of the map holds heights[ix][iy].
    let mut values = Vec::with_capacity(nx * ny);
    for iy in 0..ny {
        values.extend((0..nx).map(|ix| {
            let k = ix * ny + iy;
            let v = raw[k];
            let masked = mask.as_ref().is_some_and(|m| m[k] != 0.0);
            if masked || fill.contains(&Some(v)) { f64::NAN } else { v * scale + offset }
        }));
    }
    Ok(vec![Channel { info, values: Values::Parsed(values), unreadable: None }])
}
