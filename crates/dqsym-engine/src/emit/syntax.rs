//! The syntax of each target language, written once: literals, locals, comments, constants
//! ([`Syntax`]), and the statements of an IK solver ([`SolverSyntax`]). Each language's
//! implementation lives in its own module (`rust.rs`, `c.rs`, `python.rs`, `javascript.rs`),
//! beside its fk function writer; fk code ([`function`]), `show`, both IK methods' solver
//! writers (`ik/emit.rs`, `ik/general/emit.rs`, which hold the solvers' logic once) and the
//! walkthrough page's code all write through it.
//!
//! Adding a language: a module implementing these traits (the compiler lists what is missing)
//! and its arm in [`syntax`] / [`solver_syntax`]; for IK solvers, its runtime helpers
//! (`runtime/ik_helpers.*`, each declared by a marker line, see `helpers.rs`).

use super::codegen::{CodegenError, CodegenOptions, Output};
use super::names::{Comment, Lang};

/// The syntax every generated text of a language shares, and its function writer.
pub(crate) trait Syntax {
    /// The language, for its reserved names ([`super::names`]).
    fn lang(&self) -> Lang;

    /// A self-contained function `name` computing `outputs` from `args` (fk code, `show`'s
    /// code formats, the walkthrough page's functions): the language's `*_function`.
    ///
    /// # Errors
    /// As [`super::rust_function`].
    fn function(
        &self,
        name: &str,
        doc: &str,
        outputs: &[Output],
        args: &[String],
        o: &CodegenOptions,
    ) -> Result<String, CodegenError>;

    /// The literal for `v`: the shortest text that reads back exactly (Rust: a
    /// `std::f64::consts` name where one matches, as clippy's `approx_constant` asks).
    fn literal(&self, v: f64) -> String {
        super::names::float_literal(self.lang(), v)
    }

    /// A local binding of a double `name` to `value`, without indentation or newline.
    fn local(&self, name: &str, value: &str) -> String;

    /// The prefix of a comment after code on a line (`//`, `#`).
    fn inline_comment(&self) -> &'static str;

    /// One line of a comment block at the top level (`// text`, `/* text */`), with newline.
    fn comment_line(&self, text: &str) -> String {
        format!("{} {text}\n", self.inline_comment())
    }

    /// A constant `name` of the value text `value` and type `ty` (`f64` or `usize`), with
    /// newline.
    fn constant(&self, name: &str, value: &str, ty: &str) -> String;

    /// `a || b` joined.
    fn or(&self) -> &'static str {
        " || "
    }

    /// The false boolean literal.
    fn false_literal(&self) -> &'static str {
        "false"
    }

    /// A list literal `[a, b]` (C: `{a, b}`) of the already written items.
    fn list(&self, items: &str) -> String {
        format!("[{items}]")
    }

    /// A constant table of doubles at the top level: `name`, of dimensions `dims` (rows, then
    /// columns; one for a vector), bound to the list literal `value`; with newline.
    fn table(&self, name: &str, _dims: &[usize], value: &str) -> String {
        format!("{}\n", self.local(name, value))
    }

    /// A local array of doubles `name` of dimensions `dims` bound to the list literal `value`,
    /// without indentation or newline (as [`Syntax::local`]).
    fn array_local(&self, name: &str, _dims: &[usize], value: &str) -> String {
        self.local(name, value)
    }

    /// A call of the scalar function `f` (`sin`, `cos`) on `arg`.
    fn call(&self, f: &str, arg: &str) -> String;

    /// An IK solver's shape constants after its tolerances (`IK_DOF`, `IK_POSITION_ONLY`,
    /// `IK_EPS` where the helpers need them).
    fn shape_constants(&self, dof: usize, position_only: bool) -> String;
}

/// The statements of an IK solver (see `ik/emit.rs`, which decides what they compute): the
/// calls into the language's runtime helpers (`emit/runtime/ik_helpers.*`), the loops over a
/// step's roots and the file around the solver.
pub(crate) trait SolverSyntax: Syntax {
    /// What separates the solver's helpers (and its constants before them): a blank line.
    fn helper_separator(&self) -> &'static str {
        "\n\n"
    }

    /// The comment syntax of the solver's documentation lines.
    fn doc_syntax(&self) -> Comment;

    /// The declaration of step `k`'s atan2 memo (level 0).
    fn memo(&self, k: usize) -> String;

    /// The memo of step `k` as a call argument.
    fn memo_arg(&self, k: usize) -> String;

    /// `s = sin(a)` and `c = cos(a)` at indentation `pad`, newline included.
    fn sin_cos(&self, pad: &str, s: &str, c: &str, a: &str) -> String;

    /// The name of a runtime helper (`ik_atan2`) as the language calls it.
    fn helper(&self, name: &str) -> String {
        name.to_string()
    }

    /// The binding of step `k`'s roots to the helper call `call`, without indentation.
    fn roots(&self, k: usize, call: &str) -> String;

    /// Step `i`'s flag `field` (`sg` singular, `ck` checked).
    fn flag(&self, i: usize, field: &str) -> String {
        format!("ik_r{i}.{field}")
    }

    /// Whether the roots of step `i` at its loop index are samples beside a kept value.
    fn sampled(&self, i: usize) -> String;

    /// The check's data: the axes `ax` and home rows `hm` (list literals) and the scale.
    fn chain(&self, pad: &str, ax: &str, hm: &str) -> String;

    /// The robot's scale as the solver names it.
    fn scale(&self) -> &'static str {
        "ik_ch.len"
    }

    /// The push of a complete solution `q` (joint names) with its flags.
    fn push(&self, pad: &str, q: &str, sg: &str, ck: &str, smp: &str) -> String;

    /// The loop over step `k`'s roots binding `q`, `s_q`, `c_q`; a trig step skips its pair
    /// beside a double root that already gave a solution on the pose.
    fn loop_open(&self, pad: &str, inner: &str, k: usize, q: &str, trig: bool) -> String;

    /// The end of a loop.
    fn loop_close(&self, pad: &str) -> String {
        format!("{pad}}}\n")
    }

    /// The whole file around the solver's body.
    fn file(&self, f: &SolverFile) -> String;

    /// The parameters (symbolic lengths) after the target in the solver's signatures.
    fn parameters(&self, params: &[String]) -> String;

    /// The parameters passed on from one entry point to another.
    fn pass(&self, params: &[String]) -> String {
        params.iter().map(|p| format!(", {p}")).collect()
    }

    /// The entry points over the solver's main function (`ik` over `ik_into`, `ik_dq` over
    /// `ik`), the same for every method, ending with one newline.
    fn entry_points(&self, params: &[String], variables: &[String]) -> String;

    /// The whole file of a general-method solver (`ik/general/emit.rs`): its numeric core
    /// and the driver around it.
    fn general_file(&self, f: &GeneralFile) -> String;
}

/// What a general-method solver file is made of (see [`SolverSyntax::general_file`]).
pub(crate) struct GeneralFile<'a> {
    /// The documentation, written as comment lines.
    pub doc: String,
    /// The parameters (symbolic lengths) after the target.
    pub params: &'a [String],
    /// The joint variables, in order.
    pub variables: &'a [String],
    /// The literals of the pose tolerance and of the elimination's keep tolerance.
    pub pose_tol: String,
    /// See `pose_tol`.
    pub keep_tol: String,
    /// The arrangement of the loop tried first.
    pub first: usize,
    /// The family solvers' tolerance constants (the C solver states them).
    pub tolerances: String,
    /// The numeric core's constants (none in Rust: the core is included verbatim).
    pub constants: String,
    /// The numeric core's source in the language.
    pub core: &'a str,
    /// The statements binding the axes `ik_ax` and the home pose `ik_home`.
    pub chain: String,
    /// The runtime helper `ik_dq_matrix`.
    pub dq_matrix: &'static str,
    /// The chain is a 4R2P with its slides three joints apart: the driver calls the apart
    /// core's entry (`apart_solver.rs` and its ports, after the core) instead of the core's.
    pub apart: bool,
}

/// What the language's solver file is made of (see [`SolverSyntax::file`]).
pub(crate) struct SolverFile<'a> {
    /// The documentation lines, escaped for [`SolverSyntax::doc_syntax`].
    pub doc: Vec<String>,
    /// The number of joints.
    pub dof: usize,
    /// The most solutions.
    pub max: usize,
    /// The parameters (symbolic lengths) after the target.
    pub params: &'a [String],
    /// The joint variables, in order.
    pub variables: &'a [String],
    /// The target pose's entry names, row by row (top three rows).
    pub target: &'a [[&'a str; 4]; 3],
    /// The helper functions and constants.
    pub helpers: String,
    /// The solver's body (indented by 4).
    pub body: String,
}

/// A function `name` computing `outputs` from `args` in `lang` (Rust, C, Python or
/// JavaScript), through the language's one writer.
///
/// # Errors
/// When an output reads a symbol that is not an argument, a name is not an identifier, or an
/// output's shape does not match its values; SymPy, which is not code.
pub fn function(
    lang: Lang,
    name: &str,
    doc: &str,
    outputs: &[Output],
    args: &[String],
    o: &CodegenOptions,
) -> Result<String, CodegenError> {
    if lang == Lang::Sympy {
        return Err(CodegenError::NoWriter(lang));
    }
    syntax(lang).function(name, doc, outputs, args, o)
}

/// The syntax of `lang` (SymPy text has none of its own here: JavaScript's is returned).
pub(crate) fn syntax(lang: Lang) -> &'static dyn Syntax {
    match lang {
        Lang::Rust => &super::rust::Rust,
        Lang::C => &super::c::C,
        Lang::Python => &super::python::Python,
        Lang::JavaScript | Lang::Sympy => &super::javascript::JavaScript,
    }
}

/// The solver syntax of `lang`, for the languages IK solvers are written in.
pub(crate) fn solver_syntax(lang: Lang) -> Option<&'static dyn SolverSyntax> {
    match lang {
        Lang::Rust => Some(&super::rust::Rust),
        Lang::C => Some(&super::c::C),
        Lang::Python => Some(&super::python::Python),
        Lang::JavaScript | Lang::Sympy => None,
    }
}
