//! The `#[pymodule]`: functions and the `Scenario` class.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::RecvTimeoutError;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use numpy::{PyArray1, PyReadonlyArray2};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use stiction_engine::ScenarioSource;
use stiction_engine::scenario::Scenario;
use stiction_engine::scenario_source::ScenarioError;
use stiction_engine::study::StudyRequest;
use stiction_engine::topography::{
    ArrayLayout, BorrowedHeights, HeightMap, Levelling, MapInfo, MapMetadata, Preparation, parse_length_unit,
    read_array,
};
use stiction_units::{Constraint, Dimension, parse_quantity_checked};

create_exception!(
    _stiction,
    StictionError,
    PyValueError,
    "Bad input (scenario, map, argument) or a value that cannot be computed; the message is the \
     command line's."
);

/// An error of the engine as a `StictionError` with the command line's message.
pub(crate) fn err(e: impl std::fmt::Display) -> PyErr {
    StictionError::new_err(e.to_string())
}

/// `message` with each command-line flag that is a Python argument of the call written as that
/// argument (`--e-star` -> `e_star`, clap's `'--grid <GRID>'` -> `'grid'`), so that an error names
/// what the caller typed, never a flag it did not; every other word is kept as it is.
pub(crate) fn python_names(message: &str, names: &[&str]) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(at) = rest.find("--") {
        out.push_str(&rest[..at]);
        let after = &rest[at + 2..];
        let len = after.find(|c: char| !(c.is_ascii_alphanumeric() || c == '-')).unwrap_or(after.len());
        let name = after[..len].replace('-', "_");
        let preceded_by_word = out.chars().last().is_some_and(|c| c.is_ascii_alphanumeric() || c == '-');
        if len > 0 && !preceded_by_word && names.contains(&name.as_str()) {
            out.push_str(&name);
            let mut tail = &after[len..];
            // clap's value name: '--grid <GRID>' -> 'grid'.
            if let Some(v) = tail.strip_prefix(" <")
                && let Some(end) = v.find('>')
                && v[..end].chars().all(|c| c.is_ascii_uppercase() || "_:|".contains(c))
            {
                tail = &v[end + 1..];
            }
            rest = tail;
        } else {
            out.push_str("--");
            rest = after;
        }
    }
    out.push_str(rest);
    out
}

/// An error of the engine as a `StictionError` with the command line's message, its flags named
/// as the Python arguments `names` ([`python_names`]).
pub(crate) fn err_named(names: &'static [&'static str]) -> impl Fn(String) -> PyErr {
    move |e| StictionError::new_err(python_names(&e, names))
}

/// A short text of a Python value for a message: its `repr`, at most 60 characters (a 300-digit
/// integer or a long list is cut, with its length).
pub(crate) fn short_repr(value: &Bound<'_, PyAny>) -> String {
    let text = value.repr().and_then(|r| r.extract::<String>()).unwrap_or_else(|_| "<value>".into());
    let chars = text.chars().count();
    if chars <= 60 {
        return text;
    }
    format!("{}...({chars} characters)", text.chars().take(40).collect::<String>())
}

/// An integer argument `name` of a call: a Python int or a NumPy integer (never a bool, a float or
/// a string: TypeError naming it), in `lo..=hi` (else StictionError naming it, with its value and
/// the domain `what`), checked before any work.
pub(crate) fn count(name: &str, value: &Bound<'_, PyAny>, lo: u64, hi: u64, what: &str) -> PyResult<u64> {
    let domain = if hi == u64::MAX { format!("an integer >= {lo}") } else { format!("an integer in {lo}..={hi}") };
    let domain = if what.is_empty() { domain } else { format!("{domain} ({what})") };
    let numpy_bool = value.hasattr("dtype")?
        && value.getattr("dtype")?.getattr("kind").and_then(|k| k.extract::<String>()).is_ok_and(|k| k == "b");
    if value.is_instance_of::<pyo3::types::PyBool>() || numpy_bool {
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "{name}={}: expected {domain}, got a bool",
            short_repr(value)
        )));
    }
    let index = value.call_method0("__index__").map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{name}={}: expected {domain}, got {}",
            short_repr(value),
            value.get_type().name().map_or_else(|_| "?".to_string(), |n| n.to_string())
        ))
    })?;
    match index.extract::<i128>() {
        Ok(v) if v >= i128::from(lo) && v <= i128::from(hi) => Ok(v as u64),
        _ => Err(err(format!("{name}={}: expected {domain}", short_repr(&index)))),
    }
}

/// _count(name, value, lo, hi=None, what="") -> int: [`count`] for the Python wrappers (the
/// integer arguments they turn into command-line flags).
#[pyfunction]
#[pyo3(signature = (name, value, lo, hi=None, what=""))]
pub(crate) fn _count(name: &str, value: &Bound<'_, PyAny>, lo: u64, hi: Option<u64>, what: &str) -> PyResult<u64> {
    count(name, value, lo, hi.unwrap_or(u64::MAX), what)
}

/// A vector argument `name` as f64s: a NumPy array or a sequence of numbers, its number of values
/// checked by `check` BEFORE it is converted or copied (a list of ten million floats is refused
/// at once), then read as float64 (flat, any shape, when `flat`; else at most one dimension).
/// Values that are not numbers: StictionError naming the argument.
pub(crate) fn vector(
    name: &str,
    obj: &Bound<'_, PyAny>,
    flat: bool,
    check: &dyn Fn(usize) -> Result<(), String>,
) -> PyResult<Vec<f64>> {
    let np = obj.py().import("numpy")?;
    let ndarray = np.getattr("ndarray")?;
    let known = if obj.is_instance(&ndarray)? { obj.getattr("size")?.extract::<usize>().ok() } else { obj.len().ok() };
    if let Some(n) = known {
        check(n).map_err(err)?;
    }
    let kwargs = PyDict::new(obj.py());
    kwargs.set_item("dtype", np.getattr("float64")?)?;
    let array = np.call_method("asarray", (obj,), Some(&kwargs)).map_err(|e| {
        err(format!("{name}: expected numbers (a list or a NumPy array of floats), got {} ({e})", short_repr(obj)))
    })?;
    let ndim: usize = array.getattr("ndim")?.extract()?;
    if !flat && ndim > 1 {
        return Err(err(format!("{name}: expected a 1-D list of numbers, got {ndim} dimensions")));
    }
    let size: usize = array.getattr("size")?.extract()?;
    check(size).map_err(err)?;
    let flat_array = array.call_method0("ravel")?;
    let values: numpy::PyReadonlyArray1<'_, f64> = flat_array.extract()?;
    Ok(values.as_array().iter().copied().collect())
}

/// `json.loads(text)`: the Python value of a JSON text, as a script parsing `--json` gets it.
fn json_loads<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// A JSON value as the Python object `json.loads` makes of its text (null: None; true/false: bool;
/// an integer: int; any other number: float; lists and objects: list and dict, in order), built
/// directly, without the text and its float parsing in between: the numbers are the same f64s.
/// Python's cyclic garbage collector is paused while the tree is built (a JSON tree has no
/// cycles; a sweep's thousands of new dicts and lists would otherwise set off collections that
/// walk them), and each distinct key is made into a Python string once (the points of a sweep
/// repeat the same keys).
pub(crate) fn to_py<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    let gc = py.import("gc")?;
    let was_enabled = gc.call_method0("isenabled")?.is_truthy()?;
    if was_enabled {
        gc.call_method0("disable")?;
    }
    let mut keys = std::collections::HashMap::new();
    let out = to_py_with(py, value, &mut keys);
    if was_enabled {
        gc.call_method0("enable")?;
    }
    out
}

/// [`to_py`] with the key strings made so far.
fn to_py_with<'py, 'v>(
    py: Python<'py>,
    value: &'v serde_json::Value,
    keys: &mut std::collections::HashMap<&'v str, Bound<'py, PyString>>,
) -> PyResult<Bound<'py, PyAny>> {
    use serde_json::Value;
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => pyo3::types::PyBool::new(py, *b).to_owned().into_any(),
        Value::Number(n) => match (n.as_i64(), n.as_u64()) {
            (Some(i), _) => i.into_pyobject(py)?.into_any(),
            (None, Some(u)) => u.into_pyobject(py)?.into_any(),
            (None, None) => pyo3::types::PyFloat::new(py, n.as_f64().unwrap_or(f64::NAN)).into_any(),
        },
        Value::String(text) => PyString::new(py, text).into_any(),
        Value::Array(items) => {
            let list = pyo3::types::PyList::empty(py);
            for item in items {
                list.append(to_py_with(py, item, keys)?)?;
            }
            list.into_any()
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (key, item) in map {
                let item = to_py_with(py, item, keys)?;
                let key = keys.entry(key.as_str()).or_insert_with(|| PyString::new(py, key));
                dict.set_item(&*key, item)?;
            }
            dict.into_any()
        }
    })
}

/// A result's JSON object held as the engine made it; its fields become Python objects when they
/// are read (`get`), so that a call hands over its result without building every number and
/// point of it at once (a load sweep's thousands of dicts are built when `points` is read).
#[pyclass(name = "Json", module = "stiction._stiction", frozen)]
pub(crate) struct PyJson {
    value: serde_json::Value,
}

#[pymethods]
impl PyJson {
    /// get(key): the field `key` of the object as `json.loads` would give it (KeyError if absent).
    fn get<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.value.get(key) {
            Some(v) => to_py(py, v),
            None => Err(pyo3::exceptions::PyKeyError::new_err(key.to_string())),
        }
    }

    /// keys(): the fields of the object, in order.
    fn keys(&self) -> Vec<String> {
        self.value.as_object().map(|m| m.keys().cloned().collect()).unwrap_or_default()
    }

    /// to_py(): the whole object as `json.loads` of its text gives it (a fresh copy).
    fn to_py<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.value)
    }

    /// to_json(): the object as compact JSON text (the command line's numbers, printed by the same
    /// serializer).
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.value).map_err(err)
    }
}

/// A result's JSON object as a [`PyJson`].
pub(crate) fn json_object(py: Python<'_>, value: serde_json::Value) -> PyResult<Bound<'_, PyAny>> {
    Ok(Bound::new(py, PyJson { value })?.into_any())
}

/// A scenario (the device, its surface and material, the meter; docs/scenario.md): a file
/// (`Scenario.load(path, sets)`), a dict shaped as the file (`Scenario.from_dict(d, base_dir)`)
/// or its JSON text (`Scenario.from_json`), with `set(path, value)` overrides applied in order
/// (`--set PATH=VALUE`: unit strings such as "50 nm" or SI numbers). Every function that takes a
/// scenario also takes a path or a plain dict. Relative paths in a file are read from the file's
/// folder; in a dict or a text, from `base_dir`, by default the current directory. Errors are
/// `StictionError` with the command line's messages; a scenario built in memory is named
/// "<scenario>" in them.
#[pyclass(name = "Scenario", module = "stiction._stiction", from_py_object)]
#[derive(Clone)]
pub(crate) struct PyScenario {
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

    /// The scenario as the commands read it: the file (read now) or the text, with the overrides.
    fn source(&self) -> Result<ScenarioSource, ScenarioError> {
        match &self.path {
            Some(p) => ScenarioSource::file(p, &self.sets),
            None => ScenarioSource::text(
                self.text.as_deref().unwrap_or("{}"),
                Path::new("<scenario>"),
                &self.base,
                &self.sets,
            ),
        }
    }

    /// Parses and validates, as the command line does.
    fn parse(&self) -> Result<Scenario, ScenarioError> {
        self.source()?.parse(&[])
    }

    fn from_path(path: PathBuf) -> PyScenario {
        let base = path.parent().map(PathBuf::from).unwrap_or_default();
        PyScenario { path: Some(path), text: None, base, sets: Vec::new() }
    }

    /// A `Scenario`, a dict shaped as a scenario file (its relative paths from the current
    /// directory, as `Scenario.from_dict(d)`), or a path (str or os.PathLike) to a scenario file.
    fn extract(obj: &Bound<'_, PyAny>) -> PyResult<PyScenario> {
        if let Ok(s) = obj.cast::<PyScenario>() {
            return Ok(s.borrow().clone());
        }
        if obj.is_instance_of::<PyDict>() {
            return PyScenario::from_dict(obj, None);
        }
        let os = obj.py().import("os")?;
        let path: String = os.call_method1("fspath", (obj,)).and_then(|p| p.extract()).map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(
                "expected a stiction.Scenario, a dict shaped as a scenario file, or a path to a scenario file",
            )
        })?;
        Ok(PyScenario::from_path(PathBuf::from(path)))
    }

    /// The scenario source of a call's argument, checked (StictionError with the CLI's message).
    pub(crate) fn source_of(obj: &Bound<'_, PyAny>) -> PyResult<ScenarioSource> {
        PyScenario::extract(obj)?.source().map_err(err)
    }
}

/// A value for `--set PATH=VALUE` or a quantity flag: a string as given, an integer (Python's or
/// NumPy's) in decimal, any other number as the `repr` of the Python float it converts to (which
/// reads back to the same float; NumPy 2's own repr, `np.float64(0.5)`, would not parse),
/// True/False/None as JSON, lists and dicts as JSON.
pub(crate) fn flag_text(value: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(s) = value.cast::<PyString>() {
        return s.extract::<String>();
    }
    if value.is_none() {
        return Ok("null".into());
    }
    // Python's bool, and NumPy's (a scalar of dtype kind "b").
    let numpy_bool = value.hasattr("dtype")?
        && value.getattr("dtype")?.getattr("kind").and_then(|k| k.extract::<String>()).is_ok_and(|k| k == "b");
    if value.is_instance_of::<pyo3::types::PyBool>() || numpy_bool {
        let b: bool = value.call_method0("__bool__")?.extract()?;
        return Ok(if b { "true" } else { "false" }.into());
    }
    // Python's int and NumPy's integers (they have __index__; floats have not).
    if (value.is_instance_of::<pyo3::types::PyInt>() || value.hasattr("__index__")?)
        && let Ok(i) = value.call_method0("__index__").and_then(|i| i.extract::<i128>())
    {
        return Ok(i.to_string());
    }
    if let Ok(f) = value.extract::<f64>() {
        return pyo3::types::PyFloat::new(value.py(), f).repr()?.extract::<String>();
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

    /// Scenario.from_json(text, base_dir=None): a scenario from its JSON text; relative paths in it
    /// (surface CSVs, height maps, measured voltages) are read from `base_dir`, by default the
    /// current directory.
    #[staticmethod]
    #[pyo3(signature = (text, base_dir=None))]
    fn from_json(text: String, base_dir: Option<PathBuf>) -> PyResult<PyScenario> {
        let s = PyScenario { path: None, text: Some(text), base: base_dir.unwrap_or_default(), sets: Vec::new() };
        s.parse().map_err(err)?;
        Ok(s)
    }

    /// Scenario.from_dict(d, base_dir=None): a scenario from a dict shaped as the JSON file
    /// (quantities as unit strings, "0.5 um", or SI numbers); relative paths in it (surface
    /// CSVs, height maps, measured voltages) are read from `base_dir`, by default the current
    /// directory.
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

    /// validate(): check the scenario as `stiction scenario FILE` does (parsed and validated; a
    /// height-map sidewall's map read and prepared as `run` reads it); returns the notes (list of
    /// (code, message)) or raises StictionError with the command line's message.
    fn validate(&self) -> PyResult<Vec<(String, String)>> {
        let s = stiction_engine::scenario::check(&self.source().map_err(err)?).map_err(err)?;
        Ok(s.notes.iter().map(|n| (n.code.to_string(), n.message.clone())).collect())
    }

    /// to_json(): the scenario as it is run, as `stiction scenario FILE` prints it: every field
    /// the file or `set` gave, as written (units kept), and every default the parse filled in, in
    /// SI (readable back with Scenario.from_json).
    fn to_json(&self) -> PyResult<String> {
        let s = self.parse().map_err(err)?;
        serde_json::to_string_pretty(&s.to_input_json()).map_err(err)
    }

    /// get(path): a field of the scenario as it is run, as `to_dict()` holds it: as written in the
    /// file or by `set` (get("surface.summit_sd") -> "0.04 um"; an SI number stays a number), or
    /// the default the parse filled in (SI); a section comes back as a dict. `path` is dotted as
    /// `set` takes it (a list item by its index, "meter.clamp_voltages.0"). Raises StictionError
    /// when the path names nothing in this scenario.
    fn get<'py>(&self, py: Python<'py>, path: &str) -> PyResult<Bound<'py, PyAny>> {
        let mut node = self.parse().map_err(err)?.to_input_json();
        for seg in path.split('.') {
            let next = match node {
                serde_json::Value::Object(mut m) => m.remove(seg),
                serde_json::Value::Array(mut a) => {
                    seg.parse::<usize>().ok().filter(|&i| i < a.len()).map(|i| a.swap_remove(i))
                }
                _ => None,
            };
            node = next.ok_or_else(|| {
                err(format!("{path}: no field `{seg}` in this scenario (the fields as run, in SI: to_dict())"))
            })?;
        }
        to_py(py, &node)
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

/// run(scenario, progress=None) -> dict: the JSON object `stiction run SCENARIO --json` prints.
/// `progress(done, total)` is called after each clamp voltage. The GIL is released while the
/// meter runs (it is taken back only for the callback).
#[pyfunction]
#[pyo3(signature = (scenario, progress=None))]
pub(crate) fn run_json<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let source = PyScenario::source_of(scenario)?;
    let parsed = source.parse(&[]).map_err(err)?;
    let name = source.name();
    let progress = Progress::new(progress);
    let report = progress.clone();
    let out = interruptible(py, move |_| {
        let mut on_point = |done: usize, total: usize| {
            report.report(done, total);
        };
        stiction_engine::run::run_json(&parsed, &name, &source.base, &mut on_point).map_err(|e| e.to_string())
    })?;
    if let Some(e) = progress.take_error() {
        return Err(e);
    }
    json_object(py, out.map_err(err)?)
}

/// A length flag value: a unit string ("3.9 um") or an SI number, checked as the command line
/// checks it (finite, > 0).
pub(crate) fn length(name: &str, value: Option<&Bound<'_, PyAny>>) -> PyResult<Option<f64>> {
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

/// The heights of a 2-D float32/float64 NumPy array as a height map in metres, read in place
/// (no copy of the array, whatever its order or strides: [`read_array`]) while the GIL is held, so
/// that no Python code writes the array while it is read. A view that is not contiguous (`a[:, ::2]`)
/// is read through its strides as well.
pub(crate) fn read_heights(heights: &Bound<'_, PyAny>, meta: &MapMetadata) -> PyResult<(HeightMap, MapInfo)> {
    if let Ok(a) = heights.extract::<PyReadonlyArray2<'_, f64>>() {
        let (data, layout) = in_place(a.as_array());
        return read_array(BorrowedHeights::F64(data), layout, "heights", meta).map_err(err);
    }
    if let Ok(a) = heights.extract::<PyReadonlyArray2<'_, f32>>() {
        let (data, layout) = in_place(a.as_array());
        return read_array(BorrowedHeights::F32(data), layout, "heights", meta).map_err(err);
    }
    Err(err("heights: expected a 2-D NumPy array of float32 or float64 (rows = y)"))
}

/// The memory of a 2-D view as a slice (from its lowest to its highest element) and where its
/// elements lie in it: strides in elements, negative ones included, without a copy.
fn in_place<'a, T>(view: numpy::ndarray::ArrayView2<'a, T>) -> (&'a [T], ArrayLayout) {
    let (ny, nx) = view.dim();
    let (rs, cs) = (view.strides()[0], view.strides()[1]);
    let reach = |len: usize, stride: isize| len.saturating_sub(1) * stride.unsigned_abs();
    // Element (0, 0) lies this many elements above the lowest address (negative strides).
    let offset = if rs < 0 { reach(ny, rs) } else { 0 } + if cs < 0 { reach(nx, cs) } else { 0 };
    let layout = ArrayLayout { ny, nx, row_stride: rs, col_stride: cs, offset };
    if ny == 0 || nx == 0 {
        return (&[], layout);
    }
    let len = reach(ny, rs) + reach(nx, cs) + 1;
    // SAFETY: a NumPy array (and so the view of it) holds every element between the lowest and the
    // highest address of its elements, which is `len` elements from `as_ptr() - offset`; the view
    // borrows the array for 'a (a readonly borrow, so no Rust code writes it), and the caller holds
    // the GIL while it reads, so no Python thread writes it either.
    let data = unsafe { std::slice::from_raw_parts(view.as_ptr().sub(offset), len) };
    (data, layout)
}

/// topography(heights, ...) -> (json text, summits): see the Python wrapper's docstring.
#[pyfunction]
#[pyo3(signature = (heights, pixel_size=None, pixel_size_y=None, height_unit=None, level="plane", cutoff=None, long_cutoff=None, scenario=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn topography_json<'py>(
    py: Python<'py>,
    heights: &Bound<'py, PyAny>,
    pixel_size: Option<&Bound<'py, PyAny>>,
    pixel_size_y: Option<&Bound<'py, PyAny>>,
    height_unit: Option<&Bound<'py, PyAny>>,
    level: &str,
    cutoff: Option<&Bound<'py, PyAny>>,
    long_cutoff: Option<&Bound<'py, PyAny>>,
    scenario: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyDict>)> {
    let scenario = scenario.filter(|s| !s.is_none()).map(PyScenario::source_of).transpose()?;
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
    let (raw, info) = read_heights(heights, &meta)?;
    let out = py.detach(|| -> Result<_, String> {
        let (json, map, summits) =
            stiction_engine::topography::topography_json("<array>", raw, info, &prep, scenario.as_ref())
                .map_err(|e| e.to_string())?;
        Ok((json, map, summits))
    });
    let (json, map, s): (serde_json::Value, HeightMap, _) = out.map_err(err)?;
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
    Ok((json_object(py, json)?, d))
}

/// Runs `work` on a worker thread with the GIL released, while the calling thread waits and
/// checks Python's signal handlers every 50 ms: Ctrl-C (KeyboardInterrupt, or any exception a
/// signal handler raises) sets the flag `work` is given (a study stops at the next sample), waits
/// at most half a second more for the worker and raises; a worker still running then finishes in
/// the background and its result is dropped (it owns everything it touches, so nothing a caller
/// holds is left half-written).
pub(crate) fn interruptible<T: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce(&AtomicBool) -> T + Send + 'static,
) -> PyResult<T> {
    let interrupt = Arc::new(AtomicBool::new(false));
    let (tx, rx) = std::sync::mpsc::channel();
    let flag = Arc::clone(&interrupt);
    std::thread::Builder::new()
        .name("stiction-call".into())
        .spawn(move || {
            let start = std::time::Instant::now();
            let out = work(&flag);
            LAST_ENGINE_NANOS.store(start.elapsed().as_nanos() as u64, Ordering::Relaxed);
            let _ = tx.send(out);
        })
        .map_err(|e| err(format!("cannot start a worker thread: {e}")))?;
    // The receiver goes into each GIL-free wait and comes back (it is Send, not Sync).
    let mut rx = rx;
    loop {
        let (back, got) = py.detach(move || {
            let got = rx.recv_timeout(Duration::from_millis(50));
            (rx, got)
        });
        rx = back;
        match got {
            Ok(v) => return Ok(v),
            Err(RecvTimeoutError::Disconnected) => return Err(err("internal error: the worker thread panicked")),
            Err(RecvTimeoutError::Timeout) => {}
        }
        if let Err(e) = py.check_signals() {
            interrupt.store(true, Ordering::Relaxed);
            let _ = py.detach(move || rx.recv_timeout(Duration::from_millis(500)).is_ok());
            return Err(e);
        }
    }
}

/// How long the last call's engine work took on its worker thread, ns (for the overhead benchmark).
static LAST_ENGINE_NANOS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// _last_engine_seconds() -> float: the engine time of the last long call (run, study, contact,
/// bem, fit) on its worker thread, without the binding (arguments, thread, JSON to Python).
#[pyfunction]
pub(crate) fn _last_engine_seconds() -> f64 {
    LAST_ENGINE_NANOS.load(Ordering::Relaxed) as f64 * 1e-9
}

/// A progress callback for a worker thread: `cb(done, total)` with the GIL taken for the call;
/// the first exception it raises is kept (and stops a study through `stop`).
#[derive(Clone)]
pub(crate) struct Progress {
    cb: Option<Arc<Py<PyAny>>>,
    error: Arc<Mutex<Option<PyErr>>>,
}

impl Progress {
    pub(crate) fn new(cb: Option<Py<PyAny>>) -> Progress {
        Progress { cb: cb.map(Arc::new), error: Arc::new(Mutex::new(None)) }
    }

    pub(crate) fn report(&self, done: usize, total: usize) -> bool {
        let Some(cb) = &self.cb else { return true };
        let mut error = self.error.lock().unwrap_or_else(|e| e.into_inner());
        if error.is_some() {
            return false;
        }
        Python::attach(|py| {
            if let Err(e) = cb.call1(py, (done, total)) {
                *error = Some(e);
            }
        });
        error.is_none()
    }

    pub(crate) fn take_error(&self) -> Option<PyErr> {
        self.error.lock().unwrap_or_else(|e| e.into_inner()).take()
    }
}

/// study_json(scenario, samples=100, seed=1, threads=None, fixed_surface=False, progress=None)
/// -> (summary JSON text, samples CSV text): the JSON `stiction study SCENARIO --json --samples N
/// --seed S --threads T` prints (same seed, same numbers, whatever the thread count), and the
/// samples as `stiction study --out` writes samples.csv. The scenario is a file or one built from
/// a dict (its relative paths from its base_dir). The GIL is released; Ctrl-C stops the study.
#[pyfunction]
#[pyo3(signature = (scenario, samples=None, seed=None, threads=None, fixed_surface=false, progress=None))]
pub(crate) fn study_json<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    samples: Option<&Bound<'py, PyAny>>,
    seed: Option<&Bound<'py, PyAny>>,
    threads: Option<&Bound<'py, PyAny>>,
    fixed_surface: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    // The counts first, named as the arguments (the command line's checks follow, their flags
    // named the same way): nothing is read or allocated for a refused call.
    const NAMES: &[&str] = &["samples", "seed", "threads"];
    let named = err_named(NAMES);
    let max_samples = stiction_engine::limits::max_samples() as u64;
    // None: the command line's defaults (100 samples, seed 1).
    let samples = match samples.filter(|s| !s.is_none()) {
        Some(s) => count(
            "samples",
            s,
            1,
            u64::MAX,
            &format!("at most {max_samples} per study; STICTION_MAX_SAMPLES raises the limit"),
        )?,
        None => 100,
    };
    let samples = usize::try_from(samples).unwrap_or(usize::MAX);
    let seed = match seed.filter(|s| !s.is_none()) {
        Some(s) => count("seed", s, 0, u64::MAX, "")?,
        None => 1,
    };
    let max_threads = stiction_engine::limits::MAX_THREADS as u64;
    let threads = match threads.filter(|t| !t.is_none()) {
        Some(t) => Some(count("threads", t, 1, max_threads, "worker threads; None: one per core")? as usize),
        None => None,
    };
    // The command line's study request (nominal calibration, light slip path, one shard).
    let config = StudyRequest { samples, seed, fixed_surface, threads, ..StudyRequest::default() }
        .config()
        .map_err(|e| named(e.to_string()))?;
    let pool =
        stiction_engine::study::thread_pool(threads, &|f: &str| f.to_string()).map_err(|e| named(e.to_string()))?;
    let source = PyScenario::source_of(scenario)?;
    let study = stiction_engine::study::prepare_source(&source, &config).map_err(err)?;
    let progress = Progress::new(progress);
    let report = progress.clone();
    let out = interruptible(py, move |interrupt| {
        let total = study.config.shard_len();
        // An exception of the callback stops the study as Ctrl-C does (and is raised).
        let on_sample = |done: usize| {
            if !report.report(done, total) {
                interrupt.store(true, Ordering::Relaxed);
            }
        };
        let mut csv = Vec::new();
        let summary = stiction_engine::study::study_json_of(&study, &pool, &on_sample, interrupt, Some(&mut csv))
            .map_err(|e| e.to_string())?;
        Ok::<_, String>((summary, String::from_utf8_lossy(&csv).into_owned()))
    })?;
    if let Some(e) = progress.take_error() {
        return Err(e);
    }
    match out.map_err(err)? {
        (Some(json), csv) => Ok((json_object(py, json)?, csv)),
        (None, _) => {
            // Stopped by Ctrl-C between the worker's end and the last check: raise it now.
            py.check_signals()?;
            Err(pyo3::exceptions::PyKeyboardInterrupt::new_err("the study was interrupted"))
        }
    }
}

/// _limits() -> dict: the command line's limits that the functions apply to their array and
/// count arguments (the same constants the commands check; `max_samples` as
/// STICTION_MAX_SAMPLES sets it now).
#[pyfunction]
pub(crate) fn _limits(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    use stiction_engine::limits::*;
    let d = PyDict::new(py);
    d.set_item("max_sweep_steps", DEFAULT_MAX_SWEEP_STEPS)?;
    d.set_item("bem_max_path_steps", BEM_MAX_PATH_STEPS)?;
    d.set_item("bem_max_grid_side", BEM_MAX_GRID_SIDE)?;
    d.set_item("max_rh", MAX_RH)?;
    d.set_item("max_samples", max_samples())?;
    d.set_item("max_threads", MAX_THREADS)?;
    d.set_item("fit_max_surfaces", MAX_SURFACES)?;
    d.set_item("fit_max_draws", MAX_DRAWS)?;
    d.set_item("fit_max_rows", MAX_FIT_ROWS)?;
    Ok(d)
}

/// The Rust heap of the extension, counted: bytes in use and the peak since the last reset, so
/// that a test can see how much a call allocates (a copy of a 4096^2 input is 128 MiB). The count
/// costs two relaxed atomic operations per allocation.
mod heap {
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

    pub struct Counting;
    pub static IN_USE: AtomicUsize = AtomicUsize::new(0);
    pub static PEAK: AtomicUsize = AtomicUsize::new(0);

    fn grew(by: usize) {
        let now = IN_USE.fetch_add(by, Relaxed) + by;
        PEAK.fetch_max(now, Relaxed);
    }

    // SAFETY: every call is forwarded to the system allocator unchanged; only counters are kept.
    unsafe impl GlobalAlloc for Counting {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            let p = unsafe { System.alloc(layout) };
            if !p.is_null() {
                grew(layout.size());
            }
            p
        }
        unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
            let p = unsafe { System.alloc_zeroed(layout) };
            if !p.is_null() {
                grew(layout.size());
            }
            p
        }
        unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
            unsafe { System.dealloc(ptr, layout) };
            IN_USE.fetch_sub(layout.size(), Relaxed);
        }
        unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
            let p = unsafe { System.realloc(ptr, layout, new_size) };
            if !p.is_null() {
                if new_size >= layout.size() {
                    grew(new_size - layout.size());
                } else {
                    IN_USE.fetch_sub(layout.size() - new_size, Relaxed);
                }
            }
            p
        }
    }

    #[global_allocator]
    static ALLOCATOR: Counting = Counting;
}

/// _heap() -> (bytes in use, peak bytes since the last reset) of the extension's Rust heap.
#[pyfunction]
pub(crate) fn _heap() -> (usize, usize) {
    use std::sync::atomic::Ordering::Relaxed;
    (heap::IN_USE.load(Relaxed), heap::PEAK.load(Relaxed))
}

/// _reset_heap_peak(): the peak becomes the bytes in use now.
#[pyfunction]
pub(crate) fn _reset_heap_peak() {
    use std::sync::atomic::Ordering::Relaxed;
    heap::PEAK.store(heap::IN_USE.load(Relaxed), Relaxed);
}

/// _read_heights(heights, pixel_size, height_unit) -> (nx, ny): the input step of `topography`
/// and `bem` alone (the array read into a map in metres), for the memory test.
#[pyfunction]
pub(crate) fn _read_heights(heights: &Bound<'_, PyAny>, pixel_size: f64, height_unit: f64) -> PyResult<(usize, usize)> {
    let meta = MapMetadata { pixel_size_x_m: Some(pixel_size), height_unit_m: Some(height_unit), ..Default::default() };
    let (map, _) = read_heights(heights, &meta)?;
    Ok((map.nx(), map.ny()))
}
