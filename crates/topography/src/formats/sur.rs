//! Digital Surf (MountainsMap) surface files (`.sur`), uncompressed, one object.
//!
//! Layout (Digital Surf's SUR format description, as Gwyddion's `surffile` module and
//! SurfaceTopography read it): a 512-byte little-endian header (`DIGITAL SURF` at 0; at 12 the
//! byte order, 0 for PC; 14 the number of objects; 18 the object type, 2 a surface; 86 the
//! non-measured-points flag; 98 bits per sample, 16 or 32; 100 `zmin`; 108, 112 the grid
//! `nx`, `ny`; 116 the point count; 120, 124 the steps (float32, in the units at 180 and 196);
//! 128 the height step (float32, in the unit at 212); 290 the inversion flag; 334, 336 the sizes of
//! a comment and a private zone that follow the header), then the samples, x fastest, row 0 =
//! y = 0. When the flag at 86 is 1, a sample of `zmin - 2` is a non-measured (missing) point.
//!
//! Not read (refused with the reason): compressed files (`DSCOMPRESSED`), Macintosh byte order,
//! several objects, profiles and other object types, inverted or flipped data (inversion flag
//! other than 0).

use super::{Channel, ChannelInfo, Missing, Raster, Sample, Values, clean, latin1, length_unit};
use crate::TopographyError;

const HEADER: usize = 512;

pub(crate) fn is_sur(bytes: &[u8]) -> bool {
    bytes.starts_with(b"DIGITAL SURF") || bytes.starts_with(b"DSCOMPRESSED")
}

/// A unit as the file writes it (latin-1; `æm`, an old code page's micro sign, is `µm`).
fn unit_at(bytes: &[u8], at: usize) -> String {
    let u = clean(latin1(&bytes[at..at + 16]).trim());
    if u == "\u{e6}m" { "µm".into() } else { u }
}

pub(crate) fn channels(bytes: &[u8], origin: &str) -> Result<Vec<Channel>, TopographyError> {
    let bad = |m: String| TopographyError::format(origin, 0, m);
    if bytes.starts_with(b"DSCOMPRESSED") {
        return Err(bad("a compressed Digital Surf file (`DSCOMPRESSED`) is not read: save it uncompressed".into()));
    }
    if !bytes.starts_with(b"DIGITAL SURF") {
        return Err(bad("not a Digital Surf file: it does not start with `DIGITAL SURF`".into()));
    }
    if bytes.len() < HEADER {
        return Err(bad(format!("{} bytes: a Digital Surf header has {HEADER}", bytes.len())));
    }
    let u16_at = |at: usize| u16::from_le_bytes([bytes[at], bytes[at + 1]]);
    let i32_at = |at: usize| i32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let f32_at = |at: usize| f64::from(f32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]));
    match u16_at(12) {
        0 => {}
        257 => return Err(bad("Macintosh byte order (format 257) is not read".into())),
        f => return Err(bad(format!("format {f}: expected 0 (PC byte order)"))),
    }
    if u16_at(14) != 1 {
        return Err(bad(format!("{} objects: only a file of one object is read", u16_at(14))));
    }
    if u16_at(18) != 2 {
        return Err(bad(format!("object type {}: only a surface (2) is read", u16_at(18))));
    }
    if u16_at(290) != 0 {
        return Err(bad(format!("inversion flag {}: inverted or flipped data are not read", u16_at(290))));
    }
    let sample = match u16_at(98) {
        16 => Sample::I16,
        32 => Sample::I32,
        b => return Err(bad(format!("{b} bits per sample: expected 16 or 32"))),
    };
    let (nx, ny) = (i32_at(108), i32_at(112));
    if nx < 0 || ny < 0 {
        return Err(bad(format!("a {nx} x {ny} grid")));
    }
    let (nx, ny) = (nx as u64, ny as u64);
    crate::map::check_grid_size(origin, nx, ny)?;
    let points = u64::from(u32::from_le_bytes([bytes[116], bytes[117], bytes[118], bytes[119]]));
    if points != nx * ny {
        return Err(bad(format!("{points} points, but the grid is {nx} x {ny}")));
    }
    let offset = HEADER + usize::from(u16_at(334)) + usize::from(u16_at(336));
    let need = nx * ny * sample.bytes() as u64;
    if (bytes.len() as u64) < offset as u64 + need {
        return Err(bad(format!(
            "{nx} x {ny} samples of {} bytes from byte {offset} need {} bytes, the file has {}",
            sample.bytes(),
            offset as u64 + need,
            bytes.len()
        )));
    }
    let (dx, dy, dz) = (f32_at(120), f32_at(124), f32_at(128));
    let (ux, uy, uz) = (unit_at(bytes, 180), unit_at(bytes, 196), unit_at(bytes, 212));
    let size_m = match (length_unit(&ux), length_unit(&uy)) {
        (Some(fx), Some(fy)) if dx.is_finite() && dy.is_finite() && dx > 0.0 && dy > 0.0 => {
            Some((dx * fx * nx as f64, dy * fy * ny as f64))
        }
        (Some(_), Some(_)) => return Err(bad(format!("steps {dx:e}, {dy:e}: expected finite values > 0"))),
        _ => None,
    };
    if !(dz.is_finite() && dz != 0.0) {
        return Err(bad(format!("height step {dz:e}: expected a finite value other than 0")));
    }
    let height_unit_m = length_unit(&uz);
    let invalid = (u16_at(86) == 1).then(|| Missing::Equal(f64::from(i32_at(100)) - 2.0));
    Ok(vec![Channel {
        info: ChannelInfo {
            index: 0,
            name: "Default".into(),
            nx: nx as usize,
            ny: ny as usize,
            size_m,
            is_height: height_unit_m.is_some() || uz.is_empty(),
            unit: uz,
            height_unit_m,
        },
        values: Values::Raster(Raster {
            offset,
            sample,
            big_endian: false,
            flip_x: false,
            flip_y: false,
            scale: dz,
            shift: 0.0,
            row_bytes: None,
            invalid,
        }),
        unreadable: None,
    }])
}
