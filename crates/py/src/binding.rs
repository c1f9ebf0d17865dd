//! The `#[pymodule]`: functions and the `Scenario` class.

use std::path::{Path, PathBuf};

use numpy::{PyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use stiction_scenario::Scenario;
use stiction_study::{Calibration, StudyConfig};
use stiction_topography::{HeightMap, Levelling, MapMetadata, Preparation, parse_length_unit, read_npy};
use stiction_units::{Constraint, Dimension, parse_quantity_checked};

create_exception!(
    _stiction,
    StictionError,
    PyValueError,
    "Bad input (scenario, map, argument) or a value that cannot be computed; the message is the \
     command line's."
);

/// An error of the engine as a `StictionError` with the command line's message.
fn err(e: impl std::fmt::Display) -> PyErr {
    StictionError::new_err(e.to_string())
}

/// `json.loads(text)`: the Python value of a JSON text, as a script parsing `--json` gets it.
fn json_loads<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// A scenario: a file (with `set` overrides applied in order) or a JSON tree built in Python.
#[pyclass(name = "Scenario", module = "stiction._stiction", from_py_object)]
#[derive(Clone)]
struct PyScenario {
    /// The scenario file, if it came from one.
    path: Option<PathBuf>,
    /// The JSON text of a scenario built from a dict or a string.
    text: Option<String>,
    /// Folder of the relative paths in the scenario.
    base: PathBuf,
    /// `--set PATH=VALUE` overrides, in order.
    sets: Vec<String>,
}

impl PyScenario {
    /// The name of the scenario in errors and in the `scenario` field of results.
    fn name(&self) -> String {
        self.path.as_ref().map_or_else(|| "<scenario>".to_string(), |p| p.display().to_string())
    }

    /// Parses and validates, as the command line does.
    fn parse(&self) -> Result<Scenario, stiction_scenario::ScenarioError> {
        match (&self.path, &self.text) {
            (Some(p), _) => Scenario::load(p, &self.sets),
            (None, Some(t)) => Scenario::from_str_with_sets(t, Path::new("<scenario>"), &self.sets),
            (None, None) => Scenario::from_str_with_sets("{}", Path::new("<scenario>"), &self.sets),
        }
    }

    fn from_path(path: PathBuf) -> PyScenario {
        let base = path.parent().map(PathBuf::from).unwrap_or_default();
        PyScenario { path: Some(path), text: None, base, sets: Vec::new() }
    }

    /// A `Scenario`, or a path (str or os.PathLike) to a scenario file.
    fn extract(obj: &Bound<'_, PyAny>) -> PyResult<PyScenario> {
        if let Ok(s) = obj.cast::<PyScenario>() {
            return Ok(s.borrow().clone());
        }
        let os = obj.py().import("os")?;
        let path: String = os.call_method1("fspath", (obj,))?.extract().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err("expected a stiction.Scenario or a path to a scenario file")
        })?;
        Ok(PyScenario::from_path(PathBuf::from(path)))
    }
}

/// A value for `--set PATH=VALUE` or a quantity flag: a string as given, a number as Python's
/// `repr` (which reads back to the same float), True/False/None as JSON.
fn flag_text(value: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(s) = value.cast::<PyString>() {
        return s.extract::<String>();
    }
    if value.is_none() {
        return Ok("null".into());
    }
    if let Ok(b) = value.extract::<bool>()
        && value.is_instance_of::<pyo3::types::PyBool>()
    {
        return Ok(if b { "true" } else { "false" }.into());
    }
    if value.extract::<f64>().is_ok() {
        return value.repr()?.extract::<String>();
    }
    let json = value.py().import("json")?;
    json.call_method1("dumps", (value,))?.extract()
}

#[pymethods]
impl PyScenario {
    /// Scenario.load(path, sets=None): a scenario file (JSON with units, see docs/scenario.md),
    /// with `sets`, a list of "PATH=VALUE" overrides as the command line's --set takes them.
    /// Raises StictionError when the file or an override is invalid.
    #[staticmethod]
    #[pyo3(signature = (path, sets=None))]
    fn load(path: &Bound<'_, PyAny>, sets: Option<Vec<String>>) -> PyResult<PyScenario> {
        let mut s = PyScenario::extract(path)?;
        s.sets.extend(sets.unwrap_or_default());
        s.parse().map_err(err)?;
        Ok(s)
    }

    /// Scenario.from_json(text, base_dir="."): a scenario from its JSON text; relative paths in it
    /// (surface CSVs, height maps, measured voltages) are read from `base_dir`.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=None))]
    fn from_json(text: String, base_dir: Option<PathBuf>) -> PyResult<PyScenario> {
        let s = PyScenario { path: None, text: Some(text), base: base_dir.unwrap_or_default(), sets: Vec::new() };
        s.parse().map_err(err)?;
        Ok(s)
    }

    /// Scenario.from_dict(d, base_dir="."): a scenario from a dict shaped as the JSON file
    /// (quantities as unit strings, "0.5 um", or SI numbers).
    #[staticmethod]
    #[pyo3(signature = (d, base_dir=None))]
    fn from_dict(d: &Bound<'_, PyAny>, base_dir: Option<PathBuf>) -> PyResult<PyScenario> {
        let text: String = d.py().import("json")?.call_method1("dumps", (d,))?.extract()?;
        PyScenario::from_json(text, base_dir)
    }

    /// set(path, value): override a field, as --set PATH=VALUE does ("surface.summit_sd", "40 nm"
    /// or 4e-8 in SI); the scenario is checked at once and left unchanged when the override is
    /// refused (StictionError).
    fn set(&mut self, path: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        self.sets.push(format!("{path}={}", flag_text(value)?));
        if let Err(e) = self.parse() {
            self.sets.pop();
            return Err(err(e));
        }
        Ok(())
    }

    /// validate(): parse and check the scenario as `stiction scenario FILE` does; returns the
    /// notes (list of (code, message)) or raises StictionError.
    fn validate(&self) -> PyResult<Vec<(String, String)>> {
        let s = self.parse().map_err(err)?;
        Ok(s.notes.iter().map(|n| (n.code.to_string(), n.message.clone())).collect())
    }

    /// to_json(): the scenario as it is run, in SI units, as `stiction scenario FILE` prints it
    /// (readable back with Scenario.from_json).
    fn to_json(&self) -> PyResult<String> {
        let s = self.parse().map_err(err)?;
        serde_json::to_string_pretty(&s.to_input_json()).map_err(err)
    }

    /// to_dict(): `json.loads(self.to_json())`.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_loads(py, &self.to_json()?)
    }

    /// The scenario file, or None for a scenario built from a dict or text.
    #[getter]
    fn path(&self) -> Option<String> {
        self.path.as_ref().map(|p| p.display().to_string())
    }

    /// The overrides applied, in order ("PATH=VALUE").
    #[getter]
    fn sets(&self) -> Vec<String> {
        self.sets.clone()
    }

    fn __repr__(&self) -> String {
        format!("stiction.Scenario({:?}, sets={:?})", self.name(), self.sets)
    }
}

/// run(scenario, progress=None) -> str: the JSON text `stiction run SCENARIO --json` prints.
/// `progress(done, total)` is called after each clamp voltage. The GIL is released while the
/// meter runs (it is taken back only for the callback).
#[pyfunction]
#[pyo3(signature = (scenario, progress=None))]
fn run_json(py: Python<'_>, scenario: &Bound<'_, PyAny>, progress: Option<Py<PyAny>>) -> PyResult<String> {
    let s = PyScenario::extract(scenario)?;
    let parsed = s.parse().map_err(err)?;
    let name = s.name();
    let mut callback_error: Option<PyErr> = None;
    let out = py.detach(|| {
        let mut report = |done: usize, total: usize| {
            if let (Some(cb), None) = (&progress, &callback_error) {
                Python::attach(|py| {
                    if let Err(e) = cb.call1(py, (done, total)) {
                        callback_error = Some(e);
                    }
                });
            }
        };
        stiction_cli::api::run_json(&parsed, &name, &s.base, &mut report)
            .map_err(|e| e.to_string())
            .and_then(|v| serde_json::to_string(&v).map_err(|e| e.to_string()))
    });
    if let Some(e) = callback_error {
        return Err(e);
    }
    out.map_err(err)
}

/// A length flag value: a unit string ("3.9 um") or an SI number, checked as the command line
/// checks it (finite, > 0).
fn length(name: &str, value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<f64>> {
    match value {
        None => Ok(None),
        Some(v) if v.is_none() => Ok(None),
        Some(v) => {
            let text = flag_text(v)?;
            parse_quantity_checked(&text, Dimension::Length, Constraint::Positive)
                .map(Some)
                .map_err(|e| err(format!("{name}={text}: {e}")))
        }
    }
}

/// A height map's values in C order (rows = y) as .npy bytes, so that it is read by the same
/// reader as a .npy file.
fn npy_bytes<T: Copy>(view: numpy::ndarray::ArrayView2<'_, T>, descr: &str, le: impl Fn(T) -> Vec<u8>) -> Vec<u8> {
    let (ny, nx) = view.dim();
    let mut header = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': ({ny}, {nx}), }}");
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let size = if descr.ends_with('8') { 8 } else { 4 };
    let mut out = Vec::with_capacity(10 + header.len() + nx * ny * size);
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    match view.as_slice() {
        Some(slice) => slice.iter().for_each(|&v| out.extend_from_slice(&le(v))),
        None => view.iter().for_each(|&v| out.extend_from_slice(&le(v))),
    }
    out
}

/// topography(heights, ...) -> (json text, summits): see the Python wrapper's docstring.
#[pyfunction]
#[pyo3(signature = (heights, pixel_size=None, pixel_size_y=None, height_unit=None, level="plane", cutoff=None, long_cutoff=None, scenario=None))]
#[allow(clippy::too_many_arguments)]
fn topography_json<'py>(
    py: Python<'py>,
    heights: &Bound<'py, PyAny>,
    pixel_size: Option<&Bound<'py, PyAny>>,
    pixel_size_y: Option<&Bound<'py, PyAny>>,
    height_unit: Option<&Bound<'py, PyAny>>,
    level: &str,
    cutoff: Option<&Bound<'py, PyAny>>,
    long_cutoff: Option<&Bound<'py, PyAny>>,
    scenario: Option<PathBuf>,
) -> PyResult<(String, Bound<'py, PyDict>)> {
    let meta = MapMetadata {
        pixel_size_x_m: length("pixel_size", pixel_size)?,
        pixel_size_y_m: length("pixel_size_y", pixel_size_y)?,
        height_unit_m: match height_unit {
            Some(v) if !v.is_none() => {
                let text = flag_text(v)?;
                Some(parse_length_unit(&text).map_err(|e| err(format!("height_unit={text}: {e}")))?)
            }
            _ => None,
        },
        xy_unit_m: None,
    };
    let prep = Preparation {
        levelling: level.parse::<Levelling>().map_err(|e| err(format!("level={level}: {e}")))?,
        short_cutoff_m: length("cutoff", cutoff)?,
        long_cutoff_m: length("long_cutoff", long_cutoff)?,
    };
    let bytes = if let Ok(a) = heights.extract::<PyReadonlyArray2<'py, f64>>() {
        if !a.is_c_contiguous() && !a.is_fortran_contiguous() {
            return Err(err("heights: expected a C- or Fortran-ordered 2-D array"));
        }
        npy_bytes(a.as_array(), "<f8", |v: f64| v.to_le_bytes().to_vec())
    } else if let Ok(a) = heights.extract::<PyReadonlyArray2<'py, f32>>() {
        npy_bytes(a.as_array(), "<f4", |v: f32| v.to_le_bytes().to_vec())
    } else {
        return Err(err("heights: expected a 2-D NumPy array of float32 or float64 (rows = y)"));
    };
    let out = py.detach(|| -> Result<_, String> {
        let (raw, info) = read_npy(&bytes, "heights", &meta).map_err(|e| e.to_string())?;
        drop(bytes);
        let (json, map, summits) = stiction_cli::api::topography_json("<array>", raw, info, &prep, scenario.as_deref())
            .map_err(|e| e.to_string())?;
        Ok((serde_json::to_string(&json).map_err(|e| e.to_string())?, map, summits))
    });
    let (json, map, s): (String, HeightMap, _) = out.map_err(err)?;
    let d = PyDict::new(py);
    let x: Vec<f64> = s.ix.iter().map(|&i| (f64::from(i) + 0.5) * map.dx_m()).collect();
    let y: Vec<f64> = s.iy.iter().map(|&i| (f64::from(i) + 0.5) * map.dy_m()).collect();
    let r: Vec<f64> = (0..s.len()).map(|i| s.radius_m(i)).collect();
    d.set_item("x_m", PyArray1::from_vec(py, x))?;
    d.set_item("y_m", PyArray1::from_vec(py, y))?;
    d.set_item("height_m", PyArray1::from_slice(py, &s.height_m))?;
    d.set_item("curvature_per_m", PyArray1::from_slice(py, &s.curvature_per_m))?;
    d.set_item("radius_m", PyArray1::from_vec(py, r))?;
    d.set_item("ix", PyArray1::from_vec(py, s.ix.clone()))?;
    d.set_item("iy", PyArray1::from_vec(py, s.iy.clone()))?;
    Ok((json, d))
}

/// study_json(scenario, samples=100, seed=1, threads=None, fixed_surface=False) -> str: the JSON
/// text `stiction study SCENARIO --json --samples N --seed S --threads T` prints (same seed, same
/// numbers, whatever the thread count). The GIL is released while the study runs.
#[pyfunction]
#[pyo3(signature = (scenario, samples=100, seed=1, threads=None, fixed_surface=false))]
fn study_json(
    py: Python<'_>,
    scenario: &Bound<'_, PyAny>,
    samples: usize,
    seed: u64,
    threads: Option<usize>,
    fixed_surface: bool,
) -> PyResult<String> {
    let s = PyScenario::extract(scenario)?;
    let Some(path) = s.path.clone() else {
        return Err(err("study: the scenario must come from a file (Scenario.load or a path)"));
    };
    let config = StudyConfig {
        calibration: Calibration::Nominal,
        slip_path: stiction_meter::SlipPath::Light,
        samples,
        seed,
        vary_surface: !fixed_surface,
        shard_index: 0,
        shard_count: 1,
    };
    py.detach(|| {
        stiction_cli::api::study_json(&path, &s.sets, &config, threads, &|_| {})
            .map_err(|e| e.to_string())
            .and_then(|v| serde_json::to_string(&v).map_err(|e| e.to_string()))
    })
    .map_err(err)
}

/// gw(theta, load_star) -> dict of arrays: the stable-branch Greenwood-Williamson + DMT state
/// (eq. 5-9) at each normalized load L* (as `stiction gw --theta T --load-star L --json`).
#[pyfunction]
fn gw_arrays<'py>(py: Python<'py>, theta: Option<f64>, load_star: Vec<f64>) -> PyResult<Bound<'py, PyDict>> {
    let theta = theta.filter(|t| !t.is_infinite());
    let model = stiction_contact::gw::GwModel::new(theta).map_err(err)?;
    let states = py.detach(|| {
        load_star
            .iter()
            .enumerate()
            .map(|(i, &l)| {
                if !l.is_finite() {
                    return Err(format!("load_star[{i}] = {l}: expected a finite normalized load"));
                }
                model.solve(l).map_err(|e| format!("load_star[{i}] = {l}: {e}"))
            })
            .collect::<Result<Vec<_>, String>>()
    });
    let states = states.map_err(err)?;
    let d = PyDict::new(py);
    let col = |f: &dyn Fn(&stiction_contact::gw::GwState) -> f64| states.iter().map(f).collect::<Vec<f64>>();
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

/// discrete_json(...) -> str: a JSON list, per load, of what `stiction discrete ... --json` prints.
#[pyfunction]
#[pyo3(signature = (contacts, radius, work_of_adhesion, compliance, shear_strength, loads, adhesion="dmt", equilibrium_spacing=None, target_slope=None))]
#[allow(clippy::too_many_arguments)]
fn discrete_json(
    py: Python<'_>,
    contacts: u32,
    radius: &Bound<'_, PyAny>,
    work_of_adhesion: &Bound<'_, PyAny>,
    compliance: &Bound<'_, PyAny>,
    shear_strength: &Bound<'_, PyAny>,
    loads: Vec<Bound<'_, PyAny>>,
    adhesion: &str,
    equilibrium_spacing: Option<&Bound<'_, PyAny>>,
    target_slope: Option<f64>,
) -> PyResult<String> {
    use stiction_cli::api::{DiscreteArgs, Law};
    let law = match adhesion.to_ascii_lowercase().as_str() {
        "dmt" => Law::Dmt,
        "jkr" => Law::Jkr,
        "maugis-dugdale" => Law::MaugisDugdale,
        "hertz" => Law::Hertz,
        other => return Err(err(format!("adhesion={other}: expected dmt, jkr, maugis-dugdale or hertz"))),
    };
    let template = DiscreteArgs {
        contacts,
        radius: quantity("radius", radius, Dimension::Length, Constraint::Positive)?,
        work_of_adhesion: quantity(
            "work_of_adhesion",
            work_of_adhesion,
            Dimension::SurfaceEnergy,
            Constraint::NonNegative,
        )?,
        compliance: quantity("compliance", compliance, Dimension::Compliance, Constraint::Positive)?,
        shear_strength: quantity("shear_strength", shear_strength, Dimension::Pressure, Constraint::NonNegative)?,
        load: 0.0,
        adhesion: law,
        equilibrium_spacing: match equilibrium_spacing {
            Some(v) if !v.is_none() => quantity("equilibrium_spacing", v, Dimension::Length, Constraint::Positive)?,
            // The command line's default, parsed as it parses it.
            _ => parse_quantity_checked("0.3 nm", Dimension::Length, Constraint::Positive).map_err(err)?,
        },
        target_slope,
        json: true,
    };
    let loads: Vec<f64> = loads
        .iter()
        .enumerate()
        .map(|(i, l)| quantity(&format!("load[{i}]"), l, Dimension::Force, Constraint::Finite))
        .collect::<PyResult<_>>()?;
    py.detach(|| {
        let mut out = Vec::with_capacity(loads.len());
        for (i, &load) in loads.iter().enumerate() {
            let args = DiscreteArgs { load, ..template };
            out.push(stiction_cli::api::discrete_json(&args).map_err(|e| format!("load[{i}] = {load} N: {e}"))?);
        }
        serde_json::to_string(&out).map_err(|e| e.to_string())
    })
    .map_err(err)
}

/// The extension module `stiction._stiction`.
#[pymodule]
fn _stiction(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("StictionError", m.py().get_type::<StictionError>())?;
    m.add_class::<PyScenario>()?;
    m.add_function(wrap_pyfunction!(run_json, m)?)?;
    m.add_function(wrap_pyfunction!(topography_json, m)?)?;
    m.add_function(wrap_pyfunction!(study_json, m)?)?;
    m.add_function(wrap_pyfunction!(gw_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(discrete_json, m)?)?;
    Ok(())
}
