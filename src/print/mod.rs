//! Printers: pure functions from display expressions to text. They never simplify.

mod plain;

pub use plain::{legend, plain, shorthand_name, PlainOptions};
