//! The contact models a fit can use, and what each predicts for a measured row.
//!
//! For a row with clamp voltage `V_c`, the model's load is `L = a_clamp V_c^2 - F_spring` (the
//! scenario's device values, as the virtual meter uses them), its contact state at `L` comes from
//! the meter's own contact-model builder ([`stiction_meter::build_contact_model`]), and the slip
//! threshold by the scenario's criterion is linear in the shear strength, `T = s g + h`:
//! `g = A_r`, `h = 0` for `shear-area` (eq. 1); `g = L_el / H` for `plastic`; `g = A_r`,
//! `h = alpha L_el` for `pressure-dependent`. The predicted `V_pull^2 = T / a_pull` (the pull gap
//! is fixed while the shoe sticks). With `L <= 0` the model has no contact and predicts no
//! friction (`g = h = 0`), as the meter does. The meter's pull ramp quantises `V_pull` to its
//! step (0.05 V in the paper's scenario, well below any measured noise); the fit uses the
//! continuous threshold.

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::Serialize;
use stiction_meter::{ContactModel, Reduction, build_contact_model};
use stiction_scenario::{ContactModel as Kind, MaterialSpec, Scenario, SlipCriterion};

use crate::error::FitError;

/// Largest number of surfaces in an ensemble band.
pub const MAX_SURFACES: usize = 10_000;

/// A contact model to fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ModelKind {
    /// The discrete model with N equally loaded summits (eq. 12) and the scenario's law.
    Discrete(u32),
    /// Greenwood-Williamson with DMT adhesion (eq. 5, 8).
    Gw,
    /// The explicit solver on the scenario's surface (its seed).
    Explicit,
    /// The explicit solver on an ensemble of surface realisations (seeds seed .. seed + n - 1):
    /// fitted to the ensemble's mean curve, with the realisations' spread as a band.
    ExplicitEnsemble,
}

impl ModelKind {
    /// Name in reports and on the command line.
    pub fn name(&self) -> String {
        match self {
            ModelKind::Discrete(n) => format!("discrete-n{n}"),
            ModelKind::Gw => "gw-dmt".into(),
            ModelKind::Explicit => "explicit".into(),
            ModelKind::ExplicitEnsemble => "explicit-ensemble".into(),
        }
    }

    /// Parses a comma-separated list (`discrete-n1,discrete-n2,discrete-n3,gw-dmt,explicit,explicit-ensemble`);
    /// `name` (the flag `--models`, the argument `models`) names it in errors.
    pub fn parse_list(list: &str, name: &str) -> Result<Vec<ModelKind>, FitError> {
        let mut out = Vec::new();
        for item in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let kind = match item {
                "gw-dmt" | "gw" => ModelKind::Gw,
                "explicit" => ModelKind::Explicit,
                "explicit-ensemble" => ModelKind::ExplicitEnsemble,
                other => match other.strip_prefix("discrete-n").and_then(|n| n.parse::<u32>().ok()) {
                    Some(n) if (1..=1000).contains(&n) => ModelKind::Discrete(n),
                    _ => {
                        return Err(FitError::Setting(format!(
                            "{name}: unknown model `{other}`; expected a comma-separated list of discrete-nN (N = 1..1000), gw-dmt, explicit, explicit-ensemble"
                        )));
                    }
                },
            };
            if out.contains(&kind) {
                return Err(FitError::Setting(format!("{name}: `{item}` is listed twice")));
            }
            out.push(kind);
        }
        if out.is_empty() {
            return Err(FitError::Setting(format!("{name}: the list is empty")));
        }
        Ok(out)
    }

    /// The default list: discrete N = 1, 2, 3, GW+DMT, explicit, explicit ensemble.
    pub fn defaults() -> Vec<ModelKind> {
        vec![
            ModelKind::Discrete(1),
            ModelKind::Discrete(2),
            ModelKind::Discrete(3),
            ModelKind::Gw,
            ModelKind::Explicit,
            ModelKind::ExplicitEnsemble,
        ]
    }

    /// Whether the model is cheap (closed form or a 1-D root per load).
    pub fn is_cheap(&self) -> bool {
        matches!(self, ModelKind::Discrete(_) | ModelKind::Gw)
    }
}

/// The slip threshold at one load, `T = s g + h` (N), or why there is none.
pub type Parts = Result<(f64, f64), String>;

/// The scenario's device values and contact models, ready to evaluate.
#[derive(Clone)]
pub struct ModelContext {
    scenario: Scenario,
    base_dir: PathBuf,
    material: MaterialSpec,
    slip: SlipCriterion,
    reclamp: bool,
    /// The device's own reduction (the nominal a_clamp, a_pull, F_spring).
    pub device: Reduction,
    /// The scenario's mean summit radius, m.
    pub nominal_radius_m: f64,
}

impl ModelContext {
    /// From a loaded scenario with a `meter` section.
    pub fn new(scenario: &Scenario, base_dir: &Path) -> Result<ModelContext, FitError> {
        let meter = stiction_meter::Meter::from_scenario(scenario, base_dir)?;
        let device = meter.device_reduction()?;
        let material = scenario.require_material().map_err(FitError::Setting)?.clone();
        let surface = scenario.require_surface().map_err(FitError::Setting)?;
        let nominal_radius_m = stiction_meter::model_summit_radius_m(surface, base_dir)?;
        let protocol = scenario.meter.clone().ok_or_else(|| FitError::Setting("the scenario has no `meter`".into()))?;
        Ok(ModelContext {
            scenario: scenario.clone(),
            base_dir: base_dir.to_path_buf(),
            material,
            slip: protocol.slip,
            reclamp: protocol.reclamp,
            device,
            nominal_radius_m,
        })
    }

    /// A contact model of `kind` with summit radius `radius_m` (None: the scenario's) on the
    /// surface of seed `seed` (None: the scenario's).
    pub fn build(&self, kind: ModelKind, radius_m: Option<f64>, seed: Option<u64>) -> Result<ContactModel, FitError> {
        let mut s = self.scenario.clone();
        let mut c = s.contact_or_default();
        match kind {
            ModelKind::Discrete(n) => {
                c.model = Kind::Discrete;
                c.contacts = Some(n as usize);
            }
            ModelKind::Gw => c.model = Kind::Gw,
            ModelKind::Explicit | ModelKind::ExplicitEnsemble => c.model = Kind::Explicit,
        }
        s.contact = Some(c);
        if let Some(surface) = s.surface.as_mut() {
            if let Some(r) = radius_m {
                surface.summit_radius = Some(r);
            }
            if let Some(seed) = seed {
                surface.seed = seed;
            }
        }
        Ok(build_contact_model(&s, &self.material, &self.base_dir)?)
    }

    /// The threshold parts at each load (N), in the order given; loads are visited in ascending
    /// order so that a load path (no reclamp) is followed as the meter does.
    pub fn parts(&self, model: &mut ContactModel, loads_n: &[f64]) -> Vec<Parts> {
        let mut order: Vec<usize> = (0..loads_n.len()).collect();
        order.sort_by(|&a, &b| loads_n[a].total_cmp(&loads_n[b]));
        let mut out: Vec<Parts> = vec![Ok((0.0, 0.0)); loads_n.len()];
        let mut previous_in_contact = false;
        for i in order {
            let load = loads_n[i];
            if !(load > 0.0) {
                previous_in_contact = false;
                continue;
            }
            let fresh = self.reclamp || !previous_in_contact;
            out[i] = match model.state_at_load(load, fresh) {
                Ok(st) => {
                    previous_in_contact = true;
                    Ok(match self.slip {
                        SlipCriterion::ShearArea => (st.real_area_m2, 0.0),
                        SlipCriterion::Plastic => (st.elastic_load_n() / self.material.hardness, 0.0),
                        SlipCriterion::PressureDependent { alpha } => (st.real_area_m2, alpha * st.elastic_load_n()),
                    })
                }
                Err(e) => {
                    previous_in_contact = false;
                    Err(e.to_string())
                }
            };
        }
        out
    }

    /// Loads at clamp voltages squared `x_v2` with spring force `spring_n`, N.
    pub fn loads(&self, x_v2: &[f64], spring_n: f64) -> Vec<f64> {
        x_v2.iter().map(|x| self.device.a_clamp_n_per_v2 * x - spring_n).collect()
    }

    /// Parts of `kind` on `surfaces` realisations (seeds `seed + k`), in parallel; result k is
    /// the realisation k, whatever the thread count.
    pub fn ensemble_parts(
        &self,
        kind: ModelKind,
        radius_m: Option<f64>,
        surfaces: usize,
        loads_n: &[f64],
    ) -> Result<Vec<Vec<Parts>>, FitError> {
        if surfaces == 0 || surfaces > MAX_SURFACES {
            return Err(FitError::Setting(format!("--surfaces {surfaces}: expected 1 to {MAX_SURFACES}")));
        }
        let base = self.scenario.surface.as_ref().map_or(0, |s| s.seed);
        (0..surfaces)
            .into_par_iter()
            .map(|k| {
                let mut m = self.build(kind, radius_m, Some(base.wrapping_add(k as u64)))?;
                Ok(self.parts(&mut m, loads_n))
            })
            .collect()
    }
}
