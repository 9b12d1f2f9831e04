//! Printers: pure functions from display expressions to text. They never simplify.

mod plain;

pub(crate) use plain::angle_text;
pub use plain::{legend, plain, shorthand_name, PlainOptions};
