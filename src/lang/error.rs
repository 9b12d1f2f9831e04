//! Parse errors: what went wrong, where, and a rendered snippet with a caret.
//!
//! Every error carries its location, so the binary can print it as is and the REPL can point
//! into the line just typed. Messages are lowercase without a trailing period and name the
//! token found ("expected an expression, found `)`"); pest's rule names never reach the user,
//! they are translated by [`describe`], which plays the part of pest's `renamed_rules`.

use super::ast::Span;
use super::parse::Rule;
use super::scan::SourceMap;
use thiserror::Error;

/// Lines longer than this are shown as a window around the error, so that an error in a 1 MB
/// line does not print 1 MB.
const MAX_SHOWN: usize = 100;

/// A script that could not be parsed: the reason, its place, and a rendered message.
///
/// `Display` shows the rendered form:
/// ```text
/// error: expected an expression, found end of input
///  --> 1:9
///   |
/// 1 | x = (1 +
///   |         ^
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("{rendered}")]
pub struct ParseError {
    kind: ParseErrorKind,
    span: Span,
    rendered: String,
}

impl ParseError {
    /// Builds the error for bytes `start..end` of the source, rendering it at once (the source is
    /// not kept, so the error is `'static` and cheap to pass around).
    /// Offsets are moved out to character boundaries, so callers may pass `start + 1`.
    pub(crate) fn new(map: &SourceMap<'_>, kind: ParseErrorKind, start: usize, end: usize) -> Self {
        let src = map.src();
        let start = (0..=start.min(src.len()))
            .rev()
            .find(|&i| src.is_char_boundary(i))
            .unwrap_or(0);
        let end = (end.max(start)..=src.len())
            .find(|&i| src.is_char_boundary(i))
            .unwrap_or(src.len());
        let span = map.span(start, end);
        let rendered = render(map, &kind.to_string(), span);
        ParseError {
            kind,
            span,
            rendered,
        }
    }

    /// Why the parse failed.
    pub fn kind(&self) -> &ParseErrorKind {
        &self.kind
    }

    /// Where it failed.
    pub fn span(&self) -> Span {
        self.span
    }

    /// The 1-based line of the error.
    pub fn line(&self) -> usize {
        self.span.line
    }

    /// The 1-based column of the error, in characters.
    pub fn col(&self) -> usize {
        self.span.col
    }

    /// The one-line message, without location or snippet.
    pub fn message(&self) -> String {
        self.kind.to_string()
    }

    /// The full message with location, source line and caret (the same as `Display`).
    pub fn rendered(&self) -> &str {
        &self.rendered
    }
}

/// The reasons a parse can fail.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum ParseErrorKind {
    /// The text does not follow the grammar.
    #[error("expected {expected}, found {found}")]
    Syntax {
        /// What would have been accepted, in words ("an operator or `)`").
        expected: String,
        /// What was there, in words ("`;`", "end of input").
        found: String,
    },
    /// An opening bracket is never closed (a `(` must close on its own line).
    #[error("this `{open}` is never closed")]
    Unclosed {
        /// The bracket.
        open: char,
    },
    /// A closing bracket closes nothing.
    #[error("this `{close}` has nothing to close")]
    Unmatched {
        /// The bracket.
        close: char,
    },
    /// A closing bracket does not match the innermost open one.
    #[error("this `{close}` does not match the `{open}` at {open_line}:{open_col}")]
    Mismatched {
        /// The open bracket.
        open: char,
        /// The closing bracket found.
        close: char,
        /// Line of the open bracket.
        open_line: usize,
        /// Column of the open bracket.
        open_col: usize,
    },
    /// Brackets, prefix operators or powers nest deeper than the limit.
    #[error("nesting deeper than {limit}")]
    TooDeep {
        /// The limit, [`ParseOptions::max_depth`](super::ParseOptions).
        limit: usize,
    },
    /// A line longer than the limit.
    #[error("line longer than the limit of {limit} bytes")]
    LongLine {
        /// The limit, [`ParseOptions::max_line_len`](super::ParseOptions).
        limit: usize,
    },
    /// A decimal or scientific literal whose exact value needs too many digits (`1e999999`).
    #[error("the number `{literal}` needs more than {limit} digits")]
    LongDecimal {
        /// The literal as written.
        literal: String,
        /// The limit, [`ParseOptions::max_integer_digits`](super::ParseOptions).
        limit: usize,
    },
    /// A number directly followed by a name, like `2x`.
    #[error("a number cannot run into a name: write `{number}*{name}` for a product")]
    GluedNumber {
        /// The digits.
        number: String,
        /// The name after them.
        name: String,
    },
    /// An integer literal with more digits than allowed.
    #[error("integer with {digits} digits, more than the limit of {limit}")]
    LongInteger {
        /// Its number of digits.
        digits: usize,
        /// The limit, [`ParseOptions::max_integer_digits`](super::ParseOptions).
        limit: usize,
    },
    /// A keyword used as a name.
    #[error("`{word}` is a keyword and cannot be used as a name")]
    Keyword {
        /// The keyword.
        word: String,
    },
    /// The left side of `=` is not a plain name.
    #[error("the left side of `=` must be a name")]
    AssignToExpr,
    /// `syms` with no names.
    #[error("`syms` needs at least one name")]
    EmptySyms,
    /// Matrix rows of different lengths.
    #[error("matrix row {row} has {} but row 1 has {}", entries(*.len), entries(*.first))]
    RaggedMatrix {
        /// The 1-based index of the offending row.
        row: usize,
        /// Its length.
        len: usize,
        /// The length of the first row.
        first: usize,
    },
    /// pest gave up on its own resource limits; the pre-scan normally prevents this.
    #[error("input too complex to parse ({reason})")]
    Limit {
        /// pest's reason, "stack limit reached" or "call limit reached".
        reason: String,
    },
}

/// "1 entry", "2 entries".
fn entries(n: usize) -> String {
    if n == 1 {
        "1 entry".to_owned()
    } else {
        format!("{n} entries")
    }
}

/// Renders `message` at `span`: a header, the location, the source line and a caret under the
/// span (cut at the end of the line).
pub(crate) fn render(map: &SourceMap<'_>, message: &str, span: Span) -> String {
    let line: Vec<char> = map
        .line_text(span.line)
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    let col = span.col - 1;
    let width = map.src()[span.start.min(span.end)..span.end]
        .chars()
        .take_while(|&c| c != '\n')
        .count()
        .clamp(1, (line.len().saturating_sub(col)).max(1));
    let (from, to) = if line.len() <= MAX_SHOWN {
        (0, line.len())
    } else {
        let from = col
            .saturating_sub(MAX_SHOWN / 2)
            .min(line.len() - MAX_SHOWN);
        (from, from + MAX_SHOWN)
    };
    let mut shown: String = line[from..to].iter().collect();
    let mut caret_at = col - from;
    if from > 0 {
        shown.insert_str(0, "...");
        caret_at += 3;
    }
    if to < line.len() {
        shown.push_str("...");
    }
    let number = span.line.to_string();
    let pad = " ".repeat(number.len());
    format!(
        "error: {message}\n{pad}--> {}:{}\n{pad} |\n{number} | {shown}\n{pad} | {}{}",
        span.line,
        span.col,
        " ".repeat(caret_at),
        "^".repeat(width.min(MAX_SHOWN)),
    )
}

/// Converts a pest failure into a [`ParseError`] with a message in words.
pub(crate) fn from_pest(map: &SourceMap<'_>, err: pest::error::Error<Rule>) -> ParseError {
    let pos = match err.location {
        pest::error::InputLocation::Pos(p) => p,
        pest::error::InputLocation::Span((p, _)) => p,
    };
    let kind = match err.variant {
        pest::error::ErrorVariant::ParsingError {
            positives,
            negatives,
        } => ParseErrorKind::Syntax {
            expected: expected_words(if positives.is_empty() {
                &negatives
            } else {
                &positives
            }),
            found: found_words(map.src(), pos),
        },
        pest::error::ErrorVariant::CustomError { message } => {
            ParseErrorKind::Limit { reason: message }
        }
    };
    ParseError::new(map, kind, pos, pos + 1)
}

/// What each rule stands for in a message, in the order the words are listed; pest's
/// `renamed_rules`, with the ordering and merging it cannot do.
fn describe(rule: Rule) -> &'static str {
    match rule {
        Rule::program
        | Rule::statement
        | Rule::syms_decl
        | Rule::halfangle_decl
        | Rule::expr_statement
        | Rule::kw_syms
        | Rule::kw_halfangle => "a statement",
        Rule::name => "a name",
        Rule::add | Rule::sub | Rule::mul | Rule::div | Rule::pow | Rule::conj => "an operator",
        Rule::assign => "`=`",
        Rule::comma => "`,`",
        Rule::row_sep => "`;`",
        Rule::close_paren => "`)`",
        Rule::close_bracket => "`]`",
        Rule::separator | Rule::EOI => "the end of the statement",
        _ => "an expression",
    }
}

/// The order in which descriptions are listed.
const ORDER: [&str; 10] = [
    "a statement",
    "an expression",
    "a name",
    "an operator",
    "`=`",
    "`,`",
    "`;`",
    "`)`",
    "`]`",
    "the end of the statement",
];

/// "a, b or c" from the rules pest expected, merged and ordered. A name is an expression, so
/// "a name" is dropped when "an expression" is listed; and a statement may be an expression or
/// empty, so neither adds anything next to "a statement".
fn expected_words(rules: &[Rule]) -> String {
    let mut words: Vec<&str> = ORDER
        .iter()
        .copied()
        .filter(|w| rules.iter().any(|&r| describe(r) == *w))
        .collect();
    if words.contains(&"an expression") {
        words.retain(|w| *w != "a name");
    }
    if words.contains(&"a statement") {
        words.retain(|w| *w != "the end of the statement" && *w != "an expression");
    }
    match words.split_last() {
        None => "something else".to_owned(),
        Some((last, [])) => (*last).to_owned(),
        Some((last, init)) => format!("{} or {last}", init.join(", ")),
    }
}

/// The token at byte `pos`, in words: a whole name or number, one other character, "end of
/// line" or "end of input".
fn found_words(src: &str, pos: usize) -> String {
    let rest = &src[pos.min(src.len())..];
    let Some(c) = rest.chars().next() else {
        return "end of input".to_owned();
    };
    if c == '\n' || rest.starts_with("\r\n") {
        return "end of line".to_owned();
    }
    if c.is_control() {
        return format!("`{}`", c.escape_default());
    }
    let word_char = |c: char| c.is_alphanumeric() || c == '_';
    let token = if word_char(c) {
        let len = rest.find(|c| !word_char(c)).unwrap_or(rest.len());
        &rest[..len]
    } else {
        &rest[..c.len_utf8()]
    };
    if token.chars().count() > 20 {
        let short: String = token.chars().take(20).collect();
        format!("`{short}...`")
    } else {
        format!("`{token}`")
    }
}
