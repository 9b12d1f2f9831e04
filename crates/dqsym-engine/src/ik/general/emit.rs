//! Generated solvers for the general method.
