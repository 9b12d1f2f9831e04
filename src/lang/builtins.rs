//! The built-in functions: their table (names, arities, help with an example) and their
//! implementations over [`Value`]s.

use super::ast::{Expr, Ident, Span};
use super::eval::{op_error, scalar_error, EvalError, EvalErrorKind, Evaluator, Event, Result};
use super::value::{self, Value};
use crate::{
    closed_form,
    kin::{dh_link, mdh_link},
    plain, DualQuat, Frac, Matrix4, PlainOptions, Quat, Scalar, ScalarError,
};
use num_traits::{One, Zero};

/// What runs a built-in: its name (shared implementations read it), the evaluated arguments
/// (as many as its arity allows) and the place of the call.
pub(super) type Run = fn(&'static str, &[Arg], Span) -> Result<Value>;

/// A built-in function: its name, arity and help as `:help` lists them, and the function that
/// runs it.
#[derive(Clone, Copy)]
pub struct Builtin {
    /// The name it is called by.
    pub name: &'static str,
    /// The signature, `dh(theta, d, a, alpha)`.
    pub usage: &'static str,
    /// What it does, one line.
    pub doc: &'static str,
    /// An example call that runs in a session where `syms theta1 d1 a1 alpha1 t l` holds.
    pub example: &'static str,
    min: usize,
    max: usize,
    run: Run,
}

impl std::fmt::Debug for Builtin {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Builtin")
            .field("name", &self.name)
            .field("usage", &self.usage)
            .field("min", &self.min)
            .field("max", &self.max)
            .finish_non_exhaustive()
    }
}

pub(super) const fn b(
    name: &'static str,
    usage: &'static str,
    min: usize,
    max: usize,
    doc: &'static str,
    example: &'static str,
    run: Run,
) -> Builtin {
    Builtin {
        name,
        usage,
        doc,
        example,
        min,
        max,
        run,
    }
}

/// Every built-in, in the order `:help` lists them: the core ones, then DQ Robotics' vocabulary
/// (`dqr.rs`).
pub const BUILTINS: &[Builtin] = &ALL;

const ALL: [Builtin; CORE.len() + super::dqr::TABLE.len()] = concat(&CORE, &super::dqr::TABLE);

/// `a` then `b` (`N` is their total length).
const fn concat<const A: usize, const B: usize, const N: usize>(
    a: &[Builtin; A],
    b: &[Builtin; B],
) -> [Builtin; N] {
    let mut out = [a[0]; N];
    let mut i = 0;
    while i < N {
        out[i] = if i < A { a[i] } else { b[i - A] };
        i += 1;
    }
    out
}

/// The core built-ins.
const CORE: [Builtin; 31] = [
    b(
        "rot",
        "rot(axis, angle) or rot(axis, angle, point)",
        2,
        3,
        "rotation by angle about the unit axis (through point)",
        "rot((1, 0, 0), theta1, (0, l, 0))",
        run_rot,
    ),
    b(
        "trans",
        "trans(v)",
        1,
        1,
        "translation by the vector v: 1 + eps v/2",
        "trans((0, 0, d1))",
        run_trans,
    ),
    b(
        "screw",
        "screw(axis, point, angle, slide)",
        4,
        4,
        "rotation by angle about the line through point, and slide along it",
        "screw((0, 0, 1), (0, l, 0), theta1, d1)",
        run_screw,
    ),
    b(
        "dh",
        "dh(theta, d, a, alpha)",
        4,
        4,
        "standard Denavit-Hartenberg link Rz(theta) Tz(d) Tx(a) Rx(alpha)",
        "dh(theta1, d1, a1, pi/2)",
        run_dh,
    ),
    b(
        "mdh",
        "mdh(alpha, a, theta, d)",
        4,
        4,
        "modified (Craig) DH link Rx(alpha) Tx(a) Rz(theta) Tz(d), the paper's sec 5",
        "mdh(alpha1, a1, theta1, d1)",
        run_dh,
    ),
    b(
        "point",
        "point(v)",
        1,
        1,
        "the point DQ 1 + eps (0; v)",
        "point((0, l, 0))",
        run_point,
    ),
    b(
        "transform",
        "transform(q, v)",
        2,
        2,
        "image of the point v under the unit DQ q: vector part of q (1 + eps v) cconj(q)",
        "transform(rot((1, 0, 0), theta1), (0, l, 0))",
        run_transform,
    ),
    b(
        "matrix",
        "matrix(q)",
        1,
        1,
        "the 4x4 homogeneous matrix of a unit DQ",
        "matrix(rot((0, 0, 1), theta1))",
        run_matrix,
    ),
    b(
        "frommatrix",
        "frommatrix(M)",
        1,
        1,
        "the unit DQ of a 4x4 rigid-motion matrix",
        "frommatrix([1, 0, 0, l; 0, 1, 0, 0; 0, 0, 1, 0; 0, 0, 0, 1])",
        run_frommatrix,
    ),
    b(
        "closed",
        "closed(x)",
        1,
        1,
        "x itself; every displayed value is shown in closed form",
        "closed(cos(t)^2 - sin(t)^2)",
        run_closed,
    ),
    b(
        "jacobian",
        "jacobian(q, [x1, x2, ...])",
        2,
        2,
        "8 x n matrix of the derivatives of the 8 DQ components by each symbol",
        "jacobian(dh(theta1, 0, a1, 0), [theta1])",
        run_jacobian,
    ),
    b(
        "gjacobian",
        "gjacobian(q, [q1, q2, ...])",
        2,
        2,
        "6 x n geometric Jacobian of a unit DQ pose: linear velocity (x, y, z) over angular (x, y, z)",
        "gjacobian(rot((0, 0, 1), theta1) * trans((l, 0, 0)), [theta1])",
        run_gjacobian,
    ),
    b(
        "screwparams",
        "screwparams(q)",
        1,
        1,
        "screw of a unit DQ as rows: (angle, slide, 0), axis n, moment m, axis point nearest O, \
         as quotients where needed",
        "screwparams(dh(theta1, d1, a1, 0))",
        run_screwparams,
    ),
    b(
        "ik",
        "ik(q, [q1, ..., qn]) or ik(q, [q1, ..., qn], T, qk)",
        2,
        4,
        "closed-form inverse kinematics of the chain q(q1, ..., qn) for the target T = [r11, r12, \
         r13, px; ...; 0, 0, 0, 1] (symbolic unless given; a 7-joint chain takes the free joint \
         qk given, else the first that leaves a supported family): one row (qk, a, b, c, n) per \
         joint in the order solved; revolute: a cos qk + b sin qk = c, n = 2 both roots, n = 1 \
         the root qk = atan2(-a, b); prismatic: a qk^2 + b qk + c = 0 (n roots); as `dqsym ik`",
        "ik(dh(theta1, 0, a1, 0) * dh(t, 0, l, 0), [theta1, t])",
        run_ik,
    ),
    b(
        "diff",
        "diff(x, t)",
        2,
        2,
        "derivative of x (any value) by the symbol t",
        "diff(sin(t)^2, t)",
        run_diff,
    ),
    b(
        "cos",
        "cos(angle)",
        1,
        1,
        "cosine of an angle (symbols and multiples of pi)",
        "cos(pi/6)",
        run_cos,
    ),
    b(
        "sin",
        "sin(angle)",
        1,
        1,
        "sine of an angle",
        "sin(theta1 + pi/2)",
        run_sin,
    ),
    b(
        "sqrt",
        "sqrt(x)",
        1,
        1,
        "exact square root of a non-negative rational",
        "sqrt(8)",
        run_sqrt,
    ),
    b(
        "real",
        "real(q)",
        1,
        1,
        "the real part q of q + eps q_eps",
        "real(trans((1, 2, 3)))",
        run_real,
    ),
    b(
        "dual",
        "dual(q)",
        1,
        1,
        "the dual part q_eps of q + eps q_eps",
        "dual(trans((1, 2, 3)))",
        run_real,
    ),
    b(
        "norm2",
        "norm2(q)",
        1,
        1,
        "the dual-number norm q q* = |q|^2 + eps 2 (q . q_eps), as a dual number a + eps b",
        "norm2(rot((0, 0, 1), t))",
        run_norm2,
    ),
    b(
        "inverse",
        "inverse(q)",
        1,
        1,
        "inverse of a scalar, quaternion or DQ (error if none)",
        "inverse((1, 1, 0, 0))",
        run_inverse,
    ),
    b(
        "unit",
        "unit(q)",
        1,
        1,
        "q itself if it is a unit DQ (a rigid motion), else an error",
        "unit(dh(theta1, d1, a1, alpha1))",
        run_unit,
    ),
    b(
        "conj",
        "conj(q)",
        1,
        1,
        "quaternion conjugate q* + eps q_eps*; postfix q' is the same",
        "conj((1, 2, 3, 4))",
        run_conj,
    ),
    b(
        "dconj",
        "dconj(q)",
        1,
        1,
        "dual conjugate q - eps q_eps (eq 8)",
        "dconj(trans((1, 0, 0)))",
        run_dconj,
    ),
    b(
        "cconj",
        "cconj(q)",
        1,
        1,
        "combined conjugate q* - eps q_eps* (eq 9)",
        "cconj(rot((1, 0, 0), t, (0, l, 0)))",
        run_dconj,
    ),
    b(
        "transpose",
        "transpose(M)",
        1,
        1,
        "matrix transpose",
        "transpose([1, 2; 3, 4])",
        run_transpose,
    ),
    b(
        "latex",
        "latex(x)",
        1,
        1,
        "x itself, displayed as LaTeX",
        "latex(rot((0, 0, 1), theta1))",
        run_closed,
    ),
    b(
        "sympy",
        "sympy(x)",
        1,
        1,
        "x itself, displayed as SymPy input (sympify parses it)",
        "sympy(cos(t)^2 - sin(t)^2)",
        run_closed,
    ),
    b(
        "rust",
        "rust(x)",
        1,
        1,
        "x itself, displayed as a Rust function of its symbols",
        "rust(transform(rot((0, 0, 1), theta1), (l, 0, 0)))",
        run_closed,
    ),
    b(
        "plain",
        "plain(x)",
        1,
        1,
        "x itself, displayed as plain text",
        "plain(sin(2*t))",
        run_closed,
    ),
];

/// The built-in called `name`.
pub fn lookup(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}

/// An evaluated argument with its place.
pub(super) struct Arg {
    pub(super) value: Value,
    pub(super) span: Span,
}

/// Calls the built-in `func` on `args`.
pub(crate) fn call(ev: &Evaluator<'_>, func: &Ident, args: &[Expr], span: Span) -> Result<Value> {
    let Some(builtin) = lookup(&func.name) else {
        let hint = if BUILTINS
            .iter()
            .any(|b| b.name.eq_ignore_ascii_case(&func.name))
        {
            let b = BUILTINS
                .iter()
                .find(|b| b.name.eq_ignore_ascii_case(&func.name))
                .map_or("", |b| b.name);
            if b.chars().all(|c| !c.is_ascii_uppercase()) {
                format!("; built-in names are lowercase: `{b}`")
            } else {
                format!("; built-in names are case-sensitive: `{b}`")
            }
        } else {
            "; `:help` lists the built-ins".to_owned()
        };
        return Err(EvalError::new(
            EvalErrorKind::UnknownFunction {
                name: func.name.clone(),
                hint,
            },
            func.span,
        ));
    };
    if args.len() < builtin.min || args.len() > builtin.max {
        let expected = match (builtin.min, builtin.max) {
            (1, 1) => "1 argument".to_owned(),
            (a, b) if a == b => format!("{a} arguments"),
            (a, b) => format!("{a} or {b} arguments"),
        };
        return Err(EvalError::new(
            EvalErrorKind::Arity {
                func: builtin.name.to_owned(),
                expected,
                got: args.len(),
                usage: builtin.usage.to_owned(),
            },
            span,
        ));
    }
    let mut vals = Vec::with_capacity(args.len());
    for a in args {
        vals.push(Arg {
            value: ev.expr(a)?,
            span: a.span,
        });
    }
    let name = builtin.name;
    let out = (builtin.run)(name, &vals, span)?;
    let out = out.check().map_err(|e| scalar_error(e, span))?;
    let text = |k: usize| (args[k].to_string(), vals[k].value.clone());
    match name {
        "rot" | "trans" | "screw" | "dh" | "mdh" | "point" | "twist" | "bodytwist" | "qdot"
        | "sclerp" | "sclerpdot" => ev.record(|| Event::Built {
            func: name,
            args: (0..args.len()).map(text).collect(),
            value: out.clone(),
        }),
        "transform" => ev.record(|| Event::Transform {
            q: text(0),
            v: text(1),
            value: out.clone(),
        }),
        _ => {}
    }
    Ok(out)
}

/// The built-in `rot`.
fn run_rot(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        let axis = unit_axis(name, &vals[0])?;
        let angle = scalar(name, "the angle", &vals[1])?;
        match vals.get(2) {
            None => Value::DualQuat(DualQuat::rotation(&axis, angle)),
            Some(p) => {
                let p = vector(name, "the point", p)?;
                Value::DualQuat(DualQuat::rotation_about_point(&axis, angle, p))
            }
        }
    })
}

/// The built-in `trans`.
fn run_trans(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok(Value::DualQuat(DualQuat::translation(vector(
        name,
        "the argument",
        &vals[0],
    )?)))
}

/// The built-in `screw`.
fn run_screw(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        let axis = unit_axis(name, &vals[0])?;
        let p = vector(name, "the point", &vals[1])?;
        let angle = scalar(name, "the angle", &vals[2])?;
        let slide = scalar(name, "the slide", &vals[3])?;
        Value::DualQuat(DualQuat::screw(&axis, p, angle, slide))
    })
}

/// The built-in `dh`, `mdh`.
fn run_dh(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        let what = if name == "dh" {
            ["theta", "d", "a", "alpha"]
        } else {
            ["alpha", "a", "theta", "d"]
        };
        let mut s = Vec::new();
        for (v, w) in vals.iter().zip(what) {
            s.push(scalar(name, w, v)?);
        }
        Value::DualQuat(if name == "dh" {
            dh_link(s[0], s[1], s[2], s[3])
        } else {
            mdh_link(s[0], s[1], s[2], s[3])
        })
    })
}

/// The built-in `point`.
fn run_point(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok(Value::DualQuat(DualQuat::point(vector(
        name,
        "the argument",
        &vals[0],
    )?)))
}

/// The built-in `transform`.
fn run_transform(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        let q = unit_dq(name, &vals[0])?;
        let v = match &vals[1].value {
            Value::DualQuat(p)
                if value::is_one(&p.real.w)
                    && p.real.vector_part().iter().all(Zero::is_zero)
                    && p.dual.w.is_zero() =>
            {
                p.dual.vector_part()
            }
            _ => vector(name, "the point", &vals[1])?.clone(),
        };
        Value::Vector(q.transform_point(&v))
    })
}

/// The built-in `matrix`.
fn run_matrix(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        let q = unit_dq(name, &vals[0])?;
        Value::Matrix(q.to_matrix().rows.iter().map(|r| r.to_vec()).collect())
    })
}

/// The built-in `frommatrix`.
fn run_frommatrix(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        let m = matrix4(name, &vals[0])?;
        let not_rigid = || {
            invalid(
                "`frommatrix` needs a rigid-motion matrix: last row 0 0 0 1 and a rotation \
                 block (R^T R = I and det R = 1 exactly) whose quaternion has an exact square root",
                vals[0].span,
            )
        };
        if !is_rotation(&m.rotation_block()).map_err(|e| scalar_error(e, vals[0].span))? {
            return Err(not_rigid());
        }
        let q = DualQuat::from_matrix(&m).ok_or_else(not_rigid)?;
        Value::DualQuat(q)
    })
}

/// Whether `r` is a rotation, exactly: `R^T R = I` and `det R = 1` (a scaling or a reflection
/// is not). A limit reached on the way is the error, never a "no".
fn is_rotation(r: &[[Scalar; 3]; 3]) -> std::result::Result<bool, ScalarError> {
    let zero = |x: Scalar| match x.as_error() {
        Some(e) => Err(e.clone()),
        None => Ok(x.is_zero_value()),
    };
    for i in 0..3 {
        for j in i..3 {
            let dot = (0..3).fold(Scalar::int(0), |acc, k| acc + r[k][i].clone() * &r[k][j]);
            if !zero(dot - Scalar::int(i64::from(i == j)))? {
                return Ok(false);
            }
        }
    }
    let minor = |a: usize, b: usize| r[1][a].clone() * &r[2][b] - r[1][b].clone() * &r[2][a];
    let det = r[0][0].clone() * minor(1, 2) - r[0][1].clone() * minor(0, 2)
        + r[0][2].clone() * minor(0, 1);
    zero(det - Scalar::int(1))
}

/// The built-in `closed`, `latex`, `sympy`, `rust`, `plain`.
fn run_closed(_name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok(vals[0].value.clone())
}

/// The built-in `jacobian`.
fn run_jacobian(_name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    jacobian(&vals[0], &vals[1])
}

/// The built-in `gjacobian`.
fn run_gjacobian(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        let q = unit_dq(name, &vals[0])?;
        let names = symbol_list(name, &vals[1])?;
        let refs: Vec<&str> = names.iter().map(String::as_str).collect();
        Value::Matrix(crate::kin::geometric_jacobian(&q, &refs))
    })
}

/// The built-in `screwparams`.
fn run_screwparams(_name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    screw_params(&vals[0])
}

/// The built-in `ik`.
fn run_ik(_name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    ik(vals)
}

/// The built-in `diff`.
fn run_diff(name: &'static str, vals: &[Arg], span: Span) -> Result<Value> {
    Ok({
        let t = symbol_name(name, &vals[1].value, vals[1].span)?;
        value::diff(&vals[0].value, &t).map_err(|e| op_error(e, span))?
    })
}

/// The built-in `cos`.
fn run_cos(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok(Value::Scalar(scalar(name, "the angle", &vals[0])?.cos()))
}

/// The built-in `sin`.
fn run_sin(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok(Value::Scalar(scalar(name, "the angle", &vals[0])?.sin()))
}

/// The built-in `sqrt`.
fn run_sqrt(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok(Value::Scalar(
        scalar(name, "the argument", &vals[0])?.sqrt(),
    ))
}

/// The built-in `real`, `dual`.
fn run_real(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        let d = dq_like(name, &vals[0])?;
        Value::Quat(if name == "real" { d.real } else { d.dual })
    })
}

/// The built-in `norm2`.
fn run_norm2(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok(match &vals[0].value {
        Value::Quat(q) => Value::Scalar(q.norm_squared()),
        _ => {
            let n = dq_like(name, &vals[0])?.norm_squared();
            Value::DualQuat(DualQuat::from_real_and_dual(
                Quat::from_scalar(n.re),
                Quat::from_scalar(n.du),
            ))
        }
    })
}

/// The built-in `inverse`.
fn run_inverse(_name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    value::inverse(&vals[0].value).map_err(|e| op_error(e, vals[0].span))
}

/// The built-in `unit`.
fn run_unit(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        unit_dq(name, &vals[0])?;
        vals[0].value.clone()
    })
}

/// The built-in `conj`.
fn run_conj(_name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    value::conj(&vals[0].value).map_err(|e| op_error(e, vals[0].span))
}

/// The built-in `dconj`, `cconj`.
fn run_dconj(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    Ok({
        let d = dq_like(name, &vals[0])?;
        Value::DualQuat(if name == "dconj" {
            d.dual_conjugate()
        } else {
            d.combined_conjugate()
        })
    })
}

/// The built-in `transpose`.
fn run_transpose(name: &'static str, vals: &[Arg], _span: Span) -> Result<Value> {
    value::transpose(&vals[0].value).ok_or_else(|| {
        type_error(
            name,
            "the argument",
            "a matrix",
            &vals[0].value,
            vals[0].span,
        )
    })
}

pub(super) fn invalid(message: &str, span: Span) -> EvalError {
    EvalError::new(EvalErrorKind::Invalid(message.to_owned()), span)
}

pub(super) fn type_error(
    func: &str,
    what: &str,
    expected: &str,
    found: &Value,
    span: Span,
) -> EvalError {
    EvalError::new(
        EvalErrorKind::Type(format!(
            "`{func}`: {what} must be {expected}, found {}",
            found.describe()
        )),
        span,
    )
}

fn scalar<'v>(func: &str, what: &str, a: &'v Arg) -> Result<&'v Scalar> {
    match &a.value {
        Value::Scalar(s) => Ok(s),
        other => Err(type_error(func, what, "a scalar", other, a.span)),
    }
}

fn vector<'v>(func: &str, what: &str, a: &'v Arg) -> Result<&'v [Scalar; 3]> {
    match &a.value {
        Value::Vector(v) => Ok(v),
        other => Err(type_error(func, what, "a vector (x, y, z)", other, a.span)),
    }
}

/// A unit axis: its squared length must be exactly 1.
fn unit_axis(func: &str, a: &Arg) -> Result<[Scalar; 3]> {
    let v = vector(func, "the axis", a)?;
    let len2 = v.iter().fold(Scalar::zero(), |acc, x| acc + x * x);
    if len2 != Scalar::one() {
        return Err(EvalError::new(
            EvalErrorKind::Invalid(format!(
                "`{func}`: the axis must be a unit vector, but its squared length is {}",
                text(&len2)
            )),
            a.span,
        ));
    }
    Ok(v.clone())
}

/// A quaternion (as a DQ with zero dual part) or a dual quaternion.
pub(super) fn dq_like(func: &str, a: &Arg) -> Result<DualQuat<Scalar>> {
    match &a.value {
        Value::DualQuat(d) => Ok(d.clone()),
        Value::Quat(q) => Ok(DualQuat::from_real(q.clone())),
        other => Err(type_error(
            func,
            "the argument",
            "a dual quaternion or a quaternion",
            other,
            a.span,
        )),
    }
}

/// A unit dual quaternion: both constraints of sec 2 hold exactly.
pub(super) fn unit_dq(func: &str, a: &Arg) -> Result<DualQuat<Scalar>> {
    let d = dq_like(func, a)?;
    let c = d.unit_constraints();
    if !c.hold_exactly() {
        return Err(EvalError::new(
            EvalErrorKind::NotUnit(format!(
                "`{func}` needs a unit dual quaternion (a rigid motion), but |q|^2 - 1 = {} \
                 and q . q_eps = {}",
                text(&c.norm_minus_one),
                text(&c.real_dot_dual)
            )),
            a.span,
        ));
    }
    Ok(d)
}

fn matrix4(func: &str, a: &Arg) -> Result<Matrix4<Scalar>> {
    if let Value::Matrix(rows) = &a.value {
        if rows.len() == 4 && rows[0].len() == 4 {
            let row = |i: usize| -> [Scalar; 4] {
                [
                    rows[i][0].clone(),
                    rows[i][1].clone(),
                    rows[i][2].clone(),
                    rows[i][3].clone(),
                ]
            };
            return Ok(Matrix4::from_rows([row(0), row(1), row(2), row(3)]));
        }
    }
    Err(type_error(
        func,
        "the argument",
        "a 4x4 matrix",
        &a.value,
        a.span,
    ))
}

/// The name of the symbol `v` is, or an error.
fn symbol_name(func: &str, v: &Value, span: Span) -> Result<String> {
    if let Value::Scalar(s) = v {
        if let [sym] = s.symbols().as_slice() {
            if *s == Scalar::sym(sym.name()) {
                return Ok(sym.name().to_owned());
            }
        }
    }
    Err(EvalError::new(
        EvalErrorKind::Type(format!(
            "`{func}`: differentiate by a symbol such as theta1, found {}",
            match v {
                Value::Scalar(s) => format!("the expression {}", text(s)),
                other => other.describe(),
            }
        )),
        span,
    ))
}

/// `screwparams(q)`: the screw of a unit DQ as a 4 x 3 matrix, rows (angle, slide, 0), axis,
/// moment, nearest point. Parameters that divide by sin(theta/2) by an expression (the centres
/// of planar displacements) are quotients, so the matrix then has quotient entries.
fn screw_params(a: &Arg) -> Result<Value> {
    let q = unit_dq("screwparams", a)?;
    let sp = crate::kin::screw_parameters(&q)
        .map_err(|e| invalid(&format!("screwparams: {e}"), a.span))?;
    Ok(value::quotient_matrix(vec![
        vec![Frac::from(sp.angle), sp.slide, Frac::from(Scalar::int(0))],
        sp.axis.to_vec(),
        sp.moment.to_vec(),
        sp.point.to_vec(),
    ]))
}

/// `ik(q, vars[, T][, free])`: the closed-form inverse kinematics as one equation per joint.
fn ik(vals: &[Arg]) -> Result<Value> {
    let q = unit_dq("ik", &vals[0])?;
    let vars = symbol_list("ik", &vals[1])?;
    let mut target = None;
    let mut free = None;
    for a in &vals[2..] {
        match &a.value {
            Value::Matrix(_) if target.is_none() => target = Some(matrix4("ik", a)?),
            Value::Scalar(s)
                if free.is_none()
                    && s.symbols().len() == 1
                    && *s == Scalar::sym(s.symbols()[0].name()) =>
            {
                free = Some(s.symbols()[0].name().to_owned());
            }
            other => {
                return Err(type_error(
                    "ik",
                    "an argument after the joint list",
                    "the target (a 4x4 matrix) or the free joint (a symbol), each at most once",
                    other,
                    a.span,
                ))
            }
        }
    }
    let sol = crate::ik::solve_dq(
        "chain",
        &q,
        &vars,
        &crate::ik::IkOptions {
            free,
            ..Default::default()
        },
    )
    .map_err(|e| invalid(&format!("ik: {e}"), vals[0].span))?;
    let at = |x: &Scalar| -> Scalar {
        let mut y = x.clone();
        if let Some(t) = &target {
            for (r, row) in crate::ik::TARGET_SYMBOLS.iter().enumerate() {
                for (c, name) in row.iter().enumerate() {
                    y = y.subs(name, &t.rows[r][c]);
                }
            }
        }
        y
    };
    let zero = Scalar::int(0);
    let one = Scalar::int(1);
    let mut rows = Vec::new();
    for step in &sol.steps {
        let (a, b, c, n) = match &step.formula {
            crate::ik::Formula::Trig { a, b, c } => (at(a), at(b), at(c), 2),
            crate::ik::Formula::Atan2 { y, x } => (-at(y), at(x), zero.clone(), 1),
            crate::ik::Formula::Value { v } => (zero.clone(), one.clone(), -at(v), 1),
            crate::ik::Formula::Linear { a, b } => (zero.clone(), at(a), -at(b), 1),
            crate::ik::Formula::Quadratic { beta, gamma } => {
                (one.clone(), Scalar::int(2) * at(beta), at(gamma), 2)
            }
        };
        if let Some(e) = [&a, &b, &c].iter().find_map(|x| x.as_error()) {
            return Err(invalid(&format!("ik: {e}"), vals[0].span));
        }
        rows.push(vec![Scalar::sym(&step.variable), a, b, c, Scalar::int(n)]);
    }
    Ok(Value::Matrix(rows))
}

/// The symbol names of a list argument `[x1, x2, ...]`.
pub(super) fn symbol_list(func: &str, vars: &Arg) -> Result<Vec<String>> {
    let list: Vec<Value> = match &vars.value {
        Value::Matrix(rows) if rows.len() == 1 || rows[0].len() == 1 => {
            rows.iter().flatten().cloned().map(Value::Scalar).collect()
        }
        Value::Scalar(s) => vec![Value::Scalar(s.clone())],
        Value::Vector(v) => v.iter().cloned().map(Value::Scalar).collect(),
        other => {
            return Err(type_error(
                func,
                "the second argument",
                "a list of symbols [x1, x2, ...]",
                other,
                vars.span,
            ))
        }
    };
    list.iter()
        .map(|v| symbol_name(func, v, vars.span))
        .collect()
}

/// `jacobian(q, vars)`: rows are the 8 (or 4) components, columns the variables.
fn jacobian(q: &Arg, vars: &Arg) -> Result<Value> {
    let comps: Vec<Scalar> = match &q.value {
        Value::DualQuat(d) => d.components().to_vec(),
        Value::Quat(x) => x.components().to_vec(),
        other => {
            return Err(type_error(
                "jacobian",
                "the first argument",
                "a dual quaternion",
                other,
                q.span,
            ))
        }
    };
    let list: Vec<Value> = match &vars.value {
        Value::Matrix(rows) if rows.len() == 1 || rows[0].len() == 1 => {
            rows.iter().flatten().cloned().map(Value::Scalar).collect()
        }
        Value::Scalar(s) => vec![Value::Scalar(s.clone())],
        Value::Vector(v) => v.iter().cloned().map(Value::Scalar).collect(),
        Value::Quat(x) => x.components().into_iter().map(Value::Scalar).collect(),
        other => {
            return Err(type_error(
                "jacobian",
                "the second argument",
                "a list of symbols [x1, x2, ...]",
                other,
                vars.span,
            ))
        }
    };
    let mut names = Vec::new();
    for v in &list {
        names.push(symbol_name("jacobian", v, vars.span)?);
    }
    Ok(Value::Matrix(
        comps
            .iter()
            .map(|c| names.iter().map(|n| c.diff(n)).collect())
            .collect(),
    ))
}

/// A scalar in closed form, for messages.
pub(super) fn text(s: &Scalar) -> String {
    match closed_form(s) {
        Ok(e) => plain(
            &e,
            &PlainOptions {
                shorthand: false,
                decimals: false,
            },
        ),
        Err(e) => e.to_string(),
    }
}
