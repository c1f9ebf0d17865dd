//! The statistical description of a rough face ([`FaceParams`]: summit density, height and radius
//! distributions) and of the apparent area it covers ([`Layout`]: size, placement, seed): the input
//! of both summit generators ([`crate::generate`], [`crate::generate_v2`]).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::SurfaceError;
use crate::surface::{check_nonnegative, check_positive};

/// Largest number of summits a surface may hold (indices are stored as u32 by the solver).
pub const MAX_SUMMITS: usize = u32::MAX as usize;

/// How summit positions are placed over the apparent area.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Placement {
    /// Homogeneous Poisson point process of density eta: the count is Poisson(eta A_a) and the
    /// positions are independent and uniform (the GW assumption). Default.
    #[default]
    Poisson,
    /// One summit per cell of a grid of round(eta A_a) nearly square cells, uniformly placed in
    /// its cell: the count is fixed and the summits never cluster.
    JitteredGrid,
}

/// Distribution of the summit heights.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum HeightDistribution {
    /// Gaussian with mean 0 and SD sigma (the paper's section 3.1). Default.
    #[default]
    Gaussian,
    /// Shifted exponential sigma (E - 1), E ~ Exp(1): mean 0, SD sigma, upper tail exp(-x/sigma)
    /// (GW's exponential comparison case).
    Exponential,
}

/// Distribution of the summit radii.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum RadiusDistribution {
    /// Every summit has the mean radius (radius SD must be 0). Default.
    #[default]
    Fixed,
    /// Lognormal with the given mean and SD: ln R ~ N(mu, s^2) with s^2 = ln(1 + (SD/mean)^2),
    /// mu = ln(mean) - s^2 / 2.
    Lognormal,
}

/// Statistical description of one rough face (GW parameters, paper section 3.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceParams {
    /// Summit density eta \[m^-2\].
    pub summit_density_per_m2: f64,
    /// Standard deviation of the summit heights sigma \[m\].
    pub summit_sd_m: f64,
    /// Height distribution.
    pub height_distribution: HeightDistribution,
    /// Mean summit radius R \[m\].
    pub summit_radius_m: f64,
    /// Standard deviation of the summit radius \[m\] (0 for fixed radii).
    pub radius_sd_m: f64,
    /// Radius distribution.
    pub radius_distribution: RadiusDistribution,
}

impl FaceParams {
    /// A face with Gaussian heights and one fixed radius (the paper's model).
    pub fn gaussian_fixed(summit_density_per_m2: f64, summit_sd_m: f64, summit_radius_m: f64) -> Self {
        Self {
            summit_density_per_m2,
            summit_sd_m,
            height_distribution: HeightDistribution::Gaussian,
            summit_radius_m,
            radius_sd_m: 0.0,
            radius_distribution: RadiusDistribution::Fixed,
        }
    }

    /// The paper's composite of two faces (section 3.1): eta = eta1 + eta2,
    /// sigma^2 = sigma1^2 + sigma2^2, 1/R = 1/R1 + 1/R2 (mean radii; the radius SD of the result is
    /// not defined by the paper and is set to 0, use [`crate::generate_composite`] to sample it).
    pub fn composite(&self, other: &FaceParams) -> FaceParams {
        FaceParams {
            summit_density_per_m2: self.summit_density_per_m2 + other.summit_density_per_m2,
            summit_sd_m: self.summit_sd_m.hypot(other.summit_sd_m),
            height_distribution: if self.height_distribution == other.height_distribution {
                self.height_distribution
            } else {
                HeightDistribution::Gaussian
            },
            summit_radius_m: 1.0 / (1.0 / self.summit_radius_m + 1.0 / other.summit_radius_m),
            radius_sd_m: 0.0,
            radius_distribution: RadiusDistribution::Fixed,
        }
    }

    pub(crate) fn validate(&self, prefix: &str) -> Result<(), SurfaceError> {
        check_positive(&format!("{prefix}summit_density"), self.summit_density_per_m2, "m^-2")?;
        check_nonnegative(&format!("{prefix}summit_sd"), self.summit_sd_m, "m")?;
        check_positive(&format!("{prefix}summit_radius"), self.summit_radius_m, "m")?;
        check_nonnegative(&format!("{prefix}radius_sd"), self.radius_sd_m, "m")?;
        match self.radius_distribution {
            RadiusDistribution::Fixed if self.radius_sd_m != 0.0 => Err(SurfaceError::InvalidParameter {
                field: format!("{prefix}radius_sd"),
                value: self.radius_sd_m.to_string(),
                expected: "0 for radius_distribution = fixed (use \"lognormal\" for a spread)".into(),
            }),
            RadiusDistribution::Lognormal if self.radius_sd_m <= 0.0 => Err(SurfaceError::InvalidParameter {
                field: format!("{prefix}radius_sd"),
                value: self.radius_sd_m.to_string(),
                expected: "a value > 0 m for radius_distribution = lognormal".into(),
            }),
            _ => Ok(()),
        }
    }
}

/// Apparent contact area and random settings shared by all generators.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Length of the apparent area along x \[m\] (the paper's shoe: 20 um).
    pub apparent_length_m: f64,
    /// Width of the apparent area along y \[m\] (the paper's shoe: 5 um).
    pub apparent_width_m: f64,
    /// Placement of the summits.
    pub placement: Placement,
    /// Seed of the ChaCha8 generator.
    pub seed: u64,
}

impl Layout {
    pub(crate) fn validate(&self) -> Result<(), SurfaceError> {
        check_positive("apparent_length", self.apparent_length_m, "m")?;
        check_positive("apparent_width", self.apparent_width_m, "m")
    }
    pub(crate) fn area(&self) -> f64 {
        self.apparent_length_m * self.apparent_width_m
    }
}

/// Rounds to f32, keeping the value inside [0, lim] (rounding up could leave the area).
pub(crate) fn clamp_f32(v: f64, lim: f64) -> f32 {
    let mut f = v as f32;
    while f64::from(f) > lim {
        f = f.next_down();
    }
    f
}
