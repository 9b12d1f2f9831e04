//! Printers: pure functions from display expressions to text. They never simplify.

mod plain;

pub use plain::{legend, plain, plain_named, plain_quotient, plain_quotient_named, PlainOptions};

/// The output language of `--format`, one for the language's results and the `ik` report.
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
