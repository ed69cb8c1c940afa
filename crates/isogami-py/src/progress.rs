//! What a long library call does while the GIL is released: it reports progress to an
//! optional Python callback, checks for Ctrl-C, and keeps a deadline. All three go through the
//! library's one cancellation hook, the progress callback that returns `false` to stop (the
//! same hook the web server's live deploy uses for its deadline and for a closed connection).

use crate::errors;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::time::{Duration, Instant};

/// Ctrl-C is checked at least this often (and at every step when a callback is given).
const SIGNAL_INTERVAL: Duration = Duration::from_millis(20);

/// Why a watched call stopped itself.
enum Stop {
    /// The callback returned False.
    Callback,
    /// The timeout passed.
    Timeout(Duration),
    /// Python raised: KeyboardInterrupt from a signal handler, or the callback's exception.
    Raised(PyErr),
}

/// The state of one watched call.
pub struct Watch {
    callback: Option<Py<PyAny>>,
    started: Instant,
    timeout: Option<Duration>,
    last_check: Instant,
    stop: Option<Stop>,
    /// The count the callback last heard.
    reported: Option<usize>,
}

impl Watch {
    /// A watch with an optional callback `callback(states) -> bool | None` and an optional
    /// timeout in seconds (finite, above zero).
    pub fn new(callback: Option<Bound<'_, PyAny>>, timeout: Option<f64>) -> PyResult<Watch> {
        if let Some(cb) = &callback {
            if !cb.is_callable() {
                return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                    "progress must be callable (one argument) -> bool | None, got {}",
                    crate::convert::type_name(cb)
                )));
            }
        }
        let timeout = match timeout {
            None => None,
            Some(s) if s.is_finite() && s > 0.0 && s < 1e9 => Some(Duration::from_secs_f64(s)),
            Some(s) => {
                return Err(errors::SettingsError::new_err(format!(
                    "invalid setting: timeout {s} must be a finite number of seconds above 0"
                )))
            }
        };
        crate::pickle::computing();
        let now = Instant::now();
        Ok(Watch {
            callback: callback.map(Bound::unbind),
            started: now,
            timeout,
            last_check: now,
            stop: None,
            reported: None,
        })
    }

    /// Called by the library after every accepted step with the number of states so far;
    /// `false` stops the call. Attaches to Python only when a callback is given or a signal
    /// check is due.
    ///
    /// The library asks on with the count unchanged while a later stage runs (a finite
    /// sheet's completion, a print's solid: `isogami::stop::watched`); the callback hears
    /// each count once, while the timeout and Ctrl-C are still checked.
    pub fn tick(&mut self, states: usize) -> bool {
        let new = self.reported != Some(states);
        self.reported = Some(states);
        self.check(new, |py| one(py, states.into_pyobject(py)?.into_any()))
    }

    /// As [`Watch::tick`], with the callback's one argument made by `argument` (called only
    /// when the callback is due).
    pub fn tick_with(
        &mut self,
        argument: impl FnOnce(Python<'_>) -> PyResult<Bound<'_, PyAny>>,
    ) -> bool {
        self.check(true, |py| one(py, argument(py)?))
    }

    /// As [`Watch::tick_with`], with all the callback's arguments made by `arguments` (a
    /// graded sheet's `progress(iteration, cost)`).
    pub fn tick_args(
        &mut self,
        arguments: impl FnOnce(Python<'_>) -> PyResult<Bound<'_, PyTuple>>,
    ) -> bool {
        self.check(true, arguments)
    }

    /// The timeout and (when due) Ctrl-C, never the callback: for the polls of
    /// `isogami::stop::watched` while the work reports its own progress on another thread.
    pub fn poll(&mut self) -> bool {
        self.check(false, |py| Ok(PyTuple::empty(py)))
    }

    /// The timeout, then (when due) Ctrl-C and, when `call` is set, the callback.
    fn check(
        &mut self,
        call: bool,
        arguments: impl FnOnce(Python<'_>) -> PyResult<Bound<'_, PyTuple>>,
    ) -> bool {
        let callback = self.callback.as_ref().filter(|_| call);
        if let Some(limit) = self.timeout {
            if self.started.elapsed() >= limit {
                self.stop = Some(Stop::Timeout(limit));
                return false;
            }
        }
        let now = Instant::now();
        if callback.is_none() && now.duration_since(self.last_check) < SIGNAL_INTERVAL {
            return true;
        }
        self.last_check = now;
        let outcome = Python::attach(|py| -> Result<bool, PyErr> {
            py.check_signals()?;
            match callback {
                None => Ok(true),
                Some(cb) => {
                    let answer = cb.call1(py, arguments(py)?)?;
                    // None (no return value) goes on; False (any falsy value) stops.
                    let answer = answer.bind(py);
                    Ok(answer.is_none() || answer.is_truthy()?)
                }
            }
        });
        match outcome {
            Ok(true) => true,
            Ok(false) => {
                self.stop = Some(Stop::Callback);
                false
            }
            Err(e) => {
                self.stop = Some(Stop::Raised(e));
                false
            }
        }
    }

    /// The Python result of the watched call: a cancellation becomes the exception that
    /// caused it (KeyboardInterrupt, the callback's own), or `CancelledError` saying why.
    pub fn finish<T>(self, result: isogami::Result<T>) -> PyResult<T> {
        result.map_err(|e| self.error(e))
    }

    /// The Python exception of a library error raised under this watch.
    pub fn error(self, e: isogami::Error) -> PyErr {
        if !e.is_cancelled() {
            return errors::library(e);
        }
        self.cancelled(|| errors::library(e))
    }

    /// The Python exception of a cancellation under this watch: what stopped it, or
    /// `otherwise` when the watch did not.
    pub fn cancelled(self, otherwise: impl FnOnce() -> PyErr) -> PyErr {
        match self.stop {
            Some(Stop::Raised(err)) => err,
            Some(Stop::Timeout(limit)) => errors::CancelledError::new_err(format!(
                "cancelled: did not finish within the timeout of {} s",
                limit.as_secs_f64()
            )),
            Some(Stop::Callback) => {
                errors::CancelledError::new_err("cancelled: the progress callback returned False")
            }
            None => otherwise(),
        }
    }
}

/// A one-argument tuple.
fn one<'py>(py: Python<'py>, argument: Bound<'py, PyAny>) -> PyResult<Bound<'py, PyTuple>> {
    PyTuple::new(py, [argument])
}
