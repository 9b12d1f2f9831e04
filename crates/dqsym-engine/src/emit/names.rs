//! Names from outside (a robot's name, joint names, the user's symbols) in the text we write.
//! Two rules, each in one place:
//!
//! - **Text never becomes code.** Text in a comment or a docstring goes through
//!   [`comment_lines`] for its syntax: every line of a multi-line text is commented on its own,
//!   control characters and Unicode's invisible line and direction controls are escaped
//!   ([`printable`]: `\u{1b}`, `\r`), and what would end the comment or change its meaning is
//!   broken up: `*/` and `/*` in C and JavaScript block comments (`* /`, `/ *`), trigraphs and a
//!   trailing backslash in C line comments, `"""`, `\` and `"` in Python docstrings (`\"`, `\\`),
//!   a `coding:` declaration in Python comments, Markdown that rustdoc would run or render in
//!   Rust doc comments (code fences, indented code, HTML, links). [`html_text`] escapes text for
//!   Markdown headings and HTML, [`toml_string`] writes a TOML basic string, [`terminal_text`]
//!   keeps an error message's lines but escapes the rest (a robot file's quoted text).
//! - **Symbols never become keywords.** A name the target language reserves gets `_` appended
//!   (`int` -> `int_`, `fn` -> `fn_`, `lambda` -> `lambda_`), again until it is neither reserved
//!   nor another name of the same function ([`safe_names`]). What a language reserves is one
//!   table per language ([`reserved`]): C's keywords (C99 to C23) and every name `<math.h>`
//!   declares or defines (`cos`, `M_PI`, `HUGE_VAL`, the `f`/`l` variants); Rust's strict and
//!   reserved keywords, the prelude's variants (`None`, `Some`, `Ok`, `Err`: a parameter
//!   pattern cannot bind them) and the paths the code names (`std`, `core`, `f64`; `f64`'s
//!   methods are called with `.` and cannot collide); Python's keywords and builtins and the
//!   NumPy function's own names (`np`, `shape`); JavaScript's reserved words and `Math`. Each
//!   emitter adds the names it writes itself (its outputs, its function and struct). SymPy is
//!   the exception: a symbol keeps its name, and one `sympify` reads as something else (a
//!   constant `E`, `oo`, a function `beta`, `gamma`, `S`, a keyword `lambda`: every name of
//!   `from sympy import *` (SymPy 1.14), Python's keywords and builtin functions) is written
//!   `Symbol('E')`, which `sympify` reads back as the symbol.

use std::collections::HashSet;
use std::sync::OnceLock;

/// A language or syntax we write names into.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Lang {
    /// C99 (`gcc -std=c99`).
    C,
    /// Rust (2021 edition).
    Rust,
    /// Python 3 with NumPy.
    Python,
    /// JavaScript (strict mode).
    JavaScript,
    /// Text for SymPy's `sympify`.
    Sympy,
}

/// A comment or docstring syntax.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Comment {
    /// Inside a C or JavaScript `/* ... */` block.
    Block,
    /// A C `//` line.
    CLine,
    /// A Rust or JavaScript `//` line.
    Slashes,
    /// A Rust `///` doc line (Markdown, run by rustdoc).
    RustDoc,
    /// A Python `#` line.
    Python,
    /// Inside a Python `"""` docstring.
    Docstring,
    /// A `#` line of TOML or of a plain report.
    Hash,
    /// A LaTeX `%` line.
    Latex,
}

/// Whether `c` is invisible or moves the text: control characters, Unicode's line and
/// paragraph separators, direction marks, embeddings, overrides and isolates (which reorder
/// what a reader sees: rustc rejects them in comments), the byte-order mark.
fn hidden(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{200b}'..='\u{200f}'
                | '\u{2028}'..='\u{202e}'
                | '\u{2060}'..='\u{2069}'
                | '\u{feff}'
        )
}

/// `text` with every hidden character (control characters, line separators, direction
/// controls) written as an escape: `\n`, `\r`, `\t`, `\u{1b}`. For a terminal and for every
/// comment: nothing in it clears a screen, colours text or starts a line.
pub fn printable(text: &str) -> String {
    if !text.chars().any(hidden) {
        return text.to_owned();
    }
    text.chars()
        .map(|c| {
            if hidden(c) {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// `text` for a terminal, lines kept: every hidden character but `\n` and `\t` escaped as
/// [`printable`] does. For messages that quote a file's text (a field, a name, a path).
pub fn terminal_text(text: &str) -> String {
    text.split('\n')
        .map(|l| l.split('\t').map(printable).collect::<Vec<_>>().join("\t"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The lines of `text` (split at `\n`), each escaped for the comment syntax: one comment line
/// each, or one line of a block or docstring, with the comment markers the caller adds.
pub fn comment_lines(syntax: Comment, text: &str) -> Vec<String> {
    text.split('\n')
        .map(|l| {
            let l = printable(l);
            match syntax {
                Comment::Block => block_line(&l),
                Comment::CLine => c_line(&l),
                Comment::Slashes | Comment::Hash | Comment::Latex => l,
                Comment::RustDoc => rust_doc_line(&l),
                Comment::Python => python_line(&l),
                Comment::Docstring => l.replace('\\', "\\\\").replace('"', "\\\""),
            }
        })
        .collect()
}

/// `text` as whole comment lines: `prefix` and a space before each line (none before an empty
/// one), each line ended.
pub fn line_comment(syntax: Comment, prefix: &str, text: &str) -> String {
    comment_lines(syntax, text)
        .iter()
        .map(|l| {
            if l.is_empty() {
                format!("{prefix}\n")
            } else {
                format!("{prefix} {l}\n")
            }
        })
        .collect()
}

/// A line inside `/* */`: no `*/` to end it, no `/*` (gcc's `-Wcomment`), no `??` (a trigraph
/// `??/` before the line's end would join two lines).
fn block_line(l: &str) -> String {
    let mut out = String::with_capacity(l.len());
    let mut prev = ' ';
    for c in l.chars() {
        if matches!((prev, c), ('*', '/') | ('/', '*') | ('?', '?')) {
            out.push(' ');
        }
        out.push(c);
        prev = c;
    }
    out
}

/// A C `//` line: no trigraph, and no backslash at its end (a line splice would comment out
/// the next line).
fn c_line(l: &str) -> String {
    let mut out = block_line(l).trim_end().to_owned();
    if out.ends_with('\\') {
        out.push('.');
    }
    out
}

/// A Python `#` line: `coding:` or `coding=` would declare the file's encoding on its first
/// two lines.
fn python_line(l: &str) -> String {
    l.replace("coding:", "coding :")
        .replace("coding=", "coding =")
}

/// A rustdoc line that Markdown reads as text, so that no code block (a doctest) can start:
/// no indentation (leading whitespace dropped, runs of spaces inside made one: an indented
/// block can also follow a list marker or `>`), no fence (a run of three or more backticks or
/// tildes escaped; one or two only mark inline code), HTML and links escaped.
fn rust_doc_line(l: &str) -> String {
    let chars: Vec<char> = l.trim().chars().collect();
    let mut out = String::with_capacity(l.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let run = chars[i..].iter().take_while(|&&x| x == c).count();
        if c.is_whitespace() {
            out.push(' ');
            i += run;
            continue;
        }
        let fence = matches!(c, '`' | '~') && run >= 3;
        for _ in 0..run {
            if fence || matches!(c, '\\' | '<' | '>' | '&' | '[' | ']') {
                out.push('\\');
            }
            out.push(c);
        }
        i += run;
    }
    out
}

/// `text` for HTML and for Markdown read by a renderer that passes HTML through: `&`, `<`,
/// `>`, `"`, `'` as entities, hidden characters escaped (a newline too, so a heading stays
/// one line).
pub fn html_text(text: &str) -> String {
    printable(text)
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&#39;")
}

/// `text` as a TOML basic string, quotes included: `\"`, `\\`, control characters as
/// `\uXXXX` (TOML has no `\u{...}`).
pub fn toml_string(text: &str) -> String {
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// C keywords, C99 to C23 (and GNU's `asm`).
const C_KEYWORDS: &[&str] = &[
    "_Alignas",
    "_Alignof",
    "_Atomic",
    "_BitInt",
    "_Bool",
    "_Complex",
    "_Decimal128",
    "_Decimal32",
    "_Decimal64",
    "_Generic",
    "_Imaginary",
    "_Noreturn",
    "_Static_assert",
    "_Thread_local",
    "alignas",
    "alignof",
    "asm",
    "auto",
    "bool",
    "break",
    "case",
    "char",
    "const",
    "constexpr",
    "continue",
    "default",
    "do",
    "double",
    "else",
    "enum",
    "extern",
    "false",
    "float",
    "for",
    "goto",
    "if",
    "inline",
    "int",
    "long",
    "nullptr",
    "register",
    "restrict",
    "return",
    "short",
    "signed",
    "sizeof",
    "static",
    "static_assert",
    "struct",
    "switch",
    "thread_local",
    "true",
    "typedef",
    "typeof",
    "typeof_unqual",
    "union",
    "unsigned",
    "void",
    "volatile",
    "while",
];

/// The functions `<math.h>` declares (C99); each has `f` and `l` variants too.
const C_MATH_FUNCTIONS: &[&str] = &[
    "acos",
    "acosh",
    "asin",
    "asinh",
    "atan",
    "atan2",
    "atanh",
    "cbrt",
    "ceil",
    "copysign",
    "cos",
    "cosh",
    "erf",
    "erfc",
    "exp",
    "exp2",
    "expm1",
    "fabs",
    "fdim",
    "floor",
    "fma",
    "fmax",
    "fmin",
    "fmod",
    "frexp",
    "hypot",
    "ilogb",
    "ldexp",
    "lgamma",
    "llrint",
    "llround",
    "log",
    "log10",
    "log1p",
    "log2",
    "logb",
    "lrint",
    "lround",
    "modf",
    "nan",
    "nearbyint",
    "nextafter",
    "nexttoward",
    "pow",
    "remainder",
    "remquo",
    "rint",
    "round",
    "scalbln",
    "scalbn",
    "sin",
    "sinh",
    "sqrt",
    "tan",
    "tanh",
    "tgamma",
    "trunc",
];

/// The macros and types of `<math.h>` (C99, and the POSIX constants glibc defines).
const C_MATH_MACROS: &[&str] = &[
    "FP_FAST_FMA",
    "FP_FAST_FMAF",
    "FP_FAST_FMAL",
    "FP_ILOGB0",
    "FP_ILOGBNAN",
    "FP_INFINITE",
    "FP_NAN",
    "FP_NORMAL",
    "FP_SUBNORMAL",
    "FP_ZERO",
    "HUGE_VAL",
    "HUGE_VALF",
    "HUGE_VALL",
    "INFINITY",
    "MATH_ERREXCEPT",
    "MATH_ERRNO",
    "M_1_PI",
    "M_2_PI",
    "M_2_SQRTPI",
    "M_E",
    "M_LN10",
    "M_LN2",
    "M_LOG10E",
    "M_LOG2E",
    "M_PI",
    "M_PI_2",
    "M_PI_4",
    "M_SQRT1_2",
    "M_SQRT2",
    "NAN",
    "NULL",
    "double_t",
    "float_t",
    "fpclassify",
    "isfinite",
    "isgreater",
    "isgreaterequal",
    "isinf",
    "isless",
    "islessequal",
    "islessgreater",
    "isnan",
    "isnormal",
    "isunordered",
    "math_errhandling",
    "signbit",
];

/// Rust's strict, reserved and 2024 keywords, the prelude's variants and the paths the
/// generated code names.
const RUST_RESERVED: &[&str] = &[
    "Err", "None", "Ok", "Self", "Some", "abstract", "as", "async", "await", "become", "box",
    "break", "const", "continue", "core", "crate", "do", "dyn", "else", "enum", "extern", "f64",
    "false", "final", "fn", "for", "gen", "if", "impl", "in", "let", "loop", "macro", "match",
    "mod", "move", "mut", "override", "priv", "pub", "ref", "return", "self", "static", "std",
    "struct", "super", "trait", "true", "try", "type", "typeof", "unsafe", "unsized", "use",
    "virtual", "where", "while", "yield",
];

/// Python's keywords and builtins (but its exceptions), and the NumPy function's own names.
const PYTHON_RESERVED: &[&str] = &[
    "Ellipsis",
    "False",
    "None",
    "NotImplemented",
    "True",
    "abs",
    "aiter",
    "all",
    "and",
    "anext",
    "any",
    "as",
    "ascii",
    "assert",
    "async",
    "await",
    "bin",
    "bool",
    "break",
    "breakpoint",
    "bytearray",
    "bytes",
    "callable",
    "chr",
    "class",
    "classmethod",
    "compile",
    "complex",
    "continue",
    "copyright",
    "credits",
    "def",
    "del",
    "delattr",
    "dict",
    "dir",
    "divmod",
    "elif",
    "else",
    "enumerate",
    "eval",
    "except",
    "exec",
    "exit",
    "filter",
    "finally",
    "float",
    "for",
    "format",
    "from",
    "frozenset",
    "getattr",
    "global",
    "globals",
    "hasattr",
    "hash",
    "help",
    "hex",
    "id",
    "if",
    "import",
    "in",
    "input",
    "int",
    "is",
    "isinstance",
    "issubclass",
    "iter",
    "lambda",
    "len",
    "license",
    "list",
    "locals",
    "map",
    "math",
    "max",
    "memoryview",
    "min",
    "next",
    "nonlocal",
    "not",
    "np",
    "object",
    "oct",
    "open",
    "or",
    "ord",
    "pass",
    "pow",
    "print",
    "property",
    "quit",
    "raise",
    "range",
    "repr",
    "return",
    "reversed",
    "round",
    "set",
    "setattr",
    "shape",
    "slice",
    "sorted",
    "staticmethod",
    "str",
    "sum",
    "super",
    "try",
    "tuple",
    "type",
    "vars",
    "while",
    "with",
    "yield",
    "zip",
];

/// JavaScript's reserved words (ES2023, strict mode) and the globals the code reads or that
/// strict mode forbids binding.
const JS_RESERVED: &[&str] = &[
    "Infinity",
    "Math",
    "NaN",
    "arguments",
    "await",
    "break",
    "case",
    "catch",
    "class",
    "const",
    "continue",
    "debugger",
    "default",
    "delete",
    "do",
    "else",
    "enum",
    "eval",
    "export",
    "extends",
    "false",
    "finally",
    "for",
    "function",
    "if",
    "implements",
    "import",
    "in",
    "instanceof",
    "interface",
    "let",
    "new",
    "null",
    "package",
    "private",
    "protected",
    "public",
    "return",
    "static",
    "super",
    "switch",
    "this",
    "throw",
    "true",
    "try",
    "typeof",
    "undefined",
    "var",
    "void",
    "while",
    "with",
    "yield",
];

/// The names `sympify` reads as something other than a symbol: `from sympy import *`
/// (SymPy 1.14), Python's keywords and the builtin functions `parse_expr` binds.
const SYMPY_NAMES: &str = include_str!("sympy_names.txt");

fn sympy_names() -> &'static HashSet<&'static str> {
    static SET: OnceLock<HashSet<&'static str>> = OnceLock::new();
    SET.get_or_init(|| SYMPY_NAMES.lines().filter(|l| !l.is_empty()).collect())
}

/// Every name of the language's table (see the module documentation): what [`safe_names`]
/// renames. The generated family of tests uses every one of them as a symbol.
pub fn reserved_names(lang: Lang) -> Vec<String> {
    let list: Vec<&str> = match lang {
        Lang::C => C_KEYWORDS
            .iter()
            .chain(C_MATH_MACROS)
            .copied()
            .chain(C_MATH_FUNCTIONS.iter().copied())
            .collect(),
        Lang::Rust => RUST_RESERVED.to_vec(),
        Lang::Python => PYTHON_RESERVED.to_vec(),
        Lang::JavaScript => JS_RESERVED.to_vec(),
        Lang::Sympy => sympy_names().iter().copied().collect(),
    };
    let mut v: Vec<String> = list.into_iter().map(str::to_owned).collect();
    if lang == Lang::C {
        for f in C_MATH_FUNCTIONS {
            v.push(format!("{f}f"));
            v.push(format!("{f}l"));
        }
    }
    v.sort();
    v.dedup();
    v
}

/// Whether `lang` reserves `name` (its table; see the module documentation).
pub fn reserved(lang: Lang, name: &str) -> bool {
    match lang {
        Lang::C => {
            C_KEYWORDS.contains(&name)
                || C_MATH_MACROS.contains(&name)
                || C_MATH_FUNCTIONS.contains(&name)
                || name
                    .strip_suffix(['f', 'l'])
                    .is_some_and(|b| C_MATH_FUNCTIONS.contains(&b))
        }
        Lang::Rust => RUST_RESERVED.contains(&name),
        Lang::Python => PYTHON_RESERVED.contains(&name),
        Lang::JavaScript => JS_RESERVED.contains(&name),
        Lang::Sympy => sympy_names().contains(name),
    }
}

/// The identifiers `names` are written as in `lang`: each name `lang` reserves, or that is
/// among `fixed` (the names the emitter writes itself), with `_` appended until it is none of
/// those and no other name of the list (`int` -> `int_`; `int_` when `int_` is taken too ->
/// `int__`). Names that need no change keep theirs, so the result has no duplicates when
/// `names` has none.
pub fn safe_names(lang: Lang, names: &[String], fixed: &[&str]) -> Vec<String> {
    let bad = |n: &str| reserved(lang, n) || fixed.contains(&n);
    let mut taken: HashSet<String> = names.iter().filter(|n| !bad(n)).cloned().collect();
    names
        .iter()
        .map(|n| {
            if !bad(n) {
                return n.clone();
            }
            let mut s = format!("{n}_");
            while bad(&s) || taken.contains(&s) {
                s.push('_');
            }
            taken.insert(s.clone());
            s
        })
        .collect()
}

/// One name as [`safe_names`] writes it alone (a function's name).
pub fn safe_name(lang: Lang, name: &str, fixed: &[&str]) -> String {
    safe_names(lang, &[name.to_owned()], fixed).remove(0)
}

/// A symbol as SymPy text: its name, or `Symbol('name')` when `sympify` would read the name
/// as something else.
pub fn sympy_symbol(name: &str) -> String {
    if reserved(Lang::Sympy, name) {
        format!("Symbol('{name}')")
    } else {
        name.to_owned()
    }
}

/// The literal for an f64 in `lang`: the shortest text that reads back exactly (`0.5`,
/// `2.0`), and past f64's range the language's infinity: an exact constant too large for a
/// double evaluates there as dqsym's own f64 evaluation does.
pub(crate) fn float_literal(lang: Lang, v: f64) -> String {
    if v.is_finite() {
        return format!("{v:?}");
    }
    let (inf, nan) = match lang {
        Lang::C => ("HUGE_VAL", "NAN"),
        Lang::Rust => ("f64::INFINITY", "f64::NAN"),
        Lang::Python => ("np.inf", "np.nan"),
        Lang::JavaScript => ("Infinity", "NaN"),
        Lang::Sympy => ("oo", "nan"),
    };
    match v {
        v if v.is_nan() => nan.to_owned(),
        v if v > 0.0 => inf.to_owned(),
        _ => format!("(-{inf})"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renamed_names_avoid_each_other_and_the_fixed_ones() {
        let names: Vec<String> = ["int", "int_", "x", "value"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        assert_eq!(
            safe_names(Lang::C, &names, &["value"]),
            ["int__", "int_", "x", "value_"]
        );
        assert_eq!(safe_name(Lang::Rust, "self", &[]), "self_");
        assert!(reserved(Lang::C, "cosf") && reserved(Lang::C, "sqrtl") && !reserved(Lang::C, "x"));
    }

    #[test]
    fn comment_lines_break_every_terminator() {
        let l = comment_lines(Comment::Block, "a*/b/*c??/\nd\u{1b}");
        assert_eq!(l, ["a* /b/ *c? ?/", "d\\u{1b}"]);
        assert_eq!(comment_lines(Comment::CLine, "x \\ "), ["x \\."]);
        assert_eq!(
            comment_lines(Comment::Docstring, "\"\"\" \\N"),
            ["\\\"\\\"\\\" \\\\N"]
        );
        assert_eq!(
            comment_lines(Comment::RustDoc, "   ```rust  <b>`x`"),
            ["\\`\\`\\`rust \\<b\\>`x`"]
        );
        assert_eq!(line_comment(Comment::Hash, "#", "a\n\nb"), "# a\n#\n# b\n");
        assert_eq!(toml_string("a\"\\\n\u{1b}"), "\"a\\\"\\\\\\n\\u001B\"");
        assert_eq!(
            html_text("<a href='x'>&"),
            "&lt;a href=&#39;x&#39;&gt;&amp;"
        );
    }
}
