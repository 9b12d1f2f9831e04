//! Evaluation: a [`Session`] runs statements and keeps the bindings between them.
//!
//! Names resolve in this order: the constants `I`/`eps` (the dual unit) and `pi`, then the
//! session's bindings (variables, `syms` symbols, `halfangle` names). Any other name is an
//! error, except in the angle of a `halfangle` declaration, whose free names become symbols,
//! and in sessions made with [`Session::with_implicit_symbols`] (one-liners), where every free
//! name is a symbol.
//!
//! A statement is evaluated against the current bindings and committed only when it succeeds,
//! so a failing statement never changes the session. Recursion follows the tree, whose depth
//! the parser bounds.

use super::ast::{AddOp, Expr, ExprKind, MulOp, Program, Span, Stmt, StmtKind, UnaryOp};
use super::builtins;
use super::error::render;
use super::scan::SourceMap;
use super::value::{self, OpError, Value};
use crate::print::Format;
use crate::{Context, DualQuat, Quat, Scalar, ScalarError, Trig};
use std::collections::BTreeMap;
use thiserror::Error;

/// Names that stand for constants and cannot be bound.
pub const CONSTANTS: [(&str, &str); 3] = [
    ("I", "the dual unit"),
    ("eps", "the dual unit"),
    ("pi", "the number pi"),
];

/// What a name is bound to, and how it came to be.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Binding {
    /// The value.
    pub value: Value,
    /// How it was bound.
    pub kind: BindingKind,
}

/// How a name was bound.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BindingKind {
    /// By `name = value`.
    Variable,
    /// By `syms`, or as a free name of a `halfangle` angle.
    Symbol,
    /// By `halfangle c, s = angle`: cos or sin of half the angle, written as given.
    HalfAngle {
        /// The cosine (the first name) or the sine (the second).
        f: Trig,
        /// The angle as written, bracketed unless it is one name, number or call: `theta3`,
        /// `(theta1 + theta2)`.
        angle: String,
    },
}

impl BindingKind {
    /// What a `halfangle` name stands for, `cos(theta3/2)`; `None` for other bindings.
    pub fn half_angle_meaning(&self) -> Option<String> {
        match self {
            BindingKind::HalfAngle { f, angle } => Some(format!("{}({angle}/2)", f.name())),
            _ => None,
        }
    }
}

/// A result to show: a label (the assigned name, or the expression as written) and a value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Displayed {
    /// `v2`, or `dq3*v3*cq3` for an expression statement.
    pub label: String,
    /// The value.
    pub value: Value,
    /// The format asked for by an output function (`latex(x)`, `sympy(x)`, `rust(x)`) around
    /// the statement's value, overriding the session's.
    pub format: Option<Format>,
}

/// An error while evaluating a statement: the reason and the place.
///
/// `Display` gives `error: message` with `line:col`; [`EvalError::render`] adds the source line
/// and a caret, in the same shape as a [`ParseError`](super::ParseError).
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("error: {kind}\n --> {}:{}", span.line, span.col)]
pub struct EvalError {
    kind: EvalErrorKind,
    span: Span,
}

/// The reasons evaluation can fail.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum EvalErrorKind {
    /// A name with no binding.
    #[error("unknown name `{name}`{hint}")]
    UnknownName {
        /// The name.
        name: String,
        /// A suggestion, starting with "; ".
        hint: String,
    },
    /// A call of a function that does not exist.
    #[error("unknown function `{name}`{hint}")]
    UnknownFunction {
        /// The name.
        name: String,
        /// A suggestion, starting with "; ".
        hint: String,
    },
    /// A built-in called with the wrong number of arguments.
    #[error("`{func}` takes {expected}, got {got}: {usage}")]
    Arity {
        /// The built-in.
        func: String,
        /// "2 or 3 arguments".
        expected: String,
        /// The number given.
        got: usize,
        /// The signature, `dh(theta, d, a, alpha)`.
        usage: String,
    },
    /// Operands or arguments of the wrong kind.
    #[error("{0}")]
    Type(String),
    /// A constant on the left of `=`.
    #[error("`{name}` is {meaning} and cannot be assigned")]
    Reserved {
        /// The constant.
        name: String,
        /// What it is.
        meaning: String,
    },
    /// A name already declared by `halfangle`.
    #[error("`{name}` is already declared as {meaning} by `halfangle`")]
    HalfAngleName {
        /// The name.
        name: String,
        /// What it stands for.
        meaning: String,
    },
    /// An exact scalar operation failed (division by zero, a result too large, ...).
    #[error("{0}")]
    Scalar(ScalarError),
    /// A bad exponent.
    #[error("{0}")]
    Exponent(String),
    /// No inverse where one is needed.
    #[error("{0}")]
    NotInvertible(String),
    /// A dual quaternion that is not unit where a rigid motion is needed.
    #[error("{0}")]
    NotUnit(String),
    /// A tuple that is neither a vector nor a quaternion.
    #[error("a tuple of {0} is neither a vector (3 entries) nor a quaternion (4 entries)")]
    TupleSize(usize),
    /// An argument outside what a built-in accepts.
    #[error("{0}")]
    Invalid(String),
    /// The computation was interrupted (Ctrl-C).
    #[error("interrupted")]
    Interrupted,
}

impl EvalError {
    pub(crate) fn new(kind: EvalErrorKind, span: Span) -> EvalError {
        EvalError { kind, span }
    }

    /// Why evaluation failed.
    pub fn kind(&self) -> &EvalErrorKind {
        &self.kind
    }

    /// Where.
    pub fn span(&self) -> Span {
        self.span
    }

    /// The one-line message, without location.
    pub fn message(&self) -> String {
        // A huge number in a message (a base, an exponent) is shown abbreviated.
        crate::scalar::short_numbers(&self.kind.to_string())
    }

    /// The full message with location, source line and caret, `src` being the text the
    /// program was parsed from.
    pub fn render(&self, src: &str) -> String {
        let map = SourceMap::new(src);
        let mut span = self.span;
        // A span from another text (or the default span) must not index out of `src`.
        if span.end > src.len() || span.start > span.end || span.line == 0 {
            span = map.span(0, 0);
        }
        render(&map, &self.message(), span)
    }
}

pub(crate) type Result<T> = std::result::Result<T, EvalError>;

/// Turns an [`OpError`] into an [`EvalError`] at `span`.
pub(crate) fn op_error(e: OpError, span: Span) -> EvalError {
    let kind = match e {
        OpError::Scalar(ScalarError::Cancelled) => EvalErrorKind::Interrupted,
        OpError::Type(m) => EvalErrorKind::Type(m),
        OpError::Scalar(e) => EvalErrorKind::Scalar(e),
        OpError::Exponent(m) => EvalErrorKind::Exponent(m),
        OpError::NotInvertible(m) => EvalErrorKind::NotInvertible(m),
    };
    EvalError::new(kind, span)
}

/// The bindings of a script or REPL session, and how names are resolved.
#[derive(Clone, Debug, Default)]
pub struct Session {
    bindings: BTreeMap<String, Binding>,
    implicit_symbols: bool,
    /// Since [`Session::checkpoint`]: each name bound, with what it was bound to before.
    journal: Option<Vec<(String, Option<Binding>)>>,
}

/// The language's keywords: never names (the grammar's `keyword` rule).
pub const KEYWORDS: [&str; 2] = ["syms", "halfangle"];

impl Session {
    /// An empty session in which names must be declared (`syms`) or assigned before use.
    pub fn new() -> Session {
        Session::default()
    }

    /// An empty session in which every free name is a symbol, for one-liners
    /// (`dqsym -e 'cos(t)^2 + sin(t)^2'`).
    pub fn with_implicit_symbols() -> Session {
        Session {
            implicit_symbols: true,
            ..Session::default()
        }
    }

    /// Binds `name` to `value` as `name = value` would, for callers that hold values rather
    /// than text (the Python package). Constants and `halfangle` names are refused with the
    /// error that assignment gives, at the default span.
    pub fn define(&mut self, name: &str, value: Value) -> Result<()> {
        if KEYWORDS.contains(&name) {
            return Err(EvalError::new(
                EvalErrorKind::Reserved {
                    name: name.to_owned(),
                    meaning: "a keyword".to_owned(),
                },
                Span::default(),
            ));
        }
        check_not_constant(name, Span::default())?;
        self.check_not_half_angle(name, Span::default())?;
        self.bind(name, value, BindingKind::Variable);
        Ok(())
    }

    /// Starts recording what statements bind, so that [`Session::rollback`] can undo them
    /// (an interrupted statement whose result was computed but must not count); costs one
    /// entry per binding made, never a copy of the session.
    pub fn checkpoint(&mut self) {
        self.journal = Some(Vec::new());
    }

    /// Keeps what was bound since [`Session::checkpoint`] and stops recording; returns the
    /// names that were not bound before (a REPL's completion list grows by them).
    pub fn commit(&mut self) -> Vec<String> {
        self.journal
            .take()
            .unwrap_or_default()
            .into_iter()
            .filter_map(|(name, old)| old.is_none().then_some(name))
            .collect()
    }

    /// Puts every binding made since [`Session::checkpoint`] back as it was, and stops
    /// recording (nothing happens without a checkpoint).
    pub fn rollback(&mut self) {
        for (name, old) in self.journal.take().unwrap_or_default().into_iter().rev() {
            match old {
                Some(b) => self.bindings.insert(name, b),
                None => self.bindings.remove(&name),
            };
        }
    }

    /// The bindings, sorted by name.
    pub fn bindings(&self) -> &BTreeMap<String, Binding> {
        &self.bindings
    }

    /// The value bound to `name`, if any.
    pub fn get(&self, name: &str) -> Option<&Value> {
        self.bindings.get(name).map(|b| &b.value)
    }

    /// Runs every statement in order and returns the results to display. Statements before a
    /// failing one keep their effect; use [`Session::exec`] to show results as they come.
    pub fn run(&mut self, program: &Program) -> Result<Vec<Displayed>> {
        let mut shown = Vec::new();
        for stmt in &program.statements {
            shown.extend(self.exec(stmt)?);
        }
        Ok(shown)
    }

    /// Runs one statement; on error the session is unchanged. The statement runs under the
    /// [`Context`](crate::Context) entered on this thread, with a work budget of its own (the
    /// context's whole budget), and stops with [`EvalErrorKind::Interrupted`] when the
    /// context is cancelled.
    pub fn exec(&mut self, stmt: &Stmt) -> Result<Option<Displayed>> {
        self.exec_with(stmt, None)
    }

    /// [`Session::exec`], telling `observer` about every motion built, product taken and
    /// point transformed (a walkthrough listens so).
    pub(crate) fn exec_observed(
        &mut self,
        stmt: &Stmt,
        observer: &dyn Observer,
    ) -> Result<Option<Displayed>> {
        self.exec_with(stmt, Some(observer))
    }

    fn exec_with(&mut self, stmt: &Stmt, rec: Option<&dyn Observer>) -> Result<Option<Displayed>> {
        let _statement = Context::entered().enter();
        match &stmt.kind {
            StmtKind::Syms(names) => {
                for n in names {
                    if CONSTANTS.iter().any(|(c, _)| *c == n.name) {
                        // Appendix II declares `syms I`; the constant stays what it is.
                        continue;
                    }
                    // A half-angle name keeps its meaning, so that Appendix III's `syms c3`
                    // lines can stay next to the `halfangle` declarations.
                    let keep = matches!(
                        self.bindings.get(&n.name),
                        Some(Binding {
                            kind: BindingKind::HalfAngle { .. },
                            ..
                        })
                    );
                    if !keep {
                        self.bind(
                            &n.name,
                            Value::Scalar(Scalar::sym(&n.name)),
                            BindingKind::Symbol,
                        );
                    }
                }
                Ok(None)
            }
            StmtKind::HalfAngle { cos, sin, angle } => {
                for n in [cos, sin] {
                    check_not_constant(&n.name, n.span)?;
                    self.check_not_half_angle(&n.name, n.span)?;
                }
                if cos.name == sin.name {
                    return Err(EvalError::new(
                        EvalErrorKind::Invalid(format!(
                            "`{}` cannot be both the cosine and the sine",
                            sin.name
                        )),
                        sin.span,
                    ));
                }
                let value = self.eval_with(angle, true, None)?;
                let Value::Scalar(a) = value else {
                    return Err(EvalError::new(
                        EvalErrorKind::Type(format!(
                            "a half angle needs a scalar angle, found {}",
                            value.describe()
                        )),
                        angle.span,
                    ));
                };
                let half =
                    &a * Scalar::rational(num_rational::BigRational::new(1.into(), 2.into()));
                let (c, s) = (
                    half.cos()
                        .check()
                        .map_err(|e| scalar_error(e, angle.span))?,
                    half.sin()
                        .check()
                        .map_err(|e| scalar_error(e, angle.span))?,
                );
                for sym in a.symbols() {
                    if !self.bindings.contains_key(sym.name()) && !sym.is_pi() {
                        let name = sym.name().to_owned();
                        self.bind(
                            &name,
                            Value::Scalar(Scalar::sym(&name)),
                            BindingKind::Symbol,
                        );
                    }
                }
                let text = match angle.kind {
                    ExprKind::Name(_)
                    | ExprKind::Int(_)
                    | ExprKind::Decimal { .. }
                    | ExprKind::Degrees { .. }
                    | ExprKind::Call { .. } => angle.to_string(),
                    _ => format!("({angle})"),
                };
                self.bind(
                    &cos.name,
                    Value::Scalar(c),
                    BindingKind::HalfAngle {
                        f: Trig::Cos,
                        angle: text.clone(),
                    },
                );
                self.bind(
                    &sin.name,
                    Value::Scalar(s),
                    BindingKind::HalfAngle {
                        f: Trig::Sin,
                        angle: text,
                    },
                );
                Ok(None)
            }
            StmtKind::Assign { name, value } => {
                check_not_constant(&name.name, name.span)?;
                self.check_not_half_angle(&name.name, name.span)?;
                let v = self.eval_with(value, self.implicit_symbols, rec)?;
                self.bind(&name.name, v.clone(), BindingKind::Variable);
                Ok((!stmt.quiet).then(|| Displayed {
                    label: name.name.clone(),
                    value: v,
                    format: output_format(value),
                }))
            }
            StmtKind::Expr(e) => {
                let v = self.eval_with(e, self.implicit_symbols, rec)?;
                self.bind("ans", v.clone(), BindingKind::Variable);
                let text = e.to_string();
                let label = if text.chars().count() <= 60 {
                    text
                } else {
                    "ans".to_owned()
                };
                Ok((!stmt.quiet).then_some(Displayed {
                    label,
                    value: v,
                    format: output_format(e),
                }))
            }
        }
    }

    fn bind(&mut self, name: &str, value: Value, kind: BindingKind) {
        let old = self
            .bindings
            .insert(name.to_owned(), Binding { value, kind });
        if let Some(j) = &mut self.journal {
            j.push((name.to_owned(), old));
        }
    }

    fn check_not_half_angle(&self, name: &str, span: Span) -> Result<()> {
        if let Some(meaning) = self
            .bindings
            .get(name)
            .and_then(|b| b.kind.half_angle_meaning())
        {
            return Err(EvalError::new(
                EvalErrorKind::HalfAngleName {
                    name: name.to_owned(),
                    meaning,
                },
                span,
            ));
        }
        Ok(())
    }

    /// Evaluates one expression against the current bindings, with a work budget of its own
    /// (see [`Session::exec`]).
    pub fn eval(&self, e: &Expr) -> Result<Value> {
        let _statement = Context::entered().enter();
        self.eval_with(e, self.implicit_symbols, None)
    }

    fn eval_with(&self, e: &Expr, implicit: bool, rec: Option<&dyn Observer>) -> Result<Value> {
        Evaluator {
            session: self,
            implicit,
            rec,
        }
        .expr(e)
    }
}

/// The format of an output function call (`latex(x)`) at the top of `e`.
fn output_format(e: &Expr) -> Option<Format> {
    match &e.kind {
        ExprKind::Call { func, args } if args.len() == 1 => match func.name.as_str() {
            "latex" => Some(Format::Latex),
            "sympy" => Some(Format::Sympy),
            "rust" => Some(Format::Rust),
            "plain" => Some(Format::Plain),
            _ => None,
        },
        _ => None,
    }
}

fn check_not_constant(name: &str, span: Span) -> Result<()> {
    match CONSTANTS.iter().find(|(n, _)| *n == name) {
        Some((_, meaning)) => Err(EvalError::new(
            EvalErrorKind::Reserved {
                name: name.to_owned(),
                meaning: (*meaning).to_owned(),
            },
            span,
        )),
        None => Ok(()),
    }
}

pub(crate) fn scalar_error(e: ScalarError, span: Span) -> EvalError {
    match e {
        ScalarError::Cancelled => EvalError::new(EvalErrorKind::Interrupted, span),
        e => EvalError::new(EvalErrorKind::Scalar(e), span),
    }
}

/// Who listens to an evaluation: told of each [`Event`] as it happens. The evaluator knows
/// nothing of what listens (a walkthrough records the events and explains them).
pub(crate) trait Observer {
    /// One evaluation step happened.
    fn observe(&self, event: Event);
}

/// What an observer of the evaluation is told about one evaluation step.
// Events are few and short-lived (one list per statement), so boxing the larger variants
// would buy nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub(crate) enum Event {
    /// A built-in that builds a motion or a point (`rot`, `trans`, `screw`, `dh`, `mdh`,
    /// `point`), a twist or a velocity (`twist`, `bodytwist`, `qdot`, `sclerp`, `sclerpdot`)
    /// was called.
    Built {
        /// The built-in.
        func: &'static str,
        /// Each argument as written, with its value.
        args: Vec<(String, Value)>,
        /// The result.
        value: Value,
    },
    /// A product `f1 * f2 * ... * fn` of quaternions, dual quaternions and vectors;
    /// `partials[k]` is the product of the first `k + 2` factors.
    Chain {
        /// Each factor as written, with its value.
        factors: Vec<(String, Value)>,
        /// The running products.
        partials: Vec<Value>,
    },
    /// `transform(q, v)` was called.
    Transform {
        /// The motion as written, with its value.
        q: (String, Value),
        /// The point as written, with its value.
        v: (String, Value),
        /// The image point.
        value: Value,
    },
}

/// One evaluation: the session to read, whether free names are symbols, and where to record
/// events for a walkthrough.
pub(crate) struct Evaluator<'a> {
    session: &'a Session,
    implicit: bool,
    rec: Option<&'a dyn Observer>,
}

impl Evaluator<'_> {
    /// Tells the observer about `event`, when one is listening.
    pub(crate) fn record(&self, event: impl FnOnce() -> Event) {
        if let Some(r) = self.rec {
            r.observe(event());
        }
    }

    /// Evaluates `e`; every value returned is free of scalar error values.
    pub(crate) fn expr(&self, e: &Expr) -> Result<Value> {
        if crate::Context::check_cancelled().is_err() {
            return Err(EvalError::new(EvalErrorKind::Interrupted, e.span));
        }
        let v = self.expr_unchecked(e)?;
        v.check().map_err(|err| scalar_error(err, e.span))
    }

    fn expr_unchecked(&self, e: &Expr) -> Result<Value> {
        let at = |r: value::OpResult, span: Span| r.map_err(|err| op_error(err, span));
        match &e.kind {
            ExprKind::Int(n) => Ok(Value::Scalar(Scalar::rational(
                num_rational::BigRational::from_integer(n.clone().into()),
            ))),
            ExprKind::Decimal { value, .. } => Ok(Value::Scalar(Scalar::rational(value.clone()))),
            ExprKind::Degrees { value, .. } => Ok(Value::Scalar(
                Scalar::rational(value / num_rational::BigRational::from_integer(180.into()))
                    * Scalar::pi(),
            )),
            ExprKind::Name(name) => self.name(name, e.span),
            ExprKind::Unary { op, operand } => {
                let v = self.expr(operand)?;
                match op {
                    UnaryOp::Neg => Ok(value::neg(&v)),
                    UnaryOp::Conj => at(value::conj(&v), e.span),
                }
            }
            ExprKind::Sum { first, rest } => {
                let mut acc = self.expr(first)?;
                for (op, term) in rest {
                    let v = self.expr(term)?;
                    let span = join(first.span, term.span);
                    acc = at(value::add(&acc, &v, *op == AddOp::Sub), span)?;
                    acc = acc.check().map_err(|err| scalar_error(err, span))?;
                }
                Ok(acc)
            }
            ExprKind::Product { first, rest } => {
                let mut acc = self.expr(first)?;
                let mut chain = self.rec.is_some().then(|| ChainRec::new(first, &acc));
                for (op, factor) in rest {
                    let v = self.expr(factor)?;
                    if let Some(c) = chain.as_mut() {
                        c.factor(*op, factor, &v);
                    }
                    let r = match op {
                        MulOp::Mul => value::mul(&acc, &v),
                        MulOp::Div => match value::div(&acc, &v) {
                            // The divisor is at fault, so point at it.
                            Err(err) => return Err(op_error(err, factor.span)),
                            ok => ok,
                        },
                    };
                    let span = join(first.span, factor.span);
                    acc = at(r, span)?;
                    acc = acc.check().map_err(|err| scalar_error(err, span))?;
                    if let Some(c) = chain.as_mut() {
                        c.partials.push(acc.clone());
                    }
                }
                if let Some(c) = chain.filter(ChainRec::is_motion_chain) {
                    self.record(|| Event::Chain {
                        factors: c.factors,
                        partials: c.partials,
                    });
                }
                Ok(acc)
            }
            ExprKind::Pow { base, exponent } => {
                let b = self.expr(base)?;
                let x = self.expr(exponent)?;
                value::pow(&b, &x).map_err(|err| match err {
                    OpError::Exponent(_) => op_error(err, exponent.span),
                    _ => op_error(err, e.span),
                })
            }
            ExprKind::Call { func, args } => builtins::call(self, func, args, e.span),
            ExprKind::Tuple(items) => {
                let mut vals = Vec::with_capacity(items.len());
                for item in items {
                    match self.expr(item)? {
                        Value::Scalar(s) => vals.push(s),
                        other => {
                            return Err(EvalError::new(
                                EvalErrorKind::Type(format!(
                                    "a tuple entry must be a scalar, found {}",
                                    other.describe()
                                )),
                                item.span,
                            ))
                        }
                    }
                }
                match <[Scalar; 4]>::try_from(vals) {
                    Ok(q) => Ok(Value::Quat(Quat::from_components(q))),
                    Err(vals) => match <[Scalar; 3]>::try_from(vals) {
                        Ok(v) => Ok(Value::Vector(v)),
                        Err(vals) => {
                            Err(EvalError::new(EvalErrorKind::TupleSize(vals.len()), e.span))
                        }
                    },
                }
            }
            ExprKind::Matrix(rows) => {
                let mut out = Vec::with_capacity(rows.len());
                for row in rows {
                    let mut r = Vec::with_capacity(row.len());
                    for item in row {
                        match self.expr(item)? {
                            Value::Scalar(s) => r.push(s),
                            other => {
                                return Err(EvalError::new(
                                    EvalErrorKind::Type(format!(
                                        "a matrix entry must be a scalar, found {}",
                                        other.describe()
                                    )),
                                    item.span,
                                ))
                            }
                        }
                    }
                    out.push(r);
                }
                Ok(Value::Matrix(out))
            }
        }
    }

    fn name(&self, name: &str, span: Span) -> Result<Value> {
        match name {
            "I" | "eps" => {
                return Ok(Value::DualQuat(DualQuat::from_real_and_dual(
                    Quat::zero(),
                    Quat::identity(),
                )))
            }
            "pi" => return Ok(Value::Scalar(Scalar::pi())),
            _ => {}
        }
        if let Some(b) = self.session.bindings.get(name) {
            return Ok(b.value.clone());
        }
        if self.implicit {
            return Ok(Value::Scalar(Scalar::sym(name)));
        }
        let hint = if builtins::lookup(name).is_some() {
            format!("; `{name}` is a function: call it as `{name}(...)`")
        } else {
            format!("; declare a symbol with `syms {name}` or assign it with `{name} = ...`")
        };
        Err(EvalError::new(
            EvalErrorKind::UnknownName {
                name: name.to_owned(),
                hint,
            },
            span,
        ))
    }
}

/// The span from the start of `a` to the end of `b`, on `a`'s line and column.
fn join(a: Span, b: Span) -> Span {
    Span {
        end: b.end.max(a.end),
        ..a
    }
}

/// A product being evaluated, for [`Event::Chain`].
struct ChainRec {
    factors: Vec<(String, Value)>,
    partials: Vec<Value>,
    /// Only `*`, no factor is a scalar or the dual unit itself.
    plain: bool,
}

impl ChainRec {
    fn new(first: &Expr, v: &Value) -> ChainRec {
        let mut c = ChainRec {
            factors: Vec::new(),
            partials: Vec::new(),
            plain: true,
        };
        c.factor(MulOp::Mul, first, v);
        c
    }

    fn factor(&mut self, op: MulOp, e: &Expr, v: &Value) {
        let unit = matches!(&e.kind, ExprKind::Name(n) if n == "I" || n == "eps");
        if op != MulOp::Mul
            || unit
            || matches!(
                v,
                Value::Scalar(_) | Value::Matrix(_) | Value::QuotientMatrix(_)
            )
        {
            self.plain = false;
        }
        // A sum or a negation as a factor keeps its brackets: `qd2*(1 + I*(x2, y2, z2))`.
        let text = match e.kind {
            ExprKind::Sum { .. } | ExprKind::Unary { .. } | ExprKind::Product { .. } => {
                format!("({e})")
            }
            _ => e.to_string(),
        };
        self.factors.push((text, v.clone()));
    }

    /// A product of motions and points, as a walkthrough shows it.
    fn is_motion_chain(&self) -> bool {
        self.plain
            && self
                .factors
                .iter()
                .any(|(_, v)| matches!(v, Value::Quat(_) | Value::DualQuat(_)))
    }
}
