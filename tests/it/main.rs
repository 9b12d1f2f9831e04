//! The integration tests: one binary, one module per concern.

mod algebra;
mod common;
mod scalar;
mod paper;
mod paper_support;
