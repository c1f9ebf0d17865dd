//! `discrete`: the discrete N-contact model (eq. 12), and the paper's Fig. 7 model of a scenario.

use serde::{Deserialize, Serialize};
use stiction_contact::single::AsperityParams;
use stiction_scenario::MaterialSpec;

use crate::Error;
use crate::check::{Names, domain};

// The model's types that a front end names or prints: the discrete model (its parameters, and the
// paper's Fig. 7 model, `DiscreteModel::fig7`) and the single-asperity laws.
pub use stiction_contact::discrete::DiscreteModel;
pub use stiction_contact::single::AdhesionLaw;

/// The most contacts the discrete model takes: the paper's 1, 2 or 3 (a rigid shoe's degrees of
/// freedom put it on at most three summits; section 3.4), as the scenario's `contact.contacts`.
pub const MAX_CONTACTS: u32 = 3;

/// The default equilibrium spacing z0 of the surface forces, m (0.3 nm).
pub const DEFAULT_EQUILIBRIUM_SPACING_M: f64 = 0.3e-9;

/// Friction of N equally loaded summits: F_f = s N pi a^2 with a from the single-asperity law at
/// L/N (eq. 12), at one load.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscreteRequest {
    /// Number of contacts N, 1 to [`MAX_CONTACTS`].
    pub contacts: u32,
    /// Summit radius R, m (the domain of `surface.summit_radius`).
    pub radius_m: f64,
    /// Work of adhesion dgamma, J/m^2 (`material.work_of_adhesion`).
    pub work_of_adhesion_j_per_m2: f64,
    /// Composite compliance D = 3/4 ((1-nu1^2)/E1 + (1-nu2^2)/E2), 1/Pa (`material.compliance`).
    pub compliance_per_pa: f64,
    /// Interfacial shear strength s, Pa (>= 0).
    pub shear_strength_pa: f64,
    /// Applied load L, N (negative down to the pull-off load; the domain of `load`).
    pub load_n: f64,
    /// Single-asperity law.
    #[serde(default = "dmt")]
    pub law: AdhesionLaw,
    /// Equilibrium spacing z0 of the surface forces, m, for the Tabor and Maugis parameters.
    #[serde(default = "default_spacing")]
    pub equilibrium_spacing_m: f64,
    /// Also give the shear strength for which the slope at the load equals this value.
    #[serde(default)]
    pub target_slope: Option<f64>,
}

fn dmt() -> AdhesionLaw {
    AdhesionLaw::Dmt
}

fn default_spacing() -> f64 {
    DEFAULT_EQUILIBRIUM_SPACING_M
}

impl DiscreteRequest {
    /// Checks every field against its physical domain (the scenario's domains where the field is
    /// a scenario quantity), naming a field as `names` calls it; the warnings of values outside
    /// their usual range come back.
    pub fn validate(&self, names: &Names) -> Result<Vec<stiction_scenario::Warning>, Error> {
        if !(1..=MAX_CONTACTS).contains(&self.contacts) {
            return Err(
                format!("{} {}: expected 1 to {MAX_CONTACTS} contacts", names("contacts"), self.contacts).into()
            );
        }
        let mut w = Vec::new();
        domain(&mut w, names, "radius_m", "surface.summit_radius", self.radius_m)?;
        domain(
            &mut w,
            names,
            "work_of_adhesion_j_per_m2",
            "material.work_of_adhesion",
            self.work_of_adhesion_j_per_m2,
        )?;
        domain(&mut w, names, "compliance_per_pa", "material.compliance", self.compliance_per_pa)?;
        domain(&mut w, names, "load_n", "load", self.load_n)?;
        domain(&mut w, names, "equilibrium_spacing_m", "material.equilibrium_spacing", self.equilibrium_spacing_m)?;
        if !(self.shear_strength_pa.is_finite() && self.shear_strength_pa >= 0.0) {
            return Err(format!(
                "{} {}: expected a finite shear strength >= 0",
                names("shear_strength_pa"),
                self.shear_strength_pa
            )
            .into());
        }
        Ok(w)
    }
}

/// What `discrete --json` prints.
#[allow(missing_docs)]
#[derive(Clone, Debug, Serialize)]
pub struct DiscreteOutput {
    pub contacts: u32,
    pub law: AdhesionLaw,
    pub load_n: f64,
    pub friction_n: f64,
    /// null where the contact radius is 0 (then `friction_slope_null_reason` says why).
    pub friction_slope: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_slope_null_reason: Option<&'static str>,
    pub zero_load_friction_n: f64,
    pub apparent_adhesion_force_n: Option<f64>,
    /// Why F_a0 is null (the slope at the load is not positive or not defined).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub apparent_adhesion_force_note: Option<&'static str>,
    pub pull_off_load_n: f64,
    pub real_area_m2: f64,
    pub contact_radius_m: f64,
    pub interference_m: f64,
    pub max_pressure_pa: f64,
    pub tabor_parameter: f64,
    pub recommended_law: AdhesionLaw,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shear_strength_for_target_slope_pa: Option<f64>,
}

/// The discrete model at the request's load.
pub fn discrete(req: &DiscreteRequest) -> Result<DiscreteOutput, Error> {
    let params = AsperityParams {
        radius_m: req.radius_m,
        compliance_per_pa: req.compliance_per_pa,
        work_of_adhesion_j_per_m2: req.work_of_adhesion_j_per_m2,
        equilibrium_spacing_m: req.equilibrium_spacing_m,
    };
    let model = DiscreteModel::new(req.contacts, req.law, params, req.shear_strength_pa)?;
    let at = model.at_load(req.load_n)?;
    let zero = model.at_load(0.0)?;
    let rec = params.recommendation();
    Ok(DiscreteOutput {
        contacts: req.contacts,
        law: req.law,
        load_n: req.load_n,
        friction_n: at.friction_n,
        friction_slope: at.friction_slope,
        friction_slope_null_reason: at.friction_slope.is_none().then_some(DiscreteModel::SLOPE_NULL_REASON),
        zero_load_friction_n: zero.friction_n,
        // Eq. 10 as the paper evaluates it in section 5: F_a0 = F_f(0) / (dF_f/dL at the load).
        apparent_adhesion_force_n: at.friction_slope.filter(|s| *s > 0.0).map(|s| zero.friction_n / s),
        apparent_adhesion_force_note: at
            .friction_slope
            .filter(|s| *s > 0.0)
            .is_none()
            .then_some("F_a0 = F_f(0) / (dF_f/dL) needs a positive friction slope at the load, and it has none there"),
        pull_off_load_n: model.pull_off_load_n()?,
        real_area_m2: at.real_area_m2,
        contact_radius_m: at.contact_radius_m,
        interference_m: at.interference_m,
        max_pressure_pa: at.max_pressure_pa,
        tabor_parameter: params.tabor_parameter(),
        recommended_law: rec.law,
        shear_strength_for_target_slope_pa: req
            .target_slope
            .map(|t| model.shear_strength_for_slope(t, req.load_n))
            .transpose()?,
    })
}

/// The paper's Fig. 7 curve, N = 3, from the scenario's material and radius, from pull-off to
/// `max_load_n`: (L, F_f) in uN.
pub fn friction_curve_n3(material: &MaterialSpec, radius_m: f64, max_load_n: f64) -> Result<Vec<(f64, f64)>, Error> {
    let params = stiction_meter::asperity_params(material, radius_m);
    let model = DiscreteModel::new(3, AdhesionLaw::Dmt, params, material.shear_strength)?;
    let pull_off = model.pull_off_load_n()?;
    Ok(model.friction_curve(pull_off, max_load_n, 200)?.into_iter().map(|(l, f)| (l * 1e6, f * 1e6)).collect())
}

/// The discrete model of a scenario's Fig. 7: its material, model summit radius, contact law and
/// number of contacts (the scenario's `contact.contacts` for the discrete model or a fixed shoe,
/// else the paper's 3).
pub fn fig7_model(s: &stiction_scenario::Scenario, base: &std::path::Path) -> Result<DiscreteModel, Error> {
    let material = s.require_material()?;
    let radius = stiction_meter::model_summit_radius_m(s.require_surface()?, base)?;
    let contact = s.contact_or_default();
    let fixed = contact.model == stiction_scenario::ContactModel::Discrete
        || contact.mode == stiction_scenario::ShoeMode::Fixed;
    let n = if fixed { contact.contacts.unwrap_or(3) } else { 3 };
    let n = u32::try_from(n).map_err(|_| format!("contact.contacts {n}: expected 1, 2 or 3"))?;
    Ok(DiscreteModel::new(n, contact.law, stiction_meter::asperity_params(material, radius), material.shear_strength)?)
}

/// Fig. 7's numbers of a discrete model: the curve F_f(L) from pull-off to 15 uN (uN, uN), the
/// slope mu = dF_f/dL at 3 uN, F_f(0) (N) and the pull-off load (N).
pub struct Fig7Curve {
    /// (L, F_f) in uN, 300 points from pull-off to 15 uN.
    pub curve_un: Vec<(f64, f64)>,
    /// dF_f/dL at 3 uN (the paper's mu_e,a).
    pub slope_at_3un: f64,
    /// F_f at L = 0, N.
    pub zero_load_friction_n: f64,
    /// The pull-off load, N.
    pub pull_off_n: f64,
}

/// The numbers Fig. 7 draws for `model`.
pub fn fig7_curve(model: &DiscreteModel) -> Result<Fig7Curve, Error> {
    let pull_off = model.pull_off_load_n()?;
    let curve_un = model.friction_curve(pull_off, 15e-6, 300)?.into_iter().map(|(l, f)| (l * 1e6, f * 1e6)).collect();
    let mu = model.at_load(3e-6)?.friction_slope.ok_or(DiscreteModel::SLOPE_NULL_REASON)?;
    Ok(Fig7Curve {
        curve_un,
        slope_at_3un: mu,
        zero_load_friction_n: model.at_load(0.0)?.friction_n,
        pull_off_n: pull_off,
    })
}
