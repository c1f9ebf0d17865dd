//! Bruker / Veeco NanoScope files (`.spm`, `.di`, `.001`, `.002`, ...), version 4.3 and later.
//!
//! Layout (Bruker's NanoScope file format description, as Gwyddion's `nanoscope` module documents
//! it): a text header of `\Key: Value` lines (CR LF), in sections opened by `\*Section name`,
//! starting with `\*File list` and ending with `\*File list end`; the `\Data length` of the File
//! list is the header's size. Each `\*Ciao image list` section is one channel: `\Data offset`,
//! `\Data length`, `\Bytes/pixel` (2 or 4: little-endian signed integers), `\Samps/line` (x),
//! `\Number of lines` (y), `\Scan Size: 500 500 nm`, `\@2:Image Data: S [Height] "Height"` (the
//! name) and the scale chain `\@2:Z scale: V [Sens. Zsens] (0.0050354 V/LSB) 2.910461 V`: the
//! hard value (2.910461 V) is the full range of a 16-bit sample, so a sample is worth
//! `hard value / 65536` (a 32-bit sample, `/ 65536^2`), times the soft scale the bracket names,
//! looked up as `\@Sens. Zsens: V 20.82646 nm/V` in the other sections; its unit's numerator
//! (`nm`) is the channel's unit. Lines are stored from the top of the image: the file's last line
//! is row 0 (y = 0) of the map, as Gwyddion and SurfaceTopography read it.
//!
//! Not read: the text variant (`?*File list`, samples as text), force curves and force volumes
//! (`\*Force file list`), electrochemistry files, and old files without `@2:Z scale`; each is
//! refused with its reason.

use std::collections::HashMap;

use stiction_units::text::{MAX_LINE_BYTES, check_line_bytes, excerpt};

use super::{Channel, ChannelInfo, Raster, Sample, Values, clean, height_like, length_unit};
use crate::TopographyError;

/// Largest NanoScope header accepted, bytes (instruments write 20 to 80 kB).
pub const NANOSCOPE_MAX_HEADER_BYTES: usize = 1 << 20;

const MAGIC: &[u8] = b"\\*File list";

pub(crate) fn is_nanoscope(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
        || bytes.starts_with(b"?*File list")
        || bytes.starts_with(b"\\*EC File list")
        || bytes.starts_with(b"\\*Force file list")
}

/// A parsed `@2:Z scale`-style value: `V [soft] (hard scale unit/LSB) hard value unit`.
struct Scaled {
    soft: Option<String>,
    hard_value: f64,
    hard_unit: String,
}

fn parse_scaled(v: &str) -> Option<Scaled> {
    let rest = v.trim().strip_prefix('V')?.trim_start();
    let (soft, rest) = match rest.strip_prefix('[') {
        Some(r) => {
            let end = r.find(']')?;
            (Some(r[..end].trim().to_string()), r[end + 1..].trim_start())
        }
        None => (None, rest),
    };
    let rest = match rest.strip_prefix('(') {
        Some(r) => r[r.find(')')? + 1..].trim_start(),
        None => rest,
    };
    let mut it = rest.split_whitespace();
    let hard_value: f64 = it.next()?.parse().ok()?;
    let hard_unit = it.next().unwrap_or("").to_string();
    hard_value.is_finite().then_some(Scaled { soft: soft.filter(|s| !s.is_empty()), hard_value, hard_unit })
}

type Section = HashMap<String, String>;

/// The header's sections, in order: (name, keys lower-cased).
fn sections(bytes: &[u8], origin: &str) -> Result<(Vec<(String, Section)>, usize), TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if bytes.starts_with(b"?*File list") {
        return Err(bad("a NanoScope text-variant file (`?*File list`, samples as text) is not read: export it as \
                        binary"
            .into()));
    }
    if !bytes.starts_with(MAGIC) {
        return Err(bad(
            "not a NanoScope image file: it does not start with `\\*File list` (force curves and electrochemistry \
             files are not read)"
                .into(),
        ));
    }
    let end_marker = b"\\*File list end";
    let search = &bytes[..bytes.len().min(NANOSCOPE_MAX_HEADER_BYTES)];
    let header_end = search.windows(end_marker.len()).position(|w| w == end_marker).ok_or_else(|| {
        bad(format!(
            "no `\\*File list end` in the first {} bytes: the header is truncated or longer than the limit of \
                 {NANOSCOPE_MAX_HEADER_BYTES} bytes",
            search.len()
        ))
    })?;
    let header = &bytes[..header_end];
    check_line_bytes(header, MAX_LINE_BYTES).map_err(|e| TopographyError::format(origin, e.line, e.to_string()))?;
    let mut out: Vec<(String, Section)> = Vec::new();
    for (k, raw) in header.split(|&b| b == b'\n').enumerate() {
        let line: String = raw.iter().map(|&b| char::from(b)).collect();
        let line = line.trim_end_matches(['\r', '\u{1a}', '\0']).trim();
        if line.is_empty() {
            continue;
        }
        let Some(body) = line.strip_prefix('\\') else {
            return Err(TopographyError::format(
                origin,
                k as u64 + 1,
                format!("{} is not a `\\Key: Value` header line", excerpt(line)),
            ));
        };
        if let Some(name) = body.strip_prefix('*') {
            out.push((name.trim().to_ascii_lowercase(), Section::new()));
            continue;
        }
        // `\@2:Image Data: S [Height] "Height"`: the key ends at the first `: ` (keys hold colons).
        let (key, value) = match body.find(": ") {
            Some(k) => (&body[..k], &body[k + 2..]),
            None => (body.trim_end_matches(':'), ""),
        };
        if let Some((_, s)) = out.last_mut() {
            s.entry(key.trim().to_ascii_lowercase()).or_insert_with(|| value.trim().to_string());
        }
    }
    Ok((out, header_end))
}

fn number<T: std::str::FromStr>(s: &Section, key: &str, origin: &str, k: usize) -> Result<T, TopographyError> {
    let v = s.get(key).ok_or_else(|| {
        TopographyError::format(origin, 0, format!("image {k}: `\\{key}` is missing from its `Ciao image list`"))
    })?;
    v.split_whitespace().next().and_then(|t| t.parse().ok()).ok_or_else(|| {
        TopographyError::format(origin, 0, format!("image {k}: `\\{key}` = {}: expected a number", excerpt(v)))
    })
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let (secs, header_end) = sections(bytes, origin)?;
    let mut global = Section::new();
    for (name, s) in &secs {
        if name != "ciao image list" {
            for (k, v) in s {
                global.entry(k.clone()).or_insert_with(|| v.clone());
            }
        }
    }
    let mut list = Vec::new();
    for (name, s) in &secs {
        if name != "ciao image list" {
            continue;
        }
        let k = list.len();
        let bad = |m: String| TopographyError::format(origin, 0, format!("image {k}: {m}"));
        let offset: u64 = number(s, "data offset", origin, k)?;
        let length: u64 = number(s, "data length", origin, k)?;
        let bpp: u64 = number(s, "bytes/pixel", origin, k)?;
        let nx: u64 = number(s, "samps/line", origin, k)?;
        let ny: u64 = number(s, "number of lines", origin, k)?;
        crate::map::check_grid_size(origin, nx, ny)?;
        let sample = match bpp {
            2 => Sample::I16,
            4 => Sample::I32,
            b => return Err(bad(format!("`\\Bytes/pixel` = {b}: expected 2 or 4"))),
        };
        let need = nx * ny * bpp;
        if need > length {
            return Err(bad(format!(
                "{nx} x {ny} samples of {bpp} bytes need {need} bytes, more than its `\\Data length` of {length}"
            )));
        }
        if offset < header_end as u64 || offset.checked_add(need).is_none_or(|e| e > bytes.len() as u64) {
            return Err(bad(format!(
                "its data ({need} bytes from `\\Data offset` {offset}) lie outside the file's data part (bytes \
                 {header_end} to {})",
                bytes.len()
            )));
        }
        let size_text = s.get("scan size").cloned().unwrap_or_default();
        let parts: Vec<&str> = size_text.split_whitespace().collect();
        let size_m = match parts[..] {
            [a, b, u] => match (a.parse::<f64>(), b.parse::<f64>(), length_unit(u)) {
                (Ok(a), Ok(b), Some(f)) if a.is_finite() && b.is_finite() && a > 0.0 && b > 0.0 => Some((a * f, b * f)),
                _ => None,
            },
            _ => None,
        };
        let size_m = size_m.ok_or_else(|| {
            bad(format!("`\\Scan Size` = {}: expected `X Y unit` such as `500 500 nm`", excerpt(&size_text)))
        })?;
        let image = s.get("@2:image data").cloned().unwrap_or_default();
        let name = clean(&bracket(&image).or_else(|| quoted(&image)).unwrap_or_else(|| format!("image {k}")));
        let (scale, unit, unreadable) = match s.get("@2:z scale").map(|v| (v, parse_scaled(v))) {
            None => (1.0, String::new(), Some("no `\\@2:Z scale` in its header: its values have no scale".into())),
            Some((v, None)) => (
                1.0,
                String::new(),
                Some(format!("`\\@2:Z scale` = {} is not `V [scale] (..) value unit`", excerpt(v))),
            ),
            Some((_, Some(z))) => soft_scale(&z, &global),
        };
        let per_lsb = if bpp == 4 { 1.0 / 65536.0 / 65536.0 } else { 1.0 / 65536.0 };
        let height_unit_m = length_unit(&unit);
        list.push(Channel {
            info: ChannelInfo {
                index: k,
                is_height: height_unit_m.is_some() && height_like(&name),
                name,
                nx: nx as usize,
                ny: ny as usize,
                size_m: Some(size_m),
                unit: clean(&unit),
                height_unit_m,
            },
            values: Values::Raster(Raster {
                offset: offset as usize,
                sample,
                big_endian: false,
                flip_x: false,
                flip_y: true,
                scale: scale * per_lsb,
                shift: 0.0,
                row_bytes: None,
                invalid: None,
            }),
            unreadable,
        });
    }
    if list.is_empty() {
        return Err(TopographyError::format(origin, 0, "no image (`\\*Ciao image list`) in the header"));
    }
    Ok(list)
}

/// The value of one LSB-range unit (hard value x soft scale) and the unit; a reason when the chain
/// cannot be followed.
fn soft_scale(z: &Scaled, global: &Section) -> (f64, String, Option<String>) {
    let Some(soft) = &z.soft else {
        return (z.hard_value, z.hard_unit.clone(), None);
    };
    let key = format!("@{}", soft.to_ascii_lowercase());
    let Some(sv) = global.get(&key) else {
        return (1.0, String::new(), Some(format!("the soft scale `\\@{}` is not in the header", excerpt(soft))));
    };
    let mut it = sv.split_whitespace();
    let (Some("V"), Some(value), unit) = (it.next(), it.next().and_then(|t| t.parse::<f64>().ok()), it.next()) else {
        return (1.0, String::new(), Some(format!("`\\@{}` = {} is not `V value unit`", excerpt(soft), excerpt(sv))));
    };
    // A soft scale without a unit (`V 1.000000`) leaves the values in the hard value's unit.
    let unit = unit.unwrap_or(&z.hard_unit);
    let (num, den) = unit.split_once('/').unwrap_or((unit, ""));
    if !den.is_empty() && den != z.hard_unit {
        return (
            1.0,
            num.to_string(),
            Some(format!("the soft scale is per {}, the hard value in {}", excerpt(den), excerpt(&z.hard_unit))),
        );
    }
    if !value.is_finite() {
        return (1.0, num.to_string(), Some("the soft scale is not finite".into()));
    }
    (z.hard_value * value, num.to_string(), None)
}

fn bracket(s: &str) -> Option<String> {
    let a = s.find('[')?;
    let b = a + s[a..].find(']')?;
    let t = s[a + 1..b].trim();
    (!t.is_empty()).then(|| t.to_string())
}

fn quoted(s: &str) -> Option<String> {
    let a = s.find('"')?;
    let b = a + 1 + s[a + 1..].find('"')?;
    let t = s[a + 1..b].trim();
    (!t.is_empty()).then(|| t.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_line_parses() {
        let z = parse_scaled("V [Sens. Zsens] (0.005035400 V/LSB) 2.910461 V").unwrap();
        assert_eq!((z.soft.as_deref(), z.hard_value, z.hard_unit.as_str()), (Some("Sens. Zsens"), 2.910461, "V"));
        let z = parse_scaled("V (0.1 V/LSB) 3 nm").unwrap();
        assert_eq!((z.soft, z.hard_value, z.hard_unit.as_str()), (None, 3.0, "nm"));
        assert!(parse_scaled("C [2:Z scale] 1.6").is_none());
    }
}
