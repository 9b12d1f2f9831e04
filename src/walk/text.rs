//! Walkthroughs as terminal text and as Markdown with LaTeX.
//!
//! Both number the steps from 1 and print each value through the same closed forms as
//! `dqsym run` (plain text with its shorthand legend, or [`latex_value`]).

use super::forms::half;
use super::notation::Names;
use super::{
    Block, ComponentTrace, Forms, HalfAngle, Prose, Shown, SolutionRow, Step, WalkError,
    Walkthrough, Word, Words,
};
use crate::closed::angle_text;
use crate::emit::visual_len;
use crate::{
    closed::TraceStep,
    emit::{latex_aligned_named, latex_named, latex_symbol},
    print::{plain_named, plain_quotient_named},
    Expr, LatexOptions, PlainOptions, Scalar, Value,
};

/// Expanded sums longer than this are listed in rows of this many terms.
const ROW: usize = 6;

/// Expanded sums with more terms than this are folded on the page (expandable), not dropped.
pub(crate) const FOLD: usize = 16;

/// Display formulas wider than this (in [`visual_len`] characters) are laid out one entry per
/// line, long entries broken at a `+` or `-`: about 900 px of KaTeX display math.
pub(crate) const WIDTH: usize = 72;

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

/// Plain text in the page's notation, the closed forms looked up in the walkthrough's.
pub(crate) struct Plain<'a>(pub &'a Names, pub &'a Forms);

impl Style for Plain<'_> {
    fn scalar(&self, x: &Scalar) -> Result<String, WalkError> {
        Ok(self.expr(self.1.of(x)?))
    }
    fn expr(&self, e: &Expr) -> String {
        plain_named(e, &PlainOptions::default(), &|s, a| self.0.plain(s, a))
    }
    fn tuple(&self, parts: &[String]) -> String {
        format!("({})", parts.join(", "))
    }
}

/// Markdown: values in `$...$`, in the page's notation, the closed forms looked up in the
/// walkthrough's.
pub(crate) struct Tex<'a>(pub &'a Names, pub &'a Forms);

impl Style for Tex<'_> {
    fn scalar(&self, x: &Scalar) -> Result<String, WalkError> {
        Ok(format!("${}$", self.expr(self.1.of(x)?)))
    }
    fn expr(&self, e: &Expr) -> String {
        latex_named(e, &latex_opts(), &|s, a| self.0.tex(s, a))
    }
    fn tuple(&self, parts: &[String]) -> String {
        let inner: Vec<&str> = parts.iter().map(|p| p.trim_matches('$')).collect();
        format!("$({})$", inner.join(", "))
    }
}

impl Tex<'_> {
    /// Named rows in `aligned`, each broken at [`WIDTH`].
    fn aligned(&self, rows: &[(String, Expr)]) -> String {
        let o = LatexOptions {
            width: WIDTH,
            ..latex_opts()
        };
        latex_aligned_named(rows, &o, &|s, a| self.0.tex(s, a))
    }
}

pub(crate) fn latex_opts() -> LatexOptions {
    LatexOptions::default()
}

/// A quaternion part of a DQ: its scalar when the vector part is zero (a point reads
/// `1 + eps (0, x, y, z)`).
fn dq_part(q: &crate::Quat<Scalar>) -> Option<&Scalar> {
    q.vector_part()
        .iter()
        .all(num_traits::Zero::is_zero)
        .then_some(&q.w)
}

/// A value as plain lines (several for a matrix).
fn plain_value(v: &Value, st: &Plain) -> Result<Vec<String>, WalkError> {
    let list = |items: Vec<&Scalar>| -> Result<String, WalkError> {
        let parts: Result<Vec<String>, WalkError> = items.iter().map(|x| st.scalar(x)).collect();
        Ok(parts?.join(", "))
    };
    let part = |q: &crate::Quat<Scalar>| -> Result<String, WalkError> {
        match dq_part(q) {
            Some(w) => {
                let t = st.scalar(w)?;
                let simple = !t.contains([' ', '+', '-']) || t.starts_with('(');
                Ok(if simple { t } else { format!("({t})") })
            }
            None => Ok(format!("({})", list(vec![&q.w, &q.x, &q.y, &q.z])?)),
        }
    };
    Ok(match v {
        Value::Scalar(x) => vec![st.scalar(x)?],
        Value::Quat(q) => vec![format!("({})", list(vec![&q.w, &q.x, &q.y, &q.z])?)],
        Value::Vector(x) => vec![format!("({})", list(x.iter().collect())?)],
        Value::DualQuat(d) => vec![format!("{} + eps {}", part(&d.real)?, part(&d.dual)?)],
        Value::Matrix(rows) => rows
            .iter()
            .map(|r| Ok(format!("[{}]", list(r.iter().collect())?)))
            .collect::<Result<_, WalkError>>()?,
        Value::QuotientMatrix(rows) => {
            let mut lines = Vec::new();
            for r in rows {
                let mut parts = Vec::new();
                for q in r {
                    let (n, d) = (st.1.of(q.num())?, st.1.of(q.den())?);
                    parts.push(plain_quotient_named(
                        n,
                        d,
                        &PlainOptions::default(),
                        &|s, a| st.0.plain(s, a),
                    ));
                }
                lines.push(format!("[{}]", parts.join(", ")));
            }
            lines
        }
    })
}

/// `label = value` in plain text, each line indented by `pad`.
fn shown(label: &str, value: &Value, st: &Plain, pad: &str) -> Result<String, WalkError> {
    let lines = plain_value(value, st)?;
    Ok(match lines.as_slice() {
        [one] => format!("{pad}{label} = {one}\n"),
        _ => {
            let mut s = format!("{pad}{label} =\n");
            for l in &lines {
                s += &format!("{pad}  {l}\n");
            }
            s
        }
    })
}

/// The legend of a page in plain text: the notation, and the script's own `halfangle` names.
fn legend_text(w: &Walkthrough, names: &Names) -> String {
    let mut out = String::new();
    for l in legend_prose(w) {
        out += &format!("\n{}\n", l.plain);
    }
    let lines = names.legend_plain();
    if !lines.is_empty() {
        out += "\nNotation (each symbol has one meaning on this page):\n";
        for l in lines {
            out += &format!("  {l}\n");
        }
    }
    if let Some(s) = script_names(w) {
        out += &format!("  the script's halfangle names: {s}\n");
    }
    out
}

/// The legend lines a builder gave ([`Step::Legend`]).
fn legend_prose(w: &Walkthrough) -> Vec<&Prose> {
    w.steps
        .iter()
        .filter_map(|s| match s {
            Step::Legend(l) => Some(l),
            _ => None,
        })
        .flatten()
        .collect()
}

/// The script's `halfangle` names, in words.
fn script_names(w: &Walkthrough) -> Option<String> {
    let m: Vec<&str> = w
        .steps
        .iter()
        .filter_map(|s| match s {
            Step::Notation { meaning, .. } => Some(meaning.as_str()),
            _ => None,
        })
        .collect();
    (!m.is_empty()).then(|| m.join(", "))
}

/// The walkthrough as terminal text.
///
/// # Errors
/// When a value cannot be shown (never for a walkthrough this crate built).
pub fn walk_text(w: &Walkthrough) -> Result<String, WalkError> {
    let names = Names::for_walk(w);
    let st = Plain(&names, &w.forms);
    let mut out = String::new();
    let pad = "   ";
    let mut n = 0;
    for step in &w.steps {
        if matches!(step, Step::Notation { .. } | Step::Legend(_)) {
            continue;
        }
        n += 1;
        out.push('\n');
        match step {
            Step::Notation { .. } | Step::Legend(_) => {}
            Step::Explain { title, blocks } => {
                out += &format!("{n}. {}\n", title.plain);
                for b in blocks {
                    out += &block_text(b, &st, pad);
                }
            }
            Step::Solutions {
                what,
                variables,
                rows,
            } => {
                out += &format!("{n}. Check: {}\n", what.plain);
                out += &format!("{pad}({})\n", variables.join(", "));
                for r in rows {
                    out += &format!("{pad}{}\n", solution_text(r));
                }
            }
            Step::Factor {
                name,
                value,
                meaning,
            } => {
                out += &format!("{n}. Factor {name}: {}\n", st.words(meaning)?);
                out += &shown(name, value, &st, pad)?;
            }
            Step::Define {
                name,
                value,
                meaning,
            } => {
                out += &format!("{n}. Define {name}: {}\n", st.words(meaning)?);
                out += &shown(name, value, &st, pad)?;
            }
            Step::Product { left, right, value } => {
                out += &format!("{n}. Product {left} times {right}\n");
                out += &shown(&format!("{left}*{right}"), value, &st, pad)?;
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
                out += &shown(label, value, &st, pad)?;
                if !half_angles.is_empty() {
                    out += &format!("{pad}{}\n", half_angle_text(half_angles, &st)?);
                }
                for t in traces {
                    out += &trace_text(t, &st, pad);
                }
            }
            Step::Result { label, value } => {
                out += &format!("{n}. Result: the closed form\n");
                out += &shown(label, value, &st, pad)?;
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
    Ok(format!(
        "Walkthrough: {}\n{}{out}",
        crate::emit::names::printable(&w.title),
        legend_text(w, &names)
    ))
}

/// A block of an explained step as plain text.
fn block_text(b: &Block, st: &Plain, pad: &str) -> String {
    match b {
        Block::Text(p) => format!("{pad}{}\n", p.plain),
        Block::List(items) => items
            .iter()
            .map(|p| format!("{pad}- {}\n", p.plain))
            .collect(),
        Block::Display(p) => format!("{pad}    {}\n", p.plain),
        Block::Formulas(rows) => rows
            .iter()
            .map(|r| {
                let parts: Vec<String> = r.parts.iter().map(|e| st.expr(e)).collect();
                if parts.len() == 1 {
                    format!("{pad}  {} = {}\n", r.label, parts[0])
                } else {
                    format!("{pad}  {} = ({})\n", r.label, parts.join(", "))
                }
            })
            .collect(),
    }
}

/// One row of a solver's check: the joint values, the merged branches, the deviation.
fn solution_text(r: &SolutionRow) -> String {
    let q: Vec<String> = r.q.iter().map(|x| format!("{x:.4}")).collect();
    format!(
        "({}){}{}: pose deviation {}",
        q.join(", "),
        if r.branches > 1 {
            format!(", {} branches meet", r.branches)
        } else {
            String::new()
        },
        if r.singular { " (singular)" } else { "" },
        deviation(r.deviation)
    )
}

/// The deviation, machine-independent when it is rounding noise.
pub(crate) fn deviation(d: f64) -> String {
    if d < 1e-12 {
        "below 1e-12: the results agree".to_owned()
    } else {
        format!("{d:.3e}: the results DISAGREE")
    }
}

/// The identities of the half angles, as expressions: `c3^2 - s3^2 = C3`, `2 s3 c3 = S3`,
/// `c3^2 + s3^2 = 1`.
fn half_angle_identities(symbol: &str, forms: &Forms) -> Result<[(Expr, Expr); 3], WalkError> {
    let t = Scalar::sym(symbol);
    let h = half(&t);
    let (c, s) = (forms.of(&h.cos())?.clone(), forms.of(&h.sin())?.clone());
    let sq = |e: &Expr| Expr::Pow(Box::new(e.clone()), 2);
    Ok([
        (
            Expr::Add(vec![sq(&c), Expr::Neg(Box::new(sq(&s)))]),
            forms.of(&t.cos())?.clone(),
        ),
        (
            Expr::Mul(vec![
                Expr::Num(num_rational::BigRational::from_integer(2.into())),
                s.clone(),
                c.clone(),
            ]),
            forms.of(&t.sin())?.clone(),
        ),
        (
            Expr::Add(vec![sq(&c), sq(&s)]),
            Expr::Num(num_rational::BigRational::from_integer(1.into())),
        ),
    ])
}

const HALF_ANGLES: &str = "Half angles lifted: the factor and its conjugate each hold the half \
    angle, so the product has pairs of them";

fn half_angle_text(h: &[HalfAngle], st: &Plain) -> Result<String, WalkError> {
    let mut parts = Vec::new();
    for a in h {
        let ids = half_angle_identities(&a.symbol, st.1)?;
        let each: Vec<String> = ids
            .iter()
            .map(|(l, r)| format!("{} = {}", st.expr(l), st.expr(r)))
            .collect();
        parts.push(each.join(", "));
    }
    Ok(format!("{HALF_ANGLES}: {}", parts.join("; ")))
}

/// A sum with numbered terms: `[1] l1 + [2] l2 C2 - [3] l3 S2 S3`.
fn numbered_sum(terms: &[Expr], st: &Plain, pad: &str) -> String {
    let mut out = String::new();
    for (i, t) in terms.iter().enumerate() {
        let (neg, body) = match t {
            Expr::Neg(e) => (true, &**e),
            e => (false, e),
        };
        let body = st.expr(body);
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

fn trace_text(t: &ComponentTrace, st: &Plain, pad: &str) -> String {
    let mut out = format!("{pad}{}:\n", t.label);
    let inner = format!("{pad}  ");
    let mut last: &[Expr] = &[];
    for s in &t.steps {
        match s {
            TraceStep::Sum { round, terms } => {
                let what = if *round == 1 {
                    "expanded sum"
                } else {
                    "regrouped"
                };
                out += &format!("{inner}{what}: {}\n", numbered_sum(terms, st, &inner));
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
                let pair = pair_expr(last, *terms)
                    .map(|p| st.expr(&p))
                    .unwrap_or_default();
                out += &format!(
                    "{inner}{}, a = {}, b = {}, terms {} and {}: {pair} = {}\n",
                    identity.text(),
                    angle_text(a),
                    angle_text(b),
                    terms[0],
                    terms[1],
                    st.expr(result)
                );
            }
            TraceStep::Factored(e) => {
                out += &format!("{inner}common factors out: {}\n", st.expr(e));
            }
            TraceStep::KeptWhole(e) => {
                out += &format!(
                    "{inner}closed form (the Fourier modes kept whole are shorter): {}\n",
                    st.expr(e)
                );
            }
            TraceStep::Shorter(e) => {
                out += &format!(
                    "{inner}closed form (a shorter equivalent form): {}\n",
                    st.expr(e)
                );
            }
        }
    }
    out
}

/// The two terms `i` and `j` (from 1) of `terms` as a sum.
fn pair_expr(terms: &[Expr], [i, j]: [usize; 2]) -> Option<Expr> {
    let x = terms.get(i.wrapping_sub(1))?;
    let y = terms.get(j.wrapping_sub(1))?;
    Some(Expr::Add(vec![x.clone(), y.clone()]))
}

/// A label as LaTeX: a name as a symbol, an expression in typewriter type.
pub(crate) fn label_tex(label: &str) -> String {
    if is_ident(label) {
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

fn is_ident(label: &str) -> bool {
    label
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic())
        && label.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The name of component `c` (LaTeX) of the value labelled `label`: `q_{x}`, `q_{1,x}` for
/// `q1`, `\hat q_{x}` for a label that is an expression; a dual part's component carries an
/// `\varepsilon` above: `q^{\varepsilon}_{x}`.
fn component(label: &str, c: &str, dual: bool) -> String {
    let up = if dual { "^{\\varepsilon}" } else { "" };
    if !is_ident(label) {
        return format!("\\hat q{up}_{{{c}}}");
    }
    let l = latex_symbol(label);
    match l.split_once("_{") {
        Some((base, sub)) if sub.ends_with('}') && !sub[..sub.len() - 1].contains('{') => {
            format!("{base}{up}_{{{},{c}}}", &sub[..sub.len() - 1])
        }
        Some(_) => format!("{{{l}}}{up}_{{{c}}}"),
        None => format!("{l}{up}_{{{c}}}"),
    }
}

/// The closed form of `x` when it is not a constant (constants are shown in place).
fn entry(x: &Scalar, forms: &Forms) -> Result<(Expr, bool), WalkError> {
    Ok((forms.of(x)?.clone(), x.is_constant()))
}

/// The entries of a value as shown in place (a constant, or a name), and the named ones.
type Named = (Vec<String>, Vec<(String, Expr)>);

/// `label = value` as display math that fits the page: on one line when it is short, else the
/// value with its entries named, then the entries one per line (a matrix column by column),
/// each broken at [`WIDTH`].
pub(crate) fn value_tex(label: &str, value: &Value, st: &Tex) -> Result<Vec<Piece>, WalkError> {
    let lab = label_tex(label);
    let line = match value {
        Value::QuotientMatrix(rows) => {
            return Ok(vec![Piece::Display(quotient_matrix_tex(&lab, rows, st)?)]);
        }
        Value::Matrix(rows) => {
            if let Some(one) = short_matrix_tex(&lab, rows, st)? {
                return Ok(vec![Piece::Display(one)]);
            }
            String::new()
        }
        _ => inline_tex(value, st)?,
    };
    if !line.is_empty() && visual_len(&line) + visual_len(&lab) + 3 <= WIDTH {
        return Ok(vec![Piece::Display(format!("{lab} = {line}"))]);
    }
    // Too wide: the entries named, then listed.
    named_value_tex(label, &lab, value, st)
}

/// A scalar, quaternion, vector or DQ on one line (empty for a matrix).
fn inline_tex(value: &Value, st: &Tex) -> Result<String, WalkError> {
    let e = |x: &Scalar| -> Result<String, WalkError> { Ok(st.expr(st.1.of(x)?)) };
    let tuple = |xs: &[&Scalar]| -> Result<String, WalkError> {
        let parts: Result<Vec<String>, WalkError> = xs.iter().map(|x| e(x)).collect();
        Ok(format!("\\left({}\\right)", parts?.join(", ")))
    };
    let part = |q: &crate::Quat<Scalar>| -> Result<String, WalkError> {
        match dq_part(q) {
            Some(w) => {
                let t = e(w)?;
                let simple = !t.contains([' ', '+', '-']) || t.starts_with('(');
                Ok(if simple {
                    t
                } else {
                    format!("\\left({t}\\right)")
                })
            }
            None => tuple(&[&q.w, &q.x, &q.y, &q.z]),
        }
    };
    Ok(match value {
        Value::Scalar(x) => e(x)?,
        Value::Quat(q) => tuple(&[&q.w, &q.x, &q.y, &q.z])?,
        Value::Vector(x) => tuple(&[&x[0], &x[1], &x[2]])?,
        Value::DualQuat(d) => format!("{} + \\varepsilon {}", part(&d.real)?, part(&d.dual)?),
        Value::Matrix(_) | Value::QuotientMatrix(_) => String::new(),
    })
}

/// A matrix on one line, when its widest row fits.
fn short_matrix_tex(
    lab: &str,
    rows: &[Vec<Scalar>],
    st: &Tex,
) -> Result<Option<String>, WalkError> {
    let e = |x: &Scalar| -> Result<String, WalkError> { Ok(st.expr(st.1.of(x)?)) };
    let body: Vec<String> = rows
        .iter()
        .map(|r| {
            let cells: Result<Vec<String>, WalkError> = r.iter().map(e).collect();
            Ok(cells?.join(" & "))
        })
        .collect::<Result<_, WalkError>>()?;
    let widest = body.iter().map(|r| visual_len(r)).max().unwrap_or(0);
    Ok((widest <= WIDTH).then(|| {
        format!(
            "{lab} = \\begin{{pmatrix}} {} \\end{{pmatrix}}",
            body.join(" \\\\ ")
        )
    }))
}

/// A matrix of quotients, entry by entry as fractions.
fn quotient_matrix_tex(
    lab: &str,
    rows: &[Vec<crate::Frac>],
    st: &Tex,
) -> Result<String, WalkError> {
    let body: Result<Vec<String>, WalkError> = rows
        .iter()
        .map(|r| {
            let cells: Result<Vec<String>, WalkError> = r
                .iter()
                .map(|q| {
                    let (n, d) = (st.1.of(q.num())?, st.1.of(q.den())?);
                    Ok(if matches!(d, Expr::Num(x) if num_traits::One::is_one(x)) {
                        st.expr(n)
                    } else {
                        format!("\\frac{{{}}}{{{}}}", st.expr(n), st.expr(d))
                    })
                })
                .collect();
            Ok(cells?.join(" & "))
        })
        .collect();
    Ok(format!(
        "{lab} = \\begin{{pmatrix}} {} \\end{{pmatrix}}",
        body?.join(" \\\\ ")
    ))
}

/// A value too wide for one line: its entries named in place, then listed.
fn named_value_tex(
    label: &str,
    lab: &str,
    value: &Value,
    st: &Tex,
) -> Result<Vec<Piece>, WalkError> {
    let named = |xs: &[(&Scalar, String)]| -> Result<Named, WalkError> {
        let mut shown = Vec::new();
        let mut rows = Vec::new();
        for (x, name) in xs {
            let (ex, constant) = entry(x, st.1)?;
            if constant {
                shown.push(st.expr(&ex));
            } else {
                shown.push(name.clone());
                rows.push((name.clone(), ex));
            }
        }
        Ok((shown, rows))
    };
    let c = |k: &str| component(label, k, false);
    let cd = |k: &str| component(label, k, true);
    let mut out = Vec::new();
    match value {
        Value::Scalar(x) => {
            out.push(Piece::Display(
                st.aligned(&[(lab.to_string(), st.1.of(x)?.clone())]),
            ));
        }
        Value::Quat(q) => {
            let (shown, rows) = named(&[
                (&q.w, c("w")),
                (&q.x, c("x")),
                (&q.y, c("y")),
                (&q.z, c("z")),
            ])?;
            out.push(Piece::Display(format!(
                "{lab} = \\left({}\\right)",
                shown.join(", ")
            )));
            out.push(Piece::Text("where".to_owned()));
            out.push(Piece::Display(st.aligned(&rows)));
        }
        Value::Vector(x) => {
            let (shown, rows) = named(&[(&x[0], c("x")), (&x[1], c("y")), (&x[2], c("z"))])?;
            out.push(Piece::Display(format!(
                "{lab} = \\left({}\\right)",
                shown.join(", ")
            )));
            out.push(Piece::Text("where".to_owned()));
            out.push(Piece::Display(st.aligned(&rows)));
        }
        Value::DualQuat(d) => {
            let (re, mut rows) = if let Some(w) = dq_part(&d.real) {
                (st.expr(st.1.of(w)?), Vec::new())
            } else {
                let (shown, rows) = named(&[
                    (&d.real.w, c("w")),
                    (&d.real.x, c("x")),
                    (&d.real.y, c("y")),
                    (&d.real.z, c("z")),
                ])?;
                (format!("\\left({}\\right)", shown.join(", ")), rows)
            };
            let (du, rows2) = named(&[
                (&d.dual.w, cd("w")),
                (&d.dual.x, cd("x")),
                (&d.dual.y, cd("y")),
                (&d.dual.z, cd("z")),
            ])?;
            rows.extend(rows2);
            out.push(Piece::Display(format!(
                "{lab} = {re} + \\varepsilon \\left({}\\right)",
                du.join(", ")
            )));
            out.push(Piece::Text("where".to_owned()));
            out.push(Piece::Display(st.aligned(&rows)));
        }
        Value::Matrix(rows) => out.extend(named_matrix_tex(label, lab, rows, st)?),
        Value::QuotientMatrix(_) => {}
    }
    Ok(out)
}

/// A wide matrix: its skeleton with the entries named, then the entries column by column.
fn named_matrix_tex(
    label: &str,
    lab: &str,
    rows: &[Vec<Scalar>],
    st: &Tex,
) -> Result<Vec<Piece>, WalkError> {
    let n = rows.first().map_or(0, Vec::len);
    let mut skeleton = Vec::new();
    let mut columns: Vec<Vec<(String, Expr)>> = vec![Vec::new(); n];
    for (i, r) in rows.iter().enumerate() {
        let mut cells = Vec::new();
        for (j, x) in r.iter().enumerate() {
            let name = component(label, &format!("{}{}", i + 1, j + 1), false);
            let (ex, constant) = entry(x, st.1)?;
            if constant {
                cells.push(st.expr(&ex));
            } else {
                cells.push(name.clone());
                columns[j].push((name, ex));
            }
        }
        skeleton.push(cells.join(" & "));
    }
    let mut out = vec![
        Piece::Display(format!(
            "{lab} = \\begin{{pmatrix}} {} \\end{{pmatrix}}",
            skeleton.join(" \\\\ ")
        )),
        Piece::Text("where, column by column:".to_owned()),
    ];
    for col in columns.iter().filter(|c| !c.is_empty()) {
        out.push(Piece::Display(st.aligned(col)));
    }
    Ok(out)
}

/// A sum with numbered terms as LaTeX, `\underbrace{term}_{k}`, in rows of at most [`WIDTH`].
pub(crate) fn numbered_sum_tex(terms: &[Expr], st: &Tex) -> String {
    let mut rows: Vec<String> = Vec::new();
    let mut row = String::new();
    let mut len = 0;
    for (i, t) in terms.iter().enumerate() {
        let (neg, body) = match t {
            Expr::Neg(e) => (true, &**e),
            e => (false, e),
        };
        let body = st.expr(body);
        let w = visual_len(&body) + 3;
        let new_row = i > 0 && len + w > WIDTH;
        if new_row {
            rows.push(std::mem::take(&mut row));
            len = 0;
        }
        let sign = match (i, neg) {
            (0, false) => "&",
            (0, true) => "&-",
            (_, true) if new_row => "&-",
            (_, false) if new_row => "&+",
            (_, true) => " - ",
            (_, false) => " + ",
        };
        len += w;
        row += &format!("{sign}\\underbrace{{{body}}}_{{{}}}", i + 1);
    }
    if terms.is_empty() {
        row.push_str("&0");
    }
    rows.push(row);
    format!("\\begin{{aligned}}{}\\end{{aligned}}", rows.join(" \\\\ "))
}

/// A formula or text piece of a Markdown or HTML walkthrough.
pub(crate) enum Piece {
    /// Prose with inline `$...$` math.
    Text(String),
    /// Display math.
    Display(String),
    /// Display math folded away behind a summary (prose), for very long expanded sums.
    Folded(String, String),
    /// A bulleted list of prose items.
    List(Vec<String>),
    /// A table: the head's cells and the rows' cells, prose with inline math.
    Table(Vec<String>, Vec<Vec<String>>),
}

/// A walkthrough laid out for Markdown and HTML.
pub(crate) struct Page {
    /// The notation, as prose lines with inline math.
    pub legend: Vec<String>,
    /// One heading per step, then prose and display formulas.
    pub sections: Vec<(String, Vec<Piece>)>,
}

/// The walkthrough as pieces, shared by Markdown and HTML: the legend, then one heading per
/// step with prose and display formulas.
pub(crate) fn page(w: &Walkthrough) -> Result<Page, WalkError> {
    let names = Names::for_walk(w);
    let st = Tex(&names, &w.forms);
    let mut out = Vec::new();
    let mut n = 0;
    for step in &w.steps {
        if matches!(step, Step::Notation { .. } | Step::Legend(_)) {
            continue;
        }
        n += 1;
        let (head, body) = match step {
            Step::Notation { .. } | Step::Legend(_) => continue,
            Step::Explain { title, blocks } => (
                format!("{n}. {}", title.tex),
                blocks.iter().map(|b| block_tex(b, &st)).collect(),
            ),
            Step::Solutions {
                what,
                variables,
                rows,
            } => (
                format!("{n}. Check at the robot's own values"),
                solutions_tex(what, variables, rows),
            ),
            Step::Factor {
                name,
                value,
                meaning,
            } => {
                let mut body = vec![Piece::Text(format!("{}.", capitalize(&st.words(meaning)?)))];
                body.extend(value_tex(name, value, &st)?);
                (format!("{n}. Factor ${}$", label_tex(name)), body)
            }
            Step::Define {
                name,
                value,
                meaning,
            } => {
                let mut body = vec![Piece::Text(format!("{}.", capitalize(&st.words(meaning)?)))];
                body.extend(value_tex(name, value, &st)?);
                (format!("{n}. Define ${}$", label_tex(name)), body)
            }
            Step::Product { left, right, value } => {
                let mut body = vec![Piece::Text(format!(
                    "${}$ times ${}$:",
                    label_tex(left),
                    label_tex(right)
                ))];
                body.extend(value_tex(&format!("{left}*{right}"), value, &st)?);
                (format!("{n}. Product"), body)
            }
            Step::Transform {
                label,
                q,
                v,
                value,
                half_angles,
                traces,
            } => {
                let mut body = vec![Piece::Text(format!(
                    "The point ${}$ carried by ${}$ (eq 10, $\\hat q \\hat v \\bar{{\\hat q}}^*$):",
                    label_tex(v),
                    label_tex(q)
                ))];
                body.extend(value_tex(label, value, &st)?);
                if !half_angles.is_empty() {
                    body.push(Piece::Text(format!("{HALF_ANGLES}:")));
                    for a in half_angles {
                        let ids = half_angle_identities(&a.symbol, st.1)?;
                        let each: Vec<String> = ids
                            .iter()
                            .map(|(l, r)| format!("{} = {}", st.expr(l), st.expr(r)))
                            .collect();
                        body.push(Piece::Display(each.join(", \\quad ")));
                    }
                }
                for t in traces {
                    body.extend(trace_tex(t, &st));
                }
                (format!("{n}. Transform ${}$", label_tex(label)), body)
            }
            Step::Result { label, value } => {
                let mut body = vec![Piece::Text("The closed form:".to_owned())];
                body.extend(value_tex(label, value, &st)?);
                (format!("{n}. Result"), body)
            }
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
    let mut legend: Vec<String> = legend_prose(w).iter().map(|p| p.tex.clone()).collect();
    let lines = names.legend_tex();
    if !lines.is_empty() {
        legend.push("**Notation**, one meaning per symbol on this page.".to_owned());
        legend.extend(lines);
    }
    if let Some(s) = script_names(w) {
        legend.push(format!("The script's `halfangle` names: `{s}`."));
    }
    Ok(Page {
        legend,
        sections: out,
    })
}

/// A block of an explained step as a piece of a page.
fn block_tex(b: &Block, st: &Tex) -> Piece {
    match b {
        Block::Text(p) => Piece::Text(p.tex.clone()),
        Block::List(items) => Piece::List(items.iter().map(|p| p.tex.clone()).collect()),
        Block::Display(p) => Piece::Display(p.tex.clone()),
        Block::Formulas(rows) => Piece::Display(target_names(&formulas_tex(rows, st))),
    }
}

/// Named values in one `aligned` display; single values broken at [`WIDTH`].
fn formulas_tex(rows: &[Shown], st: &Tex) -> String {
    if rows.iter().all(|r| r.parts.len() == 1) {
        let named: Vec<(String, Expr)> = rows
            .iter()
            .map(|r| (label_tex(&r.label), r.parts[0].clone()))
            .collect();
        return st.aligned(&named);
    }
    let lines: Vec<String> = rows
        .iter()
        .map(|r| {
            let parts: Vec<String> = r.parts.iter().map(|e| st.expr(e)).collect();
            format!("{} &= ({})", label_tex(&r.label), parts.join(", "))
        })
        .collect();
    format!("\\begin{{aligned}}{}\\end{{aligned}}", lines.join(" \\\\ "))
}

/// The target's position entries `px`, `py`, `pz` as `p_x`, never the product `p x`.
fn target_names(tex: &str) -> String {
    tex.replace("\\mathit{px}", "p_{x}")
        .replace("\\mathit{py}", "p_{y}")
        .replace("\\mathit{pz}", "p_{z}")
}

/// A solver's check on a page: the words, then a table of the distinct solutions.
fn solutions_tex(what: &Prose, variables: &[String], rows: &[SolutionRow]) -> Vec<Piece> {
    let mut head = vec!["#".to_owned()];
    head.extend(
        variables
            .iter()
            .enumerate()
            .map(|(k, v)| super::ik::column_head(v, k)),
    );
    head.extend(["×".to_owned(), "dev.".to_owned()]);
    let cells = rows
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let mut c = vec![(k + 1).to_string()];
            c.extend(r.q.iter().map(|x| format!("{x:.3}")));
            c.push(format!(
                "{}{}",
                r.branches,
                if r.singular { "*" } else { "" }
            ));
            c.push(if r.deviation < 1e-12 {
                "< 1e-12".to_owned()
            } else {
                format!("{:.0e}", r.deviation)
            });
            c
        })
        .collect();
    let mut out = vec![Piece::Text(what.tex.clone()), Piece::Table(head, cells)];
    out.extend(super::ik::column_key(variables).map(Piece::Text));
    out.push(Piece::Text(
        "×: how many of the solver's branches give the solution (more than one where \
             branches meet, at a singularity); * a singular set was met; dev.: the largest \
             difference of an entry of its pose from the target's."
            .to_owned(),
    ));
    out
}

fn capitalize(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().collect::<String>() + c.as_str(),
        None => String::new(),
    }
}

fn trace_tex(t: &ComponentTrace, st: &Tex) -> Vec<Piece> {
    let name = match t.label.split_once('.') {
        Some((v, k)) => component(v, k, false),
        None => label_tex(&t.label),
    };
    let mut out = vec![Piece::Text(format!("Coordinate `{}`:", t.label))];
    let mut last: &[Expr] = &[];
    for s in &t.steps {
        match s {
            TraceStep::Sum { round, terms } => {
                let what = if *round == 1 {
                    "expanded sum, terms numbered"
                } else {
                    "regrouped"
                };
                let sum = numbered_sum_tex(terms, st);
                if terms.len() > FOLD {
                    out.push(Piece::Folded(
                        format!("{what}: {} terms (select to show)", terms.len()),
                        sum,
                    ));
                } else {
                    out.push(Piece::Text(format!("{what}:")));
                    out.push(Piece::Display(sum));
                }
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
                let pair = pair_expr(last, *terms)
                    .map(|p| st.expr(&p))
                    .unwrap_or_default();
                out.push(Piece::Text(format!(
                    "${}$ with $a = {}$, $b = {}$, terms {} and {}:",
                    identity.latex(),
                    angle_tex(a, st),
                    angle_tex(b, st),
                    terms[0],
                    terms[1]
                )));
                out.push(Piece::Display(format!("{pair} = {}", st.expr(result))));
            }
            TraceStep::Factored(e) => {
                out.push(Piece::Text("common factors out:".to_owned()));
                out.push(Piece::Display(st.aligned(&[(name.clone(), e.clone())])));
            }
            TraceStep::KeptWhole(e) => {
                out.push(Piece::Text(
                    "closed form (the Fourier modes kept whole are shorter):".to_owned(),
                ));
                out.push(Piece::Display(st.aligned(&[(name.clone(), e.clone())])));
            }
            TraceStep::Shorter(e) => {
                out.push(Piece::Text(
                    "closed form (a shorter equivalent form):".to_owned(),
                ));
                out.push(Piece::Display(st.aligned(&[(name.clone(), e.clone())])));
            }
        }
    }
    out
}

fn angle_tex(a: &crate::Angle, st: &Tex) -> String {
    match st.1.of(&a.to_scalar()) {
        Ok(e) => st.expr(e),
        Err(_) => String::new(),
    }
}

/// Text from outside (a robot's name) inert in Markdown: HTML escaped (no live tag), and the
/// characters that open inline Markdown (links and images `[`, `]`, `!`; emphasis `*`, `_`;
/// code spans; GFM tables and strikethrough `|`, `~`) and the backslash itself escaped with a
/// backslash, which CommonMark allows before any ASCII punctuation. An underscore between two
/// letters or digits opens nothing (CommonMark: no emphasis inside a word), so file names such
/// as `appendix2_product.dq` stay as they are.
fn markdown_text(text: &str) -> String {
    let chars: Vec<char> = crate::emit::names::html_text(text).chars().collect();
    let mut out = String::new();
    for (i, &c) in chars.iter().enumerate() {
        let word = |j: Option<usize>| {
            j.and_then(|j| chars.get(j))
                .is_some_and(|c| c.is_alphanumeric())
        };
        let inside_word = c == '_' && word(i.checked_sub(1)) && word(Some(i + 1));
        if "\\`*_[]!|~".contains(c) && !inside_word {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

/// The walkthrough as Markdown: the notation, then a heading per step, formulas in
/// `$$ ... $$`; very long expanded sums inside `<details>`.
///
/// # Errors
/// When a value cannot be shown (never for a walkthrough this crate built).
pub fn walk_markdown(w: &Walkthrough) -> Result<String, WalkError> {
    let p = page(w)?;
    // The title is a robot's name or a file's: text from outside, inert in the heading.
    let mut out = format!("# Walkthrough: {}\n", markdown_text(&w.title));
    for l in &p.legend {
        out += &format!("\n{l}\n");
    }
    for (head, body) in p.sections {
        out += &format!("\n## {head}\n");
        for p in body {
            match p {
                Piece::Text(t) => out += &format!("\n{t}\n"),
                Piece::Display(d) => out += &format!("\n$$\n{d}\n$$\n"),
                Piece::Folded(summary, d) => {
                    out += &format!(
                        "\n<details><summary>{summary}</summary>\n\n$$\n{d}\n$$\n\n</details>\n"
                    )
                }
                Piece::List(items) => {
                    out.push('\n');
                    for i in items {
                        out += &format!("- {i}\n");
                    }
                }
                Piece::Table(head, rows) => {
                    out += &format!("\n| {} |\n", head.join(" | "));
                    out += &format!("|{}\n", " --- |".repeat(head.len()));
                    for r in rows {
                        out += &format!("| {} |\n", r.join(" | "));
                    }
                }
            }
        }
    }
    Ok(out)
}
