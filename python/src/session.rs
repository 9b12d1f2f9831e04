//! `Session` (statements and bindings), `evaluate` (one-liners), `Output` (a displayed result
//! with the project's LaTeX for Jupyter) and `latex`/`text` of any value.

use crate::convert::{Forms, FromPython, ToSympy};
use crate::errors;
use crate::work::{self, Limits};
use dqsym::{
    lang::{parse_with, show_value, Displayed},
    show, Format, Session as LibSession, ShowOptions, Value,
};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex, MutexGuard, TryLockError};
use std::time::Duration;

/// A displayed result: its label, its value as a SymPy object (`value`), and the project's
/// plain text and LaTeX of the value (`text`, `latex`; `_repr_latex_` for Jupyter).
#[pyclass(module = "dqsym", frozen)]
pub(crate) struct Output {
    #[pyo3(get)]
    label: String,
    #[pyo3(get)]
    value: PyObject,
    shown: Displayed,
}

/// `label = value` in one format, or the value alone when the label is an expression.
fn shown_text(d: &Displayed, format: Format) -> Result<String, dqsym::lang::ShowError> {
    let opts = ShowOptions {
        format,
        explicit: false,
    };
    show(
        &Displayed {
            format: None,
            ..d.clone()
        },
        &opts,
    )
}

#[pymethods]
impl Output {
    /// The result as the command line prints it (plain robotics notation, `c12`).
    #[getter]
    fn text(&self, py: Python<'_>) -> PyResult<String> {
        shown_text(&self.shown, Format::Plain).map_err(|e| errors::other(py, e.to_string()))
    }

    /// The value in LaTeX, as `--format latex` prints it (KaTeX-compatible).
    #[getter]
    fn latex(&self, py: Python<'_>) -> PyResult<String> {
        show_value(&self.shown.value, &latex_opts())
            .map(|s| s.trim_end().to_owned())
            .map_err(|e| errors::other(py, e.to_string()))
    }

    fn _repr_latex_(&self, py: Python<'_>) -> PyResult<String> {
        let t =
            shown_text(&self.shown, Format::Latex).map_err(|e| errors::other(py, e.to_string()))?;
        // An expression label comes as a `% label` comment line, which display math cannot hold.
        let body: Vec<&str> = t.lines().filter(|l| !l.starts_with('%')).collect();
        Ok(format!("$\\displaystyle {}$", body.join("\n")))
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(self.text(py)?.trim_end().to_owned())
    }
}

fn latex_opts() -> ShowOptions {
    ShowOptions {
        format: Format::Latex,
        explicit: false,
    }
}

/// A statement's result on the worker: the displayed value and its closed forms.
type Computed = Option<(Displayed, Forms)>;

/// What a run of statements did: the results shown, and the error that stopped it.
struct Run {
    shown: Vec<(Displayed, Forms)>,
    error: Option<RunError>,
}

enum RunError {
    Parse(dqsym::ParseError),
    Eval(dqsym::EvalError),
    Scalar(dqsym::ScalarError),
}

/// Parses `src` and runs its statements in `session` in order, as `dqsym run` does: statements
/// before a failing one keep their effect.
fn run_statements(session: &mut LibSession, src: &str, limits: &Limits) -> Run {
    let mut shown = Vec::new();
    let program = match parse_with(src, &limits.parse_options()) {
        Ok(p) => p,
        Err(e) => {
            return Run {
                shown,
                error: Some(RunError::Parse(e)),
            }
        }
    };
    for stmt in &program.statements {
        // What the statement binds is undone unless it completes, closed forms included, and
        // uninterrupted: a step that does not look at the cancel flag may finish after
        // KeyboardInterrupt set it, and its binding must not stay.
        session.checkpoint();
        let r: Result<Computed, RunError> = match session.exec(stmt) {
            Ok(Some(d)) => match Forms::of(&d.value) {
                Ok(f) => Ok(Some((d, f))),
                Err(e) => Err(RunError::Scalar(e)),
            },
            Ok(None) => Ok(None),
            Err(e) => Err(RunError::Eval(e)),
        };
        let r = match (r, dqsym::Context::check_cancelled()) {
            (Ok(_), Err(e)) => Err(RunError::Scalar(e)),
            (r, _) => r,
        };
        match r {
            Ok(Some(x)) => {
                session.commit();
                shown.push(x)
            }
            Ok(None) => {
                session.commit();
            }
            Err(e) => {
                session.rollback();
                return Run {
                    shown,
                    error: Some(e),
                };
            }
        }
    }
    Run { shown, error: None }
}

fn outputs(py: Python<'_>, shown: Vec<(Displayed, Forms)>) -> PyResult<Vec<Output>> {
    let mut conv = ToSympy::new(py)?;
    shown
        .into_iter()
        .map(|(d, f)| {
            Ok(Output {
                label: d.label.clone(),
                value: conv.forms(&f)?.unbind(),
                shown: d,
            })
        })
        .collect()
}

fn run_error(py: Python<'_>, e: &RunError, src: &str) -> PyErr {
    match e {
        RunError::Parse(p) => errors::parse_error(py, p),
        RunError::Eval(v) => errors::eval_error(py, v, src),
        RunError::Scalar(s) => errors::scalar_error(py, s),
    }
}

/// A dqsym session: statements of the language run one after another, bindings kept between
/// them, as in a script or the REPL.
///
/// `Session()` requires names to be declared (`syms l1 l2`) or assigned before use, as scripts
/// do; `Session(implicit_symbols=True)` makes every free name a symbol, as `dqsym -e` does.
/// The limits are the command line's options (defaults as there).
///
/// Safe to share between threads: calls are serialized by a lock (a thread waits, with the
/// GIL released, while another runs statements), so statements from several threads run one
/// after another, each whole.
#[pyclass(module = "dqsym", frozen)]
pub(crate) struct Session {
    inner: Mutex<LibSession>,
    limits: Limits,
    cancel: Arc<AtomicBool>,
}

/// How long a thread waiting for a session in use sleeps between looks (with the GIL
/// released, and looking for KeyboardInterrupt in between).
const LOCK_POLL: Duration = Duration::from_millis(1);

impl Session {
    /// The session's bindings, once no other thread uses them. The lock is taken with the
    /// GIL held but never waited for with it: a thread holding the lock releases the GIL
    /// while it computes, and one waiting must not keep it meanwhile.
    fn lock(&self, py: Python<'_>) -> PyResult<MutexGuard<'_, LibSession>> {
        loop {
            match self.inner.try_lock() {
                Ok(g) => return Ok(g),
                Err(TryLockError::Poisoned(p)) => return Ok(p.into_inner()),
                Err(TryLockError::WouldBlock) => {
                    py.allow_threads(|| std::thread::sleep(LOCK_POLL));
                    py.check_signals()?;
                }
            }
        }
    }

    /// Runs `src` on the worker, with the session moved there and back.
    fn run_src(&self, py: Python<'_>, src: &str) -> PyResult<Vec<Output>> {
        let mut guard = self.lock(py)?;
        let mut session = std::mem::take(&mut *guard);
        let limits = self.limits;
        let text = src.to_owned();
        let ((session, run), interrupted) = work::run(py, limits, Some(&self.cancel), move || {
            let run = run_statements(&mut session, &text, &limits);
            (session, run)
        })?;
        *guard = session;
        drop(guard);
        if let Some(e) = interrupted {
            return Err(e);
        }
        let shown = outputs(py, run.shown)?;
        match run.error {
            None => Ok(shown),
            Some(e) => Err(run_error(py, &e, src)),
        }
    }

    fn convert_in(&self, py: Python<'_>, x: &Bound<'_, PyAny>, what: &str) -> PyResult<Value> {
        // Conversions compute (sums, products, powers): under the session's limits.
        let _limits = self.limits.enter();
        FromPython::new(py)?.value(x, what)
    }
}

fn is_identifier(name: &str) -> bool {
    let mut c = name.chars();
    c.next().is_some_and(|f| f.is_ascii_alphabetic())
        && c.all(|ch| ch.is_ascii_alphanumeric() || ch == '_')
}

#[pymethods]
impl Session {
    #[new]
    #[pyo3(signature = (implicit_symbols=false, term_limit=Limits::SCRIPT.term_limit, work_budget=Limits::SCRIPT.work_budget, max_exponent=Limits::SCRIPT.max_exponent, max_depth=Limits::SCRIPT.max_depth, **bindings))]
    fn new(
        py: Python<'_>,
        implicit_symbols: bool,
        term_limit: usize,
        work_budget: u64,
        max_exponent: u64,
        max_depth: usize,
        bindings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Session> {
        if !(1..=4096).contains(&max_depth) {
            return Err(PyValueError::new_err(
                "max_depth must be between 1 and 4096",
            ));
        }
        let inner = if implicit_symbols {
            LibSession::with_implicit_symbols()
        } else {
            LibSession::new()
        };
        let cancel = Arc::new(AtomicBool::new(false));
        let s = Session {
            inner: Mutex::new(inner),
            limits: Limits {
                term_limit,
                max_depth,
                max_exponent,
                work_budget,
            },
            cancel,
        };
        if let Some(b) = bindings {
            for (k, v) in b.iter() {
                let k: String = k.extract()?;
                s.__setitem__(py, &k, &v)?;
            }
        }
        Ok(s)
    }

    /// Runs the statements of `src` (one or several lines) and returns the displayed results
    /// (statements ending in `;` display nothing). Raises ParseError or EvalError, with `line`
    /// and `column`, at the first failing statement; the ones before it keep their effect and
    /// the failing one changes nothing. KeyboardInterrupt stops a long statement and leaves the
    /// bindings as they were before it.
    fn run(&self, py: Python<'_>, src: &str) -> PyResult<Vec<Output>> {
        self.run_src(py, src)
    }

    /// Runs `src` and returns the value (a SymPy object) of its last displayed result, or None.
    fn eval(&self, py: Python<'_>, src: &str) -> PyResult<PyObject> {
        let mut out = self.run_src(py, src)?;
        Ok(match out.pop() {
            Some(o) => o.value,
            None => py.None(),
        })
    }

    /// The value bound to `name`, as a SymPy object.
    fn __getitem__(&self, py: Python<'_>, name: &str) -> PyResult<PyObject> {
        let v = self
            .lock(py)?
            .get(name)
            .ok_or_else(|| PyKeyError::new_err(name.to_owned()))?
            .clone();
        let (forms, _) = work::run(py, self.limits, None, move || Forms::of(&v))?;
        let forms = forms.map_err(|e| errors::scalar_error(py, &e))?;
        Ok(ToSympy::new(py)?.forms(&forms)?.unbind())
    }

    /// Binds `name` to a SymPy expression, a Matrix, a Quaternion, a DQ, a tuple (3: vector,
    /// 4: quaternion, 8: dual quaternion) or a number (exact: ints, Fractions, Rationals).
    fn __setitem__(&self, py: Python<'_>, name: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
        if !is_identifier(name) {
            return Err(PyValueError::new_err(format!("`{name}` is not a name")));
        }
        let v = self.convert_in(py, value, name)?;
        self.lock(py)?
            .define(name, v)
            .map_err(|e| errors::eval_error(py, &e, ""))
    }

    fn __contains__(&self, py: Python<'_>, name: &str) -> PyResult<bool> {
        Ok(self.lock(py)?.get(name).is_some())
    }

    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        Ok(self.lock(py)?.bindings().len())
    }

    /// The bound names, sorted.
    fn keys(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        Ok(self.lock(py)?.bindings().keys().cloned().collect())
    }

    /// How each name was bound: "variable", "symbol" or "halfangle".
    fn kinds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, b) in self.lock(py)?.bindings() {
            let kind = match &b.kind {
                dqsym::lang::BindingKind::Variable => "variable",
                dqsym::lang::BindingKind::Symbol => "symbol",
                dqsym::lang::BindingKind::HalfAngle { .. } => "halfangle",
                _ => "other",
            };
            d.set_item(k, kind)?;
        }
        Ok(d)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(format!(
            "dqsym.Session({} bindings)",
            self.lock(py)?.bindings().len()
        ))
    }
}

/// Evaluates `src` as `dqsym -e` does (every free name is a symbol) and returns the value of
/// its last displayed result as a SymPy object (None if nothing is displayed). Keyword
/// arguments bind names first: `evaluate("transform(q, p)", q=..., p=(x, 0, 0))`.
#[pyfunction]
#[pyo3(signature = (src, **bindings))]
pub(crate) fn evaluate(
    py: Python<'_>,
    src: &str,
    bindings: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyObject> {
    let s = Session::new(
        py,
        true,
        Limits::SCRIPT.term_limit,
        Limits::SCRIPT.work_budget,
        Limits::SCRIPT.max_exponent,
        Limits::SCRIPT.max_depth,
        bindings,
    )?;
    s.eval(py, src)
}

/// The value in the project's LaTeX (`--format latex`): a SymPy expression, a Matrix, a
/// Quaternion, a DQ or a tuple, each scalar put in closed form first.
#[pyfunction]
pub(crate) fn latex(py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<String> {
    shown_value(py, value, Format::Latex)
}

/// The value as the command line prints it (plain robotics notation: `c12` for
/// `cos(theta1 + theta2)`, with its legend).
#[pyfunction]
pub(crate) fn text(py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<String> {
    shown_value(py, value, Format::Plain)
}

fn shown_value(py: Python<'_>, value: &Bound<'_, PyAny>, format: Format) -> PyResult<String> {
    let _limits = Limits::SCRIPT.enter();
    let v = FromPython::new(py)?.value(value, "value")?;
    let (r, interrupted) = work::run(py, Limits::SCRIPT, None, move || {
        show_value(
            &v,
            &ShowOptions {
                format,
                explicit: false,
            },
        )
    })?;
    if let Some(e) = interrupted {
        return Err(e);
    }
    r.map(|s| s.trim_end().to_owned())
        .map_err(|e| errors::other(py, e.to_string()))
}
