//! ISO 25178-72 / ISO 5436-2 XML surface profiles (`.x3p`).
//!
//! Layout (ISO 5436-2:2012 and the openGPS schema `ISO5436_2.xsd`): a zip archive holding
//! `main.xml` and the binary point data it names. `main.xml`'s `Record1` gives the feature type
//! (`SUR`, an areal surface) and the axes: `CX`, `CY` of type `I` (incremental) with their
//! `Increment` (the pixel steps, metres), `CZ` of type `A` (absolute) with its `DataType` (`I`
//! int16, `L` int32, `F` float32, `D` float64) and, for integers, an optional `Increment` (metres
//! per stored unit); `Record3` the matrix (`SizeX` x `SizeY` x `SizeZ` = 1) and the data file
//! (`DataLink/PointDataLink`): little-endian values, x fastest, row 0 = y = 0. A NaN is an invalid
//! (missing) point.
//!
//! The archive is read with the `zip` crate (stored and deflate entries only); every entry's
//! declared size is checked against a limit before it is decompressed, and the decompression
//! stops at the limit whatever the header says (a zip bomb is refused, not inflated). Not read:
//! profiles and point clouds (`PRF`, `PCL`, axes not `I`, `I`, `A`), data inline in the XML
//! (`DataList`), integer data with a valid-points mask (`ValidPointsLink`), layers (`SizeZ` > 1).
//! Not checked: the MD5 checksums. The `CZ` offset is not added (heights are relative; maps are
//! levelled).

use std::collections::HashMap;
use std::io::Read;

use quick_xml::events::Event;
use stiction_units::text::excerpt;

use super::{Channel, ChannelInfo, Values};
use crate::{BINARY_INPUT_LIMIT_BYTES, MAX_PIXELS, TopographyError};

/// Largest `main.xml` accepted, bytes (writers produce 2 to 10 kB).
pub const X3P_MAX_XML_BYTES: u64 = 1 << 20;

/// Deepest element nesting of `main.xml` accepted.
const MAX_DEPTH: usize = 32;

pub(crate) fn is_zip(bytes: &[u8]) -> bool {
    bytes.starts_with(b"PK\x03\x04")
}

/// An entry's bytes, refusing a declared or actual size beyond `limit`.
fn entry(
    archive: &mut zip::ZipArchive<std::io::Cursor<&[u8]>>,
    name: &str,
    limit: u64,
    origin: &str,
) -> Result<Vec<u8>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    let f = archive.by_name(name).map_err(|e| match e {
        zip::result::ZipError::FileNotFound => bad(format!("the archive has no {}", excerpt(name))),
        e => bad(format!("entry {}: {}", excerpt(name), excerpt(&e.to_string()))),
    })?;
    if f.size() > limit {
        return Err(bad(format!(
            "entry {} declares {} bytes, more than the limit of {limit} bytes",
            excerpt(name),
            f.size()
        )));
    }
    let mut out = Vec::with_capacity(f.size() as usize);
    f.take(limit + 1)
        .read_to_end(&mut out)
        .map_err(|e| bad(format!("entry {}: {}", excerpt(name), excerpt(&e.to_string()))))?;
    if out.len() as u64 > limit {
        return Err(bad(format!("entry {} inflates past the limit of {limit} bytes", excerpt(name))));
    }
    Ok(out)
}

/// The text of every element of `xml`, by its path of local names (`Record1/Axes/CX/Increment`).
fn elements(xml: &str, origin: &str) -> Result<HashMap<String, String>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, format!("main.xml: {m}"));
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut path: Vec<String> = Vec::new();
    let mut out = HashMap::new();
    loop {
        match reader.read_event() {
            Err(e) => return Err(bad(excerpt(&e.to_string()))),
            Ok(Event::Eof) => break,
            Ok(Event::Start(e)) => {
                if path.len() >= MAX_DEPTH {
                    return Err(bad(format!("elements nested deeper than {MAX_DEPTH}")));
                }
                path.push(e.local_name().as_ref().to_string());
            }
            Ok(Event::End(_)) => {
                path.pop();
            }
            Ok(Event::Text(t)) => {
                let text = t.xml10_content();
                let text = text.trim();
                if !text.is_empty() && path.len() > 1 {
                    out.entry(path[1..].join("/")).or_insert_with(|| text.to_string());
                }
            }
            Ok(Event::Empty(e)) => {
                if !path.is_empty() {
                    let mut p = path[1..].to_vec();
                    p.push(e.local_name().as_ref().to_string());
                    out.entry(p.join("/")).or_insert_with(String::new);
                }
            }
            Ok(_) => {}
        }
    }
    Ok(out)
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if !is_zip(bytes) {
        return Err(bad("not an X3P file: it is not a zip archive (no `PK\\x03\\x04` at the start)".into()));
    }
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes))
        .map_err(|e| bad(format!("not a readable zip archive: {}", excerpt(&e.to_string()))))?;
    let xml = entry(&mut archive, "main.xml", X3P_MAX_XML_BYTES, origin)?;
    let xml = std::str::from_utf8(&xml).map_err(|_| bad("main.xml is not UTF-8 text".into()))?;
    let el = elements(xml, origin)?;
    let get = |k: &str| -> Result<&str, TopographyError> {
        el.get(k).map(String::as_str).ok_or_else(|| bad(format!("main.xml has no `{k}`")))
    };
    let feature = get("Record1/FeatureType")?;
    if feature != "SUR" {
        return Err(bad(format!("feature type {}: only areal surfaces (`SUR`) are read", excerpt(feature))));
    }
    for (axis, want) in [("CX", "I"), ("CY", "I"), ("CZ", "A")] {
        let t = get(&format!("Record1/Axes/{axis}/AxisType"))?;
        if t != want {
            return Err(bad(format!(
                "axis {axis} is of type {}: only a regular grid (CX, CY incremental `I`, CZ absolute `A`) is read",
                excerpt(t)
            )));
        }
    }
    let real = |k: &str| -> Result<f64, TopographyError> {
        let v = get(k)?;
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && *x > 0.0)
            .ok_or_else(|| bad(format!("`{k}` = {}: expected a finite number > 0", excerpt(v))))
    };
    let int = |k: &str| -> Result<u64, TopographyError> {
        let v = get(k)?;
        v.parse::<u64>().map_err(|_| bad(format!("`{k}` = {}: expected an integer >= 0", excerpt(v))))
    };
    let (dx, dy) = (real("Record1/Axes/CX/Increment")?, real("Record1/Axes/CY/Increment")?);
    let nx = int("Record3/MatrixDimension/SizeX")?;
    let ny = int("Record3/MatrixDimension/SizeY")?;
    let nz = int("Record3/MatrixDimension/SizeZ")?;
    if nz != 1 {
        return Err(bad(format!("`SizeZ` = {nz}: only one layer (1) is read")));
    }
    crate::map::check_grid_size(origin, nx, ny)?;
    let (size, float) = match get("Record1/Axes/CZ/DataType")? {
        "I" => (2usize, false),
        "L" => (4, false),
        "F" => (4, true),
        "D" => (8, true),
        t => return Err(bad(format!("CZ data type {}: expected I, L, F or D", excerpt(t)))),
    };
    let scale = match el.get("Record1/Axes/CZ/Increment") {
        Some(_) => real("Record1/Axes/CZ/Increment")?,
        None => 1.0,
    };
    if el.contains_key("Record3/DataList") || el.keys().any(|k| k.starts_with("Record3/DataList/")) {
        return Err(bad("the points are inline in main.xml (`DataList`): not read".into()));
    }
    if !float && el.keys().any(|k| k.ends_with("ValidPointsLink")) {
        return Err(bad("integer data with a valid-points mask (`ValidPointsLink`): not read".into()));
    }
    let link = get("Record3/DataLink/PointDataLink")?.to_string();
    let n = nx * ny;
    let need = n * size as u64;
    let data = entry(&mut archive, &link, need.min(BINARY_INPUT_LIMIT_BYTES), origin)?;
    if (data.len() as u64) < need {
        return Err(bad(format!(
            "{} holds {} bytes, fewer than {nx} x {ny} x {size} = {need}",
            excerpt(&link),
            data.len()
        )));
    }
    debug_assert!(n <= MAX_PIXELS);
    let values: Vec<f64> = match (size, float) {
        (2, false) => {
            data.chunks_exact(2).take(n as usize).map(|c| f64::from(i16::from_le_bytes([c[0], c[1]])) * scale).collect()
        }
        (4, false) => data
            .chunks_exact(4)
            .take(n as usize)
            .map(|c| f64::from(i32::from_le_bytes([c[0], c[1], c[2], c[3]])) * scale)
            .collect(),
        (4, true) => data
            .chunks_exact(4)
            .take(n as usize)
            .map(|c| f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])) * scale)
            .collect(),
        _ => data
            .chunks_exact(8)
            .take(n as usize)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])) * scale)
            .collect(),
    };
    Ok(vec![Channel {
        info: ChannelInfo {
            index: 0,
            name: "Default".into(),
            nx: nx as usize,
            ny: ny as usize,
            size_m: Some((dx * nx as f64, dy * ny as f64)),
            unit: "m".into(),
            height_unit_m: Some(1.0),
            is_height: true,
        },
        values: Values::Parsed(values),
        unreadable: None,
    }])
}
