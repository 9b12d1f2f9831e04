//! Printers: pure functions from display expressions to text. They never simplify.

mod convert;
mod fk;
mod plain;
mod recurrence;
mod task;

pub use convert::robot_toml;
pub use fk::{fk_entries, fk_report, ops_tables, FkEntries, FkOptions, ReportError, ReportFormat};
pub(crate) use plain::angle_text;
pub use plain::{
    legend, plain, plain_named, plain_quotient, plain_quotient_named, shorthand_name, PlainOptions,
    TrigNames,
};
pub use recurrence::fk_recurrence;
pub use task::{rate_name, task_jacobian, task_report, TaskJacobian};
