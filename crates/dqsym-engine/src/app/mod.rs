//! The application layer: whole derivations built from the layers below (kinematics, closed
//! forms, printers, emitters): the `fk` report and its recurrence, the task Jacobians, the ops
//! tables, a robot written back as a screw-form file.

mod convert;
mod fk;
mod recurrence;
mod task;

pub use convert::{dh_refusal, robot_toml};
pub use fk::{fk_entries, fk_report, ops_tables, FkEntries, FkOptions, ReportError, ReportFormat};
pub use recurrence::fk_recurrence;
pub use task::{rate_name, task_jacobian, task_report, TaskJacobian, TaskMatrix};
