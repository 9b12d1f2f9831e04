//! The solver of 4R2P arms with their slides three joints apart (the module docs of
//! `general/mod.rs`): its text, `apart_solver.rs`, is also written verbatim after the core into
//! generated Rust solvers, where the core's items are in scope without this import.

use super::core::*;

include!("apart_solver.rs");
