//! The syntax tree of a dqsym script.
//!
//! The tree is purely syntactic: it knows nothing of quaternions, and `I`, `eps` and `pi` are
//! ordinary names that the evaluator binds. Every node carries a [`Span`] so that the evaluator
//! can report errors at the right line and column.
//!
//! Two shapes are chosen for robustness rather than taste:
//! - Chains of `+`/`-` and of `*`/`/` are n-ary ([`ExprKind::Sum`], [`ExprKind::Product`]), so a
//!   long sum is a wide node, not a deep one; recursion over the tree then never depends on the
//!   length of an expression, only on its nesting, which the parser bounds.
//! - Greek letters are already spelled out in names (`θ1` is stored as `theta1`), so the rest of
//!   the crate compares plain ASCII strings.
//!
//! # Invariants (upheld by the parser)
//! - A `Sum` or `Product` has a non-empty `rest`; a `Tuple` has at least two elements; a `Matrix`
//!   has at least one row and all rows have the same, non-zero length.
//! - Names are non-empty ASCII (letters, digits, `_`, starting with a letter) and never keywords.
//! - The tree is at most [`ParseOptions::max_depth`](super::ParseOptions) levels deep.

use num_bigint::BigUint;
use num_rational::BigRational;

/// Where a node sits in the source: a byte range plus the 1-based line and column (counted in
/// characters) of its first character.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Span {
    /// 1-based line of `start`.
    pub line: usize,
    /// 1-based column of `start`, in characters (so `θ` counts once).
    pub col: usize,
    /// Byte offset of the first character.
    pub start: usize,
    /// Byte offset one past the last character.
    pub end: usize,
}

/// A parsed script: its statements in order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Program {
    /// The statements, without the empty ones.
    pub statements: Vec<Stmt>,
}

/// One statement with its span.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stmt {
    /// What the statement does.
    pub kind: StmtKind,
    /// The whole statement, without its separator.
    pub span: Span,
    /// Ended by `;`: as in Matlab, the statement's value is not displayed.
    pub quiet: bool,
}

/// The kinds of statement.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StmtKind {
    /// `name = value`.
    Assign {
        /// The name being bound.
        name: Ident,
        /// The bound expression.
        value: Expr,
    },
    /// A bare expression, whose value is displayed.
    Expr(Expr),
    /// `syms a b c`: declares symbols; a no-op apart from that.
    Syms(Vec<Ident>),
    /// `halfangle c3, s3 = theta3`: `cos` stands for cos(angle/2) and `sin` for sin(angle/2).
    HalfAngle {
        /// The name of the half-angle cosine.
        cos: Ident,
        /// The name of the half-angle sine.
        sin: Ident,
        /// The full angle.
        angle: Expr,
    },
}

/// A name with the place it was written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ident {
    /// The normalized name: Greek letters spelled out (`θ1` becomes `theta1`).
    pub name: String,
    /// Where the name was written.
    pub span: Span,
}

/// An expression with its span.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Expr {
    /// What the expression is.
    pub kind: ExprKind,
    /// The source text of the expression, including any parentheses around it.
    pub span: Span,
}

/// The kinds of expression.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ExprKind {
    /// A non-negative integer of any size.
    Int(BigUint),
    /// A decimal or scientific literal (`0.4318`, `1e-3`), exact; `text` as written.
    Decimal {
        /// The literal as written, printed back unchanged.
        text: String,
        /// Its exact value (non-negative).
        value: BigRational,
    },
    /// An angle in degrees (`90deg`, `22.5deg`): `value` pi/180, exact.
    Degrees {
        /// The number as written, without `deg`.
        text: String,
        /// The number of degrees (non-negative).
        value: BigRational,
    },
    /// A name: a variable, a symbol, or `I`/`eps`/`pi`, which the evaluator binds.
    Name(String),
    /// A prefix or postfix unary operator.
    Unary {
        /// The operator.
        op: UnaryOp,
        /// Its operand.
        operand: Box<Expr>,
    },
    /// `first ± rest[0] ± rest[1] ...`, evaluated left to right.
    Sum {
        /// The first term.
        first: Box<Expr>,
        /// The following terms with their signs; never empty.
        rest: Vec<(AddOp, Expr)>,
    },
    /// `first */ rest[0] */ rest[1] ...`, evaluated left to right (the product does not commute,
    /// so the order is kept as written).
    Product {
        /// The first factor.
        first: Box<Expr>,
        /// The following factors with their operators; never empty.
        rest: Vec<(MulOp, Expr)>,
    },
    /// `base ^ exponent`.
    Pow {
        /// The base.
        base: Box<Expr>,
        /// The exponent.
        exponent: Box<Expr>,
    },
    /// `f(a, b)`: a call of a built-in function.
    Call {
        /// The function name.
        func: Ident,
        /// The arguments, possibly none.
        args: Vec<Expr>,
    },
    /// `(a, b, ...)`, at least two elements: a quaternion (4), a vector (3), or an error later.
    Tuple(Vec<Expr>),
    /// `[a, b; c, d]`: rows of equal, non-zero length.
    Matrix(Vec<Vec<Expr>>),
}

/// The unary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum UnaryOp {
    /// Prefix `-`.
    Neg,
    /// Postfix `'`: the quaternion conjugate, like `conj(q)`.
    Conj,
}

/// The operators of a [`ExprKind::Sum`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AddOp {
    /// `+`.
    Add,
    /// `-`.
    Sub,
}

/// The operators of a [`ExprKind::Product`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MulOp {
    /// `*`.
    Mul,
    /// `/`.
    Div,
}

impl Expr {
    /// An expression at the default (empty) span, for building trees in code and tests.
    pub fn new(kind: ExprKind) -> Expr {
        Expr {
            kind,
            span: Span::default(),
        }
    }

    /// Resets every span in the tree to `Span::default()`, so that trees parsed from different
    /// texts (say, an expression and its pretty-printed form) compare equal with `==`.
    pub fn erase_spans(&mut self) {
        self.span = Span::default();
        match &mut self.kind {
            ExprKind::Int(_)
            | ExprKind::Decimal { .. }
            | ExprKind::Degrees { .. }
            | ExprKind::Name(_) => {}
            ExprKind::Unary { operand, .. } => operand.erase_spans(),
            ExprKind::Sum { first, rest } => {
                first.erase_spans();
                rest.iter_mut().for_each(|(_, e)| e.erase_spans());
            }
            ExprKind::Product { first, rest } => {
                first.erase_spans();
                rest.iter_mut().for_each(|(_, e)| e.erase_spans());
            }
            ExprKind::Pow { base, exponent } => {
                base.erase_spans();
                exponent.erase_spans();
            }
            ExprKind::Call { func, args } => {
                func.span = Span::default();
                args.iter_mut().for_each(Expr::erase_spans);
            }
            ExprKind::Tuple(items) => items.iter_mut().for_each(Expr::erase_spans),
            ExprKind::Matrix(rows) => rows.iter_mut().flatten().for_each(Expr::erase_spans),
        }
    }
}

impl Stmt {
    /// Resets every span in the statement, as [`Expr::erase_spans`] does.
    pub fn erase_spans(&mut self) {
        self.span = Span::default();
        match &mut self.kind {
            StmtKind::Assign { name, value } => {
                name.span = Span::default();
                value.erase_spans();
            }
            StmtKind::Expr(e) => e.erase_spans(),
            StmtKind::Syms(names) => names.iter_mut().for_each(|n| n.span = Span::default()),
            StmtKind::HalfAngle { cos, sin, angle } => {
                cos.span = Span::default();
                sin.span = Span::default();
                angle.erase_spans();
            }
        }
    }
}

impl Program {
    /// Resets every span in the program, as [`Expr::erase_spans`] does.
    pub fn erase_spans(&mut self) {
        self.statements.iter_mut().for_each(Stmt::erase_spans);
    }
}
