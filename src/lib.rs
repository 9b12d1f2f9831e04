//! dqsym: exact symbolic algebra of dual quaternions for robot kinematics, with a script
//! language, teaching walkthroughs and the paper's derivations.
//!
//! This crate re-exports the engine ([`dqsym_engine`]: scalars, algebra, kinematics, closed
//! forms, printers, emitters, reports) and adds, above it:
//!
//! - [`lang`]: the script language: [`parse`] a program, run it in a [`Session`], [`show`]
//!   a [`Value`] as plain text, LaTeX, SymPy or Rust; robot-file fields are read through
//!   [`eval_scalar_text`];
//! - [`walk`]: walkthroughs of a script or a robot file, as text, Markdown or an HTML page;
//! - [`paper`]: the paper's worked examples, derived from the files of `examples/`.
//!
//! The core nouns are re-exported here; everything else is reached through its module
//! (`dqsym::lang::parse_with`, `dqsym::walk::Config`, `dqsym::emit::rust_function`). The
//! binary's dependencies (clap, rustyline, ctrlc) come with the default feature `cli`; a
//! library user depends on `dqsym = { ..., default-features = false }` and builds none of them.
//!
//! ```
//! use dqsym::{parse, Scalar, Session, Value};
//!
//! let mut session = Session::new();
//! session.run(&parse("syms t\nx = cos(t)^2 + sin(t)^2")?)?;
//! assert_eq!(session.get("x"), Some(&Value::Scalar(Scalar::int(1))));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

pub use dqsym_engine::*;

pub mod lang;
mod paper;
pub mod walk;

// The core nouns of the language, the walkthroughs and the paper.
pub use lang::{
    eval_scalar_text, parse, show, EvalError, ParseError, Program, Session, ShowOptions, Value,
};
pub use paper::{paper, PaperError};
pub use walk::{walk_html, walk_markdown, walk_robot, walk_script, walk_text, Walkthrough};
