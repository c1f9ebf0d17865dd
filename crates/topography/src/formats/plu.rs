//! Sensofar `.plu` files (confocal and interferometric profilers), topography measurements.
//!
//! Layout (little-endian; Sensofar's SPM file layout as Gwyddion's `sensofar` module and
//! SurfaceTopography read it): a 128-byte date string, a uint32 time and a 256-byte comment; at 388
//! the calibration (uint32 rows `ny`, columns `nx`, planes; float32 `dy_multip`, the µm per pixel
//! along x at 404 and y at 408, offsets, the µm per height unit, z offset); at 428 the measurement
//! configuration (uint32 type, 3 a topography, 1 a profile; algorithm; method; objective; area
//! type), 40 bytes of scan settings, then at 488 the bytes `restore`, `num_layers`, `version`,
//! `config_hardware`, `num_images`, 3 reserved and a uint32: 500 bytes of header. Then each layer:
//! uint32 `ny`, `nx`, `nx x ny` float32 heights in µm (x fastest, row 0 first), float32 min, max.
//! A height of 1000001 is a non-measured point (missing).
//!
//! The format has no magic bytes: a file is taken for Sensofar when its first bytes are a text date
//! (printable ASCII up to a NUL), its calibration grid equals its first layer's and the measurement
//! type is a topography or a profile. Not read (refused): profiles and other measurement types.

use super::fields::Fields;
use super::{Channel, ChannelInfo, Missing, Raster, Sample, Values};
use crate::TopographyError;

const HEADER: usize = 500;
const TOPOGRAPHY: u32 = 3;
const PROFILE: u32 = 1;
/// A non-measured point.
const UNDEFINED: f64 = 1_000_001.0;

pub(crate) fn is_plu(bytes: &[u8]) -> bool {
    let f = Fields::le(bytes);
    if bytes.len() < HEADER + 8 {
        return false;
    }
    let date = &bytes[..128];
    let text = date.iter().take_while(|&&b| b != 0).count();
    if text == 0 || text == 128 || !date[..text].iter().all(|b| (0x20..0x7f).contains(b)) {
        return false;
    }
    let grid = (f.u32(388), f.u32(392));
    grid == (f.u32(HEADER), f.u32(HEADER + 4)) && matches!(f.u32(428), Some(TOPOGRAPHY | PROFILE))
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if !is_plu(bytes) {
        return Err(bad(
            "not a Sensofar PLU file: no date string, calibration grid and first layer grid that agree".into()
        ));
    }
    let f = Fields::le(bytes);
    let kind = f.u32(428).unwrap_or(0);
    if kind != TOPOGRAPHY {
        return Err(bad(format!("measurement type {kind}: only a topography (3) is read, not a profile")));
    }
    let (px_um, py_um) = (f.f32(404).unwrap_or(f64::NAN), f.f32(408).unwrap_or(f64::NAN));
    if !(px_um.is_finite() && py_um.is_finite() && px_um > 0.0 && py_um > 0.0) {
        return Err(bad(format!("pixel size {px_um:e} x {py_um:e} µm: expected finite values > 0")));
    }
    let layers = usize::from(f.u8(489).unwrap_or(0));
    if layers == 0 {
        return Err(bad("no layer: the file holds no map".into()));
    }
    let mut at = HEADER;
    let mut list = Vec::with_capacity(layers);
    for k in 0..layers {
        let (ny, nx) = match (f.u32(at), f.u32(at + 4)) {
            (Some(a), Some(b)) => (u64::from(a), u64::from(b)),
            _ => return Err(bad(format!("layer {k}: its grid at byte {at} is past the end ({} bytes)", bytes.len()))),
        };
        crate::map::check_grid_size(origin, nx, ny)?;
        let offset = at + 8;
        let end = offset as u64 + nx * ny * 4 + 8;
        if end > bytes.len() as u64 {
            return Err(bad(format!(
                "layer {k}: {nx} x {ny} float32 heights from byte {offset} need {end} bytes, the file has {}",
                bytes.len()
            )));
        }
        let name = format!("layer{k}");
        list.push(Channel {
            info: ChannelInfo {
                index: k,
                name,
                nx: nx as usize,
                ny: ny as usize,
                size_m: Some((px_um * 1e-6 * nx as f64, py_um * 1e-6 * ny as f64)),
                unit: "µm".into(),
                height_unit_m: Some(1e-6),
                is_height: true,
            },
            values: Values::Raster(Raster {
                offset,
                sample: Sample::F32,
                big_endian: false,
                flip_x: false,
                flip_y: false,
                scale: 1.0,
                shift: 0.0,
                row_bytes: None,
                invalid: Some(Missing::Equal(UNDEFINED)),
            }),
            unreadable: None,
        });
        at = end as usize;
    }
    Ok(list)
}
