//! Running the library's work off the Python thread: limits, a large stack, the GIL released,
//! and KeyboardInterrupt.
//!
//! The work runs on a worker thread with the command line's 256 MB stack (deep but legal
//! inputs recurse up to the parser's depth limit) and the caller's limits, applied there
//! because the library's limits belong to the evaluating thread. The calling thread releases
//! the GIL and wakes every few milliseconds to run Python's signal handlers
//! (`Python::check_signals`); on KeyboardInterrupt it sets the cancel flag, waits for the
//! worker to stop (the evaluator polls the flag, and the work budget bounds what does not),
//! and hands back both the worker's result and the interruption, so that the caller can keep
//! its state consistent before raising.

use dqsym::Preset;
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError};
use pyo3::prelude::*;
use std::panic::AssertUnwindSafe;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

/// The worker's stack, as in the command line.
const STACK: usize = 256 << 20;

/// How often the calling thread looks for a pending KeyboardInterrupt.
const POLL: Duration = Duration::from_millis(20);

/// The limits of one computation, as the command line's options.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Limits {
    pub term_limit: usize,
    pub max_depth: usize,
    pub max_exponent: u64,
    pub work_budget: u64,
}

impl Limits {
    /// The command line's defaults for scripts and one-liners.
    pub(crate) const SCRIPT: Limits = Limits::of(Preset::Script);

    /// The command line's defaults for `fk`.
    pub(crate) const FK: Limits = Limits::of(Preset::Fk);

    /// The limits of a preset, and the parser's default depth.
    const fn of(p: Preset) -> Limits {
        Limits {
            term_limit: p.term_limit(),
            max_depth: dqsym::lang::DEFAULT_MAX_DEPTH,
            max_exponent: p.max_exponent(),
            work_budget: p.work_budget(),
        }
    }

    /// The library's execution context with these limits and `cancel` as its cancel flag.
    pub(crate) fn context(&self, cancel: Arc<AtomicBool>) -> dqsym::Context {
        dqsym::Context::new()
            .with_term_limit(self.term_limit)
            .with_max_exponent(self.max_exponent)
            .with_work_budget(self.work_budget)
            .with_cancel_flag(cancel)
    }

    /// Enters these limits on the calling thread (for conversions done on the Python thread)
    /// until the guard is dropped.
    pub(crate) fn enter(&self) -> dqsym::scalar::Entered {
        self.context(Arc::new(AtomicBool::new(false))).enter()
    }

    /// The parser's options.
    pub(crate) fn parse_options(&self) -> dqsym::lang::ParseOptions {
        dqsym::lang::ParseOptions {
            max_depth: self.max_depth,
            ..dqsym::lang::ParseOptions::default()
        }
    }
}

type Slot<T> = Arc<(Mutex<Option<std::thread::Result<T>>>, Condvar)>;

/// Waits for the worker's result, at most `timeout` (forever when `None`).
fn wait<T>(slot: &Slot<T>, timeout: Option<Duration>) -> Option<std::thread::Result<T>> {
    let (m, c) = &**slot;
    let guard = m.lock().unwrap_or_else(|p| p.into_inner());
    let mut guard = match timeout {
        Some(t) => {
            c.wait_timeout_while(guard, t, |r| r.is_none())
                .unwrap_or_else(|p| p.into_inner())
                .0
        }
        None => c
            .wait_while(guard, |r| r.is_none())
            .unwrap_or_else(|p| p.into_inner()),
    };
    guard.take()
}

/// Runs `f` on a worker thread under `limits` with the GIL released. Returns its result and,
/// when a KeyboardInterrupt (or another signal handler's exception) arrived meanwhile, that
/// exception: `cancel` was set then and the worker ran to its end (the flag is cleared again).
pub(crate) fn run<T, F>(
    py: Python<'_>,
    limits: Limits,
    cancel: Option<&Arc<AtomicBool>>,
    f: F,
) -> PyResult<(T, Option<PyErr>)>
where
    F: FnOnce() -> T + Send + 'static,
    T: Send + 'static,
{
    // Every computation is cancellable: a caller without a flag of its own gets a fresh one.
    let cancel = cancel
        .cloned()
        .unwrap_or_else(|| Arc::new(AtomicBool::new(false)));
    let ctx = limits.context(cancel.clone());
    let slot: Slot<T> = Arc::new((Mutex::new(None), Condvar::new()));
    let worker_slot = slot.clone();
    let handle = std::thread::Builder::new()
        .name("dqsym".into())
        .stack_size(STACK)
        .spawn(move || {
            let _entered = ctx.enter();
            let r = std::panic::catch_unwind(AssertUnwindSafe(f));
            let (m, c) = &*worker_slot;
            *m.lock().unwrap_or_else(|p| p.into_inner()) = Some(r);
            c.notify_all();
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a worker thread: {e}")))?;
    let mut interrupted = None;
    let result = loop {
        if let Some(r) = py.allow_threads(|| wait(&slot, Some(POLL))) {
            break r;
        }
        if let Err(e) = py.check_signals() {
            cancel.store(true, Ordering::Relaxed);
            interrupted = Some(if e.is_instance_of::<PyKeyboardInterrupt>(py) {
                PyKeyboardInterrupt::new_err(
                    "dqsym: interrupted; the session's bindings are as before the statement",
                )
            } else {
                e
            });
            // The evaluator stops soon after the flag is set; work that does not poll it is
            // bounded by the work budget.
            let r = py.allow_threads(|| loop {
                if let Some(r) = wait(&slot, None) {
                    return r;
                }
            });
            break r;
        }
    };
    cancel.store(false, Ordering::Relaxed);
    let _ = handle.join();
    match result {
        Ok(v) => Ok((v, interrupted)),
        Err(_) => Err(PyRuntimeError::new_err(
            "internal failure in dqsym (a panic); please report the input",
        )),
    }
}
