//! Printers: pure functions from display expressions to text. They never simplify.

mod plain;

pub use plain::angle_text;
pub use plain::{
    legend, plain, plain_named, plain_quotient, plain_quotient_named, shorthand_name, PlainOptions,
    TrigNames,
};
