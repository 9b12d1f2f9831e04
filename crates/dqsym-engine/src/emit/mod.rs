//! Emitters: pure functions from closed forms ([`Expr`](crate::Expr)) to text that another tool
//! reads. LaTeX for papers (checked by KaTeX in the tests), SymPy-parsable text, and source code
//! (Rust, C, Python/NumPy, JavaScript for the interactive walkthrough page) that shares common subexpressions across all outputs. Like the
//! printers, emitters never simplify: what they write equals the expression they were given.

mod c;
pub(crate) mod codegen;
mod count;
pub(crate) mod helpers;
pub(crate) mod javascript;
pub use latex::visual_len;
mod latex;
pub mod names;
mod python;
mod rust;
pub(crate) mod sympy;
pub(crate) mod syntax;

pub use c::c_function;
pub use codegen::{arguments, CodegenError, CodegenOptions, OpCount, Output};
pub use count::{count_ops, generated_ops, product_table, rotation_chain_ops, Counted};
pub use javascript::javascript_function;
pub use latex::{
    latex, latex_aligned, latex_aligned_named, latex_dual_quat, latex_matrix, latex_named,
    latex_quotient, latex_quotient_matrix, latex_shorthand, latex_symbol, latex_tuple,
    LatexOptions,
};
pub use python::{python_function, python_names};
pub use rust::rust_function;
pub use sympy::{sympy, sympy_decimals, sympy_quotient};
pub use syntax::function;
