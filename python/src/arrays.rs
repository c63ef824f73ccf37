//! Arrays handed in from Python (a network's results, a trajectory's samples), read as real
//! float64 arrays of the expected rank, with errors that name the field: lists and integer
//! arrays are converted; complex, boolean, object and string data, ragged lists and arrays of
//! the wrong rank are refused (numpy's own cast would drop an imaginary part silently).

use numpy::ndarray::{Array, Dimension};
use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

/// `value` as a float64 array of the rank of `D` (`Ix1`, `Ix2`); `what` names it in errors.
pub fn real_array<D: Dimension>(value: &Bound<'_, PyAny>, what: &str) -> PyResult<Array<f64, D>> {
    let ndim = D::NDIM.unwrap_or(0);
    let py = value.py();
    let numpy = py.import("numpy")?;
    let array = numpy.call_method1("asarray", (value,)).map_err(|e| {
        PyTypeError::new_err(format!(
            "{what} must be an array of real numbers ({})",
            e.value(py)
        ))
    })?;
    let dtype = array.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "i" | "u" | "f") {
        return Err(PyTypeError::new_err(format!(
            "{what} must be real numbers, got an array of dtype {}",
            dtype.str()?
        )));
    }
    let array = array
        .call_method1("astype", (numpy.getattr("float64")?,))?
        .cast_into::<PyArrayDyn<f64>>()?;
    if array.ndim() != ndim {
        return Err(PyValueError::new_err(format!(
            "{what} must be a {ndim}-D array, got shape {:?}",
            array.shape()
        )));
    }
    array
        .readonly()
        .as_array()
        .to_owned()
        .into_dimensionality::<D>()
        .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))
}
