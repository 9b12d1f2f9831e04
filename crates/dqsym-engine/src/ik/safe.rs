//! The solver code's names: a robot parameter or joint variable that the target language
//! reserves, or that the solver code writes itself, is renamed before the code is written.
//!
//! The rule is the emitters' ([`crate::emit::names`]): `_` appended (`int` -> `int_`, `fn`
//! -> `fn_`, `lambda` -> `lambda_`) until the name is free. Besides each language's table, the
//! solver's own names are taken: every name starting with `ik` or `IK` (its helpers, types,
//! locals and macros), the locals `s_q`, `c_q` of each joint `q`, and in Python the arguments
//! `T` and `q`. The parameters keep their order, so positional calls are unchanged.

use super::{Formula, IkSolution};
use crate::emit::names::{safe_names, Lang};
use crate::Scalar;
use std::borrow::Cow;

/// `sol` with its parameters and joint variables renamed for `lang` (borrowed when no name
/// changes).
pub(super) fn solution(sol: &IkSolution, lang: Lang) -> Cow<'_, IkSolution> {
    let mut user: Vec<String> = sol
        .params
        .iter()
        .chain(&sol.variables)
        .chain(sol.steps.iter().map(|s| &s.variable))
        .chain(&sol.free)
        .cloned()
        .collect();
    user.sort();
    user.dedup();
    let own = |n: &str| {
        n.get(..2).is_some_and(|p| p.eq_ignore_ascii_case("ik"))
            || (lang == Lang::Python && matches!(n, "T" | "q"))
            || ["s_", "c_"].iter().any(|p| {
                n.strip_prefix(p)
                    .is_some_and(|v| sol.variables.iter().any(|x| x == v))
            })
    };
    let fixed: Vec<&str> = user.iter().map(String::as_str).filter(|n| own(n)).collect();
    let safe = safe_names(lang, &user, &fixed);
    let map: Vec<(&String, &String)> = user.iter().zip(&safe).filter(|(a, b)| a != b).collect();
    if map.is_empty() {
        return Cow::Borrowed(sol);
    }
    let name = |n: &String| {
        map.iter()
            .find(|(a, _)| *a == n)
            .map_or_else(|| n.clone(), |(_, b)| (*b).clone())
    };
    let subs = |x: &Scalar| {
        map.iter()
            .fold(x.clone(), |acc, (a, b)| acc.subs(a, &Scalar::sym(b)))
    };
    let mut out = sol.clone();
    out.forms = std::sync::OnceLock::new();
    out.params = sol.params.iter().map(name).collect();
    out.variables = sol.variables.iter().map(name).collect();
    out.free = sol.free.as_ref().map(name);
    for step in &mut out.steps {
        step.variable = name(&step.variable);
        step.formula = match &step.formula {
            Formula::Atan2 { y, x } => Formula::Atan2 {
                y: subs(y),
                x: subs(x),
            },
            Formula::Trig { a, b, c } => Formula::Trig {
                a: subs(a),
                b: subs(b),
                c: subs(c),
            },
            Formula::Value { v } => Formula::Value { v: subs(v) },
            Formula::Linear { a, b } => Formula::Linear {
                a: subs(a),
                b: subs(b),
            },
            Formula::Quadratic { beta, gamma } => Formula::Quadratic {
                beta: subs(beta),
                gamma: subs(gamma),
            },
        };
    }
    for row in out.home.rows.iter_mut() {
        for x in row.iter_mut() {
            *x = subs(x);
        }
    }
    // The axes the solver checks its solutions with are written with the same names.
    for a in &mut out.axes {
        a.variable = name(&a.variable);
        for v in [&mut a.dir, &mut a.point, &mut a.moment] {
            for x in v.iter_mut() {
                *x = subs(x);
            }
        }
    }
    Cow::Owned(out)
}
