//! Conversion at the boundary, in both directions, structurally (no text is parsed):
//!
//! - A closed form ([`dqsym::Expr`]) becomes a SymPy tree built with SymPy's own constructors
//!   (`Add`, `Mul`, `Pow`, `Rational`, `sqrt`, `cos`, `sin`, `Symbol`, `pi`), so it is the
//!   same object `sympify` makes of the SymPy emitter's text, without the parser's cost.
//!   Values: a scalar is an expression, a vector a 3x1 `Matrix`, a quaternion a SymPy
//!   `Quaternion`, a dual quaternion a `dqsym.DQ`, a matrix a `Matrix`.
//! - A SymPy expression (rationals, symbols, `pi`, `+ - * /`, integer powers, square roots,
//!   `cos`, `sin`), a Python int or `Fraction`, a tuple (3: vector, 4: quaternion, 8: dual
//!   quaternion), a SymPy `Quaternion`, a `dqsym.DQ` or a `Matrix` becomes a library value.
//!   Floats are refused: results are exact.

use dqsym::{closed_form, Angle, DualQuat, Expr, Quat, Scalar, Value};
use num_bigint::BigInt;
use num_rational::BigRational;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use std::collections::HashMap;

/// A value's closed forms, computed on the worker thread and converted with the GIL.
#[derive(Clone, Debug)]
pub(crate) enum Forms {
    Scalar(Expr),
    Quat(Vec<Expr>),
    Vector(Vec<Expr>),
    DualQuat(Vec<Expr>),
    Matrix(Vec<Vec<Expr>>),
    /// Numerator and denominator of each entry.
    Quotient(Vec<Vec<(Expr, Expr)>>),
}

fn all(items: &[&Scalar]) -> Result<Vec<Expr>, dqsym::ScalarError> {
    items.iter().map(|s| closed_form(s)).collect()
}

impl Forms {
    /// The closed forms of every scalar of `v`.
    pub(crate) fn of(v: &Value) -> Result<Forms, dqsym::ScalarError> {
        Ok(match v {
            Value::Scalar(s) => Forms::Scalar(closed_form(s)?),
            Value::Quat(q) => Forms::Quat(all(&[&q.w, &q.x, &q.y, &q.z])?),
            Value::Vector(x) => Forms::Vector(all(&[&x[0], &x[1], &x[2]])?),
            Value::DualQuat(d) => {
                let c = d.components();
                Forms::DualQuat(all(&c.iter().collect::<Vec<_>>())?)
            }
            Value::Matrix(rows) => Forms::Matrix(
                rows.iter()
                    .map(|r| all(&r.iter().collect::<Vec<_>>()))
                    .collect::<Result<_, _>>()?,
            ),
            Value::QuotientMatrix(rows) => Forms::Quotient(
                rows.iter()
                    .map(|r| {
                        r.iter()
                            .map(|f| Ok((closed_form(f.num())?, closed_form(f.den())?)))
                            .collect::<Result<Vec<_>, dqsym::ScalarError>>()
                    })
                    .collect::<Result<_, _>>()?,
            ),
            // A kind of value this version of the package does not know.
            other => {
                return Err(dqsym::ScalarError::OutOfRange(format!(
                    "{} cannot be converted to SymPy by this version of the package",
                    other.describe()
                )))
            }
        })
    }
}

/// SymPy's constructors, looked up once per conversion, and the symbols made so far.
pub(crate) struct ToSympy<'py> {
    py: Python<'py>,
    sympy: Bound<'py, PyModule>,
    add: Bound<'py, PyAny>,
    mul: Bound<'py, PyAny>,
    pow: Bound<'py, PyAny>,
    rational: Bound<'py, PyAny>,
    integer: Bound<'py, PyAny>,
    sqrt: Bound<'py, PyAny>,
    cos: Bound<'py, PyAny>,
    sin: Bound<'py, PyAny>,
    symbol: Bound<'py, PyAny>,
    pi: Bound<'py, PyAny>,
    minus_one: Bound<'py, PyAny>,
    symbols: HashMap<String, Bound<'py, PyAny>>,
    /// The cosines and sines made so far (`true`: a sine), shared: a report repeats a few
    /// angles in every entry (the PUMA 560's Jacobian: 384 trigonometric factors a
    /// conversion), and SymPy's objects are immutable.
    trig: HashMap<(bool, Angle), Bound<'py, PyAny>>,
}

impl<'py> ToSympy<'py> {
    pub(crate) fn new(py: Python<'py>) -> PyResult<ToSympy<'py>> {
        let sympy = py.import("sympy")?;
        let get = |n: &str| sympy.getattr(n);
        let integer = get("Integer")?;
        Ok(ToSympy {
            py,
            add: get("Add")?,
            mul: get("Mul")?,
            pow: get("Pow")?,
            rational: get("Rational")?,
            minus_one: integer.call1((-1,))?,
            integer,
            sqrt: get("sqrt")?,
            cos: get("cos")?,
            sin: get("sin")?,
            symbol: get("Symbol")?,
            pi: get("pi")?,
            sympy,
            symbols: HashMap::new(),
            trig: HashMap::new(),
        })
    }

    fn symbol(&mut self, name: &str) -> PyResult<Bound<'py, PyAny>> {
        if let Some(s) = self.symbols.get(name) {
            return Ok(s.clone());
        }
        let s = self.symbol.call1((name,))?;
        self.symbols.insert(name.to_owned(), s.clone());
        Ok(s)
    }

    fn rational(&self, n: BigInt, d: BigInt) -> PyResult<Bound<'py, PyAny>> {
        if d == BigInt::from(1) {
            self.integer.call1((n,))
        } else {
            self.rational.call1((n, d))
        }
    }

    /// `k`, or `-k` when `negate` (negated as a big integer: `i64::MIN` has no negative).
    fn small_signed(
        &self,
        k: &num_rational::Ratio<i64>,
        negate: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = BigInt::from(*k.numer());
        self.rational(if negate { -n } else { n }, BigInt::from(*k.denom()))
    }

    /// A closed form as a SymPy expression.
    pub(crate) fn expr(&mut self, e: &Expr) -> PyResult<Bound<'py, PyAny>> {
        Ok(match e {
            Expr::Num(q) => self.rational(q.numer().clone(), q.denom().clone())?,
            Expr::Sqrt(n) => self.sqrt.call1((self.integer.call1((*n,))?,))?,
            Expr::Sym(s) if s.is_pi() => self.pi.clone(),
            Expr::Sym(s) if s.is_one() => self.integer.call1((1,))?,
            Expr::Sym(s) => self.symbol(s.name())?,
            Expr::Trig { f, angle } => {
                let key = (f.is_sin(), angle.clone());
                if let Some(t) = self.trig.get(&key) {
                    return Ok(t.clone());
                }
                let t = self.trig(f.is_sin(), angle)?;
                self.trig.insert(key, t.clone());
                t
            }
            Expr::Add(v) => {
                let parts = v
                    .iter()
                    .map(|x| self.expr(x))
                    .collect::<PyResult<Vec<_>>>()?;
                self.add.call1(PyTuple::new(self.py, parts)?)?
            }
            Expr::Mul(v) => {
                let parts = v
                    .iter()
                    .map(|x| self.expr(x))
                    .collect::<PyResult<Vec<_>>>()?;
                self.mul.call1(PyTuple::new(self.py, parts)?)?
            }
            Expr::Neg(x) => {
                let x = self.expr(x)?;
                self.mul.call1((self.minus_one.clone(), x))?
            }
            Expr::Pow(b, n) => {
                let b = self.expr(b)?;
                self.pow.call1((b, self.integer.call1((*n,))?))?
            }
        })
    }

    /// `sin(angle)` (`sin`) or `cos(angle)` as SymPy's evaluated call makes it.
    fn trig(&mut self, sin: bool, angle: &Angle) -> PyResult<Bound<'py, PyAny>> {
        // SymPy's `cos(arg)` spends milliseconds on a cold cache looking for multiples of pi
        // and imaginary parts. An angle without pi and with a symbol has neither, and the
        // only rewrite SymPy would make is the sign: done here the same way
        // (`could_extract_minus_sign`), then built unevaluated. The result is the same tree as
        // the evaluated call (a test compares with `sympify` structurally).
        let plain = *angle.pi.numer() == 0 && angle.terms.iter().any(|(s, _)| !s.is_pi());
        if !plain {
            let arg = self.angle(angle, false)?;
            return if sin {
                self.sin.call1((arg,))
            } else {
                self.cos.call1((arg,))
            };
        }
        let negate = match plain_angle_is_negative(angle) {
            Some(n) => n,
            None => self
                .angle(angle, false)?
                .call_method0("could_extract_minus_sign")?
                .extract::<bool>()?,
        };
        let arg = self.angle(angle, negate)?;
        let kw = PyDict::new(self.py);
        kw.set_item("evaluate", false)?;
        Ok(match (sin, negate) {
            (false, _) => self.cos.call((arg,), Some(&kw))?,
            (true, false) => self.sin.call((arg,), Some(&kw))?,
            (true, true) => {
                let s = self.sin.call((arg,), Some(&kw))?;
                self.mul.call1((self.minus_one.clone(), s))?
            }
        })
    }

    /// An angle as a SymPy sum (`negate`: its negative, each coefficient negated).
    fn angle(&mut self, angle: &Angle, negate: bool) -> PyResult<Bound<'py, PyAny>> {
        let mut parts = Vec::with_capacity(angle.terms.len() + 2);
        if *angle.constant.numer() != 0 {
            parts.push(self.small_signed(&angle.constant, negate)?);
        }
        for (s, k) in &angle.terms {
            let k = self.small_signed(k, negate)?;
            parts.push(if s.is_pi() {
                self.mul.call1((k, self.pi.clone()))?
            } else {
                let x = self.symbol(s.name())?;
                self.mul.call1((k, x))?
            });
        }
        if *angle.pi.numer() != 0 {
            let k = self.small_signed(&angle.pi, negate)?;
            parts.push(self.mul.call1((k, self.pi.clone()))?);
        }
        self.add.call1(PyTuple::new(self.py, parts)?)
    }

    fn exprs(&mut self, v: &[Expr]) -> PyResult<Vec<Bound<'py, PyAny>>> {
        v.iter().map(|x| self.expr(x)).collect()
    }

    /// A SymPy `Matrix` of the rows.
    pub(crate) fn matrix(&mut self, rows: &[Vec<Expr>]) -> PyResult<Bound<'py, PyAny>> {
        let rows = rows
            .iter()
            .map(|r| PyList::new(self.py, self.exprs(r)?))
            .collect::<PyResult<Vec<_>>>()?;
        self.sympy
            .getattr("Matrix")?
            .call1((PyList::new(self.py, rows)?,))
    }

    /// A `dqsym.DQ` of the 8 components (w, x, y, z, w_e, x_e, y_e, z_e).
    pub(crate) fn dual_quat(&mut self, comps: &[Expr]) -> PyResult<Bound<'py, PyAny>> {
        let c = self.exprs(comps)?;
        let dq = self.py.import("dqsym._types")?.getattr("DQ")?;
        dq.call1(PyTuple::new(self.py, c)?)
    }

    /// A value's closed forms as SymPy objects.
    pub(crate) fn forms(&mut self, f: &Forms) -> PyResult<Bound<'py, PyAny>> {
        match f {
            Forms::Scalar(e) => self.expr(e),
            Forms::Vector(v) => {
                let col: Vec<Vec<Expr>> = v.iter().map(|x| vec![x.clone()]).collect();
                self.matrix(&col)
            }
            Forms::Quat(v) => {
                let c = self.exprs(v)?;
                self.sympy
                    .getattr("Quaternion")?
                    .call1(PyTuple::new(self.py, c)?)
            }
            Forms::DualQuat(v) => self.dual_quat(v),
            Forms::Matrix(rows) => self.matrix(rows),
            Forms::Quotient(rows) => {
                let div = |s: &mut Self, n: &Expr, d: &Expr| -> PyResult<Bound<'py, PyAny>> {
                    let n = s.expr(n)?;
                    let d = s.expr(d)?;
                    let inv = s.pow.call1((d, s.minus_one.clone()))?;
                    s.mul.call1((n, inv))
                };
                let mut out = Vec::with_capacity(rows.len());
                for r in rows {
                    let mut row = Vec::with_capacity(r.len());
                    for (n, d) in r {
                        row.push(div(self, n, d)?);
                    }
                    out.push(PyList::new(self.py, row)?);
                }
                self.sympy
                    .getattr("Matrix")?
                    .call1((PyList::new(self.py, out)?,))
            }
        }
    }

    /// Named closed forms as a dict, in order.
    pub(crate) fn dict(&mut self, rows: &[(String, Expr)]) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(self.py);
        for (n, e) in rows {
            d.set_item(n, self.expr(e)?)?;
        }
        Ok(d)
    }
}

/// SymPy's `could_extract_minus_sign` of a plain angle's sum (no multiple of pi; see
/// [`ToSympy::expr`]), decided without building it when the signs of its summands decide it,
/// as they almost always do: the sum of the constant and each `k*symbol` (each summand kept
/// by SymPy's `Add`, the symbols being distinct) extracts a minus sign when more summands have
/// a negative coefficient than a positive one, and not when fewer (SymPy's
/// `_could_extract_minus_sign`); a single summand `k*x` when `k` is negative, as `Mul`'s
/// rule says (`x` alone: never). `None` on a tie, which SymPy breaks with its `sort_key`: the
/// caller asks SymPy then. Asking SymPy for every angle was half of the PUMA 560's
/// `jacobian()` conversion (cProfile: 0.22 of 0.43 s for ten conversions).
fn plain_angle_is_negative(angle: &Angle) -> Option<bool> {
    let constant = (*angle.constant.numer() != 0).then_some(&angle.constant);
    let (mut negative, mut positive) = (0usize, 0usize);
    for k in constant
        .into_iter()
        .chain(angle.terms.iter().map(|(_, k)| k))
    {
        if *k.numer() < 0 {
            negative += 1;
        } else {
            positive += 1;
        }
    }
    match negative.cmp(&positive) {
        std::cmp::Ordering::Greater => Some(true),
        std::cmp::Ordering::Less => Some(false),
        std::cmp::Ordering::Equal => None,
    }
}

/// Python values to library values. `what` names the value in messages.
pub(crate) struct FromPython<'py> {
    py: Python<'py>,
    basic: Bound<'py, PyAny>,
    matrix_base: Bound<'py, PyAny>,
    quaternion: Bound<'py, PyAny>,
    cos: Bound<'py, PyAny>,
    sin: Bound<'py, PyAny>,
    pi: Bound<'py, PyAny>,
    dq: Bound<'py, PyAny>,
    fraction: Bound<'py, PyAny>,
}

fn unsupported(what: &str, found: &str) -> PyErr {
    PyTypeError::new_err(format!(
        "{what}: dqsym cannot represent {found} exactly (it takes rationals, symbols, pi, \
         + - * /, integer powers, square roots of rationals, cos and sin of angles)"
    ))
}

fn checked(what: &str, s: Scalar) -> PyResult<Scalar> {
    s.check()
        .map_err(|e| PyValueError::new_err(format!("{what}: {e}")))
}

impl<'py> FromPython<'py> {
    pub(crate) fn new(py: Python<'py>) -> PyResult<FromPython<'py>> {
        let sympy = py.import("sympy")?;
        Ok(FromPython {
            py,
            basic: sympy.getattr("Basic")?,
            matrix_base: sympy.getattr("MatrixBase")?,
            quaternion: sympy.getattr("Quaternion")?,
            cos: sympy.getattr("cos")?,
            sin: sympy.getattr("sin")?,
            pi: sympy.getattr("pi")?,
            dq: py.import("dqsym._types")?.getattr("DQ")?,
            fraction: py.import("fractions")?.getattr("Fraction")?,
        })
    }

    fn big(&self, x: &Bound<'py, PyAny>) -> PyResult<BigInt> {
        x.extract::<BigInt>()
    }

    /// An exact scalar.
    pub(crate) fn scalar(&self, x: &Bound<'py, PyAny>, what: &str) -> PyResult<Scalar> {
        if x.is_instance_of::<pyo3::types::PyBool>() {
            return Err(unsupported(what, "a bool"));
        }
        if x.is_instance_of::<pyo3::types::PyInt>() {
            return Ok(Scalar::rational(BigRational::from_integer(self.big(x)?)));
        }
        if x.is_instance(&self.fraction)? {
            let n = self.big(&x.getattr("numerator")?)?;
            let d = self.big(&x.getattr("denominator")?)?;
            return Ok(Scalar::rational(BigRational::new(n, d)));
        }
        if x.is_instance_of::<pyo3::types::PyFloat>() {
            return Err(PyTypeError::new_err(format!(
                "{what}: {} is a float; dqsym is exact: use sympy.Rational or an integer",
                x.str()?
            )));
        }
        if !x.is_instance(&self.basic)? {
            return Err(unsupported(what, &format!("a {}", x.get_type().name()?)));
        }
        let flag = |n: &str| -> PyResult<bool> { x.getattr(n)?.extract::<bool>() };
        if flag("is_Float")? {
            return Err(PyTypeError::new_err(format!(
                "{what}: {} is a float; dqsym is exact: use sympy.Rational or sympy.nsimplify",
                x.str()?
            )));
        }
        if flag("is_Rational")? {
            let n = self.big(&x.getattr("p")?)?;
            let d = self.big(&x.getattr("q")?)?;
            return Ok(Scalar::rational(BigRational::new(n, d)));
        }
        if x.eq(&self.pi)? {
            return Ok(Scalar::pi());
        }
        if flag("is_Symbol")? {
            let name: String = x.getattr("name")?.extract()?;
            if matches!(name.as_str(), "pi" | "1" | "I" | "eps") || name.is_empty() {
                return Err(PyValueError::new_err(format!(
                    "{what}: a symbol cannot be named `{name}` in dqsym"
                )));
            }
            return Ok(Scalar::sym(&name));
        }
        let args: Vec<Bound<'py, PyAny>> = x.getattr("args")?.extract()?;
        if flag("is_Add")? {
            let mut acc = Scalar::int(0);
            for a in &args {
                acc = checked(what, acc + self.scalar(a, what)?)?;
            }
            return Ok(acc);
        }
        if flag("is_Mul")? {
            let mut acc = Scalar::int(1);
            for a in &args {
                acc = checked(what, acc * self.scalar(a, what)?)?;
            }
            return Ok(acc);
        }
        if flag("is_Pow")? {
            let base = self.scalar(&args[0], what)?;
            let e = &args[1];
            let (p, q): (BigInt, BigInt) = if e.getattr("is_Rational")?.extract::<bool>()? {
                (self.big(&e.getattr("p")?)?, self.big(&e.getattr("q")?)?)
            } else {
                return Err(unsupported(what, &format!("the power {}", x.str()?)));
            };
            let base = if q == BigInt::from(2) {
                checked(what, base.sqrt())?
            } else if q == BigInt::from(1) {
                base
            } else {
                return Err(unsupported(what, &format!("the power {}", x.str()?)));
            };
            let shown = x.str()?.to_string();
            let n: i64 = p.try_into().map_err(|_| {
                PyValueError::new_err(format!("{what}: the exponent of {shown} is too large"))
            })?;
            if n.unsigned_abs() > dqsym::Context::current().max_exponent() {
                return Err(PyValueError::new_err(format!(
                    "{what}: exponent {n} is larger than the limit of {}",
                    dqsym::Context::current().max_exponent()
                )));
            }
            let base = if n < 0 {
                checked(what, base.recip())?
            } else {
                base
            };
            return checked(what, base.pow(n.unsigned_abs()));
        }
        for (f, sin) in [(&self.cos, false), (&self.sin, true)] {
            if x.is_instance(f)? {
                let a = self.scalar(&args[0], what)?;
                return checked(what, if sin { a.sin() } else { a.cos() });
            }
        }
        Err(unsupported(what, &x.str()?.to_string()))
    }

    /// A library value: scalars, tuples, quaternions, dual quaternions, matrices.
    pub(crate) fn value(&self, x: &Bound<'py, PyAny>, what: &str) -> PyResult<Value> {
        if x.is_instance(&self.dq)? {
            let c: Vec<Bound<'py, PyAny>> = x.getattr("components")?.extract()?;
            return Ok(Value::DualQuat(DualQuat::from_components(
                self.array(&c, what)?,
            )));
        }
        if x.is_instance(&self.quaternion)? {
            let c: Vec<Bound<'py, PyAny>> = ["a", "b", "c", "d"]
                .iter()
                .map(|n| x.getattr(*n))
                .collect::<PyResult<_>>()?;
            return Ok(Value::Quat(Quat::from_components(self.array(&c, what)?)));
        }
        if x.is_instance(&self.matrix_base)? {
            let (r, c): (usize, usize) = x.getattr("shape")?.extract()?;
            if r == 0 || c == 0 {
                return Err(PyValueError::new_err(format!("{what}: an empty matrix")));
            }
            let cells: Vec<Bound<'py, PyAny>> = x
                .call_method0("tolist")?
                .extract::<Vec<Vec<_>>>()?
                .into_iter()
                .flatten()
                .collect();
            let cells = cells
                .iter()
                .map(|e| self.scalar(e, what))
                .collect::<PyResult<Vec<_>>>()?;
            // A column of three is a point or a direction, as vectors come out.
            if (r, c) == (3, 1) {
                return Ok(Value::Vector(self.array3(cells)));
            }
            return Ok(Value::Matrix(
                cells.chunks(c).map(<[Scalar]>::to_vec).collect(),
            ));
        }
        if x.is_instance_of::<PyTuple>() || x.is_instance_of::<PyList>() {
            let items: Vec<Bound<'py, PyAny>> = x.extract()?;
            if items
                .iter()
                .all(|i| i.is_instance_of::<PyList>() || i.is_instance_of::<PyTuple>())
                && !items.is_empty()
            {
                // A list of rows.
                let m = self.py.import("sympy")?.getattr("Matrix")?.call1((x,))?;
                return self.value(&m, what);
            }
            return match items.len() {
                3 => Ok(Value::Vector(self.array(&items, what)?)),
                4 => Ok(Value::Quat(Quat::from_components(
                    self.array(&items, what)?,
                ))),
                8 => Ok(Value::DualQuat(DualQuat::from_components(
                    self.array(&items, what)?,
                ))),
                n => Err(PyValueError::new_err(format!(
                    "{what}: a tuple of {n} is neither a vector (3), a quaternion (4) nor a dual \
                     quaternion (8)"
                ))),
            };
        }
        Ok(Value::Scalar(self.scalar(x, what)?))
    }

    fn array<const N: usize>(
        &self,
        items: &[Bound<'py, PyAny>],
        what: &str,
    ) -> PyResult<[Scalar; N]> {
        let v = items
            .iter()
            .map(|e| self.scalar(e, what))
            .collect::<PyResult<Vec<_>>>()?;
        v.try_into().map_err(|v: Vec<Scalar>| {
            PyValueError::new_err(format!(
                "{what}: expected {N} components, found {}",
                v.len()
            ))
        })
    }

    fn array3(&self, v: Vec<Scalar>) -> [Scalar; 3] {
        let mut it = v.into_iter();
        [
            it.next().unwrap_or_else(|| Scalar::int(0)),
            it.next().unwrap_or_else(|| Scalar::int(0)),
            it.next().unwrap_or_else(|| Scalar::int(0)),
        ]
    }
}
