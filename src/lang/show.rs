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

use super::eval::Displayed;
use super::value::Value;
use crate::{closed_form, legend, plain, Expr, PlainOptions, Quat, Scalar, ScalarError};
use num_traits::Zero;

/// The output language.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Format {
    /// Plain text in robotics notation.
    #[default]
    Plain,
}

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
        })
    }
}

fn lay_out(v: &Value, opts: &ShowOptions) -> Result<Laid, ScalarError> {
    let mut w = Writer {
        opts: PlainOptions {
            shorthand: !opts.explicit,
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

/// A displayed result as text, `label = value`, ending with a newline.
///
/// # Errors
/// Only when the value holds a scalar error value, which the evaluator never returns.
pub fn show(d: &Displayed, opts: &ShowOptions) -> Result<String, ScalarError> {
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
/// Only when the value holds a scalar error value.
pub fn show_value(v: &Value, opts: &ShowOptions) -> Result<String, ScalarError> {
    let laid = lay_out(v, opts)?;
    let mut out = laid.lines.join("\n");
    out.push('\n');
    if let Some(l) = legend_line(&laid.exprs, opts) {
        out += &l;
        out.push('\n');
    }
    Ok(out)
}
