//! The `surface` section of a scenario file.
//!
//! ```json
//! "surface": {
//!   "apparent_length": "20 um", "apparent_width": "5 um",
//!   "summit_density": "4e12 m^-2", "summit_sd": "0.04 um", "summit_radius": "0.5 um",
//!   "seed": 1
//! }
//! ```
//!
//! Quantities accept a JSON number (SI), a string with a unit ("0.5 um") or an uncertain-parameter
//! object (its nominal value is used). Unknown fields are rejected.

use std::path::PathBuf;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::{FaceParams, HeightDistribution, Layout, Placement, RadiusDistribution, SurfaceError};

/// Where the summits come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceSource {
    /// Generated from the statistical parameters (default).
    #[default]
    Generated,
    /// Read from the CSV file `csv_path` (columns x_m, y_m, height_m, radius_m).
    Csv,
    /// Found on a patch of a measured height map (`height_map` and/or `counter_height_map`).
    HeightMap,
    /// Read from the NumPy file `npy_path`: an N x 4 float array (x, y, height, radius in m), a
    /// structured array with float fields x, y, height\[, radius\], or heights alone (N,) with
    /// `summit_radius` and positions drawn uniformly from `seed`.
    Npy,
}

/// How a second rough face (`counter_face`) is combined with the first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TwoFaceMode {
    /// The paper's composite surface (section 3.1): eta = eta1 + eta2, sigma^2 = sigma1^2 + sigma2^2,
    /// 1/R = 1/R1 + 1/R2, against a flat shoe (default).
    #[default]
    Composite,
    /// Both faces generated; shoe summits meet wall summits pair by pair (see
    /// [`crate::generate_two_face`]).
    Explicit,
}

/// Statistical parameters of the second rough face (the shoe's face).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FaceSpec {
    /// Summit density eta \[m^-2\], e.g. "2e12 m^-2".
    #[serde(deserialize_with = "stiction_units::de::areal_density_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub summit_density: f64,
    /// Summit height standard deviation sigma \[m\], e.g. "0.03 um".
    #[serde(deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub summit_sd: f64,
    /// Height distribution: "gaussian" (default) or "exponential".
    #[serde(default)]
    pub height_distribution: HeightDistribution,
    /// Mean summit radius R \[m\], e.g. "1 um".
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub summit_radius: f64,
    /// Summit radius SD \[m\]; default 0 (required > 0 with `radius_distribution` = "lognormal").
    #[serde(default, deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub radius_sd: f64,
    /// Radius distribution: "fixed" (default) or "lognormal".
    #[serde(default)]
    pub radius_distribution: RadiusDistribution,
}

impl FaceSpec {
    /// The generator parameters of this face.
    pub fn params(&self) -> FaceParams {
        FaceParams {
            summit_density_per_m2: self.summit_density,
            summit_sd_m: self.summit_sd,
            height_distribution: self.height_distribution,
            summit_radius_m: self.summit_radius,
            radius_sd_m: self.radius_sd,
            radius_distribution: self.radius_distribution,
        }
    }
}

/// The rough sidewall as a scenario file describes it.
///
/// With `source` = "generated" (default) the fields `summit_density`, `summit_sd` and
/// `summit_radius` are required; they describe the wall face, or, without a `counter_face`, the
/// composite of both faces as in the paper's Table 1. With `source` = "csv", `csv_path` is required
/// and the statistical fields must be absent.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SurfaceSpec {
    /// Length of the apparent contact area along x \[m\] (the paper's shoe: "20 um").
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub apparent_length: f64,
    /// Width of the apparent contact area along y \[m\] (the paper's shoe: "5 um").
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub apparent_width: f64,
    /// "generated" (default) or "csv".
    #[serde(default)]
    pub source: SurfaceSource,
    /// CSV file with columns x_m, y_m, height_m, radius_m (SI); relative paths are resolved
    /// against the scenario file's folder (given with `--set` on the command line: against the
    /// current directory). Only with `source` = "csv".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("x-stiction-path" = true))]
    pub csv_path: Option<PathBuf>,
    /// NumPy `.npy` file of summits (see [`SurfaceSource::Npy`]); relative paths as for
    /// `csv_path`. Only with `source` = "npy".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("x-stiction-path" = true))]
    pub npy_path: Option<PathBuf>,
    /// "poisson" (default) or "jittered_grid".
    #[serde(default)]
    pub placement: Placement,
    /// Summit density eta \[m^-2\] (Table 1: "4e12 m^-2").
    #[serde(default, deserialize_with = "stiction_units::de::opt_areal_density_positive")]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub summit_density: Option<f64>,
    /// Summit height SD sigma \[m\] (Table 1: "0.04 um").
    #[serde(default, deserialize_with = "stiction_units::de::opt_length_nonnegative")]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub summit_sd: Option<f64>,
    /// "gaussian" (default) or "exponential".
    #[serde(default)]
    pub height_distribution: HeightDistribution,
    /// Mean summit radius R \[m\] (Table 1: "0.5 um").
    #[serde(default, deserialize_with = "stiction_units::de::opt_length_positive")]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub summit_radius: Option<f64>,
    /// Summit radius SD \[m\]; default 0 (Table 1 quotes "0.3 um" as R's uncertainty).
    #[serde(default, deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub radius_sd: f64,
    /// "fixed" (default) or "lognormal".
    #[serde(default)]
    pub radius_distribution: RadiusDistribution,
    /// Seed of the random generator; default 0.
    #[serde(default)]
    pub seed: u64,
    /// Version of the summit generator's random stream: 1 (default when absent: ChaCha8 streams,
    /// the heights sorted after drawing) or 2 (xoshiro256++ blocks, the heights drawn in descending
    /// order: 1.5-2x faster, parallel). Both draw the same random field; a version and a seed
    /// always give the same summits. Only with `source` = "generated".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1, max = 2))]
    pub generator: Option<u32>,
    /// The shoe's rough face, when both faces are described separately.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub counter_face: Option<FaceSpec>,
    /// How `counter_face` is combined: "composite" (default) or "explicit".
    #[serde(default)]
    pub two_face: TwoFaceMode,
    /// Explicit two-face mode: largest height a summit pair may lose to its lateral offset,
    /// r^2 / (2 (R1 + R2)) \[m\]; default 4 sqrt(sigma1^2 + sigma2^2).
    #[serde(default, deserialize_with = "stiction_units::de::opt_length_positive")]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub pair_reach: Option<f64>,
    /// Largest number of summits (or, in explicit two-face mode, summit pairs) the surface may
    /// hold; default 10 000 000 (about 1 GB with the explicit solver's arrays, see
    /// docs/reliability.md). The expected count eta A_a is checked against it before anything is
    /// generated. Raise it when the machine has the memory.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_summits: Option<u64>,
    /// With `source` = "height_map": the wall's measured height map, whose patch under the shoe
    /// gives the summits (see `stiction_topography::HeightMapSpec`).
    pub height_map: Option<stiction_topography::HeightMapSpec>,
    /// With `source` = "height_map": the shoe face's height map (heights towards the wall); with
    /// `height_map` as well, the two patches are added (composite surface).
    pub counter_height_map: Option<stiction_topography::HeightMapSpec>,
}

/// The default of `surface.max_summits`.
pub const DEFAULT_MAX_SUMMITS: u64 = 10_000_000;

/// Bytes per summit the budget message estimates (surface arrays 16-24 B plus the explicit
/// solver's per-summit state and sort buffers; measured order of magnitude, see docs/reliability.md).
pub const ESTIMATED_BYTES_PER_SUMMIT: f64 = 100.0;

/// Largest length any surface field may have, m: a MEMS sidewall and its summits are far below
/// a metre; beyond it the heights and offsets overflow the solver's arithmetic.
pub const MAX_LENGTH_M: f64 = 1.0;

impl SurfaceSpec {
    /// The wall face's (or only face's) parameters; errors name a missing field.
    pub fn face_params(&self) -> Result<FaceParams, SurfaceError> {
        let need = |v: Option<f64>, name: &str| {
            v.ok_or_else(|| SurfaceError::Spec(format!("`{name}` is required when `source` is \"generated\"")))
        };
        Ok(FaceParams {
            summit_density_per_m2: need(self.summit_density, "summit_density")?,
            summit_sd_m: need(self.summit_sd, "summit_sd")?,
            height_distribution: self.height_distribution,
            summit_radius_m: need(self.summit_radius, "summit_radius")?,
            radius_sd_m: self.radius_sd,
            radius_distribution: self.radius_distribution,
        })
    }

    /// The summit budget: `max_summits` or [`DEFAULT_MAX_SUMMITS`].
    pub fn summit_budget(&self) -> u64 {
        self.max_summits.unwrap_or(DEFAULT_MAX_SUMMITS)
    }

    /// Checks ranges and the summit budget without generating anything (called when a scenario
    /// is loaded, so `stiction scenario` reports it). Returns (field, message).
    pub fn check(&self) -> Result<(), (String, String)> {
        let mut lengths = vec![
            ("apparent_length", Some(self.apparent_length)),
            ("apparent_width", Some(self.apparent_width)),
            ("summit_sd", self.summit_sd),
            ("summit_radius", self.summit_radius),
            ("radius_sd", Some(self.radius_sd)),
            ("pair_reach", self.pair_reach),
        ];
        if let Some(c) = &self.counter_face {
            lengths.extend([
                ("counter_face.summit_sd", Some(c.summit_sd)),
                ("counter_face.summit_radius", Some(c.summit_radius)),
                ("counter_face.radius_sd", Some(c.radius_sd)),
            ]);
        }
        for (name, v) in lengths {
            if let Some(v) = v
                && v > MAX_LENGTH_M
            {
                return Err((
                    name.into(),
                    format!(
                        "{v:e} m is larger than {MAX_LENGTH_M} m, the largest length a MEMS surface field may have"
                    ),
                ));
            }
        }
        if let (Some(c), TwoFaceMode::Explicit, None) = (&self.counter_face, self.two_face, self.pair_reach)
            && self.summit_sd == Some(0.0)
            && c.summit_sd == 0.0
        {
            return Err((
                "summit_sd".into(),
                "0 m on both faces (and counter_face.summit_sd = 0 m): the default `pair_reach` is \
                 4 sqrt(summit_sd^2 + counter_face.summit_sd^2) = 0; give a summit_sd > 0 or a `pair_reach`"
                    .into(),
            ));
        }
        if let Some(v) = self.generator
            && v != 1
            && v != 2
        {
            return Err(("generator".into(), format!("{v}: expected 1 or 2 (the version of the summit generator)")));
        }
        if self.generator == Some(2) && self.counter_face.is_some() && self.two_face == TwoFaceMode::Explicit {
            return Err((
                "generator".into(),
                "2 is not available with `two_face` = \"explicit\" (use generator 1, the default)".into(),
            ));
        }
        if self.max_summits == Some(0) {
            return Err(("max_summits".into(), "0: expected a positive number of summits".into()));
        }
        let budget = self.summit_budget() as f64;
        let area = self.apparent_length * self.apparent_width;
        let (field, expected) = match (self.source, &self.counter_face, self.two_face) {
            (SurfaceSource::Csv | SurfaceSource::Npy, _, _) => return Ok(()),
            (_, None, _) => ("summit_density", self.summit_density.unwrap_or(0.0) * area),
            (_, Some(c), TwoFaceMode::Composite) => {
                ("summit_density", (self.summit_density.unwrap_or(0.0) + c.summit_density) * area)
            }
            (_, Some(c), TwoFaceMode::Explicit) => {
                let n_wall = self.summit_density.unwrap_or(0.0) * area;
                let n_shoe = c.summit_density * area;
                let over = |n: f64| n > budget;
                if over(n_wall) {
                    ("summit_density", n_wall)
                } else if over(n_shoe) {
                    ("counter_face.summit_density", n_shoe)
                } else {
                    // Pairs within the reach: a shoe summit pairs with the wall summits in a disc
                    // of radius sqrt(2 (R1 + R2) reach) (capped at the whole area).
                    let sd = self.summit_sd.unwrap_or(0.0).hypot(c.summit_sd);
                    let reach = self.pair_reach.unwrap_or(4.0 * sd);
                    let r_sum = self.summit_radius.unwrap_or(0.0) + c.summit_radius;
                    let disc = std::f64::consts::PI * 2.0 * r_sum * reach;
                    let fraction = if area > 0.0 { (disc / area).min(1.0) } else { 1.0 };
                    ("pair_reach", n_wall * n_shoe * fraction)
                }
            }
        };
        if expected.is_nan() || expected > budget {
            return Err((
                field.into(),
                format!(
                    "this surface would hold about {expected:.3e} summits{} (about {:.3e} bytes), more than the \
                     limit of {budget:.0} (`surface.max_summits`, default {DEFAULT_MAX_SUMMITS}); lower the value or \
                     raise `surface.max_summits` if the machine has the memory",
                    if field == "pair_reach" { " pairs" } else { "" },
                    expected * ESTIMATED_BYTES_PER_SUMMIT
                ),
            ));
        }
        Ok(())
    }

    /// The apparent area, placement and seed.
    pub fn layout(&self) -> Layout {
        Layout {
            apparent_length_m: self.apparent_length,
            apparent_width_m: self.apparent_width,
            placement: self.placement,
            seed: self.seed,
        }
    }
}
