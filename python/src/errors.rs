//! The library's errors as Python exceptions. Each carries the message the command line
//! prints (`str(e)`, with the source line and a caret where there is a place) and, as
//! attributes, its parts: `message`, `line`, `column` (1-based), `rendered` (the text with the
//! caret), and for robot files `file`, `joint` and `field`. Every exception has every
//! attribute (None where it does not apply), set from one table ([`Attrs::table`]); which
//! class a library error becomes is decided in one place per error type.

use dqsym::{
    lang::EvalErrorKind, EvalError as LibEvalError, ParseError as LibParseError, ScalarError,
};
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

/// The exception classes of the module.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Class {
    Dqsym,
    Parse,
    Eval,
    Limit,
    Robot,
}

impl Class {
    /// A new exception of this class with `str(e)` = `shown`.
    fn new_err(self, shown: String) -> PyErr {
        match self {
            Class::Dqsym => DqsymError::new_err(shown),
            Class::Parse => ParseError::new_err(shown),
            Class::Eval => EvalError::new_err(shown),
            Class::Limit => LimitError::new_err(shown),
            Class::Robot => RobotError::new_err(shown),
        }
    }

    /// A scalar failure: a limit (not a mistake in the input) is a LimitError.
    fn of_scalar(e: &ScalarError) -> Class {
        match e {
            ScalarError::TooLarge { .. }
            | ScalarError::TooManyPairs { .. }
            | ScalarError::Budget { .. }
            | ScalarError::CyclotomicDegree { .. }
            | ScalarError::TooManyDigits { .. }
            | ScalarError::AngleSymbols { .. }
            | ScalarError::OutOfRange(_) => Class::Limit,
            _ => Class::Eval,
        }
    }
}

/// The attributes of an exception.
#[derive(Default)]
struct Attrs<'a> {
    message: &'a str,
    line: Option<usize>,
    column: Option<usize>,
    rendered: Option<&'a str>,
    file: Option<&'a str>,
    joint: Option<usize>,
    field: Option<&'a str>,
}

impl Attrs<'_> {
    /// Every attribute by its Python name.
    fn table(&self, py: Python<'_>) -> [(&'static str, PyObject); 7] {
        let text = |t: Option<&str>| match t {
            Some(t) => t.into_pyobject(py).unwrap().into_any().unbind(),
            None => py.None(),
        };
        let num = |n: Option<usize>| match n {
            Some(n) => n.into_pyobject(py).unwrap().into_any().unbind(),
            None => py.None(),
        };
        [
            ("message", text(Some(self.message))),
            ("line", num(self.line)),
            ("column", num(self.column)),
            ("rendered", text(self.rendered)),
            ("file", text(self.file)),
            ("joint", num(self.joint)),
            ("field", text(self.field)),
        ]
    }

    /// The exception of `class` with `str(e)` = `shown` and these attributes.
    fn raise(&self, py: Python<'_>, class: Class, shown: String) -> PyErr {
        let err = class.new_err(shown);
        let value = err.value(py);
        for (name, v) in self.table(py) {
            // Setting an attribute on a fresh exception object cannot fail in practice; if it
            // did, the exception would still carry its message.
            let _ = value.setattr(name, v);
        }
        err
    }
}

/// A parse error, `src` being the parsed text.
pub(crate) fn parse_error(py: Python<'_>, e: &LibParseError) -> PyErr {
    let message = e.message();
    Attrs {
        message: &message,
        line: Some(e.line()),
        column: Some(e.col()),
        rendered: Some(e.rendered()),
        ..Attrs::default()
    }
    .raise(py, Class::Parse, e.rendered().to_owned())
}

/// An evaluation error of a statement of `src`; an interruption is KeyboardInterrupt.
pub(crate) fn eval_error(py: Python<'_>, e: &LibEvalError, src: &str) -> PyErr {
    if matches!(e.kind(), EvalErrorKind::Interrupted) {
        return PyKeyboardInterrupt::new_err("interrupted; the bindings are unchanged");
    }
    let (rendered, message) = (e.render(src), e.message());
    let span = e.span();
    let at = |n: usize| (span.line != 0).then_some(n);
    let class = match e.kind() {
        EvalErrorKind::Scalar(s) => Class::of_scalar(s),
        _ => Class::Eval,
    };
    Attrs {
        message: &message,
        line: at(span.line),
        column: at(span.col),
        rendered: Some(&rendered),
        ..Attrs::default()
    }
    .raise(py, class, rendered.clone())
}

/// A scalar error outside any statement (a robot's derivation, a conversion).
pub(crate) fn scalar_error(py: Python<'_>, e: &ScalarError) -> PyErr {
    let message = e.to_string();
    Attrs {
        message: &message,
        ..Attrs::default()
    }
    .raise(py, Class::of_scalar(e), format!("error: {message}"))
}

/// A robot file error, with its file, joint and field (and the line and column of a TOML
/// syntax error).
pub(crate) fn robot_error(py: Python<'_>, e: &dqsym::kin::RobotError) -> PyErr {
    let (file, joint, field, message) = match e {
        dqsym::kin::RobotError::File { file, message } => {
            (Some(file.as_str()), None, None, message.clone())
        }
        dqsym::kin::RobotError::Field {
            file,
            joint,
            field,
            message,
        } => (
            Some(file.as_str()),
            Some(*joint),
            Some(field.as_str()),
            message.clone(),
        ),
        other => (None, None, None, other.to_string()),
    };
    // `line N, column M: ` at the start of a TOML syntax message.
    let (line, column) = toml_position(&message);
    Attrs {
        message: &message,
        line,
        column,
        file,
        joint,
        field,
        ..Attrs::default()
    }
    .raise(py, Class::Robot, format!("error: {e}"))
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
    Attrs {
        message: &message,
        ..Attrs::default()
    }
    .raise(py, Class::Dqsym, format!("error: {message}"))
}

/// A report error: limits as [`LimitError`], the rest as [`DqsymError`].
pub(crate) fn report_error(py: Python<'_>, e: &dqsym::app::ReportError) -> PyErr {
    match e {
        dqsym::app::ReportError::Scalar(s) => scalar_error(py, s),
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
        .trim_start_matches("error: ");
    Attrs {
        message,
        line: pos.map(|p| p.0),
        column: pos.map(|p| p.1),
        rendered: Some(&rendered),
        ..Attrs::default()
    }
    .raise(py, Class::Eval, rendered.clone())
}
