//! `fit`: measured friction-meter voltages against physics (eq. 10 with regression and
//! calibration uncertainty; maximum-likelihood shear strength per contact model; ranked models),
//! and the synthetic data of a scenario's virtual meter.

use std::path::{Path, PathBuf};

use stiction_fit::{FitOptions, read_measured_voltages, synth};
use stiction_scenario::Scenario;

use crate::Error;
use crate::scenario_source::ScenarioSource;

// The fit's types that a front end names or prints: the measured data and the report (what
// `fit --json` prints).
pub use stiction_fit::{Dataset, Estimate, FitReport, StructureFitReport};
/// A contact model to fit and the free parameters besides s (the request's typed lists).
pub use stiction_fit::{Free, ModelKind};

/// Where the measured voltages come from.
#[derive(Clone, Debug)]
pub enum FitData {
    /// The scenario's `measured.voltages_csv`.
    Scenario,
    /// A CSV file (columns v_clamp_v, v_pull_v [, v_pull_sd_v, device]).
    File(PathBuf),
    /// CSV text held in memory, named in messages.
    Text {
        /// The CSV bytes.
        bytes: Vec<u8>,
        /// Its name in messages.
        name: String,
    },
}

/// The fit of measured voltages to a scenario's device.
#[derive(Clone, Debug)]
pub struct FitRequest {
    /// The measured voltages.
    pub data: FitData,
    /// Models to fit (discrete-nN, gw-dmt, explicit, explicit-ensemble), parsed by the front end
    /// from its own text with [`parse_models`], each once, at least one.
    pub models: Vec<ModelKind>,
    /// Free parameters besides s (R, F_spring), parsed with [`parse_free`].
    pub free: Free,
    /// Surface realisations of the explicit ensemble (its band), 1 to
    /// `stiction_fit::models::MAX_SURFACES`.
    pub surfaces: usize,
    /// Calibration Monte Carlo draws, at most `stiction_fit::MAX_DRAWS`.
    pub draws: usize,
    /// Seed of the calibration Monte Carlo.
    pub seed: u64,
}

/// The default models of a fit, as a front end writes them (`ModelKind::defaults()`).
pub const DEFAULT_MODELS: &str = "discrete-n1,discrete-n2,discrete-n3,gw-dmt,explicit,explicit-ensemble";

/// A front end's comma-separated model list ("discrete-n3,gw-dmt"); `name` (the flag
/// `--models`, the argument `models`) names it in errors.
pub fn parse_models(text: &str, name: &str) -> Result<Vec<ModelKind>, String> {
    ModelKind::parse_list(text, name).map_err(|e| e.to_string())
}

/// A front end's list of free parameters ("s,R,F_spring"; s always); `name` (the flag
/// `--free`, the argument `free`) names it in errors.
pub fn parse_free(text: &str, name: &str) -> Result<Free, String> {
    Free::parse(text, name).map_err(|e| e.to_string())
}

impl FitRequest {
    /// The fit's options. The model list is checked here too (a request built without
    /// [`parse_models`]): at least one model, none twice.
    pub fn options(&self) -> Result<FitOptions, Error> {
        if self.models.is_empty() {
            return Err("models: the list is empty".into());
        }
        if let Some((i, m)) = self.models.iter().enumerate().find(|(i, m)| self.models[..*i].contains(m)) {
            return Err(format!("models[{i}]: `{}` is listed twice", m.name()).into());
        }
        Ok(FitOptions {
            models: self.models.clone(),
            free: self.free,
            surfaces: self.surfaces,
            calibration_draws: self.draws,
            seed: self.seed,
            ..FitOptions::default()
        })
    }
}

/// One source of truth, as in `run`: a given spring force that contradicts the clamp spring is
/// refused, naming the scenario `name`.
pub fn check_spring(scenario: &Scenario, name: &str) -> Result<(), Error> {
    if let Some(conflict) = scenario.spring_force_conflict() {
        return Err(format!("{name}: {conflict}").into());
    }
    Ok(())
}

/// Reads the request's measured voltages (relative paths of the scenario from `base`).
pub fn read_data(data: &FitData, scenario: &Scenario, base: &Path) -> Result<Dataset, Error> {
    Ok(match data {
        FitData::File(p) => read_measured_voltages(p)?,
        FitData::Text { bytes, name } => stiction_fit::parse_measured_voltages(bytes, name)?,
        FitData::Scenario => match &scenario.measured {
            Some(m) => read_measured_voltages(&base.join(&m.voltages_csv))?,
            None => return Err("missing DATA.csv (the scenario has no `measured` section either)".into()),
        },
    })
}

/// The fit of `data` to `scenario` (its JSON tree `json`, relative paths from `base`).
pub fn analyse(
    req: &FitRequest,
    data: &Dataset,
    scenario: &Scenario,
    json: &serde_json::Value,
    base: &Path,
) -> Result<FitReport, Error> {
    Ok(stiction_fit::analyse(data, scenario, json, base, &req.options()?)?)
}

/// The default free parameters and surfaces of a fit (what a structure's fit, eq. 10 only, takes).
pub const DEFAULT_FREE: &str = "s";
/// The default number of surface realisations of the explicit ensemble.
pub const DEFAULT_SURFACES: usize = 100;

/// Reads a structure's measured thresholds (relative paths from the scenario's folder do not
/// apply: a structure's scenario has no `measured` section).
pub fn read_thresholds(data: &FitData) -> Result<stiction_fit::ThresholdData, Error> {
    Ok(match data {
        FitData::File(p) => stiction_fit::read_thresholds(p)?,
        FitData::Text { bytes, name } => stiction_fit::parse_thresholds(bytes, name)?,
        FitData::Scenario => {
            return Err("missing DATA.csv: a structure's measured thresholds are given as a file (columns \
                        v_normal_v or normal_load_n, and v_tangential_v, displacement_m or tangential_load_n)"
                .into());
        }
    })
}

/// The fit of a structure's measured thresholds (eq. 10 on the forces its parts imply, with the
/// regression's and the parts' calibration intervals). The contact-model options (`models`,
/// `free`, `surfaces`) fit a paper meter's voltages: given for a structure they are refused,
/// naming them (`names` gives the front end's name of each: the CLI's flag, Python's argument).
pub fn structure_fit(
    req: &FitRequest,
    scenario: &Scenario,
    json: &serde_json::Value,
    names: &dyn Fn(&str) -> String,
) -> Result<StructureFitReport, Error> {
    let odd: Vec<String> = [
        ("models", req.models != ModelKind::defaults()),
        ("free", req.free != Free::default()),
        ("surfaces", req.surfaces != DEFAULT_SURFACES),
    ]
    .iter()
    .filter(|(_, given)| *given)
    .map(|(n, _)| names(n))
    .collect();
    if !odd.is_empty() {
        return Err(format!(
            "{} fit contact models to a paper meter's voltages; a `structure`'s fit is eq. 10 on the forces its \
             parts imply: leave {} out",
            odd.join(", "),
            if odd.len() > 1 { "them" } else { "it" }
        )
        .into());
    }
    let data = read_thresholds(&req.data)?;
    Ok(stiction_fit::analyse_structure(&data, scenario, json, req.draws, req.seed)?)
}

/// What `fit [DATA] --scenario S --json` prints for the scenario `source` (a file or a tree
/// built in memory, with its overrides). Every number checked finite. A scenario with a
/// `structure` is fitted by [`structure_fit`] (Python's argument names in its refusals).
pub fn fit_json(req: &FitRequest, source: &ScenarioSource) -> Result<serde_json::Value, Error> {
    let scenario = source.parse(&[])?;
    if scenario.structure.is_some() {
        let json = source.json(&[])?;
        let report = structure_fit(req, &scenario, &json, &|n| format!("`{n}`"))?;
        return Ok(crate::json::finite_value(&report)?);
    }
    check_spring(&scenario, &source.name())?;
    let json = source.json(&[])?;
    let data = read_data(&req.data, &scenario, &source.base)?;
    let report = analyse(req, &data, &scenario, &json, &source.base)?;
    Ok(crate::json::finite_value(&report)?)
}

/// A labelled synthetic data file of the scenario's virtual meter (named `name` in its comment):
/// at its clamp voltages, `repeats` each, Gaussian noise of sd `noise_v` (V) on each pull
/// voltage, ChaCha8 `seed`; `command` is the command line that made it, for the comment. The
/// CSV text and its row count.
pub fn synthesize(
    scenario: &Scenario,
    name: &str,
    base: &Path,
    noise_v: f64,
    repeats: usize,
    seed: u64,
    command: &str,
) -> Result<(String, usize), Error> {
    if scenario.structure.is_some() {
        return Err("--synthesize runs the paper's meter (`actuators` and `meter`); this scenario describes a \
                    `structure`: run it (`stiction run`) for its thresholds"
            .into());
    }
    let meter = scenario.meter.as_ref().ok_or("the scenario has no `meter` section")?;
    let voltages = meter.clamp_voltages.voltages();
    let rows = synth::from_meter(scenario, base, &voltages, repeats, noise_v, seed)?;
    let s = scenario.material.as_ref().map_or(f64::NAN, |m| m.shear_strength);
    let comment = format!(
        "SYNTHETIC DATA made by stiction itself, not a measurement.\n\
         Virtual meter of {} (contact model {}, s = {}), {} repeats per clamp voltage,\n\
         Gaussian noise SD {} V added to each pull voltage (ChaCha8 seed {}).\n\
         Command: {command}",
        name,
        scenario.contact_or_default().model,
        stiction_units::format_quantity(s, stiction_units::Dimension::Pressure),
        repeats,
        noise_v,
        seed,
    );
    Ok((synth::to_csv(&rows, &comment)?, rows.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(models: Vec<ModelKind>) -> FitRequest {
        FitRequest { data: FitData::Scenario, models, free: Free::default(), surfaces: 1, draws: 1, seed: 1 }
    }

    #[test]
    fn model_and_free_lists_are_parsed_naming_the_front_ends_field() {
        assert_eq!(parse_models(DEFAULT_MODELS, "--models").unwrap(), ModelKind::defaults());
        let e = parse_models("gw-dmt,bogus", "models").unwrap_err();
        assert!(e.starts_with("models: unknown model `bogus`"), "{e}");
        assert_eq!(parse_models("gw,gw-dmt", "--models").unwrap_err(), "--models: `gw-dmt` is listed twice");
        assert_eq!(parse_free("s,R", "free").unwrap(), Free { radius: true, spring: false });
        assert!(parse_free("R", "--free").unwrap_err().starts_with("--free: the list must contain s"));
        // A typed list built without the parser is checked by the engine.
        assert!(request(vec![]).options().is_err());
        let e = request(vec![ModelKind::Gw, ModelKind::Gw]).options().unwrap_err().to_string();
        assert_eq!(e, "models[1]: `gw-dmt` is listed twice");
        assert_eq!(request(ModelKind::defaults()).options().unwrap().models, ModelKind::defaults());
    }
}
