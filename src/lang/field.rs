//! One expression of the language evaluated to an exact scalar: the fields of robot files and
//! the `--point` option. Free names are symbols; `pi`, `sqrt`, `cos`, `sin` work as in scripts.

use super::{parse_expr, Session, Value};
use crate::kin::split_top_level;
use crate::Scalar;

/// The exact scalar value of `text`, or a one-line message saying why there is none.
pub fn eval_scalar_text(text: &str) -> Result<Scalar, String> {
    let e = parse_expr(text).map_err(|e| format!("`{text}`: {}", e.message()))?;
    let session = Session::with_implicit_symbols();
    match session.eval(&e) {
        Ok(Value::Scalar(s)) => Ok(s),
        Ok(v) => Err(format!(
            "`{text}` is {}, not a number or symbolic expression",
            v.describe()
        )),
        Err(err) => Err(format!("`{text}`: {}", err.message())),
    }
}

/// A comma-separated point `x, y, z`, each coordinate an expression.
pub fn eval_point_text(text: &str) -> Result<[Scalar; 3], String> {
    let parts: Vec<&str> = split_top_level(text);
    if parts.len() != 3 {
        return Err(format!(
            "a point needs 3 coordinates separated by commas, found {}",
            parts.len()
        ));
    }
    Ok([
        eval_scalar_text(parts[0])?,
        eval_scalar_text(parts[1])?,
        eval_scalar_text(parts[2])?,
    ])
}
