//! A height map as a scenario's surface section sources it, and the shoe's patch cut from it.
//!
//! ```json
//! "height_map": {
//!   "file": "../data/topography-example/example.gsf",
//!   "level": "plane", "short_cutoff": "40 nm",
//!   "patch_x": "1 um", "patch_y": "0.5 um"
//! }
//! ```
//!
//! The map is read ([`crate::read_file`], relative paths against the scenario's folder) and
//! prepared ([`crate::prepare`]); the shoe's apparent area (`apparent_length x apparent_width` of
//! the surface section) is cut from it at the stated corner (`patch_x`, `patch_y`) or, without
//! them, at a random pixel-aligned corner drawn from the surface seed, so that each Monte Carlo
//! sample (seed + i) sees another part of the measured wall. Summits are sought in the patch with
//! the map's pixels around it as neighbours.

use std::path::{Path, PathBuf};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::{
    HeightMap, Levelling, MapFormat, MapInfo, MapMetadata, Preparation, PreparationReport, TopographyError,
    find_summits_in, parse_length_unit, prepare, read_file,
};

/// A height-map file with its metadata and preparation (a scenario's `surface.height_map`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HeightMapSpec {
    /// The height-map file; a relative path is resolved against the scenario file's folder.
    pub file: PathBuf,
    /// "npy", "text", "gsf" or "xyz"; default: from the file's extension (.npy, .gsf, .xyz, else text).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub format: Option<MapFormat>,
    /// Pixel size along x \[m\] ("10 nm"), when the file does not state it.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub pixel_size: Option<f64>,
    /// Pixel size along y \[m\]; default: `pixel_size`.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub pixel_size_y: Option<f64>,
    /// Unit of the file's heights ("nm", "um", "m"), when the file does not state it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_unit: Option<String>,
    /// Unit of the x and y coordinates of an xyz point list ("um").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub xy_unit: Option<String>,
    /// Levelling: "none", "mean", "plane" (default), "poly2" or "poly3".
    #[serde(default)]
    pub level: Levelling,
    /// Short-wavelength cut-off \[m\] (Gaussian low-pass, 50 % at this wavelength); default none.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub short_cutoff: Option<f64>,
    /// Long-wavelength cut-off \[m\] (Gaussian high-pass, 50 % at this wavelength); default none.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub long_cutoff: Option<f64>,
    /// x of the patch's corner in the map \[m\] (with `patch_y`); absent: a random corner per seed.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_nonnegative",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub patch_x: Option<f64>,
    /// y of the patch's corner in the map \[m\] (with `patch_x`).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_nonnegative",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub patch_y: Option<f64>,
}

/// A pixel window of a map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Patch {
    /// First column.
    pub ix0: usize,
    /// First row.
    pub iy0: usize,
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
}

/// Summits of a patch, positioned in the patch's frame (the patch's corner at 0, pixel centres).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PatchSummits {
    /// x \[m\], in `(0, nx dx)`.
    pub x_m: Vec<f64>,
    /// y \[m\], in `(0, ny dy)`.
    pub y_m: Vec<f64>,
    /// Height above the prepared map's reference plane \[m\].
    pub height_m: Vec<f64>,
    /// Radius 1/kappa \[m\].
    pub radius_m: Vec<f64>,
}

impl HeightMapSpec {
    /// The metadata given in the scenario.
    pub fn metadata(&self) -> Result<MapMetadata, TopographyError> {
        let unit = |field: &str, v: &Option<String>| -> Result<Option<f64>, TopographyError> {
            v.as_deref()
                .map(|u| {
                    parse_length_unit(u).map_err(|e| TopographyError::invalid(field, u, format!("a length unit: {e}")))
                })
                .transpose()
        };
        Ok(MapMetadata {
            pixel_size_x_m: self.pixel_size,
            pixel_size_y_m: self.pixel_size_y,
            height_unit_m: unit("height_unit", &self.height_unit)?,
            xy_unit_m: unit("xy_unit", &self.xy_unit)?,
        })
    }

    /// The preparation asked for.
    pub fn preparation(&self) -> Preparation {
        Preparation { levelling: self.level, short_cutoff_m: self.short_cutoff, long_cutoff_m: self.long_cutoff }
    }

    /// Reads (relative paths against `base_dir`) and prepares the map.
    pub fn load(&self, base_dir: &Path) -> Result<(HeightMap, MapInfo, PreparationReport), TopographyError> {
        let path = if self.file.is_absolute() { self.file.clone() } else { base_dir.join(&self.file) };
        let (map, info) = read_file(&path, self.format, &self.metadata()?)?;
        let (prepared, report) = prepare(&map, &self.preparation())?;
        Ok((prepared, info, report))
    }

    /// The patch of `length_m x width_m` for this spec: at (`patch_x`, `patch_y`) or drawn from
    /// `seed` on ChaCha8 stream `stream`.
    pub fn patch(
        &self,
        map: &HeightMap,
        length_m: f64,
        width_m: f64,
        seed: u64,
        stream: u64,
    ) -> Result<Patch, TopographyError> {
        let corner = match (self.patch_x, self.patch_y) {
            (Some(x), Some(y)) => Some((x, y)),
            (None, None) => None,
            _ => {
                return Err(TopographyError::invalid(
                    "patch_x/patch_y",
                    "only one given",
                    "both (a stated corner) or neither (a random corner per seed)",
                ));
            }
        };
        choose_patch(map, length_m, width_m, corner, seed, stream)
    }
}

/// Pixels of a patch `length` long at pixel size `d`: `floor(length/d)` (with a 1e-9 relative
/// allowance for rounding, so 20 um at 10 nm is 2000 pixels).
fn patch_pixels(length: f64, d: f64) -> usize {
    (length / d * (1.0 + 1e-9)).floor() as usize
}

/// The window of a map covering an apparent area of `length_m x width_m`: at the corner
/// `corner_m` (rounded to the nearest pixel) or at a uniformly drawn pixel corner
/// (`ChaCha8Rng::seed_from_u64(seed)`, stream `stream`).
pub fn choose_patch(
    map: &HeightMap,
    length_m: f64,
    width_m: f64,
    corner_m: Option<(f64, f64)>,
    seed: u64,
    stream: u64,
) -> Result<Patch, TopographyError> {
    let (nx, ny) = (patch_pixels(length_m, map.dx_m()), patch_pixels(width_m, map.dy_m()));
    if nx < 3 || ny < 3 || nx > map.nx() || ny > map.ny() {
        return Err(TopographyError::invalid(
            "apparent area",
            format!("{length_m} m x {width_m} m ({nx} x {ny} pixels)"),
            format!(
                "a patch of at least 3 x 3 pixels inside the map of {} x {} pixels ({} m x {} m)",
                map.nx(),
                map.ny(),
                map.length_x_m(),
                map.length_y_m()
            ),
        ));
    }
    let (ix0, iy0) = match corner_m {
        Some((x, y)) => {
            let (ix0, iy0) = ((x / map.dx_m()).round() as usize, (y / map.dy_m()).round() as usize);
            if ix0 + nx > map.nx() || iy0 + ny > map.ny() {
                return Err(TopographyError::invalid(
                    "patch_x/patch_y",
                    format!("({x} m, {y} m)"),
                    format!(
                        "a corner with the {length_m} m x {width_m} m patch inside the {} m x {} m map",
                        map.length_x_m(),
                        map.length_y_m()
                    ),
                ));
            }
            (ix0, iy0)
        }
        None => {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            rng.set_stream(stream);
            (rng.random_range(0..=map.nx() - nx), rng.random_range(0..=map.ny() - ny))
        }
    };
    Ok(Patch { ix0, iy0, nx, ny })
}

/// The patch with up to one pixel of margin on each side (where the map has it), and the margins
/// (left, bottom).
fn with_margin(map: &HeightMap, p: &Patch, left: usize, bottom: usize, right: usize, top: usize) -> HeightMap {
    // The window always lies inside the map (margins are clamped by the caller).
    map.crop(p.ix0 - left, p.iy0 - bottom, p.nx + left + right, p.ny + bottom + top).unwrap_or_else(|_| map.clone())
}

/// The summits of one or two prepared maps' patches: with two, their heights are added (the
/// composite surface of two faces: the gap between them is that of a flat against the sum, with
/// the second face's heights measured towards the first), which needs equal pixel sizes.
pub fn patch_summits(faces: &[(&HeightMap, Patch)]) -> Result<PatchSummits, TopographyError> {
    let margin = |f: &dyn Fn(&HeightMap, &Patch) -> usize| faces.iter().map(|(m, p)| f(m, p).min(1)).min().unwrap_or(0);
    let left = margin(&|_, p| p.ix0);
    let bottom = margin(&|_, p| p.iy0);
    let right = margin(&|m, p| m.nx() - p.ix0 - p.nx);
    let top = margin(&|m, p| m.ny() - p.iy0 - p.ny);
    let mut window: Option<HeightMap> = None;
    for (m, p) in faces {
        let w = with_margin(m, p, left, bottom, right, top);
        window = Some(match window {
            None => w,
            Some(acc) => acc.add(&w)?,
        });
    }
    let Some(w) = window else { return Ok(PatchSummits::default()) };
    let p = faces[0].1;
    let s = find_summits_in(&w, left, bottom, left + p.nx, bottom + p.ny);
    let mut out = PatchSummits::default();
    for i in 0..s.len() {
        out.x_m.push((s.ix[i] as usize - left) as f64 * w.dx_m() + 0.5 * w.dx_m());
        out.y_m.push((s.iy[i] as usize - bottom) as f64 * w.dy_m() + 0.5 * w.dy_m());
        out.height_m.push(s.height_m[i]);
        out.radius_m.push(s.radius_m(i));
    }
    Ok(out)
}
