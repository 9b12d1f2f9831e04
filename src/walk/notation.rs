//! One notation per walkthrough page: the cosine and sine of a half angle inside the factors
//! are `c1 = cos(theta1/2)`, `s12 = sin((theta1 + theta2)/2)` (lower case); those of a full
//! angle in the results are `C1 = cos(theta1)`, `S123 = sin(theta1 + theta2 + theta3)` (upper
//! case). Any other angle is written out. A name that is also a symbol of the page is never
//! used as a shorthand, so no name means two things.
//!
//! The renderers print through [`Names`], which records every shorthand it hands out; the
//! legend at the top of the page lists exactly those.

use super::{Step, Walkthrough};
use crate::{
    closed::shorthand_name,
    emit::{latex_shorthand, latex_symbol},
    Angle, Scalar, Trig, Value,
};
use num_traits::Zero;
use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};

/// A shorthand handed out: its text and LaTeX forms, and what it stands for in both.
#[derive(Clone, Debug)]
struct Entry {
    plain: String,
    tex: String,
    plain_meaning: String,
    tex_meaning: String,
}

/// The notation of one page.
#[derive(Debug, Default)]
pub(crate) struct Names {
    /// The symbols of the page: never reused as shorthand names.
    taken: BTreeSet<String>,
    /// Shorthands used, by (full angle?, number of symbols, index, plain name): c1, s1, c2, ...
    used: RefCell<BTreeMap<(bool, usize, String, String), Entry>>,
}

/// Every scalar of a value.
pub(crate) fn scalars(v: &Value) -> Vec<&Scalar> {
    match v {
        Value::Scalar(s) => vec![s],
        Value::Quat(q) => vec![&q.w, &q.x, &q.y, &q.z],
        Value::Vector(x) => x.iter().collect(),
        Value::DualQuat(d) => vec![
            &d.real.w, &d.real.x, &d.real.y, &d.real.z, &d.dual.w, &d.dual.x, &d.dual.y, &d.dual.z,
        ],
        Value::Matrix(rows) => rows.iter().flatten().collect(),
        Value::QuotientMatrix(rows) => rows
            .iter()
            .flatten()
            .flat_map(|f| [f.num(), f.den()])
            .collect(),
    }
}

impl Names {
    /// The notation for `w`: every symbol of its values is taken.
    pub(crate) fn for_walk(w: &Walkthrough) -> Names {
        let mut taken = BTreeSet::new();
        let mut add = |v: &Value| {
            for s in scalars(v) {
                taken.extend(s.symbols().into_iter().map(|x| x.name().to_owned()));
            }
        };
        for step in &w.steps {
            match step {
                Step::Factor { value, .. }
                | Step::Define { value, .. }
                | Step::Product { value, .. }
                | Step::Transform { value, .. }
                | Step::Result { value, .. } => add(value),
                Step::Notation { .. }
                | Step::Check { .. }
                | Step::Explain { .. }
                | Step::Legend(_)
                | Step::Solutions { .. } => {}
            }
        }
        Names {
            taken,
            used: RefCell::default(),
        }
    }

    /// The shorthand of cos or sin of `a`, recorded for the legend: `(plain, tex)`.
    fn name(&self, f: Trig, a: &Angle) -> Option<(String, String)> {
        if !a.pi.is_zero() || !a.constant.is_zero() || a.terms.is_empty() {
            return None;
        }
        let half = num_rational::Ratio::new(1, 2);
        let full = a.is_plain_sum();
        let is_half = a.terms.iter().all(|(_, k)| *k == half);
        if !full && !is_half {
            return None;
        }
        let whole = Angle::new(
            a.terms
                .iter()
                .map(|(s, _)| (s.clone(), num_rational::Ratio::from_integer(1)))
                .collect(),
            a.constant,
            a.pi,
        );
        let short = shorthand_name(f, &whole)?;
        let (_, rest) = short.split_at(1);
        let letter = match (f, full) {
            (Trig::Cos, false) => "c",
            (Trig::Sin, false) => "s",
            (Trig::Cos, true) => "C",
            (Trig::Sin, true) => "S",
        };
        let plain = format!("{letter}{rest}");
        if self.taken.contains(&plain) {
            return None;
        }
        let tex = latex_shorthand(letter, rest);
        let f = f.name();
        let names: Vec<&str> = whole.terms.iter().map(|(s, _)| s.name()).collect();
        let tex_names: Vec<String> = names.iter().map(|n| latex_symbol(n)).collect();
        let (plain_meaning, tex_meaning) = match (full, names.len()) {
            // `\cos q_{1}`, never `\cosq_{1}`: a space ends the command before a letter
            // (`\cos\theta_{1}` needs none).
            (true, 1) => (
                format!("{f}({})", names[0]),
                if tex_names[0].starts_with('\\') {
                    format!("\\{f}{}", tex_names[0])
                } else {
                    format!("\\{f} {}", tex_names[0])
                },
            ),
            (true, _) => (
                format!("{f}({})", names.join(" + ")),
                format!("\\{f}({})", tex_names.join(" + ")),
            ),
            (false, 1) => (
                format!("{f}({}/2)", names[0]),
                format!("\\{f}\\frac{{{}}}{{2}}", tex_names[0]),
            ),
            (false, _) => (
                format!("{f}(({})/2)", names.join(" + ")),
                format!("\\{f}\\frac{{{}}}{{2}}", tex_names.join(" + ")),
            ),
        };
        self.used.borrow_mut().insert(
            (full, names.len(), rest.to_owned(), plain.clone()),
            Entry {
                plain: plain.clone(),
                tex: tex.clone(),
                plain_meaning,
                tex_meaning,
            },
        );
        Some((plain, tex))
    }

    /// The plain-text name of cos or sin of `a`, if it has one.
    pub(crate) fn plain(&self, f: Trig, a: &Angle) -> Option<String> {
        self.name(f, a).map(|(p, _)| p)
    }

    /// The LaTeX name of cos or sin of `a`, if it has one.
    pub(crate) fn tex(&self, f: Trig, a: &Angle) -> Option<String> {
        self.name(f, a).map(|(_, t)| t)
    }

    /// The names handed out so far, half angles first, as `(plain, meaning, tex, tex meaning,
    /// full angle?)`.
    fn entries(&self) -> Vec<(Entry, bool)> {
        self.used
            .borrow()
            .iter()
            .map(|((full, ..), e)| (e.clone(), *full))
            .collect()
    }

    /// The legend as plain-text lines (empty when no shorthand was used).
    pub(crate) fn legend_plain(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (full, what) in [
            (false, "half angles, inside the factors"),
            (true, "full angles, in the results"),
        ] {
            let items: Vec<String> = self
                .entries()
                .into_iter()
                .filter(|(_, f)| *f == full)
                .map(|(e, _)| format!("{} = {}", e.plain, e.plain_meaning))
                .collect();
            if !items.is_empty() {
                out.push(format!("{what}: {}", items.join(", ")));
            }
        }
        out
    }

    /// The legend as Markdown text with inline math (empty when no shorthand was used).
    pub(crate) fn legend_tex(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (full, what) in [
            (false, "Half angles, inside the factors"),
            (true, "Full angles, in the results"),
        ] {
            let items: Vec<String> = self
                .entries()
                .into_iter()
                .filter(|(_, f)| *f == full)
                .map(|(e, _)| format!("${} = {}$", e.tex, e.tex_meaning))
                .collect();
            if !items.is_empty() {
                out.push(format!("{what}: {}.", items.join(", ")));
            }
        }
        out
    }
}
