//! Suspension springs of a gap-closing actuator.
//!
//! Beam formulas (Euler-Bernoulli, small deflection, in-plane bending of a beam of length `L`,
//! in-plane width `w` and out-of-plane thickness `t`, second moment `I = t w^3 / 12`):
//!
//! * clamped-guided beam (one end clamped, the other end free to translate but not to rotate):
//!   `k = 12 E I / L^3 = E t w^3 / L^3`;
//! * folded beam: two clamped-guided segments in series per fold, `k_fold = E t w^3 / (2 L^3)`.
//!
//! `E` may be replaced by the plane-strain modulus `E / (1 - nu^2)` (wide beams, `t >> w`),
//! as Rauf et al. (JMEMS 2022) do for their GCA suspension.

use serde::{Deserialize, Serialize};

use crate::error::{ActuatorError, nonnegative, positive};

/// Geometry and material of a suspension built from identical beams.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BeamSuspension {
    /// Arrangement of the beams.
    pub kind: BeamKind,
    /// Number of beams (clamped-guided) or folds (folded), acting in parallel.
    pub count: u32,
    /// Beam length `L` (m).
    pub length_m: f64,
    /// In-plane beam width `w` (m), the bending dimension.
    pub width_m: f64,
    /// Out-of-plane thickness `t` (m).
    pub thickness_m: f64,
    /// Young's modulus `E` (Pa).
    pub youngs_modulus_pa: f64,
    /// Poisson's ratio for the plane-strain modulus `E/(1-nu^2)`; `None` uses `E`.
    pub plane_strain_poisson: Option<f64>,
}

/// Beam arrangement.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BeamKind {
    /// Clamped-guided beams in parallel: `k = count E t w^3 / L^3`.
    ClampedGuided,
    /// Folds of two clamped-guided segments in series, folds in parallel:
    /// `k = count E t w^3 / (2 L^3)`.
    Folded,
}

impl BeamSuspension {
    /// Effective modulus: `E` or `E/(1 - nu^2)` (Pa).
    pub fn effective_modulus_pa(&self) -> f64 {
        match self.plane_strain_poisson {
            Some(nu) => self.youngs_modulus_pa / (1.0 - nu * nu),
            None => self.youngs_modulus_pa,
        }
    }

    /// Checks every field; the error names it.
    pub fn validate(&self) -> Result<(), ActuatorError> {
        if self.count == 0 {
            return Err(ActuatorError::InvalidField {
                field: "beams.count".into(),
                value: 0.0,
                expected: "at least 1".into(),
            });
        }
        positive("beams.length", self.length_m)?;
        positive("beams.width", self.width_m)?;
        positive("beams.thickness", self.thickness_m)?;
        positive("beams.youngs_modulus", self.youngs_modulus_pa)?;
        if let Some(nu) = self.plane_strain_poisson
            && !(nu.is_finite() && (-1.0..0.5).contains(&nu))
        {
            return Err(ActuatorError::InvalidField {
                field: "beams.poisson_ratio".into(),
                value: nu,
                expected: "a Poisson ratio in [-1, 0.5)".into(),
            });
        }
        Ok(())
    }

    /// Stiffness (N/m) against travel of the guided end(s): see module docs.
    pub fn stiffness_n_per_m(&self) -> f64 {
        let e = self.effective_modulus_pa();
        let one = e * self.thickness_m * self.width_m.powi(3) / self.length_m.powi(3);
        let per = match self.kind {
            BeamKind::ClampedGuided => one,
            BeamKind::Folded => one / 2.0,
        };
        f64::from(self.count) * per
    }

    /// Applies a process undercut `u` (m per edge): the width shrinks by `2u`; the length is
    /// kept (anchors and shuttle recede together).
    pub fn with_undercut(&self, undercut_m: f64) -> Result<Self, ActuatorError> {
        nonnegative("undercut", undercut_m)?;
        let mut out = *self;
        out.width_m -= 2.0 * undercut_m;
        out.validate()?;
        Ok(out)
    }
}

/// The suspension of the moving plates: a main spring plus optional extra stiffness.
///
/// Total stiffness `k = 1 / (1/(k_main + k_parallel) + 1/k_series)` (the series term is left out
/// when not given). The paper's pull connection beam (section 5) is a parallel stiffness of the
/// clamp array: both deflect by the clamp travel.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Suspension {
    /// Main spring stiffness (N/m), given or from [`BeamSuspension::stiffness_n_per_m`].
    pub main_stiffness_n_per_m: f64,
    /// Extra stiffness in parallel (N/m), 0 for none.
    pub parallel_stiffness_n_per_m: f64,
    /// Extra stiffness in series (N/m), `None` for a rigid link.
    pub series_stiffness_n_per_m: Option<f64>,
}

impl Suspension {
    /// A plain linear spring of stiffness `k` (N/m).
    pub fn linear(stiffness_n_per_m: f64) -> Self {
        Self {
            main_stiffness_n_per_m: stiffness_n_per_m,
            parallel_stiffness_n_per_m: 0.0,
            series_stiffness_n_per_m: None,
        }
    }

    /// Checks every field; the error names it.
    pub fn validate(&self) -> Result<(), ActuatorError> {
        positive("spring.stiffness", self.main_stiffness_n_per_m)?;
        nonnegative("spring.parallel_stiffness", self.parallel_stiffness_n_per_m)?;
        if let Some(s) = self.series_stiffness_n_per_m {
            positive("spring.series_stiffness", s)?;
        }
        Ok(())
    }

    /// Total stiffness `k` (N/m), see the type docs.
    pub fn stiffness_n_per_m(&self) -> f64 {
        let k = self.main_stiffness_n_per_m + self.parallel_stiffness_n_per_m;
        match self.series_stiffness_n_per_m {
            Some(s) => 1.0 / (1.0 / k + 1.0 / s),
            None => k,
        }
    }

    /// Restoring force `F_spring = k x` (N) at travel `x` (m).
    pub fn force_n(&self, travel_m: f64) -> f64 {
        self.stiffness_n_per_m() * travel_m
    }
}
