//! Walkthroughs as terminal text and as Markdown with LaTeX.
//!
//! Both number the steps from 1 and print each value through the same closed forms as
//! `dqsym run` (plain text with its shorthand legend, or [`latex_value`]).

use super::{ComponentTrace, HalfAngle, Step, WalkError, Walkthrough, Word, Words};
use crate::lang::latex_value;
use crate::print::angle_text;
use crate::{
    closed_form, latex, latex_symbol, legend, plain, show, Displayed, Expr, LatexOptions,
    PlainOptions, Scalar, ShowOptions, TraceStep, Value,
};

/// Expanded sums longer than this are listed in rows of this many terms.
const ROW: usize = 6;

/// How a renderer writes values and words.
pub(crate) trait Style {
    fn scalar(&self, x: &Scalar) -> Result<String, WalkError>;
    fn expr(&self, e: &Expr) -> String;
    fn words(&self, w: &Words) -> Result<String, WalkError> {
        let mut out = String::new();
        for p in &w.0 {
            match p {
                Word::Text(t) => out.push_str(t),
                Word::Scalar(x) => out.push_str(&self.scalar(x)?),
                Word::Tuple(v) => {
                    let parts: Result<Vec<String>, WalkError> =
                        v.iter().map(|x| self.scalar(x)).collect();
                    out.push_str(&self.tuple(&parts?));
                }
            }
        }
        Ok(out)
    }
    fn tuple(&self, parts: &[String]) -> String;
}

struct Plain;

impl Style for Plain {
    fn scalar(&self, x: &Scalar) -> Result<String, WalkError> {
        Ok(plain(&closed_form(x)?, &PlainOptions { shorthand: false }))
    }
    fn expr(&self, e: &Expr) -> String {
        plain(e, &PlainOptions::default())
    }
    fn tuple(&self, parts: &[String]) -> String {
        format!("({})", parts.join(", "))
    }
}

/// Markdown: values in `$...$`.
pub(crate) struct Tex;

impl Style for Tex {
    fn scalar(&self, x: &Scalar) -> Result<String, WalkError> {
        Ok(format!("${}$", latex(&closed_form(x)?, &latex_opts())))
    }
    fn expr(&self, e: &Expr) -> String {
        latex(e, &latex_opts())
    }
    fn tuple(&self, parts: &[String]) -> String {
        let inner: Vec<&str> = parts.iter().map(|p| p.trim_matches('$')).collect();
        format!("$({})$", inner.join(", "))
    }
}

pub(crate) fn latex_opts() -> LatexOptions {
    LatexOptions::default()
}

/// `label = value` in plain text, each line indented by `pad`.
fn shown(label: &str, value: &Value, pad: &str) -> Result<String, WalkError> {
    let d = Displayed {
        label: label.to_owned(),
        value: value.clone(),
        format: None,
    };
    let text = show(&d, &ShowOptions::default())?;
    Ok(text.lines().map(|l| format!("{pad}{l}\n")).collect())
}

/// The walkthrough as terminal text.
///
/// # Errors
/// When a value cannot be shown (never for a walkthrough this crate built).
pub fn walk_text(w: &Walkthrough) -> Result<String, WalkError> {
    let mut out = format!("Walkthrough: {}\n", w.title);
    let pad = "   ";
    for (i, step) in w.steps.iter().enumerate() {
        let n = i + 1;
        out.push('\n');
        match step {
            Step::Notation { meaning, .. } => out += &format!("{n}. Notation: {meaning}\n"),
            Step::Factor {
                name,
                value,
                meaning,
            } => {
                out += &format!("{n}. Factor {name}: {}\n", Plain.words(meaning)?);
                out += &shown(name, value, pad)?;
            }
            Step::Define {
                name,
                value,
                meaning,
            } => {
                out += &format!("{n}. Define {name}: {}\n", Plain.words(meaning)?);
                out += &shown(name, value, pad)?;
            }
            Step::Product { left, right, value } => {
                out += &format!("{n}. Product {left} times {right}\n");
                out += &shown(&format!("{left}*{right}"), value, pad)?;
            }
            Step::Transform {
                label,
                q,
                v,
                value,
                half_angles,
                traces,
            } => {
                out += &format!(
                    "{n}. Transform: {label} is the point {v} carried by {q} (eq 10, q v q*)\n"
                );
                out += &shown(label, value, pad)?;
                if !half_angles.is_empty() {
                    out += &format!("{pad}{}\n", half_angle_text(half_angles));
                }
                for t in traces {
                    out += &trace_text(t, pad);
                }
            }
            Step::Result { label, value } => {
                out += &format!("{n}. Result: the closed form\n");
                out += &shown(label, value, pad)?;
            }
            Step::Check {
                what,
                oracle,
                samples,
                max_deviation,
            } => {
                out += &format!(
                    "{n}. Check against 4x4 homogeneous matrices: {what} at {samples} random \
                     configurations against {oracle}\n{pad}max deviation {}\n",
                    deviation(*max_deviation)
                );
            }
        }
    }
    Ok(out)
}

/// The deviation, machine-independent when it is rounding noise.
pub(crate) fn deviation(d: f64) -> String {
    if d < 1e-12 {
        "below 1e-12: the results agree".to_owned()
    } else {
        format!("{d:.3e}: the results DISAGREE")
    }
}

fn half_angle_text(h: &[HalfAngle]) -> String {
    let mut parts = Vec::new();
    for a in h {
        let (c, s) = match &a.names {
            Some((c, s)) => (c.clone(), s.clone()),
            None => (
                format!("cos({}/2)", a.symbol),
                format!("sin({}/2)", a.symbol),
            ),
        };
        parts.push(format!(
            "{c}^2 - {s}^2 = cos({t}), 2 {s} {c} = sin({t}), {c}^2 + {s}^2 = 1",
            t = a.symbol
        ));
    }
    format!(
        "Half angles lifted: the factor and its conjugate each hold the half angle, so the \
         product has pairs of them: {}",
        parts.join("; ")
    )
}

/// A sum with numbered terms: `[1] l1 + [2] l2 c2 - [3] l3 s2 s3`.
fn numbered_sum(terms: &[Expr], pad: &str) -> String {
    let mut out = String::new();
    for (i, t) in terms.iter().enumerate() {
        let (neg, body) = match t {
            Expr::Neg(e) => (true, &**e),
            e => (false, e),
        };
        let body = plain(body, &PlainOptions::default());
        if i > 0 && i % ROW == 0 {
            out += &format!("\n{pad}  ");
        }
        match (i, neg) {
            (0, true) => out += &format!("-[{}] {body}", i + 1),
            (0, false) => out += &format!("[{}] {body}", i + 1),
            (_, true) => out += &format!(" - [{}] {body}", i + 1),
            (_, false) => out += &format!(" + [{}] {body}", i + 1),
        }
    }
    if terms.is_empty() {
        out.push('0');
    }
    out
}

fn trace_text(t: &ComponentTrace, pad: &str) -> String {
    let mut out = format!("{pad}{}:\n", t.label);
    let inner = format!("{pad}  ");
    let mut last: &[Expr] = &[];
    let mut exprs: Vec<Expr> = Vec::new();
    for s in &t.steps {
        match s {
            TraceStep::Sum { round, terms } => {
                let what = if *round == 1 {
                    "expanded sum"
                } else {
                    "regrouped"
                };
                out += &format!("{inner}{what}: {}\n", numbered_sum(terms, &inner));
                exprs.extend(terms.iter().cloned());
                last = terms;
            }
            TraceStep::Identity {
                identity,
                a,
                b,
                terms,
                result,
                ..
            } => {
                let pair = pair_text(last, *terms);
                out += &format!(
                    "{inner}{}, a = {}, b = {}, terms {} and {}: {pair} = {}\n",
                    identity.text(),
                    angle_text(a),
                    angle_text(b),
                    terms[0],
                    terms[1],
                    plain(result, &PlainOptions::default())
                );
                exprs.push(result.clone());
            }
            TraceStep::Factored(e) => {
                out += &format!(
                    "{inner}common factors out: {}\n",
                    plain(e, &PlainOptions::default())
                );
                exprs.push(e.clone());
            }
            TraceStep::KeptWhole(e) => {
                out += &format!(
                    "{inner}closed form (the Fourier modes kept whole are shorter): {}\n",
                    plain(e, &PlainOptions::default())
                );
                exprs.push(e.clone());
            }
        }
    }
    let refs: Vec<&Expr> = exprs.iter().collect();
    let names = legend(&refs);
    if !names.is_empty() {
        out += &format!("{inner}where {}\n", names.join(", "));
    }
    out
}

/// The two terms `i` and `j` (from 1) of `terms` as a sum, plain text.
fn pair_text(terms: &[Expr], [i, j]: [usize; 2]) -> String {
    match (terms.get(i.wrapping_sub(1)), terms.get(j.wrapping_sub(1))) {
        (Some(x), Some(y)) => plain(
            &Expr::Add(vec![x.clone(), y.clone()]),
            &PlainOptions::default(),
        ),
        _ => String::new(),
    }
}

/// A label as LaTeX: a name as a symbol, an expression in typewriter type.
pub(crate) fn label_tex(label: &str) -> String {
    let ident = label
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic())
        && label.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if ident {
        return latex_symbol(label);
    }
    let mut s = String::new();
    for c in label.chars() {
        match c {
            '_' | '%' | '#' | '&' | '$' | '{' | '}' => {
                s.push('\\');
                s.push(c);
            }
            '^' => s.push_str("\\textasciicircum{}"),
            '~' => s.push_str("\\textasciitilde{}"),
            '\\' => s.push_str("\\textbackslash{}"),
            c if c.is_ascii() => s.push(c),
            _ => s.push('?'),
        }
    }
    format!("\\texttt{{{s}}}")
}

/// `label = value` as display LaTeX.
pub(crate) fn value_tex(label: &str, value: &Value) -> Result<String, WalkError> {
    let v = latex_value(value, &latex_opts()).map_err(WalkError::Scalar)?;
    Ok(format!("{} = {v}", label_tex(label)))
}

/// A sum with numbered terms as LaTeX, `\underbrace{term}_{k}`, in rows of [`ROW`].
pub(crate) fn numbered_sum_tex(terms: &[Expr]) -> String {
    let mut rows: Vec<String> = Vec::new();
    let mut row = String::new();
    for (i, t) in terms.iter().enumerate() {
        let (neg, body) = match t {
            Expr::Neg(e) => (true, &**e),
            e => (false, e),
        };
        if i > 0 && i % ROW == 0 {
            rows.push(std::mem::take(&mut row));
        }
        let sign = match (i, neg) {
            (0, false) => "",
            (0, true) => "-",
            (_, true) => " - ",
            (_, false) => " + ",
        };
        let sign = if i % ROW == 0 && i > 0 {
            format!("&{}", sign.trim())
        } else if i == 0 {
            format!("&{sign}")
        } else {
            sign.to_owned()
        };
        row += &format!(
            "{sign}\\underbrace{{{}}}_{{{}}}",
            latex(body, &latex_opts()),
            i + 1
        );
    }
    if terms.is_empty() {
        row.push_str("&0");
    }
    rows.push(row);
    format!("\\begin{{aligned}}{}\\end{{aligned}}", rows.join(" \\\\ "))
}

/// The notation of results, said once at the top of Markdown and HTML walkthroughs.
pub(crate) const NOTATION: &str = "In results, $c_{1}$, $s_{12}$, $c_{123}$ are $\\cos\\theta_{1}$, \
    $\\sin(\\theta_{1} + \\theta_{2})$, $\\cos(\\theta_{1} + \\theta_{2} + \\theta_{3})$ of full joint \
    angles; half angles inside the factors are written out, $\\cos\\frac{\\theta_{3}}{2}$.";

/// A formula or text piece of a Markdown or HTML walkthrough.
pub(crate) enum Piece {
    /// Prose with inline `$...$` math.
    Text(String),
    /// Display math.
    Display(String),
}

/// The walkthrough as pieces, shared by Markdown and HTML: one heading per step, then
/// prose and display formulas.
pub(crate) fn pieces(w: &Walkthrough) -> Result<Vec<(String, Vec<Piece>)>, WalkError> {
    let mut out = Vec::new();
    for (i, step) in w.steps.iter().enumerate() {
        let n = i + 1;
        let (head, body) = match step {
            Step::Notation { names, meaning } => {
                let _ = names;
                (
                    format!("{n}. Notation"),
                    vec![Piece::Text(format!("`{meaning}`"))],
                )
            }
            Step::Factor {
                name,
                value,
                meaning,
            } => (
                format!("{n}. Factor ${}$", label_tex(name)),
                vec![
                    Piece::Text(format!("{}.", capitalize(&Tex.words(meaning)?))),
                    Piece::Display(value_tex(name, value)?),
                ],
            ),
            Step::Define {
                name,
                value,
                meaning,
            } => (
                format!("{n}. Define ${}$", label_tex(name)),
                vec![
                    Piece::Text(format!("{}.", capitalize(&Tex.words(meaning)?))),
                    Piece::Display(value_tex(name, value)?),
                ],
            ),
            Step::Product { left, right, value } => (
                format!("{n}. Product"),
                vec![
                    Piece::Text(format!(
                        "${}$ times ${}$:",
                        label_tex(left),
                        label_tex(right)
                    )),
                    Piece::Display(value_tex(&format!("{left}*{right}"), value)?),
                ],
            ),
            Step::Transform {
                label,
                q,
                v,
                value,
                half_angles,
                traces,
            } => {
                let mut body = vec![
                    Piece::Text(format!(
                        "The point ${}$ carried by ${}$ (eq 10, $\\hat q \\hat v \\bar{{\\hat q}}^*$):",
                        label_tex(v),
                        label_tex(q)
                    )),
                    Piece::Display(value_tex(label, value)?),
                ];
                if !half_angles.is_empty() {
                    body.push(Piece::Text(
                        "Half angles lifted: the factor and its conjugate each hold the half \
                         angle, so the product has pairs of them:"
                            .to_owned(),
                    ));
                    for a in half_angles {
                        body.push(Piece::Display(half_angle_tex(a)));
                    }
                }
                for t in traces {
                    body.extend(trace_tex(t));
                }
                (format!("{n}. Transform ${}$", label_tex(label)), body)
            }
            Step::Result { label, value } => (
                format!("{n}. Result"),
                vec![
                    Piece::Text("The closed form:".to_owned()),
                    Piece::Display(value_tex(label, value)?),
                ],
            ),
            Step::Check {
                what,
                oracle,
                samples,
                max_deviation,
            } => (
                format!("{n}. Check against 4x4 homogeneous matrices"),
                vec![Piece::Text(format!(
                    "{what} at {samples} random configurations against {oracle}: max \
                     deviation {}.",
                    deviation(*max_deviation)
                ))],
            ),
        };
        out.push((head, body));
    }
    Ok(out)
}

fn capitalize(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().collect::<String>() + c.as_str(),
        None => String::new(),
    }
}

fn half_angle_tex(a: &HalfAngle) -> String {
    let t = latex_symbol(&a.symbol);
    let (c, s) = match &a.names {
        Some((c, s)) => (latex_symbol(c), latex_symbol(s)),
        None => (
            format!("\\cos\\tfrac{{{t}}}{{2}}"),
            format!("\\sin\\tfrac{{{t}}}{{2}}"),
        ),
    };
    format!("{c}^2 - {s}^2 = \\cos {t}, \\quad 2 {s} {c} = \\sin {t}, \\quad {c}^2 + {s}^2 = 1")
}

fn trace_tex(t: &ComponentTrace) -> Vec<Piece> {
    let mut out = vec![Piece::Text(format!("Coordinate `{}`:", t.label))];
    let mut last: &[Expr] = &[];
    for s in &t.steps {
        match s {
            TraceStep::Sum { round, terms } => {
                out.push(Piece::Text(
                    if *round == 1 {
                        "expanded sum, terms numbered:"
                    } else {
                        "regrouped:"
                    }
                    .to_owned(),
                ));
                out.push(Piece::Display(numbered_sum_tex(terms)));
                last = terms;
            }
            TraceStep::Identity {
                identity,
                a,
                b,
                terms,
                result,
                ..
            } => {
                let pair = match (
                    last.get(terms[0].wrapping_sub(1)),
                    last.get(terms[1].wrapping_sub(1)),
                ) {
                    (Some(x), Some(y)) => Tex.expr(&Expr::Add(vec![x.clone(), y.clone()])),
                    _ => String::new(),
                };
                out.push(Piece::Text(format!(
                    "${}$ with $a = {}$, $b = {}$, terms {} and {}:",
                    identity.latex(),
                    angle_tex(a),
                    angle_tex(b),
                    terms[0],
                    terms[1]
                )));
                out.push(Piece::Display(format!("{pair} = {}", Tex.expr(result))));
            }
            TraceStep::Factored(e) => {
                out.push(Piece::Text("common factors out:".to_owned()));
                out.push(Piece::Display(Tex.expr(e)));
            }
            TraceStep::KeptWhole(e) => {
                out.push(Piece::Text(
                    "closed form (the Fourier modes kept whole are shorter):".to_owned(),
                ));
                out.push(Piece::Display(Tex.expr(e)));
            }
        }
    }
    out
}

fn angle_tex(a: &crate::Angle) -> String {
    match closed_form(&a.to_scalar()) {
        Ok(e) => Tex.expr(&e),
        Err(_) => String::new(),
    }
}

/// The walkthrough as Markdown: a heading per step, formulas in `$$ ... $$`.
///
/// # Errors
/// When a value cannot be shown (never for a walkthrough this crate built).
pub fn walk_markdown(w: &Walkthrough) -> Result<String, WalkError> {
    let mut out = format!("# Walkthrough: {}\n\n{}\n", w.title, NOTATION);
    for (head, body) in pieces(w)? {
        out += &format!("\n## {head}\n");
        for p in body {
            match p {
                Piece::Text(t) => out += &format!("\n{t}\n"),
                Piece::Display(d) => out += &format!("\n$$\n{d}\n$$\n"),
            }
        }
    }
    Ok(out)
}
