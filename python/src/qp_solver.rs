//! A QP solver written in Python, behind the suite's one solver seam (`qp::QpSolver`): a
//! Python object with
//!
//! ```text
//! solve(P, q, A, b, G, h, lower, upper) -> dict
//! min x'Px/2 + q'x   s.t.   A x = b,   G x <= h,   lower <= x <= upper
//! ```
//!
//! (numpy arrays in the form of `qp::Qp`, infinite bounds as +-inf) answering a dict: `x` (the
//! primal answer), the multipliers in the seam's convention (stationarity P x + q + A'lambda +
//! G'mu - z_lower + z_upper = 0) `lambda`, `mu`, `z_lower`, `z_upper` (zeros where absent),
//! `iterations` (default 1), or, for a solve that failed, `status`: one of the seam's statuses
//! other than `solved` (`iteration-limit`, `infeasible`, `unbounded`, `singular`,
//! `numerical-failure`, `invalid-input`, `inaccurate`) and an optional `message`. An exception
//! raised by `solve`, or an answer of other sizes or with NaN, is a failed solve (status
//! `numerical-failure`, the exception's text as the message), never a panic.
//!
//! `register_qp_solver(id, factory, name=None)` registers it in the registry of QP solvers
//! (`solvers::registry`, ids of `settings::qp_solver`): `factory(dims)` builds a solver for QPs
//! of the sizes `dims` (a class taking a `QpDims` will do). From then on the id is a run's
//! solver as any built-in one (`simulate(task, id)`: every instant of the task's fixed-step
//! numerical loop is one `solve`), and `check_qp_solver(factory)` holds it to the conformance
//! kit (`solvers::conformance`) without registering it.

use crate::arrays::real_array;
use crate::network::{matrix, vector, PyQpDims};
use nalgebra::DVector;
use numpy::ndarray::Ix1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use qp::{Qp, QpDims, QpDuals, QpSolve, QpSolver, QpSolverError, QpStatus, SolverId};
use settings::qp_solver::QpSolverInfo;
use solvers::registry::BoxedQpSolver;
use std::sync::Arc;

/// The seam's statuses, by name.
const STATUSES: [QpStatus; 8] = [
    QpStatus::Solved,
    QpStatus::IterationLimit,
    QpStatus::Infeasible,
    QpStatus::Unbounded,
    QpStatus::Singular,
    QpStatus::NumericalFailure,
    QpStatus::InvalidInput,
    QpStatus::Inaccurate,
];

/// Why a Python solve failed, as the seam's error source.
#[derive(Debug, thiserror::Error)]
#[error("Python QP solver {id}: {message}")]
struct PySolveError {
    id: SolverId,
    message: String,
}

/// A Python QP solver (module docs).
pub struct PyQpSolver {
    /// The Python object, or why the factory gave none.
    object: Result<Py<PyAny>, FactoryError>,
    id: SolverId,
    x: Vec<f64>,
    duals: QpDuals,
}

impl PyQpSolver {
    fn fail(&self, status: QpStatus, message: impl Into<String>) -> QpSolverError {
        QpSolverError::new(
            status,
            PySolveError {
                id: self.id.clone(),
                message: message.into(),
            },
        )
    }

    /// One call of `solve` and its answer read (module docs); Err: the status and message.
    fn call(
        &self,
        py: Python<'_>,
        qp: &Qp,
    ) -> Result<(Vec<f64>, QpDuals, u32), (QpStatus, String)> {
        let failure = |e: PyErr| (QpStatus::NumericalFailure, e.to_string());
        let object = self
            .object
            .as_ref()
            .map_err(|e| (QpStatus::InvalidInput, e.to_string()))?;
        let args = (
            matrix(py, &qp.p),
            vector(py, &qp.q),
            matrix(py, &qp.a),
            vector(py, &qp.b),
            matrix(py, &qp.g),
            vector(py, &qp.h),
            vector(py, &qp.lower),
            vector(py, &qp.upper),
        );
        let answer = object
            .bind(py)
            .call_method1("solve", args)
            .map_err(failure)?;
        let answer = answer.cast_into::<PyDict>().map_err(|_| {
            (
                QpStatus::NumericalFailure,
                "solve must return a dict (x, lambda, mu, z_lower, z_upper, iterations or \
                 status)"
                    .to_string(),
            )
        })?;
        if let Some(status) = answer.get_item("status").map_err(failure)? {
            let status = status.extract::<String>().map_err(failure)?;
            let Some(&status) = STATUSES.iter().find(|s| s.as_str() == status) else {
                let names: Vec<&str> = STATUSES.iter().map(|s| s.as_str()).collect();
                return Err((
                    QpStatus::NumericalFailure,
                    format!("status must be one of {}", names.join(", ")),
                ));
            };
            if status != QpStatus::Solved {
                let message = match answer.get_item("message").map_err(failure)? {
                    Some(m) => m.str().map_err(failure)?.to_string(),
                    None => format!("solve returned status {status}"),
                };
                return Err((status, message));
            }
        }
        let dims = qp.dims();
        let read =
            |key: &str, len: usize, required: bool| -> Result<DVector<f64>, (QpStatus, String)> {
                match answer.get_item(key).map_err(failure)? {
                    Some(v) => {
                        let v = real_array::<Ix1>(&v, key).map_err(failure)?;
                        if v.len() != len || v.iter().any(|e| !e.is_finite()) {
                            return Err((
                                QpStatus::NumericalFailure,
                                format!(
                                    "{key} must be {len} finite numbers, got {} entries",
                                    v.len()
                                ),
                            ));
                        }
                        Ok(DVector::from_iterator(len, v.iter().copied()))
                    }
                    None if required => Err((
                        QpStatus::NumericalFailure,
                        format!("solve's dict has no {key}"),
                    )),
                    None => Ok(DVector::zeros(len)),
                }
            };
        let x = read("x", dims.nx, true)?;
        let duals = QpDuals {
            lambda: read("lambda", dims.n_eq, false)?,
            mu: read("mu", dims.n_in, false)?,
            z_lower: read("z_lower", dims.nx, false)?,
            z_upper: read("z_upper", dims.nx, false)?,
        };
        let iterations = match answer.get_item("iterations").map_err(failure)? {
            Some(i) => i.extract::<u32>().map_err(failure)?,
            None => 1,
        };
        Ok((x.as_slice().to_vec(), duals, iterations))
    }
}

fn zero_duals(dims: QpDims) -> QpDuals {
    QpDuals {
        lambda: DVector::zeros(dims.n_eq),
        mu: DVector::zeros(dims.n_in),
        z_lower: DVector::zeros(dims.nx),
        z_upper: DVector::zeros(dims.nx),
    }
}

impl QpSolver for PyQpSolver {
    fn id(&self) -> SolverId {
        self.id.clone()
    }

    fn solve(&mut self, qp: &Qp) -> Result<QpSolve, QpSolverError> {
        let bad = [&qp.q, &qp.b, &qp.h]
            .iter()
            .any(|v| v.iter().any(|e| e.is_nan()))
            || [&qp.p, &qp.a, &qp.g]
                .iter()
                .any(|m| m.iter().any(|e| !e.is_finite()));
        if bad {
            return Err(self.fail(QpStatus::InvalidInput, "the QP has NaN or infinite data"));
        }
        match Python::attach(|py| self.call(py, qp)) {
            Ok((x, duals, iterations)) => {
                self.x = x;
                self.duals = duals;
                Ok(QpSolve::solved(iterations))
            }
            Err((status, message)) => Err(self.fail(status, message)),
        }
    }

    fn x(&self) -> &[f64] {
        &self.x
    }

    fn duals(&self, _qp: &Qp, duals: &mut QpDuals) {
        duals.clone_from(&self.duals);
    }

    /// A Python solver's state is its own: nothing is kept on this side but the last answer.
    fn reset(&mut self) {
        self.x.iter_mut().for_each(|v| *v = 0.0);
    }
}

/// `factory(dims)` as a solver under `id`; where the factory raises (or returns an object
/// without `solve`), a solver whose every solve fails with that message (status
/// `invalid-input`): the registry's constructors cannot fail.
pub fn build(factory: &Py<PyAny>, id: &SolverId, dims: QpDims) -> PyQpSolver {
    let object = Python::attach(|py| -> PyResult<Py<PyAny>> {
        let object = factory.bind(py).call1((PyQpDims::from(dims),))?;
        if !object.hasattr("solve")? {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "the factory returned an object without a solve method",
            ));
        }
        Ok(object.unbind())
    });
    PyQpSolver {
        object: object.map_err(|e| FactoryError(e.to_string())),
        id: id.clone(),
        x: vec![0.0; dims.nx],
        duals: zero_duals(dims),
    }
}

/// Why a Python solver's factory gave no object (its exception's message): every solve of
/// that solver then fails with status `InvalidInput`, saying so.
#[derive(Debug, thiserror::Error)]
#[error("its factory failed: {0}")]
struct FactoryError(String);

/// Why a Python QP solver could not be registered.
#[derive(Debug, thiserror::Error)]
pub enum RegisterError {
    /// The id is not a slug.
    #[error("QP solver id \"{0}\" is not a slug (lower-case letters, digits and -, at most 64)")]
    NotASlug(String),
    /// The registry refused it (an id taken).
    #[error(transparent)]
    Registry(#[from] solvers::registry::RegistryError),
}

/// Registers `factory` under `id` (module docs) in the registry of QP solvers, display name
/// `name`.
pub fn register(id: &str, name: &str, factory: Py<PyAny>) -> Result<(), RegisterError> {
    let sid =
        SolverId::new(id.to_string()).ok_or_else(|| RegisterError::NotASlug(id.to_string()))?;
    // The registry keeps ids and names for the process's life ('static): one leak per
    // registration, which the registry refuses to repeat for an id.
    let info = QpSolverInfo {
        id: Box::leak(id.to_string().into_boxed_str()),
        name: Box::leak(name.to_string().into_boxed_str()),
        tolerance: None,
        max_iterations: None,
    };
    let factory = Arc::new(factory);
    solvers::registry::register(
        info,
        Arc::new(move |dims, _settings| -> BoxedQpSolver { Box::new(build(&factory, &sid, dims)) }),
    )
    .map(|_| ())
    .map_err(RegisterError::from)
}
