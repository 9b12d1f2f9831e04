//! Displayed results as text: each scalar in closed form, then a printer.
//!
//! Layout (plain):
//! ```text
//! v2 = 1 + eps (0, 0, l1 + l2 + l3 c3, l3 s3)
//!   where c3 = cos(theta3), s3 = sin(theta3)
//! M =
//!   [c1, -s1, 0, 0]
//!   ...
//! ```
//! A part of a dual quaternion whose vector part is zero is written as its scalar, so a point
//! reads `1 + eps (0, x, y, z)` and Appendix II's product `q1 q3 + eps (q1 q4 + q2 q3)`.
//!
//! The other formats reuse the emitters: LaTeX (`latex`, `latex_tuple`, ...), SymPy (a scalar
//! as `sympify` text, a quaternion or vector as a tuple, a dual quaternion as the 8-tuple
//! `(w, x, y, z, w_eps, x_eps, y_eps, z_eps)`, a matrix as `Matrix([[...], ...])`), and Rust (a
//! function of the value's symbols, from `rust_function`).
//!
//! A matrix with quotient entries prints each quotient as `(num)/(den)` (`\frac` in LaTeX),
//! both parts in closed form. Its Rust function returns the numerators and the denominators as
//! two matrices, so that the caller decides what a vanishing denominator (theta = 0) means.

use super::eval::Displayed;
use super::value::Value;
use crate::{
    closed_form,
    emit::{
        arguments, function, latex_dual_quat, latex_matrix, latex_quotient_matrix, latex_symbol,
        latex_tuple, names::Lang, sympy, sympy_quotient, CodegenError, CodegenOptions, Output,
    },
    latex, plain,
    print::{legend, plain_quotient},
    Expr, Frac, LatexOptions, PlainOptions, Quat, Scalar, ScalarError,
};
use num_traits::Zero;
use thiserror::Error;

/// Why a value could not be shown.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum ShowError {
    /// The value holds a scalar error value (the evaluator never returns one).
    #[error(transparent)]
    Scalar(#[from] ScalarError),
    /// Code generation refused the value.
    #[error(transparent)]
    Codegen(#[from] CodegenError),
}

impl ShowError {
    /// The error at `span`, the statement or expression whose value could not be shown, so it
    /// is rendered with its line, column and caret like any evaluation error (a limit reached
    /// while the closed form is built for display, Ctrl-C during it).
    pub fn at(self, span: super::Span) -> super::EvalError {
        use super::EvalErrorKind as K;
        let kind = match self {
            ShowError::Scalar(ScalarError::Cancelled) => K::Interrupted,
            ShowError::Scalar(e) => K::Scalar(e),
            ShowError::Codegen(e) => K::Invalid(e.to_string()),
        };
        super::EvalError::new(kind, span)
    }
}

use crate::print::Format;

/// How results are shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShowOptions {
    /// The output language.
    pub format: Format,
    /// Plain format: `cos(theta1 + theta2)` instead of `c12`.
    pub explicit: bool,
}

/// A value laid out as text, before the label is added.
struct Laid {
    /// One line, or several for a matrix.
    lines: Vec<String>,
    /// The closed forms, for the legend.
    exprs: Vec<Expr>,
}

struct Writer {
    opts: PlainOptions,
    exprs: Vec<Expr>,
}

impl Writer {
    fn scalar(&mut self, s: &Scalar) -> Result<String, ScalarError> {
        let e = closed_form(s)?;
        let t = plain(&e, &self.opts);
        self.exprs.push(e);
        Ok(t)
    }

    fn quotient(&mut self, q: &Frac) -> Result<String, ScalarError> {
        let (n, d) = closed_quotient(q)?;
        let t = plain_quotient(&n, &d, &self.opts);
        self.exprs.push(n);
        self.exprs.push(d);
        Ok(t)
    }

    fn list(&mut self, items: &[&Scalar]) -> Result<String, ScalarError> {
        let mut parts = Vec::with_capacity(items.len());
        for s in items {
            parts.push(self.scalar(s)?);
        }
        Ok(parts.join(", "))
    }

    /// A quaternion part of a DQ: its scalar when the vector part is zero.
    fn part(&mut self, q: &Quat<Scalar>) -> Result<String, ScalarError> {
        if q.vector_part().iter().all(Zero::is_zero) {
            let w = self.scalar(&q.w)?;
            let simple = !w.contains([' ', '+', '-']) || w.starts_with('(');
            Ok(if simple { w } else { format!("({w})") })
        } else {
            Ok(format!("({})", self.list(&[&q.w, &q.x, &q.y, &q.z])?))
        }
    }

    fn value(&mut self, v: &Value) -> Result<Vec<String>, ScalarError> {
        Ok(match v {
            Value::Scalar(s) => vec![self.scalar(s)?],
            Value::Quat(q) => vec![format!("({})", self.list(&[&q.w, &q.x, &q.y, &q.z])?)],
            Value::Vector(x) => vec![format!("({})", self.list(&[&x[0], &x[1], &x[2]])?)],
            Value::DualQuat(d) => {
                let re = if d.real.vector_part().iter().all(Zero::is_zero) {
                    self.scalar(&d.real.w)?
                } else {
                    self.part(&d.real)?
                };
                let du = self.part(&d.dual)?;
                vec![format!("{re} + eps {du}")]
            }
            Value::Matrix(rows) => {
                let mut lines = Vec::with_capacity(rows.len());
                for r in rows {
                    let items: Vec<&Scalar> = r.iter().collect();
                    lines.push(format!("[{}]", self.list(&items)?));
                }
                lines
            }
            Value::QuotientMatrix(rows) => {
                let mut lines = Vec::with_capacity(rows.len());
                for r in rows {
                    let mut parts = Vec::with_capacity(r.len());
                    for q in r {
                        parts.push(self.quotient(q)?);
                    }
                    lines.push(format!("[{}]", parts.join(", ")));
                }
                lines
            }
        })
    }
}

fn lay_out(v: &Value, opts: &ShowOptions) -> Result<Laid, ScalarError> {
    let mut w = Writer {
        opts: PlainOptions {
            shorthand: !opts.explicit,
            decimals: false,
        },
        exprs: Vec::new(),
    };
    let lines = w.value(v)?;
    Ok(Laid {
        lines,
        exprs: w.exprs,
    })
}

/// The legend line for the shorthand names in `exprs`, if any.
fn legend_line(exprs: &[Expr], opts: &ShowOptions) -> Option<String> {
    if opts.explicit {
        return None;
    }
    let refs: Vec<&Expr> = exprs.iter().collect();
    let names = legend(&refs);
    (!names.is_empty()).then(|| format!("  where {}", names.join(", ")))
}

/// Closed forms of a list of scalars.
fn closed_all<'a>(items: impl IntoIterator<Item = &'a Scalar>) -> Result<Vec<Expr>, ScalarError> {
    items.into_iter().map(closed_form).collect()
}

/// The closed forms of a quotient's numerator and denominator.
fn closed_quotient(q: &Frac) -> Result<(Expr, Expr), ScalarError> {
    Ok((closed_form(q.num())?, closed_form(q.den())?))
}

/// Closed forms of the rows of a matrix with quotient entries.
fn closed_quotient_rows(rows: &[Vec<Frac>]) -> Result<Vec<Vec<(Expr, Expr)>>, ScalarError> {
    rows.iter()
        .map(|r| r.iter().map(closed_quotient).collect())
        .collect()
}

fn quat_items(q: &Quat<Scalar>) -> [&Scalar; 4] {
    [&q.w, &q.x, &q.y, &q.z]
}

/// The value in LaTeX.
pub(crate) fn latex_value(v: &Value, o: &LatexOptions) -> Result<String, ScalarError> {
    Ok(match v {
        Value::Scalar(s) => latex(&closed_form(s)?, o),
        Value::Quat(q) => latex_tuple(&closed_all(quat_items(q))?, o),
        Value::Vector(x) => latex_tuple(&closed_all(x)?, o),
        Value::DualQuat(d) => latex_dual_quat(
            &closed_all(quat_items(&d.real))?,
            &closed_all(quat_items(&d.dual))?,
            o,
        ),
        Value::Matrix(rows) => {
            let rows: Result<Vec<Vec<Expr>>, ScalarError> = rows.iter().map(closed_all).collect();
            latex_matrix(&rows?, o)
        }
        Value::QuotientMatrix(rows) => latex_quotient_matrix(&closed_quotient_rows(rows)?, o),
    })
}

/// The value as SymPy text.
fn sympy_value(v: &Value) -> Result<String, ScalarError> {
    let tuple = |items: Vec<Expr>| {
        let parts: Vec<String> = items.iter().map(sympy).collect();
        format!("({})", parts.join(", "))
    };
    Ok(match v {
        Value::Scalar(s) => sympy(&closed_form(s)?),
        Value::Quat(q) => tuple(closed_all(quat_items(q))?),
        Value::Vector(x) => tuple(closed_all(x)?),
        Value::DualQuat(d) => tuple(closed_all(d.components().iter().collect::<Vec<_>>())?),
        Value::Matrix(rows) => {
            let mut out = Vec::new();
            for r in rows {
                let parts: Vec<String> = closed_all(r)?.iter().map(sympy).collect();
                out.push(format!("[{}]", parts.join(", ")));
            }
            format!("Matrix([{}])", out.join(", "))
        }
        Value::QuotientMatrix(rows) => {
            let mut out = Vec::new();
            for r in closed_quotient_rows(rows)? {
                let parts: Vec<String> = r.iter().map(|(n, d)| sympy_quotient(n, d)).collect();
                out.push(format!("[{}]", parts.join(", ")));
            }
            format!("Matrix([{}])", out.join(", "))
        }
    })
}

/// Whether `label` can name a function or a LaTeX symbol.
fn is_identifier(label: &str) -> bool {
    let mut chars = label.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The language of a code format, whose one writer ([`function`]) writes it.
fn emitter(format: Format) -> Option<Lang> {
    match format {
        Format::Rust => Some(Lang::Rust),
        Format::C => Some(Lang::C),
        Format::Python => Some(Lang::Python),
        _ => None,
    }
}

/// The value as a function named after `label` (or `value`) in the language of `emit`. A
/// matrix with quotient entries becomes two outputs, `{name}_num` and `{name}_den`: the
/// emitters have no division.
fn code_value(label: &str, v: &Value, lang: Lang) -> Result<String, ShowError> {
    let name = if is_identifier(label) {
        label.to_lowercase()
    } else {
        "value".to_owned()
    };
    let doc = format!("`{label}`, generated by dqsym.");
    let outputs = match v {
        Value::Scalar(s) => vec![Output::scalar(&name, &doc, closed_form(s)?)],
        Value::Quat(q) => vec![Output::vector(&name, &doc, closed_all(quat_items(q))?)],
        Value::Vector(x) => vec![Output::vector(&name, &doc, closed_all(x)?)],
        Value::DualQuat(d) => vec![Output::vector(
            &name,
            &doc,
            closed_all(d.components().iter().collect::<Vec<_>>())?,
        )],
        Value::Matrix(rows) => {
            let rows: Result<Vec<Vec<Expr>>, ScalarError> = rows.iter().map(closed_all).collect();
            vec![Output::matrix(&name, &doc, rows?)]
        }
        Value::QuotientMatrix(rows) => {
            let rows = closed_quotient_rows(rows)?;
            let part = |den: bool| -> Vec<Vec<Expr>> {
                rows.iter()
                    .map(|r| {
                        r.iter()
                            .map(|(n, d)| if den { d.clone() } else { n.clone() })
                            .collect()
                    })
                    .collect()
            };
            let entry = format!("entry (i, j) is {name}_num[i][j] / {name}_den[i][j]");
            vec![
                Output::matrix(
                    &format!("{name}_num"),
                    &format!("The numerators of `{label}`: {entry}."),
                    part(false),
                ),
                Output::matrix(
                    &format!("{name}_den"),
                    &format!(
                        "The denominators of `{label}`; an entry is undefined where one is 0."
                    ),
                    part(true),
                ),
            ]
        }
    };
    let args = arguments(&outputs, &[]);
    Ok(function(
        lang,
        &name,
        &doc,
        &outputs,
        &args,
        &CodegenOptions::default(),
    )?)
}

fn latex_options(opts: &ShowOptions) -> LatexOptions {
    LatexOptions {
        shorthand: !opts.explicit,
        ..LatexOptions::default()
    }
}

/// A displayed result as text, `label = value`, ending with a newline.
///
/// # Errors
/// When the value holds a scalar error value (the evaluator never returns one), or code
/// generation refuses it.
pub fn show(d: &Displayed, opts: &ShowOptions) -> Result<String, ShowError> {
    let opts = &ShowOptions {
        format: d.format.unwrap_or(opts.format),
        ..*opts
    };
    match opts.format {
        Format::Plain => {}
        Format::Latex => {
            let value = latex_value(&d.value, &latex_options(opts))?;
            return Ok(if is_identifier(&d.label) {
                format!("{} = {value}\n", latex_symbol(&d.label))
            } else {
                format!("% {}\n{value}\n", d.label)
            });
        }
        Format::Sympy => return Ok(format!("{} = {}\n", d.label, sympy_value(&d.value)?)),
        code => {
            if let Some(emit) = emitter(code) {
                return code_value(&d.label, &d.value, emit);
            }
        }
    }
    let laid = lay_out(&d.value, opts)?;
    let mut out = if let [one] = laid.lines.as_slice() {
        format!("{} = {one}\n", d.label)
    } else {
        let mut s = format!("{} =\n", d.label);
        for l in &laid.lines {
            s += &format!("  {l}\n");
        }
        s
    };
    if let Some(l) = legend_line(&laid.exprs, opts) {
        out += &l;
        out.push('\n');
    }
    Ok(out)
}

/// A value alone, without a label, ending with a newline (for one-liners).
///
/// # Errors
/// As [`show`].
pub fn show_value(v: &Value, opts: &ShowOptions) -> Result<String, ShowError> {
    match opts.format {
        Format::Plain => {}
        Format::Latex => return Ok(latex_value(v, &latex_options(opts))? + "\n"),
        Format::Sympy => return Ok(sympy_value(v)? + "\n"),
        code => {
            if let Some(emit) = emitter(code) {
                return code_value("value", v, emit);
            }
        }
    }
    let laid = lay_out(v, opts)?;
    let mut out = laid.lines.join("\n");
    out.push('\n');
    if let Some(l) = legend_line(&laid.exprs, opts) {
        out += &l;
        out.push('\n');
    }
    Ok(out)
}
