//! The derivation as text: plain (the field's `c1`, `s23` notation), LaTeX, SymPy lines.

use super::general::exact::ExactError;
use super::{
    Branch, BranchPart, BranchSigns, EndFrame, Fact, Formula, FreeChoice, IkSolution, IkStep,
    Phrase, Reach, Relation,
};
use crate::closed::Expr;
use crate::emit::names::{line_comment, Comment};
use crate::emit::{latex, latex_symbol, sympy, LatexOptions};
use crate::kin::JointKind;
use crate::print::{plain, Format, PlainOptions};
use crate::{closed_form, Scalar, ScalarError};

/// The named parts of a formula (`a`, `b`, `c`; `y`, `x`; `v`; `beta`, `gamma`), each in
/// closed form.
pub(crate) fn parts(f: &Formula) -> Result<Vec<(&'static str, Expr)>, ScalarError> {
    let named: Vec<(&'static str, &Scalar)> = match f {
        Formula::Atan2 { y, x } => vec![("y", y), ("x", x)],
        Formula::Trig { a, b, c } => vec![("a", a), ("b", b), ("c", c)],
        Formula::Value { v } => vec![("v", v)],
        Formula::Linear { a, b } => vec![("a", a), ("b", b)],
        Formula::Quadratic { beta, gamma } => vec![("beta", beta), ("gamma", gamma)],
    };
    let forms = crate::scalar::par_map(&named, |(_, s)| best_form(s));
    named
        .iter()
        .zip(forms)
        .map(|((n, _), e)| Ok((*n, e?)))
        .collect()
}

/// The closed form of a scalar, or the closed form of its cos/sin polynomial when that is
/// cheaper (squares of `px c1 + py s1` read better than double angles).
fn best_form(s: &Scalar) -> Result<Expr, ScalarError> {
    let e = closed_form(s)?;
    let alt = s
        .to_cos_sin_polynomial()
        .and_then(|p| crate::closed::closed_form_cos_sin(&p).ok());
    Ok(match alt {
        Some(a) if a.cost() < e.cost() => a,
        _ => e,
    })
}

/// The closed form of a step's joint, in plain text over its part names.
fn solution_text(step: &IkStep) -> String {
    let q = &step.variable;
    match &step.formula {
        Formula::Atan2 { .. } => format!("{q} = atan2(y, x)"),
        Formula::Trig { .. } => {
            format!("{q} = atan2(b, a) ± atan2(sqrt(a^2 + b^2 - c^2), c)")
        }
        Formula::Value { .. } => format!("{q} = v"),
        Formula::Linear { .. } => format!("{q} = b / a"),
        Formula::Quadratic { .. } => format!("{q} = -beta ± sqrt(beta^2 - gamma)"),
    }
}

fn equation_text(step: &IkStep) -> Option<String> {
    let q = &step.variable;
    match &step.formula {
        Formula::Trig { .. } => Some(format!("a cos({q}) + b sin({q}) = c")),
        Formula::Quadratic { .. } => Some(format!("{q}^2 + 2 beta {q} + gamma = 0")),
        Formula::Linear { .. } => Some(format!("a {q} = b")),
        _ => None,
    }
}

fn branch_count(sol: &IkSolution) -> usize {
    sol.steps.iter().map(|s| s.formula.branches()).product()
}

impl std::fmt::Display for Phrase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.reversed {
            f.write_str("chain reversed: ")?;
        }
        let mut rest = self.template;
        while let Some(i) = rest.find('{') {
            f.write_str(&rest[..i])?;
            let j = i + rest[i..].find('}').unwrap_or(rest.len() - i);
            match &rest[i + 1..j] {
                "v" => f.write_str(&self.value.as_ref().map(scalar_text).unwrap_or_default())?,
                "p" => {
                    if let Some(p) = &self.inner {
                        write!(f, "{p}")?;
                    }
                }
                k => {
                    let a = k.parse::<usize>().ok().and_then(|k| self.axes.get(k));
                    match a {
                        Some(a) => write!(f, "{a}")?,
                        None => f.write_str(&rest[i..=j.min(rest.len() - 1)])?,
                    }
                }
            }
            rest = rest.get(j + 1..).unwrap_or("");
        }
        f.write_str(rest)
    }
}

fn rel_text(rel: &Relation) -> String {
    match rel {
        Relation::Parallel { same_line: true } => "coincide".into(),
        Relation::Parallel { .. } => "are parallel".into(),
        Relation::Intersecting => "intersect".into(),
        Relation::Skew => "are skew (neither parallel nor intersecting)".into(),
        Relation::SkewUnless(r) => format!(
            "are skew unless {} = 0 (their reciprocal product)",
            scalar_text(r)
        ),
    }
}

impl std::fmt::Display for Fact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Fact::Joints(kinds) => {
                let k: String = kinds
                    .iter()
                    .map(|k| match k {
                        JointKind::Revolute => 'R',
                        JointKind::Prismatic => 'P',
                    })
                    .collect();
                write!(f, "joints: {k} ({})", kinds.len())
            }
            Fact::Pair {
                axes: [i, j],
                relation,
            } => {
                write!(f, "axes {i} and {j} {}", rel_text(relation))
            }
            Fact::Directions {
                axes: [i, j],
                parallel,
            } => {
                let p = if *parallel {
                    "parallel"
                } else {
                    "not parallel"
                };
                write!(f, "axes {i} and {j}: directions {p}")
            }
            Fact::SphericalWrist {
                axes: [a, b, c],
                yes,
            } => {
                let y = if *yes { "yes" } else { "no" };
                write!(
                    f,
                    "axes {a}, {b}, {c} through one point (spherical wrist): {y}"
                )
            }
            Fact::Numbering(vars) => {
                let v: Vec<String> = vars
                    .iter()
                    .enumerate()
                    .map(|(i, v)| format!("{} = {v}", i + 1))
                    .collect();
                write!(f, "axes numbered without the free joint: {}", v.join(", "))
            }
            Fact::FreeChosen { variable, which } => {
                let why = match which {
                    FreeChoice::First => "the first joint whose value leaves a supported family",
                    FreeChoice::Last => {
                        "the last joint: the first joint's value leaves no supported family, the \
                         last joint's does (an end joint is preferred)"
                    }
                    FreeChoice::Inner => {
                        "the first inner joint whose value leaves a supported family (neither end \
                         joint's does)"
                    }
                };
                write!(
                    f,
                    "7 joints, no --free given: {variable} chosen as the free joint (a \
                     parameter), {why}"
                )
            }
        }
    }
}

impl Branch {
    /// The branch's name and the names of its `+` and `−` signs.
    pub fn words(&self) -> (&'static str, &'static str, &'static str) {
        let name = match self.part {
            BranchPart::Shoulder => "shoulder",
            BranchPart::Elbow => "elbow",
            BranchPart::Wrist => "wrist",
            BranchPart::Reach => "reach",
        };
        let (p, m) = match self.signs {
            BranchSigns::LeftRight => ("left", "right"),
            BranchSigns::UpDown => ("up", "down"),
            BranchSigns::NoFlipFlip => ("no flip", "flip"),
            BranchSigns::FarNear => ("far", "near"),
        };
        (name, p, m)
    }
}

/// The parts of the end frame, base first: `[base] frame, the joints, ...`.
fn end_text(end: &EndFrame) -> String {
    let frames = |n: usize, what: &str| match n {
        0 => None,
        1 => Some(format!("1 constant frame {what}")),
        n => Some(format!("{n} constant frames {what}")),
    };
    let point = end.tool_point.as_ref().map(|p| {
        let text: Vec<String> = p.iter().map(scalar_text).collect();
        format!(
            "the tool point ({}) of the last frame, with its axes",
            text.join(", ")
        )
    });
    [
        frames(end.base_frames, "before the first joint"),
        Some("the joints".to_string()),
        frames(end.tool_frames, "after the last joint"),
        point,
    ]
    .into_iter()
    .flatten()
    .collect::<Vec<_>>()
    .join(", then ")
}

/// A scalar in closed form, plain text.
fn scalar_text(x: &Scalar) -> String {
    closed_form(x)
        .map(|e| plain(&e, &PlainOptions::default()))
        .unwrap_or_else(|_| x.to_string())
}

fn header(sol: &IkSolution) -> Vec<String> {
    let mut out = vec![
        format!("Inverse kinematics of {}", sol.robot),
        format!("family: {}", sol.family),
    ];
    out.push("geometry (decided exactly on the home-pose axes):".into());
    out.extend(sol.geometry.iter().map(|g| format!("  {g}")));
    out.push(if sol.position_only {
        "target: the position (px, py, pz) of the end effector".into()
    } else {
        "target: T = [r11 r12 r13 px; r21 r22 r23 py; r31 r32 r33 pz; 0 0 0 1]".into()
    });
    match &sol.reach {
        Reach::PositionAndAngle { axes } => out.push(format!(
            "reachable: the position (px, py, pz) and one angle, the turn about the parallel \
             axes {} (the target's orientation must be Rot(axis 1, theta1) Rot(axis 2, phi), \
             theta1 read from it)",
            axes.iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        )),
        Reach::PositionAndApproach { approach } => out.push(format!(
            "reachable: the position (px, py, pz) and the approach axis, the end frame's \
             direction ({}) (R times it); the turn about it is not controlled",
            approach
                .iter()
                .map(scalar_text)
                .collect::<Vec<_>>()
                .join(", ")
        )),
        _ => {}
    }
    if !sol.end.is_plain() {
        out.push(format!(
            "end frame (the end fk reports): {}",
            end_text(&sol.end)
        ));
    }
    if let Some(f) = &sol.free {
        out.push(format!("free joint (a parameter): {f}"));
    }
    out.push(format!(
        "parameters: {}",
        if sol.params.is_empty() {
            "none".into()
        } else {
            sol.params.join(", ")
        }
    ));
    if let Some(info) = &sol.general {
        out.push(format!(
            "solutions: at most {0} isolated (the real roots of one polynomial of degree {0}), all at once",
            info.degree
        ));
        return out;
    }
    let names: Vec<String> = sol
        .steps
        .iter()
        .filter_map(|s| s.branch.as_ref().map(|b| b.words().0.to_string()))
        .collect();
    out.push(format!(
        "branches: {}{}",
        branch_count(sol),
        if names.is_empty() {
            String::new()
        } else {
            format!(" ({})", names.join(" x "))
        }
    ));
    out.push(format!(
        "solved in the order: {}",
        sol.steps
            .iter()
            .map(|s| s.variable.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    ));
    out
}

/// The derivation as text: plain (`shorthand` writes `c1`, `s23`), LaTeX (an `aligned` block
/// per joint; `shorthand` writes `c_{1}`), or `NAME = EXPR` lines SymPy's `sympify` reads (one
/// sign symbol `sign_q` per branch); for Rust, C and Python the solver ([`super::ik_rust`],
/// [`super::ik_c`], [`super::ik_python`]).
///
/// # Errors
/// A closed form that fails (term limit, work budget).
pub fn ik_report(sol: &IkSolution, format: Format, shorthand: bool) -> Result<String, ScalarError> {
    match format {
        Format::Rust => return super::ik_rust(sol),
        Format::C => return super::ik_c(sol),
        Format::Python => return super::ik_python(sol),
        _ => {}
    }
    let all = sol.forms()?;
    let mut out = String::new();
    match format {
        Format::Plain => {
            let o = PlainOptions {
                shorthand,
                decimals: false,
            };
            for l in header(sol) {
                out.push_str(&crate::emit::names::printable(&l));
                out.push('\n');
            }
            if let Some(info) = &sol.general {
                out.push_str("\nelimination\n");
                for l in super::general::elimination_lines(sol, info) {
                    out.push_str(&format!("  {}\n", crate::emit::names::printable(&l)));
                }
                out.push_str(&general_plain(sol, info, &o)?);
            }
            for (step, parts) in sol.steps.iter().zip(all) {
                out.push('\n');
                out.push_str(&step.variable);
                if let Some((n, p, m)) = step.branch.as_ref().map(Branch::words) {
                    out.push_str(&format!(" ({n}: + {p}, - {m})"));
                }
                out.push('\n');
                out.push_str(&format!("  {}\n", step.method));
                if let Some(e) = equation_text(step) {
                    out.push_str(&format!("  {e}\n"));
                }
                for (n, e) in parts {
                    out.push_str(&format!("    {n} = {}\n", plain(e, &o)));
                }
                out.push_str(&format!("  {}\n", solution_text(step)));
                if matches!(
                    step.formula,
                    Formula::Trig { .. } | Formula::Quadratic { .. }
                ) {
                    out.push_str("  exists where the radicand is >= 0 (else out of reach)\n");
                }
                out.push_str(&format!("  singular: {}\n", step.singular));
            }
            if shorthand {
                let refs: Vec<&Expr> = all.iter().flatten().map(|(_, e)| e).collect();
                let leg = crate::print::legend(&refs);
                if !leg.is_empty() {
                    out.push('\n');
                    for l in leg {
                        out.push_str(&l);
                        out.push('\n');
                    }
                }
            }
        }
        Format::Latex => {
            let o = LatexOptions {
                shorthand,
                ..LatexOptions::default()
            };
            for l in header(sol) {
                out.push_str(&line_comment(Comment::Latex, "%", &l));
            }
            if let Some(info) = &sol.general {
                for l in super::general::elimination_lines(sol, info) {
                    out.push_str(&line_comment(Comment::Latex, "%", &l));
                }
                out.push_str(&general_latex(sol, info));
                out.push_str(&general_exact_latex(sol, info, shorthand)?);
            }
            for (step, parts) in sol.steps.iter().zip(all) {
                let q = latex_symbol(&step.variable);
                out.push_str(&format!("% {}\n", step.method));
                out.push_str("\\begin{aligned}\n");
                for (n, e) in parts {
                    let n = match *n {
                        "beta" => "\\beta".to_string(),
                        "gamma" => "\\gamma".to_string(),
                        n => n.to_string(),
                    };
                    out.push_str(&format!("{n}_{{{q}}} &= {} \\\\\n", latex(e, &o)));
                }
                let sub = |n: &str| format!("{n}_{{{q}}}");
                let line = match &step.formula {
                    Formula::Atan2 { .. } => {
                        format!("{q} &= \\operatorname{{atan2}}({}, {})", sub("y"), sub("x"))
                    }
                    Formula::Trig { .. } => format!(
                        "{q} &= \\operatorname{{atan2}}({b}, {a}) \\pm \\operatorname{{atan2}}\\left(\\sqrt{{{a}^2 + {b}^2 - {c}^2}}, {c}\\right)",
                        a = sub("a"),
                        b = sub("b"),
                        c = sub("c")
                    ),
                    Formula::Value { .. } => format!("{q} &= {}", sub("v")),
                    Formula::Linear { .. } => {
                        format!("{q} &= \\frac{{{}}}{{{}}}", sub("b"), sub("a"))
                    }
                    Formula::Quadratic { .. } => format!(
                        "{q} &= -{b} \\pm \\sqrt{{{b}^2 - {g}}}",
                        b = sub("\\beta"),
                        g = sub("\\gamma")
                    ),
                };
                out.push_str(&line);
                out.push_str("\n\\end{aligned}\n");
            }
        }
        _ => {
            for l in header(sol) {
                out.push_str(&line_comment(Comment::Hash, "#", &l));
            }
            if let Some(info) = &sol.general {
                for l in super::general::elimination_lines(sol, info) {
                    out.push_str(&line_comment(Comment::Hash, "#", &l));
                }
            }
            for (step, parts) in sol.steps.iter().zip(all) {
                let q = &step.variable;
                out.push_str(&format!("# {}\n", step.method));
                for (n, e) in parts {
                    out.push_str(&format!("{q}_{n} = {}\n", sympy(e)));
                }
                let line = match &step.formula {
                    Formula::Atan2 { .. } => format!("{q} = atan2({q}_y, {q}_x)"),
                    Formula::Trig { .. } => format!(
                        "{q} = atan2({q}_b, {q}_a) + sign_{q}*atan2(sqrt({q}_a**2 + {q}_b**2 - {q}_c**2), {q}_c)"
                    ),
                    Formula::Value { .. } => format!("{q} = {q}_v"),
                    Formula::Linear { .. } => format!("{q} = {q}_b/{q}_a"),
                    Formula::Quadratic { .. } => {
                        format!("{q} = -{q}_beta + sign_{q}*sqrt({q}_beta**2 - {q}_gamma)")
                    }
                };
                out.push_str(&line);
                out.push('\n');
            }
        }
    }
    Ok(out)
}

/// The exact equations of the general method in plain text (`ik::general::exact`).
fn general_plain(
    sol: &IkSolution,
    info: &super::general::GeneralInfo,
    o: &PlainOptions,
) -> Result<String, ScalarError> {
    let shown = super::general::exact::exact_equations(sol, info).and_then(|eq| {
        Ok::<_, ExactError>((super::general::exact_scope_text(sol, &eq), eq.shown(sol)?))
    });
    let (scope, groups) = match shown {
        Ok(x) => x,
        // Past the term limit or the work budget (a symbolic arm with symbolic twists), the
        // rest of the report still stands; an interruption stops it.
        Err(ExactError::Scalar(ScalarError::Cancelled)) => return Err(ScalarError::Cancelled),
        Err(e) => return Ok(format!("\nexact equations: not printed ({e})\n")),
    };
    let mut out =
        format!("\nexact equations (Bm X12 = Am X45, every coefficient exact; {scope})\n");
    for g in groups {
        out.push_str(&format!("  {}\n", g.title));
        for s in &g.items {
            out.push_str(&format!("    {} = {}\n", s.label, plain(&s.expr, o)));
        }
    }
    Ok(out)
}

/// The exact equations as LaTeX: one `aligned` block per group, its title a comment.
fn general_exact_latex(
    sol: &IkSolution,
    info: &super::general::GeneralInfo,
    shorthand: bool,
) -> Result<String, ScalarError> {
    let o = LatexOptions {
        shorthand,
        ..LatexOptions::default()
    };
    let shown = super::general::exact::exact_equations(sol, info).and_then(|eq| {
        Ok::<_, ExactError>((super::general::exact_scope_text(sol, &eq), eq.shown(sol)?))
    });
    let (scope, groups) = match shown {
        Ok(x) => x,
        Err(ExactError::Scalar(ScalarError::Cancelled)) => return Err(ScalarError::Cancelled),
        Err(e) => {
            return Ok(line_comment(
                Comment::Latex,
                "%",
                &format!("exact equations: not printed ({e})"),
            ))
        }
    };
    let mut out = line_comment(Comment::Latex, "%", &format!("exact equations: {scope}"));
    for g in groups {
        out.push_str(&line_comment(Comment::Latex, "%", &g.title));
        out.push_str("\\begin{aligned}\n");
        for s in &g.items {
            out.push_str(&format!("{} &= {} \\\\\n", s.tex, latex(&s.expr, &o)));
        }
        out.push_str("\\end{aligned}\n");
    }
    Ok(out)
}

/// The general method's polynomial as a LaTeX block: the matrix polynomial and its degree.
fn general_latex(sol: &IkSolution, info: &super::general::GeneralInfo) -> String {
    let slides = sol.axes.iter().any(|a| a.kind == JointKind::Prismatic);
    if slides {
        // A sliding hidden joint enters M through the Möbius map of the shift, and the
        // spurious factor depends on the arrangement (`general` module docs).
        let var = if super::general::hidden_slides(sol, info) {
            "d = \\frac{t + x}{1 - t x}, \\ t = \\tan\\tfrac{\\varphi}{2}"
        } else {
            "x = \\tan\\tfrac{\\theta - \\varphi}{2}"
        };
        return format!(
            "\\begin{{aligned}}\n\
M(x) &= A x^2 + B x + C \\in \\mathbb{{R}}^{{12 \\times 12}}, \\quad {var} \\\\\n\
\\det M(x) &= s(x) \\, p(x), \\quad \\deg p = {} \\quad (s \\text{{: the spurious factor}})\n\\end{{aligned}}\n",
            info.degree
        );
    }
    format!(
        "\\begin{{aligned}}\n\
M(x) &= A x^2 + B x + C \\in \\mathbb{{R}}^{{12 \\times 12}}, \\quad x = \\tan\\tfrac{{\\theta - \\varphi}}{{2}} \\\\\n\
\\det M(x) &= (1 + x^2)^4 \\, p(x), \\quad \\deg p = {}\n\\end{{aligned}}\n",
        info.degree
    )
}
