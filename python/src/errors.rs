//! The library's errors as Python exceptions. Each carries the message the command line
//! prints (`str(e)`, with the source line and a caret where there is a place) and, as
//! attributes, its parts: `message`, `line`, `column` (1-based, or None), and for robot files
//! `file`, `joint` and `field`.

use dqsym::{EvalError as LibEvalError, EvalErrorKind, ParseError as LibParseError, ScalarError};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyKeyboardInterrupt};
use pyo3::prelude::*;

create_exception!(
    dqsym,
    DqsymError,
    PyException,
    "An error of dqsym: bad input or a limit."
);
create_exception!(
    dqsym,
    ParseError,
    DqsymError,
    "Text that is not a dqsym statement (line and column in `line`, `column`)."
);
create_exception!(
    dqsym,
    EvalError,
    DqsymError,
    "A statement that cannot be evaluated (line and column in `line`, `column`)."
);
create_exception!(
    dqsym,
    LimitError,
    EvalError,
    "A limit was reached: the term limit, the work budget, the exponent limit."
);
create_exception!(
    dqsym,
    RobotError,
    DqsymError,
    "A robot file that cannot be read (file, joint and field where known)."
);

/// An exception of type `T` with `str(e)` = `shown` and the attributes set.
fn with_attrs<T: pyo3::PyTypeInfo>(
    py: Python<'_>,
    shown: String,
    attrs: &[(&str, PyObject)],
) -> PyErr {
    let err = PyErr::from_type(py.get_type::<T>(), (shown,));
    let value = err.value(py);
    for (k, v) in attrs {
        // Setting an attribute on a fresh exception object cannot fail in practice; if it did,
        // the exception would still carry its message.
        let _ = value.setattr(*k, v);
    }
    err
}

/// A parse error, `src` being the parsed text.
pub(crate) fn parse_error(py: Python<'_>, e: &LibParseError) -> PyErr {
    with_attrs::<ParseError>(
        py,
        e.rendered().to_owned(),
        &[
            (
                "message",
                e.message().into_pyobject(py).unwrap().into_any().unbind(),
            ),
            (
                "line",
                e.line().into_pyobject(py).unwrap().into_any().unbind(),
            ),
            (
                "column",
                e.col().into_pyobject(py).unwrap().into_any().unbind(),
            ),
            (
                "rendered",
                e.rendered().into_pyobject(py).unwrap().into_any().unbind(),
            ),
        ],
    )
}

/// Whether a scalar error is a limit (not a mistake in the input).
fn is_limit(e: &ScalarError) -> bool {
    matches!(
        e,
        ScalarError::TooLarge { .. }
            | ScalarError::TooManyPairs { .. }
            | ScalarError::Budget { .. }
            | ScalarError::OutOfRange(_)
    )
}

/// An evaluation error of a statement of `src`; an interruption is KeyboardInterrupt.
pub(crate) fn eval_error(py: Python<'_>, e: &LibEvalError, src: &str) -> PyErr {
    if matches!(e.kind(), EvalErrorKind::Interrupted) {
        return PyKeyboardInterrupt::new_err("interrupted; the bindings are unchanged");
    }
    let rendered = e.render(src);
    let span = e.span();
    let (line, col) = if span.line == 0 {
        (py.None(), py.None())
    } else {
        (
            span.line.into_pyobject(py).unwrap().into_any().unbind(),
            span.col.into_pyobject(py).unwrap().into_any().unbind(),
        )
    };
    let attrs = [
        (
            "message",
            e.message().into_pyobject(py).unwrap().into_any().unbind(),
        ),
        ("line", line),
        ("column", col),
        (
            "rendered",
            rendered
                .as_str()
                .into_pyobject(py)
                .unwrap()
                .into_any()
                .unbind(),
        ),
    ];
    match e.kind() {
        EvalErrorKind::Scalar(s) if is_limit(s) => with_attrs::<LimitError>(py, rendered, &attrs),
        _ => with_attrs::<EvalError>(py, rendered, &attrs),
    }
}

/// A scalar error outside any statement (a robot's derivation, a conversion).
pub(crate) fn scalar_error(py: Python<'_>, e: &ScalarError) -> PyErr {
    let message = e.to_string();
    let attrs = [
        (
            "message",
            message
                .as_str()
                .into_pyobject(py)
                .unwrap()
                .into_any()
                .unbind(),
        ),
        ("line", py.None()),
        ("column", py.None()),
    ];
    if is_limit(e) {
        with_attrs::<LimitError>(py, format!("error: {message}"), &attrs)
    } else {
        with_attrs::<EvalError>(py, format!("error: {message}"), &attrs)
    }
}

/// A robot file error, with its file, joint and field.
pub(crate) fn robot_error(py: Python<'_>, e: &dqsym::RobotError) -> PyErr {
    let none = || py.None();
    let s = |x: &str| x.into_pyobject(py).unwrap().into_any().unbind();
    let (file, joint, field) = match e {
        dqsym::RobotError::File { file, .. } => (s(file), none(), none()),
        dqsym::RobotError::Field {
            file, joint, field, ..
        } => (
            s(file),
            joint.into_pyobject(py).unwrap().into_any().unbind(),
            s(field),
        ),
        _ => (none(), none(), none()),
    };
    let message = match e {
        dqsym::RobotError::File { message, .. } | dqsym::RobotError::Field { message, .. } => {
            message.clone()
        }
        other => other.to_string(),
    };
    // `line N, column M: ` at the start of a TOML syntax message.
    let (line, col) = toml_position(&message);
    let num = |n: Option<usize>| match n {
        Some(n) => n.into_pyobject(py).unwrap().into_any().unbind(),
        None => py.None(),
    };
    with_attrs::<RobotError>(
        py,
        format!("error: {e}"),
        &[
            ("message", s(&message)),
            ("file", file),
            ("joint", joint),
            ("field", field),
            ("line", num(line)),
            ("column", num(col)),
        ],
    )
}

/// The position the robot reader puts in front of a TOML syntax error.
fn toml_position(message: &str) -> (Option<usize>, Option<usize>) {
    let Some(rest) = message.strip_prefix("line ") else {
        return (None, None);
    };
    let Some((line, rest)) = rest.split_once(", column ") else {
        return (None, None);
    };
    let Some((col, _)) = rest.split_once(':') else {
        return (None, None);
    };
    (line.parse().ok(), col.parse().ok())
}

/// Any other failure of the library (a report or a walkthrough that could not be made).
pub(crate) fn other(py: Python<'_>, message: String) -> PyErr {
    with_attrs::<DqsymError>(
        py,
        format!("error: {message}"),
        &[
            (
                "message",
                message
                    .as_str()
                    .into_pyobject(py)
                    .unwrap()
                    .into_any()
                    .unbind(),
            ),
            ("line", py.None()),
            ("column", py.None()),
        ],
    )
}

/// A report error: limits as [`LimitError`], the rest as [`DqsymError`].
pub(crate) fn report_error(py: Python<'_>, e: &dqsym::ReportError) -> PyErr {
    match e {
        dqsym::ReportError::Scalar(s) => scalar_error(py, s),
        other_err => other(py, other_err.to_string()),
    }
}

/// A script error already rendered by the library (`error: ...`, ` --> line:col`, the line and
/// a caret), as an EvalError with the position read back from it.
pub(crate) fn rendered(py: Python<'_>, rendered: String) -> PyErr {
    let pos = rendered.lines().find_map(|l| {
        let rest = l.trim_start().strip_prefix("--> ")?;
        let mut parts = rest.rsplitn(2, ':');
        let col: usize = parts.next()?.trim().parse().ok()?;
        let line: usize = parts.next()?.rsplit(':').next()?.trim().parse().ok()?;
        Some((line, col))
    });
    let message = rendered
        .lines()
        .next()
        .unwrap_or("")
        .trim_start_matches("error: ")
        .to_owned();
    let num = |n: Option<usize>| match n {
        Some(n) => n.into_pyobject(py).unwrap().into_any().unbind(),
        None => py.None(),
    };
    with_attrs::<EvalError>(
        py,
        rendered.clone(),
        &[
            (
                "message",
                message
                    .as_str()
                    .into_pyobject(py)
                    .unwrap()
                    .into_any()
                    .unbind(),
            ),
            ("line", num(pos.map(|p| p.0))),
            ("column", num(pos.map(|p| p.1))),
            (
                "rendered",
                rendered
                    .as_str()
                    .into_pyobject(py)
                    .unwrap()
                    .into_any()
                    .unbind(),
            ),
        ],
    )
}
