//! The wall budget of a run of a Python network (`leaderboard(wall_budget=)`,
//! `simulate(wall_budget=)`): B seconds of wall time, after which the run is a failed run
//! (`failure_kind = "wall-time"`), not a call that never returns.
//!
//! Two guards share the budget:
//! - the integrator's own (`max_wall_s = B`, `solvers::ode`): checked after every accepted
//!   step, it stops a run whose calls return but which goes on too long (a slow network, or a
//!   step size that keeps shrinking);
//! - [`watched`]: a watchdog thread for a call into the network that does not return (a loop
//!   inside `rhs`). At B it raises [`WallBudgetExceeded`] inside the running Python code, as the
//!   interpreter's asynchronous exception of the run's thread (`PyThreadState_SetAsyncExc`),
//!   which stops the run as any exception of the network does. The interpreter delivers such
//!   an exception between two bytecodes: a call blocked outside Python code (a long
//!   `time.sleep`, a loop inside a C extension) is stopped when it returns to Python code.

use pyo3::create_exception;
use pyo3::exceptions::PyBaseException;
use pyo3::prelude::*;
use pyo3::PyTypeInfo;
use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::time::Duration;

create_exception!(
    driftbench,
    WallBudgetExceeded,
    PyBaseException,
    "A run of a Python network used up its wall budget inside a call into the network (raised \
     into the call by the budget's watchdog; a BaseException, so that `except Exception` in the \
     network does not swallow it)."
);

/// Whether `e`, or the exception it was raised from (`__cause__`), is the watchdog's
/// [`WallBudgetExceeded`].
pub fn is_exceeded(py: Python<'_>, e: &PyErr) -> bool {
    e.is_instance_of::<WallBudgetExceeded>(py)
        || e.cause(py)
            .is_some_and(|c| c.is_instance_of::<WallBudgetExceeded>(py))
}

/// Runs `body` (a run that calls into Python on this thread) with a watchdog that raises
/// [`WallBudgetExceeded`] into this thread's Python code once `budget` has passed (module
/// docs). The watchdog acts only under the interpreter's lock and only while the run is on,
/// and an exception it raised that the run did not meet is withdrawn at the end, so nothing is
/// raised into the code after the run.
pub fn watched<T>(py: Python<'_>, budget: Duration, body: impl FnOnce() -> T) -> PyResult<T> {
    let thread: u64 = py
        .import("threading")?
        .call_method0("get_ident")?
        .extract()?;
    // The thread id as CPython's `unsigned long` in pyo3's `c_long` signature: the same bits.
    let thread = thread as std::os::raw::c_long;
    let done = Arc::new((Mutex::new(false), Condvar::new()));
    let watch = Arc::clone(&done);
    let dog = std::thread::spawn(move || {
        let (flag, bell) = &*watch;
        let over = flag.lock().unwrap_or_else(PoisonError::into_inner);
        let (over, _) = bell
            .wait_timeout_while(over, budget, |done| !*done)
            .unwrap_or_else(PoisonError::into_inner);
        if *over {
            return;
        }
        drop(over);
        Python::attach(|py| {
            // Under the interpreter's lock, as the run's end below sets the flag: the run is
            // either still on (the exception is raised into it) or over (nothing to do).
            if !*flag.lock().unwrap_or_else(PoisonError::into_inner) {
                let kind = WallBudgetExceeded::type_object(py);
                // SAFETY: the interpreter's lock is held; `kind` is a live exception type.
                unsafe { pyo3::ffi::PyThreadState_SetAsyncExc(thread, kind.as_ptr()) };
            }
        });
    });
    let out = body();
    {
        let (flag, bell) = &*done;
        *flag.lock().unwrap_or_else(PoisonError::into_inner) = true;
        bell.notify_all();
    }
    let joined = py.detach(|| dog.join());
    // SAFETY: the interpreter's lock is held; a null exception withdraws a pending one.
    unsafe { pyo3::ffi::PyThreadState_SetAsyncExc(thread, std::ptr::null_mut()) };
    joined.map_err(|_| {
        pyo3::exceptions::PyRuntimeError::new_err("the wall budget's watchdog panicked")
    })?;
    Ok(out)
}
