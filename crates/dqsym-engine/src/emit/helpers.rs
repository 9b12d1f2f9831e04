//! The runtime helpers of generated IK solvers (`runtime/ik_helpers.*`) as data: each helper
//! is declared in its file by a marker line before its text, `//@ name: users` (`#@` in
//! Python), where `users` are the kinds of step whose roots it computes (`atan2`, `trig`,
//! `quadratic`, `linear`, several separated by spaces) or `always`. A solver keeps the helpers its steps
//! use, decided from its formulas; nothing here or in the writers reads the helpers' code.

use std::sync::OnceLock;

use super::names::Lang;

/// The kind of step whose roots a helper computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepKind {
    /// `atan2(y, x)`, remembered between calls.
    Atan2,
    /// `a cos q + b sin q = c`.
    Trig,
    /// `q^2 + 2 beta q + gamma = 0`.
    Quadratic,
    /// `a q = b`.
    Linear,
}

impl StepKind {
    fn parse(word: &str) -> Option<StepKind> {
        match word {
            "atan2" => Some(StepKind::Atan2),
            "trig" => Some(StepKind::Trig),
            "quadratic" => Some(StepKind::Quadratic),
            "linear" => Some(StepKind::Linear),
            _ => None,
        }
    }

    /// The runtime helper computing the roots of this kind of step (before the language's
    /// prefix, see [`super::syntax::SolverSyntax::helper`]).
    pub fn helper(self) -> &'static str {
        match self {
            StepKind::Atan2 => "ik_atan2",
            StepKind::Trig => "ik_trig",
            StepKind::Quadratic => "ik_quadratic",
            StepKind::Linear => "ik_linear",
        }
    }
}

/// One runtime helper: its name, the steps that use it (none: every solver) and its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Helper {
    /// The name it defines (a function, a type with its methods).
    pub name: &'static str,
    /// The kinds of step that use it; empty when every solver does.
    pub users: Vec<StepKind>,
    /// Its source text, without the marker, without blank lines around it.
    pub text: &'static str,
}

impl Helper {
    /// Whether a solver whose steps are of the kinds `kinds` uses it.
    pub fn used_by(&self, kinds: &[StepKind]) -> bool {
        self.users.is_empty() || self.users.iter().any(|u| kinds.contains(u))
    }
}

/// A runtime file whose markers do not read (a defect of the file, found by the tests).
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[non_exhaustive]
pub enum HelperFileError {
    /// Text before the first marker.
    #[error("text before the first helper marker")]
    Unmarked,
    /// A marker without `name: users`.
    #[error("helper marker `{0}` is not `name: users`")]
    Marker(String),
    /// A user that is not a kind of step.
    #[error("helper `{name}`: `{word}` is not atan2, trig, quadratic, linear or always")]
    User { name: String, word: String },
}

/// The marker prefix of `lang`'s runtime file.
fn marker(lang: Lang) -> &'static str {
    match lang {
        Lang::Python => "#@ ",
        _ => "//@ ",
    }
}

/// The helpers declared in `text`, a runtime file of `lang`, in file order.
///
/// # Errors
/// A marker that does not read, or text before the first marker.
pub fn parse(lang: Lang, text: &'static str) -> Result<Vec<Helper>, HelperFileError> {
    let mark = marker(lang);
    let mut out = Vec::new();
    let mut rest = text;
    let at_marker = |s: &str| s.starts_with(mark);
    if !at_marker(rest) {
        return Err(HelperFileError::Unmarked);
    }
    while let Some(body) = rest.strip_prefix(mark) {
        let (line, after) = body.split_once('\n').unwrap_or((body, ""));
        let (name, users) = line
            .split_once(": ")
            .ok_or_else(|| HelperFileError::Marker(line.to_string()))?;
        let users = match users.trim() {
            "always" => Vec::new(),
            words => words
                .split(' ')
                .map(|w| {
                    StepKind::parse(w).ok_or_else(|| HelperFileError::User {
                        name: name.to_string(),
                        word: w.to_string(),
                    })
                })
                .collect::<Result<_, _>>()?,
        };
        // The helper's text runs to the next marker at the start of a line.
        let end = after
            .match_indices(&format!("\n{mark}"))
            .next()
            .map_or(after.len(), |(i, _)| i + 1);
        out.push(Helper {
            name,
            users,
            text: after[..end].trim_matches('\n'),
        });
        rest = &after[end..];
    }
    Ok(out)
}

/// The runtime file of `lang` (JavaScript: the IK page's helpers; SymPy has none).
pub fn runtime_text(lang: Lang) -> &'static str {
    match lang {
        Lang::Rust => include_str!("runtime/ik_helpers.rs"),
        Lang::C => include_str!("runtime/ik_helpers.c"),
        Lang::Python => include_str!("runtime/ik_helpers.py"),
        Lang::JavaScript => include_str!("runtime/ik_helpers.js"),
        Lang::Sympy => "",
    }
}

/// The runtime helpers of `lang`, read once from its file (compiled in: the unit tests below
/// read every file, so a marker that does not read never reaches a user).
pub fn runtime(lang: Lang) -> &'static [Helper] {
    static CELLS: [OnceLock<Vec<Helper>>; 4] = [
        OnceLock::new(),
        OnceLock::new(),
        OnceLock::new(),
        OnceLock::new(),
    ];
    let i = match lang {
        Lang::Rust => 0,
        Lang::C => 1,
        Lang::Python => 2,
        Lang::JavaScript => 3,
        Lang::Sympy => return &[],
    };
    CELLS[i].get_or_init(|| {
        parse(lang, runtime_text(lang)).expect("the runtime files' markers read (unit tested)")
    })
}

/// The helper `name` of `lang`'s runtime.
pub(crate) fn helper(lang: Lang, name: &str) -> Option<&'static Helper> {
    runtime(lang).iter().find(|h| h.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    const LANGS: [Lang; 4] = [Lang::Rust, Lang::C, Lang::Python, Lang::JavaScript];

    /// Every identifier of `text` (letters, digits, `_`).
    fn words(text: &str) -> Vec<&str> {
        text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .filter(|w| !w.is_empty())
            .collect()
    }

    /// Every runtime file reads, loses no line to its markers and names in each marker what
    /// its text defines.
    #[test]
    fn every_runtime_file_declares_its_helpers() {
        for lang in LANGS {
            let text = runtime_text(lang);
            let helpers = parse(lang, text).unwrap_or_else(|e| panic!("{lang:?}: {e}"));
            assert!(helpers.len() >= 8, "{lang:?}: {}", helpers.len());
            let code = |t: &str| -> Vec<String> {
                t.lines()
                    .filter(|l| !l.trim().is_empty() && !l.starts_with(marker(lang)))
                    .map(str::to_string)
                    .collect()
            };
            let kept: Vec<String> = helpers.iter().flat_map(|h| code(h.text)).collect();
            assert_eq!(kept, code(text), "{lang:?}: lines outside every helper");
            for h in &helpers {
                assert!(words(h.text).contains(&h.name), "{lang:?}: {}", h.name);
            }
        }
        assert_eq!(
            parse(Lang::Rust, "fn f() {}\n"),
            Err(HelperFileError::Unmarked)
        );
        assert!(matches!(
            parse(Lang::Rust, "//@ f: sometimes\nfn f() {}\n"),
            Err(HelperFileError::User { .. })
        ));
    }

    /// For every set of step kinds, the helpers kept for it define every helper name they use
    /// (no kept helper calls a dropped one), and the helper of each kind is kept.
    #[test]
    fn kept_helpers_never_call_a_dropped_one() {
        use StepKind::{Atan2, Linear, Quadratic, Trig};
        let all = [Atan2, Trig, Quadratic, Linear];
        for lang in [Lang::Rust, Lang::C, Lang::Python] {
            let helpers = runtime(lang);
            let names: Vec<&str> = helpers.iter().map(|h| h.name).collect();
            for mask in 0..16usize {
                let kinds: Vec<StepKind> = (0..4)
                    .filter(|i| mask >> i & 1 == 1)
                    .map(|i| all[i])
                    .collect();
                let kept: Vec<&Helper> = helpers.iter().filter(|h| h.used_by(&kinds)).collect();
                let defined: Vec<&str> = kept.iter().map(|h| h.name).collect();
                for h in &kept {
                    for w in words(h.text) {
                        assert!(
                            !names.contains(&w) || defined.contains(&w),
                            "{lang:?} {kinds:?}: {} uses {w}, dropped",
                            h.name
                        );
                    }
                }
                for k in &kinds {
                    let want = match lang {
                        Lang::Python => format!("_{}", k.helper()),
                        _ => k.helper().to_string(),
                    };
                    assert!(defined.contains(&want.as_str()), "{lang:?}: {want}");
                }
            }
        }
    }
}
