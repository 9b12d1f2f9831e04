//! The integration tests: one binary, one module per concern.

mod algebra;
mod cli;
mod codegen;
mod common;
mod counts;
mod dqr;
mod emit;
mod hostile;
mod ik;
mod kinematics;
mod lang;
mod laws;
mod layers;
mod limits;
mod paper;
mod paper_arms;
mod paper_support;
mod parse;
mod props;
mod quotients;
mod recurrence;
mod robots;
mod scalar;
mod tools;
mod urdf;
mod walk;
