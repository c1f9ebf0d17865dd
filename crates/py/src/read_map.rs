//! `read_map(path, ...)`: a height-map file (any format stiction reads) as a NumPy array with its
//! metadata. The logic is `stiction_engine::topography::read_with_metadata`; this file only converts.

use std::path::PathBuf;

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use stiction_engine::topography::{ChannelSelector, MapFormat, MapMetadata, parse_length_unit, read_with_metadata};

/// The error of the argument `name` given as `value` (StictionError, as every other bad input).
fn arg_error<'a>(name: &'a str, value: &'a str) -> impl Fn(String) -> PyErr + 'a {
    move |e| crate::binding::err(format!("{name}={value:?}: {e}"))
}

/// _read_map(path, format, channel, pixel_size, height_unit) -> (heights (ny, nx) float64 in
/// metres, NaN where missing; metadata JSON text). The heights' buffer is moved into the array,
/// not copied.
#[pyfunction]
#[pyo3(signature = (path, format=None, channel=None, pixel_size=None, height_unit=None))]
pub(crate) fn _read_map<'py>(
    py: Python<'py>,
    path: PathBuf,
    format: Option<&str>,
    channel: Option<&str>,
    pixel_size: Option<&str>,
    height_unit: Option<&str>,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let format: Option<MapFormat> =
        format.map(|f| f.parse().map_err(|e: String| arg_error("format", f)(e))).transpose()?;
    let channel: Option<ChannelSelector> =
        channel.map(|c| c.parse().map_err(|e: String| arg_error("channel", c)(e))).transpose()?;
    let height_unit_m = height_unit
        .map(|u| parse_length_unit(u).map_err(|e| arg_error("height_unit", u)(e.to_string())))
        .transpose()?;
    let pixel_size_m = pixel_size
        .map(|p| {
            stiction_units::parse_quantity(p, stiction_units::Dimension::Length)
                .map_err(|e| arg_error("pixel_size", p)(e.to_string()))
        })
        .transpose()?;
    let meta = MapMetadata { pixel_size_x_m: pixel_size_m, height_unit_m, ..Default::default() };
    let (heights, m) = py
        .detach(|| read_with_metadata(&path, format, channel.as_ref(), &meta).map_err(|e| e.to_string()))
        .map_err(crate::binding::StictionError::new_err)?;
    let json = serde_json::to_string(&m).map_err(crate::binding::err)?;
    let array = PyArray1::from_vec(py, heights).reshape([m.ny, m.nx])?;
    Ok((array.into_any(), json))
}
