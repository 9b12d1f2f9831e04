//! Linear passes over the raw source: positions (byte offset to line and column) and the
//! bracket pre-scan that runs before pest.
//!
//! The pre-scan exists for two reasons. Deeply nested input (20,000 parentheses) must be refused
//! before any recursive code sees it, and a flat loop over bytes cannot overflow the stack.
//! And an unbalanced bracket is best reported where the bracket is ("this `(` is never
//! closed"), whereas pest would report the place where it gave up, often a line later.

use super::ast::Span;
use super::error::ParseErrorKind;

/// How many bytes apart the character-count checkpoints are. Columns are counted in
/// characters, and a checkpoint table keeps each lookup O(this) even on a 1 MB line.
const CHECKPOINT: usize = 64;

/// Byte offsets to 1-based lines and character columns, built once per parse.
pub(crate) struct SourceMap<'s> {
    src: &'s str,
    /// Byte offset at which each line starts.
    line_starts: Vec<usize>,
    /// `chars_at[k]` is the number of characters before byte `k * CHECKPOINT`.
    chars_at: Vec<usize>,
}

impl<'s> SourceMap<'s> {
    /// Indexes `src`: one pass over its bytes.
    pub(crate) fn new(src: &'s str) -> SourceMap<'s> {
        let bytes = src.as_bytes();
        let mut line_starts = vec![0];
        let mut chars_at = Vec::with_capacity(bytes.len() / CHECKPOINT + 1);
        let mut chars = 0;
        for (i, &b) in bytes.iter().enumerate() {
            if i % CHECKPOINT == 0 {
                chars_at.push(chars);
            }
            if !is_continuation(b) {
                chars += 1;
            }
            if b == b'\n' {
                line_starts.push(i + 1);
            }
        }
        chars_at.push(chars);
        SourceMap {
            src,
            line_starts,
            chars_at,
        }
    }

    /// The source text.
    pub(crate) fn src(&self) -> &'s str {
        self.src
    }

    /// Number of characters before byte `offset`.
    fn chars_before(&self, offset: usize) -> usize {
        let k = offset / CHECKPOINT;
        let from = k * CHECKPOINT;
        let extra = self.src.as_bytes()[from..offset]
            .iter()
            .filter(|&&b| !is_continuation(b))
            .count();
        self.chars_at[k] + extra
    }

    /// The 1-based line and character column of byte `offset` (clamped to the input).
    pub(crate) fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.src.len());
        let line = self.line_starts.partition_point(|&s| s <= offset);
        let start = self.line_starts[line - 1];
        (
            line,
            self.chars_before(offset) - self.chars_before(start) + 1,
        )
    }

    /// The span of bytes `start..end`.
    pub(crate) fn span(&self, start: usize, end: usize) -> Span {
        let (line, col) = self.line_col(start);
        Span {
            line,
            col,
            start,
            end,
        }
    }

    /// The text of 1-based line `line`, without its line break.
    pub(crate) fn line_text(&self, line: usize) -> &'s str {
        let start = self.line_starts[line - 1];
        let end = self
            .line_starts
            .get(line)
            .map_or(self.src.len(), |&next| next - 1);
        self.src[start..end].trim_end_matches('\r')
    }
}

/// Whether `b` continues a multi-byte UTF-8 character (and so does not start a character).
fn is_continuation(b: u8) -> bool {
    b & 0xC0 == 0x80
}

/// A problem found by the pre-scan: what, and the byte range it points at.
pub(crate) type ScanError = (ParseErrorKind, usize, usize);

/// Checks that no line is longer than `max_line_len` bytes, that brackets balance, and that
/// nesting stays within `max_depth`. Comments and `...` continuations are skipped as the
/// grammar skips them. Reports the first problem in text order; an unclosed bracket is
/// reported at the bracket.
///
/// Returns the byte ranges the grammar must read as spaces: a line break whose innermost open
/// bracket is `(` continues the expression (as in the REPL), so it is blanked together with a
/// comment before it on its line; inside `[` a line break separates matrix rows and stays.
///
/// The line limit is there because pest spends a few microseconds per token (more in debug
/// builds): a 1 MB line would take seconds, while a line at the limit parses in milliseconds.
pub(crate) fn prescan(
    map: &SourceMap<'_>,
    max_depth: usize,
    max_line_len: usize,
) -> Result<Vec<(usize, usize)>, ScanError> {
    check_line_lengths(map.src(), max_line_len)?;
    let bytes = map.src().as_bytes();
    let mut open: Vec<(u8, usize)> = Vec::new();
    let mut blanks: Vec<(usize, usize)> = Vec::new();
    // Where a comment on the current line starts.
    let mut comment: Option<usize> = None;
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'%' | b'#' => {
                comment = Some(i);
                i = skip_to_line_break(bytes, i);
                continue;
            }
            b'/' if bytes.get(i + 1) == Some(&b'/') => {
                comment = Some(i);
                i = skip_to_line_break(bytes, i);
                continue;
            }
            b'.' if bytes[i..].starts_with(b"...") => {
                // A continuation hides the rest of its line and the line break itself.
                i = skip_to_line_break(bytes, i) + 1;
                continue;
            }
            b'(' | b'[' => {
                if open.len() == max_depth {
                    return Err((ParseErrorKind::TooDeep { limit: max_depth }, i, i + 1));
                }
                open.push((bytes[i], i));
            }
            b')' | b']' => {
                let close = bytes[i];
                match open.pop() {
                    None => {
                        let kind = ParseErrorKind::Unmatched {
                            close: char::from(close),
                        };
                        return Err((kind, i, i + 1));
                    }
                    Some((o, at)) if o != opener_of(close) => {
                        let (open_line, open_col) = map.line_col(at);
                        let kind = ParseErrorKind::Mismatched {
                            open: char::from(o),
                            close: char::from(close),
                            open_line,
                            open_col,
                        };
                        return Err((kind, i, i + 1));
                    }
                    Some(_) => {}
                }
            }
            b'\n' => {
                if open.last().is_some_and(|&(o, _)| o == b'(') {
                    let mut start = comment.unwrap_or(i);
                    if comment.is_none() && i > 0 && bytes[i - 1] == b'\r' {
                        start = i - 1;
                    }
                    blanks.push((start, i + 1));
                }
                comment = None;
            }
            _ => {}
        }
        i += 1;
    }
    match open.last() {
        Some(&(o, at)) => Err((
            ParseErrorKind::Unclosed {
                open: char::from(o),
            },
            at,
            at + 1,
        )),
        None => Ok(blanks),
    }
}

/// `src` with the byte ranges of [`prescan`] as spaces (the same length, so every byte offset
/// and every line:column stays that of `src`).
pub(crate) fn blank<'s>(src: &'s str, ranges: &[(usize, usize)]) -> std::borrow::Cow<'s, str> {
    if ranges.is_empty() {
        return std::borrow::Cow::Borrowed(src);
    }
    let mut bytes = src.as_bytes().to_vec();
    for &(a, b) in ranges {
        bytes[a..b].fill(b' ');
    }
    // Whole characters were replaced by ASCII spaces.
    std::borrow::Cow::Owned(String::from_utf8(bytes).unwrap_or_else(|_| src.to_owned()))
}

/// Whether `text` is an unfinished statement that continues on the next line: a bracket is
/// still open, or the last line ends with a `...` continuation. The REPL asks this before it
/// runs a line; `dqsym run` follows the same rules (see `prescan`).
pub fn continues(text: &str) -> bool {
    let bytes = text.as_bytes();
    let mut open = 0usize;
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'%' | b'#' => i = skip_to_line_break(bytes, i),
            b'/' if bytes.get(i + 1) == Some(&b'/') => i = skip_to_line_break(bytes, i),
            b'.' if bytes[i..].starts_with(b"...") => {
                let end = skip_to_line_break(bytes, i);
                if end + 1 >= bytes.len() {
                    return true;
                }
                i = end;
            }
            b'(' | b'[' => open += 1,
            // A stray closing bracket is left for the parser to report.
            b')' | b']' => match open.checked_sub(1) {
                Some(n) => open = n,
                None => return false,
            },
            _ => {}
        }
        i += 1;
    }
    open > 0
}

/// Refuses the first line longer than `limit` bytes, pointing at the first byte past the limit.
fn check_line_lengths(src: &str, limit: usize) -> Result<(), ScanError> {
    let mut start = 0;
    for line in src.split('\n') {
        if line.len() > limit {
            let mut at = start + limit;
            while !src.is_char_boundary(at) {
                at -= 1;
            }
            return Err((ParseErrorKind::LongLine { limit }, at, at + 1));
        }
        start += line.len() + 1;
    }
    Ok(())
}

/// The opening bracket that `close` closes.
fn opener_of(close: u8) -> u8 {
    if close == b')' {
        b'('
    } else {
        b'['
    }
}

/// The index of the next `\n` at or after `i`, or the end of the input.
fn skip_to_line_break(bytes: &[u8], i: usize) -> usize {
    bytes[i..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |p| i + p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_count_characters_not_bytes() {
        let map = SourceMap::new("θ1 = 2\nx");
        assert_eq!(map.line_col(0), (1, 1));
        assert_eq!(map.line_col(2), (1, 2)); // after the two-byte θ
        assert_eq!(map.line_col(8), (2, 1));
        assert_eq!(map.line_text(1), "θ1 = 2");
    }

    #[test]
    fn columns_are_right_past_many_checkpoints() {
        let line = "θ".repeat(1000);
        let map = SourceMap::new(&line);
        assert_eq!(map.line_col(2 * 777), (1, 778));
    }

    fn check(src: &str) -> Result<Vec<(usize, usize)>, ScanError> {
        prescan(&SourceMap::new(src), 8, 100)
    }

    #[test]
    fn brackets_in_comments_are_ignored() {
        assert!(check("x = 1 % (\n[1, 2 # ]\n 3, 4]").is_ok());
        assert!(check("x = (1 + ... (\n 2)").is_ok());
    }

    #[test]
    fn long_lines_are_refused_at_the_limit() {
        let err = check(&format!("x = 1\n{}", "a".repeat(101))).unwrap_err();
        assert_eq!(err.0, ParseErrorKind::LongLine { limit: 100 });
        assert_eq!(err.1, 6 + 100);
    }

    #[test]
    fn a_line_break_in_a_paren_is_blanked_and_a_row_break_is_kept() {
        assert_eq!(check("[1, 2\n3, 4]"), Ok(vec![]));
        assert_eq!(check("x = (1 % c\r\n)"), Ok(vec![(7, 12)]));
        assert_eq!(check("x = (1\r\n)"), Ok(vec![(6, 8)]));
        assert_eq!(check("f([1\n2])"), Ok(vec![]));
        let src = "x = (1 + # note\n 2)";
        let ranges = check(src).unwrap();
        assert_eq!(
            blank(src, &ranges),
            format!("x = (1 + {} 2)", " ".repeat(7))
        );
    }

    #[test]
    fn continuation_follows_brackets_and_dots() {
        assert!(continues("x = (1 +\n"));
        assert!(continues("m = [1, 2\n"));
        assert!(continues("x = 1 + ...\n"));
        assert!(!continues("x = (1 + 2) % (\n"));
        assert!(!continues("x = 1)\n"));
        assert!(!continues("x = 1\n"));
    }
}
