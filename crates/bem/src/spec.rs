//! The scenario section of the `bem` contact model (`contact.bem`), and the grid it solves on.
//!
//! ```json
//! "contact": {"model": "bem", "bem": {"pixel_size": "40 nm", "tolerance": 1e-6, "range": "2 nm"}}
//! ```
//!
//! The shoe face is the composite height patch of the scenario's height map(s) under the shoe's
//! apparent area; `pixel_size` or `points` coarsen it by block averages of whole pixels, and
//! `max_points` bounds the grid before anything is allocated.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::BemError;
use crate::grid::{BYTES_PER_POINT, MAX_POINTS};

/// Default of `max_points`: 2^22 points (about 335 MB of solver state at [`BYTES_PER_POINT`], a
/// few seconds per solve at the tolerance 1e-6).
pub const DEFAULT_MAX_POINTS: u64 = 1 << 22;

/// Default relative tolerance of the scenario's solves.
pub const DEFAULT_TOLERANCE: f64 = 1e-6;

/// Ratio of the Dugdale range to the equilibrium spacing `z0` when `range` is not given: Maugis
/// (1992) matched the Dugdale stress to the Lennard-Jones maximum, `sigma0 = 1.03 w/z0`, so
/// `h0 = w/sigma0 = 0.971 z0`.
pub const RANGE_PER_EQUILIBRIUM_SPACING: f64 = 1.0 / 1.03;

/// The `bem` contact model's settings (scenario `contact.bem`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(deny_unknown_fields)]
pub struct BemSpec {
    /// Grid spacing \[m\] ("40 nm"): the height patch is coarsened by block averages of
    /// `round(pixel_size/dx)` x `round(pixel_size/dy)` pixels; default: the map's own pixels.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub pixel_size: Option<f64>,
    /// Instead of `pixel_size`: at most this many grid points; the patch is coarsened by the
    /// smallest whole factor (the same along x and y) that brings it there.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<u64>,
    /// Largest grid the model accepts, in points (default 4 194 304 = 2^22; at most 2^24):
    /// checked before the solver allocates (about 80 bytes per point).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_points: Option<u64>,
    /// Relative tolerance of the constrained conjugate gradient (default 1e-6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Range h0 \[m\] of the Dugdale cohesive law (adhesive laws only); the Dugdale stress is
    /// `w/h0` with the material's work of adhesion. Default `z0/1.03` (Maugis's match to the
    /// Lennard-Jones law with the material's `equilibrium_spacing` z0).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub range: Option<f64>,
    /// The Green's function: "non_periodic" (default: the shoe face is a finite patch, a rigid
    /// punch of the shoe's size on a wall that goes on beyond it; zero-padded FFT of twice the
    /// size; docs/bem.md, "A finite shoe on a wall (the non-periodic Green's function)") or "periodic" (the face is one periodic cell: its opposite edges meet).
    /// With "periodic" the shoe cannot tilt.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub boundary: Option<crate::Boundary>,
    /// Whether the rigid shoe tilts (true: approach and two tilts from the force and moment
    /// balances about the patch centre, docs/bem.md, "The tilting shoe (`contact.bem.tilt`)"; non-periodic only; about 10-60 solves per
    /// load) or approaches flat (false, the default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tilt: Option<bool>,
    /// Whether the contact pressure is capped at the material's hardness (`material.hardness`):
    /// perfectly plastic pixels flow at `H` (true; docs/bem.md, "Solvers", the hardness cap) or
    /// the contact stays elastic whatever its pressure (false, the default). With adhesion the net
    /// traction is capped (`p_c - sigma0 <= H`); a flat shoe only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plastic: Option<bool>,
}

impl BemSpec {
    /// Checks the fields that need no grid; returns (field, message).
    pub fn validate(&self) -> Result<(), (String, String)> {
        if self.pixel_size.is_some() && self.points.is_some() {
            return Err(("pixel_size".into(), "give `pixel_size` or `points`, not both".into()));
        }
        if let Some(p) = self.points.filter(|&p| p < 4) {
            return Err(("points".into(), format!("{p}: expected at least 4 grid points")));
        }
        if let Some(m) = self.max_points.filter(|m| !(4..=MAX_POINTS as u64).contains(m)) {
            let bytes = MAX_POINTS * BYTES_PER_POINT;
            return Err((
                "max_points".into(),
                format!("{m}: expected 4..={MAX_POINTS} (the solver's limit, {bytes} bytes)"),
            ));
        }
        if let Some(t) = self.tolerance.filter(|t| !(t.is_finite() && *t > 0.0 && *t < 1.0)) {
            return Err(("tolerance".into(), format!("{t}: expected a relative tolerance in (0, 1)")));
        }
        if self.tilt() && self.boundary() == crate::Boundary::Periodic {
            return Err((
                "tilt".into(),
                "a tilting shoe needs the finite patch (`boundary` = \"non_periodic\"); a periodic cell has no edge \
                 to tilt about"
                    .into(),
            ));
        }
        Ok(())
    }

    /// The Green's function in use (default non-periodic).
    pub fn boundary(&self) -> crate::Boundary {
        self.boundary.unwrap_or(crate::Boundary::NonPeriodic)
    }

    /// Bytes of solver state per grid point with this spec's Green's function.
    pub fn bytes_per_point(&self) -> usize {
        match self.boundary() {
            crate::Boundary::Periodic => BYTES_PER_POINT,
            crate::Boundary::NonPeriodic => BYTES_PER_POINT + crate::green::PADDED_BYTES_PER_POINT,
        }
    }

    /// Whether the shoe tilts (default false).
    pub fn tilt(&self) -> bool {
        self.tilt.unwrap_or(false)
    }

    /// Whether the pressure is capped at the material's hardness (default false).
    pub fn plastic(&self) -> bool {
        self.plastic.unwrap_or(false)
    }

    /// The tolerance in use.
    pub fn tolerance(&self) -> f64 {
        self.tolerance.unwrap_or(DEFAULT_TOLERANCE)
    }

    /// The block factors (along x, y) that turn an `nx x ny` map of `dx x dy` pixels into the
    /// model's grid, and the check of its size against `max_points` (before any allocation).
    pub fn coarsening(&self, nx: usize, ny: usize, dx_m: f64, dy_m: f64) -> Result<(usize, usize), BemError> {
        let (kx, ky) = match (self.pixel_size, self.points) {
            (Some(ps), _) => (((ps / dx_m).round() as usize).max(1), ((ps / dy_m).round() as usize).max(1)),
            (None, Some(p)) => {
                let mut k = 1usize;
                while (nx / k) * (ny / k) > p as usize && k < nx.max(ny) {
                    k += 1;
                }
                (k, k)
            }
            (None, None) => (1, 1),
        };
        let (cx, cy) = (nx / kx, ny / ky);
        let limit = self.max_points.unwrap_or(DEFAULT_MAX_POINTS) as usize;
        // The padded operator works on four times the grid: its own limit.
        let limit = match self.boundary() {
            crate::Boundary::Periodic => limit,
            crate::Boundary::NonPeriodic => limit.min(crate::green::MAX_POINTS_NON_PERIODIC),
        };
        if cx < 2 || cy < 2 || cx.checked_mul(cy).is_none_or(|n| n > limit) {
            return Err(BemError::GridSize { nx: cx, ny: cy, limit });
        }
        Ok((kx, ky))
    }
}

/// Block averages of `kx x ky` pixels of a row-major `nx x ny` field: an `(nx/kx) x (ny/ky)`
/// field (trailing pixels that do not fill a block are dropped).
pub fn coarsen(heights_m: &[f64], nx: usize, ny: usize, kx: usize, ky: usize) -> Vec<f64> {
    let (cx, cy) = (nx / kx.max(1), ny / ky.max(1));
    if kx <= 1 && ky <= 1 {
        return heights_m.to_vec();
    }
    let norm = 1.0 / (kx * ky) as f64;
    let mut out = vec![0.0; cx * cy];
    for j in 0..cy {
        for i in 0..cx {
            let mut s = 0.0;
            for y in j * ky..(j + 1) * ky {
                s += heights_m[y * nx + i * kx..y * nx + (i + 1) * kx].iter().sum::<f64>();
            }
            out[j * cx + i] = s * norm;
        }
    }
    out
}

/// Refuses a height field with missing (NaN) or infinite values, counting them: the solver needs
/// every point of the periodic grid.
pub fn check_complete(heights_m: &[f64]) -> Result<(), BemError> {
    let bad = heights_m.iter().filter(|h| !h.is_finite()).count();
    if bad > 0 {
        let first = heights_m.iter().position(|h| !h.is_finite()).unwrap_or(0);
        return Err(BemError::MissingHeights { count: bad, first_index: first });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarsening_by_spacing_points_and_limit() {
        let s = BemSpec { pixel_size: Some(40e-9), ..Default::default() };
        assert_eq!(s.coarsening(1000, 250, 20e-9, 20e-9).unwrap(), (2, 2));
        let s = BemSpec { points: Some(10_000), ..Default::default() };
        // 500 x 125 = 62 500 > 10 000; k = 3: 166 x 41 = 6 806.
        assert_eq!(s.coarsening(500, 125, 1e-8, 1e-8).unwrap(), (3, 3));
        let s = BemSpec { max_points: Some(100), ..Default::default() };
        assert!(matches!(s.coarsening(20, 20, 1.0, 1.0), Err(BemError::GridSize { nx: 20, ny: 20, limit: 100 })));
        let h: Vec<f64> = (0..12).map(f64::from).collect();
        // 4 x 3 field, blocks of 2 x 1: row means of pairs.
        assert_eq!(coarsen(&h, 4, 3, 2, 1), vec![0.5, 2.5, 4.5, 6.5, 8.5, 10.5]);
        assert!(check_complete(&[1.0, f64::NAN, f64::NAN]).is_err());
    }
}
