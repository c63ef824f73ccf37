//! A network written in Python, run by the library as any `NeuralSolver`.
//!
//! The Python object gives its state dimension and its dynamics ydot = F(t, y; QP(t)) over numpy
//! arrays; the QP is handed over as a dict of arrays in the form of `qp::Qp`:
//!
//! ```text
//! min x'Px/2 + q'x   s.t.   A x = b,   G x <= h,   lower <= x <= upper
//! ```
//!
//! with keys `P, q, A, b, G, h, lower, upper` (infinite bounds as +-inf). Where the network sets
//! `needs_qp_dot = True`, `rhs` and `jacobian` also get dQP/dt (every field differentiated) as a
//! fourth argument. A `jacobian` method (dF/dy with the QP frozen) is optional: without it, or
//! where it returns None, the library differences F. Only these calls cross into Python: the
//! arm, the scheme, the integrator and the exact scoring stay in Rust.
//!
//! A result that is not a real array of the state's size, or that holds NaN or inf, is an
//! exception of the call (a NaN would leave the integrator shrinking its step for ever).
//! A Python exception inside a call cannot unwind through the integrator: from then on the
//! network answers ydot = 0 (and a zero Jacobian) without calling Python, so the run ends at
//! once with the network frozen (NaN would leave the integrator shrinking its step), and the
//! first exception is kept ([`Callbacks::take_error`])
//! to be raised to the caller once the run has stopped. Ctrl-C is one such exception: each call
//! first lets the interpreter run its signal handlers, so a pending SIGINT raises
//! `KeyboardInterrupt` (unwrapped) and the run stops at its next call into Python.

use crate::arrays::real_array;
use nalgebra::{DMatrix, DVector};
use numpy::ndarray::{Ix1, Ix2};
use numpy::IntoPyArray;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use qp::{Qp, QpDims};
use solvers::neural::NeuralSolver;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// The sizes of a task's QP, handed to a network's `state_dim` and `handles` (and a task's
/// `dims`): x has `nx` entries, the joint command x[:dof] first, then the scheme's auxiliary
/// variables.
#[pyclass(name = "QpDims", module = "driftbench", frozen, get_all)]
#[derive(Clone, Copy)]
pub struct PyQpDims {
    /// Unknowns of the QP (the joint command first).
    pub nx: usize,
    /// Equality rows (A x = b).
    pub n_eq: usize,
    /// Inequality rows (G x <= h).
    pub n_in: usize,
}

#[pymethods]
impl PyQpDims {
    fn __repr__(&self) -> String {
        format!(
            "QpDims(nx={}, n_eq={}, n_in={})",
            self.nx, self.n_eq, self.n_in
        )
    }
}

impl PyQpDims {
    /// `nx = .., n_eq = .., n_in = ..`, for messages.
    pub fn describe(&self) -> String {
        format!(
            "nx = {}, n_eq = {}, n_in = {}",
            self.nx, self.n_eq, self.n_in
        )
    }
}

impl From<QpDims> for PyQpDims {
    fn from(d: QpDims) -> Self {
        PyQpDims {
            nx: d.nx,
            n_eq: d.n_eq,
            n_in: d.n_in,
        }
    }
}

/// What the Python calls of one run cost, and the first exception they raised.
#[derive(Default)]
pub struct Callbacks {
    error: Option<PyErr>,
    /// Calls of `rhs` and `jacobian`.
    pub calls: usize,
    /// Wall time spent in them, the conversions of arguments and results included.
    pub seconds: f64,
}

impl Callbacks {
    /// The first exception of the run, if any.
    pub fn take_error(&mut self) -> Option<PyErr> {
        self.error.take()
    }

    /// Keeps `e` unless an earlier exception is kept.
    pub fn keep_error(&mut self, e: PyErr) {
        self.error.get_or_insert(e);
    }
}

/// The shared record of a run's calls (the library builds the network twice: the network and a
/// probe that reads its error norm).
pub type SharedCallbacks = Arc<Mutex<Callbacks>>;

/// A Python network (module docs).
pub struct PyNetwork {
    object: Py<PyAny>,
    name: String,
    state_dim: usize,
    needs_qp_dot: bool,
    has_jacobian: bool,
    has_error_norm: bool,
    callbacks: SharedCallbacks,
}

/// The network's display name: its `name` attribute, else its class name.
pub fn network_name(object: &Bound<'_, PyAny>) -> PyResult<String> {
    match object.getattr_opt("name")? {
        Some(name) => name.extract(),
        None => Ok(object.get_type().name()?.to_string()),
    }
}

impl PyNetwork {
    /// Reads the network's interface for QPs of sizes `dims`: `state_dim` (an int, or a method
    /// of the dims), `needs_qp_dot` (default False), whether it has `jacobian` and `error_norm`.
    pub fn new(
        object: &Bound<'_, PyAny>,
        dims: QpDims,
        callbacks: SharedCallbacks,
    ) -> PyResult<Self> {
        if !object.hasattr("rhs")? {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "a network needs a method rhs(t, y, qp) returning dy/dt",
            ));
        }
        let dim = object.getattr("state_dim").map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(
                "a network needs state_dim: an int, or a method state_dim(dims) -> int",
            )
        })?;
        let value = if dim.is_callable() {
            dim.call1((PyQpDims::from(dims),))?
        } else {
            dim
        };
        let state_dim = read_state_dim(&value, dims.nx)?;
        let needs_qp_dot = match object.getattr_opt("needs_qp_dot")? {
            Some(v) => v.is_truthy()?,
            None => false,
        };
        let name = network_name(object)?;
        for method in ["rhs", "jacobian"] {
            if let Some(m) = object.getattr_opt(method)? {
                check_arity(&m, &name, method, needs_qp_dot)?;
            }
        }
        Ok(PyNetwork {
            object: object.clone().unbind(),
            name,
            state_dim,
            needs_qp_dot,
            has_jacobian: object.hasattr("jacobian")?,
            has_error_norm: object.hasattr("error_norm")?,
            callbacks,
        })
    }

    /// Calls `method(t, y, qp[, qp_dot])`, timed and counted; an exception is kept, not raised.
    fn call<T>(
        &self,
        method: &str,
        t: f64,
        y: &[f64],
        qp: &Qp,
        qp_dot: Option<&Qp>,
        read: impl FnOnce(&Bound<'_, PyAny>) -> PyResult<T>,
    ) -> Option<T> {
        // After an exception the run is lost: answer at once (module docs).
        if self.callbacks.lock().map_or(true, |c| c.error.is_some()) {
            return None;
        }
        let started = Instant::now();
        let out = Python::attach(|py| {
            // Ctrl-C (SIGINT) waits in the interpreter until this thread looks: it then raises
            // KeyboardInterrupt here, which stops the run like any exception (module docs).
            py.check_signals()?;
            let object = self.object.bind(py);
            let y = y.to_vec().into_pyarray(py);
            let qp = qp_dict(py, qp)?;
            let result = match (self.needs_qp_dot, qp_dot) {
                (true, Some(d)) => object.call_method1(method, (t, y, qp, qp_dict(py, d)?))?,
                _ => object.call_method1(method, (t, y, qp))?,
            };
            read(&result)
        });
        let mut c = self.callbacks.lock().unwrap_or_else(|p| p.into_inner());
        c.calls += 1;
        c.seconds += started.elapsed().as_secs_f64();
        match out {
            Ok(v) => Some(v),
            Err(e) => {
                let e = Python::attach(|py| {
                    if e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                        return e;
                    }
                    let wrapped = pyo3::exceptions::PyRuntimeError::new_err(format!(
                        "{}.{method} at t = {t}",
                        self.name
                    ));
                    wrapped.set_cause(py, Some(e));
                    wrapped
                });
                c.error.get_or_insert(e);
                None
            }
        }
    }
}

/// The QP as a dict of numpy arrays (module docs).
pub fn qp_dict<'py>(py: Python<'py>, qp: &Qp) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (key, m) in [("P", &qp.p), ("A", &qp.a), ("G", &qp.g)] {
        d.set_item(key, matrix(py, m))?;
    }
    for (key, v) in [
        ("q", &qp.q),
        ("b", &qp.b),
        ("h", &qp.h),
        ("lower", &qp.lower),
        ("upper", &qp.upper),
    ] {
        d.set_item(key, vector(py, v))?;
    }
    Ok(d)
}

pub fn vector<'py>(py: Python<'py>, v: &DVector<f64>) -> Bound<'py, numpy::PyArray1<f64>> {
    v.as_slice().to_vec().into_pyarray(py)
}

/// A matrix as a C-ordered 2-D array.
pub fn matrix<'py>(py: Python<'py>, m: &DMatrix<f64>) -> Bound<'py, numpy::PyArray2<f64>> {
    numpy::ndarray::Array2::from_shape_fn(m.shape(), |(i, j)| m[(i, j)]).into_pyarray(py)
}

/// The largest state a network may declare: its dense Jacobian (state_dim^2 floats) is then at
/// most 128 MiB. The papers' networks have at most a few dozen states (x, multipliers,
/// auxiliary variables); a larger `state_dim` is a mistake, not a network.
const MAX_STATE_DIM: usize = 4096;

/// `state_dim` (the attribute, or what the method returned): an int from `nx` (the state starts
/// with the QP's unknowns x) to [`MAX_STATE_DIM`].
fn read_state_dim(value: &Bound<'_, PyAny>, nx: usize) -> PyResult<usize> {
    if !value.is_instance_of::<pyo3::types::PyInt>() {
        return Err(PyTypeError::new_err(format!(
            "state_dim must be an int (or a method state_dim(dims) returning one), got {}",
            value
                .get_type()
                .name()
                .map_or_else(|_| "an object".to_string(), |n| n.to_string())
        )));
    }
    match value.extract::<usize>() {
        Ok(n) if (nx..=MAX_STATE_DIM).contains(&n) => Ok(n),
        _ => Err(pyo3::exceptions::PyValueError::new_err(format!(
            "state_dim {value} is outside {nx}..={MAX_STATE_DIM}: the network's state starts with \
             the QP's {nx} unknowns x, and a dense Jacobian of more than {MAX_STATE_DIM} states is \
             refused"
        ))),
    }
}

/// How many positional arguments a callable takes: (required, most; None for `*args`), or
/// None when Python cannot tell (a builtin without a signature).
fn positional_arity(f: &Bound<'_, PyAny>) -> PyResult<Option<(usize, Option<usize>)>> {
    let inspect = f.py().import("inspect")?;
    let Ok(signature) = inspect.call_method1("signature", (f,)) else {
        return Ok(None);
    };
    let parameter = inspect.getattr("Parameter")?;
    let kind_of = |k: &str| parameter.getattr(k);
    let (only, either, var) = (
        kind_of("POSITIONAL_ONLY")?,
        kind_of("POSITIONAL_OR_KEYWORD")?,
        kind_of("VAR_POSITIONAL")?,
    );
    let empty = parameter.getattr("empty")?;
    let (mut required, mut most) = (0, Some(0));
    for p in signature
        .getattr("parameters")?
        .call_method0("values")?
        .try_iter()?
    {
        let p = p?;
        let kind = p.getattr("kind")?;
        if kind.eq(&var)? {
            most = None;
        } else if kind.eq(&only)? || kind.eq(&either)? {
            most = most.map(|m| m + 1);
            if p.getattr("default")?.is(&empty) {
                required += 1;
            }
        }
    }
    Ok(Some((required, most)))
}

/// Checks that the network's `method` (`rhs` or `jacobian`) can be called as the library
/// calls it: `(t, y, qp)`, or `(t, y, qp, qp_dot)` where the network sets `needs_qp_dot`.
/// The error says which of the two the method takes and what to set.
fn check_arity(
    method: &Bound<'_, PyAny>,
    network: &str,
    name: &str,
    needs_qp_dot: bool,
) -> PyResult<()> {
    let Some((required, most)) = positional_arity(method)? else {
        return Ok(());
    };
    let takes = |n: usize| required <= n && most.is_none_or(|m| n <= m);
    let given = if needs_qp_dot { 4 } else { 3 };
    if takes(given) {
        return Ok(());
    }
    let hint = if !needs_qp_dot && takes(4) {
        format!(
            "{network}.{name} takes (t, y, qp, qp_dot) but the network does not set \
             needs_qp_dot = True, so the library would call it with (t, y, qp): set \
             needs_qp_dot = True (e.g. a class attribute) to get dQP/dt as the fourth argument"
        )
    } else if needs_qp_dot && takes(3) {
        format!(
            "{network}.{name} takes (t, y, qp) but the network sets needs_qp_dot = True, so \
             the library would call it with (t, y, qp, qp_dot): add the qp_dot argument, or \
             drop needs_qp_dot"
        )
    } else {
        format!(
            "{network}.{name} must take (t, y, qp), or (t, y, qp, qp_dot) with needs_qp_dot = \
             True; it takes {required} to {} positional arguments",
            most.map_or("any number of".to_string(), |m| m.to_string())
        )
    };
    Err(PyTypeError::new_err(hint))
}

/// Reads a 1-D float array of length `n` (lists and integer arrays are converted).
fn read_vector(value: &Bound<'_, PyAny>, n: usize, what: &str) -> PyResult<Vec<f64>> {
    let v: Vec<f64> = real_array::<Ix1>(value, &format!("the result of {what}"))?
        .iter()
        .copied()
        .collect();
    if v.len() != n {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "{what} returned {} entries, the network's state has {n}",
            v.len()
        )));
    }
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "{what} returned a non-finite entry ({} at index {i}): the run stops here",
            v[i]
        )));
    }
    Ok(v)
}

impl NeuralSolver for PyNetwork {
    fn name(&self) -> String {
        self.name.clone()
    }

    fn state_dim(&self, _dims: QpDims) -> usize {
        self.state_dim
    }

    fn needs_qp_dot(&self) -> bool {
        self.needs_qp_dot
    }

    fn rhs(&mut self, t: f64, y: &[f64], qp: &Qp, qp_dot: Option<&Qp>, ydot: &mut [f64]) {
        let n = y.len();
        match self.call("rhs", t, y, qp, qp_dot, |r| read_vector(r, n, "rhs")) {
            Some(v) => ydot.copy_from_slice(&v),
            None => ydot.fill(0.0),
        }
    }

    fn error_norm(&mut self, qp: &Qp, y: &[f64]) -> Option<f64> {
        if !self.has_error_norm {
            return None;
        }
        Python::attach(|py| {
            let qp = qp_dict(py, qp).ok()?;
            let y = y.to_vec().into_pyarray(py);
            let r = self.object.bind(py).call_method1("error_norm", (qp, y));
            match r.and_then(|v| v.extract::<Option<f64>>()) {
                Ok(v) => v,
                Err(e) => {
                    let mut c = self.callbacks.lock().unwrap_or_else(|p| p.into_inner());
                    c.error.get_or_insert(e);
                    None
                }
            }
        })
    }

    fn jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        qp: &Qp,
        qp_dot: Option<&Qp>,
        jac: &mut DMatrix<f64>,
    ) -> bool {
        if !self.has_jacobian {
            return false;
        }
        let n = y.len();
        let read = |r: &Bound<'_, PyAny>| -> PyResult<Option<DMatrix<f64>>> {
            if r.is_none() {
                return Ok(None);
            }
            let a = real_array::<Ix2>(r, "the result of jacobian (an n x n array or None)")?;
            if a.shape() != [n, n] {
                return Err(pyo3::exceptions::PyValueError::new_err(format!(
                    "jacobian returned shape {:?}, the network's state has {n} entries",
                    a.shape()
                )));
            }
            if a.iter().any(|x| !x.is_finite()) {
                return Err(pyo3::exceptions::PyValueError::new_err(
                    "jacobian returned a non-finite entry (NaN or inf): the run stops here",
                ));
            }
            Ok(Some(DMatrix::from_fn(n, n, |i, j| a[[i, j]])))
        };
        match self.call("jacobian", t, y, qp, qp_dot, read) {
            Some(Some(m)) => {
                jac.copy_from(&m);
                true
            }
            Some(None) => false,
            None => {
                jac.fill(0.0);
                true
            }
        }
    }
}
