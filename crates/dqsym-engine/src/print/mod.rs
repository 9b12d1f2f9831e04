//! Printers: pure functions from display expressions to text. They never simplify.

mod plain;

pub use plain::{legend, plain, plain_named, plain_quotient, plain_quotient_named, PlainOptions};
