//! The extension module `stiction._stiction`: its functions and classes.

use pyo3::prelude::*;

use crate::{binding, requests};

/// The extension module `stiction._stiction`.
#[pymodule]
fn _stiction(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("StictionError", m.py().get_type::<binding::StictionError>())?;
    m.add_class::<binding::PyScenario>()?;
    m.add_class::<binding::PyJson>()?;
    m.add_function(wrap_pyfunction!(binding::run_json, m)?)?;
    m.add_function(wrap_pyfunction!(binding::topography_json, m)?)?;
    m.add_function(wrap_pyfunction!(crate::read_map::_read_map, m)?)?;
    m.add_function(wrap_pyfunction!(binding::study_json, m)?)?;
    m.add_function(wrap_pyfunction!(requests::gw_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(requests::discrete_json, m)?)?;
    m.add_function(wrap_pyfunction!(requests::contact_json, m)?)?;
    m.add_function(wrap_pyfunction!(requests::bem_json, m)?)?;
    m.add_function(wrap_pyfunction!(requests::humidity_json, m)?)?;
    m.add_function(wrap_pyfunction!(requests::fit_json, m)?)?;
    m.add_function(wrap_pyfunction!(binding::_heap, m)?)?;
    m.add_function(wrap_pyfunction!(binding::_count, m)?)?;
    m.add_function(wrap_pyfunction!(binding::_limits, m)?)?;
    m.add_function(wrap_pyfunction!(binding::_last_engine_seconds, m)?)?;
    m.add_function(wrap_pyfunction!(binding::_reset_heap_peak, m)?)?;
    m.add_function(wrap_pyfunction!(binding::_read_heights, m)?)?;
    Ok(())
}
