//! LaTeX in the paper's notation: `\theta_{1}`, `l_{1}`, `c_{12}` (or `\cos(\theta_{1} +
//! \theta_{2})`), `\frac{\theta_{3}}{2}`, `\sqrt{2}`, `\varepsilon` for the dual unit, matrices
//! as `pmatrix`, long sums broken over lines inside `aligned`.
//!
//! Every string written here is valid KaTeX input; the tests render each snapshot with KaTeX
//! (`throwOnError: true`).

use crate::closed::{shorthand_name, shows_as_decimal, Angle, Expr, Trig, TrigNames};
use crate::scalar::Small;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

/// How LaTeX is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LatexOptions {
    /// `c_{12}` for `\cos(\theta_{1} + \theta_{2})` where the angle allows it (a plain sum of
    /// numbered symbols, see [`shorthand_name`](crate::closed::shorthand_name)).
    pub shorthand: bool,
    /// [`latex_aligned`] breaks a line longer than this many characters (a command counting as one) at a
    /// `+` or `-` of the outermost sum it can; 0 never breaks.
    pub width: usize,
    /// Decimal fractions (a factor 5 in the denominator) as exact decimals, `0.425` for
    /// `\frac{17}{40}` (see [`decimal_form`](crate::closed::decimal_form)).
    pub decimals: bool,
}

impl Default for LatexOptions {
    fn default() -> Self {
        LatexOptions {
            shorthand: true,
            width: 80,
            decimals: false,
        }
    }
}

const GREEK: &[&str] = &[
    "alpha",
    "beta",
    "gamma",
    "delta",
    "epsilon",
    "varepsilon",
    "zeta",
    "eta",
    "theta",
    "vartheta",
    "iota",
    "kappa",
    "lambda",
    "mu",
    "nu",
    "xi",
    "pi",
    "rho",
    "sigma",
    "tau",
    "upsilon",
    "phi",
    "varphi",
    "chi",
    "psi",
    "omega",
    "Gamma",
    "Delta",
    "Theta",
    "Lambda",
    "Xi",
    "Pi",
    "Sigma",
    "Upsilon",
    "Phi",
    "Psi",
    "Omega",
];

/// A symbol name in LaTeX: `theta1` -> `\theta_{1}`, `l1` -> `l_{1}`, `d` -> `d`, `pi` -> `\pi`,
/// `q_e` -> `q_{e}`, `tx` -> `\mathit{tx}`.
pub fn latex_symbol(name: &str) -> String {
    let (base, sub) = match name.split_once('_') {
        Some((b, s)) if !b.is_empty() && !s.is_empty() => (b, Some(s)),
        _ => {
            let cut = name.trim_end_matches(|c: char| c.is_ascii_digit()).len();
            if cut == 0 || cut == name.len() {
                (name, None)
            } else {
                (&name[..cut], Some(&name[cut..]))
            }
        }
    };
    let mut s = base_text(base);
    if let Some(sub) = sub {
        let sub = if sub.chars().all(|c| c.is_ascii_digit()) {
            sub.to_string()
        } else {
            latex_symbol(sub)
        };
        s.push_str(&format!("_{{{sub}}}"));
    }
    s
}

/// A shorthand name in LaTeX: the letter `c` (or `s`, `C`, `S`) with the rest of the name
/// (`12`, `alpha5`, `q_1`, `joint_a1`) as its subscript: `c_{12}`, `c_{\alpha_{5}}`,
/// `c_{q_{1}}`, `c_{{\mathit{joint}_{a}}_{1}}` (a prefix with a subscript of its own in
/// braces, so no subscript is doubled).
pub fn latex_shorthand(letter: &str, rest: &str) -> String {
    let cut = rest.find(|ch: char| ch.is_ascii_digit()).unwrap_or(0);
    let (prefix, idx) = rest.split_at(cut);
    // `q_1`: the prefix `q_` is the symbol `q`.
    let prefix = prefix.trim_end_matches('_');
    if prefix.is_empty() {
        return format!("{letter}_{{{idx}}}");
    }
    let p = latex_symbol(prefix);
    if p.contains('_') {
        format!("{letter}_{{{{{p}}}_{{{idx}}}}}")
    } else {
        format!("{letter}_{{{p}_{{{idx}}}}}")
    }
}

fn base_text(base: &str) -> String {
    if GREEK.contains(&base) {
        format!("\\{base}")
    } else if base.chars().count() == 1 {
        base.to_string()
    } else {
        format!("\\mathit{{{base}}}")
    }
}

/// The expression as inline LaTeX, on one line.
pub fn latex(e: &Expr, o: &LatexOptions) -> String {
    let mut w = Writer::new(o);
    w.expr(e, 0);
    w.out
}

/// The expression as inline LaTeX, cos and sin named by `names` (LaTeX text, a walkthrough's
/// notation: `C_{12}`) instead of the shorthand; `None` writes the function out.
pub fn latex_named(e: &Expr, o: &LatexOptions, names: TrigNames) -> String {
    let mut w = Writer::new(o);
    w.names = Some(names);
    w.expr(e, 0);
    w.out
}

/// A tuple `(a, b, c)`: a point, a vector or a quaternion `(w, x, y, z)`.
pub fn latex_tuple(v: &[Expr], o: &LatexOptions) -> String {
    let parts: Vec<String> = v.iter().map(|e| latex(e, o)).collect();
    format!("\\left({}\\right)", parts.join(", "))
}

/// A dual quaternion `(w, x, y, z) + \varepsilon (w', x', y', z')` from its real and dual parts.
pub fn latex_dual_quat(real: &[Expr], dual: &[Expr], o: &LatexOptions) -> String {
    format!(
        "{} + \\varepsilon {}",
        latex_tuple(real, o),
        latex_tuple(dual, o)
    )
}

/// A matrix as `\begin{pmatrix} a & b \\ c & d \end{pmatrix}`, from its rows.
pub fn latex_matrix<R: AsRef<[Expr]>>(rows: &[R], o: &LatexOptions) -> String {
    pmatrix(
        rows.iter()
            .map(|r| r.as_ref().iter().map(|e| latex(e, o)).collect()),
    )
}

/// The quotient `num / den` as `\frac{num}{den}`, or `num` alone when `den` is 1.
pub fn latex_quotient(num: &Expr, den: &Expr, o: &LatexOptions) -> String {
    if is_one(den) {
        return latex(num, o);
    }
    format!("\\frac{{{}}}{{{}}}", latex(num, o), latex(den, o))
}

/// A matrix of quotients `(num, den)` as [`latex_matrix`] writes a matrix, each entry as
/// [`latex_quotient`] writes it.
pub fn latex_quotient_matrix<R: AsRef<[(Expr, Expr)]>>(rows: &[R], o: &LatexOptions) -> String {
    pmatrix(rows.iter().map(|r| {
        r.as_ref()
            .iter()
            .map(|(n, d)| latex_quotient(n, d, o))
            .collect()
    }))
}

/// Rows of LaTeX cells as a `pmatrix`.
fn pmatrix(rows: impl Iterator<Item = Vec<String>>) -> String {
    let body: Vec<String> = rows.map(|cells| cells.join(" & ")).collect();
    format!(
        "\\begin{{pmatrix}}\n{}\n\\end{{pmatrix}}",
        body.join(" \\\\\n")
    )
}

/// Whether `e` is the number 1.
fn is_one(e: &Expr) -> bool {
    matches!(e, Expr::Num(q) if q.is_one())
}

/// Named values as `\begin{aligned} name &= value \\ ... \end{aligned}`; `name` is LaTeX
/// already. A value longer than [`LatexOptions::width`] is broken at the `+` or `-` of the
/// outermost sum that keeps the line within the width, continued on the next line after
/// `\quad`.
pub fn latex_aligned(rows: &[(String, Expr)], o: &LatexOptions) -> String {
    aligned(rows, o, None)
}

/// [`latex_aligned`] with cos and sin named by `names`, as [`latex_named`].
pub fn latex_aligned_named(rows: &[(String, Expr)], o: &LatexOptions, names: TrigNames) -> String {
    aligned(rows, o, Some(names))
}

fn aligned(rows: &[(String, Expr)], o: &LatexOptions, names: Option<TrigNames>) -> String {
    let mut lines = Vec::new();
    for (name, e) in rows {
        let mut w = Writer::new(o);
        w.names = names;
        w.expr(e, 0);
        let parts = wrap(&w.out, &w.breaks, o.width);
        for (i, p) in parts.iter().enumerate() {
            if i == 0 {
                lines.push(format!("{name} &= {p}"));
            } else {
                lines.push(format!("&\\quad {p}"));
            }
        }
    }
    format!(
        "\\begin{{aligned}}\n{}\n\\end{{aligned}}",
        lines.join(" \\\\\n")
    )
}

/// Splits `s` at recorded break points so that each piece is at most `width` wide (as
/// [`visual_len`] measures) where a break allows it. Among the break points that fit, the latest
/// wins, less a penalty for each enclosing parenthesis: a break in an outer sum reads better.
fn wrap(s: &str, breaks: &[(usize, usize)], width: usize) -> Vec<String> {
    if width == 0 || visual_len(s) <= width {
        return vec![s.to_string()];
    }
    let mut out = Vec::new();
    let mut start = 0;
    while visual_len(&s[start..]) > width {
        let best = breaks
            .iter()
            .filter(|&&(p, _)| p > start)
            .map(|&(p, d)| (p, d, visual_len(&s[start..p])))
            .filter(|&(_, _, v)| v >= width / 3 && v <= width)
            .max_by_key(|&(p, d, v)| (v.saturating_sub(12 * d), p))
            .map(|(p, _, _)| p)
            .or_else(|| breaks.iter().map(|&(p, _)| p).find(|&p| p > start));
        match best {
            Some(p) => {
                out.push(s[start..p].trim().to_string());
                start = p;
            }
            None => break,
        }
    }
    out.push(s[start..].trim().to_string());
    out
}

/// The width of LaTeX source as rendered, roughly: a command counts as one character, braces
/// and sub- and superscript marks as none.
pub fn visual_len(s: &str) -> usize {
    let mut n = 0;
    let mut chars = s.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' => {
                while chars.next_if(|c| c.is_ascii_alphabetic()).is_some() {}
                n += 1;
            }
            '{' | '}' | '_' | '^' => {}
            _ => n += 1,
        }
    }
    n
}

struct Writer<'a> {
    o: &'a LatexOptions,
    /// Names of cos and sin overriding the shorthand, when given.
    names: Option<TrigNames<'a>>,
    out: String,
    /// Positions just before a ` + ` or ` - ` of a sum, with the parenthesis depth there.
    breaks: Vec<(usize, usize)>,
    depth: usize,
}

impl<'a> Writer<'a> {
    fn new(o: &'a LatexOptions) -> Self {
        Writer {
            o,
            names: None,
            out: String::new(),
            breaks: Vec::new(),
            depth: 0,
        }
    }

    fn open(&mut self) {
        self.out.push('(');
        self.depth += 1;
    }

    fn close(&mut self) {
        self.out.push(')');
        self.depth -= 1;
    }

    /// `cos` or `sin` of `angle`, by its shorthand name when it has one, else written out with
    /// the exponent `pow` on the function: `\cos^{2}(\frac{\theta_{3}}{2})`.
    fn trig(&mut self, f: Trig, angle: &Angle, pow: Option<u32>) {
        let name = match self.names {
            Some(names) => names(f, angle),
            None => self
                .o
                .shorthand
                .then(|| shorthand_name(f, angle))
                .flatten()
                .map(|name| {
                    let (c, rest) = name.split_at(1);
                    latex_shorthand(c, rest)
                }),
        };
        let pow = pow.map(|n| format!("^{{{n}}}")).unwrap_or_default();
        match name {
            Some(n) => {
                self.out.push_str(&n);
                self.out.push_str(&pow);
            }
            None => {
                self.out.push_str(match f {
                    Trig::Cos => "\\cos",
                    Trig::Sin => "\\sin",
                });
                self.out.push_str(&pow);
                self.out.push('(');
                self.out.push_str(&latex_angle(angle, self.o.decimals));
                self.out.push(')');
            }
        }
    }

    /// A number: an exact decimal under `decimals`, else an integer or `\frac`.
    fn number(&self, q: &BigRational) -> String {
        if self.o.decimals && shows_as_decimal(q) {
            if let Some(t) = crate::scalar::decimal_text(q, 1_000) {
                return t;
            }
        }
        rational(q)
    }

    /// Precedence levels: 0 top, 1 sum term, 2 product factor, 3 power base.
    fn expr(&mut self, e: &Expr, prec: u8) {
        match e {
            Expr::Num(q) => {
                let t = self.number(q);
                let paren = prec >= 3 && !q.denom().is_one();
                if paren {
                    self.open();
                }
                self.out.push_str(&t);
                if paren {
                    self.close();
                }
            }
            Expr::Sqrt(n) => self.out.push_str(&format!("\\sqrt{{{n}}}")),
            Expr::Sym(s) => self.out.push_str(&latex_symbol(s.name())),
            Expr::Trig { f, angle } => self.trig(*f, angle, None),
            Expr::Add(v) => {
                let paren = prec > 1;
                if paren {
                    self.open();
                }
                for (i, t) in v.iter().enumerate() {
                    if i > 0 {
                        self.breaks.push((self.out.len(), self.depth));
                    }
                    match t {
                        Expr::Neg(inner) => {
                            self.out.push_str(if i == 0 { "-" } else { " - " });
                            self.expr(inner, 2);
                        }
                        t => {
                            if i > 0 {
                                self.out.push_str(" + ");
                            }
                            self.expr(t, 1);
                        }
                    }
                }
                if paren {
                    self.close();
                }
            }
            Expr::Mul(v) => {
                // `\frac{\pi}{2}`, `\frac{3\pi}{4}`, `\frac{l}{3}`: a fraction times one symbol
                // reads as a quotient, as in plain text.
                if let [Expr::Num(q), Expr::Sym(s)] = v.as_slice() {
                    let unit = q.numer().is_one() || s.is_pi();
                    let decimal = self.o.decimals && shows_as_decimal(q);
                    if unit && !decimal && !q.denom().is_one() && q.numer() > &0.into() && prec <= 2
                    {
                        let k = if q.numer().is_one() {
                            String::new()
                        } else {
                            format!("{} ", q.numer())
                        };
                        self.out.push_str(&format!(
                            "\\frac{{{k}{}}}{{{}}}",
                            latex_symbol(s.name()),
                            q.denom()
                        ));
                        return;
                    }
                }
                let paren = prec > 2;
                if paren {
                    self.open();
                }
                for (i, t) in v.iter().enumerate() {
                    if i > 0 {
                        self.out.push(' ');
                    }
                    // A leading fraction reads as a coefficient: `\frac{3}{8} \cos(\theta)`.
                    if let (0, Expr::Num(q)) = (i, t) {
                        let t = self.number(q);
                        self.out.push_str(&t);
                        continue;
                    }
                    self.expr(t, 2);
                }
                if paren {
                    self.close();
                }
            }
            Expr::Neg(inner) => {
                let paren = prec > 1;
                if paren {
                    self.open();
                }
                self.out.push('-');
                self.expr(inner, 2);
                if paren {
                    self.close();
                }
            }
            Expr::Pow(b, n) => match &**b {
                // The exponent on the function: `\cos^{2}(x)`, never on its argument.
                Expr::Trig { f, angle } => self.trig(*f, angle, Some(*n)),
                b => {
                    self.expr(b, 3);
                    self.out.push_str(&format!("^{{{n}}}"));
                }
            },
        }
    }
}

fn rational(q: &BigRational) -> String {
    if q.denom().is_one() {
        q.numer().to_string()
    } else {
        let sign = if q.is_negative() { "-" } else { "" };
        format!("{sign}\\frac{{{}}}{{{}}}", q.numer().abs(), q.denom())
    }
}

/// The angle: `\theta_{1} + \theta_{2}`, `\frac{\theta_{3}}{2}`, `\frac{\theta_{1} -
/// \theta_{4}}{2}`, `\theta - \frac{\pi}{2}`. Coefficients sharing one denominator are written
/// over it once.
fn latex_angle(angle: &Angle, decimals: bool) -> String {
    let mut items: Vec<(Small, Option<String>)> = Vec::with_capacity(angle.terms.len() + 2);
    // Symbols first, then the constant and pi, as `angle_text` writes them.
    items.extend(
        angle
            .terms
            .iter()
            .map(|(sym, k)| (*k, Some(latex_symbol(sym.name())))),
    );
    if !angle.constant.is_zero() {
        items.push((angle.constant, None));
    }
    if !angle.pi.is_zero() {
        items.push((angle.pi, Some("\\pi".to_string())));
    }
    if let Some(d) = crate::closed::decimal_constant(angle.constant, decimals) {
        // A decimal constant stands alone (`\theta_{1} + 0.3`); the other parts keep theirs.
        let sign = if angle.constant.is_negative() {
            "-"
        } else {
            "+"
        };
        let rest: Vec<(Small, Option<String>)> =
            items.iter().filter(|(_, n)| n.is_some()).cloned().collect();
        return if rest.is_empty() {
            format!("{}{d}", if sign == "-" { "-" } else { "" })
        } else {
            format!("{} {sign} {d}", sum_text(&rest))
        };
    }
    let den = items.first().map_or(1, |(k, _)| *k.denom());
    if items.len() > 1 && den > 1 && items.iter().all(|(k, _)| *k.denom() == den) {
        let whole: Vec<(Small, Option<String>)> = items
            .iter()
            .map(|(k, n)| (*k * Small::from_integer(den), n.clone()))
            .collect();
        return format!("\\frac{{{}}}{{{den}}}", sum_text(&whole));
    }
    sum_text(&items)
}

/// `k1 x1 + k2 x2 ...` with fractions as `\frac{x}{q}`; a missing name is the constant 1.
fn sum_text(items: &[(Small, Option<String>)]) -> String {
    let mut s = String::new();
    for (i, (k, name)) in items.iter().enumerate() {
        let neg = k.is_negative();
        let a = k.abs();
        if i == 0 {
            if neg {
                s.push('-');
            }
        } else {
            s.push_str(if neg { " - " } else { " + " });
        }
        let (p, q) = (*a.numer(), *a.denom());
        let num = match name {
            None => p.to_string(),
            Some(n) if p == 1 => n.clone(),
            Some(n) => format!("{p} {n}"),
        };
        if q == 1 {
            s.push_str(&num);
        } else {
            s.push_str(&format!("\\frac{{{num}}}{{{q}}}"));
        }
    }
    if s.is_empty() {
        s.push('0');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    #[test]
    fn symbols_follow_the_paper() {
        assert_eq!(latex_symbol("theta1"), "\\theta_{1}");
        assert_eq!(latex_symbol("alpha2"), "\\alpha_{2}");
        assert_eq!(latex_symbol("l1"), "l_{1}");
        assert_eq!(latex_symbol("d"), "d");
        assert_eq!(latex_symbol("q_e"), "q_{e}");
        assert_eq!(latex_symbol("tx"), "\\mathit{tx}");
        assert_eq!(
            rational(&BigRational::new(BigInt::from(-3), BigInt::from(8))),
            "-\\frac{3}{8}"
        );
    }
}
