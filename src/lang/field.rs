//! One expression of the language evaluated to an exact scalar: the fields of robot files and
//! the `--point` option. Free names are symbols; `pi`, `sqrt`, `cos`, `sin` work as in scripts.

use super::{parse_expr, Session, Value};
use crate::kin::{split_top_level, ExprError};
use crate::Scalar;

/// The exact scalar value of `text`, or why there is none (one line).
pub fn eval_scalar_text(text: &str) -> Result<Scalar, ExprError> {
    let invalid = |message: String| ExprError::Invalid {
        text: text.to_string(),
        message,
    };
    let e = parse_expr(text).map_err(|e| invalid(e.message()))?;
    let session = Session::with_implicit_symbols();
    match session.eval(&e) {
        Ok(Value::Scalar(s)) => Ok(s),
        Ok(v) => Err(ExprError::NotScalar {
            text: text.to_string(),
            kind: v.describe(),
        }),
        Err(err) => Err(invalid(err.message())),
    }
}

/// A comma-separated point `x, y, z`, each coordinate an expression.
pub fn eval_point_text(text: &str) -> Result<[Scalar; 3], ExprError> {
    let parts: Vec<&str> = split_top_level(text);
    if parts.len() != 3 {
        return Err(ExprError::PointArity { found: parts.len() });
    }
    Ok([
        eval_scalar_text(parts[0])?,
        eval_scalar_text(parts[1])?,
        eval_scalar_text(parts[2])?,
    ])
}
