//! The commands whose keyword arguments become an engine request field by field (contact, bem,
//! fit, humidity, gw, discrete): each argument parsed as the command line parses its flag, and
//! every error names the Python argument.

use std::path::PathBuf;

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stiction_engine::topography::{Levelling, MapMetadata, Preparation, parse_length_unit};
use stiction_units::{Constraint, Dimension, parse_quantity_checked};

use crate::binding::{
    Progress, PyScenario, count, err, err_named, flag_text, interruptible, json_object, read_heights, short_repr,
    to_py, vector,
};

/// contact_json(scenario, load=None, loads=None, mode=None, contacts=None, summits=False,
/// model=None, max_sweep_steps=None) -> dict: what `stiction contact SCENARIO --json` prints, from
/// the engine's request built of these arguments: `load` one force (a unit string or N), `loads`
/// (N, in order: a list or an array) a sweep of those loads, at most `max_sweep_steps` of them
/// (default 1,000,000), counted before they are read. Errors name the Python arguments. The GIL
/// is released; Ctrl-C raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (scenario, load=None, loads=None, mode=None, contacts=None, summits=false, model=None, max_sweep_steps=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn contact_json<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    load: Option<&Bound<'py, PyAny>>,
    loads: Option<&Bound<'py, PyAny>>,
    mode: Option<&str>,
    contacts: Option<&Bound<'py, PyAny>>,
    summits: bool,
    model: Option<&str>,
    max_sweep_steps: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    use stiction_engine::contact::{ContactRequest, Mode, Model};
    use stiction_engine::limits::{DEFAULT_MAX_SWEEP_STEPS, check_sweep_len};
    let max = match max_sweep_steps.filter(|m| !m.is_none()) {
        Some(m) => count("max_sweep_steps", m, 1, usize::MAX as u64, "loads of one sweep")? as usize,
        None => DEFAULT_MAX_SWEEP_STEPS,
    };
    let loads = match loads.filter(|l| !l.is_none()) {
        Some(l) => Some(vector("load", l, true, &|n| {
            check_sweep_len("load", n, max, "raise it with max_sweep_steps=N if you mean it")
        })?),
        None => None,
    };
    if let Some(loads) = &loads
        && let Some((i, l)) = loads.iter().enumerate().find(|(_, l)| !l.is_finite())
    {
        return Err(err(format!("load[{i}] = {l}: expected a finite load in N")));
    }
    let load_n = match load.filter(|l| !l.is_none()) {
        Some(l) => Some(quantity("load", l, Dimension::Force, Constraint::Finite)?),
        None => None,
    };
    let req = ContactRequest {
        model: match model.map(str::to_ascii_lowercase).as_deref() {
            None | Some("explicit") => Model::Explicit,
            Some("bem") => Model::Bem,
            Some(other) => return Err(err(format!("model={other:?}: expected \"explicit\" or \"bem\""))),
        },
        load_n,
        loads_n: loads,
        mode: match mode.map(str::to_ascii_lowercase).as_deref() {
            None => None,
            Some("tilt") => Some(Mode::Tilt),
            Some("flat") => Some(Mode::Flat),
            Some("fixed") => Some(Mode::Fixed),
            Some(other) => return Err(err(format!("mode={other:?}: expected \"tilt\", \"flat\" or \"fixed\""))),
        },
        contacts: match contacts.filter(|c| !c.is_none()) {
            Some(c) => {
                Some(count("contacts", c, 0, usize::MAX as u64, "summits carrying the shoe in mode 'fixed'")? as usize)
            }
            None => None,
        },
        summits,
    };
    req.validate(&python_field).map_err(err)?;
    let source = PyScenario::source_of(scenario)?;
    let out = interruptible(py, move |_| {
        stiction_engine::contact::contact_json(&req, &source, &python_field).map_err(|e| e.to_string())
    })?;
    json_object(py, out.map_err(err)?)
}

/// The Python argument of an engine request's field (`load_n` -> `load`, `radius_m` -> `radius`).
fn python_field(field: &str) -> String {
    match field {
        "load_n" | "loads_n" => "load",
        "radius_m" => "radius",
        "work_of_adhesion_j_per_m2" => "work_of_adhesion",
        "compliance_per_pa" => "compliance",
        "shear_strength_pa" => "shear_strength",
        "equilibrium_spacing_m" => "equilibrium_spacing",
        other => other,
    }
    .to_string()
}

/// The Python arguments of `bem`, whose command-line flags its errors name by these names.
const BEM_NAMES: &[&str] = &[
    "heights",
    "pressure",
    "pixel_size",
    "pixel_size_y",
    "height_unit",
    "level",
    "cutoff",
    "long_cutoff",
    "e_star",
    "sweep",
    "gap_sweep",
    "gap_back",
    "work_of_adhesion",
    "range",
    "shear_strength",
    "tolerance",
    "compare_asperity",
    "scenario",
    "rh",
    "temperature",
    "contact_angle",
    "rh_step",
    "min_kelvin_radius",
    "size",
    "grid",
    "hurst",
    "roll_off",
    "short",
    "rms_height",
    "seed",
    "boundary",
    "tilt",
    "hardness",
];

/// The keyword arguments of a call, read one by one into an engine request; each error names
/// its argument.
struct Kw<'a, 'py>(&'a Bound<'py, PyDict>);

impl Kw<'_, '_> {
    fn get(&self, name: &str) -> PyResult<Option<Bound<'_, PyAny>>> {
        Ok(self.0.get_item(name)?.filter(|v| !v.is_none()))
    }

    fn quantity(&self, name: &str, dim: Dimension, constraint: Constraint) -> PyResult<Option<f64>> {
        self.get(name)?.map(|v| quantity(name, &v, dim, constraint)).transpose()
    }

    fn text(&self, name: &str) -> PyResult<Option<String>> {
        self.get(name)?.map(|v| flag_text(&v)).transpose()
    }

    fn flag(&self, name: &str) -> PyResult<bool> {
        Ok(match self.get(name)? {
            Some(v) => v.is_truthy()?,
            None => false,
        })
    }

    fn number(&self, name: &str) -> PyResult<Option<f64>> {
        self.get(name)?
            .map(|v| {
                let text = flag_text(&v)?;
                text.trim().parse::<f64>().map_err(|_| err(format!("{name}={text}: expected a number")))
            })
            .transpose()
    }
}

/// bem_json(heights, kw, pressures=None, scenario=None, rh=None) -> dict: what `stiction bem
/// --map FILE.npy --json` prints for the height map `heights` (a 2-D array, read in place), its
/// `file` being "<array>"; or, with `heights` None and a scenario (a Scenario, a dict or a path),
/// what `stiction bem --scenario SCENARIO --json` prints; or, with neither, what `stiction bem
/// --json` prints on the generated surface. `kw` holds the keyword arguments given (pixel_size,
/// level, e_star, pressure, sweep, ..., seed), read into the engine's request; `pressures` (Pa,
/// in order; a list or an array of at most 10,000, the limit of a sweep) instead of one pressure;
/// `rh` (fractions, at most 1000) instead of its text. Every length and the map's grid are
/// checked before anything is read or copied; errors name the Python arguments. The GIL is
/// released; Ctrl-C raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (heights, kw, pressures=None, scenario=None, rh=None))]
pub(crate) fn bem_json<'py>(
    py: Python<'py>,
    heights: &Bound<'py, PyAny>,
    kw: &Bound<'py, PyDict>,
    pressures: Option<&Bound<'py, PyAny>>,
    scenario: Option<&Bound<'py, PyAny>>,
    rh: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    use stiction_engine::bem::{BemHumidity, BemRequest, BemSurface};
    use stiction_engine::limits::{MAX_RH, check_bem_grid, check_pressures_len};
    use stiction_engine::range::{GapRange, PressureRange};
    let named = err_named(BEM_NAMES);
    let pressures = match pressures.filter(|p| !p.is_none()) {
        Some(p) => Some(vector("pressure", p, true, &|n| check_pressures_len("pressure", n))?),
        None => None,
    };
    let rh = match rh.filter(|r| !r.is_none()) {
        Some(r) => Some(vector("rh", r, false, &|n| {
            if n > MAX_RH { Err(format!("rh: expected 1 to {MAX_RH} humidities, got {n}")) } else { Ok(()) }
        })?),
        None => None,
    };
    // A map larger than the solver's grid is refused before it is read (a copy of the array).
    if !heights.is_none()
        && let Ok((ny, nx)) = heights.getattr("shape").and_then(|s| s.extract::<(usize, usize)>())
    {
        check_bem_grid("heights", nx, ny).map_err(err)?;
    }
    let kw = Kw(kw);
    let rh_text = kw.text("rh")?;
    if let Some(values) = &rh {
        // Checked and named here (rh[i]).
        stiction_engine::rh::check_rh_values(values).map_err(err)?;
    }
    let rh_given = rh.is_some() || rh_text.is_some();
    // The argument rules of the command line's flags, named as the Python arguments.
    let given = |n: &str| kw.get(n).map(|v| v.is_some());
    for (a, b) in [("pressure", "sweep"), ("pressure", "gap_sweep"), ("sweep", "gap_sweep")] {
        if given(a)? && given(b)? || (a == "pressure" && pressures.is_some() && given(b)?) {
            return Err(err(format!("bem: the argument '{a}' cannot be used with '{b}'")));
        }
    }
    if rh_given {
        for b in ["sweep", "gap_sweep"] {
            if given(b)? {
                return Err(err(format!("bem: the argument 'rh' cannot be used with '{b}'")));
            }
        }
        if kw.flag("compare_asperity")? {
            return Err(err("bem: the argument 'rh' cannot be used with 'compare_asperity'"));
        }
    }
    match (given("work_of_adhesion")?, given("range")?) {
        (true, false) => {
            return Err(err("bem: the argument 'work_of_adhesion' needs 'range' (the Dugdale law's range h0)"));
        }
        (false, true) => {
            return Err(err("bem: the argument 'range' needs 'work_of_adhesion' (the Dugdale law's work of adhesion)"));
        }
        _ => {}
    }
    let level = match kw.text("level")? {
        Some(l) => l.parse::<Levelling>().map_err(|e| err(format!("level={l}: {e}")))?,
        None => Levelling::Plane,
    };
    let length = |n: &str| kw.quantity(n, Dimension::Length, Constraint::Positive);
    let grid = match kw.get("grid")? {
        Some(g) => count("grid", &g, 0, u64::MAX, "points per side")? as usize,
        None => 256,
    };
    let seed = match kw.get("seed")? {
        Some(s) => count("seed", &s, 0, u64::MAX, "")?,
        None => 1,
    };
    let req = BemRequest {
        preparation: Preparation {
            levelling: level,
            short_cutoff_m: length("cutoff")?,
            long_cutoff_m: length("long_cutoff")?,
        },
        size_m: match length("size")? {
            Some(v) => v,
            None => parse_quantity_checked(stiction_engine::bem::DEFAULT_SIZE, Dimension::Length, Constraint::Positive)
                .map_err(err)?,
        },
        grid,
        hurst: kw.number("hurst")?.unwrap_or(0.8),
        roll_off_m: length("roll_off")?,
        short_m: length("short")?,
        rms_height_m: match length("rms_height")? {
            Some(v) => v,
            None => parse_quantity_checked(
                stiction_engine::bem::DEFAULT_RMS_HEIGHT,
                Dimension::Length,
                Constraint::Positive,
            )
            .map_err(err)?,
        },
        seed,
        e_star_pa: kw.quantity("e_star", Dimension::Pressure, Constraint::Positive)?,
        pressure_pa: kw.quantity("pressure", Dimension::Pressure, Constraint::Positive)?,
        sweep: kw.text("sweep")?.map(|t| PressureRange::parse(&t, "sweep")).transpose().map_err(err)?,
        gap_sweep: kw.text("gap_sweep")?.map(|t| GapRange::parse(&t, "gap_sweep")).transpose().map_err(err)?,
        gap_back: kw.flag("gap_back")?,
        work_of_adhesion_j_per_m2: kw.quantity("work_of_adhesion", Dimension::SurfaceEnergy, Constraint::Positive)?,
        range_m: length("range")?,
        humidity: BemHumidity {
            // The humidities as numbers, or as the text of --rh (a list or FROM:TO:STEPS) named `rh`.
            rh: match (rh, rh_text) {
                (Some(values), _) => Some(values),
                (None, Some(text)) => Some(stiction_engine::rh::parse_rh_as(&text, "rh").map_err(err)?),
                (None, None) => None,
            },
            temperature_k: stiction_engine::bem::humidity::parse_temperature(
                &kw.text("temperature")?.unwrap_or_else(|| "25 C".into()),
                "temperature",
            )
            .map_err(err)?,
            contact_angle_rad: kw.quantity("contact_angle", Dimension::Angle, Constraint::NonNegative)?.unwrap_or(0.0),
            rh_step_m: length("rh_step")?,
            min_kelvin_radius_m: length("min_kelvin_radius")?,
        },
        shear_strength_pa: kw.quantity("shear_strength", Dimension::Pressure, Constraint::NonNegative)?,
        tolerance: kw.number("tolerance")?.unwrap_or(1e-6),
        compare_asperity: kw.flag("compare_asperity")?,
        boundary: match kw.text("boundary")?.as_deref() {
            None | Some("periodic") => stiction_engine::bem::Boundary::Periodic,
            Some("non_periodic" | "non-periodic") => stiction_engine::bem::Boundary::NonPeriodic,
            Some(other) => {
                return Err(err(format!("boundary={other:?}: expected \"periodic\" or \"non_periodic\"")));
            }
        },
        tilt: kw.flag("tilt")?,
        hardness_pa: kw.quantity("hardness", Dimension::Pressure, Constraint::Positive)?,
    };
    if let Some(scenario) = scenario.filter(|s| !s.is_none()) {
        if !heights.is_none() {
            return Err(err("bem: give a height map (heights) or a scenario, not both"));
        }
        let source = PyScenario::source_of(scenario)?;
        let out = interruptible(py, move |_| {
            stiction_engine::bem::bem_json(&req, BemSurface::Scenario(&source), pressures.as_deref())
                .map_err(|e| e.to_string())
        })?;
        return json_object(py, out.map_err(named)?);
    }
    if heights.is_none() {
        let out = interruptible(py, move |_| {
            stiction_engine::bem::bem_json(&req, BemSurface::Generated, pressures.as_deref()).map_err(|e| e.to_string())
        })?;
        return json_object(py, out.map_err(named)?);
    }
    let meta = MapMetadata {
        pixel_size_x_m: length("pixel_size")?,
        pixel_size_y_m: length("pixel_size_y")?,
        height_unit_m: match kw.text("height_unit")? {
            Some(text) => Some(parse_length_unit(&text).map_err(|e| err(format!("height_unit={text}: {e}")))?),
            None => None,
        },
        xy_unit_m: None,
    };
    let (raw, info) = read_heights(heights, &meta)?;
    let out = interruptible(py, move |_| {
        let surface = BemSurface::Map { file: "<array>", raw, info };
        stiction_engine::bem::bem_json(&req, surface, pressures.as_deref()).map_err(|e| e.to_string())
    })?;
    json_object(py, out.map_err(named)?)
}

/// humidity_json(scenario, rh_text=None, rh=None, progress=None) -> dict: what `stiction plot
/// humidity --scenario SCENARIO --rh RH --json` prints: the friction meter at each relative
/// humidity, the dry point first. `rh_text` is the text of --rh ("0:0.9:10", "0.1,35 %"); `rh`
/// the humidities as fractions (each in [0, 1), increasing); neither: the command line's default.
/// `progress(done, total)` is called after each humidity. The GIL is released; Ctrl-C raises
/// KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (scenario, rh_text=None, rh=None, progress=None))]
pub(crate) fn humidity_json<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    rh_text: Option<String>,
    rh: Option<&Bound<'py, PyAny>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    use stiction_engine::limits::MAX_RH;
    let named = err_named(&["rh"]);
    let rh = match rh.filter(|r| !r.is_none()) {
        // Counted before it is read: at most the --rh limit of humidities.
        Some(r) => Some(vector("rh", r, false, &|n| {
            if n > MAX_RH { Err(format!("rh: expected 1 to {MAX_RH} humidities, got {n}")) } else { Ok(()) }
        })?),
        None => None,
    };
    let rhs = match (rh_text, rh) {
        (Some(_), Some(_)) => return Err(err("rh: give the humidities as text or as numbers, not both")),
        (Some(text), None) => stiction_engine::humidity::rh_grid(Some(&text)),
        (None, Some(values)) => stiction_engine::humidity::rh_grid_of(&values),
        (None, None) => stiction_engine::humidity::rh_grid(None),
    }
    .map_err(named)?;
    let source = PyScenario::source_of(scenario)?;
    let progress = Progress::new(progress);
    let report = progress.clone();
    let out = interruptible(py, move |_| {
        let mut on_point = |done: usize, total: usize| {
            report.report(done, total);
        };
        stiction_engine::humidity::humidity_json(&source, &rhs, &mut on_point).map_err(|e| e.to_string())
    })?;
    if let Some(e) = progress.take_error() {
        return Err(e);
    }
    json_object(py, out.map_err(err)?)
}

/// fit_json(scenario, data_path=None, data_csv=None, data_name=None, models=None, free=None,
/// surfaces=None, draws=None, seed=None) -> dict: what `stiction fit [DATA] --scenario SCENARIO
/// --json` prints, from the engine's request of these arguments; `data_csv`, the CSV text of the
/// measured voltages, instead of a file; neither: the scenario's own. The GIL is released;
/// Ctrl-C raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (scenario, data_path=None, data_csv=None, data_name=None, models=None, free=None, surfaces=None, draws=None, seed=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit_json<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    data_path: Option<PathBuf>,
    data_csv: Option<String>,
    data_name: Option<String>,
    models: Option<String>,
    free: Option<String>,
    surfaces: Option<usize>,
    draws: Option<usize>,
    seed: Option<u64>,
) -> PyResult<Bound<'py, PyAny>> {
    use stiction_engine::fit::{FitData, FitRequest, Free, ModelKind, parse_free, parse_models};
    let source = PyScenario::source_of(scenario)?;
    let data = match (data_path, data_csv) {
        (Some(p), _) => FitData::File(p),
        (None, Some(text)) => {
            FitData::Text { bytes: text.into_bytes(), name: data_name.unwrap_or_else(|| "<data>".into()) }
        }
        (None, None) => FitData::Scenario,
    };
    let req = FitRequest {
        data,
        models: match models {
            Some(text) => parse_models(&text, "models").map_err(err)?,
            None => ModelKind::defaults(),
        },
        free: match free {
            Some(text) => parse_free(&text, "free").map_err(err)?,
            None => Free::default(),
        },
        surfaces: surfaces.unwrap_or(100),
        draws: draws.unwrap_or(4000),
        seed: seed.unwrap_or(1),
    };
    let out = interruptible(py, move |_| stiction_engine::fit::fit_json(&req, &source).map_err(|e| e.to_string()))?;
    json_object(py, out.map_err(err_named(&["models", "free", "surfaces", "draws", "seed", "data", "scenario"]))?)
}

/// gw(theta, load_star) -> dict of arrays: the stable-branch Greenwood-Williamson + DMT state
/// (eq. 5-9) at each normalized load L* (as `stiction gw --theta T --load-star L --json`).
#[pyfunction]
pub(crate) fn gw_arrays<'py>(
    py: Python<'py>,
    theta: Option<f64>,
    load_star: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    use stiction_engine::limits::{DEFAULT_MAX_SWEEP_STEPS, check_sweep_len};
    // One CLI call per load: at most the loads of one sweep, counted before they are read.
    let load_star = vector("load_star", load_star, true, &|n| {
        if n == 0 {
            Ok(())
        } else {
            check_sweep_len("load_star", n, DEFAULT_MAX_SWEEP_STEPS, "split the loads over several calls")
        }
    })?;
    let theta = theta.filter(|t| !t.is_infinite());
    let model = stiction_engine::gw::model(theta).map_err(err)?;
    let solve = || {
        load_star
            .iter()
            .enumerate()
            .map(|(i, &l)| {
                if !l.is_finite() {
                    return Err(format!("load_star[{i}] = {l}: expected a finite normalized load"));
                }
                stiction_engine::gw::state(&model, l).map_err(|e| format!("load_star[{i}] = {l}: {e}"))
            })
            .collect::<Result<Vec<_>, String>>()
    };
    // A few loads take microseconds: releasing the GIL would cost more than it frees.
    let states = if load_star.len() < 64 { solve() } else { py.detach(solve) };
    let states = states.map_err(err)?;
    let d = PyDict::new(py);
    let col = |f: &dyn Fn(&stiction_engine::gw::GwOutput) -> f64| states.iter().map(f).collect::<Vec<f64>>();
    d.set_item("l_star", PyArray1::from_vec(py, col(&|s| s.l_star)))?;
    d.set_item("h", PyArray1::from_vec(py, col(&|s| s.h)))?;
    d.set_item("n_star", PyArray1::from_vec(py, col(&|s| s.n_star)))?;
    d.set_item("log10_n_star", PyArray1::from_vec(py, col(&|s| s.log10_n_star)))?;
    d.set_item("a_star", PyArray1::from_vec(py, col(&|s| s.a_star)))?;
    d.set_item("log10_a_star", PyArray1::from_vec(py, col(&|s| s.log10_a_star)))?;
    d.set_item("elastic_l_star", PyArray1::from_vec(py, col(&|s| s.elastic_l_star)))?;
    d.set_item("adhesive_l_star", PyArray1::from_vec(py, col(&|s| s.adhesive_l_star)))?;
    d.set_item("elastic_pressure_star", PyArray1::from_vec(py, col(&|s| s.elastic_pressure_star)))?;
    d.set_item("theta", theta)?;
    d.set_item("pull_off_l_star", model.pull_off().map(|p| p.l_star))?;
    d.set_item("pull_off_h", model.pull_off().map(|p| p.h))?;
    Ok(d)
}

/// A quantity argument: a unit string or an SI number, checked as the command line's flag.
fn quantity(name: &str, value: &Bound<'_, PyAny>, dim: Dimension, constraint: Constraint) -> PyResult<f64> {
    let text = flag_text(value)?;
    parse_quantity_checked(&text, dim, constraint).map_err(|e| err(format!("{name}={text}: {e}")))
}

/// discrete_json(...) -> list: per load, the object `stiction discrete ... --json` prints.
#[pyfunction]
#[pyo3(signature = (contacts, radius, work_of_adhesion, compliance, shear_strength, loads, adhesion="dmt", equilibrium_spacing=None, target_slope=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn discrete_json<'py>(
    py: Python<'py>,
    contacts: &Bound<'_, PyAny>,
    radius: &Bound<'_, PyAny>,
    work_of_adhesion: &Bound<'_, PyAny>,
    compliance: &Bound<'_, PyAny>,
    shear_strength: &Bound<'_, PyAny>,
    loads: &Bound<'_, PyAny>,
    adhesion: &str,
    equilibrium_spacing: Option<&Bound<'_, PyAny>>,
    target_slope: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    use stiction_engine::discrete::{AdhesionLaw, DEFAULT_EQUILIBRIUM_SPACING_M, DiscreteRequest};
    use stiction_engine::limits::{DEFAULT_MAX_SWEEP_STEPS, check_sweep_len};
    // The counts first: contacts as the command line's --contacts (u32), the loads (one CLI
    // call each) at most those of one sweep, counted before they are read.
    let contacts = count("contacts", contacts, 0, u64::from(u32::MAX), "summits in contact")? as u32;
    // A NumPy array counted by its size (any shape, read flat), a list by its length.
    let is_array = loads.is_instance(&py.import("numpy")?.getattr("ndarray")?)?;
    let n = if is_array { loads.getattr("size")?.extract()? } else { loads.len().unwrap_or(usize::MAX) };
    if n == usize::MAX {
        return Err(err(format!("load: expected a force or a list of forces, got {}", short_repr(loads))));
    }
    if n > 0 {
        check_sweep_len("load", n, DEFAULT_MAX_SWEEP_STEPS, "split the loads over several calls").map_err(err)?;
    }
    let flat = if is_array { loads.call_method0("ravel")? } else { loads.clone() };
    let loads: Vec<Bound<'_, PyAny>> = flat.try_iter()?.collect::<PyResult<_>>()?;
    let law = match adhesion.to_ascii_lowercase().as_str() {
        "dmt" => AdhesionLaw::Dmt,
        "jkr" => AdhesionLaw::Jkr,
        "maugis-dugdale" => AdhesionLaw::MaugisDugdale,
        "hertz" => AdhesionLaw::Hertz,
        other => return Err(err(format!("adhesion={other}: expected dmt, jkr, maugis-dugdale or hertz"))),
    };
    let template = DiscreteRequest {
        contacts,
        radius_m: quantity("radius", radius, Dimension::Length, Constraint::Positive)?,
        work_of_adhesion_j_per_m2: quantity(
            "work_of_adhesion",
            work_of_adhesion,
            Dimension::SurfaceEnergy,
            Constraint::NonNegative,
        )?,
        compliance_per_pa: quantity("compliance", compliance, Dimension::Compliance, Constraint::Positive)?,
        shear_strength_pa: quantity("shear_strength", shear_strength, Dimension::Pressure, Constraint::NonNegative)?,
        load_n: 0.0,
        law,
        equilibrium_spacing_m: match equilibrium_spacing {
            Some(v) if !v.is_none() => quantity("equilibrium_spacing", v, Dimension::Length, Constraint::Positive)?,
            // The command line's default, parsed as it parses it ("0.3 nm", the engine's
            // DEFAULT_EQUILIBRIUM_SPACING_M).
            _ => parse_quantity_checked("0.3 nm", Dimension::Length, Constraint::Positive).map_err(err)?,
        },
        target_slope,
    };
    let _ = DEFAULT_EQUILIBRIUM_SPACING_M;
    let loads: Vec<f64> = loads
        .iter()
        .enumerate()
        .map(|(i, l)| quantity(&format!("load[{i}]"), l, Dimension::Force, Constraint::Finite))
        .collect::<PyResult<_>>()?;
    // The domains of the command line's flags (radius, work of adhesion, compliance, spacing,
    // each load), named as the Python arguments.
    template.validate(&python_field).map_err(err)?;
    for (i, &load) in loads.iter().enumerate() {
        DiscreteRequest { load_n: load, ..template }
            .validate(&|f: &str| if f == "load_n" { format!("load[{i}]") } else { python_field(f) })
            .map_err(err)?;
    }
    let out = py.detach(|| {
        let mut out = Vec::with_capacity(loads.len());
        for (i, &load) in loads.iter().enumerate() {
            let req = DiscreteRequest { load_n: load, ..template };
            let o = stiction_engine::discrete::discrete(&req).map_err(|e| format!("load[{i}] = {load} N: {e}"))?;
            out.push(stiction_engine::json::finite_value(&o).map_err(|e| format!("load[{i}] = {load} N: {e}"))?);
        }
        Ok::<_, String>(serde_json::Value::Array(out))
    });
    to_py(py, &out.map_err(err)?)
}
