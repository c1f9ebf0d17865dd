//! Summit lists as NumPy `.npy` files.
//!
//! # Written
//!
//! [`Surface::to_npy_bytes`] writes an `N x 4` array of little-endian float64 (`'<f8'`), C order,
//! format version 1.0, columns x, y, height, radius in metres (SI), one row per summit in summit
//! order: `np.load(path)` gives the array, `a[:, 2]` the heights.
//!
//! # Read
//!
//! [`read_npy_summits`] accepts
//!
//! * an `N x 4` float array (float64 or float32, either byte order, C or Fortran order) with the
//!   columns x, y, height, radius in metres;
//! * a structured array of shape `(N,)` with float fields named `x`, `y`, `height` and optionally
//!   `radius` (the names `x_m`, `y_m`, `height_m`, `radius_m` as well; no other fields);
//! * heights alone: a float array of shape `(N,)`.
//!
//! Without a radius column or field the radius, and without positions the positions, come from
//! the scenario (see [`crate::SurfaceSpec`]). Values must be finite, radii > 0 and positions inside
//! the apparent area; every error names the file, and the row and column where a value is wrong.
//!
//! The header (a Python dict literal: `descr`, `fortran_order`, `shape`) is parsed by a small
//! literal parser with a nesting limit; the data length is checked against the declared shape
//! before anything is allocated, so the memory used is bounded by the file size, which the caller
//! bounds ([`stiction_units::io::read_input`]).

use std::path::Path;

use crate::{Radii, Surface, SurfaceError};

/// Longest `.npy` header accepted, bytes (NumPy's own reader refuses more than 10 000 by default).
pub const NPY_MAX_HEADER_BYTES: usize = 65_536;

/// Bytes per summit of the largest accepted layout (four float64 columns), for input size limits.
pub const NPY_MAX_BYTES_PER_SUMMIT: u64 = 32;

/// Summits read from a `.npy` file.
#[derive(Debug, Clone, PartialEq)]
pub enum NpySummits {
    /// Positions and heights, and radii when the file has them (`None`: the scenario's radius).
    Summits {
        /// x positions \[m\].
        x_m: Vec<f64>,
        /// y positions \[m\].
        y_m: Vec<f64>,
        /// Heights \[m\].
        height_m: Vec<f64>,
        /// Radii \[m\], when the file has them.
        radius_m: Option<Vec<f64>>,
    },
    /// Heights alone \[m\] (a 1-D float array).
    Heights(Vec<f64>),
}

impl NpySummits {
    /// Number of summits.
    pub fn len(&self) -> usize {
        match self {
            NpySummits::Summits { height_m, .. } | NpySummits::Heights(height_m) => height_m.len(),
        }
    }

    /// True when there is no summit (never for a successfully read file).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl Surface {
    /// The summits as `.npy` bytes: an `N x 4` little-endian float64 array in C order (version 1.0
    /// header), columns x, y, height, radius in metres. [`read_npy_summits`] reads it back bit for
    /// bit (positions are stored as f32 and widen exactly).
    pub fn to_npy_bytes(&self) -> Vec<u8> {
        let n = self.len();
        let mut out = npy_header("'<f8'", false, &format!("({n}, 4)"));
        out.reserve(n * 32);
        let (xs, ys, hs) = (self.xs_m(), self.ys_m(), self.heights_m());
        for i in 0..n {
            out.extend_from_slice(&f64::from(xs[i]).to_le_bytes());
            out.extend_from_slice(&f64::from(ys[i]).to_le_bytes());
            out.extend_from_slice(&hs[i].to_le_bytes());
            out.extend_from_slice(&self.radius_m(i).to_le_bytes());
        }
        out
    }

    /// Writes [`Surface::to_npy_bytes`] to a file atomically
    /// ([`stiction_units::io::write_atomic`]).
    pub fn write_npy_file(&self, path: &Path) -> Result<(), SurfaceError> {
        stiction_units::io::write_atomic(path, &self.to_npy_bytes())
            .map_err(|e| SurfaceError::Io { path: path.display().to_string(), message: e.to_string() })
    }
}

/// A version 1.0 `.npy` header for `descr` (a Python literal), padded with spaces so that the data
/// starts at a multiple of 64 bytes, as NumPy writes it.
pub fn npy_header(descr: &str, fortran_order: bool, shape: &str) -> Vec<u8> {
    let mut header = format!(
        "{{'descr': {descr}, 'fortran_order': {}, 'shape': {shape}, }}",
        if fortran_order { "True" } else { "False" }
    );
    while !(10 + header.len() + 1).is_multiple_of(64) {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out
}

/// Reads a summit file (see the module documentation) through the shared input layer: a regular
/// file of at most `limit_bytes`, checked before reading.
pub fn read_npy_summits_file(path: &Path, limit_bytes: u64) -> Result<NpySummits, SurfaceError> {
    let bytes = stiction_units::io::read_input(path, limit_bytes)
        .map_err(|e| SurfaceError::Io { path: path.display().to_string(), message: e.to_string() })?;
    read_npy_summits(&bytes, &path.display().to_string())
}

/// Parses `.npy` bytes holding summits (see the module documentation); `origin` names the file in
/// errors. Values are checked for finiteness here; positions against the apparent area and radii
/// in [`npy_surface`].
pub fn read_npy_summits(bytes: &[u8], origin: &str) -> Result<NpySummits, SurfaceError> {
    let bad = |message: String| SurfaceError::Npy { path: origin.to_string(), message };
    let (header, data) = split_header(bytes).map_err(bad)?;
    let dict = match parse_literal(header).map_err(|m| bad(format!("the header {}: {m}", quote(header))))? {
        Literal::Dict(d) => d,
        _ => return Err(bad(format!("the header {} is not a dict", quote(header)))),
    };
    let get = |key: &str| dict.iter().find(|(k, _)| k == key).map(|(_, v)| v);
    for (k, _) in &dict {
        if !["descr", "fortran_order", "shape"].contains(&k.as_str()) {
            return Err(bad(format!("unknown header key '{k}': expected 'descr', 'fortran_order' and 'shape'")));
        }
    }
    let fortran = match get("fortran_order") {
        Some(Literal::Bool(b)) => *b,
        _ => return Err(bad("'fortran_order' is missing or not True/False".into())),
    };
    let shape: Vec<u64> = match get("shape") {
        Some(Literal::Tuple(items)) => items
            .iter()
            .map(|v| match v {
                Literal::Int(n) => Ok(*n),
                _ => Err(bad("'shape' is not a tuple of integers".into())),
            })
            .collect::<Result<_, _>>()?,
        _ => return Err(bad("'shape' is missing or not a tuple".into())),
    };
    let n = match shape[..] {
        [n] | [n, _] => n,
        _ => {
            return Err(bad(format!(
                "shape {}: expected (N, 4) for x, y, height, radius columns, or (N,) for a structured array or \
                 heights alone",
                shape_text(&shape)
            )));
        }
    };
    if n == 0 {
        return Err(bad("the array holds no summit (N = 0): expected at least one".into()));
    }
    if n > crate::MAX_SUMMITS as u64 {
        return Err(bad(format!("shape {}: more than {} summits", shape_text(&shape), crate::MAX_SUMMITS)));
    }
    let n = n as usize;
    match get("descr") {
        Some(Literal::Str(descr)) => {
            let float = parse_float_dtype(descr).ok_or_else(|| {
                bad(format!(
                    "dtype '{descr}' is not supported: expected float64 or float32 ('<f8', '>f8', '<f4', '>f4') or a \
                     structured array with float fields x, y, height[, radius]"
                ))
            })?;
            let cols = match shape[..] {
                [_] => 1,
                [_, 4] => 4,
                _ => {
                    return Err(bad(format!(
                        "shape {}: a float array must be (N, 4) with the columns x, y, height, radius, or (N,) \
                         with heights alone",
                        shape_text(&shape)
                    )));
                }
            };
            check_data_len(data.len(), n, cols * float.size, &shape, descr).map_err(bad)?;
            // Element (row i, column c): C order at i * cols + c, Fortran order at c * n + i.
            let column = |c: usize| -> Vec<f64> {
                if fortran || cols == 1 {
                    let off = c * n * float.size;
                    data[off..off + n * float.size].chunks_exact(float.size).map(|b| float.read(b)).collect()
                } else {
                    data.chunks_exact(cols * float.size)
                        .map(|row| float.read(&row[c * float.size..(c + 1) * float.size]))
                        .collect()
                }
            };
            let native = FloatType { size: 8, little: true };
            let out = if cols == 4 && !fortran && float == native {
                // The layout this crate and NumPy write by default: one pass over the rows.
                let (mut x, mut y, mut h, mut r) =
                    (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
                let le = |b: &[u8]| f64::from_le_bytes(b.try_into().unwrap_or_default());
                for row in data.chunks_exact(32) {
                    x.push(le(&row[0..8]));
                    y.push(le(&row[8..16]));
                    h.push(le(&row[16..24]));
                    r.push(le(&row[24..32]));
                }
                NpySummits::Summits { x_m: x, y_m: y, height_m: h, radius_m: Some(r) }
            } else if cols == 1 {
                NpySummits::Heights(column(0))
            } else {
                NpySummits::Summits { x_m: column(0), y_m: column(1), height_m: column(2), radius_m: Some(column(3)) }
            };
            check_finite(&out).map_err(bad)?;
            Ok(out)
        }
        Some(Literal::List(fields)) => {
            if shape.len() != 1 {
                return Err(bad(format!("shape {}: a structured array must be 1-D, (N,)", shape_text(&shape))));
            }
            // (name, offset, dtype) of each field, packed in order.
            let mut slots: [Option<(usize, FloatType)>; 4] = [None; 4];
            let mut offset = 0usize;
            for f in fields {
                let (name, dtype) = match f {
                    Literal::Tuple(t) if t.len() == 2 => match (&t[0], &t[1]) {
                        (Literal::Str(a), Literal::Str(b)) => (a, b),
                        _ => return Err(bad("a structured dtype entry is not ('name', 'type')".into())),
                    },
                    _ => {
                        return Err(bad(
                            "a structured dtype entry is not ('name', 'type') (sub-arrays are not supported)".into(),
                        ));
                    }
                };
                let slot = match name.as_str() {
                    "x" | "x_m" => 0,
                    "y" | "y_m" => 1,
                    "height" | "height_m" => 2,
                    "radius" | "radius_m" => 3,
                    other => {
                        return Err(bad(format!(
                            "field '{other}': expected only the fields x, y, height and radius (or x_m, y_m, \
                             height_m, radius_m)"
                        )));
                    }
                };
                let float = parse_float_dtype(dtype)
                    .ok_or_else(|| bad(format!("field '{name}' has dtype '{dtype}': expected float64 or float32")))?;
                if slots[slot].is_some() {
                    return Err(bad(format!("field '{name}' appears twice (x/x_m etc. name the same column)")));
                }
                slots[slot] = Some((offset, float));
                offset += float.size;
            }
            let record = offset;
            let [Some(sx), Some(sy), Some(sh), sr] = slots else {
                return Err(bad("a structured array needs the fields x, y and height (radius is optional)".into()));
            };
            check_data_len(data.len(), n, record, &shape, "the structured dtype").map_err(bad)?;
            let field = |(off, float): (usize, FloatType)| -> Vec<f64> {
                data.chunks_exact(record).map(|rec| float.read(&rec[off..off + float.size])).collect()
            };
            let out =
                NpySummits::Summits { x_m: field(sx), y_m: field(sy), height_m: field(sh), radius_m: sr.map(field) };
            check_finite(&out).map_err(bad)?;
            Ok(out)
        }
        _ => Err(bad("'descr' is missing or neither a dtype string nor a list of fields".into())),
    }
}

/// Builds the surface from summits read by [`read_npy_summits`] over the apparent area: radii from
/// the file or `radius_m` (the scenario's), positions from the file or `positions` (called with
/// the number of summits). Errors name the file and the row of a summit outside the area or with
/// a radius <= 0, and a radius given both ways.
pub fn npy_surface(
    summits: NpySummits,
    origin: &str,
    apparent_length_m: f64,
    apparent_width_m: f64,
    radius_m: Option<f64>,
    positions: impl FnOnce(usize) -> (Vec<f32>, Vec<f32>),
) -> Result<Surface, SurfaceError> {
    let bad = |message: String| SurfaceError::Npy { path: origin.to_string(), message };
    let need_radius = || {
        radius_m.ok_or_else(|| {
            bad("the file has no radius column: give the scenario's `surface.summit_radius`".to_string())
        })
    };
    let (xs, ys, hs, radii) = match summits {
        NpySummits::Heights(h) => {
            let r = need_radius()?;
            let (xs, ys) = positions(h.len());
            (xs, ys, h, Radii::Uniform(r))
        }
        NpySummits::Summits { x_m, y_m, height_m, radius_m: file_radii } => {
            let radii = match file_radii {
                Some(r) => {
                    if radius_m.is_some() {
                        return Err(bad(
                            "the file gives every summit's radius: `surface.summit_radius` must be absent".into(),
                        ));
                    }
                    if let Some((i, v)) = r.iter().enumerate().find(|(_, v)| **v <= 0.0) {
                        return Err(bad(format!("row {i}, radius: {v} m, expected a radius > 0 m")));
                    }
                    match r.first() {
                        Some(&r0) if r.iter().all(|&v| v == r0) => Radii::Uniform(r0),
                        _ => Radii::PerSummit(r),
                    }
                }
                None => Radii::Uniform(need_radius()?),
            };
            let to_f32 = |v: &[f64], lim: f64, name: &str| -> Result<Vec<f32>, SurfaceError> {
                let inside = |x: &f64| (*x >= 0.0) & (*x <= lim);
                if !v.iter().fold(true, |ok, x| ok & inside(x))
                    && let Some((i, x)) = v.iter().enumerate().find(|(_, x)| !inside(x))
                {
                    return Err(bad(format!("row {i}, {name}: {x} m lies outside the apparent area [0, {lim}] m")));
                }
                Ok(v.iter().map(|&x| round_inside(x, lim)).collect())
            };
            let xs = to_f32(&x_m, apparent_length_m, "x")?;
            drop(x_m);
            let ys = to_f32(&y_m, apparent_width_m, "y")?;
            (xs, ys, height_m, radii)
        }
    };
    Surface::new(apparent_length_m, apparent_width_m, xs, ys, hs, radii)
}

fn round_inside(v: f64, lim: f64) -> f32 {
    let mut f = v as f32;
    while f64::from(f) > lim {
        f = f.next_down();
    }
    f
}

fn check_finite(s: &NpySummits) -> Result<(), String> {
    let cols: Vec<(&str, &Vec<f64>)> = match s {
        NpySummits::Heights(h) => vec![("height", h)],
        NpySummits::Summits { x_m, y_m, height_m, radius_m } => {
            let mut c = vec![("x", x_m), ("y", y_m), ("height", height_m)];
            if let Some(r) = radius_m {
                c.push(("radius", r));
            }
            c
        }
    };
    for (name, v) in cols {
        if !v.iter().fold(true, |ok, x| ok & x.is_finite())
            && let Some((i, x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite())
        {
            return Err(format!("row {i}, {name}: {x} is not a finite number (expected SI metres)"));
        }
    }
    Ok(())
}

fn check_data_len(len: usize, n: usize, record: usize, shape: &[u64], what: &str) -> Result<(), String> {
    let need = n.checked_mul(record).ok_or_else(|| format!("shape {} is too large", shape_text(shape)))?;
    if len != need {
        return Err(format!(
            "{len} data bytes after the header, expected {need} for shape {} of {what} ({record} bytes per summit){}",
            shape_text(shape),
            if len < need { ": the file is truncated" } else { "" }
        ));
    }
    Ok(())
}

fn shape_text(shape: &[u64]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!("({})", shape.iter().map(u64::to_string).collect::<Vec<_>>().join(", ")),
    }
}

/// The header text, shortened, for an error message (it is the file's structure, not its data).
fn quote(header: &str) -> String {
    let t: String = header.trim().chars().take(120).collect();
    if t.len() < header.trim().len() { format!("{t:?}...") } else { format!("{t:?}") }
}

/// Splits the magic, version and header length off: (header text, data bytes).
fn split_header(bytes: &[u8]) -> Result<(&str, &[u8]), String> {
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err("not a NumPy .npy file (no \\x93NUMPY magic at the start)".into());
    }
    let (len, start) = match bytes[6] {
        1 => (usize::from(u16::from_le_bytes([bytes[8], bytes[9]])), 10usize),
        2 | 3 if bytes.len() >= 12 => (u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize, 12),
        2 | 3 => return Err("the file ends inside the .npy preamble".into()),
        v => return Err(format!(".npy format version {v} is not supported (expected 1, 2 or 3)")),
    };
    if len > NPY_MAX_HEADER_BYTES {
        return Err(format!("the header length {len} bytes exceeds the limit of {NPY_MAX_HEADER_BYTES}"));
    }
    let end = start
        .checked_add(len)
        .filter(|&e| e <= bytes.len())
        .ok_or_else(|| format!("the header length {len} runs past the end of the file"))?;
    let header = std::str::from_utf8(&bytes[start..end]).map_err(|_| "the .npy header is not text".to_string())?;
    Ok((header, &bytes[end..]))
}

#[derive(Debug, Clone, Copy, PartialEq)]
struct FloatType {
    size: usize,
    little: bool,
}

impl FloatType {
    fn read(self, b: &[u8]) -> f64 {
        if self.size == 8 {
            let a: [u8; 8] = b.try_into().unwrap_or_default();
            if self.little { f64::from_le_bytes(a) } else { f64::from_be_bytes(a) }
        } else {
            let a: [u8; 4] = b.try_into().unwrap_or_default();
            f64::from(if self.little { f32::from_le_bytes(a) } else { f32::from_be_bytes(a) })
        }
    }
}

fn parse_float_dtype(d: &str) -> Option<FloatType> {
    let (little, rest) = match d.as_bytes().first()? {
        b'<' | b'=' => (true, &d[1..]),
        b'>' => (false, &d[1..]),
        _ => (true, d),
    };
    match rest {
        "f8" | "d" => Some(FloatType { size: 8, little }),
        "f4" | "f" => Some(FloatType { size: 4, little }),
        _ => None,
    }
}

/// The subset of Python literals a `.npy` header uses.
#[derive(Debug, Clone, PartialEq)]
enum Literal {
    Str(String),
    Bool(bool),
    Int(u64),
    Tuple(Vec<Literal>),
    List(Vec<Literal>),
    Dict(Vec<(String, Literal)>),
}

const MAX_DEPTH: usize = 8;

fn parse_literal(text: &str) -> Result<Literal, String> {
    let mut p = Parser { s: text.as_bytes(), i: 0 };
    let v = p.value(0)?;
    p.ws();
    if p.i != p.s.len() {
        return Err(format!("unexpected text at byte {}", p.i));
    }
    Ok(v)
}

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn ws(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_ascii_whitespace() {
            self.i += 1;
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.ws();
        self.s.get(self.i).copied()
    }

    fn value(&mut self, depth: usize) -> Result<Literal, String> {
        if depth > MAX_DEPTH {
            return Err(format!("nested deeper than {MAX_DEPTH} levels"));
        }
        match self.peek() {
            Some(q @ (b'\'' | b'"')) => {
                let start = self.i + 1;
                let end =
                    self.s[start..].iter().position(|&c| c == q).map(|k| start + k).ok_or("unterminated string")?;
                self.i = end + 1;
                let t = std::str::from_utf8(&self.s[start..end]).map_err(|_| "a string is not text")?;
                if t.contains('\\') {
                    return Err("escapes in strings are not supported".into());
                }
                Ok(Literal::Str(t.to_string()))
            }
            Some(b'0'..=b'9') => {
                let start = self.i;
                while self.i < self.s.len() && self.s[self.i].is_ascii_digit() {
                    self.i += 1;
                }
                // Python 2 writers appended L to long integers.
                let t = std::str::from_utf8(&self.s[start..self.i]).map_err(|_| "bad integer")?;
                if self.s.get(self.i) == Some(&b'L') {
                    self.i += 1;
                }
                t.parse::<u64>().map(Literal::Int).map_err(|_| format!("integer {t} is too large"))
            }
            Some(b'T') if self.s[self.i..].starts_with(b"True") => {
                self.i += 4;
                Ok(Literal::Bool(true))
            }
            Some(b'F') if self.s[self.i..].starts_with(b"False") => {
                self.i += 5;
                Ok(Literal::Bool(false))
            }
            Some(open @ (b'(' | b'[')) => {
                let close = if open == b'(' { b')' } else { b']' };
                self.i += 1;
                let mut items = Vec::new();
                loop {
                    if self.peek() == Some(close) {
                        self.i += 1;
                        break;
                    }
                    items.push(self.value(depth + 1)?);
                    match self.peek() {
                        Some(b',') => self.i += 1,
                        Some(c) if c == close => {}
                        _ => return Err(format!("expected ',' or '{}' at byte {}", close as char, self.i)),
                    }
                }
                Ok(if open == b'(' { Literal::Tuple(items) } else { Literal::List(items) })
            }
            Some(b'{') => {
                self.i += 1;
                let mut items: Vec<(String, Literal)> = Vec::new();
                loop {
                    if self.peek() == Some(b'}') {
                        self.i += 1;
                        break;
                    }
                    let Literal::Str(key) = self.value(depth + 1)? else {
                        return Err("a dict key is not a string".into());
                    };
                    if self.peek() != Some(b':') {
                        return Err(format!("expected ':' after the key '{key}'"));
                    }
                    self.i += 1;
                    let v = self.value(depth + 1)?;
                    if items.iter().any(|(k, _)| *k == key) {
                        return Err(format!("the key '{key}' appears twice"));
                    }
                    items.push((key, v));
                    match self.peek() {
                        Some(b',') => self.i += 1,
                        Some(b'}') => {}
                        _ => return Err(format!("expected ',' or '}}' at byte {}", self.i)),
                    }
                }
                Ok(Literal::Dict(items))
            }
            Some(_) => Err(format!("unexpected character at byte {}", self.i)),
            None => Err("unexpected end of the header".into()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_literals_parse() {
        let d =
            parse_literal("{'descr': [('x', '<f8'), ('y', '>f4')], 'fortran_order': False, 'shape': (3,), }").unwrap();
        let Literal::Dict(items) = d else { panic!("not a dict") };
        assert_eq!(items[2], ("shape".to_string(), Literal::Tuple(vec![Literal::Int(3)])));
        assert!(parse_literal("{'a': ((((((((((1,),),),),),),),),),)}").is_err(), "depth limit");
        assert!(parse_literal("{'a': 1").is_err());
        assert!(parse_literal("{'a': 99999999999999999999999}").is_err());
    }
}
