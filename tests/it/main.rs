//! The integration tests: one binary, one module per concern.

mod algebra;
mod cli;
mod common;
mod lang;
mod laws;
mod paper;
mod paper_arms;
mod paper_support;
mod parse;
mod scalar;
