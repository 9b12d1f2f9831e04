//! The values a script computes, and the arithmetic between them.
//!
//! The typing rules, which `:help` repeats for users:
//! - A 4-tuple is a quaternion, a 3-tuple a vector; `I`/`eps` is the dual unit, a dual
//!   quaternion, so `I*(x, y, z)` is the dual part `eps (0; x, y, z)` of Appendix III.
//! - A number or symbol may be added to a dual quaternion (the paper's points
//!   `1 + I*(0, y, 0)`), and a quaternion may be added to one (`(c, s, 0, 0) + I*(...)`), both
//!   promoting to a dual quaternion. A number or symbol may *not* be added to a quaternion or a
//!   vector: in the paper a 4-tuple is a whole quaternion, so `(c3, s3, 0, 0) + l1` is a
//!   missing `I*` or a misplaced component far more often than it is meant.
//! - Products keep their order (quaternions do not commute). In a product with a quaternion or
//!   a dual quaternion, a vector is the pure quaternion `(0, x, y, z)`.
//! - Division only by nonzero numbers (rationals and radicals); powers only with integer
//!   exponents.
//! - A matrix may hold quotients of expressions (`screwparams` of a planar displacement divides
//!   by sin(theta/2)). Such a matrix adds to matrices, multiplies with matrices and scalars, and
//!   divides by numbers like any other; it becomes a plain matrix again whenever every entry
//!   reduces to an expression.

use crate::{DualQuat, Frac, Quat, Scalar, ScalarError};
use num_traits::{One, Zero};

/// The default largest exponent accepted by `^`, in absolute value ([`crate::Context::max_exponent`] is
/// the current one). Larger powers of symbols are one cheap term but never meant, and larger
/// powers of sums blow up; both are refused at once.
pub const MAX_EXPONENT: u64 = crate::scalar::DEFAULT_MAX_EXPONENT;

/// A value computed by a script.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Value {
    /// A number or symbolic expression.
    Scalar(Scalar),
    /// A quaternion `(w, x, y, z)`.
    Quat(Quat<Scalar>),
    /// A dual quaternion `q + eps q_eps`.
    DualQuat(DualQuat<Scalar>),
    /// A vector `(x, y, z)`.
    Vector([Scalar; 3]),
    /// A matrix: at least one row, all rows of the same non-zero length.
    Matrix(Vec<Vec<Scalar>>),
    /// A matrix shaped as [`Value::Matrix`] with at least one entry that [`Frac::new`] does not
    /// reduce to a scalar, such as the centre `(d1 s - d2 c)/(2 s)` of a planar displacement.
    /// Operations build it through `quotient_matrix`, so it is never all scalars.
    QuotientMatrix(Vec<Vec<Frac>>),
}

/// Why an operation on values failed; the evaluator adds the place.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum OpError {
    /// The operand types do not fit the operation.
    Type(String),
    /// An exact scalar operation failed.
    Scalar(ScalarError),
    /// An exponent that is not a small integer.
    Exponent(String),
    /// No inverse.
    NotInvertible(String),
}

impl From<ScalarError> for OpError {
    fn from(e: ScalarError) -> Self {
        OpError::Scalar(e)
    }
}

pub(crate) type OpResult = Result<Value, OpError>;

impl Value {
    /// What the value is, in words, for messages: "a quaternion", "a 2x2 matrix".
    pub fn describe(&self) -> String {
        match self {
            Value::Scalar(_) => "a scalar".into(),
            Value::Quat(_) => "a quaternion".into(),
            Value::DualQuat(_) => "a dual quaternion".into(),
            Value::Vector(_) => "a vector".into(),
            Value::Matrix(rows) => format!("a {}x{} matrix", rows.len(), rows[0].len()),
            Value::QuotientMatrix(rows) => format!(
                "a {}x{} matrix with quotient entries",
                rows.len(),
                rows[0].len()
            ),
        }
    }

    /// Every scalar inside the value.
    pub fn scalars(&self) -> Vec<&Scalar> {
        match self {
            Value::Scalar(s) => vec![s],
            Value::Quat(q) => vec![&q.w, &q.x, &q.y, &q.z],
            Value::DualQuat(d) => {
                let (r, e) = (&d.real, &d.dual);
                vec![&r.w, &r.x, &r.y, &r.z, &e.w, &e.x, &e.y, &e.z]
            }
            Value::Vector(v) => v.iter().collect(),
            Value::Matrix(rows) => rows.iter().flatten().collect(),
            Value::QuotientMatrix(rows) => rows
                .iter()
                .flatten()
                .flat_map(|f| [f.num(), f.den()])
                .collect(),
        }
    }

    /// The value itself, or the first error value inside it.
    pub fn check(self) -> Result<Value, ScalarError> {
        if let Some(e) = self.scalars().iter().find_map(|s| s.as_error()) {
            return Err(e.clone());
        }
        Ok(self)
    }

    /// Applies `f` to every scalar, keeping the shape. `f` must be linear (a negation, a
    /// scaling): of a quotient it maps the numerator.
    pub(crate) fn map(&self, f: &dyn Fn(&Scalar) -> Scalar) -> Value {
        let q = |q: &Quat<Scalar>| Quat::new(f(&q.w), f(&q.x), f(&q.y), f(&q.z));
        match self {
            Value::Scalar(s) => Value::Scalar(f(s)),
            Value::Quat(x) => Value::Quat(q(x)),
            Value::DualQuat(d) => {
                Value::DualQuat(DualQuat::from_real_and_dual(q(&d.real), q(&d.dual)))
            }
            Value::Vector(v) => Value::Vector([f(&v[0]), f(&v[1]), f(&v[2])]),
            Value::Matrix(rows) => {
                Value::Matrix(rows.iter().map(|r| r.iter().map(f).collect()).collect())
            }
            Value::QuotientMatrix(rows) => quotient_matrix(
                rows.iter()
                    .map(|r| {
                        r.iter()
                            .map(|q| {
                                Frac::new(f(q.num()), q.den().clone())
                                    .unwrap_or_else(|e| Frac::from(Scalar::error(e)))
                            })
                            .collect()
                    })
                    .collect(),
            ),
        }
    }

    /// The entries of a matrix, plain or with quotients, as quotients.
    fn frac_rows(&self) -> Option<Vec<Vec<Frac>>> {
        match self {
            Value::Matrix(rows) => Some(
                rows.iter()
                    .map(|r| r.iter().cloned().map(Frac::from).collect())
                    .collect(),
            ),
            Value::QuotientMatrix(rows) => Some(rows.clone()),
            _ => None,
        }
    }

    /// The value as a dual quaternion, where that is a promotion the rules allow in sums
    /// (scalars, quaternions) and products (also vectors).
    fn promote(&self, vectors: bool) -> Option<DualQuat<Scalar>> {
        match self {
            Value::Scalar(s) => Some(DualQuat::from_real(Quat::from_scalar(s.clone()))),
            Value::Quat(q) => Some(DualQuat::from_real(q.clone())),
            Value::DualQuat(d) => Some(d.clone()),
            Value::Vector(v) if vectors => Some(DualQuat::from_real(Quat::from_vector(v))),
            _ => None,
        }
    }

    /// The value as a quaternion in a product: a quaternion, or a vector as a pure one.
    fn as_quat(&self) -> Option<Quat<Scalar>> {
        match self {
            Value::Quat(q) => Some(q.clone()),
            Value::Vector(v) => Some(Quat::from_vector(v)),
            _ => None,
        }
    }
}

/// A matrix of quotients as a value: a plain [`Value::Matrix`] when every entry is a scalar.
pub(crate) fn quotient_matrix(rows: Vec<Vec<Frac>>) -> Value {
    if rows.iter().flatten().all(|f| f.as_scalar().is_some()) {
        return Value::Matrix(
            rows.iter()
                .map(|r| r.iter().map(|f| f.num().clone()).collect())
                .collect(),
        );
    }
    Value::QuotientMatrix(rows)
}

/// The matrix sum or product of `a` and `b` when one of them has quotient entries.
fn quotient_op(a: &Value, b: &Value, op: QuotientOp) -> OpResult {
    let (Some(x), Some(y)) = (a.frac_rows(), b.frac_rows()) else {
        return Err(unreachable_type());
    };
    let rows = match op {
        QuotientOp::Add { sub } => {
            let mut rows = Vec::with_capacity(x.len());
            for (r, s) in x.iter().zip(&y) {
                let mut row = Vec::with_capacity(r.len());
                for (p, q) in r.iter().zip(s) {
                    row.push(if sub { p.sub(q)? } else { p.add(q)? });
                }
                rows.push(row);
            }
            rows
        }
        QuotientOp::Mul => {
            let mut rows = Vec::with_capacity(x.len());
            for r in &x {
                let mut row = Vec::with_capacity(y[0].len());
                for j in 0..y[0].len() {
                    let mut acc = Frac::from(Scalar::zero());
                    for (p, yrow) in r.iter().zip(&y) {
                        acc = acc.add(&p.mul(&yrow[j])?)?;
                    }
                    row.push(acc);
                }
                rows.push(row);
            }
            rows
        }
    };
    Ok(quotient_matrix(rows))
}

/// What [`quotient_op`] computes.
#[derive(Clone, Copy)]
enum QuotientOp {
    Add { sub: bool },
    Mul,
}

/// The rows and columns of a matrix value.
fn shape(v: &Value) -> Option<(usize, usize)> {
    match v {
        Value::Matrix(rows) => Some((rows.len(), rows[0].len())),
        Value::QuotientMatrix(rows) => Some((rows.len(), rows[0].len())),
        _ => None,
    }
}

/// `a + b` (or `a - b` when `sub`).
pub(crate) fn add(a: &Value, b: &Value, sub: bool) -> OpResult {
    let op = |x: &Scalar, y: &Scalar| if sub { x - y } else { x + y };
    let word = if sub { "subtract" } else { "add" };
    Ok(match (a, b) {
        (Value::Scalar(x), Value::Scalar(y)) => Value::Scalar(op(x, y)),
        (Value::Quat(x), Value::Quat(y)) => Value::Quat(if sub { x - y } else { x + y }),
        (Value::Vector(x), Value::Vector(y)) => {
            Value::Vector([op(&x[0], &y[0]), op(&x[1], &y[1]), op(&x[2], &y[2])])
        }
        (
            Value::Matrix(_) | Value::QuotientMatrix(_),
            Value::Matrix(_) | Value::QuotientMatrix(_),
        ) if shape(a) != shape(b) => {
            return Err(OpError::Type(format!(
                "cannot {word} {} and {}: the shapes differ",
                a.describe(),
                b.describe()
            )))
        }
        (Value::Matrix(x), Value::Matrix(y)) => Value::Matrix(
            x.iter()
                .zip(y)
                .map(|(r, s)| r.iter().zip(s).map(|(p, q)| op(p, q)).collect())
                .collect(),
        ),
        (Value::Matrix(_) | Value::QuotientMatrix(_), Value::QuotientMatrix(_))
        | (Value::QuotientMatrix(_), Value::Matrix(_)) => {
            return quotient_op(a, b, QuotientOp::Add { sub })
        }
        (Value::DualQuat(_), Value::Scalar(_) | Value::Quat(_) | Value::DualQuat(_))
        | (Value::Scalar(_) | Value::Quat(_), Value::DualQuat(_)) => {
            let (x, y) = (a.promote(false), b.promote(false));
            let (Some(x), Some(y)) = (x, y) else {
                return Err(unreachable_type());
            };
            Value::DualQuat(if sub { x - y } else { x + y })
        }
        (Value::Quat(_), Value::Scalar(_)) | (Value::Scalar(_), Value::Quat(_)) => {
            return Err(OpError::Type(format!(
                "cannot {word} a scalar and a quaternion: a 4-tuple is a whole quaternion; \
                 put the scalar inside it, as `(w + s, x, y, z)`, or write `s*(1, 0, 0, 0)`, \
                 or make it a dual part with `I*(...)`"
            )))
        }
        _ => {
            return Err(OpError::Type(format!(
                "cannot {word} {} and {}",
                a.describe(),
                b.describe()
            )))
        }
    })
}

/// A type combination the match above has already excluded; an error rather than a panic.
fn unreachable_type() -> OpError {
    OpError::Type("internal error: unexpected operand types".into())
}

/// `-a`.
pub(crate) fn neg(a: &Value) -> Value {
    a.map(&|s| -s)
}

/// `a * b`, in that order.
pub(crate) fn mul(a: &Value, b: &Value) -> OpResult {
    Ok(match (a, b) {
        (Value::Scalar(x), Value::Scalar(y)) => Value::Scalar(x * y),
        (Value::Scalar(k), v) | (v, Value::Scalar(k)) => v.map(&|s| s * k),
        (
            Value::Matrix(_) | Value::QuotientMatrix(_),
            Value::Matrix(_) | Value::QuotientMatrix(_),
        ) if shape(a).map(|s| s.1) != shape(b).map(|s| s.0) => {
            return Err(OpError::Type(format!(
                "cannot multiply {} by {}: the inner sizes differ",
                a.describe(),
                b.describe()
            )))
        }
        (Value::Matrix(x), Value::Matrix(y)) => {
            let n = y[0].len();
            let rows = x
                .iter()
                .map(|r| {
                    (0..n)
                        .map(|j| {
                            r.iter()
                                .zip(y)
                                .fold(Scalar::zero(), |acc, (p, row)| acc + p * &row[j])
                        })
                        .collect()
                })
                .collect();
            Value::Matrix(rows)
        }
        (Value::Matrix(_) | Value::QuotientMatrix(_), Value::QuotientMatrix(_))
        | (Value::QuotientMatrix(_), Value::Matrix(_)) => {
            return quotient_op(a, b, QuotientOp::Mul)
        }
        (Value::QuotientMatrix(_), _) | (_, Value::QuotientMatrix(_)) => {
            return Err(OpError::Type(format!(
                "cannot multiply {} by {}",
                a.describe(),
                b.describe()
            )))
        }
        (Value::Matrix(_), _) | (_, Value::Matrix(_)) => {
            return Err(OpError::Type(format!(
                "cannot multiply {} by {}: convert with `matrix(q)` or `frommatrix(M)` first",
                a.describe(),
                b.describe()
            )))
        }
        (Value::DualQuat(_), _) | (_, Value::DualQuat(_)) => {
            let (Some(x), Some(y)) = (a.promote(true), b.promote(true)) else {
                return Err(unreachable_type());
            };
            Value::DualQuat(x * y)
        }
        _ => {
            let (Some(x), Some(y)) = (a.as_quat(), b.as_quat()) else {
                return Err(OpError::Type(format!(
                    "cannot multiply {} by {}",
                    a.describe(),
                    b.describe()
                )));
            };
            Value::Quat(x * y)
        }
    })
}

/// `a / b`: `b` must be a nonzero number.
pub(crate) fn div(a: &Value, b: &Value) -> OpResult {
    let Value::Scalar(d) = b else {
        return Err(OpError::Type(format!(
            "cannot divide by {}: divide only by numbers, and multiply by `inverse(q)` instead",
            b.describe()
        )));
    };
    let r = d.recip().check()?;
    Ok(a.map(&|s| s * &r))
}

/// The quaternion conjugate (postfix `'`, `conj`): of both parts of a dual quaternion.
pub(crate) fn conj(a: &Value) -> OpResult {
    Ok(match a {
        Value::Scalar(_) => a.clone(),
        Value::Quat(q) => Value::Quat(q.conjugate()),
        Value::DualQuat(d) => Value::DualQuat(d.conjugate()),
        Value::Vector(_) => neg(a),
        Value::Matrix(_) | Value::QuotientMatrix(_) => {
            return Err(OpError::Type(format!(
                "the quaternion conjugate needs a quaternion or a dual quaternion, found {}; \
                 `transpose(M)` transposes a matrix",
                a.describe()
            )))
        }
    })
}

/// The derivative of every entry by the symbol `t`; of a quotient by the quotient rule.
pub(crate) fn diff(a: &Value, t: &str) -> OpResult {
    match a {
        Value::QuotientMatrix(rows) => {
            let mut out = Vec::with_capacity(rows.len());
            for r in rows {
                let row: Result<Vec<Frac>, ScalarError> = r.iter().map(|q| q.diff(t)).collect();
                out.push(row?);
            }
            Ok(quotient_matrix(out))
        }
        _ => Ok(a.map(&|s| s.diff(t))),
    }
}

/// The transpose of a matrix, plain or with quotients.
pub(crate) fn transpose(a: &Value) -> Option<Value> {
    fn t<T: Clone>(rows: &[Vec<T>]) -> Vec<Vec<T>> {
        (0..rows[0].len())
            .map(|j| rows.iter().map(|r| r[j].clone()).collect())
            .collect()
    }
    match a {
        Value::Matrix(rows) => Some(Value::Matrix(t(rows))),
        Value::QuotientMatrix(rows) => Some(Value::QuotientMatrix(t(rows))),
        _ => None,
    }
}

/// The inverse of a scalar, quaternion or dual quaternion.
pub(crate) fn inverse(a: &Value) -> OpResult {
    let fail = |what: &str| {
        OpError::NotInvertible(format!(
            "{} is not invertible: {what} is not a nonzero number",
            a.describe()
        ))
    };
    Ok(match a {
        Value::Scalar(s) => Value::Scalar(s.recip().check()?),
        Value::Quat(q) => Value::Quat(q.try_inverse().ok_or_else(|| fail("|q|^2"))?),
        Value::DualQuat(d) => Value::DualQuat(
            d.try_inverse()
                .ok_or_else(|| fail("the norm of the real part"))?,
        ),
        _ => {
            return Err(OpError::Type(format!(
                "`inverse` needs a scalar, a quaternion or a dual quaternion, found {}",
                a.describe()
            )))
        }
    })
}

/// `base ^ exponent` for an integer exponent of at most the context's
/// [`max_exponent`](crate::Context::max_exponent) in absolute value.
pub(crate) fn pow(base: &Value, exponent: &Value) -> OpResult {
    let n = match exponent {
        Value::Scalar(s) => s.as_rational().filter(|q| q.is_integer()).ok_or_else(|| {
            OpError::Exponent(format!(
                "the exponent must be an integer, got {s}; use `sqrt` for square roots"
            ))
        })?,
        other => {
            return Err(OpError::Exponent(format!(
                "the exponent must be an integer, got {}",
                other.describe()
            )))
        }
    };
    let magnitude = n.numer().magnitude();
    let limit = crate::Context::entered().max_exponent();
    let Some(k) = num_traits::ToPrimitive::to_u64(magnitude).filter(|&k| k <= limit) else {
        return Err(OpError::Exponent(format!(
            "exponent {n} is too large: the limit is {limit} (--max-exponent raises it)"
        )));
    };
    let negative = n < num_rational::BigRational::zero();
    let base = if negative {
        inverse(base)?
    } else {
        base.clone()
    };
    match &base {
        Value::Scalar(s) => Ok(Value::Scalar(s.pow(k))),
        Value::Quat(_) | Value::DualQuat(_) => {
            let mut acc = match &base {
                Value::Quat(_) => Value::Quat(Quat::identity()),
                _ => Value::DualQuat(DualQuat::identity()),
            };
            let mut sq = base.clone();
            let mut e = k;
            while e > 0 {
                crate::Context::check_cancelled()?;
                if e & 1 == 1 {
                    acc = mul(&acc, &sq)?.check()?;
                }
                e >>= 1;
                if e > 0 {
                    sq = mul(&sq, &sq)?.check()?;
                }
            }
            Ok(acc)
        }
        other => Err(OpError::Type(format!(
            "cannot raise {} to a power",
            other.describe()
        ))),
    }
}

/// Whether `s` is exactly one.
pub(crate) fn is_one(s: &Scalar) -> bool {
    *s == Scalar::one()
}
