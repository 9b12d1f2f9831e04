//! Printers: pure functions from display expressions ([`Expr`](crate::Expr)) to plain text in
//! robotics notation. [`plain`] writes `c12` or `cos(theta1 + theta2)` ([`PlainOptions`]),
//! [`plain_named`] with the caller's names for angles, [`plain_quotient`] a quotient of two
//! closed forms, and [`legend`] lists the shorthand a text used. [`Format`] is the one output
//! format of every report; LaTeX, SymPy and code are written by [`emit`](crate::emit).
//! Printers never simplify: the text is the expression they were given.

mod plain;

pub(crate) use plain::plain_len_bound;
pub use plain::{legend, plain, plain_named, plain_quotient, plain_quotient_named, PlainOptions};

/// The output language of `--format`, one for the language's results, the `fk` report
/// ([`FkOptions`](crate::FkOptions), with `shorthand` a separate flag) and the `ik` report.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Format {
    /// Plain text in robotics notation.
    #[default]
    Plain,
    /// LaTeX, inline math.
    Latex,
    /// Text SymPy's `sympify` parses.
    Sympy,
    /// A Rust function computing the value from its symbols.
    Rust,
    /// A C99 function computing the value from its symbols.
    C,
    /// A NumPy function computing the value from its symbols, vectorized.
    Python,
}
