//! The application layer: whole derivations built from the layers below (kinematics, closed
//! forms, printers, emitters).
//!
//! - [`fk_report`]: the `dqsym fk` report of a [`Robot`](crate::Robot) in any
//!   [`Format`](crate::Format) ([`FkOptions`]); [`fk_entries`] its closed forms before any
//!   formatting, its entries and sections typed ([`Quantity`], [`SectionKind`]: every name,
//!   LaTeX letter, generated output and title is written in `quantity.rs`); [`fk_recurrence`] the recurrence over the joint factors it prints past the
//!   term limit; [`fk_ops`] the operation counts of its generated code (`dqsym ops ROBOT`).
//! - [`task_report`], [`task_jacobian`]: the task Jacobians of `fk --jacobian=KIND`
//!   ([`TaskJacobian`]).
//! - [`ops_tables`]: the paper's operation-count tables.
//! - [`robot_toml`]: a robot written back as a robot file (classic DH when the axes allow,
//!   screw form otherwise, [`dh_refusal`] says why).

mod convert;
mod fk;
mod quantity;
mod recurrence;
mod task;

pub use convert::{dh_refusal, robot_toml, DhRefusal};
pub use fk::{
    fk_entries, fk_ops, fk_report, fk_report_and_entries, in_decimals, ops_tables, FkEntries,
    FkOptions, ReportError,
};
pub use quantity::{
    Family, Letters, MatrixFrom, Quantity, Section, SectionKind, Step, TaskBase, TaskName,
};
pub use recurrence::fk_recurrence;
pub use task::{rate_name, task_jacobian, task_report, TaskJacobian, TaskMatrix, TaskParseError};
