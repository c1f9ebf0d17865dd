//! The discrete few-contact model (section 4, eq. 12): `N` (1, 2 or 3) equally loaded summits
//! carry the applied load `L`, each with the chosen single-asperity law, and the friction is
//! `F_f = s A_r` (eq. 1) with `A_r = N pi a^2`.
//!
//! With DMT (the paper's choice) this is eq. 12:
//! `F_f(L) = s N pi R [ (1/N) (D/R^(1/2)) (L + N 2 pi dgamma R) ]^(2/3)`, i.e. each summit carries
//! `P = L/N` and has `a^3 = R D (P + 2 pi dgamma R)`. The slope is analytic for every law:
//! `dF_f/dL = s N 2 pi a (da/dP) (1/N) = 2 pi s a da/dP` (DMT: `(2/3) pi s R D / a`).
//! The apparent zero-load adhesion force of eq. 10 is `F_a0 = F_f(0)/mu`, where the paper takes
//! `mu` as the slope at a reference load (Fig. 7: `L = 3 uN`).

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

use crate::capillary::Capillarity;
use crate::error::{ContactError, check_finite, check_nonnegative, check_positive};
use crate::single::{AdhesionLaw, AsperityParams, load_state_wet};

/// A discrete-contact configuration: `contacts` equally loaded summits of one law.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct DiscreteModel {
    /// Number of contacts `N`: 1, 2 or 3 (the paper, by the shoe's degrees of freedom; eq. 12 with
    /// equal loads holds by statics only for N <= 3, as for the scenario field `contact.contacts`).
    pub contacts: u32,
    /// Single-asperity law (DMT in the paper).
    pub law: AdhesionLaw,
    /// Summit parameters.
    pub params: AsperityParams,
    /// Interfacial shear strength `s`, Pa (eq. 1).
    pub shear_strength_pa: f64,
}

/// The discrete model at one load.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct DiscretePoint {
    /// Applied load `L`, N.
    pub load_n: f64,
    /// Load per summit `L/N`, N.
    pub load_per_contact_n: f64,
    /// Friction force `F_f = s A_r` (eq. 1, 12), N.
    pub friction_n: f64,
    /// Slope `dF_f/dL` (dimensionless; the friction coefficient mu_e,a of eq. 10 at this load);
    /// `None` where the contact radius is 0 (zero load without adhesion, or the DMT pull-off): there
    /// `a ~ P^(1/3)` and the slope is unbounded (see [`DiscreteModel::SLOPE_NULL_REASON`]).
    pub friction_slope: Option<f64>,
    /// Real contact area `A_r = N pi a^2`, m^2.
    pub real_area_m2: f64,
    /// Contact radius of each summit `a`, m.
    pub contact_radius_m: f64,
    /// Interference of each summit, m.
    pub interference_m: f64,
    /// Peak Hertzian pressure of each summit, `3a/(2 pi D R)` (eq. 11 with `z = a^2/R`), Pa.
    pub max_pressure_pa: f64,
}

impl DiscreteModel {
    /// Validated model.
    pub fn new(
        contacts: u32,
        law: AdhesionLaw,
        params: AsperityParams,
        shear_strength_pa: f64,
    ) -> Result<Self, ContactError> {
        let m = DiscreteModel { contacts, law, params, shear_strength_pa };
        m.validate()?;
        Ok(m)
    }

    /// The paper's Fig. 7 model: N = 3, DMT, Table 1 summit (R = 0.5 um, dgamma = 0.1 J/m^2,
    /// D = 9.1e-12 1/Pa), s = 1.4 GPa.
    pub fn fig7() -> Self {
        DiscreteModel { contacts: 3, law: AdhesionLaw::Dmt, params: AsperityParams::table1(), shear_strength_pa: 1.4e9 }
    }

    /// Capillary load of the `N` wetted contacts, `N 2 pi R gamma (cos th1 + cos th2)`, N (0 when dry).
    pub fn capillary_load_n(&self, capillarity: Option<&Capillarity>) -> f64 {
        capillarity.map_or(0.0, |c| f64::from(self.contacts) * c.sphere_flat_force_n(self.params.radius_m, 0.0))
    }

    /// Why [`DiscretePoint::friction_slope`] is `None`.
    pub const SLOPE_NULL_REASON: &'static str = "the contact radius is 0 at this load (zero load without adhesion, or the pull-off): dF_f/dL ~ L^(-1/3) is unbounded";

    /// Check the fields.
    pub fn validate(&self) -> Result<(), ContactError> {
        if !(1..=3).contains(&self.contacts) {
            return Err(ContactError::InvalidParameter {
                field: "contacts",
                value: f64::from(self.contacts),
                expected: "1, 2 or 3 contacts: the discrete model (eq. 12) shares the load equally, which statics \
                           guarantees only for up to 3 (as the scenario field contact.contacts)",
            });
        }
        self.params.validate()?;
        check_nonnegative("shear_strength_pa", self.shear_strength_pa, "a finite shear strength >= 0 (Pa)")?;
        Ok(())
    }

    /// The model at applied load `load_n` (N); below the pull-off load `-N P_c` an
    /// `Err(NoEquilibrium)`.
    pub fn at_load(&self, load_n: f64) -> Result<DiscretePoint, ContactError> {
        self.at_load_wet(load_n, None)
    }

    /// The model at applied load `load_n` (N) with a water meniscus at each of the `N` contacts
    /// (`None`: exactly [`DiscreteModel::at_load`]). Each summit carries `L/N` and is pulled by its
    /// meniscus with the constant `F_m = 2 pi R gamma (cos th1 + cos th2)`, so its solid law carries
    /// `L/N + F_m` ([`crate::single::load_state_wet`]); with DMT, eq. 12 with
    /// `dgamma -> dgamma + gamma (cos th1 + cos th2)`. The capillary load is `N F_m`
    /// ([`DiscreteModel::capillary_load_n`]).
    pub fn at_load_wet(&self, load_n: f64, capillarity: Option<&Capillarity>) -> Result<DiscretePoint, ContactError> {
        self.validate()?;
        check_finite("load_n", load_n, "a finite load (N)")?;
        let n = f64::from(self.contacts);
        let per = load_n / n;
        let st = load_state_wet(self.law, &self.params, per, capillarity).map_err(|e| match e {
            ContactError::NoEquilibrium { pull_off, .. } => ContactError::NoEquilibrium {
                quantity: "load_n",
                value: load_n,
                pull_off: format!("{} x {pull_off}", self.contacts),
            },
            other => other,
        })?;
        let a = st.contact_radius_m;
        let area = n * PI * a * a;
        Ok(DiscretePoint {
            load_n,
            load_per_contact_n: per,
            friction_n: self.shear_strength_pa * area,
            friction_slope: Some(2.0 * PI * self.shear_strength_pa * a * st.dradius_dload_m_per_n)
                .filter(|v| v.is_finite() && a > 0.0),
            real_area_m2: area,
            contact_radius_m: a,
            interference_m: st.interference_m,
            max_pressure_pa: st.max_pressure_pa,
        })
    }

    /// Apparent zero-load adhesion force of eq. 10, `F_a0 = F_f(0)/mu` with `mu = dF_f/dL` at
    /// `reference_load_n` (the paper: 3 uN), N; `None` where the slope is (see
    /// [`DiscretePoint::friction_slope`]) or is 0 (zero shear strength).
    pub fn apparent_adhesion_force_n(&self, reference_load_n: f64) -> Result<Option<f64>, ContactError> {
        let slope = self.at_load(reference_load_n)?.friction_slope;
        let f0 = self.at_load(0.0)?.friction_n;
        Ok(slope.filter(|s| *s > 0.0).map(|s| f0 / s))
    }

    /// The shear strength (Pa) for which the slope `dF_f/dL` at `load_n` equals `target_slope`
    /// (the paper's fit: slope 0.7 at 3 uN gives s = 1.4 GPa). `F_f` is proportional to `s`, so
    /// `s = target / (slope per unit s)`.
    pub fn shear_strength_for_slope(&self, target_slope: f64, load_n: f64) -> Result<f64, ContactError> {
        check_positive("target_slope", target_slope, "a finite friction slope > 0")?;
        let unit = DiscreteModel { shear_strength_pa: 1.0, ..*self };
        let Some(per_unit) = unit.at_load(load_n)?.friction_slope else {
            return Err(ContactError::InvalidParameter {
                field: "load_n",
                value: load_n,
                expected: "a load where the contact radius is > 0 (the slope is unbounded where it is 0)",
            });
        };
        Ok(target_slope / per_unit)
    }

    /// Pull-off load of the whole contact, `-N P_c` (N; negative, 0 for Hertz).
    pub fn pull_off_load_n(&self) -> Result<f64, ContactError> {
        Ok(-f64::from(self.contacts) * crate::single::pull_off_force(self.law, &self.params)?)
    }

    /// `(load, friction)` pairs for `points` loads evenly spaced over `[load_min, load_max]` (N);
    /// loads below the pull-off load are an error (start at [`DiscreteModel::pull_off_load_n`]).
    pub fn friction_curve(
        &self,
        load_min_n: f64,
        load_max_n: f64,
        points: usize,
    ) -> Result<Vec<(f64, f64)>, ContactError> {
        friction_curve(self, load_min_n, load_max_n, points)
    }
}

/// `(load_n, friction_n)` pairs of the discrete model for `points >= 2` loads evenly spaced over
/// `[load_min_n, load_max_n]` (Fig. 7).
pub fn friction_curve(
    model: &DiscreteModel,
    load_min_n: f64,
    load_max_n: f64,
    points: usize,
) -> Result<Vec<(f64, f64)>, ContactError> {
    check_finite("load_min_n", load_min_n, "a finite load (N)")?;
    check_finite("load_max_n", load_max_n, "a finite load (N)")?;
    if load_max_n <= load_min_n || points < 2 {
        return Err(ContactError::InvalidParameter {
            field: "load_max_n",
            value: load_max_n,
            expected: "load_max_n > load_min_n and at least 2 points",
        });
    }
    (0..points)
        .map(|i| {
            let l = load_min_n + (load_max_n - load_min_n) * i as f64 / (points - 1) as f64;
            Ok((l, model.at_load(l)?.friction_n))
        })
        .collect()
}
