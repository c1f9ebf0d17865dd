//! Igor binary wave files (`.ibw`), version 5, as Asylum Research (Oxford Instruments) AFMs write
//! them.
//!
//! Layout (WaveMetrics Technical Note PTN003, "Igor Pro binary wave file format"): a 64-byte
//! `BinHeader5` (version 5 as an int16 in the file's byte order, which the version field itself
//! gives; a checksum that makes the int16 sum of the first 384 bytes zero; the sizes of the
//! sections after the data), a 320-byte `WaveHeader5` (at its byte 76 `npnts`, 80 the number type,
//! 132 `nDim[4]`, 148 `sfA[4]` the pixel steps, 212 `dataUnits`, 216 `dimUnits[4][4]`), the samples
//! from byte 384 (dimension 0 fastest), then the formula, the note, the extended data unit, the
//! extended dimension units and the dimension labels (32 bytes per label, label 0 the dimension's
//! own). An image of `nDim = [nx, ny, channels]` holds one channel per layer; the layers' labels
//! (dimension 2) name the channels. Dimension 1 is stored from y = 0 at the bottom: the file's
//! last row is row 0 of the map, as SurfaceTopography reads it.
//!
//! Units: the data unit is the heights' unit and the dimension units the pixel steps'; a wave
//! without them (the minimal files Igor writes) has none, and the reader asks for
//! `--pixel-size`/`--height-unit`. Not read: versions 1 to 3 and complex or text waves (refused).

use super::{Channel, ChannelInfo, Raster, Sample, Values, clean, height_like, latin1, length_unit};
use crate::TopographyError;

const HEADER_BYTES: usize = 384;

/// The file's byte order if it is a version-5 wave with a valid header checksum.
fn byte_order(bytes: &[u8]) -> Option<bool> {
    if bytes.len() < HEADER_BYTES {
        return None;
    }
    let big = match (bytes[0], bytes[1]) {
        (5, 0) => false,
        (0, 5) => true,
        _ => return None,
    };
    let sum = bytes[..HEADER_BYTES].chunks_exact(2).fold(0u16, |s, c| {
        s.wrapping_add(if big { u16::from_be_bytes([c[0], c[1]]) } else { u16::from_le_bytes([c[0], c[1]]) })
    });
    (sum == 0).then_some(big)
}

pub(crate) fn is_ibw(bytes: &[u8]) -> bool {
    byte_order(bytes).is_some()
}

struct Reader<'a> {
    b: &'a [u8],
    big: bool,
}

impl Reader<'_> {
    fn i16(&self, at: usize) -> i16 {
        let a = [self.b[at], self.b[at + 1]];
        if self.big { i16::from_be_bytes(a) } else { i16::from_le_bytes(a) }
    }
    fn i32(&self, at: usize) -> i32 {
        let a = [self.b[at], self.b[at + 1], self.b[at + 2], self.b[at + 3]];
        if self.big { i32::from_be_bytes(a) } else { i32::from_le_bytes(a) }
    }
    fn f64(&self, at: usize) -> f64 {
        let mut a = [0u8; 8];
        a.copy_from_slice(&self.b[at..at + 8]);
        if self.big { f64::from_be_bytes(a) } else { f64::from_le_bytes(a) }
    }
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if bytes.len() >= 2 && bytes.len() < HEADER_BYTES {
        return Err(bad(format!("{} bytes: an Igor binary wave has a header of {HEADER_BYTES}", bytes.len())));
    }
    let big = match byte_order(bytes) {
        Some(b) => b,
        None => {
            let v = bytes.get(..2).map(|v| (v[0], v[1]));
            return Err(bad(match v {
                Some((v @ 1..=3, 0)) | Some((0, v @ 1..=3)) => {
                    format!("Igor binary wave version {v} is not read (only version 5)")
                }
                Some((5, 0)) | Some((0, 5)) => {
                    "the Igor binary wave header's checksum does not match: the file is damaged".to_string()
                }
                _ => "not an Igor binary wave (version 5): the first two bytes are not 5".to_string(),
            }));
        }
    };
    let r = Reader { b: bytes, big };
    let size = |at: usize, what: &str| -> Result<usize, TopographyError> {
        let v = r.i32(at);
        usize::try_from(v).map_err(|_| bad(format!("the {what} size is {v}: expected >= 0")))
    };
    let wfm = size(4, "wave")?;
    let formula = size(8, "formula")?;
    let note = size(12, "note")?;
    let data_eunits = size(16, "extended data unit")?;
    let mut dim_eunits = [0usize; 4];
    let mut dim_labels = [0usize; 4];
    for d in 0..4 {
        dim_eunits[d] = size(20 + 4 * d, "extended dimension unit")?;
        dim_labels[d] = size(36 + 4 * d, "dimension label")?;
    }
    let npnts = r.i32(76);
    let sample = match r.i16(80) {
        2 => Sample::F32,
        4 => Sample::F64,
        8 => Sample::I8,
        0x10 => Sample::I16,
        0x20 => Sample::I32,
        0x48 => Sample::U8,
        0x50 => Sample::U16,
        0x60 => Sample::U32,
        0 => return Err(bad("a text wave holds no heights".into())),
        t if t & 1 == 1 => return Err(bad(format!("number type {t} is complex: a height map is real"))),
        t => return Err(bad(format!("number type {t} is not an Igor number type"))),
    };
    let dims: Vec<i32> = (0..4).map(|d| r.i32(132 + 4 * d)).collect();
    let (nx, ny, layers) = match dims[..] {
        [nx, ny, l, 0] if nx >= 2 && ny >= 2 && l >= 0 => (nx as u64, ny as u64, l.max(1) as u64),
        _ => {
            return Err(bad(format!(
                "dimensions {dims:?}: expected an image or a stack of images (nx >= 2, ny >= 2, layers, 0)"
            )));
        }
    };
    crate::map::check_grid_size(origin, nx, ny)?;
    let per_layer = nx * ny;
    let total = per_layer
        .checked_mul(layers)
        .filter(|&t| t == npnts.max(0) as u64)
        .ok_or_else(|| bad(format!("{nx} x {ny} x {layers} points, but the header's point count is {npnts}")))?;
    let data_bytes = total * sample.bytes() as u64;
    let end_of_data = HEADER_BYTES as u64 + data_bytes;
    if end_of_data > bytes.len() as u64 || (wfm as u64) < 320 + data_bytes {
        return Err(bad(format!(
            "{total} samples of {} bytes from byte {HEADER_BYTES} need {end_of_data} bytes (the file has {}, the \
             wave size is {wfm})",
            sample.bytes(),
            bytes.len()
        )));
    }
    // Sections after the wave: formula, note, extended data unit, extended dimension units, labels.
    let mut at = 64usize.saturating_add(wfm);
    let mut take = |n: usize| -> Option<&[u8]> {
        let s = at;
        at = at.checked_add(n)?;
        bytes.get(s..at)
    };
    let _formula = take(formula);
    let _note = take(note);
    let ext_data_unit = take(data_eunits).map(latin1);
    let ext_dim_units: Vec<Option<String>> = (0..4).map(|d| take(dim_eunits[d]).map(latin1)).collect();
    let labels: Vec<Option<&[u8]>> = (0..4).map(|d| take(dim_labels[d])).collect();
    let unit_of = |short_at: usize, ext: Option<String>| -> String {
        let short = latin1(&bytes[short_at..short_at + 4]);
        if short.is_empty() { ext.unwrap_or_default() } else { short }
    };
    let data_unit = unit_of(212, ext_data_unit.filter(|_| data_eunits > 0));
    let x_unit = unit_of(216, ext_dim_units[0].clone().filter(|_| dim_eunits[0] > 0));
    let y_unit = unit_of(220, ext_dim_units[1].clone().filter(|_| dim_eunits[1] > 0));
    let (sx, sy) = (r.f64(148), r.f64(156));
    let size_m = match (length_unit(&x_unit), length_unit(&y_unit)) {
        (Some(fx), Some(fy)) => {
            let (a, b) = (sx * fx * nx as f64, sy * fy * ny as f64);
            if !(a.is_finite() && b.is_finite() && a > 0.0 && b > 0.0) {
                return Err(bad(format!("pixel steps sfA = {sx:e}, {sy:e}: expected finite values > 0")));
            }
            Some((a, b))
        }
        _ => None,
    };
    let height_unit_m = length_unit(&data_unit);
    let names: Vec<String> = (0..layers as usize)
        .map(|k| {
            labels[2]
                .and_then(|l| l.get((k + 1) * 32..(k + 2) * 32))
                .map(latin1)
                .map(|s| clean(&s))
                .filter(|s| !s.trim().is_empty())
                .unwrap_or_else(|| format!("no name ({})", k + 1))
        })
        .collect();
    let any_height_name = names.iter().any(|n| height_like(n));
    let unit_ok = data_unit.is_empty() || height_unit_m.is_some();
    Ok(names
        .into_iter()
        .enumerate()
        .map(|(k, name)| Channel {
            info: ChannelInfo {
                index: k,
                is_height: unit_ok && (height_like(&name) || (!any_height_name && k == 0)),
                name,
                nx: nx as usize,
                ny: ny as usize,
                size_m,
                unit: clean(&data_unit),
                height_unit_m,
            },
            values: Values::Raster(Raster {
                offset: HEADER_BYTES + k * (per_layer as usize) * sample.bytes(),
                sample,
                big_endian: big,
                flip_x: false,
                flip_y: true,
                scale: 1.0,
                shift: 0.0,
                row_bytes: None,
                invalid: None,
            }),
            unreadable: None,
        })
        .collect())
}
